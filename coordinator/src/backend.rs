//! The seam between the schedule and where agents and simulator live: the
//! schedule drives a [`Backend`] episode by episode, whatever the transport.

use agent::{Mode, Snapshot};
use env_server::Outcome;

use crate::error::Error;
use crate::experiment::Experiment;
use analysis::{AgentStats, Restart, SimulatorRestart};

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
