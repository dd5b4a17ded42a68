//! A study published: what a reader needs to redraw every figure and
//! analyse it again, and nothing bulky (docs/results.md, "A published
//! study"). `study.json`, `REPORT.md`, `significance.json`, `figures/` and
//! each entry's `config.json` and `summary.json` are copied; every finished
//! run's `run-<k>.json` and `run-<k>.csv` are gzipped (`.gz`), the same
//! bytes every time; the pretraining, snapshots and anything else are left
//! out.

use std::path::{Path, PathBuf};

use node::files::TEMP_PREFIX;
use serde_json::Value;

use crate::error::Error;
use crate::files::{self, GZ, STUDY_FILE};
use crate::study::Study;

/// The study's files besides its entries, copied as they are; `REPORT.md`
/// is written last.
const STUDY_FILES: [&str; 2] = ["significance.json", "REPORT.md"];
/// An entry's files besides its runs, copied as they are.
const ENTRY_FILES: [&str; 2] = ["config.json", "summary.json"];
/// The figures' directory, copied whole.
const FIGURES: &str = "figures";
/// What a study directory must be to be published.
const FINISHED: &str = "expected a finished study (`coordinator study` without --shard writes \
                        every summary.json, the figures and the report; `analyse DIR` the last two)";

/// What a publication wrote.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Published {
    /// Files written.
    pub files: usize,
    /// Their bytes.
    pub bytes: u64,
}

/// One file of the publication: where it comes from, where it goes.
struct Planned {
    /// Its path in the study's directory.
    from: PathBuf,
    /// Its path in the publication, relative to it.
    to: PathBuf,
    /// Whether it is gzipped on the way.
    gzip: bool,
}

/// Publishes the study in `dir` into `dest` (created as needed): refused,
/// with nothing written, when `dest` holds another study or files of no
/// study, or when `dir` lacks a file a publication holds.
pub fn publish(dir: &Path, dest: &Path) -> Result<Published, Error> {
    let identity: Value = files::read_json(&dir.join(STUDY_FILE))?;
    let study: Study = serde_json::from_value(identity.clone())
        .map_err(|e| Error::invalid(dir.join(STUDY_FILE), e.to_string()))?;
    check_destination(dir, dest, &identity)?;
    let copies = plan(dir, &study)?;
    let mut published = Published { files: 0, bytes: 0 };
    for copy in copies {
        let to = dest.join(&copy.to);
        if let Some(parent) = to.parent() {
            files::create_dir(parent)?;
        }
        let mut bytes = files::read(&copy.from)?;
        if copy.gzip {
            bytes = files::gzip(&bytes).map_err(|e| Error::io("compress", &copy.from, e))?;
        }
        files::write(&to, &bytes)?;
        published.files += 1;
        published.bytes += bytes.len() as u64;
    }
    Ok(published)
}

/// Refuses a `dest` that is `dir` itself, not a directory, holds another
/// study (its `study.json` differs but for `runs`, which grow as a study
/// does), or holds files without a `study.json`.
fn check_destination(dir: &Path, dest: &Path, identity: &Value) -> Result<(), Error> {
    let refuse = |reason: String| Err(Error::invalid(dest, reason));
    if !dest.exists() {
        return Ok(());
    }
    if !dest.is_dir() {
        return refuse("is not a directory: expected a directory to publish into".into());
    }
    let same = |a: &Path, b: &Path| a.canonicalize().ok() == b.canonicalize().ok();
    if same(dir, dest) {
        return refuse("is the study itself: expected another directory to publish into".into());
    }
    let theirs = dest.join(STUDY_FILE);
    if theirs.exists() {
        let theirs: Value = files::read_json(&theirs)?;
        return match first_difference(identity, &theirs) {
            None => Ok(()),
            Some(key) => refuse(format!(
                "holds another study (its {STUDY_FILE} differs at `{key}`): expected a new or \
                 empty directory, or one this study was published into"
            )),
        };
    }
    match (files::list(dest)?.into_iter()).find(|name| !name.starts_with(TEMP_PREFIX)) {
        Some(name) => refuse(format!(
            "holds {name} but no {STUDY_FILE}: expected a new or empty directory, or one this \
             study was published into"
        )),
        None => Ok(()),
    }
}

/// The first top-level key whose value differs between two `study.json`,
/// `runs` aside.
fn first_difference(ours: &Value, theirs: &Value) -> Option<String> {
    let (Some(ours), Some(theirs)) = (ours.as_object(), theirs.as_object()) else {
        return (ours != theirs).then(|| "the top level".to_owned());
    };
    let mut keys: Vec<&String> = ours.keys().chain(theirs.keys()).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .find(|&key| key != "runs" && ours.get(key) != theirs.get(key))
        .cloned()
}

/// Every file of the publication, `study.json` first and `REPORT.md` last;
/// an error naming the first file `dir` lacks.
fn plan(dir: &Path, study: &Study) -> Result<Vec<Planned>, Error> {
    let copy = |to: PathBuf, gzip: bool| -> Result<Planned, Error> {
        let from = dir.join(&to);
        if !from.is_file() {
            return Err(Error::invalid(&from, format!("is missing: {FINISHED}")));
        }
        Ok(Planned { from, to, gzip })
    };
    let mut copies = vec![copy(STUDY_FILE.into(), false)?];
    for entry in &study.entries {
        let at = Path::new(&entry.name);
        for name in ENTRY_FILES {
            copies.push(copy(at.join(name), false)?);
        }
        let runs = files::finished_runs(&dir.join(at))?;
        if runs.is_empty() {
            return Err(Error::invalid(
                dir.join(at),
                format!("holds no finished run (run-<k>.json): {FINISHED}"),
            ));
        }
        for (k, json) in runs {
            copies.push(copy(at.join(&json), !json.ends_with(GZ))?);
            let csv = at.join(format!("run-{k}.csv"));
            let mut gzipped = csv.clone().into_os_string();
            gzipped.push(GZ);
            // A published study's CSV is gzipped already.
            copies.push(
                if dir.join(&gzipped).is_file() && !dir.join(&csv).is_file() {
                    copy(gzipped.into(), false)?
                } else {
                    copy(csv, true)?
                },
            );
        }
    }
    for name in files::list(&dir.join(FIGURES))? {
        let figure = Path::new(FIGURES).join(&name);
        if !name.starts_with(TEMP_PREFIX) && dir.join(&figure).is_file() {
            copies.push(copy(figure, false)?);
        }
    }
    if !copies.iter().any(|c| c.to.starts_with(FIGURES)) {
        return Err(Error::invalid(
            dir.join(FIGURES),
            format!("holds no figure: {FINISHED}"),
        ));
    }
    for name in STUDY_FILES {
        copies.push(copy(name.into(), false)?);
    }
    // Compressed, each run's files take their name's `.gz`.
    for c in &mut copies {
        if c.gzip {
            c.to.as_mut_os_string().push(GZ);
        }
    }
    Ok(copies)
}

#[cfg(test)]
mod tests {
    use std::fs;

    use serde_json::json;

    use super::*;
    use crate::fixtures::run_with_goals;

    /// A finished study of two entries and three runs in `dir` (a copy of
    /// one made once: drawing its figures takes seconds).
    fn finished_study(dir: &Path) {
        static MADE: std::sync::OnceLock<tempfile::TempDir> = std::sync::OnceLock::new();
        let made = MADE.get_or_init(|| {
            let made = tempfile::tempdir().unwrap();
            make_finished_study(made.path());
            made
        });
        for (name, bytes) in tree(made.path()) {
            let to = dir.join(name);
            fs::create_dir_all(to.parent().unwrap()).unwrap();
            fs::write(to, bytes).unwrap();
        }
    }

    /// A finished study of two entries and three runs in `dir`, with what a
    /// publication leaves out beside it: the pretraining, a snapshot, a log,
    /// a run cut short.
    fn make_finished_study(dir: &Path) {
        let study = json!({
            "name": "tiny", "runs": 3, "episodes": 40, "eval_every": 20,
            "eval_episodes": 5, "seed": 3, "transport": "in-process", "baseline": "a",
            "pretrain": {"algorithm": "no-advice", "episodes": 10, "expert": 0},
            "entry": [{"name": "a", "algorithm": "no-advice"},
                      {"name": "b", "algorithm": "adhoc-td"}],
        });
        fs::write(dir.join(STUDY_FILE), study.to_string()).unwrap();
        for (entry, lift) in [("a", 0.0), ("b", 12.0)] {
            let at = dir.join(entry);
            fs::create_dir_all(&at).unwrap();
            fs::write(
                at.join("config.json"),
                r#"{"format": 5, "config": {"team": []}}"#,
            )
            .unwrap();
            fs::write(at.join("summary.json"), "{}\n").unwrap();
            for k in 0..3 {
                let goals = [10.0 + k as f64, 20.0 + lift + k as f64, 30.0 + lift];
                let run = serde_json::to_vec(&run_with_goals(k, 20, &goals)).unwrap();
                fs::write(at.join(format!("run-{k}.json")), run).unwrap();
                fs::write(
                    at.join(format!("run-{k}.csv")),
                    format!("episode\n0\n{k}\n"),
                )
                .unwrap();
            }
            fs::write(at.join("run-3.csv"), "episode\n0\n").unwrap();
            fs::write(at.join("run-0-agent-0.snapshot"), [0u8; 64]).unwrap();
        }
        fs::create_dir_all(dir.join("pretrain")).unwrap();
        fs::write(dir.join("pretrain/expert.snapshot"), [1u8; 64]).unwrap();
        fs::write(dir.join("study.log"), "played\n").unwrap();
        let (study, entries) = files::read_study(dir).unwrap();
        crate::report::write_report(dir, &study, &entries).unwrap();
    }

    /// Every file under `dir`, relative to it, with its bytes.
    fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
        let mut found = Vec::new();
        let mut todo = vec![dir.to_path_buf()];
        while let Some(at) = todo.pop() {
            for file in fs::read_dir(&at).unwrap() {
                let path = file.unwrap().path();
                if path.is_dir() {
                    todo.push(path);
                } else {
                    let name = path.strip_prefix(dir).unwrap().display().to_string();
                    found.push((name, fs::read(&path).unwrap()));
                }
            }
        }
        found.sort();
        found
    }

    #[test]
    fn a_published_study_holds_its_runs_gzipped_and_analyses_to_the_same_report() {
        let tmp = tempfile::tempdir().unwrap();
        let (dir, dest) = (tmp.path().join("study"), tmp.path().join("published"));
        fs::create_dir(&dir).unwrap();
        finished_study(&dir);
        let published = publish(&dir, &dest).unwrap();

        let names: Vec<String> = tree(&dest).into_iter().map(|(name, _)| name).collect();
        let figures = files::list(&dir.join(FIGURES)).unwrap();
        assert!(!figures.is_empty());
        let mut expected: Vec<String> = ["REPORT.md", "significance.json", "study.json"]
            .map(String::from)
            .into_iter()
            .chain(figures.iter().map(|f| format!("figures/{f}")))
            .collect();
        for entry in ["a", "b"] {
            expected.extend(ENTRY_FILES.map(|f| format!("{entry}/{f}")));
            for k in 0..3 {
                expected.push(format!("{entry}/run-{k}.csv.gz"));
                expected.push(format!("{entry}/run-{k}.json.gz"));
            }
        }
        expected.sort();
        assert_eq!(names, expected);
        assert_eq!(published.files, expected.len());
        for name in ["b/run-2.json", "b/run-2.csv"] {
            let gz = dest.join(format!("{name}{GZ}"));
            assert_eq!(
                files::read_maybe_gzipped(&gz).unwrap(),
                fs::read(dir.join(name)).unwrap()
            );
        }

        // The published copy, analysed anew, writes the report it carries.
        let (study, entries) = files::read_study(&dest).unwrap();
        assert_eq!(
            entries.iter().map(|e| e.results.len()).collect::<Vec<_>>(),
            [3, 3]
        );
        crate::report::write_report(&dest, &study, &entries).unwrap();
        for name in ["REPORT.md", "significance.json"] {
            assert_eq!(
                fs::read_to_string(dest.join(name)).unwrap(),
                fs::read_to_string(dir.join(name)).unwrap(),
                "{name}"
            );
        }
        for figure in figures {
            let name = format!("{FIGURES}/{figure}");
            assert!(
                fs::read(dest.join(&name)).unwrap() == fs::read(dir.join(&name)).unwrap(),
                "{name}"
            );
        }
    }

    #[test]
    fn publishing_again_changes_no_byte_and_a_published_study_publishes_as_itself() {
        let tmp = tempfile::tempdir().unwrap();
        let (dir, dest) = (tmp.path().join("study"), tmp.path().join("published"));
        fs::create_dir(&dir).unwrap();
        finished_study(&dir);
        publish(&dir, &dest).unwrap();
        let first = tree(&dest);
        publish(&dir, &dest).unwrap();
        assert!(tree(&dest) == first);
        let again = tmp.path().join("again");
        publish(&dest, &again).unwrap();
        assert!(tree(&again) == first);
    }

    #[test]
    fn another_study_or_stray_files_are_refused_untouched() {
        let tmp = tempfile::tempdir().unwrap();
        let (dir, dest) = (tmp.path().join("study"), tmp.path().join("published"));
        fs::create_dir(&dir).unwrap();
        finished_study(&dir);
        fs::create_dir(&dest).unwrap();
        let mut other: Value = files::read_json(&dir.join(STUDY_FILE)).unwrap();
        other["seed"] = json!(4);
        fs::write(dest.join(STUDY_FILE), other.to_string()).unwrap();
        let e = publish(&dir, &dest).unwrap_err().to_string();
        assert!(
            e.contains("holds another study") && e.contains("`seed`"),
            "{e}"
        );
        assert_eq!(files::list(&dest).unwrap(), [STUDY_FILE]);

        fs::remove_file(dest.join(STUDY_FILE)).unwrap();
        fs::write(dest.join("notes.txt"), "mine").unwrap();
        let e = publish(&dir, &dest).unwrap_err().to_string();
        assert!(e.contains("holds notes.txt but no study.json"), "{e}");
        assert_eq!(files::list(&dest).unwrap(), ["notes.txt"]);

        let e = publish(&dir, &dir).unwrap_err().to_string();
        assert!(e.contains("is the study itself"), "{e}");

        // The same study with more runs is the same study.
        fs::remove_file(dest.join("notes.txt")).unwrap();
        other["seed"] = json!(3);
        other["runs"] = json!(2);
        fs::write(dest.join(STUDY_FILE), other.to_string()).unwrap();
        publish(&dir, &dest).unwrap();
    }

    #[test]
    fn an_unfinished_study_is_refused_naming_what_it_lacks() {
        let tmp = tempfile::tempdir().unwrap();
        let (dir, dest) = (tmp.path().join("study"), tmp.path().join("published"));
        fs::create_dir(&dir).unwrap();
        finished_study(&dir);
        for lacking in ["REPORT.md", "b/summary.json", "a/run-1.csv"] {
            let kept = fs::read(dir.join(lacking)).unwrap();
            fs::remove_file(dir.join(lacking)).unwrap();
            let e = publish(&dir, &dest).unwrap_err().to_string();
            assert!(e.contains(&format!("{lacking}: is missing")), "{e}");
            assert!(!dest.exists(), "nothing is written");
            fs::write(dir.join(lacking), kept).unwrap();
        }
    }
}
