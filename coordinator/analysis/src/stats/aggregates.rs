//! Each method's aggregate statistics (Agarwal et al. 2021, `rliable`;
//! see [`crate::stats::bootstrap`]): the mean and the interquartile mean of its
//! per-run scores with stratified bootstrap intervals, and its probability
//! of improvement over its baseline, on the last ten evaluations and on the
//! area under the curve (the scores of [`super::gains`]).

use std::collections::BTreeMap;

use serde::Serialize;

use crate::baselines::{Pair, common_baseline};
use crate::results::RunResult;
use crate::stats::bootstrap::{Aggregate, Improvement, RESAMPLES, SEED, aggregate, improvement};
use crate::stats::gains::{area, last_ten};
use crate::study::EntryResults;

/// One score's statistics over a method's runs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scores {
    /// Mean and IQM with their intervals.
    #[serde(flatten)]
    pub aggregate: Aggregate,
    /// P(a run of the method scores more than a run of its baseline), none
    /// for a baseline itself or without one.
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
    /// Its baseline: none for a baseline itself or without one.
    pub baseline: Option<String>,
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
    /// The baseline of every probability of improvement, if they share
    /// one (else each entry's own).
    pub baseline: Option<String>,
    /// Every method, in entry order.
    pub entries: Vec<EntryAggregate>,
}

/// `coordinator aggregate`'s answer: every algorithm's statistics of its
/// scores (one per run), with its probability of improvement over the
/// baseline's; fields in the order they are printed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ScoreAggregates<'a> {
    /// Each algorithm's statistics, none for an algorithm without a score.
    pub algorithms: BTreeMap<&'a str, Option<Scores>>,
    /// The baseline of the probabilities of improvement.
    pub baseline: &'a str,
    /// The intervals' confidence level.
    pub level: f64,
    /// Bootstrap resamples behind every interval.
    pub resamples: usize,
    /// The seed of every interval's generator.
    pub seed: u64,
}

/// The statistics of `scores` (each algorithm's scores, one per run) against
/// the algorithm named `baseline`; the error says which input is wrong.
pub fn score_aggregates<'a>(
    scores: &'a BTreeMap<String, Vec<f64>>,
    baseline: &'a str,
    level: f64,
) -> Result<ScoreAggregates<'a>, String> {
    if !(level > 0.0 && level < 1.0) {
        return Err(format!("the level must be in (0, 1), got {level}"));
    }
    if let Some((name, _)) = scores.iter().find(|(_, v)| v.is_empty()) {
        return Err(format!("{name} has no score"));
    }
    let Some(base) = scores.get(baseline) else {
        let names: Vec<&str> = scores.keys().map(String::as_str).collect();
        return Err(format!("no baseline {baseline:?} among {names:?}"));
    };
    let algorithms = (scores.iter())
        .map(|(name, x)| {
            let y = (name != baseline).then_some(base.as_slice());
            (name.as_str(), Scores::of(x, y, level))
        })
        .collect();
    Ok(ScoreAggregates {
        algorithms,
        baseline,
        level,
        resamples: RESAMPLES,
        seed: SEED,
    })
}

/// The scores of every run of `entry` that has one.
fn scores(entry: &EntryResults, metric: fn(&RunResult) -> Option<f64>) -> Vec<f64> {
    entry.results.iter().filter_map(metric).collect()
}

/// Every entry's statistics at `level`, with the probabilities of
/// improvement of `pairs`' entries over their baselines.
pub fn aggregates(entries: &[EntryResults], pairs: &[Pair], level: f64) -> Aggregates {
    let of =
        |e: &EntryResults, base: Option<&EntryResults>, metric: fn(&RunResult) -> Option<f64>| {
            let y = base.map(|b| scores(b, metric));
            Scores::of(&scores(e, metric), y.as_deref(), level)
        };
    Aggregates {
        level,
        resamples: RESAMPLES,
        seed: SEED,
        baseline: common_baseline(pairs).map(str::to_owned),
        entries: (entries.iter().enumerate())
            .map(|(slot, e)| {
                let base = pairs.iter().find(|p| p.slot == slot).map(|p| p.baseline);
                EntryAggregate {
                    entry: e.entry.name.clone(),
                    baseline: base.map(|b| b.entry.name.clone()),
                    last_ten: of(e, base, last_ten),
                    area: of(e, base, area),
                }
            })
            .collect(),
    }
}
