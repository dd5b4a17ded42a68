//! librcsc's KickTable (rcsc/action/kick_table.cpp): plans of one, two or
//! three kicks through 35 ball spots around the kicker (spec 6.2.3).

use crate::sim::geom::{angle_diff, direction, normalize_angle, polar};
use crate::sim::params::*;
use crate::sim::world::{Player, World};
use glam::DVec2;
use std::f64::consts::PI;
use std::sync::OnceLock;

use super::kick::max_one_kick_speed;
use crate::sim::physics::tackle_probability_at;

/// Ring radii (`calc_near_dist`, `calc_mid_dist`, `calc_far_dist`) and spots per ring.
const RINGS: [(f64, usize); 3] = [
    (PLAYER_SIZE + 0.3 * KICKABLE_MARGIN + BALL_SIZE, 8),
    (PLAYER_SIZE + 0.5 * KICKABLE_MARGIN + BALL_SIZE, 12),
    (PLAYER_SIZE + 0.7 * KICKABLE_MARGIN + BALL_SIZE, 15),
];
/// Number of spots (`NUM_STATE`).
const SPOTS: usize = 35;
/// Target directions of the three-kick tables (`DEST_DIR_DIVS`, 5° apart).
const DIRECTIONS: usize = 72;
/// Paths kept per direction (`MAX_TABLE_SIZE`).
const TABLE_SIZE: usize = 256;

/// A spot's interference flags (`checkInterfereAt`).
const OUT_OF_PITCH: u8 = 1;
const KICKABLE: u8 = 2;
const TACKLABLE: u8 = 4;
const NEXT_TACKLABLE: u8 = 8;
const NEXT_KICKABLE: u8 = 16;
const KICK_MISS: u8 = 32;

/// A ball spot relative to the kicker's body: offset and kick rate there.
#[derive(Clone, Copy, Debug)]
struct Spot {
    rel: DVec2,
    dist: f64,
    rate: f64,
}

/// A spot at a given cycle: field position, kick rate and flags.
#[derive(Clone, Copy, Debug)]
struct KickState {
    pos: DVec2,
    dist: f64,
    rate: f64,
    flag: u8,
}

/// A planned kick sequence: where each kick leaves the ball next cycle.
#[derive(Clone, Debug, Default)]
struct Sequence {
    first: DVec2,
    kicks: usize,
    speed: f64,
    power: f64,
    flag: u8,
}

/// The last kick of a plan of `kicks` kicks, from the spot `from` where the
/// ball arrives with velocity `vel` (already decayed).
struct LastKick<'a> {
    first: DVec2,
    kicks: usize,
    from: &'a KickState,
    vel: DVec2,
    flag: u8,
    miss: u8,
}

impl LastKick<'_> {
    /// Adds the plan to `out` if its last kick reaches `speed` towards
    /// `target` and says so; otherwise, with `effort` allowed, keeps the
    /// fastest such plan in librcsc's single best-effort slot.
    fn finish(
        &self,
        target: DVec2,
        speed: f64,
        effort: bool,
        best_effort: &mut f64,
        out: &mut Vec<Sequence>,
    ) -> bool {
        let dir = aim(target - self.from.pos, speed);
        let last = (polar(speed, dir) - self.vel).length();
        let limit = max_accel(self.from.rate);
        if last <= limit {
            out.push(Sequence {
                first: self.first,
                kicks: self.kicks,
                speed,
                power: last / self.from.rate,
                flag: self.flag | self.miss,
            });
            return true;
        }
        let top = max_one_kick_speed(dir, self.vel, limit);
        if effort && top > *best_effort {
            if *best_effort == 0.0 {
                out.push(Sequence::default());
            }
            *best_effort = top;
            *out.last_mut().expect("pushed") = Sequence {
                first: self.first,
                kicks: self.kicks,
                speed: top,
                power: (polar(top, dir) - self.vel).length() / self.from.rate,
                flag: self.flag,
            };
        }
        false
    }
}

/// The direction of librcsc's target velocity `rel.setLength(speed)`:
/// that of `rel`, but 0° when the speed is 0 (the angle of a zero vector).
fn aim(rel: DVec2, speed: f64) -> f64 {
    if speed > 0.0 { direction(rel) } else { 0.0 }
}

/// The first kick's ball position (after this cycle's move) of the best plan
/// of at most `max_kicks` kicks that sends the ball towards `target` at
/// `speed`, if the plan reaches at least `min_speed` (`KickTable::simulate`
/// with `max_step = max_kicks`, then Body_SmartKick's acceptance test).
pub(super) fn plan(
    p: &Player,
    world: &World,
    target: DVec2,
    (speed, min_speed): (f64, f64),
    max_kicks: usize,
) -> Option<DVec2> {
    let speed = speed.clamp(0.0, BALL_SPEED_MAX);
    let min_speed = min_speed.clamp(0.0, speed);
    let planner = Planner::new(p, world);
    let mut candidates = Vec::new();
    planner.one_step(target, speed, &mut candidates);
    if max_kicks >= 2 {
        planner.two_step(target, speed, &mut candidates);
    }
    if max_kicks >= 3 {
        planner.three_step(target, speed, &mut candidates);
    }
    let best = candidates
        .iter()
        .map(|c| (evaluate(c, speed, min_speed), c))
        .reduce(|a, b| if b.0 > a.0 { b } else { a })?
        .1;
    (best.speed >= min_speed || best.speed >= speed - 1e-6).then_some(best.first)
}

/// agent2d's sequence score (`KickTable::evaluate`).
fn evaluate(c: &Sequence, speed: f64, min_speed: f64) -> f64 {
    let mut score = 1000.0;
    if c.speed < speed {
        if c.kicks > 1 || c.speed < min_speed {
            score = -10000.0 - (speed - c.speed) * 100000.0;
        } else {
            score -= 50.0;
        }
    }
    if c.flag & TACKLABLE != 0 {
        score -= 500.0;
    }
    if c.flag & NEXT_TACKLABLE != 0 {
        score -= 300.0;
    }
    if c.flag & NEXT_KICKABLE != 0 {
        score -= 600.0;
    }
    score -= match c.kicks {
        3 => 200.0,
        2 => 50.0,
        _ => 0.0,
    };
    if c.kicks > 1 {
        if c.power > 0.94 * MAX_KICK_POWER {
            score -= 75.0;
        } else if c.power > 0.9 * MAX_KICK_POWER {
            score -= 25.0;
        }
    }
    score -= 0.5 * c.power;
    if c.flag & KICK_MISS != 0 {
        score -= 30.0;
    }
    score
}

/// The 35 spots relative to the body (`createStateList`).
fn spots() -> &'static [Spot; SPOTS] {
    static SPOTS_LIST: OnceLock<[Spot; SPOTS]> = OnceLock::new();
    SPOTS_LIST.get_or_init(|| {
        let mut list = [Spot {
            rel: DVec2::ZERO,
            dist: 0.0,
            rate: 0.0,
        }; SPOTS];
        let mut i = 0;
        for (dist, n) in RINGS {
            for k in 0..n {
                let angle = -PI + 2.0 * PI * k as f64 / n as f64;
                list[i] = Spot {
                    rel: polar(dist, angle),
                    dist,
                    rate: rate_at(dist, angle.abs()),
                };
                i += 1;
            }
        }
        list
    })
}

/// Kick rate for the ball `dist` from the centre, `dir_diff` off the body (spec 3.1).
pub(super) fn rate_at(dist: f64, dir_diff: f64) -> f64 {
    let dist_ball = (dist - PLAYER_SIZE - BALL_SIZE).max(0.0);
    KICK_POWER_RATE * (1.0 - 0.25 * dir_diff / PI - 0.25 * dist_ball / KICKABLE_MARGIN)
}

fn max_accel(rate: f64) -> f64 {
    (MAX_KICK_POWER * rate).min(BALL_ACCEL_MAX)
}

/// Per target direction relative to the body, the (origin, destination)
/// spot pairs by falling top speed, then rising power (`createTable`).
fn tables() -> &'static [Vec<(u8, u8)>] {
    static TABLES: OnceLock<Vec<Vec<(u8, u8)>>> = OnceLock::new();
    TABLES.get_or_init(|| {
        let spots = spots();
        (0..DIRECTIONS)
            .map(|d| {
                let angle = -PI + 2.0 * PI * d as f64 / DIRECTIONS as f64;
                let mut paths = Vec::with_capacity(SPOTS * SPOTS);
                for (o, origin) in spots.iter().enumerate() {
                    for (t, dest) in spots.iter().enumerate() {
                        let vel = dest.rel - origin.rel;
                        let top = max_one_kick_speed(angle, vel, max_accel(dest.rate));
                        let power = (polar(top, angle) - vel).length() / dest.rate;
                        paths.push((top, power, o as u8, t as u8));
                    }
                }
                paths.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.total_cmp(&b.1)));
                paths.truncate(TABLE_SIZE);
                paths.into_iter().map(|(_, _, o, t)| (o, t)).collect()
            })
            .collect()
    })
}

/// One planning call's state: the kicker, the ball and the spots one and two cycles ahead.
struct Planner<'a> {
    p: &'a Player,
    world: &'a World,
    current: u8,
    current_rate: f64,
    states: [[KickState; SPOTS]; 2],
    /// Terms of the kick-miss estimate for a first kick (`my_noise`, position and speed rates).
    miss_terms: (f64, f64),
}

impl<'a> Planner<'a> {
    /// `createStateCache`.
    fn new(p: &'a Player, world: &'a World) -> Self {
        let ball = &world.ball;
        let mut states = [[KickState {
            pos: DVec2::ZERO,
            dist: 0.0,
            rate: 0.0,
            flag: 0,
        }; SPOTS]; 2];
        let (mut pos, mut vel) = (p.pos, p.vel);
        for depth in &mut states {
            pos += vel;
            vel *= PLAYER_DECAY;
            for (state, spot) in depth.iter_mut().zip(spots()) {
                let at = pos + spot.rel.rotate(polar(1.0, p.body));
                let mut flag = interference(world, at);
                if at.x.abs() > PITCH_HALF_LENGTH || at.y.abs() > PITCH_HALF_WIDTH {
                    flag |= OUT_OF_PITCH;
                }
                *state = KickState {
                    pos: at,
                    dist: spot.dist,
                    rate: spot.rate,
                    flag,
                };
            }
        }
        let rel = ball.pos - p.pos;
        let dir_rate = angle_diff(direction(rel), p.body) / PI;
        let dist_rate = (rel.length() - PLAYER_SIZE - BALL_SIZE) / KICKABLE_MARGIN;
        let pos_rate = 0.5 + 0.25 * (dir_rate + dist_rate);
        let speed_rate = 0.5 + 0.5 * ball.vel.length() / (BALL_SPEED_MAX * BALL_DECAY);
        Planner {
            p,
            world,
            current: interference(world, ball.pos),
            current_rate: crate::sim::physics::kick_rate(p, ball.pos),
            states,
            miss_terms: (p.vel.length() * PLAYER_RAND, pos_rate + speed_rate),
        }
    }

    /// Whether the first kick, moving the ball by `vel` with `accel`, may miss `state`.
    fn miss(&self, vel: DVec2, accel: f64, state: &KickState) -> u8 {
        let power = accel / self.current_rate;
        let noise = self.miss_terms.0
            + vel.length() * BALL_RAND
            + KICK_RAND * power / MAX_KICK_POWER * self.miss_terms.1;
        if noise > KICKABLE_AREA - state.dist - 0.05 {
            KICK_MISS
        } else {
            0
        }
    }

    /// `simulateOneStep`.
    fn one_step(&self, target: DVec2, speed: f64, out: &mut Vec<Sequence>) {
        let ball = &self.world.ball;
        let dir = aim(target - ball.pos, speed);
        let want = polar(speed, dir);
        let limit = max_accel(self.current_rate);
        let vel = if (want - ball.vel).length() > limit {
            polar(max_one_kick_speed(dir, ball.vel, limit), dir)
        } else {
            want
        };
        out.push(Sequence {
            first: ball.pos + vel,
            kicks: 1,
            speed: vel.length().min(speed),
            power: (vel - ball.vel).length() / self.current_rate,
            flag: self.current,
        });
    }

    /// `simulateTwoStep`, with librcsc's single best-effort slot.
    fn two_step(&self, target: DVec2, speed: f64, out: &mut Vec<Sequence>) {
        let ball = &self.world.ball;
        let limit = max_accel(self.current_rate);
        let mut best_effort = 0.0;
        for state in &self.states[0] {
            if state.flag & (OUT_OF_PITCH | KICKABLE) != 0 {
                continue;
            }
            let mut vel = state.pos - ball.pos;
            let accel = (vel - ball.vel).length();
            if accel > limit {
                continue;
            }
            let miss = self.miss(vel, accel, state);
            vel *= BALL_DECAY;
            let last = LastKick {
                first: state.pos,
                kicks: 2,
                from: state,
                vel,
                flag: self.current | state.flag,
                miss,
            };
            last.finish(target, speed, true, &mut best_effort, out);
        }
    }

    /// `simulateThreeStep`: the direction's table, up to 11 successes.
    fn three_step(&self, target: DVec2, speed: f64, out: &mut Vec<Sequence>) {
        let ball = &self.world.ball;
        let limit = max_accel(self.current_rate);
        let rel_deg = normalize_angle(direction(target - self.p.pos) - self.p.body).to_degrees();
        let index = libm::rint(DIRECTIONS as f64 * (rel_deg + 180.0) / 360.0) as usize % DIRECTIONS;
        let (mut successes, mut best_effort) = (0, 0.0);
        for &(o, t) in &tables()[index] {
            if successes > 10 {
                break;
            }
            let (first, second) = (&self.states[0][o as usize], &self.states[1][t as usize]);
            if (first.flag | second.flag) & (OUT_OF_PITCH | KICKABLE) != 0 {
                continue;
            }
            let mut vel1 = first.pos - ball.pos;
            let accel = (vel1 - ball.vel).length();
            if accel > limit {
                continue;
            }
            let miss = self.miss(vel1, accel, first);
            vel1 *= BALL_DECAY;
            let mut vel2 = second.pos - first.pos;
            if (vel2 - vel1).length() > max_accel(first.rate) {
                continue;
            }
            vel2 *= BALL_DECAY;
            let last = LastKick {
                first: first.pos,
                kicks: 3,
                from: second,
                vel: vel2,
                flag: self.current | first.flag | second.flag,
                miss,
            };
            if last.finish(target, speed, successes == 0, &mut best_effort, out) {
                successes += 1;
            }
        }
    }
}

/// The keeper's interference flags at ball position `at` next cycle (`checkInterfereAt`).
fn interference(world: &World, at: DVec2) -> u8 {
    let keeper = &world.keeper;
    if keeper.pos.distance(world.ball.pos) > 10.0 {
        return 0;
    }
    let next = keeper.pos + keeper.vel;
    let control = if in_penalty_area(keeper.pos) && in_penalty_area(at) {
        KEEPER_CONTROL_AREA
    } else {
        KICKABLE_AREA
    };
    if next.distance(at) < control + 0.15 {
        return KICKABLE;
    }
    let rel = (at - next).rotate(polar(1.0, -keeper.body));
    let mut flag = 0;
    if tackle_probability_at(rel, TACKLE_EXPONENT) > 0.7 {
        flag |= TACKLABLE;
    }
    let dash = MAX_DASH_POWER * DASH_POWER_RATE;
    let step = DVec2::new(dash, 0.0);
    if rel.y.abs() < control
        && (rel.x.abs() < dash
            || (rel + step).length() < control
            || (rel - step).length() < control)
    {
        flag |= NEXT_KICKABLE;
    } else if rel.y.abs() < 0.7 * TACKLE_WIDTH && rel.x > 0.0 && rel.x - dash < TACKLE_DIST - 0.3 {
        flag |= NEXT_TACKLABLE;
    }
    flag
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fastest plan each depth alone finds.
    fn best_by_kicks(p: &Player, w: &World, target: DVec2, speed: f64) -> [f64; 3] {
        let planner = Planner::new(p, w);
        let mut out = Vec::new();
        planner.one_step(target, speed, &mut out);
        planner.two_step(target, speed, &mut out);
        planner.three_step(target, speed, &mut out);
        let mut best = [0.0; 3];
        for c in out {
            best[c.kicks - 1] = f64::max(best[c.kicks - 1], c.speed);
        }
        best
    }

    #[test]
    fn three_kicks_reach_what_two_cannot() {
        let mut w = World::new(1);
        w.keeper.pos = DVec2::new(52.0, 30.0);
        let p = Player::new(DVec2::ZERO, 0.0);
        w.offense[0] = p;
        w.ball.pos = DVec2::new(0.7, 0.0);
        let target = DVec2::new(50.0, 0.0);
        let best = best_by_kicks(&p, &w, target, 3.0);
        assert!(best[0] < 2.97 && best[1] < 2.97, "{best:?}");
        assert_eq!(best[2], 3.0);
        assert_eq!(plan(&p, &w, target, (3.0, 2.97), 2), None);
        let first = plan(&p, &w, target, (3.0, 2.97), 3).expect("a three-kick plan");
        // The first kick only moves the ball around the kicker.
        assert!(first.distance(p.pos) < KICKABLE_AREA);
    }
}
