//! The server: control queries and the step deadline in an event loop, and
//! actions where they arrive, in zenoh's callback, one at a time under one
//! lock, so that an episode waiting for actions never holds up a control
//! query and a silent agent never holds up the episode.
//!
//! Rules beyond `docs/protocol.md`: `Report` and `Stop` concern the process
//! and are obeyed whatever run their header names; `PlayEpisode` must name
//! the run of the last `Reset` and an episode after the last one played
//! (else it is stale), and is refused while another episode is played;
//! `Reset` abandons an episode in progress. An action from an agent that
//! has no decision to make (or whose id differs from its key's) is counted
//! as malformed; any action not of the current run, episode and frame is
//! stale.

use super::episode::{Batches, Episode, Offer, ServedRun};
use super::link::{Inbox, Link};
use super::real_hfo::RealHfoInstall;
use super::simulator::ServedSimulator;
use anyhow::{Result, bail};
use env_server::MAX_OFFENSE;
use node::sync::lock;
use proto::{
    Body, Control, ControlReply, DecodeError, Direction, DropReason, Envelope, Header,
    MessageCounters, MessageKind, Mode, ServerReport, Simulator,
};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::mpsc::unbounded_channel;
use tracing::{debug, warn};
use zenoh::query::Query;
use zenoh::sample::Sample;

/// Whether the loop goes on after a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Flow {
    Continue,
    Stop,
}

/// The episode being played and the query that asked for it.
struct Play {
    query: Query,
    episode: Episode,
    /// When the awaited actions are given up (set while waiting).
    deadline: Option<Instant>,
}

/// The current run.
struct CurrentRun {
    run: u32,
    envs: ServedRun,
    /// The agents given HFO's features, bit `i` for agent `i`.
    features: u8,
    /// The last episode played in this run.
    last_episode: Option<u32>,
}

/// env-server's state.
struct Server {
    link: Link,
    experiment: u64,
    /// Where the real HFO is, when this server plays it instead of ours.
    real_hfo: Option<RealHfoInstall>,
    step_timeout: Duration,
    /// How long a kicker may stay silent, frame after frame.
    stall_limit: Duration,
    /// Since when each agent has sent no awaited action (None: it answered
    /// its last decision).
    silent_since: [Option<Instant>; MAX_OFFENSE],
    run: Option<CurrentRun>,
    play: Option<Play>,
    /// The observations of the frames not sent yet.
    batches: Batches,
    frames: u64,
    actions_timed_out: u64,
    counters: MessageCounters,
}

impl Server {
    /// A server on `link`, playing the real HFO where `real_hfo` says; each
    /// run's reset sets how long it waits for a frame's actions.
    fn new(link: Link, real_hfo: Option<RealHfoInstall>) -> Self {
        let experiment = link.experiment();
        Server {
            link,
            experiment,
            real_hfo,
            step_timeout: Duration::ZERO,
            stall_limit: Duration::ZERO,
            silent_since: [None; MAX_OFFENSE],
            run: None,
            play: None,
            batches: Batches::default(),
            frames: 0,
            actions_timed_out: 0,
            counters: MessageCounters::default(),
        }
    }

    /// When the awaited actions are given up, if they are awaited.
    fn deadline(&self) -> Option<Instant> {
        self.play.as_ref().and_then(|p| p.deadline)
    }

    /// Handles one control query: decodes it (replying `Error` to what
    /// cannot be accepted, and counting it) and carries it out.
    fn on_query(&mut self, query: Query) -> Result<Flow> {
        let decoded = match query.payload() {
            Some(payload) => {
                let bytes = payload.to_bytes();
                proto::decode(&bytes, self.experiment).map(|e| (e, bytes.len()))
            }
            None => Err(DecodeError::Malformed("no payload".to_owned())),
        };
        let (Envelope { header, body }, size) = match decoded {
            Ok(ok) => ok,
            Err(e) => {
                self.counters.drop_undecodable(&e);
                debug!(error = %e, "dropped a control query");
                let header = Header::new(self.experiment, self.current_run(), 0, 0);
                let text = format!("rejected: {e}");
                self.reply(&query, header, ControlReply::Error(text));
                return Ok(Flow::Continue);
            }
        };
        let Body::Control(control) = body else {
            self.counters.record_drop(DropReason::Malformed);
            debug!(kind = ?MessageKind::of(&body), "dropped a control query");
            let text = format!(
                "expected a control command, got {:?}",
                MessageKind::of(&body)
            );
            self.reply(&query, header, ControlReply::Error(text));
            return Ok(Flow::Continue);
        };
        if let Control::PlayEpisode { mode, seed } = control {
            return match self.check_episode(&header) {
                Ok(()) => {
                    self.received(size);
                    self.begin(query, header, mode, seed)?;
                    Ok(Flow::Continue)
                }
                Err(text) => {
                    self.reply(&query, header, ControlReply::Error(text));
                    Ok(Flow::Continue)
                }
            };
        }
        self.received(size);
        let (reply, flow) = match control {
            Control::Reset {
                seed,
                config,
                wait_ms,
                stall_ms,
                simulator,
                features,
            } => {
                let run = (seed, &config[..], simulator, features);
                (
                    self.reset(header, run, (wait_ms, stall_ms))?,
                    Flow::Continue,
                )
            }
            Control::Report => (
                ControlReply::Server(Box::new(self.report())),
                Flow::Continue,
            ),
            Control::Stop => {
                self.abandon("env-server stopped", ControlReply::Error);
                (ControlReply::Ok, Flow::Stop)
            }
            other => {
                let text = format!("env-server does not handle {other:?}");
                (ControlReply::Error(text), Flow::Continue)
            }
        };
        self.reply(&query, header, reply);
        Ok(flow)
    }

    /// Starts run `header.run` with a training simulator seeded with
    /// `seed`, giving the agents of `features` HFO's features, waiting
    /// `wait_ms` for actions and abandoning an episode after `stall_ms` of
    /// silence; an in-progress episode is abandoned. A bad config, or
    /// another simulator than this server plays, changes nothing.
    fn reset(
        &mut self,
        header: Header,
        (seed, config, simulator, features): (u64, &[u8], Simulator, u8),
        (wait_ms, stall_ms): (u64, u64),
    ) -> Result<ControlReply> {
        if !(1..=proto::MAX_WAIT_MS).contains(&wait_ms) {
            return Ok(ControlReply::Error(format!(
                "the step timeout must be 1 to {} ms, got {wait_ms}",
                proto::MAX_WAIT_MS
            )));
        }
        if !(wait_ms..=proto::MAX_STALL_MS).contains(&stall_ms) {
            return Ok(ControlReply::Error(format!(
                "the stall limit must be {wait_ms} (the step timeout) to {} ms, got {stall_ms}",
                proto::MAX_STALL_MS
            )));
        }
        let kind = (simulator, features);
        let envs = match ServedRun::new(config, seed, kind, self.real_hfo.as_ref()) {
            Ok(s) => s,
            Err(text) => return Ok(ControlReply::Error(text)),
        };
        self.step_timeout = Duration::from_millis(wait_ms);
        self.stall_limit = Duration::from_millis(stall_ms);
        self.silent_since = [None; MAX_OFFENSE];
        self.abandon("its run was reset", ControlReply::Error);
        self.link.set_team(envs.offense())?;
        self.run = Some(CurrentRun {
            run: header.run,
            envs,
            features,
            last_episode: None,
        });
        Ok(ControlReply::Ok)
    }

    /// Whether `PlayEpisode` with `header` may start now; counts stale ones.
    fn check_episode(&mut self, header: &Header) -> Result<(), String> {
        if let Some(play) = &self.play {
            let h = play.episode.header;
            return Err(format!(
                "busy playing episode {} of run {}",
                h.episode, h.run
            ));
        }
        let verdict = match &self.run {
            None => Err("no run: Reset first".to_owned()),
            Some(r) if r.run != header.run => Err(format!(
                "run {} is not the current run {}",
                header.run, r.run
            )),
            Some(r) if r.last_episode.is_some_and(|last| header.episode <= last) => Err(format!(
                "episode {} of run {} is not after the last one played",
                header.episode, r.run
            )),
            Some(_) => Ok(()),
        };
        if verdict.is_err() {
            self.counters.record_drop(DropReason::Stale);
            debug!(
                run = header.run,
                episode = header.episode,
                "dropped a stale PlayEpisode"
            );
        }
        verdict
    }

    /// Starts episode `header.episode` and plays it up to its first wait.
    fn begin(&mut self, query: Query, header: Header, mode: Mode, seed: Option<u64>) -> Result<()> {
        let Some(run) = self.run.as_mut() else {
            return Ok(());
        };
        let env = match run.envs.prepare(mode, seed) {
            Ok(env) => env,
            Err(text) => {
                self.reply(&query, header, ControlReply::Error(text));
                return Ok(());
            }
        };
        run.last_episode = Some(header.episode);
        let start = Header::new(self.experiment, header.run, header.episode, 0);
        let episode = match Episode::start(env, start, mode, run.features) {
            Ok(episode) => episode,
            Err(text) => {
                warn!(run = header.run, episode = header.episode, "{text}");
                self.reply(&query, header, ControlReply::SimulatorFailed(text));
                return Ok(());
            }
        };
        self.play = Some(Play {
            query,
            episode,
            deadline: None,
        });
        self.advance()
    }

    /// Steps on through frames where no agent can kick, holding back their
    /// observations, until one awaits actions (arming the deadline) or the
    /// episode ends (answering its query); then sends each agent its frames
    /// in one message.
    fn advance(&mut self) -> Result<()> {
        loop {
            let Some((play, env)) = playing(&mut self.play, &mut self.run) else {
                return Ok(());
            };
            self.batches.push(&play.episode, env);
            let (over, waiting) = (play.episode.is_over(), play.episode.is_waiting());
            if over || waiting || self.batches.is_full() {
                self.send_observations()?;
            }
            if over {
                self.finish();
                return Ok(());
            }
            let Some((play, env)) = playing(&mut self.play, &mut self.run) else {
                return Ok(());
            };
            if waiting {
                play.deadline = Some(Instant::now() + self.step_timeout);
                return Ok(());
            }
            if let Err(why) = play.episode.step(env) {
                self.abandon(&why, ControlReply::SimulatorFailed);
                return Ok(());
            }
            self.frames += 1;
        }
    }

    /// Sends every agent the observations held for it.
    fn send_observations(&mut self) -> Result<()> {
        for (agent, bytes) in self.batches.take().into_iter().enumerate() {
            self.counters
                .record(Direction::Sent, MessageKind::Observation, bytes.len());
            self.link.publish(agent, bytes)?;
        }
        Ok(())
    }

    /// Steps the episode with the actions it has, then advances.
    fn proceed(&mut self) -> Result<()> {
        if let Some((play, env)) = playing(&mut self.play, &mut self.run) {
            play.deadline = None;
            if let Err(why) = play.episode.step(env) {
                self.abandon(&why, ControlReply::SimulatorFailed);
                return Ok(());
            }
            self.frames += 1;
        }
        self.advance()
    }

    /// Answers the query of the finished episode with its result.
    fn finish(&mut self) {
        if let Some(play) = self.play.take() {
            let reply = match play.episode.result() {
                Some(result) => ControlReply::Episode(result),
                None => ControlReply::Error("the episode did not end".to_owned()),
            };
            self.reply(&play.query, play.episode.header, reply);
        }
    }

    /// Gives up the episode in progress, if any, answering its query with
    /// `reply` and why: an error, or its simulator failed (the next episode
    /// gets it started afresh).
    fn abandon(&mut self, why: &str, reply: fn(String) -> ControlReply) {
        self.batches.clear();
        if let Some(play) = self.play.take() {
            let h = play.episode.header;
            warn!(
                run = h.run,
                episode = h.episode,
                frame = h.frame,
                "episode abandoned: {why}"
            );
            let text = format!("episode {} of run {} abandoned: {why}", h.episode, h.run);
            self.reply(&play.query, h, reply(text));
        }
    }

    /// Handles a sample on `act/*`: the awaited action of a kicker moves
    /// the episode on once the frame's last one arrives; anything else is
    /// dropped and counted.
    fn on_action(&mut self, sample: &Sample) -> Result<()> {
        let bytes = sample.payload().to_bytes();
        let envelope = match proto::decode(&bytes, self.experiment) {
            Ok(envelope) => envelope,
            Err(e) => {
                self.counters.drop_undecodable(&e);
                debug!(key = %sample.key_expr(), error = %e, "dropped an action");
                return Ok(());
            }
        };
        let offer = match (&envelope.body, self.play.as_mut()) {
            (Body::Action(choice), _) if key_agent(sample) != Some(choice.agent) => {
                Offer::Unexpected
            }
            (Body::Action(choice), Some(play)) => play.episode.offer(&envelope.header, choice),
            (Body::Action(_), None) => Offer::Stale,
            _ => Offer::Unexpected,
        };
        let reason = match offer {
            Offer::Accepted => {
                if let Body::Action(choice) = &envelope.body
                    && let Some(since) = self.silent_since.get_mut(usize::from(choice.agent))
                {
                    *since = None;
                }
                self.counters
                    .record(Direction::Received, MessageKind::Action, bytes.len());
                let waiting = self.play.as_ref().is_some_and(|p| p.episode.is_waiting());
                return if waiting { Ok(()) } else { self.proceed() };
            }
            Offer::Stale => DropReason::Stale,
            Offer::Duplicate => DropReason::Duplicate,
            Offer::Unexpected => DropReason::Malformed,
        };
        self.counters.record_drop(reason);
        debug!(key = %sample.key_expr(), header = ?envelope.header, ?reason, "dropped an action");
        Ok(())
    }

    /// The step timeout passed: every missing kicker moves, and the episode
    /// is abandoned if one of them has been silent for the stall limit.
    fn on_timeout(&mut self) -> Result<()> {
        let Some(play) = &mut self.play else {
            return Ok(());
        };
        let h = play.episode.header;
        let now = Instant::now();
        let mut stalled = None;
        for agent in play.episode.missing() {
            warn!(
                run = h.run,
                episode = h.episode,
                frame = h.frame,
                agent,
                "no action within the step timeout: Move instead"
            );
            self.actions_timed_out += 1;
            let since = *self.silent_since[agent].get_or_insert(now - self.step_timeout);
            if now.duration_since(since) >= self.stall_limit {
                stalled = Some((agent, now.duration_since(since)));
            }
        }
        play.episode.time_out();
        if let Some((agent, silent)) = stalled {
            let why = format!(
                "agent {agent} sent no action for {:.1} s, the stall limit {:?}: \
                 is its process stopped or overloaded?",
                silent.as_secs_f64(),
                self.stall_limit
            );
            self.abandon(&why, ControlReply::Error);
            return Ok(());
        }
        self.proceed()
    }

    /// Replies `reply` with `header`'s run, episode and frame; a reply that
    /// cannot be sent is logged (the asker is gone or timed out).
    fn reply(&mut self, query: &Query, header: Header, reply: ControlReply) {
        let header = Header::new(self.experiment, header.run, header.episode, header.frame);
        let bytes = proto::encode(&Envelope {
            header,
            body: Body::ControlReply(reply),
        });
        self.counters
            .record(Direction::Sent, MessageKind::ControlReply, bytes.len());
        if let Err(e) = self.link.reply(query, bytes) {
            warn!("{e:#}");
        }
    }

    /// Counts an accepted control command of `size` bytes.
    fn received(&mut self, size: usize) {
        self.counters
            .record(Direction::Received, MessageKind::Control, size);
    }

    /// The counters so far.
    fn report(&self) -> ServerReport {
        ServerReport {
            frames: self.frames,
            actions_timed_out: self.actions_timed_out,
            messages: self.counters.clone(),
        }
    }

    /// The run of the last Reset (0 before any).
    fn current_run(&self) -> u32 {
        self.run.as_ref().map_or(0, |r| r.run)
    }
}

/// Serves on `link` until `Stop`, then closes the session: actions are
/// handled in the subscriber's callback as they arrive, control queries
/// and the step deadline here. Episodes are played on our simulator, or on
/// the real HFO where `real_hfo` says.
pub async fn run(link: Link, mut inbox: Inbox, real_hfo: Option<RealHfoInstall>) -> Result<()> {
    let server = Arc::new(Mutex::new(Server::new(link, real_hfo)));
    let (failed, mut failure) = unbounded_channel();
    // Weak: the callback must not keep the server (and its session) alive.
    let weak = Arc::downgrade(&server);
    let listening = lock(&server).link.listen(move |sample| {
        let Some(server) = weak.upgrade() else { return };
        if let Err(e) = lock(&server).on_action(&sample) {
            // The loop below stops on it.
            let _ = failed.send(e);
        }
    })?;
    let sleep = tokio::time::sleep(Duration::ZERO);
    tokio::pin!(sleep);
    loop {
        // The callback only ever moves the deadline later or clears it:
        // the timer, armed at an earlier one, checks again when it fires.
        let deadline = lock(&server).deadline();
        if let Some(d) = deadline {
            sleep.as_mut().reset(d.into());
        }
        tokio::select! {
            biased;
            query = inbox.queries.recv() => {
                let Some(query) = query else { bail!("the control queryable closed") };
                if lock(&server).on_query(query)? == Flow::Stop {
                    break;
                }
            }
            () = &mut sleep, if deadline.is_some() => {
                let mut server = lock(&server);
                if server.deadline().is_some_and(|d| d <= Instant::now()) {
                    server.on_timeout()?;
                }
            }
            Some(()) = inbox.coordinator_gone.recv() => {
                bail!("the coordinator that started this server is gone; stopping");
            }
            Some(e) = failure.recv() => return Err(e),
        }
    }
    // Undeclared first: no callback runs once it is gone.
    drop(listening);
    lock(&server).link.close()
}

/// The episode being played and its simulator, if any.
fn playing<'a>(
    play: &'a mut Option<Play>,
    run: &'a mut Option<CurrentRun>,
) -> Option<(&'a mut Play, &'a mut dyn ServedSimulator)> {
    let play = play.as_mut()?;
    let env = run.as_mut()?.envs.env(play.episode.mode)?;
    Some((play, env))
}

/// The agent id in a sample's key (`.../act/<id>`).
fn key_agent(sample: &Sample) -> Option<u8> {
    sample.key_expr().as_str().rsplit('/').next()?.parse().ok()
}
