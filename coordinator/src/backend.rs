//! The seam between the protocol and where agents and simulator live: the
//! protocol drives a [`Backend`] episode by episode, whatever the transport.
//!
//! [`InProcess`] holds the simulator and an `agent::Team` in the run's own
//! thread and calls them directly: fast and bit-for-bit deterministic.

use agent::{Agent, Mode, Observation, Snapshot, Team};
use env_server::{Env, EnvConfig, Outcome};
use serde::Serialize;

use crate::error::Error;
use crate::experiment::{Experiment, RunSeeds};
use crate::remote::{Network, RemoteBackend};

/// The transports a run can use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Transport {
    /// env-server and every agent as separate processes talking over zenoh.
    #[default]
    Zenoh,
    /// Simulator and agents as library calls in the run's thread.
    InProcess,
}

/// How one episode ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Episode {
    /// The terminal outcome.
    pub outcome: Outcome,
    /// Agent decisions taken (the authors' "frames").
    pub frames: u32,
}

/// One agent's budgets and communication so far.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct AgentStats {
    /// The give budget the paper plots: advice given, or transitions shared.
    pub spent_give: u64,
    /// The ask budget spent: steps acted on advice.
    pub spent_ask: u64,
    /// Advice requests sent.
    pub requests: u64,
    /// Replies received to those requests (advice or not).
    pub replies_received: u64,
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
    /// Received messages dropped as malformed, foreign, stale or duplicate.
    pub dropped: u64,
}

impl AgentStats {
    /// The statistics of a local agent.
    pub fn of(agent: &Agent) -> Self {
        let c = agent.counters();
        Self {
            spent_give: agent.spent_budget(),
            spent_ask: c.advised_steps,
            requests: c.requests_sent,
            replies_received: c.advice_received,
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
    fn play_episode(&mut self, mode: Mode) -> Result<Episode, Error>;

    /// Every agent's budgets and communication so far, by id.
    fn agent_stats(&self) -> Result<Vec<AgentStats>, Error>;

    /// Every agent's learned state, by id.
    fn snapshots(&self) -> Result<Vec<Snapshot>, Error>;

    /// Every agent's advice round-trip times (ms) as of the last
    /// [`agent_stats`](Self::agent_stats); empty in process.
    fn advice_rtt_ms(&self) -> Vec<Vec<f32>> {
        Vec::new()
    }
}

/// Opens the backend of run `run` on `transport`.
pub fn open<'a>(
    transport: Transport,
    experiment: &Experiment,
    run: u64,
    network: Option<&'a Network>,
) -> Result<Box<dyn Backend + 'a>, Error> {
    match (transport, network) {
        (Transport::InProcess, _) => Ok(Box::new(InProcess::new(experiment, run)?)),
        (Transport::Zenoh, Some(network)) => {
            Ok(Box::new(RemoteBackend::new(network, experiment, run)?))
        }
        (Transport::Zenoh, None) => Err(Error::Backend {
            run,
            message: "the zenoh transport needs a joined network".into(),
        }),
    }
}

/// The in-process backend: the simulator and the team, called directly.
#[derive(Debug)]
pub struct InProcess {
    run: u64,
    env_config: EnvConfig,
    training: Env,
    evaluation: Option<Env>,
    team: Team,
    observations: Vec<Observation>,
}

impl InProcess {
    /// Run `run` of `experiment`, its agents at their start.
    pub fn new(experiment: &Experiment, run: u64) -> Result<Self, Error> {
        let RunSeeds { simulator, agents } = experiment.seeds(run);
        let env_config = experiment.config().env.clone();
        let training = Env::new(env_config.clone(), simulator)
            .map_err(|e| crate::config::ConfigError::new("env", e.to_string()))?;
        let agents = experiment.agents(&RunSeeds { simulator, agents })?;
        let team = Team::new(agents).map_err(|e| Error::Backend {
            run,
            message: e.to_string(),
        })?;
        let n = env_config.offense;
        Ok(Self {
            run,
            env_config,
            training,
            evaluation: None,
            team,
            observations: Vec::with_capacity(n),
        })
    }

    /// The team.
    pub fn team(&self) -> &Team {
        &self.team
    }
}

impl Backend for InProcess {
    fn begin_evaluation(&mut self, seed: u64) -> Result<(), Error> {
        let env = Env::new(self.env_config.clone(), seed)
            .map_err(|e| crate::config::ConfigError::new("env", e.to_string()))?;
        self.evaluation = Some(env);
        Ok(())
    }

    fn play_episode(&mut self, mode: Mode) -> Result<Episode, Error> {
        let run = self.run;
        let env = match mode {
            Mode::Training => &mut self.training,
            Mode::Evaluation => self.evaluation.as_mut().ok_or_else(|| Error::Backend {
                run,
                message: "evaluation episode before begin_evaluation".into(),
            })?,
        };
        env.reset();
        self.team.begin_episode(mode);
        let mut reward = 0.0;
        loop {
            self.observations.clear();
            self.observations.extend((0..env.offense()).map(|i| {
                let pos = env.world().offense[i].pos;
                Observation {
                    state: env.state(i),
                    can_kick: env.can_kick(i),
                    position: [pos.x, pos.y],
                }
            }));
            let actions =
                self.team
                    .act(&self.observations, reward)
                    .map_err(|e| Error::Backend {
                        run,
                        message: e.to_string(),
                    })?;
            let outcome = env.step(actions);
            if outcome.is_terminal() {
                self.team.end_episode(outcome.reward());
                return Ok(Episode {
                    outcome,
                    frames: env.frame(),
                });
            }
            reward = outcome.reward();
        }
    }

    fn agent_stats(&self) -> Result<Vec<AgentStats>, Error> {
        Ok(self.team.agents().iter().map(AgentStats::of).collect())
    }

    fn snapshots(&self) -> Result<Vec<Snapshot>, Error> {
        Ok(self.team.agents().iter().map(Agent::snapshot).collect())
    }
}
