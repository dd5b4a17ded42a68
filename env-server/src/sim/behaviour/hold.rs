//! librcsc's Body_HoldBall2008 (spec 6.3.4): keep the ball within the
//! kickable area, out of the keeper's reach. In order: kick it to the side
//! away from a kick target, turn to the front while the ball stays, kick it
//! to the front of the body, kick it to the best of 60 keep points around the
//! body, else stop it.

use super::body::turn_to_point;
use super::kick_table::rate_at;
use crate::sim::geom::{angle_diff, direction, normalize_angle, polar, unit};
use crate::sim::params::*;
use crate::sim::physics::{Command, kick_rate, tackle_probability_at};
use crate::sim::world::{Player, World};
use glam::DVec2;

/// The score of a keep point no opponent threatens.
const SAFE: f64 = 100.0;
/// Keep points stay this far inside the pitch.
const PITCH_MAX: DVec2 = DVec2::new(PITCH_HALF_LENGTH - 0.2, PITCH_HALF_WIDTH - 0.2);
/// Where a holder with nothing better to face turns to.
const FACE_POINT: DVec2 = DVec2::new(PITCH_HALF_LENGTH - 5.0, 0.0);

/// Body_HoldBall2008 of a kickable `p`: `face` is the point it turns to
/// (`do_turn`), `kick_target` where a kick would go next (the ball is kept
/// on the other side).
pub(super) fn hold_ball(
    p: &Player,
    world: &World,
    face: Option<DVec2>,
    kick_target: Option<DVec2>,
) -> Command {
    let hold = Hold::new(p, world);
    kick_target
        .and_then(|target| hold.keep_reverse(target))
        .or_else(|| hold.turn_to_face(face.unwrap_or(FACE_POINT)))
        .or_else(|| hold.keep_front())
        .or_else(|| hold.avoid_keeper())
        .unwrap_or_else(|| hold.stop_ball())
}

/// What every part of the behaviour reads.
struct Hold<'a> {
    p: &'a Player,
    world: &'a World,
    /// The player's next position.
    next: DVec2,
    /// Its current kick rate.
    rate: f64,
    /// The player's movement noise.
    noise: f64,
    /// `current_pos_rate + current_speed_rate` of the kick noise.
    noise_rate: f64,
}

impl<'a> Hold<'a> {
    fn new(p: &'a Player, world: &'a World) -> Self {
        let ball = &world.ball;
        let rel = ball.pos - p.pos;
        let dir_rate = angle_diff(direction(rel), p.body) / std::f64::consts::PI;
        let dist_rate = (rel.length() - PLAYER_SIZE - BALL_SIZE) / KICKABLE_MARGIN;
        let pos_rate = 0.5 + 0.25 * (dir_rate + dist_rate);
        let speed_rate = 0.5 + 0.5 * ball.vel.length() / (BALL_SPEED_MAX * BALL_DECAY);
        Hold {
            p,
            world,
            next: p.pos + p.vel,
            rate: kick_rate(p, ball.pos),
            noise: p.vel.length() * PLAYER_RAND,
            noise_rate: pos_rate + speed_rate,
        }
    }

    /// The kick that moves the ball to `spot` in one cycle, with its power.
    fn kick_to(&self, spot: DVec2) -> (DVec2, f64) {
        let accel = spot - self.world.ball.pos - self.world.ball.vel;
        (accel, accel.length() / self.rate)
    }

    /// The largest error the kick to `spot` at `power` may leave: the
    /// player's, the ball's and the kick's noise.
    fn noise_to(&self, spot: DVec2, power: f64) -> f64 {
        let move_dist = (spot - self.world.ball.pos).length();
        let kick_noise = KICK_RAND * (power / MAX_KICK_POWER) * self.noise_rate;
        self.noise + move_dist * BALL_RAND + kick_noise
    }

    /// Whether a kick can stop the ball at `spot` next cycle, from `dist` out
    /// and `dir_diff` off the body (`strict`: librcsc's `<`, else `<=`).
    fn stoppable(&self, spot: DVec2, dist: f64, dir_diff: f64, strict: bool) -> bool {
        let (need, have) = (
            (spot - self.world.ball.pos).length() * BALL_DECAY,
            MAX_KICK_POWER * rate_at(dist, dir_diff),
        );
        if strict { need < have } else { need <= have }
    }

    /// keepReverse: the ball to the side of the next position away from
    /// `target`, as far out as it can be kept.
    fn keep_reverse(&self, target: DVec2) -> Option<Command> {
        let angle = direction(self.next - target);
        let dir_diff = angle_diff(angle, self.p.body);
        let min_dist = PLAYER_SIZE + BALL_SIZE + 0.2;
        let mut dist = PLAYER_SIZE + 0.7 * KICKABLE_MARGIN + BALL_SIZE;
        while dist > min_dist {
            let spot = self.next + polar(dist, angle);
            let (accel, power) = self.kick_to(spot);
            let fits = inside_pitch(spot)
                && power <= MAX_KICK_POWER
                && self.noise_to(spot, power) <= KICKABLE_AREA - dist - 0.1
                && self.stoppable(spot, dist, dir_diff, false);
            if fits && self.safety(spot) >= SAFE {
                return Some(kick(self.p, accel, power));
            }
            dist -= 0.05;
        }
        None
    }

    /// turnToPoint: turn to `face` if the ball stays kickable and safe next
    /// cycle and the body is more than 5° off it.
    fn turn_to_face(&self, face: DVec2) -> Option<Command> {
        let ball = &self.world.ball;
        let ball_next = ball.pos + ball.vel;
        let margin = self.noise + ball.vel.length() * BALL_RAND + 0.15;
        let final_pos = self.p.final_drift();
        let stays = inside_pitch(ball_next)
            && self.next.distance(ball_next) <= KICKABLE_AREA - margin
            && angle_diff(self.p.body, direction(face - final_pos)) >= 5f64.to_radians()
            && self.safety(ball_next) >= SAFE;
        stays.then(|| turn_to_point(self.p, face))
    }

    /// keepFront: the ball just in front of the body, if one kick can and the
    /// spot is safe.
    fn keep_front(&self) -> Option<Command> {
        let spot = self.next + polar(PLAYER_SIZE + BALL_SIZE + 0.05, self.p.body);
        let (accel, power) = self.kick_to(spot);
        (inside_pitch(spot) && power <= MAX_KICK_POWER && self.safety(spot) >= SAFE)
            .then(|| kick(self.p, accel, power))
    }

    /// avoidOpponent: the ball to the best keep point: the safest, then the
    /// best kick rate (or, threatened, the farthest from the ball).
    fn avoid_keeper(&self) -> Option<Command> {
        let mut best: Option<(f64, DVec2)> = None;
        for k in 0..20 {
            let angle = (-180.0 + 18.0 * k as f64).to_radians();
            let dir_diff = angle_diff(angle, self.p.body);
            for (margin, near) in [(0.4, true), (0.6, false), (0.8, false)] {
                let dist = PLAYER_SIZE + BALL_SIZE + margin * KICKABLE_MARGIN;
                let spot = self.next + polar(dist, angle);
                let (_, power) = self.kick_to(spot);
                let inside = spot.x.abs() < PITCH_MAX.x && spot.y.abs() < PITCH_MAX.y;
                if !inside || power >= MAX_KICK_POWER {
                    continue;
                }
                let quiet = near || 0.95 * self.noise_to(spot, power) < KICKABLE_AREA - dist - 0.1;
                if !(quiet && self.stoppable(spot, dist, dir_diff, true)) {
                    continue;
                }
                let rate = rate_at(dist, dir_diff);
                let safety = self.safety(spot);
                let score = if safety < SAFE {
                    safety + spot.distance(self.world.ball.pos)
                } else {
                    safety + 1000.0 * rate
                };
                if best.is_none_or(|(b, _)| score > b) {
                    best = Some((score, spot));
                }
            }
        }
        let (_, spot) = best?;
        let (accel, power) = self.kick_to(spot);
        Some(kick(self.p, accel, power))
    }

    /// Body_StopBall: the ball kept at its distance (within 0.485 and
    /// 0.985 m) on its side of the player; else as near that as one kick can.
    fn stop_ball(&self) -> Command {
        let ball = &self.world.ball;
        let rel = ball.pos - self.p.pos;
        let target_dist = rel
            .length()
            .clamp(PLAYER_SIZE + BALL_SIZE + 0.1, KICKABLE_AREA - 0.1);
        let needed = self.p.vel + rel.normalize_or_zero() * target_dist - rel - ball.vel;
        let max_accel = MAX_KICK_POWER * self.rate;
        let accel = if needed.length() < 0.01 || max_accel > needed.length() {
            needed
        } else {
            let to_self = self.p.vel - rel - ball.vel;
            let radius = max_accel.min(to_self.length() - (PLAYER_SIZE + 0.4 * KICKABLE_MARGIN));
            if radius < 0.0 {
                -unit(direction(to_self)) * (-radius).min(max_accel)
            } else {
                unit(direction(to_self)) * radius
            }
        };
        if accel.length() < 0.02 {
            return Command::Turn { moment: 0.0 };
        }
        kick(self.p, accel, accel.length() / self.rate)
    }

    /// evaluateKeepPoint: `SAFE` less what the keeper threatens at `spot`.
    fn safety(&self, spot: DVec2) -> f64 {
        let keeper = &self.world.keeper;
        let ball = self.world.ball.pos;
        let mut score = SAFE;
        let consider = TACKLE_DIST + PLAYER_SPEED_MAX + 1.0;
        if keeper.pos.distance(ball) <= consider && keeper.tackle_freeze == 0 {
            score -= keeper_threat(keeper, spot);
        }
        if (spot - ball).length() > 1.6 * KICKABLE_AREA {
            let threshold = KICKABLE_AREA - 0.4;
            score *= 1.0 - 0.5 * ((self.next.distance(spot) - threshold) / 0.4).max(0.0);
        }
        score
    }
}

/// How much the keeper threatens a ball kept at `spot` (evaluateKeepPoint's
/// opponent terms).
fn keeper_threat(keeper: &Player, spot: DVec2) -> f64 {
    let next = keeper.pos + keeper.vel;
    let in_box = |p: DVec2| {
        p.x >= PENALTY_AREA_X && p.x <= PITCH_HALF_LENGTH && p.y.abs() <= PENALTY_AREA_HALF_WIDTH
    };
    let control = if in_box(next) && in_box(spot) {
        KEEPER_CONTROL_AREA
    } else {
        KICKABLE_AREA
    };
    let mut threat = 0.0;
    let dist = next.distance(spot);
    if dist < 0.5 * control {
        threat += 100.0;
    } else if dist < control + 0.1 {
        threat += 50.0;
    } else if dist < TACKLE_DIST - 0.2 {
        threat += 25.0;
    }
    // The keeper's body is known every cycle (fullstate).
    let body = unit(keeper.body);
    let rel = DVec2::new((spot - next).dot(body), body.perp_dot(spot - next));
    let line_dist = rel.y.abs();
    if line_dist < control {
        threat += if line_dist < 0.8 * control {
            20.0
        } else {
            10.0
        };
    }
    if tackle_probability_at(rel, TACKLE_EXPONENT) > 0.7 {
        threat += 30.0;
    }
    let max_accel = MAX_DASH_POWER * DASH_POWER_RATE;
    if rel.y.abs() < control
        && rel.x > 0.0
        && (rel.x.abs() < max_accel || (rel - DVec2::new(max_accel, 0.0)).length() < control + 0.1)
    {
        threat += 20.0;
    } else if rel.y.abs() < 0.7 * TACKLE_WIDTH
        && rel.x > 0.0
        && rel.x - max_accel < TACKLE_DIST - 0.25
    {
        threat += 10.0;
    }
    threat
}

fn inside_pitch(p: DVec2) -> bool {
    p.x.abs() <= PITCH_MAX.x && p.y.abs() <= PITCH_MAX.y
}

/// A kick of `power` in the direction of `accel`.
fn kick(p: &Player, accel: DVec2, power: f64) -> Command {
    Command::Kick {
        power: power.min(MAX_KICK_POWER),
        dir: normalize_angle(direction(accel) - p.body),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The holder at (40, 0) facing the goal, the ball 0.6 m ahead.
    fn world(keeper: DVec2) -> World {
        let mut w = World::new(1);
        w.offense[0] = Player::new(DVec2::new(40.0, 0.0), 0.0);
        w.ball.pos = DVec2::new(40.6, 0.0);
        w.keeper = Player::new(keeper, std::f64::consts::PI);
        w
    }

    /// Where the ball goes with `cmd` (noise-free).
    fn ball_after(w: &World, cmd: Command) -> DVec2 {
        let p = &w.offense[0];
        match cmd {
            Command::Kick { power, dir } => {
                w.ball.pos + w.ball.vel + polar(power * kick_rate(p, w.ball.pos), p.body + dir)
            }
            _ => w.ball.pos + w.ball.vel,
        }
    }

    #[test]
    fn with_the_keeper_far_the_ball_stays_just_in_front() {
        let w = world(DVec2::new(51.0, 0.0));
        let cmd = hold_ball(&w.offense[0], &w, None, None);
        let Command::Kick { .. } = cmd else {
            panic!("keepFront kicks: {cmd:?}");
        };
        let spot = ball_after(&w, cmd);
        assert!((spot - DVec2::new(40.435, 0.0)).length() < 1e-6, "{spot}");
    }

    #[test]
    fn with_the_keeper_in_front_the_ball_goes_away_from_it() {
        let w = world(DVec2::new(41.8, 0.4));
        let hold = Hold::new(&w.offense[0], &w);
        assert!(hold.keep_front().is_none(), "the front spot is threatened");
        let spot = ball_after(&w, hold_ball(&w.offense[0], &w, None, None));
        let keeper_next = w.keeper.pos + w.keeper.vel;
        assert!(
            spot.distance(keeper_next) > KEEPER_CONTROL_AREA + 0.1,
            "{spot}"
        );
        assert!(spot.distance(w.offense[0].pos) < KICKABLE_AREA, "{spot}");
    }

    #[test]
    fn a_failed_kick_keeps_the_ball_on_the_far_side_from_its_target() {
        let w = world(DVec2::new(51.0, 0.0));
        let target = DVec2::new(52.5, 3.0);
        let spot = ball_after(&w, hold_ball(&w.offense[0], &w, None, Some(target)));
        let away = unit(direction(w.offense[0].pos - target));
        assert!((spot - w.offense[0].pos).dot(away) > 0.5, "{spot}");
    }
}
