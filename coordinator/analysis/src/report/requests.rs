//! What became of the advice requests: how many each agent sent, and the
//! shares answered, declined, futile and lost.

use super::markdown::{Markdown, label};
use crate::results::{AgentStats, RunResult};
use crate::stats::frontier::per_agent_episode;
use crate::study::EntryResults;

/// An entry's requests over its runs (means over runs).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Fates {
    /// Requests each agent sent per training episode.
    per_agent_episode: f64,
    /// Shares of the requests (%), over the runs that sent some: answered,
    /// declined, futile, lost.
    shares: [f64; 4],
}

/// The counters of the fates, in [`Fates::shares`]'s order.
const FATES: [fn(&AgentStats) -> u64; 4] = [
    |a| a.answered_requests,
    |a| a.declined_requests,
    |a| a.futile_requests,
    |a| a.lost_requests,
];

/// The fates of `runs`' requests at their last evaluation; none without a
/// request.
fn fates(runs: &[RunResult]) -> Option<Fates> {
    let mut rates = Vec::new();
    let mut shares = Vec::new();
    for run in runs {
        let Some(last) = run.points.last() else {
            continue;
        };
        rates.extend(per_agent_episode(run, |a| a.advice_requests));
        let total = |f: fn(&AgentStats) -> u64| last.agents.iter().map(f).sum::<u64>() as f64;
        let requests = total(|a| a.advice_requests);
        if requests > 0.0 {
            shares.push(FATES.map(|f| 100.0 * total(f) / requests));
        }
    }
    if shares.is_empty() {
        return None;
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let column = |k: usize| mean(&shares.iter().map(|s| s[k]).collect::<Vec<_>>());
    Some(Fates {
        per_agent_episode: mean(&rates),
        shares: [0, 1, 2, 3].map(column),
    })
}

/// The table "Requests" of the entries that sent requests; nothing when
/// none did.
pub(super) fn requests(md: &mut Markdown, entries: &[EntryResults]) {
    let (asked, silent): (Vec<_>, Vec<_>) = (entries.iter())
        .map(|e| (e, fates(&e.results)))
        .partition(|(_, f)| f.is_some());
    if asked.is_empty() {
        return;
    }
    md.heading(2, "Requests");
    md.paragraph(
        "What became of the advice requests, means over runs at the last evaluation: the \
         requests each agent sent per training episode, and the shares that brought advice \
         (answered), that brought a decline from an advisor who could have advised (declined), \
         that every advisor asked answered with its give budget spent (futile), and that lost \
         replies to the network or the timeout (lost).",
    );
    let rows = asked.iter().filter_map(|(e, f)| {
        let f = (*f)?;
        let [answered, declined, futile, lost] = f.shares.map(|s| format!("{s:.1}"));
        Some([
            label(&e.entry),
            format!("{:.2}", f.per_agent_episode),
            answered,
            declined,
            futile,
            lost,
        ])
    });
    md.table(
        [
            "entry",
            "requests / agent / episode",
            "answered (%)",
            "declined (%)",
            "futile (%)",
            "lost (%)",
        ],
        rows,
    );
    if !silent.is_empty() {
        let names: Vec<String> = silent.iter().map(|(e, _)| label(&e.entry)).collect();
        md.paragraph(&format!("No requests: {}.", names.join(", ")));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{entry_results, run_with_goals};

    /// A run whose two agents sent `requests` each over 100 training
    /// episodes, with `fates` of them answered, declined, futile, lost.
    fn run(k: u64, requests: u64, fates: [u64; 4]) -> RunResult {
        let mut r = run_with_goals(k, 100, &[0.0, 10.0]);
        let agent = AgentStats {
            advice_requests: requests,
            answered_requests: fates[0],
            declined_requests: fates[1],
            futile_requests: fates[2],
            lost_requests: fates[3],
            ..AgentStats::default()
        };
        r.points[1].agents = vec![agent; 2];
        r
    }

    #[test]
    fn requests_split_by_their_fate() {
        let runs = [run(0, 50, [25, 5, 20, 0]), run(1, 150, [30, 0, 90, 30])];
        let f = fates(&runs).unwrap();
        assert_eq!(f.per_agent_episode, 1.0);
        assert_eq!(f.shares, [35.0, 5.0, 50.0, 10.0]);
        assert_eq!(fates(&[run(0, 0, [0; 4])]), None);
        let entries = [
            entry_results("adhoc-td", None, runs.to_vec()),
            entry_results("no-advice", None, vec![run(0, 0, [0; 4])]),
        ];
        let mut md = Markdown::default();
        requests(&mut md, &entries);
        let text = md.finish();
        assert!(
            text.contains("| adhoc-td | 1.00 | 35.0 | 5.0 | 50.0 | 10.0 |"),
            "{text}"
        );
        assert!(text.contains("No requests: no-advice."), "{text}");
        // Without any request, no table.
        let mut md = Markdown::default();
        requests(&mut md, &entries[1..]);
        assert!(md.finish().is_empty());
    }
}
