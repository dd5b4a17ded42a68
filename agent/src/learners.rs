//! The learner an agent's settings name, made.

use crate::config::AgentConfig;
use crate::dqn::Dqn;
use crate::ensemble::EnsembleSarsa;
use crate::learner::Learner;
use crate::learner_settings::LearnerSettings;
use crate::sarsa::TabularSarsa;

/// Mixed into an agent's seed for its ensemble's masks.
const ENSEMBLE_STREAM: u64 = 0x5243_4d50_6865_6164;

/// Mixed into an agent's seed for its DQN's weights, masks and samples.
const DQN_STREAM: u64 = 0x4451_4e5f_6e65_7473;

/// The learner of an agent of `config` in a team of `team_size`, seeded
/// with `seed`.
pub(crate) fn learner_of(config: &AgentConfig, team_size: usize, seed: u64) -> Box<dyn Learner> {
    match config.learner {
        LearnerSettings::Sarsa => Box::new(TabularSarsa::new(config)),
        LearnerSettings::Ensemble {
            heads,
            mask_probability,
        } => Box::new(EnsembleSarsa::new(
            config,
            heads as usize,
            mask_probability,
            seed ^ ENSEMBLE_STREAM,
        )),
        LearnerSettings::Dqn(ref dqn) => {
            let inputs = dqn.observation.width(team_size);
            Box::new(Dqn::new(dqn, config.gamma, inputs, seed ^ DQN_STREAM))
        }
    }
}
