//! `env-server serve` as a real process, driven over zenoh by an in-test
//! session that plays the coordinator and three fake agents
//! (docs/protocol.md).

use env_server::{Env, EnvConfig, Outcome, RunEnvs};
use node::net::{NetConfig, free_port};
use node::secret::Secret;
use proto::keys::{Keys, Role};
use proto::{
    Action, ActionChoice, AgentFrame, Body, Control, ControlReply, Envelope, EpisodeOutcome,
    EpisodeResult, Header, Mode, PROTOCOL_VERSION, ServerReport,
};
use std::net::TcpStream;
use std::process::{Child, Command, Output, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use zenoh::Session;
use zenoh::pubsub::Publisher;
use zenoh::query::{ConsolidationMode, QueryTarget};

const AGENTS: u8 = 3;

/// The server process, killed (if still running) when dropped.
struct ServerProcess(Child);

impl Drop for ServerProcess {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

impl ServerProcess {
    /// Waits up to `limit` for the process to exit.
    fn wait_exit(&mut self, limit: Duration) -> Option<std::process::ExitStatus> {
        let start = Instant::now();
        while start.elapsed() < limit {
            if let Some(status) = self.0.try_wait().expect("try_wait") {
                return Some(status);
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        None
    }
}

fn command(args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_env-server"));
    command.arg("serve").args(args);
    command
}

/// Starts `env-server serve` for `experiment` on `port`, with `extra` flags.
fn start(experiment: &str, port: u16, extra: &[&str]) -> ServerProcess {
    let listen = format!("tcp/127.0.0.1:{port}");
    let mut args = vec!["--experiment", experiment, "--listen", &listen];
    args.extend_from_slice(extra);
    let child = command(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn env-server");
    ServerProcess(child)
}

/// What fake agent `i` saw and did.
#[derive(Debug, Default)]
struct Seen {
    observations: Vec<(Header, AgentFrame)>,
    /// Observation messages received, by all agents.
    messages: u64,
    actions_sent: u64,
}

/// How the fake agents behave.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Behaviour {
    /// Every kicker shoots at once.
    Shoot,
    /// Nobody ever answers.
    Silent,
    /// Like `Shoot`, and agent 0 first publishes noise on `act/0` when it
    /// sees the first frame of the first episode.
    ShootAfterNoise,
}

/// The in-test session: coordinator and fake agents.
struct Harness {
    server: ServerProcess,
    session: Session,
    keys: Keys,
    experiment: u64,
    seen: Vec<Arc<Mutex<Seen>>>,
    /// The step timeout every reset sets (ms).
    step_timeout_ms: u64,
    _secret_dir: tempfile::TempDir,
}

impl Harness {
    /// Starts a server and joins it with fake agents behaving `behaviour`;
    /// every run waits `step_timeout_ms` for a kicker's action.
    async fn new(name: &str, behaviour: Behaviour, step_timeout_ms: u64) -> Self {
        let port = free_port().expect("a free port");
        let dir = tempfile::tempdir().expect("a temporary directory");
        let secret = Secret::create(&dir.path().join("secret")).expect("a secret");
        let secret_file = secret.path().display().to_string();
        let server = start(name, port, &["--secret-file", &secret_file]);
        let net = NetConfig::loopback_peer(0, vec![format!("tcp/127.0.0.1:{port}")])
            .with_secret(Some(secret));
        let session = node::net::open(&net).await.expect("open the test session");
        let keys = Keys::new(name).expect("keys");
        let experiment = proto::experiment_id(name);
        let mut seen = Vec::new();
        for i in 0..AGENTS {
            let log = Arc::new(Mutex::new(Seen::default()));
            spawn_agent(&session, &keys, experiment, i, behaviour, log.clone()).await;
            seen.push(log);
        }
        let alive = session
            .liveliness()
            .declare_subscriber(keys.alive(Role::Server))
            .history(true)
            .await
            .expect("liveliness subscriber");
        tokio::time::timeout(Duration::from_secs(15), alive.recv_async())
            .await
            .expect("the server's liveliness token within 15 s")
            .expect("liveliness sample");
        Harness {
            step_timeout_ms,
            _secret_dir: dir,
            server,
            session,
            keys,
            experiment,
            seen,
        }
    }

    /// Sends `control` with `header` (run, episode) and returns the reply.
    async fn control(&self, run: u32, episode: u32, control: Control) -> ControlReply {
        let header = Header::new(self.experiment, run, episode, 0);
        let bytes = proto::encode(&Envelope {
            header,
            body: Body::Control(control),
        });
        self.query(bytes).await
    }

    /// Sends raw bytes to the control queryable and returns the reply.
    async fn query(&self, bytes: Vec<u8>) -> ControlReply {
        let replies = self
            .session
            .get(self.keys.control(Role::Server))
            .payload(bytes)
            .consolidation(ConsolidationMode::None)
            .target(QueryTarget::All)
            .timeout(Duration::from_secs(60))
            .await
            .expect("get");
        let reply = replies.recv_async().await.expect("a reply");
        let sample = reply.result().expect("a sample reply");
        let envelope =
            proto::decode(&sample.payload().to_bytes(), self.experiment).expect("decodable");
        match envelope.body {
            Body::ControlReply(reply) => reply,
            other => panic!("not a control reply: {other:?}"),
        }
    }

    async fn reset(&self, run: u32, seed: u64) {
        let config = proto::encode_settings(&EnvConfig::default()).expect("settings");
        let reset = Control::Reset {
            seed,
            config,
            wait_ms: self.step_timeout_ms,
            stall_ms: proto::MAX_STALL_MS,
            simulator: proto::Simulator::Ours,
            features: 0,
        };
        let reply = self.control(run, 0, reset).await;
        assert_eq!(reply, ControlReply::Ok);
    }

    async fn play(&self, run: u32, episode: u32, mode: Mode, seed: Option<u64>) -> EpisodeResult {
        match self
            .control(run, episode, Control::PlayEpisode { mode, seed })
            .await
        {
            ControlReply::Episode(result) => result,
            other => panic!("episode {episode}: {other:?}"),
        }
    }

    async fn report(&self, run: u32) -> ServerReport {
        match self.control(run, 0, Control::Report).await {
            ControlReply::Server(report) => *report,
            other => panic!("report: {other:?}"),
        }
    }

    /// Waits until every agent has seen the terminal frame of `episode`
    /// and returns each agent's observations of it.
    async fn observations(&self, run: u32, episode: u32) -> Vec<Vec<AgentFrame>> {
        let start = Instant::now();
        loop {
            let of_episode: Vec<Vec<(Header, AgentFrame)>> = self
                .seen
                .iter()
                .map(|s| {
                    let seen = s.lock().expect("lock");
                    seen.observations
                        .iter()
                        .filter(|(h, _)| (h.run, h.episode) == (run, episode))
                        .cloned()
                        .collect()
                })
                .collect();
            if of_episode
                .iter()
                .all(|o| o.last().is_some_and(|(_, obs)| obs.is_terminal()))
            {
                return of_episode
                    .into_iter()
                    .map(|o| {
                        for (f, (h, _)) in o.iter().enumerate() {
                            assert_eq!(h.frame as usize, f, "frames in order");
                        }
                        o.into_iter().map(|(_, obs)| obs).collect()
                    })
                    .collect();
            }
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "terminal observations of episode {episode} missing"
            );
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
    }

    fn messages(&self) -> u64 {
        self.seen
            .iter()
            .map(|s| s.lock().expect("lock").messages)
            .sum()
    }

    fn actions_sent(&self) -> u64 {
        self.seen
            .iter()
            .map(|s| s.lock().expect("lock").actions_sent)
            .sum()
    }
}

/// Declares fake agent `i` (subscriber on `obs/i`, publisher on `act/i`)
/// and runs it in a task.
async fn spawn_agent(
    session: &Session,
    keys: &Keys,
    experiment: u64,
    i: u8,
    behaviour: Behaviour,
    seen: Arc<Mutex<Seen>>,
) {
    let subscriber = session
        .declare_subscriber(keys.observation(i))
        .await
        .expect("subscriber");
    let publisher = session
        .declare_publisher(keys.action(i))
        .await
        .expect("publisher");
    tokio::spawn(async move {
        let mut noisy = behaviour == Behaviour::ShootAfterNoise && i == 0;
        while let Ok(sample) = subscriber.recv_async().await {
            let envelope =
                proto::decode(&sample.payload().to_bytes(), experiment).expect("observation");
            let Body::Observations(frames) = envelope.body else {
                panic!("not observations: {envelope:?}");
            };
            assert!((1..=proto::MAX_FRAMES_PER_MESSAGE).contains(&frames.len()));
            seen.lock().expect("lock").messages += 1;
            let last = frames.len() - 1;
            for (k, obs) in frames.into_iter().enumerate() {
                let header = Header {
                    frame: envelope.header.frame + k as u32,
                    ..envelope.header
                };
                assert_eq!(obs.agent, i);
                let decides = obs.can_kick && !obs.is_terminal();
                assert!(!decides || k == last, "a decision ends its message");
                if noisy {
                    noisy = false;
                    send_noise(&publisher, header).await;
                }
                let answer = decides && behaviour != Behaviour::Silent;
                seen.lock().expect("lock").observations.push((header, obs));
                if answer {
                    let choice = ActionChoice {
                        agent: i,
                        action: Action::Shoot,
                    };
                    let bytes = proto::encode(&Envelope {
                        header,
                        body: Body::Action(choice),
                    });
                    publisher.put(bytes).await.expect("put");
                    seen.lock().expect("lock").actions_sent += 1;
                }
            }
        }
    });
}

/// One malformed, one foreign, one other-version and one stale message,
/// each saying "agent 0 dribbles" in frame `header`.
async fn send_noise(publisher: &Publisher<'static>, header: Header) {
    let dribble = |header| {
        proto::encode(&Envelope {
            header,
            body: Body::Action(ActionChoice {
                agent: 0,
                action: Action::Dribble,
            }),
        })
    };
    let mut truncated = dribble(header);
    truncated.pop();
    let foreign = dribble(Header {
        experiment: header.experiment ^ 1,
        ..header
    });
    let version = dribble(Header {
        version: PROTOCOL_VERSION + 1,
        ..header
    });
    let stale = dribble(Header {
        run: header.run + 1,
        ..header
    });
    for bytes in [truncated, foreign, version, stale] {
        publisher.put(bytes).await.expect("put");
    }
}

/// The episode the server should play: the same simulator stepped
/// directly, kickers playing `kick` and the others moving.
/// The episode `env` plays when every kicker plays `kick`; `silent` kickers
/// send nothing, so their actions time out and count.
fn replay_with(env: &mut Env, kick: Action, silent: bool) -> EpisodeResult {
    env.reset();
    let mut timed_out = 0;
    loop {
        let actions: Vec<Action> = (0..env.offense())
            .map(|i| if env.can_kick(i) { kick } else { Action::Move })
            .collect();
        if silent {
            timed_out += (0..env.offense()).filter(|&i| env.can_kick(i)).count() as u32;
        }
        let outcome = env.step(&actions);
        let outcome = match outcome {
            Outcome::InGame => continue,
            Outcome::Goal => EpisodeOutcome::Goal,
            Outcome::Captured => EpisodeOutcome::Captured,
            Outcome::OutOfBounds => EpisodeOutcome::OutOfBounds,
            Outcome::OutOfTime => EpisodeOutcome::OutOfTime,
        };
        return EpisodeResult {
            outcome,
            frames: env.frame(),
            actions_timed_out: timed_out,
        };
    }
}

fn replay(env: &mut Env, kick: Action) -> EpisodeResult {
    replay_with(env, kick, false)
}

/// Checks that every agent saw frames 0..=frames of an episode, the last
/// one terminal with the final reward; returns the kicker frames seen.
fn check_observations(seen: &[Vec<AgentFrame>], result: EpisodeResult, mode: Mode) -> u64 {
    let mut kicks = 0;
    for (i, obs) in seen.iter().enumerate() {
        assert_eq!(obs.len() as u32, result.frames + 1, "agent {i}");
        let (last, rest) = obs.split_last().expect("observations");
        assert!(last.is_terminal() && !last.can_kick);
        assert_eq!(last.reward, result.outcome.reward());
        assert_eq!(last.outcome, Some(result.outcome));
        assert_eq!(rest[0].reward, 0.0);
        for o in obs {
            assert_eq!((o.agent as usize, o.mode), (i, mode));
            assert_eq!(o.positions.len(), AGENTS as usize);
            assert!(o.state.iter().all(|x| (-1.0..=1.0).contains(x)));
        }
        assert!(rest.iter().all(|o| !o.is_terminal()));
        kicks += rest.iter().filter(|o| o.can_kick).count() as u64;
    }
    kicks
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn episodes_match_the_simulator_and_reach_every_agent() {
    let h = Harness::new("serve-episodes", Behaviour::Shoot, 10000).await;
    let config = EnvConfig::default();
    // The same run in process: the evaluation block carries the training
    // simulator's memories there and back.
    let mut simulators = RunEnvs::new(config.clone(), 7).expect("env");
    h.reset(3, 7).await;
    let plan = [
        (Mode::Training, None),
        (Mode::Evaluation, Some(99)),
        (Mode::Evaluation, None),
        (Mode::Training, None),
    ];
    let (mut frames, mut kicks) = (0, 0);
    for (episode, (mode, seed)) in plan.into_iter().enumerate() {
        let episode = episode as u32;
        let result = h.play(3, episode, mode, seed).await;
        if let Some(seed) = seed {
            simulators.begin_evaluation(seed);
        }
        let env = simulators.env(mode).expect("a simulator");
        assert_eq!(result, replay(env, Action::Shoot), "episode {episode}");
        assert!((1..=config.frames_per_trial).contains(&result.frames));
        let seen = h.observations(3, episode).await;
        kicks += check_observations(&seen, result, mode);
        frames += u64::from(result.frames);
    }
    let report = h.report(3).await;
    assert_eq!(report.frames, frames);
    assert_eq!(report.actions_timed_out, 0);
    assert_eq!(kicks, h.actions_sent());
    let m = &report.messages;
    assert_eq!(
        m.received[proto::MessageKind::Action as usize].messages,
        kicks
    );
    // Frames are sent in batches, up to each decision and the episode's end.
    assert_eq!(
        m.sent[proto::MessageKind::Observation as usize].messages,
        h.messages()
    );
    assert!(h.messages() < (frames + plan.len() as u64) * u64::from(AGENTS));
    assert_eq!(m.dropped.total(), 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn silent_agents_fall_back_to_move() {
    let h = Harness::new("serve-silent", Behaviour::Silent, 20).await;
    h.reset(0, 5).await;
    let result = h.play(0, 0, Mode::Training, None).await;
    let mut env = Env::new(EnvConfig::default(), 5).expect("env");
    assert_eq!(result, replay_with(&mut env, Action::Move, true));
    let kicks = check_observations(&h.observations(0, 0).await, result, Mode::Training);
    let report = h.report(0).await;
    assert!(report.actions_timed_out > 0);
    assert_eq!(report.actions_timed_out, kicks);
    assert_eq!(u64::from(result.actions_timed_out), kicks);
    assert_eq!(report.frames, u64::from(result.frames));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_agent_silent_for_the_stall_limit_ends_the_episode_with_an_error() {
    let h = Harness::new("serve-stall", Behaviour::Silent, 20).await;
    let config = proto::encode_settings(&EnvConfig::default()).expect("settings");
    let reset = Control::Reset {
        seed: 5,
        config,
        wait_ms: 20,
        stall_ms: 100,
        simulator: proto::Simulator::Ours,
        features: 0,
    };
    assert_eq!(h.control(0, 0, reset).await, ControlReply::Ok);
    let reply = h
        .control(
            0,
            0,
            Control::PlayEpisode {
                mode: Mode::Training,
                seed: None,
            },
        )
        .await;
    let ControlReply::Error(text) = reply else {
        panic!("expected the stall error, got {reply:?}");
    };
    assert!(
        text.contains("stall limit") && text.contains("agent"),
        "{text}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn noise_on_act_is_dropped_and_counted() {
    let h = Harness::new("serve-noise", Behaviour::ShootAfterNoise, 10000).await;
    h.reset(0, 21).await;
    let mut env = Env::new(EnvConfig::default(), 21).expect("env");
    let mut kicks = 0;
    for episode in 0..3 {
        let result = h.play(0, episode, Mode::Training, None).await;
        assert_eq!(result, replay(&mut env, Action::Shoot), "episode {episode}");
        kicks += check_observations(&h.observations(0, episode).await, result, Mode::Training);
    }
    let report = h.report(0).await;
    let d = report.messages.dropped;
    assert_eq!(
        (d.malformed, d.foreign, d.version, d.stale, d.duplicate),
        (1, 1, 1, 1, 0)
    );
    assert_eq!(
        report.messages.received[proto::MessageKind::Action as usize].messages,
        kicks
    );
    assert_eq!(report.actions_timed_out, 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_commands_get_errors_and_change_nothing() {
    let h = Harness::new("serve-control", Behaviour::Shoot, 10000).await;
    let error = |reply: ControlReply| match reply {
        ControlReply::Error(text) => text,
        other => panic!("expected an error, got {other:?}"),
    };
    let play =
        |run, episode, mode, seed| h.control(run, episode, Control::PlayEpisode { mode, seed });
    assert!(error(play(0, 0, Mode::Training, None).await).contains("Reset"));
    let reset = |config: &[u8]| Control::Reset {
        seed: 1,
        config: config.to_owned(),
        wait_ms: 10_000,
        stall_ms: proto::MAX_STALL_MS,
        simulator: proto::Simulator::Ours,
        features: 0,
    };
    let nine = EnvConfig {
        offense: 9,
        ..EnvConfig::default()
    };
    let nine = proto::encode_settings(&nine).expect("settings");
    assert!(error(h.control(0, 0, reset(&nine)).await).contains("offense"));
    assert!(error(h.control(0, 0, reset(b"{")).await).contains("invalid env config"));
    let good = proto::encode_settings(&EnvConfig::default()).expect("settings");
    let fourth = Control::Reset {
        seed: 1,
        config: good.clone(),
        wait_ms: 10_000,
        stall_ms: proto::MAX_STALL_MS,
        simulator: proto::Simulator::Ours,
        features: 0b1000,
    };
    assert_eq!(
        error(h.control(0, 0, fourth).await),
        "HFO's features are asked for agents 0b1000 of a team of 3"
    );
    for wait_ms in [0, proto::MAX_WAIT_MS + 1] {
        let unbounded = Control::Reset {
            seed: 1,
            config: good.clone(),
            wait_ms,
            stall_ms: proto::MAX_STALL_MS,
            simulator: proto::Simulator::Ours,
            features: 0,
        };
        assert!(error(h.control(0, 0, unbounded).await).contains("step timeout"));
    }
    for stall_ms in [999, proto::MAX_STALL_MS + 1] {
        let unbounded = Control::Reset {
            seed: 1,
            config: good.clone(),
            wait_ms: 1000,
            stall_ms,
            simulator: proto::Simulator::Ours,
            features: 0,
        };
        assert!(error(h.control(0, 0, unbounded).await).contains("stall limit"));
    }
    h.reset(1, 4).await;
    assert!(error(play(0, 0, Mode::Training, None).await).contains("run"));
    assert!(error(play(1, 0, Mode::Evaluation, None).await).contains("evaluation"));
    let load = Control::Load {
        part: 0,
        parts: 1,
        bytes: vec![0; 64],
    };
    assert!(error(h.control(1, 0, load).await).contains("does not handle Load"));
    assert!(!error(h.query(vec![0xff, 0xff]).await).is_empty());
    let foreign = proto::encode(&Envelope {
        header: Header::new(h.experiment ^ 1, 1, 0, 0),
        body: Body::Control(Control::Stop),
    });
    assert!(error(h.query(foreign).await).contains("experiment"));
    let newer = proto::encode(&Envelope {
        header: Header {
            version: PROTOCOL_VERSION + 1,
            ..Header::new(h.experiment, 1, 0, 0)
        },
        body: Body::Control(Control::Stop),
    });
    assert!(error(h.query(newer).await).contains("protocol version"));
    // The run is intact: its first episode is the simulator's first.
    let result = play(1, 0, Mode::Training, None).await;
    let mut env = Env::new(EnvConfig::default(), 4).expect("env");
    assert_eq!(
        result,
        ControlReply::Episode(replay(&mut env, Action::Shoot))
    );
    assert!(error(play(1, 0, Mode::Training, None).await).contains("episode"));
    let d = h.report(1).await.messages.dropped;
    assert_eq!((d.malformed, d.foreign, d.version, d.stale), (1, 1, 1, 3));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn stop_exits_zero() {
    let mut h = Harness::new("serve-stop", Behaviour::Shoot, 10_000).await;
    h.reset(0, 1).await;
    assert_eq!(h.control(0, 0, Control::Stop).await, ControlReply::Ok);
    let status = h.server.wait_exit(Duration::from_secs(10));
    assert_eq!(status.and_then(|s| s.code()), Some(0));
}

/// Runs a `serve` that must fail, checking exit code 2 and a one-line error.
fn fails(args: &[&str], within: Duration) -> String {
    let start = Instant::now();
    let Output { status, stderr, .. } = command(args).output().expect("run env-server");
    assert!(
        start.elapsed() < within,
        "{args:?} took {:?}",
        start.elapsed()
    );
    assert_eq!(status.code(), Some(2), "{args:?}");
    let stderr = String::from_utf8(stderr).expect("utf-8");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    stderr
}

#[test]
fn second_server_on_the_same_port_exits_2() {
    let port = free_port().expect("a free port");
    let _first = start("serve-port", port, &["--no-auth"]);
    let start = Instant::now();
    while TcpStream::connect(("127.0.0.1", port)).is_err() {
        assert!(start.elapsed() < Duration::from_secs(10), "first server");
        std::thread::sleep(Duration::from_millis(20));
    }
    let listen = format!("tcp/127.0.0.1:{port}");
    let args = [
        "--experiment",
        "serve-port",
        "--listen",
        &listen,
        "--no-auth",
    ];
    let e = fails(&args, Duration::from_secs(10));
    assert!(e.contains("in use") && e.contains(&listen), "{e}");
}

#[test]
fn bad_input_is_one_line_and_exit_2() {
    let quick = Duration::from_secs(10);
    assert!(fails(&["--experiment", "a/b", "--no-auth"], quick).contains("experiment name"));
    assert!(fails(&["--experiment", "x"], quick).contains("--secret-file"));
    let e = fails(
        &["--experiment", "x", "--secret-file", "/nonexistent/s"],
        quick,
    );
    assert!(e.contains("secret file /nonexistent/s: cannot read"), "{e}");
    let e = fails(
        &["--experiment", "x", "--listen", "nonsense", "--no-auth"],
        quick,
    );
    assert!(
        e.contains("invalid network settings (listen nonsense;"),
        "{e}"
    );
    let e = fails(
        &[
            "--experiment",
            "x",
            "--listen",
            "tcp/127.0.0.1:99999",
            "--no-auth",
        ],
        quick,
    );
    assert!(e.contains("port"), "{e}");
    let nobody = format!("tcp/127.0.0.1:{}", free_port().expect("a free port"));
    let e = fails(
        &["--experiment", "x", "--connect", &nobody, "--no-auth"],
        quick,
    );
    assert!(e.contains(&nobody), "{e}");
}

/// Frames per second with fake agents answering at once (information, not
/// a check): `cargo test --release -p env-server-process --test serve -- --ignored --nocapture`.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "measurement"]
async fn frames_per_second() {
    let h = Harness::new("serve-speed", Behaviour::Shoot, 1000).await;
    h.reset(0, 3).await;
    let episodes = 300;
    let start = Instant::now();
    let mut frames = 0u64;
    for episode in 0..episodes {
        frames += u64::from(h.play(0, episode, Mode::Training, None).await.frames);
    }
    let secs = start.elapsed().as_secs_f64();
    let report = h.report(0).await;
    println!(
        "{episodes} episodes, {frames} frames in {secs:.2} s: {:.0} frames/s, {:.1} episodes/s, {} missing actions, {} actions",
        frames as f64 / secs,
        f64::from(episodes) / secs,
        report.actions_timed_out,
        h.actions_sent()
    );
}
