//! Each strategy's settings, with the paper's defaults, and their checks.

use serde::{Deserialize, Serialize};

use crate::advice::Reachable;
use crate::algorithm::Algorithm;
use crate::config_error::{AgentConfigError, require, require_non_negative, require_unit};
use crate::fidelity::Profile;

/// The paper's budget of every advising and sharing side.
const PAPER_BUDGET: u64 = 1000;

/// The confidence function Psi of an ad hoc advisor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Confidence {
    /// Visit-based: `Psi = log2 n(s)` (AdHocVisit).
    Visit,
    /// TD-based: `Psi = sqrt(n(s)) * spread of Q(s, .)` (AdHocTD).
    Td,
}

/// The constants of ad hoc advising (Algorithms 1 and 2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdHoc {
    /// The advisor's confidence function: `adhoc-visit` or `adhoc-td`.
    pub confidence: Confidence,
    /// Scaling v_a of P_ask, finite and >= 0 (default 0.5).
    pub v_a: f64,
    /// Scaling v_g of P_give, finite and >= 0 (default 0.5 for `adhoc-visit`,
    /// 0.4 under the authors' profile, 1.5 for `adhoc-td`).
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
    /// Ad hoc advising with `confidence` and the paper's constants.
    pub fn new(confidence: Confidence) -> Self {
        Self {
            confidence,
            v_a: 0.5,
            v_g: match confidence {
                Confidence::Visit => 0.5,
                Confidence::Td => 1.5,
            },
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
        Self::new(Confidence::Visit)
    }

    /// AdHocTD with the paper's constants.
    pub fn td() -> Self {
        Self::new(Confidence::Td)
    }
}

/// The constants of Torrey's importance advising from the fixed teacher
/// `(i + 1) mod n`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Torrey {
    /// The teacher advises when the spread of Q(s, .) exceeds this
    /// importance threshold t, finite and >= 0 (default 0.01).
    pub importance_threshold: f64,
    /// Teacher budget: answers given (default 1000).
    pub give_budget: u64,
    /// Mistake Correcting, as for [`AdHoc::mistake_correcting`] (default off).
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

/// The constants of the action-advising baselines of Ilhan, Gow & Perez-
/// Liebana (early and random advising): an advisee asks its reachable set
/// at a training step with the ball, every time (early advising) or with
/// probability `ask_probability` (random advising), while its ask budget
/// lasts; an advisor answers about a state it visited while its give budget
/// lasts (docs/algorithms.md section 7).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Budgeted {
    /// The probability of asking at a step (1 for early advising; default
    /// 0.5 for random advising), in [0, 1].
    pub ask_probability: f64,
    /// Advisee budget: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given (default 1000).
    pub give_budget: u64,
    /// The reachable set G: whom the advisee asks (default everyone).
    pub reachable: Reachable,
}

impl Budgeted {
    /// Asking with probability `ask_probability` and the paper's budgets.
    pub fn new(ask_probability: f64) -> Self {
        Self {
            ask_probability,
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
        }
    }
}

/// How an advice-reuse student decides to reuse the advice it stored for a
/// state (Zhu et al., JAAMAS 2023).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReuseRule {
    /// "Q-change per step": reuse while its own values in the state still
    /// change, between visits, by more than `q_change_threshold`.
    QChange,
    /// "Decay reusing probability": reuse with a probability that starts at
    /// 1 and is multiplied by `reuse_decay` at each reuse.
    Decay,
}

/// The memory of an advice-reuse student (Zhu et al., "Learning by reusing
/// previous advice: a memory-based teacher-student framework", JAAMAS
/// 2023): it keeps the advice it followed per state and reuses it on later
/// visits instead of asking.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Reuse {
    /// Which rule decides a reuse (default `q-change`).
    pub reuse_rule: ReuseRule,
    /// `q-change`: the change of its values (largest over the actions)
    /// above which it still reuses, finite and >= 0 (default 0.01).
    pub q_change_threshold: f64,
    /// `decay`: the factor of the reuse probability after each reuse, in
    /// [0, 1] (default 0.9).
    pub reuse_decay: f64,
}

impl Default for Reuse {
    fn default() -> Self {
        Self {
            reuse_rule: ReuseRule::QChange,
            q_change_threshold: 0.01,
            reuse_decay: 0.9,
        }
    }
}

/// The constants of peer learning (Derstroff et al., AAAI 2024): whom to
/// follow by trust learned from outcomes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeerLearning {
    /// Advisee budget: steps acted on a peer's recommendation (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: recommendations given (default 1000).
    pub give_budget: u64,
    /// The peers asked (default everyone).
    pub reachable: Reachable,
    /// The softmax temperature T of the choice among recommendations,
    /// finite and > 0 (default 1, the paper's).
    pub temperature: f64,
    /// The learning rate of trust, in [0, 1] (default 0.001, the paper's).
    pub trust_lr: f64,
    /// Decisions a chosen peer (or its own choice) is followed for, at
    /// least 1 (default 10, the paper's).
    pub follow_steps: u32,
}

impl Default for PeerLearning {
    fn default() -> Self {
        Self {
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
            temperature: 1.0,
            trust_lr: 0.001,
            follow_steps: 10,
        }
    }
}

/// The constants of RCMP (da Silva et al., AAAI 2020): ask where the
/// ensemble's heads disagree.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rcmp {
    /// Heads K of the ensemble, 2 to 64 (default 5).
    pub heads: u32,
    /// The probability p that a head learns a transition (its bootstrap
    /// mask), in (0, 1] (default 0.5).
    pub mask_probability: f64,
    /// Ask where the heads' variance exceeds it, finite and >= 0 (default
    /// 0.001: a first update of a head, alpha 0.1, leaves 0.0025).
    pub uncertainty_threshold: f64,
    /// Advisee budget: steps acted on advice (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given (default 1000).
    pub give_budget: u64,
    /// The reachable set G (default everyone).
    pub reachable: Reachable,
}

impl Default for Rcmp {
    fn default() -> Self {
        Self {
            heads: 5,
            mask_probability: 0.5,
            uncertainty_threshold: 0.001,
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
        }
    }
}

/// The constants of the Partaker-Sharer Advising Framework (Zhu et al.,
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

/// Which learner and advising strategy an agent runs, with its constants.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum Strategy {
    /// SARSA(lambda) alone.
    #[default]
    NoAdvice,
    /// Ad hoc advising (AdHocVisit or AdHocTD).
    AdHoc(AdHoc),
    /// Importance advising from a fixed teacher.
    Torrey(Torrey),
    /// Tan's episode sharing after goal episodes.
    EpisodeSharing {
        /// Transitions sent, one unit per transition per receiver (default 1000).
        sharing_budget: u64,
    },
    /// The authors' random baseline: never learns, never advises.
    Random,
    /// Early advising: ask at every step until the budget is spent
    /// (`ask_probability` is 1).
    EarlyAdvising(Budgeted),
    /// Random advising: ask with a fixed probability.
    RandomAdvising(Budgeted),
    /// AdHocTD whose advisee reuses the advice it stored per state.
    AdviceReuse(AdHoc, Reuse),
    /// Peer learning: follow recommendations by trust.
    PeerLearning(PeerLearning),
    /// RCMP: ask by the uncertainty of an ensemble.
    Rcmp(Rcmp),
    /// PSAF: share values instead of actions.
    Psaf(Psaf),
    /// Decisions given from outside (a strategy process, or
    /// `Agent::with_strategy`); until given, NoAdvice's.
    External,
}

impl From<Algorithm> for Strategy {
    /// The strategy `name` with the paper's constants.
    fn from(name: Algorithm) -> Self {
        Strategy::of(name, Profile::Paper)
    }
}

impl Strategy {
    /// The strategy `name` with the constants of `profile`.
    pub fn of(name: Algorithm, profile: Profile) -> Self {
        match name {
            Algorithm::NoAdvice => Strategy::NoAdvice,
            Algorithm::AdHocVisit => Strategy::AdHoc(AdHoc {
                v_g: profile.visit_v_g(),
                ..AdHoc::visit()
            }),
            Algorithm::AdHocTd => Strategy::AdHoc(AdHoc::td()),
            Algorithm::Torrey => Strategy::Torrey(Torrey::default()),
            Algorithm::EpisodeSharing => Strategy::EpisodeSharing {
                sharing_budget: PAPER_BUDGET,
            },
            Algorithm::Random => Strategy::Random,
            Algorithm::EarlyAdvising => Strategy::EarlyAdvising(Budgeted::new(1.0)),
            Algorithm::RandomAdvising => Strategy::RandomAdvising(Budgeted::new(0.5)),
            Algorithm::AdviceReuse => Strategy::AdviceReuse(AdHoc::td(), Reuse::default()),
            Algorithm::PeerLearning => Strategy::PeerLearning(PeerLearning::default()),
            Algorithm::Rcmp => Strategy::Rcmp(Rcmp::default()),
            Algorithm::Psaf => Strategy::Psaf(Psaf::default()),
            Algorithm::External => Strategy::External,
        }
    }

    /// Its name.
    pub fn name(&self) -> Algorithm {
        match self {
            Strategy::NoAdvice => Algorithm::NoAdvice,
            Strategy::AdHoc(a) => match a.confidence {
                Confidence::Visit => Algorithm::AdHocVisit,
                Confidence::Td => Algorithm::AdHocTd,
            },
            Strategy::Torrey(_) => Algorithm::Torrey,
            Strategy::EpisodeSharing { .. } => Algorithm::EpisodeSharing,
            Strategy::Random => Algorithm::Random,
            Strategy::EarlyAdvising(_) => Algorithm::EarlyAdvising,
            Strategy::RandomAdvising(_) => Algorithm::RandomAdvising,
            Strategy::AdviceReuse(..) => Algorithm::AdviceReuse,
            Strategy::PeerLearning(_) => Algorithm::PeerLearning,
            Strategy::Rcmp(_) => Algorithm::Rcmp,
            Strategy::Psaf(_) => Algorithm::Psaf,
            Strategy::External => Algorithm::External,
        }
    }

    /// Whether it runs in Mistake Correcting mode.
    pub fn mistake_correcting(&self) -> bool {
        match self {
            Strategy::AdHoc(a) => a.mistake_correcting,
            Strategy::Torrey(t) => t.mistake_correcting,
            _ => false,
        }
    }

    /// Switches Mistake Correcting on or off; switching it on is an error for
    /// a strategy without that mode.
    pub fn set_mistake_correcting(&mut self, on: bool) -> Result<(), AgentConfigError> {
        match self {
            Strategy::AdHoc(AdHoc {
                mistake_correcting, ..
            })
            | Strategy::Torrey(Torrey {
                mistake_correcting, ..
            }) => *mistake_correcting = on,
            _ if on => {
                return Err(AgentConfigError::new(
                    "mistake_correcting",
                    format!(
                        "only for adhoc-visit, adhoc-td and torrey, not {}",
                        self.name()
                    ),
                ));
            }
            _ => {}
        }
        Ok(())
    }

    /// Switches the back-off after unanswered requests on or off; switching
    /// it on is an error for a method other than the ad hoc ones.
    pub fn set_backoff(&mut self, on: bool) -> Result<(), AgentConfigError> {
        match self {
            Strategy::AdHoc(a) | Strategy::AdviceReuse(a, _) => a.backoff = on,
            _ if on => {
                return Err(AgentConfigError::new(
                    "backoff",
                    format!(
                        "only for adhoc-visit, adhoc-td and advice-reuse, not {}",
                        self.name()
                    ),
                ));
            }
            _ => {}
        }
        Ok(())
    }

    /// Sets the ad hoc methods' trust learning rate (none: no trust); a
    /// rate is an error for a method other than the ad hoc ones.
    pub fn set_trust(&mut self, trust_lr: Option<f64>) -> Result<(), AgentConfigError> {
        match self {
            Strategy::AdHoc(a) | Strategy::AdviceReuse(a, _) => a.trust_lr = trust_lr,
            _ if trust_lr.is_some() => {
                return Err(AgentConfigError::new(
                    "trust_lr",
                    format!(
                        "trust for adhoc-visit, adhoc-td and advice-reuse, or peer-learning's own, not {}",
                        self.name()
                    ),
                ));
            }
            _ => {}
        }
        Ok(())
    }

    /// Returns the first invalid constant, naming its key.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
        if let Strategy::AdHoc(AdHoc {
            trust_lr: Some(lr), ..
        })
        | Strategy::AdviceReuse(
            AdHoc {
                trust_lr: Some(lr), ..
            },
            _,
        ) = self
            && !(*lr > 0.0 && *lr <= 1.0)
        {
            return Err(AgentConfigError::new(
                "trust_lr",
                format!("must be in (0, 1], got {lr}"),
            ));
        }
        match self {
            Strategy::Psaf(p) => {
                require_non_negative("v_a", p.v_a)?;
                require_non_negative("v_g", p.v_g)?;
                if let Reachable::WithinDistance(d) = p.reachable {
                    require_non_negative("reachable", d)?;
                }
                Ok(())
            }
            Strategy::Rcmp(r) => {
                if !(2..=64).contains(&r.heads) {
                    return Err(AgentConfigError::new(
                        "heads",
                        format!("must be 2 to 64, got {}", r.heads),
                    ));
                }
                let p = r.mask_probability;
                require("mask_probability", p, "in (0, 1]", p > 0.0 && p <= 1.0)?;
                require_non_negative("uncertainty_threshold", r.uncertainty_threshold)?;
                if let Reachable::WithinDistance(d) = r.reachable {
                    require_non_negative("reachable", d)?;
                }
                Ok(())
            }
            Strategy::PeerLearning(p) => {
                require(
                    "temperature",
                    p.temperature,
                    "finite and > 0",
                    p.temperature > 0.0,
                )?;
                require_unit("trust_lr", p.trust_lr)?;
                if p.follow_steps == 0 {
                    return Err(AgentConfigError::new("follow_steps", "must be at least 1"));
                }
                if let Reachable::WithinDistance(d) = p.reachable {
                    require_non_negative("reachable", d)?;
                }
                Ok(())
            }
            Strategy::AdviceReuse(a, r) => {
                Strategy::AdHoc(a.clone()).validate()?;
                require_non_negative("q_change_threshold", r.q_change_threshold)?;
                require_unit("reuse_decay", r.reuse_decay)
            }
            Strategy::AdHoc(a) => {
                require_non_negative("v_a", a.v_a)?;
                require_non_negative("v_g", a.v_g)?;
                if let Reachable::WithinDistance(d) = a.reachable {
                    require_non_negative("reachable", d)?;
                }
                Ok(())
            }
            Strategy::Torrey(t) => {
                require_non_negative("importance_threshold", t.importance_threshold)
            }
            Strategy::EarlyAdvising(b) | Strategy::RandomAdvising(b) => {
                require_unit("ask_probability", b.ask_probability)?;
                if let Reachable::WithinDistance(d) = b.reachable {
                    require_non_negative("reachable", d)?;
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }

    /// Its reachable set, for the methods that ask a set of advisors.
    pub fn reachable(&self) -> Option<&Reachable> {
        match self {
            Strategy::AdHoc(a) | Strategy::AdviceReuse(a, _) => Some(&a.reachable),
            Strategy::PeerLearning(p) => Some(&p.reachable),
            Strategy::Rcmp(r) => Some(&r.reachable),
            Strategy::Psaf(p) => Some(&p.reachable),
            Strategy::EarlyAdvising(b) | Strategy::RandomAdvising(b) => Some(&b.reachable),
            _ => None,
        }
    }

    /// Checks the agent ids its reachable set names against the team size.
    pub(crate) fn check_team(&self, team_size: usize) -> Result<(), AgentConfigError> {
        let bad = |j: usize| {
            AgentConfigError::new(
                "reachable",
                format!("agent {j} is out of range or repeated"),
            )
        };
        match self.reachable() {
            Some(Reachable::Agents(ids)) => {
                for (k, &j) in ids.iter().enumerate() {
                    if j >= team_size || ids[..k].contains(&j) {
                        return Err(bad(j));
                    }
                }
                Ok(())
            }
            Some(&Reachable::Star(hub)) if hub >= team_size => Err(bad(hub)),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_gives_its_strategy_with_the_papers_constants() {
        for name in Algorithm::ALL {
            assert_eq!(Strategy::from(name).name(), name);
            Strategy::from(name).validate().unwrap();
        }
        let Strategy::AdHoc(visit) = Strategy::from(Algorithm::AdHocVisit) else {
            panic!("adhoc-visit is ad hoc");
        };
        let Strategy::AdHoc(td) = Strategy::from(Algorithm::AdHocTd) else {
            panic!("adhoc-td is ad hoc");
        };
        assert_eq!((visit.v_a, visit.v_g, td.v_a, td.v_g), (0.5, 0.5, 0.5, 1.5));
        assert_eq!(
            (visit.ask_budget, visit.give_budget, visit.reachable),
            (1000, 1000, Reachable::Everyone)
        );
        assert_eq!(
            Torrey::default(),
            Torrey {
                importance_threshold: 0.01,
                give_budget: 1000,
                mistake_correcting: false
            }
        );
        assert_eq!(
            Strategy::from(Algorithm::EpisodeSharing),
            Strategy::EpisodeSharing {
                sharing_budget: 1000
            }
        );
    }

    #[test]
    fn mistake_correcting_only_where_it_exists() {
        for name in Algorithm::ALL {
            let mut s = Strategy::from(name);
            assert!(!s.mistake_correcting());
            let set = s.set_mistake_correcting(true);
            assert_eq!(set.is_ok(), name.supports_mistake_correcting(), "{name}");
            assert_eq!(s.mistake_correcting(), set.is_ok(), "{name}");
            s.set_mistake_correcting(false).unwrap();
            assert!(!s.mistake_correcting());
        }
        let e = Strategy::NoAdvice.set_mistake_correcting(true).unwrap_err();
        assert_eq!(e.key, "mistake_correcting");
        assert!(e.reason.contains("no-advice"), "{e}");
    }

    #[test]
    fn bad_constants_name_their_key() {
        let key = |s: Strategy| s.validate().unwrap_err().key;
        let v_g = AdHoc {
            v_g: -1.0,
            ..AdHoc::td()
        };
        assert_eq!(key(Strategy::AdHoc(v_g)), "v_g");
        let v_a = AdHoc {
            v_a: f64::NAN,
            ..AdHoc::visit()
        };
        assert_eq!(key(Strategy::AdHoc(v_a)), "v_a");
        let far = AdHoc {
            reachable: Reachable::WithinDistance(f64::INFINITY),
            ..AdHoc::td()
        };
        assert_eq!(key(Strategy::AdHoc(far)), "reachable");
        let t = Torrey {
            importance_threshold: -0.1,
            ..Torrey::default()
        };
        assert_eq!(key(Strategy::Torrey(t)), "importance_threshold");
        let twice = AdHoc {
            reachable: Reachable::Agents(vec![1, 1]),
            ..AdHoc::td()
        };
        assert_eq!(
            Strategy::AdHoc(twice).check_team(3).unwrap_err().key,
            "reachable"
        );
        let outside = AdHoc {
            reachable: Reachable::Agents(vec![3]),
            ..AdHoc::td()
        };
        assert!(Strategy::AdHoc(outside).check_team(3).is_err());
    }
}
