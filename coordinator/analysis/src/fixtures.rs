//! Test inputs shared by the study's and the statistics' modules.

use crate::baselines::{Pair, pairs};
use crate::results::{EvalPoint, RunResult};
use crate::study::{Entry, EntryResults};

/// Run `run` with goal percentages `goals` at episodes 0, `every`, 2 `every`, ...
pub(crate) fn run_with_goals(run: u64, every: u64, goals: &[f64]) -> RunResult {
    let points = (goals.iter().enumerate())
        .map(|(i, &goal_pct)| EvalPoint {
            episode: every * i as u64,
            episodes: 100,
            goals: goal_pct as u64,
            goal_pct,
            time_to_goal: None,
            agents: Vec::new(),
            spent_budget: 0.0,
            actions_timed_out: 0,
        })
        .collect();
    RunResult {
        run,
        points,
        timing: Default::default(),
        advice_rtt_ms: Vec::new(),
        joins: Vec::new(),
        played_with: None,
        restarts: Vec::new(),
        simulator_restarts: Vec::new(),
        advice_matrix: Vec::new(),
    }
}

/// The entry `name` of `group` (algorithm no-advice) with `runs`,
/// summarised at 95 %.
pub(crate) fn entry_results(name: &str, group: Option<&str>, runs: Vec<RunResult>) -> EntryResults {
    let entry = Entry {
        name: name.to_owned(),
        algorithm: "no-advice".parse().expect("an algorithm"),
        group: group.map(str::to_owned),
        baseline: None,
        expert: false,
        network: None,
        events: Vec::new(),
    };
    EntryResults::new(entry, serde_json::Value::Null, runs, 0.95)
}

/// Every entry of `entries` but the one named `baseline`, compared with it.
pub(crate) fn against<'a>(entries: &'a [EntryResults], baseline: &'a str) -> Vec<Pair<'a>> {
    pairs(entries, |e| (e.name != baseline).then_some(baseline))
}
