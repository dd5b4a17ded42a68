//! An experiment's `summary.json`: its configuration, and the analysis's
//! summary of its runs (`analysis::stats::summary`).

use analysis::RunResult;
use analysis::stats::summary::{CommSummary, Cost, SummaryPoint, advice_matrices, summary_points};
use serde::Serialize;

use crate::config::ExperimentConfig;
use crate::experiment::Record;

/// What `summary.json` holds. It depends only on the configuration, the
/// loaded snapshots and the seed, never on threads or timing, except for the
/// measured times in `cost` (`wall_s`, `frames_per_sec`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Version of the output formats.
    pub format: u32,
    /// The experiment seed.
    pub seed: u64,
    /// Runs summarised.
    pub runs: u64,
    /// Confidence level of the intervals.
    pub ci_level: f64,
    /// The configuration.
    pub config: ExperimentConfig,
    /// Per agent, the digest of the snapshot it starts from (hex), or null.
    pub snapshot_digests: Vec<Option<String>>,
    /// Every evaluation point, in order.
    pub eval_points: Vec<SummaryPoint>,
    /// Who advised whom, per run (each as `RunResult::advice_matrix`, zeros
    /// where no advice was acted on); absent when no run acted on advice.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub advice_matrix: Vec<Vec<Vec<u64>>>,
    /// Communication costs, for runs whose agents are processes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub comm: Option<CommSummary>,
    /// What the runs cost in frames and time.
    pub cost: Cost,
}

/// Summarises `results`, which must be every run of the experiment
/// recorded in `record`, sorted by run index. Over a transport that
/// communicates, the summary also holds the communication costs.
pub fn summarize(record: &Record<'_>, results: &[RunResult]) -> Summary {
    debug_assert!(results.windows(2).all(|w| w[0].run < w[1].run));
    let config = record.config;
    let level = config.ci_level;
    let eval_points = summary_points(results, level);
    Summary {
        format: record.format,
        seed: config.seed,
        runs: results.len() as u64,
        ci_level: level,
        config: config.clone(),
        snapshot_digests: record.snapshot_digests.clone(),
        eval_points,
        advice_matrix: advice_matrices(results, config.team.len()),
        comm: config
            .transport
            .communicates()
            .then(|| CommSummary::of(results, config.team.len())),
        cost: Cost::of(results),
    }
}
