//! The study's figures, drawn and linked.

use std::path::Path;

use super::against::Against;
use super::markdown::{Markdown, mean_at_end, per_agent};
use crate::baselines::{Pair, baselines};
use crate::difference::difference_sets;
use crate::error::Error;
use crate::figures::{
    DIFFERENCE, Figure, FrontierDot, FrontierGroup, Point, SeriesSet, TradeoffPoint,
    draw_difference, draw_figures, draw_frontier, draw_tradeoff,
};
use crate::files;
use crate::results::EvalPoint;
use crate::stats::frontier::{CostUnit, Frontier};
use crate::stats::gains::{Gain, LAST_POINTS};
use crate::study::{EntryResults, Study};
use crate::sweep::sweep_figures;

/// Draws the figures of every entry into `out/figures`, with `pairs` the
/// difference from their baselines after the goal percentage, then each
/// method's `gains` against the messages it sent and, last, the `frontier`
/// against messages and bytes.
pub(super) fn write_figures(
    out: &Path,
    study: &Study,
    entries: &[EntryResults],
    pairs: &[Pair],
    gains: &[Gain],
    frontier: Option<&Frontier>,
) -> Result<Vec<Figure>, Error> {
    let sets: Vec<SeriesSet> = entries
        .iter()
        .map(|e| series_set(e, study.ci_level()))
        .collect();
    let mut figures = draw_figures(&sets)?;
    let against = Against::of(pairs);
    if let Some(against) = against {
        let differences = difference_sets(pairs, study.ci_level());
        figures.insert(1, draw_difference(against.plain(), &differences)?);
    }
    figures.extend(sweep_figures(entries, &baselines(pairs), study.ci_level())?);
    let runs = entries
        .iter()
        .map(|e| e.results.len() as u64)
        .max()
        .unwrap_or(0);
    let level = (runs, study.ci_level());
    if let (Some(against), false) = (against, gains.is_empty()) {
        let points = tradeoff_points(entries, gains);
        figures.push(draw_tradeoff(against.plain(), LAST_POINTS, level, &points)?);
    }
    if let Some(f) = frontier {
        let against = Against::named(f.baseline.as_deref());
        for unit in CostUnit::ALL {
            let groups = frontier_groups(f, unit);
            figures.push(draw_frontier(
                unit,
                against.plain(),
                LAST_POINTS,
                level,
                &groups,
            )?);
        }
    }
    let dir = out.join("figures");
    files::create_dir(&dir)?;
    for figure in &figures {
        for (file, bytes) in figure.files() {
            files::write(&dir.join(file), bytes)?;
        }
    }
    Ok(figures)
}

/// Every figure, as an image; the difference from the baselines with what
/// it shows.
pub(super) fn figure_links(md: &mut Markdown, against: Option<Against>, figures: &[Figure]) {
    md.heading(2, "Figures");
    for f in figures {
        if let (DIFFERENCE, Some(against)) = (f.name, against) {
            let baseline = against.each();
            md.paragraph(&format!(
                "Each method's goal percentage minus {baseline}'s, paired by run (mean and interval over runs); \
                 triangles mark where the signed-rank test against {baseline} above finds it better (up) or worse (down)."
            ));
        }
        md.paragraph(&format!("![{name}.svg](figures/{name}.svg)", name = f.name));
    }
}

/// Each method's dot of the gain-against-messages figure.
pub(super) fn tradeoff_points(entries: &[EntryResults], gains: &[Gain]) -> Vec<TradeoffPoint> {
    (entries.iter())
        .filter_map(|e| {
            let gain = gains.iter().find(|g| g.entry == e.entry.name)?;
            let messages = |p: &EvalPoint| per_agent(p, |a| a.advising_messages, true);
            Some(TradeoffPoint {
                label: e.entry.name.clone(),
                messages: mean_at_end(e, &messages)?,
                gain: gain.last_ten_gain,
            })
        })
        .collect()
}

/// The frontier's groups, each with its entries' cost in `unit` and gain.
fn frontier_groups(f: &Frontier, unit: CostUnit) -> Vec<FrontierGroup> {
    (f.groups().into_iter())
        .map(|(group, points)| FrontierGroup {
            label: group.to_owned(),
            dots: (points.iter())
                .map(|p| FrontierDot {
                    entry: p.entry.clone(),
                    cost: *p.cost(unit),
                    gain: p.last_ten_gain,
                    on_front: p.on_front(unit),
                })
                .collect(),
        })
        .collect()
}

/// The figures' input: an experiment's summary, from memory.
pub(super) fn series_set(e: &EntryResults, level: f64) -> SeriesSet {
    let points = e
        .points
        .iter()
        .map(|p| Point {
            episode: p.episode,
            goal_pct: p.goal_pct,
            time_to_goal: p.time_to_goal,
            spent_budget: p.spent_budget,
            advising_messages: p.advising_messages,
            advising_bytes: p.advising_bytes,
        })
        .collect();
    SeriesSet::new(&e.entry.name, e.runs(), level, points)
}
