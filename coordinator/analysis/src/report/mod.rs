//! A study's `REPORT.md`, `significance.json` and figures, from its
//! entries' runs: one module per section of the report.

mod against;
mod costs;
mod figures;
mod frontier;
mod introduction;
mod markdown;
mod network;
mod performance;
mod requests;
mod significance;
mod sweeps;
mod teams;

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::Error;
use crate::files;
use crate::stats::aggregates::{Aggregates, aggregates};
use crate::stats::analysis::{Comparison, compare_all};
use crate::stats::frontier::{Frontier, frontier};
use crate::stats::gains::{Gain, gains};
use crate::stats::holm::{HolmComparison, holm_against};
use crate::stats::sweeps::{SweepTest, sweep_tests};
use crate::study::{EntryResults, Study};
use against::Against;
use costs::{communication, cost, restarts};
use figures::{figure_links, write_figures};
use frontier::frontier_section;
use introduction::{introduction, settings};
use markdown::Markdown;
use network::network_conditions;
pub use performance::gains_table;
use performance::{aggregate_table, at_a_glance, final_performance, first_evaluation, gains_over};
use requests::requests;
use significance::{holm_table, significance_against, significance_between_advising};
use sweeps::sweeps_section;
use teams::{newcomers, who_advised_whom};

/// What `significance.json` holds.
#[derive(Serialize)]
struct Significance<'a> {
    /// Every pair of entries, point by point.
    comparisons: &'a [Comparison],
    /// Every entry's gain over its baseline (none without one).
    gains: &'a [Gain],
    /// Every entry's mean, IQM and probability of improvement over its
    /// baseline, with bootstrap intervals.
    aggregate: &'a Aggregates,
    /// Every entry's tests against its baseline, Holm-corrected across
    /// the entries of each baseline.
    holm: &'a [HolmComparison],
    /// Every entry's cost and gain, the Pareto front and the gains at equal
    /// cost (absent without a baseline and a group of two entries).
    #[serde(skip_serializing_if = "Option::is_none")]
    frontier: Option<&'a Frontier>,
    /// Whether each swept group's result depends on its value (absent
    /// without a group of two entries).
    #[serde(skip_serializing_if = "<[SweepTest]>::is_empty")]
    sweeps: &'a [SweepTest],
}

/// Writes `significance.json`, the figures and `REPORT.md` into `out`.
pub fn write_report(out: &Path, study: &Study, entries: &[EntryResults]) -> Result<PathBuf, Error> {
    let comparisons = &compare_all(study, entries);
    let level = study.ci_level();
    let pairs = study.pairs(entries);
    let against = Against::of(&pairs);
    let gains = gains(&pairs, level);
    let aggregate = aggregates(entries, &pairs, level);
    let holm = holm_against(&pairs, 1.0 - level);
    let frontier = frontier(&pairs, level);
    let sweeps = sweep_tests(entries);
    let significance = Significance {
        comparisons,
        gains: &gains,
        aggregate: &aggregate,
        holm: &holm,
        frontier: frontier.as_ref(),
        sweeps: &sweeps,
    };
    files::write_json(&out.join("significance.json"), &significance)?;
    let figures = write_figures(out, study, entries, &pairs, &gains, frontier.as_ref())?;
    let mut md = Markdown::default();
    introduction(&mut md, study, entries);
    if let Some(against) = against {
        at_a_glance(&mut md, against, entries, &gains, &aggregate);
    }
    if let Some(frontier) = &frontier {
        frontier_section(&mut md, frontier);
    }
    first_evaluation(&mut md, against, entries, &gains, &aggregate);
    final_performance(&mut md, study, entries);
    if let Some(against) = against {
        gains_over(&mut md, against, &gains);
        aggregate_table(&mut md, against, &aggregate);
        significance_against(&mut md, against, &pairs, comparisons);
        holm_table(&mut md, against, &holm);
    }
    sweeps_section(&mut md, &sweeps, 1.0 - level);
    requests(&mut md, entries);
    newcomers(&mut md, entries);
    who_advised_whom(&mut md, entries);
    significance_between_advising(&mut md, study, entries, comparisons);
    network_conditions(&mut md, study, entries);
    md.paragraph("Every pair, with the same intervals: `significance.json`.");
    figure_links(&mut md, against, &figures);
    if study.communicates() {
        communication(&mut md, entries);
    }
    cost(&mut md, entries);
    restarts(&mut md, entries);
    settings(&mut md, entries);
    md.paragraph(
        "Data: `<algorithm>/summary.json` (every point, mean and interval), `<algorithm>/run-<k>.csv` (every run).",
    );
    let path = out.join("REPORT.md");
    files::write(&path, md.finish().as_bytes())?;
    Ok(path)
}
