//! Tan's episode sharing (docs/algorithms.md section 3): after a goal
//! episode an agent sends its transitions to every other agent, one budget
//! unit per transition per receiver; nobody asks or answers (the seam's
//! defaults).

use super::seam::AdvisingStrategy;
use crate::advice_counters::AdviceCounters;

/// Episode sharing with its budget of transitions sent.
#[derive(Clone, Copy, Debug)]
pub(super) struct EpisodeSharing {
    pub sharing_budget: u64,
}

impl AdvisingStrategy for EpisodeSharing {
    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.shared_sent
    }

    fn sharing_allowance(&self, counters: &AdviceCounters) -> u64 {
        self.sharing_budget.saturating_sub(counters.shared_sent)
    }
}
