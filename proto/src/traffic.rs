//! Message and byte counters by kind and direction, and dropped-message counts.

use serde::{Deserialize, Serialize};

/// The kinds of message, for accounting.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum MessageKind {
    /// Observation messages (each with one or more frames).
    Observation,
    /// Actions.
    Action,
    /// Advice requests.
    AdviceRequest,
    /// Advice replies.
    AdviceReply,
    /// Shared episodes.
    SharedEpisode,
    /// Control commands.
    Control,
    /// Control replies.
    ControlReply,
    /// Values replies (value-sharing methods).
    ValuesReply,
    /// Announcements of a spent give budget.
    Exhausted,
    /// Experience batches.
    ExperienceBatch,
    /// Reports of advice outcomes.
    AdviceOutcome,
}

impl MessageKind {
    /// Every kind, in counter order.
    pub const ALL: [MessageKind; 11] = [
        MessageKind::Observation,
        MessageKind::Action,
        MessageKind::AdviceRequest,
        MessageKind::AdviceReply,
        MessageKind::SharedEpisode,
        MessageKind::Control,
        MessageKind::ControlReply,
        MessageKind::ValuesReply,
        MessageKind::Exhausted,
        MessageKind::ExperienceBatch,
        MessageKind::AdviceOutcome,
    ];

    /// The kinds an advising method's traffic is made of: requests,
    /// replies, shared episodes, announcements, experience batches and
    /// advice outcomes.
    pub const ADVISING: [MessageKind; 7] = [
        MessageKind::AdviceRequest,
        MessageKind::AdviceReply,
        MessageKind::ValuesReply,
        MessageKind::SharedEpisode,
        MessageKind::Exhausted,
        MessageKind::ExperienceBatch,
        MessageKind::AdviceOutcome,
    ];

    /// Snake-case name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            MessageKind::Observation => "observation",
            MessageKind::Action => "action",
            MessageKind::AdviceRequest => "advice_request",
            MessageKind::AdviceReply => "advice_reply",
            MessageKind::SharedEpisode => "shared_episode",
            MessageKind::Control => "control",
            MessageKind::ControlReply => "control_reply",
            MessageKind::ValuesReply => "values_reply",
            MessageKind::Exhausted => "exhausted",
            MessageKind::ExperienceBatch => "experience_batch",
            MessageKind::AdviceOutcome => "advice_outcome",
        }
    }
}

/// Whether a message was sent or received.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// Sent by this process.
    Sent,
    /// Received by this process.
    Received,
}

/// Why a received message was dropped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DropReason {
    /// Undecodable bytes.
    Malformed,
    /// Another protocol version.
    Version,
    /// Another experiment.
    Foreign,
    /// From an earlier run, episode or frame.
    Stale,
    /// Already received.
    Duplicate,
    /// An advice reply from an agent that was not asked for this request.
    Unrequested,
}

/// Messages and bytes of one kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Tally {
    /// Messages.
    pub messages: u64,
    /// Payload bytes.
    pub bytes: u64,
}

/// Dropped messages by reason.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Dropped {
    /// Undecodable.
    pub malformed: u64,
    /// Other protocol version.
    pub version: u64,
    /// Other experiment.
    pub foreign: u64,
    /// Earlier run, episode or frame.
    pub stale: u64,
    /// Already received.
    pub duplicate: u64,
    /// Advice replies from an agent not asked for that request.
    #[serde(default)]
    pub unrequested: u64,
}

impl Dropped {
    /// All dropped messages.
    pub fn total(&self) -> u64 {
        self.malformed
            + self.version
            + self.foreign
            + self.stale
            + self.duplicate
            + self.unrequested
    }
}

/// A process's message accounting.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct MessageCounters {
    /// Sent, indexed like [`MessageKind::ALL`].
    pub sent: [Tally; MessageKind::ALL.len()],
    /// Received and accepted, indexed like [`MessageKind::ALL`].
    pub received: [Tally; MessageKind::ALL.len()],
    /// Received and dropped.
    pub dropped: Dropped,
}

impl MessageCounters {
    /// Counts one message of `bytes` bytes.
    pub fn record(&mut self, direction: Direction, kind: MessageKind, bytes: usize) {
        let table = match direction {
            Direction::Sent => &mut self.sent,
            Direction::Received => &mut self.received,
        };
        let tally = &mut table[kind as usize];
        tally.messages += 1;
        tally.bytes += bytes as u64;
    }

    /// Counts one dropped message.
    pub fn record_drop(&mut self, reason: DropReason) {
        let d = &mut self.dropped;
        match reason {
            DropReason::Malformed => d.malformed += 1,
            DropReason::Version => d.version += 1,
            DropReason::Foreign => d.foreign += 1,
            DropReason::Stale => d.stale += 1,
            DropReason::Duplicate => d.duplicate += 1,
            DropReason::Unrequested => d.unrequested += 1,
        }
    }

    /// Messages and bytes sent of `kinds`.
    pub fn sent_of(&self, kinds: &[MessageKind]) -> Tally {
        kinds.iter().fold(Tally::default(), |a, &k| Tally {
            messages: a.messages + self.sent[k as usize].messages,
            bytes: a.bytes + self.sent[k as usize].bytes,
        })
    }

    /// Total messages and bytes in one direction.
    pub fn total(&self, direction: Direction) -> Tally {
        let table = match direction {
            Direction::Sent => &self.sent,
            Direction::Received => &self.received,
        };
        table.iter().fold(Tally::default(), |a, t| Tally {
            messages: a.messages + t.messages,
            bytes: a.bytes + t.bytes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn totals_add_up_every_kind() {
        let mut c = MessageCounters::default();
        c.record(Direction::Sent, MessageKind::AdviceRequest, 40);
        c.record(Direction::Sent, MessageKind::AdviceRequest, 40);
        c.record(Direction::Sent, MessageKind::Action, 20);
        c.record(Direction::Received, MessageKind::Action, 7);
        c.record_drop(DropReason::Foreign);
        c.record_drop(DropReason::Stale);
        assert_eq!(
            c.total(Direction::Sent),
            Tally {
                messages: 3,
                bytes: 100
            }
        );
        assert_eq!(c.sent[MessageKind::AdviceRequest as usize].messages, 2);
        assert_eq!(c.total(Direction::Received).bytes, 7);
        assert_eq!(c.dropped.total(), 2);
    }
}
