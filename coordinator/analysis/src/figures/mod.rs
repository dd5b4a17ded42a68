//! Figures of experiments in the style of the paper's: goal percentage with
//! a confidence band per algorithm (its Figures 3, 5, 7), time to goal
//! (Figure 2), spent budget (Figures 4a, 6a, 8a) and the goal percentage of
//! the last training episodes zoomed in (Figures 4b, 6b, 8b); and, beyond
//! the paper, each method's goal percentage minus the baseline's, paired by
//! run ([`draw_difference`], with a method whose differences dwarf the
//! others' drawn apart: [`drawn_apart`]), and what advising costs in
//! messages and bytes per training episode, and each method's gain against
//! the messages it sent ([`draw_tradeoff`]); and the communication frontier
//! of a study that sweeps settings, gain against messages or bytes on a
//! logarithmic axis, each method a curve ([`draw_frontier`]).
//!
//! Pure: the input is every algorithm's estimates in memory
//! ([`SeriesSet`]), the output every figure as an SVG document drawn with
//! `plotters` and a PNG of the same size rasterised by the `raster` crate
//! with the system's fonts (without any, the PNG has no text); the caller
//! writes them. Unknown means leave gaps in the lines; unknown interval
//! bounds leave gaps in the bands.
//!
//! ```
//! use analysis::Estimate;
//! use analysis::figures::{Point, SeriesSet, draw_figures};
//!
//! let goal = |mean| Estimate { n: 1, mean: Some(mean), ci_low: None, ci_high: None };
//! let point = |episode, pct| Point {
//!     episode,
//!     goal_pct: goal(pct),
//!     time_to_goal: goal(100.0 - pct),
//!     spent_budget: goal(0.0),
//!     advising_messages: goal(0.0),
//!     advising_bytes: goal(0.0),
//! };
//! let sets = [SeriesSet::new("NoAdvice", 1, 0.95, vec![point(0, 5.0), point(100, 30.0)])];
//! for figure in draw_figures(&sets)? {
//!     for (file, bytes) in figure.files() {
//!         println!("{file}: {} bytes", bytes.len());
//!     }
//! }
//! # Ok::<(), analysis::figures::FigureError>(())
//! ```

mod catalogue;
mod data;
mod difference;
mod draw;
mod figure;
#[cfg(test)]
mod fixtures;
mod frontier;
mod layout;
mod log_axis;
mod sweep;
mod tradeoff;

pub use data::{Metric, Point, Series, SeriesPoint, SeriesSet};
pub use difference::{
    APART_FACTOR, APART_FLOOR, DIFFERENCE, DifferencePoint, DifferenceSet, draw_difference,
    drawn_apart,
};
pub use figure::{Figure, FigureError};
pub use frontier::{FRONTIER_BYTES, FRONTIER_MESSAGES, FrontierDot, FrontierGroup, draw_frontier};
pub use layout::SIZE;
pub use sweep::{Condition, ConditionPoint, ConditionSet, draw_sweep};
pub use tradeoff::{TRADEOFF, TradeoffPoint, draw_tradeoff};

use catalogue::{FIGURES, note};

/// Every figure of `sets`, one colour per set in order: `goal_pct`,
/// `time_to_goal`, `spent_budget`, `goal_pct_last`, and the communication
/// cost: `advising_messages` and `advising_bytes` per training episode.
pub fn draw_figures(sets: &[SeriesSet]) -> Result<Vec<Figure>, FigureError> {
    let note = note(sets);
    FIGURES
        .iter()
        .map(|kind| {
            let series: Vec<Series> = sets.iter().map(|s| s.series(kind.metric)).collect();
            Figure::drawn(kind.name, kind.svg(&series, &note))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::fixtures::set;
    use super::*;

    #[test]
    fn draws_every_figure_as_svg_and_png() {
        let sets = [
            set("NoAdvice", &[Some(5.0), Some(20.0), Some(30.0), Some(35.0)]),
            set("AdHocTD", &[Some(5.0), Some(25.0), Some(40.0), Some(45.0)]),
        ];
        let figures = draw_figures(&sets).unwrap();
        let names: Vec<_> = figures.iter().map(|f| f.name).collect();
        assert_eq!(
            names,
            [
                "goal_pct",
                "time_to_goal",
                "spent_budget",
                "goal_pct_last",
                "advising_messages",
                "advising_bytes"
            ]
        );
        for (figure, axis) in figures.iter().zip([
            "Goal percentage (%)",
            "Time to goal (frames)",
            "Spent budget (advice given, per agent)",
            "Goal percentage (%)",
        ]) {
            let name = figure.name;
            for text in [
                "NoAdvice",
                "AdHocTD",
                "Training episodes",
                axis,
                "Mean over 3 runs; shaded: 95% confidence interval",
            ] {
                assert!(figure.svg.contains(text), "{name}.svg lacks {text:?}");
            }
            assert!(figure.png.starts_with(b"\x89PNG\r\n\x1a\n"), "{name}.png");
            let [(svg, svg_bytes), (png, png_bytes)] = figure.files();
            assert_eq!((svg, png), (format!("{name}.svg"), format!("{name}.png")));
            assert_eq!(
                (svg_bytes, png_bytes),
                (figure.svg.as_bytes(), &figure.png[..])
            );
        }
    }

    #[test]
    fn drawing_is_deterministic_and_needs_no_sets() {
        let sets = [set("A", &[Some(1.0), None, Some(3.0)])];
        assert_eq!(draw_figures(&sets).unwrap(), draw_figures(&sets).unwrap());
        assert_eq!(draw_figures(&[]).unwrap().len(), FIGURES.len());
    }
}
