//! Kicks towards a target that fall back to holding the ball: librcsc's
//! Body_SmartKick (spec 6.2.3) and Body_KickOneStep.

use super::hold::hold_ball;
use super::kick::{kick_to_velocity, max_one_kick_speed};
use super::kick_table;
use crate::sim::geom::{direction, unit};
use crate::sim::params::*;
use crate::sim::physics::{Command, max_kick_accel};
use crate::sim::world::{Player, World};
use glam::DVec2;

/// Body_SmartKick (spec 6.2.3): the first kick of the KickTable's best plan
/// of up to three kicks sending the ball towards `target` at `speed`, if it
/// reaches at least `min_speed`; else hold the ball.
pub(super) fn smart_kick(
    p: &Player,
    world: &World,
    target: DVec2,
    speed: f64,
    min_speed: f64,
) -> Command {
    planned_kick(p, world, target, (speed, min_speed), 3)
        .unwrap_or_else(|| hold_ball(p, world, None, Some(target)))
}

/// Body_SmartKick's kick with plans of at most `max_kicks` kicks, or `None`
/// where it would fail (and hold the ball).
pub(super) fn planned_kick(
    p: &Player,
    world: &World,
    target: DVec2,
    speeds: (f64, f64),
    max_kicks: usize,
) -> Option<Command> {
    kick_table::plan(p, world, target, speeds, max_kicks)
        .and_then(|first| kick_to_velocity(p, &world.ball, first - world.ball.pos))
}

/// Body_KickOneStep: one kick towards `target` at `speed`, or as fast as one
/// kick can send it that way; hold the ball if even that needs too much power.
pub(super) fn kick_one_step(p: &Player, world: &World, target: DVec2, speed: f64) -> Command {
    let ball = &world.ball;
    let dir = direction(target - ball.pos);
    let max = max_one_kick_speed(dir, ball.vel, max_kick_accel(p, ball.pos));
    kick_to_velocity(p, ball, unit(dir) * speed.min(max).min(BALL_SPEED_MAX))
        .unwrap_or_else(|| hold_ball(p, world, Some(target), Some(target)))
}
