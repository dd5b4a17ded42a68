//! What each offense agent carries from cycle to cycle and across episode
//! resets, as HFO's agent processes do: its last shot course and its view.

use crate::sim::view::Sight;
use glam::DVec2;

/// One shot course: a goal-mouth target and the ball's first speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShotCourse {
    /// Aim point on (or just behind) the goal line.
    pub target: DVec2,
    /// First ball speed (m/cycle).
    pub speed: f64,
}

/// One offense agent's memory; like the agent's own world model it
/// survives episode resets.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AgentMemory {
    /// The first course of the agent's most recent non-empty shot search
    /// (spec 6.2.2), like HFO's per-agent `ShootGenerator` storage; `None`
    /// until its first such search.
    pub last_shot: Option<ShotCourse>,
    /// The agent's view and seen-direction counts (spec 6.6).
    pub sight: Sight,
}
