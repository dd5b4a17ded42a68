//! What a newcomer costs a team and how fast the team recovers: for each
//! membership event of an entry, the team's goal % before the join, right
//! after it and at its lowest since, and the training episodes until the
//! team is back at its level before the join.

use crate::stats::gains::LAST_POINTS;
use crate::study::EntryResults;

/// One join, over the runs of its entry.
#[derive(Clone, Debug, PartialEq)]
pub struct CatchUp {
    /// The entry.
    pub entry: String,
    /// Training episodes before the newcomer joined.
    pub episode: u64,
    /// Its slot.
    pub slot: usize,
    /// Mean goal % of the last [`LAST_POINTS`] evaluations before the
    /// join, over runs: the team with the agent that left.
    pub before: f64,
    /// Mean goal % at the first evaluation after the join.
    pub after: f64,
    /// The lowest mean goal % of an evaluation since the join.
    pub lowest: f64,
    /// Training episodes from the join to the first evaluation whose mean
    /// goal % is back at `before`; `None` if it never is.
    pub catch_up: Option<u64>,
}

/// Every join of `entries`.
pub fn catch_ups(entries: &[EntryResults]) -> Vec<CatchUp> {
    let mut all = Vec::new();
    for e in entries.iter().filter(|e| !e.results.is_empty()) {
        // The mean goal % over runs at every evaluation point, by episode.
        let points = &e.results[0].points;
        let curve: Vec<(u64, f64)> = (0..points.len())
            .map(|k| {
                let goals: f64 = e.results.iter().map(|r| r.points[k].goal_pct).sum();
                (points[k].episode, goals / e.results.len() as f64)
            })
            .collect();
        for event in &e.entry.events {
            let k = event.episode;
            let earlier: Vec<f64> = (curve.iter().filter(|(ep, _)| *ep < k))
                .map(|&(_, g)| g)
                .collect();
            let since: Vec<(u64, f64)> = curve.iter().copied().filter(|(ep, _)| *ep >= k).collect();
            let (Some(&(_, after)), false) = (since.first(), earlier.is_empty()) else {
                continue;
            };
            let last = &earlier[earlier.len().saturating_sub(LAST_POINTS)..];
            let before = last.iter().sum::<f64>() / last.len() as f64;
            all.push(CatchUp {
                entry: e.entry.name.clone(),
                episode: k,
                slot: event.slot,
                before,
                after,
                lowest: since.iter().map(|&(_, g)| g).fold(f64::INFINITY, f64::min),
                catch_up: since
                    .iter()
                    .find(|&&(_, g)| g >= before)
                    .map(|&(ep, _)| ep - k),
            });
        }
    }
    all
}
