//! The advisor side: the agent's advice queryable, answered in zenoh's
//! callback, concurrently with the agent's own decisions (docs/protocol.md §6).

use agent::{Answer, Leg};
use proto::{
    AdviceAnswer, AdviceReply, Body, DropReason, Envelope, Exhausted, FeaturedRequest, Features,
    Header, MessageKind, ValuesReply,
};
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
    let (request, features) = match body {
        Body::AdviceRequest(request) => (request, Features::NONE),
        Body::FeaturedRequest(FeaturedRequest { request, features }) => (request, features),
        _ => return ctx.dropped(DropReason::Malformed, Some(&header)),
    };
    let answer = match ctx.learner().advise(&header, &request, &features) {
        Ok(answer) => {
            ctx.accepted(MessageKind::AdviceRequest, bytes.len());
            answer
        }
        Err(DropReason::Malformed) => return ctx.dropped(DropReason::Malformed, Some(&header)),
        // Another run's asker still gets its answer: no advice.
        Err(reason) => {
            ctx.dropped(reason, Some(&header));
            Answer::Action(AdviceAnswer::Declined)
        }
    };
    let from = ctx.id;
    let reply = match answer {
        Answer::Action(answer) => Body::AdviceReply(AdviceReply { from, answer }),
        Answer::Values(answer) => Body::ValuesReply(ValuesReply { from, answer }),
    };
    if ctx.learner().take_announcement() {
        announce(ctx, header, runtime);
    }
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

/// Tells every agent once that this agent's give budget is spent
/// (`announce_exhausted`): one message on its announcement key, sent from
/// `runtime` (a callback sends only small messages itself).
fn announce(ctx: &Context, header: Header, runtime: &tokio::runtime::Handle) {
    let bytes = ctx.encode(header, Body::Exhausted(Exhausted { from: ctx.id }));
    let (session, key) = (ctx.session.clone(), ctx.keys.exhausted(ctx.id));
    runtime.spawn(async move {
        if let Err(e) = session.put(key, bytes).await {
            tracing::warn!(error = %e, "cannot announce the spent give budget");
        }
    });
}

/// Takes another agent's announcement that its give budget is spent: it
/// is asked no more in this run (until its process joins again).
pub fn on_exhausted(ctx: &Context, bytes: &[u8]) {
    let Some(Envelope { header, body }) = ctx.decode(bytes) else {
        return;
    };
    let Body::Exhausted(Exhausted { from }) = body else {
        return ctx.dropped(DropReason::Malformed, Some(&header));
    };
    if from == ctx.id {
        // Its own, heard back.
        return;
    }
    match ctx.learner().hear_exhausted(&header, from) {
        Ok(()) => ctx.accepted(MessageKind::Exhausted, bytes.len()),
        Err(reason) => ctx.dropped(reason, Some(&header)),
    }
}
