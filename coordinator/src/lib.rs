//! Experiments of "ad hoc advising among simultaneously learning agents"
//! (da Silva, Glatt & Costa, AAMAS 2017): the protocol of docs/algorithms.md
//! section 4 for one configuration, its runs in parallel, statistics and
//! output files.
//!
//! - [`config`]: what an experiment is ([`ExperimentConfig`], one
//!   [`AgentSpec`] per agent), validated with errors naming the key.
//! - [`transport`]: where agents and simulator live ([`Transport`]), part of
//!   an experiment's identity.
//! - [`seeds`]: the seed of every random stream of a run from `(seed, run, stream)`.
//! - [`experiment`]: a validated configuration with its snapshots loaded.
//! - [`replay`]: one evaluation episode of a team, recorded for pictures and monitors.
//! - [`request`]: what one `coordinator run` asks for, from the command line or Python.
//! - [`plugin`]: learners and strategies given as objects in this process (Python's `run()`).
//! - [`backend`]: the [`Backend`] a run is played on; [`in_process`] calls
//!   the simulator and an `agent::Team` directly, [`remote`] drives
//!   env-server and agents as processes over zenoh.
//! - [`driver`]: a transport opened for one experiment, handing out backends.
//! - [`schedule`]: one run: evaluate, train K, evaluate, ..., through N.
//! - [`stats`] and [`summary`]: mean and Student's t interval over runs.
//! - [`bootstrap`]: mean, IQM and probability of improvement with
//!   stratified bootstrap intervals (Agarwal et al. 2021, `rliable`).
//! - [`wilcoxon`]: signed-rank test between algorithms, intervals where one is better.
//! - [`store`]: the results directory: claim, resume, atomic writes.
//! - [`runner`]: R runs over T threads, then the summary.
//! - [`figures`]: the paper's figures of in-memory results, as SVG and PNG.
//! - [`study`]: the paper's experiments in one command: presets, tests
//!   between algorithms, figures and `REPORT.md`.
//!
//! ```no_run
//! use coordinator::{Experiment, ExperimentConfig, ExperimentDir, RunOptions, run_experiment};
//!
//! let config = ExperimentConfig { runs: 2, episodes: 100, ..ExperimentConfig::default() };
//! let experiment = Experiment::prepare(config)?;
//! let out = ExperimentDir::check("results/no-advice".as_ref(), &experiment.record())?;
//! let report = run_experiment(&experiment, &out, &RunOptions::default())?;
//! println!("{:?}", report.summary.eval_points.last());
//! # Ok::<(), coordinator::Error>(())
//! ```

#![warn(missing_docs)]

#[cfg(not(unix))]
compile_error!(
    "the coordinator runs on Unix only: it stops the processes it starts with Unix signals \
     (kill(2), SIGTERM and SIGINT handlers)"
);

pub mod agent_spec;
pub mod backend;
pub mod config;
pub mod driver;
pub mod error;
pub mod experiment;
pub mod in_process;
pub mod membership;
pub mod plugin;
pub mod provenance;
#[cfg(feature = "zenoh")]
pub mod remote;
pub mod replay;
pub mod request;
pub mod runner;
pub mod schedule;
pub mod seeds;
pub mod store;
pub mod study;
pub mod summary;
pub mod transport;

pub use analysis::{Estimate, EvalPoint, RunResult, Timing};
pub use backend::{Backend, EpisodeEnd};
pub use config::{AgentSpec, ExperimentConfig, TeamSpec, load_team_file};
pub use error::{ConfigError, Error};
pub use experiment::{Experiment, RunSeeds};
pub use in_process::InProcess;
#[cfg(feature = "zenoh")]
pub use remote::{RemoteBackend, ZenohTeam};
pub use runner::{Report, RunOptions, run_experiment};
pub use store::ExperimentDir;
pub use summary::{Summary, summarize};
pub use transport::{Endpoints, Transport, ZenohSettings};
