//! The advisor side: the agent's advice queryable, answered in zenoh's
//! callback, concurrently with the agent's own decisions (docs/protocol.md §6).

use proto::{AdviceReply, Body, DropReason, Envelope, MessageKind};
use zenoh::Wait;
use zenoh::query::Query;

use crate::context::Node;

/// Answers one request: advice, or `None` when the agent gives none (or the
/// request belongs to another run). Undecodable requests get no answer.
pub fn answer(node: &Node, query: &Query) {
    let bytes = query.payload().map(|p| p.to_bytes()).unwrap_or_default();
    let Some(Envelope { header, body }) = node.decode(&bytes) else {
        return;
    };
    let Body::AdviceRequest(request) = body else {
        return node.dropped(DropReason::Malformed, Some(&header));
    };
    let advice = match node.learner().advise(&header, &request) {
        Ok(advice) => {
            node.accepted(MessageKind::AdviceRequest, bytes.len());
            advice
        }
        Err(DropReason::Malformed) => return node.dropped(DropReason::Malformed, Some(&header)),
        // Another run's asker still gets its answer: no advice.
        Err(reason) => {
            node.dropped(reason, Some(&header));
            None
        }
    };
    let reply = AdviceReply {
        from: node.id,
        advice,
    };
    let bytes = node.encode(header, Body::AdviceReply(reply));
    if let Err(e) = query.reply(node.keys.advice(node.id), bytes).wait() {
        tracing::warn!(error = %e, "cannot answer an advice request");
    }
}
