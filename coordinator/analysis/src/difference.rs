//! Each method's goal % minus its baseline's at every evaluation point,
//! paired by run, with the verdicts of the study's signed-rank tests
//! against the baseline: the input of the difference figure.

use crate::baselines::Pair;
use crate::figures::{DifferencePoint, DifferenceSet};
use crate::results::RunResult;
use crate::stats::analysis::point_tests;
use crate::stats::estimate;
use crate::stats::wilcoxon::better_side;

/// The differences of each pair's entry from its baseline, with intervals
/// at `level` and tests at `1 - level`.
pub fn difference_sets(pairs: &[Pair], level: f64) -> Vec<DifferenceSet> {
    (pairs.iter())
        .map(|p| {
            let (runs, base) = (&p.entry.results, &p.baseline.results);
            DifferenceSet {
                label: p.entry.entry.name.clone(),
                slot: p.slot,
                runs: (runs.iter())
                    .filter(|r| base.iter().any(|b| b.run == r.run))
                    .count() as u64,
                ci_level: level,
                points: differences(runs, base, level),
            }
        })
        .collect()
}

/// The differences of `runs` from `base` at every evaluation point of the
/// first run, paired by run number.
fn differences(runs: &[RunResult], base: &[RunResult], level: f64) -> Vec<DifferencePoint> {
    let tests = point_tests(runs, base);
    let goal = |r: &RunResult, episode| {
        (r.points.iter())
            .find(|p| p.episode == episode)
            .map(|p| p.goal_pct)
    };
    let episodes = runs.first().map_or(&[][..], |r| &r.points);
    (episodes.iter())
        .map(|p| {
            let differences: Vec<f64> = (runs.iter())
                .filter_map(|r| {
                    let b = base.iter().find(|b| b.run == r.run)?;
                    Some(goal(r, p.episode)? - goal(b, p.episode)?)
                })
                .collect();
            let better = (tests.iter())
                .find(|t| t.0 == p.episode)
                .and_then(|&(_, p, mean_diff)| better_side(p, mean_diff, 1.0 - level));
            DifferencePoint {
                episode: p.episode,
                difference: estimate(&differences, level),
                better,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{against, entry_results, run_with_goals};

    /// Run `run` with goal percentages `goals` every 50 episodes.
    fn run(run: u64, goals: &[f64]) -> RunResult {
        run_with_goals(run, 50, goals)
    }

    #[test]
    fn differences_are_paired_by_run_with_the_tests_verdicts() {
        // The baseline varies a lot between runs; each method run is its
        // baseline run plus 1..6 at episode 0, minus that at 50, plus 0 at
        // 100.
        let base: Vec<RunResult> = (0..6)
            .map(|k| run(k, &[10.0 * k as f64, 20.0 * k as f64, 5.0]))
            .collect();
        let method: Vec<RunResult> = (0..6)
            .map(|k| {
                let d = k as f64 + 1.0;
                run(k, &[10.0 * k as f64 + d, 20.0 * k as f64 - d, 5.0])
            })
            .collect();
        let entries = [
            entry_results("base", None, base),
            entry_results("method", None, method),
        ];
        let sets = difference_sets(&against(&entries, "base"), 0.95);
        assert_eq!(sets.len(), 1);
        let set = &sets[0];
        assert_eq!((set.label.as_str(), set.slot, set.runs), ("method", 1, 6));
        let ds = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let negated: Vec<f64> = ds.iter().map(|d| -d).collect();
        let expected = [
            (0, estimate(&ds, 0.95), Some(true)),
            (50, estimate(&negated, 0.95), Some(false)),
            (100, estimate(&[0.0; 6], 0.95), None),
        ];
        for (p, (episode, difference, better)) in set.points.iter().zip(expected) {
            assert_eq!(
                (p.episode, p.difference, p.better),
                (episode, difference, better)
            );
        }
        // The interval is the paired one: narrow despite the spread.
        let d = set.points[0].difference;
        assert!(d.ci_high.unwrap() - d.ci_low.unwrap() < 5.0, "{d:?}");
        // Without a baseline among the entries, nothing.
        assert!(difference_sets(&against(&entries, "other"), 0.95).is_empty());
    }
}
