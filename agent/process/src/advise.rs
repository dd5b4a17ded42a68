//! The advisor side: the agent's advice queryable, answered in zenoh's
//! callback, concurrently with the agent's own decisions (docs/protocol.md §6).

use proto::{AdviceReply, Body, DropReason, Envelope, MessageKind};
use zenoh::Wait;
use zenoh::query::Query;

use crate::context::Context;

/// Answers one request: advice, or `None` when the agent gives none (or the
/// request belongs to another run). Undecodable requests get no answer.
pub fn answer(ctx: &Context, query: &Query) {
    let bytes = query.payload().map(|p| p.to_bytes()).unwrap_or_default();
    let Some(Envelope { header, body }) = ctx.decode(&bytes) else {
        return;
    };
    let Body::AdviceRequest(request) = body else {
        return ctx.dropped(DropReason::Malformed, Some(&header));
    };
    let advice = match ctx.learner().advise(&header, &request) {
        Ok(advice) => {
            ctx.accepted(MessageKind::AdviceRequest, bytes.len());
            advice
        }
        Err(DropReason::Malformed) => return ctx.dropped(DropReason::Malformed, Some(&header)),
        // Another run's asker still gets its answer: no advice.
        Err(reason) => {
            ctx.dropped(reason, Some(&header));
            None
        }
    };
    let reply = AdviceReply {
        from: ctx.id,
        advice,
    };
    let bytes = ctx.encode(header, Body::AdviceReply(reply));
    if let Err(e) = query.reply(ctx.keys.advice(ctx.id), bytes).wait() {
        tracing::warn!(error = %e, "cannot answer an advice request");
    }
}
