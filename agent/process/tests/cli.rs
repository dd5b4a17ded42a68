//! Bad input makes the `agent` binary print one clear line and exit 2.

mod support;

use std::net::TcpListener;
use std::time::Duration;

use node::net::free_port;
use support::Guard;

/// One case a few lines long for every kind of bad input, in one test so
/// that the cases share the busy port and the unreachable endpoint.
#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let busy = TcpListener::bind("127.0.0.1:0").unwrap();
    let busy_port = busy.local_addr().unwrap().port();
    let listen_busy = format!("tcp/127.0.0.1:{busy_port}");
    let nobody = format!("tcp/127.0.0.1:{}", free_port().unwrap());
    let ok = [
        "--experiment",
        "e",
        "--id",
        "0",
        "--team-size",
        "2",
        "--no-auth",
    ];
    let dir = tempfile::tempdir().unwrap();
    let open_secret = dir.path().join("secret");
    std::fs::write(&open_secret, "adv:x\n").unwrap();
    let open_secret = open_secret.display().to_string();
    let cases: Vec<(Vec<&str>, String)> = vec![
        (
            [&ok[..], &["--listen", &listen_busy]].concat(),
            format!("{busy_port}: Address already in use"),
        ),
        (
            [&ok[..], &["--connect", &nobody]].concat(),
            format!("Unable to connect to any of [Single({nobody})]"),
        ),
        (
            [&ok[..], &["--listen", "foo"]].concat(),
            "invalid network settings (listen foo".into(),
        ),
        (
            vec![
                "--experiment",
                "a/b",
                "--id",
                "0",
                "--team-size",
                "2",
                "--no-auth",
            ],
            "invalid experiment name 'a/b'".into(),
        ),
        (
            vec![
                "--experiment",
                "e",
                "--id",
                "2",
                "--team-size",
                "2",
                "--no-auth",
            ],
            "agent id 2 is not below the team size 2".into(),
        ),
        (
            vec![
                "--experiment",
                "e",
                "--id",
                "0",
                "--team-size",
                "0",
                "--no-auth",
            ],
            "--team-size".into(),
        ),
        (
            vec!["--id", "0", "--team-size", "2", "--no-auth"],
            "--experiment".into(),
        ),
        (
            vec![
                "--experiment",
                "e",
                "--id",
                "first",
                "--team-size",
                "2",
                "--no-auth",
            ],
            "--id".into(),
        ),
        (ok[..6].to_vec(), "--secret-file".into()),
        (
            [&ok[..6], &["--secret-file", &open_secret]].concat(),
            "mode 644); expected 600".into(),
        ),
    ];
    // All at once: the unreachable endpoint takes the connect timeout (5 s).
    let mut running: Vec<(Guard, &Vec<&str>, &String)> = cases
        .iter()
        .map(|(args, expected)| (Guard::agent(args), args, expected))
        .collect();
    for (agent, args, expected) in &mut running {
        let status = agent.wait_exit(Duration::from_secs(20));
        assert_eq!(status.map(|s| s.code()), Some(Some(2)), "{args:?}");
        let stderr = agent.stderr();
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
        assert!(stderr.contains(expected.as_str()), "{args:?}: {stderr}");
        assert!(!stderr.contains(".rs:"), "{args:?}: {stderr}");
    }
    drop(busy);
}
