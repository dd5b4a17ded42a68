//! The Partaker-Sharer Advising Framework (Zhu, Leung, Hu & Cai, "A
//! Q-values Sharing Framework for Multiple Independent Q-learners", AAMAS
//! 2019, and arXiv 2011.14281; docs/algorithms.md section 7): agents share
//! values instead of actions. A partaker that visited a state little asks,
//! sending how often it took each action there; a sharer more confident in
//! its best action than the partaker is sends that action's value, which the
//! partaker takes as its own before it plays greedily.

use proto::Action;
use serde::{Deserialize, Serialize};

use super::seam::{Adopted, AdvisingStrategy, AskContext, GiveContext, Replies};
use crate::advice::{PAPER_BUDGET, Reachable, p_ask, p_give, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require_non_negative};
use crate::exchange::Advice;
use crate::fidelity::VoteTies;
use crate::fidelity::{Fidelity, Profile};
use crate::learner::ActionValues;
use crate::method::Method;
use crate::selection::{AgentRng, chance, greedy_first};

/// What a PSAF sharer shares.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PsafShares {
    /// The AAMAS 2019 rule: its best action a* and max_a Q(s, a), when its
    /// confidence m(s, a*) x D(s), D(s) = 1 - 1 / (max Q - min Q + 1),
    /// exceeds the partaker's m(s, a*); the partaker overwrites its
    /// Q(s, a*) with the largest value shared and plays greedily.
    Best,
    /// This project's first reading: the whole row Q(s, .) with P_give of
    /// its visits; the partaker takes the row of the sharer that visited the
    /// state most, if more than it did, and plays its epsilon-greedy choice.
    Row,
}

/// The settings of the Partaker-Sharer Advising Framework (Zhu et al.,
/// AAMAS 2019): a partaker asks with P_ask; sharers more confident than it
/// share their best value; separate budgets.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Psaf {
    /// What a sharer shares (default `best`, the paper's).
    pub shares: PsafShares,
    /// Scaling v_a of the partaker's P_ask = (1 + v_a)^(-sqrt n(s)),
    /// finite and >= 0 (default 0.7, the paper's v_p).
    pub v_a: f64,
    /// `row`: scaling v_g of the sharer's P_give = 1 - (1 + v_g)^(-log2
    /// n(s)), finite and >= 0 (default 0.5).
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
            shares: PsafShares::Best,
            v_a: 0.7,
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

/// A sharer's confidence in its best action a* of a state:
/// m(s, a*) x D(s), with D(s) = 1 - 1 / (max Q - min Q + 1) over the kick
/// actions it learned there (0 with none learned).
fn confidence(values: &ActionValues, action_visits: &[u32; 5]) -> (Action, f64) {
    let best = greedy_first(&values.q);
    let learned = Action::KICK_TIE_ORDER
        .iter()
        .filter(|a| values.learned & (1 << a.index()) != 0)
        .map(|a| values.q[a.index()]);
    let (min, max) = learned.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
        (lo.min(q), hi.max(q))
    });
    let spread = if max >= min {
        1.0 - 1.0 / (max - min + 1.0)
    } else {
        0.0
    };
    (best, f64::from(action_visits[best.index()]) * spread)
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

    fn shares_best(&self) -> bool {
        self.shares == PsafShares::Best
    }

    /// Give budget left, a visited state, and `best`: its confidence in its
    /// best action above the partaker's visits of it (0 where the request
    /// did not say); `row`: P_give of its visits.
    fn gives(&mut self, at: &GiveContext<'_>, rng: &mut AgentRng) -> bool {
        if at.counters.advice_given >= self.give_budget || at.visits == 0 {
            return false;
        }
        match self.shares {
            PsafShares::Best => {
                let (best, mine) = confidence(at.values, &at.action_visits);
                let theirs = at.asker_visits.map_or(0, |m| m[best.index()]);
                mine > f64::from(theirs)
            }
            PsafShares::Row => chance(rng, p_give(psi_visit(at.visits), self.v_g)),
        }
    }

    /// `best`: the largest value shared, with its action; `row`: the values
    /// of the sharer with the most visits (the first of them), if it visited
    /// the state more than the partaker did.
    fn adopt(&mut self, replies: &Replies<'_>, visits: u64) -> Option<Adopted> {
        match self.shares {
            PsafShares::Best => (replies.best.iter())
                .rev()
                .max_by(|a, b| a.value.total_cmp(&b.value))
                .map(|b| Adopted::Best {
                    action: b.action,
                    value: b.value,
                }),
            PsafShares::Row => (replies.values.iter())
                .filter(|v| v.values.visits > visits)
                .rev()
                .max_by_key(|v| v.values.visits)
                .map(|v| Adopted::Row(v.values)),
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exchange::BestValue;
    use proto::Action::{Dribble, Shoot};
    use rand::SeedableRng;

    fn values(shoot: f64, dribble: f64) -> ActionValues {
        let mut v = ActionValues::default();
        v.q[Shoot.index()] = shoot;
        v.q[Dribble.index()] = dribble;
        v.learned = 1 << Shoot.index() | 1 << Dribble.index();
        v
    }

    #[test]
    fn a_sharer_shares_when_more_confident_in_its_best_action() {
        let mut psaf = Psaf::default();
        let counters = AdviceCounters::default();
        let mut rng = AgentRng::seed_from_u64(1);
        // Shoot is best; D = 1 - 1 / (0.8 - (-0.2) + 1) = 0.5; 6 visits of
        // Shoot give a confidence of 3.
        let v = values(0.8, -0.2);
        let mut mine = [0; 5];
        mine[Shoot.index()] = 6;
        let mut asker = |m: u32| {
            let mut theirs = [9; 5];
            theirs[Shoot.index()] = m;
            let at = GiveContext {
                asker: 1,
                state: &[0.0; 6],
                features: &[],
                visits: 6,
                action_visits: mine,
                values: &v,
                asker_visits: Some(theirs),
                counters: &counters,
            };
            psaf.gives(&at, &mut rng)
        };
        assert!(asker(2), "3 > 2");
        assert!(!asker(3), "3 is not above 3");
        // Equal values: no spread, no confidence.
        let flat = values(0.5, 0.5);
        let at = GiveContext {
            asker: 1,
            state: &[0.0; 6],
            features: &[],
            visits: 6,
            action_visits: [6; 5],
            values: &flat,
            asker_visits: Some([0; 5]),
            counters: &counters,
        };
        assert!(!psaf.gives(&at, &mut rng));
    }

    #[test]
    fn a_partaker_adopts_the_largest_best_value() {
        let mut psaf = Psaf::default();
        let best = [
            BestValue {
                advisor: 1,
                action: Shoot,
                value: 0.3,
            },
            BestValue {
                advisor: 2,
                action: Dribble,
                value: 0.7,
            },
        ];
        let replies = Replies {
            best: &best,
            ..Replies::default()
        };
        assert_eq!(
            psaf.adopt(&replies, 100),
            Some(Adopted::Best {
                action: Dribble,
                value: 0.7
            })
        );
        assert_eq!(psaf.adopt(&Replies::default(), 0), None);
    }
}
