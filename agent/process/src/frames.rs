//! The agent's stream task: observations and shared episodes, processed
//! strictly in order, one at a time (docs/protocol.md §5).

use std::sync::Arc;

use agent::Transition;
use proto::{ActionChoice, Body, DropReason, Envelope, Header, MessageKind, SharedEpisode};
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
                Ok(s) => on_observations(&node, &actions, &s.payload().to_bytes()).await,
                Err(_) => break,
            },
            sample = shares.recv_async() => match sample {
                Ok(s) => on_share(&node, &s.payload().to_bytes()),
                Err(_) => break,
            },
        }
    }
}

/// One observation message: its frames in order, as if each had come alone.
async fn on_observations(node: &Node, actions: &Publisher<'static>, bytes: &[u8]) {
    let Some(Envelope { header, body }) = node.decode(bytes) else {
        return;
    };
    let Body::Observations(frames) = body else {
        return node.dropped(DropReason::Malformed, Some(&header));
    };
    // Frames header.frame ..= header.frame + len - 1, at least one.
    let fits = (1..=proto::MAX_FRAMES_PER_MESSAGE).contains(&frames.len())
        && header.frame.checked_add(frames.len() as u32 - 1).is_some();
    if !fits {
        return node.dropped(DropReason::Malformed, Some(&header));
    }
    // Counted as received once one of its frames is accepted.
    let mut counted = false;
    for (k, obs) in frames.iter().enumerate() {
        let header = Header {
            frame: header.frame + k as u32,
            ..header
        };
        let alive = node.alive();
        let step = node.learner().observe(&header, obs, &|j| {
            u8::try_from(j).is_ok_and(|j| alive.contains(&j))
        });
        match step {
            Ok(step) => {
                if !std::mem::replace(&mut counted, true) {
                    node.accepted(MessageKind::Observation, bytes.len());
                }
                carry_out(node, actions, header, step).await;
            }
            Err(reason) => node.dropped(reason, Some(&header)),
        }
    }
}

/// A frame's step: the action to publish (after asking for advice, if
/// the learner wants to), or the end of the episode with its shares.
async fn carry_out(node: &Node, actions: &Publisher<'static>, header: Header, step: Step) {
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
async fn publish_shares(node: &Node, header: Header, shares: Vec<(usize, Vec<Transition>)>) {
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
