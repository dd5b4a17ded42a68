//! The difference of each method's goal percentage from the baseline's,
//! paired by run: one line and band per method around a line at zero, with
//! the evaluation points where a test finds it better or worse marked.
//!
//! The figure is for differences of a few points (the advising methods'
//! gains). A method whose differences dwarf the others' (the `random`
//! policy's, some -55 points) is drawn apart, in a chart of its own below,
//! so that its scale does not squeeze the others into a line around zero:
//! see [`APART_FACTOR`] for the rule.

use super::catalogue::note_of;
use super::data::{Series, SeriesPoint};
use super::draw::{self, Captions, Curve, Mark, MarkShape, PALETTE, Panel, Style};
use super::figure::{Figure, FigureError};
use super::layout::{self, Layout, PLOT, YRange};
use crate::stats::Estimate;

/// The figure's file name, without extension.
pub const DIFFERENCE: &str = "goal_pct_difference";

/// A method is drawn apart when its reach (its largest mean difference in
/// absolute value, over every evaluation point) is more than this many
/// times the median of the other methods' reaches, counted as at least
/// [`APART_FLOOR`] points.
pub const APART_FACTOR: f64 = 4.0;

/// The least median reach [`APART_FACTOR`] multiplies (points): methods
/// that all stay within a few points of the baseline are drawn together.
pub const APART_FLOOR: f64 = 2.5;

/// Size of the plotting area of the chart drawn apart (pixels).
const APART_PLOT: (u32, u32) = (PLOT.0, 200);

/// The y axis title of both charts.
const AXIS: &str = "Difference in goal percentage (points)";

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

    /// The mean difference farthest from zero, if any is known.
    fn extreme(&self) -> Option<f64> {
        (self.points.iter())
            .filter_map(|p| p.difference.mean.filter(|m| m.is_finite()))
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))
    }

    /// How far from zero its mean difference goes (0 without any known).
    fn reach(&self) -> f64 {
        self.extreme().map_or(0.0, f64::abs)
    }

    /// The marks of the points found better or worse with a known mean.
    fn marks(&self) -> Vec<Mark> {
        (self.points.iter())
            .filter_map(|p| {
                let point = SeriesPoint::of(p.episode, &p.difference);
                Some(Mark {
                    episode: point.episode,
                    value: point.mean?,
                    shape: if p.better? {
                        MarkShape::Up
                    } else {
                        MarkShape::Down
                    },
                })
            })
            .collect()
    }
}

/// The figure of every method's difference from `baseline`; methods whose
/// differences dwarf the others' ([`drawn_apart`]) in a chart of their own
/// below.
pub fn draw_difference(baseline: &str, sets: &[DifferenceSet]) -> Result<Figure, FigureError> {
    let series: Vec<Series> = sets.iter().map(DifferenceSet::series).collect();
    let marks: Vec<Vec<Mark>> = sets.iter().map(DifferenceSet::marks).collect();
    let curve = |k: usize| Curve {
        colour: PALETTE[sets[k].slot % PALETTE.len()],
        series: &series[k],
        marks: &marks[k],
        style: Style::Line,
    };
    let apart = drawn_apart(sets);
    let (aside, together): (Vec<usize>, Vec<usize>) = (0..sets.len()).partition(|&k| apart[k]);
    let shown = |ks: &[usize]| -> Vec<Series> { ks.iter().map(|&k| series[k].clone()).collect() };
    let main_curves: Vec<Curve> = together.iter().map(|&k| curve(k)).collect();
    let mut main_layout = Layout::of(&shown(&together), YRange::Around(0.0));
    let aside_curves: Vec<Curve> = aside.iter().map(|&k| curve(k)).collect();
    let heading = apart_heading(sets, &aside, &together);
    let mut aside_layout = Layout::sized(&shown(&aside), YRange::Around(0.0), APART_PLOT);
    aside_layout.ranges.x = main_layout.ranges.x;
    if !aside.is_empty() {
        layout::align(&mut [&mut main_layout, &mut aside_layout]);
    }
    let main = Panel {
        curves: &main_curves,
        layout: main_layout,
        y_axis: AXIS,
        heading: "",
    };
    let lower = Panel {
        curves: &aside_curves,
        layout: aside_layout,
        y_axis: "Difference (points)",
        heading: &heading,
    };

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
    };
    let mut panels = vec![main];
    if !aside.is_empty() {
        panels.push(lower);
    }
    Figure::drawn(DIFFERENCE, draw::svg(&captions, &panels))
}

/// Which of `sets` are drawn apart: those whose reach is more than
/// [`APART_FACTOR`] times the median reach of the others (at least
/// [`APART_FLOOR`]). The set of the smallest reach never is, so some are
/// always drawn together.
pub fn drawn_apart(sets: &[DifferenceSet]) -> Vec<bool> {
    let reaches: Vec<f64> = sets.iter().map(DifferenceSet::reach).collect();
    (0..sets.len())
        .map(|k| {
            let mut others: Vec<f64> = (reaches.iter().enumerate())
                .filter(|&(j, _)| j != k)
                .map(|(_, &r)| r)
                .collect();
            others.sort_by(f64::total_cmp);
            let median = match others.len() {
                0 => return false,
                n if n % 2 == 1 => others[n / 2],
                n => (others[n / 2 - 1] + others[n / 2]) / 2.0,
            };
            reaches[k] > APART_FACTOR * median.max(APART_FLOOR)
        })
        .collect()
}

/// The heading of the chart of the sets `aside`, drawn apart from those
/// `together`: their names, how far they reach and how far the others do.
fn apart_heading(sets: &[DifferenceSet], aside: &[usize], together: &[usize]) -> String {
    let names: Vec<&str> = aside.iter().map(|&k| sets[k].label.as_str()).collect();
    let extreme = (aside.iter())
        .filter_map(|&k| sets[k].extreme())
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(0.0);
    let others = (together.iter())
        .map(|&k| sets[k].reach())
        .fold(0.0, f64::max);
    format!(
        "Drawn apart, on its own scale: {} (mean difference reaching {extreme:+.0} points; the others stay within \u{00B1}{others:.0})",
        names.join(", ")
    )
}
#[cfg(test)]
mod tests {
    use super::super::fixtures::estimate;
    use super::super::layout::{HEADER_H, HEADING_H, MARGIN, X_LABELS_H};
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
        // One method: one chart, of the usual size.
        assert!(figure.svg.contains(r#"width="1000" height="600""#));
        assert!(!figure.svg.contains("Drawn apart"));
    }

    /// A method's differences `means` at episodes 0, 100, ... (± 5).
    fn set(label: &str, slot: usize, means: &[f64]) -> DifferenceSet {
        let points = (means.iter().enumerate())
            .map(|(i, &mean)| DifferencePoint {
                episode: 100 * i as u64,
                difference: estimate(Some(mean)),
                better: None,
            })
            .collect();
        DifferenceSet {
            label: label.to_owned(),
            slot,
            runs: 10,
            ci_level: 0.9,
            points,
        }
    }

    #[test]
    fn only_a_method_that_dwarfs_the_others_is_drawn_apart() {
        let reaching = |reaches: &[f64]| -> Vec<DifferenceSet> {
            (reaches.iter().enumerate())
                .map(|(k, &r)| set(&format!("m{k}"), k, &[0.0, -r / 2.0, -r]))
                .collect()
        };
        // The paper's scratch study: advising methods within 3 to 8 points,
        // the random policy 57 below.
        let study = reaching(&[6.0, 8.0, 6.0, 3.0, 57.0]);
        assert_eq!(drawn_apart(&study), [false, false, false, false, true]);
        // Four times the others' median, not more: together.
        assert_eq!(drawn_apart(&reaching(&[5.0, 6.0, 7.0, 24.0])), [false; 4]);
        assert_eq!(
            drawn_apart(&reaching(&[5.0, 6.0, 7.0, 24.1])),
            [false, false, false, true]
        );
        // Two far ones are both apart; the nearest never is.
        assert_eq!(
            drawn_apart(&reaching(&[4.0, 5.0, 60.0, 70.0])),
            [false, false, true, true]
        );
        assert_eq!(drawn_apart(&reaching(&[6.0, 57.0])), [false, true]);
        // Small differences stay together however they compare (the floor).
        assert_eq!(drawn_apart(&reaching(&[0.1, 0.2, 9.0])), [false; 3]);
        assert_eq!(
            drawn_apart(&reaching(&[0.0, 0.0, 10.5])),
            [false, false, true]
        );
        // One method, none, or none known: nothing apart.
        assert_eq!(drawn_apart(&reaching(&[57.0])), [false]);
        assert!(drawn_apart(&[]).is_empty());
        let mut unknown = set("u", 0, &[1.0]);
        unknown.points[0].difference = estimate(None);
        assert_eq!(drawn_apart(&[unknown.clone(), unknown]), [false, false]);
    }

    #[test]
    fn the_far_method_gets_its_own_chart_below_the_others() {
        let sets = [
            set("adhoc-td", 2, &[0.0, 2.0, 4.0, 6.0]),
            set("torrey", 3, &[0.0, -3.0, -1.0, 2.0]),
            set("random", 5, &[5.0, -30.0, -50.0, -57.0]),
        ];
        let figure = draw_difference("no-advice", &sets).unwrap();
        let svg = &figure.svg;
        // A taller figure: the chart, a heading and a chart of 200 pixels.
        let height = 600 + HEADING_H + MARGIN.0 + 200 + X_LABELS_H + MARGIN.2;
        assert!(svg.contains(&format!(r#"width="1000" height="{height}""#)));
        let heading = "Drawn apart, on its own scale: random (mean difference reaching -57 points; the others stay within \u{00B1}6)";
        assert!(svg.contains(heading), "no heading {heading:?}");
        assert_eq!(svg.matches("Training episodes").count(), 1);
        let raster = raster::rgb(svg).unwrap();
        assert_eq!((raster.width, raster.height), (1000, height as usize));
        // Each curve in one chart: adhoc-td's line spans most of the upper
        // one (its band reaches 11 of the range's about 23 points), random's
        // all of the lower one.
        let ys = |colour: &str| -> Vec<f64> {
            let line = (svg.lines())
                .find(|l| {
                    l.starts_with("<polyline")
                        && l.contains(&format!(r#"stroke="{colour}" stroke-width="2""#))
                })
                .unwrap_or_else(|| panic!("no line of {colour}"));
            let points = line.split("points=\"").nth(1).unwrap();
            let points = points.split('"').next().unwrap();
            (points.split_whitespace())
                .map(|xy| xy.split(',').nth(1).unwrap().parse().unwrap())
                .collect()
        };
        let spread = |ys: &[f64]| {
            let lo = ys.iter().copied().fold(f64::MAX, f64::min);
            let hi = ys.iter().copied().fold(f64::MIN, f64::max);
            (lo, hi)
        };
        let top = f64::from(HEADER_H + MARGIN.0);
        let upper_bottom = top + f64::from(PLOT.1);
        let (lo, hi) = spread(&ys("#009E73"));
        assert!(top < lo && hi < upper_bottom, "adhoc-td at {lo}..{hi}");
        assert!(
            hi - lo > 0.2 * f64::from(PLOT.1),
            "adhoc-td squeezed: {lo}..{hi}"
        );
        let (lo, hi) = spread(&ys("#E69F00"));
        assert!(
            lo > upper_bottom + f64::from(HEADING_H),
            "random at {lo}..{hi}"
        );
        assert!(hi - lo > 0.7 * 200.0, "random squeezed: {lo}..{hi}");
        // Without random, one chart again.
        let together = draw_difference("no-advice", &sets[..2]).unwrap();
        assert!(together.svg.contains(r#"width="1000" height="600""#));
        assert!(!together.svg.contains("Drawn apart"));
    }
}
