//! Advice reuse (Zhu et al., "Learning by reusing previous advice: a
//! memory-based teacher-student framework", JAAMAS 2023; docs/algorithms.md
//! section 7): AdHocTD whose advisee keeps the advice it followed per state
//! and, on later visits, plays it again instead of asking, while its reuse
//! rule allows.

use fnv::FnvHashMap;
use proto::Action;

use super::ad_hoc::AdHocAdvising;
use super::seam::{AdvisingStrategy, AskContext, GiveContext, Outcome, Replies};
use super::settings::{AdHoc, Reuse, ReuseRule};
use crate::advice_counters::AdviceCounters;
use crate::exchange::Advice;
use crate::fidelity::VoteTies;
use crate::learner::ActionValues;
use crate::selection::{ACTIONS, AgentRng, chance};

/// The advice kept for one state.
#[derive(Clone, Copy, Debug)]
struct Kept {
    action: Action,
    /// Its values in the state when the advice was last played (q-change).
    values: Option<[f64; ACTIONS]>,
    /// The probability of the next reuse (decay).
    p: f64,
}

/// Ad hoc advising with a memory of the advice followed.
#[derive(Clone, Debug)]
pub(super) struct ReusingAdvice {
    ad_hoc: AdHocAdvising,
    rule: Reuse,
    kept: FnvHashMap<u64, Kept>,
}

impl ReusingAdvice {
    pub fn new(settings: AdHoc, rule: Reuse) -> Self {
        Self {
            ad_hoc: AdHocAdvising::new(settings),
            rule,
            kept: FnvHashMap::default(),
        }
    }
}

/// The largest change of any action's value.
fn change(a: &[f64; ACTIONS], b: &[f64; ACTIONS]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

impl AdvisingStrategy for ReusingAdvice {
    /// The kept advice of the state, while the rule allows: q-change while
    /// its values moved by more than the threshold since the advice was
    /// last played (then it forgets the advice), decay with a probability
    /// that shrinks at every reuse.
    fn reuse(
        &mut self,
        key: u64,
        values: &mut dyn FnMut() -> ActionValues,
        rng: &mut AgentRng,
    ) -> Option<Action> {
        let kept = self.kept.get_mut(&key)?;
        match self.rule.reuse_rule {
            ReuseRule::QChange => {
                let now = values().q;
                let moving = kept
                    .values
                    .is_none_or(|then| change(&now, &then) > self.rule.q_change_threshold);
                if moving {
                    kept.values = Some(now);
                    Some(kept.action)
                } else {
                    self.kept.remove(&key);
                    None
                }
            }
            ReuseRule::Decay => {
                let reuse = chance(rng, kept.p);
                if reuse {
                    kept.p *= self.rule.reuse_decay;
                }
                reuse.then_some(kept.action)
            }
        }
    }

    fn asks(&mut self, at: &AskContext<'_>, rng: &mut AgentRng) -> bool {
        self.ad_hoc.asks(at, rng)
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        self.ad_hoc.advisors(me, team_size, positions, out);
    }

    fn gives(&mut self, at: &GiveContext<'_>, rng: &mut AgentRng) -> bool {
        self.ad_hoc.gives(at, rng)
    }

    /// The majority vote, kept for the state when there is one.
    fn follow(
        &mut self,
        replies: &Replies<'_>,
        ties: VoteTies,
        rng: &mut AgentRng,
    ) -> Option<Advice> {
        let advice = self.ad_hoc.follow(replies, ties, rng)?;
        let kept = Kept {
            action: advice.action,
            values: None,
            p: 1.0,
        };
        self.kept.insert(replies.key, kept);
        Some(advice)
    }

    fn learns_from_outcomes(&self) -> bool {
        self.ad_hoc.learns_from_outcomes()
    }

    fn learn_outcome(&mut self, outcome: &Outcome) {
        self.ad_hoc.learn_outcome(outcome);
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        self.ad_hoc.spent_budget(counters)
    }
}
