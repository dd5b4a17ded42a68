//! The team: who advised whom, and how it fared around its newcomers.

use super::markdown::{Markdown, label};
use crate::newcomers::catch_ups;
use crate::stats::gains::LAST_POINTS;
use crate::stats::summary::advice_matrices;
use crate::study::EntryResults;

/// Each entry's advice acted on, by advisee and advisor (means over runs).
pub(super) fn who_advised_whom(md: &mut Markdown, entries: &[EntryResults]) {
    let advising: Vec<(&EntryResults, Vec<Vec<Vec<u64>>>)> = (entries.iter())
        .map(|e| (e, advice_matrices(&e.results, e.team_size())))
        .filter(|(_, matrices)| !matrices.is_empty())
        .collect();
    let Some(n) = advising.iter().map(|(e, _)| e.team_size()).max() else {
        return;
    };
    md.heading(2, "Who advised whom");
    md.paragraph(
        "The decisions each agent acted on each teammate's advice over a run, means over runs: \
         `i ← j` is agent i following agent j (with newcomers, every agent that held slot i).",
    );
    let pairs: Vec<(usize, usize)> = (0..n)
        .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
        .collect();
    let rows = advising.iter().map(|(e, matrices)| {
        let runs = matrices.len().max(1) as f64;
        let mean = |i: usize, j: usize| {
            let total: u64 = (matrices.iter()).filter_map(|m| m.get(i)?.get(j)).sum();
            format!("{:.1}", total as f64 / runs)
        };
        std::iter::once(label(&e.entry))
            .chain(pairs.iter().map(|&(i, j)| mean(i, j)))
            .collect::<Vec<String>>()
    });
    let header: Vec<String> = std::iter::once("algorithm".to_owned())
        .chain(pairs.iter().map(|(i, j)| format!("{i} ← {j}")))
        .collect();
    md.table(header, rows);
}

/// How each entry's team fared around its newcomers' joins.
pub(super) fn newcomers(md: &mut Markdown, entries: &[EntryResults]) {
    let joins = catch_ups(entries);
    if joins.is_empty() {
        return;
    }
    md.heading(2, "Newcomers");
    md.paragraph(&format!(
        "At each join the agent in the slot leaves and a newcomer takes it while the others keep \
         learning. The team's goal % (means over runs): over the last {LAST_POINTS} evaluations \
         before the join, at the first evaluation after it, at its lowest since, and the training \
         episodes until an evaluation is back at the level before the join."
    ));
    let rows = joins.iter().map(|j| {
        [
            j.entry.clone(),
            j.episode.to_string(),
            j.slot.to_string(),
            format!("{:.1}", j.before),
            format!("{:.1}", j.after),
            format!("{:.1}", j.lowest),
            j.catch_up
                .map_or("not within the run".into(), |e| e.to_string()),
        ]
    });
    md.table(
        [
            "algorithm",
            "joined after",
            "slot",
            "goal % before",
            "right after",
            "lowest since",
            "episodes to catch up",
        ],
        rows,
    );
}
