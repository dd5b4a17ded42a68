//! The in-process backend: all agents in one `Vec`, advising by direct calls
//! in a fixed order, so a run is bit-for-bit deterministic.

use proto::{Action, Mode, State};

use crate::agent::{Agent, Observation};
use crate::exchange::{AdviceExchange, Transition};

/// A team that does not fit together, or a frame of the wrong size.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TeamError {
    /// The agent at `index` was built with another id.
    #[error("the agent at index {index} has id {id}")]
    Id {
        /// Position in the team.
        index: usize,
        /// Its id.
        id: usize,
    },
    /// An agent was built for another team size.
    #[error("agent {id} was built for a team of {built_for}, the team has {size}")]
    Size {
        /// The agent.
        id: usize,
        /// Team size given at its construction.
        built_for: usize,
        /// Actual team size.
        size: usize,
    },
    /// A frame did not carry one observation per agent.
    #[error("expected {expected} observations, got {got}")]
    Observations {
        /// Team size.
        expected: usize,
        /// Observations given.
        got: usize,
    },
}

/// Every agent of a team, driven frame by frame.
///
/// In a frame, agents act in id order; an advisee asks its advisors in the
/// order of its reachable set, each advisor answering from its current state.
#[derive(Debug)]
pub struct Team {
    agents: Vec<Agent>,
    actions: Vec<Action>,
    positions: Vec<[f64; 2]>,
}

impl Team {
    /// A team of agents whose ids are their indices.
    pub fn new(agents: Vec<Agent>) -> Result<Self, TeamError> {
        let size = agents.len();
        for (index, a) in agents.iter().enumerate() {
            if a.id() != index {
                return Err(TeamError::Id { index, id: a.id() });
            }
            if a.team_size() != size {
                return Err(TeamError::Size {
                    id: index,
                    built_for: a.team_size(),
                    size,
                });
            }
        }
        Ok(Self {
            actions: vec![Action::Move; size],
            positions: Vec::with_capacity(size),
            agents,
        })
    }

    /// The agents, by id.
    pub fn agents(&self) -> &[Agent] {
        &self.agents
    }

    /// Starts an episode for every agent.
    pub fn begin_episode(&mut self, mode: Mode) {
        for a in &mut self.agents {
            a.begin_episode(mode);
        }
    }

    /// One frame: every agent closes its previous step with the shared
    /// `reward` (ignored on the first frame) and picks its action.
    pub fn act(
        &mut self,
        observations: &[Observation],
        reward: f64,
    ) -> Result<&[Action], TeamError> {
        let n = self.agents.len();
        if observations.len() != n {
            return Err(TeamError::Observations {
                expected: n,
                got: observations.len(),
            });
        }
        self.positions.clear();
        self.positions
            .extend(observations.iter().map(|o| o.position));
        for (i, obs) in observations.iter().enumerate() {
            let (me, mut peers) = Peers::split(&mut self.agents, i);
            self.actions[i] = me.act(obs, reward, &self.positions, &mut peers);
        }
        Ok(&self.actions)
    }

    /// The terminal frame: every agent learns its last step, then the agents
    /// that share episodes send them, in id order.
    pub fn end_episode(&mut self, final_reward: f64) {
        for a in &mut self.agents {
            a.end_episode(final_reward);
        }
        for i in 0..self.agents.len() {
            let (me, mut peers) = Peers::split(&mut self.agents, i);
            me.share_episode(&mut peers);
        }
    }
}

/// Every agent but one, reachable by id.
struct Peers<'a> {
    before: &'a mut [Agent],
    after: &'a mut [Agent],
    me: usize,
}

impl<'a> Peers<'a> {
    /// Agent `i` and the others.
    fn split(agents: &'a mut [Agent], i: usize) -> (&'a mut Agent, Self) {
        let (before, rest) = agents.split_at_mut(i);
        let (me, after) = rest.split_first_mut().expect("index below the team size");
        (
            me,
            Self {
                before,
                after,
                me: i,
            },
        )
    }

    fn get(&mut self, id: usize) -> Option<&mut Agent> {
        match id.checked_sub(self.me) {
            None => self.before.get_mut(id),
            Some(0) => None,
            Some(d) => self.after.get_mut(d - 1),
        }
    }
}

impl AdviceExchange for Peers<'_> {
    fn ask(
        &mut self,
        _from: usize,
        to: &[usize],
        state: &State,
        intended: Option<Action>,
        answers: &mut Vec<Action>,
    ) {
        for &j in to {
            if let Some(advice) = self.get(j).and_then(|a| a.advise(state, intended)) {
                answers.push(advice);
            }
        }
    }

    fn share(&mut self, _from: usize, to: usize, transitions: &[Transition]) {
        if let Some(a) = self.get(to) {
            a.receive_shared(transitions);
        }
    }
}
