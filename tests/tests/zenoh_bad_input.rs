//! The coordinator's zenoh transport refuses bad network settings with one
//! line and exit code 2, leaving no process behind.

use std::process::Command;

use integration_tests::bin;
use node::net::free_port;

fn refused(args: &[&str], needle: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let output = Command::new(bin("coordinator"))
        .args([
            "run",
            "--algorithm",
            "no-advice",
            "--runs",
            "1",
            "--episodes",
            "20",
        ])
        .args([
            "--transport",
            "zenoh",
            "--quiet",
            "--startup-timeout",
            "10",
            "--out",
        ])
        .arg(&out)
        .args(args)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{args:?}: {stderr}");
    assert!(
        stderr.starts_with("error:") && stderr.contains(needle),
        "{args:?}: {stderr}"
    );
}

#[test]
fn a_port_in_use_is_refused() {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = listener.local_addr().unwrap().port().to_string();
    refused(&["--port", &port], &port);
}

#[test]
fn an_unreachable_router_is_refused() {
    let endpoint = format!("tcp/127.0.0.1:{}", free_port().unwrap());
    refused(
        &["--attach", "--connect", &endpoint, "--no-auth"],
        &endpoint,
    );
}

#[test]
fn attaching_without_a_secret_is_refused() {
    let endpoint = format!("tcp/127.0.0.1:{}", free_port().unwrap());
    refused(
        &["--attach", "--connect", &endpoint],
        "--attach needs --secret-file",
    );
    let tmp = tempfile::tempdir().unwrap();
    let open = tmp.path().join("secret");
    std::fs::write(&open, "adv:x\n").unwrap();
    let open = open.display().to_string();
    refused(&["--attach", "--secret-file", &open], "expected 600");
}

#[test]
fn a_bad_experiment_name_is_refused() {
    refused(&["--experiment", "no/slashes"], "experiment");
}
