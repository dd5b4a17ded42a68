//! RCMP (da Silva, Hernandez-Leal, Kartal & Taylor, "Uncertainty-Aware
//! Action Advising for Deep Reinforcement Learning Agents", AAAI 2020;
//! docs/algorithms.md section 7): an agent asks where its epistemic
//! uncertainty, the disagreement of its ensemble's heads
//! ([`EnsembleSarsa`](crate::EnsembleSarsa)), is above a threshold.

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use super::settings::Rcmp;
use crate::advice::reachable_set;
use crate::advice_counters::AdviceCounters;
use crate::selection::AgentRng;

impl AdvisingStrategy for Rcmp {
    fn asks_by_uncertainty(&self) -> bool {
        true
    }

    /// Ask budget left and an uncertainty above the threshold.
    fn asks(&mut self, at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        at.counters.ask_spent < self.ask_budget
            && at
                .uncertainty
                .is_some_and(|u| u > self.uncertainty_threshold)
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        reachable_set(&self.reachable, me, team_size, positions, out);
    }

    /// Every request about a visited state, while the give budget lasts.
    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        at.visited_within(self.give_budget)
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
