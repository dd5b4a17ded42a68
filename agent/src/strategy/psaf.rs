//! The Partaker-Sharer Advising Framework (Zhu, Leung, Hu & Cai, "A
//! Q-values Sharing Framework for Multiple Independent Q-learners", AAMAS
//! 2019, and arXiv 2011.14281; docs/algorithms.md section 7): agents share
//! values instead of actions. A partaker that visited a state little asks;
//! sharers that visited it more send their values, and the partaker takes
//! those of the sharer with the most visits as its own.

use proto::SharedValues;

use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Replies};
use crate::advice::{PAPER_BUDGET, Reachable, p_ask, p_give, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require_non_negative};
use crate::exchange::Advice;
use crate::fidelity::VoteTies;
use crate::fidelity::{Fidelity, Profile};
use crate::method::Method;
use crate::selection::{AgentRng, chance};

/// The settings of the Partaker-Sharer Advising Framework (Zhu et al.,
/// AAMAS 2019): a partaker asks with P_ask, sharers answer with their
/// values with P_give of their visits; separate budgets.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Psaf {
    /// Scaling v_a of the partaker's P_ask = (1 + v_a)^(-sqrt n(s)),
    /// finite and >= 0 (default 0.5).
    pub v_a: f64,
    /// Scaling v_g of the sharer's P_give = 1 - (1 + v_g)^(-log2 n(s)),
    /// finite and >= 0 (default 0.5).
    pub v_g: f64,
    /// Partaker budget: states whose shared values it took (default 1000).
    pub ask_budget: u64,
    /// Sharer budget: values shared (default 1000).
    pub give_budget: u64,
    /// The sharers asked (default everyone).
    pub reachable: Reachable,
}

impl Default for Psaf {
    fn default() -> Self {
        Self {
            v_a: 0.5,
            v_g: 0.5,
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
        }
    }
}

/// `psaf`: share values instead of actions.
pub(crate) struct PsafMethod;

impl Method for PsafMethod {
    type Settings = Psaf;
    const NAME: &'static str = "psaf";
    const ABOUT: &'static str = "share values instead of actions (Zhu et al., AAMAS 2019)";

    fn defaults(_: Profile) -> Psaf {
        Psaf::default()
    }

    fn validate(p: &Psaf) -> Result<(), AgentConfigError> {
        require_non_negative("v_a", p.v_a)?;
        require_non_negative("v_g", p.v_g)?;
        p.reachable.validate()
    }

    fn strategy(settings: &Psaf, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(settings.clone())
    }
}

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

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        counters.advice_given >= self.give_budget
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}
