//! What each method achieved: at a glance, at the first evaluation and at
//! the end, its gains and their aggregate statistics.

use super::against::{Against, baseline_cell};
use super::markdown::{Markdown, interval, label, mean_at_end, per_agent};
use crate::results::{AgentStats, EvalPoint};
use crate::stats::Estimate;
use crate::stats::aggregates::{Aggregates, Scores};
use crate::stats::gains::{Gain, LAST_POINTS, first};
use crate::study::{EntryResults, Study};

/// The table a report leads with: each method's gain over its baseline
/// and what it cost, side by side.
pub(super) fn at_a_glance(
    md: &mut Markdown,
    against: Against,
    entries: &[EntryResults],
    gains: &[Gain],
    aggregate: &Aggregates,
) {
    md.heading(2, "At a glance");
    let baseline = against.each();
    let column = match against {
        Against::One(_) => "",
        Against::Several => {
            " The column baseline names each method's; the baselines, marked *baseline*, have \
             no gain."
        }
    };
    md.paragraph(&format!(
        "Each method against {baseline}: its gain in goal % over the last {LAST_POINTS} \
         evaluations and over the whole curve (the area under it, divided by the episodes it \
         spans), paired by run; P(> {baseline}) on the last {LAST_POINTS}; the budget spent \
         and the steps acted on advice per agent at the end; and the advising messages and \
         bytes each agent sent per training episode. Means over runs.{column}"
    ));
    let rows = entries.iter().map(|e| {
        let name = &e.entry.name;
        let gain = gains.iter().find(|g| &g.entry == name);
        let show = |x: Option<&Estimate>| x.map_or("-".into(), |x| format!("{x:.1}"));
        let improvement = (aggregate.entries.iter())
            .find(|a| &a.entry == name)
            .and_then(|a| a.last_ten?.p_improvement)
            .map_or("-".into(), |p| interval(p.estimate, p.ci, 2));
        let at_end = |f: &dyn Fn(&EvalPoint) -> f64, digits: usize| {
            mean_at_end(e, f).map_or("-".into(), |mean| format!("{mean:.digits$}"))
        };
        let per_agent = |f: fn(&AgentStats) -> u64, per_episode: bool| {
            at_end(&move |p: &EvalPoint| per_agent(p, f, per_episode), 2)
        };
        let row = vec![
            label(&e.entry),
            show(gain.map(|g| &g.last_ten_gain)),
            show(gain.map(|g| &g.area_gain)),
            improvement,
            at_end(&|p: &EvalPoint| p.spent_budget, 0),
            per_agent(|a| a.ask_spent, false),
            per_agent(|a| a.advising_messages, true),
            per_agent(|a| a.advising_bytes, true),
        ];
        against.row(row, &baseline_cell(aggregate, name))
    });
    md.table(
        against.header(&[
            "algorithm",
            "gain: last ten",
            "gain: whole curve",
            "P(> baseline)",
            "budget spent",
            "advice acted on",
            "messages / agent / episode",
            "bytes / agent / episode",
        ]),
        rows,
    );
}

/// Each method's goal % at the first evaluation, with its difference
/// from its baseline's (the jumpstart); only where the entries' first
/// evaluations differ in some run, or their agents learn with different
/// learners (whose starts are then compared).
pub(super) fn first_evaluation(
    md: &mut Markdown,
    against: Option<Against>,
    entries: &[EntryResults],
    gains: &[Gain],
    aggregate: &Aggregates,
) {
    let firsts = |e: &EntryResults| -> Vec<(u64, Option<f64>)> {
        e.results.iter().map(|r| (r.run, first(r))).collect()
    };
    let same_start = entries.windows(2).all(|w| firsts(&w[0]) == firsts(&w[1]));
    let same_learners = (entries.windows(2)).all(|w| w[0].learners() == w[1].learners());
    let Some(first_point) = entries.iter().find_map(|e| e.points.first()) else {
        return;
    };
    if same_start && same_learners {
        return;
    }
    md.heading(2, "First evaluation");
    let jumpstart = against.map_or(String::new(), |a| {
        format!(
            ", and its jumpstart: that minus {}'s, paired by run",
            a.each()
        )
    });
    let same = if same_start {
        " It is the same for every entry in every run."
    } else {
        ""
    };
    md.paragraph(&format!(
        "Goal % at the first evaluation (episode {}): each method's mean over runs{jumpstart}.{same}",
        first_point.episode
    ));
    let column = |row: Vec<String>, cell: &str| match against {
        Some(a) => a.row(row, cell),
        None => row,
    };
    let mut header = vec!["algorithm".to_owned(), "goal %".to_owned()];
    if !gains.is_empty() {
        header.push("jumpstart".into());
    }
    let rows = entries.iter().map(|e| {
        let name = &e.entry.name;
        let mut row = vec![
            label(&e.entry),
            e.points
                .first()
                .map_or("-".into(), |p| format!("{:.1}", p.goal_pct)),
        ];
        if !gains.is_empty() {
            let gain = gains.iter().find(|g| &g.entry == name);
            row.push(gain.map_or("-".into(), |g| format!("{:.1}", g.first_gain)));
        }
        column(row, &baseline_cell(aggregate, name))
    });
    md.table(column(header, "baseline"), rows);
}

/// Goal percentage, time to goal and spent budget at the last point.
pub(super) fn final_performance(md: &mut Markdown, study: &Study, entries: &[EntryResults]) {
    let level = study.ci_level();
    md.heading(
        2,
        &format!("Final performance (episode {})", study.episodes),
    );
    md.table(
        [
            "algorithm",
            "goal %",
            "time to goal (frames)",
            "spent budget (advice given per agent)",
        ],
        entries.iter().map(|e| {
            [
                label(&e.entry),
                format!("{:.1}", e.last(level, |p| Some(p.goal_pct))),
                format!("{:.1}", e.last(level, |p| p.time_to_goal)),
                format!("{:.1}", e.last(level, |p| Some(p.spent_budget))),
            ]
        }),
    );
}

/// Every algorithm's gain over its baseline on the last ten evaluations
/// and on the area under the curve, paired by run.
pub(super) fn gains_over(md: &mut Markdown, against: Against, gains: &[Gain]) {
    md.heading(2, &format!("Gains over {}", against.all()));
    md.paragraph(&format!(
        "Goal percentage averaged over the last {LAST_POINTS} evaluations, and over the whole \
         curve (its area divided by the episodes it spans), each with the algorithm's gain over \
         {}: the mean over runs of the per-run difference, with its interval.",
        against.each()
    ));
    md.0.push_str(&gains_table(gains));
}

/// A Markdown table of `gains`: each algorithm's goal % on the last ten
/// evaluations and on the whole curve, with its gain over its baseline
/// (named in a column when they have several).
pub fn gains_table(gains: &[Gain]) -> String {
    let mut common = gains.first().map(|g| g.baseline.as_str());
    if gains.iter().any(|g| Some(g.baseline.as_str()) != common) {
        common = None;
    }
    let against = Against::named(common);
    let mut md = Markdown::default();
    md.table(
        against.header(&[
            "algorithm",
            "last ten: goal %",
            "gain",
            "whole curve: goal %",
            "gain",
        ]),
        gains.iter().map(|g| {
            let row = vec![
                g.entry.clone(),
                format!("{:.1}", g.last_ten),
                format!("{:.1}", g.last_ten_gain),
                format!("{:.1}", g.area),
                format!("{:.1}", g.area_gain),
            ];
            against.row(row, &g.baseline)
        }),
    );
    md.0
}

/// Every algorithm's mean, IQM and probability of improvement over its
/// baseline, on the last ten evaluations and on the whole curve.
pub(super) fn aggregate_table(md: &mut Markdown, against: Against, a: &Aggregates) {
    md.heading(2, "Aggregate statistics (Agarwal et al. 2021)");
    let baseline = against.each();
    md.paragraph(&format!(
        "The same per-run scores (last {LAST_POINTS} evaluations; whole curve): their mean, their \
         interquartile mean (IQM), and P(> {baseline}), the probability that a run of the \
         algorithm scores more than a run of {baseline} (ties count half). Intervals: {}% \
         stratified bootstrap percentile intervals over runs ({} resamples, seed {}), as rliable \
         computes them.",
        100.0 * a.level,
        a.resamples,
        a.seed,
    ));
    let cells = |s: &Option<Scores>| match s {
        Some(s) => [
            interval(s.aggregate.mean, s.aggregate.mean_ci, 1),
            interval(s.aggregate.iqm, s.aggregate.iqm_ci, 1),
            s.p_improvement
                .map_or("-".into(), |p| interval(p.estimate, p.ci, 2)),
        ],
        None => ["-".into(), "-".into(), "-".into()],
    };
    md.table(
        against.header(&[
            "algorithm",
            "last ten: mean",
            "IQM",
            "P(> baseline)",
            "whole curve: mean",
            "IQM",
            "P(> baseline)",
        ]),
        a.entries.iter().map(|e| {
            let [m, i, p] = cells(&e.last_ten);
            let [am, ai, ap] = cells(&e.area);
            let row = vec![e.entry.clone(), m, i, p, am, ai, ap];
            against.row(row, &baseline_cell(a, &e.entry))
        }),
    );
}
