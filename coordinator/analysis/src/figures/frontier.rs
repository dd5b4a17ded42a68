//! The communication frontier: each entry's gain over the baseline against
//! the advising messages (or bytes) each agent sent per training episode,
//! on a logarithmic axis; one colour per group (the method it was swept
//! from), its entries joined in order of cost, whiskers on both axes, the
//! Pareto front ringed.

use super::data::{Series, SeriesPoint};
use super::draw::{self, Captions, Curve, MARKERS, Mark, MarkShape, PALETTE, Panel, Style};
use super::figure::{Figure, FigureError};
use super::layout::{Layout, YRange};
use crate::stats::Estimate;
use crate::stats::frontier::CostUnit;

/// The file name of the figure of messages.
pub const FRONTIER_MESSAGES: &str = "frontier_messages";
/// The file name of the figure of bytes.
pub const FRONTIER_BYTES: &str = "frontier_bytes";

/// One entry's point.
#[derive(Clone, Debug, PartialEq)]
pub struct FrontierDot {
    /// The entry.
    pub entry: String,
    /// What each agent sent per training episode, over runs.
    pub cost: Estimate,
    /// Its gain over the baseline, paired by run.
    pub gain: Estimate,
    /// Whether it is on the Pareto front.
    pub on_front: bool,
}

/// One group's points: a curve of the figure.
#[derive(Clone, Debug, PartialEq)]
pub struct FrontierGroup {
    /// Its name, in the legend.
    pub label: String,
    /// Its entries' points, in any order.
    pub dots: Vec<FrontierDot>,
}

/// The figure of `groups` in `unit` against `baseline`, whose gains are over
/// the last `last` evaluations of `runs` runs with intervals at
/// `ci_level`. A group keeps its colour (and marker) by its place in
/// `groups`. Entries that sent nothing have no place on a logarithmic
/// axis: the legend counts them beside their group's name.
pub fn draw_frontier(
    unit: CostUnit,
    baseline: &str,
    last: usize,
    (runs, ci_level): (u64, f64),
    groups: &[FrontierGroup],
) -> Result<Figure, FigureError> {
    let placed = |d: &&FrontierDot| {
        d.cost.mean.is_some_and(|c| c > 0.0 && c.is_finite()) && d.gain.mean.is_some()
    };
    let mut shown: Vec<(usize, Series, Vec<Mark>)> = Vec::new();
    for (k, g) in groups.iter().enumerate() {
        let mut dots: Vec<&FrontierDot> = g.dots.iter().filter(placed).collect();
        let silent = (g.dots.iter()).filter(|d| d.cost.mean == Some(0.0)).count();
        let label = match (silent, dots.len()) {
            (0, 0) => continue,
            (0, _) => g.label.clone(),
            (_, 0) => format!("{} (sent none)", g.label),
            (n, _) => format!("{} ({n} sent none)", g.label),
        };
        dots.sort_by(|a, b| {
            a.cost
                .mean
                .unwrap_or(0.0)
                .total_cmp(&b.cost.mean.unwrap_or(0.0))
        });
        let points = (dots.iter())
            .map(|d| {
                let mut p = SeriesPoint::at(d.cost.mean.unwrap_or(0.0), &d.gain);
                p.x_interval = d.cost.ci_low.zip(d.cost.ci_high);
                p
            })
            .collect();
        let marks = (dots.iter().filter(|d| d.on_front))
            .filter_map(|d| {
                Some(Mark {
                    episode: d.cost.mean?,
                    value: d.gain.mean?,
                    shape: MarkShape::Ring,
                })
            })
            .collect();
        shown.push((k, Series { label, points }, marks));
    }
    let series: Vec<Series> = shown.iter().map(|(_, s, _)| s.clone()).collect();
    let curves: Vec<Curve> = (shown.iter())
        .map(|(k, series, marks)| Curve {
            colour: PALETTE[k % PALETTE.len()],
            series,
            marks,
            style: Style::Path(MARKERS[(k / PALETTE.len()) % MARKERS.len()]),
        })
        .collect();
    let pct = (ci_level * 1e4).round() / 100.0;
    let runs = if runs == 1 {
        "1 run".to_owned()
    } else {
        format!("{runs} runs")
    };
    let note = format!(
        "Gain over {baseline} on the last {last} evaluations, mean over {runs}; whiskers: {pct}% \
         intervals; ringed: the Pareto front"
    );
    let (name, title, x_axis) = match unit {
        CostUnit::Messages => (
            FRONTIER_MESSAGES,
            "Gain against advising messages",
            "Advising messages sent per agent per training episode (log scale)",
        ),
        CostUnit::Bytes => (
            FRONTIER_BYTES,
            "Gain against advising bytes",
            "Advising bytes sent per agent per training episode (log scale)",
        ),
    };
    let panel = Panel {
        curves: &curves,
        layout: Layout::log_x(&series, YRange::Around(0.0)),
        y_axis: "Gain in goal percentage (points)",
        heading: "",
    };
    let captions = Captions {
        title,
        note: &note,
        x_axis,
    };
    Figure::drawn(name, draw::svg(&captions, &[panel]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A dot of `entry` at `cost` ± 10 % gaining `gain` ± 2.
    fn dot(entry: &str, cost: f64, gain: f64, on_front: bool) -> FrontierDot {
        let around = |mean: f64, half: f64| Estimate {
            n: 5,
            mean: Some(mean),
            ci_low: Some(mean - half),
            ci_high: Some(mean + half),
        };
        FrontierDot {
            entry: entry.to_owned(),
            cost: around(cost, cost / 10.0),
            gain: around(gain, 2.0),
            on_front,
        }
    }

    #[test]
    fn draws_each_group_as_a_path_with_its_front_ringed() {
        let groups = [
            FrontierGroup {
                label: "adhoc-td".to_owned(),
                dots: vec![
                    dot("adhoc-td-300", 3.0, 5.0, false),
                    dot("adhoc-td-30", 0.3, 4.0, true),
                    dot("adhoc-td-3000", 30.0, 6.0, true),
                ],
            },
            FrontierGroup {
                label: "torrey".to_owned(),
                dots: vec![
                    dot("torrey-30", 1.0, 1.0, false),
                    dot("torrey-300", 10.0, -1.0, false),
                ],
            },
            FrontierGroup {
                label: "no-advice-ensemble".to_owned(),
                dots: vec![dot("no-advice-ensemble", 0.0, -0.5, false)],
            },
        ];
        let figure = draw_frontier(CostUnit::Messages, "no-advice", 10, (5, 0.9), &groups).unwrap();
        assert_eq!(figure.name, FRONTIER_MESSAGES);
        for text in [
            "adhoc-td",
            "torrey",
            "Advising messages sent per agent per training episode (log scale)",
            "Gain over no-advice on the last 10 evaluations, mean over 5 runs; whiskers: 90% \
             intervals; ringed: the Pareto front",
            "no-advice-ensemble (sent none)",
        ] {
            assert!(figure.svg.contains(text), "the figure lacks {text:?}");
        }
        // Log ticks from 0.5 to 20 at 1, 2 and 5 times a power of ten.
        for tick in ["0.5", "1", "2", "5", "10", "20"] {
            let label = format!(">\n{tick}\n</text>");
            assert!(figure.svg.contains(&label), "no tick {tick}");
        }
        assert!(!figure.svg.contains(">\n15\n</text>"));
        // Five dots and three in the legend, two of them ringed.
        let circles = figure.svg.matches("<circle").count();
        assert_eq!(circles, 5 + 3 + 2, "{circles} circles");
        // A line through each group's three and two dots, in cost order.
        let blue = (figure.svg.lines())
            .filter(|l| l.starts_with("<polyline") && l.contains("#0072B2"))
            .filter_map(|l| l.split("points=\"").nth(1)?.split('"').next())
            .filter(|points| points.split_whitespace().count() == 3)
            .count();
        assert_eq!(blue, 1, "one line through adhoc-td's three dots");
        assert!(figure.png.starts_with(b"\x89PNG\r\n\x1a\n"));
        let bytes = draw_frontier(CostUnit::Bytes, "no-advice", 10, (5, 0.9), &groups).unwrap();
        assert_eq!(bytes.name, FRONTIER_BYTES);
        assert!(bytes.svg.contains("Advising bytes sent per agent"));
    }

    #[test]
    fn groups_past_the_palette_change_marker() {
        let groups: Vec<FrontierGroup> = (0..9)
            .map(|k| FrontierGroup {
                label: format!("method-{k}"),
                dots: vec![dot(&format!("method-{k}-30"), 1.0 + k as f64, 1.0, false)],
            })
            .collect();
        let figure = draw_frontier(CostUnit::Messages, "no-advice", 10, (5, 0.9), &groups).unwrap();
        // The first eight are dots, in the plot and the legend; the ninth
        // takes the first colour again, as squares.
        assert_eq!(figure.svg.matches("<circle").count(), 2 * 8);
        assert!(figure.svg.contains("method-8"));
    }
}
