//! A logarithmic axis for `plotters`: positive values placed by their
//! logarithm, with ticks at 1, 2 and 5 times a power of ten (coarser where
//! those would crowd, finer within a decade), labelled as plain numbers.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};

/// An axis from one positive value to a greater one.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct LogAxis(pub Range<f64>);

impl Ranged for LogAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let (lo, hi) = (self.0.start.ln(), self.0.end.ln());
        let fraction = (value.ln() - lo) / (hi - lo);
        let pixels = f64::from(limit.1 - limit.0);
        // As plotters maps a linear axis; a value out of range (or not
        // positive) saturates.
        limit.0 + (pixels * fraction + 1e-3).floor() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        ticks(self.0.start, self.0.end, hint.max_num_points())
    }

    fn range(&self) -> Range<f64> {
        self.0.clone()
    }
}

/// The ticks from `lo` to `hi`, at most `most`: at 1, 2 and 5 times each
/// power of ten, else 1 and 3, else every power of ten, else every second,
/// third, ... power; at every integer multiple within a decade when 1, 2
/// and 5 give fewer than three.
pub(super) fn ticks(lo: f64, hi: f64, most: usize) -> Vec<f64> {
    let on = |mantissas: &[f64], step: i32| -> Vec<f64> {
        let decades = lo.log10().floor() as i32..=hi.log10().floor() as i32;
        (decades.filter(|k| k.rem_euclid(step) == 0))
            .flat_map(|k| mantissas.iter().map(move |&m| power(m, k)))
            .filter(|x| (lo..=hi).contains(x))
            .collect()
    };
    if !(lo > 0.0 && hi > lo && hi.is_finite()) || most == 0 {
        return Vec::new();
    }
    let fine = on(&[1.0, 2.0, 5.0], 1);
    if fine.len() < 3 {
        return on(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 1);
    }
    let ladders: [&[f64]; 3] = [&[1.0, 2.0, 5.0], &[1.0, 3.0], &[1.0]];
    for mantissas in ladders {
        let t = on(mantissas, 1);
        if t.len() <= most {
            return t;
        }
    }
    (2..)
        .map(|step| on(&[1.0], step))
        .find(|t| t.len() <= most)
        .unwrap_or_default()
}

/// `m` × 10^`k`, as near as a float gets (0.3, not 0.30000000000000004).
fn power(m: f64, k: i32) -> f64 {
    if k >= 0 {
        m * 10f64.powi(k)
    } else {
        m / 10f64.powi(-k)
    }
}

/// A tick's label: the number with the decimals it needs (0.05, 0.2, 3,
/// 2000).
pub(super) fn tick_label(x: f64) -> String {
    let decimals = if x >= 1.0 {
        0
    } else {
        (-x.log10() - 1e-9).ceil().max(0.0) as usize
    };
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_as_dense_as_the_range_allows() {
        assert_eq!(ticks(0.8, 25.0, 11), [1.0, 2.0, 5.0, 10.0, 20.0]);
        assert_eq!(
            ticks(0.06, 400.0, 11),
            [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0]
        );
        assert_eq!(
            ticks(0.05, 900.0, 11),
            [0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0]
        );
        assert_eq!(ticks(0.001, 1e8, 6), [0.01, 1.0, 100.0, 1e4, 1e6, 1e8]);
        // Within a decade, every integer multiple.
        assert_eq!(ticks(2.5, 6.5, 11), [3.0, 4.0, 5.0, 6.0]);
        assert!(ticks(0.0, 10.0, 11).is_empty() && ticks(1.0, 10.0, 0).is_empty());
    }

    #[test]
    fn labels_have_the_decimals_they_need() {
        let labels: Vec<String> = [0.05, 0.2, 0.3, 1.0, 3.0, 2000.0]
            .into_iter()
            .map(tick_label)
            .collect();
        assert_eq!(labels, ["0.05", "0.2", "0.3", "1", "3", "2000"]);
    }

    #[test]
    fn values_are_placed_by_their_logarithm() {
        let axis = LogAxis(1.0..100.0);
        assert_eq!(axis.map(&1.0, (0, 200)), 0);
        assert_eq!(axis.map(&10.0, (0, 200)), 100);
        assert_eq!(axis.map(&100.0, (0, 200)), 200);
        // Pixel rows grow downwards on a y axis.
        assert_eq!(axis.map(&10.0, (400, 0)), 200);
    }
}
