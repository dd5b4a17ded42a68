//! Fixed baseline policies for rollouts and calibration (spec 9.2).

use proto::Action;
use rand::Rng;
use std::fmt;
use std::str::FromStr;

/// A policy that ignores the state except whether the agent can kick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BaselinePolicy {
    /// The paper's random agent: with the ball Dribble, Dribble, Shoot, Shoot, PassFar, PassNear uniformly.
    Random,
    /// Shoot whenever able to kick.
    Shoot,
    /// Dribble whenever able to kick.
    Dribble,
    /// Pass whenever able to kick.
    Pass,
    /// With the ball, uniformly one of Shoot, Dribble, PassNear, PassFar.
    Uniform,
}

/// The paper's random draw for an agent with the ball.
const RANDOM_KICKS: [Action; 6] = [
    Action::Dribble,
    Action::Dribble,
    Action::Shoot,
    Action::Shoot,
    Action::PassFar,
    Action::PassNear,
];

impl BaselinePolicy {
    /// Every policy, in the order of [`BaselinePolicy::NAMES`].
    pub const ALL: [BaselinePolicy; 5] = [
        BaselinePolicy::Random,
        BaselinePolicy::Shoot,
        BaselinePolicy::Dribble,
        BaselinePolicy::Pass,
        BaselinePolicy::Uniform,
    ];
    /// Accepted names.
    pub const NAMES: [&'static str; 5] = ["random", "shoot", "dribble", "pass", "uniform"];

    /// The action of an agent; `Move` whenever it cannot kick.
    pub fn choose(self, can_kick: bool, rng: &mut impl Rng) -> Action {
        if !can_kick {
            return Action::Move;
        }
        match self {
            BaselinePolicy::Random => RANDOM_KICKS[rng.random_range(0..RANDOM_KICKS.len())],
            BaselinePolicy::Shoot => Action::Shoot,
            BaselinePolicy::Dribble => Action::Dribble,
            BaselinePolicy::Pass => Action::PassNear,
            BaselinePolicy::Uniform => Action::KICK_TIE_ORDER[rng.random_range(0..4)],
        }
    }

    /// The policy's name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl fmt::Display for BaselinePolicy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown policy name.
#[derive(Debug, thiserror::Error)]
#[error("unknown policy '{0}' (expected one of: random, shoot, dribble, pass, uniform)")]
pub struct UnknownPolicy(String);

impl FromStr for BaselinePolicy {
    type Err = UnknownPolicy;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| UnknownPolicy(s.to_owned()))
    }
}
