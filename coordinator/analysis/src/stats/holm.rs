//! The study's tests against the baselines with Holm's correction across
//! the methods compared with the same baseline: at every evaluation point,
//! the Wilcoxon p-values of every method against one baseline form one
//! family (one family per baseline).

use std::collections::BTreeMap;

use serde::Serialize;

use crate::baselines::Pair;
use crate::stats::analysis::point_tests;
use crate::stats::wilcoxon::{Interval, better_intervals};

/// Where one method is significantly better or worse than its baseline,
/// on Holm-adjusted p-values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HolmComparison {
    /// The method.
    pub entry: String,
    /// Its baseline.
    pub baseline: String,
    /// Episode intervals `[first, last]` where the method is better.
    pub better: Vec<Interval>,
    /// Episode intervals where it is worse.
    pub worse: Vec<Interval>,
    /// Adjusted two-sided p-value at the last evaluation point.
    pub final_p: Option<f64>,
}

/// Each pair's comparison of its entry with its baseline at level
/// `alpha`, in their order.
pub fn holm_against(pairs: &[Pair], alpha: f64) -> Vec<HolmComparison> {
    let mut tests: Vec<Vec<(u64, f64, f64)>> = pairs
        .iter()
        .map(|p| point_tests(&p.entry.results, &p.baseline.results))
        .collect();
    // Every family, by baseline and episode: (method, test) of the methods
    // tested there against that baseline.
    let mut families: BTreeMap<(&str, u64), Vec<(usize, usize)>> = BTreeMap::new();
    for (m, (t, pair)) in tests.iter().zip(pairs).enumerate() {
        for (k, &(episode, _, _)) in t.iter().enumerate() {
            (families.entry((pair.baseline_name(), episode)).or_default()).push((m, k));
        }
    }
    for family in families.values() {
        let p: Vec<f64> = family.iter().map(|&(m, k)| tests[m][k].1).collect();
        for (&(m, k), adjusted) in family.iter().zip(holm(&p)) {
            tests[m][k].1 = adjusted;
        }
    }
    (pairs.iter().zip(&tests))
        .map(|(pair, t)| {
            let (better, worse) = better_intervals(t, alpha);
            HolmComparison {
                entry: pair.entry.entry.name.clone(),
                baseline: pair.baseline_name().to_owned(),
                better,
                worse,
                final_p: t.last().map(|t| t.1),
            }
        })
        .collect()
}

/// Holm's step-down adjustment of a family of p-values, in their order:
/// with the m p-values sorted ascending, the k-th (from 0) becomes the
/// largest of min(1, (m - j) p_(j)) over j <= k. Rejecting where the
/// adjusted p-value is below alpha bounds the family-wise error by alpha.
pub fn holm(p: &[f64]) -> Vec<f64> {
    let m = p.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&i, &j| p[i].total_cmp(&p[j]));
    let mut adjusted = vec![0.0; m];
    let mut running = 0.0f64;
    for (k, &i) in order.iter().enumerate() {
        running = running.max(((m - k) as f64 * p[i]).min(1.0));
        adjusted[i] = running;
    }
    adjusted
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn holm_by_hand() {
        // Sorted 0.01, 0.02, 0.03, 0.5 times 4, 3, 2, 1: 0.04, 0.06, 0.06
        // (kept monotone), 0.5; statsmodels' multipletests(method="holm").
        let got = holm(&[0.03, 0.5, 0.01, 0.02]);
        let want = [0.06, 0.5, 0.04, 0.06];
        assert!(
            got.iter().zip(want).all(|(g, w)| (*g - w).abs() <= 1e-12),
            "{got:?}"
        );
        assert_eq!(holm(&[0.9, 0.8]), vec![1.0, 1.0]);
        assert_eq!(holm(&[]), Vec::<f64>::new());
    }
}
