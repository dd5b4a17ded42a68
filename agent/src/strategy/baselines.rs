//! The two methods that never advise: SARSA(lambda) alone (NoAdvice) and
//! the authors' random baseline, which does not learn either. They never
//! ask nor give: the seam's defaults.

use super::seam::AdvisingStrategy;
use crate::advice_counters::AdviceCounters;

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

    fn spent_budget(&self, _counters: &AdviceCounters) -> u64 {
        0
    }
}
