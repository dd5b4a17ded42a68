//! Advice reuse (Zhu et al., "Learning by reusing previous advice: a
//! memory-based teacher-student framework", JAAMAS 2023; docs/algorithms.md
//! section 7): AdHocTD whose advisee keeps the advice it followed per state
//! and, on later visits, plays it again instead of asking, while its reuse
//! rule allows.

use fnv::FnvHashMap;
use proto::Action;

use serde::{Deserialize, Serialize};

use super::ad_hoc::{AdHoc, AdHocAdvising, Confidence};
use super::seam::{AdvisingStrategy, AskContext, GiveContext, Outcome, Replies, ReuseContext};
use crate::advice::Reachable;
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require_non_negative, require_unit};
use crate::exchange::Advice;
use crate::fidelity::{Fidelity, Profile, VoteTies};
use crate::learner::ActionValues;
use crate::method::Method;
use crate::selection::{ACTIONS, AgentRng, chance};

/// How an advice-reuse student decides to reuse the advice it stored for a
/// state (Zhu et al., JAAMAS 2023).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReuseRule {
    /// "Q-change per step" (the paper's): reuse while the advice leads to
    /// an increase in its value: the advised action's value in the state
    /// rose by more than `q_change_threshold` since the advice was last
    /// played (then it forgets the advice).
    QChange,
    /// This project's first reading of it: reuse while its values in the
    /// state change, in either direction, by more than
    /// `q_change_threshold` (the largest change over the actions).
    QChangeEither,
    /// "Decay reusing probability": reuse with a probability that starts at
    /// 1 and is multiplied by `reuse_decay` at each reuse.
    Decay,
}

/// The settings of advice reuse (Zhu et al., "Learning by reusing previous
/// advice: a memory-based teacher-student framework", JAAMAS 2023): AdHocTD's
/// and the reuse rule's.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdviceReuse {
    /// AdHocTD's v_a (default 0.5).
    pub v_a: f64,
    /// AdHocTD's v_g (default 1.5).
    pub v_g: f64,
    /// Advisee budget: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given (default 1000).
    pub give_budget: u64,
    /// The reachable set G (default everyone).
    pub reachable: Reachable,
    /// AdHocTD's back-off (default off).
    pub backoff: bool,
    /// AdHocTD's trust in advisors (default none).
    pub trust_lr: Option<f64>,
    /// AdHocTD's Mistake Correcting (default off).
    pub mistake_correcting: bool,
    /// Which rule decides a reuse (default `q-change`).
    pub reuse_rule: ReuseRule,
    /// `q-change`: the rise of the advised action's value (`q-change-either`:
    /// the change of its values, largest over the actions) above which it
    /// still reuses, finite and >= 0 (default 0.001).
    pub q_change_threshold: f64,
    /// `decay`: the factor of the reuse probability after each reuse, in
    /// [0, 1] (default 0.9).
    pub reuse_decay: f64,
}

impl AdviceReuse {
    /// AdHocTD's part.
    fn ad_hoc(&self) -> AdHoc {
        AdHoc {
            v_a: self.v_a,
            v_g: self.v_g,
            ask_budget: self.ask_budget,
            give_budget: self.give_budget,
            reachable: self.reachable.clone(),
            backoff: self.backoff,
            trust_lr: self.trust_lr,
            mistake_correcting: self.mistake_correcting,
        }
    }
}

/// `advice-reuse`: AdHocTD whose advisee reuses stored advice.
pub(crate) struct AdviceReuseMethod;

impl Method for AdviceReuseMethod {
    type Settings = AdviceReuse;
    const NAME: &'static str = "advice-reuse";
    const ABOUT: &'static str =
        "AdHocTD whose advisee reuses the advice it stored (Zhu et al., JAAMAS 2023)";
    const WRITTEN_WHEN_TRUE: &'static [&'static str] = &["backoff"];

    fn defaults(_: Profile) -> AdviceReuse {
        let td = AdHoc::td();
        AdviceReuse {
            v_a: td.v_a,
            v_g: td.v_g,
            ask_budget: td.ask_budget,
            give_budget: td.give_budget,
            reachable: td.reachable,
            backoff: td.backoff,
            trust_lr: td.trust_lr,
            mistake_correcting: false,
            reuse_rule: ReuseRule::QChange,
            q_change_threshold: 0.001,
            reuse_decay: 0.9,
        }
    }

    fn validate(settings: &AdviceReuse) -> Result<(), AgentConfigError> {
        settings.ad_hoc().validate()?;
        require_non_negative("q_change_threshold", settings.q_change_threshold)?;
        require_unit("reuse_decay", settings.reuse_decay)
    }

    fn strategy(settings: &AdviceReuse, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(ReusingAdvice {
            ad_hoc: AdHocAdvising::new(Confidence::Td, settings.ad_hoc()),
            rule: settings.clone(),
            kept: FnvHashMap::default(),
        })
    }
}

/// The advice kept for one state.
#[derive(Clone, Copy, Debug)]
struct Kept {
    action: Action,
    /// Its values in the state when the advice was last played (q-change
    /// rules).
    values: Option<[f64; ACTIONS]>,
    /// The probability of the next reuse (decay).
    p: f64,
}

/// Ad hoc advising with a memory of the advice followed.
#[derive(Clone, Debug)]
struct ReusingAdvice {
    ad_hoc: AdHocAdvising,
    rule: AdviceReuse,
    kept: FnvHashMap<u64, Kept>,
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
    /// the advised action's value rose by more than the threshold since the
    /// advice was last played (q-change-either: while its values moved by
    /// more than it), then it forgets the advice; decay with a probability
    /// that shrinks at every reuse.
    fn reuse(
        &mut self,
        at: &ReuseContext<'_>,
        values: &mut dyn FnMut() -> ActionValues,
        rng: &mut AgentRng,
    ) -> Option<Action> {
        let key = at.key;
        let kept = self.kept.get_mut(&key)?;
        let threshold = self.rule.q_change_threshold;
        match self.rule.reuse_rule {
            ReuseRule::QChange | ReuseRule::QChangeEither => {
                let now = values().q;
                let moving = kept.values.is_none_or(|then| match self.rule.reuse_rule {
                    ReuseRule::QChange => {
                        let a = kept.action.index();
                        now[a] - then[a] > threshold
                    }
                    _ => change(&now, &then) > threshold,
                });
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

    fn mistake_correcting(&self) -> bool {
        self.ad_hoc.mistake_correcting()
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

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        self.ad_hoc.exhausted(counters)
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        self.ad_hoc.spent_budget(counters)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action::Shoot;
    use rand::SeedableRng;

    /// A student that followed Shoot in state 7, reusing by `rule`.
    fn student(rule: ReuseRule) -> ReusingAdvice {
        let settings = AdviceReuse {
            reuse_rule: rule,
            ..AdviceReuseMethod::defaults(Profile::Paper)
        };
        let mut s = ReusingAdvice {
            ad_hoc: AdHocAdvising::new(Confidence::Td, settings.ad_hoc()),
            rule: settings,
            kept: FnvHashMap::default(),
        };
        let advice = [Advice {
            advisor: 1,
            action: Shoot,
        }];
        let replies = Replies {
            key: 7,
            advice: &advice,
            ..Replies::default()
        };
        let mut rng = AgentRng::seed_from_u64(1);
        s.follow(&replies, VoteTies::Fixed, &mut rng);
        s
    }

    /// Whether it reuses in state 7 when Shoot's value is `q` (the others 0).
    fn reuses(s: &mut ReusingAdvice, q: f64) -> bool {
        let mut values = || {
            let mut v = ActionValues::default();
            v.q[Shoot.index()] = q;
            v
        };
        let counters = AdviceCounters::default();
        let at = ReuseContext {
            key: 7,
            state: &[0.0; 6],
            features: &[],
            training_episodes: 1,
            counters: &counters,
        };
        s.reuse(&at, &mut values, &mut AgentRng::seed_from_u64(1))
            .is_some()
    }

    #[test]
    fn q_change_reuses_while_the_advice_raises_its_value() {
        let mut s = student(ReuseRule::QChange);
        assert!(reuses(&mut s, 0.1), "the first visit reuses");
        assert!(reuses(&mut s, 0.2), "a rise reuses");
        assert!(!reuses(&mut s, 0.1), "a fall forgets the advice");
        assert!(!reuses(&mut s, 0.5), "forgotten");
        // The first reading reused on a fall too.
        let mut s = student(ReuseRule::QChangeEither);
        assert!(reuses(&mut s, 0.2) && reuses(&mut s, 0.1));
        assert!(!reuses(&mut s, 0.1), "no change forgets the advice");
    }
}
