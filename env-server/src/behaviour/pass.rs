//! PASS (spec 6.4): the best safe direct, lead or through pass to a
//! teammate, or no command when there is none.

use super::Situation;
use super::body::smart_kick;
use crate::geom::{angle_diff, direction, polar, unit};
use crate::params::*;
use crate::physics::{Command, kick_rate};
use crate::world::Player;
use glam::DVec2;

/// A pass route: receive point and first speed.
#[derive(Clone, Copy, Debug)]
struct Route {
    target: DVec2,
    speed: f64,
}

/// The PASS command of a kickable agent; `receiver` restricts the routes to
/// one teammate (HFO itself ignores the requested receiver).
pub fn command(s: &Situation, receiver: Option<usize>) -> Command {
    let mut best: Option<(f64, Route)> = None;
    let mut consider = |route: Route| {
        let score = score(s, route);
        if best.is_none_or(|(b, _)| score > b) {
            best = Some((score, route));
        }
    };
    let ball = s.world.ball.pos;
    for (j, mate) in s.world.offense.iter().enumerate() {
        if j == s.agent || receiver.is_some_and(|r| r != j) {
            continue;
        }
        if mate.pos.x > s.world.offside_line + 1.0 || mate.pos.x < ball.x - 25.0 {
            continue;
        }
        direct_passes(s, mate, &mut consider);
        lead_passes(s, mate, &mut consider);
        through_passes(s, mate, &mut consider);
    }
    match best {
        Some((_, r)) => smart_kick(s.me(), s.world, r.target, r.speed, 0.96 * r.speed),
        None => Command::None,
    }
}

/// Cycles a ball kicked at `speed` needs to travel `dist` (infinite if it stops short).
fn ball_cycles(dist: f64, speed: f64) -> f64 {
    let ratio = 0.06 * dist / speed;
    if ratio >= 1.0 {
        f64::INFINITY
    } else {
        (1.0 - ratio).ln() / BALL_DECAY.ln()
    }
}

/// Whether the keeper can cut the ball's path to `target` (`verify_direct_pass` path test).
fn keeper_near_path(s: &Situation, target: DVec2, speed: f64) -> bool {
    let ball = s.world.ball.pos;
    let keeper = s.world.keeper.pos;
    let dir = direction(target - ball);
    if angle_diff(direction(keeper - ball), dir) > 100f64.to_radians() {
        return false;
    }
    let origin = ball + polar(speed, dir);
    let u = unit(dir);
    let rel = keeper - origin;
    let along = rel.dot(u);
    let length = target.distance(origin);
    if along <= 0.0 || along >= length {
        return false;
    }
    let across = rel.perp_dot(u).abs() - KICKABLE_AREA - 0.1;
    across < 0.0 || across <= ball_cycles(along + speed, speed)
}

/// `create_direct_pass` (spec 6.4 step 2).
fn direct_passes(s: &Situation, mate: &Player, consider: &mut impl FnMut(Route)) {
    let me = s.me();
    let ball = s.world.ball.pos;
    let r = mate.pos;
    let d_self = r.distance(me.pos);
    if r.x.abs() > 49.5 || r.y.abs() > 31.0 || !(6.0..=40.0).contains(&d_self) {
        return;
    }
    if r.x < me.pos.x + 5.0 {
        let defense_line = s
            .world
            .offense
            .iter()
            .map(|p| p.pos.x)
            .fold(ball.x.min(0.0), f64::min);
        let forward = direction(r - me.pos).abs() < 40f64.to_radians();
        let behind_defence = r.x > defense_line + 10.0 && r.x > 0.0;
        if !(forward || behind_defence) {
            return;
        }
    }
    let receive = mate.final_drift();
    let dist = receive.distance(ball);
    let Some(speed) = (0..=6)
        .map(|k| 1.5 - 0.1 * k as f64)
        .map(|end| end + 0.0638 * dist)
        .find(|&v0| v0 <= BALL_SPEED_MAX)
    else {
        return;
    };
    let keeper = s.world.keeper.pos;
    if keeper.distance(receive) < 3.0 {
        return;
    }
    let spread = KICKABLE_AREA / dist;
    let base = direction(receive - ball);
    let aims = [
        (0.0, speed),
        (spread, 0.94 * speed),
        (-spread, 0.94 * speed),
    ];
    for (offset, v0) in aims {
        let target = ball + polar(dist, base + offset);
        if !keeper_near_path(s, target, v0) {
            consider(Route { target, speed: v0 });
        }
    }
}

/// `create_lead_pass` (spec 6.4 step 3).
fn lead_passes(s: &Situation, mate: &Player, consider: &mut impl FnMut(Route)) {
    let me = s.me();
    let ball = s.world.ball.pos;
    let r = mate.pos;
    let d_self = r.distance(me.pos);
    if !(2.0..=35.0).contains(&d_self) || (r.x < me.pos.x - 15.0 && r.x < 15.0) {
        return;
    }
    let dist = r.distance(ball);
    let base = direction(r - ball);
    let step = 5f64.to_radians().max(2.0 / dist);
    for k in 1..=5 {
        if k as f64 * step >= 31f64.to_radians() {
            break;
        }
        let Some(speed) = (0..10)
            .map(|i| 1.2 - 0.11 * (k - 1) as f64 - 0.1 * i as f64)
            .take_while(|&end| end > 0.5)
            .map(|end| end + 0.0638 * dist)
            .find(|&v0| v0 < BALL_SPEED_MAX)
        else {
            continue;
        };
        for sign in [-1.0, 1.0] {
            let target = ball + polar(dist, base + sign * k as f64 * step);
            let behind_self_or_mate = target.x < me.pos.x.min(r.x);
            if !inside_shrunk_pitch(target)
                || target.x < r.x - 6.0
                || (target.x < 0.0 && behind_self_or_mate)
            {
                continue;
            }
            if through_pass_safe(s, mate, target, speed) {
                consider(Route { target, speed });
            }
        }
    }
}

/// `create_through_pass` (spec 6.4 step 4).
fn through_passes(s: &Situation, mate: &Player, consider: &mut impl FnMut(Route)) {
    let me = s.me();
    let ball = s.world.ball.pos;
    let r = mate.pos;
    let line = s.world.offside_line;
    if r.x > line - 0.5
        || r.x < me.pos.x - 10.0
        || (r.y - me.pos.y).abs() > 35.0
        || direction(r - me.pos).abs() > 135f64.to_radians()
        || (line < 30.0 && r.x < line - 15.0)
    {
        return;
    }
    for theta in [-20.0f64, -10.0, 0.0, 10.0, 20.0] {
        for l in [5.0, 9.0, 13.0, 17.0, 21.0, 25.0] {
            let target = r + polar(l, theta.to_radians());
            let dist = target.distance(ball);
            if !inside_shrunk_pitch(target) || target.x < me.pos.x + 3.0 || dist > 45.0 || dist < l
            {
                continue;
            }
            let receiver_cycles = target.distance(r);
            let speed = (0..4)
                .map(|i| 0.81 - 0.1 * i as f64)
                .map(|end| end + 0.0638 * dist)
                .find(|&v0| v0 <= BALL_SPEED_MAX && receiver_cycles <= ball_cycles(dist, v0));
            if let Some(speed) = speed
                && through_pass_safe(s, mate, target, speed)
            {
                consider(Route { target, speed });
            }
        }
    }
}

fn inside_shrunk_pitch(p: DVec2) -> bool {
    p.x.abs() <= PITCH_HALF_LENGTH - 3.0 && p.y.abs() <= PITCH_HALF_WIDTH - 3.0
}

/// `verify_through_pass` (spec 6.4 step 5).
fn through_pass_safe(s: &Situation, mate: &Player, target: DVec2, speed: f64) -> bool {
    let ball = s.world.ball.pos;
    let line = s.world.offside_line;
    let keeper = s.world.keeper.pos;
    if target.x < 38.0 || target.y.abs() > 37.32 {
        return true;
    }
    let very_aggressive = (target.x > 28.0 && target.x > ball.x + 20.0)
        || (target.x > line + 15.0 && target.x > ball.x + 15.0)
        || (target.x > 38.0 && target.x > line && target.y.abs() < 14.0);
    let (rate, buf) = if very_aggressive {
        (0.8, 0.5)
    } else {
        (1.0, 2.0)
    };
    keeper.distance(target) >= rate * mate.pos.distance(target) + buf
        && !keeper_near_path(s, target, speed)
}

/// `evaluate_routes` (spec 6.4 step 6), with every direction counted as just seen.
fn score(s: &Situation, route: Route) -> f64 {
    let me = s.me();
    let ball = &s.world.ball;
    let keeper = s.world.keeper.pos;
    let q = route.target;
    let d_opp = keeper.distance(q);
    let mut score = 1000.0
        * 0.99f64.powf((30.0 - d_opp).max(0.0))
        * 0.98f64.powf((30.0 - (q.x - me.pos.x)).max(0.0))
        * 0.98f64.powf((q.y - ball.pos.y).abs().max(5.0));
    if d_opp < 10.0 && direction(keeper - q).abs() < 45f64.to_radians() {
        score *= 0.95;
    }
    let first = polar(route.speed, direction(q - ball.pos));
    if (first - ball.vel).length() < MAX_KICK_POWER * kick_rate(me, ball.pos) {
        score *= 1.2;
    }
    score
}
