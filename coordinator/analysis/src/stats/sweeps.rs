//! Whether a method's result depends on a swept setting: for each group of
//! entries swept from one study entry, Friedman's test (Friedman 1937;
//! Demšar, JMLR 2006, for comparing several treatments paired by run) on
//! each run's last-ten goal %, across the group's values, the runs every
//! value played paired; Holm-corrected across groups.

use serde::Serialize;
use statrs::distribution::{ChiSquared, ContinuousCDF};

use crate::stats::gains::last_ten;
use crate::stats::holm::holm;
use crate::study::EntryResults;

/// One group's test.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepTest {
    /// The group: the study entry its entries were swept from.
    pub group: String,
    /// Its entries, in entry order.
    pub entries: Vec<String>,
    /// Each entry's mean last-ten goal % over the paired runs, in the same
    /// order.
    pub means: Vec<f64>,
    /// The runs every entry played.
    pub runs: usize,
    /// Friedman's statistic (ties averaged and corrected for).
    pub statistic: f64,
    /// Its p-value (chi-squared with entries - 1 degrees of freedom).
    pub p: f64,
    /// `p` Holm-adjusted across the study's groups.
    pub holm_p: f64,
}

impl SweepTest {
    /// Whether the result depends on the swept value at significance
    /// `alpha` (on the Holm-adjusted p).
    pub fn depends(&self, alpha: f64) -> bool {
        self.holm_p < alpha
    }

    /// The largest difference between two entries' means.
    pub fn spread(&self) -> f64 {
        let max = self.means.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = self.means.iter().copied().fold(f64::INFINITY, f64::min);
        max - min
    }
}

/// Every group of two or more entries that shares two or more runs, tested
/// in order of its first entry.
pub fn sweep_tests(entries: &[EntryResults]) -> Vec<SweepTest> {
    let mut groups: Vec<(&str, Vec<&EntryResults>)> = Vec::new();
    for e in entries {
        let Some(group) = e.entry.group.as_deref() else {
            continue;
        };
        match groups.iter_mut().find(|(g, _)| *g == group) {
            Some((_, members)) => members.push(e),
            None => groups.push((group, vec![e])),
        }
    }
    let mut tests: Vec<SweepTest> = (groups.into_iter())
        .filter(|(_, members)| members.len() >= 2)
        .filter_map(|(group, members)| test(group, &members))
        .collect();
    let adjusted = holm(&tests.iter().map(|t| t.p).collect::<Vec<_>>());
    for (t, p) in tests.iter_mut().zip(adjusted) {
        t.holm_p = p;
    }
    tests
}

/// The test of one group over the runs all its entries played with a
/// last-ten value; none with fewer than two such runs.
fn test(group: &str, members: &[&EntryResults]) -> Option<SweepTest> {
    let runs: Vec<u64> = (members[0].results.iter())
        .filter(|r| last_ten(r).is_some())
        .map(|r| r.run)
        .filter(|&k| {
            (members.iter()).all(|m| {
                m.results
                    .iter()
                    .any(|r| r.run == k && last_ten(r).is_some())
            })
        })
        .collect();
    if runs.len() < 2 {
        return None;
    }
    // blocks[i][j]: run i's last-ten goal % under entry j.
    let blocks: Vec<Vec<f64>> = (runs.iter())
        .map(|&k| {
            (members.iter())
                .map(|m| m.results.iter().find(|r| r.run == k).and_then(last_ten))
                .collect::<Option<Vec<f64>>>()
                .expect("every run kept has a value under every entry")
        })
        .collect();
    let (statistic, p) = friedman(&blocks)?;
    let n = blocks.len() as f64;
    let means = (0..members.len())
        .map(|j| blocks.iter().map(|b| b[j]).sum::<f64>() / n)
        .collect();
    Some(SweepTest {
        group: group.to_owned(),
        entries: members.iter().map(|m| m.entry.name.clone()).collect(),
        means,
        runs: blocks.len(),
        statistic,
        p,
        holm_p: p,
    })
}

/// Friedman's statistic and p-value over `blocks` (each a run: one value
/// per treatment, as many in each), ranks averaged over ties and the
/// statistic corrected for them, as SciPy's `friedmanchisquare`; none with
/// fewer than two treatments or blocks, or when every block is all ties.
pub fn friedman(blocks: &[Vec<f64>]) -> Option<(f64, f64)> {
    let k = blocks.first()?.len();
    let n = blocks.len();
    if k < 2 || n < 2 || blocks.iter().any(|b| b.len() != k) {
        return None;
    }
    let mut rank_sums = vec![0.0; k];
    let mut ties = 0.0;
    for block in blocks {
        let mut order: Vec<usize> = (0..k).collect();
        order.sort_by(|&a, &b| block[a].total_cmp(&block[b]));
        let mut i = 0;
        while i < k {
            let mut j = i;
            while j + 1 < k && block[order[j + 1]] == block[order[i]] {
                j += 1;
            }
            // Positions i..=j tie: each takes their mean rank (1-based).
            let rank = (i + j) as f64 / 2.0 + 1.0;
            for &t in &order[i..=j] {
                rank_sums[t] += rank;
            }
            let t = (j - i + 1) as f64;
            ties += t * t * t - t;
            i = j + 1;
        }
    }
    let (n, kf) = (n as f64, k as f64);
    let correction = 1.0 - ties / (n * kf * (kf * kf - 1.0));
    if correction <= 0.0 {
        return None;
    }
    let sum_squares: f64 = rank_sums.iter().map(|r| r * r).sum();
    let statistic =
        (12.0 / (n * kf * (kf + 1.0)) * sum_squares - 3.0 * n * (kf + 1.0)) / correction;
    let chi = ChiSquared::new(kf - 1.0).ok()?;
    Some((statistic, chi.sf(statistic)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{entry_results, run_with_goals};

    #[test]
    fn friedman_agrees_with_scipy() {
        // scipy.stats.friedmanchisquare([1, 2, 3, 4, 5], [2, 3, 3, 5, 6],
        // [3, 1, 5, 4, 7]) (SciPy 1.17.1): statistic 3.000000000000003,
        // p 0.22313016014842948 (ties in the third and fourth blocks).
        let blocks = [
            vec![1.0, 2.0, 3.0],
            vec![2.0, 3.0, 1.0],
            vec![3.0, 3.0, 5.0],
            vec![4.0, 5.0, 4.0],
            vec![5.0, 6.0, 7.0],
        ];
        let (statistic, p) = friedman(&blocks).unwrap();
        assert!((statistic - 3.0).abs() < 1e-12, "{statistic}");
        assert!((p - 0.22313016014842948).abs() < 1e-12, "{p}");
        // Every block a tie: nothing to rank.
        assert_eq!(friedman(&[vec![1.0, 1.0], vec![2.0, 2.0]]), None);
        assert_eq!(friedman(&[vec![1.0, 2.0]]), None);
    }

    #[test]
    fn a_group_whose_values_order_every_run_alike_depends_on_them() {
        let entry = |name: &str, group: Option<&str>, level: f64| {
            let runs = (0..8)
                .map(|k| run_with_goals(k, 100, &[level + k as f64; 3]))
                .collect();
            entry_results(name, group, runs)
        };
        let entries = [
            entry("base", None, 10.0),
            entry("a-1", Some("a"), 10.0),
            entry("a-2", Some("a"), 12.0),
            entry("a-3", Some("a"), 14.0),
            // Equal levels in every run: no evidence either way.
            entry("b-1", Some("b"), 10.0),
            entry("b-2", Some("b"), 10.0),
            entry("alone", Some("c"), 10.0),
        ];
        let tests = sweep_tests(&entries);
        // b's blocks are all ties: no test; c has one entry.
        assert_eq!(tests.len(), 1);
        let a = &tests[0];
        assert_eq!((a.group.as_str(), a.runs), ("a", 8));
        // Ranks 1, 2, 3 in each of 8 runs: 12/(8·3·4)·(8²+16²+24²) - 3·8·4 = 16.
        assert!((a.statistic - 16.0).abs() < 1e-12, "{a:?}");
        assert!(a.depends(0.05) && a.holm_p == a.p);
        assert!((a.spread() - 4.0).abs() < 1e-12);
        assert_eq!(a.means, [13.5, 15.5, 17.5]);
    }
}
