//! An experiment's processes refuse a zenoh peer without the experiment's
//! secret: it can neither join, nor see a liveliness token, nor read or
//! send a message, even knowing every endpoint.

use std::process::{Child, Command, Stdio};
use std::time::Duration;

use agent::{Algorithm, Mode, Profile};
use coordinator::transport::Auth;
use coordinator::{
    AgentSpec, Backend, Endpoints, Experiment, ExperimentConfig, RemoteBackend, ZenohSettings,
    ZenohTeam,
};
use integration_tests::{bin, bin_dir, experiment_name};
use node::net::{NetConfig, free_port};
use node::secret::Secret;
use zenoh::handlers::FifoChannelHandler;
use zenoh::pubsub::Subscriber;
use zenoh::query::Reply;
use zenoh::sample::Sample;

/// A process killed when dropped.
struct KillOnDrop(Child);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn spawn(program: &str, args: &[String]) -> KillOnDrop {
    KillOnDrop(
        Command::new(bin(program))
            .args(args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    )
}

#[test]
fn a_peer_without_the_secret_can_neither_join_nor_listen() {
    let tmp = tempfile::tempdir().unwrap();
    let secret = Secret::create(&tmp.path().join("secret")).unwrap();
    let name = experiment_name("intruder-auth");
    let endpoints: Vec<String> = (0..4)
        .map(|_| format!("tcp/127.0.0.1:{}", free_port().unwrap()))
        .collect();
    let processes = start_services(&name, &secret, &endpoints);
    let settings = attached_settings(&name, &secret, &endpoints);
    let team = vec![AgentSpec::of("adhoc-td".parse::<Algorithm>().unwrap(), Profile::Paper); 3];
    let net = ZenohTeam::start(&settings, &team).expect("the attached processes join");
    let experiment = Experiment::prepare(ExperimentConfig {
        runs: 1,
        episodes: 20,
        team,
        ..ExperimentConfig::default()
    })
    .unwrap();
    let mut backend = RemoteBackend::new(&net, &experiment, 0).unwrap();
    backend.play_episode(Mode::Training).unwrap();

    let runtime = tokio::runtime::Runtime::new().unwrap();
    let other = Secret::create(&tmp.path().join("other")).unwrap();
    runtime.block_on(no_session_opens_without_the_secret(&endpoints, other));
    // A lurker that keeps trying every endpoint while the run goes on
    // sees no token and no message, and what it sends arrives nowhere.
    let lurker = runtime.block_on(Lurker::start(&name, &endpoints));
    for _ in 0..5 {
        backend.play_episode(Mode::Training).unwrap();
    }
    runtime.block_on(lurker.saw_nothing());
    drop(backend);
    drop(net);
    drop(processes);
}

/// env-server and three agents as services on `endpoints`, with `secret`.
fn start_services(name: &str, secret: &Secret, endpoints: &[String]) -> Vec<KillOnDrop> {
    let common = |listen: &str| {
        let path = secret.path().display().to_string();
        [
            "--experiment",
            name,
            "--listen",
            listen,
            "--secret-file",
            &path,
        ]
        .map(str::to_owned)
    };
    let mut processes = vec![spawn(
        "env-server",
        &[&["serve".to_owned()][..], &common(&endpoints[0])].concat(),
    )];
    for (i, listen) in endpoints[1..].iter().enumerate() {
        let id = ["--id", &i.to_string(), "--team-size", "3"].map(str::to_owned);
        processes.push(spawn("agent", &[&id[..], &common(listen)].concat()));
    }
    processes
}

/// A coordinator's settings to attach to the services on `endpoints`.
fn attached_settings(name: &str, secret: &Secret, endpoints: &[String]) -> ZenohSettings {
    ZenohSettings {
        advice_timeout_ms: 20,
        step_timeout_ms: 2000,
        stall_limit_ms: 10_000,
        restart_agents: false,
        snapshot_every: 100,
        endpoints: Endpoints {
            experiment: name.to_owned(),
            connect: endpoints.to_vec(),
            attach: true,
            bin_dir: Some(bin_dir()),
            auth: Auth::File(secret.path().to_owned()),
            startup_timeout: Duration::from_secs(60),
            ..Endpoints::default()
        },
        ..ZenohSettings::default()
    }
}

/// Without credentials, or with `other` ones, no process opens a session
/// (all tried at once: each refusal takes the 5 s connect timeout).
async fn no_session_opens_without_the_secret(endpoints: &[String], other: Secret) {
    let tries: Vec<_> = endpoints
        .iter()
        .flat_map(|endpoint| [None, Some(other.clone())].map(|s| (endpoint.clone(), s)))
        .map(|(endpoint, secret)| {
            tokio::spawn(async move {
                let guest = NetConfig::loopback_peer(0, vec![endpoint.clone()]);
                let result = node::net::open(&guest.with_secret(secret)).await;
                (endpoint, result.map(|_| ()))
            })
        })
        .collect();
    for attempt in tries {
        let (endpoint, result) = attempt.await.unwrap();
        let e = result.expect_err(&endpoint).to_string();
        assert!(e.starts_with("cannot join the zenoh network"), "{e}");
    }
}

/// A peer without the secret that keeps connecting to every endpoint,
/// watching tokens and messages, with a control query sent.
struct Lurker {
    session: zenoh::Session,
    tokens: Subscriber<FifoChannelHandler<Sample>>,
    messages: Subscriber<FifoChannelHandler<Sample>>,
    replies: FifoChannelHandler<Reply>,
}

impl Lurker {
    async fn start(name: &str, endpoints: &[String]) -> Self {
        let config = serde_json::json!({
            "mode": "peer",
            "connect": { "endpoints": endpoints, "timeout_ms": 1000, "exit_on_failure": false },
            "scouting": { "multicast": { "enabled": false } },
        });
        let config = zenoh::Config::from_json5(&config.to_string()).unwrap();
        let session = zenoh::open(config).await.unwrap();
        let tokens = session
            .liveliness()
            .declare_subscriber("adv/**")
            .history(true)
            .await
            .unwrap();
        let messages = session.declare_subscriber("adv/**").await.unwrap();
        let stop = proto::encode(&proto::Envelope {
            header: proto::Header::new(proto::experiment_id(name), 0, 0, 0),
            body: proto::Body::Control(proto::Control::Stop),
        });
        let replies = session
            .get(format!("adv/{name}/**"))
            .payload(stop)
            .timeout(Duration::from_millis(500))
            .await
            .unwrap();
        Lurker {
            session,
            tokens,
            messages,
            replies,
        }
    }

    /// Asserts that no token, message or reply reached it.
    async fn saw_nothing(self) {
        tokio::time::sleep(Duration::from_secs(1)).await;
        assert!(self.tokens.try_recv().unwrap().is_none(), "a token leaked");
        assert!(
            self.messages.try_recv().unwrap().is_none(),
            "a message leaked"
        );
        assert!(
            !matches!(self.replies.try_recv(), Ok(Some(_))),
            "a query was answered"
        );
        self.session.close().await.unwrap();
    }
}
