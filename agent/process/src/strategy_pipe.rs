//! A strategy in a child process of its own (docs/strategies.md): the
//! advising decisions of algorithm `external`, made by a Python class (or
//! any program) over the child's standard input and output, one JSON object per
//! line ([`crate::child`]). The framework keeps the learner, the budgets'
//! counters, the exchange and the network conditions.

use std::cell::RefCell;

use agent::{
    ActionValues, Adopted, Advice, AdviceCounters, AdvisingStrategy, AdvisorTies, AgentRng,
    AskContext, Batch, EndContext, GiveContext, Outcome, Replies, ReuseContext, Sends, Share,
    Transition, VoteTies,
};
use proto::{Action, SharedValues, Standing, State, TransitionNote};
use serde::Deserialize;
use serde_json::{Value, json};

use crate::child::{ChildCommand, JsonChild};

/// The strategy process of one agent for one run.
#[derive(Debug)]
pub struct PipeStrategy {
    /// Behind a cell: the seam asks `advisors` and `spent_budget` of a
    /// shared strategy, and the child answers every question.
    child: RefCell<JsonChild>,
    traits: Traits,
}

/// What `start` answers: who the strategy is and which decisions it makes.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Traits {
    name: String,
    #[serde(default)]
    version: String,
    learns: bool,
    reuses: bool,
    asks_by_uncertainty: bool,
    mistake_correcting: bool,
    intends_greedy: bool,
    shares_values: bool,
    learns_from_outcomes: bool,
    #[serde(default)]
    asks_by_values: bool,
    #[serde(default)]
    records_transitions: bool,
    #[serde(default)]
    ends_episodes: bool,
    #[serde(default)]
    ends_evaluations: bool,
    #[serde(default)]
    receives_batches: bool,
    #[serde(default)]
    reports_advice_outcomes: bool,
    #[serde(default)]
    hears_advice_outcomes: bool,
}

impl PipeStrategy {
    /// Starts `command` for agent `agent` of `team_size` in run `run`, with
    /// `seed` for its own random choices, and waits for its `start` answer.
    pub fn start(
        command: &ChildCommand,
        agent: u8,
        team_size: u8,
        run: u32,
        seed: u64,
    ) -> Result<Self, String> {
        let (child, traits): (_, Traits) = JsonChild::start(
            command,
            "strategy",
            (agent, team_size, run, seed),
            json!({}),
        )?;
        tracing::info!(
            agent,
            name = traits.name,
            version = traits.version,
            "strategy started"
        );
        Ok(Self {
            child: RefCell::new(child),
            traits,
        })
    }

    fn query<T: for<'de> Deserialize<'de>>(&self, what: &str, request: Value) -> T {
        self.child.borrow_mut().query(what, request)
    }

    fn fail(&self, cause: &str) -> ! {
        self.child.borrow_mut().fail(cause)
    }

    /// A kick action (1-4) the strategy answered, or the end of the agent.
    fn kick(&self, what: &str, index: usize) -> Action {
        match Action::ALL.get(index) {
            Some(&a) if a.is_kick() => a,
            _ => self.fail(&format!(
                "answered `{what}` with action {index}; a kicker's actions are 1 to {} (SHOOT, DRIBBLE, PASS_NEAR, PASS_FAR)",
                Action::ALL.len() - 1
            )),
        }
    }
}

/// Q(s, a) by action index, `null` where unlearned: as learners write them.
fn values(v: &ActionValues) -> Value {
    let q: Vec<Option<f64>> = Action::ALL
        .iter()
        .map(|&a| v.is_learned(a).then_some(v.q[a.index()]))
        .collect();
    json!(q)
}

/// A transition as the strategy reads it (as learners do).
fn transition(t: &Transition) -> Value {
    json!({
        "state": t.state, "action": t.action.index(), "reward": t.reward,
        "next_state": t.next.map(|(s, _)| s), "next_action": t.next.map(|(_, a)| a.index()),
    })
}

/// What the strategy is told at an episode's end.
fn end(op: &str, end: &EndContext<'_>) -> Value {
    json!({
        "op": op, "final_reward": end.final_reward, "outcome": end.outcome.name(),
        "episode_return": end.episode_return, "me": end.me, "team_size": end.team_size,
        "counters": counters(end.counters),
    })
}

/// The counters by their results names.
fn counters(c: &AdviceCounters) -> Value {
    serde_json::to_value(c).unwrap_or_default()
}

/// The advice and the shared values that arrived, as the strategy reads them.
fn replies(r: &Replies<'_>) -> Value {
    let advice: Vec<Value> = (r.advice.iter())
        .map(|a| json!({ "advisor": a.advisor, "action": a.action.index() }))
        .collect();
    let shared: Vec<Value> = (r.values.iter())
        .map(|v| {
            let shared = ActionValues {
                q: v.values.q,
                learned: v.values.learned,
            };
            json!({ "advisor": v.advisor, "values": values(&shared), "visits": v.values.visits })
        })
        .collect();
    json!({ "key": r.key, "advice": advice, "values": shared })
}

/// An action answered, or none.
#[derive(Deserialize)]
struct Chosen {
    action: Option<usize>,
}

/// A yes or no.
#[derive(Deserialize)]
struct Decision {
    decision: bool,
}

/// Whom to ask.
#[derive(Deserialize)]
struct Advisors {
    advisors: Vec<usize>,
}

/// The advice followed, or none.
#[derive(Deserialize)]
struct Followed {
    advice: Option<FollowedAdvice>,
}

#[derive(Deserialize)]
struct FollowedAdvice {
    advisor: usize,
    action: usize,
}

/// The values taken into the learner, or none.
#[derive(Deserialize)]
struct AdoptReply {
    values: Option<[Option<f64>; Action::ALL.len()]>,
}

/// What it sends at an episode's end: batches of experience.
#[derive(Deserialize)]
struct Ended {
    batches: Vec<SentBatch>,
}

#[derive(Deserialize)]
struct SentBatch {
    to: usize,
    transitions: Vec<SentTransition>,
    #[serde(default)]
    notes: Vec<TransitionNote>,
    #[serde(default)]
    standing: Option<Standing>,
}

/// What its learner learns of a batch that arrived: the transitions by
/// index, or all of them.
#[derive(Deserialize)]
struct Learn {
    learn: Option<Vec<usize>>,
}

#[derive(Deserialize)]
struct SentTransition {
    state: State,
    action: usize,
    reward: f64,
    next_state: Option<State>,
    next_action: Option<usize>,
}

/// The budget the results plot.
#[derive(Deserialize)]
struct Spent {
    spent: u64,
}

impl AdvisingStrategy for PipeStrategy {
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
        let request = json!({ "op": "reuse", "key": at.key, "values": values(&learner()) });
        let Chosen { action } = self.query("reuse", request);
        action.map(|a| self.kick("reuse", a))
    }

    fn asks_by_uncertainty(&self) -> bool {
        self.traits.asks_by_uncertainty
    }

    fn asks_by_values(&self) -> bool {
        self.traits.asks_by_values
    }

    fn asks(&mut self, at: &AskContext<'_>, _: &mut AgentRng) -> bool {
        let request = json!({
            "op": "asks", "fresh": at.fresh, "visits": at.visits,
            "training_episodes": at.training_episodes, "counters": counters(at.counters),
            "uncertainty": at.uncertainty, "state": at.state, "features": at.features,
            "values": at.values.as_ref().map(values),
        });
        self.query::<Decision>("asks", request).decision
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        let request = json!({
            "op": "advisors", "me": me, "team_size": team_size, "positions": positions,
        });
        let Advisors { advisors } = self.query("advisors", request);
        if let Some(bad) = advisors.iter().find(|&&j| j >= team_size || j == me) {
            self.fail(&format!(
                "named advisor {bad}; advisors are the other agents, 0 to {} but {me}",
                team_size - 1
            ));
        }
        out.clear();
        out.extend(advisors);
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
        let mut request = replies(r);
        request["op"] = "adopt".into();
        request["visits"] = visits.into();
        let AdoptReply { values } = self.query("adopt", request);
        let mut shared = SharedValues {
            q: [0.0; Action::ALL.len()],
            learned: 0,
            visits,
        };
        for (a, q) in values?.into_iter().enumerate() {
            let Some(q) = q else { continue };
            if !q.is_finite() {
                self.fail(&format!(
                    "adopted value {q} for action {a}, not a finite number"
                ));
            }
            shared.q[a] = q;
            shared.learned |= 1 << a;
        }
        Some(Adopted::Row(shared))
    }

    fn gives(&mut self, at: &GiveContext<'_>, _: &mut AgentRng) -> bool {
        let request = json!({
            "op": "gives", "visits": at.visits, "values": values(at.values),
            "counters": counters(at.counters), "asker": at.asker, "state": at.state,
            "features": at.features,
        });
        self.query::<Decision>("gives", request).decision
    }

    fn advice(&mut self, v: &ActionValues, _: AdvisorTies, _: &mut AgentRng) -> Action {
        let Chosen { action } =
            self.query("advice", json!({ "op": "advice", "values": values(v) }));
        match action {
            Some(a) => self.kick("advice", a),
            None => {
                self.fail("answered `advice` with no action; an advisor that answers names one")
            }
        }
    }

    fn follow(&mut self, r: &Replies<'_>, _: VoteTies, _: &mut AgentRng) -> Option<Advice> {
        let mut request = replies(r);
        request["op"] = "follow".into();
        let Followed { advice } = self.query("follow", request);
        let FollowedAdvice { advisor, action } = advice?;
        let arrived = r
            .advice
            .iter()
            .find(|a| a.advisor == advisor && a.action.index() == action);
        match arrived {
            Some(&a) => Some(a),
            None => self.fail(&format!(
                "followed advice {action} of agent {advisor}, which did not arrive"
            )),
        }
    }

    fn learns_from_outcomes(&self) -> bool {
        self.traits.learns_from_outcomes
    }

    fn learn_outcome(&mut self, outcome: &Outcome) {
        let request = json!({
            "op": "learn_outcome", "advisor": outcome.advisor, "advantage": outcome.advantage,
        });
        self.child.get_mut().send("learn_outcome", &request);
    }

    fn reports_advice_outcomes(&self) -> bool {
        self.traits.reports_advice_outcomes
    }

    fn advice_outcome(&mut self, asker: usize, followed: bool, advantage: f64) {
        if self.traits.hears_advice_outcomes {
            let request = json!({
                "op": "advice_outcome", "asker": asker, "followed": followed,
                "advantage": advantage,
            });
            self.child.get_mut().send("advice_outcome", &request);
        }
    }

    fn records_transitions(&self, _: &AdviceCounters) -> bool {
        self.traits.records_transitions
    }

    fn learned(&mut self, t: &Transition) {
        let request = json!({ "op": "learned", "transition": transition(t) });
        self.child.get_mut().send("learned", &request);
    }

    fn end_episode(&mut self, at: &EndContext<'_>) -> Sends {
        if !self.traits.ends_episodes {
            return Sends::new();
        }
        let Ended { batches } = self.query("end_episode", end("end_episode", at));
        let mut sends = Sends::new();
        for SentBatch {
            to,
            transitions,
            notes,
            standing,
        } in batches
        {
            if to >= at.team_size || to == at.me {
                self.fail(&format!(
                    "sent a batch to agent {to}; receivers are the other agents, 0 to {} but {}",
                    at.team_size - 1,
                    at.me
                ));
            }
            let transitions = (transitions.into_iter())
                .map(|t| {
                    let next = (t.next_state, t.next_action);
                    Transition::from_parts(t.state, t.action, t.reward, next)
                })
                .collect::<Result<Vec<_>, _>>()
                .unwrap_or_else(|e| self.fail(&format!("sent a transition with {e}")));
            let batch = Batch {
                transitions,
                notes,
                standing,
            };
            if let Err(e) = batch.check() {
                self.fail(&format!("sent {e}"));
            }
            sends.push((to, Share::Batch(batch)));
        }
        sends
    }

    fn end_evaluation(&mut self, at: &EndContext<'_>) {
        if self.traits.ends_evaluations {
            let request = end("end_evaluation", at);
            self.child.get_mut().send("end_evaluation", &request);
        }
    }

    fn received(&mut self, from: usize, batch: &Batch) -> Option<Vec<Transition>> {
        if !self.traits.receives_batches {
            return None;
        }
        let transitions: Vec<Value> = batch.transitions.iter().map(transition).collect();
        let request = json!({
            "op": "received", "from": from, "to": self.child.get_mut().agent(), "transitions": transitions,
            "notes": batch.notes, "standing": batch.standing,
        });
        let Learn { learn } = self.query("received", request);
        let chosen = batch.chosen(&learn?);
        Some(chosen.unwrap_or_else(|e| self.fail(&format!("answered `received` with {e}"))))
    }

    fn spent_budget(&self, c: &AdviceCounters) -> u64 {
        let request = json!({ "op": "spent_budget", "counters": counters(c) });
        self.query::<Spent>("spent_budget", request).spent
    }
}
