//! The two methods that never advise: SARSA(lambda) alone (NoAdvice) and
//! the authors' random baseline, which does not learn either.

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use crate::advice_counters::AdviceCounters;
use crate::selection::AgentRng;

/// NoAdvice, or the random baseline when it does not `learn`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Alone {
    /// False for the random baseline.
    pub learns: bool,
}

impl AdvisingStrategy for Alone {
    fn learns(&self) -> bool {
        self.learns
    }

    fn asks(&mut self, _at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        false
    }

    fn advisors(&self, _me: usize, _n: usize, _positions: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
    }

    fn gives(&mut self, _at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        false
    }

    fn spent_budget(&self, _counters: &AdviceCounters) -> u64 {
        0
    }
}
