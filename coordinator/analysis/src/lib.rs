//! The analysis of advising experiments, apart from running them: from the
//! results files alone (docs/results.md), every statistic, figure and the
//! study's `REPORT.md`. It depends on no transport and no runner; the
//! coordinator's `study` calls it after playing, and `analyse DIR` (this
//! crate's binary) re-analyses a study directory, or with `--publish DEST`
//! publishes it.
//!
//! - [`results`]: what a run records (`run-<k>.json`).
//! - [`study`]: what a study ran (`study.json`) and each entry's runs.
//! - [`baselines`]: which entry each entry is compared with.
//! - [`stats`]: means and intervals, the summary of an experiment,
//!   Wilcoxon, Holm, gains, bootstrap aggregates.
//! - [`figures`]: the figures, as SVG and PNG.
//! - [`report`]: `REPORT.md`, `significance.json` and the figures of a
//!   study, one module per section.
//! - [`files`]: a study directory read (plain or published), the report
//!   written.
//! - [`publish`]: a study published: what redraws its figures, its runs
//!   gzipped.
//! - [`published`]: the authors' published results read as runs.
//!
//! ```no_run
//! let dir = std::path::Path::new("results/quick");
//! let (study, entries) = analysis::files::read_study(dir)?;
//! let report = analysis::report::write_report(dir, &study, &entries)?;
//! println!("{}", report.display());
//! # Ok::<(), analysis::Error>(())
//! ```

#![warn(missing_docs)]

pub mod baselines;
mod difference;
pub mod error;
pub mod figures;
pub mod files;
#[cfg(test)]
mod fixtures;
mod newcomers;
pub mod publish;
pub mod published;
pub mod report;
pub mod results;
pub mod stats;
pub mod study;
mod sweep;

pub use error::Error;
pub use results::{
    AgentStats, EvalPoint, Join, PlayedWith, Restart, RunResult, SimulatorRestart, Timing,
};
pub use stats::{Estimate, estimate};
pub use study::{Entry, EntryResults, Study};
