//! The analysis's files: a study directory read (its `study.json`, each
//! entry's `config.json` and finished runs, plain or gzipped as a
//! published study holds them), the report written, each file at once
//! (`node::files`).

use std::fs;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use flate2::Compression;
use flate2::read::MultiGzDecoder;
use serde_json::Value;

use crate::error::Error;
use crate::results::RunResult;
use crate::study::{EntryResults, Study};

/// A study directory's record of what it ran.
pub const STUDY_FILE: &str = "study.json";

/// The suffix of a gzipped file: `run-<k>.json.gz` is `run-<k>.json`
/// compressed.
pub const GZ: &str = ".gz";

/// Reads `dir`'s study and every entry's finished runs (`run-<k>.json`),
/// summarised at the study's level.
pub fn read_study(dir: &Path) -> Result<(Study, Vec<EntryResults>), Error> {
    let path = dir.join(STUDY_FILE);
    let study: Study = read_json(&path)?;
    (study.check_baselines())
        .map_err(|e| Error::invalid(&path, format!("`{}`: {}", e.key, e.reason)))?;
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

/// Every finished run in an entry's directory, by index: `run-<k>.json`,
/// else `run-<k>.json.gz`.
fn read_runs(dir: &Path) -> Result<Vec<RunResult>, Error> {
    let mut runs = Vec::new();
    for (_, name) in finished_runs(dir)? {
        let path = dir.join(name);
        let bytes = read_maybe_gzipped(&path)?;
        runs.push(
            serde_json::from_slice::<RunResult>(&bytes)
                .map_err(|e| Error::invalid(&path, e.to_string()))?,
        );
    }
    if runs.is_empty() {
        return Err(Error::invalid(
            dir,
            "no finished run (run-<k>.json or run-<k>.json.gz)",
        ));
    }
    runs.sort_by_key(|r| r.run);
    Ok(runs)
}

/// The finished runs in an entry's directory, by index, each with the file
/// that holds it: `run-<k>.json`, else (in a published study)
/// `run-<k>.json.gz`.
pub fn finished_runs(dir: &Path) -> Result<Vec<(u64, String)>, Error> {
    let listing = fs::read_dir(dir).map_err(|e| Error::io("read", dir, e))?;
    let mut runs = std::collections::BTreeMap::new();
    for file in listing {
        let name = file.map_err(|e| Error::io("read", dir, e))?.file_name();
        let Some(name) = name.to_str() else { continue };
        let (stem, gzipped) = match name.strip_suffix(GZ) {
            Some(stem) => (stem, true),
            None => (name, false),
        };
        let Some(k) = (stem.strip_prefix("run-"))
            .and_then(|rest| rest.strip_suffix(".json"))
            .filter(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|k| k.parse::<u64>().ok())
        else {
            continue;
        };
        // The plain file wins over its compressed copy.
        if !gzipped || !runs.contains_key(&k) {
            runs.insert(k, name.to_owned());
        }
    }
    Ok(runs.into_iter().collect())
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
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, Error> {
    let bytes = read(path)?;
    serde_json::from_slice(&bytes).map_err(|e| Error::invalid(path, e.to_string()))
}

/// A file's bytes.
pub fn read(path: &Path) -> Result<Vec<u8>, Error> {
    fs::read(path).map_err(|e| Error::io("read", path, e))
}

/// A file's bytes, decompressed when its name ends in `.gz`.
pub fn read_maybe_gzipped(path: &Path) -> Result<Vec<u8>, Error> {
    let bytes = read(path)?;
    if !path.to_str().is_some_and(|p| p.ends_with(GZ)) {
        return Ok(bytes);
    }
    let mut plain = Vec::new();
    MultiGzDecoder::new(&bytes[..])
        .read_to_end(&mut plain)
        .map_err(|e| Error::invalid(path, format!("is not a readable gzip file: {e}")))?;
    Ok(plain)
}

/// `bytes` gzipped, the same bytes every time: the header holds no time
/// and no file name.
pub fn gzip(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    let mut encoder = flate2::GzBuilder::new()
        .mtime(0)
        .write(Vec::new(), Compression::best());
    encoder.write_all(bytes)?;
    encoder.finish()
}

/// The names of the entries of `dir`, sorted; none when `dir` is absent.
pub fn list(dir: &Path) -> Result<Vec<String>, Error> {
    let listing = match fs::read_dir(dir) {
        Ok(listing) => listing,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(Error::io("read", dir, e)),
    };
    let mut names = Vec::new();
    for file in listing {
        let name = file.map_err(|e| Error::io("read", dir, e))?.file_name();
        names.push(name.to_string_lossy().into_owned());
    }
    names.sort();
    Ok(names)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::run_with_goals;

    #[test]
    fn runs_read_plain_else_gzipped_and_a_broken_gzip_is_named() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let json = |k, goal| serde_json::to_vec(&run_with_goals(k, 20, &[goal])).unwrap();
        fs::write(dir.join("run-0.json"), json(0, 10.0)).unwrap();
        fs::write(dir.join("run-0.json.gz"), gzip(&json(0, 90.0)).unwrap()).unwrap();
        fs::write(dir.join("run-1.json.gz"), gzip(&json(1, 20.0)).unwrap()).unwrap();
        fs::write(dir.join("run-1.csv.gz"), gzip(b"episode\n").unwrap()).unwrap();
        fs::write(dir.join("run-0-agent-0.snapshot"), [0u8; 8]).unwrap();
        let names: Vec<_> = finished_runs(dir).unwrap();
        assert_eq!(
            names,
            [(0, "run-0.json".into()), (1, "run-1.json.gz".into())]
        );
        let goals: Vec<f64> = (read_runs(dir).unwrap().iter())
            .map(|r| r.points[0].goal_pct)
            .collect();
        assert_eq!(goals, [10.0, 20.0]);

        fs::write(dir.join("run-2.json.gz"), json(2, 30.0)).unwrap();
        let e = read_runs(dir).unwrap_err().to_string();
        assert!(
            e.contains("run-2.json.gz") && e.contains("not a readable gzip"),
            "{e}"
        );
    }

    #[test]
    fn gzip_writes_the_same_bytes_every_time() {
        let text = b"{\"run\": 0}".repeat(100);
        let gz = gzip(&text).unwrap();
        assert_eq!(gz, gzip(&text).unwrap());
        assert_eq!(gz[4..8], [0; 4], "no modification time");
        assert!(gz.len() < text.len() / 10);
    }
}
