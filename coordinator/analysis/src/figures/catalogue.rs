//! The figures made and what each shows: its metric, episodes, y range
//! rule, title and subtitle, and which curves it draws in which colour.

use super::data::{Metric, Series, SeriesPoint, SeriesSet};
use super::draw::{self, Captions, Curve, PALETTE, Panel, Style};
use super::layout::{Layout, YRange, zoom_start};

/// One figure: what it plots, how, and its file name.
pub(super) struct FigureKind {
    /// File name without extension.
    pub name: &'static str,
    /// The metric plotted.
    pub metric: Metric,
    /// Only the last training episodes (the zoom window).
    zoom: bool,
    /// How the y range is chosen.
    y: YRange,
    /// Curves that are zero throughout are named in the note instead of
    /// drawn (algorithms that never advise, in the spent budget).
    skip_zero: bool,
}

/// Every figure made, in order.
pub(super) const FIGURES: [FigureKind; 6] = [
    FigureKind {
        name: "goal_pct",
        metric: Metric::GoalPct,
        zoom: false,
        y: YRange::Fixed(0.0, 100.0),
        skip_zero: false,
    },
    FigureKind {
        name: "time_to_goal",
        metric: Metric::TimeToGoal,
        zoom: false,
        y: YRange::Fitted(None),
        skip_zero: false,
    },
    FigureKind {
        name: "spent_budget",
        metric: Metric::SpentBudget,
        zoom: false,
        y: YRange::FromZero,
        skip_zero: true,
    },
    FigureKind {
        name: "goal_pct_last",
        metric: Metric::GoalPct,
        zoom: true,
        y: YRange::Fitted(Some(100.0)),
        skip_zero: false,
    },
    FigureKind {
        name: "advising_messages",
        metric: Metric::AdvisingMessages,
        zoom: false,
        y: YRange::FromZero,
        skip_zero: true,
    },
    FigureKind {
        name: "advising_bytes",
        metric: Metric::AdvisingBytes,
        zoom: false,
        y: YRange::FromZero,
        skip_zero: true,
    },
];

impl FigureKind {
    /// The figure of `series` (coloured in order) as an SVG document, with
    /// the subtitle `note`, or what went wrong in drawing it.
    pub(super) fn svg(&self, series: &[Series], note: &str) -> Result<String, String> {
        let from = if self.zoom { zoom_start(series) } else { None };
        let mut skipped = Vec::new();
        let mut shown = Vec::new();
        let mut colours = Vec::new();
        for (s, &colour) in series.iter().zip(PALETTE.iter().cycle()) {
            let points: Vec<SeriesPoint> = s
                .points
                .iter()
                .filter(|p| from.is_none_or(|from| p.episode >= from))
                .copied()
                .collect();
            let zero = |v: Option<f64>| v.is_none_or(|v| v == 0.0);
            let known = points.iter().any(|p| p.mean.is_some());
            if self.skip_zero && known && points.iter().all(|p| zero(p.mean) && zero(p.high)) {
                skipped.push(s.label.as_str());
                continue;
            }
            let label = s.label.clone();
            shown.push(Series { label, points });
            colours.push(colour);
        }
        let mut note = note.to_owned();
        if !skipped.is_empty() {
            let sep = if note.is_empty() { "" } else { ". " };
            note = format!(
                "{note}{sep}Zero throughout, not drawn: {}",
                skipped.join(", ")
            );
        }

        let layout = Layout::of(&shown, self.y);
        let curves: Vec<Curve> = shown
            .iter()
            .zip(colours)
            .map(|(series, colour)| Curve {
                colour,
                series,
                marks: &[],
                style: Style::Line,
            })
            .collect();
        let captions = Captions {
            title: &self.title(),
            note: &note,
            x_axis: draw::EPISODES_AXIS,
        };
        let panel = Panel {
            curves: &curves,
            layout,
            y_axis: self.metric.axis(),
            heading: "",
        };
        draw::svg(&captions, &[panel])
    }

    /// The title.
    fn title(&self) -> String {
        if self.zoom {
            format!("{} in the last training episodes", self.metric.title())
        } else {
            format!("{} during training", self.metric.title())
        }
    }
}

/// The subtitle of every figure of `sets`: runs behind the means and the
/// level of the bands.
pub(super) fn note(sets: &[SeriesSet]) -> String {
    note_of(sets.iter().map(|s| (s.runs, s.ci_level)))
}

/// The subtitle of a figure of sets of `(runs, confidence level)`.
pub(super) fn note_of(sets: impl Iterator<Item = (u64, f64)> + Clone) -> String {
    let (Some(min), Some(max)) = (
        sets.clone().map(|s| s.0).min(),
        sets.clone().map(|s| s.0).max(),
    ) else {
        return String::new();
    };
    let runs = match (min == max, max) {
        (true, 1) => "1 run".to_owned(),
        (true, n) => format!("{n} runs"),
        (false, _) => format!("{min}\u{2013}{max} runs"),
    };
    let level = sets.clone().next().map_or(0.0, |s| s.1);
    let band = if sets.clone().all(|s| s.1 == level) {
        format!("{}% confidence interval", (level * 1e4).round() / 100.0)
    } else {
        "confidence interval".to_owned()
    };
    format!("Mean over {runs}; shaded: {band}")
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{RISING, estimate, set};
    use super::super::layout::{HEADER_H, MARGIN, PLOT};
    use super::*;
    use crate::stats::Estimate;

    #[test]
    fn the_note_names_runs_and_level() {
        let mut a = set("A", &[Some(1.0)]);
        a.ci_level = 0.9;
        a.runs = 2;
        assert_eq!(
            note(std::slice::from_ref(&a)),
            "Mean over 2 runs; shaded: 90% confidence interval"
        );
        let mut b = set("B", &[Some(1.0)]);
        b.runs = 1;
        assert_eq!(
            note(&[b.clone()]),
            "Mean over 1 run; shaded: 95% confidence interval"
        );
        assert_eq!(
            note(&[a, b]),
            "Mean over 1\u{2013}2 runs; shaded: confidence interval"
        );
        assert_eq!(note(&[]), "");
    }

    #[test]
    fn unknown_means_leave_gaps_not_zeros() {
        let s = set(
            "Gappy",
            &[Some(40.0), Some(50.0), None, Some(60.0), Some(70.0)],
        );
        let svg = FIGURES[0].svg(&[s.series(Metric::GoalPct)], "").unwrap();
        // Two lines of two points each, all above the 35% level.
        let y_at = |v: f64| f64::from(HEADER_H + MARGIN.0 + PLOT.1) - v / 100.0 * f64::from(PLOT.1);
        let lines: Vec<Vec<f64>> = svg
            .lines()
            .filter(|l| {
                l.starts_with("<polyline") && l.contains("stroke=\"#0072B2\" stroke-width=\"2\"")
            })
            .map(|l| {
                let points = l
                    .split("points=\"")
                    .nth(1)
                    .unwrap()
                    .split('"')
                    .next()
                    .unwrap();
                let ys = points
                    .split_whitespace()
                    .map(|xy| xy.split(',').nth(1).unwrap());
                ys.map(|y| y.parse().unwrap()).collect()
            })
            .collect();
        assert_eq!(lines.len(), 2, "{lines:?}");
        for y in lines.iter().flatten() {
            assert!(*y < y_at(35.0), "{y} is below 35%: {lines:?}");
        }
    }

    #[test]
    fn zoomed_figure_shows_the_last_episodes() {
        let s = set("A", &RISING);
        let series = [s.series(Metric::GoalPct)];
        let zoom = &FIGURES[3];
        assert!(zoom.zoom && FIGURES.iter().filter(|f| f.zoom).count() == 1);
        // Drawn, the zoomed figure's x axis starts at episode 400.
        let svg = zoom.svg(&series, "").unwrap();
        assert!(svg.contains(">\n400\n</text>") && !svg.contains(">\n300\n</text>"));
        assert!(svg.contains("Goal percentage in the last training episodes"));
        // The full one shows every episode.
        let svg = FIGURES[0].svg(&series, "").unwrap();
        assert!(svg.contains(">\n300\n</text>"));
    }

    #[test]
    fn never_advising_curves_are_named_not_drawn() {
        let mut silent = set("NoAdvice", &[Some(1.0), Some(2.0), Some(3.0)]);
        for p in &mut silent.points {
            p.spent_budget = Estimate {
                n: 3,
                mean: Some(0.0),
                ci_low: Some(0.0),
                ci_high: Some(0.0),
            };
        }
        let advising = set("AdHocTD", &[Some(1.0), Some(2.0), Some(3.0)]);
        let series = [
            silent.series(Metric::SpentBudget),
            advising.series(Metric::SpentBudget),
        ];
        let svg = FIGURES[2].svg(&series, "Mean over 3 runs").unwrap();
        assert!(svg.contains("Mean over 3 runs. Zero throughout, not drawn: NoAdvice"));
        assert!(!svg.contains("#0072B2"), "the first colour is not drawn");
        assert!(svg.contains("#D55E00"), "the second keeps its colour");
        // In the goal percentage, both are drawn.
        let series = [
            silent.series(Metric::GoalPct),
            advising.series(Metric::GoalPct),
        ];
        assert!(FIGURES[0].svg(&series, "").unwrap().contains("#0072B2"));
        // A curve without any known value is drawn (as nothing), not named.
        let mut unknown = set("Unknown", &[Some(1.0)]);
        unknown.points[0].spent_budget = estimate(None);
        let svg = FIGURES[2]
            .svg(&[unknown.series(Metric::SpentBudget)], "")
            .unwrap();
        assert!(!svg.contains("not drawn") && svg.contains("Unknown"));
    }
}
