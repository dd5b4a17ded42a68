//! Open teams: a newcomer takes a slot during training while the others
//! keep learning, in process (bit for bit reproducible) and over zenoh (the
//! leaver's process stops, the newcomer is a new process joining the
//! running experiment).

use std::path::Path;
use std::process::Command;

use integration_tests::bin;
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
    let output = Command::new(bin("coordinator"))
        .args(["run", "--team"])
        .arg(team)
        .args(["--runs", "1", "--episodes", "120", "--eval-every", "30"])
        .args([
            "--eval-episodes",
            "5",
            "--transport",
            transport,
            "--quiet",
            "--out",
        ])
        .arg(out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{transport}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let mut run: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run-0.json")).unwrap()).unwrap();
    run.as_object_mut().unwrap().remove("timing");
    run
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
