//! The communication frontier: what each entry gains over its baseline for
//! what it sends. Entries swept from one study entry share a group (the
//! method), and each is a point of its group's curve: its cost (advising
//! messages, or bytes, each agent sent per training episode over the whole
//! training) against its gain, paired by run. The Pareto front, each
//! group's gain at equal cost, and the messages each point of gain took.

use serde::Serialize;

use crate::baselines::{Pair, common_baseline};
use crate::results::{AgentStats, RunResult};
use crate::stats::gains::gain;
use crate::stats::{Estimate, estimate};
use crate::study::EntryResults;

/// What a cost is counted in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CostUnit {
    /// Advising messages: requests, replies and shared episodes.
    Messages,
    /// Their encoded bytes.
    Bytes,
}

impl CostUnit {
    /// Both, in the report's order.
    pub const ALL: [CostUnit; 2] = [CostUnit::Messages, CostUnit::Bytes];

    /// `messages` or `bytes`.
    pub fn name(self) -> &'static str {
        match self {
            CostUnit::Messages => "messages",
            CostUnit::Bytes => "bytes",
        }
    }

    /// The counter this unit counts.
    fn counter(self) -> fn(&AgentStats) -> u64 {
        match self {
            CostUnit::Messages => |a| a.advising_messages,
            CostUnit::Bytes => |a| a.advising_bytes,
        }
    }
}

/// One entry on the frontier.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FrontierPoint {
    /// The entry.
    pub entry: String,
    /// Its group: the entry it was swept from, or its own name.
    pub group: String,
    /// Its baseline.
    pub baseline: String,
    /// Advising messages each agent sent per training episode over the
    /// whole training, over runs.
    pub messages: Estimate,
    /// Their bytes, likewise.
    pub bytes: Estimate,
    /// Its gain in goal % over its baseline on the last ten evaluations,
    /// paired by run.
    pub last_ten_gain: Estimate,
    /// The same on the whole curve (its mean height).
    pub area_gain: Estimate,
    /// On the Pareto front of messages and last-ten gain (among the
    /// entries of its baseline).
    pub front_messages: bool,
    /// On the Pareto front of bytes and last-ten gain.
    pub front_bytes: bool,
    /// Mean messages ÷ mean last-ten gain, where the gain's interval lies
    /// above 0.
    pub messages_per_point: Option<f64>,
}

impl FrontierPoint {
    /// Its cost in `unit`.
    pub fn cost(&self, unit: CostUnit) -> &Estimate {
        match unit {
            CostUnit::Messages => &self.messages,
            CostUnit::Bytes => &self.bytes,
        }
    }

    /// Whether it is on the Pareto front of `unit`.
    pub fn on_front(&self, unit: CostUnit) -> bool {
        match unit {
            CostUnit::Messages => self.front_messages,
            CostUnit::Bytes => self.front_bytes,
        }
    }
}

/// One group's last-ten gain at each of the frontier's message rates.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EqualCost {
    /// The group.
    pub group: String,
    /// Its gain at each rate, interpolated along its curve; `None` outside
    /// the range of its entries' costs.
    pub gains: Vec<Option<Estimate>>,
}

/// A study's frontier against its baselines.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Frontier {
    /// The baseline of every point, if they share one (else each point's
    /// own).
    pub baseline: Option<String>,
    /// Every entry compared with a baseline, in entry order.
    pub points: Vec<FrontierPoint>,
    /// The message rates of the equal-cost table (messages per agent per
    /// training episode).
    pub rates: Vec<f64>,
    /// Every group of two or more entries that sent messages, at those
    /// rates, in entry order.
    pub equal_cost: Vec<EqualCost>,
}

impl Frontier {
    /// The groups in order of their first entry, each with its points in
    /// entry order.
    pub fn groups(&self) -> Vec<(&str, Vec<&FrontierPoint>)> {
        let mut groups: Vec<(&str, Vec<&FrontierPoint>)> = Vec::new();
        for p in &self.points {
            match groups.iter_mut().find(|(g, _)| *g == p.group) {
                Some((_, points)) => points.push(p),
                None => groups.push((&p.group, vec![p])),
            }
        }
        groups
    }
}

/// The frontier of `pairs`' entries against their baselines, with
/// intervals at `level`; none with fewer than two of them. Each group of
/// two or more (a swept entry's values) is also a curve, read at equal
/// cost.
pub fn frontier(pairs: &[Pair], level: f64) -> Option<Frontier> {
    let mut points: Vec<FrontierPoint> = (pairs.iter())
        .map(|p| {
            let (e, g) = (p.entry, gain(p.entry, p.baseline, level));
            let messages = cost(e, CostUnit::Messages, level);
            FrontierPoint {
                entry: e.entry.name.clone(),
                group: (e.entry.group.clone()).unwrap_or_else(|| e.entry.name.clone()),
                baseline: p.baseline_name().to_owned(),
                messages,
                bytes: cost(e, CostUnit::Bytes, level),
                messages_per_point: messages_per_point(&messages, &g.last_ten_gain),
                last_ten_gain: g.last_ten_gain,
                area_gain: g.area_gain,
                front_messages: false,
                front_bytes: false,
            }
        })
        .collect();
    let mut frontier = Frontier {
        baseline: common_baseline(pairs).map(str::to_owned),
        points: Vec::new(),
        rates: Vec::new(),
        equal_cost: Vec::new(),
    };
    for unit in CostUnit::ALL {
        let at = |p: &FrontierPoint| Some((p.cost(unit).mean?, p.last_ten_gain.mean?));
        let known: Vec<(&str, Option<(f64, f64)>)> = points
            .iter()
            .map(|p| (p.baseline.as_str(), at(p)))
            .collect();
        let on: Vec<bool> = (points.iter().zip(pairs))
            .map(|(p, pair)| {
                // The baseline counts as a point at its own cost and a gain of 0.
                let base = cost(pair.baseline, unit, level).mean.map(|c| (c, 0.0));
                let rivals: Vec<(f64, f64)> = (known.iter())
                    .filter(|(b, _)| *b == p.baseline)
                    .filter_map(|(_, point)| *point)
                    .chain(base)
                    .collect();
                at(p).is_some_and(|me| !rivals.iter().any(|&other| dominates(other, me)))
            })
            .collect();
        for (p, on) in points.iter_mut().zip(on) {
            match unit {
                CostUnit::Messages => p.front_messages = on,
                CostUnit::Bytes => p.front_bytes = on,
            }
        }
    }
    if points.len() < 2 {
        return None;
    }
    frontier.points = points;
    let groups = frontier.groups();
    let curves: Vec<(String, Vec<Curve>)> = (groups.into_iter())
        .map(|(group, points)| (group.to_owned(), curve(&points)))
        .filter(|(_, curve)| curve.len() >= 2)
        .collect();
    frontier.rates = rates(
        &curves
            .iter()
            .filter_map(|(_, c)| range(c))
            .collect::<Vec<_>>(),
    );
    frontier.equal_cost = (curves.into_iter())
        .map(|(group, c)| EqualCost {
            group,
            gains: frontier.rates.iter().map(|&r| at_cost(&c, r)).collect(),
        })
        .collect();
    Some(frontier)
}

/// Whether `a` dominates `b` (each `(cost, gain)`): it costs no more and
/// gains no less, and one of them strictly.
pub fn dominates(a: (f64, f64), b: (f64, f64)) -> bool {
    a.0 <= b.0 && a.1 >= b.1 && (a.0 < b.0 || a.1 > b.1)
}

/// `unit` each agent sent per training episode over the whole training,
/// over the runs of `e`: per run, the team's count at the last evaluation
/// divided by its agents and the training episodes played.
pub fn cost(e: &EntryResults, unit: CostUnit, level: f64) -> Estimate {
    let per_run: Vec<f64> = (e.results.iter())
        .filter_map(|r| per_agent_episode(r, unit.counter()))
        .collect();
    estimate(&per_run, level)
}

/// A run's count of `counter` over its agents at its last evaluation, per
/// agent per training episode; none before any training or without agents.
pub(crate) fn per_agent_episode(run: &RunResult, counter: fn(&AgentStats) -> u64) -> Option<f64> {
    let last = run.points.last()?;
    if last.episode == 0 || last.agents.is_empty() {
        return None;
    }
    let total: u64 = last.agents.iter().map(counter).sum();
    Some(total as f64 / (last.agents.len() as f64 * last.episode as f64))
}

/// Mean messages per mean point of gain, where the gain's interval lies
/// above 0 (so neither is near a division by zero).
pub fn messages_per_point(messages: &Estimate, gain: &Estimate) -> Option<f64> {
    let (cost, mean) = (messages.mean?, gain.mean?);
    (gain.ci_low? > 0.0).then(|| cost / mean)
}

/// A point of a group's curve: its mean message cost and its gain.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Curve {
    cost: f64,
    gain: Estimate,
}

/// A group's curve: its entries with a positive mean cost and a known
/// mean gain, by cost (equal costs in entry order).
fn curve(points: &[&FrontierPoint]) -> Vec<Curve> {
    let mut curve: Vec<Curve> = (points.iter())
        .filter_map(|p| {
            let cost = p.messages.mean.filter(|c| *c > 0.0 && c.is_finite())?;
            p.last_ten_gain.mean?;
            Some(Curve {
                cost,
                gain: p.last_ten_gain,
            })
        })
        .collect();
    curve.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    curve
}

/// The costs a curve spans, if it has two points or more.
fn range(curve: &[Curve]) -> Option<(f64, f64)> {
    match curve {
        [first, .., last] => Some((first.cost, last.cost)),
        _ => None,
    }
}

/// The curve's gain at `rate`: at a point of that cost (the mean of such
/// points), else each of the mean and the interval bounds interpolated
/// linearly in log10(cost) between the points around it; none outside the
/// curve's range, or where a bound is unknown on either side.
fn at_cost(curve: &[Curve], rate: f64) -> Option<Estimate> {
    let (lo, hi) = range(curve)?;
    if !(lo..=hi).contains(&rate) {
        return None;
    }
    let same: Vec<&Curve> = curve.iter().filter(|c| c.cost == rate).collect();
    if !same.is_empty() {
        let mean_of = |f: fn(&Estimate) -> Option<f64>| {
            let values: Option<Vec<f64>> = same.iter().map(|c| f(&c.gain)).collect();
            values.map(|v| v.iter().sum::<f64>() / v.len() as f64)
        };
        return Some(Estimate {
            n: same.iter().map(|c| c.gain.n).min().unwrap_or(0),
            mean: mean_of(|e| e.mean),
            ci_low: mean_of(|e| e.ci_low),
            ci_high: mean_of(|e| e.ci_high),
        });
    }
    let above = curve.iter().position(|c| c.cost > rate)?;
    let (a, b) = (&curve[above - 1], &curve[above]);
    let t = (rate.log10() - a.cost.log10()) / (b.cost.log10() - a.cost.log10());
    let between = |f: fn(&Estimate) -> Option<f64>| Some(f(&a.gain)? * (1.0 - t) + f(&b.gain)? * t);
    Some(Estimate {
        n: a.gain.n.min(b.gain.n),
        mean: between(|e| e.mean),
        ci_low: between(|e| e.ci_low),
        ci_high: between(|e| e.ci_high),
    })
}

/// The most rates the equal-cost table shows, and the fewest it seeks.
const RATES: (usize, usize) = (6, 4);

/// Mantissas of log-spaced rates in tenths, coarsest first: decades, then
/// 1-3, 1-2-5, 1-2-3-5, 1-1.5-2-3-5-7, 1 to 9, and 1.0 to 9.9 by tenths in
/// each decade.
const LADDERS: [&[u32]; 7] = [
    &[10],
    &[10, 30],
    &[10, 20, 50],
    &[10, 20, 30, 50],
    &[10, 15, 20, 30, 50, 70],
    &[10, 20, 30, 40, 50, 60, 70, 80, 90],
    &TENTHS,
];

/// 1.0 to 9.9 in tenths.
const TENTHS: [u32; 90] = {
    let mut tenths = [0; 90];
    let mut i = 0;
    while i < 90 {
        tenths[i] = 10 + i as u32;
        i += 1;
    }
    tenths
};

/// Log-spaced message rates over `ranges` (each a curve's costs), each
/// inside two of them (the one, if there is one), so that every rate
/// compares groups: the coarsest ladder that gives [`RATES`]`.1` or more
/// of them, thinned evenly to [`RATES`]`.0`; with none that does, the
/// (coarsest) ladder that gives the most.
fn rates(ranges: &[(f64, f64)]) -> Vec<f64> {
    let (Some(lo), Some(hi)) = (
        ranges.iter().map(|r| r.0).min_by(f64::total_cmp),
        ranges.iter().map(|r| r.1).max_by(f64::total_cmp),
    ) else {
        return Vec::new();
    };
    let needed = ranges.len().min(2);
    let inside = |x: f64| ranges.iter().filter(|&&(a, b)| a <= x && x <= b).count() >= needed;
    let ladder = |tenths: &[u32]| -> Vec<f64> {
        let decades = lo.log10().floor() as i32..=hi.log10().floor() as i32;
        decades
            .flat_map(|k| tenths.iter().map(move |&m| nice(m, k - 1)))
            .filter(|&x| inside(x))
            .collect()
    };
    let all: Vec<Vec<f64>> = LADDERS.iter().map(|m| ladder(m)).collect();
    let chosen = (all.iter())
        .find(|r| r.len() >= RATES.1)
        .or_else(|| all.iter().rev().max_by_key(|r| r.len()))
        .cloned()
        .unwrap_or_default();
    thin(chosen, RATES.0)
}

/// `m` × 10^`k`, as near as a float gets (0.3, not 0.30000000000000004).
fn nice(m: u32, k: i32) -> f64 {
    if k >= 0 {
        f64::from(m) * 10f64.powi(k)
    } else {
        f64::from(m) / 10f64.powi(-k)
    }
}

/// At most `most` of `values`, evenly spread, first and last kept.
fn thin(values: Vec<f64>, most: usize) -> Vec<f64> {
    let n = values.len();
    if n <= most || most < 2 {
        return values;
    }
    (0..most)
        .map(|i| values[(i * (n - 1) + (most - 1) / 2) / (most - 1)])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{against, entry_results, run_with_goals};

    /// Run `run` with goals `goals` every 100 episodes, its 3 agents having
    /// sent `messages` advising messages (and 40 bytes each) by the end.
    fn run(run: u64, goals: &[f64], messages: u64) -> RunResult {
        let mut r = run_with_goals(run, 100, goals);
        let agents = [0, 1, 2].map(|i| AgentStats {
            advising_messages: messages / 3 + u64::from(i < messages % 3),
            advising_bytes: 40 * (messages / 3 + u64::from(i < messages % 3)),
            ..AgentStats::default()
        });
        for p in &mut r.points {
            p.agents = agents.to_vec();
        }
        r
    }

    /// An entry named `name` of group `group` whose runs gain `gains` over
    /// a baseline at 10 % and sent `messages` each.
    fn entry(name: &str, group: Option<&str>, gains: [f64; 3], messages: [u64; 3]) -> EntryResults {
        let runs = (0..3)
            .map(|k| run(k, &[10.0 + gains[k as usize]; 3], messages[k as usize]))
            .collect();
        entry_results(name, group, runs)
    }

    fn baseline() -> EntryResults {
        entry("base", None, [0.0; 3], [0; 3])
    }

    #[test]
    fn the_cost_is_per_agent_per_training_episode_over_runs() {
        // 3 agents, 200 training episodes: 600, 1200 and 1800 messages are
        // 1, 2 and 3 a agent a episode.
        let e = entry("a", None, [0.0; 3], [600, 1200, 1800]);
        let messages = cost(&e, CostUnit::Messages, 0.95);
        assert_eq!(messages, estimate(&[1.0, 2.0, 3.0], 0.95));
        assert_eq!(cost(&e, CostUnit::Bytes, 0.95).mean, Some(80.0));
        // Before any training, no cost is known.
        let untrained = entry_results("u", None, vec![run(0, &[5.0], 30)]);
        assert_eq!(cost(&untrained, CostUnit::Messages, 0.95).n, 0);
    }

    #[test]
    fn the_front_holds_what_nothing_beats_at_its_cost() {
        let entries = [
            baseline(),
            // Cheap and good: on the front.
            entry("a-1", Some("a"), [4.0, 5.0, 6.0], [600; 3]),
            // Dearer and better: on the front.
            entry("a-2", Some("a"), [7.0, 8.0, 9.0], [1800; 3]),
            // Dearer than a-1 and no better: off.
            entry("b", None, [4.0, 5.0, 6.0], [1200; 3]),
            // Free but worse than the baseline, which is free too: off.
            entry("c", None, [-2.0, -1.0, 0.0], [0; 3]),
        ];
        let f = frontier(&against(&entries, "base"), 0.95).unwrap();
        let on: Vec<(&str, bool)> = (f.points.iter())
            .map(|p| (p.entry.as_str(), p.front_messages))
            .collect();
        assert_eq!(
            on,
            [("a-1", true), ("a-2", true), ("b", false), ("c", false)]
        );
        // The groups, and a's gain per message where its gain is clear of 0.
        let groups: Vec<(&str, usize)> = (f.groups().into_iter())
            .map(|(g, p)| (g, p.len()))
            .collect();
        assert_eq!(groups, [("a", 2), ("b", 1), ("c", 1)]);
        assert_eq!(f.points[0].messages_per_point, Some(1.0 / 5.0));
        assert_eq!(f.points[3].messages_per_point, None);
        // Equal costs and gains: neither dominates the other.
        assert!(!dominates((1.0, 2.0), (1.0, 2.0)));
        assert!(dominates((1.0, 2.0), (1.0, 1.0)) && dominates((0.5, 2.0), (1.0, 2.0)));
    }

    #[test]
    fn no_frontier_without_a_baseline_or_two_entries() {
        let single = [baseline(), entry("a", None, [1.0; 3], [600; 3])];
        assert_eq!(frontier(&against(&single, "base"), 0.95), None);
        // Two methods at one budget each: points, no curve.
        let two = [
            baseline(),
            entry("a", None, [1.0; 3], [600; 3]),
            entry("b", None, [2.0; 3], [900; 3]),
        ];
        let f = frontier(&against(&two, "base"), 0.95).unwrap();
        assert_eq!(
            (f.points.len(), f.rates.len(), f.equal_cost.len()),
            (2, 0, 0)
        );
        let swept = [
            entry("a-1", Some("a"), [1.0; 3], [600; 3]),
            entry("a-2", Some("a"), [2.0; 3], [900; 3]),
        ];
        assert_eq!(frontier(&against(&swept, "base"), 0.95), None);
    }

    #[test]
    fn the_gain_at_equal_cost_is_interpolated_in_log_cost() {
        let point = |cost: f64, mean: f64| Curve {
            cost,
            gain: Estimate {
                n: 3,
                mean: Some(mean),
                ci_low: Some(mean - 2.0),
                ci_high: Some(mean + 2.0),
            },
        };
        let curve = [point(0.1, 2.0), point(10.0, 6.0), point(100.0, 0.0)];
        // 1 is halfway from 0.1 to 10 in log10: 4 [2, 6].
        let at_1 = at_cost(&curve, 1.0).unwrap();
        assert!((at_1.mean.unwrap() - 4.0).abs() < 1e-12, "{at_1:?}");
        assert!((at_1.ci_low.unwrap() - 2.0).abs() < 1e-12, "{at_1:?}");
        assert!((at_1.ci_high.unwrap() - 6.0).abs() < 1e-12, "{at_1:?}");
        // 30 is log10(3) of the way from 10 to 100.
        let at_30 = at_cost(&curve, 30.0).unwrap().mean.unwrap();
        assert!((at_30 - 6.0 * (1.0 - 3f64.log10())).abs() < 1e-12);
        assert_eq!(at_cost(&curve, 10.0).unwrap().mean, Some(6.0));
        assert_eq!(at_cost(&curve, 0.05), None);
        assert_eq!(at_cost(&curve, 200.0), None);
        assert_eq!(at_cost(&curve[..1], 0.1), None);
    }

    #[test]
    fn the_rates_are_log_spaced_inside_two_curves() {
        // Where two curves overlap, two decades and a half: 1-2-5 steps.
        assert_eq!(
            rates(&[(0.08, 12.0), (0.5, 40.0)]),
            [0.5, 1.0, 2.0, 5.0, 10.0]
        );
        // One curve of seven decades: decades, thinned to six.
        assert_eq!(rates(&[(0.001, 20000.0)]).len(), 6);
        // A decade: 1-2-3-5, or finer; within one: 1 to 9.
        assert_eq!(rates(&[(1.2, 16.0), (2.0, 17.0)]), [2.0, 3.0, 5.0, 10.0]);
        assert_eq!(rates(&[(2.57, 16.4)]), [3.0, 5.0, 7.0, 10.0, 15.0]);
        assert_eq!(rates(&[(2.5, 6.5)]), [3.0, 4.0, 5.0, 6.0]);
        // Within a factor of two: tenths.
        assert_eq!(
            rates(&[(1.28, 1.84), (1.11, 1.81)]),
            [1.3, 1.4, 1.5, 1.6, 1.7, 1.8]
        );
        assert_eq!(rates(&[(0.111, 0.13)]), [0.12, 0.13]);
        // Narrower than a tenth, or curves apart: none.
        assert!(rates(&[(1.75, 1.77)]).is_empty());
        assert!(rates(&[(0.1, 0.35), (20.0, 35.0)]).is_empty());
        // Rates where only one of three curves lies are left out.
        assert_eq!(
            rates(&[(1.1, 1.8), (1.2, 3.9), (3.0, 3.8)]),
            [1.2, 1.5, 1.8, 3.2, 3.5, 3.8]
        );
        assert!(rates(&[]).is_empty());
    }

    #[test]
    fn every_group_of_two_is_in_the_equal_cost_table() {
        let entries = [
            baseline(),
            entry("a-1", Some("a"), [1.0, 2.0, 3.0], [600; 3]),
            entry("a-2", Some("a"), [3.0, 4.0, 5.0], [60000; 3]),
            entry("b", None, [1.0; 3], [600; 3]),
            // Two entries, but only one on the curve: it sent messages.
            entry("c-0", Some("c"), [1.0; 3], [0; 3]),
            entry("c-1", Some("c"), [1.0; 3], [600; 3]),
        ];
        let f = frontier(&against(&entries, "base"), 0.95).unwrap();
        // From 1 to 100 messages a agent a episode.
        assert_eq!(f.rates, [1.0, 3.0, 10.0, 30.0, 100.0]);
        assert_eq!(f.equal_cost.len(), 1);
        let a = &f.equal_cost[0];
        assert_eq!(a.group, "a");
        // At 10, halfway in log10 from 1 to 100: gain 3.
        let at_10 = a.gains[2].unwrap();
        assert!((at_10.mean.unwrap() - 3.0).abs() < 1e-12, "{at_10:?}");
        assert_eq!(a.gains[0], Some(f.points[0].last_ten_gain));
    }
}
