//! What an agent sees and does: the paper's 6-feature [`State`] and HFO's
//! high-level [`Action`]s.

use serde::{Deserialize, Serialize};

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
