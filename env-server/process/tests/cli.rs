//! The `env-server` command line: JSON summaries and one-line errors with exit code 2.

use std::process::{Command, Output};

fn env_server(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_env-server"))
        .args(args)
        .output()
        .expect("env-server runs")
}

#[test]
fn rollout_prints_the_json_summary() {
    let out = env_server(&[
        "rollout",
        "--policy",
        "random",
        "--episodes",
        "20",
        "--seed",
        "3",
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(v["episodes"], 20);
    let o = &v["outcomes"];
    let total: u64 = ["goal", "captured", "out_of_bounds", "out_of_time"]
        .iter()
        .map(|k| o[k].as_u64().expect("count"))
        .sum();
    assert_eq!(total, 20);
    for key in [
        "goal_pct",
        "mean_frames",
        "mean_frames_to_goal",
        "frames_per_sec",
    ] {
        assert!(v[key].is_number(), "{key}");
    }
}

#[test]
fn bad_input_is_one_line_and_exit_code_2() {
    let cases: [(&[&str], &str); 5] = [
        (
            &["rollout", "--policy", "juggle"],
            "random, shoot, dribble, pass, uniform",
        ),
        (&["rollout", "--episodes", "0"], "at least 1"),
        (&["rollout", "--offense", "5"], "1..=4"),
        (
            &["render", "--out", "/nonexistent-dir/x.svg"],
            "/nonexistent-dir/x.svg",
        ),
        (&["render", "--out", "picture.gif"], ".svg, .png or .rcg"),
    ];
    for (args, needle) in cases {
        let out = env_server(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}
