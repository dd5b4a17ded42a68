//! Learners and strategies given as objects in this process instead of
//! named in a file: how Python's `run()` brings classes of its own into an
//! in-process experiment (docs/python.md). The results record what each
//! object says it is.

use std::fmt;

use agent::{AdvisingStrategy, Learner};
use serde::{Deserialize, Serialize};

/// What the results record of an agent's objects (`plugin` in its table of
/// `config.json`): what each says it is.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PluginSpec {
    /// The learner in place of SARSA(lambda), if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub learner: Option<String>,
    /// The strategy making algorithm `external`'s decisions, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub strategy: Option<String>,
}

/// Who an object is made for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PluginStart {
    /// The agent's id.
    pub agent: usize,
    /// Agents in the team.
    pub team_size: usize,
    /// The run.
    pub run: u64,
    /// The agent's seed, for the object's own random choices.
    pub seed: u64,
}

/// Makes one agent's learner and strategy for each run.
///
/// The seams cannot return errors, so an object that fails keeps the
/// failure for [`failure`](Self::failure), which the in-process backend
/// asks after every frame: the run then ends with it.
pub trait Plugin: Send + Sync + fmt::Debug {
    /// What the results record of it.
    fn spec(&self) -> PluginSpec;

    /// The learner for `start`, if it brings one.
    fn learner(&self, start: PluginStart) -> Result<Option<Box<dyn Learner>>, String>;

    /// The strategy for `start`, if it brings one.
    fn strategy(&self, start: PluginStart) -> Result<Option<Box<dyn AdvisingStrategy>>, String>;

    /// The first failure of one of its objects, if any.
    fn failure(&self) -> Option<String>;
}
