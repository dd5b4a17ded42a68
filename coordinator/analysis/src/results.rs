//! The results of runs, as `run-<k>.json` records them (docs/results.md):
//! what the coordinator writes while it plays and what the analysis reads.

use serde::{Deserialize, Serialize};

use proto::Simulator;

/// The measurements of one evaluation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EvalPoint {
    /// Training episodes played before it.
    pub episode: u64,
    /// Evaluation episodes played (M).
    pub episodes: u64,
    /// Evaluation episodes ending in a goal.
    pub goals: u64,
    /// Goal percentage, `100 * goals / episodes`.
    pub goal_pct: f64,
    /// Mean frames of the goal episodes; `None` without a goal.
    pub time_to_goal: Option<f64>,
    /// Every agent's budgets and communication so far, by id.
    pub agents: Vec<AgentStats>,
    /// The paper's spent budget: give budget spent, averaged over agents.
    pub spent_budget: f64,
    /// Awaited actions played as Move because they missed the step timeout,
    /// over the run so far (training and evaluation; 0 in process).
    #[serde(default)]
    pub actions_timed_out: u64,
}

/// What a run cost: the frames it played and the wall time they took. Saved
/// with the run; the times vary from one machine and moment to another.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timing {
    /// Agent decisions in training episodes.
    pub training_frames: u64,
    /// Wall time of the training episodes (s).
    pub training_s: f64,
    /// Agent decisions in evaluation episodes.
    pub evaluation_frames: u64,
    /// Wall time of the evaluations (s).
    pub evaluation_s: f64,
}

impl Timing {
    /// Adds another run's timing.
    pub fn add(&mut self, other: &Timing) {
        self.training_frames += other.training_frames;
        self.training_s += other.training_s;
        self.evaluation_frames += other.evaluation_frames;
        self.evaluation_s += other.evaluation_s;
    }

    /// Training decisions per second of one thread's time.
    pub fn training_frames_per_sec(&self) -> f64 {
        rate(self.training_frames, self.training_s)
    }

    /// Evaluation decisions per second of one thread's time.
    pub fn evaluation_frames_per_sec(&self) -> f64 {
        rate(self.evaluation_frames, self.evaluation_s)
    }

    /// Decisions per second of one thread's time, training and evaluation.
    pub fn frames_per_sec(&self) -> f64 {
        rate(
            self.training_frames + self.evaluation_frames,
            self.training_s + self.evaluation_s,
        )
    }
}

fn rate(frames: u64, secs: f64) -> f64 {
    if secs > 0.0 {
        frames as f64 / secs
    } else {
        0.0
    }
}

/// The results of one run (saved as `run-<k>.json` once it is complete).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// The run's index.
    pub run: u64,
    /// Its evaluations, in order.
    pub points: Vec<EvalPoint>,
    /// What it cost (absent from the files of older versions).
    #[serde(default)]
    pub timing: Timing,
    /// Every agent's advice round-trip times (ms) over the run; empty in process.
    pub advice_rtt_ms: Vec<Vec<f32>>,
    /// Who advised whom over the run: row i, column j, the decisions agent
    /// i (its slot's agents) acted on agent j's advice; absent when no
    /// advice was acted on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub advice_matrix: Vec<Vec<u64>>,
    /// Agents restarted after their process died (none without
    /// `restart_agents`, or without a crash).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub restarts: Vec<Restart>,
    /// The simulator's restarts after it failed (only the real HFO fails).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub simulator_restarts: Vec<SimulatorRestart>,
    /// The newcomers that joined, in order (none in a fixed team).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joins: Vec<Join>,
    /// The code and simulator that played it (absent from the files of
    /// versions before 4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub played_with: Option<PlayedWith>,
}

/// One agent's budgets and communication so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct AgentStats {
    /// The give budget the paper plots: advice given, or transitions shared.
    pub give_spent: u64,
    /// The ask budget spent: steps acted on advice.
    pub ask_spent: u64,
    /// Advice requests sent.
    pub advice_requests: u64,
    /// Replies received to those requests (advice or not).
    pub advice_replies_received: u64,
    /// Answers given.
    pub advice_given: u64,
    /// Messages sent (0 in process).
    pub messages_sent: u64,
    /// Bytes sent (0 in process).
    pub bytes_sent: u64,
    /// Messages received (0 in process).
    pub messages_received: u64,
    /// Bytes received (0 in process).
    pub bytes_received: u64,
    /// Received messages dropped as malformed, foreign, stale, duplicate or
    /// unrequested advice.
    pub messages_dropped: u64,
    /// Advising messages sent: advice requests, replies and shared episodes
    /// (in process, those the zenoh transport would send).
    pub advising_messages: u64,
    /// Their encoded bytes.
    pub advising_bytes: u64,
    /// Requests that brought advice (or values).
    pub answered_requests: u64,
    /// Requests that brought replies, some advisor declining: it could
    /// have advised.
    pub declined_requests: u64,
    /// Requests every advisor asked answered with its give budget spent:
    /// nobody could answer them.
    pub futile_requests: u64,
    /// Requests some of whose replies were lost or late, and none brought
    /// advice or a decline.
    pub lost_requests: u64,
    /// Decisions that played kept advice instead of asking (advice reuse).
    pub reused_advice: u64,
}

/// A newcomer that joined a run: who played which episodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Join {
    /// Training episodes played before it joined.
    pub episode: u64,
    /// Its slot.
    pub slot: usize,
    /// The index of its event in the configuration.
    pub event: usize,
    /// Wall time from asking the leaver to stop to the newcomer reset and
    /// ready (ms; 0 in process).
    pub wait_ms: u64,
}

/// An agent process that died and was restarted from its latest
/// snapshot: the gap in its learning. One that died before joining (at
/// the team's start-up, as a newcomer or as a restarted agent) was started
/// again as it was to start: nothing of its learning was lost.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Restart {
    /// Its slot.
    pub slot: usize,
    /// Training episodes played when it was found lost.
    pub episode: u64,
    /// The training episodes of the snapshot it restarted from; `None`:
    /// none yet (or a learner process without snapshot hooks), it
    /// restarted fresh. For one that died before joining, the snapshot it
    /// was to load: a restart's, or a newcomer's (or, at start-up, the
    /// team's) `load`, counted at `episode`. (`checkpoint` before 0.3.)
    #[serde(alias = "checkpoint")]
    pub snapshot: Option<u64>,
    /// Whether the episode in flight was abandoned and played again.
    pub replayed: bool,
    /// Wall time from the start of the episode (or call) that found it
    /// lost, or for one that died before joining from its exit, to the
    /// restarted agent ready (ms).
    pub wait_ms: u64,
    /// How it was lost.
    pub cause: String,
}

/// A simulator (the real HFO) that failed and was started afresh: the
/// episode in flight was abandoned and played again.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SimulatorRestart {
    /// Training episodes played when it failed.
    pub episode: u64,
    /// Whether the abandoned episode was an evaluation episode.
    pub evaluation: bool,
    /// Wall time from the start of the abandoned episode to its failure (ms).
    pub lost_ms: u64,
    /// How it failed.
    pub cause: String,
}

/// The code and simulator that played a run.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlayedWith {
    /// The commit of the code (see [`COMMIT`]).
    pub commit: String,
    /// The simulator: `ours` or `real-hfo`.
    pub simulator: Simulator,
    /// Ours: the fingerprint of its trajectories over
    /// [`RECORDED_EPISODES`] episodes of each scripted policy from seed 1
    /// (`cargo run --release -p env-server --example fingerprint --
    /// 10`'s `all`); none for the real HFO.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fingerprint: Option<String>,
}
