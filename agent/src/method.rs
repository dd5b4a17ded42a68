//! What an advising method registers: a [`Method`] (its name, its settings
//! with their defaults and checks, the learner it needs, how its decisions
//! are made), erased by [`Registration::of`] into the one list of
//! algorithms (`strategy::ALGORITHMS`), and its settings as
//! [`MethodSettings`], which the framework handles without knowing the
//! method.

use std::any::Any;
use std::fmt::Debug;

use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

use crate::config_error::AgentConfigError;
use crate::fidelity::{Fidelity, Profile};
pub use crate::learner_settings::LearnerNeed;
use crate::learner_settings::LearnerSettings;
use crate::strategy::AdvisingStrategy;

/// A method's settings as a flat table: key to value.
pub(crate) type Table = Map<String, Value>;

/// The agent a strategy is built for: its learner's settings, its
/// discount factor and its seed.
#[derive(Clone, Copy, Debug)]
pub struct Seat<'a> {
    /// Its learner's settings.
    pub learner: &'a LearnerSettings,
    /// Its discount factor per frame.
    pub gamma: f64,
    /// The seed of its generator.
    pub seed: u64,
}

impl<'a> Seat<'a> {
    /// An agent learning with `learner` under the default discount (0.9)
    /// and seed 0.
    pub(crate) fn of(learner: &'a LearnerSettings) -> Self {
        Self {
            learner,
            gamma: 0.9,
            seed: 0,
        }
    }
}

/// An advising method: everything the framework needs to know of it.
/// Registered once, in `strategy::ALGORITHMS` (docs/strategies.md).
pub(crate) trait Method: 'static {
    /// Its settings. Team and study files write them as flat keys, named as
    /// the fields; they must serialise as a JSON object.
    type Settings: Serialize + DeserializeOwned + Clone + PartialEq + Debug + Send + Sync;
    /// Its name in kebab-case, on the command line and in files.
    const NAME: &'static str;
    /// Older spellings still read (never written).
    const ALIASES: &'static [&'static str] = &[];
    /// One line on what it does.
    const ABOUT: &'static str;
    /// Boolean keys written only when true, so that results from before
    /// them keep their identity (a key whose value is null is never
    /// written).
    const WRITTEN_WHEN_TRUE: &'static [&'static str] = &[];
    /// What it needs of the learner.
    const LEARNER: LearnerNeed = LearnerNeed::Values;
    /// Whether its agents exchange anything (advice, values, episodes).
    const COMMUNICATES: bool = true;
    /// Whether its agents learn from the episodes others share, which
    /// carry the paper's states only.
    const SHARES_EPISODES: bool = false;
    /// Whether its decisions are given from outside (a strategy process or
    /// object) rather than made from its settings.
    const EXTERNAL: bool = false;

    /// Its settings under `profile`'s defaults.
    fn defaults(profile: Profile) -> Self::Settings;

    /// The first invalid setting, naming its key.
    fn validate(_settings: &Self::Settings) -> Result<(), AgentConfigError> {
        Ok(())
    }

    /// Its decisions for one agent, under the fidelity rules `fidelity`.
    fn strategy(settings: &Self::Settings, fidelity: &Fidelity) -> Box<dyn AdvisingStrategy>;

    /// Its decisions for the agent of `seat`: those of
    /// [`strategy`](Self::strategy), unless they build on the agent's
    /// learner (a network of the method's own beside the learner's,
    /// decisions folded as the learner folds them).
    fn strategy_for(
        settings: &Self::Settings,
        fidelity: &Fidelity,
        _seat: &Seat<'_>,
    ) -> Box<dyn AdvisingStrategy> {
        Self::strategy(settings, fidelity)
    }
}

/// A [`Method`] as the list of algorithms holds it: its constants and its
/// functions, without its types.
#[derive(Debug)]
pub struct Registration {
    pub(crate) name: &'static str,
    pub(crate) aliases: &'static [&'static str],
    pub(crate) about: &'static str,
    pub(crate) written_when_true: &'static [&'static str],
    pub(crate) learner: LearnerNeed,
    pub(crate) communicates: bool,
    pub(crate) shares_episodes: bool,
    pub(crate) external: bool,
    pub(crate) defaults: fn(Profile) -> Box<dyn MethodSettings>,
    pub(crate) from_table: fn(Table) -> Result<Box<dyn MethodSettings>, serde_json::Error>,
}

impl Registration {
    /// The registration of method `M`.
    pub(crate) const fn of<M: Method>() -> Self {
        Self {
            name: M::NAME,
            aliases: M::ALIASES,
            about: M::ABOUT,
            written_when_true: M::WRITTEN_WHEN_TRUE,
            learner: M::LEARNER,
            communicates: M::COMMUNICATES,
            shares_episodes: M::SHARES_EPISODES,
            external: M::EXTERNAL,
            defaults: |profile| Box::new(Typed::<M>(M::defaults(profile))),
            from_table: |table| {
                let settings = serde_json::from_value(Value::Object(table))?;
                Ok(Box::new(Typed::<M>(settings)))
            },
        }
    }
}

/// A method's settings, whatever the method.
pub(crate) trait MethodSettings: Debug + Send + Sync {
    /// Every key with its value.
    fn table(&self) -> Table;
    /// The first invalid setting, naming its key.
    fn validate(&self) -> Result<(), AgentConfigError>;
    /// Its decisions for the agent of `seat`.
    fn strategy(&self, fidelity: &Fidelity, seat: &Seat<'_>) -> Box<dyn AdvisingStrategy>;
    /// A copy.
    fn boxed_clone(&self) -> Box<dyn MethodSettings>;
    /// The typed settings, to downcast.
    fn as_any(&self) -> &dyn Any;
    /// The typed settings, to downcast and change.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

/// The settings of method `M`.
struct Typed<M: Method>(M::Settings);

impl<M: Method> Debug for Typed<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl<M: Method> MethodSettings for Typed<M> {
    fn table(&self) -> Table {
        match serde_json::to_value(&self.0) {
            Ok(Value::Object(table)) => table,
            other => unreachable!(
                "{}'s settings serialise to a JSON object, not {other:?}",
                M::NAME
            ),
        }
    }

    fn validate(&self) -> Result<(), AgentConfigError> {
        M::validate(&self.0)
    }

    fn strategy(&self, fidelity: &Fidelity, seat: &Seat<'_>) -> Box<dyn AdvisingStrategy> {
        M::strategy_for(&self.0, fidelity, seat)
    }

    fn boxed_clone(&self) -> Box<dyn MethodSettings> {
        Box::new(Typed::<M>(self.0.clone()))
    }

    fn as_any(&self) -> &dyn Any {
        &self.0
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        &mut self.0
    }
}
