//! The agent's control queryable: the coordinator's commands (docs/protocol.md
//! §2, §7, §8), each answered in its own task so that a report waiting for
//! an episode to end blocks nothing else.

use std::sync::Arc;
use std::time::Duration;

use proto::keys::Role;
use proto::{AgentReport, Body, Control, ControlReply, DropReason, Envelope, Header, MessageKind};
use zenoh::handlers::FifoChannelHandler;
use zenoh::query::{Query, Queryable};

use crate::context::{Context, Exit, Traffic};

/// How long Report and Snapshot wait for their episode to end
/// (less than the coordinator's 30 s, so that it gets this error).
const EPISODE_WAIT: Duration = Duration::from_secs(8);

/// A queryable whose queries are read from a channel.
pub type Queries = Queryable<FifoChannelHandler<Query>>;

/// Answers commands until the session closes.
pub async fn serve(ctx: Arc<Context>, queries: Queries) {
    while let Ok(query) = queries.recv_async().await {
        tokio::spawn(answer(ctx.clone(), query));
    }
}

/// Answers one command; undecodable ones get no answer, but for a command
/// of this experiment in another protocol version, which gets an error
/// naming both versions.
async fn answer(ctx: Arc<Context>, query: Query) {
    let bytes = query.payload().map(|p| p.to_bytes()).unwrap_or_default();
    let Some(Envelope { header, body }) = ctx.decode(&bytes) else {
        if let Some(refusal) = proto::version_refusal(&bytes, ctx.experiment) {
            let key = ctx.keys.control(Role::Agent(ctx.id));
            if let Err(e) = query.reply(key, proto::encode(&refusal)).await {
                tracing::warn!(error = %e, "cannot refuse a command of another version");
            }
        }
        return;
    };
    let Body::Control(control) = body else {
        return ctx.dropped(DropReason::Malformed, Some(&header));
    };
    tracing::debug!(?header, ?control, "command");
    let reset = matches!(control, Control::Reset { .. });
    let stop = control == Control::Stop;
    let reply = execute(&ctx, header, control).await;
    if reset && reply == ControlReply::Ok {
        // A new run counts its messages afresh, this command included.
        *ctx.traffic() = Traffic::default();
    }
    ctx.accepted(MessageKind::Control, bytes.len());
    let reply = ctx.encode(header, Body::ControlReply(reply));
    if let Err(e) = query
        .reply(ctx.keys.control(Role::Agent(ctx.id)), reply)
        .await
    {
        tracing::warn!(error = %e, "cannot answer a command");
    }
    // The final reply message goes out when the query is dropped.
    drop(query);
    if stop {
        ctx.stop(Exit::Stopped);
    }
}

/// Runs one command.
async fn execute(ctx: &Context, header: Header, control: Control) -> ControlReply {
    let done = |r: Result<(), String>| r.map_or_else(ControlReply::Error, |()| ControlReply::Ok);
    match control {
        Control::Reset {
            seed,
            config,
            wait_ms,
            stall_ms: _,
            simulator: _,
            features: _,
        } => {
            if !(1..=proto::MAX_WAIT_MS).contains(&wait_ms) {
                return ControlReply::Error(format!(
                    "the advice timeout must be 1 to {} ms, got {wait_ms}",
                    proto::MAX_WAIT_MS
                ));
            }
            let mut learner = ctx.learner();
            let result = learner.reset(header.run, seed, &config);
            if result.is_ok() {
                // A reset for a later episode joins the run there.
                learner.join_at(header.episode);
                // Network conditions bring their own advice timeout.
                let link = learner.agent().ok().and_then(|a| a.link().copied());
                let timeout = link.map_or(Duration::from_millis(wait_ms), |l| {
                    Duration::from_secs_f64(l.timeout_ms() / 1000.0)
                });
                ctx.set_advice(timeout, link);
            }
            ctx.publish_progress(&learner);
            done(result)
        }
        Control::Load { part, parts, bytes } => {
            match ctx.transfers().loading.take(part, parts, &bytes) {
                Ok(None) => ControlReply::Ok,
                Ok(Some(snapshot)) => done(ctx.learner().load(&snapshot)),
                Err(e) => ControlReply::Error(e),
            }
        }
        Control::Snapshot { part } => snapshot_part(ctx, header, part)
            .await
            .unwrap_or_else(ControlReply::Error),
        Control::Report => after_episode(ctx, header, report)
            .await
            .map_or_else(ControlReply::Error, |r| ControlReply::Agent(Box::new(r))),
        Control::Stop => ControlReply::Ok,
        Control::PlayEpisode { .. } => {
            ControlReply::Error("an agent does not play episodes; ask env-server".to_owned())
        }
    }
}

/// Part `part` of the agent's snapshot after episode `header.episode`:
/// part 0 takes it once that episode has ended, the others come from it.
async fn snapshot_part(ctx: &Context, header: Header, part: u32) -> Result<ControlReply, String> {
    let at = (header.run, header.episode);
    if part == 0 {
        let bytes = after_episode(ctx, header, |n| {
            let snapshot = n.learner().agent()?.snapshot();
            snapshot.encode().map_err(|e| e.to_string())
        })
        .await?;
        ctx.transfers().sending = Some((at, bytes));
    }
    let mut transfers = ctx.transfers();
    let Some((taken, bytes)) = &transfers.sending else {
        return Err(format!("snapshot part {part} asked before part 0"));
    };
    if *taken != at {
        return Err(format!(
            "snapshot part {part} asked for run {} episode {}, but the snapshot was taken at run {} \
             episode {}",
            at.0, at.1, taken.0, taken.1
        ));
    }
    let parts = proto::parts::split(bytes);
    let count = parts.len() as u32;
    let Some(piece) = parts.get(part as usize) else {
        return Err(format!("snapshot part {part} asked of {count}"));
    };
    let reply = ControlReply::Snapshot {
        parts: count,
        bytes: piece.to_vec(),
    };
    if part + 1 == count {
        transfers.sending = None;
    }
    Ok(reply)
}

/// Runs `f` once the terminal frame of `header.episode` of run `header.run`
/// has been processed.
async fn after_episode<T>(
    ctx: &Context,
    header: Header,
    f: impl FnOnce(&Context) -> Result<T, String>,
) -> Result<T, String> {
    let mut progress = ctx.watch_progress();
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
        Ok(Ok(_)) => f(ctx),
    }
}

/// The agent's report: learned state, budgets, advice and message counters.
fn report(ctx: &Context) -> Result<AgentReport, String> {
    let mut report = {
        let learner = ctx.learner();
        let agent = learner.agent()?;
        let c = agent.counters();
        AgentReport {
            agent: ctx.id,
            digest: agent.digest(),
            ask_spent: c.ask_spent,
            give_spent: agent.spent_budget(),
            advice_requests: c.advice_requests,
            advice_replies_received: c.advice_replies_received,
            advice_given: c.advice_given,
            request_outcomes: {
                let o = agent.request_outcomes();
                [o.answered, o.declined, o.futile, o.lost, o.reused]
            },
            advised_by: agent.advised_by().to_vec(),
            ..AgentReport::default()
        }
    };
    let traffic = ctx.traffic().clone();
    report.messages = traffic.messages;
    report.advice_rtt_ms = traffic.rtt_ms;
    report.alive_peers = ctx.alive().into_iter().filter(|&j| j != ctx.id).collect();
    Ok(report)
}
