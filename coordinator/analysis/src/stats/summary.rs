//! An experiment's summary (its `summary.json` but the configuration): at
//! every evaluation point, the mean and confidence interval over runs of
//! each metric; the communication and the cost of the runs.

use serde::Serialize;

use crate::results::{AgentStats, EvalPoint, RunResult, Timing};
use crate::stats::{Estimate, estimate};

/// One evaluation point over all runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SummaryPoint {
    /// Training episodes played before the evaluation.
    pub episode: u64,
    /// Goal percentage.
    pub goal_pct: Estimate,
    /// Mean frames to a goal, over the runs that scored at this point.
    pub time_to_goal: Estimate,
    /// Give budget spent, averaged over agents.
    pub spent_budget: Estimate,
    /// Advising messages the team sent per training episode since the
    /// previous point (unknown at the first).
    pub advising_messages: Estimate,
    /// Their bytes per training episode.
    pub advising_bytes: Estimate,
}

/// What an experiment's runs cost, summed over runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Cost {
    /// Agent decisions in training episodes.
    pub training_frames: u64,
    /// Agent decisions in evaluation episodes.
    pub evaluation_frames: u64,
    /// Wall time of the runs, each measured on its own thread when it was
    /// played (s; it varies from one machine and moment to another).
    pub wall_s: f64,
    /// `(training_frames + evaluation_frames) / wall_s`.
    pub frames_per_sec: f64,
}

impl Cost {
    /// The cost of `results`.
    pub fn of(results: &[RunResult]) -> Self {
        let mut total = Timing::default();
        for r in results {
            total.add(&r.timing);
        }
        Cost {
            training_frames: total.training_frames,
            evaluation_frames: total.evaluation_frames,
            wall_s: total.training_s + total.evaluation_s,
            frames_per_sec: total.frames_per_sec(),
        }
    }
}

/// Communication of a team or an agent over a run, averaged over runs
/// (round-trip times pooled over runs).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CommTotals {
    /// Advice requests sent.
    pub advice_requests: f64,
    /// Replies received to them.
    pub advice_replies_received: f64,
    /// Advice given.
    pub advice_given: f64,
    /// Messages sent, every kind.
    pub messages_sent: f64,
    /// Bytes sent, every kind.
    pub bytes_sent: f64,
    /// Messages received, every kind.
    pub messages_received: f64,
    /// Bytes received, every kind.
    pub bytes_received: f64,
    /// Received messages dropped (malformed, foreign, stale, duplicate,
    /// unrequested advice).
    pub messages_dropped: f64,
    /// Advice round-trip time (ms).
    pub advice_rtt_ms: Percentiles,
}

/// Median and 99th percentile of a sample (null without samples).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Percentiles {
    /// Median.
    pub median: Option<f64>,
    /// 99th percentile.
    pub p99: Option<f64>,
}

impl Percentiles {
    /// Nearest-rank percentiles of `samples`.
    pub fn of(mut samples: Vec<f64>) -> Self {
        if samples.is_empty() {
            return Self::default();
        }
        samples.sort_by(f64::total_cmp);
        let rank = |p: f64| {
            samples[((p * samples.len() as f64).ceil() as usize).clamp(1, samples.len()) - 1]
        };
        Self {
            median: Some(rank(0.5)),
            p99: Some(rank(0.99)),
        }
    }
}

/// The team's communication and every agent's.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CommSummary {
    /// Totals over agents.
    #[serde(flatten)]
    pub team: CommTotals,
    /// Awaited actions env-server played as Move because they missed the
    /// step timeout, per run (mean over runs).
    pub actions_timed_out: f64,
    /// The same per agent, by id.
    pub per_agent: Vec<CommTotals>,
}

impl CommSummary {
    /// Communication over `results` (every run, each with its final agent statistics).
    pub fn of(results: &[RunResult], agents: usize) -> Self {
        let of_agents = |which: &dyn Fn(usize) -> bool| {
            let runs = results.len().max(1) as f64;
            let mut t = CommTotals::default();
            let mut rtt = Vec::new();
            for r in results {
                let Some(last) = r.points.last() else {
                    continue;
                };
                for (i, a) in last.agents.iter().enumerate().filter(|(i, _)| which(*i)) {
                    t.advice_requests += a.advice_requests as f64 / runs;
                    t.advice_replies_received += a.advice_replies_received as f64 / runs;
                    t.advice_given += a.advice_given as f64 / runs;
                    t.messages_sent += a.messages_sent as f64 / runs;
                    t.bytes_sent += a.bytes_sent as f64 / runs;
                    t.messages_received += a.messages_received as f64 / runs;
                    t.bytes_received += a.bytes_received as f64 / runs;
                    t.messages_dropped += a.messages_dropped as f64 / runs;
                    if let Some(samples) = r.advice_rtt_ms.get(i) {
                        rtt.extend(samples.iter().map(|&ms| f64::from(ms)));
                    }
                }
            }
            t.advice_rtt_ms = Percentiles::of(rtt);
            t
        };
        let timed_out: u64 = results
            .iter()
            .filter_map(|r| r.points.last())
            .map(|p| p.actions_timed_out)
            .sum();
        Self {
            team: of_agents(&|_| true),
            actions_timed_out: timed_out as f64 / results.len().max(1) as f64,
            per_agent: (0..agents).map(|i| of_agents(&|j| j == i)).collect(),
        }
    }
}

/// The mean and interval over `results` of each metric at every
/// evaluation point (those of the run with the most), at level `level`.
pub fn summary_points(results: &[RunResult], level: f64) -> Vec<SummaryPoint> {
    let episodes: Vec<u64> = (results.iter())
        .max_by_key(|r| r.points.len())
        .map(|r| r.points.iter().map(|p| p.episode).collect())
        .unwrap_or_default();
    let column = |p: usize, f: &dyn Fn(&EvalPoint) -> Option<f64>| {
        results
            .iter()
            .filter_map(|r| r.points.get(p).and_then(f))
            .collect::<Vec<f64>>()
    };
    // Per run, the team's count per training episode between points p - 1 and p.
    let rates = |p: usize, count: fn(&AgentStats) -> u64| {
        let team = |e: &EvalPoint| e.agents.iter().map(count).sum::<u64>() as f64;
        results
            .iter()
            .filter_map(|r| {
                let (before, now) = (r.points.get(p.checked_sub(1)?)?, r.points.get(p)?);
                let episodes = now.episode.checked_sub(before.episode).filter(|&n| n > 0)?;
                Some((team(now) - team(before)) / episodes as f64)
            })
            .collect::<Vec<f64>>()
    };
    (episodes.into_iter().enumerate())
        .map(|(p, episode)| SummaryPoint {
            episode,
            goal_pct: estimate(&column(p, &|e| Some(e.goal_pct)), level),
            time_to_goal: estimate(&column(p, &|e| e.time_to_goal), level),
            spent_budget: estimate(&column(p, &|e| Some(e.spent_budget)), level),
            advising_messages: estimate(&rates(p, |a| a.advising_messages), level),
            advising_bytes: estimate(&rates(p, |a| a.advising_bytes), level),
        })
        .collect()
}

/// Every run's advice matrix (n x n zeros for a run without advice), or
/// none when no run acted on advice.
pub fn advice_matrices(results: &[RunResult], n: usize) -> Vec<Vec<Vec<u64>>> {
    if results.iter().all(|r| r.advice_matrix.is_empty()) {
        return Vec::new();
    }
    (results.iter())
        .map(|r| match r.advice_matrix.is_empty() {
            true => vec![vec![0; n]; n],
            false => r.advice_matrix.clone(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::Percentiles;

    #[test]
    fn nearest_rank_percentiles() {
        let p = Percentiles::of((1..=100).map(f64::from).collect());
        assert_eq!((p.median, p.p99), (Some(50.0), Some(99.0)));
        let one = Percentiles::of(vec![3.0]);
        assert_eq!((one.median, one.p99), (Some(3.0), Some(3.0)));
        assert_eq!(Percentiles::of(Vec::new()), Percentiles::default());
    }
}
