//! `analyse DIR --publish DEST` refuses, in one line and with exit code 2,
//! a DEST that holds another study, and leaves it as it was.

use std::fs;
use std::process::Command;

#[test]
fn publishing_into_another_study_is_refused_in_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let (dir, dest) = (tmp.path().join("study"), tmp.path().join("other"));
    let study = |name: &str| {
        format!(
            r#"{{"name": "{name}", "runs": 1, "episodes": 20, "eval_every": 10,
                "eval_episodes": 5, "transport": "in-process",
                "entry": [{{"name": "a", "algorithm": "no-advice"}}]}}"#
        )
    };
    fs::create_dir(&dir).unwrap();
    fs::write(dir.join("study.json"), study("mine")).unwrap();
    fs::create_dir(&dest).unwrap();
    fs::write(dest.join("study.json"), study("theirs")).unwrap();

    let out = Command::new(env!("CARGO_BIN_EXE_analyse"))
        .arg(&dir)
        .arg("--publish")
        .arg(&dest)
        .output()
        .unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: ")
            && stderr.contains("holds another study")
            && stderr.contains("`name`")
            && stderr.contains("expected a new or empty directory"),
        "{stderr}"
    );
    assert_eq!(
        fs::read_to_string(dest.join("study.json")).unwrap(),
        study("theirs")
    );
    assert_eq!(fs::read_dir(&dest).unwrap().count(), 1);
}
