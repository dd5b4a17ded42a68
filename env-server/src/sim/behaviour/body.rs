//! librcsc's basic body behaviours that turn and dash (spec 6.1.5), and
//! agent2d's estimates of the turns and dashes a player needs.

use crate::sim::geom::{angle_diff, asin_clamped, direction, normalize_angle, unit};
use crate::sim::kinematics::{dash_cycles, max_turn};
use crate::sim::params::*;
use crate::sim::physics::Command;
use crate::sim::world::Player;
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// Turn the body to global direction `dir`, compensating for inertia.
pub(super) fn turn_to_direction(p: &Player, dir: f64) -> Command {
    let e = normalize_angle(dir - p.body);
    Command::Turn {
        moment: (e * (1.0 + INERTIA_MOMENT * p.vel.length())).clamp(-PI, PI),
    }
}

/// Turn the body towards `target`, as seen from the player's next position.
pub(super) fn turn_to_point(p: &Player, target: DVec2) -> Command {
    turn_to_direction(p, direction(target - (p.pos + p.vel)))
}

/// Dash that cancels the player's velocity as far as one dash can.
pub(super) fn stop_dash(p: &Player) -> Command {
    let along = p.vel.dot(unit(p.body));
    Command::Dash {
        power: (-along / (DASH_POWER_RATE * p.effort)).clamp(-MAX_DASH_POWER, MAX_DASH_POWER),
        dir: 0.0,
    }
}

/// Body_GoToPoint (spec 6.1.5): a turn or dash towards `target`, or `None`
/// when the player's drift point is already within `tolerance`.
pub(super) fn go_to_point(
    p: &Player,
    target: DVec2,
    tolerance: f64,
    max_power: f64,
) -> Option<Command> {
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

/// agent2d's `FieldAnalyzer::predict_player_turn_cycle` with back dashes
/// allowed, for `player` to face `target_dir` at `dist` within `control`.
pub(super) fn predict_turn_cycles(
    player: &Player,
    target_dir: f64,
    dist: f64,
    control: f64,
) -> usize {
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
pub(super) fn player_reach_cycle(p: &Player, target: DVec2, dist_thr: f64) -> usize {
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
