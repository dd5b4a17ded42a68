//! Wilcoxon signed-rank test between two algorithms at one evaluation point,
//! paired by run, and the intervals of episodes where one of them is
//! significantly better (docs/algorithms.md section 4).
//!
//! [`signed_rank`] follows `scipy.stats.wilcoxon` of SciPy 1.17.1 with its
//! defaults (`zero_method="wilcox"`, `correction=False`, `method="auto"`):
//!
//! - zero differences are dropped before ranking (but still count as pairs
//!   in the choice of method below, as in SciPy);
//! - `|d|` is ranked with average ranks for ties; W+ (W-) is the sum of the
//!   ranks of the positive (negative) differences;
//! - the p-values come from (with `pairs` the number of pairs, zero
//!   differences included):
//!   1. `pairs > 50`: the normal approximation ([`Method::Normal`]);
//!   2. else no ties and no zeros: the exact null distribution of W+
//!      ([`Method::Exact`]);
//!   3. else `pairs <= 13`: the exact distribution of W+ over all sign flips
//!      of the observed (tied) ranks ([`Method::Permutation`]; SciPy runs a
//!      permutation test, which enumerates all 2^pairs flips there);
//!   4. else the normal approximation.
//! - The normal approximation uses mean n(n+1)/4 and variance
//!   n(n+1)(2n+1)/24 - Σ(t³ - t)/48 over the tie groups of size t (n counts
//!   the non-zero differences only), and no continuity correction unless
//!   asked for with [`signed_rank_with`].
//!
//! One deliberate difference: with no non-zero difference at all, SciPy
//! returns p = 1 for up to 13 pairs but NaN beyond (its normal approximation
//! divides by a zero variance); here every p-value is then 1 with
//! [`Method::Permutation`] (W+ = 0 is the only possible value), so that two
//! algorithms with identical results (e.g. 0% goals in every run before any
//! training) are simply not significantly different.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal};

/// More pairs than this always use the normal approximation (SciPy's
/// `method="auto"`).
const MAX_EXACT_PAIRS: usize = 50;

/// Up to this many pairs, ties or zeros use the sign-flip distribution
/// (SciPy's deterministic permutation test: 2^13 ≤ 9999 resamples).
const MAX_PERMUTATION_PAIRS: usize = 13;

/// How the p-values of a [`SignedRank`] were computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Exact null distribution of W+ (each of the 2^n sign patterns of the
    /// ranks 1..n equally likely): at most 50 pairs, no ties, no zeros.
    Exact,
    /// Exact distribution of W+ over the 2^n sign flips of the observed
    /// average ranks: ties or zeros with at most 13 pairs, or no non-zero
    /// difference at all.
    Permutation,
    /// Normal approximation with the tie correction of the variance.
    Normal,
}

/// The Wilcoxon signed-rank test of paired samples `x` and `y`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SignedRank {
    /// Number of pairs, zero differences included.
    pub pairs: usize,
    /// Number of non-zero differences, the ones ranked.
    pub n: usize,
    /// Sum of the ranks of the positive differences `x - y`.
    pub w_plus: f64,
    /// Sum of the ranks of the negative differences `x - y`.
    pub w_minus: f64,
    /// How the p-values were computed.
    pub method: Method,
    /// Two-sided p-value (SciPy's `alternative="two-sided"`).
    pub p_value: f64,
    /// One-sided p-value against the alternative "x tends to be larger than
    /// y" (large W+; SciPy's `alternative="greater"`).
    pub p_greater: f64,
    /// One-sided p-value against the alternative "x tends to be smaller than
    /// y" (small W+; SciPy's `alternative="less"`).
    pub p_less: f64,
}

/// The Wilcoxon signed-rank test of `x` against `y`, paired by index, with
/// SciPy's defaults (see the module documentation).
///
/// `None` if the lengths differ, there is no pair, or a difference is NaN.
pub fn signed_rank(x: &[f64], y: &[f64]) -> Option<SignedRank> {
    signed_rank_with(x, y, false)
}

/// [`signed_rank`] with the choice of SciPy's `correction`: with
/// `continuity_correction`, the normal approximation moves z by 0.5 / σ
/// towards zero (two-sided) or towards the alternative (one-sided). The
/// exact methods ignore it.
pub fn signed_rank_with(x: &[f64], y: &[f64], continuity_correction: bool) -> Option<SignedRank> {
    if x.len() != y.len() || x.is_empty() {
        return None;
    }
    let pairs = x.len();
    let mut d = Vec::with_capacity(pairs);
    for (a, b) in x.iter().zip(y) {
        let diff = a - b;
        if diff.is_nan() {
            return None;
        }
        if diff != 0.0 {
            d.push(diff);
        }
    }
    let n = d.len();
    d.sort_by(|a, b| a.abs().total_cmp(&b.abs()));

    // Twice the average ranks (integers), in the order of `d`.
    let mut ranks2 = Vec::with_capacity(n);
    let mut tie_sum = 0.0; // Σ (t³ - t) over tie groups
    let mut start = 0;
    while start < n {
        let mut end = start + 1;
        while end < n && d[end].abs() == d[start].abs() {
            end += 1;
        }
        // Ranks start + 1 ..= end share their average (start + 1 + end) / 2.
        let t = end - start;
        ranks2.extend(std::iter::repeat_n((start + 1 + end) as u64, t));
        let t = t as f64;
        tie_sum += t * t * t - t;
        start = end;
    }
    let ties = tie_sum > 0.0;
    let w_plus2: u64 = d
        .iter()
        .zip(&ranks2)
        .filter(|(diff, _)| **diff > 0.0)
        .map(|(_, r)| r)
        .sum();
    let w_minus2 = (n * (n + 1)) as u64 - w_plus2;
    let (w_plus, w_minus) = (w_plus2 as f64 / 2.0, w_minus2 as f64 / 2.0);

    let method = if n == 0 {
        Method::Permutation
    } else if pairs > MAX_EXACT_PAIRS {
        Method::Normal
    } else if !ties && n == pairs {
        Method::Exact
    } else if pairs <= MAX_PERMUTATION_PAIRS {
        Method::Permutation
    } else {
        Method::Normal
    };
    let (p_value, p_greater, p_less) = match method {
        Method::Exact | Method::Permutation => sign_flip_p_values(&ranks2, w_plus2),
        Method::Normal => normal_p_values(n, tie_sum, w_plus, continuity_correction),
    };
    Some(SignedRank {
        pairs,
        n,
        w_plus,
        w_minus,
        method,
        p_value,
        p_greater,
        p_less,
    })
}

/// Two-sided, greater and less p-values of `w_plus2` (twice W+) under the
/// distribution of twice W+ when each of the (doubled) `ranks2` is positive
/// or negative with probability 1/2 independently, counted exactly by
/// dynamic programming over the ranks. With no tie the ranks are 1..n and
/// this is the exact null distribution of W+.
///
/// The counts stay below 2^50 (n ≤ 50), so they and the p-values (multiples
/// of 2^-n) are exact in `u64` and `f64`; the two-sided value is
/// min(1, 2 min(P(W+ ≤ w), P(W+ ≥ w))) as in SciPy.
fn sign_flip_p_values(ranks2: &[u64], w_plus2: u64) -> (f64, f64, f64) {
    let max: u64 = ranks2.iter().sum();
    let mut counts = vec![0u64; max as usize + 1];
    counts[0] = 1;
    let mut reach = 0;
    for &r in ranks2 {
        let r = r as usize;
        for s in (0..=reach).rev() {
            counts[s + r] += counts[s];
        }
        reach += r;
    }
    let w = w_plus2 as usize;
    let less: u64 = counts[..=w].iter().sum();
    let greater: u64 = counts[w..].iter().sum();
    let total = (1u64 << ranks2.len()) as f64;
    let two_sided = (2 * less.min(greater)) as f64 / total;
    (
        two_sided.min(1.0),
        greater as f64 / total,
        less as f64 / total,
    )
}

/// Two-sided, greater and less p-values of W+ by the normal approximation
/// for `n` non-zero differences whose tie groups of sizes t give
/// `tie_sum` = Σ (t³ - t); z is moved by 0.5 / σ if `continuity_correction`
/// (SciPy's rule: towards zero for two-sided, by `-0.5 / σ` for greater and
/// `+0.5 / σ` for less).
fn normal_p_values(
    n: usize,
    tie_sum: f64,
    w_plus: f64,
    continuity_correction: bool,
) -> (f64, f64, f64) {
    let n = n as f64;
    let mean = n * (n + 1.0) * 0.25;
    let sd = ((n * (n + 1.0) * (2.0 * n + 1.0) - tie_sum / 2.0) / 24.0).sqrt();
    let z = (w_plus - mean) / sd;
    let c = if continuity_correction { 0.5 / sd } else { 0.0 };
    // SciPy's sign(z), which is 0 at 0 (f64::signum is not).
    let sign = if z > 0.0 {
        1.0
    } else if z < 0.0 {
        -1.0
    } else {
        0.0
    };
    let normal = Normal::standard();
    (
        2.0 * normal.sf((z - sign * c).abs()),
        normal.sf(z - c),
        normal.cdf(z + c),
    )
}

/// Whether A is significantly better at a point with two-sided p-value `p`
/// and difference of the means `mean_diff` (A minus B) at level `alpha`:
/// `Some(true)` if A is, `Some(false)` if B is, else `None`.
pub fn better_side(p: f64, mean_diff: f64, alpha: f64) -> Option<bool> {
    if p < alpha && mean_diff > 0.0 {
        Some(true)
    } else if p < alpha && mean_diff < 0.0 {
        Some(false)
    } else {
        None
    }
}

/// Episodes `(first, last)` of a maximal run of consecutive evaluation
/// points, both inclusive; serialized as `[first, last]`.
pub type Interval = (u64, u64);

/// The maximal runs of consecutive evaluation points where A is
/// significantly better than B (first) and where B is significantly better
/// than A (second), each in evaluation order.
///
/// `points` holds, in evaluation order, `(episode, p, mean_diff)`: the
/// two-sided p-value of the test between A and B at that episode (e.g.
/// [`SignedRank::p_value`]) and the mean of A minus the mean of B. A point
/// counts for A or B by [`better_side`] (for neither with a NaN p). "Better" is
/// "larger": for a metric where smaller is better (time to goal), pass the
/// negated difference.
pub fn better_intervals(points: &[(u64, f64, f64)], alpha: f64) -> (Vec<Interval>, Vec<Interval>) {
    let (mut a_better, mut b_better) = (Vec::new(), Vec::new());
    // The current run: whether A is the better one, first and last episode.
    let mut run: Option<(bool, u64, u64)> = None;
    for &(episode, p, mean_diff) in points {
        let side = better_side(p, mean_diff, alpha);
        match (run, side) {
            (Some((a, first, _)), Some(b)) if a == b => run = Some((a, first, episode)),
            _ => {
                if let Some((a, first, last)) = run {
                    let list = if a { &mut a_better } else { &mut b_better };
                    list.push((first, last));
                }
                run = side.map(|a| (a, episode, episode));
            }
        }
    }
    if let Some((a, first, last)) = run {
        let list = if a { &mut a_better } else { &mut b_better };
        list.push((first, last));
    }
    (a_better, b_better)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reference case: inputs and SciPy's outputs.
    struct Case {
        name: &'static str,
        method: Method,
        x: &'static [f64],
        y: &'static [f64],
        /// `statistic` for `alternative="two-sided"`: min(W+, W-).
        statistic: f64,
        /// `statistic` for `alternative="greater"`: W+.
        w_plus: f64,
        /// p-values for two-sided, greater, less with `correction=False`.
        p: [f64; 3],
        /// The same with `correction=True`.
        p_corrected: [f64; 3],
    }

    /// Reference values from SciPy 1.17.1 (NumPy 2.4.6):
    /// `r = scipy.stats.wilcoxon(x, y, zero_method="wilcox",
    /// correction=c, method="auto", alternative=a)` for `c` in
    /// `False, True` and `a` in `"two-sided", "greater", "less"`, printing
    /// `float(r.statistic)` and `float(r.pvalue)` with `repr`. The comments
    /// give the number of pairs, of non-zero differences and whether the
    /// absolute differences tie; `method` is the branch SciPy's `auto`
    /// takes. Larger samples were drawn once with NumPy and pasted.
    #[allow(clippy::approx_constant)] // hw9's 3.14 is data, not pi
    const CASES: &[Case] = &[
        // hw9: 9 pairs, 9 non-zero, no ties (Hollander & Wolfe depression
        // scale, SciPy's documentation example)
        Case {
            name: "hw9",
            method: Method::Exact,
            x: &[1.83, 0.5, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.3],
            y: &[0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29],
            statistic: 5.0,
            w_plus: 40.0,
            p: [0.0390625, 0.01953125, 0.986328125],
            p_corrected: [0.0390625, 0.01953125, 0.986328125],
        },
        // all_pos5: 5 pairs, 5 non-zero, no ties
        Case {
            name: "all_pos5",
            method: Method::Exact,
            x: &[2.0, 4.0, 6.0, 8.0, 10.0],
            y: &[1.0, 2.0, 3.0, 4.0, 5.0],
            statistic: 0.0,
            w_plus: 15.0,
            p: [0.0625, 0.03125, 1.0],
            p_corrected: [0.0625, 0.03125, 1.0],
        },
        // one: 1 pair, 1 non-zero, no ties
        Case {
            name: "one",
            method: Method::Exact,
            x: &[2.0],
            y: &[1.0],
            statistic: 0.0,
            w_plus: 1.0,
            p: [1.0, 0.5, 1.0],
            p_corrected: [1.0, 0.5, 1.0],
        },
        // ties8: 8 pairs, 8 non-zero, ties
        Case {
            name: "ties8",
            method: Method::Permutation,
            x: &[5.0, 3.0, 8.0, 6.0, 2.0, 9.0, 4.0, 7.0],
            y: &[3.0, 4.0, 6.0, 4.0, 3.0, 6.0, 2.0, 4.0],
            statistic: 3.0,
            w_plus: 33.0,
            p: [0.03125, 0.015625, 0.98828125],
            p_corrected: [0.03125, 0.015625, 0.98828125],
        },
        // zeros9: 9 pairs, 6 non-zero, ties
        Case {
            name: "zeros9",
            method: Method::Permutation,
            x: &[10.0, 12.0, 9.0, 15.0, 11.0, 13.0, 8.0, 14.0, 10.5],
            y: &[10.0, 10.0, 9.0, 11.0, 12.0, 9.5, 8.0, 10.0, 7.0],
            statistic: 1.0,
            w_plus: 20.0,
            p: [0.0625, 0.03125, 0.984375],
            p_corrected: [0.0625, 0.03125, 0.984375],
        },
        // gp5: 5 pairs, 4 non-zero, ties
        Case {
            name: "gp5",
            method: Method::Permutation,
            x: &[42.0, 38.0, 45.0, 40.0, 47.0],
            y: &[35.0, 38.0, 40.0, 33.0, 41.0],
            statistic: 0.0,
            w_plus: 10.0,
            p: [0.125, 0.0625, 1.0],
            p_corrected: [0.125, 0.0625, 1.0],
        },
        // equal5: 5 pairs, 0 non-zero, no ties
        Case {
            name: "equal5",
            method: Method::Permutation,
            x: &[40.0, 40.0, 40.0, 40.0, 40.0],
            y: &[40.0, 40.0, 40.0, 40.0, 40.0],
            statistic: 0.0,
            w_plus: 0.0,
            p: [1.0, 1.0, 1.0],
            p_corrected: [1.0, 1.0, 1.0],
        },
        // noties10: 10 pairs, 10 non-zero, no ties
        Case {
            name: "noties10",
            method: Method::Exact,
            x: &[93.0, 5.0, -5.0, 97.0, 26.0, 38.0, 63.0, 11.0, 91.0, 94.0],
            y: &[98.0, 9.0, 3.0, 98.0, 35.0, 32.0, 61.0, 8.0, 84.0, 84.0],
            statistic: 27.0,
            w_plus: 28.0,
            p: [1.0, 0.5, 0.5390625],
            p_corrected: [1.0, 0.5, 0.5390625],
        },
        // noties25: 25 pairs, 25 non-zero, no ties
        Case {
            name: "noties25",
            method: Method::Exact,
            x: &[
                81.0, 41.0, 44.0, 42.0, 39.0, 37.0, 53.0, 21.0, 65.0, 82.0, 94.0, 33.0, 68.0, 61.0,
                38.0, 93.0, 91.0, 30.0, 63.0, 19.0, -3.0, 40.0, 96.0, -1.0, 69.0,
            ],
            y: &[
                63.0, 32.0, 23.0, 46.0, 49.0, 53.0, 66.0, 45.0, 71.0, 71.0, 89.0, 50.0, 69.0, 84.0,
                24.0, 96.0, 69.0, 50.0, 61.0, 34.0, 5.0, 47.0, 84.0, 24.0, 50.0,
            ],
            statistic: 133.0,
            w_plus: 133.0,
            p: [0.4418373703956604, 0.7869290113449097, 0.2209186851978302],
            p_corrected: [0.4418373703956604, 0.7869290113449097, 0.2209186851978302],
        },
        // noties50: 50 pairs, 50 non-zero, no ties
        Case {
            name: "noties50",
            method: Method::Exact,
            x: &[
                58.0, 54.0, 56.0, 58.0, 93.0, 68.0, 62.0, -6.0, 56.0, -6.0, 54.0, 47.0, 63.0, 39.0,
                27.0, 55.0, 10.0, 22.0, 103.0, 89.0, 9.0, 31.0, 90.0, 64.0, 78.0, 112.0, -2.0,
                73.0, 81.0, 37.0, 3.0, 17.0, 107.0, 85.0, -42.0, 66.0, 47.0, 18.0, 26.0, 70.0,
                80.0, 39.0, 0.0, 36.0, 133.0, 141.0, 3.0, 64.0, 21.0, 125.0,
            ],
            y: &[
                44.0, 13.0, 8.0, 38.0, 53.0, 33.0, 33.0, 4.0, 20.0, 40.0, 87.0, 59.0, 90.0, 2.0,
                21.0, 51.0, 29.0, 60.0, 54.0, 67.0, 17.0, 56.0, 67.0, 95.0, 48.0, 65.0, 24.0, 60.0,
                83.0, 30.0, 37.0, 12.0, 89.0, 82.0, 1.0, 83.0, 15.0, 2.0, 41.0, 42.0, 79.0, 30.0,
                42.0, 15.0, 89.0, 96.0, 53.0, 53.0, 45.0, 86.0,
            ],
            statistic: 502.0,
            w_plus: 773.0,
            p: [0.19427670053532076, 0.09713835026766038, 0.9045201278189072],
            p_corrected: [0.19427670053532076, 0.09713835026766038, 0.9045201278189072],
        },
        // noties60: 60 pairs, 60 non-zero, no ties
        Case {
            name: "noties60",
            method: Method::Normal,
            x: &[
                -16.0, 29.0, -9.0, 39.0, 33.0, 73.0, 81.0, 128.0, 50.0, 20.0, -17.0, 19.0, 97.0,
                22.0, 20.0, 47.0, -29.0, 48.0, 35.0, 66.0, 58.0, 69.0, 116.0, 94.0, 93.0, 65.0,
                33.0, -7.0, 104.0, -18.0, 37.0, 8.0, -23.0, 49.0, -53.0, 112.0, 109.0, 84.0, 84.0,
                105.0, 114.0, 23.0, 46.0, 116.0, 3.0, 24.0, 117.0, 64.0, 73.0, -38.0, -8.0, 2.0,
                65.0, 94.0, 98.0, -53.0, 13.0, 67.0, -23.0, 66.0,
            ],
            y: &[
                41.0, 72.0, 43.0, 31.0, 57.0, 83.0, 34.0, 92.0, 91.0, 11.0, 33.0, 1.0, 72.0, 5.0,
                60.0, 10.0, 6.0, 94.0, 5.0, 61.0, 42.0, 21.0, 62.0, 41.0, 33.0, 9.0, 12.0, 19.0,
                84.0, 15.0, 23.0, 50.0, 28.0, 68.0, 2.0, 54.0, 96.0, 57.0, 62.0, 99.0, 80.0, 16.0,
                45.0, 87.0, 18.0, 26.0, 86.0, 53.0, 41.0, 11.0, 15.0, 40.0, 37.0, 90.0, 54.0, 6.0,
                1.0, 28.0, 22.0, 63.0,
            ],
            statistic: 855.0,
            w_plus: 975.0,
            p: [0.6587090742591128, 0.3293545371295564, 0.6706454628704436],
            p_corrected: [0.6613751354300965, 0.33068756771504826, 0.6719763279834216],
        },
        // noties51: 51 pairs, 51 non-zero, no ties
        Case {
            name: "noties51",
            method: Method::Normal,
            x: &[
                -20.0, 21.0, 36.0, 75.0, 16.0, 76.0, 125.0, 140.0, 28.0, 142.0, 24.0, 14.0, 79.0,
                100.0, 72.0, 88.0, 30.0, 38.0, 78.0, 58.0, 103.0, 101.0, -20.0, 14.0, 54.0, 49.0,
                -17.0, 57.0, 86.0, 80.0, -3.0, 110.0, 38.0, 118.0, 87.0, 58.0, 57.0, 64.0, 51.0,
                -3.0, -19.0, 108.0, 115.0, 3.0, 50.0, 78.0, 86.0, 26.0, 77.0, 71.0, -19.0,
            ],
            y: &[
                5.0, 19.0, 5.0, 31.0, 6.0, 67.0, 75.0, 95.0, 54.0, 95.0, 39.0, 9.0, 52.0, 61.0,
                92.0, 77.0, 49.0, 59.0, 60.0, 70.0, 54.0, 94.0, 4.0, 8.0, 57.0, 84.0, 12.0, 35.0,
                87.0, 46.0, 1.0, 62.0, 5.0, 82.0, 71.0, 18.0, 14.0, 27.0, 93.0, 25.0, 19.0, 62.0,
                83.0, 20.0, 42.0, 92.0, 56.0, 13.0, 36.0, 48.0, 32.0,
            ],
            statistic: 424.0,
            w_plus: 902.0,
            p: [
                0.025074140489837644,
                0.012537070244918822,
                0.9874629297550812,
            ],
            p_corrected: [
                0.025379830388343967,
                0.012689915194171984,
                0.9876141783078511,
            ],
        },
        // ties13: 13 pairs, 13 non-zero, ties
        Case {
            name: "ties13",
            method: Method::Permutation,
            x: &[
                21.0, 11.0, 10.0, 3.0, 10.0, 16.0, 18.0, 10.0, 2.0, 19.0, 12.0, 20.0, 9.0,
            ],
            y: &[
                18.0, 9.0, 14.0, 4.0, 14.0, 14.0, 16.0, 11.0, 0.0, 17.0, 10.0, 22.0, 6.0,
            ],
            statistic: 34.0,
            w_plus: 57.0,
            p: [0.419677734375, 0.2098388671875, 0.791015625],
            p_corrected: [0.419677734375, 0.2098388671875, 0.791015625],
        },
        // ties14: 14 pairs, 14 non-zero, ties
        Case {
            name: "ties14",
            method: Method::Normal,
            x: &[
                6.0, 23.0, 21.0, 28.0, 6.0, 8.0, 25.0, 2.0, 22.0, 22.0, 29.0, 12.0, 0.0, 9.0,
            ],
            y: &[
                10.0, 27.0, 22.0, 30.0, 3.0, 9.0, 26.0, 3.0, 26.0, 20.0, 27.0, 13.0, 2.0, 6.0,
            ],
            statistic: 36.0,
            w_plus: 36.0,
            p: [0.2960883641628492, 0.8519558179185753, 0.1480441820814246],
            p_corrected: [0.31096648434280927, 0.8591528200290159, 0.15548324217140463],
        },
        // zeros14: 14 pairs, 10 non-zero, ties
        Case {
            name: "zeros14",
            method: Method::Normal,
            x: &[
                12.0, 8.0, 2.0, 6.0, 2.0, 10.0, 13.0, 19.0, 18.0, 16.0, 3.0, 11.0, 15.0, 3.0,
            ],
            y: &[
                17.0, 8.0, 6.0, 6.0, -1.0, 10.0, 15.0, 24.0, 23.0, 16.0, 2.0, 15.0, 14.0, 2.0,
            ],
            statistic: 11.0,
            w_plus: 11.0,
            p: [0.09069333544841966, 0.9546533322757902, 0.04534666772420983],
            p_corrected: [0.10090406338669114, 0.9593346645642826, 0.05045203169334557],
        },
        // ties20: 20 pairs, 20 non-zero, ties
        Case {
            name: "ties20",
            method: Method::Normal,
            x: &[
                24.0, 29.0, 37.0, 38.0, 25.0, 32.0, 33.0, 28.0, 36.0, 22.0, 31.0, 28.0, 21.0, 20.0,
                22.0, 35.0, 35.0, 29.0, 33.0, 33.0,
            ],
            y: &[
                21.0, 27.0, 38.0, 40.0, 21.0, 29.0, 35.0, 24.0, 38.0, 18.0, 32.0, 24.0, 20.0, 18.0,
                21.0, 36.0, 34.0, 30.0, 30.0, 31.0,
            ],
            statistic: 47.5,
            w_plus: 162.5,
            p: [
                0.030270264108183422,
                0.015135132054091711,
                0.9848648679459083,
            ],
            p_corrected: [
                0.03173788162422131,
                0.015868940812110655,
                0.9855693291968795,
            ],
        },
        // gp50: 50 pairs, 45 non-zero, ties
        Case {
            name: "gp50",
            method: Method::Normal,
            x: &[
                40.0, 44.0, 37.0, 53.0, 44.0, 48.0, 52.0, 54.0, 42.0, 52.0, 38.0, 40.0, 46.0, 37.0,
                45.0, 49.0, 43.0, 45.0, 43.0, 46.0, 45.0, 51.0, 44.0, 42.0, 52.0, 46.0, 42.0, 39.0,
                45.0, 48.0, 41.0, 50.0, 42.0, 47.0, 36.0, 45.0, 45.0, 42.0, 46.0, 46.0, 52.0, 52.0,
                49.0, 40.0, 41.0, 39.0, 47.0, 33.0, 54.0, 45.0,
            ],
            y: &[
                33.0, 44.0, 39.0, 48.0, 38.0, 45.0, 56.0, 51.0, 35.0, 56.0, 37.0, 34.0, 45.0, 36.0,
                46.0, 48.0, 40.0, 44.0, 47.0, 39.0, 49.0, 53.0, 46.0, 40.0, 56.0, 49.0, 42.0, 35.0,
                40.0, 48.0, 45.0, 48.0, 35.0, 47.0, 32.0, 41.0, 41.0, 37.0, 40.0, 41.0, 45.0, 51.0,
                49.0, 41.0, 45.0, 41.0, 44.0, 35.0, 52.0, 43.0,
            ],
            statistic: 290.0,
            w_plus: 745.0,
            p: [
                0.009944633751756405,
                0.0049723168758782025,
                0.9950276831241218,
            ],
            p_corrected: [
                0.010108860792572916,
                0.005054430396286458,
                0.9951086061815994,
            ],
        },
        // tz60: 60 pairs, 49 non-zero, ties
        Case {
            name: "tz60",
            method: Method::Normal,
            x: &[
                0.0, 2.0, 3.0, 1.0, 3.0, 1.0, 5.0, 8.0, 5.0, 2.0, 3.0, 1.0, 3.0, 6.0, 3.0, 0.0,
                4.0, 1.0, 6.0, 6.0, 1.0, 9.0, 2.0, 7.0, 0.0, 2.0, 9.0, 4.0, 6.0, 5.0, 1.0, 9.0,
                1.0, 0.0, 2.0, 2.0, 6.0, 4.0, 4.0, 6.0, 3.0, 6.0, 0.0, 2.0, 3.0, 8.0, 3.0, 6.0,
                1.0, 9.0, 7.0, 3.0, 4.0, 9.0, 7.0, 1.0, 8.0, 4.0, 7.0, 0.0,
            ],
            y: &[
                0.0, 3.0, 2.0, 8.0, 4.0, 2.0, 5.0, 1.0, 5.0, 1.0, 4.0, 1.0, 3.0, 0.0, 3.0, 3.0,
                6.0, 5.0, 5.0, 5.0, 3.0, 8.0, 5.0, 2.0, 0.0, 0.0, 7.0, 8.0, 3.0, 3.0, 6.0, 6.0,
                8.0, 8.0, 5.0, 0.0, 1.0, 0.0, 3.0, 1.0, 6.0, 9.0, 0.0, 3.0, 5.0, 2.0, 4.0, 1.0,
                3.0, 2.0, 7.0, 1.0, 3.0, 9.0, 8.0, 1.0, 1.0, 1.0, 0.0, 1.0,
            ],
            statistic: 532.5,
            w_plus: 692.5,
            p: [0.42378610253092497, 0.21189305126546248, 0.7881069487345376],
            p_corrected: [0.42668863580765437, 0.21334431790382719, 0.7895524237915608],
        },
    ];

    /// `a == b` or `|a - b| <= tol * |b|`.
    fn close_rel(a: f64, b: f64, tol: f64) -> bool {
        a == b || (a - b).abs() <= tol * b.abs()
    }

    #[test]
    fn matches_scipy() {
        for case in CASES {
            let name = case.name;
            for (corrected, expected) in [(false, case.p), (true, case.p_corrected)] {
                let r = signed_rank_with(case.x, case.y, corrected).unwrap();
                assert_eq!(r.method, case.method, "{name}");
                assert_eq!(r.pairs, case.x.len(), "{name}");
                // SciPy's two-sided statistic is min(W+, W-).
                assert_eq!(r.w_plus.min(r.w_minus), case.statistic, "{name}");
                assert_eq!(r.w_plus, case.w_plus, "{name}");
                assert_eq!(r.w_plus + r.w_minus, (r.n * (r.n + 1)) as f64 / 2.0);
                let got = [r.p_value, r.p_greater, r.p_less];
                for (g, e) in got.iter().zip(expected) {
                    let ok = match r.method {
                        // Multiples of 2^-n, exact on both sides.
                        Method::Exact | Method::Permutation => *g == e,
                        // statrs' erfc is within about 1e-10 relative of
                        // SciPy's ndtr (measured for z in 0..8).
                        Method::Normal => close_rel(*g, e, 1e-9),
                    };
                    assert!(ok, "{name} corrected {corrected}: {got:?} vs {expected:?}");
                }
            }
        }
    }

    #[test]
    fn default_is_without_continuity_correction() {
        for case in CASES {
            assert_eq!(
                signed_rank(case.x, case.y),
                signed_rank_with(case.x, case.y, false),
                "{}",
                case.name
            );
        }
    }

    #[test]
    fn swapping_the_samples_mirrors_the_test() {
        for case in CASES {
            let r = signed_rank(case.x, case.y).unwrap();
            let s = signed_rank(case.y, case.x).unwrap();
            assert_eq!((s.w_plus, s.w_minus), (r.w_minus, r.w_plus));
            assert_eq!(s.p_value, r.p_value, "{}", case.name);
            assert!(close_rel(s.p_greater, r.p_less, 1e-12), "{}", case.name);
            assert!(close_rel(s.p_less, r.p_greater, 1e-12), "{}", case.name);
        }
    }

    #[test]
    fn counts_pairs_and_ranks_non_zero_differences() {
        // gp5: differences 7, 0, 5, 7, 6.
        let r = signed_rank(
            &[42.0, 38.0, 45.0, 40.0, 47.0],
            &[35.0, 38.0, 40.0, 33.0, 41.0],
        )
        .unwrap();
        assert_eq!((r.pairs, r.n), (5, 4));
        assert_eq!((r.w_plus, r.w_minus), (10.0, 0.0));
        // Tied at W+ = W- = 1.5: differences 1, -1.
        let r = signed_rank(&[1.0, 2.0], &[2.0, 1.0]).unwrap();
        assert_eq!((r.w_plus, r.w_minus), (1.5, 1.5));
        assert_eq!(r.p_value, 1.0);
    }

    #[test]
    fn all_equal_samples_are_not_different() {
        // SciPy 1.17.1 gives statistic 0 and p 1.0 for 5 equal pairs (a
        // permutation test) but p NaN for 20 (a normal approximation with
        // zero variance); here p is 1 for any number of pairs.
        for pairs in [1, 5, 13, 14, 20, 50, 51] {
            let r = signed_rank(&vec![40.0; pairs], &vec![40.0; pairs]).unwrap();
            assert_eq!(r.method, Method::Permutation);
            assert_eq!((r.pairs, r.n), (pairs, 0));
            assert_eq!((r.w_plus, r.w_minus), (0.0, 0.0));
            assert_eq!((r.p_value, r.p_greater, r.p_less), (1.0, 1.0, 1.0));
        }
    }

    #[test]
    fn rejects_unpaired_empty_or_nan_samples() {
        assert_eq!(signed_rank(&[1.0, 2.0], &[1.0]), None);
        assert_eq!(signed_rank(&[], &[]), None);
        assert_eq!(signed_rank(&[1.0, f64::NAN], &[0.0, 1.0]), None);
        assert_eq!(signed_rank(&[f64::INFINITY], &[f64::INFINITY]), None);
    }

    #[test]
    fn exact_distribution_of_three_ranks() {
        // Ranks 1, 2, 3: W+ takes 0, 1, 2, 3, 3, 4, 5, 6 over the 8 sign
        // patterns; W+ = 5 (differences 2, -1, 3) has P(W+ >= 5) = 2/8.
        let r = signed_rank(&[2.0, -1.0, 3.0], &[0.0; 3]).unwrap();
        assert_eq!(r.method, Method::Exact);
        assert_eq!(
            (r.w_plus, r.p_greater, r.p_less, r.p_value),
            (5.0, 0.25, 0.875, 0.5)
        );
    }

    #[test]
    fn intervals_of_significant_points() {
        let points = [
            (0, 0.5, 1.0),
            (20, 0.01, 2.0),
            (40, 0.04, 1.0),
            (60, 0.05, 3.0), // p = alpha is not significant
            (80, 0.001, -1.0),
            (100, 0.002, -2.0),
            (120, 0.003, 4.0), // switches straight from B to A
            (140, 0.2, 4.0),
            (160, 0.01, 0.0), // no difference in means
            (180, f64::NAN, 1.0),
            (200, 0.03, 1.0),
        ];
        let got = better_intervals(&points, 0.05);
        assert_eq!(
            got,
            (vec![(20, 40), (120, 120), (200, 200)], vec![(80, 100)])
        );
    }

    #[test]
    fn intervals_of_nothing_or_everything() {
        assert_eq!(better_intervals(&[], 0.05), (vec![], vec![]));
        let none = [(0, 0.9, 1.0), (20, 0.01, 0.0)];
        assert_eq!(better_intervals(&none, 0.05), (vec![], vec![]));
        let all_b = [(0, 0.01, -1.0), (20, 0.01, -0.5), (40, 0.0, -2.0)];
        assert_eq!(better_intervals(&all_b, 0.05), (vec![], vec![(0, 40)]));
    }

    #[test]
    fn intervals_serialize_as_pairs() {
        let (a_better, _) = better_intervals(&[(20, 0.01, 1.0), (40, 0.01, 1.0)], 0.05);
        assert_eq!(serde_json::to_string(&a_better).unwrap(), "[[20,40]]");
    }

    #[test]
    fn intervals_from_runs_at_each_evaluation_point() {
        // Goal percentages of 6 runs of A and B at three evaluation points:
        // equal at 0, A above B in every run at 20 and 40. Six positive
        // differences without ties: exact two-sided p = 2/64 < 0.05.
        let a = [
            [0.0; 6],
            [30.0, 32.0, 35.0, 31.0, 40.0, 28.0],
            [50.0, 52.0, 55.0, 51.0, 60.0, 48.0],
        ];
        let b = [
            [0.0; 6],
            [29.0, 30.0, 32.0, 27.0, 35.0, 22.0],
            [49.0, 50.0, 52.0, 47.0, 55.0, 42.0],
        ];
        let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
        let points: Vec<(u64, f64, f64)> = (0..3)
            .map(|k| {
                let r = signed_rank(&a[k], &b[k]).unwrap();
                (20 * k as u64, r.p_value, mean(&a[k]) - mean(&b[k]))
            })
            .collect();
        assert_eq!(points[0].1, 1.0);
        assert_eq!(points[1].1, 0.03125);
        assert_eq!(better_intervals(&points, 0.05), (vec![(20, 40)], vec![]));
    }
}
