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
