//! Studies: the paper's experiments in one command. A study runs several
//! experiments (one per algorithm, optionally after a pretraining stage)
//! and hands their runs to the analysis (`analysis::report`), which
//! compares them run by run, draws figures and writes `REPORT.md`; started
//! again on the same directory it continues from the runs already finished.
//! Split into shards (`--shard K/N`), several processes, on one host or
//! many sharing a file system, play their shares into one directory at the
//! same time; an invocation without a shard then completes it.

mod config;
mod run;
mod shard;

pub use config::{PRESETS, Pretrain, StudyConfig, StudyEntry};
pub use run::{StudyOptions, StudyOutcome, run_study};
pub use shard::{MAX_SHARDS, Shard};
