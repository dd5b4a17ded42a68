//! librcsc's basic body behaviours, simplified as spec 6.1.3, 6.1.5 and 6.2.3 allow.

use super::hold::hold_ball;
use super::intercept::best_interception;
use super::kick_table;
use crate::sim::analysis::Analysis;
use crate::sim::geom::{angle_diff, asin_clamped, direction, normalize_angle, unit};
use crate::sim::params::*;
use crate::sim::physics::{Command, kick_for_accel, max_kick_accel};
use crate::sim::self_intercept::SHORT_STEPS;
use crate::sim::world::{Ball, Player, World};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// Turn the body to global direction `dir`, compensating for inertia.
pub fn turn_to_direction(p: &Player, dir: f64) -> Command {
    let e = normalize_angle(dir - p.body);
    Command::Turn {
        moment: (e * (1.0 + INERTIA_MOMENT * p.vel.length())).clamp(-PI, PI),
    }
}

/// Turn the body towards `target`, as seen from the player's next position.
pub fn turn_to_point(p: &Player, target: DVec2) -> Command {
    turn_to_direction(p, direction(target - (p.pos + p.vel)))
}

/// Dash that cancels the player's velocity as far as one dash can.
pub fn stop_dash(p: &Player) -> Command {
    let along = p.vel.dot(unit(p.body));
    Command::Dash {
        power: (-along / (DASH_POWER_RATE * p.effort)).clamp(-MAX_DASH_POWER, MAX_DASH_POWER),
        dir: 0.0,
    }
}

/// Body_GoToPoint (spec 6.1.5): a turn or dash towards `target`, or `None`
/// when the player's drift point is already within `tolerance`.
pub fn go_to_point(p: &Player, target: DVec2, tolerance: f64, max_power: f64) -> Option<Command> {
    let q = p.final_drift();
    let rel = target - q;
    let dist = rel.length();
    if dist < tolerance {
        return None;
    }
    let mut e = normalize_angle(direction(rel) - p.body);
    let back = e.abs() > FRAC_PI_2 && dist < 2.0 && p.stamina > 0.5 * STAMINA_MAX;
    if back {
        e = normalize_angle(e + PI);
    }
    let threshold = 15f64.to_radians().max(asin_clamped(tolerance / dist));
    if e.abs() > threshold {
        return Some(turn_to_direction(p, p.body + e));
    }
    // A dash adds accel/(1 - decay) to the drift distance.
    let accel = (dist * (1.0 - PLAYER_DECAY)).min(PLAYER_ACCEL_MAX);
    if accel < 0.05 {
        return None;
    }
    let power = (accel / (DASH_POWER_RATE * p.effort)).min(max_power);
    Some(Command::Dash {
        power: if back { -power } else { power },
        dir: 0.0,
    })
}

/// Body_Intercept (spec 6.1.3) for offense agent `agent`: towards the
/// interception `getBestIntercept` picks from its cache; `face` is where to
/// look when the ball comes to the player.
///
/// Simplified: from the chosen cycle on, the turn and the full dash follow
/// 6.1.2's others' rule with the own estimate's margin (0.15 m up to cycle
/// 5, 0.2 m later) instead of the cache entry's turns, power and direction
/// and librcsc's `doWaitTurn` and `doInertiaDash`.
pub fn intercept(world: &World, analysis: &Analysis, agent: usize, face: DVec2) -> Command {
    let (p, reach) = (&world.offense[agent], analysis.own_reach[agent]);
    if reach > 100 {
        let rest = world.ball_final();
        return go_to_point(p, rest, 2.0, MAX_DASH_POWER).unwrap_or_else(|| turn_to_point(p, rest));
    }
    let cache = analysis.own_cache(world, agent);
    let cycle = best_interception(p, world, analysis, &cache).map_or(reach, |best| best.cycle);
    let target = analysis.ball_at(cycle);
    let rel = target - p.drift(cycle as u32);
    let d = rel.length();
    // No dash when the ball comes inside the kickable area by the own
    // estimate's margin (`control_area_buf`, and 0.2 m in the long step).
    let margin = if cycle <= SHORT_STEPS { 0.15 } else { 0.2 };
    if d <= KICKABLE_AREA - margin {
        return turn_to_point(p, face);
    }
    let mut e = angle_diff(direction(rel), p.body);
    let back = e > FRAC_PI_2 && d < 5.0;
    if back {
        e = PI - e;
    }
    let threshold = 12f64.to_radians().max(asin_clamped(KICKABLE_AREA / d));
    if e > threshold {
        let to_ball = direction(rel);
        return turn_to_direction(p, if back { to_ball + PI } else { to_ball });
    }
    if p.stamina - MAX_DASH_POWER < 0.3 * STAMINA_MAX + 1.0 {
        return Command::Turn { moment: 0.0 };
    }
    let power = if back {
        -MAX_DASH_POWER
    } else {
        MAX_DASH_POWER
    };
    Command::Dash { power, dir: 0.0 }
}

/// Largest speed along `dir` that one kick can give a ball moving at
/// `ball_vel` with at most `max_accel` (librcsc `calc_max_velocity`).
pub fn max_one_kick_speed(dir: f64, ball_vel: DVec2, max_accel: f64) -> f64 {
    let u = unit(dir);
    let uc = u.dot(ball_vel);
    let disc = uc * uc - ball_vel.length_squared() + max_accel * max_accel;
    if disc < 0.0 {
        return 0.0;
    }
    (uc + disc.sqrt()).clamp(0.0, BALL_SPEED_MAX)
}

/// Kick the ball so that its new velocity is `vel`, if one kick can.
pub fn kick_to_velocity(p: &Player, ball: &Ball, vel: DVec2) -> Option<Command> {
    kick_for_accel(p, ball, vel - ball.vel)
}

/// Body_SmartKick (spec 6.2.3): the first kick of the KickTable's best plan
/// of up to three kicks sending the ball towards `target` at `speed`, if it
/// reaches at least `min_speed`; else hold the ball.
pub fn smart_kick(p: &Player, world: &World, target: DVec2, speed: f64, min_speed: f64) -> Command {
    planned_kick(p, world, target, (speed, min_speed), 3)
        .unwrap_or_else(|| hold_ball(p, world, None, Some(target)))
}

/// Body_SmartKick's kick with plans of at most `max_kicks` kicks, or `None`
/// where it would fail (and hold the ball).
pub fn planned_kick(
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
pub fn kick_one_step(p: &Player, world: &World, target: DVec2, speed: f64) -> Command {
    let ball = &world.ball;
    let dir = direction(target - ball.pos);
    let max = max_one_kick_speed(dir, ball.vel, max_kick_accel(p, ball.pos));
    kick_to_velocity(p, ball, unit(dir) * speed.min(max).min(BALL_SPEED_MAX))
        .unwrap_or_else(|| hold_ball(p, world, Some(target), Some(target)))
}

/// agent2d's `FieldAnalyzer::predict_player_turn_cycle` with back dashes
/// allowed, for `player` to face `target_dir` at `dist` within `control`.
pub fn predict_turn_cycles(player: &Player, target_dir: f64, dist: f64, control: f64) -> usize {
    let mut angle = angle_diff(target_dir, player.body);
    if dist < 5.0 && angle > PI / 2.0 {
        angle = PI - angle;
    }
    let margin = if control < dist {
        15f64.to_radians().max(asin_clamped(control / dist))
    } else {
        PI
    };
    let mut speed = player.vel.length();
    let mut n = 0;
    while angle > margin {
        angle -= max_turn(speed);
        speed *= PLAYER_DECAY;
        n += 1;
    }
    n
}

/// agent2d's `FieldAnalyzer::predict_player_reach_cycle` (no wait, no
/// penalty, back dashes allowed): cycles `p` needs to come within
/// `dist_thr` of `target`. The player's body is taken as seen (librcsc then
/// counts its turns instead of assuming one).
pub fn player_reach_cycle(p: &Player, target: DVec2, dist_thr: f64) -> usize {
    let turns =
        |from: DVec2, dist: f64| predict_turn_cycles(p, direction(target - from), dist, dist_thr);
    let rest = p.final_drift();
    let rest_dist = rest.distance(target);
    let final_cycle = turns(rest, rest_dist) + dash_cycles(rest_dist);
    if final_cycle > 6 {
        return final_cycle;
    }
    for cycle in 0..=6 {
        let drift = p.drift(cycle as u32);
        let dist = drift.distance(target);
        let dash_dist = dist - 0.5 * dist_thr;
        if dist < dist_thr || dash_dist < 0.001 {
            return cycle;
        }
        if dash_dist > REAL_SPEED_MAX * cycle as f64 {
            continue;
        }
        if turns(drift, dist) + dash_cycles(dash_dist) <= cycle {
            return cycle;
        }
    }
    final_cycle
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reach_cycle_of_a_resting_player_follows_the_dash_table() {
        let p = Player::new(DVec2::ZERO, 0.0);
        assert_eq!(
            player_reach_cycle(&p, DVec2::new(0.5, 0.0), KICKABLE_AREA),
            0
        );
        // 4 m ahead: the dashes that cover 4 - 0.54 m (librcsc aims at half
        // the threshold).
        let target = DVec2::new(4.0, 0.0);
        assert_eq!(
            player_reach_cycle(&p, target, KICKABLE_AREA),
            dash_cycles(4.0 - 0.5425)
        );
        // As far behind (within 5 m): backward dashes, no turn.
        assert_eq!(
            player_reach_cycle(&p, -target, KICKABLE_AREA),
            dash_cycles(4.0 - 0.5425)
        );
        // To the side: one turn first; beyond 6 cycles the estimate stays the
        // rough one that dashes the whole distance.
        let side = DVec2::new(0.0, 5.0);
        assert_eq!(
            player_reach_cycle(&p, side, KICKABLE_AREA),
            1 + dash_cycles(5.0)
        );
    }

    #[test]
    fn one_kick_speed_from_rest_is_the_accel_limit() {
        assert!((max_one_kick_speed(0.3, DVec2::ZERO, 2.7) - 2.7).abs() < 1e-12);
        // A ball already moving along the direction can reach the 3.0 cap.
        assert_eq!(max_one_kick_speed(0.0, DVec2::new(1.0, 0.0), 2.7), 3.0);
        // Against the motion only accel - speed remains.
        assert!((max_one_kick_speed(0.0, DVec2::new(-1.0, 0.0), 2.7) - 1.7).abs() < 1e-12);
    }

    #[test]
    fn go_to_point_arrives_within_tolerance() {
        let p = Player::new(DVec2::ZERO, 0.0);
        assert_eq!(go_to_point(&p, DVec2::new(0.5, 0.0), 1.0, 100.0), None);
        assert!(matches!(
            go_to_point(&p, DVec2::new(10.0, 0.0), 1.0, 100.0),
            Some(Command::Dash { power, .. }) if power == 100.0
        ));
        assert!(matches!(
            go_to_point(&p, DVec2::new(0.0, 10.0), 1.0, 100.0),
            Some(Command::Turn { .. })
        ));
    }
}
