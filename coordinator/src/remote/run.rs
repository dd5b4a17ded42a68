//! One run driven over the network with the control messages of `docs/protocol.md`.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use agent::{Mode, ObservationSet, Snapshot};
use env_server::Outcome;
use node::sync::lock;
use proto::MessageKind;
use proto::keys::Role;
use proto::{AgentReport, Control, ControlReply, EpisodeOutcome, Header};

use super::{StartedAgain, ZenohTeam};
use crate::backend::{Backend, EpisodeEnd};
use crate::config::{AgentSpec, ExperimentConfig};
use crate::error::Error;
use crate::experiment::Experiment;
use analysis::{AgentStats, Restart, SimulatorRestart};

/// How long a process may take to answer a command other than playing
/// (a reset includes starting a learner process: an `import torch`).
const CONTROL_TIMEOUT: Duration = Duration::from_secs(30);
/// How long one episode may take (200 frames, each at most one step timeout).
const EPISODE_TIMEOUT: Duration = Duration::from_secs(600);
/// How many times in a row an episode is played again after its simulator
/// failed.
const SIMULATOR_RETRIES: u32 = 3;

/// Run `run` of an experiment, played by remote processes.
#[derive(Debug)]
pub struct RemoteBackend<'a> {
    network: &'a ZenohTeam,
    run: u64,
    agents: usize,
    /// Episodes played so far in this run (the next episode's number).
    episode: u32,
    /// Seed of the evaluation simulator to start with the next evaluation episode.
    evaluation_seed: Option<u64>,
    /// Advice round-trip times of every agent, as of the last report.
    rtt_ms: Mutex<Vec<Vec<f32>>>,
    /// Each slot's agent now and its seed (a newcomer's after its join).
    members: Vec<(AgentSpec, u64)>,
    /// Training episodes played.
    trained: u64,
    /// With `restart_agents`: the latest snapshots, at these training
    /// episodes, of every agent (none for a learner process without
    /// snapshot hooks).
    latest: Option<(u64, Vec<Option<Snapshot>>)>,
    /// The agents restarted so far.
    restarts: Mutex<Vec<Restart>>,
    /// The simulator's restarts so far.
    simulator_restarts: Vec<SimulatorRestart>,
}

impl<'a> RemoteBackend<'a> {
    /// Resets env-server and every agent for run `run` of `experiment`;
    /// the first run records the agent processes started again during the
    /// team's start-up.
    pub fn new(network: &'a ZenohTeam, experiment: &Experiment, run: u64) -> Result<Self, Error> {
        let config = experiment.config();
        let seeds = experiment.seeds(run);
        let backend = Self {
            network,
            run,
            agents: config.team.len(),
            episode: 0,
            evaluation_seed: None,
            rtt_ms: Mutex::new(Vec::new()),
            members: (config.team.iter().cloned())
                .zip(seeds.agents.iter().copied())
                .collect(),
            trained: 0,
            latest: None,
            restarts: Mutex::new(Vec::new()),
            simulator_restarts: Vec::new(),
        };
        let env = proto::encode_settings(&config.env).map_err(|e| backend.error(e.to_string()))?;
        backend.expect_ok(
            Role::Server,
            Control::Reset {
                seed: seeds.simulator,
                config: env,
                wait_ms: network.settings().step_timeout_ms,
                stall_ms: network.settings().stall_limit_ms,
                simulator: network.settings().simulator,
                features: hfo_features(config),
            },
        )?;
        for (i, spec) in config.team.iter().enumerate() {
            backend.reset_agent(i, spec, seeds.agents[i], experiment.snapshot(i))?;
        }
        let loaded = |slot| experiment.snapshot(slot).map(|_| 0);
        backend.record_started_again(network.take_started_again(), loaded);
        Ok(backend)
    }

    /// Starts agent `i` on this run as `spec` says, seeded `seed`, from
    /// `snapshot` if given, from the next episode on (a newcomer or a
    /// restarted agent joins there); without restarting anyone.
    fn reset_agent(
        &self,
        i: usize,
        spec: &AgentSpec,
        seed: u64,
        snapshot: Option<&Snapshot>,
    ) -> Result<(), Error> {
        let role = Role::Agent(i as u8);
        let config = proto::encode_settings(&spec.config).map_err(|e| self.error(e.to_string()))?;
        let settings = self.network.settings();
        let reset = self.call_once(
            role,
            self.episode,
            Control::Reset {
                seed,
                config,
                wait_ms: settings.advice_timeout_ms,
                stall_ms: settings.stall_limit_ms,
                simulator: settings.simulator,
                features: 0,
            },
            CONTROL_TIMEOUT,
        )?;
        if reset != ControlReply::Ok {
            return Err(self.error(format!("{role} answered {reset:?}")));
        }
        if let Some(snapshot) = snapshot {
            let snapshot = (snapshot.encode())
                .map_err(|e| self.error(format!("agent {i}'s snapshot: {e}")))?;
            let parts = proto::parts::split(&snapshot);
            for (part, bytes) in (0..).zip(&parts) {
                let load = Control::Load {
                    part,
                    parts: parts.len() as u32,
                    bytes: bytes.to_vec(),
                };
                self.expect_ok_once(role, load)?;
            }
        }
        Ok(())
    }

    fn header(&self, episode: u32) -> Header {
        Header::new(self.network.experiment(), self.run as u32, episode, 0)
    }

    fn error(&self, message: impl Into<String>) -> Error {
        Error::run(self.run, message.into())
    }

    /// Fails if a process of the experiment is gone.
    fn check_alive(&self) -> Result<(), Error> {
        match self.network.lost() {
            Some(role) => Err(self.error(format!(
                "{}; stopping the experiment",
                self.network.loss(role)
            ))),
            None => Ok(()),
        }
    }

    /// The slot of a lost agent the restart policy brings back, if any.
    fn restartable(&self) -> Option<usize> {
        match self.network.lost() {
            Some(Role::Agent(i)) if self.network.settings().restart_agents => Some(i.into()),
            _ => None,
        }
    }

    /// With the restart policy, restarts a lost agent; then fails if a
    /// process of the experiment is still gone.
    fn recover(&self, replayed: bool, played: Instant) -> Result<(), Error> {
        if let Some(slot) = self.restartable() {
            self.restart(slot, replayed, played)?;
        }
        self.check_alive()
    }

    /// Sends `control` to `role`; under the restart policy an agent lost
    /// meanwhile is restarted and the control sent once more.
    fn call(
        &self,
        role: Role,
        episode: u32,
        control: Control,
        timeout: Duration,
    ) -> Result<ControlReply, Error> {
        self.recover(false, Instant::now())?;
        let reply = self
            .network
            .control(role, self.header(episode), control.clone(), timeout);
        if reply.is_err() && self.restartable().is_some() {
            self.recover(false, Instant::now())?;
            return self.call_once(role, episode, control, timeout);
        }
        reply.map_err(|e| self.check_alive().err().unwrap_or_else(|| self.error(e)))
    }

    /// Sends `control` to `role`; a process lost meanwhile is an error,
    /// but, under the restart policy, another agent (restarted later).
    fn call_once(
        &self,
        role: Role,
        episode: u32,
        control: Control,
        timeout: Duration,
    ) -> Result<ControlReply, Error> {
        let reply = (self.network).control(role, self.header(episode), control, timeout);
        reply.map_err(|e| match self.restartable() {
            Some(_) => self.error(e),
            None => self.check_alive().err().unwrap_or_else(|| self.error(e)),
        })
    }

    fn expect_ok(&self, role: Role, control: Control) -> Result<(), Error> {
        match self.call(role, 0, control, CONTROL_TIMEOUT)? {
            ControlReply::Ok => Ok(()),
            other => Err(self.error(format!("{role} answered {other:?}"))),
        }
    }

    /// As [`expect_ok`](Self::expect_ok), without restarting anyone.
    fn expect_ok_once(&self, role: Role, control: Control) -> Result<(), Error> {
        match self.call_once(role, 0, control, CONTROL_TIMEOUT)? {
            ControlReply::Ok => Ok(()),
            other => Err(self.error(format!("{role} answered {other:?}"))),
        }
    }

    /// Every agent's snapshot now, kept to restart an agent that dies (none
    /// for a learner process without snapshot hooks).
    fn take_snapshots(&mut self) -> Result<(), Error> {
        let snapshots = self.snapshots()?;
        let kept = (snapshots.into_iter().zip(&self.members))
            .map(|(s, (spec, _))| {
                (spec.learner.is_none() || s.learner_state.is_some()).then_some(s)
            })
            .collect();
        self.latest = Some((self.trained, kept));
        Ok(())
    }

    /// Agent `i`'s snapshot after the last episode, gathered part by part.
    fn snapshot(&self, i: usize) -> Result<Snapshot, Error> {
        let (role, episode) = (Role::Agent(i as u8), self.last_episode());
        let bad = |e: String| self.error(format!("agent {i} sent a bad snapshot: {e}"));
        let mut gathering = proto::parts::Gathering::default();
        for part in 0..proto::parts::MAX_PARTS {
            match self.call(role, episode, Control::Snapshot { part }, CONTROL_TIMEOUT)? {
                ControlReply::Snapshot { parts, bytes } => {
                    if let Some(whole) = gathering.take(part, parts, &bytes).map_err(bad)? {
                        return Snapshot::decode(&whole).map_err(|e| bad(e.to_string()));
                    }
                }
                other => {
                    return Err(self.error(format!(
                        "agent {i} answered {other:?} to a snapshot request"
                    )));
                }
            }
        }
        Err(bad(format!("more than {} parts", proto::parts::MAX_PARTS)))
    }

    /// Restarts the lost agent `slot` from its latest snapshot and
    /// records the gap; `replayed`: the episode in flight, begun at
    /// `played`, is played again.
    fn restart(&self, slot: usize, replayed: bool, played: Instant) -> Result<(), Error> {
        let (spec, seed) = self.members[slot].clone();
        let (cause, again) = self.network.restart(slot, &spec)?;
        let snapshot = (self.latest.as_ref())
            .and_then(|(episode, s)| Some((*episode, s.get(slot)?.as_ref()?)));
        self.reset_agent(slot, &spec, seed, snapshot.map(|(_, s)| s))?;
        let taken = snapshot.map(|(episode, _)| episode);
        self.record(Restart {
            slot,
            episode: self.trained,
            snapshot: taken,
            replayed,
            wait_ms: played.elapsed().as_millis() as u64,
            cause,
        });
        self.record_started_again(again, |_| taken);
        Ok(())
    }

    /// Records the agent processes that exited before joining and were
    /// started again, once the last of their slot is ready: each restarted
    /// from what its slot was to load, the snapshot of `snapshot(slot)`
    /// training episodes (`None`: fresh).
    fn record_started_again(
        &self,
        again: Vec<StartedAgain>,
        snapshot: impl Fn(usize) -> Option<u64>,
    ) {
        for StartedAgain { slot, cause, found } in again {
            self.record(Restart {
                slot,
                episode: self.trained,
                snapshot: snapshot(slot),
                replayed: false,
                wait_ms: found.elapsed().as_millis() as u64,
                cause,
            });
        }
    }

    fn record(&self, restart: Restart) {
        tracing::warn!(run = self.run, ?restart, "agent restarted");
        lock(&self.restarts).push(restart);
    }

    /// Plays the next episode in `mode` (`seed`: see
    /// [`Backend::begin_evaluation`]) and returns env-server's answer; an
    /// agent lost meanwhile comes back under the restart policy, and the
    /// episode, if abandoned, is played again.
    fn play_once(&mut self, mode: Mode, seed: Option<u64>) -> Result<ControlReply, Error> {
        self.recover(false, Instant::now())?;
        loop {
            let played = Instant::now();
            let reply = self.network.control(
                Role::Server,
                self.header(self.episode),
                Control::PlayEpisode { mode, seed },
                EPISODE_TIMEOUT,
            );
            self.episode += 1;
            if self.restartable().is_none() {
                return reply
                    .map_err(|e| self.check_alive().err().unwrap_or_else(|| self.error(e)));
            }
            // An agent died during the episode: it comes back, and an
            // abandoned episode is played again.
            self.recover(reply.is_err(), played)?;
            if let Ok(reply) = reply {
                return Ok(reply);
            }
        }
    }

    /// The last played episode, which reports and snapshots wait for.
    fn last_episode(&self) -> u32 {
        self.episode.saturating_sub(1)
    }

    /// Every agent's report as of the last played episode.
    pub fn reports(&self) -> Result<Vec<AgentReport>, Error> {
        (0..self.agents)
            .map(|i| {
                match self.call(
                    Role::Agent(i as u8),
                    self.last_episode(),
                    Control::Report,
                    CONTROL_TIMEOUT,
                )? {
                    ControlReply::Agent(report) => Ok(*report),
                    other => {
                        Err(self.error(format!("agent {i} answered {other:?} to a report request")))
                    }
                }
            })
            .collect()
    }
}

impl Backend for RemoteBackend<'_> {
    fn begin_evaluation(&mut self, seed: u64) -> Result<(), Error> {
        self.evaluation_seed = Some(seed);
        Ok(())
    }

    fn play_episode(&mut self, mode: Mode) -> Result<EpisodeEnd, Error> {
        let seed = match mode {
            Mode::Training => None,
            Mode::Evaluation => self.evaluation_seed.take(),
        };
        let mut failures = 0;
        let result = loop {
            let played = Instant::now();
            match self.play_once(mode, seed)? {
                ControlReply::Episode(result) => break result,
                // The real HFO went down: env-server starts it afresh and
                // the episode is played again, a few times in a row at most.
                ControlReply::SimulatorFailed(cause) if failures < SIMULATOR_RETRIES => {
                    failures += 1;
                    let restart = SimulatorRestart {
                        episode: self.trained,
                        evaluation: mode == Mode::Evaluation,
                        lost_ms: played.elapsed().as_millis() as u64,
                        cause,
                    };
                    tracing::warn!(run = self.run, ?restart, "simulator restarted");
                    self.simulator_restarts.push(restart);
                }
                ControlReply::SimulatorFailed(cause) => {
                    return Err(self.error(format!(
                        "the simulator failed {} times in a row, the last time: {cause}",
                        failures + 1
                    )));
                }
                other => {
                    return Err(self.error(format!(
                        "env-server answered {other:?} to an episode request"
                    )));
                }
            }
        };
        self.check_alive()?;
        if mode == Mode::Training {
            self.trained += 1;
            let every = self.network.settings().snapshot_every;
            if self.network.settings().restart_agents && self.trained % every == 0 {
                self.take_snapshots()?;
            }
        }
        Ok(EpisodeEnd {
            outcome: match result.outcome {
                EpisodeOutcome::Goal => Outcome::Goal,
                EpisodeOutcome::Captured => Outcome::Captured,
                EpisodeOutcome::OutOfBounds => Outcome::OutOfBounds,
                EpisodeOutcome::OutOfTime => Outcome::OutOfTime,
            },
            frames: result.frames,
            actions_timed_out: result.actions_timed_out,
        })
    }

    fn agent_stats(&self) -> Result<Vec<AgentStats>, Error> {
        let reports = self.reports()?;
        *lock(&self.rtt_ms) = reports.iter().map(|r| r.advice_rtt_ms.clone()).collect();
        Ok(reports.iter().map(stats_of).collect())
    }

    fn advice_matrix(&self) -> Result<Vec<Vec<u64>>, Error> {
        Ok(self.reports()?.into_iter().map(|r| r.advised_by).collect())
    }

    fn replace(&mut self, experiment: &Experiment, event: usize) -> Result<u64, Error> {
        let (spec, seed, snapshot) = experiment.newcomer_of(self.run, event);
        let slot = experiment.config().events[event].slot;
        let started = Instant::now();
        self.recover(false, started)?;
        self.network.retire(slot).map_err(|e| self.error(e))?;
        let again = self.network.admit(slot, &spec)?;
        self.reset_agent(slot, &spec, seed, snapshot)?;
        self.record_started_again(again, |_| snapshot.map(|_| self.trained));
        if let Some((_, snapshots)) = &mut self.latest {
            // Until the next snapshots, a restart starts it as it joined.
            snapshots[slot] = snapshot.cloned();
        }
        self.members[slot] = (spec, seed);
        Ok(started.elapsed().as_millis() as u64)
    }

    fn restarts(&self) -> Vec<Restart> {
        lock(&self.restarts).clone()
    }

    fn simulator_restarts(&self) -> Vec<SimulatorRestart> {
        self.simulator_restarts.clone()
    }

    fn snapshots(&self) -> Result<Vec<Snapshot>, Error> {
        (0..self.agents).map(|i| self.snapshot(i)).collect()
    }

    fn advice_rtt_ms(&self) -> Vec<Vec<f32>> {
        lock(&self.rtt_ms).clone()
    }
}

/// The slots whose agent, or a newcomer to it, reads HFO's features (bit
/// `i` for slot `i`): env-server sends them with those slots' observations
/// for the whole run.
fn hfo_features(config: &ExperimentConfig) -> u8 {
    let newcomers = (config.events.iter()).map(|e| (e.slot, e.newcomer(&config.team[e.slot])));
    (config.team.iter().cloned().enumerate())
        .chain(newcomers)
        .filter(|(_, spec)| spec.config.learner.observation() == ObservationSet::Hfo)
        .fold(0, |mask, (slot, _)| mask | 1 << slot)
}

/// The coordinator's view of an agent's report.
fn stats_of(r: &AgentReport) -> AgentStats {
    let sent = r.messages.total(proto::Direction::Sent);
    let received = r.messages.total(proto::Direction::Received);
    let advising = r.messages.sent_of(&MessageKind::ADVISING);
    let [answered, declined, futile, lost, reused] = r.request_outcomes;
    AgentStats {
        give_spent: r.give_spent,
        ask_spent: r.ask_spent,
        advice_requests: r.advice_requests,
        advice_replies_received: r.advice_replies_received,
        advice_given: r.advice_given,
        messages_sent: sent.messages,
        bytes_sent: sent.bytes,
        messages_received: received.messages,
        bytes_received: received.bytes,
        messages_dropped: r.messages.dropped.total(),
        advising_messages: advising.messages,
        advising_bytes: advising.bytes,
        answered_requests: answered,
        declined_requests: declined,
        futile_requests: futile,
        lost_requests: lost,
        reused_advice: reused,
    }
}

#[cfg(test)]
mod tests {
    use agent::{AgentConfig, DqnSettings, LearnerSettings};

    use super::*;
    use crate::membership::MembershipEvent;

    #[test]
    fn hfos_features_go_to_the_slots_whose_agent_or_newcomer_reads_them() {
        let hfo = AgentSpec {
            config: AgentConfig {
                learner: LearnerSettings::Dqn(DqnSettings {
                    observation: ObservationSet::Hfo,
                    ..DqnSettings::default()
                }),
                ..AgentConfig::default()
            },
            ..AgentSpec::default()
        };
        let mut config = ExperimentConfig {
            team: vec![AgentSpec::default(), hfo.clone(), AgentSpec::default()],
            ..ExperimentConfig::default()
        };
        assert_eq!(hfo_features(&config), 0b010);
        let joins = |slot, newcomer| MembershipEvent {
            episode: 1,
            slot,
            newcomer,
        };
        // A newcomer reading them, and the fresh copy of an agent that does.
        config.events = vec![joins(2, Some(hfo)), joins(1, None), joins(0, None)];
        assert_eq!(hfo_features(&config), 0b110);
    }
}
