//! DRIBBLE (spec 6.3): turn to face forward if badly oriented, else the best
//! short dribble by agent2d's field evaluator, else hold the ball.

use super::Situation;
use super::body::{hold_ball, kick_to_velocity, turn_to_point};
use crate::geom::{angle_diff, asin_clamped, decay_sum, direction, normalize_angle, polar, unit};
use crate::params::*;
use crate::physics::{Command, max_kick_accel};
use crate::world::Player;
use glam::DVec2;
use std::f64::consts::PI;

/// A short-dribble candidate: the first command and where the ball ends up.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    command: Command,
    ball_end: DVec2,
}

/// The DRIBBLE command of a kickable agent.
pub fn command(s: &Situation) -> Command {
    let me = s.me();
    let ball = &s.world.ball;
    let forward = DVec2::new(42.0, 0.0);
    let keeper_near = s.world.keeper.pos.distance(me.pos) < 4.0;
    if angle_diff(me.body, direction(forward - me.pos)) >= 110f64.to_radians() && !keeper_near {
        let self_next = me.pos + me.vel;
        let ball_next = ball.pos + ball.vel;
        let keep = KICKABLE_AREA - 0.1 * me.vel.length() - 0.05 * ball.vel.length() - 0.2;
        if self_next.distance(ball_next) < keep {
            return turn_to_point(me, DVec2::new(42.0, 0.5 * me.pos.y));
        }
        return hold_ball(me, s.world);
    }
    let mut best = evaluate(s, ball.pos);
    let mut choice = None;
    let kicks = (0..16).flat_map(|a| kick_candidates(s, me, a));
    for c in kicks.chain(dash_candidates(s)) {
        let value = evaluate(s, c.ball_end);
        if value > best {
            best = value;
            choice = Some(c.command);
        }
    }
    choice.unwrap_or_else(|| hold_ball(me, s.world))
}

/// agent2d's SampleFieldEvaluator for the ball at `ball` held by this agent (spec 6.3.2).
fn evaluate(s: &Situation, ball: DVec2) -> f64 {
    if ball.x.abs() > PITCH_HALF_LENGTH || ball.y.abs() > PITCH_HALF_WIDTH {
        return f64::NEG_INFINITY;
    }
    if ball.x > 52.4 && ball.y.abs() < 9.01 {
        return 1e7;
    }
    let mut value = ball.x + (40.0 - ball.distance(GOAL_CENTER)).max(0.0);
    if can_shoot_from(ball, s.world.keeper.pos) {
        value += 1.5e6;
    }
    value
}

/// `FieldAnalyzer::can_shoot_from` for this agent (20° clearance) (spec 6.3.2).
pub fn can_shoot_from(from: DVec2, keeper: DVec2) -> bool {
    if from.distance(GOAL_CENTER) > 17.0 {
        return false;
    }
    let left = direction(DVec2::new(PITCH_HALF_LENGTH, -6.51) - from);
    let right = direction(DVec2::new(PITCH_HALF_LENGTH, 6.51) - from);
    let width = (right - left).abs();
    let step = (width / 10.0).max(2f64.to_radians());
    let keeper_dist = keeper.distance(from);
    let keeper_dir = direction(keeper - from);
    let hide = asin_clamped(1.2 / keeper_dist.max(1e-6));
    let threshold = 20f64.to_radians();
    let mut a = left.min(right);
    while a <= left.max(right) + 1e-9 {
        if angle_diff(a, keeper_dir) - hide >= threshold {
            return true;
        }
        a += step;
    }
    false
}

/// Turns needed to rotate by `angle` from speed `speed`, and the leftover angle.
fn turns_for(mut angle: f64, mut speed: f64) -> (usize, f64) {
    let mut n = 0;
    speed *= PLAYER_DECAY; // the first cycle is the kick
    while angle > 10f64.to_radians() {
        angle = (angle - max_turn(speed)).max(0.0);
        speed *= PLAYER_DECAY;
        n += 1;
        if n >= 3 {
            break;
        }
    }
    (n, angle)
}

/// Kick-then-run candidates along body + 22.5°·a for 4, 3 and 2 dashes.
fn kick_candidates<'a>(
    s: &'a Situation<'a>,
    me: &'a Player,
    a: usize,
) -> impl Iterator<Item = Candidate> + 'a {
    let rel_angle = a as f64 * PI / 8.0;
    let folded = if rel_angle > PI {
        2.0 * PI - rel_angle
    } else {
        rel_angle
    };
    let sign = if rel_angle > PI { -1.0 } else { 1.0 };
    let (n_turn, left) = turns_for(folded, me.vel.length());
    let dir = me.body + sign * (folded - left);
    let backward = me.pos.x < 16.0 && normalize_angle(dir).abs() > 100f64.to_radians();
    let ok = n_turn < 3 && !backward;
    [4usize, 3, 2]
        .into_iter()
        .filter(move |_| ok)
        .filter_map(move |n_dash| kick_candidate(s, me, dir, n_turn, n_dash))
}

fn kick_candidate(
    s: &Situation,
    me: &Player,
    dir: f64,
    n_turn: usize,
    n_dash: usize,
) -> Option<Candidate> {
    let ball = &s.world.ball;
    // Kicker after the kick cycle, the turns and the dashes.
    let mut pos = me.pos + me.vel;
    let mut vel = me.vel * PLAYER_DECAY;
    for _ in 0..n_turn {
        pos += vel;
        vel *= PLAYER_DECAY;
    }
    let self_next = me.pos + me.vel;
    let accel = polar(me.effort * MAX_DASH_POWER * DASH_POWER_RATE, dir);
    for _ in 0..n_dash {
        vel = (vel + accel).clamp_length_max(PLAYER_SPEED_MAX);
        pos += vel;
        vel *= PLAYER_DECAY;
    }
    let trap = pos + polar(PLAYER_SIZE + 0.2 * KICKABLE_MARGIN + BALL_SIZE, dir);
    if trap.x.abs() > 51.5 || trap.y.abs() > 33.0 {
        return None;
    }
    let cycles = 1 + n_turn + n_dash;
    let first = (trap - ball.pos) / decay_sum(BALL_DECAY, cycles as u32);
    if first.length() > BALL_SPEED_MAX || (first - ball.vel).length() > max_kick_accel(me, ball.pos)
    {
        return None;
    }
    if (ball.pos + first).distance(self_next) < PLAYER_SIZE + BALL_SIZE + 0.1 {
        return None;
    }
    if keeper_gets_there_first(s, me, trap, dir, cycles) {
        return None;
    }
    Some(Candidate {
        command: kick_to_velocity(me, ball, first)?,
        ball_end: trap,
    })
}

/// Whether the keeper reaches the dribble's end point in time (spec 6.3.1).
fn keeper_gets_there_first(
    s: &Situation,
    me: &Player,
    trap: DVec2,
    dir: f64,
    cycles: usize,
) -> bool {
    let keeper = &s.world.keeper;
    let ball = s.world.ball.pos;
    let behind = (keeper.pos - ball).dot(unit(dir)) < -4.0;
    if keeper.pos.distance(me.pos) > 20.0 || behind {
        return false;
    }
    let control = if in_penalty_area(trap) {
        KEEPER_CONTROL_AREA
    } else {
        KICKABLE_AREA
    };
    let drift = keeper.drift(cycles as u32);
    let dist = drift.distance(trap);
    if dist < control {
        return true;
    }
    let turn = usize::from(angle_diff(direction(trap - drift), keeper.body) > 15f64.to_radians());
    let steps = dash_cycles(dist - 0.5 * control - 0.2) + 2 * turn;
    let bonus = usize::from(trap.x < 30.0);
    steps <= cycles + bonus
}

/// Dash-only carries along the body while the moving ball stays in reach (spec 6.3.1).
fn dash_candidates(s: &Situation) -> impl Iterator<Item = Candidate> + use<> {
    let me = *s.me();
    let ball = s.world.ball;
    let keeper_reach = s.analysis.keeper_reach;
    let mut found: Vec<Candidate> = Vec::new();
    if keeper_reach >= 2 && ball.vel.length() > 0.1 {
        let mut pos = me.pos;
        let mut vel = me.vel;
        let (mut bpos, mut bvel) = (ball.pos, ball.vel);
        let facing = unit(me.body);
        for n in 1..=20usize.min(keeper_reach) {
            bpos += bvel;
            bvel *= BALL_DECAY;
            let near = (0.585 - 0.1 * n as f64).max(PLAYER_SIZE + BALL_SIZE);
            let far = KICKABLE_AREA - 0.15;
            // The largest dash (in 0.05 accel steps) that keeps the ball in the band.
            let max_accel = MAX_DASH_POWER * DASH_POWER_RATE * me.effort;
            let fits = (0..=12)
                .rev()
                .map(|k| k as f64 * 0.05)
                .filter(|&a| a <= max_accel)
                .find_map(|acc| {
                    let v = (vel + facing * acc).clamp_length_max(PLAYER_SPEED_MAX);
                    let d = (pos + v).distance(bpos);
                    (d >= near && d <= far).then_some((acc, v))
                });
            let Some((acc, v)) = fits else { break };
            if bpos.x.abs() > 52.0 || bpos.y.abs() > 33.5 {
                break;
            }
            pos += v;
            vel = v * PLAYER_DECAY;
            if n == 1 {
                found.push(Candidate {
                    command: Command::Dash {
                        power: acc / (DASH_POWER_RATE * me.effort),
                        dir: 0.0,
                    },
                    ball_end: bpos,
                });
            } else if let Some(first) = found.first().copied() {
                found.push(Candidate {
                    ball_end: bpos,
                    ..first
                });
            }
        }
    }
    found.into_iter()
}
