//! The study's `REPORT.md`, `significance.json` and figures.

use std::path::{Path, PathBuf};

use agent::Algorithm;
use proto::Simulator;

use serde::Serialize;

use super::config::{StudyConfig, StudyEntry};
use super::difference::difference_sets;
use super::newcomers::catch_ups;
use super::sweep::{EPISODES, advised, conditions, goal_at, sweep_figures};
use crate::backend::AgentStats;
use crate::error::Error;
use crate::figures::{
    DIFFERENCE, Figure, Point, SeriesSet, TradeoffPoint, draw_difference, draw_figures,
    draw_tradeoff,
};
use crate::schedule::{EvalPoint, RunResult};
use crate::stats::Estimate;
use crate::stats::aggregates::{Aggregates, Scores, aggregates};
use crate::stats::analysis::{Comparison, EntryResults};
use crate::stats::gains::{Gain, LAST_POINTS, gains};
use crate::stats::holm::{HolmComparison, holm_against};
use crate::store;
use crate::transport::Transport;

/// What `significance.json` holds.
#[derive(Serialize)]
struct Significance<'a> {
    /// Every pair of entries, point by point.
    comparisons: &'a [Comparison],
    /// Every entry's gain over the baseline (none without one).
    gains: &'a [Gain],
    /// Every entry's mean, IQM and probability of improvement over the
    /// baseline, with bootstrap intervals.
    aggregate: &'a Aggregates,
    /// Every entry's tests against the baseline, Holm-corrected across
    /// entries (none without a baseline).
    holm: &'a [HolmComparison],
}

/// Writes `significance.json`, the figures and `REPORT.md` into `out`.
pub fn write_report(
    out: &Path,
    study: &StudyConfig,
    entries: &[EntryResults],
    comparisons: &[Comparison],
) -> Result<PathBuf, Error> {
    let level = study.ci_level();
    let gains = (study.baseline.as_deref()).map_or_else(Vec::new, |b| gains(entries, b, level));
    let aggregate = aggregates(entries, study.baseline.as_deref(), level);
    let holm = (study.baseline.as_deref())
        .map_or_else(Vec::new, |b| holm_against(entries, b, 1.0 - level));
    let significance = Significance {
        comparisons,
        gains: &gains,
        aggregate: &aggregate,
        holm: &holm,
    };
    store::write_json(&out.join("significance.json"), &significance)?;
    let figures = write_figures(out, study, entries, &gains)?;
    let mut md = Markdown::default();
    introduction(&mut md, study, entries);
    if let Some(baseline) = &study.baseline {
        at_a_glance(&mut md, baseline, entries, &gains, &aggregate);
    }
    final_performance(&mut md, study, entries);
    if let Some(baseline) = &study.baseline {
        gains_over(&mut md, baseline, &gains);
        aggregate_table(&mut md, baseline, &aggregate);
        significance_against(&mut md, baseline, comparisons);
        holm_table(&mut md, baseline, &holm);
    }
    newcomers(&mut md, entries);
    who_advised_whom(&mut md, entries);
    significance_between_advising(&mut md, study, entries, comparisons);
    network_conditions(&mut md, study, entries);
    md.paragraph("Every pair, with the same intervals: `significance.json`.");
    figure_links(&mut md, study, &figures);
    if study.transport.communicates() {
        communication(&mut md, entries);
    }
    cost(&mut md, entries);
    restarts(&mut md, entries);
    md.paragraph(
        "Data: `<algorithm>/summary.json` (every point, mean and interval), `<algorithm>/run-<k>.csv` (every run).",
    );
    let path = out.join("REPORT.md");
    store::write_atomically(&path, md.finish().as_bytes())?;
    Ok(path)
}

/// Draws the figures of every entry into `out/figures`, with a baseline
/// the difference from it after the goal percentage and, last, each
/// method's `gains` against the messages it sent.
fn write_figures(
    out: &Path,
    study: &StudyConfig,
    entries: &[EntryResults],
    gains: &[Gain],
) -> Result<Vec<Figure>, Error> {
    let sets: Vec<SeriesSet> = entries
        .iter()
        .map(|e| series_set(e, study.ci_level()))
        .collect();
    let mut figures = draw_figures(&sets)?;
    let runs: Vec<_> = (entries.iter())
        .map(|e| (e.entry.name.as_str(), &e.results[..]))
        .collect();
    let differences = difference_sets(&runs, study.baseline.as_deref(), study.ci_level());
    if let (Some(baseline), false) = (&study.baseline, differences.is_empty()) {
        figures.insert(1, draw_difference(baseline, &differences)?);
    }
    let baseline = study.baseline.as_deref();
    figures.extend(sweep_figures(entries, baseline, study.ci_level())?);
    if let (Some(baseline), false) = (baseline, gains.is_empty()) {
        let runs = entries
            .iter()
            .map(|e| e.results.len() as u64)
            .max()
            .unwrap_or(0);
        let points = tradeoff_points(entries, gains);
        let level = (runs, study.ci_level());
        figures.push(draw_tradeoff(baseline, LAST_POINTS, level, &points)?);
    }
    let dir = out.join("figures");
    store::create_dir(&dir)?;
    for figure in &figures {
        for (file, bytes) in figure.files() {
            store::write_atomically(&dir.join(file), bytes)?;
        }
    }
    Ok(figures)
}

/// Markdown written block by block (headings, paragraphs, tables), each
/// followed by a blank line.
#[derive(Default)]
struct Markdown(String);

impl Markdown {
    /// A heading of `level` (1 for `#`).
    fn heading(&mut self, level: usize, text: &str) {
        self.paragraph(&format!("{} {text}", "#".repeat(level)));
    }

    /// A paragraph, or any block of lines.
    fn paragraph(&mut self, text: &str) {
        self.0.push_str(text);
        self.0.push_str("\n\n");
    }

    /// A table: its header, then one line per row (as many cells).
    fn table<H: AsRef<str>, R: AsRef<[String]>>(
        &mut self,
        header: impl AsRef<[H]>,
        rows: impl IntoIterator<Item = R>,
    ) {
        let header: Vec<&str> = header.as_ref().iter().map(AsRef::as_ref).collect();
        let line = |cells: &[&str]| format!("| {} |\n", cells.join(" | "));
        self.0.push_str(&line(&header));
        self.0
            .push_str(&format!("|{}\n", "---|".repeat(header.len())));
        for row in rows {
            let cells: Vec<&str> = row.as_ref().iter().map(String::as_str).collect();
            self.0.push_str(&line(&cells));
        }
        self.0.push('\n');
    }

    /// The document, ending with one newline.
    fn finish(mut self) -> String {
        if self.0.ends_with("\n\n") {
            self.0.pop();
        }
        self.0
    }
}

/// The simulator the study was played on, when not ours.
fn simulator(transport: &Transport) -> &'static str {
    match transport.zenoh().map(|z| z.simulator) {
        Some(Simulator::RealHfo) => {
            " on the real HFO (not deterministic: docs/protocol.md, \"The real HFO\")"
        }
        _ => "",
    }
}

/// The title, the study's description, its protocol and its pretraining.
fn introduction(md: &mut Markdown, study: &StudyConfig, entries: &[EntryResults]) {
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
        study.transport.name(),
        simulator(&study.transport),
        study.profile,
    ));
    if let Some(p) = &study.pretrain {
        md.paragraph(&format!(
            "Pretraining: a {} team trained for {} episodes; agent {} was saved as the expert that \
             starts every run of the entries marked *expert* (it keeps learning and never asks).",
            p.algorithm.name(),
            p.episodes,
            p.expert + 1
        ));
    }
}

/// Goal percentage, time to goal and spent budget at the last point.
fn final_performance(md: &mut Markdown, study: &StudyConfig, entries: &[EntryResults]) {
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

/// Every algorithm's gain over `baseline` on the last ten evaluations and
/// on the area under the curve, paired by run.
fn gains_over(md: &mut Markdown, baseline: &str, gains: &[Gain]) {
    md.heading(2, &format!("Gains over `{baseline}`"));
    md.paragraph(&format!(
        "Goal percentage averaged over the last {LAST_POINTS} evaluations, and over the whole \
         curve (its area divided by the episodes it spans), each with the algorithm's gain over \
         `{baseline}`: the mean over runs of the per-run difference, with its interval."
    ));
    md.0.push_str(&gains_table(gains));
}

/// The table a report leads with: each method's gain over the baseline and
/// what it cost, side by side.
fn at_a_glance(
    md: &mut Markdown,
    baseline: &str,
    entries: &[EntryResults],
    gains: &[Gain],
    aggregate: &Aggregates,
) {
    md.heading(2, "At a glance");
    md.paragraph(&format!(
        "Each method against `{baseline}`: its gain in goal % over the last {LAST_POINTS} \
         evaluations and over the whole curve (the area under it, divided by the episodes it \
         spans), paired by run; P(> `{baseline}`) on the last {LAST_POINTS}; the budget spent \
         and the steps acted on advice per agent at the end; and the advising messages and \
         bytes each agent sent per training episode. Means over runs."
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
        [
            label(&e.entry),
            show(gain.map(|g| &g.last_ten_gain)),
            show(gain.map(|g| &g.area_gain)),
            improvement,
            at_end(&|p: &EvalPoint| p.spent_budget, 0),
            per_agent(|a| a.ask_spent, false),
            per_agent(|a| a.advising_messages, true),
            per_agent(|a| a.advising_bytes, true),
        ]
    });
    md.table(
        [
            "algorithm",
            "gain: last ten",
            "gain: whole curve",
            "P(> baseline)",
            "budget spent",
            "advice acted on",
            "messages / agent / episode",
            "bytes / agent / episode",
        ],
        rows,
    );
}

/// Each entry's advice acted on, by advisee and advisor (means over runs).
fn who_advised_whom(md: &mut Markdown, entries: &[EntryResults]) {
    let advising: Vec<&EntryResults> = (entries.iter())
        .filter(|e| !e.summary.advice_matrix.is_empty())
        .collect();
    let Some(n) = advising.iter().map(|e| e.summary.config.team.len()).max() else {
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
    let rows = advising.iter().map(|e| {
        let runs = e.summary.advice_matrix.len().max(1) as f64;
        let mean = |i: usize, j: usize| {
            let total: u64 = (e.summary.advice_matrix.iter())
                .filter_map(|m| m.get(i)?.get(j))
                .sum();
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
fn newcomers(md: &mut Markdown, entries: &[EntryResults]) {
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

/// The mean over runs of `f` of each run's last point; `None` without runs.
fn mean_at_end(e: &EntryResults, f: &dyn Fn(&EvalPoint) -> f64) -> Option<f64> {
    let ends: Vec<f64> = (e.results.iter())
        .filter_map(|r| r.points.last())
        .map(f)
        .collect();
    (!ends.is_empty()).then(|| ends.iter().sum::<f64>() / ends.len() as f64)
}

/// A counter at `p` summed over the agents, per agent, and per training
/// episode when `per_episode`.
fn per_agent(p: &EvalPoint, f: fn(&AgentStats) -> u64, per_episode: bool) -> f64 {
    let total = p.agents.iter().map(f).sum::<u64>() as f64;
    let episodes = if per_episode {
        p.episode.max(1) as f64
    } else {
        1.0
    };
    total / p.agents.len().max(1) as f64 / episodes
}

/// Each method's dot of the gain-against-messages figure.
fn tradeoff_points(entries: &[EntryResults], gains: &[Gain]) -> Vec<TradeoffPoint> {
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

/// A Markdown table of `gains`: each algorithm's goal % on the last ten
/// evaluations and on the whole curve, with its gain over the baseline.
pub fn gains_table(gains: &[Gain]) -> String {
    let mut md = Markdown::default();
    md.table(
        [
            "algorithm",
            "last ten: goal %",
            "gain",
            "whole curve: goal %",
            "gain",
        ],
        gains.iter().map(|g| {
            [
                g.entry.clone(),
                format!("{:.1}", g.last_ten),
                format!("{:.1}", g.last_ten_gain),
                format!("{:.1}", g.area),
                format!("{:.1}", g.area_gain),
            ]
        }),
    );
    md.0
}

/// Where every algorithm is significantly better or worse than `baseline`.
fn significance_against(md: &mut Markdown, baseline: &str, comparisons: &[Comparison]) {
    md.heading(2, &format!("Significance against `{baseline}`"));
    md.paragraph(&format!(
        "Episodes where the algorithm's goal percentage is significantly higher or lower than `{baseline}`'s."
    ));
    let rows = comparisons
        .iter()
        .filter(|c| c.a == baseline || c.b == baseline)
        .map(|c| {
            let (other, better, worse) = if c.a == baseline {
                (&c.b, &c.b_better, &c.a_better)
            } else {
                (&c.a, &c.a_better, &c.b_better)
            };
            [
                other.clone(),
                intervals(better),
                intervals(worse),
                p_value(c.final_p),
            ]
        });
    md.table(
        [
            "algorithm",
            "better (episodes)",
            "worse (episodes)",
            "p at the end",
        ],
        rows,
    );
}

/// The tests against `baseline` with Holm's correction across algorithms.
fn holm_table(md: &mut Markdown, baseline: &str, holm: &[HolmComparison]) {
    md.paragraph(&format!(
        "The same with Holm's correction: at every evaluation point, the p-values of every \
         algorithm against `{baseline}` adjusted together."
    ));
    md.table(
        [
            "algorithm",
            "better (episodes, Holm)",
            "worse (episodes, Holm)",
            "p at the end (Holm)",
        ],
        holm.iter().map(|h| {
            [
                h.entry.clone(),
                intervals(&h.better),
                intervals(&h.worse),
                p_value(h.final_p),
            ]
        }),
    );
}

/// Every algorithm's mean, IQM and probability of improvement over
/// `baseline`, on the last ten evaluations and on the whole curve.
fn aggregate_table(md: &mut Markdown, baseline: &str, a: &Aggregates) {
    md.heading(2, "Aggregate statistics (Agarwal et al. 2021)");
    md.paragraph(&format!(
        "The same per-run scores (last {LAST_POINTS} evaluations; whole curve): their mean, their \
         interquartile mean (IQM), and P(> `{baseline}`), the probability that a run of the \
         algorithm scores more than a run of `{baseline}` (ties count half). Intervals: {}% \
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
        [
            "algorithm",
            "last ten: mean",
            "IQM",
            "P(> baseline)",
            "whole curve: mean",
            "IQM",
            "P(> baseline)",
        ],
        a.entries.iter().map(|e| {
            let [m, i, p] = cells(&e.last_ten);
            let [am, ai, ap] = cells(&e.area);
            [e.entry.clone(), m, i, p, am, ai, ap]
        }),
    );
}

/// `value [low, high]` with `digits` decimals.
fn interval(value: f64, [low, high]: [f64; 2], digits: usize) -> String {
    format!("{value:.digits$} [{low:.digits$}, {high:.digits$}]")
}

/// Pairs of advising methods (the baseline aside) with at least one ad hoc
/// method among them; nothing without such a pair.
fn significance_between_advising(
    md: &mut Markdown,
    study: &StudyConfig,
    entries: &[EntryResults],
    comparisons: &[Comparison],
) {
    let kind = |name: &str| {
        entries
            .iter()
            .find(|e| e.entry.name == name)
            .map(|e| e.entry.algorithm)
    };
    let advising = |name: &str| {
        Some(name) != study.baseline.as_deref() && kind(name).is_some_and(Algorithm::communicates)
    };
    // The paper's methods, `adhoc-visit` and `adhoc-td`.
    let ad_hoc = |name: &str| kind(name).is_some_and(|a| a.name().starts_with("adhoc-"));
    let between: Vec<&Comparison> = comparisons
        .iter()
        .filter(|c| advising(&c.a) && advising(&c.b) && (ad_hoc(&c.a) || ad_hoc(&c.b)))
        .collect();
    if between.is_empty() {
        return;
    }
    md.heading(
        2,
        "Significance between the ad hoc methods and the other advising methods",
    );
    md.table(
        [
            "A",
            "B",
            "A better (episodes)",
            "B better (episodes)",
            "p at the end",
        ],
        between.iter().map(|c| {
            [
                c.a.clone(),
                c.b.clone(),
                intervals(&c.a_better),
                intervals(&c.b_better),
                p_value(c.final_p),
            ]
        }),
    );
}

/// The entries under network conditions: their conditions, goal
/// percentage at [`EPISODES`], the advice acted on and the messages sent.
fn network_conditions(md: &mut Markdown, study: &StudyConfig, entries: &[EntryResults]) {
    if entries.iter().all(|e| conditions(e).is_none()) {
        return;
    }
    let level = study.ci_level();
    md.heading(2, "Network conditions of advice messages");
    md.paragraph(
        "Each advice request and reply is lost with the given probability or delayed by a latency \
         drawn from its distribution; a reply whose round trip exceeds the timeout is lost to the \
         asker (docs/algorithms.md section 6). Acted on: steps taken on advice per agent by the \
         end; messages: advising messages the team sent per training episode, over the last \
         evaluation interval.",
    );
    let goal_heads: Vec<String> = EPISODES
        .iter()
        .map(|ep| format!("goal % at {ep}"))
        .collect();
    md.table(
        [
            "entry",
            "latency (ms)",
            "loss",
            "timeout (ms)",
            &goal_heads[0],
            &goal_heads[1],
            &goal_heads[2],
            "acted on advice",
            "messages / episode",
        ],
        entries.iter().map(|e| {
            let (latency, loss, timeout) =
                conditions(e).map_or(("none".to_owned(), "0".to_owned(), "-".to_owned()), |n| {
                    (
                        n.latency.to_string(),
                        n.loss.to_string(),
                        n.timeout_ms.to_string(),
                    )
                });
            let messages = e.summary.eval_points.last().map(|p| p.advising_messages);
            [
                label(&e.entry),
                latency,
                loss,
                timeout,
                format!("{:.1}", goal_at(e, EPISODES[0])),
                format!("{:.1}", goal_at(e, EPISODES[1])),
                format!("{:.1}", goal_at(e, EPISODES[2])),
                format!("{:.1}", advised(e, level)),
                messages
                    .as_ref()
                    .map_or("-".to_owned(), |m| format!("{m:.1}")),
            ]
        }),
    );
}

/// Every figure, as an image; the difference from the baseline with what
/// it shows.
fn figure_links(md: &mut Markdown, study: &StudyConfig, figures: &[Figure]) {
    md.heading(2, "Figures");
    for f in figures {
        if let (DIFFERENCE, Some(baseline)) = (f.name, &study.baseline) {
            md.paragraph(&format!(
                "Each method's goal percentage minus `{baseline}`'s, paired by run (mean and interval over runs); \
                 triangles mark where the signed-rank test against `{baseline}` above finds it better (up) or worse (down)."
            ));
        }
        md.paragraph(&format!("![{name}.svg](figures/{name}.svg)", name = f.name));
    }
}

/// Messages and advice of the entries that communicate.
fn communication(md: &mut Markdown, entries: &[EntryResults]) {
    md.heading(2, "Communication (per run, team totals, means over runs)");
    let ms = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.3}"));
    let rows = entries.iter().filter_map(|e| {
        let c = &e.summary.comm.as_ref()?.team;
        Some([
            label(&e.entry),
            format!("{:.0}", c.advice_requests),
            format!("{:.0}", c.advice_replies_received),
            format!("{:.0}", c.advice_given),
            format!("{:.0}", c.messages_sent),
            format!("{:.0}", c.bytes_sent),
            format!(
                "{} / {}",
                ms(c.advice_rtt_ms.median),
                ms(c.advice_rtt_ms.p99)
            ),
        ])
    });
    md.table(
        [
            "algorithm",
            "advice requests",
            "advice replies received",
            "advice given",
            "messages sent",
            "bytes sent",
            "advice RTT median / p99 (ms)",
        ],
        rows,
    );
}

/// Frames played and the time they took.
fn cost(md: &mut Markdown, entries: &[EntryResults]) {
    md.heading(
        2,
        "Cost (all runs; wall time summed over runs, each on one thread)",
    );
    md.table(
        [
            "algorithm",
            "training frames",
            "evaluation frames",
            "wall time (s)",
            "frames per second",
        ],
        entries.iter().map(|e| {
            let c = &e.summary.cost;
            [
                label(&e.entry),
                c.training_frames.to_string(),
                c.evaluation_frames.to_string(),
                format!("{:.1}", c.wall_s),
                format!("{:.0}", c.frames_per_sec),
            ]
        }),
    );
}

/// Every agent or simulator restart of every run, when there was one.
fn restarts(md: &mut Markdown, entries: &[EntryResults]) {
    let rows: Vec<[String; 7]> = (entries.iter())
        .flat_map(|e| (e.results.iter()).flat_map(move |r| restart_rows(&label(&e.entry), r)))
        .collect();
    if rows.is_empty() {
        return;
    }
    md.heading(2, "Restarts");
    md.paragraph(
        "Processes that went down in a run and were started again: an agent (with \
         `--restart-agents`) from its latest checkpoint, losing what it learned since; the real \
         HFO afresh, playing the abandoned episode again. Each row is one restart.",
    );
    md.table(
        [
            "algorithm",
            "run",
            "process",
            "after episode",
            "training episodes lost",
            "wall time lost (s)",
            "cause",
        ],
        rows,
    );
}

/// The rows of [`restarts`] for run `r` of the entry labelled `label`.
fn restart_rows(label: &str, r: &RunResult) -> Vec<[String; 7]> {
    let row = |process: String, episode: u64, lost: String, ms: u64, cause: &str| {
        [
            label.to_owned(),
            r.run.to_string(),
            process,
            episode.to_string(),
            lost,
            format!("{:.1}", ms as f64 / 1000.0),
            cause.replace('|', "\\|").replace('\n', " "),
        ]
    };
    let agents = r.restarts.iter().map(|a| {
        let lost = a.checkpoint.map_or_else(
            || format!("{} (restarted fresh)", a.episode),
            |c| a.episode.saturating_sub(c).to_string(),
        );
        row(
            format!("agent {}", a.slot),
            a.episode,
            lost,
            a.wait_ms,
            &a.cause,
        )
    });
    let simulator = r.simulator_restarts.iter().map(|s| {
        let replayed = if s.evaluation {
            "evaluation"
        } else {
            "training"
        };
        let lost = format!("0 ({replayed} episode played again)");
        row("simulator".into(), s.episode, lost, s.lost_ms, &s.cause)
    });
    agents.chain(simulator).collect()
}

/// The figures' input: an experiment's summary, from memory.
fn series_set(e: &EntryResults, level: f64) -> SeriesSet {
    let points = e
        .summary
        .eval_points
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
    SeriesSet::new(&e.entry.name, e.summary.runs, level, points)
}

fn label(e: &StudyEntry) -> String {
    let mut s = e.name.clone();
    if e.expert {
        s.push_str(" (expert)");
    }
    s
}

fn intervals(v: &[(u64, u64)]) -> String {
    if v.is_empty() {
        return "none".into();
    }
    v.iter()
        .map(|(a, b)| {
            if a == b {
                a.to_string()
            } else {
                format!("{a}–{b}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn p_value(p: Option<f64>) -> String {
    p.map_or("-".into(), |p| {
        if p < 0.001 {
            "< 0.001".into()
        } else {
            format!("{p:.3}")
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::membership::{Restart, SimulatorRestart};
    use crate::study::fixtures::run_with_goals;

    #[test]
    fn each_restart_is_a_row_with_what_it_cost() {
        let mut run = run_with_goals(3, 100, &[10.0, 20.0]);
        assert!(restart_rows("adhoc-td", &run).is_empty());
        run.restarts = vec![
            Restart {
                slot: 2,
                episode: 250,
                checkpoint: Some(200),
                replayed: true,
                wait_ms: 1500,
                cause: "its process exited | code 9".into(),
            },
            Restart {
                slot: 0,
                episode: 40,
                checkpoint: None,
                replayed: false,
                wait_ms: 200,
                cause: "lost".into(),
            },
        ];
        run.simulator_restarts = vec![SimulatorRestart {
            episode: 700,
            evaluation: true,
            lost_ms: 12_345,
            cause: "its server went down".into(),
        }];
        let rows = restart_rows("adhoc-td", &run);
        let cells = |k: usize| rows[k].iter().map(String::as_str).collect::<Vec<_>>();
        assert_eq!(
            cells(0),
            [
                "adhoc-td",
                "3",
                "agent 2",
                "250",
                "50",
                "1.5",
                "its process exited \\| code 9"
            ]
        );
        assert_eq!(cells(1)[2..5], ["agent 0", "40", "40 (restarted fresh)"]);
        assert_eq!(
            cells(2)[2..6],
            [
                "simulator",
                "700",
                "0 (evaluation episode played again)",
                "12.3"
            ]
        );
    }
}
