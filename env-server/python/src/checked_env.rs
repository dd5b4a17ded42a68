//! One environment between Python calls: the simulator with its
//! observation set, and the checks a step's actions pass before anything
//! reaches the simulator.

use crate::actions::{MOVE, action_name, decode, write_mask};
use crate::observation::ObservationSet;
use crate::settings::{MaskedAction, TaskSettings, agent_name};
use crate::status;
use env_server::{Env, EnvConfigError, Outcome};
use proto::Action;

/// Why a step's actions were refused (nothing was stepped).
#[derive(Debug, thiserror::Error)]
pub(crate) enum StepError {
    /// Not one action per agent.
    #[error("expected one action per agent ({expected}), got {got}")]
    Count {
        /// Agents.
        expected: usize,
        /// Actions given.
        got: usize,
    },
    /// An index outside the action space.
    #[error(
        "action {action} of {agent} is out of range: expected an integer from 0 (MOVE) to {last} ({last_name})"
    )]
    OutOfRange {
        /// The agent's name.
        agent: String,
        /// The index given.
        action: i64,
        /// The highest index.
        last: usize,
        /// Its name.
        last_name: String,
    },
    /// A kick action of an agent that cannot kick, refused by `masked_action="raise"`.
    #[error(
        "{agent} cannot kick, so MOVE (0) is its only allowed action, got {action} ({name}); masked_action=\"raise\" refuses it"
    )]
    Masked {
        /// The agent's name.
        agent: String,
        /// The index given.
        action: usize,
        /// Its name.
        name: String,
    },
    /// The episode is over.
    #[error("the episode has ended ({status} at frame {frame}): call reset() before step()")]
    Finished {
        /// HFO's status that ended it.
        status: &'static str,
        /// Its frame.
        frame: u32,
    },
}

/// One simulator and how its agents observe and act.
#[derive(Clone, Debug)]
pub(crate) struct CheckedEnv {
    env: Env,
    observation: ObservationSet,
    masked: MaskedAction,
    actions: usize,
    /// The episode ended before its first decision (the ball pushed out in
    /// the idle cycles): its first step is played and reports the end, as
    /// HFO's and env-server's first step do.
    ended_at_reset: bool,
}

impl CheckedEnv {
    /// A simulator of `settings` drawing from `seed`, before its first episode.
    pub(crate) fn new(settings: &TaskSettings, seed: u64) -> Result<Self, EnvConfigError> {
        Ok(CheckedEnv {
            env: Env::new(settings.config.clone(), seed)?,
            observation: settings.observation,
            masked: settings.masked,
            actions: settings.action_count(),
            ended_at_reset: false,
        })
    }

    /// The simulator.
    pub(crate) fn env(&self) -> &Env {
        &self.env
    }

    /// The observation set.
    pub(crate) fn observation(&self) -> ObservationSet {
        self.observation
    }

    /// Discrete actions of one agent.
    pub(crate) fn action_count(&self) -> usize {
        self.actions
    }

    /// Starts a new episode.
    pub(crate) fn reset(&mut self) {
        self.env.reset();
        self.ended_at_reset = self.env.outcome().is_terminal();
    }

    /// The simulator's actions for `actions`, one index per agent, or why
    /// they cannot be played now.
    pub(crate) fn decode(&self, actions: &[i64]) -> Result<Vec<Action>, StepError> {
        let outcome = self.env.outcome();
        if outcome.is_terminal() && !self.ended_at_reset {
            return Err(StepError::Finished {
                status: status::name(outcome),
                frame: self.env.frame(),
            });
        }
        let n = self.env.offense();
        if actions.len() != n {
            return Err(StepError::Count {
                expected: n,
                got: actions.len(),
            });
        }
        (0..n)
            .zip(actions)
            .map(|(agent, &action)| self.decode_one(agent, action))
            .collect()
    }

    fn decode_one(&self, agent: usize, action: i64) -> Result<Action, StepError> {
        let index = usize::try_from(action)
            .ok()
            .filter(|&i| i < self.actions)
            .ok_or_else(|| StepError::OutOfRange {
                agent: agent_name(agent),
                action,
                last: self.actions - 1,
                last_name: action_name(self.actions - 1),
            })?;
        if index != MOVE && !self.env.can_kick(agent) {
            match self.masked {
                // HFO runs the action; without the ball it issues no command.
                MaskedAction::Hfo => {}
                MaskedAction::Move => return Ok(Action::Move),
                MaskedAction::Raise => {
                    return Err(StepError::Masked {
                        agent: agent_name(agent),
                        action: index,
                        name: action_name(index),
                    });
                }
            }
        }
        Ok(decode(&self.env, self.observation, agent, index))
    }

    /// Plays one step of checked `actions`.
    pub(crate) fn step(&mut self, actions: &[Action]) -> Outcome {
        self.ended_at_reset = false;
        self.env.step(actions)
    }

    /// Every agent's observation into `out` (agent after agent).
    pub(crate) fn write_observations(&self, out: &mut [f32]) {
        self.observation.write(&self.env, out);
    }

    /// Every agent's action mask into `out` (agent after agent).
    pub(crate) fn write_masks(&self, out: &mut [i8]) {
        for (agent, mask) in out.chunks_exact_mut(self.actions).enumerate() {
            write_mask(self.env.can_kick(agent), mask);
        }
    }
}
