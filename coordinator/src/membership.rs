//! Open teams: at a training episode the agent in a slot leaves and a
//! newcomer takes its place while the others keep learning (the paper's
//! motivation: an agent joining a system that has been learning for some
//! time).

use serde::{Deserialize, Serialize};

use crate::agent_spec::AgentSpec;
use crate::error::ConfigError;

/// At training episode `episode`, the agent in slot `slot` leaves and the
/// newcomer takes the slot: after that episode, before the evaluation there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MembershipEvent {
    /// Training episodes played before the newcomer joins (1 to N).
    pub episode: u64,
    /// The slot (agent id) whose agent is replaced.
    pub slot: usize,
    /// The newcomer: any agent table (its algorithm, a snapshot to `load`,
    /// a learner or strategy process); by default a fresh agent with the
    /// slot's settings and no snapshot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub newcomer: Option<AgentSpec>,
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
/// checkpoint: the gap in its learning. One that died before joining (at
/// the team's start-up, as a newcomer or as a restarted agent) was started
/// again as it was to start: nothing of its learning was lost.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Restart {
    /// Its slot.
    pub slot: usize,
    /// Training episodes played when it was found lost.
    pub episode: u64,
    /// The training episodes of the checkpoint it restarted from; `None`:
    /// none yet (or a learner process without snapshot hooks), it
    /// restarted fresh. For one that died before joining, the snapshot it
    /// was to load: the checkpoint of a restart, or a newcomer's (or, at
    /// start-up, the team's) `load`, counted at `episode`.
    pub checkpoint: Option<u64>,
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

impl MembershipEvent {
    /// The agent that joins: the newcomer, or the slot's agent `slot_spec`
    /// fresh (without its snapshot).
    pub fn newcomer(&self, slot_spec: &AgentSpec) -> AgentSpec {
        self.newcomer.clone().unwrap_or_else(|| AgentSpec {
            load: None,
            keep_counters: false,
            ..slot_spec.clone()
        })
    }
}

/// Checks `events` of a team of `team_size` playing `episodes` training
/// episodes; errors name `events[<k>]`.
pub fn validate(
    events: &[MembershipEvent],
    team_size: usize,
    episodes: u64,
) -> Result<(), ConfigError> {
    for (k, e) in events.iter().enumerate() {
        let key = |field: &str| format!("events[{k}].{field}");
        if !(1..=episodes).contains(&e.episode) {
            return Err(ConfigError::new(
                key("episode"),
                format!(
                    "must be 1 to the training episodes {episodes}, got {}",
                    e.episode
                ),
            ));
        }
        if e.slot >= team_size {
            return Err(ConfigError::new(
                key("slot"),
                format!("must be below the team size {team_size}, got {}", e.slot),
            ));
        }
        if let Some(earlier) = events[..k].iter().find(|x| x.episode > e.episode) {
            return Err(ConfigError::new(
                key("episode"),
                format!(
                    "events must be in the order they happen: {} comes after an event at {}",
                    e.episode, earlier.episode
                ),
            ));
        }
        if (events[..k].iter()).any(|x| x.episode == e.episode && x.slot == e.slot) {
            return Err(ConfigError::new(
                key("slot"),
                format!(
                    "slot {} is already replaced at episode {}",
                    e.slot, e.episode
                ),
            ));
        }
    }
    Ok(())
}
