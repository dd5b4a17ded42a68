//! The results' format version held to the files' keys: every key and
//! column `config.json`, `run-<k>.csv`, `run-<k>.json` and `summary.json`
//! can hold, made by the code that writes them, is recorded with
//! `RESULTS_FORMAT_VERSION` in `tests/results-format.json`. A key added or
//! removed without the version rising fails here, and so does a version
//! that rose without the record following it.
//!
//! After raising the version (and saying what changed in docs/results.md,
//! "Format versions"), write the record anew:
//! `ADV_BLESS=1 cargo test -p coordinator --test results_format`.

use std::collections::BTreeSet;
use std::fs;
use std::path::Path;

use agent::{AgentConfig, Algorithm, LearnerSettings, NetworkConditions, Profile};
use analysis::{
    AgentStats, EvalPoint, Join, PlayedWith, Restart, RunResult, SimulatorRestart, Timing,
};
use coordinator::config::ChildSpec;
use coordinator::experiment::{RESULTS_FORMAT_VERSION, Record};
use coordinator::membership::MembershipEvent;
use coordinator::plugin::PluginSpec;
use coordinator::{AgentSpec, ExperimentConfig, Transport, ZenohSettings, summarize};
use proto::Simulator;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// Where the keys of the current version are recorded.
const RECORD: &str = "tests/results-format.json";

/// A version and its keys.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
struct Format {
    version: u32,
    keys: BTreeSet<String>,
}

/// Every key path of `value` under `file`, arrays' items as `[]`.
fn keys_of(value: &Value, at: String, into: &mut BTreeSet<String>) {
    match value {
        Value::Object(map) => {
            for (key, v) in map {
                let path = format!("{at}.{key}");
                into.insert(path.clone());
                keys_of(v, path, into);
            }
        }
        Value::Array(items) => items
            .iter()
            .for_each(|v| keys_of(v, format!("{at}[]"), into)),
        _ => {}
    }
}

/// A team with every kind of agent table: every algorithm, every optional
/// setting of each given, every learner, a learner process, a snapshot.
fn every_agent() -> Vec<AgentSpec> {
    let mut team: Vec<AgentSpec> = Algorithm::all()
        .map(|algorithm| {
            let mut config = AgentConfig {
                network: Some(NetworkConditions::default()),
                ..AgentConfig::of(algorithm, Profile::Paper)
            };
            for (key, value) in config.algorithm.settings() {
                match value {
                    // An unset option: a fraction where one is taken, else 1.
                    Value::Null => (config.algorithm.set(&key, Value::from(0.1)))
                        .or_else(|_| config.algorithm.set(&key, Value::from(1)))
                        .unwrap(),
                    Value::Bool(false) => config.algorithm.set(&key, Value::Bool(true)).unwrap(),
                    _ => continue,
                }
            }
            AgentSpec {
                config,
                ..AgentSpec::default()
            }
        })
        .collect();
    team.push(AgentSpec {
        config: AgentConfig {
            learner: LearnerSettings::named("ensemble").unwrap(),
            advises: "worst".parse().unwrap(),
            announce_exhausted: true,
            ..AgentConfig::default()
        },
        load: Some("expert.snapshot".into()),
        keep_counters: true,
        learner: Some(ChildSpec {
            command: vec!["python3".into(), "learner.py".into()],
            dir: Some("learners".into()),
            source: Some("learner.py".into()),
            source_fnv64: Some("0123456789abcdef".into()),
        }),
        strategy_process: Some(ChildSpec {
            command: vec!["python3".into(), "strategy.py".into()],
            ..ChildSpec::default()
        }),
        plugin: Some(PluginSpec {
            learner: Some("mine 1".into()),
            strategy: Some("mine 1".into()),
        }),
    });
    team
}

/// A run with every optional part: advice, restarts, a join, what played it.
fn every_run(config: &ExperimentConfig) -> RunResult {
    let agents = config.team.len();
    let points = (config.eval_points().into_iter())
        .map(|episode| EvalPoint {
            episode,
            episodes: 1,
            goals: 1,
            goal_pct: 100.0,
            time_to_goal: Some(50.0),
            agents: vec![AgentStats::default(); agents],
            spent_budget: 0.0,
            actions_timed_out: 0,
        })
        .collect();
    RunResult {
        run: 0,
        points,
        timing: Timing::default(),
        advice_rtt_ms: vec![vec![1.5]; agents],
        advice_matrix: vec![vec![1; agents]; agents],
        restarts: vec![Restart {
            slot: 1,
            episode: 1,
            snapshot: Some(0),
            replayed: true,
            wait_ms: 1,
            cause: "lost".into(),
        }],
        simulator_restarts: vec![SimulatorRestart {
            episode: 1,
            evaluation: false,
            lost_ms: 1,
            cause: "down".into(),
        }],
        joins: vec![Join {
            episode: 1,
            slot: 0,
            event: 0,
            wait_ms: 0,
        }],
        played_with: Some(PlayedWith {
            commit: "0123456789ab".into(),
            simulator: Simulator::Ours,
            fingerprint: Some("0123456789abcdef".into()),
        }),
    }
}

/// Every key and column the four files can hold, each under its file.
fn current_keys() -> BTreeSet<String> {
    let mut config = ExperimentConfig {
        runs: 1,
        episodes: 10,
        eval_every: 10,
        eval_episodes: 1,
        transport: Transport::Zenoh(ZenohSettings {
            restart_agents: true,
            snapshot_every: 7,
            simulator: Simulator::RealHfo,
            ..ZenohSettings::default()
        }),
        team: every_agent(),
        ..ExperimentConfig::default()
    };
    config.events = vec![MembershipEvent {
        episode: 1,
        slot: 0,
        newcomer: Some(config.team[0].clone()),
    }];
    let record = Record {
        format: RESULTS_FORMAT_VERSION,
        config: &config,
        snapshot_digests: vec![Some("0123456789abcdef".into()); config.team.len()],
    };
    let run = every_run(&config);
    let summary = summarize(&record, std::slice::from_ref(&run));
    let mut keys = BTreeSet::new();
    keys_of(
        &serde_json::to_value(&record).unwrap(),
        "config.json".into(),
        &mut keys,
    );
    keys_of(
        &serde_json::to_value(&run).unwrap(),
        "run-<k>.json".into(),
        &mut keys,
    );
    keys_of(
        &serde_json::to_value(&summary).unwrap(),
        "summary.json".into(),
        &mut keys,
    );
    for column in csv_columns() {
        keys.insert(format!("run-<k>.csv.{column}"));
    }
    keys
}

/// The columns of a run's CSV, as a real run writes them (each agent's
/// column as `<name>_<i>`).
fn csv_columns() -> Vec<String> {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_coordinator"))
        .args([
            "run",
            "--algorithm",
            "adhoc-td",
            "--runs",
            "1",
            "--episodes",
            "2",
        ])
        .args([
            "--eval-every",
            "1",
            "--eval-episodes",
            "1",
            "--transport",
            "in-process",
        ])
        .args(["--quiet", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let csv = fs::read_to_string(out.join("run-0.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    let agent = |c: &str| match c.rsplit_once('_') {
        Some((name, i)) if i.parse::<usize>().is_ok() => format!("{name}_<i>"),
        _ => c.to_owned(),
    };
    let mut columns: Vec<String> = header.split(',').map(agent).collect();
    columns.dedup();
    columns
}

#[test]
fn the_results_format_version_rises_with_its_keys() {
    let current = Format {
        version: RESULTS_FORMAT_VERSION,
        keys: current_keys(),
    };
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(RECORD);
    if std::env::var_os("ADV_BLESS").is_some() {
        let json = serde_json::to_string_pretty(&current).unwrap();
        fs::write(&path, json + "\n").unwrap();
        return;
    }
    let recorded: Format = serde_json::from_str(&fs::read_to_string(&path).unwrap()).unwrap();
    let added: Vec<&String> = current.keys.difference(&recorded.keys).collect();
    let removed: Vec<&String> = recorded.keys.difference(&current.keys).collect();
    assert!(
        recorded.version != current.version || (added.is_empty() && removed.is_empty()),
        "the results' keys changed but RESULTS_FORMAT_VERSION is still {}: added {added:?}, \
         removed {removed:?}. Raise it (coordinator/src/experiment.rs), say what changed in \
         docs/results.md (\"Format versions\"), then write {RECORD} anew: ADV_BLESS=1 cargo test \
         -p coordinator --test results_format",
        current.version
    );
    assert_eq!(
        recorded, current,
        "RESULTS_FORMAT_VERSION is {} but {RECORD} records version {}: write it anew with \
         ADV_BLESS=1 cargo test -p coordinator --test results_format",
        current.version, recorded.version
    );
}
