//! The communication and budget counters of one agent.

use serde::{Deserialize, Serialize};

/// Communication and budget counters of one agent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct AdviceCounters {
    /// Advice requests sent (one per request, whatever the number of recipients).
    pub advice_requests: u64,
    /// Replies that arrived, with or without advice.
    pub advice_replies_received: u64,
    /// Steps acted on advice: the ad hoc ask budget spent.
    pub ask_spent: u64,
    /// Answers given: the give budget spent (ad hoc advisor or Torrey teacher).
    pub advice_given: u64,
    /// Transitions sent to receivers: the EpisodeSharing budget spent.
    pub shared_sent: u64,
    /// Transitions received and replayed.
    pub shared_received: u64,
}
