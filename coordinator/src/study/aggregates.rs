//! Each method's aggregate statistics (Agarwal et al. 2021, `rliable`;
//! see [`crate::bootstrap`]): the mean and the interquartile mean of its
//! per-run scores with stratified bootstrap intervals, and its probability
//! of improvement over the baseline, on the last ten evaluations and on the
//! area under the curve (the scores of [`super::gains`]).

use serde::Serialize;

use super::analysis::EntryResults;
use super::gains::{area, last_ten};
use crate::bootstrap::{Aggregate, Improvement, RESAMPLES, SEED, aggregate, improvement};
use crate::schedule::RunResult;

/// One score's statistics over a method's runs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scores {
    /// Mean and IQM with their intervals.
    #[serde(flatten)]
    pub aggregate: Aggregate,
    /// P(a run of the method scores more than a run of the baseline), none
    /// for the baseline itself or without one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p_improvement: Option<Improvement>,
}

impl Scores {
    /// The statistics of `scores` at `level`, with the probability of
    /// improvement over `baseline`'s scores if given (none without a score).
    pub fn of(scores: &[f64], baseline: Option<&[f64]>, level: f64) -> Option<Scores> {
        Some(Scores {
            aggregate: aggregate(scores, level)?,
            p_improvement: baseline.and_then(|y| improvement(scores, y, level)),
        })
    }
}

/// One method's statistics.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EntryAggregate {
    /// The method.
    pub entry: String,
    /// On the mean goal % of each run's last ten evaluations.
    pub last_ten: Option<Scores>,
    /// On the mean height of each run's goal % curve.
    pub area: Option<Scores>,
}

/// Every method's statistics, and how they were computed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Aggregates {
    /// The intervals' confidence level.
    pub level: f64,
    /// Bootstrap resamples behind every interval.
    pub resamples: usize,
    /// The seed of every interval's generator.
    pub seed: u64,
    /// The baseline of the probabilities of improvement.
    pub baseline: Option<String>,
    /// Every method, in entry order.
    pub entries: Vec<EntryAggregate>,
}

/// The scores of every run of `entry` that has one.
fn scores(entry: &EntryResults, metric: fn(&RunResult) -> Option<f64>) -> Vec<f64> {
    entry.results.iter().filter_map(metric).collect()
}

/// Every entry's statistics at `level`, with probabilities of improvement
/// over the entry named `baseline` if there is one.
pub fn aggregates(entries: &[EntryResults], baseline: Option<&str>, level: f64) -> Aggregates {
    let base = entries
        .iter()
        .find(|e| Some(e.entry.name.as_str()) == baseline);
    let of = |e: &EntryResults, metric: fn(&RunResult) -> Option<f64>| {
        let y = (base.filter(|b| b.entry.name != e.entry.name)).map(|b| scores(b, metric));
        Scores::of(&scores(e, metric), y.as_deref(), level)
    };
    Aggregates {
        level,
        resamples: RESAMPLES,
        seed: SEED,
        baseline: base.map(|b| b.entry.name.clone()),
        entries: (entries.iter())
            .map(|e| EntryAggregate {
                entry: e.entry.name.clone(),
                last_ten: of(e, last_ten),
                area: of(e, area),
            })
            .collect(),
    }
}
