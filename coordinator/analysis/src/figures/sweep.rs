//! Advising under network conditions: each method's goal percentage at a
//! few training episodes, and the advice it acted on, against one condition
//! of its advice messages (their loss probability or median latency).

use super::catalogue::note_of;
use super::data::{Series, SeriesPoint};
use super::draw::{self, Captions, Curve, PALETTE, Panel, Style};
use super::figure::{Figure, FigureError};
use super::layout::{Layout, YRange};
use crate::stats::Estimate;

/// The condition a sweep varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Condition {
    /// The probability that a message is lost.
    Loss,
    /// The median one-way latency (ms).
    Latency,
}

impl Condition {
    /// Both, in the report's order.
    pub const ALL: [Condition; 2] = [Condition::Loss, Condition::Latency];

    /// The x axis title.
    fn axis(self) -> &'static str {
        match self {
            Condition::Loss => "Probability that an advice message is lost",
            Condition::Latency => "Median one-way latency of an advice message (ms)",
        }
    }

    /// The two figures' file names.
    fn names(self) -> [&'static str; 2] {
        match self {
            Condition::Loss => ["network_loss_goal_pct", "network_loss_advice"],
            Condition::Latency => ["network_latency_goal_pct", "network_latency_advice"],
        }
    }
}

/// One method under one condition.
#[derive(Clone, Debug, PartialEq)]
pub struct ConditionPoint {
    /// The condition's value.
    pub x: f64,
    /// Goal percentage at each of the sweep's episodes.
    pub goal_pct: Vec<Estimate>,
    /// Steps acted on advice, per agent, by the end of training.
    pub advised: Estimate,
}

/// One method along a sweep: the figures' input.
#[derive(Clone, Debug, PartialEq)]
pub struct ConditionSet {
    /// Legend label (the method's name).
    pub label: String,
    /// Runs behind every mean.
    pub runs: u64,
    /// Confidence level of the intervals.
    pub ci_level: f64,
    /// Its points, by increasing condition.
    pub points: Vec<ConditionPoint>,
}

/// The figures of `sets` along `condition`: goal percentage at each of
/// `episodes` (one line per method and episode), and the advice acted on;
/// `note` is added to the goal figure's subtitle (e.g. the baseline's).
pub fn draw_sweep(
    condition: Condition,
    episodes: &[u64],
    sets: &[ConditionSet],
    note: &str,
) -> Result<[Figure; 2], FigureError> {
    let series = |set: &ConditionSet,
                  label: String,
                  value: &dyn Fn(&ConditionPoint) -> Option<&Estimate>| Series {
        label,
        points: (set.points.iter())
            .filter_map(|p| Some(SeriesPoint::at(p.x, value(p)?)))
            .collect(),
    };
    let goals: Vec<Series> = (sets.iter())
        .flat_map(|s| {
            (episodes.iter().enumerate()).map(move |(k, ep)| {
                series(s, format!("{} at {ep}", s.label), &|p| p.goal_pct.get(k))
            })
        })
        .collect();
    let advice: Vec<Series> = (sets.iter())
        .map(|s| series(s, s.label.clone(), &|p| Some(&p.advised)))
        .collect();
    let runs = note_of(sets.iter().map(|s| (s.runs, s.ci_level)));
    let [goal_name, advice_name] = condition.names();
    let goal_note = [runs.as_str(), note]
        .into_iter()
        .filter(|t| !t.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    let goal = figure(
        goal_name,
        &Captions {
            title: "Goal percentage under network conditions",
            note: &goal_note,
            x_axis: condition.axis(),
        },
        "Goal percentage (%)",
        &goals,
        YRange::Fixed(0.0, 100.0),
    )?;
    let advised = figure(
        advice_name,
        &Captions {
            title: "Advice acted on under network conditions",
            note: &runs,
            x_axis: condition.axis(),
        },
        "Steps acted on advice, per agent, by the end",
        &advice,
        YRange::FromZero,
    )?;
    Ok([goal, advised])
}

/// One figure of `series`, coloured in order, with the y axis title
/// `y_axis`.
fn figure(
    name: &'static str,
    captions: &Captions,
    y_axis: &str,
    series: &[Series],
    y: YRange,
) -> Result<Figure, FigureError> {
    let curves: Vec<Curve> = (series.iter().zip(PALETTE.iter().cycle()))
        .map(|(series, &colour)| Curve {
            colour,
            series,
            marks: &[],
            style: Style::Line,
        })
        .collect();
    let panel = Panel {
        curves: &curves,
        layout: Layout::of(series, y),
        y_axis,
        heading: "",
    };
    Figure::drawn(name, draw::svg(captions, &[panel]))
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::estimate;
    use super::*;

    #[test]
    fn draws_goal_and_advice_against_the_condition() {
        let point = |x: f64, goal: f64, advised: f64| ConditionPoint {
            x,
            goal_pct: vec![estimate(Some(goal / 2.0)), estimate(Some(goal))],
            advised: estimate(Some(advised)),
        };
        let set = ConditionSet {
            label: "adhoc-td".to_owned(),
            runs: 5,
            ci_level: 0.9,
            points: vec![
                point(0.0, 60.0, 90.0),
                point(0.5, 55.0, 40.0),
                point(0.9, 50.0, 8.0),
            ],
        };
        let [goal, advice] =
            draw_sweep(Condition::Loss, &[1000, 5000], &[set], "no-advice: 48 %").unwrap();
        assert_eq!(
            (goal.name, advice.name),
            ("network_loss_goal_pct", "network_loss_advice")
        );
        for text in [
            "adhoc-td at 1000",
            "adhoc-td at 5000",
            "Probability that an advice message is lost",
            "Mean over 5 runs; shaded: 90% confidence interval; no-advice: 48 %",
        ] {
            assert!(goal.svg.contains(text), "the goal figure lacks {text:?}");
        }
        assert!(advice.svg.contains("Steps acted on advice"));
        assert!(advice.png.starts_with(b"\x89PNG\r\n\x1a\n"));
    }
}
