//! Studies: the paper's experiments in one command. A study runs several
//! experiments (one per algorithm, optionally after a pretraining stage),
//! compares them run by run, draws figures and writes `REPORT.md`; started
//! again on the same directory it continues from the runs already finished.

mod analysis;
mod config;
mod report;
mod run;

pub use analysis::{Comparison, EntryResults, compare};
pub use config::{Entry, PRESETS, Pretrain, StudyConfig};
pub use run::{StudyOptions, StudyOutcome, run_study};
