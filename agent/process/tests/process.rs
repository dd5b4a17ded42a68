//! The `agent` binary as real processes on loopback, driven by an in-test
//! zenoh session playing env-server and the coordinator.

mod support;

use std::time::{Duration, Instant};

use agent::{Agent, AgentConfig, Isolated, Profile};
use node::net::NetConfig;
use node::net::free_port;
use node::secret::Secret;
use proto::keys::{Keys, Role};
use proto::{
    ActionChoice, AgentFrame, AgentReport, Body, Control, ControlReply, Envelope, EpisodeOutcome,
    Header, MessageKind, Mode, PROTOCOL_VERSION,
};
use support::Guard;
use zenoh::Session;
use zenoh::handlers::FifoChannelHandler;
use zenoh::pubsub::Subscriber;
use zenoh::query::{ConsolidationMode, QueryTarget};
use zenoh::sample::{Sample, SampleKind};

/// Starts agent `id` of a team of 2, connected to the fake coordinator
/// with its secret.
fn spawn_agent(name: &str, id: u8, fake: &Fake) -> Guard {
    spawn_agent_with(name, id, fake, &[])
}

/// The same with the arguments `extra`.
fn spawn_agent_with(name: &str, id: u8, fake: &Fake, extra: &[&str]) -> Guard {
    let (id, listen) = (
        id.to_string(),
        format!("tcp/127.0.0.1:{}", free_port().unwrap()),
    );
    let connect = format!("tcp/127.0.0.1:{}", fake.port);
    let secret = fake.secret.path().display().to_string();
    let args = ["--experiment", name, "--id", &id, "--team-size", "2"];
    let network = [
        "--listen",
        &listen,
        "--connect",
        &connect,
        "--secret-file",
        &secret,
    ];
    Guard::agent(&[&args[..], &network, &["--exit-with-coordinator"], extra].concat())
}

/// The in-test coordinator and env-server.
struct Fake {
    session: Session,
    keys: Keys,
    experiment: u64,
    tokens: Subscriber<FifoChannelHandler<Sample>>,
    port: u16,
    secret: Secret,
    _secret_dir: tempfile::TempDir,
}

impl Fake {
    async fn open(name: &str) -> Self {
        let port = free_port().unwrap();
        let dir = tempfile::tempdir().unwrap();
        let secret = Secret::create(&dir.path().join("secret")).unwrap();
        let net = NetConfig::loopback_peer(port, Vec::new()).with_secret(Some(secret.clone()));
        let session = node::net::open(&net).await.unwrap();
        let keys = Keys::new(name).unwrap();
        let tokens = session
            .liveliness()
            .declare_subscriber(keys.alive_all())
            .history(true)
            .await
            .unwrap();
        Self {
            session,
            experiment: proto::experiment_id(name),
            keys,
            tokens,
            port,
            secret,
            _secret_dir: dir,
        }
    }

    /// Waits until the tokens of agents `ids` are seen.
    async fn wait_for_agents(&self, ids: &[u8]) {
        let mut seen = Vec::new();
        let deadline = tokio::time::Instant::now() + Duration::from_secs(30);
        while !ids.iter().all(|i| seen.contains(i)) {
            let sample = tokio::time::timeout_at(deadline, self.tokens.recv_async())
                .await
                .expect("agents did not join in time")
                .unwrap();
            if let (Some(Role::Agent(i)), SampleKind::Put) = (
                self.keys.role_of_alive(sample.key_expr().as_str()),
                sample.kind(),
            ) {
                seen.push(i);
            }
        }
    }

    fn header(&self, run: u32, episode: u32, frame: u32) -> Header {
        Header::new(self.experiment, run, episode, frame)
    }

    /// Sends a command to agent `id` and returns its reply.
    async fn control(&self, id: u8, header: Header, control: Control) -> ControlReply {
        let bytes = proto::encode(&Envelope {
            header,
            body: Body::Control(control),
        });
        let replies = self
            .session
            .get(self.keys.control(Role::Agent(id)))
            .payload(bytes)
            .consolidation(ConsolidationMode::None)
            .target(QueryTarget::All)
            .timeout(Duration::from_secs(15))
            .await
            .unwrap();
        let reply = replies.recv_async().await.expect("no reply");
        let payload = reply.result().unwrap().payload().to_bytes();
        match proto::decode(&payload, self.experiment).unwrap().body {
            Body::ControlReply(r) => r,
            other => panic!("not a control reply: {other:?}"),
        }
    }

    async fn reset(&self, id: u8, config: &AgentConfig) {
        let config = proto::encode_settings(config).unwrap();
        let reply = self
            .control(
                id,
                self.header(0, 0, 0),
                Control::Reset {
                    seed: 7 + u64::from(id),
                    config,
                    // Generous, for a loaded test machine.
                    wait_ms: 200,
                    stall_ms: 10_000,
                    simulator: proto::Simulator::Ours,
                    features: 0,
                },
            )
            .await;
        assert_eq!(reply, ControlReply::Ok);
    }

    async fn report(&self, id: u8, episode: u32) -> AgentReport {
        match self
            .control(id, self.header(0, episode, 0), Control::Report)
            .await
        {
            ControlReply::Agent(r) => *r,
            other => panic!("agent {id} answered {other:?}"),
        }
    }

    /// Reports of agent `id` until `done` holds (or panics after 20 s).
    async fn report_until(
        &self,
        id: u8,
        episode: u32,
        done: impl Fn(&AgentReport) -> bool,
    ) -> AgentReport {
        let deadline = Instant::now() + Duration::from_secs(20);
        loop {
            let r = self.report(id, episode).await;
            if done(&r) {
                return r;
            }
            assert!(Instant::now() < deadline, "agent {id}: {r:?}");
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    }

    async fn publish(&self, id: u8, bytes: Vec<u8>) {
        self.session
            .put(self.keys.observation(id), bytes)
            .await
            .unwrap();
    }

    /// Publishes one frame to both agents.
    async fn frame(&self, header: Header, mode: Mode, kick: bool, terminal: bool, reward: f64) {
        for id in 0..2u8 {
            let obs = observation(id, header.frame, mode, kick, terminal, reward);
            self.publish(id, observations(header, vec![obs])).await;
        }
    }

    /// Publishes `n` frames from `header`'s to both agents in one message
    /// each, none with the ball; the last ends the episode with `reward`.
    async fn episode_tail(&self, header: Header, n: u32, reward: f64) {
        for id in 0..2u8 {
            let frames = (0..n)
                .map(|k| {
                    let last = k + 1 == n;
                    let reward = if last { reward } else { 0.0 };
                    observation(id, header.frame + k, Mode::Training, false, last, reward)
                })
                .collect();
            self.publish(id, observations(header, frames)).await;
        }
    }

    async fn stop(&self, id: u8) {
        let reply = self.control(id, self.header(0, 0, 0), Control::Stop).await;
        assert_eq!(reply, ControlReply::Ok);
    }
}

/// An observation message.
fn observations(header: Header, frames: Vec<AgentFrame>) -> Vec<u8> {
    proto::encode(&Envelope {
        header,
        body: Body::Observations(frames),
    })
}

/// Agent `id`'s observation of `frame`: a state of its own per frame.
fn observation(
    id: u8,
    frame: u32,
    mode: Mode,
    kick: bool,
    terminal: bool,
    reward: f64,
) -> AgentFrame {
    let f = f64::from(frame) / 10.0;
    AgentFrame {
        agent: id,
        mode,
        state: [f, 0.5 - f, f64::from(id) / 2.0, 0.1, -0.2, 0.3],
        features: proto::Features::NONE,
        can_kick: kick,
        positions: vec![[0.0, 0.0], [1.0, 0.0]],
        reward,
        outcome: terminal.then_some(ended(reward)),
    }
}

/// How an episode that ended with `reward` ended.
fn ended(reward: f64) -> EpisodeOutcome {
    match reward {
        r if r > 0.0 => EpisodeOutcome::Goal,
        r if r < 0.0 => EpisodeOutcome::Captured,
        _ => EpisodeOutcome::OutOfTime,
    }
}

/// The next action published, with its header (other messages skipped).
async fn next_action(
    actions: &Actions,
    fake: &Fake,
    deadline: tokio::time::Instant,
) -> (Header, ActionChoice) {
    loop {
        let sample = tokio::time::timeout_at(deadline, actions.recv_async())
            .await
            .expect("actions did not arrive")
            .unwrap();
        let envelope = proto::decode(&sample.payload().to_bytes(), fake.experiment).unwrap();
        if let Body::Action(choice) = envelope.body {
            return (envelope.header, choice);
        }
    }
}

/// Waits for the actions of both agents for `header`'s frame.
async fn both_actions(actions: &Actions, fake: &Fake, header: Header) {
    let mut seen = [false; 2];
    let deadline = tokio::time::Instant::now() + Duration::from_secs(10);
    while seen != [true; 2] {
        let (h, choice) = next_action(actions, fake, deadline).await;
        assert_eq!(h, header);
        assert!(choice.action.is_kick(), "{choice:?}");
        seen[usize::from(choice.agent)] = true;
    }
}

fn received(r: &AgentReport, kind: MessageKind) -> u64 {
    r.messages.received[kind as usize].messages
}

fn sent(r: &AgentReport, kind: MessageKind) -> u64 {
    r.messages.sent[kind as usize].messages
}

/// The actions the agents publish.
type Actions = Subscriber<FifoChannelHandler<Sample>>;

#[tokio::test(flavor = "multi_thread")]
async fn two_agent_processes_advise_each_other_and_drop_bad_messages() {
    let name = format!("advise-{}", std::process::id());
    let fake = Fake::open(&name).await;
    let mut agents = [spawn_agent(&name, 0, &fake), spawn_agent(&name, 1, &fake)];
    fake.wait_for_agents(&[0, 1]).await;
    let actions = fake
        .session
        .declare_subscriber(fake.keys.actions())
        .await
        .unwrap();
    let config = AgentConfig::of("adhoc-td".parse().unwrap(), Profile::Paper);
    for id in 0..2 {
        fake.reset(id, &config).await;
    }
    let reports = advise_each_other(&fake, &actions).await;
    bad_messages_change_nothing(&fake, &reports[0]).await;
    evaluation_is_frozen(&fake, &actions, &reports).await;
    frames_arriving_while_asking_keep_their_order(&fake, &actions).await;
    for (id, agent) in agents.iter_mut().enumerate() {
        fake.stop(id as u8).await;
        let status = agent.wait_exit(Duration::from_secs(5));
        assert_eq!(status.map(|s| s.code()), Some(Some(0)), "agent {id}");
    }
}

/// Episode 0 without the ball (so that both may ask), then episode 1 where
/// both kick at once in fresh states (P_ask = 1): each asks the other while
/// answering the other's request. The agents' reports after it.
async fn advise_each_other(fake: &Fake, actions: &Actions) -> Vec<AgentReport> {
    fake.frame(fake.header(0, 0, 0), Mode::Training, false, false, 0.0)
        .await;
    fake.frame(fake.header(0, 0, 1), Mode::Training, false, true, 0.0)
        .await;
    for id in 0..2 {
        let r = fake
            .report_until(id, 0, |r| r.alive_peers == vec![1 - id])
            .await;
        assert_eq!(r.advice_requests, 0);
    }
    for frame in 0..3 {
        let header = fake.header(0, 1, frame);
        fake.frame(header, Mode::Training, true, false, 0.0).await;
        both_actions(actions, fake, header).await;
    }
    fake.frame(fake.header(0, 1, 3), Mode::Training, false, true, 1.0)
        .await;
    let mut reports = Vec::new();
    for id in 0..2 {
        let r = fake.report(id, 1).await;
        assert!(r.advice_requests > 0, "{r:?}");
        assert!(r.advice_replies_received > 0, "{r:?}");
        assert_eq!(r.advice_rtt_ms.len() as u64, r.advice_replies_received);
        assert!(sent(&r, MessageKind::AdviceRequest) > 0, "{r:?}");
        assert!(
            received(&r, MessageKind::AdviceRequest) > 0,
            "served: {r:?}"
        );
        assert!(sent(&r, MessageKind::AdviceReply) > 0, "{r:?}");
        assert_eq!(sent(&r, MessageKind::Action), 3);
        assert_eq!(received(&r, MessageKind::Observation), 6);
        assert_eq!(r.messages.dropped.total(), 0);
        eprintln!(
            "agent {id}: {} requests, {} replies, advice RTT ms {:?}",
            r.advice_requests, r.advice_replies_received, r.advice_rtt_ms
        );
        reports.push(r);
    }
    reports
}

/// Bad messages on agent 0's observations are counted and change nothing
/// of what it learned (`before`).
async fn bad_messages_change_nothing(fake: &Fake, before: &AgentReport) {
    let frame = AgentFrame {
        agent: 0,
        mode: Mode::Training,
        state: [0.9; 6],
        features: proto::Features::NONE,
        can_kick: true,
        positions: vec![],
        reward: 1.0,
        outcome: None,
    };
    let good = |header: Header| observations(header, vec![frame.clone()]);
    fake.publish(0, observations(fake.header(0, 2, 0), vec![]))
        .await;
    let too_many = vec![frame.clone(); proto::MAX_FRAMES_PER_MESSAGE + 1];
    fake.publish(0, observations(fake.header(0, 2, 0), too_many))
        .await;
    let past_the_last_frame = vec![frame.clone(); 2];
    let last = fake.header(0, 2, u32::MAX);
    fake.publish(0, observations(last, past_the_last_frame))
        .await;
    fake.publish(0, vec![0xff, 0x00, 0x13, 0x37]).await;
    fake.publish(0, good(Header::new(proto::experiment_id("other"), 0, 2, 0)))
        .await;
    let old = Header {
        version: PROTOCOL_VERSION + 1,
        ..fake.header(0, 2, 0)
    };
    fake.publish(0, good(old)).await;
    fake.publish(0, good(fake.header(0, 1, 2))).await; // an ended episode
    fake.publish(0, good(fake.header(5, 2, 0))).await; // another run
    // HFO's features of another team size (21 for two agents), or not finite.
    for features in [vec![0.5; 27], [vec![0.5; 20], vec![f32::NAN]].concat()] {
        let features = proto::Features::new(&features).unwrap();
        let odd = AgentFrame {
            features,
            ..frame.clone()
        };
        fake.publish(0, observations(fake.header(0, 2, 0), vec![odd]))
            .await;
    }
    let r = fake
        .report_until(0, 1, |r| r.messages.dropped.total() == 10)
        .await;
    let d = r.messages.dropped;
    assert_eq!((d.malformed, d.foreign, d.version, d.stale), (6, 1, 1, 2));
    assert_eq!(r.digest, before.digest);
    assert_eq!(received(&r, MessageKind::Observation), 6);
    // A command in another protocol version is refused, naming both.
    let other = Header {
        version: PROTOCOL_VERSION + 1,
        ..fake.header(0, 2, 0)
    };
    let ControlReply::Error(e) = fake.control(0, other, Control::Report).await else {
        panic!("a command of another version is answered with an error");
    };
    let versions = format!(
        "version {PROTOCOL_VERSION}, the command came in version {}",
        PROTOCOL_VERSION + 1
    );
    assert!(e.contains(&versions), "{e}");
}

/// An evaluation episode: frozen, nobody asks, nothing learned.
async fn evaluation_is_frozen(fake: &Fake, actions: &Actions, before: &[AgentReport]) {
    fake.frame(fake.header(0, 2, 0), Mode::Evaluation, true, false, 0.0)
        .await;
    both_actions(actions, fake, fake.header(0, 2, 0)).await;
    fake.frame(fake.header(0, 2, 1), Mode::Evaluation, false, true, 0.0)
        .await;
    for id in 0..2u8 {
        let r = fake.report(id, 2).await;
        let before = &before[usize::from(id)];
        assert_eq!(r.digest, before.digest);
        assert_eq!(r.advice_requests, before.advice_requests);
    }
}

/// Episode 3: kicks in fresh states published back to back, without
/// waiting for the actions, so that frames arrive while an agent waits
/// for advice: each frame's action comes once, in frame order, and
/// nothing is dropped.
async fn frames_arriving_while_asking_keep_their_order(fake: &Fake, actions: &Actions) {
    let before: Vec<AgentReport> = [fake.report(0, 2).await, fake.report(1, 2).await].into();
    for frame in 0..4u32 {
        let last = frame == 3;
        let header = fake.header(0, 3, frame);
        for id in 0..2u8 {
            let mut obs = observation(id, frame, Mode::Training, !last, last, 0.0);
            obs.state[3] = 0.9;
            fake.publish(id, observations(header, vec![obs])).await;
        }
    }
    let mut next = [0u32; 2];
    let deadline = tokio::time::Instant::now() + Duration::from_secs(10);
    while next != [3; 2] {
        let (h, choice) = next_action(actions, fake, deadline).await;
        let id = usize::from(choice.agent);
        assert_eq!(h, fake.header(0, 3, next[id]), "agent {id}");
        next[id] += 1;
    }
    for id in 0..2u8 {
        let (r, was) = (fake.report(id, 3).await, &before[usize::from(id)]);
        assert!(r.advice_requests > was.advice_requests, "{r:?}");
        assert_eq!(
            received(&r, MessageKind::Observation),
            received(was, MessageKind::Observation) + 4
        );
        assert_eq!(r.messages.dropped.total(), was.messages.dropped.total());
    }
}

#[tokio::test(flavor = "multi_thread")]
async fn episode_sharing_travels_as_published_messages() {
    let name = format!("share-{}", std::process::id());
    let fake = Fake::open(&name).await;
    let _agents = [spawn_agent(&name, 0, &fake), spawn_agent(&name, 1, &fake)];
    fake.wait_for_agents(&[0, 1]).await;
    let config = AgentConfig::of("episode-sharing".parse().unwrap(), Profile::Paper);
    for id in 0..2 {
        fake.reset(id, &config).await;
    }
    // Episode 0 ends without a goal (nothing shared), its frames sent one
    // by one; episode 1 with one, its frames in one message.
    for frame in 0..3 {
        let header = fake.header(0, 0, frame);
        fake.frame(header, Mode::Training, false, false, 0.0).await;
    }
    fake.frame(fake.header(0, 0, 3), Mode::Training, false, true, 0.0)
        .await;
    for id in 0..2 {
        fake.report_until(id, 0, |r| r.alive_peers == vec![1 - id])
            .await;
    }
    fake.episode_tail(fake.header(0, 1, 0), 4, 1.0).await;

    // The same episodes in process: after the goal each agent sends its 3
    // transitions to the other, who replays them.
    let mut local: Vec<Agent> = (0..2u8)
        .map(|id| Agent::new(id.into(), 2, config.clone(), 7 + u64::from(id)).unwrap())
        .collect();
    for (id, a) in local.iter_mut().enumerate() {
        for reward in [0.0, 1.0] {
            a.begin_episode(agent::Mode::Training);
            for frame in 0..3 {
                let o = observation(id as u8, frame, Mode::Training, false, false, 0.0);
                let me = agent::Observation {
                    state: o.state,
                    features: o.features,
                    can_kick: false,
                    position: o.positions[id],
                };
                a.act(&me, 0.0, &o.positions, &mut Isolated);
            }
            a.end_episode(ended(reward));
        }
    }
    let shares: Vec<_> = local.iter_mut().map(Agent::take_shared).collect();
    for (from, to_share) in shares.into_iter().enumerate() {
        assert_eq!(to_share.len(), 1);
        let (to, share) = &to_share[0];
        assert_eq!((*to, share.transitions().len()), (1 - from, 3));
        local[*to].receive_shared(share.transitions());
    }

    for id in 0..2u8 {
        let expected = local[usize::from(id)].digest();
        let r = fake.report_until(id, 1, |r| r.digest == expected).await;
        assert_eq!(sent(&r, MessageKind::SharedEpisode), 1);
        assert_eq!(received(&r, MessageKind::SharedEpisode), 1);
        assert_eq!(received(&r, MessageKind::Observation), 4 + 1);
        assert_eq!(r.give_spent, 3);
    }

    // Learned state travels as snapshot bytes, in parts: agent 1 takes
    // agent 0's; a part out of order or a broken snapshot is refused.
    let header = fake.header(0, 1, 0);
    let ControlReply::Snapshot { parts, bytes } =
        fake.control(0, header, Control::Snapshot { part: 0 }).await
    else {
        panic!("agent 0 sent no snapshot");
    };
    assert_eq!(parts, 1, "a small snapshot is one part");
    let reply = fake.control(0, header, Control::Snapshot { part: 1 }).await;
    assert!(
        matches!(&reply, ControlReply::Error(e) if e.contains("asked before part 0")),
        "{reply:?}"
    );
    let load = |part, parts, bytes: &[u8]| Control::Load {
        part,
        parts,
        bytes: bytes.to_vec(),
    };
    let reply = fake.control(1, header, load(1, 2, &bytes)).await;
    assert!(
        matches!(&reply, ControlReply::Error(e) if e.contains("expected part 0")),
        "{reply:?}"
    );
    let truncated = load(0, 1, &bytes[..bytes.len() - 1]);
    let reply = fake.control(1, header, truncated).await;
    assert!(
        matches!(&reply, ControlReply::Error(e) if e.contains("snapshot")),
        "{reply:?}"
    );
    let (first, second) = bytes.split_at(bytes.len() / 2);
    assert_eq!(
        fake.control(1, header, load(0, 2, first)).await,
        ControlReply::Ok
    );
    assert_eq!(
        fake.control(1, header, load(1, 2, second)).await,
        ControlReply::Ok
    );
    let digest = fake.report(0, 1).await.digest;
    assert_eq!(fake.report(1, 1).await.digest, digest);
}
#[tokio::test(flavor = "multi_thread")]
async fn a_second_agent_with_the_same_id_exits_2_and_a_lost_coordinator_stops_agents() {
    let name = format!("twice-{}", std::process::id());
    let fake = Fake::open(&name).await;
    let _token = fake
        .session
        .liveliness()
        .declare_token(fake.keys.alive(Role::Coordinator))
        .await
        .unwrap();
    let mut first = spawn_agent(&name, 0, &fake);
    fake.wait_for_agents(&[0]).await;
    let mut second = spawn_agent(&name, 0, &fake);
    let status = second.wait_exit(Duration::from_secs(20));
    assert_eq!(status.map(|s| s.code()), Some(Some(2)));
    let stderr = second.stderr();
    assert_eq!(
        stderr.trim_end(),
        format!("error: agent id 0 is already running in experiment {name}")
    );
    assert!(
        first.wait_exit(Duration::ZERO).is_none(),
        "the first one runs on"
    );

    // Without its coordinator the agent stops by itself.
    fake.session.close().await.unwrap();
    let status = first.wait_exit(Duration::from_secs(10));
    assert_eq!(status.map(|s| s.code()), Some(Some(1)));
    assert!(first.stderr().contains("coordinator"));
}

/// A strategy process in POSIX sh (the line protocol is the language's
/// choice): it asks agent `$1` at every step with the ball, answers every
/// request with SHOOT, reports how advice turned out and hears the reports,
/// and sends `$1` a batch of one transition at every episode's end.
const BATCHER: &str = r#"other=$1
batch='{"batches":[{"to":'$other',"transitions":[{"state":[0.1,0.2,0.3,0.4,0.5,0.6],"action":1,"reward":1.0,"next_state":null,"next_action":null}]}]}'
while IFS= read -r line; do
  case "$line" in
    *'"op":"start"'*) printf '%s\n' '{"name":"batcher","learns":true,"reuses":false,"asks_by_uncertainty":false,"mistake_correcting":false,"intends_greedy":false,"shares_values":false,"learns_from_outcomes":false,"ends_episodes":true,"reports_advice_outcomes":true,"hears_advice_outcomes":true}' ;;
    *'"op":"asks"'*|*'"op":"gives"'*) printf '%s\n' '{"decision":true}' ;;
    *'"op":"advisors"'*) printf '%s\n' "{\"advisors\":[$other]}" ;;
    *'"op":"advice"'*) printf '%s\n' '{"action":1}' ;;
    *'"op":"follow"'*) printf '%s\n' '{"advice":null}' ;;
    *'"op":"end_episode"'*) printf '%s\n' "$batch" ;;
    *'"op":"spent_budget"'*) printf '%s\n' '{"spent":0}' ;;
  esac
done
"#;

#[tokio::test(flavor = "multi_thread")]
async fn batches_and_advice_outcomes_travel_between_agent_processes_and_are_counted() {
    let name = format!("batch-{}", std::process::id());
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("batcher.sh");
    std::fs::write(&script, BATCHER).unwrap();
    let fake = Fake::open(&name).await;
    let command = |other: u8| format!("sh {} {other}", script.display());
    let (zero, one) = (command(1), command(0));
    let _agents = [
        spawn_agent_with(&name, 0, &fake, &["--strategy", &zero]),
        spawn_agent_with(&name, 1, &fake, &["--strategy", &one]),
    ];
    fake.wait_for_agents(&[0, 1]).await;
    let actions = fake
        .session
        .declare_subscriber(fake.keys.actions())
        .await
        .unwrap();
    let config = AgentConfig {
        learner: agent::LearnerSettings::Dqn(agent::DqnSettings::default()),
        ..AgentConfig::of("external".parse().unwrap(), Profile::Paper)
    };
    for id in 0..2 {
        fake.reset(id, &config).await;
    }
    // Episode 0 without the ball, until both see each other; episode 1
    // where both kick twice, asking each other, then score.
    fake.frame(fake.header(0, 0, 0), Mode::Training, false, false, 0.0)
        .await;
    fake.frame(fake.header(0, 0, 1), Mode::Training, false, true, 0.0)
        .await;
    for id in 0..2 {
        fake.report_until(id, 0, |r| r.alive_peers == vec![1 - id])
            .await;
    }
    for frame in 0..2 {
        let header = fake.header(0, 1, frame);
        fake.frame(header, Mode::Training, true, false, 0.0).await;
        both_actions(&actions, &fake, header).await;
    }
    fake.frame(fake.header(0, 1, 2), Mode::Training, false, true, 1.0)
        .await;
    // A batch per episode each way; a report per advice that arrived.
    let mut reports = Vec::new();
    for id in 0..2u8 {
        let r = fake
            .report_until(id, 1, |r| {
                received(r, MessageKind::ExperienceBatch) == 2
                    && sent(r, MessageKind::AdviceOutcome) == r.advice_replies_received
            })
            .await;
        assert_eq!(sent(&r, MessageKind::ExperienceBatch), 2, "{r:?}");
        assert!(r.advice_replies_received > 0, "{r:?}");
        reports.push(r);
    }
    for id in 0..2 {
        let heard = sent(&reports[1 - id], MessageKind::AdviceOutcome);
        let r = fake
            .report_until(id as u8, 1, |r| {
                received(r, MessageKind::AdviceOutcome) == heard
            })
            .await;
        assert_eq!(r.messages.dropped.total(), 0, "{r:?}");
    }
    // An oversized batch, a batch of misplaced notes and a report of an
    // advantage that is no number are dropped as malformed.
    let publish = |body| {
        let bytes = proto::encode(&Envelope {
            header: fake.header(0, 1, 0),
            body,
        });
        fake.session.put(fake.keys.share(1), bytes)
    };
    let t = proto::SharedTransition {
        state: [0.5; 6],
        action: proto::Action::Shoot,
        reward: 1.0,
        next: None,
    };
    let long = proto::ExperienceBatch {
        from: 0,
        to: 1,
        transitions: vec![t; proto::MAX_BATCH + 1],
        notes: Vec::new(),
        standing: None,
    };
    publish(Body::ExperienceBatch(long)).await.unwrap();
    // Notes that are not one per transition.
    let note = proto::TransitionNote {
        frames: 1,
        uncertainty: 0.5,
    };
    let misnoted = proto::ExperienceBatch {
        from: 0,
        to: 1,
        transitions: vec![t; 3],
        notes: vec![note; 2],
        standing: None,
    };
    publish(Body::ExperienceBatch(misnoted)).await.unwrap();
    let nan = proto::AdviceOutcome {
        from: 0,
        to: 1,
        followed: true,
        advantage: f64::NAN,
    };
    publish(Body::AdviceOutcome(nan)).await.unwrap();
    let r = fake
        .report_until(1, 1, |r| r.messages.dropped.malformed == 3)
        .await;
    assert_eq!(received(&r, MessageKind::ExperienceBatch), 2);
}
