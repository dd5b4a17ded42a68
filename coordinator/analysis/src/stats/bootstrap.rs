//! The aggregate statistics of Agarwal et al., "Deep reinforcement learning
//! at the edge of the statistical precipice" (NeurIPS 2021), as their
//! `rliable` package computes them for one task: the mean and the
//! interquartile mean (IQM) of per-run scores, the probability of
//! improvement P(X > Y) of one algorithm over another, and their stratified
//! bootstrap percentile intervals (with one task, resampling runs with
//! replacement).
//!
//! Every resample comes from a generator seeded with [`SEED`], a fresh one
//! per interval, so the same scores give the same intervals bit for bit.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::Serialize;

/// Bootstrap resamples behind every interval.
pub const RESAMPLES: usize = 2000;

/// The seed of every interval's generator.
pub const SEED: u64 = 2017;

/// The mean and the IQM of some runs' scores with their `level` intervals.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Aggregate {
    /// The mean over runs.
    pub mean: f64,
    /// Its stratified bootstrap percentile interval.
    pub mean_ci: [f64; 2],
    /// The interquartile mean: the mean of the runs left after cutting
    /// ⌊n/4⌋ from each end of the sorted scores (SciPy's `trim_mean(x,
    /// 0.25)`, rliable's `aggregate_iqm`).
    pub iqm: f64,
    /// Its stratified bootstrap percentile interval.
    pub iqm_ci: [f64; 2],
}

/// The probability that a run of one algorithm scores more than a run of
/// another, with its `level` interval.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Improvement {
    /// P(X > Y) + P(X = Y) / 2 over every pair of runs (the Mann-Whitney U
    /// statistic divided by the number of pairs).
    pub estimate: f64,
    /// Its bootstrap percentile interval, each algorithm's runs resampled
    /// independently.
    pub ci: [f64; 2],
}

/// The mean of `x` (not empty).
fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// The interquartile mean of `x` (not empty), sorting it in place.
fn iqm(x: &mut [f64]) -> f64 {
    x.sort_by(f64::total_cmp);
    let cut = x.len() / 4;
    mean(&x[cut..x.len() - cut])
}

/// P(X > Y) + P(X = Y) / 2 over every pair of `x` and `y` (not empty).
pub fn probability_of_improvement(x: &[f64], y: &[f64]) -> f64 {
    let wins: f64 = (x.iter())
        .flat_map(|a| y.iter().map(move |b| a.total_cmp(b)))
        .map(|order| match order {
            std::cmp::Ordering::Greater => 1.0,
            std::cmp::Ordering::Equal => 0.5,
            std::cmp::Ordering::Less => 0.0,
        })
        .sum();
    wins / (x.len() * y.len()) as f64
}

/// `x` resampled with replacement into `into` (as long as `x`).
fn resample(x: &[f64], rng: &mut Xoshiro256PlusPlus, into: &mut Vec<f64>) {
    into.clear();
    into.extend((0..x.len()).map(|_| x[rng.random_range(0..x.len())]));
}

/// The `level` percentile interval of `values` (sorted in place), with
/// NumPy's default linear interpolation between order statistics.
fn percentile_interval(values: &mut [f64], level: f64) -> [f64; 2] {
    values.sort_by(f64::total_cmp);
    let quantile = |q: f64| {
        let h = q * (values.len() - 1) as f64;
        let (i, frac) = (h.floor() as usize, h.fract());
        let next = values[(i + 1).min(values.len() - 1)];
        values[i] + frac * (next - values[i])
    };
    [quantile((1.0 - level) / 2.0), quantile((1.0 + level) / 2.0)]
}

/// The mean and IQM of `scores` (one per run) with their `level` intervals
/// over [`RESAMPLES`] resamples of the runs; none without a score.
pub fn aggregate(scores: &[f64], level: f64) -> Option<Aggregate> {
    if scores.is_empty() {
        return None;
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
    let (mut means, mut iqms) = (Vec::with_capacity(RESAMPLES), Vec::with_capacity(RESAMPLES));
    let mut sample = Vec::with_capacity(scores.len());
    for _ in 0..RESAMPLES {
        resample(scores, &mut rng, &mut sample);
        means.push(mean(&sample));
        iqms.push(iqm(&mut sample));
    }
    Some(Aggregate {
        mean: mean(scores),
        mean_ci: percentile_interval(&mut means, level),
        iqm: iqm(&mut scores.to_vec()),
        iqm_ci: percentile_interval(&mut iqms, level),
    })
}

/// P(X > Y) of runs `x` over runs `y` with its `level` interval over
/// [`RESAMPLES`] independent resamples of both; none if either is empty.
pub fn improvement(x: &[f64], y: &[f64], level: f64) -> Option<Improvement> {
    if x.is_empty() || y.is_empty() {
        return None;
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
    let (mut rx, mut ry) = (Vec::with_capacity(x.len()), Vec::with_capacity(y.len()));
    let mut estimates: Vec<f64> = (0..RESAMPLES)
        .map(|_| {
            resample(x, &mut rng, &mut rx);
            resample(y, &mut rng, &mut ry);
            probability_of_improvement(&rx, &ry)
        })
        .collect();
    Some(Improvement {
        estimate: probability_of_improvement(x, y),
        ci: percentile_interval(&mut estimates, level),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_iqm_cuts_a_quarter_from_each_end() {
        // 8 runs: cut 2 each side, mean of 3, 4, 5, 6.
        assert_eq!(iqm(&mut [8.0, 1.0, 7.0, 2.0, 6.0, 3.0, 5.0, 4.0]), 4.5);
        // 7 runs: cut 1 each side (SciPy's trim_mean rounds down).
        assert_eq!(iqm(&mut [100.0, 1.0, 2.0, 3.0, 4.0, 5.0, 0.0]), 3.0);
        assert_eq!(iqm(&mut [3.0]), 3.0);
    }

    #[test]
    fn improvement_counts_ties_as_half() {
        assert_eq!(probability_of_improvement(&[2.0], &[1.0]), 1.0);
        assert_eq!(probability_of_improvement(&[1.0, 3.0], &[1.0, 2.0]), 0.625);
        let same = [1.0, 5.0, 5.0, 9.0];
        assert_eq!(probability_of_improvement(&same, &same), 0.5);
    }

    #[test]
    fn percentiles_interpolate_as_numpy() {
        // np.percentile([0, 10, 20, 30, 40], [25, 75]) = [10, 30], and
        // [5, 95] = [2, 38].
        let mut v = [40.0, 0.0, 30.0, 10.0, 20.0];
        assert_eq!(percentile_interval(&mut v, 0.5), [10.0, 30.0]);
        let [lo, hi] = percentile_interval(&mut v, 0.9);
        assert!(
            (lo - 2.0).abs() < 1e-12 && (hi - 38.0).abs() < 1e-12,
            "{lo} {hi}"
        );
    }

    #[test]
    fn intervals_are_reproducible_and_hold_the_estimate() {
        let scores = [12.0, 30.5, 18.0, 22.0, 25.0, 9.0, 40.0, 27.5, 15.0, 21.0];
        let a = aggregate(&scores, 0.95).unwrap();
        assert_eq!(aggregate(&scores, 0.95), Some(a));
        assert!(a.mean_ci[0] < a.mean && a.mean < a.mean_ci[1], "{a:?}");
        assert!(a.iqm_ci[0] < a.iqm && a.iqm < a.iqm_ci[1], "{a:?}");
        let i = improvement(&scores, &[10.0, 11.0, 20.0], 0.95).unwrap();
        assert!(i.ci[0] <= i.estimate && i.estimate <= i.ci[1], "{i:?}");
        assert_eq!(aggregate(&[], 0.95), None);
        assert_eq!(improvement(&scores, &[], 0.95), None);
        // One run: every resample is that run.
        let one = aggregate(&[7.0], 0.95).unwrap();
        assert_eq!((one.mean_ci, one.iqm_ci), ([7.0, 7.0], [7.0, 7.0]));
    }
}
