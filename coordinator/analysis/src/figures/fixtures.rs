//! Results to draw in the figures' tests.

use super::data::{Point, SeriesSet};
use crate::stats::Estimate;

/// A goal curve that rises and levels off, at episodes 0 to 500.
pub(super) const RISING: [Option<f64>; 6] = [
    Some(0.0),
    Some(10.0),
    Some(20.0),
    Some(30.0),
    Some(40.0),
    Some(42.0),
];

/// An estimate of `mean` ± 5 over 3 runs, or all unknown.
pub(super) fn estimate(mean: Option<f64>) -> Estimate {
    Estimate {
        n: 3,
        mean,
        ci_low: mean.map(|m| m - 5.0),
        ci_high: mean.map(|m| m + 5.0),
    }
}

/// A set of 3 runs whose goal percentage is `goal` at episodes 0, 100,
/// 200, ...; its time to goal is `120 - goal`, its spent budget grows by
/// 10 a point.
pub(super) fn set(label: &str, goal: &[Option<f64>]) -> SeriesSet {
    let points = goal
        .iter()
        .enumerate()
        .map(|(i, &g)| Point {
            episode: 100 * i as u64,
            goal_pct: estimate(g),
            time_to_goal: estimate(g.map(|g| 120.0 - g)),
            spent_budget: estimate(Some(10.0 * i as f64)),
            advising_messages: estimate((i > 0).then_some(2.0)),
            advising_bytes: estimate((i > 0).then_some(80.0)),
        })
        .collect();
    SeriesSet::new(label, 3, 0.95, points)
}
