//! A learner in a child process of its own (docs/learners.md): the agent
//! framework stays here, the learner answers over the child's standard
//! input and output, one JSON object per line ([`crate::child`]).
//!
//! Queries (`start`, `values`, `choose`, `save`, `restore`) wait for one
//! answer line, within the learner timeout; `learn`, `end_episode` and
//! `replay` are sent without an answer. A saved state travels as base64.

use agent::{ActionValues, AgentRng, Experience, Learner, Seen, Step};
use proto::Action;
use serde::Deserialize;
use serde_json::{Value, json};

use std::cell::RefCell;

use base64::Engine;
use base64::engine::general_purpose::STANDARD as BASE64;

use crate::child::{ChildCommand, JsonChild};

/// The learner process of one agent for one run.
#[derive(Debug)]
pub struct PipeLearner {
    /// Behind a cell: a snapshot asks `save_state` of a shared learner.
    child: RefCell<JsonChild>,
}

/// What `start` answers: who the learner is.
#[derive(Deserialize)]
struct Hello {
    name: String,
    #[serde(default)]
    version: String,
}

impl PipeLearner {
    /// Starts `command` for agent `agent` of `team_size` in run `run`, with
    /// `seed` for its own random choices, and waits for its `start` answer.
    pub fn start(
        command: &ChildCommand,
        agent: u8,
        team_size: u8,
        run: u32,
        seed: u64,
    ) -> Result<Self, String> {
        let features = json!({ "features": proto::STATE_FEATURES });
        let (child, hello): (_, Hello) =
            JsonChild::start(command, "learner", (agent, team_size, run, seed), features)?;
        tracing::info!(
            agent,
            name = hello.name,
            version = hello.version,
            "learner started"
        );
        Ok(Self {
            child: RefCell::new(child),
        })
    }

    /// A state as the learner reads it.
    fn state(at: Seen<'_>) -> Value {
        json!({ "state": at.state, "index": at.index })
    }
}

/// The answer to `values`: Q(s, a) by action index, `null` where unlearned.
#[derive(Deserialize)]
struct Values {
    q: [Option<f64>; Action::ALL.len()],
}

/// The answer to `save`: its state in base64, or none.
#[derive(Deserialize)]
struct Saved {
    state: Option<String>,
}

/// The answer to `restore`.
#[derive(Deserialize)]
struct Restored {}

/// The answer to `choose`.
#[derive(Deserialize)]
struct Choice {
    action: usize,
}

/// A transition as the learner reads it.
fn transition((from, reward, next): &Experience<'_>) -> Value {
    json!({
        "state": from.at.state, "action": from.action.index(), "reward": reward,
        "next_state": next.map(|n: Step<'_>| n.at.state),
        "next_action": next.map(|n| n.action.index()),
    })
}

impl Learner for PipeLearner {
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        let mut request = Self::state(at);
        request["op"] = "values".into();
        let Values { q } = self.child.get_mut().query("values", request);
        let mut values = ActionValues::default();
        for (a, q) in Action::ALL.iter().zip(q) {
            let Some(q) = q else { continue };
            if !q.is_finite() {
                self.child
                    .get_mut()
                    .fail(&format!("valued {} at {q}, not a finite number", a.name()));
            }
            values.q[a.index()] = q;
            values.learned |= 1 << a.index();
        }
        values
    }

    fn choose(&mut self, at: Seen<'_>, _rng: &mut AgentRng) -> Action {
        let mut request = Self::state(at);
        request["op"] = "choose".into();
        let Choice { action } = self.child.get_mut().query("choose", request);
        match Action::ALL.get(action) {
            Some(&a) if a != Action::Move => a,
            _ => self.child.get_mut().fail(&format!(
                "chose action {action}; a kicker's actions are 1 to {} (SHOOT, DRIBBLE, PASS_NEAR, PASS_FAR)",
                Action::ALL.len() - 1
            )),
        }
    }

    fn learn(&mut self, step: Experience<'_>) {
        let mut request = transition(&step);
        request["op"] = "learn".into();
        self.child.get_mut().send("learn", &request);
    }

    fn end_episode(&mut self) {
        self.child
            .get_mut()
            .send("end_episode", &json!({ "op": "end_episode" }));
    }

    fn replay(&mut self, episode: &[Experience<'_>]) {
        let episode: Vec<Value> = episode.iter().map(transition).collect();
        self.child
            .get_mut()
            .send("replay", &json!({ "op": "replay", "episode": episode }));
    }

    fn table(&self) -> Option<Vec<ActionValues>> {
        None
    }

    fn save_state(&self) -> Option<Vec<u8>> {
        let Saved { state } = self
            .child
            .borrow_mut()
            .query("save", json!({ "op": "save" }));
        let state = state?;
        match BASE64.decode(&state) {
            Ok(bytes) => Some(bytes),
            Err(e) => self.child.borrow_mut().fail(&format!(
                "answered `save` with a state that is not base64: {e}"
            )),
        }
    }

    fn load_state(&mut self, state: &[u8]) -> Result<(), String> {
        let request = json!({ "op": "restore", "state": BASE64.encode(state) });
        let Restored {} = self.child.get_mut().query("restore", request);
        Ok(())
    }

    fn restore(&mut self, _: Vec<ActionValues>) -> Result<(), String> {
        Err(format!(
            "agent {}'s learner `{}` keeps its learned state itself and this snapshot holds none \
             of it (a learner without `save`/`restore`, or a snapshot of another learner)",
            self.child.borrow().agent(),
            self.child.borrow().command_line()
        ))
    }
}
