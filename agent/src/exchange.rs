//! The advising seam: how an agent reaches the others, whatever the transport.
//!
//! Budgets, probabilities and votes live in the agent ([`crate::Agent::advise`],
//! [`crate::Agent::receive_shared`]); an exchange only carries messages.

use proto::{
    Action, AdviceAnswer, Along, Features, SharedValues, Standing, State, TransitionNote,
    ValuesAnswer,
};

/// One step of a shared episode, `(s, a, r, s', a')`: the wire type itself,
/// so that a transport ships shared episodes as they are.
pub use proto::SharedTransition as Transition;

/// What an agent sends one teammate unasked at an episode's end, and how
/// the receiver learns it.
#[derive(Clone, Debug, PartialEq)]
pub enum Share {
    /// An episode's transitions, replayed step by step (EpisodeSharing's
    /// goal episodes): [`Learner::replay`](crate::Learner::replay).
    Episode(Vec<Transition>),
    /// Experience learned as one batch
    /// ([`Learner::learn_batch`](crate::Learner::learn_batch)), at most
    /// [`proto::MAX_BATCH`] transitions (the framework keeps the first that
    /// many) and one batch per receiver and episode (the framework drops a
    /// second).
    Batch(Batch),
}

impl Share {
    /// The transitions it carries.
    pub fn transitions(&self) -> &[Transition] {
        match self {
            Share::Episode(t) => t,
            Share::Batch(b) => &b.transitions,
        }
    }
}

/// A batch of experience and what its sender says with it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Batch {
    /// The transitions.
    pub transitions: Vec<Transition>,
    /// What the sender notes of each transition: one per transition, or
    /// none (the framework drops notes that are neither).
    pub notes: Vec<TransitionNote>,
    /// The sender's standing, if it tells one.
    pub standing: Option<Standing>,
}

impl Batch {
    /// Why the wire cannot carry it as it is, if it cannot
    /// ([`proto::check_batch`]).
    pub fn check(&self) -> Result<(), String> {
        proto::check_batch(&self.transitions, &self.notes, self.standing.as_ref())
    }

    /// Its transitions at `indices`, in that order (what a strategy naming
    /// them by index chose to learn), or which index it does not have.
    pub fn chosen(&self, indices: &[usize]) -> Result<Vec<Transition>, String> {
        let n = self.transitions.len();
        (indices.iter())
            .map(|&i| {
                (self.transitions.get(i).copied())
                    .ok_or_else(|| format!("transition {i} of a batch of {n}"))
            })
            .collect()
    }
}

impl From<Vec<Transition>> for Batch {
    /// The transitions alone.
    fn from(transitions: Vec<Transition>) -> Self {
        Batch {
            transitions,
            ..Batch::default()
        }
    }
}

/// One piece of advice and who gave it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Advice {
    /// The advisor's id.
    pub advisor: usize,
    /// The action it advises.
    pub action: Action,
}

/// An advisee's report to an advisor of how a decision on which the
/// advisor's advice arrived turned out (a strategy that
/// [`reports_advice_outcomes`](crate::AdvisingStrategy::reports_advice_outcomes)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdviceReport {
    /// The advisor's id.
    pub advisor: usize,
    /// Whether the advisee played the action it advised.
    pub followed: bool,
    /// The decision's advantage (as [`Outcome::advantage`](crate::Outcome::advantage)).
    pub advantage: f64,
}

/// One sharer's values of a state (a value-sharing method's answer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValuesAdvice {
    /// The sharer's id.
    pub advisor: usize,
    /// Its values and visits.
    pub values: SharedValues,
}

/// One sharer's best action in a state and its value, max_a Q(s, a)
/// (PSAF's answer).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BestValue {
    /// The sharer's id.
    pub advisor: usize,
    /// Its best action.
    pub action: Action,
    /// That action's value.
    pub value: f64,
}

/// An advisor's answer to one request, as its method answers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Answer {
    /// An action, or none (and why).
    Action(AdviceAnswer),
    /// Its values of the state, or none (a value-sharing method).
    Values(ValuesAnswer),
}

impl Answer {
    /// Whether it says the advisor's give budget is spent.
    pub fn exhausted(&self) -> bool {
        matches!(
            self,
            Answer::Action(AdviceAnswer::Exhausted) | Answer::Values(ValuesAnswer::Exhausted)
        )
    }
}

/// What arrived for one request: actions advised and values shared, and
/// how many replies brought neither.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Answers {
    /// The actions advised, with who advised them.
    pub advice: Vec<Advice>,
    /// The values shared, with who shared them.
    pub values: Vec<ValuesAdvice>,
    /// The best values shared, with who shared them.
    pub best: Vec<BestValue>,
    /// Replies without advice from advisors that could have given some.
    pub declined: u32,
    /// Replies without advice from advisors whose give budget is spent.
    pub exhausted: u32,
    /// What the advisors that recommended said of themselves, by advisor.
    pub advisor_values: Vec<(usize, f64)>,
}

impl Answers {
    /// Forgets every answer, keeping the room.
    pub fn clear(&mut self) {
        self.advice.clear();
        self.values.clear();
        self.best.clear();
        self.declined = 0;
        self.exhausted = 0;
        self.advisor_values.clear();
    }

    /// Takes advisor `advisor`'s answer.
    pub fn take(&mut self, advisor: usize, answer: Answer) {
        match answer {
            Answer::Action(AdviceAnswer::Advice(action)) => {
                self.advice.push(Advice { advisor, action })
            }
            Answer::Action(AdviceAnswer::Recommendation(action, value)) => {
                self.advice.push(Advice { advisor, action });
                self.advisor_values.push((advisor, f64::from(value)));
            }
            Answer::Values(ValuesAnswer::Values(values)) => {
                self.values.push(ValuesAdvice { advisor, values })
            }
            Answer::Values(ValuesAnswer::Best(action, value)) => self.best.push(BestValue {
                advisor,
                action,
                value,
            }),
            Answer::Action(AdviceAnswer::Declined) | Answer::Values(ValuesAnswer::Declined) => {
                self.declined += 1
            }
            Answer::Action(AdviceAnswer::Exhausted) | Answer::Values(ValuesAnswer::Exhausted) => {
                self.exhausted += 1
            }
        }
    }
}

/// Carries advice requests, shared episodes and batches between agents.
pub trait AdviceExchange {
    /// Asks every agent of `to`, in order, for advice on `state` (with the
    /// asker's HFO `features` of it, where it has them, and what the
    /// request carries `along`: the asker's intended action in Mistake
    /// Correcting mode, its visits for PSAF) and appends each answer to
    /// `answers`; returns the replies that arrived, with or without advice
    /// (an advisor without advice replies all the same).
    fn ask(
        &mut self,
        from: usize,
        to: &[usize],
        state: &State,
        features: &Features,
        along: Along,
        answers: &mut Answers,
    ) -> u64;

    /// Delivers what `from` sends agent `to` unasked at an episode's end (a
    /// goal episode's transitions, in order, or a batch).
    fn share(&mut self, from: usize, to: usize, share: &Share);
}

/// An exchange that reaches nobody: no advice arrives and shares are dropped.
#[derive(Clone, Copy, Debug, Default)]
pub struct Isolated;

impl AdviceExchange for Isolated {
    fn ask(
        &mut self,
        _: usize,
        _: &[usize],
        _: &State,
        _: &Features,
        _: Along,
        _: &mut Answers,
    ) -> u64 {
        0
    }

    fn share(&mut self, _: usize, _: usize, _: &Share) {}
}
