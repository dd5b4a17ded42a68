//! A study's entries that sweep network conditions: each advising method's
//! goal percentage at 1000, 2000 and 5000 training episodes and the advice
//! it acted on, against the loss probability or the median latency of its
//! advice messages.

use agent::NetworkConditions;

use crate::figures::{Condition, ConditionPoint, ConditionSet, Figure, FigureError, draw_sweep};
use crate::results::EvalPoint;
use crate::stats::Estimate;
use crate::study::EntryResults;

/// The training episodes at which the goal percentage is read.
pub const EPISODES: [u64; 3] = [1000, 2000, 5000];

/// Where conditions `network` lie on `condition`'s axis: without them, at
/// zero on both; a loss without latency on the loss axis; a latency without
/// loss on the latency axis; both at once on neither.
fn x_of(condition: Condition, network: Option<&NetworkConditions>) -> Option<f64> {
    let Some(n) = network else {
        return Some(0.0);
    };
    let latency = n.latency.median_ms();
    match condition {
        Condition::Loss => (latency == 0.0).then_some(n.loss),
        Condition::Latency => (n.loss == 0.0).then_some(latency),
    }
}

/// The entry's network conditions (every agent has the entry's).
pub fn conditions(e: &EntryResults) -> Option<&NetworkConditions> {
    e.entry.network.as_ref()
}

/// The entry's goal percentage at `episode` (unknown if never evaluated there).
pub fn goal_at(e: &EntryResults, episode: u64) -> Estimate {
    (e.points.iter())
        .find(|p| p.episode == episode)
        .map_or_else(Estimate::default, |p| p.goal_pct)
}

/// Steps acted on advice per agent by the end of training, over runs.
pub fn advised(e: &EntryResults, level: f64) -> Estimate {
    e.last(level, |p: &EvalPoint| {
        let n = p.agents.len().max(1) as f64;
        Some(p.agents.iter().map(|a| a.ask_spent as f64).sum::<f64>() / n)
    })
}

/// The figures of every condition the study sweeps, the `baselines`'
/// goal percentages at [`EPISODES`] in their subtitle.
pub fn sweep_figures(
    entries: &[EntryResults],
    baselines: &[&EntryResults],
    level: f64,
) -> Result<Vec<Figure>, FigureError> {
    let episodes: Vec<String> = EPISODES.iter().map(u64::to_string).collect();
    let notes: Vec<String> = (baselines.iter())
        .map(|b| {
            let goals: Vec<String> = (EPISODES.iter())
                .map(|&ep| {
                    goal_at(b, ep)
                        .mean
                        .map_or("-".to_owned(), |m| format!("{m:.1}"))
                })
                .collect();
            format!(
                "{}: {} % at {}",
                b.entry.name,
                goals.join(" / "),
                episodes.join(" / ")
            )
        })
        .collect();
    let note = notes.join("; ");
    let mut figures = Vec::new();
    for condition in Condition::ALL {
        let sets = condition_sets(entries, condition, level);
        if !sets.is_empty() {
            figures.extend(draw_sweep(condition, &EPISODES, &sets, &note)?);
        }
    }
    Ok(figures)
}

/// One set per advising method along `condition`, if the study sweeps it:
/// some method has points at two values of it.
fn condition_sets(entries: &[EntryResults], condition: Condition, level: f64) -> Vec<ConditionSet> {
    let advising = |e: &&EntryResults| e.entry.algorithm.communicates();
    let mut sets: Vec<ConditionSet> = Vec::new();
    for e in entries.iter().filter(advising) {
        let Some(x) = x_of(condition, conditions(e)) else {
            continue;
        };
        let point = ConditionPoint {
            x,
            goal_pct: EPISODES.iter().map(|&ep| goal_at(e, ep)).collect(),
            advised: advised(e, level),
        };
        let label = e.method();
        match sets.iter_mut().find(|s| s.label == label) {
            Some(s) if s.points.iter().all(|p| p.x != x) => s.points.push(point),
            Some(_) => {}
            None => sets.push(ConditionSet {
                label,
                runs: e.runs(),
                ci_level: level,
                points: vec![point],
            }),
        }
    }
    for s in &mut sets {
        s.points.sort_by(|a, b| a.x.total_cmp(&b.x));
    }
    let swept = sets.iter().any(|s| s.points.len() > 1);
    if swept { sets } else { Vec::new() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::Study;

    #[test]
    fn the_presets_entries_lie_on_both_axes() {
        let preset = include_str!("../../presets/advice-network.toml");
        let study: Study = toml::from_str(preset).unwrap();
        for algorithm in ["adhoc-td", "adhoc-visit"].map(|a| a.parse::<agent::Algorithm>().unwrap())
        {
            let xs = |condition| -> Vec<f64> {
                (study.entries.iter())
                    .filter(|e| e.algorithm == algorithm)
                    .filter_map(|e| x_of(condition, e.network.as_ref()))
                    .collect()
            };
            assert_eq!(xs(Condition::Loss), [0.0, 0.25, 0.5, 0.75]);
            assert_eq!(xs(Condition::Latency), [0.0, 1.0, 2.0, 3.0]);
        }
        let both = NetworkConditions {
            latency: agent::Latency::Fixed(1.0),
            loss: 0.1,
            timeout_ms: 5.0,
        };
        assert_eq!(x_of(Condition::Loss, Some(&both)), None);
        assert_eq!(x_of(Condition::Latency, Some(&both)), None);
    }
}
