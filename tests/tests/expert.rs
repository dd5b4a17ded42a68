//! The expert scenario over both transports: an agent starting from a saved
//! snapshot brings its spent give budget along only with `keep_counters`,
//! the same whether the team plays in process or as processes over zenoh.

use std::path::Path;
use std::process::Command;

use integration_tests::bin;

/// Runs the coordinator with `args`, failing the test if it fails.
fn coordinator(args: &[&str], out: &Path) {
    let output = Command::new(bin("coordinator"))
        .args(args)
        .args(["--quiet", "--out"])
        .arg(out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// The value of `column` at evaluation point `episode` of `out`'s run 0.
fn value_at(out: &Path, episode: u64, column: &str) -> u64 {
    let text = std::fs::read_to_string(out.join("run-0.csv")).unwrap();
    let mut lines = text.lines().map(|l| l.split(',').collect::<Vec<_>>());
    let header = lines.next().unwrap();
    let at = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (episode_at, column_at) = (at("episode"), at(column));
    let row = lines
        .find(|row| row[episode_at] == episode.to_string())
        .unwrap_or_else(|| panic!("no evaluation at episode {episode}: {text}"));
    row[column_at].parse().unwrap()
}

#[test]
fn an_expert_keeps_its_spent_budget_only_with_keep_counters_over_both_transports() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    // Pretraining: after 200 episodes with this seed, agent 2 has given advice.
    let agents = dir.join("agents");
    let pretrain: Vec<&str> = "run --algorithm adhoc-td --runs 1 --episodes 200 --eval-every 200 \
                               --eval-episodes 1 --seed 3 --transport in-process --save-agents"
        .split_whitespace()
        .chain([agents.to_str().unwrap()])
        .collect();
    coordinator(&pretrain, &dir.join("pretrain"));
    let spent = value_at(&dir.join("pretrain"), 200, "give_spent_2");
    assert!(spent > 0, "the expert must have spent some give budget");

    for keep_counters in [true, false] {
        let team = dir.join(format!("team-{keep_counters}.toml"));
        let adhoc = "[[agent]]\nalgorithm = \"ad-hoc-td\"\n";
        std::fs::write(
            &team,
            format!(
                "{adhoc}{adhoc}{adhoc}load = \"agents/run-0-agent-2.snapshot\"\nkeep_counters = {keep_counters}\n"
            ),
        )
        .unwrap();
        let mut seen = Vec::new();
        for transport in ["in-process", "zenoh"] {
            let out = dir.join(format!("expert-{keep_counters}-{transport}"));
            let args: Vec<&str> = [
                "run",
                "--team",
                team.to_str().unwrap(),
                "--transport",
                transport,
            ]
            .into_iter()
            .chain("--runs 1 --episodes 2 --eval-every 2 --eval-episodes 1".split(' '))
            .collect();
            coordinator(&args, &out);
            seen.push(value_at(&out, 0, "give_spent_2"));
        }
        let expected = if keep_counters { spent } else { 0 };
        assert_eq!(
            seen,
            [expected, expected],
            "keep_counters = {keep_counters}: in-process, zenoh"
        );
    }
}
