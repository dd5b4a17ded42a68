//! The action-advising baselines of Ilhan, Gow & Perez-Liebana ("Teaching
//! on a Budget in Multi-Agent Deep Reinforcement Learning", IEEE CoG 2019):
//! early advising asks at every step until the budget is spent, random
//! advising with a fixed probability; the advisors answer with their greedy
//! action. Which states an advisor answers about is not part of those
//! baselines; the reading taken here: any state it has visited.

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use super::settings::Budgeted;
use crate::advice::reachable_set;
use crate::advice_counters::AdviceCounters;
use crate::selection::{AgentRng, chance};

impl AdvisingStrategy for Budgeted {
    /// Ask budget left, then `ask_probability` (no draw at 1).
    fn asks(&mut self, at: &AskContext<'_>, rng: &mut AgentRng) -> bool {
        at.counters.ask_spent < self.ask_budget && chance(rng, self.ask_probability)
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        reachable_set(&self.reachable, me, team_size, positions, out);
    }

    /// Give budget left and a visited state.
    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        at.visited_within(self.give_budget)
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
