//! Python learners and strategies given as objects to `run()`
//! (coordinator's `plugin` seam), called in this process with the GIL taken
//! for each call by the run's thread.
//!
//! The seams cannot return errors, so the first exception of an
//! agent's objects is kept (with the exception itself, for `run()` to raise
//! from) and every later call returns at once; the in-process backend asks
//! for it after every frame and ends the run.

use std::cell::RefCell;
use std::sync::{Arc, Mutex, PoisonError};

use agent::{
    ActionValues, Adopted, Advice, AdviceCounters, AdvisingStrategy, AdvisorTies, AgentRng,
    AskContext, Batch, EndContext, Experience, GiveContext, Learner, Outcome, Replies,
    ReuseContext, Seen, Sends, Share, Step, Transition, VoteTies,
};
use coordinator::plugin::{Plugin, PluginSpec, PluginStart};
use proto::{Action, SharedValues};
use pyo3::call::PyCallArgs;
use pyo3::prelude::*;

/// The first failure of one agent's objects: what the run ends with, and
/// the Python exception.
#[derive(Debug, Default)]
pub(crate) struct Failure(Mutex<Option<(String, PyErr)>>);

impl Failure {
    fn get(&self) -> std::sync::MutexGuard<'_, Option<(String, PyErr)>> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    fn failed(&self) -> bool {
        self.get().is_some()
    }

    /// Keeps `err` unless an earlier failure is kept.
    fn keep(&self, py: Python<'_>, what: String, err: PyErr) {
        let mut slot = self.get();
        if slot.is_none() {
            *slot = Some((format!("{what}: {}", describe(py, &err)), err));
        }
    }

    /// The kept exception, taken.
    pub(crate) fn take(&self, py: Python<'_>) -> Option<(String, Py<PyAny>)> {
        let (message, err) = self.get().take()?;
        Some((message, err.into_value(py).into_any()))
    }
}

/// One agent's objects: factories of its learner's and strategy's
/// adapters (`adhoc_advising._objects`), called with `(agent, team_size,
/// run, seed)` for every run.
#[derive(Debug)]
pub(crate) struct PythonObjects {
    pub(crate) learner: Option<Py<PyAny>>,
    pub(crate) strategy: Option<Py<PyAny>>,
    /// What the results record.
    pub(crate) spec: PluginSpec,
    pub(crate) failure: Arc<Failure>,
}

impl PythonObjects {
    /// The adapter `make` makes for `start`, as the object of `role` named
    /// `label`.
    fn make(
        &self,
        make: &Py<PyAny>,
        start: PluginStart,
        role: &str,
        label: &str,
    ) -> Result<PythonObject, String> {
        Python::attach(|py| {
            let args = (start.agent, start.team_size, start.run, start.seed);
            let object = make
                .call1(py, args)
                .map_err(|e| format!("making {role} `{label}` raised {}", describe(py, &e)))?;
            Ok(PythonObject {
                object,
                what: format!("agent {}'s {role} `{label}`", start.agent),
                failure: self.failure.clone(),
            })
        })
    }
}

impl Plugin for PythonObjects {
    fn spec(&self) -> PluginSpec {
        self.spec.clone()
    }

    fn learner(&self, start: PluginStart) -> Result<Option<Box<dyn Learner>>, String> {
        let Some(make) = &self.learner else {
            return Ok(None);
        };
        let label = self.spec.learner.as_deref().unwrap_or_default();
        let object = self.make(make, start, "learner", label)?;
        Ok(Some(Box::new(PythonLearner::new(object))))
    }

    fn strategy(&self, start: PluginStart) -> Result<Option<Box<dyn AdvisingStrategy>>, String> {
        let Some(make) = &self.strategy else {
            return Ok(None);
        };
        let label = self.spec.strategy.as_deref().unwrap_or_default();
        let object = self.make(make, start, "strategy", label)?;
        let traits = Python::attach(|py| object.answer(py, "traits", ()))
            .ok_or_else(|| self.failure().unwrap_or_default())?;
        Ok(Some(Box::new(PythonStrategy { object, traits })))
    }

    fn failure(&self) -> Option<String> {
        self.failure
            .get()
            .as_ref()
            .map(|(message, _)| message.clone())
    }
}

/// An exception as one line: its type and message.
fn describe(py: Python<'_>, err: &PyErr) -> String {
    err.value(py)
        .repr()
        .map_or_else(|_| err.to_string(), |r| r.to_string())
}

/// An adapter object of the package (`adhoc_advising._objects`), whose
/// methods take and return plain values.
#[derive(Debug)]
struct PythonObject {
    object: Py<PyAny>,
    /// "agent 2's learner `numpy-linear-sarsa 2`", for failures.
    what: String,
    failure: Arc<Failure>,
}

impl PythonObject {
    /// `method(*args)` of the object, or `None` after a failure (kept).
    fn call<'py>(
        &self,
        py: Python<'py>,
        method: &str,
        args: impl PyCallArgs<'py>,
    ) -> Option<Bound<'py, PyAny>> {
        if self.failure.failed() {
            return None;
        }
        match self.object.bind(py).call_method1(method, args) {
            Ok(v) => Some(v),
            Err(e) => {
                let what = format!("{} raised in `{method}`", self.what);
                self.failure.keep(py, what, e);
                None
            }
        }
    }

    /// What `method(*args)` answered, as a `T`, or `None` after a failure.
    fn answer<'py, T>(&self, py: Python<'py>, method: &str, args: impl PyCallArgs<'py>) -> Option<T>
    where
        T: for<'a> FromPyObject<'a, 'py, Error = PyErr>,
    {
        match self.call(py, method, args)?.extract() {
            Ok(v) => Some(v),
            Err(e) => {
                self.refuse(py, method, e.to_string());
                None
            }
        }
    }

    /// Q(s, a) by action index as `method` answered them, `None` for
    /// unlearned; a failure unless one per action, each finite.
    fn values(&self, py: Python<'_>, method: &str, q: Vec<Option<f64>>) -> Option<ActionValues> {
        if q.len() != Action::ALL.len() {
            let reason = format!("{} values, one per action ({})", q.len(), Action::ALL.len());
            self.refuse(py, method, reason);
            return None;
        }
        let mut values = ActionValues::default();
        for (a, q) in q.into_iter().enumerate() {
            let Some(q) = q else { continue };
            if !q.is_finite() {
                self.refuse(py, method, format!("action {a} valued {q}, not finite"));
                return None;
            }
            values.q[a] = q;
            values.learned |= 1 << a;
        }
        Some(values)
    }

    /// Keeps a failure of an answer (not an exception).
    fn refuse(&self, py: Python<'_>, method: &str, reason: String) {
        let what = format!("{} answered `{method}` with what it cannot", self.what);
        let err = pyo3::exceptions::PyValueError::new_err(reason);
        self.failure.keep(py, what, err);
    }
}

/// The most transitions kept for the learner before they are handed over.
const MAX_LEARNED_AT_ONCE: usize = 64;

/// A learner adapter, called by its run's thread. `learn` keeps the
/// transition and returns at once, as it does over a learner process's
/// pipe; the kept transitions are handed over in one call (its adapter's
/// `learn` takes a list) before any other call, at the end of an episode
/// (so that a failure among them is known when its episode ends) and when
/// [`MAX_LEARNED_AT_ONCE`] are kept. The same calls in the same order: the
/// same results.
#[derive(Debug)]
struct PythonLearner {
    object: PythonObject,
    /// Transitions not yet handed over (a `RefCell` for `save_state`,
    /// which takes `&self`).
    learns: RefCell<Vec<PyTransition>>,
}

impl PythonLearner {
    fn new(object: PythonObject) -> Self {
        Self {
            object,
            learns: RefCell::default(),
        }
    }

    /// What `call` answers, made after the kept transitions are learned.
    fn ask<T>(&self, call: impl FnOnce(Python<'_>, &PythonObject) -> T) -> T {
        Python::attach(|py| {
            self.flush(py);
            call(py, &self.object)
        })
    }

    /// Hands the kept transitions to the learner.
    fn flush(&self, py: Python<'_>) {
        let learns = std::mem::take(&mut *self.learns.borrow_mut());
        if !learns.is_empty() {
            self.object.call(py, "learn", (learns,));
        }
    }
}

/// The six features as a Python tuple.
type Features = (f64, f64, f64, f64, f64, f64);

fn features(s: &proto::State) -> Features {
    (s[0], s[1], s[2], s[3], s[4], s[5])
}

/// A state as the adapter takes it: the features and the index.
fn state(at: Seen<'_>) -> (Features, Option<usize>) {
    (features(at.state), at.index)
}

/// A transition as the adapter takes it: `(state, action, reward,
/// next_state, next_action)`.
type PyTransition = (Features, usize, f64, Option<Features>, Option<usize>);

/// What a sender notes of a transition, as the adapter takes and gives it:
/// `(frames, uncertainty)`.
type PyNote = (u32, f64);

fn note((frames, uncertainty): PyNote) -> proto::TransitionNote {
    proto::TransitionNote {
        frames,
        uncertainty,
    }
}

/// A sender's standing as the adapter takes and gives it: `(episodes,
/// uncertainty, mean_return)`.
type PyStanding = (u64, Option<f64>, f64);

fn standing_of((episodes, uncertainty, mean_return): PyStanding) -> proto::Standing {
    proto::Standing {
        episodes,
        uncertainty,
        mean_return,
    }
}

/// A batch as the adapter gives it: `(to, transitions, notes, standing)`.
type PyBatch = (usize, Vec<PyTransition>, Vec<PyNote>, Option<PyStanding>);

/// A shared transition as the adapter takes it.
fn shared(t: &Transition) -> PyTransition {
    (
        features(&t.state),
        t.action.index(),
        t.reward,
        t.next.map(|(s, _)| features(&s)),
        t.next.map(|(_, a)| a.index()),
    )
}

/// A transition the adapter answered, or why it is none.
fn unshared((s, a, r, next_state, next_action): PyTransition) -> Result<Transition, String> {
    let state = |s: Features| [s.0, s.1, s.2, s.3, s.4, s.5];
    Transition::from_parts(state(s), a, r, (next_state.map(state), next_action))
}

/// What the strategy is told at an episode's end: the final reward, the
/// outcome's name, the return, its id, the team size and the counters.
type PyEnd = (f64, &'static str, f64, usize, usize, PyCounters);

fn end(e: &EndContext<'_>) -> PyEnd {
    let c = counters(e.counters);
    (
        e.final_reward,
        e.outcome.name(),
        e.episode_return,
        e.me,
        e.team_size,
        c,
    )
}

fn transition((from, reward, next): &Experience<'_>) -> PyTransition {
    (
        features(from.at.state),
        from.action.index(),
        *reward,
        next.map(|n: Step<'_>| features(n.at.state)),
        next.map(|n| n.action.index()),
    )
}

impl Learner for PythonLearner {
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        self.ask(|py, o| {
            let q = o.answer(py, "values", state(at));
            q.and_then(|q| o.values(py, "values", q))
        })
        .unwrap_or_default()
    }

    fn choose(&mut self, at: Seen<'_>, _: &mut AgentRng) -> Action {
        self.ask(|py, o| {
            let action: Option<usize> = o.answer(py, "choose", state(at));
            match action.map(|a| (a, Action::ALL.get(a))) {
                Some((_, Some(&a))) if a.is_kick() => a,
                Some((a, _)) => {
                    let reason = format!("action {a}; a kicker's actions are 1 to 4");
                    o.refuse(py, "choose", reason);
                    Action::Shoot
                }
                None => Action::Shoot,
            }
        })
    }

    fn learn(&mut self, step: Experience<'_>) {
        let learns = self.learns.get_mut();
        learns.push(transition(&step));
        if learns.len() == MAX_LEARNED_AT_ONCE {
            Python::attach(|py| self.flush(py));
        }
    }

    fn end_episode(&mut self) {
        self.ask(|py, o| {
            o.call(py, "end_episode", ());
        });
    }

    fn replay(&mut self, episode: &[Experience<'_>]) {
        let episode: Vec<PyTransition> = episode.iter().map(transition).collect();
        self.ask(|py, o| {
            o.call(py, "replay", (episode,));
        });
    }

    fn table(&self) -> Option<Vec<ActionValues>> {
        None
    }

    fn save_state(&self) -> Option<Vec<u8>> {
        self.ask(|py, o| o.answer::<Option<Vec<u8>>>(py, "save", ()))
            .flatten()
    }

    fn load_state(&mut self, state: &[u8]) -> Result<(), String> {
        let restored = self.ask(|py, o| {
            let bytes = pyo3::types::PyBytes::new(py, state);
            o.call(py, "restore", (bytes,)).is_some()
        });
        if restored {
            Ok(())
        } else {
            Err(format!(
                "{} could not restore its saved state",
                self.object.what
            ))
        }
    }

    fn restore(&mut self, _: Vec<ActionValues>) -> Result<(), String> {
        Err(format!(
            "{} keeps its learned state itself and this snapshot holds none of it (a learner \
             without `save`/`restore`, or a snapshot of another learner)",
            self.object.what
        ))
    }
}

/// What a strategy's `traits` answer: which decisions it makes (the
/// class attributes and overridden methods of `AdvisingStrategy`).
#[derive(Debug, FromPyObject)]
#[pyo3(from_item_all)]
struct Traits {
    learns: bool,
    reuses: bool,
    asks_by_uncertainty: bool,
    mistake_correcting: bool,
    intends_greedy: bool,
    shares_values: bool,
    learns_from_outcomes: bool,
    asks_by_values: bool,
    records_transitions: bool,
    ends_episodes: bool,
    ends_evaluations: bool,
    receives_batches: bool,
    reports_advice_outcomes: bool,
    hears_advice_outcomes: bool,
}

/// A strategy adapter, with the traits it answered at its start.
#[derive(Debug)]
struct PythonStrategy {
    object: PythonObject,
    traits: Traits,
}

/// Values as the adapter takes them: Q(s, a) by index, `None` unlearned.
fn values(v: &ActionValues) -> Vec<Option<f64>> {
    (Action::ALL.iter())
        .map(|&a| v.is_learned(a).then_some(v.q[a.index()]))
        .collect()
}

/// Counters in the order of the package's `Counters` fields.
type PyCounters = (u64, u64, u64, u64, u64, u64);

fn counters(c: &AdviceCounters) -> PyCounters {
    (
        c.advice_requests,
        c.advice_replies_received,
        c.ask_spent,
        c.advice_given,
        c.shared_sent,
        c.shared_received,
    )
}

/// Advice and shared values as the adapter takes them, after the key.
type PyReplies = (
    u64,
    Vec<(usize, usize)>,
    Vec<(usize, Vec<Option<f64>>, u64)>,
);

fn replies(r: &Replies<'_>) -> PyReplies {
    let advice = (r.advice.iter())
        .map(|a| (a.advisor, a.action.index()))
        .collect();
    let shared = (r.values.iter())
        .map(|v| {
            let shared = ActionValues {
                q: v.values.q,
                learned: v.values.learned,
            };
            (v.advisor, values(&shared), v.values.visits)
        })
        .collect();
    (r.key, advice, shared)
}

impl PythonStrategy {
    /// The kick action (1-4) `method` answered, or a failure.
    fn kick(&self, py: Python<'_>, method: &str, index: usize) -> Option<Action> {
        match Action::ALL.get(index) {
            Some(&a) if a.is_kick() => Some(a),
            _ => {
                let reason = format!("action {index}; a kicker's actions are 1 to 4");
                self.object.refuse(py, method, reason);
                None
            }
        }
    }
}

impl AdvisingStrategy for PythonStrategy {
    fn learns(&self) -> bool {
        self.traits.learns
    }

    fn reuse(
        &mut self,
        at: &ReuseContext<'_>,
        learner: &mut dyn FnMut() -> ActionValues,
        _: &mut AgentRng,
    ) -> Option<Action> {
        if !self.traits.reuses {
            return None;
        }
        let key = at.key;
        let v = values(&learner());
        Python::attach(|py| {
            let action: Option<usize> = self.object.answer(py, "reuse", (key, v))?;
            self.kick(py, "reuse", action?)
        })
    }

    fn asks_by_uncertainty(&self) -> bool {
        self.traits.asks_by_uncertainty
    }

    fn asks_by_values(&self) -> bool {
        self.traits.asks_by_values
    }

    fn asks(&mut self, at: &AskContext<'_>, _: &mut AgentRng) -> bool {
        let args = (
            at.fresh,
            at.visits,
            at.training_episodes,
            counters(at.counters),
            at.uncertainty,
            features(at.state),
            at.features.to_vec(),
            at.values.as_ref().map(values),
        );
        Python::attach(|py| self.object.answer(py, "asks", args)).unwrap_or(false)
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
        let positions: Vec<(f64, f64)> = positions.iter().map(|p| (p[0], p[1])).collect();
        Python::attach(|py| {
            let chosen: Option<Vec<usize>> =
                self.object
                    .answer(py, "advisors", (me, team_size, positions));
            let chosen = chosen.unwrap_or_default();
            match chosen.iter().find(|&&j| j >= team_size || j == me) {
                Some(bad) => {
                    let reason = format!(
                        "advisor {bad}; advisors are the other agents, 0 to {} but {me}",
                        team_size - 1
                    );
                    self.object.refuse(py, "advisors", reason);
                }
                None => out.extend(chosen),
            }
        });
    }

    fn mistake_correcting(&self) -> bool {
        self.traits.mistake_correcting
    }

    fn intends_greedy(&self) -> bool {
        self.traits.intends_greedy
    }

    fn shares_values(&self) -> bool {
        self.traits.shares_values
    }

    fn adopt(&mut self, r: &Replies<'_>, visits: u64) -> Option<Adopted> {
        if r.values.is_empty() {
            return None;
        }
        let (key, advice, shared) = replies(r);
        Python::attach(|py| {
            let q: Option<Vec<Option<f64>>> =
                self.object
                    .answer(py, "adopt", (key, advice, shared, visits))?;
            let v = self.object.values(py, "adopt", q?)?;
            Some(Adopted::Row(SharedValues {
                q: v.q,
                learned: v.learned,
                visits,
            }))
        })
    }

    fn gives(&mut self, at: &GiveContext<'_>, _: &mut AgentRng) -> bool {
        let args = (
            at.visits,
            values(at.values),
            counters(at.counters),
            at.asker,
            features(at.state),
            at.features.to_vec(),
        );
        Python::attach(|py| self.object.answer(py, "gives", args)).unwrap_or(false)
    }

    fn advice(&mut self, v: &ActionValues, _: AdvisorTies, _: &mut AgentRng) -> Action {
        Python::attach(|py| {
            let action: Option<usize> = self.object.answer(py, "advice", (values(v),));
            action.and_then(|a| self.kick(py, "advice", a))
        })
        .unwrap_or(Action::Shoot)
    }

    fn follow(&mut self, r: &Replies<'_>, _: VoteTies, _: &mut AgentRng) -> Option<Advice> {
        Python::attach(|py| {
            let followed: Option<(usize, usize)> = self.object.answer(py, "follow", replies(r))?;
            let (advisor, action) = followed?;
            let arrived = (r.advice.iter())
                .find(|a| a.advisor == advisor && a.action.index() == action)
                .copied();
            if arrived.is_none() {
                let reason = format!("advice {action} of agent {advisor}, which did not arrive");
                self.object.refuse(py, "follow", reason);
            }
            arrived
        })
    }

    fn learns_from_outcomes(&self) -> bool {
        self.traits.learns_from_outcomes
    }

    fn learn_outcome(&mut self, outcome: &Outcome) {
        Python::attach(|py| {
            self.object
                .call(py, "learn_outcome", (outcome.advisor, outcome.advantage));
        });
    }

    fn reports_advice_outcomes(&self) -> bool {
        self.traits.reports_advice_outcomes
    }

    fn advice_outcome(&mut self, asker: usize, followed: bool, advantage: f64) {
        if self.traits.hears_advice_outcomes {
            Python::attach(|py| {
                (self.object).call(py, "advice_outcome", (asker, followed, advantage));
            });
        }
    }

    fn records_transitions(&self, _: &AdviceCounters) -> bool {
        self.traits.records_transitions
    }

    fn learned(&mut self, t: &Transition) {
        Python::attach(|py| {
            self.object.call(py, "learned", (shared(t),));
        });
    }

    fn end_episode(&mut self, at: &EndContext<'_>) -> Sends {
        if !self.traits.ends_episodes {
            return Sends::new();
        }
        Python::attach(|py| {
            let batches: Vec<PyBatch> = self.object.answer(py, "end_episode", end(at))?;
            let sends = (batches.into_iter())
                .map(|(to, transitions, notes, standing)| {
                    if to >= at.team_size || to == at.me {
                        return Err(format!("a batch to agent {to}, not another agent"));
                    }
                    let batch = Batch {
                        transitions: (transitions.into_iter().map(unshared))
                            .collect::<Result<_, _>>()?,
                        notes: notes.into_iter().map(note).collect(),
                        standing: standing.map(standing_of),
                    };
                    batch.check().map(|()| (to, Share::Batch(batch)))
                })
                .collect::<Result<Sends, String>>();
            sends
                .map_err(|reason| self.object.refuse(py, "end_episode", reason))
                .ok()
        })
        .unwrap_or_default()
    }

    fn end_evaluation(&mut self, at: &EndContext<'_>) {
        if self.traits.ends_evaluations {
            Python::attach(|py| {
                self.object.call(py, "end_evaluation", end(at));
            });
        }
    }

    fn received(&mut self, from: usize, batch: &Batch) -> Option<Vec<Transition>> {
        if !self.traits.receives_batches {
            return None;
        }
        let transitions: Vec<PyTransition> = batch.transitions.iter().map(shared).collect();
        let notes: Vec<PyNote> = (batch.notes.iter())
            .map(|n| (n.frames, n.uncertainty))
            .collect();
        let standing = (batch.standing).map(|s| (s.episodes, s.uncertainty, s.mean_return));
        Python::attach(|py| {
            let args = (from, transitions, notes, standing);
            let chosen: Option<Vec<usize>> = self.object.answer(py, "received", args)?;
            (batch.chosen(&chosen?))
                .map_err(|reason| self.object.refuse(py, "received", reason))
                .ok()
        })
    }

    fn spent_budget(&self, c: &AdviceCounters) -> u64 {
        Python::attach(|py| self.object.answer(py, "spent_budget", (counters(c),))).unwrap_or(0)
    }
}
