//! The Partaker-Sharer Advising Framework (Zhu, Leung, Hu & Cai, "A
//! Q-values Sharing Framework for Multiple Independent Q-learners", AAMAS
//! 2019, and arXiv 2011.14281; docs/algorithms.md section 7): agents share
//! values instead of actions. A partaker that visited a state little asks;
//! sharers that visited it more send their values, and the partaker takes
//! those of the sharer with the most visits as its own.

use proto::SharedValues;

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Replies};
use super::settings::Psaf;
use crate::advice::{p_ask, p_give, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::exchange::Advice;
use crate::fidelity::VoteTies;
use crate::selection::{AgentRng, chance};

impl AdvisingStrategy for Psaf {
    /// A fresh state, ask budget left, after the first episode, with
    /// P_ask(n(s)).
    fn asks(&mut self, at: &AskContext<'_>, rng: &mut AgentRng) -> bool {
        at.fresh
            && at.counters.ask_spent < self.ask_budget
            && at.training_episodes >= 1
            && chance(rng, p_ask(at.visits, self.v_a))
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        reachable_set(&self.reachable, me, team_size, positions, out);
    }

    fn shares_values(&self) -> bool {
        true
    }

    /// Give budget left, a visited state, and P_give of its visits.
    fn gives(&mut self, at: &GiveContext<'_>, rng: &mut AgentRng) -> bool {
        at.counters.advice_given < self.give_budget
            && at.visits > 0
            && chance(rng, p_give(psi_visit(at.visits), self.v_g))
    }

    /// The values of the sharer with the most visits (the first of them),
    /// if it visited the state more than the partaker did.
    fn adopt(&mut self, replies: &Replies<'_>, visits: u64) -> Option<SharedValues> {
        (replies.values.iter())
            .filter(|v| v.values.visits > visits)
            .rev()
            .max_by_key(|v| v.values.visits)
            .map(|v| v.values)
    }

    /// A partaker follows no action: it plays its own choice on the values
    /// it took.
    fn follow(&mut self, _: &Replies<'_>, _: VoteTies, _: &mut AgentRng) -> Option<Advice> {
        None
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
