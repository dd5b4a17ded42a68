//! A study entry names its own baseline: each entry's gains, tests and
//! statistics are against it (checked against gains computed by hand from
//! the run files), the report names each entry's, and a baseline that
//! cannot be is refused with one line and exit code 2, nothing written.

use std::fs;
use std::path::Path;
use std::process::Command;

use analysis::RunResult;
use analysis::stats::gains::{first, last_ten};
use coordinator::study::{StudyConfig, StudyOptions, run_study};
use serde_json::Value;

/// SARSA(λ) and DQN agents, each learner's advising against NoAdvice of
/// the same learner.
const TWO_BASELINES: &str = r#"
name = "two-baselines"
runs = 2
episodes = 40
eval_every = 20
eval_episodes = 5
seed = 3
transport = "in-process"
baseline = "no-advice"

[[entry]]
name = "no-advice"
algorithm = "no-advice"

[[entry]]
name = "adhoc-td"
algorithm = "adhoc-td"

[[entry]]
name = "no-advice-dqn"
algorithm = "no-advice"
learner = "dqn"
hidden = [8]
batch = 8
warmup = 8

[[entry]]
name = "adhoc-td-dqn"
algorithm = "adhoc-td"
learner = "dqn"
hidden = [8]
batch = 8
warmup = 8
baseline = "no-advice-dqn"
"#;

fn read_json(path: &Path) -> Value {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap()
}

/// The mean over runs of `entry`'s `metric` minus `baseline`'s, paired by
/// run, from their run files.
fn gain_by_hand(
    out: &Path,
    (entry, baseline): (&str, &str),
    metric: fn(&RunResult) -> Option<f64>,
) -> f64 {
    let runs = 2;
    let of = |name: &str, k: u64| {
        let run: RunResult =
            serde_json::from_value(read_json(&out.join(name).join(format!("run-{k}.json"))))
                .unwrap();
        metric(&run).unwrap()
    };
    (0..runs)
        .map(|k| of(entry, k) - of(baseline, k))
        .sum::<f64>()
        / runs as f64
}

/// The item of `list` (a `significance.json` array) about `entry`.
fn about<'a>(list: &'a Value, entry: &str) -> Option<&'a Value> {
    (list.as_array().unwrap().iter()).find(|item| item["entry"] == entry)
}

#[test]
fn each_entry_is_compared_with_its_own_baseline() {
    let tmp = tempfile::tempdir().unwrap();
    let (file, out) = (tmp.path().join("study.toml"), tmp.path().join("out"));
    fs::write(&file, TWO_BASELINES).unwrap();
    let study = StudyConfig::load(&file).unwrap();
    let options = StudyOptions {
        threads: 2,
        progress: false,
        shard: None,
        stop: None,
    };
    run_study(&study, &out, &options).unwrap();

    let significance = read_json(&out.join("significance.json"));
    let gains = &significance["gains"];
    let names: Vec<&str> = (gains.as_array().unwrap().iter())
        .map(|g| g["entry"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["adhoc-td", "adhoc-td-dqn"],
        "baselines have no gain"
    );
    for (entry, baseline, other) in [
        ("adhoc-td", "no-advice", "no-advice-dqn"),
        ("adhoc-td-dqn", "no-advice-dqn", "no-advice"),
    ] {
        let gain = about(gains, entry).unwrap();
        assert_eq!(gain["baseline"], baseline);
        let mean = |key: &str| gain[key]["mean"].as_f64().unwrap();
        let (own, wrong) = (
            gain_by_hand(&out, (entry, baseline), last_ten),
            gain_by_hand(&out, (entry, other), last_ten),
        );
        assert!(
            (mean("last_ten_gain") - own).abs() < 1e-9,
            "{entry}: {gain}"
        );
        assert!(
            (own - wrong).abs() > 1e-9,
            "{entry}: the two baselines must differ for the test to tell them apart"
        );
        let jumpstart = gain_by_hand(&out, (entry, baseline), first);
        assert!(
            (mean("first_gain") - jumpstart).abs() < 1e-9,
            "{entry}: {gain}"
        );
        assert_eq!(
            about(&significance["holm"], entry).unwrap()["baseline"],
            baseline
        );
    }
    let aggregate = &significance["aggregate"];
    assert_eq!(aggregate["baseline"], Value::Null, "several baselines");
    let own = |entry: &str| about(&aggregate["entries"], entry).unwrap()["baseline"].clone();
    assert_eq!(
        [own("no-advice"), own("adhoc-td-dqn"), own("no-advice-dqn")],
        [Value::Null, "no-advice-dqn".into(), Value::Null]
    );
    let improvement = |entry: &str| {
        about(&aggregate["entries"], entry).unwrap()["last_ten"]
            .get("p_improvement")
            .is_some()
    };
    assert!(improvement("adhoc-td-dqn") && !improvement("no-advice-dqn"));

    let report = fs::read_to_string(out.join("REPORT.md")).unwrap();
    for line in [
        "## First evaluation",
        "## Gains over the baselines",
        "## Significance against the baselines",
        "| algorithm | baseline | gain: last ten |",
        "| no-advice-dqn | *baseline* | - | - | - |",
        "| adhoc-td-dqn | no-advice-dqn | ",
        "| adhoc-td | no-advice | ",
        "Each method's goal percentage minus its baseline's, paired by run",
    ] {
        assert!(report.contains(line), "no {line:?} in\n{report}");
    }
    assert!(!report.contains("`no-advice`"), "{report}");
    let difference = fs::read_to_string(out.join("figures/goal_pct_difference.svg")).unwrap();
    assert!(difference.contains("minus its baseline"));

    // The analysis refuses a study.json whose baselines cannot be.
    let path = out.join("study.json");
    let mut chained = read_json(&path);
    chained["entry"][2]["baseline"] = "adhoc-td".into();
    fs::write(&path, chained.to_string()).unwrap();
    let e = analysis::files::read_study(&out).unwrap_err().to_string();
    assert!(
        e.contains("`entry[2].baseline`") && e.contains("'no-advice-dqn' is a baseline itself"),
        "{e}"
    );
}

#[test]
fn a_baseline_that_cannot_be_is_refused_in_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let dqn = "name = \"no-advice-dqn\"\n";
    for (from, to, needle) in [
        (
            "baseline = \"no-advice-dqn\"",
            "baseline = \"none-such\"",
            "`entry[3].baseline`: no entry is named 'none-such'",
        ),
        (
            "baseline = \"no-advice-dqn\"",
            "baseline = \"adhoc-td-dqn\"",
            "'adhoc-td-dqn' is this entry",
        ),
        // A chain: no-advice-dqn is adhoc-td-dqn's baseline, and one of its own.
        (
            dqn,
            &format!("{dqn}baseline = \"no-advice\"\n"),
            "`entry[2].baseline`: 'no-advice-dqn' is a baseline itself (that of 'adhoc-td-dqn')",
        ),
    ] {
        let text = TWO_BASELINES.replace(from, to);
        let file = tmp.path().join("bad.toml");
        fs::write(&file, text).unwrap();
        let output = Command::new(env!("CARGO_BIN_EXE_coordinator"))
            .args(["study", "--quiet", "--config"])
            .arg(&file)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
        assert!(stderr.contains(needle), "{needle:?} not in {stderr}");
        assert!(!out.exists(), "nothing written");
    }
}
