//! The discrete actions: MOVE, SHOOT, DRIBBLE, then PASS to each teammate
//! in the observation's order, to and from the simulator's actions.

use crate::observation::ObservationSet;
use env_server::Env;
use env_server::features::teammates_from_self;
use proto::Action;

/// Index of MOVE.
pub(crate) const MOVE: usize = 0;
/// Index of SHOOT.
const SHOOT: usize = 1;
/// Index of DRIBBLE.
const DRIBBLE: usize = 2;
/// Index of PASS to the first teammate; teammate j is `PASS + j`.
const PASS: usize = 3;

/// The name of action `index`, for error messages.
pub(crate) fn action_name(index: usize) -> String {
    match index {
        MOVE => "MOVE".to_owned(),
        SHOOT => "SHOOT".to_owned(),
        DRIBBLE => "DRIBBLE".to_owned(),
        j => format!("PASS to teammate {}", j - PASS),
    }
}

/// The simulator's action for action `index` of agent `agent` (a valid
/// index). Any PASS is HFO's best pass to anyone unless the simulator
/// passes to the named receiver; then PASS to the nearest teammate is
/// PassNear and to any other PassFar (the farthest: with four attackers
/// the middle teammate cannot be named).
pub(crate) fn decode(env: &Env, observation: ObservationSet, agent: usize, index: usize) -> Action {
    match index {
        MOVE => Action::Move,
        SHOOT => Action::Shoot,
        DRIBBLE => Action::Dribble,
        j if env.config().pass_to_named_receiver => {
            let receiver = observation.teammates(env, agent)[j - PASS];
            if teammates_from_self(env.world(), agent).first() == Some(&receiver) {
                Action::PassNear
            } else {
                Action::PassFar
            }
        }
        _ => Action::PassNear,
    }
}

/// The index of the simulator's `action` for agent `agent`: PassNear is
/// PASS to its nearest teammate, PassFar to its farthest; `None` for a pass
/// without a teammate.
pub(crate) fn encode(
    env: &Env,
    observation: ObservationSet,
    agent: usize,
    action: Action,
) -> Option<usize> {
    let pass_to = |receiver: Option<&usize>| {
        let order = observation.teammates(env, agent);
        receiver
            .and_then(|r| order.iter().position(|j| j == r))
            .map(|j| PASS + j)
    };
    match action {
        Action::Move => Some(MOVE),
        Action::Shoot => Some(SHOOT),
        Action::Dribble => Some(DRIBBLE),
        Action::PassNear => pass_to(teammates_from_self(env.world(), agent).first()),
        Action::PassFar => pass_to(teammates_from_self(env.world(), agent).last()),
    }
}

/// The action mask of an agent into `out`: MOVE always allowed, the kick
/// actions only when it can kick.
pub(crate) fn write_mask(can_kick: bool, out: &mut [i8]) {
    out.fill(i8::from(can_kick));
    out[MOVE] = 1;
}
