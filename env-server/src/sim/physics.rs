//! The server's command models and movement step (spec sections 2 and 3).

use crate::sim::geom::{angle_diff, direction, normalize_angle, polar, polar_noise, uniform, unit};
use crate::sim::params::*;
use crate::sim::world::{Ball, Player, World};
use glam::DVec2;
use rand::Rng;
use std::f64::consts::PI;

/// One player's body command for a cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Command {
    /// No body command.
    #[default]
    None,
    /// Dash.
    Dash {
        /// Power, `-100..=100` (negative: backwards).
        power: f64,
        /// Direction, radians relative to the body.
        dir: f64,
    },
    /// Turn.
    Turn {
        /// Moment, radians.
        moment: f64,
    },
    /// Kick.
    Kick {
        /// Power, `0..=100`.
        power: f64,
        /// Direction, radians relative to the body.
        dir: f64,
    },
    /// Goalkeeper catch aimed at the ball.
    Catch,
    /// Tackle.
    Tackle {
        /// Direction, radians relative to the body.
        dir: f64,
        /// Whether to ask for the server's foul tackle (spec 3.5).
        foul: bool,
    },
}

/// Effective kick power per unit of power for `player` and the ball at `ball` (spec 3.1).
pub(crate) fn kick_rate(player: &Player, ball: DVec2) -> f64 {
    let rel = ball - player.pos;
    let dir_diff = angle_diff(direction(rel), player.body);
    let dist_ball = (rel.length() - PLAYER_SIZE - BALL_SIZE).max(0.0);
    KICK_POWER_RATE * (1.0 - 0.25 * dir_diff / PI - 0.25 * dist_ball / KICKABLE_MARGIN)
}

/// Largest change of ball velocity one kick can make (`min(100·rate, 2.7)`).
pub(crate) fn max_kick_accel(player: &Player, ball: DVec2) -> f64 {
    (MAX_KICK_POWER * kick_rate(player, ball)).min(BALL_ACCEL_MAX)
}

/// The kick command that changes the ball velocity by `accel`, if one kick can.
pub(crate) fn kick_for_accel(player: &Player, ball: &Ball, accel: DVec2) -> Option<Command> {
    let rate = kick_rate(player, ball.pos);
    let power = accel.length() / rate;
    if power > MAX_KICK_POWER + 1e-9 || accel.length() > BALL_ACCEL_MAX + 1e-9 {
        return None;
    }
    Some(Command::Kick {
        power: power.min(MAX_KICK_POWER),
        dir: normalize_angle(direction(accel) - player.body),
    })
}

/// Applies a kick to the ball's pending acceleration; nothing if the ball is out of reach.
pub(crate) fn kick(
    player: &Player,
    ball: &Ball,
    accel: &mut DVec2,
    power: f64,
    dir: f64,
    rng: &mut impl Rng,
) {
    let rel = ball.pos - player.pos;
    if rel.length() > KICKABLE_AREA {
        return;
    }
    let power = power.clamp(-MAX_KICK_POWER, MAX_KICK_POWER);
    let dir = dir.clamp(-PI, PI);
    let dir_diff = angle_diff(direction(rel), player.body);
    let dist_ball = (rel.length() - PLAYER_SIZE - BALL_SIZE).max(0.0);
    let eff = power * kick_rate(player, ball.pos);
    let pos_rate = 0.5 + 0.25 * (dir_diff / PI + dist_ball / KICKABLE_MARGIN);
    let speed_rate = 0.5 + 0.5 * ball.vel.length() / (BALL_SPEED_MAX * BALL_DECAY);
    let max_rand = KICK_RAND * (power.abs() / MAX_KICK_POWER) * (pos_rate + speed_rate);
    *accel += polar(eff, player.body + dir) + polar_noise(rng, max_rand);
}

/// Success probability of a tackle by `player` on the ball at `ball` with the
/// failure exponent `exponent` (rcssserver `Player::tackle`, spec 3.5):
/// `1 - (bx/2)^e - (|by|/1.25)^e` with the ball in body coordinates, 0 behind.
pub(crate) fn tackle_probability(player: &Player, ball: DVec2, exponent: f64) -> f64 {
    let rel = ball - player.pos;
    // Beyond sqrt(TACKLE_DIST² + TACKLE_WIDTH²) ≈ 2.36 m one term of the
    // failure is at least 1 whatever the body angle: skip the rotation.
    if rel.length_squared() > 6.0 {
        return 0.0;
    }
    tackle_probability_at(rel.rotate(unit(-player.body)), exponent)
}

/// [`tackle_probability`] of a ball at `rel` in the tackler's body coordinates.
pub(crate) fn tackle_probability_at(rel: DVec2, exponent: f64) -> f64 {
    let reach = if rel.x > 0.0 {
        TACKLE_DIST
    } else {
        TACKLE_BACK_DIST
    };
    // A term of at least 1 fails the tackle: no need for the powers.
    if reach <= 1e-5 || rel.x.abs() >= reach || rel.y.abs() >= TACKLE_WIDTH {
        return 0.0;
    }
    let fail =
        libm::pow(rel.x.abs() / reach, exponent) + libm::pow(rel.y.abs() / TACKLE_WIDTH, exponent);
    (1.0 - fail).max(0.0)
}

/// Noise-free ball acceleration of a successful tackle towards `dir`
/// (relative to the body): the protocol v14 model of `Player::tackle` (spec 3.5).
pub(crate) fn tackle_accel(player: &Player, ball: DVec2, dir: f64) -> DVec2 {
    let dir = normalize_angle(dir);
    let power =
        MAX_BACK_TACKLE_POWER + (MAX_TACKLE_POWER - MAX_BACK_TACKLE_POWER) * (1.0 - dir.abs() / PI);
    let ball_angle = angle_diff(direction(ball - player.pos), player.body);
    let eff = power * TACKLE_POWER_RATE * (1.0 - 0.5 * ball_angle / PI);
    polar(eff, player.body + dir)
}

/// Executes `player`'s tackle towards `dir` (rcssserver `Player::tackle`, spec 3.5):
/// freezes the player for [`TACKLE_CYCLES`] and, with the success probability,
/// adds the push and its noise to the ball's pending acceleration. A `foul`
/// tackle uses [`FOUL_EXPONENT`] and leaves the player free if an opponent
/// (`opponent_kickable`) can kick the ball. Returns whether the ball was hit.
pub(crate) fn tackle(
    player: &mut Player,
    ball: &Ball,
    accel: &mut DVec2,
    (dir, foul): (f64, bool),
    opponent_kickable: bool,
    rng: &mut impl Rng,
) -> bool {
    player.tackle_freeze = TACKLE_CYCLES;
    let foul = foul && opponent_kickable;
    let exponent = if foul { FOUL_EXPONENT } else { TACKLE_EXPONENT };
    let success = tackle_probability(player, ball.pos, exponent);
    if success <= 0.0 || uniform(rng, 0.0, 1.0) >= success {
        return false;
    }
    if foul {
        player.tackle_freeze = 0;
    }
    let pos_rate = 0.5 + 0.5 * success;
    let speed_rate = 0.5 + 0.5 * ball.vel.length() / (BALL_SPEED_MAX * BALL_DECAY);
    let max_rand = KICK_RAND * TACKLE_RAND_FACTOR * (pos_rate + speed_rate);
    *accel += tackle_accel(player, ball.pos, dir) + polar_noise(rng, max_rand);
    true
}

/// Applies a dash: spends stamina and adds to the player's pending acceleration (spec 3.2).
pub(crate) fn dash(player: &mut Player, accel: &mut DVec2, power: f64, dir: f64) {
    let mut power = power.clamp(-MAX_DASH_POWER, MAX_DASH_POWER);
    let available = player.stamina + EXTRA_STAMINA;
    if power < 0.0 {
        power = power.max(-available / 2.0);
        player.stamina = (player.stamina + 2.0 * power).max(0.0);
    } else {
        power = power.min(available);
        player.stamina = (player.stamina - power).max(0.0);
    }
    // The rate depends on the requested direction; a negative power then pushes backwards.
    let dir = dash_dir(dir);
    let eff = player.effort * power * dash_dir_rate(dir) * DASH_POWER_RATE;
    *accel += polar(eff, player.body + dir);
}

/// A dash direction (radians, relative to the body) as the server rounds it
/// to a multiple of 45°.
pub(crate) fn dash_dir(dir: f64) -> f64 {
    (dir.clamp(-PI, PI) / DASH_ANGLE_STEP).round() * DASH_ANGLE_STEP
}

/// The share of a dash's power that a dash towards `dir` (radians, relative
/// to the body) keeps: 1 forward, 0.4 sideways, 0.6 backwards.
pub(crate) fn dash_dir_rate(dir: f64) -> f64 {
    let a = dash_dir(dir).abs().to_degrees();
    if a <= 90.0 {
        SIDE_DASH_RATE + (1.0 - SIDE_DASH_RATE) * (1.0 - a / 90.0)
    } else {
        BACK_DASH_RATE - (BACK_DASH_RATE - SIDE_DASH_RATE) * (1.0 - (a - 90.0) / 90.0)
    }
    .clamp(0.0, 1.0)
}

/// Applies a turn with the server's ±10% noise and speed-dependent inertia (spec 3.3).
pub(crate) fn turn(player: &mut Player, moment: f64, rng: &mut impl Rng) {
    let moment = moment.clamp(-PI, PI) * (1.0 + uniform(rng, -0.1, 0.1));
    player.body =
        normalize_angle(player.body + moment / (1.0 + INERTIA_MOMENT * player.vel.length()));
}

/// Goalkeeper catch (spec 3.4) in agent2d's direction, which puts the catch
/// area's diagonal on the ball (librcsc `ActionEffector::setCatch`): on
/// success the keeper steps next to the ball, faces it and stops. Returns
/// whether it succeeded.
pub(crate) fn catch(world: &mut World) -> bool {
    if world.catch_ban > 0 {
        return false;
    }
    world.catch_ban = CATCH_BAN_CYCLES;
    let rel = world.ball.pos - world.keeper.pos;
    let dist = rel.length();
    let diagonal = libm::atan2(CATCH_AREA_HALF_WIDTH, CATCH_AREA_LENGTH);
    let in_area = rel.rotate(unit(-(direction(rel) + diagonal)));
    if !(0.0..=CATCH_AREA_LENGTH).contains(&in_area.x) || in_area.y.abs() > CATCH_AREA_HALF_WIDTH {
        return false;
    }
    let gap = PLAYER_SIZE + BALL_SIZE;
    if dist > gap {
        world.keeper.pos += rel * ((dist - gap) / dist);
    }
    world.keeper.body = direction(rel);
    world.keeper.vel = DVec2::ZERO;
    true
}

/// Kinematic constants of one kind of moving object.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyConstants {
    /// Radius.
    pub(crate) size: f64,
    /// Acceleration limit.
    pub(crate) accel_max: f64,
    /// Speed limit.
    pub(crate) speed_max: f64,
    /// Movement noise rate.
    pub(crate) rand: f64,
    /// Velocity decay.
    pub(crate) decay: f64,
}

/// The ball's constants.
pub(crate) const BALL_BODY: BodyConstants = BodyConstants {
    size: BALL_SIZE,
    accel_max: BALL_ACCEL_MAX,
    speed_max: BALL_SPEED_MAX,
    rand: BALL_RAND,
    decay: BALL_DECAY,
};

/// A player's constants.
pub(crate) const PLAYER_BODY: BodyConstants = BodyConstants {
    size: PLAYER_SIZE,
    accel_max: PLAYER_ACCEL_MAX,
    speed_max: PLAYER_SPEED_MAX,
    rand: PLAYER_RAND,
    decay: PLAYER_DECAY,
};

/// Moves one object by one cycle (spec 2.1 step 3): clipped acceleration, speed
/// limit, noise, goal posts, position, decay.
pub(crate) fn move_object(
    pos: &mut DVec2,
    vel: &mut DVec2,
    accel: DVec2,
    body: BodyConstants,
    rng: &mut impl Rng,
) {
    if accel != DVec2::ZERO {
        *vel += accel.clamp_length_max(body.accel_max);
        *vel = vel.clamp_length_max(body.speed_max);
    }
    *vel += polar_noise(rng, body.rand * vel.length());
    let step = bounce_off_posts(pos, vel, body.size);
    *pos += step;
    *vel *= body.decay;
}

/// Goal-post handling (spec 2.3): returns this cycle's displacement after an
/// elastic bounce off the nearest post, updating `pos`/`vel` as needed.
fn bounce_off_posts(pos: &mut DVec2, vel: &mut DVec2, size: f64) -> DVec2 {
    if (pos.x - GOAL_POSTS[0].x).abs() > 5.0 {
        return *vel;
    }
    let post = if pos.y < 0.0 {
        GOAL_POSTS[0]
    } else {
        GOAL_POSTS[1]
    };
    let r = GOAL_POST_RADIUS + size;
    let rel = *pos - post;
    let dist = rel.length();
    if dist < r {
        let normal = if dist > 0.0 { rel / dist } else { DVec2::X };
        *pos = post + normal * r;
        let towards = vel.dot(normal);
        if towards < 0.0 {
            *vel -= normal * (2.0 * towards);
        }
        return *vel;
    }
    // First intersection of the segment pos -> pos + vel with the circle.
    let a = vel.length_squared();
    if a == 0.0 {
        return *vel;
    }
    let b = 2.0 * rel.dot(*vel);
    let c = rel.length_squared() - r * r;
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return *vel;
    }
    let t = (-b - disc.sqrt()) / (2.0 * a);
    if !(0.0..=1.0).contains(&t) {
        return *vel;
    }
    let hit = *pos + *vel * t;
    let normal = (hit - post) / r;
    let mirror = |v: DVec2| v - normal * (2.0 * v.dot(normal));
    let rest = mirror(*vel * (1.0 - t));
    *vel = mirror(*vel);
    hit + rest - *pos
}

/// Separates overlapping ball-player and player-player pairs and damps every
/// object that collided (`v <- -0.1·v`) (spec 2.3).
pub(crate) fn resolve_collisions(world: &mut World, rng: &mut impl Rng) {
    let n = world.offense.len() + 1;
    // Object 0 is the ball, 1..n the offense, n the keeper.
    let mut collided = [false; 16];
    for _ in 0..10 {
        let mut any = false;
        for a in 0..=n {
            for b in (a + 1)..=n {
                let (ra, rb) = (object_size(a), object_size(b));
                let (pa, pb) = (object_pos(world, a), object_pos(world, b));
                let d = pa.distance(pb);
                if d >= ra + rb {
                    continue;
                }
                any = true;
                collided[a] = true;
                collided[b] = true;
                let mid = (pa + pb) * 0.5;
                let dir = if d > 1e-9 {
                    (pa - pb) / d
                } else {
                    polar(1.0, uniform(rng, -PI, PI))
                };
                let half = (ra + rb) * 0.5;
                *object_pos_mut(world, a) = mid + dir * half;
                *object_pos_mut(world, b) = mid - dir * half;
            }
        }
        if !any {
            break;
        }
    }
    for (i, hit) in collided.iter().enumerate().take(n + 1) {
        if *hit {
            *object_vel_mut(world, i) *= -0.1;
        }
    }
}

fn object_size(i: usize) -> f64 {
    if i == 0 { BALL_SIZE } else { PLAYER_SIZE }
}

fn object_pos(world: &World, i: usize) -> DVec2 {
    match i {
        0 => world.ball.pos,
        i if i <= world.offense.len() => world.offense[i - 1].pos,
        _ => world.keeper.pos,
    }
}

fn object_pos_mut(world: &mut World, i: usize) -> &mut DVec2 {
    match i {
        0 => &mut world.ball.pos,
        i if i <= world.offense.len() => &mut world.offense[i - 1].pos,
        _ => &mut world.keeper.pos,
    }
}

fn object_vel_mut(world: &mut World, i: usize) -> &mut DVec2 {
    match i {
        0 => &mut world.ball.vel,
        i if i <= world.offense.len() => &mut world.offense[i - 1].vel,
        _ => &mut world.keeper.vel,
    }
}

/// End-of-cycle stamina, effort and recovery update (spec 2.4).
pub(crate) fn update_stamina(p: &mut Player) {
    if p.stamina <= 0.3 * STAMINA_MAX {
        p.recovery = (p.recovery - 0.002).max(RECOVER_MIN);
        p.effort = (p.effort - 0.005).max(EFFORT_MIN);
    }
    if p.stamina >= 0.6 * STAMINA_MAX {
        p.effort = (p.effort + 0.01).min(1.0);
    }
    p.stamina += (p.recovery * STAMINA_INC_MAX).min(STAMINA_MAX - p.stamina);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn kick_rate_spans_spec_range() {
        let p = Player::new(DVec2::ZERO, 0.0);
        // Ball touching the front of the body: full rate 0.027 -> 2.7 at power 100.
        let front = DVec2::new(PLAYER_SIZE + BALL_SIZE, 0.0);
        assert!((kick_rate(&p, front) - 0.027).abs() < 1e-12);
        // Ball at the edge of the kickable area behind: rate halves -> 1.35.
        let back = DVec2::new(-KICKABLE_AREA, 0.0);
        assert!((100.0 * kick_rate(&p, back) - 1.35).abs() < 1e-9);
    }

    #[test]
    fn full_dashes_reach_one_metre_per_cycle() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let mut p = Player::new(DVec2::ZERO, 0.0);
        let body = BodyConstants {
            rand: 0.0,
            ..PLAYER_BODY
        };
        for _ in 0..10 {
            let mut a = DVec2::ZERO;
            dash(&mut p, &mut a, 100.0, 0.0);
            move_object(&mut p.pos, &mut p.vel, a, body, &mut rng);
        }
        assert!((p.pos.x - 9.333).abs() < 0.01, "{}", p.pos.x);
    }

    #[test]
    fn backward_dash_is_as_strong_as_forward_and_costs_double() {
        let mut p = Player::new(DVec2::ZERO, 0.0);
        let mut a = DVec2::ZERO;
        dash(&mut p, &mut a, -100.0, 0.0);
        assert!((a.x + 0.6).abs() < 1e-12 && a.y.abs() < 1e-12);
        assert_eq!(p.stamina, STAMINA_MAX - 200.0);
        let mut side = DVec2::ZERO;
        dash(&mut p, &mut side, 100.0, FRAC_PI_2);
        assert!((side.y - 0.6 * SIDE_DASH_RATE).abs() < 1e-12);
    }

    #[test]
    fn tackle_probability_has_exponent_six_both_ways_and_no_back_tackle() {
        let p = Player::new(DVec2::ZERO, FRAC_PI_2);
        let at = |x: f64, y: f64| p.pos + DVec2::new(x, y).rotate(unit(p.body));
        let prob = |x, y| tackle_probability(&p, at(x, y), TACKLE_EXPONENT);
        assert!((prob(1.0, 0.0) - (1.0 - 0.5f64.powi(6))).abs() < 1e-12);
        assert!((prob(0.2, 0.625) - (1.0 - 0.1f64.powi(6) - 0.5f64.powi(6))).abs() < 1e-12);
        assert!((prob(1.0, 0.625) - (1.0 - 2.0 * 0.5f64.powi(6))).abs() < 1e-12);
        assert_eq!(prob(2.0, 0.0), 0.0);
        assert_eq!(prob(-0.5, 0.0), 0.0);
        let foul = tackle_probability(&p, at(1.0, 0.0), FOUL_EXPONENT);
        assert!((foul - (1.0 - 0.5f64.powi(10))).abs() < 1e-12);
    }

    #[test]
    fn tackle_push_shrinks_with_direction_and_ball_angle() {
        let p = Player::new(DVec2::ZERO, 0.0);
        let ahead = DVec2::new(1.0, 0.0);
        assert!((tackle_accel(&p, ahead, 0.0) - DVec2::new(2.7, 0.0)).length() < 1e-12);
        let side = tackle_accel(&p, ahead, FRAC_PI_2);
        assert!((side - DVec2::new(0.0, 1.35)).length() < 1e-12);
        assert!(tackle_accel(&p, ahead, PI).length() < 1e-12);
        // Ball 90° off the body: three quarters of the push.
        let beside = DVec2::new(0.0, 1.0);
        assert!((tackle_accel(&p, beside, 0.0).x - 2.025).abs() < 1e-12);
    }

    #[test]
    fn tackle_freezes_its_player_unless_a_foul_succeeds() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let ball = Ball {
            pos: DVec2::new(0.5, 0.0),
            vel: DVec2::ZERO,
        };
        let mut p = Player::new(DVec2::ZERO, 0.0);
        let mut accel = DVec2::ZERO;
        assert!(tackle(
            &mut p,
            &ball,
            &mut accel,
            (0.0, false),
            true,
            &mut rng
        ));
        assert_eq!(p.tackle_freeze, TACKLE_CYCLES);
        // Noise at most 0.1·2·(pos_rate + speed_rate) around the 2.7 push.
        assert!((accel - DVec2::new(2.7, 0.0)).length() <= 0.2 * (1.0 + 0.5) + 1e-9);
        let behind = Ball {
            pos: DVec2::new(-0.5, 0.0),
            ..ball
        };
        let mut q = Player::new(DVec2::ZERO, 0.0);
        let mut none = DVec2::ZERO;
        assert!(!tackle(
            &mut q,
            &behind,
            &mut none,
            (0.0, false),
            true,
            &mut rng
        ));
        assert_eq!((q.tackle_freeze, none), (TACKLE_CYCLES, DVec2::ZERO));
        assert!(tackle(
            &mut q,
            &ball,
            &mut none,
            (0.0, true),
            true,
            &mut rng
        ));
        assert_eq!(q.tackle_freeze, 0);
        assert!(tackle(
            &mut q,
            &ball,
            &mut none,
            (0.0, true),
            false,
            &mut rng
        ));
        assert_eq!(q.tackle_freeze, TACKLE_CYCLES);
    }

    #[test]
    fn the_catch_reaches_the_area_diagonal_of_1_3_m() {
        let catch_at = |dist: f64| {
            let mut w = World::new(1);
            w.keeper = Player::new(DVec2::new(48.0, 0.0), 2.0);
            w.ball.pos = w.keeper.pos + polar(dist, -0.7);
            w.ball.vel = DVec2::new(0.5, 0.0);
            (catch(&mut w), w)
        };
        let (caught, w) = catch_at(1.28);
        assert!(caught);
        assert!((w.keeper.pos.distance(w.ball.pos) - (PLAYER_SIZE + BALL_SIZE)).abs() < 1e-9);
        assert_eq!(w.keeper.vel, DVec2::ZERO);
        assert_eq!(w.ball.vel, DVec2::new(0.5, 0.0), "the ball is not stopped");
        let (caught, w) = catch_at(1.32);
        assert!(!caught);
        assert_eq!(w.catch_ban, CATCH_BAN_CYCLES);
    }

    #[test]
    fn ball_bounces_off_post() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let post = GOAL_POSTS[1];
        let mut pos = post - DVec2::new(1.0, 0.0);
        let mut vel = DVec2::new(2.0, 0.0);
        let body = BodyConstants {
            rand: 0.0,
            ..BALL_BODY
        };
        move_object(&mut pos, &mut vel, DVec2::ZERO, body, &mut rng);
        assert!(vel.x < 0.0);
        assert!(pos.distance(post) >= GOAL_POST_RADIUS + BALL_SIZE - 1e-9);
    }
}
