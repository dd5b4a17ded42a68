//! What an offense behaviour reads: the state, this cycle's analysis, the
//! settings and the acting agent's memory.

use crate::sim::analysis::Analysis;
use crate::sim::config::EnvConfig;
use crate::sim::memory::AgentMemory;
use crate::sim::world::{Player, World};

/// What an offense behaviour sees: the state, its analysis, who is acting
/// and what that agent remembers.
pub(crate) struct Situation<'a> {
    /// The exact state (everyone has full state).
    pub(crate) world: &'a World,
    /// This cycle's shared analysis.
    pub(crate) analysis: &'a Analysis,
    /// Simulator settings.
    pub(crate) config: &'a EnvConfig,
    /// Index of the acting offense agent.
    pub(crate) agent: usize,
    /// The acting agent's memory.
    pub(crate) memory: &'a AgentMemory,
}

impl Situation<'_> {
    /// The acting agent's body.
    pub(crate) fn me(&self) -> &Player {
        &self.world.offense[self.agent]
    }

    /// The teammate nearest to (`farthest == false`) or farthest from the acting agent.
    pub(crate) fn teammate_by_distance(&self, farthest: bool) -> Option<usize> {
        let me = self.me().pos;
        let others = (0..self.world.offense.len()).filter(|&j| j != self.agent);
        let dist = |j: &usize| self.world.offense[*j].pos.distance(me);
        if farthest {
            others.max_by(|a, b| dist(a).total_cmp(&dist(b)))
        } else {
            others.min_by(|a, b| dist(a).total_cmp(&dist(b)))
        }
    }
}
