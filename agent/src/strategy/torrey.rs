//! Torrey & Taylor's importance advising (docs/algorithms.md section 3):
//! the student asks its fixed teacher `(i + 1) mod n` at every fresh state;
//! the teacher answers where the spread of its values exceeds a threshold.

use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use crate::advice::PAPER_BUDGET;
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require_non_negative};
use crate::fidelity::{Fidelity, Profile, TorreyIntent, TorreyUnknownState};
use crate::method::Method;
use crate::selection::AgentRng;

/// The settings of Torrey's importance advising from the fixed teacher
/// `(i + 1) mod n`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Torrey {
    /// The teacher advises when the spread of Q(s, .) exceeds this
    /// importance threshold t, finite and >= 0 (default 0.01).
    pub importance_threshold: f64,
    /// Teacher budget: answers given (default 1000).
    pub give_budget: u64,
    /// Mistake Correcting, as for [`AdHoc::mistake_correcting`](crate::AdHoc::mistake_correcting)
    /// (default off).
    pub mistake_correcting: bool,
}

impl Default for Torrey {
    /// The paper's constants.
    fn default() -> Self {
        Self {
            importance_threshold: 0.01,
            give_budget: PAPER_BUDGET,
            mistake_correcting: false,
        }
    }
}

/// `torrey`: importance advising from a fixed teacher.
pub(crate) struct TorreyMethod;

impl Method for TorreyMethod {
    type Settings = Torrey;
    const NAME: &'static str = "torrey";
    const ABOUT: &'static str = "Torrey & Taylor's importance advising from a fixed teacher";

    fn defaults(_: Profile) -> Torrey {
        Torrey::default()
    }

    fn validate(settings: &Torrey) -> Result<(), AgentConfigError> {
        require_non_negative("importance_threshold", settings.importance_threshold)
    }

    fn strategy(settings: &Torrey, fidelity: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(TorreyTeacher {
            settings: settings.clone(),
            unknown: fidelity.torrey_unknown_state,
            intent: fidelity.torrey_intent,
        })
    }
}

/// Torrey's constants with the fidelity rules that concern it.
#[derive(Clone, Debug)]
struct TorreyTeacher {
    settings: Torrey,
    /// What the teacher does where it has learned no kick action.
    unknown: TorreyUnknownState,
    /// What a Mistake Correcting student sends as its intended action.
    intent: TorreyIntent,
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

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        counters.advice_given >= self.settings.give_budget
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
