//! Which learner an agent learns with (team key `learner`), chosen by its
//! settings: SARSA(lambda) by default, a Double DQN with 5 heads for an
//! algorithm that asks by uncertainty, or on request a DQN or a tabular
//! ensemble (docs/learners.md).

use serde::{Deserialize, Serialize};

use crate::config_error::{AgentConfigError, require, require_unit};

/// What an algorithm needs of its agents' learner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LearnerNeed {
    /// Values and a choice: any learner.
    Values,
    /// Also its uncertainty in a state (an ensemble's): the algorithm asks
    /// by uncertainty.
    Uncertainty,
    /// A neural network over the agent's observation (the DQN): the
    /// algorithm learns a network of its own from what the learner reads,
    /// or has its learner learn a batch by a gradient step (ef-ontl).
    Network,
}

impl LearnerNeed {
    /// What a learner must be to meet it, as an error says.
    pub fn expected(self) -> &'static str {
        match self {
            LearnerNeed::Values => "any learner",
            LearnerNeed::Uncertainty => {
                "a learner that measures its uncertainty (ensemble, or dqn with heads of 2 or more)"
            }
            LearnerNeed::Network => "a neural learner (dqn)",
        }
    }
}

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
    /// `dqn`: a Double DQN over the agent's observation, learning from one
    /// kick to the next ([`Dqn`](crate::Dqn)); with `heads` of 2 or more, a
    /// bootstrapped ensemble of heads on one torso whose variance is its
    /// uncertainty.
    Dqn(DqnSettings),
}

/// The most hidden layers of a DQN.
pub const MAX_HIDDEN_LAYERS: usize = 4;
/// The widest hidden layer of a DQN.
pub const MAX_HIDDEN_WIDTH: u32 = 1024;
/// The largest replay buffer of a DQN, in transitions.
pub const MAX_REPLAY: u64 = 1_000_000;
/// The most heads of a DQN.
pub const MAX_DQN_HEADS: u32 = 16;
/// A DQN's heads by default for an algorithm that asks by uncertainty.
const DQN_ENSEMBLE_HEADS: u32 = 5;

/// What a neural learner reads of a state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObservationSet {
    /// The paper's six features (docs/algorithms.md section 1).
    #[default]
    Paper,
    /// Today's HFO high-level feature set (docs/python.md "The `hfo` set",
    /// `env_server::Env::current_features`), which the transports deliver
    /// to the agents that read it.
    Hfo,
}

impl ObservationSet {
    /// Its name in files.
    pub fn name(self) -> &'static str {
        match self {
            ObservationSet::Paper => "paper",
            ObservationSet::Hfo => "hfo",
        }
    }

    /// The numbers it holds for an agent of a team of `team_size`.
    pub fn width(self, team_size: usize) -> usize {
        match self {
            ObservationSet::Paper => proto::STATE_FEATURES,
            ObservationSet::Hfo => proto::hfo_feature_count(team_size),
        }
    }
}

/// A DQN's settings, under the names the DQN literature gives them
/// (docs/settings.md); the agent's `gamma` is its discount per frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DqnSettings {
    /// The width of each hidden layer (ReLU), 1 to [`MAX_HIDDEN_LAYERS`]
    /// layers of 1 to [`MAX_HIDDEN_WIDTH`] units; in a file a list, or one
    /// number for one layer.
    #[serde(deserialize_with = "layers")]
    pub hidden: Vec<u32>,
    /// Adam's learning rate, in (0, 1].
    pub lr: f64,
    /// Transitions per gradient step, 1 to `replay`.
    pub batch: u32,
    /// The replay buffer's capacity in transitions, 1 to [`MAX_REPLAY`].
    pub replay: u64,
    /// Transitions stored before the first gradient step (at least
    /// `batch` are).
    pub warmup: u64,
    /// Gradient steps between copies of the network to its target, >= 1.
    pub target_every: u64,
    /// Transitions stored between gradient steps, >= 1.
    pub train_every: u64,
    /// Exploration probability at the first decision, in [0, 1].
    pub epsilon_start: f64,
    /// Exploration probability after `epsilon_decay` decisions, in [0, 1].
    pub epsilon_end: f64,
    /// Own decisions over which exploration falls linearly from
    /// `epsilon_start` to `epsilon_end` (0: `epsilon_end` from the start).
    pub epsilon_decay: u64,
    /// Heads on the torso, 1 to [`MAX_DQN_HEADS`]: 1 is a plain Double DQN,
    /// 2 or more a bootstrapped ensemble with an uncertainty.
    pub heads: u32,
    /// With heads: the probability that a head learns a transition (its
    /// bootstrap mask), in (0, 1].
    pub mask_probability: f64,
    /// What the network reads: `paper`, the six features, or `hfo`, HFO's
    /// high-level set.
    pub observation: ObservationSet,
}

/// `hidden` as a list of widths, or one width.
fn layers<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Vec<u32>, D::Error> {
    #[derive(Deserialize)]
    #[serde(
        untagged,
        expecting = "a list of layer widths, e.g. [64, 64], or one width"
    )]
    enum Layers {
        One(u32),
        Many(Vec<u32>),
    }
    Ok(match Layers::deserialize(deserializer)? {
        Layers::One(width) => vec![width],
        Layers::Many(widths) => widths,
    })
}

impl Default for DqnSettings {
    /// The defaults of docs/learners.md: the usual small-DQN values, not
    /// yet chosen by a sweep on this task.
    fn default() -> Self {
        Self {
            hidden: vec![64, 64],
            lr: 1e-3,
            batch: 32,
            replay: 50_000,
            warmup: 500,
            target_every: 250,
            train_every: 1,
            epsilon_start: 0.5,
            epsilon_end: 0.05,
            epsilon_decay: 5_000,
            heads: 1,
            mask_probability: 0.5,
            observation: ObservationSet::Paper,
        }
    }
}

impl DqnSettings {
    /// The first invalid setting, naming its key.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
        let hidden = &self.hidden;
        if hidden.is_empty() || hidden.len() > MAX_HIDDEN_LAYERS {
            return Err(AgentConfigError::new(
                "hidden",
                format!(
                    "must list 1 to {MAX_HIDDEN_LAYERS} layer widths, got {}",
                    hidden.len()
                ),
            ));
        }
        if let Some(&w) = hidden.iter().find(|&&w| w == 0 || w > MAX_HIDDEN_WIDTH) {
            return Err(AgentConfigError::new(
                "hidden",
                format!("each layer must be 1 to {MAX_HIDDEN_WIDTH} units wide, got {w}"),
            ));
        }
        let lr = self.lr;
        require("lr", lr, "in (0, 1]", lr > 0.0 && lr <= 1.0)?;
        if !(1..=MAX_REPLAY).contains(&self.replay) {
            return Err(AgentConfigError::new(
                "replay",
                format!("must be 1 to {MAX_REPLAY} transitions, got {}", self.replay),
            ));
        }
        if self.batch == 0 || u64::from(self.batch) > self.replay {
            return Err(AgentConfigError::new(
                "batch",
                format!("must be 1 to replay ({}), got {}", self.replay, self.batch),
            ));
        }
        for (key, value) in [
            ("target_every", self.target_every),
            ("train_every", self.train_every),
        ] {
            if value == 0 {
                return Err(AgentConfigError::new(key, "must be at least 1, got 0"));
            }
        }
        require_unit("epsilon_start", self.epsilon_start)?;
        require_unit("epsilon_end", self.epsilon_end)?;
        if !(1..=MAX_DQN_HEADS).contains(&self.heads) {
            return Err(AgentConfigError::new(
                "heads",
                format!("must be 1 to {MAX_DQN_HEADS}, got {}", self.heads),
            ));
        }
        let p = self.mask_probability;
        require("mask_probability", p, "in (0, 1]", p > 0.0 && p <= 1.0)
    }
}

impl LearnerSettings {
    /// Every learner's name.
    pub const NAMES: [&'static str; 3] = ["sarsa", "ensemble", "dqn"];

    /// The learner `name` with its defaults.
    pub fn named(name: &str) -> Result<Self, AgentConfigError> {
        match name {
            "sarsa" => Ok(LearnerSettings::Sarsa),
            "ensemble" => Ok(LearnerSettings::Ensemble {
                heads: 5,
                mask_probability: 0.5,
            }),
            "dqn" => Ok(LearnerSettings::Dqn(DqnSettings::default())),
            other => Err(AgentConfigError::new(
                "learner",
                format!(
                    "unknown learner `{other}` (expected one of: {})",
                    Self::NAMES.join(", ")
                ),
            )),
        }
    }

    /// The learner `name` with its defaults for an algorithm that needs
    /// `need`: a DQN for one that asks by uncertainty has 5 heads (as the
    /// ensemble), one otherwise.
    pub fn named_for(name: &str, need: LearnerNeed) -> Result<Self, AgentConfigError> {
        match (Self::named(name)?, need) {
            (LearnerSettings::Dqn(dqn), LearnerNeed::Uncertainty) => {
                Ok(LearnerSettings::Dqn(DqnSettings {
                    heads: DQN_ENSEMBLE_HEADS,
                    ..dqn
                }))
            }
            (learner, _) => Ok(learner),
        }
    }

    /// Its name.
    pub fn name(&self) -> &'static str {
        match self {
            LearnerSettings::Sarsa => "sarsa",
            LearnerSettings::Ensemble { .. } => "ensemble",
            LearnerSettings::Dqn(_) => "dqn",
        }
    }

    /// The default learner of an algorithm that needs `need`: SARSA(lambda),
    /// or for one that asks by uncertainty the DQN with 5 heads (RCMP's
    /// learner in its paper; the tabular `ensemble` is named), or for one
    /// that needs a network the DQN (one head).
    pub fn for_need(need: LearnerNeed) -> Self {
        let name = match need {
            LearnerNeed::Values => "sarsa",
            LearnerNeed::Uncertainty | LearnerNeed::Network => "dqn",
        };
        Self::named_for(name, need).expect("a learner of NAMES")
    }

    /// What it reads of a state: the tabular learners the paper's six
    /// features (their tiles), a DQN its `observation`.
    pub fn observation(&self) -> ObservationSet {
        match self {
            LearnerSettings::Dqn(dqn) => dqn.observation,
            _ => ObservationSet::Paper,
        }
    }

    /// Whether it meets `need`: it measures its uncertainty in a state, or
    /// it is a network.
    pub fn meets(&self, need: LearnerNeed) -> bool {
        match need {
            LearnerNeed::Values => true,
            LearnerNeed::Network => matches!(self, LearnerSettings::Dqn(_)),
            LearnerNeed::Uncertainty => match self {
                LearnerSettings::Sarsa => false,
                LearnerSettings::Ensemble { .. } => true,
                LearnerSettings::Dqn(dqn) => dqn.heads >= 2,
            },
        }
    }

    /// The first invalid setting, naming its key.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
        if let LearnerSettings::Dqn(dqn) = self {
            return dqn.validate();
        }
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
