//! Open teams: a newcomer takes a slot during training while the others
//! keep learning, in process (bit for bit reproducible) and over zenoh (the
//! leaver's process stops, the newcomer is a new process joining the
//! running experiment).

use std::path::Path;
use std::process::Command;

use integration_tests::{bin, team_run};
use serde_json::Value;

/// Three AdHocTD agents; after training episode 60 a fresh learner takes
/// slot 2, after 90 a peer-learning agent takes slot 0.
const TEAM: &str = r#"
[[agent]]
algorithm = "adhoc-td"
[[agent]]
algorithm = "adhoc-td"
[[agent]]
algorithm = "adhoc-td"

[[event]]
episode = 60
slot = 2

[[event]]
episode = 90
slot = 0
newcomer = { algorithm = "peer-learning" }
"#;

/// One run of `team` over `transport` into `out`: its run JSON.
fn run(team: &Path, transport: &str, out: &Path) -> Value {
    let schedule = [
        "--episodes",
        "120",
        "--eval-every",
        "30",
        "--eval-episodes",
        "5",
    ];
    team_run(team, transport, &schedule, out)
}

/// Agent `i`'s advice requests at every evaluation point.
fn requests(run: &Value, i: usize) -> Vec<u64> {
    (run["points"].as_array().unwrap().iter())
        .map(|p| p["agents"][i]["advice_requests"].as_u64().unwrap())
        .collect()
}

#[test]
fn newcomers_join_while_the_others_keep_learning_in_both_transports() {
    let tmp = tempfile::tempdir().unwrap();
    let team = tmp.path().join("team.toml");
    std::fs::write(&team, TEAM).unwrap();

    let first = run(&team, "in-process", &tmp.path().join("a"));
    assert_eq!(first, run(&team, "in-process", &tmp.path().join("b")));
    for (transport, run) in [
        ("in-process", first),
        ("zenoh", run(&team, "zenoh", &tmp.path().join("z"))),
    ] {
        let joins = run["joins"].as_array().unwrap();
        assert_eq!(joins.len(), 2, "{transport}: {joins:?}");
        assert_eq!(
            (joins[0]["episode"].as_u64(), joins[0]["slot"].as_u64()),
            (Some(60), Some(2))
        );
        assert_eq!(
            (joins[1]["episode"].as_u64(), joins[1]["slot"].as_u64()),
            (Some(90), Some(0))
        );
        // Points at 0, 30, 60, 90, 120: agent 1 never left, its counters
        // only grow; the newcomers' start from zero at their join.
        let kept = requests(&run, 1);
        assert!(
            kept.windows(2).all(|w| w[0] <= w[1]) && kept[4] > kept[2],
            "{transport}: {kept:?}"
        );
        let slot2 = requests(&run, 2);
        assert!(slot2[2] < slot2[1], "{transport}: slot 2 {slot2:?}");
        let slot0 = requests(&run, 0);
        assert!(slot0[3] < slot0[2], "{transport}: slot 0 {slot0:?}");
        if transport == "zenoh" {
            assert!(joins.iter().all(|j| j["wait_ms"].as_u64().unwrap() > 0));
        }
    }
}

/// The pid of agent `id`'s process of experiment `experiment`, if running.
fn agent_pid(experiment: &str, id: u8) -> Option<u32> {
    agent_pid_but(experiment, id, &[])
}

/// The pid of a process of agent `id` of experiment `experiment` other than
/// those of `known`, if one runs.
fn agent_pid_but(experiment: &str, id: u8, known: &[u32]) -> Option<u32> {
    let wanted = |cmdline: &str| {
        let args: Vec<&str> = cmdline.split('\0').collect();
        let after = |flag: &str| {
            args.windows(2)
                .any(|w| w[0] == flag && w[1] == id.to_string())
        };
        args.first().is_some_and(|p| p.ends_with("/agent"))
            && after("--id")
            && args
                .windows(2)
                .any(|w| w[0] == "--experiment" && w[1] == experiment)
    };
    std::fs::read_dir("/proc")
        .ok()?
        .flatten()
        .find_map(|entry| {
            let pid: u32 = entry.file_name().to_str()?.parse().ok()?;
            if known.contains(&pid) {
                return None;
            }
            let cmdline = std::fs::read_to_string(entry.path().join("cmdline")).ok()?;
            wanted(&cmdline).then_some(pid)
        })
}

#[test]
fn an_agent_that_dies_is_restarted_from_its_latest_snapshot_and_the_run_completes() {
    let tmp = tempfile::tempdir().unwrap();
    let run = killed_and_restarted(&["--algorithm", "adhoc-td"], "restart", tmp.path());
    assert_eq!(run["points"].as_array().unwrap().len(), 4);
}

/// Three AdHocTD agents learning with small DQNs; with `newcomer`, after
/// training episode 30 slot 2 is taken by a newcomer that loads the DQN
/// snapshot at that path.
fn dqn_team(newcomer: Option<&Path>) -> String {
    let dqn = "algorithm = \"adhoc-td\"\nlearner = \"dqn\"\nhidden = [16, 8]\nbatch = 8\n\
               replay = 500\nwarmup = 8\ntarget_every = 5\nepsilon_decay = 100\n";
    let mut team = format!("[[agent]]\n{dqn}\n").repeat(3);
    if let Some(load) = newcomer {
        let settings = dqn.trim_end().replace('\n', ", ");
        team += &format!(
            "[[event]]\nepisode = 30\nslot = 2\nnewcomer = {{ {settings}, load = {load:?} }}\n"
        );
    }
    team
}

#[test]
fn a_dqn_team_over_zenoh_takes_a_saved_dqn_as_newcomer_and_restarts_a_killed_one() {
    let tmp = tempfile::tempdir().unwrap();
    // A DQN trained in process, saved.
    let saved = tmp.path().join("saved");
    let team = tmp.path().join("team.toml");
    std::fs::write(&team, dqn_team(None)).unwrap();
    let schedule = [
        "--episodes",
        "20",
        "--eval-every",
        "20",
        "--eval-episodes",
        "2",
    ];
    let output = Command::new(bin("coordinator"))
        .args(["run", "--team"])
        .arg(&team)
        .args(["--runs", "1", "--transport", "in-process", "--quiet"])
        .args(schedule)
        .arg("--out")
        .arg(tmp.path().join("trained"))
        .arg("--save-agents")
        .arg(&saved)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let snapshot = saved.join("run-0-agent-0.snapshot");
    std::fs::write(&team, dqn_team(Some(&snapshot))).unwrap();

    let team = team.to_str().unwrap();
    let run = killed_and_restarted(&["--team", team], "restart-dqn", tmp.path());
    let joins = run["joins"].as_array().unwrap();
    assert_eq!(joins.len(), 1, "{joins:?}");
    assert_eq!(
        (joins[0]["episode"].as_u64(), joins[0]["slot"].as_u64()),
        (Some(30), Some(2))
    );
    let config = std::fs::read_to_string(tmp.path().join("out/config.json")).unwrap();
    let config: Value = serde_json::from_str(&config).unwrap();
    let team = config["config"]["team"].as_array().unwrap();
    assert!(team.iter().all(|a| a["learner"] == "dqn"), "{team:?}");
}

/// Plays one run of 300 training episodes over zenoh with
/// `--restart-agents` and `args` (the team), kills agent 1 once training is
/// under way, and checks that it was restarted once from a snapshot of
/// its own: the run JSON.
fn killed_and_restarted(args: &[&str], tag: &str, dir: &Path) -> Value {
    let out = dir.join("out");
    let experiment = format!("{tag}-{}", std::process::id());
    let coordinator = Command::new(bin("coordinator"))
        .arg("run")
        .args(args)
        .args(["--runs", "1", "--episodes", "300"])
        .args(["--eval-every", "100", "--eval-episodes", "10"])
        .args(["--transport", "zenoh", "--restart-agents"])
        .args(["--snapshot-every", "20", "--stall-limit-ms", "2000"])
        .args(["--experiment", &experiment, "--quiet", "--out"])
        .arg(&out)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Kill agent 1 once training is under way (after its first snapshot).
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    let pid = loop {
        assert!(
            std::time::Instant::now() < deadline,
            "agent 1 never started"
        );
        if let Some(pid) = agent_pid(&experiment, 1) {
            break pid;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    };
    std::thread::sleep(std::time::Duration::from_secs(6));
    let killed = Command::new("kill")
        .args(["-KILL", &pid.to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let output = coordinator.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let run: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run-0.json")).unwrap()).unwrap();
    let restarts = run["restarts"].as_array().unwrap();
    assert_eq!(restarts.len(), 1, "{restarts:?}");
    let restart = &restarts[0];
    assert_eq!(restart["slot"], 1);
    let (episode, snapshot) = (
        restart["episode"].as_u64().unwrap(),
        restart["snapshot"].as_u64(),
    );
    assert!(
        snapshot.is_some_and(|c| c <= episode && c % 20 == 0),
        "{restart}"
    );
    assert!(
        restart["cause"].as_str().unwrap().contains("agent/1"),
        "{restart}"
    );
    // The new process is gone with the run.
    assert_eq!(agent_pid(&experiment, 1), None);
    run
}

/// Three AdHocTD agents; after training episode 30 a fresh learner takes
/// slot 2.
const JOIN_AT_30: &str = r#"
[[agent]]
algorithm = "adhoc-td"
[[agent]]
algorithm = "adhoc-td"
[[agent]]
algorithm = "adhoc-td"

[[event]]
episode = 30
slot = 2
"#;

/// Waits for a process of agent `id` other than `known`: its pid. Panics,
/// with the coordinator's standard error (in `stderr`), if the coordinator
/// ends first.
fn seen(
    coordinator: &mut std::process::Child,
    stderr: &Path,
    (experiment, id): (&str, u8),
    known: &[u32],
) -> u32 {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    loop {
        if let Some(pid) = agent_pid_but(experiment, id, known) {
            return pid;
        }
        if let Some(status) = coordinator.try_wait().unwrap() {
            let stderr = std::fs::read_to_string(stderr).unwrap_or_default();
            panic!("the coordinator ended ({status}) before a new agent {id} was seen: {stderr}");
        }
        assert!(
            std::time::Instant::now() < deadline,
            "no new process of agent {id}"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

/// How long process `pid` has been running (Linux /proc, to the clock
/// tick, USER_HZ = 100).
fn age(pid: u32) -> std::time::Duration {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    // The fields after the command name (in parentheses): state, then ...;
    // the 22nd, start time in ticks since boot, is the 20th of them.
    let after_name: Vec<&str> = stat[stat.rfind(')').unwrap() + 2..].split(' ').collect();
    let started = after_name[19].parse::<f64>().unwrap() / 100.0;
    let uptime = std::fs::read_to_string("/proc/uptime").unwrap();
    let uptime: f64 = uptime.split(' ').next().unwrap().parse().unwrap();
    std::time::Duration::from_secs_f64((uptime - started).max(0.0))
}

/// Kills agent process `pid` (SIGKILL) and checks that it was killed before
/// it could join: an agent process declares its liveliness token no sooner
/// than a second after it starts (it first watches that long for another
/// process of its id, agent/process/src/unique.rs).
fn kill_before_joining(pid: u32) {
    let age = age(pid);
    let killed = Command::new("kill")
        .args(["-KILL", &pid.to_string()])
        .status()
        .unwrap();
    assert!(killed.success(), "process {pid} was not there to kill");
    assert!(
        age < std::time::Duration::from_millis(800),
        "process {pid} was killed {age:?} after it started: it might have joined"
    );
}

#[test]
fn an_agent_that_dies_before_joining_is_started_again_and_the_run_completes() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, team, stderr) = (
        tmp.path().join("out"),
        tmp.path().join("team.toml"),
        tmp.path().join("stderr"),
    );
    std::fs::write(&team, JOIN_AT_30).unwrap();
    let experiment = format!("early-{}", std::process::id());
    let mut coordinator = Command::new(bin("coordinator"))
        .args(["run", "--team"])
        .arg(&team)
        .args(["--runs", "1", "--episodes", "60", "--eval-every", "30"])
        .args(["--eval-episodes", "5", "--transport", "zenoh"])
        .args(["--restart-agents", "--stall-limit-ms", "2000"])
        .args(["--experiment", &experiment, "--quiet", "--out"])
        .arg(&out)
        .stderr(std::fs::File::create(&stderr).unwrap())
        .spawn()
        .unwrap();
    // Agent 1's first process and slot 2's newcomer, killed as soon as they
    // are seen, die before joining; the causes recorded below say that the
    // coordinator saw it so.
    let (one, two) = ((experiment.as_str(), 1), (experiment.as_str(), 2));
    kill_before_joining(seen(&mut coordinator, &stderr, one, &[]));
    let first = seen(&mut coordinator, &stderr, two, &[]);
    kill_before_joining(seen(&mut coordinator, &stderr, two, &[first]));
    let status = coordinator.wait().unwrap();
    let stderr = std::fs::read_to_string(&stderr).unwrap();
    assert!(status.success(), "{stderr}");
    let run: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run-0.json")).unwrap()).unwrap();
    let restarts = run["restarts"].as_array().unwrap();
    assert_eq!(restarts.len(), 2, "{restarts:?}");
    for (restart, slot, episode, process) in [
        (&restarts[0], 1, 0, "agent 1 exited"),
        (&restarts[1], 2, 30, "agent 2 (process 2) exited"),
    ] {
        assert_eq!(
            (&restart["slot"], &restart["episode"]),
            (&Value::from(slot), &Value::from(episode)),
            "{restart}"
        );
        let cause = restart["cause"].as_str().unwrap();
        assert!(
            cause.starts_with(process) && cause.contains("before joining"),
            "{restart}"
        );
        assert_eq!(restart["snapshot"], Value::Null, "{restart}");
        assert_eq!(restart["replayed"], false, "{restart}");
    }
    assert_eq!(run["joins"].as_array().unwrap().len(), 1);
    assert_eq!(run["points"].as_array().unwrap().len(), 3);
    assert_eq!(agent_pid(&experiment, 1), None);
}
