//! Wire protocol shared by env-server, agents and coordinator.
//!
//! Messages are serde types encoded with postcard ([`codec`]); every message
//! carries a [`Header`] with [`PROTOCOL_VERSION`], the experiment, run,
//! episode and frame, so that stale, duplicate, foreign or malformed
//! messages are recognised and dropped. Key expressions live in [`keys`],
//! message and byte counters in [`counters`]. Joining the zenoh network is
//! the `node` crate's job: this one knows nothing of zenoh.

pub mod codec;
pub mod counters;
pub mod keys;
pub mod message;

pub use codec::{DecodeError, SettingsError, decode, decode_settings, encode, encode_settings};
pub use counters::{Direction, DropReason, MessageCounters, MessageKind};
pub use message::*;

use serde::{Deserialize, Serialize};

/// Version of the wire protocol; bumped on every incompatible change.
pub const PROTOCOL_VERSION: u16 = 4;

/// Number of features in the paper's state view (docs/algorithms.md section 1).
pub const STATE_FEATURES: usize = 6;

/// The paper's 6-feature state of one offense agent, each in [-1, 1].
pub type State = [f64; STATE_FEATURES];

/// A high-level HFO action of an offense agent.
///
/// `Move` is the only action without the ball; the other four are the
/// choices of an agent able to kick.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Action {
    /// Go to the formation position or chase the ball (no kick).
    Move,
    /// Kick towards the best goal-mouth course.
    Shoot,
    /// Short dribble chosen by the field evaluator.
    Dribble,
    /// Pass labelled "to the nearest teammate".
    PassNear,
    /// Pass labelled "to the farthest teammate".
    PassFar,
}

impl Action {
    /// The four actions of an agent able to kick, in the paper's greedy tie order
    /// (Shoot, Dribble, PassFar, PassNear).
    pub const KICK_TIE_ORDER: [Action; 4] = [
        Action::Shoot,
        Action::Dribble,
        Action::PassFar,
        Action::PassNear,
    ];

    /// Every action, indexed by [`Action::index`].
    pub const ALL: [Action; 5] = [
        Action::Move,
        Action::Shoot,
        Action::Dribble,
        Action::PassNear,
        Action::PassFar,
    ];

    /// Dense index in `0..5`, stable across versions of this protocol.
    pub fn index(self) -> usize {
        self as usize
    }

    /// Whether the action needs the ball (everything but `Move`).
    pub fn is_kick(self) -> bool {
        self != Action::Move
    }

    /// Lower-case name, as used on command lines and in files.
    pub fn name(self) -> &'static str {
        match self {
            Action::Move => "move",
            Action::Shoot => "shoot",
            Action::Dribble => "dribble",
            Action::PassNear => "pass-near",
            Action::PassFar => "pass-far",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_matches_all_table() {
        for (i, a) in Action::ALL.iter().enumerate() {
            assert_eq!(a.index(), i);
        }
        assert!(Action::KICK_TIE_ORDER.iter().all(|a| a.is_kick()));
        assert!(!Action::Move.is_kick());
    }
}
