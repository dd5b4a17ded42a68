//! Ad hoc advising (docs/algorithms.md section 2; the paper's Algorithms 1
//! and 2): an advisee asks with P_ask(n(s)) its reachable set G(s); an
//! advisor answers with P_give(Psi(s)), Psi visit- or TD-based. With
//! `backoff` (the paper's section 7), an advisee whose requests go
//! unanswered lets its next chances to ask pass, more of them each time;
//! with `trust_lr` (section 8), it follows the advice, or its own choice, it
//! learned to trust most.

use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Outcome, Replies};
use super::trust::Trust;
use crate::advice::{PAPER_BUDGET, Reachable, p_ask, p_give, psi_td, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require, require_non_negative};
use crate::exchange::Advice;
use crate::fidelity::{Fidelity, Profile, VoteTies};
use crate::method::Method;
use crate::selection::{AgentRng, chance, majority};

/// The confidence function Psi of an ad hoc advisor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Confidence {
    /// Visit-based: `Psi = log2 n(s)` (AdHocVisit).
    Visit,
    /// TD-based: `Psi = sqrt(n(s)) * spread of Q(s, .)` (AdHocTD).
    Td,
}

/// The settings of ad hoc advising (Algorithms 1 and 2), those of
/// `adhoc-visit` and `adhoc-td`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdHoc {
    /// Scaling v_a of P_ask, finite and >= 0 (default 0.5).
    pub v_a: f64,
    /// Scaling v_g of P_give, finite and >= 0 (default 0.5 for `adhoc-visit`,
    /// 0.2 under the authors' profile, 1.5 for `adhoc-td`).
    pub v_g: f64,
    /// Advisee budget b_ask: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget b_give: answers given (default 1000).
    pub give_budget: u64,
    /// Mistake Correcting: the advisee sends its own epsilon-greedy choice
    /// along and plays it when no advice comes; advisors answer only when
    /// they disagree (default off).
    pub mistake_correcting: bool,
    /// The reachable set G: whom the advisee asks (default everyone).
    pub reachable: Reachable,
    /// Back off after unanswered requests (the paper's section 7): after
    /// k requests in a row that brought no advice, the advisee lets its
    /// next 2^k - 1 chances to ask pass (k at most 10); advice resets k
    /// (default off).
    pub backoff: bool,
    /// Trust in advisors (docs/algorithms.md section 8), learned at this
    /// rate in (0, 1] from the outcomes of the advice followed; the
    /// advisee then follows the advice, or its own choice, of most trust
    /// (default none: the majority vote).
    pub trust_lr: Option<f64>,
}

impl AdHoc {
    /// The paper's constants with giving scale `v_g`.
    pub fn with_v_g(v_g: f64) -> Self {
        Self {
            v_a: 0.5,
            v_g,
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            mistake_correcting: false,
            reachable: Reachable::Everyone,
            backoff: false,
            trust_lr: None,
        }
    }

    /// AdHocVisit with the paper's constants.
    pub fn visit() -> Self {
        Self::with_v_g(0.5)
    }

    /// AdHocTD with the paper's constants.
    pub fn td() -> Self {
        Self::with_v_g(1.5)
    }

    /// The first invalid setting, naming its key.
    pub(super) fn validate(&self) -> Result<(), AgentConfigError> {
        require_non_negative("v_a", self.v_a)?;
        require_non_negative("v_g", self.v_g)?;
        self.reachable.validate()?;
        if let Some(lr) = self.trust_lr {
            require("trust_lr", lr, "in (0, 1]", lr > 0.0 && lr <= 1.0)?;
        }
        Ok(())
    }
}

/// `adhoc-visit`: ad hoc advising with the visit-based confidence.
pub(crate) struct AdHocVisit;

impl Method for AdHocVisit {
    type Settings = AdHoc;
    const NAME: &'static str = "adhoc-visit";
    const ALIASES: &'static [&'static str] = &["ad-hoc-visit"];
    const ABOUT: &'static str = "ad hoc advising with the visit-based confidence (the paper's)";
    const WRITTEN_WHEN_TRUE: &'static [&'static str] = &["backoff"];

    fn defaults(profile: Profile) -> AdHoc {
        AdHoc::with_v_g(profile.visit_v_g())
    }

    fn validate(settings: &AdHoc) -> Result<(), AgentConfigError> {
        settings.validate()
    }

    fn strategy(settings: &AdHoc, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(AdHocAdvising::new(Confidence::Visit, settings.clone()))
    }
}

/// `adhoc-td`: ad hoc advising with the TD-based confidence.
pub(crate) struct AdHocTd;

impl Method for AdHocTd {
    type Settings = AdHoc;
    const NAME: &'static str = "adhoc-td";
    const ALIASES: &'static [&'static str] = &["ad-hoc-td"];
    const ABOUT: &'static str = "ad hoc advising with the TD-based confidence (the paper's)";
    const WRITTEN_WHEN_TRUE: &'static [&'static str] = &["backoff"];

    fn defaults(_: Profile) -> AdHoc {
        AdHoc::td()
    }

    fn validate(settings: &AdHoc) -> Result<(), AgentConfigError> {
        settings.validate()
    }

    fn strategy(settings: &AdHoc, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(AdHocAdvising::new(Confidence::Td, settings.clone()))
    }
}

/// The most requests in a row without advice that lengthen the back-off.
const MAX_BACKOFF_DOUBLINGS: u32 = 10;

/// Ad hoc advising for one agent: its constants, its back-off and its trust.
#[derive(Clone, Debug)]
pub(super) struct AdHocAdvising {
    confidence: Confidence,
    settings: AdHoc,
    /// Requests in a row that brought no advice.
    unanswered: u32,
    /// Chances to ask still to let pass.
    skips: u64,
    /// With trust: what it learned of its advisors and itself.
    trust: Trust,
}

impl AdHocAdvising {
    pub fn new(confidence: Confidence, settings: AdHoc) -> Self {
        Self {
            confidence,
            settings,
            unanswered: 0,
            skips: 0,
            trust: Trust::default(),
        }
    }

    /// Its trust in `advisor` (0 for one never followed).
    pub fn trust(&self, advisor: usize) -> f64 {
        self.trust.of(advisor)
    }

    /// The advice whose advisors it trusts most together, each weighing
    /// e^(trust / the largest trust magnitude), if that outweighs its own
    /// choice alone (ties to the advice, as without trust).
    fn most_trusted(&self, advice: &[Advice]) -> Option<Advice> {
        let weight = self.trust.weigh(advice, 1.0);
        let support = |action| {
            (advice.iter().filter(|a| a.action == action))
                .map(|a| weight(self.trust(a.advisor)))
                .sum::<f64>()
        };
        let (best, most) = advice.iter().fold((None, 0.0), |(best, most), a| {
            let s = support(a.action);
            if s > most {
                (Some(*a), s)
            } else {
                (best, most)
            }
        });
        best.filter(|_| most >= weight(self.trust.own()))
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
        let psi = match self.confidence {
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
        if self.settings.trust_lr.is_some() {
            return self.most_trusted(replies.advice);
        }
        let vote = majority(replies.advice.iter().map(|a| a.action), ties, rng)?;
        replies.from_whom(vote)
    }

    fn learns_from_outcomes(&self) -> bool {
        self.settings.trust_lr.is_some()
    }

    /// Moves its trust in whoever decided (an advisor, or itself) toward the
    /// decision's advantage.
    fn learn_outcome(&mut self, outcome: &Outcome) {
        if let Some(lr) = self.settings.trust_lr {
            self.trust.learn(outcome, lr);
        }
    }

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        counters.advice_given >= self.settings.give_budget
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action::{Dribble, Shoot};
    use rand::SeedableRng;

    #[test]
    fn trust_turns_away_from_the_advisor_whose_advice_turns_out_worse() {
        let settings = AdHoc {
            trust_lr: Some(0.1),
            ..AdHoc::td()
        };
        let mut ad_hoc = AdHocAdvising::new(Confidence::Td, settings);
        assert!(ad_hoc.learns_from_outcomes());
        let good = Advice {
            advisor: 1,
            action: Shoot,
        };
        let bad = Advice {
            advisor: 2,
            action: Dribble,
        };
        let mut rng = AgentRng::seed_from_u64(2);
        let mut follow = |ad_hoc: &mut AdHocAdvising, advice: &[Advice]| {
            let replies = Replies {
                key: 7,
                advice,
                ..Replies::default()
            };
            ad_hoc.follow(&replies, VoteTies::Fixed, &mut rng)
        };
        // Untrusted yet: advice is followed, the first of a split vote.
        assert_eq!(follow(&mut ad_hoc, &[bad, good]), Some(bad));
        assert_eq!(follow(&mut ad_hoc, &[bad]), Some(bad));
        for _ in 0..100 {
            for (advisor, advantage) in [(Some(1), 1.0), (Some(2), -1.0), (None, 0.0)] {
                ad_hoc.learn_outcome(&Outcome { advisor, advantage });
            }
        }
        assert!(ad_hoc.trust(1) > 0.9 && ad_hoc.trust(2) < -0.9);
        assert_eq!(follow(&mut ad_hoc, &[bad, good]), Some(good));
        // Alone, the bad advisor weighs less than the agent's own choice.
        assert_eq!(follow(&mut ad_hoc, &[bad]), None);
        assert_eq!(follow(&mut ad_hoc, &[good]), Some(good));
    }
}
