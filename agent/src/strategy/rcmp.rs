//! RCMP (da Silva, Hernandez-Leal, Kartal & Taylor, "Uncertainty-Aware
//! Action Advising for Deep Reinforcement Learning Agents", AAAI 2020;
//! docs/algorithms.md section 7): an agent asks where its epistemic
//! uncertainty, the disagreement of its learner's heads, is above a
//! threshold. As the paper, on a network with heads: the DQN with 5 heads
//! by default, whose uncertainty is the mean over actions of the heads'
//! variance ([`Dqn`](crate::Dqn)); the tabular variant, `learner =
//! "ensemble"` ([`EnsembleSarsa`](crate::EnsembleSarsa)), measures the
//! variance of the action it would play.

use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext};
use crate::advice::{PAPER_BUDGET, Reachable, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require_non_negative};
use crate::fidelity::{Fidelity, Profile};
use crate::method::{LearnerNeed, Method};
use crate::selection::AgentRng;

/// The settings of RCMP (da Silva et al., AAAI 2020): ask where the
/// learner's uncertainty (its heads' disagreement) is high.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rcmp {
    /// Ask where the heads' variance exceeds it, finite and >= 0 (default
    /// 0.001: a first update of a tabular head, alpha 0.1, leaves 0.0025;
    /// the DQN's asks go on past its warm-up, where 0.01 stops them
    /// within 500 episodes: docs/algorithms.md).
    pub uncertainty_threshold: f64,
    /// Advisee budget: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given (default 1000).
    pub give_budget: u64,
    /// The reachable set G (default everyone).
    pub reachable: Reachable,
    /// Mistake Correcting, as for [`AdHoc::mistake_correcting`](crate::AdHoc::mistake_correcting)
    /// (default off).
    pub mistake_correcting: bool,
}

impl Default for Rcmp {
    fn default() -> Self {
        Self {
            uncertainty_threshold: 0.001,
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
            mistake_correcting: false,
        }
    }
}

/// `rcmp`: ask by the uncertainty of a learner with heads.
pub(crate) struct RcmpMethod;

impl Method for RcmpMethod {
    type Settings = Rcmp;
    const NAME: &'static str = "rcmp";
    const ABOUT: &'static str =
        "ask where the learner's heads disagree (da Silva et al., AAAI 2020)";
    const LEARNER: LearnerNeed = LearnerNeed::Uncertainty;

    fn defaults(_: Profile) -> Rcmp {
        Rcmp::default()
    }

    fn validate(r: &Rcmp) -> Result<(), AgentConfigError> {
        require_non_negative("uncertainty_threshold", r.uncertainty_threshold)?;
        r.reachable.validate()
    }

    fn strategy(settings: &Rcmp, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(settings.clone())
    }
}

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

    fn mistake_correcting(&self) -> bool {
        self.mistake_correcting
    }

    /// Every request about a visited state, while the give budget lasts.
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
