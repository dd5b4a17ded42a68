//! Running a study: pretraining, every experiment, then the analysis.

use std::path::{Component, Path, PathBuf};
use std::time::{Duration, Instant};

use super::analysis::{EntryResults, compare_all};
use super::config::StudyConfig;
use super::report::write_report;
use super::shard::Shard;
use crate::error::Error;
use crate::experiment::Experiment;
use crate::runner::{RunOptions, new_bar, run_experiment, run_share};
use crate::store::{self, ExperimentDir, agent_file_name};

/// How to run a study (none of it changes the results in process).
#[derive(Clone, Debug)]
pub struct StudyOptions {
    /// Worker threads for in-process runs.
    pub threads: usize,
    /// Show one progress bar for the whole study.
    pub progress: bool,
    /// Play only this share of the runs, and no statistics.
    pub shard: Option<Shard>,
}

/// What a finished study reports besides its files.
#[derive(Clone, Debug)]
pub struct StudyOutcome {
    /// `REPORT.md`; none for a shard.
    pub report: Option<PathBuf>,
    /// Runs a shard played (the pretraining counts as one); 0 without a shard.
    pub runs_played: usize,
    /// Wall time of this invocation.
    pub wall: Duration,
}

/// `path` without `.` components and trailing slashes, so that `./out`,
/// `out/` and `out` name one study (the expert's path is part of the
/// experiments' identity).
fn normalise(path: &Path) -> PathBuf {
    let clean: PathBuf = path
        .components()
        .filter(|c| !matches!(c, Component::CurDir))
        .collect();
    if clean.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        clean
    }
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
    let out = &normalise(out);
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
    let run_options = |save_agents: Option<PathBuf>| RunOptions {
        threads: options.threads,
        save_agents,
        progress: options.progress,
        bar: Some(bar.clone()),
    };
    // Over zenoh every experiment gets its own processes and keys.
    let prepare = |mut config: crate::config::ExperimentConfig, name: &str| {
        config.transport = config.transport.for_experiment(name);
        Experiment::prepare(config)
    };

    let mut runs_played = 0;
    let expert = out.join("pretrain").join("expert.qtable");
    if let Some(p) = &study.pretrain {
        let dir = out.join("pretrain");
        let experiment = prepare(study.pretraining(p), "pretrain")?;
        if expert.is_file() || options.shard.is_some_and(|s| !s.is_first()) {
            bar.inc(experiment.config().episodes_per_run());
        } else {
            let output = ExperimentDir::check(&dir, &experiment.record())?;
            let agents = dir.join("agents");
            run_experiment(&experiment, &output, &run_options(Some(agents.clone())))?;
            let saved = agents.join(agent_file_name(0, p.expert));
            let bytes = std::fs::read(&saved).map_err(|e| Error::io("read", &saved, e))?;
            store::write_atomically(&expert, &bytes)?;
            runs_played += usize::from(options.shard.is_some());
        }
    }

    let mut entries = Vec::with_capacity(study.entries.len());
    for (i, entry) in study.entries.iter().enumerate() {
        if entry.expert && !expert.is_file() {
            // Only a shard other than the first gets here: the first pretrains.
            tracing::warn!(entry = %entry.name, "no expert yet: its runs are left to another invocation");
            continue;
        }
        let config = study.experiment(entry, entry.expert.then_some(expert.as_path()));
        let experiment = prepare(config, &entry.name)?;
        let output = ExperimentDir::check(&out.join(&entry.name), &experiment.record())?;
        let first = i as u64 * study.runs;
        match options.shard {
            Some(shard) => {
                let ours = |run| shard.owns(first, run);
                runs_played += run_share(&experiment, &output, &run_options(None), &ours)?;
            }
            None => {
                let report = run_experiment(&experiment, &output, &run_options(None))?;
                entries.push(EntryResults {
                    entry: entry.clone(),
                    results: report.results,
                    summary: report.summary,
                });
            }
        }
    }
    bar.finish_and_clear();
    let report = match options.shard {
        Some(_) => None,
        None => {
            let comparisons = compare_all(study, &entries);
            Some(write_report(out, study, &entries, &comparisons)?)
        }
    };
    Ok(StudyOutcome {
        report,
        runs_played,
        wall: start.elapsed(),
    })
}

/// Refuses a directory holding another study; records this one in it.
fn claim_directory(out: &Path, study: &StudyConfig) -> Result<(), Error> {
    let ours = serde_json::to_value(study).expect("a study serialises");
    store::check_claim(out, STUDY_FILE, &ours)?;
    store::claim(out, STUDY_FILE, &ours)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_of_one_directory_normalise_alike() {
        for spelling in ["out", "./out", "out/", "./out/."] {
            assert_eq!(
                normalise(Path::new(spelling)),
                Path::new("out"),
                "{spelling}"
            );
        }
        assert_eq!(normalise(Path::new("/a/./b/")), Path::new("/a/b"));
        assert_eq!(normalise(Path::new(".")), Path::new("."));
        assert_eq!(normalise(Path::new("../x")), Path::new("../x"));
    }
}
