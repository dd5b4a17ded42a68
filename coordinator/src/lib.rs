//! Experiments of "ad hoc advising among simultaneously learning agents"
//! (da Silva, Glatt & Costa, AAMAS 2017): the protocol of docs/algorithms.md
//! section 4 for one configuration, its runs in parallel, statistics and
//! output files.
//!
//! - [`config`]: what an experiment is ([`ExperimentConfig`], one
//!   [`AgentSpec`] per agent), validated with errors naming the key.
//! - [`seeds`]: every run's and role's seed from `(seed, run, role)`.
//! - [`experiment`]: a validated configuration with its snapshots loaded.
//! - [`backend`]: the [`Backend`] the protocol drives; [`InProcess`] calls
//!   the simulator and an `agent::Team` directly.
//! - [`remote`]: the zenoh transport: env-server and agents as processes.
//! - [`protocol`]: one run: evaluate, train K, evaluate, ..., through N.
//! - [`stats`] and [`summary`]: mean and Student's t interval over runs.
//! - [`wilcoxon`]: signed-rank test between algorithms, intervals where one is better.
//! - [`output`]: `config.json`, `run-<k>.csv`, `summary.json`.
//! - [`runner`]: R runs over T threads, then the summary.
//! - [`figures`]: the paper's figures of summaries, as SVG and PNG.
//! - [`study`]: the paper's experiments in one command: presets, tests
//!   between algorithms, figures and `REPORT.md`.
//!
//! ```no_run
//! use coordinator::{Experiment, ExperimentConfig, OutputDir, RunOptions, run_experiment};
//!
//! let config = ExperimentConfig { runs: 2, episodes: 100, ..ExperimentConfig::default() };
//! let experiment = Experiment::prepare(config)?;
//! let out = OutputDir::check("results/no-advice".as_ref(), &experiment.record())?;
//! let report = run_experiment(&experiment, &out, &RunOptions::default())?;
//! println!("{:?}", report.last.goal_pct);
//! # Ok::<(), coordinator::Error>(())
//! ```

#![warn(missing_docs)]

pub mod backend;
pub mod config;
pub mod error;
pub mod experiment;
pub mod figures;
pub mod output;
pub mod protocol;
pub mod remote;
pub mod runner;
pub mod seeds;
pub mod stats;
pub mod study;
pub mod summary;
pub mod wilcoxon;

pub use backend::{AgentStats, Backend, Episode, InProcess, Transport};
pub use config::{AgentSpec, ConfigError, ExperimentConfig, load_team_file};
pub use error::Error;
pub use experiment::{Experiment, RunSeeds};
pub use figures::{FigureError, Metric, Series, SeriesSet, write_figures};
pub use output::OutputDir;
pub use protocol::{EvalPoint, RunResult, Timing};
pub use remote::{Network, NetworkOptions, RemoteBackend};
pub use runner::{Report, RunOptions, run_experiment};
pub use stats::{Estimate, estimate};
pub use summary::{Summary, SummaryPoint, summarize};
pub use wilcoxon::{Interval, SignedRank, better_intervals, signed_rank};
