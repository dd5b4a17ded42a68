//! An experiment's R runs over T worker threads, then its summary.
//!
//! Every run is independent and deterministic from its own seeds; results
//! are sorted by run index before the summary is computed, so the summary
//! is byte-identical whatever the number of threads.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

use crate::backend::{self, Transport};
use crate::error::Error;
use crate::experiment::Experiment;
use crate::output::{OutputDir, SUMMARY_FILE};
use crate::protocol::{self, RunResult, Timing};
use crate::remote::{Network, NetworkOptions};
use crate::summary::{SummaryPoint, summarize};

/// How to run an experiment (none of it changes the results).
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Worker threads (at least 1; more than the runs is pointless).
    pub threads: usize,
    /// Where agents and simulator live.
    pub transport: Transport,
    /// Save every agent's snapshot at the end of each run into this
    /// directory, as `run-<k>-agent-<i>.qtable`.
    pub save_agents: Option<PathBuf>,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// A progress bar to advance instead of a new one (a study's, over all
    /// its experiments): one step per episode.
    pub bar: Option<ProgressBar>,
    /// How to reach the processes, for the zenoh transport.
    pub network: Option<NetworkOptions>,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            threads: default_threads(),
            transport: Transport::InProcess,
            save_agents: None,
            progress: false,
            bar: None,
            network: None,
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
    /// Runs played.
    pub runs: u64,
    /// Summed over runs.
    pub timing: Timing,
    /// Wall time of the whole experiment.
    pub wall: Duration,
    /// The summary's path.
    pub summary: PathBuf,
    /// The first evaluation point of the summary.
    pub first: SummaryPoint,
    /// The last evaluation point of the summary.
    pub last: SummaryPoint,
    /// Every run's results, sorted by run.
    pub results: Vec<RunResult>,
}

/// The snapshot file of agent `agent` at the end of run `run`.
pub fn agent_file_name(run: u64, agent: usize) -> String {
    format!("run-{run}-agent-{agent}.qtable")
}

/// Plays every run of `experiment` into `out` and writes the summary.
pub fn run_experiment(
    experiment: &Experiment,
    out: &OutputDir,
    options: &RunOptions,
) -> Result<Report, Error> {
    let config = experiment.config();
    out.create()?;
    if let Some(dir) = &options.save_agents {
        std::fs::create_dir_all(dir).map_err(|e| Error::io("create", dir, e))?;
    }
    let bar = match &options.bar {
        Some(bar) => bar.clone(),
        None => new_bar(options.progress, config.runs * config.episodes_per_run()),
    };
    // Runs an earlier invocation finished are kept, not played again.
    let finished: Vec<RunResult> = (0..config.runs)
        .filter_map(|r| out.finished_run(r))
        .collect();
    let pending: Vec<u64> = (0..config.runs)
        .filter(|r| finished.iter().all(|f| f.run != *r))
        .collect();
    bar.inc(finished.len() as u64 * config.episodes_per_run());
    if !finished.is_empty() {
        tracing::info!(
            runs = finished.len(),
            "resuming: runs already finished are kept"
        );
    }
    // Within a study's bar, say which experiment the runs belong to.
    let label = match (&options.bar, out.path().file_name()) {
        (Some(_), Some(name)) => format!("{}: ", name.to_string_lossy()),
        _ => String::new(),
    };
    let done = AtomicU64::new(finished.len() as u64);
    let frames = AtomicU64::new(0);
    let start = Instant::now();
    let tick = |n: u64| {
        bar.inc(1);
        let total = frames.fetch_add(n, Ordering::Relaxed) + n;
        if bar.position() % 50 == 0 {
            let rate = total as f64 / start.elapsed().as_secs_f64().max(1e-9);
            bar.set_message(format!(
                "{label}{}/{} runs, {rate:.0} frames/s",
                done.load(Ordering::Relaxed),
                config.runs
            ));
        }
    };
    let next = AtomicU64::new(0);
    let failed = AtomicBool::new(false);
    let results = Mutex::new(finished);
    let errors = Mutex::new(Vec::new());
    // Over zenoh the runs play one after another on the same processes.
    let network = match options.transport {
        Transport::Zenoh => {
            let net = options.network.as_ref().ok_or_else(|| Error::Backend {
                run: 0,
                message: "the zenoh transport needs network options".into(),
            })?;
            Some(Network::start(net, config.team.len())?)
        }
        Transport::InProcess => None,
    };
    let threads = match network {
        Some(_) => 1,
        None => options.threads.clamp(1, pending.len().max(1)),
    };
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                while !failed.load(Ordering::Relaxed) {
                    let Some(&run) = pending.get(next.fetch_add(1, Ordering::Relaxed) as usize)
                    else {
                        break;
                    };
                    match one_run(experiment, out, options, run, network.as_ref(), &tick) {
                        Ok(result) => {
                            done.fetch_add(1, Ordering::Relaxed);
                            tracing::info!(
                                run,
                                training_frames_per_sec = result.timing.training_frames_per_sec(),
                                "run finished"
                            );
                            results.lock().expect("no panic").push(result);
                        }
                        Err(e) => {
                            failed.store(true, Ordering::Relaxed);
                            errors.lock().expect("no panic").push((run, e));
                        }
                    }
                }
            });
        }
    });
    if options.bar.is_none() {
        bar.finish_and_clear();
    }
    let mut errors = errors.into_inner().expect("no panic");
    if !errors.is_empty() {
        errors.sort_by_key(|(run, _)| *run);
        return Err(errors.swap_remove(0).1);
    }
    let mut results: Vec<RunResult> = results.into_inner().expect("no panic");
    results.sort_by_key(|r| r.run);
    let summary = summarize(experiment, &results, options.transport == Transport::Zenoh);
    out.write_summary(&summary)?;
    let mut timing = Timing::default();
    for r in &results {
        timing.add(&r.timing);
    }
    let points = &summary.eval_points;
    Ok(Report {
        runs: results.len() as u64,
        timing,
        wall: start.elapsed(),
        summary: out.path().join(SUMMARY_FILE),
        first: points[0].clone(),
        last: points[points.len() - 1].clone(),
        results,
    })
}

/// One run: its backend, its CSV and, if asked, its agents saved.
fn one_run(
    experiment: &Experiment,
    out: &OutputDir,
    options: &RunOptions,
    run: u64,
    network: Option<&Network>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<RunResult, Error> {
    let mut backend = backend::open(options.transport, experiment, run, network)?;
    let mut writer = out.run_writer(run, experiment.config().team.len())?;
    let result = protocol::run(
        experiment,
        backend.as_mut(),
        run,
        |p| writer.write_point(p),
        progress,
    )?;
    if let Some(dir) = &options.save_agents {
        save_agents(dir, run, &backend.snapshots()?)?;
    }
    out.write_run_result(&result)?;
    Ok(result)
}

fn save_agents(dir: &Path, run: u64, snapshots: &[agent::Snapshot]) -> Result<(), Error> {
    for (i, s) in snapshots.iter().enumerate() {
        let path = dir.join(agent_file_name(run, i));
        s.save(&path).map_err(|e| match e {
            agent::PersistError::Io { source, .. } => Error::io("write", &path, source),
            other => Error::io("write", &path, std::io::Error::other(other.to_string())),
        })?;
    }
    Ok(())
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
