//! Tan's episode sharing (docs/algorithms.md section 3): after a goal
//! episode an agent sends its transitions to every other agent, one budget
//! unit per transition per receiver; nobody asks or answers.

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use crate::advice_counters::AdviceCounters;
use crate::selection::AgentRng;

/// Episode sharing with its budget of transitions sent.
#[derive(Clone, Copy, Debug)]
pub(super) struct EpisodeSharing {
    pub sharing_budget: u64,
}

impl AdvisingStrategy for EpisodeSharing {
    fn asks(&mut self, _at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        false
    }

    fn advisors(&self, _me: usize, _n: usize, _positions: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
    }

    fn gives(&mut self, _at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        false
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.shared_sent
    }

    fn sharing_allowance(&self, counters: &AdviceCounters) -> u64 {
        self.sharing_budget.saturating_sub(counters.shared_sent)
    }
}
