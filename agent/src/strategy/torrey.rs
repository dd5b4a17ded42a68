//! Torrey & Taylor's importance advising (docs/algorithms.md section 3):
//! the student asks its fixed teacher `(i + 1) mod n` at every fresh state;
//! the teacher answers where the spread of its values exceeds a threshold.

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use super::settings::Torrey;
use crate::advice_counters::AdviceCounters;
use crate::fidelity::{TorreyIntent, TorreyUnknownState};
use crate::selection::AgentRng;

/// Torrey's constants with the fidelity rules that concern it.
#[derive(Clone, Debug)]
pub(super) struct TorreyTeacher {
    pub settings: Torrey,
    /// What the teacher does where it has learned no kick action.
    pub unknown: TorreyUnknownState,
    /// What a Mistake Correcting student sends as its intended action.
    pub intent: TorreyIntent,
}

impl AdvisingStrategy for TorreyTeacher {
    fn asks(&mut self, at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        at.fresh
    }

    fn advisors(&self, me: usize, team_size: usize, _positions: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
        let teacher = (me + 1) % team_size;
        out.extend((teacher != me).then_some(teacher));
    }

    fn mistake_correcting(&self) -> bool {
        self.settings.mistake_correcting
    }

    fn intends_greedy(&self) -> bool {
        self.intent == TorreyIntent::Greedy
    }

    /// Give budget left and an importance above the threshold (infinite
    /// where it knows no kick action, if its fidelity says so).
    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        let importance = match self.unknown {
            TorreyUnknownState::Advise if !at.values.any_kick_learned() => f64::INFINITY,
            _ => at.values.kick_spread(),
        };
        at.counters.advice_given < self.settings.give_budget
            && importance > self.settings.importance_threshold
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
