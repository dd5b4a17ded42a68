//! Comparisons between the study's experiments: at every evaluation point,
//! a Wilcoxon signed-rank test of goal percentages paired by run.

use serde::Serialize;

use crate::results::RunResult;
use crate::stats::wilcoxon::{Interval, better_intervals, signed_rank};
use crate::study::{EntryResults, Study};

/// Where one experiment is significantly better than another.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// The first experiment.
    pub a: String,
    /// The second experiment.
    pub b: String,
    /// Episode intervals `[first, last]` where `a` is significantly better.
    pub a_better: Vec<Interval>,
    /// Episode intervals where `b` is significantly better.
    pub b_better: Vec<Interval>,
    /// Two-sided p-value at the last evaluation point (none without data).
    pub final_p: Option<f64>,
}

/// The signed-rank tests of the goal percentages of `a` and `b` (every run,
/// sorted by run) at every evaluation point that has one: its episode, the
/// two-sided p-value and the difference of the means, `a` minus `b`.
pub fn point_tests(ra: &[RunResult], rb: &[RunResult]) -> Vec<(u64, f64, f64)> {
    let points = ra.first().map_or(0, |r| r.points.len());
    let mut tests = Vec::with_capacity(points);
    for p in 0..points {
        let goal_pct = |runs: &[RunResult]| -> Vec<f64> {
            runs.iter()
                .filter_map(|r| r.points.get(p))
                .map(|e| e.goal_pct)
                .collect()
        };
        let (x, y) = (goal_pct(ra), goal_pct(rb));
        let Some(test) = signed_rank(&x, &y) else {
            continue;
        };
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        tests.push((ra[0].points[p].episode, test.p_value, mean(&x) - mean(&y)));
    }
    tests
}

/// Compares the goal percentages of `a` and `b` (every run, sorted by run)
/// point by point at level `alpha`.
pub fn compare(a: &EntryResults, b: &EntryResults, alpha: f64) -> Comparison {
    let tests = point_tests(&a.results, &b.results);
    let (a_better, b_better) = better_intervals(&tests, alpha);
    Comparison {
        a: a.entry.name.clone(),
        b: b.entry.name.clone(),
        a_better,
        b_better,
        final_p: tests.last().map(|t| t.1),
    }
}

/// Every pair of the study's experiments, in entry order.
pub fn compare_all(study: &Study, entries: &[EntryResults]) -> Vec<Comparison> {
    let alpha = 1.0 - study.ci_level();
    let mut out = Vec::new();
    for (i, a) in entries.iter().enumerate() {
        for b in &entries[i + 1..] {
            out.push(compare(a, b, alpha));
        }
    }
    out
}
