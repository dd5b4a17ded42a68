//! The report's opening: what the study ran, what played it, and every
//! agent's settings, so that a report can be held against its preset.

use std::collections::BTreeMap;

use serde_json::Value;

use super::markdown::{Markdown, label};
use crate::study::{EntryResults, Study};

/// The keys of an agent's table that every learner of the tiles shares.
const SHARED_KEYS: [&str; 8] = [
    "alpha",
    "gamma",
    "lambda",
    "epsilon",
    "tiles_per_feature",
    "tile_width",
    "tile_step",
    "trace_threshold",
];

/// The simulator the study was played on, when not ours.
fn simulator(study: &Study) -> &'static str {
    match study.simulator() {
        "real-hfo" => " on the real HFO (not deterministic: docs/protocol.md, \"The real HFO\")",
        _ => "",
    }
}

/// The title, the study's description, its protocol and its pretraining.
pub(super) fn introduction(md: &mut Markdown, study: &Study, entries: &[EntryResults]) {
    let pct = 100.0 * study.ci_level();
    let points = entries[0].results[0].points.len();
    md.heading(1, &format!("Study `{}`", study.name));
    if !study.description.is_empty() {
        md.paragraph(&study.description);
    }
    md.paragraph(&format!(
        "{} runs x {} training episodes per algorithm; an evaluation of {} episodes with every agent \
         frozen before training and every {} episodes ({points} points); seed {}; transport {}{}; \
         fidelity profile {} (docs/fidelity.md). Intervals: {pct}% Student's t over runs. Tests: Wilcoxon signed-rank on goal percentage, \
         paired by run, two-sided, at the {pct}% level.",
        study.runs,
        study.episodes,
        study.eval_episodes,
        study.eval_every,
        study.seed,
        study.transport_name(),
        simulator(study),
        study.profile,
    ));
    md.paragraph(&played_with(entries));
    if let Some(p) = &study.pretrain {
        md.paragraph(&format!(
            "Pretraining: a {} team trained for {} episodes; agent {} was saved as the expert that \
             starts every run of the entries marked *expert* (it keeps learning; its ask budget is 0 in every method that has one).",
            p.algorithm.name(),
            p.episodes,
            p.expert + 1
        ));
    }
}

/// What played the runs: each commit and simulator (with its fingerprint)
/// and how many runs it played.
fn played_with(entries: &[EntryResults]) -> String {
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for run in entries.iter().flat_map(|e| &e.results) {
        let what = match &run.played_with {
            Some(p) => match &p.fingerprint {
                Some(f) => format!(
                    "commit `{}`, simulator `{}` (fingerprint `{f}`)",
                    p.commit,
                    p.simulator.name()
                ),
                None => format!("commit `{}`, simulator `{}`", p.commit, p.simulator.name()),
            },
            None => "code not recorded (results format before 4)".to_owned(),
        };
        *counts.entry(what).or_default() += 1;
    }
    let parts: Vec<String> = (counts.iter())
        .map(|(what, runs)| format!("{what}: {runs} runs"))
        .collect();
    format!("Played with {}.", parts.join("; "))
}

/// Every entry's agents' settings as their `config.json` records them:
/// the learner's shared keys once when every agent has the same, then per
/// entry (and per group of agents where they differ) the learner, the
/// algorithm's keys and the fidelity rules.
pub(super) fn settings(md: &mut Markdown, entries: &[EntryResults]) {
    let team = |e: &EntryResults| -> Vec<BTreeMap<String, Value>> {
        (e.config.pointer("/config/team").and_then(Value::as_array))
            .map(|agents| {
                (agents.iter())
                    .filter_map(Value::as_object)
                    .map(|t| t.clone().into_iter().collect())
                    .collect()
            })
            .unwrap_or_default()
    };
    let shared = |agent: &BTreeMap<String, Value>| -> String {
        keys(
            agent
                .iter()
                .filter(|(k, _)| SHARED_KEYS.contains(&k.as_str())),
        )
    };
    let all: Vec<String> = entries.iter().flat_map(&team).map(|a| shared(&a)).collect();
    let common = all.first().filter(|first| all.iter().all(|s| s == *first));
    md.heading(2, "Settings");
    match common {
        Some(shared) => md.paragraph(&format!(
            "Every agent's settings, as each entry's `config.json` records them; every agent learns with {shared}."
        )),
        None => md.paragraph("Every agent's settings, as each entry's `config.json` records them."),
    }
    let rows = entries.iter().flat_map(|e| {
        let mut groups: Vec<(Vec<usize>, String)> = Vec::new();
        for (i, agent) in team(e).iter().enumerate() {
            let own = keys(
                agent
                    .iter()
                    .filter(|(k, _)| common.is_none() || !SHARED_KEYS.contains(&k.as_str())),
            );
            match groups.iter_mut().find(|(_, s)| *s == own) {
                Some((ids, _)) => ids.push(i),
                None => groups.push((vec![i], own)),
            }
        }
        let whole = groups.len() == 1;
        groups.into_iter().map(move |(ids, own)| {
            let agents = if whole {
                "all".to_owned()
            } else {
                ids.iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            [label(&e.entry), agents, own]
        })
    });
    md.table(["entry", "agents", "settings"], rows);
}

/// The keys an agent's table lists last: the profile and its rules.
const FIDELITY_KEYS: [&str; 6] = [
    "profile",
    "torrey_unknown_state",
    "torrey_intent",
    "advisor_ties",
    "vote_ties",
    "shared_bootstrap",
];

/// `key value` pairs, comma-separated, strings without their quotes: the
/// algorithm first, the fidelity rules last, the others by name.
fn keys<'a>(pairs: impl Iterator<Item = (&'a String, &'a Value)>) -> String {
    let value = |v: &Value| match v {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    let rank = |key: &str| match FIDELITY_KEYS.iter().position(|k| *k == key) {
        _ if key == "algorithm" => 0,
        Some(i) => 2 + i,
        None => 1,
    };
    let mut pairs: Vec<_> = pairs.collect();
    pairs.sort_by_key(|(k, _)| rank(k));
    (pairs.iter())
        .map(|(k, v)| format!("{k} {}", value(v)))
        .collect::<Vec<_>>()
        .join(", ")
}
