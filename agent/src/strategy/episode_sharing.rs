//! Tan's episode sharing (docs/algorithms.md section 3): after a goal
//! episode an agent sends its transitions to every other agent, one budget
//! unit per transition per receiver; nobody asks or answers (the seam's
//! defaults).

use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, EndContext, Sends};
use crate::advice::{PAPER_BUDGET, shared_prefix};
use crate::advice_counters::AdviceCounters;
use crate::exchange::{Share, Transition};
use crate::fidelity::{Fidelity, Profile};
use crate::method::Method;
use proto::Mode;

/// The settings of episode sharing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeSharing {
    /// Transitions sent, one unit per transition per receiver (default 1000).
    pub sharing_budget: u64,
}

/// `episode-sharing`: Tan's episode sharing after goal episodes.
pub(crate) struct EpisodeSharingMethod;

impl Method for EpisodeSharingMethod {
    type Settings = EpisodeSharing;
    const NAME: &'static str = "episode-sharing";
    const ABOUT: &'static str = "Tan's episode sharing after goal episodes";
    const SHARES_EPISODES: bool = true;

    fn defaults(_: Profile) -> EpisodeSharing {
        EpisodeSharing {
            sharing_budget: PAPER_BUDGET,
        }
    }

    fn strategy(settings: &EpisodeSharing, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Sharer {
            sharing_budget: settings.sharing_budget,
            episode: Vec::new(),
        })
    }
}

/// An agent sharing its goal episodes: its budget and the episode so far.
#[derive(Clone, Debug)]
struct Sharer {
    sharing_budget: u64,
    /// The transitions learned in this episode, while budget is left.
    episode: Vec<Transition>,
}

impl AdvisingStrategy for Sharer {
    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.shared_sent
    }

    fn begin_episode(&mut self, _mode: Mode) {
        self.episode.clear();
    }

    /// While budget is left.
    fn records_transitions(&self, counters: &AdviceCounters) -> bool {
        self.sharing_budget > counters.shared_sent
    }

    fn learned(&mut self, transition: &Transition) {
        self.episode.push(*transition);
    }

    /// After a goal: the episode's first transitions to each other agent,
    /// in id order, as many as the budget left covers
    /// ([`shared_prefix`]).
    fn end_episode(&mut self, end: &EndContext<'_>) -> Sends {
        let episode = std::mem::take(&mut self.episode);
        if end.final_reward <= 0.0 || episode.is_empty() {
            return Sends::new();
        }
        let budget = self.sharing_budget.saturating_sub(end.counters.shared_sent);
        let receivers = end.team_size - 1;
        (0..end.team_size)
            .filter(|&j| j != end.me)
            .enumerate()
            .filter_map(|(k, to)| {
                let n = shared_prefix(episode.len(), receivers, k, budget);
                (n > 0).then(|| (to, Share::Episode(episode[..n].to_vec())))
            })
            .collect()
    }
}
