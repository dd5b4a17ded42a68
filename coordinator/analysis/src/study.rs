//! A study as its files record it: the parts of `study.json` the analysis
//! reads, and each entry's runs.

use agent::{Algorithm, NetworkConditions, Profile};
use serde::Deserialize;
use serde_json::Value;

use crate::results::{EvalPoint, RunResult};
use crate::stats::summary::{CommSummary, Cost, SummaryPoint, summary_points};
use crate::stats::{Estimate, estimate};

/// What a study ran, as `study.json` holds it (keys the analysis does not
/// read are ignored).
#[derive(Clone, Debug, Deserialize)]
pub struct Study {
    /// Short name.
    pub name: String,
    /// One line on what it reproduces.
    #[serde(default)]
    pub description: String,
    /// Runs of every entry.
    pub runs: u64,
    /// Training episodes per run.
    pub episodes: u64,
    /// An evaluation every this many training episodes.
    pub eval_every: u64,
    /// Episodes per evaluation.
    pub eval_episodes: u64,
    /// The study's seed.
    #[serde(default = "first_seed")]
    pub seed: u64,
    /// Where agents and simulator lived: `"in-process"` or `{"zenoh": {...}}`.
    pub transport: Value,
    /// The fidelity profile of every agent.
    #[serde(default)]
    pub profile: Profile,
    /// Confidence level of intervals and tests (default: the profile's).
    #[serde(default)]
    pub ci_level: Option<f64>,
    /// The entry every other is compared with, unless it names its own.
    #[serde(default)]
    pub baseline: Option<String>,
    /// A pretraining stage that produced an expert.
    #[serde(default)]
    pub pretrain: Option<Pretrain>,
    /// The entries.
    #[serde(rename = "entry")]
    pub entries: Vec<Entry>,
}

/// A study file's default seed.
fn first_seed() -> u64 {
    1
}

/// The pretraining of an expert.
#[derive(Clone, Debug, Deserialize)]
pub struct Pretrain {
    /// Its team's algorithm.
    pub algorithm: Algorithm,
    /// Its training episodes.
    pub episodes: u64,
    /// The agent saved as the expert.
    pub expert: usize,
}

/// One entry of a study, as its files record it.
#[derive(Clone, Debug, Deserialize)]
pub struct Entry {
    /// Its name: its directory and its label.
    pub name: String,
    /// Its team's algorithm.
    pub algorithm: Algorithm,
    /// The method it belongs to in the frontier: the entry it was swept
    /// from (none: its own name).
    #[serde(default)]
    pub group: Option<String>,
    /// The entry it is compared with, when not the study's baseline.
    #[serde(default)]
    pub baseline: Option<String>,
    /// Whether an expert replaces one of its agents.
    #[serde(default)]
    pub expert: bool,
    /// Network conditions of its agents' advice messages.
    #[serde(default)]
    pub network: Option<NetworkConditions>,
    /// Its newcomers: at training episode `episode` a newcomer takes slot
    /// `slot`.
    #[serde(default, rename = "event")]
    pub events: Vec<Event>,
}

/// A newcomer's arrival.
#[derive(Clone, Copy, Debug, Deserialize)]
pub struct Event {
    /// Training episodes before it joins.
    pub episode: u64,
    /// The slot it takes.
    pub slot: usize,
}

impl Study {
    /// The confidence level: as given, else the profile's.
    pub fn ci_level(&self) -> f64 {
        self.ci_level.unwrap_or(self.profile.ci_level())
    }

    /// The transport's name: `in-process` or `zenoh`.
    pub fn transport_name(&self) -> &str {
        match &self.transport {
            Value::String(name) => name,
            Value::Object(map) => map.keys().next().map_or("unknown", String::as_str),
            _ => "unknown",
        }
    }

    /// Whether its agents were processes whose messages were counted.
    pub fn communicates(&self) -> bool {
        self.transport_name() == "zenoh"
    }

    /// The simulator its runs played: `ours` or `real-hfo`.
    pub fn simulator(&self) -> &str {
        (self.transport.pointer("/zenoh/simulator/name"))
            .and_then(Value::as_str)
            .unwrap_or("ours")
    }
}

/// An entry with its runs: everything the analysis computes from.
#[derive(Clone, Debug)]
pub struct EntryResults {
    /// The entry.
    pub entry: Entry,
    /// Its `config.json` (the configuration its runs were played with).
    pub config: Value,
    /// Every run, by index.
    pub results: Vec<RunResult>,
    /// The mean and interval of each metric at every evaluation point.
    pub points: Vec<SummaryPoint>,
}

impl EntryResults {
    /// `entry`'s `results` under `config`, summarised at level `level`.
    pub fn new(entry: Entry, config: Value, mut results: Vec<RunResult>, level: f64) -> Self {
        results.sort_by_key(|r| r.run);
        let points = summary_points(&results, level);
        Self {
            entry,
            config,
            results,
            points,
        }
    }

    /// Runs summarised.
    pub fn runs(&self) -> u64 {
        self.results.len() as u64
    }

    /// Agents of its team.
    pub fn team_size(&self) -> usize {
        (self.results.iter())
            .filter_map(|r| r.points.first())
            .map(|p| p.agents.len())
            .max()
            .unwrap_or(0)
    }

    /// Each agent's learner as its `config.json` names it (null:
    /// SARSA(λ), which it does not name).
    pub fn learners(&self) -> Vec<&Value> {
        (self
            .config
            .pointer("/config/team")
            .and_then(Value::as_array))
        .map_or_else(Vec::new, |team| {
            team.iter()
                .map(|a| a.get("learner").unwrap_or(&Value::Null))
                .collect()
        })
    }

    /// Its method: the algorithm's name, with its first agent's learner's
    /// when that is not SARSA(λ) (`rcmp (dqn)`, `adhoc-td (process)` for
    /// a learner process).
    pub fn method(&self) -> String {
        let algorithm = self.entry.algorithm.name();
        match self.learners().first() {
            Some(Value::String(name)) => format!("{algorithm} ({name})"),
            Some(Value::Object(_)) => format!("{algorithm} (process)"),
            _ => algorithm.to_owned(),
        }
    }

    /// What its runs cost.
    pub fn cost(&self) -> Cost {
        Cost::of(&self.results)
    }

    /// Its communication over zenoh, where it was counted.
    pub fn comm(&self) -> CommSummary {
        CommSummary::of(&self.results, self.team_size())
    }

    /// The metric over runs at the last evaluation point.
    pub fn last(&self, level: f64, metric: fn(&EvalPoint) -> Option<f64>) -> Estimate {
        let samples: Vec<f64> = (self.results.iter())
            .filter_map(|r| r.points.last().and_then(metric))
            .collect();
        estimate(&samples, level)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_method_is_named_with_its_learner_unless_sarsa() {
        let with = |config: Value| {
            let entry = Entry {
                name: "e".into(),
                algorithm: "no-advice".parse().unwrap(),
                group: None,
                baseline: None,
                expert: false,
                network: None,
                events: Vec::new(),
            };
            EntryResults::new(entry, config, Vec::new(), 0.95).method()
        };
        let team = |learner: serde_json::Value| serde_json::json!({"config": {"team": [learner]}});
        assert_eq!(with(serde_json::Value::Null), "no-advice");
        assert_eq!(with(team(serde_json::json!({}))), "no-advice");
        let dqn = team(serde_json::json!({"learner": "dqn"}));
        assert_eq!(with(dqn), "no-advice (dqn)");
        let process = team(serde_json::json!({"learner": {"command": ["python3"]}}));
        assert_eq!(with(process), "no-advice (process)");
    }
}
