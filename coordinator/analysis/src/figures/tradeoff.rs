//! What each method gains for what it sends: its gain in goal % over the
//! baseline against the advising messages each agent sent per training
//! episode, one dot per method with the gain's paired interval.

use super::data::{Series, SeriesPoint};
use super::draw::{self, Captions, Curve, PALETTE, Panel, Style};
use super::figure::{Figure, FigureError};
use super::layout::{Layout, YRange};
use crate::stats::Estimate;

/// The figure's file name.
pub const TRADEOFF: &str = "gain_vs_messages";

/// One method's dot.
#[derive(Clone, Debug, PartialEq)]
pub struct TradeoffPoint {
    /// Its label (the method's name).
    pub label: String,
    /// Advising messages each agent sent per training episode, mean over
    /// runs.
    pub messages: f64,
    /// Its gain over the baseline, paired by run, with its interval.
    pub gain: Estimate,
}

/// The figure of `points` against `baseline`, whose gains are over the last
/// `last` evaluations of `runs` runs with intervals at `ci_level`.
pub fn draw_tradeoff(
    baseline: &str,
    last: usize,
    (runs, ci_level): (u64, f64),
    points: &[TradeoffPoint],
) -> Result<Figure, FigureError> {
    let series: Vec<Series> = (points.iter())
        .map(|p| Series {
            label: p.label.clone(),
            points: vec![SeriesPoint::at(p.messages, &p.gain)],
        })
        .collect();
    let curves: Vec<Curve> = (series.iter().zip(PALETTE.iter().cycle()))
        .map(|(series, &colour)| Curve {
            colour,
            series,
            marks: &[],
            style: Style::Dots,
        })
        .collect();
    // Each dot is labelled beside it; room on the right for the last label.
    let mut layout = Layout::unlabelled(&series, YRange::Around(0.0));
    let (lo, hi) = layout.ranges.x;
    layout.ranges.x = (lo.min(0.0), hi + (hi - lo.min(0.0)).max(1.0) * 0.25);
    let note = format!(
        "Gain over {baseline} on the last {last} evaluations, mean over {runs} runs; \
         whiskers: {}% confidence interval, paired by run",
        (ci_level * 1e4).round() / 100.0
    );
    let panel = Panel {
        curves: &curves,
        layout,
        y_axis: "Gain in goal percentage (points)",
        heading: "",
    };
    let captions = Captions {
        title: "Gain against communication",
        note: &note,
        x_axis: "Advising messages sent per agent per training episode",
    };
    Figure::drawn(TRADEOFF, draw::svg(&captions, &[panel]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_one_labelled_dot_per_method_with_its_interval() {
        let point = |label: &str, messages, mean| TradeoffPoint {
            label: label.to_owned(),
            messages,
            gain: Estimate {
                n: 5,
                mean: Some(mean),
                ci_low: Some(mean - 2.0),
                ci_high: Some(mean + 2.0),
            },
        };
        let points = [
            point("no-advice", 0.0, 0.0),
            point("adhoc-td", 1.5, 6.0),
            point("early-advising", 9.0, -3.0),
        ];
        let figure = draw_tradeoff("no-advice", 10, (5, 0.9), &points).unwrap();
        assert_eq!(figure.name, TRADEOFF);
        for text in [
            "adhoc-td",
            "early-advising",
            "Advising messages sent per agent per training episode",
            "Gain over no-advice on the last 10 evaluations, mean over 5 runs; whiskers: 90%",
        ] {
            assert!(figure.svg.contains(text), "the figure lacks {text:?}");
        }
        // A dot and two caps per method.
        assert_eq!(figure.svg.matches("<circle").count(), 3);
        assert!(figure.png.starts_with(b"\x89PNG\r\n\x1a\n"));
    }
}
