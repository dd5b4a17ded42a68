//! The entries under network conditions of advice messages.

use super::markdown::{Markdown, label};
use crate::study::{EntryResults, Study};
use crate::sweep::{EPISODES, advised, conditions, goal_at};

/// The entries under network conditions: their conditions, goal
/// percentage at [`EPISODES`], the advice acted on and the messages sent.
pub(super) fn network_conditions(md: &mut Markdown, study: &Study, entries: &[EntryResults]) {
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
            let messages = e.points.last().map(|p| p.advising_messages);
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
