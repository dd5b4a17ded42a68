//! The simulator's settings ([`EnvConfig`], with [`EvaluationMemory`]) and
//! their validation: what the behaviours and the environment read, apart
//! from both.

use serde::{Deserialize, Serialize};

/// Most offense agents the simulator supports.
pub const MAX_OFFENSE: usize = 4;

/// Settings of the simulated task; the defaults are the paper's setup.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EnvConfig {
    /// Number of offense agents (1 to 4).
    pub offense: usize,
    /// Cycles after which a trial ends out of time (`--frames-per-trial`).
    pub frames_per_trial: u32,
    /// Cycles without a touch after which a trial ends out of time.
    pub untouched_time: u32,
    /// Pass to the teammate the action names instead of HFO's best pass to anyone.
    pub pass_to_named_receiver: bool,
    /// What the agents of an evaluation simulator remember when it starts.
    pub evaluation_memory: EvaluationMemory,
}

impl Default for EnvConfig {
    fn default() -> Self {
        EnvConfig {
            offense: 3,
            frames_per_trial: 200,
            untouched_time: 100,
            pass_to_named_receiver: false,
            evaluation_memory: EvaluationMemory::Carried,
        }
    }
}

/// A rejected simulator setting.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum EnvConfigError {
    /// The offense count is outside the supported range.
    #[error("offense must be between 1 and {MAX_OFFENSE}, got {0}")]
    Offense(usize),
    /// A time limit is zero.
    #[error("{0} must be at least 1")]
    ZeroLimit(&'static str),
}

impl EnvConfig {
    /// Checks every setting, naming the first bad one.
    pub fn validate(&self) -> Result<(), EnvConfigError> {
        if !(1..=MAX_OFFENSE).contains(&self.offense) {
            return Err(EnvConfigError::Offense(self.offense));
        }
        if self.frames_per_trial == 0 {
            return Err(EnvConfigError::ZeroLimit("frames_per_trial"));
        }
        if self.untouched_time == 0 {
            return Err(EnvConfigError::ZeroLimit("untouched_time"));
        }
        Ok(())
    }

    /// The first setting that only our simulator has, set otherwise than
    /// the real HFO plays (which passes as HFO does and plays a run on one
    /// server); `None` when the real HFO can play these settings.
    pub fn unlike_real_hfo(&self) -> Option<&'static str> {
        if self.pass_to_named_receiver {
            return Some("pass_to_named_receiver");
        }
        if self.evaluation_memory != EvaluationMemory::Carried {
            return Some("evaluation_memory");
        }
        None
    }
}

/// What the agents of an evaluation block's simulator remember at its
/// start (docs/fidelity.md, item 9). HFO plays a run's training and
/// evaluation episodes on one server whose agent processes keep their
/// memories (their last shot course, their view) from episode to episode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EvaluationMemory {
    /// What the training simulator's agents remember, handed back to it
    /// when training resumes: as HFO.
    #[default]
    Carried,
    /// Nothing: every evaluation block starts as a new server would.
    Fresh,
}

impl std::str::FromStr for EvaluationMemory {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "carried" => Ok(EvaluationMemory::Carried),
            "fresh" => Ok(EvaluationMemory::Fresh),
            _ => Err(format!(
                "unknown evaluation memory '{s}' (expected carried or fresh)"
            )),
        }
    }
}
