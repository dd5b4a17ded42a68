//! The action-advising baselines of Ilhan, Gow & Perez-Liebana ("Teaching
//! on a Budget in Multi-Agent Deep Reinforcement Learning", IEEE CoG 2019):
//! early advising asks at every step until the budget is spent, random
//! advising with a fixed probability; the advisors answer with their greedy
//! action. Which states an advisor answers about is not part of those
//! baselines; the reading taken here: any state it has visited.

use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use crate::advice::{PAPER_BUDGET, Reachable, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require_unit};
use crate::fidelity::{Fidelity, Profile};
use crate::method::Method;
use crate::selection::{AgentRng, chance};

/// The settings of early advising: the budgets and whom to ask.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EarlyAdvising {
    /// Advisee budget: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given (default 1000).
    pub give_budget: u64,
    /// The reachable set G: whom the advisee asks (default everyone).
    pub reachable: Reachable,
    /// Mistake Correcting, as for [`AdHoc::mistake_correcting`](crate::AdHoc::mistake_correcting)
    /// (default off).
    pub mistake_correcting: bool,
}

impl Default for EarlyAdvising {
    fn default() -> Self {
        Self {
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
            mistake_correcting: false,
        }
    }
}

/// The settings of random advising: early advising's, and the probability
/// of asking at a step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RandomAdvising {
    /// The probability of asking at a step, in [0, 1] (default 0.5).
    pub ask_probability: f64,
    /// Advisee budget: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given (default 1000).
    pub give_budget: u64,
    /// The reachable set G: whom the advisee asks (default everyone).
    pub reachable: Reachable,
    /// Mistake Correcting, as for [`AdHoc::mistake_correcting`](crate::AdHoc::mistake_correcting)
    /// (default off).
    pub mistake_correcting: bool,
}

impl Default for RandomAdvising {
    fn default() -> Self {
        Self {
            ask_probability: 0.5,
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
            mistake_correcting: false,
        }
    }
}

/// `early-advising`: ask at every step until the budget is spent.
pub(crate) struct EarlyAdvisingMethod;

impl Method for EarlyAdvisingMethod {
    type Settings = EarlyAdvising;
    const NAME: &'static str = "early-advising";
    const ABOUT: &'static str =
        "ask at every step until the budget is spent (Ilhan et al.'s baseline)";

    fn defaults(_: Profile) -> EarlyAdvising {
        EarlyAdvising::default()
    }

    fn validate(settings: &EarlyAdvising) -> Result<(), AgentConfigError> {
        settings.reachable.validate()
    }

    fn strategy(s: &EarlyAdvising, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Budgeted {
            ask_probability: 1.0,
            ask_budget: s.ask_budget,
            give_budget: s.give_budget,
            reachable: s.reachable.clone(),
            mistake_correcting: s.mistake_correcting,
        })
    }
}

/// `random-advising`: ask with a fixed probability while the budget lasts.
pub(crate) struct RandomAdvisingMethod;

impl Method for RandomAdvisingMethod {
    type Settings = RandomAdvising;
    const NAME: &'static str = "random-advising";
    const ABOUT: &'static str =
        "ask with a fixed probability while the budget lasts (Ilhan et al.'s baseline)";

    fn defaults(_: Profile) -> RandomAdvising {
        RandomAdvising::default()
    }

    fn validate(settings: &RandomAdvising) -> Result<(), AgentConfigError> {
        require_unit("ask_probability", settings.ask_probability)?;
        settings.reachable.validate()
    }

    fn strategy(s: &RandomAdvising, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Budgeted {
            ask_probability: s.ask_probability,
            ask_budget: s.ask_budget,
            give_budget: s.give_budget,
            reachable: s.reachable.clone(),
            mistake_correcting: s.mistake_correcting,
        })
    }
}

/// Asking with a probability while a budget lasts: early advising's and
/// random advising's decisions.
#[derive(Clone, Debug)]
struct Budgeted {
    ask_probability: f64,
    ask_budget: u64,
    give_budget: u64,
    reachable: Reachable,
    mistake_correcting: bool,
}

impl AdvisingStrategy for Budgeted {
    /// Ask budget left, then `ask_probability` (no draw at 1).
    fn asks(&mut self, at: &AskContext<'_>, rng: &mut AgentRng) -> bool {
        at.counters.ask_spent < self.ask_budget && chance(rng, self.ask_probability)
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        reachable_set(&self.reachable, me, team_size, positions, out);
    }

    fn mistake_correcting(&self) -> bool {
        self.mistake_correcting
    }

    /// Give budget left and a visited state.
    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        at.visited_within(self.give_budget)
    }

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        counters.advice_given >= self.give_budget
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
