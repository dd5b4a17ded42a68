//! The experiment's summary: at every evaluation point, the mean and
//! confidence interval over runs of each metric.

use serde::Serialize;

use crate::config::ExperimentConfig;
use crate::experiment::{Experiment, FORMAT_VERSION};
use crate::protocol::RunResult;
use crate::stats::{Estimate, estimate};

/// One evaluation point over all runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SummaryPoint {
    /// Training episodes played before the evaluation.
    pub episode: u64,
    /// Goal percentage.
    pub goal_pct: Estimate,
    /// Mean frames to a goal, over the runs that scored at this point.
    pub time_to_goal: Estimate,
    /// Give budget spent, averaged over agents.
    pub spent_budget: Estimate,
}

/// What `summary.json` holds. It depends only on the configuration, the
/// loaded snapshots and the seed: never on threads or timing.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary<'a> {
    /// Version of the output formats.
    pub format: u32,
    /// The experiment seed.
    pub seed: u64,
    /// Runs summarised.
    pub runs: u64,
    /// Confidence level of the intervals.
    pub ci_level: f64,
    /// The configuration.
    pub config: &'a ExperimentConfig,
    /// Per agent, the digest of the snapshot it starts from (hex), or null.
    pub snapshot_digests: Vec<Option<String>>,
    /// Every evaluation point, in order.
    pub eval_points: Vec<SummaryPoint>,
}

/// Summarises `results`, which must be every run of `experiment`, sorted by
/// run index.
pub fn summarize<'a>(experiment: &'a Experiment, results: &[RunResult]) -> Summary<'a> {
    debug_assert!(results.windows(2).all(|w| w[0].run < w[1].run));
    let config = experiment.config();
    let level = config.ci_level;
    let points = config.eval_points();
    let column = |p: usize, f: &dyn Fn(&crate::protocol::EvalPoint) -> Option<f64>| {
        results
            .iter()
            .filter_map(|r| r.points.get(p).and_then(f))
            .collect::<Vec<f64>>()
    };
    let eval_points = points
        .iter()
        .enumerate()
        .map(|(p, &episode)| SummaryPoint {
            episode,
            goal_pct: estimate(&column(p, &|e| Some(e.goal_pct)), level),
            time_to_goal: estimate(&column(p, &|e| e.time_to_goal), level),
            spent_budget: estimate(&column(p, &|e| Some(e.spent_budget)), level),
        })
        .collect();
    Summary {
        format: FORMAT_VERSION,
        seed: config.seed,
        runs: results.len() as u64,
        ci_level: level,
        config,
        snapshot_digests: experiment.record().snapshot_digests,
        eval_points,
    }
}
