//! Running a study: pretraining, every experiment, then the analysis.

use std::path::{Component, Path, PathBuf};
use std::time::{Duration, Instant};

use analysis::EntryResults;
use analysis::report::write_report;
use indicatif::ProgressBar;

use super::config::{Pretrain, StudyConfig};
use super::shard::Shard;
use crate::config::ExperimentConfig;
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
    /// Set to stop after the episodes in flight (see [`RunOptions::stop`]).
    pub stop: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
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
    let invocation = Invocation {
        study,
        out,
        options,
        bar: new_bar(options.progress, total_episodes(study)),
    };
    let mut runs_played = match &study.pretrain {
        Some(p) => invocation.pretrain(p)?,
        None => 0,
    };
    let (entries, played) = invocation.entries()?;
    runs_played += played;
    invocation.bar.finish_and_clear();
    let report = match options.shard {
        Some(_) => None,
        None => Some(write_report(out, &study.record(), &entries)?),
    };
    Ok(StudyOutcome {
        report,
        runs_played,
        wall: start.elapsed(),
    })
}

/// Episodes of the whole study, pretraining included: the progress bar's length.
fn total_episodes(study: &StudyConfig) -> u64 {
    study
        .pretrain
        .as_ref()
        .map_or(0, |p| study.pretraining(p).episodes_per_run())
        + study.entries.len() as u64
            * study.runs
            * study.experiment(&study.entries[0], None).episodes_per_run()
}

/// The experiment of `config`, named `name`: over zenoh every experiment
/// gets its own processes and keys.
fn prepare(mut config: ExperimentConfig, name: &str) -> Result<Experiment, Error> {
    config.transport = config.transport.for_experiment(name);
    Experiment::prepare(config)
}

/// One invocation of a study: what its stages share.
struct Invocation<'a> {
    study: &'a StudyConfig,
    out: &'a Path,
    options: &'a StudyOptions,
    /// One bar over the whole study.
    bar: ProgressBar,
}

impl Invocation<'_> {
    fn run_options(&self, save_agents: Option<PathBuf>) -> RunOptions {
        RunOptions {
            threads: self.options.threads,
            save_agents,
            progress: self.options.progress,
            bar: Some(self.bar.clone()),
            stop: self.options.stop.clone(),
        }
    }

    /// Where the pretrained expert is saved: `expert.snapshot`, or
    /// `expert.qtable` in a study directory of a version before 0.3.
    fn expert(&self) -> PathBuf {
        let dir = self.out.join("pretrain");
        let old = dir.join("expert.qtable");
        if old.is_file() {
            old
        } else {
            dir.join("expert.snapshot")
        }
    }

    /// Pretrains the team of `p` and saves its expert, unless the expert
    /// exists or a shard other than the first is running; returns the runs
    /// a shard played (1 if it pretrained).
    fn pretrain(&self, p: &Pretrain) -> Result<usize, Error> {
        let dir = self.out.join("pretrain");
        let experiment = prepare(self.study.pretraining(p), "pretrain")?;
        let expert = self.expert();
        if expert.is_file() || self.options.shard.is_some_and(|s| !s.is_first()) {
            self.bar.inc(experiment.config().episodes_per_run());
            return Ok(0);
        }
        let output = ExperimentDir::check(&dir, &experiment.record())?;
        let agents = dir.join("agents");
        run_experiment(
            &experiment,
            &output,
            &self.run_options(Some(agents.clone())),
        )?;
        let saved = agents.join(agent_file_name(0, p.expert));
        let bytes = std::fs::read(&saved).map_err(|e| Error::io("read", &saved, e))?;
        store::write_atomically(&expert, &bytes)?;
        Ok(usize::from(self.options.shard.is_some()))
    }

    /// Plays every entry's runs, or a shard's share of them; returns every
    /// entry's results (none for a shard) and the runs a shard played.
    fn entries(&self) -> Result<(Vec<EntryResults>, usize), Error> {
        let (study, expert) = (self.study, self.expert());
        let record = study.record();
        let mut entries = Vec::with_capacity(study.entries.len());
        let mut runs_played = 0;
        for (i, entry) in study.entries.iter().enumerate() {
            if entry.expert && !expert.is_file() {
                // Only a shard other than the first gets here: the first pretrains.
                tracing::warn!(entry = %entry.name, "no expert yet: its runs are left to another invocation");
                continue;
            }
            let config = study.experiment(entry, entry.expert.then_some(expert.as_path()));
            let experiment = prepare(config, &entry.name)?;
            let output = ExperimentDir::check(&self.out.join(&entry.name), &experiment.record())?;
            let first = i as u64 * study.runs;
            match self.options.shard {
                Some(shard) => {
                    let ours = |run| shard.owns(first, run);
                    runs_played += run_share(&experiment, &output, &self.run_options(None), &ours)?;
                }
                None => {
                    let report = run_experiment(&experiment, &output, &self.run_options(None))?;
                    entries.push(EntryResults::new(
                        record.entries[i].clone(),
                        serde_json::to_value(experiment.record()).expect("a record serialises"),
                        report.results,
                        study.ci_level(),
                    ));
                }
            }
        }
        Ok((entries, runs_played))
    }
}

/// Refuses a directory holding another study; records this one in it.
fn claim_directory(out: &Path, study: &StudyConfig) -> Result<(), Error> {
    let ours = study.json();
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
