//! Ad hoc advising (docs/algorithms.md section 2; the paper's Algorithms 1
//! and 2): an advisee asks with P_ask(n(s)) its reachable set G(s); an
//! advisor answers with P_give(Psi(s)), Psi visit- or TD-based. With
//! `backoff` (the paper's section 7), an advisee whose requests go
//! unanswered lets its next chances to ask pass, more of them each time.

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Replies};
use super::settings::{AdHoc, Confidence};
use crate::advice::{p_ask, p_give, psi_td, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::exchange::Advice;
use crate::fidelity::VoteTies;
use crate::selection::{AgentRng, chance, majority};

/// The most requests in a row without advice that lengthen the back-off.
const MAX_BACKOFF_DOUBLINGS: u32 = 10;

/// Ad hoc advising for one agent: its constants and its back-off.
#[derive(Clone, Debug)]
pub(super) struct AdHocAdvising {
    pub settings: AdHoc,
    /// Requests in a row that brought no advice.
    unanswered: u32,
    /// Chances to ask still to let pass.
    skips: u64,
}

impl AdHocAdvising {
    pub fn new(settings: AdHoc) -> Self {
        Self {
            settings,
            unanswered: 0,
            skips: 0,
        }
    }
}

impl AdvisingStrategy for AdHocAdvising {
    /// A fresh state, ask budget left, after the first episode, not backing
    /// off, and P_ask.
    fn asks(&mut self, at: &AskContext<'_>, rng: &mut AgentRng) -> bool {
        let a = &self.settings;
        let eligible =
            at.fresh && at.counters.ask_spent < a.ask_budget && at.training_episodes >= 1;
        if !eligible {
            return false;
        }
        if self.skips > 0 {
            self.skips -= 1;
            return false;
        }
        chance(rng, p_ask(at.visits, a.v_a))
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        reachable_set(&self.settings.reachable, me, team_size, positions, out);
    }

    fn mistake_correcting(&self) -> bool {
        self.settings.mistake_correcting
    }

    /// Give budget left, a visited state, and P_give(Psi).
    fn gives(&mut self, at: &GiveContext<'_>, rng: &mut AgentRng) -> bool {
        let a = &self.settings;
        let psi = match a.confidence {
            Confidence::Visit => psi_visit(at.visits),
            Confidence::Td => psi_td(at.visits, at.values.kick_spread()),
        };
        at.counters.advice_given < a.give_budget && at.visits > 0 && chance(rng, p_give(psi, a.v_g))
    }

    /// The majority vote; with back-off, a request without advice doubles
    /// the chances to let pass (1, 3, 7, ...), advice resets them.
    fn follow(
        &mut self,
        replies: &Replies<'_>,
        ties: VoteTies,
        rng: &mut AgentRng,
    ) -> Option<Advice> {
        if self.settings.backoff {
            if replies.advice.is_empty() {
                self.unanswered = (self.unanswered + 1).min(MAX_BACKOFF_DOUBLINGS);
                self.skips = (1 << self.unanswered) - 1;
            } else {
                self.unanswered = 0;
            }
        }
        let vote = majority(replies.advice.iter().map(|a| a.action), ties, rng)?;
        replies.from_whom(vote)
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
