//! The real HFO's seam: `coordinator run --simulator real-hfo` trains
//! agents over zenoh on a simulator that is a child process of env-server
//! (the harness's backend, `env-server/oracle/hfo_oracle/backend.py`),
//! here playing the fake HFO tree of the harness's tests
//! (`env-server/oracle/tests/fake_hfo`: a launcher and an `hfo` module that
//! play a scripted game, whatever the agents do, as real processes over
//! real pipes), and a fake server that goes down. Where the real HFO is
//! built ($HFO_DIR), a short run on it too.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use integration_tests::bin;
use serde_json::Value;

/// The harness's fake HFO tree.
fn fake_hfo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../env-server/oracle/tests/fake_hfo")
}

/// A Python 3 interpreter for the harness (the fake HFO needs no numpy).
fn python() -> Option<PathBuf> {
    let found = Command::new("sh")
        .args(["-c", "command -v python3"])
        .output()
        .ok()?;
    let path = String::from_utf8(found.stdout).ok()?;
    Some(PathBuf::from(path.trim())).filter(|p| p.is_file())
}

/// The options that have env-server play the fake HFO tree; `None`, said,
/// without a python3 to run it.
fn on_fake_hfo() -> Option<Vec<String>> {
    let Some(python) = python() else {
        eprintln!("no python3: the real HFO's seam is not tested");
        return None;
    };
    let [hfo, python] = [fake_hfo(), python].map(|p| p.to_string_lossy().into_owned());
    let options = [
        "--simulator",
        "real-hfo",
        "--hfo-dir",
        &hfo,
        "--hfo-python",
        &python,
    ];
    Some(options.map(String::from).to_vec())
}

/// `coordinator run` of three AdHocTD agents on the simulator `args` name,
/// 1 run of 20 training episodes, 4 evaluation episodes every 10, into
/// `out`; `rundir` is where the fake HFO's processes meet.
fn coordinator_run(args: &[&str], out: &Path, rundir: &Path) -> Output {
    coordinator_run_with(args, out, rundir, "1000")
}

/// [`coordinator_run`] where the fake HFO's launches play `trials` trials
/// in turn before their server goes down (`FAKE_HFO_TRIALS`).
fn coordinator_run_with(args: &[&str], out: &Path, rundir: &Path, trials: &str) -> Output {
    Command::new(bin("coordinator"))
        .args(["run", "--algorithm", "adhoc-td", "--runs", "1"])
        .args([
            "--episodes",
            "20",
            "--eval-every",
            "10",
            "--eval-episodes",
            "4",
        ])
        .args(args)
        .args(["--quiet", "--out"])
        .arg(out)
        .env("FAKE_HFO_RUNDIR", rundir)
        .env("FAKE_HFO_TRIALS", trials)
        .env_remove("HFO_DIR")
        .output()
        .expect("start the coordinator")
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn agents_train_over_zenoh_on_a_simulator_behind_a_pipe() {
    let Some(real) = on_fake_hfo() else { return };
    let real: Vec<&str> = real.iter().map(String::as_str).collect();
    let tmp = tempfile::tempdir().unwrap();
    let rundir = tmp.path().join("meet");
    std::fs::create_dir(&rundir).unwrap();
    let out = tmp.path().join("fake");
    let done = coordinator_run(&real, &out, &rundir);
    let stderr = String::from_utf8_lossy(&done.stderr);
    assert!(done.status.success(), "{stderr}");

    let config = json(&out.join("config.json"));
    assert_eq!(
        config["config"]["transport"]["zenoh"]["simulator"],
        serde_json::json!({"name": "real-hfo", "deterministic": false})
    );
    // The scripted game: its trials end in a goal and out of bounds in
    // turn, 8 frames each, whatever the agents do; the first one, a
    // warm-up, is played out before the run begins.
    let run = json(&out.join("run-0.json"));
    let points = run["points"].as_array().unwrap();
    assert_eq!(points.len(), 3, "{run}");
    for point in points {
        assert_eq!(point["goal_pct"], 50.0, "{point}");
        assert_eq!(point["time_to_goal"], 8.0, "{point}");
    }
    assert_eq!(run["timing"]["training_frames"], 160, "{run}");
    // Agent 0 (HFO's first player, who kicks in the script) asked its
    // teammates, over zenoh, at its kicks.
    let agents = points.last().unwrap()["agents"].as_array().unwrap();
    assert!(
        agents[0]["advice_requests"].as_u64().unwrap() > 0,
        "{agents:?}"
    );
    assert!(
        agents[1]["messages_received"].as_u64().unwrap() > 0,
        "{agents:?}"
    );

    // Its runs never share a directory with ours.
    let ours = coordinator_run(&[], &out, &rundir);
    assert!(!ours.status.success());
    let said = String::from_utf8_lossy(&ours.stderr);
    assert!(said.contains("simulator"), "{said}");

    // Without the real HFO, a clear error naming what is missing.
    let missing = tmp.path().join("no-hfo");
    let nowhere = [
        "--simulator",
        "real-hfo",
        "--hfo-dir",
        missing.to_str().unwrap(),
    ];
    let refused = coordinator_run(&nowhere, &tmp.path().join("none"), &rundir);
    assert!(!refused.status.success());
    let said = String::from_utf8_lossy(&refused.stderr);
    assert!(
        said.contains("bin/HFO") && said.contains("build_hfo.sh"),
        "{said}"
    );

    // Nor in process.
    let in_process = [&real[..], &["--transport", "in-process"]].concat();
    let refused = coordinator_run(&in_process, &tmp.path().join("in-process"), &rundir);
    let said = String::from_utf8_lossy(&refused.stderr);
    assert!(
        !refused.status.success() && said.contains("--transport zenoh"),
        "{said}"
    );
}

#[test]
fn a_simulator_that_goes_down_is_started_again_and_its_episode_replayed() {
    let Some(real) = on_fake_hfo() else { return };
    let real: Vec<&str> = real.iter().map(String::as_str).collect();
    let tmp = tempfile::tempdir().unwrap();
    let meet = |name: &str| {
        let dir = tmp.path().join(name);
        std::fs::create_dir(&dir).unwrap();
        dir
    };
    // The first server goes down after its warm-up and 11 episodes, within
    // the first training block; the next one plays on.
    let out = tmp.path().join("restarted");
    let done = coordinator_run_with(&real, &out, &meet("once"), "12,1000");
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let run = json(&out.join("run-0.json"));
    let restarts = run["simulator_restarts"].as_array().unwrap();
    assert_eq!(restarts.len(), 1, "{run}");
    assert_eq!(restarts[0]["evaluation"], false, "{run}");
    assert_eq!(restarts[0]["episode"], 7, "{run}");
    let cause = restarts[0]["cause"].as_str().unwrap();
    assert!(cause.contains("server went down"), "{cause}");
    // Every episode was played in full: 20 training episodes of 8 frames.
    assert_eq!(run["points"].as_array().unwrap().len(), 3, "{run}");
    assert_eq!(run["timing"]["training_frames"], 160, "{run}");

    // A server that keeps going down ends the run, saying so.
    let out = tmp.path().join("down");
    let failed = coordinator_run_with(&real, &out, &meet("always"), "0");
    let said = String::from_utf8_lossy(&failed.stderr);
    assert!(
        !failed.status.success() && said.contains("failed 4 times in a row"),
        "{said}"
    );
}

#[test]
fn agents_train_on_the_real_hfo_where_it_is_built() {
    let Some(dir) = std::env::var_os("HFO_DIR").map(PathBuf::from) else {
        eprintln!("HFO_DIR is not set: no run on the real HFO");
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("real");
    let done = Command::new(bin("coordinator"))
        .args(["run", "--algorithm", "adhoc-visit", "--runs", "1"])
        .args([
            "--episodes",
            "20",
            "--eval-every",
            "10",
            "--eval-episodes",
            "5",
        ])
        .args(["--simulator", "real-hfo", "--quiet", "--out"])
        .arg(&out)
        .arg("--hfo-dir")
        .arg(&dir)
        .output()
        .expect("start the coordinator");
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let run = json(&out.join("run-0.json"));
    let frames = run["timing"]["training_frames"].as_u64().unwrap();
    assert!(frames >= 20, "{run}");
}
