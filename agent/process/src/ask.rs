//! The advisee side of advising: one query per live advisor, all in
//! parallel, replies taken as they stream in until every advisor answered
//! or the advice timeout passed (docs/protocol.md §6).

use std::time::{Duration, Instant};

use agent::{Answer, Answers, Leg};
use proto::{AdviceAnswer, Body, DropReason, Header, MessageKind, ValuesAnswer};
use tokio::sync::mpsc;
use zenoh::query::{ConsolidationMode, QueryTarget};

use crate::conditions;
use crate::context::Context;
use crate::learning::Ask;

/// The replies collected for one request.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Collector {
    waiting: Vec<u8>,
    answered: Vec<u8>,
    /// What was received, by advisor (replies without advice add nothing).
    pub answers: Answers,
    /// Round-trip time of each reply (ms).
    pub rtt_ms: Vec<f32>,
}

impl Collector {
    /// Waits for a reply from each of `advisors`.
    pub fn new(advisors: &[u8]) -> Self {
        Self {
            waiting: advisors.to_vec(),
            ..Self::default()
        }
    }

    /// Replies received, with or without advice.
    pub fn replies(&self) -> u64 {
        self.answered.len() as u64
    }

    /// Takes advisor `from`'s reply, received `rtt` after its request.
    /// Only kick actions count as advice, and only finite values. A reply
    /// from an advisor that was not asked is refused as unrequested, a
    /// second one as a duplicate.
    pub fn take(&mut self, from: u8, answer: Answer, rtt: Duration) -> Result<(), DropReason> {
        let finite = match answer {
            Answer::Values(ValuesAnswer::Values(values)) => values.is_valid(),
            Answer::Values(ValuesAnswer::Best(_, value)) => value.is_finite(),
            Answer::Action(AdviceAnswer::Recommendation(_, value)) => value.is_finite(),
            _ => true,
        };
        if !finite {
            return Err(DropReason::Malformed);
        }
        let Some(k) = self.waiting.iter().position(|&j| j == from) else {
            return Err(if self.answered.contains(&from) {
                DropReason::Duplicate
            } else {
                DropReason::Unrequested
            });
        };
        self.answered.push(from);
        self.waiting.swap_remove(k);
        self.rtt_ms.push(rtt.as_secs_f32() * 1000.0);
        // Only kick actions count as advice.
        let answer = match answer {
            Answer::Action(
                AdviceAnswer::Advice(action) | AdviceAnswer::Recommendation(action, _),
            ) if !action.is_kick() => Answer::Action(AdviceAnswer::Declined),
            Answer::Values(ValuesAnswer::Best(action, _)) if !action.is_kick() => {
                Answer::Values(ValuesAnswer::Declined)
            }
            answer => answer,
        };
        self.answers.take(usize::from(from), answer);
        Ok(())
    }

    /// Whether every advisor answered.
    pub fn done(&self) -> bool {
        self.waiting.is_empty()
    }
}

/// A reply as it arrives: the advisor queried, the payload and the round trip.
type Arrival = (u8, Vec<u8>, Duration);

/// Sends `ask` (for the frame of `header`) to its advisors and collects
/// their replies. Under network conditions each request is lost or delayed
/// as this agent's link draws it; the asker waits for a lost one all the
/// same, as it cannot know.
pub async fn ask(ctx: &Context, header: Header, ask: &Ask) -> Collector {
    let (timeout, link) = ctx.advice();
    let asked = Instant::now();
    let deadline = tokio::time::Instant::from_std(asked) + timeout;
    let (tx, mut rx) = mpsc::unbounded_channel::<Arrival>();
    let mut collector = Collector::new(&[]);
    for &j in &ask.to {
        let request = Request {
            session: ctx.session.clone(),
            key: ctx.keys.advice(j),
            bytes: ctx.encode(header, ask.body()),
            advisor: j,
            asked,
            deadline,
            tx: tx.clone(),
        };
        match conditions::fate(link, &header, ctx.id, j, Leg::Request) {
            None => tracing::trace!(advisor = j, "the network lost an advice request"),
            Some(ms) if ms > 0.0 => {
                tokio::spawn(request.send_after(ms));
            }
            Some(_) => {
                if let Err(e) = request.send().await {
                    tracing::warn!(advisor = j, error = %e, "cannot send an advice request");
                    continue;
                }
            }
        }
        collector.waiting.push(j);
    }
    drop(tx);
    while !collector.done() {
        let Ok(Some((j, bytes, rtt))) = tokio::time::timeout_at(deadline, rx.recv()).await else {
            break;
        };
        take_reply(ctx, header, &mut collector, j, &bytes, rtt);
    }
    collector
}

/// One advice request on its way to one advisor.
struct Request {
    session: zenoh::Session,
    key: String,
    bytes: Vec<u8>,
    advisor: u8,
    /// When the asker sent it (round trips count from here).
    asked: Instant,
    /// When the asker stops waiting.
    deadline: tokio::time::Instant,
    tx: mpsc::UnboundedSender<Arrival>,
}

impl Request {
    /// Sends the query; its replies go to the collector until the deadline.
    async fn send(self) -> zenoh::Result<()> {
        let Request {
            session,
            key,
            bytes,
            advisor,
            asked,
            deadline,
            tx,
        } = self;
        session
            .get(key)
            .payload(bytes)
            .consolidation(ConsolidationMode::None)
            .target(QueryTarget::All)
            .timeout(deadline.saturating_duration_since(tokio::time::Instant::now()))
            .callback(move |reply| {
                if let Ok(sample) = reply.result() {
                    // The receiver is gone once the request is settled.
                    let payload = sample.payload().to_bytes().into_owned();
                    let _ = tx.send((advisor, payload, asked.elapsed()));
                }
            })
            .await
    }

    /// Sends it after the network's delay of `ms`, unless the asker stopped
    /// waiting by then.
    async fn send_after(self, ms: f64) {
        conditions::delay(ms).await;
        if tokio::time::Instant::now() >= self.deadline {
            return;
        }
        let advisor = self.advisor;
        if let Err(e) = self.send().await {
            tracing::warn!(advisor, error = %e, "cannot send a delayed advice request");
        }
    }
}

/// Checks one reply and hands it to the collector, counting it.
fn take_reply(
    ctx: &Context,
    header: Header,
    collector: &mut Collector,
    j: u8,
    bytes: &[u8],
    rtt: Duration,
) {
    let Some(envelope) = ctx.decode(bytes) else {
        return;
    };
    let (kind, from, answer) = match envelope.body {
        Body::AdviceReply(r) => (MessageKind::AdviceReply, r.from, Answer::Action(r.answer)),
        Body::ValuesReply(r) => (MessageKind::ValuesReply, r.from, Answer::Values(r.answer)),
        _ => return ctx.dropped(DropReason::Malformed, Some(&envelope.header)),
    };
    let result = if envelope.header != header {
        Err(DropReason::Stale)
    } else if from != j {
        // A reply on advisor j's key that names another sender.
        Err(DropReason::Unrequested)
    } else {
        collector.take(j, answer, rtt)
    };
    match result {
        Ok(()) => ctx.accepted(kind, bytes.len()),
        Err(reason) => ctx.dropped(reason, Some(&envelope.header)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use agent::{Advice, ValuesAdvice};
    use proto::Action::{Dribble, Move, Shoot};

    #[test]
    fn collects_until_every_advisor_answered() {
        let ms = Duration::from_millis;
        let act = |a| Answer::Action(AdviceAnswer::Advice(a));
        let mut c = Collector::new(&[2, 0]);
        assert!(!c.done());
        c.take(0, act(Shoot), ms(3)).unwrap();
        assert_eq!(c.take(0, act(Dribble), ms(4)), Err(DropReason::Duplicate));
        assert_eq!(
            c.take(1, act(Dribble), ms(4)),
            Err(DropReason::Unrequested),
            "not asked"
        );
        assert!(!c.done());
        // No advice, or a non-kick one: a reply, but no advice.
        c.take(2, Answer::Action(AdviceAnswer::Declined), ms(1))
            .unwrap();
        assert!(c.done());
        let shoot = Advice {
            advisor: 0,
            action: Shoot,
        };
        assert_eq!(c.answers.advice, vec![shoot]);
        assert_eq!((c.answers.declined, c.answers.exhausted), (1, 0));
        assert_eq!(c.replies(), 2);
        assert_eq!(c.rtt_ms, vec![3.0, 1.0]);
        let mut d = Collector::new(&[1]);
        d.take(1, act(Move), ms(1)).unwrap();
        assert!(d.answers.advice.is_empty());
    }

    #[test]
    fn shared_values_are_collected_and_bad_ones_refused() {
        let ms = Duration::from_millis;
        let values = |q| proto::SharedValues {
            q,
            learned: 0b10,
            visits: 7,
        };
        let mut c = Collector::new(&[1, 2]);
        let bad = values([f64::NAN, 0.0, 0.0, 0.0, 0.0]);
        let refused = c.take(1, Answer::Values(ValuesAnswer::Values(bad)), ms(1));
        assert_eq!(refused, Err(DropReason::Malformed));
        let good = values([0.0, 0.5, 0.0, 0.0, 0.0]);
        c.take(2, Answer::Values(ValuesAnswer::Values(good)), ms(2))
            .unwrap();
        let shared = ValuesAdvice {
            advisor: 2,
            values: good,
        };
        assert_eq!(c.answers.values, vec![shared]);
        assert!(!c.done(), "the refused reply does not count");
    }

    #[test]
    fn nobody_to_ask_is_done_at_once() {
        assert!(Collector::new(&[]).done());
    }
}
