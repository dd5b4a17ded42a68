//! Each method's gain over its baseline, paired by run: on the mean of its
//! last ten evaluations, and on the area under its learning curve. Single
//! evaluation points are noisy (100 episodes each); these two average many
//! of them (docs/reproduction.md, "The gain, measured properly"). Besides,
//! the first evaluation's difference: the jumpstart.

use serde::Serialize;

use crate::baselines::Pair;
use crate::results::RunResult;
use crate::stats::{Estimate, estimate};
use crate::study::EntryResults;

/// How many of the last evaluation points the "last ten" mean averages.
pub const LAST_POINTS: usize = 10;

/// One method's level and its gain over the baseline, in goal percentage
/// points.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Gain {
    /// The method.
    pub entry: String,
    /// The baseline.
    pub baseline: String,
    /// Its mean goal % over the last ten evaluation points, over runs.
    pub last_ten: Estimate,
    /// That minus the baseline's, paired by run.
    pub last_ten_gain: Estimate,
    /// The area under its goal % curve, divided by the episodes it spans:
    /// the curve's mean height (trapezoids between evaluation points).
    pub area: Estimate,
    /// That minus the baseline's, paired by run.
    pub area_gain: Estimate,
    /// Its goal % at the first evaluation, over runs.
    pub first: Estimate,
    /// That minus the baseline's, paired by run: the jumpstart.
    pub first_gain: Estimate,
}

/// The goal % of a run's first evaluation point.
pub fn first(run: &RunResult) -> Option<f64> {
    run.points.first().map(|p| p.goal_pct)
}

/// The mean goal % of a run's last ten evaluation points (all of them if
/// it has fewer).
pub fn last_ten(run: &RunResult) -> Option<f64> {
    let points = &run.points[run.points.len().saturating_sub(LAST_POINTS)..];
    (!points.is_empty())
        .then(|| points.iter().map(|p| p.goal_pct).sum::<f64>() / points.len() as f64)
}

/// The mean height of a run's goal % curve over the episodes it spans
/// (its only point's value when it has one).
pub fn area(run: &RunResult) -> Option<f64> {
    let (first, last) = (run.points.first()?, run.points.last()?);
    let span = (last.episode - first.episode) as f64;
    if span == 0.0 {
        return Some(first.goal_pct);
    }
    let trapezoids: f64 = (run.points.windows(2))
        .map(|w| 0.5 * (w[0].goal_pct + w[1].goal_pct) * (w[1].episode - w[0].episode) as f64)
        .sum();
    Some(trapezoids / span)
}

/// The per-run values of `metric` for `a` and `b` over the runs both have.
fn paired(
    a: &EntryResults,
    b: &EntryResults,
    metric: fn(&RunResult) -> Option<f64>,
) -> Vec<(f64, f64)> {
    (a.results.iter())
        .filter_map(|ra| {
            let rb = b.results.iter().find(|rb| rb.run == ra.run)?;
            Some((metric(ra)?, metric(rb)?))
        })
        .collect()
}

/// The gain of `entry` over `baseline` with intervals at `level`.
pub fn gain(entry: &EntryResults, baseline: &EntryResults, level: f64) -> Gain {
    let level_of = |metric: fn(&RunResult) -> Option<f64>| {
        let values: Vec<f64> = entry.results.iter().filter_map(metric).collect();
        estimate(&values, level)
    };
    let gain_of = |metric| {
        let differences: Vec<f64> = (paired(entry, baseline, metric).into_iter())
            .map(|(x, y)| x - y)
            .collect();
        estimate(&differences, level)
    };
    Gain {
        entry: entry.entry.name.clone(),
        baseline: baseline.entry.name.clone(),
        last_ten: level_of(last_ten),
        last_ten_gain: gain_of(last_ten),
        area: level_of(area),
        area_gain: gain_of(area),
        first: level_of(first),
        first_gain: gain_of(first),
    }
}

/// Each pair's gain of its entry over its baseline, in their order.
pub fn gains(pairs: &[Pair], level: f64) -> Vec<Gain> {
    (pairs.iter())
        .map(|p| gain(p.entry, p.baseline, level))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::run_with_goals;

    /// Run `run` with goal percentages `goals` every 20 episodes.
    fn run(run: u64, goals: &[f64]) -> RunResult {
        run_with_goals(run, 20, goals)
    }

    #[test]
    fn the_last_ten_and_the_area_of_a_run() {
        let r = run(
            0,
            &[
                0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 110.0,
            ],
        );
        assert_eq!(last_ten(&r), Some(65.0));
        // A straight line from 0 to 110: its mean height is 55.
        assert_eq!(area(&r), Some(55.0));
        let flat = run(0, &[30.0]);
        assert_eq!((last_ten(&flat), area(&flat)), (Some(30.0), Some(30.0)));
        assert_eq!(area(&run(0, &[])), None);
    }
}
