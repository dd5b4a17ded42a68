//! The analysis's files: a study directory read (its `study.json`, each
//! entry's `config.json` and finished runs), the report written, each
//! file at once (`node::files`).

use std::fs;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::error::Error;
use crate::results::RunResult;
use crate::study::{EntryResults, Study};

/// A study directory's record of what it ran.
const STUDY_FILE: &str = "study.json";

/// Reads `dir`'s study and every entry's finished runs (`run-<k>.json`),
/// summarised at the study's level.
pub fn read_study(dir: &Path) -> Result<(Study, Vec<EntryResults>), Error> {
    let study: Study = read_json(&dir.join(STUDY_FILE))?;
    let level = study.ci_level();
    let entries = (study.entries.iter())
        .map(|entry| {
            let at = dir.join(&entry.name);
            let config: Value = read_json(&at.join("config.json"))?;
            let runs = read_runs(&at)?;
            Ok(EntryResults::new(entry.clone(), config, runs, level))
        })
        .collect::<Result<_, Error>>()?;
    Ok((study, entries))
}

/// Every finished run in an entry's directory, by index.
fn read_runs(dir: &Path) -> Result<Vec<RunResult>, Error> {
    let finished = |name: &str| name.starts_with("run-") && name.ends_with(".json");
    let mut runs = Vec::new();
    for (path, text) in read_matching(dir, finished)? {
        runs.push(
            serde_json::from_str::<RunResult>(&text)
                .map_err(|e| Error::invalid(&path, e.to_string()))?,
        );
    }
    if runs.is_empty() {
        return Err(Error::invalid(dir, "no finished run (run-<k>.json)"));
    }
    runs.sort_by_key(|r| r.run);
    Ok(runs)
}

/// The files of `dir` whose names `matches` accepts, with their text.
pub(crate) fn read_matching(
    dir: &Path,
    matches: impl Fn(&str) -> bool,
) -> Result<Vec<(PathBuf, String)>, Error> {
    let listing = fs::read_dir(dir).map_err(|e| Error::io("read", dir, e))?;
    let mut files = Vec::new();
    for file in listing {
        let path = file.map_err(|e| Error::io("read", dir, e))?.path();
        if path
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(&matches)
        {
            let text = fs::read_to_string(&path).map_err(|e| Error::io("read", &path, e))?;
            files.push((path, text));
        }
    }
    Ok(files)
}

/// A JSON file as a `T`.
fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, Error> {
    let bytes = fs::read(path).map_err(|e| Error::io("read", path, e))?;
    serde_json::from_slice(&bytes).map_err(|e| Error::invalid(path, e.to_string()))
}

/// Writes `value` as pretty JSON with a final newline, at once.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<(), Error> {
    let mut bytes = serde_json::to_vec_pretty(value).expect("results serialise");
    bytes.push(b'\n');
    write(path, &bytes)
}

/// Writes `bytes` to `path` at once: a reader sees the old file or the new.
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    node::files::write_atomically(path, bytes).map_err(|e| Error::io("write", path, e))
}

/// Creates `dir` and its parents.
pub fn create_dir(dir: &Path) -> Result<(), Error> {
    fs::create_dir_all(dir).map_err(|e| Error::io("create", dir, e))
}
