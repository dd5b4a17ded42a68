//! Each algorithm's decisions made from its settings: the one place that
//! knows every implementation of the seam.

use super::ad_hoc::AdHocAdvising;
use super::baselines::Alone;
use super::episode_sharing::EpisodeSharing;
use super::peers::Peers;
use super::reuse::ReusingAdvice;
use super::seam::AdvisingStrategy;
use super::settings::Strategy;
use super::torrey::TorreyTeacher;
use crate::config::AgentConfig;
use crate::ensemble::EnsembleSarsa;
use crate::fidelity::Fidelity;
use crate::learner::Learner;
use crate::sarsa::TabularSarsa;

/// Mixed into an agent's seed for its ensemble's masks.
const ENSEMBLE_STREAM: u64 = 0x5243_4d50_6865_6164;

impl Strategy {
    /// The learner its agent learns with: RCMP's ensemble, else SARSA(lambda).
    pub fn learner(&self, config: &AgentConfig, seed: u64) -> Box<dyn Learner> {
        match self {
            Strategy::Rcmp(r) => Box::new(EnsembleSarsa::new(
                config,
                r.heads as usize,
                r.mask_probability,
                seed ^ ENSEMBLE_STREAM,
            )),
            _ => Box::new(TabularSarsa::new(config)),
        }
    }

    /// Its decisions for one agent, under the fidelity rules `fidelity`.
    pub fn build(&self, fidelity: &Fidelity) -> Box<dyn AdvisingStrategy> {
        match self {
            // External decisions are given once the agent is built.
            Strategy::NoAdvice | Strategy::External => Box::new(Alone { learns: true }),
            Strategy::Random => Box::new(Alone { learns: false }),
            Strategy::AdHoc(a) => Box::new(AdHocAdvising::new(a.clone())),
            Strategy::AdviceReuse(a, r) => Box::new(ReusingAdvice::new(a.clone(), r.clone())),
            Strategy::PeerLearning(p) => Box::new(Peers::new(p.clone())),
            Strategy::Rcmp(r) => Box::new(r.clone()),
            Strategy::Psaf(p) => Box::new(p.clone()),
            Strategy::Torrey(t) => Box::new(TorreyTeacher {
                settings: t.clone(),
                unknown: fidelity.torrey_unknown_state,
                intent: fidelity.torrey_intent,
            }),
            Strategy::EpisodeSharing { sharing_budget } => Box::new(EpisodeSharing {
                sharing_budget: *sharing_budget,
            }),
            Strategy::EarlyAdvising(b) | Strategy::RandomAdvising(b) => Box::new(b.clone()),
        }
    }
}
