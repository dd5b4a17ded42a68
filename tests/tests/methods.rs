//! The field's methods since 2017 in mixed teams, over both transports and
//! under network conditions: each agent of a team runs its own method, and
//! advice (actions and shared values) crosses between them as real
//! processes over zenoh as it does in process.

use std::path::Path;

use integration_tests::team_run;
use serde_json::Value;

/// Two mixed teams covering every method since 2017; the first agent of
/// each under network conditions.
const TEAMS: [[&str; 3]; 2] = [
    ["psaf", "rcmp", "peer-learning"],
    ["advice-reuse", "early-advising", "random-advising"],
];

/// A team file of `methods`, the first agent's advice messages lost with
/// probability 0.1 and delayed 1 to 3 ms.
fn team_file(dir: &Path, methods: &[&str]) -> std::path::PathBuf {
    let mut text = String::new();
    for (i, method) in methods.iter().enumerate() {
        text.push_str(&format!("[[agent]]\nalgorithm = \"{method}\"\n"));
        if i == 0 {
            text.push_str("network = { latency = \"uniform:1,3\", loss = 0.1, timeout_ms = 20 }\n");
        }
        text.push('\n');
    }
    let path = dir.join(format!("{}.toml", methods[0]));
    std::fs::write(&path, text).unwrap();
    path
}

/// Every agent's counters at the last evaluation of one run of `team`.
fn last_counters(team: &Path, transport: &str, out: &Path) -> Vec<Value> {
    let schedule = [
        "--episodes",
        "120",
        "--eval-every",
        "60",
        "--eval-episodes",
        "10",
    ];
    let run = team_run(team, transport, &schedule, out);
    let points = run["points"].as_array().unwrap();
    points.last().unwrap()["agents"].as_array().unwrap().clone()
}

#[test]
fn every_method_advises_in_a_mixed_team_over_both_transports() {
    let tmp = tempfile::tempdir().unwrap();
    for methods in TEAMS {
        let team = team_file(tmp.path(), &methods);
        for transport in ["in-process", "zenoh"] {
            let out = tmp.path().join(format!("{}-{transport}", methods[0]));
            let agents = last_counters(&team, transport, &out);
            for (method, counters) in methods.iter().zip(&agents) {
                let count = |key: &str| counters[key].as_u64().unwrap();
                let said = format!("{method} over {transport}: {counters}");
                assert!(count("advice_requests") > 0, "asked nothing: {said}");
                assert!(
                    count("advice_replies_received") > 0,
                    "heard nothing: {said}"
                );
                assert!(count("advice_given") > 0, "answered nothing: {said}");
            }
        }
    }
}
