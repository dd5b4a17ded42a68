//! Ad hoc advising (docs/algorithms.md section 2; the paper's Algorithms 1
//! and 2): an advisee asks with P_ask(n(s)) its reachable set G(s); an
//! advisor answers with P_give(Psi(s)), Psi visit- or TD-based.

use super::settings::{AdHoc, Confidence};
use super::{AdvisingStrategy, AskContext, GiveContext};
use crate::advice::{p_ask, p_give, psi_td, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::selection::{AgentRng, chance};

impl AdvisingStrategy for AdHoc {
    /// A fresh state, ask budget left, after the first episode, with P_ask.
    fn asks(&mut self, at: &AskContext<'_>, rng: &mut AgentRng) -> bool {
        at.fresh
            && at.counters.ask_spent < self.ask_budget
            && at.training_episodes >= 1
            && chance(rng, p_ask(at.visits, self.v_a))
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
        reachable_set(&self.reachable, me, team_size, positions, out);
    }

    fn mistake_correcting(&self) -> bool {
        self.mistake_correcting
    }

    /// Give budget left, a visited state, and P_give(Psi).
    fn gives(&mut self, at: &GiveContext<'_>, rng: &mut AgentRng) -> bool {
        let psi = match self.confidence {
            Confidence::Visit => psi_visit(at.visits),
            Confidence::Td => psi_td(at.visits, at.values.kick_spread()),
        };
        at.counters.advice_given < self.give_budget
            && at.visits > 0
            && chance(rng, p_give(psi, self.v_g))
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
