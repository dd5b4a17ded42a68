//! What the agents see: the three observation sets, the teammates' order
//! within them, and the global state.

use env_server::features::{
    current_feature_count, current_unum_feature_indices, feature_count, teammates_from_self,
    unum_feature_indices,
};
use env_server::params::{BALL_SPEED_MAX, FEATURE_X_RANGE, FEATURE_Y_RANGE, PLAYER_SPEED_MAX};
use env_server::{Env, Player};
use proto::STATE_FEATURES;
use std::f64::consts::PI;

/// A name that is not one of the accepted choices.
#[derive(Debug, thiserror::Error)]
#[error("unknown {what} {got:?} (expected one of: {choices})")]
pub(crate) struct UnknownName {
    pub(crate) what: &'static str,
    pub(crate) got: String,
    pub(crate) choices: &'static str,
}

/// The observation each agent gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ObservationSet {
    /// Today's HFO high-level feature set (`Env::current_features`).
    Hfo,
    /// The 2016 HFO set of the paper's code (`Env::features`).
    Authors,
    /// The paper's 6-feature state (`Env::state`).
    Paper,
}

impl ObservationSet {
    /// The set named `name`.
    pub(crate) fn parse(name: &str) -> Result<Self, UnknownName> {
        match name {
            "hfo" => Ok(ObservationSet::Hfo),
            "authors" => Ok(ObservationSet::Authors),
            "paper" => Ok(ObservationSet::Paper),
            _ => Err(UnknownName {
                what: "observation",
                got: name.to_owned(),
                choices: "hfo, authors, paper",
            }),
        }
    }

    /// The set's name.
    pub(crate) fn name(self) -> &'static str {
        match self {
            ObservationSet::Hfo => "hfo",
            ObservationSet::Authors => "authors",
            ObservationSet::Paper => "paper",
        }
    }

    /// Features per agent in a team of `offense`.
    pub(crate) fn size(self, offense: usize) -> usize {
        match self {
            ObservationSet::Hfo => current_feature_count(offense),
            ObservationSet::Authors => feature_count(offense),
            ObservationSet::Paper => STATE_FEATURES,
        }
    }

    /// Indices of the features that hold raw uniform numbers (HFO writes
    /// them unnormalised); every other feature is in [-1, 1].
    pub(crate) fn unum_indices(self, offense: usize) -> Vec<usize> {
        match self {
            ObservationSet::Hfo => current_unum_feature_indices(offense).collect(),
            ObservationSet::Authors => unum_feature_indices(offense).collect(),
            ObservationSet::Paper => Vec::new(),
        }
    }

    /// Agent `agent`'s teammates in the order its observation lists them
    /// (PASS to teammate j passes to the j-th): ascending uniform number in
    /// the authors' set, nearest first in the others.
    pub(crate) fn teammates(self, env: &Env, agent: usize) -> Vec<usize> {
        match self {
            ObservationSet::Authors => (0..env.offense()).filter(|&j| j != agent).collect(),
            ObservationSet::Hfo | ObservationSet::Paper => teammates_from_self(env.world(), agent),
        }
    }

    /// Every agent's observation, one row of [`ObservationSet::size`] after
    /// the other, into `out`.
    pub(crate) fn write(self, env: &Env, out: &mut [f32]) {
        let rows = out.chunks_exact_mut(self.size(env.offense()));
        match self {
            ObservationSet::Hfo => {
                for (agent, row) in rows.enumerate() {
                    copy(&env.current_features(agent), row);
                }
            }
            ObservationSet::Authors => {
                for (agent, row) in rows.enumerate() {
                    copy(&env.features(agent), row);
                }
            }
            ObservationSet::Paper => {
                for (state, row) in env.states().zip(rows) {
                    copy(&state, row);
                }
            }
        }
    }
}

fn copy(features: &[f64], row: &mut [f32]) {
    for (to, from) in row.iter_mut().zip(features) {
        *to = *from as f32;
    }
}

/// Length of the global state of a team of `offense`.
pub(crate) fn state_size(offense: usize) -> usize {
    4 + 5 * (offense + 1)
}

/// The global state of `env` ([`state_size`] values, each in [-1, 1]): the
/// ball's position (HFO's normalisation) and velocity (over its top
/// speed), then each attacker's and the keeper's position, velocity and
/// body direction (over π).
pub(crate) fn global_state(env: &Env) -> Vec<f32> {
    let world = env.world();
    let norm =
        |v: f64, (lo, hi): (f64, f64)| (2.0 * (v.clamp(lo, hi) - lo) / (hi - lo) - 1.0) as f32;
    let speed = |v: f64, max: f64| (v / max).clamp(-1.0, 1.0) as f32;
    let ball = world.ball;
    let mut values = vec![
        norm(ball.pos.x, FEATURE_X_RANGE),
        norm(ball.pos.y, FEATURE_Y_RANGE),
        speed(ball.vel.x, BALL_SPEED_MAX),
        speed(ball.vel.y, BALL_SPEED_MAX),
    ];
    let player = |p: &Player| {
        [
            norm(p.pos.x, FEATURE_X_RANGE),
            norm(p.pos.y, FEATURE_Y_RANGE),
            speed(p.vel.x, PLAYER_SPEED_MAX),
            speed(p.vel.y, PLAYER_SPEED_MAX),
            (p.body / PI) as f32,
        ]
    };
    values.extend(world.players().flat_map(player));
    values
}
