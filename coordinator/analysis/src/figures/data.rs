//! The figures' input, built in memory: every algorithm's estimates over
//! runs at its evaluation points, and the curve of one metric taken from
//! them.

use crate::stats::Estimate;

/// What a figure plots against the training episodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    /// Percentage of evaluation episodes ending in a goal.
    GoalPct,
    /// Frames to a goal.
    TimeToGoal,
    /// Advice given, averaged over agents.
    SpentBudget,
    /// Advising messages the team sent per training episode.
    AdvisingMessages,
    /// Their bytes per training episode.
    AdvisingBytes,
}

impl Metric {
    /// The metric's estimate at `point`.
    fn of(self, point: &Point) -> &Estimate {
        match self {
            Metric::GoalPct => &point.goal_pct,
            Metric::TimeToGoal => &point.time_to_goal,
            Metric::SpentBudget => &point.spent_budget,
            Metric::AdvisingMessages => &point.advising_messages,
            Metric::AdvisingBytes => &point.advising_bytes,
        }
    }

    /// The metric's name, as in figure titles.
    pub(super) fn title(self) -> &'static str {
        match self {
            Metric::GoalPct => "Goal percentage",
            Metric::TimeToGoal => "Time to goal",
            Metric::SpentBudget => "Spent budget",
            Metric::AdvisingMessages => "Advising messages",
            Metric::AdvisingBytes => "Advising bytes",
        }
    }

    /// The y axis title, with the unit.
    pub(super) fn axis(self) -> &'static str {
        match self {
            Metric::GoalPct => "Goal percentage (%)",
            Metric::TimeToGoal => "Time to goal (frames)",
            Metric::SpentBudget => "Spent budget (advice given, per agent)",
            Metric::AdvisingMessages => "Messages sent per training episode (team)",
            Metric::AdvisingBytes => "Bytes sent per training episode (team)",
        }
    }
}

/// One evaluation point of an algorithm: the training episodes before it
/// and every metric's estimate over runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Training episodes played before the evaluation.
    pub episode: u64,
    /// Goal percentage.
    pub goal_pct: Estimate,
    /// Frames to a goal.
    pub time_to_goal: Estimate,
    /// Advice given, averaged over agents.
    pub spent_budget: Estimate,
    /// Advising messages (requests, replies, shared episodes) the team sent
    /// per training episode since the previous point.
    pub advising_messages: Estimate,
    /// Their bytes per training episode.
    pub advising_bytes: Estimate,
}

/// One algorithm's results: the input of the figures.
#[derive(Clone, Debug, PartialEq)]
pub struct SeriesSet {
    /// Legend label (the algorithm's name).
    pub label: String,
    /// Runs behind every mean.
    pub runs: u64,
    /// Confidence level of the intervals.
    pub ci_level: f64,
    /// Every evaluation point, in order.
    pub points: Vec<Point>,
}

/// One evaluation point of a curve: the mean and the interval bounds, each
/// `None` where unknown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeriesPoint {
    /// Training episodes played before the evaluation.
    pub episode: f64,
    /// Mean over runs.
    pub mean: Option<f64>,
    /// Lower bound of the confidence interval.
    pub low: Option<f64>,
    /// Upper bound of the confidence interval.
    pub high: Option<f64>,
    /// The interval of x, where x is itself an estimate (a cost); else
    /// `None`.
    pub x_interval: Option<(f64, f64)>,
}

/// One algorithm's curve of one metric: a line with a band around it.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// The evaluation points, by episode.
    pub points: Vec<SeriesPoint>,
}

impl SeriesSet {
    /// The results of `runs` runs with intervals at `ci_level`, labelled
    /// `label`.
    pub fn new(label: impl Into<String>, runs: u64, ci_level: f64, points: Vec<Point>) -> Self {
        Self {
            label: label.into(),
            runs,
            ci_level,
            points,
        }
    }

    /// The curve of `metric`; non-finite values count as unknown.
    pub fn series(&self, metric: Metric) -> Series {
        Series {
            label: self.label.clone(),
            points: self
                .points
                .iter()
                .map(|p| SeriesPoint::of(p.episode, metric.of(p)))
                .collect(),
        }
    }
}

impl SeriesPoint {
    /// The point of `estimate` at `episode`; non-finite values count as
    /// unknown.
    pub(super) fn of(episode: u64, estimate: &Estimate) -> Self {
        Self::at(episode as f64, estimate)
    }

    /// The point of `estimate` at `x` (which need not be an episode).
    pub(super) fn at(x: f64, estimate: &Estimate) -> Self {
        let known = |v: Option<f64>| v.filter(|v| v.is_finite());
        Self {
            episode: x,
            mean: known(estimate.mean),
            low: known(estimate.ci_low),
            high: known(estimate.ci_high),
            x_interval: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_and_non_finite_values_are_none() {
        let estimate = |mean, ci_low, ci_high| Estimate {
            n: 2,
            mean,
            ci_low,
            ci_high,
        };
        let set = SeriesSet::new(
            "X",
            2,
            0.9,
            vec![Point {
                episode: 50,
                goal_pct: estimate(Some(0.0), Some(0.0), Some(0.0)),
                time_to_goal: estimate(None, None, None),
                spent_budget: estimate(Some(1.5), Some(f64::NAN), None),
                advising_messages: estimate(None, None, None),
                advising_bytes: estimate(None, None, None),
            }],
        );
        assert_eq!((set.label.as_str(), set.runs, set.ci_level), ("X", 2, 0.9));
        let point = |m| set.series(m).points[0];
        assert_eq!(point(Metric::GoalPct).episode, 50.0);
        assert_eq!(point(Metric::GoalPct).mean, Some(0.0));
        assert_eq!(point(Metric::TimeToGoal).mean, None);
        assert_eq!(point(Metric::SpentBudget).mean, Some(1.5));
        assert_eq!(point(Metric::SpentBudget).low, None);
        assert_eq!(point(Metric::SpentBudget).high, None);
        assert_eq!(set.series(Metric::GoalPct).label, "X");
    }
}
