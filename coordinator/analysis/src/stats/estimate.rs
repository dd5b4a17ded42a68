//! Mean and Student's t confidence interval over runs, and Welch's
//! interval of a difference of means.

use std::fmt;

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, StudentsT};

/// The mean of some samples and a two-sided confidence interval around it.
///
/// With no sample every value is `None`; with one sample the interval is
/// undefined (no spread can be estimated) and its bounds are `None`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// Number of samples (runs) behind the estimate.
    pub n: usize,
    /// Arithmetic mean.
    pub mean: Option<f64>,
    /// Lower bound of the confidence interval.
    pub ci_low: Option<f64>,
    /// Upper bound of the confidence interval.
    pub ci_high: Option<f64>,
}

impl fmt::Display for Estimate {
    /// `mean [low, high]` to the formatter's precision (2 digits unless
    /// given), the mean alone without an interval, `-` without a sample.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = f.precision().unwrap_or(2);
        match (self.mean, self.ci_low, self.ci_high) {
            (Some(m), Some(lo), Some(hi)) => write!(f, "{m:.p$} [{lo:.p$}, {hi:.p$}]"),
            (Some(m), _, _) => write!(f, "{m:.p$}"),
            _ => f.write_str("-"),
        }
    }
}

/// The two-sided Student's t quantile `t_{(1 + level) / 2, df}`, e.g.
/// 2.262 for `level` 0.95 and 9 degrees of freedom.
///
/// # Panics
/// If `df` is zero or `level` is not in (0, 1).
pub fn t_quantile(level: f64, df: usize) -> f64 {
    assert!(df > 0, "at least one degree of freedom");
    assert!(level > 0.0 && level < 1.0, "level in (0, 1)");
    let t = StudentsT::new(0.0, 1.0, df as f64).expect("valid t distribution");
    t.inverse_cdf(0.5 + level / 2.0)
}

/// Mean and `level` confidence interval of `samples` (mean ± t · s / √n with
/// the sample standard deviation s).
pub fn estimate(samples: &[f64], level: f64) -> Estimate {
    let n = samples.len();
    if n == 0 {
        return Estimate {
            n,
            mean: None,
            ci_low: None,
            ci_high: None,
        };
    }
    let mean = samples.iter().sum::<f64>() / n as f64;
    if n == 1 {
        return Estimate {
            n,
            mean: Some(mean),
            ci_low: None,
            ci_high: None,
        };
    }
    let var = samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let half = t_quantile(level, n - 1) * (var / n as f64).sqrt();
    Estimate {
        n,
        mean: Some(mean),
        ci_low: Some(mean - half),
        ci_high: Some(mean + half),
    }
}

/// The difference of the means of two independent samples, `a` minus `b`,
/// with Welch's `level` interval (Welch–Satterthwaite degrees of freedom);
/// `n` is the smaller sample's size. Without two samples on each side the
/// interval is undefined.
pub fn difference_of_means(a: &[f64], b: &[f64], level: f64) -> Estimate {
    let (ea, eb) = (estimate(a, level), estimate(b, level));
    let (Some(ma), Some(mb)) = (ea.mean, eb.mean) else {
        return Estimate {
            n: a.len().min(b.len()),
            mean: None,
            ci_low: None,
            ci_high: None,
        };
    };
    let mean = ma - mb;
    let variance_of_mean = |v: &[f64], m: f64| {
        v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / ((v.len() - 1) * v.len()) as f64
    };
    let n = a.len().min(b.len());
    if n < 2 {
        return Estimate {
            n,
            mean: Some(mean),
            ci_low: None,
            ci_high: None,
        };
    }
    let (va, vb) = (variance_of_mean(a, ma), variance_of_mean(b, mb));
    let se = (va + vb).sqrt();
    let df =
        (va + vb).powi(2) / (va.powi(2) / (a.len() - 1) as f64 + vb.powi(2) / (b.len() - 1) as f64);
    let half = if se == 0.0 {
        0.0
    } else {
        let t = StudentsT::new(0.0, 1.0, df).expect("positive degrees of freedom");
        t.inverse_cdf(0.5 + level / 2.0) * se
    };
    Estimate {
        n,
        mean: Some(mean),
        ci_low: Some(mean - half),
        ci_high: Some(mean + half),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welch_by_hand() {
        // a: mean 5, s^2 = 32/7 over 8; b: 1, 2, 3 (mean 2, s^2 = 1). se^2 =
        // 32/56 + 1/3 = 0.904762; df = se^4 / ((32/56)^2/7 + (1/3)^2/2) =
        // 0.818594 / (0.046647 + 0.055556) = 8.009509; t_{0.975, 8.0095} = 2.305528
        // (SciPy's stats.t.ppf).
        let a = [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0];
        let e = difference_of_means(&a, &[1.0, 2.0, 3.0], 0.95);
        let half = 2.305528 * 0.904762f64.sqrt();
        assert_eq!((e.n, e.mean), (3, Some(3.0)));
        assert!(close(e.ci_low.unwrap(), 3.0 - half, 1e-4), "{e:?}");
        assert!(close(e.ci_high.unwrap(), 3.0 + half, 1e-4), "{e:?}");
        assert_eq!(difference_of_means(&a, &[], 0.95).mean, None);
        assert_eq!(difference_of_means(&a, &[1.0], 0.95).ci_low, None);
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn t_quantiles_match_the_table() {
        // Two-sided critical values from a printed t table.
        for (level, df, table) in [
            (0.95, 1, 12.706),
            (0.95, 4, 2.776),
            (0.95, 9, 2.262),
            (0.95, 49, 2.010),
            (0.90, 9, 1.833),
            (0.90, 49, 1.677),
            (0.99, 9, 3.250),
        ] {
            let t = t_quantile(level, df);
            assert!(close(t, table, 5e-4), "level {level} df {df}: {t}");
        }
    }

    #[test]
    fn mean_and_ci_by_hand() {
        // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, sum of squares 32, s^2 = 32/7,
        // s/sqrt(8) = 0.755929; t_{0.975, 7} = 2.364624; half 1.787485.
        let e = estimate(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0], 0.95);
        assert_eq!(e.n, 8);
        assert_eq!(e.mean, Some(5.0));
        assert!(close(e.ci_low.unwrap(), 5.0 - 1.787485, 1e-5), "{e:?}");
        assert!(close(e.ci_high.unwrap(), 5.0 + 1.787485, 1e-5), "{e:?}");
        // 10, 20 at 90%: mean 15, s = 7.0711, s/sqrt 2 = 5, t_{0.95, 1} = 6.313752.
        let e = estimate(&[10.0, 20.0], 0.90);
        assert!(
            close(e.ci_high.unwrap(), 15.0 + 5.0 * 6.313752, 1e-4),
            "{e:?}"
        );
    }

    #[test]
    fn identical_samples_have_a_point_interval() {
        let e = estimate(&[40.0; 5], 0.95);
        assert_eq!(
            (e.mean, e.ci_low, e.ci_high),
            (Some(40.0), Some(40.0), Some(40.0))
        );
    }

    #[test]
    fn one_sample_has_a_mean_but_no_interval() {
        let e = estimate(&[3.5], 0.95);
        assert_eq!(
            e,
            Estimate {
                n: 1,
                mean: Some(3.5),
                ci_low: None,
                ci_high: None
            }
        );
    }

    #[test]
    fn an_estimate_shows_what_is_known_of_it() {
        let e = estimate(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0], 0.95);
        assert_eq!(format!("{e}"), "5.00 [3.21, 6.79]");
        assert_eq!(format!("{e:.1}"), "5.0 [3.2, 6.8]");
        assert_eq!(format!("{:.1}", estimate(&[3.5], 0.95)), "3.5");
        assert_eq!(format!("{}", estimate(&[], 0.95)), "-");
    }

    #[test]
    fn no_sample_has_nothing() {
        let e = estimate(&[], 0.95);
        assert_eq!((e.n, e.mean, e.ci_low, e.ci_high), (0, None, None, None));
    }
}
