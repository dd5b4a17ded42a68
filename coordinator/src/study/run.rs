//! Running a study: pretraining, every experiment, then the analysis.

use std::fs;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::analysis::compare_all;
use super::config::StudyConfig;
use super::report::{EntryResults, write_report};
use crate::error::Error;
use crate::experiment::Experiment;
use crate::output::OutputDir;
use crate::remote::NetworkOptions;
use crate::runner::{RunOptions, agent_file_name, new_bar, run_experiment};

/// How to run a study (none of it changes the results in process).
#[derive(Clone, Debug)]
pub struct StudyOptions {
    /// Worker threads for in-process runs.
    pub threads: usize,
    /// Show one progress bar for the whole study.
    pub progress: bool,
    /// zenoh settings, for studies over zenoh (the experiment name gets each
    /// entry's name appended).
    pub network: Option<NetworkOptions>,
}

/// What a finished study reports besides its files.
#[derive(Clone, Debug)]
pub struct StudyOutcome {
    /// `REPORT.md`.
    pub report: PathBuf,
    /// Wall time of this invocation.
    pub wall: Duration,
}

/// The study's own record in its directory.
const STUDY_FILE: &str = "study.json";

/// Runs `study` into `out` (resuming what an earlier invocation finished).
pub fn run_study(
    study: &StudyConfig,
    out: &Path,
    options: &StudyOptions,
) -> Result<StudyOutcome, Error> {
    study.validate()?;
    claim_directory(out, study)?;
    let start = Instant::now();
    let total: u64 = study
        .pretrain
        .as_ref()
        .map_or(0, |p| study.pretraining(p).episodes_per_run())
        + study.entries.len() as u64
            * study.runs
            * study.experiment(&study.entries[0], None).episodes_per_run();
    let bar = new_bar(options.progress, total);
    let run_options = |name: &str, save_agents: Option<PathBuf>| RunOptions {
        threads: options.threads,
        transport: study.transport.into(),
        save_agents,
        progress: options.progress,
        bar: Some(bar.clone()),
        network: options.network.clone().map(|mut n| {
            n.experiment = format!("{}-{name}", n.experiment);
            n
        }),
    };

    let expert = out.join("pretrain").join("expert.qtable");
    if let Some(p) = &study.pretrain {
        let dir = out.join("pretrain");
        let experiment = Experiment::prepare(study.pretraining(p))?;
        if expert.is_file() {
            bar.inc(experiment.config().episodes_per_run());
        } else {
            let output = OutputDir::check(&dir, &experiment.record())?;
            let agents = dir.join("agents");
            run_experiment(
                &experiment,
                &output,
                &run_options("pretrain", Some(agents.clone())),
            )?;
            copy_atomically(&agents.join(agent_file_name(0, p.expert)), &expert)?;
        }
    }

    let mut entries = Vec::with_capacity(study.entries.len());
    for entry in &study.entries {
        let config = study.experiment(entry, entry.expert.then_some(expert.as_path()));
        let experiment = Experiment::prepare(config)?;
        let output = OutputDir::check(&out.join(&entry.name), &experiment.record())?;
        let report = run_experiment(&experiment, &output, &run_options(&entry.name, None))?;
        entries.push(EntryResults {
            entry: entry.clone(),
            results: report.results,
        });
    }
    bar.finish_and_clear();
    let comparisons = compare_all(study, &entries);
    let report = write_report(out, study, &entries, &comparisons, start.elapsed())?;
    Ok(StudyOutcome {
        report,
        wall: start.elapsed(),
    })
}

/// Refuses a directory holding another study; records this one in it.
fn claim_directory(out: &Path, study: &StudyConfig) -> Result<(), Error> {
    let ours = serde_json::to_value(study).expect("a study serialises");
    let path = out.join(STUDY_FILE);
    match fs::read(&path) {
        Ok(bytes) => {
            let theirs: serde_json::Value = serde_json::from_slice(&bytes).unwrap_or_default();
            if theirs != ours {
                let name = theirs["name"].as_str().unwrap_or("?").to_owned();
                return Err(Error::OtherResults {
                    dir: out.to_path_buf(),
                    reason: format!("it holds study '{name}' with other settings"),
                });
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            if out.is_dir()
                && fs::read_dir(out)
                    .map_err(|e| Error::io("read", out, e))?
                    .next()
                    .is_some()
            {
                return Err(Error::OtherResults {
                    dir: out.to_path_buf(),
                    reason: format!("it is not empty and has no {STUDY_FILE}"),
                });
            }
            fs::create_dir_all(out).map_err(|e| Error::io("create", out, e))?;
            let mut bytes = serde_json::to_vec_pretty(&ours).expect("a study serialises");
            bytes.push(b'\n');
            write_file(&path, &bytes)
        }
        Err(e) => Err(Error::io("read", path, e)),
    }
}

/// Writes `bytes` to `path` atomically (a temporary file, then a rename).
pub(super) fn write_file(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let tmp = path.with_extension("tmp");
    fs::write(&tmp, bytes).map_err(|e| Error::io("write", &tmp, e))?;
    fs::rename(&tmp, path).map_err(|e| Error::io("write", path, e))
}

fn copy_atomically(from: &Path, to: &Path) -> Result<(), Error> {
    let bytes = fs::read(from).map_err(|e| Error::io("read", from, e))?;
    write_file(to, &bytes)
}
