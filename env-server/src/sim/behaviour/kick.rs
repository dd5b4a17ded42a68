//! What one kick can do to the ball (librcsc's `calc_max_velocity` and a
//! kick to a wanted ball velocity).

use crate::sim::geom::unit;
use crate::sim::params::*;
use crate::sim::physics::{Command, kick_for_accel};
use crate::sim::world::{Ball, Player};
use glam::DVec2;

/// Largest speed along `dir` that one kick can give a ball moving at
/// `ball_vel` with at most `max_accel` (librcsc `calc_max_velocity`).
pub(super) fn max_one_kick_speed(dir: f64, ball_vel: DVec2, max_accel: f64) -> f64 {
    let u = unit(dir);
    let uc = u.dot(ball_vel);
    let disc = uc * uc - ball_vel.length_squared() + max_accel * max_accel;
    if disc < 0.0 {
        return 0.0;
    }
    (uc + disc.sqrt()).clamp(0.0, BALL_SPEED_MAX)
}

/// Kick the ball so that its new velocity is `vel`, if one kick can.
pub(super) fn kick_to_velocity(p: &Player, ball: &Ball, vel: DVec2) -> Option<Command> {
    kick_for_accel(p, ball, vel - ball.vel)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_kick_speed_from_rest_is_the_accel_limit() {
        assert!((max_one_kick_speed(0.3, DVec2::ZERO, 2.7) - 2.7).abs() < 1e-12);
        // A ball already moving along the direction can reach the 3.0 cap.
        assert_eq!(max_one_kick_speed(0.0, DVec2::new(1.0, 0.0), 2.7), 3.0);
        // Against the motion only accel - speed remains.
        assert!((max_one_kick_speed(0.0, DVec2::new(-1.0, 0.0), 2.7) - 1.7).abs() < 1e-12);
    }
}
