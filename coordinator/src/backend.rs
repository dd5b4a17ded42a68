//! The seam between the schedule and where agents and simulator live: the
//! schedule drives a [`Backend`] episode by episode, whatever the transport.

use agent::{AdvisingTraffic, Agent, Mode, Snapshot};
use env_server::Outcome;
use serde::Serialize;

use crate::error::Error;
use crate::experiment::Experiment;
use crate::membership::{Restart, SimulatorRestart};

/// How one episode ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EpisodeEnd {
    /// The terminal outcome.
    pub outcome: Outcome,
    /// Agent decisions taken (the authors' "frames").
    pub frames: u32,
    /// Awaited actions that did not reach the simulator in time and were
    /// played as Move (always 0 in process).
    pub actions_timed_out: u32,
}

/// One agent's budgets and communication so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
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
}

impl AgentStats {
    /// The statistics of a local agent that sent `traffic`.
    pub fn of(agent: &Agent, traffic: &AdvisingTraffic) -> Self {
        let c = agent.counters();
        Self {
            advising_messages: traffic.messages,
            advising_bytes: traffic.bytes,
            give_spent: agent.spent_budget(),
            ask_spent: c.ask_spent,
            advice_requests: c.advice_requests,
            advice_replies_received: c.advice_replies_received,
            advice_given: c.advice_given,
            ..Self::default()
        }
    }
}

/// Agents and simulator of one run, driven episode by episode.
pub trait Backend {
    /// Switches the evaluation episodes that follow to a fresh simulator
    /// seeded with `seed`.
    fn begin_evaluation(&mut self, seed: u64) -> Result<(), Error>;

    /// Plays one episode: training (learning, exploring, advising) on the
    /// run's training simulator, or evaluation (frozen agents) on the
    /// simulator of the last [`begin_evaluation`](Self::begin_evaluation).
    fn play_episode(&mut self, mode: Mode) -> Result<EpisodeEnd, Error>;

    /// Every agent's budgets and communication so far, by id.
    fn agent_stats(&self) -> Result<Vec<AgentStats>, Error>;

    /// Every agent's learned state, by id.
    fn snapshots(&self) -> Result<Vec<Snapshot>, Error>;

    /// Replaces the agent of membership event `event` of `experiment` by its
    /// newcomer, between episodes; returns how long the newcomer took to
    /// join (ms).
    fn replace(&mut self, experiment: &Experiment, event: usize) -> Result<u64, Error>;

    /// The agents restarted after a crash so far (none in process).
    fn restarts(&self) -> Vec<Restart> {
        Vec::new()
    }

    /// The simulator's restarts after it failed so far (none in process).
    fn simulator_restarts(&self) -> Vec<SimulatorRestart> {
        Vec::new()
    }

    /// Who advised whom so far: row i, column j, the decisions agent i acted
    /// on agent j's advice.
    fn advice_matrix(&self) -> Result<Vec<Vec<u64>>, Error>;

    /// Every agent's advice round-trip times (ms) as of the last
    /// [`agent_stats`](Self::agent_stats); empty in process.
    fn advice_rtt_ms(&self) -> Vec<Vec<f32>> {
        Vec::new()
    }
}
