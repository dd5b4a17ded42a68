//! The in-process backend: the simulator and an `agent::Team` in the run's
//! own thread, called directly: fast and bit-for-bit deterministic.

use std::sync::Arc;

use agent::{AdvisingTraffic, Agent, Features, Mode, Observation, ObservationSet, Snapshot, Team};
use analysis::AgentStats;
use env_server::{Env, Outcome, RunEnvs};

use crate::backend::{Backend, EpisodeEnd};
use crate::error::{ConfigError, Error};
use crate::experiment::{Experiment, RunSeeds};
use crate::plugin::Plugin;

/// The in-process backend of one run.
#[derive(Debug)]
pub struct InProcess {
    run: u64,
    simulators: RunEnvs,
    team: Team,
    observations: Vec<Observation>,
    /// The objects some agents are made with, whose failures end the run.
    plugins: Vec<Arc<dyn Plugin>>,
}

impl InProcess {
    /// Run `run` of `experiment`, its agents at their start.
    pub fn new(experiment: &Experiment, run: u64) -> Result<Self, Error> {
        let seeds: RunSeeds = experiment.seeds(run);
        let env_config = experiment.config().env.clone();
        let simulators = RunEnvs::new(env_config, seeds.simulator)
            .map_err(|e| ConfigError::new("env", e.to_string()))?;
        let team = Team::new(experiment.agents(run)?).map_err(|e| Error::run(run, e))?;
        let n = simulators.offense();
        Ok(Self {
            run,
            simulators,
            team,
            observations: Vec::with_capacity(n),
            plugins: experiment.plugins().cloned().collect(),
        })
    }
}

impl Backend for InProcess {
    fn begin_evaluation(&mut self, seed: u64) -> Result<(), Error> {
        self.simulators.begin_evaluation(seed);
        Ok(())
    }

    fn play_episode(&mut self, mode: Mode) -> Result<EpisodeEnd, Error> {
        let run = self.run;
        let env = (self.simulators.env(mode))
            .ok_or_else(|| Error::run(run, "evaluation episode before begin_evaluation"))?;
        let players = Players {
            team: &mut self.team,
            plugins: &self.plugins,
            run,
        };
        let outcome = players.play(env, mode, &mut self.observations, |_| {})?;
        Ok(EpisodeEnd {
            outcome,
            frames: env.frame(),
            actions_timed_out: 0,
        })
    }

    fn agent_stats(&self) -> Result<Vec<AgentStats>, Error> {
        let agents = self.team.agents().iter();
        Ok(agents
            .zip(self.team.traffic())
            .map(|(a, t)| stats_of(a, t))
            .collect())
    }

    fn advice_matrix(&self) -> Result<Vec<Vec<u64>>, Error> {
        Ok((self.team.agents().iter())
            .map(|a| a.advised_by().to_vec())
            .collect())
    }

    fn replace(&mut self, experiment: &Experiment, event: usize) -> Result<u64, Error> {
        let newcomer = experiment.newcomer(self.run, event)?;
        (self.team.replace(newcomer)).map_err(|e| Error::run(self.run, e))?;
        check(&self.plugins, self.run)?;
        Ok(0)
    }

    fn snapshots(&self) -> Result<Vec<Snapshot>, Error> {
        let snapshots = self.team.agents().iter().map(Agent::snapshot).collect();
        check(&self.plugins, self.run)?;
        Ok(snapshots)
    }
}

/// A team in a run, and the objects whose failures end it.
pub(crate) struct Players<'a> {
    pub team: &'a mut Team,
    pub plugins: &'a [Arc<dyn Plugin>],
    pub run: u64,
}

impl Players<'_> {
    /// Plays one episode on `env` in `mode` (`observations` a buffer of the
    /// agents' views), `observe` seeing every state from the reset on;
    /// returns how it ended.
    pub fn play(
        self,
        env: &mut Env,
        mode: Mode,
        observations: &mut Vec<Observation>,
        mut observe: impl FnMut(&Env),
    ) -> Result<Outcome, Error> {
        let run = self.run;
        env.reset();
        observe(env);
        self.team.begin_episode(mode);
        let mut reward = 0.0;
        loop {
            observations.clear();
            let agents = self.team.agents();
            observations.extend(env.states().enumerate().map(|(i, state)| {
                let pos = env.world().offense[i].pos;
                Observation {
                    state,
                    features: features_of(&agents[i], env, i),
                    can_kick: env.can_kick(i),
                    position: [pos.x, pos.y],
                }
            }));
            let actions = (self.team.act(observations, reward)).map_err(|e| Error::run(run, e))?;
            check(self.plugins, run)?;
            let outcome = env.step(actions);
            observe(env);
            if let Some(ended) = outcome.ended() {
                self.team.end_episode(ended);
                check(self.plugins, run)?;
                return Ok(outcome);
            }
            reward = outcome.reward();
        }
    }
}

/// HFO's features of player `i` on `env` (today's set, as env-server sends
/// them) if `agent`'s learner reads them, else none.
fn features_of(agent: &Agent, env: &Env, i: usize) -> Features {
    match agent.config().learner.observation() {
        ObservationSet::Hfo => Features::from_f64(&env.current_features(i)).unwrap_or_default(),
        ObservationSet::Paper => Features::NONE,
    }
}

/// Run `run`'s end, if an object given in process failed.
fn check(plugins: &[Arc<dyn Plugin>], run: u64) -> Result<(), Error> {
    match plugins.iter().find_map(|p| p.failure()) {
        Some(failure) => Err(Error::run(run, failure)),
        None => Ok(()),
    }
}

/// The statistics of a local agent that sent `traffic`.
fn stats_of(agent: &Agent, traffic: &AdvisingTraffic) -> AgentStats {
    let c = agent.counters();
    AgentStats {
        advising_messages: traffic.messages,
        advising_bytes: traffic.bytes,
        give_spent: agent.spent_budget(),
        ask_spent: c.ask_spent,
        advice_requests: c.advice_requests,
        advice_replies_received: c.advice_replies_received,
        advice_given: c.advice_given,
        answered_requests: agent.request_outcomes().answered,
        declined_requests: agent.request_outcomes().declined,
        futile_requests: agent.request_outcomes().futile,
        lost_requests: agent.request_outcomes().lost,
        reused_advice: agent.request_outcomes().reused,
        ..AgentStats::default()
    }
}
