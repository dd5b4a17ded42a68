//! The agent's control queryable: the coordinator's commands (docs/protocol.md
//! §2, §7, §8), each answered in its own task so that a report waiting for
//! an episode to end blocks nothing else.

use std::sync::Arc;
use std::time::Duration;

use proto::keys::Role;
use proto::{AgentReport, Body, Control, ControlReply, DropReason, Envelope, Header, MessageKind};
use zenoh::handlers::FifoChannelHandler;
use zenoh::query::{Query, Queryable};

use crate::context::{Exit, Node, Traffic};

/// How long Report and Snapshot wait for their episode to end
/// (less than the coordinator's 10 s, so that it gets this error).
const EPISODE_WAIT: Duration = Duration::from_secs(8);

/// A queryable whose queries are read from a channel.
pub type Queries = Queryable<FifoChannelHandler<Query>>;

/// Answers commands until the session closes.
pub async fn serve(node: Arc<Node>, queries: Queries) {
    while let Ok(query) = queries.recv_async().await {
        tokio::spawn(answer(node.clone(), query));
    }
}

/// Answers one command; undecodable ones get no answer.
async fn answer(node: Arc<Node>, query: Query) {
    let bytes = query.payload().map(|p| p.to_bytes()).unwrap_or_default();
    let Some(Envelope { header, body }) = node.decode(&bytes) else {
        return;
    };
    let Body::Control(control) = body else {
        return node.dropped(DropReason::Malformed, Some(&header));
    };
    tracing::debug!(?header, ?control, "command");
    let reset = matches!(control, Control::Reset { .. });
    let stop = control == Control::Stop;
    let reply = execute(&node, header, control).await;
    if reset && reply == ControlReply::Ok {
        // A new run counts its messages afresh, this command included.
        *node.traffic() = Traffic::default();
    }
    node.accepted(MessageKind::Control, bytes.len());
    let reply = node.encode(header, Body::ControlReply(reply));
    if let Err(e) = query
        .reply(node.keys.control(Role::Agent(node.id)), reply)
        .await
    {
        tracing::warn!(error = %e, "cannot answer a command");
    }
    // The final reply message goes out when the query is dropped.
    drop(query);
    if stop {
        node.stop(Exit::Stopped);
    }
}

/// Runs one command.
async fn execute(node: &Node, header: Header, control: Control) -> ControlReply {
    let done = |r: Result<(), String>| r.map_or_else(ControlReply::Error, |()| ControlReply::Ok);
    match control {
        Control::Reset {
            seed,
            config,
            wait_ms,
            stall_ms: _,
        } => {
            if !(1..=proto::MAX_WAIT_MS).contains(&wait_ms) {
                return ControlReply::Error(format!(
                    "the advice timeout must be 1 to {} ms, got {wait_ms}",
                    proto::MAX_WAIT_MS
                ));
            }
            let mut learner = node.learner();
            let result = learner.reset(header.run, seed, &config);
            if result.is_ok() {
                node.set_advice_timeout(Duration::from_millis(wait_ms));
            }
            node.publish_progress(&learner);
            done(result)
        }
        Control::Load { snapshot } => done(node.learner().load(&snapshot)),
        Control::Snapshot => after_episode(node, header, |n| {
            let snapshot = n.learner().agent()?.snapshot();
            snapshot.encode().map_err(|e| e.to_string())
        })
        .await
        .map_or_else(ControlReply::Error, ControlReply::Snapshot),
        Control::Report => after_episode(node, header, report)
            .await
            .map_or_else(ControlReply::Error, |r| ControlReply::Agent(Box::new(r))),
        Control::Stop => ControlReply::Ok,
        Control::PlayEpisode { .. } => {
            ControlReply::Error("an agent does not play episodes; ask env-server".to_owned())
        }
    }
}

/// Runs `f` once the terminal frame of `header.episode` of run `header.run`
/// has been processed.
async fn after_episode<T>(
    node: &Node,
    header: Header,
    f: impl FnOnce(&Node) -> Result<T, String>,
) -> Result<T, String> {
    let mut progress = node.watch_progress();
    let reached = async {
        // Copied out at once: the watch stays locked while borrowed.
        progress
            .wait_for(|p| p.run != header.run || p.finished.is_some_and(|e| e >= header.episode))
            .await
            .map(|p| *p)
    };
    let finished = tokio::time::timeout(EPISODE_WAIT, reached).await;
    match finished {
        Err(_) => Err(format!(
            "episode {} of run {} did not end within {EPISODE_WAIT:?}",
            header.episode, header.run
        )),
        Ok(Err(_)) => Err("the agent is stopping".to_owned()),
        Ok(Ok(p)) if p.run != header.run => Err(format!(
            "the command is for run {}, the agent is in run {}",
            header.run, p.run
        )),
        Ok(Ok(_)) => f(node),
    }
}

/// The agent's report: learned state, budgets, advice and message counters.
fn report(node: &Node) -> Result<AgentReport, String> {
    let mut report = {
        let learner = node.learner();
        let agent = learner.agent()?;
        let c = agent.counters();
        AgentReport {
            agent: node.id,
            digest: agent.digest(),
            ask_spent: c.advised_steps,
            give_spent: agent.spent_budget(),
            advice_requests_sent: c.requests_sent,
            advice_given: c.advice_given,
            ..AgentReport::default()
        }
    };
    let traffic = node.traffic().clone();
    report.advice_replies_received = traffic.replies_received;
    report.messages = traffic.messages;
    report.advice_rtt_ms = traffic.rtt_ms;
    report.alive_peers = node.alive().into_iter().filter(|&j| j != node.id).collect();
    Ok(report)
}
