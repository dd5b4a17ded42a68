//! `run()`, `study()` and `replay()`: the coordinator's experiments in this process,
//! from the same arguments as `coordinator run` and `coordinator study`
//! (the package's `adhoc_advising.experiments` gives them their Python
//! signatures and turns Python learners into [`PythonObjects`]).
//!
//! The work runs in a thread of its own while the calling thread, the GIL
//! released, waits for it and for Ctrl-C: then the runs stop after the
//! episodes in flight, their files whole, and `KeyboardInterrupt` is raised.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use agent::{Algorithm, Profile};
use coordinator::experiment::Plugins;
use coordinator::plugin::{Plugin, PluginSpec};
use coordinator::replay::record_evaluation;
use coordinator::request::{Agents, RunRequest};
use coordinator::study::{StudyConfig, StudyOptions};
use coordinator::{Error, Experiment, ExperimentDir, RunOptions, TeamSpec, load_team_file};
use env_server::tools::rcg;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use crate::objects::{Failure, PythonObjects};

/// One Python object: the factory of its adapter and what it says it is.
type Made = (Py<PyAny>, String);

/// One agent's Python learner and strategy, either possibly absent.
type AgentObjects = (Option<Made>, Option<Made>);

/// An error of the coordinator as the Python exception a user expects.
fn to_python(e: Error) -> PyErr {
    match e {
        Error::Config(_) | Error::OtherResults { .. } | Error::Snapshot { .. } => {
            PyValueError::new_err(e.to_string())
        }
        Error::Io { .. } | Error::NotADirectory(_) => PyOSError::new_err(e.to_string()),
        _ => PyRuntimeError::new_err(e.to_string()),
    }
}

/// A value of `what` parsed from its name, or a `ValueError` naming it.
fn parse<T: std::str::FromStr>(what: &str, name: &str) -> PyResult<T>
where
    T::Err: std::fmt::Display,
{
    name.parse()
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}

/// Runs `work` in a thread of its own and waits for it with the GIL
/// released, checking for Ctrl-C every 100 ms: then sets `stop` and waits
/// for the episodes in flight before raising `KeyboardInterrupt`.
fn in_background<T: Send + 'static>(
    py: Python<'_>,
    stop: Arc<AtomicBool>,
    work: impl FnOnce() -> T + Send + 'static,
) -> PyResult<T> {
    let (tx, rx) = mpsc::channel();
    std::thread::Builder::new()
        .name("adhoc-advising".into())
        .spawn(move || {
            let _ = tx.send(work());
        })
        .map_err(|e| {
            PyRuntimeError::new_err(format!("cannot start the experiment's thread: {e}"))
        })?;
    let ended = || PyRuntimeError::new_err("the experiment's thread ended without an answer");
    // Behind a lock only to cross into the GIL-free closure.
    let rx = Mutex::new(rx);
    let rx = || rx.lock().unwrap_or_else(PoisonError::into_inner);
    loop {
        match py.detach(|| rx().recv_timeout(Duration::from_millis(100))) {
            Ok(answer) => return Ok(answer),
            Err(RecvTimeoutError::Disconnected) => return Err(ended()),
            Err(RecvTimeoutError::Timeout) => {}
        }
        if let Err(interrupt) = py.check_signals() {
            stop.store(true, Ordering::Relaxed);
            py.detach(|| rx().recv()).map_err(|_| ended())?;
            return Err(interrupt);
        }
    }
}

/// The first exception of a Python object, raised as `RuntimeError` from it
/// (its traceback kept as the cause's); else `e` as is.
fn with_cause(py: Python<'_>, e: Error, failures: &[Arc<Failure>]) -> PyErr {
    let Some((message, cause)) = failures.iter().find_map(|f| f.take(py)) else {
        return to_python(e);
    };
    let run = match &e {
        Error::Run { run, .. } => format!("run {run}: "),
        _ => String::new(),
    };
    let err = PyRuntimeError::new_err(format!("{run}{message}"));
    err.set_cause(py, Some(PyErr::from_value(cause.into_bound(py))));
    err
}

/// Who plays: `algorithm` for every agent, or a team file, or a team
/// file's tables as JSON.
fn agents(
    algorithm: Option<&str>,
    team_file: Option<PathBuf>,
    team_tables: Option<&str>,
    mistake_correcting: bool,
) -> PyResult<Agents> {
    let team = |t: Result<TeamSpec, coordinator::ConfigError>| t.map_err(|e| to_python(e.into()));
    Ok(match (algorithm, team_file, team_tables) {
        (Some(name), None, None) => Agents::Algorithm {
            algorithm: parse::<Algorithm>("algorithm", name)?,
            mistake_correcting,
        },
        (None, Some(path), None) => Agents::Team(team(load_team_file(&path))?),
        (None, None, Some(json)) => {
            let tables = serde_json::from_str(json)
                .map_err(|e| PyValueError::new_err(format!("team: {e}")))?;
            Agents::Team(team(TeamSpec::from_json(tables, Path::new(""), "team"))?)
        }
        _ => return Err(PyValueError::new_err("give one of algorithm= and team=")),
    })
}

/// The plugins of `objects` for a team of `n` (agents not given: none),
/// and each agent's failure slot.
fn plugins(mut objects: Vec<AgentObjects>, n: usize) -> (Plugins, Vec<Arc<Failure>>) {
    objects.resize_with(n.max(objects.len()), || (None, None));
    let failures: Vec<Arc<Failure>> = objects.iter().map(|_| Arc::default()).collect();
    let plugins = (objects.into_iter().zip(&failures))
        .map(|(objects, failure)| match objects {
            (None, None) => None,
            (learner, strategy) => Some(Arc::new(PythonObjects {
                spec: PluginSpec {
                    learner: learner.as_ref().map(|(_, label)| label.clone()),
                    strategy: strategy.as_ref().map(|(_, label)| label.clone()),
                },
                learner: learner.map(|(make, _)| make),
                strategy: strategy.map(|(make, _)| make),
                failure: failure.clone(),
            }) as Arc<dyn Plugin>),
        })
        .collect();
    (plugins, failures)
}

/// Plays an experiment into `out` as `coordinator run --transport
/// in-process` does; returns the summary's path. `objects`: per agent, its
/// Python learner and strategy, if any (agents not given: none).
#[pyfunction]
#[pyo3(signature = (
    *, out, objects, algorithm=None, team_file=None, team_tables=None,
    mistake_correcting=false, learner=None, runs=50, episodes=5000, eval_every=20,
    eval_episodes=100, seed=1, profile="paper", ci_level=None, offense=None, evaluation_memory="carried",
    advice_latency=None, advice_loss=None, advice_timeout_ms=None, threads=None,
    save_agents=None, progress=false
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn run(
    py: Python<'_>,
    out: PathBuf,
    objects: Vec<AgentObjects>,
    algorithm: Option<&str>,
    team_file: Option<PathBuf>,
    team_tables: Option<&str>,
    mistake_correcting: bool,
    learner: Option<String>,
    runs: u64,
    episodes: u64,
    eval_every: u64,
    eval_episodes: u64,
    seed: u64,
    profile: &str,
    ci_level: Option<f64>,
    offense: Option<usize>,
    evaluation_memory: &str,
    advice_latency: Option<&str>,
    advice_loss: Option<f64>,
    advice_timeout_ms: Option<u64>,
    threads: Option<usize>,
    save_agents: Option<PathBuf>,
    progress: bool,
) -> PyResult<PathBuf> {
    let agents = agents(algorithm, team_file, team_tables, mistake_correcting)?;
    let request = RunRequest {
        runs,
        episodes,
        eval_every,
        eval_episodes,
        seed,
        profile: parse::<Profile>("profile", profile)?,
        ci_level,
        offense,
        evaluation_memory: parse("evaluation_memory", evaluation_memory)?,
        advice_latency: advice_latency
            .map(|d| parse("advice_latency", d))
            .transpose()?,
        advice_loss,
        advice_timeout_ms,
        learner,
        ..RunRequest::new(agents)
    };
    let config = request.config().map_err(|e| to_python(e.into()))?;
    let (plugins, failures) = plugins(objects, config.team.len());
    let stop = Arc::new(AtomicBool::new(false));
    let options = RunOptions {
        threads: threads.unwrap_or_else(coordinator::runner::default_threads),
        save_agents,
        progress,
        bar: None,
        stop: Some(stop.clone()),
    };
    let result = in_background(py, stop, move || -> Result<PathBuf, Error> {
        let experiment = Experiment::prepare_with(config, plugins)?;
        let dir = ExperimentDir::check(&out, &experiment.record())?;
        Ok(coordinator::run_experiment(&experiment, &dir, &options)?.summary_path)
    })?;
    result.map_err(|e| with_cause(py, e, &failures))
}

/// Plays a study into `out` as `coordinator study` does (a preset or a
/// study file, with the same overrides); returns `REPORT.md`'s path, or
/// `None` for a shard.
#[pyfunction]
#[pyo3(signature = (*, out, preset=None, config=None, runs=None, episodes=None, threads=None, progress=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn study(
    py: Python<'_>,
    out: PathBuf,
    preset: Option<&str>,
    config: Option<PathBuf>,
    runs: Option<u64>,
    episodes: Option<u64>,
    threads: Option<usize>,
    progress: bool,
) -> PyResult<Option<PathBuf>> {
    let mut study = match (preset, config) {
        (Some(name), None) => StudyConfig::preset(name),
        (None, Some(path)) => StudyConfig::load(&path),
        _ => return Err(PyValueError::new_err("give one of preset= and config=")),
    }
    .map_err(Error::from)
    .map_err(to_python)?;
    if let Some(runs) = runs {
        study.runs = runs;
    }
    if let Some(episodes) = episodes {
        study.episodes = episodes;
    }
    let stop = Arc::new(AtomicBool::new(false));
    let options = StudyOptions {
        threads: threads.unwrap_or_else(coordinator::runner::default_threads),
        progress,
        shard: None,
        stop: Some(stop.clone()),
    };
    let outcome = in_background(py, stop, move || {
        coordinator::study::run_study(&study, &out, &options)
    })?;
    outcome.map(|o| o.report).map_err(to_python)
}

/// Plays evaluation episode `episode` of a team (`algorithm` for every
/// agent, or a team whose agents `load` their snapshots) on a simulator
/// seeded `seed`; returns its summary, its animation and its paths (SVG),
/// and its rcssserver log.
#[pyfunction]
#[pyo3(signature = (
    *, objects, algorithm=None, team_file=None, team_tables=None, seed=1, episode=1,
    profile="paper"
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn replay(
    py: Python<'_>,
    objects: Vec<AgentObjects>,
    algorithm: Option<&str>,
    team_file: Option<PathBuf>,
    team_tables: Option<&str>,
    seed: u64,
    episode: u64,
    profile: &str,
) -> PyResult<(String, String, String, String)> {
    let request = RunRequest {
        runs: 1,
        episodes: 0,
        profile: parse::<Profile>("profile", profile)?,
        ..RunRequest::new(agents(algorithm, team_file, team_tables, false)?)
    };
    let label = request.label();
    let config = request.config().map_err(|e| to_python(e.into()))?;
    let (plugins, failures) = plugins(objects, config.team.len());
    let trace = py
        .detach(|| {
            let experiment = Experiment::prepare_with(config, plugins)?;
            record_evaluation(&experiment, seed, episode, &label)
        })
        .map_err(|e| with_cause(py, e, &failures))?;
    Ok((
        trace.summary(),
        trace.to_animated_svg(),
        trace.to_svg(),
        rcg::to_rcg(&trace),
    ))
}
