//! An experiment's R runs over a pool of threads, then its summary.
//!
//! Every run is independent and deterministic from its own seeds; results
//! come back in run order before the summary is computed, so the summary is
//! byte-identical whatever the number of threads.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::driver::{self, Driver};
use crate::error::Error;
use crate::experiment::Experiment;
use analysis::{RunResult, Timing};

use crate::schedule;
use crate::store::{self, ExperimentDir};
use crate::summary::{Summary, summarize};

/// How to run an experiment (none of it changes the results).
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Worker threads (at least 1; more than the runs is pointless).
    pub threads: usize,
    /// Save every agent's snapshot at the end of each run into this
    /// directory, as `run-<k>-agent-<i>.snapshot`.
    pub save_agents: Option<PathBuf>,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// A progress bar to advance instead of a new one (a study's, over all
    /// its experiments): one step per episode.
    pub bar: Option<ProgressBar>,
    /// Set to stop after the episodes in flight ([`Error::Interrupted`]);
    /// the runs finished so far are kept.
    pub stop: Option<Arc<AtomicBool>>,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            threads: default_threads(),
            save_agents: None,
            progress: false,
            bar: None,
            stop: None,
        }
    }
}

/// One worker per core.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// What a finished experiment reports besides its files.
#[derive(Clone, Debug)]
pub struct Report {
    /// Summed over the runs played by this invocation.
    pub timing: Timing,
    /// Wall time of the whole experiment.
    pub wall: Duration,
    /// The summary's path.
    pub summary_path: PathBuf,
    /// The summary, as written.
    pub summary: Summary,
    /// Every run's results, sorted by run.
    pub results: Vec<RunResult>,
}

/// Plays every run of `experiment` into `out` and writes the summary.
pub fn run_experiment(
    experiment: &Experiment,
    out: &ExperimentDir,
    options: &RunOptions,
) -> Result<Report, Error> {
    let start = Instant::now();
    let (finished, timing, _) = play_runs(experiment, out, options, &|_| true)?;
    let results: Vec<RunResult> = finished.into_iter().flatten().collect();
    let summary = summarize(&experiment.record(), &results);
    out.write_summary(&summary)?;
    Ok(Report {
        timing,
        wall: start.elapsed(),
        summary_path: out.path().join(store::SUMMARY_FILE),
        summary,
        results,
    })
}

/// Plays the runs of `experiment` that `wanted` selects (a study shard's
/// share) into `out`, writing no summary; returns how many it played.
pub fn run_share(
    experiment: &Experiment,
    out: &ExperimentDir,
    options: &RunOptions,
    wanted: &(dyn Fn(u64) -> bool + Sync),
) -> Result<usize, Error> {
    Ok(play_runs(experiment, out, options, wanted)?.2)
}

/// Plays the runs `wanted` selects that no earlier invocation finished;
/// returns every run's results, if finished, and the timing and number of
/// those played.
fn play_runs(
    experiment: &Experiment,
    out: &ExperimentDir,
    options: &RunOptions,
    wanted: &(dyn Fn(u64) -> bool + Sync),
) -> Result<(Vec<Option<RunResult>>, Timing, usize), Error> {
    let config = experiment.config();
    out.create()?;
    if let Some(dir) = &options.save_agents {
        store::create_dir(dir)?;
    }
    // Runs an earlier invocation finished are kept, not played again.
    let mut finished: Vec<Option<RunResult>> =
        (0..config.runs).map(|r| out.finished_run(r)).collect();
    let pending: Vec<u64> = (0..config.runs)
        .filter(|&r| finished[r as usize].is_none() && wanted(r))
        .collect();
    let kept = config.runs - pending.len() as u64;
    if kept > 0 {
        tracing::info!(runs = kept, "resuming: runs already finished are kept");
    }
    let progress = RunsProgress::new(experiment, out, options, kept);
    let played = if pending.is_empty() {
        Vec::new()
    } else {
        play_in_parallel(experiment, out, options, &pending, &progress)?
    };
    if options.bar.is_none() {
        progress.bar.finish_and_clear();
    }
    let mut timing = Timing::default();
    let count = played.len();
    for result in played {
        timing.add(&result.timing);
        let run = result.run as usize;
        finished[run] = Some(result);
    }
    Ok((finished, timing, count))
}

/// Plays the runs `pending` over a pool of threads; returns their results in
/// run order.
fn play_in_parallel(
    experiment: &Experiment,
    out: &ExperimentDir,
    options: &RunOptions,
    pending: &[u64],
    progress: &RunsProgress,
) -> Result<Vec<RunResult>, Error> {
    let config = experiment.config();
    let driver = driver::open(&config.transport, &config.team)?;
    let threads = options
        .threads
        .min(driver.max_parallel_runs())
        .clamp(1, pending.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Transport(format!("cannot start {threads} worker threads: {e}")))?;
    let episode = |frames| {
        progress.episode(frames);
        match &options.stop {
            Some(stop) if stop.load(Ordering::Relaxed) => Err(Error::Interrupted),
            _ => Ok(()),
        }
    };
    pool.install(|| {
        pending
            .par_iter()
            .map(|&run| {
                let result = one_run(experiment, out, options, driver.as_ref(), run, &episode)?;
                progress.done.fetch_add(1, Ordering::Relaxed);
                tracing::info!(
                    run,
                    training_frames_per_sec = result.timing.training_frames_per_sec(),
                    "run finished"
                );
                Ok(result)
            })
            .collect()
    })
}

/// The progress of an experiment's runs: one step of its bar per episode,
/// and a message with the runs done and the frame rate.
struct RunsProgress {
    bar: ProgressBar,
    /// Within a study's bar, which experiment the runs belong to.
    label: String,
    runs: u64,
    done: AtomicU64,
    frames: AtomicU64,
    start: Instant,
}

impl RunsProgress {
    /// The experiment's own bar, or the one of `options`, advanced over the
    /// `kept` runs an earlier invocation finished.
    fn new(experiment: &Experiment, out: &ExperimentDir, options: &RunOptions, kept: u64) -> Self {
        let config = experiment.config();
        let bar = match &options.bar {
            Some(bar) => bar.clone(),
            None => new_bar(options.progress, config.runs * config.episodes_per_run()),
        };
        bar.inc(kept * config.episodes_per_run());
        let label = match (&options.bar, out.path().file_name()) {
            (Some(_), Some(name)) => format!("{}: ", name.to_string_lossy()),
            _ => String::new(),
        };
        Self {
            bar,
            label,
            runs: config.runs,
            done: AtomicU64::new(kept),
            frames: AtomicU64::new(0),
            start: Instant::now(),
        }
    }

    /// One episode of `frames` frames was played.
    fn episode(&self, frames: u64) {
        self.bar.inc(1);
        let total = self.frames.fetch_add(frames, Ordering::Relaxed) + frames;
        if self.bar.position() % 50 == 0 {
            let rate = total as f64 / self.start.elapsed().as_secs_f64().max(1e-9);
            self.bar.set_message(format!(
                "{}{}/{} runs, {rate:.0} frames/s",
                self.label,
                self.done.load(Ordering::Relaxed),
                self.runs
            ));
        }
    }
}

/// One run: its backend, its CSV and, if asked, its agents saved.
fn one_run(
    experiment: &Experiment,
    out: &ExperimentDir,
    options: &RunOptions,
    driver: &dyn Driver,
    run: u64,
    progress: &(dyn Fn(u64) -> Result<(), Error> + Sync),
) -> Result<RunResult, Error> {
    let mut backend = driver.backend(experiment, run)?;
    let mut writer = out.run_writer(run, experiment.config().team.len())?;
    let result = schedule::play_run(
        experiment,
        backend.as_mut(),
        run,
        |p| writer.write_point(p),
        progress,
    )?;
    if let Some(dir) = &options.save_agents {
        store::write_agents(dir, run, &backend.snapshots()?)?;
    }
    out.write_run_result(&result)?;
    Ok(result)
}

/// A progress bar over `total` episodes, hidden unless `visible`.
pub fn new_bar(visible: bool, total: u64) -> ProgressBar {
    if !visible {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template(
            "{elapsed_precise} [{wide_bar}] {percent:>3}% {msg} eta {eta}",
        )
        .expect("a valid template")
        .progress_chars("=> "),
    );
    bar
}
