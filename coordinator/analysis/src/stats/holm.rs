//! The study's tests against the baseline with Holm's correction across
//! the methods compared with it: at every evaluation point, the Wilcoxon
//! p-values of every method against the baseline form one family.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::stats::analysis::point_tests;
use crate::stats::wilcoxon::{Interval, better_intervals};
use crate::study::EntryResults;

/// Where one method is significantly better or worse than the baseline,
/// on Holm-adjusted p-values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HolmComparison {
    /// The method.
    pub entry: String,
    /// The baseline.
    pub baseline: String,
    /// Episode intervals `[first, last]` where the method is better.
    pub better: Vec<Interval>,
    /// Episode intervals where it is worse.
    pub worse: Vec<Interval>,
    /// Adjusted two-sided p-value at the last evaluation point.
    pub final_p: Option<f64>,
}

/// Every entry's comparison with the entry named `baseline` at level
/// `alpha`, in entry order (none if there is no such entry).
pub fn holm_against(entries: &[EntryResults], baseline: &str, alpha: f64) -> Vec<HolmComparison> {
    let Some(base) = entries.iter().find(|e| e.entry.name == baseline) else {
        return Vec::new();
    };
    let others: Vec<&EntryResults> = (entries.iter())
        .filter(|e| e.entry.name != baseline)
        .collect();
    let mut tests: Vec<Vec<(u64, f64, f64)>> = others
        .iter()
        .map(|e| point_tests(&e.results, &base.results))
        .collect();
    // Every episode's family: (method, test) of the methods tested there.
    let mut families: BTreeMap<u64, Vec<(usize, usize)>> = BTreeMap::new();
    for (m, t) in tests.iter().enumerate() {
        for (k, &(episode, _, _)) in t.iter().enumerate() {
            families.entry(episode).or_default().push((m, k));
        }
    }
    for family in families.values() {
        let p: Vec<f64> = family.iter().map(|&(m, k)| tests[m][k].1).collect();
        for (&(m, k), adjusted) in family.iter().zip(holm(&p)) {
            tests[m][k].1 = adjusted;
        }
    }
    (others.iter().zip(&tests))
        .map(|(e, t)| {
            let (better, worse) = better_intervals(t, alpha);
            HolmComparison {
                entry: e.entry.name.clone(),
                baseline: baseline.to_owned(),
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
