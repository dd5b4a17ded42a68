//! The agent's stream task: observations and shared episodes, processed
//! strictly in order, one at a time (docs/protocol.md §5).

use std::sync::Arc;

use agent::Transition;
use proto::{ActionChoice, Body, DropReason, Envelope, MessageKind, SharedEpisode};
use zenoh::handlers::FifoChannelHandler;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::sample::Sample;

use crate::ask::ask;
use crate::context::Node;
use crate::learner::Step;

/// A subscriber whose samples are read from a channel.
pub type Samples = Subscriber<FifoChannelHandler<Sample>>;

/// Processes observations and shared episodes until the session closes.
pub async fn run(
    node: Arc<Node>,
    observations: Samples,
    shares: Samples,
    actions: Publisher<'static>,
) {
    loop {
        tokio::select! {
            sample = observations.recv_async() => match sample {
                Ok(s) => on_observation(&node, &actions, &s.payload().to_bytes()).await,
                Err(_) => break,
            },
            sample = shares.recv_async() => match sample {
                Ok(s) => on_share(&node, &s.payload().to_bytes()),
                Err(_) => break,
            },
        }
    }
}

/// One observation: begin, play or end the episode, asking for advice and
/// publishing the action or the shared episodes as needed.
async fn on_observation(node: &Node, actions: &Publisher<'static>, bytes: &[u8]) {
    let Some(Envelope { header, body }) = node.decode(bytes) else {
        return;
    };
    let Body::Observation(obs) = body else {
        return node.dropped(DropReason::Malformed, Some(&header));
    };
    let alive = node.alive();
    let step = node.learner().observe(&header, &obs, &|j| {
        u8::try_from(j).is_ok_and(|j| alive.contains(&j))
    });
    let step = match step {
        Ok(step) => step,
        Err(reason) => return node.dropped(reason, Some(&header)),
    };
    node.accepted(MessageKind::Observation, bytes.len());
    let action = match step {
        Step::Act(action) => action,
        Step::Ask(request) => {
            let replies = ask(node, header, &request).await;
            let action = node.learner().complete(&request, &replies.advice);
            let mut traffic = node.traffic();
            traffic.replies_received += replies.replies;
            traffic.rtt_ms.extend_from_slice(&replies.rtt_ms);
            action
        }
        Step::End(shares) => {
            publish_shares(node, header, shares).await;
            let learner = node.learner();
            node.publish_progress(&learner);
            None
        }
    };
    if let Some(action) = action {
        let choice = ActionChoice {
            agent: node.id,
            action,
        };
        let bytes = node.encode(header, Body::Action(choice));
        if let Err(e) = actions.put(bytes).await {
            tracing::warn!(error = %e, "cannot publish an action");
        }
    }
}

/// Publishes an ended episode's transitions, one message per receiver.
async fn publish_shares(node: &Node, header: proto::Header, shares: Vec<(usize, Vec<Transition>)>) {
    for (to, transitions) in shares {
        let Ok(to) = u8::try_from(to) else { continue };
        let share = SharedEpisode {
            from: node.id,
            to,
            transitions,
        };
        let bytes = node.encode(header, Body::SharedEpisode(share));
        if let Err(e) = node.session.put(node.keys.share(to), bytes).await {
            tracing::warn!(to, error = %e, "cannot publish a shared episode");
        }
    }
}

/// One shared episode: queued, and replayed when due.
fn on_share(node: &Node, bytes: &[u8]) {
    let Some(Envelope { header, body }) = node.decode(bytes) else {
        return;
    };
    let result = match body {
        Body::SharedEpisode(share) => node.learner().receive_share(&header, share),
        _ => Err(DropReason::Malformed),
    };
    match result {
        Ok(()) => node.accepted(MessageKind::SharedEpisode, bytes.len()),
        Err(reason) => node.dropped(reason, Some(&header)),
    }
}
