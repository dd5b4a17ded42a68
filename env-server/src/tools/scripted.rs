//! Fixed scripted policies for rollouts and calibration (spec 9.2), and
//! episodes played with them.

use crate::sim::config::MAX_OFFENSE;
use crate::sim::env::Env;
use crate::sim::referee::Outcome;
use proto::Action;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::fmt;
use std::str::FromStr;

/// A policy that ignores the state except whether the agent can kick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScriptedPolicy {
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

impl ScriptedPolicy {
    /// Every policy, in the order of [`ScriptedPolicy::NAMES`].
    pub const ALL: [ScriptedPolicy; 5] = [
        ScriptedPolicy::Random,
        ScriptedPolicy::Shoot,
        ScriptedPolicy::Dribble,
        ScriptedPolicy::Pass,
        ScriptedPolicy::Uniform,
    ];
    /// Accepted names.
    pub const NAMES: [&'static str; 5] = ["random", "shoot", "dribble", "pass", "uniform"];

    /// The action of an agent; `Move` whenever it cannot kick.
    pub fn choose(self, can_kick: bool, rng: &mut impl Rng) -> Action {
        if !can_kick {
            return Action::Move;
        }
        match self {
            ScriptedPolicy::Random => RANDOM_KICKS[rng.random_range(0..RANDOM_KICKS.len())],
            ScriptedPolicy::Shoot => Action::Shoot,
            ScriptedPolicy::Dribble => Action::Dribble,
            ScriptedPolicy::Pass => Action::PassNear,
            ScriptedPolicy::Uniform => Action::KICK_TIE_ORDER[rng.random_range(0..4)],
        }
    }

    /// The policy's name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl fmt::Display for ScriptedPolicy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An unknown policy name.
#[derive(Debug, thiserror::Error)]
#[error("unknown policy '{0}' (expected one of: random, shoot, dribble, pass, uniform)")]
pub struct UnknownPolicy(String);

impl FromStr for ScriptedPolicy {
    type Err = UnknownPolicy;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| UnknownPolicy(s.to_owned()))
    }
}

/// The random stream of a policy, derived from the rollout seed.
pub fn policy_rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed ^ 0x5851_f42d_4c95_7f2d)
}

/// Plays one episode of `env` under `policy`; `observe` sees the env after
/// the reset (with no actions) and after every step (with the actions it
/// applied). Returns the outcome and frame count.
pub fn play_episode(
    env: &mut Env,
    policy: ScriptedPolicy,
    rng: &mut Xoshiro256PlusPlus,
    mut observe: impl FnMut(&Env, &[Action]),
) -> (Outcome, u32) {
    env.reset();
    observe(env, &[]);
    let mut actions = [Action::Move; MAX_OFFENSE];
    let n = env.offense();
    loop {
        for (i, a) in actions[..n].iter_mut().enumerate() {
            *a = policy.choose(env.can_kick(i), rng);
        }
        let outcome = env.step(&actions[..n]);
        observe(env, &actions[..n]);
        if outcome.is_terminal() {
            return (outcome, env.frame());
        }
    }
}
