//! The study's `REPORT.md`, `significance.json` and figures.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use agent::StrategyName;

use super::analysis::{Comparison, EntryResults};
use super::config::{Entry, StudyConfig};
use crate::error::Error;
use crate::figures::{Point, SeriesSet, draw_figures};
use crate::stats::Estimate;
use crate::store;

/// Writes `significance.json`, the figures and `REPORT.md` into `out`.
pub fn write_report(
    out: &Path,
    study: &StudyConfig,
    entries: &[EntryResults],
    comparisons: &[Comparison],
) -> Result<PathBuf, Error> {
    store::write_json(&out.join("significance.json"), &comparisons)?;
    let sets: Vec<SeriesSet> = entries
        .iter()
        .map(|e| series_set(e, study.ci_level()))
        .collect();
    let figures = draw_figures(&sets)?;
    let figures_dir = out.join("figures");
    fs::create_dir_all(&figures_dir).map_err(|e| Error::io("create", &figures_dir, e))?;
    for figure in &figures {
        for (file, bytes) in figure.files() {
            store::write_atomically(&figures_dir.join(file), bytes)?;
        }
    }

    let level = study.ci_level();
    let pct = 100.0 * level;
    let points = entries[0].results[0].points.len();
    let mut md = String::new();
    let _ = writeln!(md, "# Study `{}`\n", study.name);
    if !study.description.is_empty() {
        let _ = writeln!(md, "{}\n", study.description);
    }
    let _ = writeln!(
        md,
        "{} runs x {} training episodes per algorithm; an evaluation of {} episodes with every agent \
         frozen before training and every {} episodes ({points} points); seed {}; transport {}; \
         fidelity profile {} (docs/fidelity.md). Intervals: {pct}% Student's t over runs. Tests: Wilcoxon signed-rank on goal percentage, \
         paired by run, two-sided, at the {pct}% level.\n",
        study.runs,
        study.episodes,
        study.eval_episodes,
        study.eval_every,
        study.seed,
        study.transport.name(),
        study.profile,
    );
    if let Some(p) = &study.pretrain {
        let _ = writeln!(
            md,
            "Pretraining: a {} team trained for {} episodes; agent {} was saved as the expert that \
             starts every run of the entries marked *expert* (it keeps learning and never asks).\n",
            p.algorithm.name(),
            p.episodes,
            p.expert + 1
        );
    }

    let _ = writeln!(md, "## Final performance (episode {})\n", study.episodes);
    let _ = writeln!(
        md,
        "| algorithm | goal % | time to goal (frames) | spent budget (advice given per agent) |"
    );
    let _ = writeln!(md, "|---|---|---|---|");
    for e in entries {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} |",
            label(&e.entry),
            show(&e.last(level, |p| Some(p.goal_pct))),
            show(&e.last(level, |p| p.time_to_goal)),
            show(&e.last(level, |p| Some(p.spent_budget))),
        );
    }

    if let Some(baseline) = &study.baseline {
        let _ = writeln!(md, "\n## Significance against `{baseline}`\n");
        let _ = writeln!(
            md,
            "Episodes where the algorithm's goal percentage is significantly higher or lower than `{baseline}`'s.\n"
        );
        let _ = writeln!(
            md,
            "| algorithm | better (episodes) | worse (episodes) | p at the end |"
        );
        let _ = writeln!(md, "|---|---|---|---|");
        for c in comparisons
            .iter()
            .filter(|c| &c.a == baseline || &c.b == baseline)
        {
            let (other, better, worse) = if &c.a == baseline {
                (&c.b, &c.b_better, &c.a_better)
            } else {
                (&c.a, &c.a_better, &c.b_better)
            };
            let _ = writeln!(
                md,
                "| {other} | {} | {} | {} |",
                intervals(better),
                intervals(worse),
                p_value(c.final_p)
            );
        }
    }

    // Pairs of advising methods with at least one ad hoc method among them.
    let kind = |name: &str| {
        entries
            .iter()
            .find(|e| e.entry.name == name)
            .map(|e| e.entry.algorithm)
    };
    let advising = |name: &str| {
        Some(name) != study.baseline.as_deref()
            && kind(name).is_some_and(StrategyName::communicates)
    };
    let ad_hoc = |name: &str| kind(name).is_some_and(StrategyName::is_ad_hoc);
    let between: Vec<&Comparison> = comparisons
        .iter()
        .filter(|c| advising(&c.a) && advising(&c.b) && (ad_hoc(&c.a) || ad_hoc(&c.b)))
        .collect();
    if !between.is_empty() {
        let _ = writeln!(
            md,
            "\n## Significance between the ad hoc methods and the other advising methods\n"
        );
        let _ = writeln!(
            md,
            "| A | B | A better (episodes) | B better (episodes) | p at the end |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|");
        for c in between {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} |",
                c.a,
                c.b,
                intervals(&c.a_better),
                intervals(&c.b_better),
                p_value(c.final_p)
            );
        }
    }
    let _ = writeln!(
        md,
        "\nEvery pair, with the same intervals: `significance.json`.\n"
    );

    let _ = writeln!(md, "## Figures\n");
    for f in &figures {
        let _ = writeln!(md, "![{name}.svg](figures/{name}.svg)\n", name = f.name);
    }

    if study.transport.communicates() {
        let _ = writeln!(
            md,
            "## Communication (per run, team totals, means over runs)\n"
        );
        let _ = writeln!(
            md,
            "| algorithm | advice requests | replies | advice given | messages sent | bytes sent | advice RTT median / p99 (ms) |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|---|---|");
        for e in entries {
            let Some(comm) = &e.summary.comm else {
                continue;
            };
            let c = &comm.team;
            let ms = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.3}"));
            let _ = writeln!(
                md,
                "| {} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {} / {} |",
                label(&e.entry),
                c.advice_requests_sent,
                c.advice_replies_received,
                c.advice_given,
                c.messages_sent,
                c.bytes_sent,
                ms(c.advice_rtt_ms.median),
                ms(c.advice_rtt_ms.p99)
            );
        }
        md.push('\n');
    }
    let _ = writeln!(
        md,
        "## Cost (all runs; wall time summed over runs, each on one thread)\n"
    );
    let _ = writeln!(
        md,
        "| algorithm | training frames | evaluation frames | wall time (s) | frames per second |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|");
    for e in entries {
        let c = &e.summary.cost;
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.1} | {:.0} |",
            label(&e.entry),
            c.training_frames,
            c.evaluation_frames,
            c.wall_s,
            c.frames_per_sec
        );
    }
    md.push('\n');
    let _ = writeln!(
        md,
        "Data: `<algorithm>/summary.json` (every point, mean and interval), `<algorithm>/run-<k>.csv` (every run)."
    );
    let path = out.join("REPORT.md");
    store::write_atomically(&path, md.as_bytes())?;
    Ok(path)
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
        })
        .collect();
    SeriesSet::new(&e.entry.name, e.summary.runs, level, points)
}

fn label(e: &Entry) -> String {
    let mut s = e.name.clone();
    if e.expert {
        s.push_str(" (expert)");
    }
    s
}

fn show(e: &Estimate) -> String {
    match (e.mean, e.ci_low, e.ci_high) {
        (Some(m), Some(lo), Some(hi)) => format!("{m:.1} [{lo:.1}, {hi:.1}]"),
        (Some(m), _, _) => format!("{m:.1}"),
        _ => "-".into(),
    }
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
