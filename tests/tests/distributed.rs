//! env-server, three agent processes and the coordinator over loopback zenoh.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use agent::{Algorithm, Mode, Profile};
use coordinator::transport::Auth;
use coordinator::{
    AgentSpec, Backend, Endpoints, Experiment, ExperimentConfig, RemoteBackend, ZenohSettings,
    ZenohTeam,
};
use integration_tests::{bin, bin_dir, cmdline, experiment_name, is_running};
use node::net::{NetConfig, free_port};
use node::secret::Secret;
use proto::keys::{Keys, Role};
use proto::{Body, Control, ControlReply, Envelope, Header, experiment_id};
use serde_json::Value;

fn adhoc_td_experiment() -> Experiment {
    let spec = AgentSpec::of("adhoc-td".parse::<Algorithm>().unwrap(), Profile::Paper);
    Experiment::prepare(ExperimentConfig {
        runs: 1,
        episodes: 20,
        eval_every: 20,
        eval_episodes: 5,
        team: vec![spec; 3],
        ..ExperimentConfig::default()
    })
    .expect("valid experiment")
}

fn network(tag: &str, port: u16, auth: Auth) -> ZenohTeam {
    ZenohTeam::start(
        &ZenohSettings {
            advice_timeout_ms: 20,
            step_timeout_ms: 2000,
            stall_limit_ms: 10_000,
            endpoints: Endpoints {
                experiment: experiment_name(tag),
                port,
                bin_dir: Some(bin_dir()),
                auth,
                startup_timeout: Duration::from_secs(60),
                ..Endpoints::default()
            },
            ..ZenohSettings::default()
        },
        &[
            AgentSpec::default(),
            AgentSpec::default(),
            AgentSpec::default(),
        ],
    )
    .expect("processes start and join")
}

fn digests(backend: &RemoteBackend) -> Vec<u64> {
    backend
        .reports()
        .expect("reports")
        .iter()
        .map(|r| r.digest)
        .collect()
}

#[test]
fn adhoc_td_run_advises_across_processes() {
    let summary = zenoh_run_summary("--advice-timeout-ms 20");
    let comm = &summary["comm"];
    for key in [
        "advice_requests",
        "advice_replies_received",
        "messages_sent",
        "bytes_sent",
    ] {
        assert!(comm[key].as_f64().unwrap() > 0.0, "{key}: {comm}");
    }
    assert!(comm["advice_rtt_ms"]["median"].as_f64().unwrap() > 0.0);
    assert_eq!(comm["per_agent"].as_array().unwrap().len(), 3);
    assert_eq!(summary["eval_points"].as_array().unwrap().len(), 3);
}

/// The summary of a 60-episode AdHocTD run over zenoh, with `extra` options.
fn zenoh_run_summary(extra: &str) -> Value {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("run");
    let output = Command::new(bin("coordinator"))
        .args("run --algorithm adhoc-td --runs 1 --episodes 60 --eval-every 30".split(' '))
        .args("--eval-episodes 10 --seed 3 --transport zenoh".split(' '))
        .args(extra.split(' '))
        .args(["--quiet", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// The `comm` of that run with network `conditions`.
fn comm_under(conditions: &str) -> Value {
    zenoh_run_summary(conditions)["comm"].clone()
}

#[test]
fn network_conditions_are_injected_at_the_sender() {
    let number = |comm: &Value, key: &str| comm[key].as_f64().unwrap();
    // Every request lost: asked, never answered.
    let lost = comm_under("--advice-loss 1 --advice-timeout-ms 20");
    assert!(number(&lost, "advice_requests") > 0.0, "{lost}");
    assert_eq!(number(&lost, "advice_replies_received"), 0.0, "{lost}");
    assert_eq!(number(&lost, "advice_given"), 0.0, "{lost}");
    // 4 ms each way within a 20 ms timeout: answered, round trips over 8 ms.
    let late = comm_under("--advice-latency fixed:4 --advice-timeout-ms 20");
    assert!(number(&late, "advice_replies_received") > 0.0, "{late}");
    assert!(
        late["advice_rtt_ms"]["median"].as_f64().unwrap() >= 8.0,
        "{late}"
    );
}

#[test]
fn evaluation_changes_no_learned_state() {
    let experiment = adhoc_td_experiment();
    let net = network("frozen", 0, Auth::Generated);
    let mut backend = RemoteBackend::new(&net, &experiment, 0).unwrap();
    for _ in 0..10 {
        backend.play_episode(Mode::Training).unwrap();
    }
    let before = digests(&backend);
    backend.begin_evaluation(7).unwrap();
    for _ in 0..10 {
        backend.play_episode(Mode::Evaluation).unwrap();
    }
    assert_eq!(digests(&backend), before, "evaluation changed a Q-table");
    for _ in 0..3 {
        backend.play_episode(Mode::Training).unwrap();
    }
    assert_ne!(digests(&backend), before, "training changes the Q-tables");
}

#[test]
fn malformed_and_foreign_messages_change_nothing() {
    let experiment = adhoc_td_experiment();
    // A teammate with the secret, sending garbage.
    let port = free_port().unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let secret = Secret::create(&tmp.path().join("secret")).unwrap();
    let net = network("garbage", port, Auth::File(secret.path().to_owned()));
    let mut backend = RemoteBackend::new(&net, &experiment, 0).unwrap();
    for _ in 0..3 {
        backend.play_episode(Mode::Training).unwrap();
    }
    let before = backend.reports().unwrap();
    let name = experiment_name("garbage");
    let keys = Keys::new(&name).unwrap();
    let foreign = proto::encode(&Envelope {
        header: Header::new(experiment_id("someone-else"), 0, 3, 0),
        body: Body::Control(Control::Stop),
    });
    let mut old = proto::encode(&Envelope {
        header: Header::new(experiment_id(&name), 0, 3, 0),
        body: Body::Control(Control::Stop),
    });
    old[0] = old[0].wrapping_add(1); // another protocol version
    let garbage = b"\x07not a message".to_vec();
    let runtime = tokio::runtime::Runtime::new().unwrap();
    runtime.block_on(async {
        let net = NetConfig::loopback_peer(0, vec![format!("tcp/127.0.0.1:{port}")])
            .with_secret(Some(secret));
        let session = node::net::open(&net).await.unwrap();
        tokio::time::sleep(Duration::from_millis(500)).await;
        for key in [keys.observation(0), keys.action(1), keys.share(2)] {
            for payload in [&garbage, &foreign, &old] {
                session.put(&key, payload.clone()).await.unwrap();
            }
        }
        for key in [keys.advice(1), keys.control(Role::Agent(2))] {
            for payload in [&garbage, &foreign, &old] {
                let replies = session
                    .get(&key)
                    .payload(payload.clone())
                    .timeout(Duration::from_millis(300))
                    .await
                    .unwrap();
                while replies.recv_async().await.is_ok() {}
            }
        }
        tokio::time::sleep(Duration::from_millis(300)).await;
        session.close().await.unwrap();
    });
    let after = backend.reports().unwrap();
    for (b, a) in before.iter().zip(&after) {
        assert_eq!(a.digest, b.digest, "agent {} changed", a.agent);
    }
    let dropped = |reports: &[proto::AgentReport]| -> u64 {
        reports.iter().map(|r| r.messages.dropped.total()).sum()
    };
    assert!(
        dropped(&after) >= dropped(&before) + 9,
        "dropped before {} after {}",
        dropped(&before),
        dropped(&after)
    );
    // The run goes on normally.
    backend.play_episode(Mode::Training).unwrap();
    let server = net
        .control(
            Role::Server,
            Header::new(experiment_id(&name), 0, 4, 0),
            Control::Report,
            Duration::from_secs(5),
        )
        .unwrap();
    let ControlReply::Server(report) = server else {
        panic!("server report expected, got {server:?}");
    };
    assert!(report.messages.dropped.total() >= 3, "{report:?}");
}

#[test]
fn killing_an_agent_ends_the_run_with_a_clear_message() {
    let tmp = tempfile::tempdir().unwrap();
    let mut coordinator = long_run("adhoc-td", &tmp.path().join("killed"))
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let children = wait_for_children(coordinator.id(), 4);
    std::thread::sleep(Duration::from_secs(2));
    let victim = children
        .iter()
        .copied()
        .find(|pid| cmdline(*pid).contains("--id\u{0}1\u{0}"))
        .expect("agent 1 among the children");
    assert!(
        Command::new("kill")
            .args(["-9", &victim.to_string()])
            .status()
            .unwrap()
            .success()
    );
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(status) = coordinator.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            let _ = coordinator.kill();
            panic!("the coordinator hung after an agent was killed");
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    let stderr = std::io::read_to_string(coordinator.stderr.take().unwrap()).unwrap();
    assert!(!status.success());
    assert!(stderr.contains("agent/1 is gone"), "stderr: {stderr}");
    std::thread::sleep(Duration::from_millis(200));
    for pid in children.into_iter().filter(|p| *p != victim) {
        assert!(
            !is_running(pid),
            "process {pid} left behind: {}",
            cmdline(pid)
        );
    }
}

#[test]
fn killing_the_coordinator_leaves_no_process_behind() {
    let tmp = tempfile::tempdir().unwrap();
    // SIGKILL leaves the generated secret's directory: keep it in ours.
    let mut coordinator = long_run("no-advice", &tmp.path().join("orphans"))
        .env("TMPDIR", tmp.path())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let children = wait_for_children(coordinator.id(), 4);
    std::thread::sleep(Duration::from_secs(1));
    coordinator.kill().unwrap();
    coordinator.wait().unwrap();
    let deadline = Instant::now() + Duration::from_secs(30);
    while children.iter().any(|pid| is_running(*pid)) {
        assert!(
            Instant::now() < deadline,
            "left behind: {:?}",
            children
                .iter()
                .filter(|p| is_running(**p))
                .map(|p| cmdline(*p))
                .collect::<Vec<_>>()
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn every_process_runs_zenoh_on_one_runtime() {
    let tmp = tempfile::tempdir().unwrap();
    let mut coordinator = long_run("no-advice", &tmp.path().join("threads"))
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let pids: Vec<u32> = (wait_for_children(coordinator.id(), 4).into_iter())
        .chain([coordinator.id()])
        .collect();
    // zenoh names its runtimes' threads after them: with every runtime
    // handed over to `app`, no other runtime has a thread. Read once every
    // process has joined (zenoh starts its threads then), or after 30 s.
    let thread_names = |pid: u32| -> Vec<String> {
        std::fs::read_dir(format!("/proc/{pid}/task"))
            .into_iter()
            .flatten()
            .filter_map(|t| std::fs::read_to_string(t.ok()?.path().join("comm")).ok())
            .collect()
    };
    let deadline = Instant::now() + Duration::from_secs(30);
    let threads: Vec<(String, Vec<String>)> = loop {
        let threads: Vec<_> = pids
            .iter()
            .map(|&p| (cmdline(p), thread_names(p)))
            .collect();
        let joined =
            |(_, names): &(String, Vec<String>)| names.iter().any(|n| n.starts_with("app-"));
        if threads.iter().all(joined) || Instant::now() > deadline {
            break threads;
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    // Killed before any assertion, so that a failure leaves no process behind.
    coordinator.kill().unwrap();
    coordinator.wait().unwrap();
    for (process, names) in threads {
        let zenoh = |prefix| names.iter().any(|n| n.starts_with(prefix));
        assert!(zenoh("app-"), "{process}: {names:?}");
        for other in ["rx-", "tx-", "net-", "acc-"] {
            assert!(!zenoh(other), "{process}: {names:?}");
        }
    }
}

/// A coordinator run over zenoh that lasts far longer than any test.
fn long_run(algorithm: &str, out: &std::path::Path) -> Command {
    let mut c = Command::new(bin("coordinator"));
    c.args([
        "run",
        "--algorithm",
        algorithm,
        "--runs",
        "1",
        "--episodes",
        "100000",
    ])
    .args(["--transport", "zenoh", "--quiet", "--out"])
    .arg(out)
    .stdout(Stdio::null());
    c
}

/// Child pids of `parent` once there are `n` of them (Linux /proc).
fn wait_for_children(parent: u32, n: usize) -> Vec<u32> {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let path = format!("/proc/{parent}/task/{parent}/children");
        let pids: Vec<u32> = std::fs::read_to_string(&path)
            .unwrap_or_default()
            .split_whitespace()
            .filter_map(|p| p.parse().ok())
            .collect();
        if pids.len() >= n {
            return pids;
        }
        assert!(
            Instant::now() < deadline,
            "only {} children appeared",
            pids.len()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}
