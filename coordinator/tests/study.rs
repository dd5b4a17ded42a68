//! `coordinator study`: a study interrupted and started again, or played as
//! concurrent shards, completes with the same results; bad studies are
//! refused with one line and exit code 2.

mod common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const TINY: &str = r#"
name = "tiny"
runs = 3
episodes = 200
eval_every = 50
eval_episodes = 20
seed = 5
transport = "in-process"
baseline = "no-advice"

[[entry]]
name = "no-advice"
algorithm = "no-advice"

[[entry]]
name = "adhoc-td"
algorithm = "adhoc-td"
"#;

fn study(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_coordinator"));
    c.arg("study")
        .args(args)
        .args(["--threads", "1", "--quiet"]);
    c
}

fn run(args: &[&str]) -> Output {
    study(args).output().expect("coordinator runs")
}

fn refused(output: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "stderr: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(
        stderr.starts_with("error:") && stderr.contains(needle),
        "{needle:?} not in {stderr}"
    );
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn an_interrupted_study_resumes_to_the_same_results() {
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("tiny.toml");
    fs::write(&config, TINY).unwrap();
    let config = config.to_str().unwrap();

    let whole = tmp.path().join("whole");
    let out = run(&["--config", config, "--out", whole.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    // Interrupt a second study as soon as its first run is finished.
    let resumed = tmp.path().join("resumed");
    let mut child = study(&["--config", config, "--out", resumed.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let first = resumed.join("no-advice").join("run-0.json");
    let deadline = Instant::now() + Duration::from_secs(120);
    while !first.exists() {
        assert!(Instant::now() < deadline, "the first run never finished");
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        !resumed.join("REPORT.md").exists(),
        "interrupted before the end"
    );

    let out = run(&["--config", config, "--out", resumed.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for entry in ["no-advice", "adhoc-td"] {
        let summary = |dir: &Path| common::without_times(&dir.join(entry).join("summary.json"));
        assert_eq!(summary(&resumed), summary(&whole), "{entry}");
        for k in 0..3 {
            let csv = |dir: &Path| read(&dir.join(entry).join(format!("run-{k}.csv")));
            assert_eq!(csv(&resumed), csv(&whole), "{entry} run {k}");
        }
    }
    assert_eq!(
        read(&resumed.join("significance.json")),
        read(&whole.join("significance.json"))
    );
    let significance: serde_json::Value =
        serde_json::from_str(&read(&resumed.join("significance.json"))).unwrap();
    let aggregate = &significance["aggregate"]["entries"];
    assert_eq!(aggregate[0]["entry"], "no-advice");
    assert!(aggregate[0]["last_ten"]["iqm_ci"].is_array(), "{aggregate}");
    assert!(aggregate[0]["last_ten"].get("p_improvement").is_none());
    assert!(
        aggregate[1]["area"]["p_improvement"]["ci"].is_array(),
        "{aggregate}"
    );
    assert_eq!(significance["holm"][0]["baseline"], "no-advice");
    let report = read(&resumed.join("REPORT.md"));
    for needle in [
        "| no-advice |",
        "| adhoc-td |",
        "Significance against `no-advice`",
        "The same with Holm's correction",
        "## Aggregate statistics (Agarwal et al. 2021)",
        "figures/goal_pct.svg",
        "figures/goal_pct_difference.svg",
    ] {
        assert!(report.contains(needle), "{needle:?} missing from REPORT.md");
    }
    for figure in [
        "goal_pct",
        "goal_pct_difference",
        "time_to_goal",
        "spent_budget",
        "goal_pct_last",
    ] {
        for ext in ["svg", "png"] {
            assert!(
                resumed
                    .join("figures")
                    .join(format!("{figure}.{ext}"))
                    .is_file()
            );
        }
    }
}

#[test]
fn concurrent_shards_then_one_invocation_equal_an_unsharded_study() {
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("tiny.toml");
    fs::write(&config, TINY).unwrap();
    let config = config.to_str().unwrap();
    let whole = tmp.path().join("whole");
    let sharded = tmp.path().join("sharded");
    let out = run(&["--config", config, "--out", whole.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    let children: Vec<_> = (1..=3)
        .map(|k| {
            study(&["--config", config, "--out", sharded.to_str().unwrap()])
                .args(["--shard", &format!("{k}/3")])
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    let mut played = 0;
    for child in children {
        let out = child.wait_with_output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        played += stdout
            .split(": ")
            .nth(1)
            .and_then(|s| s.split(' ').next())
            .and_then(|n| n.parse::<u64>().ok())
            .unwrap_or_else(|| panic!("runs played in {stdout:?}"));
    }
    assert_eq!(played, 2 * 3, "the shards play every run once");
    assert!(
        !sharded.join("REPORT.md").exists(),
        "shards write no report"
    );

    let out = run(&["--config", config, "--out", sharded.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(files(&sharded), files(&whole));
    for file in files(&whole) {
        let (a, b) = (whole.join(&file), sharded.join(&file));
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        if name == "summary.json" || name == "REPORT.md" {
            assert_eq!(
                common::without_times(&a),
                common::without_times(&b),
                "{name}"
            );
        } else if name.starts_with("run-") && name.ends_with(".json") {
            // A run's results record the time it took and the build.
            let results = |p: &Path| {
                let mut v: serde_json::Value = serde_json::from_str(&read(p)).unwrap();
                v["timing"]["training_s"] = 0.into();
                v["timing"]["evaluation_s"] = 0.into();
                v["played_with"]["commit"] = "<build>".into();
                v
            };
            assert_eq!(results(&a), results(&b), "{}", file.display());
        } else {
            assert!(
                fs::read(&a).unwrap() == fs::read(&b).unwrap(),
                "{}",
                file.display()
            );
        }
    }
}

#[test]
fn bad_studies_are_refused_and_nothing_is_overwritten() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = out.to_str().unwrap();
    refused(
        &run(&["--preset", "paper-everything", "--out", o]),
        "paper-scratch",
    );
    let write = |name: &str, text: &str| {
        let path = tmp.path().join(name);
        fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_owned()
    };
    let unknown = write("unknown.toml", &format!("colour = \"red\"\n{TINY}"));
    refused(&run(&["--config", &unknown, "--out", o]), "colour");
    let zero = write("zero.toml", &TINY.replace("runs = 3", "runs = 0"));
    refused(&run(&["--config", &zero, "--out", o]), "runs");
    let wide = write(
        "wide.toml",
        &TINY.replace("eval_every = 50", "eval_every = 500"),
    );
    refused(&run(&["--config", &wide, "--out", o]), "eval_every");
    assert!(!out.exists(), "nothing written for bad input");

    // A directory holding another study is left untouched.
    let tiny = write("tiny.toml", TINY);
    let done = run(&[
        "--config",
        &tiny,
        "--runs",
        "1",
        "--episodes",
        "50",
        "--out",
        o,
    ]);
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let before = read(&out.join("study.json"));
    refused(
        &run(&[
            "--config",
            &tiny,
            "--runs",
            "1",
            "--episodes",
            "60",
            "--out",
            o,
        ]),
        "study.json differs at `episodes`",
    );
    assert_eq!(read(&out.join("study.json")), before);

    // Only its runs may differ: the same study grows by a run.
    let grown = run(&[
        "--config",
        &tiny,
        "--runs",
        "2",
        "--episodes",
        "50",
        "--out",
        o,
    ]);
    assert!(
        grown.status.success(),
        "{}",
        String::from_utf8_lossy(&grown.stderr)
    );
    assert!(read(&out.join("study.json")).contains("\"runs\": 2"));
    assert!(out.join("no-advice").join("run-1.json").exists());
}

/// Every file under `dir`, relative to it, sorted.
pub fn files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                found.push(path.strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    found.sort();
    found
}
