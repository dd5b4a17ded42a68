//! The study's tests against the baseline with Holm's correction across
//! the methods compared with it: at every evaluation point, the Wilcoxon
//! p-values of every method against the baseline form one family.

use std::collections::BTreeMap;

use serde::Serialize;

use super::analysis::{EntryResults, point_tests};
use crate::stats::holm;
use crate::wilcoxon::{Interval, better_intervals};

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
