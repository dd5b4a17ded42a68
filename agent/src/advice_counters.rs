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

/// What became of the advice requests an agent sent, each counted once:
/// by what arrived, the first that applies; and the requests kept advice
/// saved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RequestOutcomes {
    /// Advice (or values) arrived.
    pub answered: u64,
    /// Replies arrived, and some advisor declined: it could have advised.
    pub declined: u64,
    /// Every advisor asked replied that its give budget is spent: the
    /// request could not be answered.
    pub futile: u64,
    /// Some reply was lost or late (network conditions, the timeout) and
    /// none arrived with advice or a decline.
    pub lost: u64,
    /// Decisions that played kept advice instead of asking (advice reuse):
    /// not requests, but requests saved.
    pub reused: u64,
}

impl RequestOutcomes {
    /// Counts a request to `asked` advisors of which `replies` replied,
    /// with `answers`.
    pub(crate) fn count(&mut self, asked: u64, replies: u64, answers: &crate::Answers) {
        let outcome =
            if !answers.advice.is_empty() || !answers.values.is_empty() || !answers.best.is_empty()
            {
                &mut self.answered
            } else if answers.declined > 0 {
                &mut self.declined
            } else if replies == asked && u64::from(answers.exhausted) == asked {
                &mut self.futile
            } else {
                &mut self.lost
            };
        *outcome += 1;
    }
}
