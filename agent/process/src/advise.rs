//! The advisor side: the agent's advice queryable, answered in zenoh's
//! callback, concurrently with the agent's own decisions (docs/protocol.md §6).

use agent::{Answer, Leg};
use proto::{AdviceReply, Body, DropReason, Envelope, MessageKind, ValuesReply};
use zenoh::Wait;
use zenoh::query::Query;

use crate::conditions;
use crate::context::Context;

/// Answers one request: advice, or `None` when the agent gives none (or the
/// request belongs to another run). Undecodable requests get no answer.
/// Under network conditions the reply is lost or delayed as this agent's
/// link draws it; a delayed reply is sent from a task on `runtime`.
pub fn answer(ctx: &Context, query: Query, runtime: &tokio::runtime::Handle) {
    let bytes = query.payload().map(|p| p.to_bytes()).unwrap_or_default();
    let Some(Envelope { header, body }) = ctx.decode(&bytes) else {
        return;
    };
    let Body::AdviceRequest(request) = body else {
        return ctx.dropped(DropReason::Malformed, Some(&header));
    };
    let answer = match ctx.learner().advise(&header, &request) {
        Ok(answer) => {
            ctx.accepted(MessageKind::AdviceRequest, bytes.len());
            answer
        }
        Err(DropReason::Malformed) => return ctx.dropped(DropReason::Malformed, Some(&header)),
        // Another run's asker still gets its answer: no advice.
        Err(reason) => {
            ctx.dropped(reason, Some(&header));
            Answer::Action(None)
        }
    };
    let from = ctx.id;
    let reply = match answer {
        Answer::Action(advice) => Body::AdviceReply(AdviceReply { from, advice }),
        Answer::Values(values) => Body::ValuesReply(ValuesReply { from, values }),
    };
    let bytes = ctx.encode(header, reply);
    let key = ctx.keys.advice(ctx.id);
    match conditions::fate(ctx.advice().1, &header, ctx.id, request.from, Leg::Reply) {
        None => tracing::trace!(asker = request.from, "the network lost an advice reply"),
        Some(ms) if ms > 0.0 => {
            runtime.spawn(async move {
                conditions::delay(ms).await;
                if let Err(e) = query.reply(key, bytes).await {
                    tracing::debug!(error = %e, "cannot send a delayed advice reply");
                }
            });
        }
        Some(_) => {
            if let Err(e) = query.reply(key, bytes).wait() {
                tracing::warn!(error = %e, "cannot answer an advice request");
            }
        }
    }
}
