//! The agent's stream of observations: frames processed strictly in order,
//! one at a time (docs/protocol.md §5). A message is stepped in zenoh's
//! callback, on the thread that received it; only a frame that asks for
//! advice, and whatever arrives until its answer is in, waits for the
//! stream task, which can wait for the advisors.

use std::sync::{Arc, Mutex};

use agent::{Sends, Share};
use node::sync::lock;
use proto::{
    ActionChoice, AdviceOutcome, AgentFrame, Body, DropReason, Envelope, ExperienceBatch, Header,
    MessageKind, SharedEpisode,
};
use tokio::runtime::Handle;
use tokio::sync::mpsc::{UnboundedReceiver, UnboundedSender, unbounded_channel};
use zenoh::Wait;
use zenoh::pubsub::Publisher;

use crate::ask::ask;
use crate::context::Context;
use crate::learning::{Ask, Step};

/// Steps observation messages and publishes what they lead to.
pub struct Stream {
    ctx: Arc<Context>,
    actions: Publisher<'static>,
    runtime: Handle,
    backlog: Mutex<Backlog>,
}

/// What the stream task has still to do. While it is busy, every message
/// that arrives goes to it, so the frames keep their order.
struct Backlog {
    busy: bool,
    task: UnboundedSender<Pending>,
}

/// A message's frames from one that asks for advice (or from the first),
/// left to the stream task.
struct Pending {
    ask: Option<(Header, Box<Ask>)>,
    frames: Frames,
}

/// A checked observation message whose frames are stepped one at a time.
struct Frames {
    header: Header,
    /// The frames not stepped yet, and the number of the next one.
    rest: std::vec::IntoIter<AgentFrame>,
    next: u32,
    /// The message's size, counted once one of its frames is accepted.
    bytes: usize,
    counted: bool,
}

impl Frames {
    /// Decodes one observation message; a malformed one is counted as
    /// dropped: no frames, more than `MAX_FRAMES_PER_MESSAGE`, or frame
    /// numbers past `u32::MAX` (the k-th frame is `header.frame + k`).
    fn open(ctx: &Context, bytes: &[u8]) -> Option<Self> {
        let Envelope { header, body } = ctx.decode(bytes)?;
        let Body::Observations(frames) = body else {
            ctx.dropped(DropReason::Malformed, Some(&header));
            return None;
        };
        let fits = (1..=proto::MAX_FRAMES_PER_MESSAGE).contains(&frames.len())
            && header.frame.checked_add(frames.len() as u32 - 1).is_some();
        if !fits {
            ctx.dropped(DropReason::Malformed, Some(&header));
            return None;
        }
        Some(Frames {
            header,
            rest: frames.into_iter(),
            next: header.frame,
            bytes: bytes.len(),
            counted: false,
        })
    }

    /// The learner's step on the next frame it accepts (the frames it
    /// drops are counted), with that frame's header; `None` at the end.
    /// `reachable` says which agents can be asked for advice.
    fn step(&mut self, ctx: &Context, reachable: &dyn Fn(usize) -> bool) -> Option<(Header, Step)> {
        for obs in self.rest.by_ref() {
            let header = Header {
                frame: self.next,
                ..self.header
            };
            self.next = self.next.wrapping_add(1);
            match ctx.learner().observe(&header, &obs, reachable) {
                Ok(step) => {
                    if !std::mem::replace(&mut self.counted, true) {
                        ctx.accepted(MessageKind::Observation, self.bytes);
                    }
                    return Some((header, step));
                }
                Err(reason) => ctx.dropped(reason, Some(&header)),
            }
        }
        None
    }
}

impl Stream {
    /// A stream of this agent's observations that publishes its actions
    /// on `actions`, and the inbox of its task ([`run`]); made within the
    /// agent's runtime.
    pub fn new(ctx: Arc<Context>, actions: Publisher<'static>) -> (Arc<Self>, Tasks) {
        let (task, pending) = unbounded_channel();
        let stream = Stream {
            ctx,
            actions,
            runtime: Handle::current(),
            backlog: Mutex::new(Backlog { busy: false, task }),
        };
        (Arc::new(stream), Tasks(pending))
    }

    /// One observation message, as it arrives: stepped here unless the
    /// task is busy; a frame that asks for advice hands the rest to it.
    pub fn on_message(&self, bytes: &[u8]) {
        let mut backlog = lock(&self.backlog);
        let Some(frames) = Frames::open(&self.ctx, bytes) else {
            return;
        };
        let pending = match backlog.busy {
            true => Some(Pending { ask: None, frames }),
            false => self.step_until_ask(frames),
        };
        if let Some(pending) = pending {
            backlog.busy = true;
            // The receiver lives as long as the runtime.
            let _ = backlog.task.send(pending);
        }
    }

    /// Steps `frames` until one asks for advice, which is returned with
    /// the frames after it.
    fn step_until_ask(&self, mut frames: Frames) -> Option<Pending> {
        let alive = self.ctx.alive();
        let reachable = |j: usize| u8::try_from(j).is_ok_and(|j| alive.contains(&j));
        while let Some((header, step)) = frames.step(&self.ctx, &reachable) {
            self.publish_reports(header);
            match step {
                Step::Act(action) => self.publish_action(header, action),
                Step::Ask(request) => {
                    return Some(Pending {
                        ask: Some((header, request)),
                        frames,
                    });
                }
                Step::End(shares) => {
                    self.publish_shares(header, shares);
                    let learner = self.ctx.learner();
                    self.ctx.publish_progress(&learner);
                }
            }
        }
        None
    }

    /// Asks for advice and publishes the action the learner then takes.
    async fn advised(&self, header: Header, request: Box<Ask>) {
        let ctx = &self.ctx;
        let replies = ask(ctx, header, &request).await;
        let action = ctx
            .learner()
            .complete(&request, &replies.answers, replies.replies());
        ctx.traffic().rtt_ms.extend_from_slice(&replies.rtt_ms);
        self.publish_reports(header);
        self.publish_action(header, action);
    }

    /// Publishes a kicker's action (nothing for `None`).
    fn publish_action(&self, header: Header, action: Option<proto::Action>) {
        let Some(action) = action else { return };
        let choice = ActionChoice {
            agent: self.ctx.id,
            action,
        };
        let bytes = self.ctx.encode(header, Body::Action(choice));
        if let Err(e) = self.actions.put(bytes).wait() {
            tracing::warn!(error = %e, "cannot publish an action");
        }
    }

    /// Publishes what an ended episode sends unasked (its transitions, a
    /// batch), one message per receiver.
    fn publish_shares(&self, header: Header, shares: Sends) {
        let from = self.ctx.id;
        for (to, share) in shares {
            let Ok(to) = u8::try_from(to) else { continue };
            let body = match share {
                Share::Episode(transitions) => Body::SharedEpisode(SharedEpisode {
                    from,
                    to,
                    transitions,
                }),
                Share::Batch(batch) => Body::ExperienceBatch(ExperienceBatch {
                    from,
                    to,
                    transitions: batch.transitions,
                    notes: batch.notes,
                    standing: batch.standing,
                }),
            };
            self.send_to(header, to, body);
        }
    }

    /// Publishes the agent's reports of advice outcomes, one message per
    /// advisor.
    fn publish_reports(&self, header: Header) {
        let reports = self.ctx.learner().take_reports();
        for r in reports {
            let Ok(to) = u8::try_from(r.advisor) else {
                continue;
            };
            let report = AdviceOutcome {
                from: self.ctx.id,
                to,
                followed: r.followed,
                advantage: r.advantage,
            };
            self.send_to(header, to, Body::AdviceOutcome(report));
        }
    }

    /// Publishes `body` on agent `to`'s key for what it is sent unasked,
    /// from the agent's runtime: a long episode is a large message, and
    /// zenoh's callback, which may be stepping this, runs on the one thread
    /// that also sends it ([`node::net::ONE_RUNTIME`]).
    fn send_to(&self, header: Header, to: u8, body: Body) {
        let ctx = &self.ctx;
        let kind = MessageKind::of(&body);
        let bytes = ctx.encode(header, body);
        let (session, key) = (ctx.session.clone(), ctx.keys.share(to));
        self.runtime.spawn(async move {
            if let Err(e) = session.put(key, bytes).await {
                tracing::warn!(to, ?kind, error = %e, "cannot publish a message");
            }
        });
    }
}

/// The stream task's inbox.
pub struct Tasks(UnboundedReceiver<Pending>);

/// The stream task: asks for advice and steps what waited meanwhile, for
/// as long as the runtime runs.
pub async fn run(stream: Arc<Stream>, Tasks(mut pending): Tasks) {
    while let Some(Pending {
        mut ask,
        mut frames,
    }) = pending.recv().await
    {
        loop {
            if let Some((header, request)) = ask.take() {
                stream.advised(header, request).await;
            }
            match stream.step_until_ask(frames) {
                Some(more) => (ask, frames) = (more.ask, more.frames),
                None => break,
            }
        }
        let mut backlog = lock(&stream.backlog);
        backlog.busy = !pending.is_empty();
    }
}

/// One message sent to this agent unasked: a shared episode or a batch
/// (queued, and learned when due), or a report of how its advice turned out.
pub fn on_share(ctx: &Context, bytes: &[u8]) {
    let Some(Envelope { header, body }) = ctx.decode(bytes) else {
        return;
    };
    let kind = MessageKind::of(&body);
    let result = match body {
        Body::SharedEpisode(share) => ctx.learner().receive_share(&header, share),
        Body::ExperienceBatch(batch) => ctx.learner().receive_batch(&header, batch),
        Body::AdviceOutcome(report) => ctx.learner().hear_advice_outcome(&header, &report),
        _ => Err(DropReason::Malformed),
    };
    match result {
        Ok(()) => ctx.accepted(kind, bytes.len()),
        Err(reason) => ctx.dropped(reason, Some(&header)),
    }
}
