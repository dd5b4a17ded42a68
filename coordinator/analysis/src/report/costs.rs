//! What the runs cost: their messages, frames and time, and their
//! restarts.

use super::markdown::{Markdown, label};
use crate::results::RunResult;
use crate::study::EntryResults;

/// Messages and advice of the entries that communicate.
pub(super) fn communication(md: &mut Markdown, entries: &[EntryResults]) {
    md.heading(2, "Communication (per run, team totals, means over runs)");
    let ms = |v: Option<f64>| v.map_or("-".to_owned(), |v| format!("{v:.3}"));
    let rows = entries.iter().map(|e| {
        let comm = e.comm();
        let c = &comm.team;
        [
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
        ]
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
pub(super) fn cost(md: &mut Markdown, entries: &[EntryResults]) {
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
            let c = &e.cost();
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
pub(super) fn restarts(md: &mut Markdown, entries: &[EntryResults]) {
    let rows: Vec<[String; 7]> = (entries.iter())
        .flat_map(|e| (e.results.iter()).flat_map(move |r| restart_rows(&label(&e.entry), r)))
        .collect();
    if rows.is_empty() {
        return;
    }
    md.heading(2, "Restarts");
    md.paragraph(
        "Processes that went down in a run and were started again: an agent (with \
         `--restart-agents`) from its latest snapshot, losing what it learned since; the real \
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
pub(super) fn restart_rows(label: &str, r: &RunResult) -> Vec<[String; 7]> {
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
        let lost = a.snapshot.map_or_else(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::run_with_goals;
    use crate::results::{Restart, SimulatorRestart};

    #[test]
    fn each_restart_is_a_row_with_what_it_cost() {
        let mut run = run_with_goals(3, 100, &[10.0, 20.0]);
        assert!(restart_rows("adhoc-td", &run).is_empty());
        run.restarts = vec![
            Restart {
                slot: 2,
                episode: 250,
                snapshot: Some(200),
                replayed: true,
                wait_ms: 1500,
                cause: "its process exited | code 9".into(),
            },
            Restart {
                slot: 0,
                episode: 40,
                snapshot: None,
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
