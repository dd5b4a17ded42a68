//! Server and agent2d constants of the simulated HFO task (spec section 1, 2.2, Appendix A).

use glam::DVec2;

/// Half the pitch length: the attacked goal line is at `x = PITCH_HALF_LENGTH`.
pub const PITCH_HALF_LENGTH: f64 = 52.5;
/// Half the pitch width.
pub const PITCH_HALF_WIDTH: f64 = 34.0;
/// Half the goal width (the goal mouth is `|y| <= GOAL_HALF_WIDTH`).
pub const GOAL_HALF_WIDTH: f64 = 7.01;
/// Depth of the goal behind the goal line.
pub const GOAL_DEPTH: f64 = 2.44;
/// Radius of a goal post.
pub const GOAL_POST_RADIUS: f64 = 0.06;
/// x of the penalty line (52.5 - 16.5).
pub const PENALTY_AREA_X: f64 = 36.0;
/// Half the penalty area width.
pub const PENALTY_AREA_HALF_WIDTH: f64 = 20.16;
/// Goal area length and half width (drawn only).
pub const GOAL_AREA_LENGTH: f64 = 5.5;
/// Half the goal area width (drawn only).
pub const GOAL_AREA_HALF_WIDTH: f64 = 9.16;

/// Centre of the attacked goal.
pub const GOAL_CENTER: DVec2 = DVec2::new(PITCH_HALF_LENGTH, 0.0);
/// Centres of the two goal posts of the attacked goal.
pub const GOAL_POSTS: [DVec2; 2] = [
    DVec2::new(
        PITCH_HALF_LENGTH - GOAL_POST_RADIUS,
        -(GOAL_HALF_WIDTH + GOAL_POST_RADIUS),
    ),
    DVec2::new(
        PITCH_HALF_LENGTH - GOAL_POST_RADIUS,
        GOAL_HALF_WIDTH + GOAL_POST_RADIUS,
    ),
];

/// Ball radius.
pub const BALL_SIZE: f64 = 0.085;
/// Ball velocity decay per cycle.
pub const BALL_DECAY: f64 = 0.94;
/// Ball movement noise rate.
pub const BALL_RAND: f64 = 0.05;
/// Ball speed limit (m/cycle).
pub const BALL_SPEED_MAX: f64 = 3.0;
/// Ball acceleration limit (m/cycle²).
pub const BALL_ACCEL_MAX: f64 = 2.7;

/// Player radius.
pub const PLAYER_SIZE: f64 = 0.3;
/// Player velocity decay per cycle.
pub const PLAYER_DECAY: f64 = 0.4;
/// Player movement noise rate.
pub const PLAYER_RAND: f64 = 0.1;
/// Player speed limit (m/cycle).
pub const PLAYER_SPEED_MAX: f64 = 1.05;
/// Player acceleration limit (m/cycle²).
pub const PLAYER_ACCEL_MAX: f64 = 1.0;
/// Turn inertia moment.
pub const INERTIA_MOMENT: f64 = 5.0;
/// Dash power to acceleration rate.
pub const DASH_POWER_RATE: f64 = 0.006;
/// librcsc's `realSpeedMax` of player type 0: full dashes' top speed (1.0 m/cycle).
pub const REAL_SPEED_MAX: f64 = MAX_DASH_POWER * DASH_POWER_RATE / (1.0 - PLAYER_DECAY);
/// Dash power limit.
pub const MAX_DASH_POWER: f64 = 100.0;
/// Dash directions are rounded to multiples of this angle (radians, 45°).
pub const DASH_ANGLE_STEP: f64 = std::f64::consts::FRAC_PI_4;
/// Rate of a sideways dash.
pub const SIDE_DASH_RATE: f64 = 0.4;
/// Rate of a backward dash.
pub const BACK_DASH_RATE: f64 = 0.6;

/// Kick power to acceleration rate.
pub const KICK_POWER_RATE: f64 = 0.027;
/// Kick power limit.
pub const MAX_KICK_POWER: f64 = 100.0;
/// Kickable margin of player type 0.
pub const KICKABLE_MARGIN: f64 = 0.7;
/// Kick noise rate.
pub const KICK_RAND: f64 = 0.1;
/// Server kickable area, centre to centre (0.3 + 0.7 + 0.085).
pub const KICKABLE_AREA: f64 = PLAYER_SIZE + KICKABLE_MARGIN + BALL_SIZE;
/// The agents' own kickable test (librcsc's buffer of 0.055 under fullstate).
pub const AGENT_KICKABLE_AREA: f64 = KICKABLE_AREA - 0.055;

/// Goalkeeper catch area length.
pub const CATCH_AREA_LENGTH: f64 = 1.2;
/// Goalkeeper catch area half width.
pub const CATCH_AREA_HALF_WIDTH: f64 = 0.5;
/// Cycles during which a new catch is refused.
pub const CATCH_BAN_CYCLES: u32 = 5;
/// agent2d's "catchable area" used for the keeper's reach inside its box.
pub const KEEPER_CONTROL_AREA: f64 = 1.3;

/// Tackle reach in front of the body (rcssserver `tackle_dist`).
pub const TACKLE_DIST: f64 = 2.0;
/// Tackle reach behind the body (`tackle_back_dist`; 0: no tackle backwards).
pub const TACKLE_BACK_DIST: f64 = 0.0;
/// Tackle half width across the body (`tackle_width`).
pub const TACKLE_WIDTH: f64 = 1.25;
/// Exponent of the tackle failure probability (`tackle_exponent`).
pub const TACKLE_EXPONENT: f64 = 6.0;
/// Exponent of a foul tackle's failure probability (`foul_exponent`).
pub const FOUL_EXPONENT: f64 = 10.0;
/// Cycles a tackle freezes its player (`tackle_cycles`), the tackle's own included.
pub const TACKLE_CYCLES: u32 = 10;
/// Tackle power to acceleration rate (`tackle_power_rate`).
pub const TACKLE_POWER_RATE: f64 = 0.027;
/// Tackle power straight ahead (`max_tackle_power`).
pub const MAX_TACKLE_POWER: f64 = 100.0;
/// Tackle power straight backwards (`max_back_tackle_power`).
pub const MAX_BACK_TACKLE_POWER: f64 = 0.0;
/// Tackle noise relative to kick noise (`tackle_rand_factor`).
pub const TACKLE_RAND_FACTOR: f64 = 2.0;

/// Stamina at the start of every episode.
pub const STAMINA_MAX: f64 = 8000.0;
/// Stamina recovered per cycle at full recovery.
pub const STAMINA_INC_MAX: f64 = 45.0;
/// Stamina a dash may use beyond what is left.
pub const EXTRA_STAMINA: f64 = 50.0;
/// Effort bounds.
pub const EFFORT_MIN: f64 = 0.6;
/// Recovery lower bound.
pub const RECOVER_MIN: f64 = 0.5;
/// Stamina below which an attacker enters agent2d's recover mode (spec 6.1.4).
pub const RECOVER_MODE_ENTER: f64 = 4000.0;
/// Stamina above which an attacker leaves agent2d's recover mode.
pub const RECOVER_MODE_LEAVE: f64 = 5600.0;

/// Normalisation box of the offense's own x (spec 1).
pub const FEATURE_X_RANGE: (f64, f64) = (-0.1 * PITCH_HALF_LENGTH, 1.1 * PITCH_HALF_LENGTH);
/// Normalisation box of the offense's own y (spec 1).
pub const FEATURE_Y_RANGE: (f64, f64) = (-1.1 * PITCH_HALF_WIDTH, 1.1 * PITCH_HALF_WIDTH);
/// HFO's largest distance, used to normalise distances: sqrt(52.5² + 34²).
pub const MAX_HFO_DISTANCE: f64 = 62.547_981_582_142_2;

/// Whether `p` lies inside the HFO play area for the ball (`0 <= x <= 52.5`, `|y| <= 34`).
pub(crate) fn in_hfo_area(p: DVec2) -> bool {
    p.x >= 0.0 && p.x <= PITCH_HALF_LENGTH && p.y.abs() <= PITCH_HALF_WIDTH
}

/// Whether `p` lies inside the attacked penalty area.
pub(crate) fn in_penalty_area(p: DVec2) -> bool {
    p.x > PENALTY_AREA_X && p.y.abs() < PENALTY_AREA_HALF_WIDTH
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kickable_areas() {
        assert!((KICKABLE_AREA - 1.085).abs() < 1e-12);
        assert!((AGENT_KICKABLE_AREA - 1.03).abs() < 1e-12);
        assert!((MAX_HFO_DISTANCE - (52.5f64.hypot(34.0))).abs() < 1e-9);
    }
}
