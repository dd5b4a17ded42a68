//! The difference of each method's goal percentage from the baseline's,
//! paired by run: one line and band per method around a line at zero, with
//! the evaluation points where a test finds it better or worse marked.

use super::catalogue::note_of;
use super::data::{Series, SeriesPoint};
use super::draw::{self, Captions, Curve, Mark, PALETTE};
use super::figure::{Figure, FigureError};
use super::layout::{Layout, YRange};
use crate::stats::Estimate;

/// The figure's file name, without extension.
pub const DIFFERENCE: &str = "goal_pct_difference";

/// One method's difference from the baseline at an evaluation point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DifferencePoint {
    /// Training episodes played before the evaluation.
    pub episode: u64,
    /// Its goal % minus the baseline's, paired by run: mean and interval.
    pub difference: Estimate,
    /// Whether a test finds it better (`Some(true)`), worse
    /// (`Some(false)`) or neither.
    pub better: Option<bool>,
}

/// One method's differences from the baseline: the figure's input.
#[derive(Clone, Debug, PartialEq)]
pub struct DifferenceSet {
    /// Legend label (the method's name).
    pub label: String,
    /// Its place among the study's methods, which picks its colour as in
    /// the other figures.
    pub slot: usize,
    /// Runs paired.
    pub runs: u64,
    /// Confidence level of the intervals; the test's is one minus it.
    pub ci_level: f64,
    /// Every evaluation point, in order.
    pub points: Vec<DifferencePoint>,
}

impl DifferenceSet {
    /// The curve of the differences.
    fn series(&self) -> Series {
        Series {
            label: self.label.clone(),
            points: (self.points.iter())
                .map(|p| SeriesPoint::of(p.episode, &p.difference))
                .collect(),
        }
    }

    /// The marks of the points found better or worse with a known mean.
    fn marks(&self) -> Vec<Mark> {
        (self.points.iter())
            .filter_map(|p| {
                let point = SeriesPoint::of(p.episode, &p.difference);
                Some(Mark {
                    episode: point.episode,
                    value: point.mean?,
                    up: p.better?,
                })
            })
            .collect()
    }
}

/// The figure of every method's difference from `baseline`.
pub fn draw_difference(baseline: &str, sets: &[DifferenceSet]) -> Result<Figure, FigureError> {
    let series: Vec<Series> = sets.iter().map(DifferenceSet::series).collect();
    let marks: Vec<Vec<Mark>> = sets.iter().map(DifferenceSet::marks).collect();
    let curves: Vec<Curve> = (sets.iter().zip(&series).zip(&marks))
        .map(|((set, series), marks)| Curve {
            colour: PALETTE[set.slot % PALETTE.len()],
            series,
            marks,
        })
        .collect();
    let mut note = note_of(sets.iter().map(|s| (s.runs, s.ci_level)));
    if let Some(set) = sets.first() {
        let alpha = ((1.0 - set.ci_level) * 1e4).round() / 1e4;
        note.push_str(&format!(
            "; \u{25B2} \u{25BC} better, worse (Wilcoxon signed-rank, p < {alpha})"
        ));
    }
    let captions = Captions {
        title: &format!("Goal percentage minus {baseline}'s, paired by run"),
        note: &note,
        x_axis: draw::EPISODES_AXIS,
        y_axis: "Difference in goal percentage (points)",
    };
    let layout = Layout::of(&series, YRange::Around(0.0));
    Figure::drawn(DIFFERENCE, draw::svg(&captions, &curves, &layout))
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::estimate;
    use super::*;

    #[test]
    fn draws_lines_around_zero_with_marked_points() {
        let point = |episode, mean, better| DifferencePoint {
            episode,
            difference: estimate(Some(mean)),
            better,
        };
        let set = DifferenceSet {
            label: "AdHocTD".to_owned(),
            slot: 1,
            runs: 3,
            ci_level: 0.95,
            points: vec![
                point(0, 0.0, None),
                point(100, 8.0, Some(true)),
                point(200, -9.0, Some(false)),
            ],
        };
        let figure = draw_difference("NoAdvice", std::slice::from_ref(&set)).unwrap();
        assert_eq!(figure.name, "goal_pct_difference");
        assert!(figure.png.starts_with(b"\x89PNG\r\n\x1a\n"));
        for text in [
            "Goal percentage minus NoAdvice&apos;s, paired by run",
            "Mean over 3 runs; shaded: 95% confidence interval; \u{25B2} \u{25BC} better, worse (Wilcoxon signed-rank, p &lt; 0.05)",
            "Difference in goal percentage (points)",
            "AdHocTD",
        ] {
            assert!(figure.svg.contains(text), "the SVG lacks {text:?}");
        }
        // The second colour, as in the other figures; two marks.
        assert!(figure.svg.contains("#D55E00") && !figure.svg.contains("#0072B2"));
        let marks = |svg: &str| svg.matches("<polygon").count();
        let unmarked = DifferenceSet {
            points: set
                .points
                .iter()
                .map(|p| point(p.episode, 1.0, None))
                .collect(),
            ..set.clone()
        };
        let plain = draw_difference("NoAdvice", &[unmarked]).unwrap();
        assert_eq!(marks(&figure.svg), marks(&plain.svg) + 2);
    }
}
