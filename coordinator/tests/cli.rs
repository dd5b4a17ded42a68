//! The `coordinator` binary end to end: output shape, determinism across
//! thread counts, saved agents, bad input, and a learning sanity check.

mod common;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn coordinator<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_coordinator"))
        .args(args)
        .env_remove("RUST_LOG")
        .output()
        .expect("the binary runs")
}

/// A tiny experiment: 2 runs x 40 episodes, evaluations of 10 every 20.
const TINY: [&str; 10] = [
    "--runs",
    "2",
    "--episodes",
    "40",
    "--eval-every",
    "20",
    "--eval-episodes",
    "10",
    "--seed",
    "7",
];

fn run_tiny(algorithm: &str, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["run", "--algorithm", algorithm];
    args.extend(TINY);
    args.extend(["--transport", "in-process", "--quiet", "--out"]);
    args.push(out.to_str().unwrap());
    args.extend(extra);
    coordinator(&args)
}

fn ok(output: &Output) {
    assert!(
        output.status.success(),
        "exit {:?}, stderr: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Asserts exit code 2 with one `error:` line naming `needle`.
fn refused(output: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "stderr: {stderr}");
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line: {stderr}");
    assert!(lines[0].starts_with("error:"), "{stderr}");
    assert!(lines[0].contains(needle), "{needle:?} not in {stderr}");
}

fn summary(dir: &Path) -> Value {
    serde_json::from_slice(&fs::read(dir.join("summary.json")).unwrap()).unwrap()
}

/// Every file of a directory with its bytes.
fn contents(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            let bytes = fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect()
}

#[test]
fn writes_run_csvs_and_a_summary_of_the_right_shape() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let output = run_tiny("adhoc-td", &out, &[]);
    ok(&output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("frames_per_sec"), "{stdout}");

    let mut names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "config.json",
            "run-0.csv",
            "run-0.json",
            "run-1.csv",
            "run-1.json",
            "summary.json"
        ]
    );
    for run in 0..2 {
        check_tiny_run_csv(&fs::read_to_string(out.join(format!("run-{run}.csv"))).unwrap());
    }
    check_tiny_summary(&out);
}

/// A run CSV of [`TINY`] with a team of three: its header, and an evaluation
/// at episodes 0, 20 and 40 of 10 episodes each.
fn check_tiny_run_csv(text: &str) {
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0],
        [
            "episode",
            "goal_pct",
            "time_to_goal",
            "give_spent_0",
            "give_spent_1",
            "give_spent_2",
            "ask_spent_0",
            "ask_spent_1",
            "ask_spent_2",
            "advice_requests",
            "advice_given",
            "spent_budget",
            "advice_replies_received",
            "messages_sent",
            "bytes_sent",
            "messages_received",
            "bytes_received",
            "messages_dropped",
            "actions_timed_out",
            "advising_messages",
            "advising_bytes",
            "answered_requests",
            "declined_requests",
            "futile_requests",
            "lost_requests",
            "reused_advice"
        ]
    );
    assert_eq!(rows.len(), 4, "header + evaluations at 0, 20, 40");
    for (row, episode) in rows[1..].iter().zip(["0", "20", "40"]) {
        assert_eq!(row.len(), 26);
        assert_eq!(row[0], episode);
        let gp: f64 = row[1].parse().unwrap();
        assert!((0.0..=100.0).contains(&gp) && gp % 10.0 == 0.0, "{gp}");
        // Empty without a goal, else a mean of 1 to 200 frames.
        assert!(
            (gp == 0.0) == row[2].is_empty(),
            "goal_pct {gp}, time_to_goal {:?}",
            row[2]
        );
        if !row[2].is_empty() {
            let tg: f64 = row[2].parse().unwrap();
            assert!((1.0..=200.0).contains(&tg), "{tg}");
        }
    }
    // Nothing is spent before training; AdHocTD never gives more than its budget.
    assert!(rows[1][3..].iter().all(|c| *c == "0"), "{:?}", rows[1]);
}

/// The summary of [`TINY`] with AdHocTD: its identity and an estimate with
/// its interval at every evaluation point.
fn check_tiny_summary(out: &Path) {
    let s = summary(out);
    assert_eq!(s["seed"], 7);
    assert_eq!(s["runs"], 2);
    assert_eq!(s["config"]["eval_every"], 20);
    assert_eq!(s["config"]["team"][0]["algorithm"], "adhoc-td");
    let points = s["eval_points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    for (p, episode) in points.iter().zip([0, 20, 40]) {
        assert_eq!(p["episode"], episode);
        for metric in ["goal_pct", "spent_budget"] {
            let m = &p[metric];
            let (mean, lo, hi) = (
                m["mean"].as_f64().unwrap(),
                m["ci_low"].as_f64().unwrap(),
                m["ci_high"].as_f64().unwrap(),
            );
            assert!(lo <= mean && mean <= hi, "{metric} {m}");
        }
        assert!(p["time_to_goal"].is_object());
    }
    let config: Value =
        serde_json::from_slice(&fs::read(out.join("config.json")).unwrap()).unwrap();
    assert_eq!(config["config"], s["config"]);
}

#[test]
fn the_summary_is_byte_identical_whatever_the_threads() {
    let tmp = tempfile::tempdir().unwrap();
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    ok(&run_tiny("adhoc-visit", &one, &["--threads", "1"]));
    ok(&run_tiny("adhoc-visit", &two, &["--threads", "2"]));
    let a = common::without_times(&one.join("summary.json"));
    let b = common::without_times(&two.join("summary.json"));
    assert_eq!(a, b);
    for run in ["run-0.csv", "run-1.csv"] {
        assert_eq!(
            fs::read(one.join(run)).unwrap(),
            fs::read(two.join(run)).unwrap()
        );
    }
    // Running the same configuration again in the same directory is allowed
    // and gives the same bytes.
    ok(&run_tiny("adhoc-visit", &one, &["--threads", "2"]));
    assert_eq!(common::without_times(&one.join("summary.json")), a);
    // Another seed gives other results.
    let three = tmp.path().join("three");
    ok(&run_tiny("adhoc-visit", &three, &["--seed", "8"]));
    assert_ne!(
        fs::read(three.join("run-0.csv")).unwrap(),
        fs::read(one.join("run-0.csv")).unwrap()
    );
}

/// `run-<k>.json` without the times it measured.
fn run_without_timing(path: &Path) -> Value {
    let mut run: Value = serde_json::from_slice(&fs::read(path).unwrap()).unwrap();
    let timing = run.as_object_mut().unwrap().remove("timing");
    assert!(timing.is_some(), "{}", path.display());
    run
}

/// A team of three AdHocTD agents learning with small DQNs that train from
/// their eighth decision, so that a tiny run takes many gradient steps.
fn dqn_team(dir: &Path, warmup: u64) -> PathBuf {
    let agent = format!(
        "[[agent]]\nalgorithm = \"adhoc-td\"\nlearner = \"dqn\"\nhidden = [16, 8]\nbatch = 8\n\
         replay = 200\nwarmup = {warmup}\ntarget_every = 5\nepsilon_decay = 100\n"
    );
    let team = dir.join(format!("dqn-{warmup}.toml"));
    fs::write(&team, [agent.as_str(); 3].join("\n")).unwrap();
    team
}

fn run_team(team: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["run", "--team", team.to_str().unwrap()];
    args.extend(TINY);
    args.extend(["--transport", "in-process", "--quiet", "--out"]);
    args.push(out.to_str().unwrap());
    args.extend(extra);
    coordinator(&args)
}

/// The two runs' files in `one` and `two` are the same but for measured times.
fn assert_same_runs(one: &Path, two: &Path) {
    assert_eq!(
        common::without_times(&one.join("summary.json")),
        common::without_times(&two.join("summary.json"))
    );
    for run in 0..2 {
        let csv = format!("run-{run}.csv");
        let read = |dir: &Path| fs::read(dir.join(&csv)).unwrap();
        assert_eq!(read(one), read(two), "{csv}");
        let json = format!("run-{run}.json");
        assert_eq!(
            run_without_timing(&one.join(&json)),
            run_without_timing(&two.join(&json)),
            "{json}"
        );
    }
}

#[test]
fn a_dqn_run_is_byte_identical_whatever_the_threads() {
    let tmp = tempfile::tempdir().unwrap();
    let team = dqn_team(tmp.path(), 8);
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    ok(&run_team(&team, &one, &["--threads", "1"]));
    ok(&run_team(&team, &two, &["--threads", "2"]));
    assert_same_runs(&one, &two);
    // The runs differ from each other, with another seed, and from DQNs
    // that never train: the files compared hold what the training did.
    let csv = |dir: &Path, run: u64| fs::read(dir.join(format!("run-{run}.csv"))).unwrap();
    assert_ne!(csv(&one, 0), csv(&one, 1));
    let other_seed = tmp.path().join("seed");
    ok(&run_team(&team, &other_seed, &["--seed", "8"]));
    assert_ne!(csv(&other_seed, 0), csv(&one, 0));
    let untrained = tmp.path().join("untrained");
    ok(&run_team(&dqn_team(tmp.path(), 100_000), &untrained, &[]));
    assert_ne!(csv(&untrained, 0), csv(&one, 0));
}

/// `dqn_team`'s agents reading HFO's features (27 for three attackers).
fn hfo_team(dir: &Path) -> PathBuf {
    let paper = fs::read_to_string(dqn_team(dir, 8)).unwrap();
    let team = dir.join("dqn-hfo.toml");
    fs::write(
        &team,
        paper.replace("[[agent]]\n", "[[agent]]\nobservation = \"hfo\"\n"),
    )
    .unwrap();
    team
}

#[test]
fn a_dqn_reading_hfos_features_is_byte_identical_whatever_the_threads() {
    let tmp = tempfile::tempdir().unwrap();
    let team = hfo_team(tmp.path());
    let (one, two) = (tmp.path().join("one"), tmp.path().join("two"));
    let agents = tmp.path().join("agents");
    let save = ["--save-agents", agents.to_str().unwrap()];
    ok(&run_team(
        &team,
        &one,
        &[&["--threads", "1"][..], &save].concat(),
    ));
    ok(&run_team(&team, &two, &["--threads", "2"]));
    assert_same_runs(&one, &two);
    let s = summary(&one);
    for agent in s["config"]["team"].as_array().unwrap() {
        assert_eq!(agent["observation"], "hfo", "{agent}");
    }
    // The paper's observation plays otherwise. The advisors, which read
    // the features too, value the askers' states: they give advice.
    let paper = tmp.path().join("paper");
    ok(&run_team(&dqn_team(tmp.path(), 8), &paper, &[]));
    let csv = |dir: &Path| fs::read(dir.join("run-0.csv")).unwrap();
    assert_ne!(csv(&one), csv(&paper));
    let run = run_without_timing(&one.join("run-0.json"));
    let last = run["points"].as_array().unwrap().last().unwrap();
    for agent in last["agents"].as_array().unwrap() {
        assert!(agent["advice_given"].as_u64().unwrap() > 0, "{agent}");
    }
    // Its snapshot goes to a DQN reading the same, and no other.
    let out = tmp.path().join("loaded");
    let load_into = |observation: &str| {
        let text = fs::read_to_string(&team).unwrap().replace(
            "observation = \"hfo\"\n",
            &format!("observation = \"{observation}\"\nload = \"agents/run-0-agent-0.snapshot\"\n"),
        );
        fs::write(tmp.path().join("load.toml"), text).unwrap();
        run_team(&tmp.path().join("load.toml"), &out, &["--runs", "1"])
    };
    refused(
        &load_into("paper"),
        "the snapshot's DQN reads observation `hfo` (27 inputs), this agent's reads `paper` \
         (6 inputs)",
    );
    assert!(!out.exists(), "nothing written for bad input");
    ok(&load_into("hfo"));
}

#[test]
fn dqn_snapshots_are_saved_and_loaded_and_other_learners_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let one_run = ["--runs", "1"];
    let agents = tmp.path().join("agents");
    let dqn = dqn_team(tmp.path(), 8);
    let mut save = one_run.to_vec();
    save.extend(["--save-agents", agents.to_str().unwrap()]);
    ok(&run_team(&dqn, &tmp.path().join("trained"), &save));
    let snapshot = |i: usize| agents.join(format!("run-0-agent-{i}.snapshot"));
    // Format version 2: the framework's state, then the DQN's own.
    let bytes = fs::read(snapshot(0)).unwrap();
    assert_eq!(&bytes[..10], b"ADVQTAB\0\x02\0");
    // Network, optimiser and replay: more than the 6-16-8-4 network alone.
    assert!(
        bytes.len() > 4 * (6 * 16 + 16 * 8 + 8 * 4) * 4,
        "{}",
        bytes.len()
    );

    // Loaded by DQN agents of the same shape, from the start and as a newcomer.
    let team = tmp.path().join("team.toml");
    let dqn_text = fs::read_to_string(&dqn).unwrap();
    let agent = dqn_text.split("\n\n").next().unwrap().trim_end().to_owned();
    let newcomer = agent
        .trim_start_matches("[[agent]]\n")
        .lines()
        .collect::<Vec<_>>()
        .join(", ");
    fs::write(
        &team,
        format!(
            "{agent}\nload = \"agents/run-0-agent-0.snapshot\"\n\n{agent}\n\n{agent}\n\n\
             [[event]]\nepisode = 20\nslot = 2\n\
             newcomer = {{ {newcomer}, load = \"agents/run-0-agent-2.snapshot\" }}\n"
        ),
    )
    .unwrap();
    let loaded = tmp.path().join("loaded");
    ok(&run_team(&team, &loaded, &one_run));
    let s = summary(&loaded);
    let digests = s["snapshot_digests"].as_array().unwrap();
    assert_eq!(digests[0].as_str().unwrap().len(), 16, "{digests:?}");
    assert!(digests[1].is_null());

    // Another learner's snapshot, or another shape's, is refused by name.
    let out = tmp.path().join("out");
    let load_into = |agent: &str, path: &Path| {
        fs::write(
            &team,
            format!(
                "[[agent]]\n[[agent]]\n{agent}\nload = {:?}\n",
                path.to_str().unwrap()
            ),
        )
        .unwrap();
        run_team(&team, &out, &one_run)
    };
    refused(
        &load_into("[[agent]]\nalgorithm = \"adhoc-td\"", &snapshot(0)),
        "it holds a DQN's network (saved by an agent of learner dqn), and this agent learns \
         with sarsa",
    );
    refused(
        &load_into("[[agent]]\nlearner = \"dqn\"\nhidden = [16]", &snapshot(0)),
        "the snapshot's network has layers [6, 16, 8, 4]",
    );
    let sarsa = tmp.path().join("sarsa");
    let mut save = one_run.to_vec();
    save.extend(["--save-agents", sarsa.to_str().unwrap()]);
    ok(&run_tiny("no-advice", &tmp.path().join("sarsa-run"), &save));
    refused(
        &load_into(&agent, &sarsa.join("run-0-agent-0.snapshot")),
        "the snapshot holds a Q-table (learner sarsa or ensemble), not a DQN's network",
    );
    assert!(!out.exists(), "nothing written for bad input");
}

#[test]
fn a_saved_team_replays_as_a_game_log_that_reads_back() {
    let tmp = tempfile::tempdir().unwrap();
    let agents = tmp.path().join("agents");
    let trained = tmp.path().join("trained");
    ok(&run_tiny(
        "adhoc-td",
        &trained,
        &["--save-agents", agents.to_str().unwrap()],
    ));
    let team = tmp.path().join("team.toml");
    let tables: Vec<String> = (0..3)
        .map(|i| {
            format!(
                "[[agent]]\nalgorithm = \"adhoc-td\"\nload = \"agents/run-0-agent-{i}.snapshot\"\n"
            )
        })
        .collect();
    fs::write(&team, tables.join("\n")).unwrap();
    let replay = |out: &Path| {
        let (team, out) = (team.to_str().unwrap(), out.to_str().unwrap());
        coordinator(&[
            "replay",
            "--team",
            team,
            "--seed",
            "5",
            "--episode",
            "2",
            "--out",
            out,
        ])
    };
    let log = tmp.path().join("episode.rcg");
    let output = replay(&log);
    ok(&output);
    // "wrote <path>: goal after 87 frames", and one show line per state.
    let said = String::from_utf8_lossy(&output.stdout);
    let frames: usize = (said.split(" after ").nth(1))
        .and_then(|rest| rest.split(' ').next()?.parse().ok())
        .unwrap_or_else(|| panic!("{said}"));
    let shows = env_server::tools::rcg::read_shows(&fs::read_to_string(&log).unwrap()).unwrap();
    assert_eq!(shows.len(), frames + 1);
    assert!(shows.iter().all(|s| s.players.len() == 4));
    // The same episode again, the same bytes; an animation beside it.
    let again = tmp.path().join("again.rcg");
    ok(&replay(&again));
    assert_eq!(fs::read(&log).unwrap(), fs::read(&again).unwrap());
    let animation = tmp.path().join("episode.svg");
    ok(&replay(&animation));
    let svg = fs::read_to_string(&animation).unwrap();
    assert_eq!(svg.matches("<animateTransform").count(), 5);
    refused(
        &replay(&tmp.path().join("episode.png")),
        ".svg, .html or .rcg",
    );
}

#[test]
fn who_advised_whom_keeps_the_advice_of_an_agent_that_left() {
    let tmp = tempfile::tempdir().unwrap();
    // Early advising asks at every step; its newcomer never asks.
    let team = tmp.path().join("team.toml");
    let agent = "[[agent]]\nalgorithm = \"early-advising\"\n";
    let event = "[[event]]\nepisode = 30\nslot = 2\n\
                 newcomer = { algorithm = \"early-advising\", ask_budget = 0 }\n";
    fs::write(&team, format!("{agent}{agent}{agent}{event}")).unwrap();
    let out = tmp.path().join("out");
    let mut args = vec!["run", "--team", team.to_str().unwrap()];
    args.extend(TINY);
    args.extend([
        "--transport",
        "in-process",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&coordinator(&args));
    let run: Value = serde_json::from_slice(&fs::read(out.join("run-0.json")).unwrap()).unwrap();
    let acted_on = |episode: u64, agent: usize| {
        let points = run["points"].as_array().unwrap();
        let point = points.iter().find(|p| p["episode"] == episode).unwrap();
        point["agents"][agent]["ask_spent"].as_u64().unwrap()
    };
    // Before the join the first agent of slot 2 acted on advice; after it
    // the newcomer acted on none, and the slot's row still counts the first's.
    let before = acted_on(20, 2);
    assert!(before > 0 && acted_on(40, 2) == 0, "{before}");
    let row: u64 = (run["advice_matrix"][2].as_array().unwrap().iter())
        .map(|n| n.as_u64().unwrap())
        .sum();
    assert!(
        row >= before,
        "slot 2's row {row} < {before} acted on before the join"
    );
}

#[test]
fn saved_agents_start_a_mixed_team() {
    let tmp = tempfile::tempdir().unwrap();
    let agents = tmp.path().join("agents");
    let pre = tmp.path().join("pre");
    ok(&run_tiny(
        "no-advice",
        &pre,
        &["--save-agents", agents.to_str().unwrap()],
    ));
    for run in 0..2 {
        for agent in 0..3 {
            assert!(
                agents
                    .join(format!("run-{run}-agent-{agent}.snapshot"))
                    .is_file()
            );
        }
    }
    // The expert experiment's team: two AdHocTD learners and a loaded
    // NoAdvice expert that never asks.
    let team = tmp.path().join("team.toml");
    fs::write(
        &team,
        "[[agent]]\nalgorithm = \"ad-hoc-td\"\n\n[[agent]]\nalgorithm = \"ad-hoc-td\"\n\n\
         [[agent]]\nalgorithm = \"ad-hoc-td\"\nask_budget = 0\nload = \"agents/run-0-agent-2.snapshot\"\n",
    )
    .unwrap();
    let out = tmp.path().join("expert");
    let mut args = vec!["run", "--team", team.to_str().unwrap()];
    args.extend(TINY);
    args.extend([
        "--transport",
        "in-process",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&coordinator(&args));
    let s = summary(&out);
    let digests = s["snapshot_digests"].as_array().unwrap();
    assert!(digests[0].is_null() && digests[1].is_null());
    assert_eq!(digests[2].as_str().unwrap().len(), 16);
    assert_eq!(s["config"]["team"][2]["ask_budget"], 0);
    // The expert never asks: its ask budget stays unspent.
    let csv = fs::read_to_string(out.join("run-0.csv")).unwrap();
    for line in csv.lines().skip(1) {
        assert_eq!(line.split(',').nth(8), Some("0"), "{line}");
    }
}

#[test]
fn bad_input_is_refused_with_exit_code_2() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();

    refused(&run_tiny("best-advice", &out, &[]), "adhoc-td");
    refused(
        &run_tiny("no-advice", &out, &["--eval-every", "0"]),
        "eval_every",
    );
    refused(
        &run_tiny("no-advice", &out, &["--eval-episodes", "0"]),
        "eval_episodes",
    );
    refused(&run_tiny("no-advice", &out, &["--runs", "0"]), "runs");
    refused(
        &run_tiny("no-advice", &out, &["--transport", "carrier-pigeon"]),
        "zenoh, in-process",
    );
    refused(
        &run_tiny("no-advice", &out, &["--mistake-correcting"]),
        "mistake_correcting",
    );
    refused(&coordinator(&["run", "--out", o]), "--algorithm");
    assert!(!out.exists(), "nothing written for bad input");

    // A missing and a corrupt agent file.
    let team = tmp.path().join("team.toml");
    let missing = tmp.path().join("missing.snapshot");
    fs::write(
        &team,
        format!(
            "[[agent]]\n[[agent]]\n[[agent]]\nload = {:?}\n",
            missing.to_str().unwrap()
        ),
    )
    .unwrap();
    let team_args = |team: &Path| {
        let mut args = vec![
            "run".to_owned(),
            "--team".into(),
            team.to_str().unwrap().into(),
        ];
        args.extend(TINY.map(String::from));
        args.extend(["--transport", "in-process", "--quiet", "--out", o].map(String::from));
        args
    };
    refused(&coordinator(&team_args(&team)), "missing.snapshot");
    fs::write(&missing, b"ADVQTAB\0 not really a snapshot").unwrap();
    refused(&coordinator(&team_args(&team)), "agent 2");
    fs::write(&missing, b"garbage").unwrap();
    refused(&coordinator(&team_args(&team)), "not an agent snapshot");
    // A team file of the wrong size or with a typo.
    fs::write(&team, "[[agent]]\n[[agent]]\n").unwrap();
    let mut args = team_args(&team);
    args.extend(["--offense".into(), "3".into()]);
    refused(&coordinator(&args), "team");
    fs::write(&team, "[[agent]]\nepsilonn = 0.2\n").unwrap();
    refused(&coordinator(&team_args(&team)), "epsilonn");
    assert!(!out.exists(), "nothing written for bad input");

    // A directory holding another configuration's results is left untouched.
    ok(&run_tiny("no-advice", &out, &[]));
    let before = contents(&out);
    refused(&run_tiny("no-advice", &out, &["--seed", "8"]), o);
    refused(&run_tiny("torrey", &out, &[]), "another configuration");
    // The transport is part of the identity: another one, or other zenoh
    // timeouts, never rewrite these results.
    let zenoh = ["--transport", "zenoh", "--advice-timeout-ms", "7"];
    refused(&run_tiny("no-advice", &out, &zenoh), "config.transport");
    // An output path that is a file.
    let file = tmp.path().join("file");
    fs::write(&file, b"mine").unwrap();
    refused(&run_tiny("no-advice", &file, &[]), "is a file");
    assert_eq!(contents(&out), before);
}

#[test]
fn a_dqn_learner_is_chosen_by_name_and_its_bad_settings_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();
    let short = ["--runs", "1", "--episodes", "20"];
    fn with<'a>(short: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
        [short, extra].concat()
    }

    // Every agent of --algorithm learns with the DQN, as config.json records.
    let played = tmp.path().join("dqn");
    let output = run_tiny("no-advice", &played, &with(&short, &["--learner", "dqn"]));
    ok(&output);
    assert!(
        String::from_utf8_lossy(&output.stdout).starts_with("no-advice (learner dqn): 1 runs"),
        "{}",
        String::from_utf8_lossy(&output.stdout)
    );
    let config: Value =
        serde_json::from_slice(&fs::read(played.join("config.json")).unwrap()).unwrap();
    let team = config["config"]["team"].as_array().unwrap();
    assert_eq!(team.len(), 3);
    for agent in team {
        assert_eq!(agent["learner"], "dqn", "{agent}");
        assert_eq!(agent["hidden"], serde_json::json!([64, 64]), "{agent}");
    }

    // Bad names and bad settings: one line naming the key, nothing written.
    refused(
        &run_tiny("no-advice", &out, &with(&short, &["--learner", "deep"])),
        "--learner",
    );
    let team = tmp.path().join("team.toml");
    let team_args = || {
        let mut args = vec!["run", "--team", team.to_str().unwrap()];
        args.extend(TINY);
        args.extend(["--transport", "in-process", "--quiet", "--out", o]);
        args
    };
    fs::write(&team, "[[agent]]\n[[agent]]\n[[agent]]\n").unwrap();
    let mut both = team_args();
    both.extend(["--learner", "dqn"]);
    refused(&coordinator(&both), "--learner");
    let dqn_team = |keys: &str| {
        let agent = format!("[[agent]]\nlearner = \"dqn\"\n{keys}\n");
        fs::write(&team, format!("[[agent]]\n[[agent]]\n{agent}")).unwrap();
        coordinator(&team_args())
    };
    for (keys, needle) in [
        (
            "hidden = 0",
            "team[2].hidden`: each layer must be 1 to 1024 units wide, got 0",
        ),
        (
            "hidden = [64, 4096]",
            "team[2].hidden`: each layer must be 1 to 1024 units wide, got 4096",
        ),
        ("lr = -0.1", "team[2].lr`: must be in (0, 1], got -0.1"),
        ("lr = nan", "`lr`: must be a finite number, got NaN"),
        (
            "epsilon_end = inf",
            "`epsilon_end`: must be a finite number",
        ),
        (
            "epsilon_end = 2.0",
            "team[2].epsilon_end`: must be in [0, 1], got 2",
        ),
        (
            "batch = 64\nreplay = 16",
            "team[2].batch`: must be 1 to replay (16), got 64",
        ),
    ] {
        let output = dqn_team(keys);
        refused(&output, needle);
    }
    fs::write(&team, "[[agent]]\nlearner = \"dqnn\"\n").unwrap();
    refused(&coordinator(&team_args()), "unknown learner `dqnn`");
    // HFO's features: a DQN's observation, not the tabular learner's, and
    // not one that learns from shared episodes.
    fs::write(
        &team,
        "[[agent]]\n[[agent]]\n[[agent]]\nobservation = \"hfo\"\n",
    )
    .unwrap();
    refused(
        &coordinator(&team_args()),
        "`observation`: does not apply to learner sarsa; it belongs to learner dqn",
    );
    let sharing = "[[agent]]\nalgorithm = \"episode-sharing\"\nlearner = \"dqn\"\n\
                   observation = \"hfo\"\n";
    fs::write(&team, sharing.repeat(3)).unwrap();
    refused(
        &coordinator(&team_args()),
        "`team[0].observation`: `hfo` cannot learn from algorithm episode-sharing's shared \
         episodes",
    );
    assert!(!out.exists(), "nothing written for bad input");
}

/// `method`, which needs the DQN, is refused with the tabular learners:
/// on the command line, and in a team file whose agent `sarsa_at` names
/// `sarsa`; one line naming the key, nothing written.
fn refuses_a_tabular_learner(method: &str, sarsa_at: usize) {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let expected = format!("algorithm {method} needs a neural learner (dqn), not");
    for learner in ["sarsa", "ensemble"] {
        let output = run_tiny(method, &out, &["--learner", learner]);
        refused(&output, &format!("learner`: {expected} {learner}"));
    }
    let team = tmp.path().join("team.toml");
    let agents: String = (0..3)
        .map(|i| {
            let learner = if i == sarsa_at {
                "learner = \"sarsa\"\n"
            } else {
                ""
            };
            format!("[[agent]]\nalgorithm = \"{method}\"\n{learner}")
        })
        .collect();
    fs::write(&team, agents).unwrap();
    let o = out.to_str().unwrap();
    let mut args = vec!["run", "--team", team.to_str().unwrap()];
    args.extend(TINY);
    args.extend(["--transport", "in-process", "--quiet", "--out", o]);
    refused(
        &coordinator(&args),
        &format!("`team[{sarsa_at}].learner`: {expected} sarsa"),
    );
    assert!(!out.exists(), "nothing written for bad input");
}

#[test]
fn advice_imitation_refuses_a_tabular_learner() {
    refuses_a_tabular_learner("advice-imitation", 2);
}

#[test]
fn ef_ontl_refuses_a_tabular_learner() {
    refuses_a_tabular_learner("ef-ontl", 1);
}

/// NoAdvice learns: over 4 runs, the mean goal percentage after 600
/// training episodes is clearly above the one before training (about 5%
/// before, 30% after with this simulator).
#[test]
fn no_advice_learns() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("learn");
    let output = coordinator(&[
        "run",
        "--algorithm",
        "no-advice",
        "--runs",
        "4",
        "--episodes",
        "600",
        "--eval-every",
        "300",
        "--eval-episodes",
        "100",
        "--seed",
        "1",
        "--transport",
        "in-process",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&output);
    let s = summary(&out);
    let points = s["eval_points"].as_array().unwrap();
    let gp = |p: &Value| p["goal_pct"]["mean"].as_f64().unwrap();
    let (first, last) = (gp(&points[0]), gp(&points[2]));
    assert!(last >= first + 10.0, "goal_pct {first} -> {last}");
}

#[test]
fn aggregate_prints_the_same_statistics_every_time() {
    let fixture = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/scores.json");
    let args = ["aggregate", "--scores", fixture, "--baseline", "no-advice"];
    let (first, again) = (coordinator(&args), coordinator(&args));
    ok(&first);
    assert_eq!(first.stdout, again.stdout);
    let out: Value = serde_json::from_slice(&first.stdout).unwrap();
    let td = &out["algorithms"]["AdHocTD"];
    assert_eq!(td["mean"], 27.208333333333332);
    assert!(td["p_improvement"]["estimate"].is_f64(), "{out}");
}

#[test]
fn aggregate_refuses_bad_scores() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str, text: &str| {
        let path = dir.path().join(name);
        fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_owned()
    };
    let run = |path: &str, baseline: &str| {
        coordinator(&["aggregate", "--scores", path, "--baseline", baseline])
    };
    let good = file("good.json", r#"{"a": [1, 2], "b": [3]}"#);
    refused(&run(&good, "c"), "no baseline \"c\"");
    refused(
        &run(&file("empty.json", r#"{"a": [], "b": [3]}"#), "b"),
        "a has no score",
    );
    refused(
        &run(&file("text.json", r#"{"a": ["x"]}"#), "a"),
        "expected an object",
    );
    refused(
        &run(&file("huge.json", r#"{"a": [1e999]}"#), "a"),
        "expected an object",
    );
    refused(
        &run(&dir.path().join("missing.json").to_string_lossy(), "a"),
        "cannot read",
    );
    refused(
        &coordinator(&[
            "aggregate",
            "--scores",
            &good,
            "--baseline",
            "a",
            "--level",
            "1",
        ]),
        "--level",
    );
}
