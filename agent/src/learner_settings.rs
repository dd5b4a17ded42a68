//! Which learner an agent learns with (team key `learner`), chosen by its
//! settings: SARSA(lambda) by default, or an ensemble of its heads for an
//! algorithm that asks by uncertainty.

use serde::{Deserialize, Serialize};

use crate::config_error::{AgentConfigError, require};
use crate::method::LearnerNeed;

/// A learner and its own settings. In team files, `learner = "<name>"` and
/// its keys beside it (`heads`, `mask_probability`); the learner's shared
/// constants (`alpha`, `gamma`, `lambda`, `epsilon`, the tiles) are the
/// agent's. Without `learner`, the one the algorithm needs
/// ([`LearnerSettings::for_need`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "learner", rename_all = "kebab-case", deny_unknown_fields)]
pub enum LearnerSettings {
    /// `sarsa`: SARSA(lambda) over the tile-coded state ([`TabularSarsa`](crate::TabularSarsa)).
    #[default]
    Sarsa,
    /// `ensemble`: `heads` SARSA(lambda) heads, each learning a transition
    /// with probability `mask_probability` ([`EnsembleSarsa`](crate::EnsembleSarsa)); its
    /// uncertainty is the heads' variance.
    Ensemble {
        /// Heads K, 2 to 64 (default 5).
        heads: u32,
        /// The probability p that a head learns a transition (its
        /// bootstrap mask), in (0, 1] (default 0.5).
        mask_probability: f64,
    },
}

impl LearnerSettings {
    /// Every learner's name.
    pub const NAMES: [&'static str; 2] = ["sarsa", "ensemble"];

    /// The learner `name` with its defaults.
    pub fn named(name: &str) -> Result<Self, AgentConfigError> {
        match name {
            "sarsa" => Ok(LearnerSettings::Sarsa),
            "ensemble" => Ok(LearnerSettings::Ensemble {
                heads: 5,
                mask_probability: 0.5,
            }),
            other => Err(AgentConfigError::new(
                "learner",
                format!(
                    "unknown learner `{other}` (expected one of: {})",
                    Self::NAMES.join(", ")
                ),
            )),
        }
    }

    /// Its name.
    pub fn name(&self) -> &'static str {
        match self {
            LearnerSettings::Sarsa => "sarsa",
            LearnerSettings::Ensemble { .. } => "ensemble",
        }
    }

    /// The default learner of an algorithm that needs `need`.
    pub fn for_need(need: LearnerNeed) -> Self {
        let name = match need {
            LearnerNeed::Values => "sarsa",
            LearnerNeed::Uncertainty => "ensemble",
        };
        Self::named(name).expect("a learner of NAMES")
    }

    /// Whether it measures its uncertainty in a state.
    pub fn meets(&self, need: LearnerNeed) -> bool {
        match need {
            LearnerNeed::Values => true,
            LearnerNeed::Uncertainty => matches!(self, LearnerSettings::Ensemble { .. }),
        }
    }

    /// The first invalid setting, naming its key.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
        if let LearnerSettings::Ensemble {
            heads,
            mask_probability: p,
        } = *self
        {
            if !(2..=64).contains(&heads) {
                return Err(AgentConfigError::new(
                    "heads",
                    format!("must be 2 to 64, got {heads}"),
                ));
            }
            require("mask_probability", p, "in (0, 1]", p > 0.0 && p <= 1.0)?;
        }
        Ok(())
    }
}
