//! The advisor side: the agent's advice queryable, served concurrently with
//! its own decisions (docs/protocol.md §6).

use std::sync::Arc;

use proto::{AdviceReply, Body, DropReason, Envelope, MessageKind};
use zenoh::handlers::FifoChannelHandler;
use zenoh::query::{Query, Queryable};

use crate::context::Node;

/// A queryable whose queries are read from a channel.
pub type Queries = Queryable<FifoChannelHandler<Query>>;

/// Answers advice requests until the session closes.
pub async fn serve(node: Arc<Node>, queries: Queries) {
    while let Ok(query) = queries.recv_async().await {
        answer(&node, &query).await;
    }
}

/// Answers one request: advice, or `None` when the agent gives none (or the
/// request belongs to another run). Undecodable requests get no answer.
async fn answer(node: &Node, query: &Query) {
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
    if let Err(e) = query.reply(node.keys.advice(node.id), bytes).await {
        tracing::warn!(error = %e, "cannot answer an advice request");
    }
}
