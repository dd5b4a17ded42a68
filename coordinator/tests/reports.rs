//! Every study report under docs/ was played with the settings its study
//! gives today (its preset's, or its own `study.json`'s), or says in its
//! first lines that it was not.

use std::fs;
use std::path::{Path, PathBuf};

use coordinator::study::StudyConfig;
use serde_json::Value;

/// The lines of a report that must say so when its settings are not
/// today's.
const FIRST_LINES: usize = 10;

/// Every `REPORT.md` under `dir`.
fn reports(dir: &Path, into: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            reports(&path, into);
        } else if path.file_name().is_some_and(|n| n == "REPORT.md") {
            into.push(path);
        }
    }
}

/// Whether a report says, in a note among its first lines, that it was
/// played with other settings (a quoted line saying what it was played
/// with).
fn says_its_settings_differ(report: &str) -> bool {
    report.lines().take(FIRST_LINES).any(|line| {
        let line = line.to_lowercase();
        line.starts_with("> ") && line.contains("played with")
    })
}

/// What of an experiment's recorded configuration are its settings: all
/// but how many runs, where they ran and the paths of the snapshots.
fn settings(config: &Value) -> Value {
    let mut config = config.clone();
    let Some(map) = config.as_object_mut() else {
        return config;
    };
    for key in ["runs", "transport", "ci_level"] {
        map.remove(key);
    }
    for agent in (map.get_mut("team").and_then(Value::as_array_mut))
        .into_iter()
        .flatten()
    {
        if let Some(agent) = agent.as_object_mut() {
            agent.remove("load");
        }
    }
    config
}

/// The first difference between the settings of `dir`'s entries as
/// recorded and as their study gives them today, or why they cannot be
/// compared.
fn difference(dir: &Path) -> Option<String> {
    let Ok(text) = fs::read_to_string(dir.join("study.json")) else {
        return Some("it keeps no study.json to hold it against".into());
    };
    let recorded: StudyConfig = match serde_json::from_str(&text) {
        Ok(study) => study,
        Err(e) => return Some(format!("its study.json does not read today: {e}")),
    };
    // A preset's study is today's preset; another's is its study.json.
    let study = StudyConfig::preset(&recorded.name).unwrap_or(recorded);
    for entry in &study.entries {
        let path = dir.join(&entry.name).join("config.json");
        let Ok(text) = fs::read_to_string(&path) else {
            return Some(format!("it keeps no {}", path.display()));
        };
        let file: Value = serde_json::from_str(&text).unwrap();
        let today = serde_json::to_value(study.experiment(entry, None)).unwrap();
        let (then, now) = (settings(&file["config"]), settings(&today));
        if then != now {
            return Some(format!(
                "entry {}: played with {then}, today {now}",
                entry.name
            ));
        }
    }
    None
}

#[test]
fn every_report_was_played_with_todays_settings_or_says_so() {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs");
    let mut found = Vec::new();
    reports(&docs, &mut found);
    found.sort();
    assert!(!found.is_empty(), "no report under {}", docs.display());
    let stale: Vec<String> = (found.iter())
        .filter(|report| !says_its_settings_differ(&fs::read_to_string(report).unwrap()))
        .filter_map(|report| {
            let why = difference(report.parent().unwrap())?;
            Some(format!("{}: {why}", report.display()))
        })
        .collect();
    assert!(
        stale.is_empty(),
        "reports played with settings other than their study's today, without a note in their \
         first {FIRST_LINES} lines (\"> Played with ...\") saying so; play them again or add the \
         note:\n{}",
        stale.join("\n")
    );
}

#[test]
fn a_note_on_other_settings_is_read_where_it_stands() {
    let note = "# Study `x`\n\n> Played with v_g 0.4, the profile's value then.\n";
    assert!(says_its_settings_differ(note));
    let late = format!("{}> Played with v_g 0.4.\n", "line\n".repeat(FIRST_LINES));
    assert!(!says_its_settings_differ(&late));
    assert!(!says_its_settings_differ(
        "# Study\n\nPlayed with commit `abc`.\n"
    ));
}
