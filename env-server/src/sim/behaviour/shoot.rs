//! SHOOT (spec 6.2): the best goal-mouth course the keeper cannot reach;
//! with none, the course the agent's last non-empty search found first (6.2.2).

use super::kick::max_one_kick_speed;
use super::situation::Situation;
use super::smart_kick::{planned_kick, smart_kick};
use crate::sim::geom::{angle_diff, asin_clamped, ceil_usize, direction, unit};
use crate::sim::kinematics::{DRIFT, dash_cycles, dash_distance, max_turn};
use crate::sim::memory::ShotCourse;
use crate::sim::params::*;
use crate::sim::physics::{Command, kick_rate, max_kick_accel};
use crate::sim::world::Player;
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// Number of targets along the goal mouth.
const TARGETS: usize = 25;

/// librcsc's `EPS` in `calc_length_geom_series`.
const GEOM_SERIES_EPS: f64 = 1e-10;

/// How far from the goal centre (m) the shot searches outside SHOOT look
/// (`ShootGenerator::generate` with `consider_shot_distance`).
const CHECK_DISTANCE: f64 = 30.0;

/// One candidate shot.
#[derive(Clone, Copy, Debug)]
struct Course {
    target: DVec2,
    speed: f64,
    one_kick: bool,
    keeper_never_reaches: bool,
}

impl Course {
    fn shot(&self) -> ShotCourse {
        ShotCourse {
            target: self.target,
            speed: self.speed,
        }
    }
}

/// One `ShootGenerator::generate` run: the first course it listed (what HFO's
/// course storage keeps) and the best by `evaluateCourses`.
struct Search {
    first: Option<Course>,
    best: Option<Course>,
}

/// The SHOOT command of a kickable agent, and the first course of this
/// cycle's search if it found any (`Agent::doSmartKick`). With no feasible
/// course HFO reads the first element of its emptied course vector: the
/// agent's last non-empty search's first course, or, for an agent whose
/// searches never found one, the zero course of fresh storage (spec 6.2.2).
pub(super) fn command(s: &Situation) -> (Command, Option<ShotCourse>) {
    let search = search(s, Want::Best);
    let first = search.first.map(|c| c.shot());
    let command = match (search.best, s.memory.last_shot) {
        (Some(c), _) => smart_kick(s.me(), s.world, c.target, c.speed, 0.99 * c.speed),
        (None, Some(c)) => smart_kick(s.me(), s.world, c.target, c.speed, 0.99 * c.speed),
        (None, None) => zero_course(s),
    };
    (command, first)
}

/// What SHOOT kicks for an agent that never had a course (spec 6.2.2):
/// HFO's course storage is reserved but never written, and reads as a
/// zero course: Body_SmartKick to (0, 0) at speed 0 with threshold 0,
/// which always kicks its best plan: it stops the ball at the agent's feet
/// (or, if one kick cannot stop it, sends it as fast as one kick can along
/// 0°). The agent so stands on the ball, kick after kick. Where no plan
/// exists at all HFO reads an empty plan (undefined); ours then does
/// nothing.
fn zero_course(s: &Situation) -> Command {
    planned_kick(s.me(), s.world, DVec2::ZERO, (0.0, 0.0), 3).unwrap_or(Command::None)
}

/// The shot searches outside SHOOT (`Bhv_StrictCheckShoot` in DRIBBLE's
/// `doPreprocess`, `Neck_OffensiveInterceptNeck` in MOVE): nothing beyond
/// 30 m from the goal centre; else the first course found, if any.
pub(super) fn check(s: &Situation) -> Option<ShotCourse> {
    if s.me().pos.distance(GOAL_CENTER) > CHECK_DISTANCE {
        return None;
    }
    search(s, Want::First).first.map(|c| c.shot())
}

/// DRIBBLE in the goalie-catch mode (spec 4.5): the action chain cancels
/// its hold, so only `doPreprocess`'s Bhv_StrictCheckShoot acts. Within 30 m
/// of the goal centre it kicks the best course, in one kick if one kick is
/// fast enough; with no course there is no command. Also returns the
/// search's first course.
pub(super) fn strict_check(s: &Situation) -> (Command, Option<ShotCourse>) {
    if s.me().pos.distance(GOAL_CENTER) > CHECK_DISTANCE {
        return (Command::None, None);
    }
    let search = search(s, Want::Best);
    let first = search.first.map(|c| c.shot());
    let Some(best) = search.best else {
        return (Command::None, first);
    };
    let (me, world) = (s.me(), s.world);
    let ball = &world.ball;
    let dir = direction(best.target - ball.pos);
    let one_kick = max_one_kick_speed(dir, ball.vel, max_kick_accel(me, ball.pos));
    let command = (one_kick > 0.99 * best.speed)
        .then(|| {
            planned_kick(
                me,
                world,
                best.target,
                (one_kick, 0.99 * one_kick - 1e-4),
                1,
            )
        })
        .flatten()
        .unwrap_or_else(|| smart_kick(me, world, best.target, best.speed, 0.99 * best.speed));
    (command, first)
}

/// How much of a search its caller reads.
#[derive(Clone, Copy, PartialEq)]
enum Want {
    /// Only the first course: the search stops there.
    First,
    /// The first and the best course.
    Best,
}

/// `ShootGenerator::generate` (spec 6.2.1). A non-kickable agent (reach 1)
/// shoots from the ball's next position with a 0.1 one-kick limit.
fn search(s: &Situation, want: Want) -> Search {
    let me = s.me();
    let kickable = s.world.agent_kickable(s.agent);
    let ball = if kickable {
        s.world.ball.pos
    } else {
        s.world.ball.pos + s.world.ball.vel
    };
    let keeper_dir = direction(s.world.keeper.pos - ball);
    let keeper = Keeper::new(s);
    let speed_max = speed_limit(s);
    let mut first = None;
    let mut best: Option<(f64, Course)> = None;
    for target in targets(me, ball) {
        let line = Line::new(s, ball, target);
        let s1 = if kickable {
            let dir = direction(target - ball);
            max_one_kick_speed(dir, s.world.ball.vel, max_kick_accel(me, ball))
        } else {
            0.1
        };
        let mut speed = (0.06 * (target.distance(ball) + 5.0)).max(s1).max(1.5);
        loop {
            let last = speed > speed_max - 0.001;
            if last {
                speed = speed_max;
            }
            if let Some(never) = keeper_verdict(&keeper, ball, &line, speed) {
                let course = Course {
                    target,
                    speed,
                    one_kick: speed <= s1 + 0.001,
                    keeper_never_reaches: never,
                };
                first.get_or_insert(course);
                if want == Want::First {
                    return Search { first, best: None };
                }
                let score = score(&course, ball, keeper_dir, if never { 1.0 } else { 10.0 });
                if best.is_none_or(|(b, _)| score > b) {
                    best = Some((score, course));
                }
                if never {
                    break;
                }
            }
            if last {
                break;
            }
            speed += 0.3;
        }
    }
    Search {
        first,
        best: best.map(|(_, c)| c),
    }
}

/// The fastest first speed a search tries: the server's limit in play-on;
/// in the goalie-catch mode one full-power kick at the agent's kick rate,
/// which librcsc sets to 0 beyond the server's kickable area (spec 4.5).
fn speed_limit(s: &Situation) -> f64 {
    let (me, ball) = (s.me(), s.world.ball.pos);
    match s.world.catch_mode {
        false => BALL_SPEED_MAX,
        true if me.pos.distance(ball) > KICKABLE_AREA => 0.0,
        true => MAX_KICK_POWER * kick_rate(me, ball),
    }
}

/// The 25 aim points along the goal mouth (spec 6.2.1 step 2-3).
fn targets(me: &Player, ball: DVec2) -> impl Iterator<Item = DVec2> {
    let margin = |post_y: f64| {
        let d = ball.distance(DVec2::new(PITCH_HALF_LENGTH, post_y));
        (0.6 + 0.042 * d).min(1.5)
    };
    let x = if me.pos.x > 51.5 && me.pos.y.abs() < GOAL_HALF_WIDTH {
        me.pos.x + 1.5
    } else {
        PITCH_HALF_LENGTH
    };
    let left = -GOAL_HALF_WIDTH + margin(-GOAL_HALF_WIDTH);
    let right = GOAL_HALF_WIDTH - margin(GOAL_HALF_WIDTH);
    (0..TARGETS).map(move |i| {
        let f = i as f64 / (TARGETS - 1) as f64;
        DVec2::new(x, left + (right - left) * f)
    })
}

/// `evaluateCourses` (spec 6.2.1 step 4).
fn score(c: &Course, ball: DVec2, keeper_dir: f64, sigma_deg: f64) -> f64 {
    let mut score = 1.0;
    if c.one_kick {
        score += 50.0;
    }
    if c.keeper_never_reaches {
        score += 100.0;
    }
    score += 100.0; // no field opponent can reach
    let dir = direction(c.target - ball);
    let delta = angle_diff(dir, keeper_dir).to_degrees();
    score *= 1.0 - (-delta * delta / (2.0 * sigma_deg * sigma_deg)).exp();
    if c.target.distance(ball) > 8.0 {
        let off = (c.target.y.abs() - 4.0).max(0.0);
        let w = GOAL_HALF_WIDTH - 1.5;
        score *= (-off * off / (2.0 * w * w)).exp();
    }
    score
}

/// What the keeper tests of the courses from `ball` to one target share
/// (spec 6.2.1 step 3): none of it depends on the course's speed.
struct Line {
    /// Distance from the ball to the target.
    length: f64,
    /// Unit vector from the ball to the target.
    u: DVec2,
    /// The first cycle the keeper could be on the path, or `None` if it
    /// never gets close: it is out of its penalty area, or behind the ball.
    /// (agent2d also skips a keeper more than 90° off the course, measured
    /// from its `angleFromSelf()`, which librcsc leaves at 0° (spec 6.4):
    /// no course to the goal line is that far off.)
    first: Option<usize>,
}

impl Line {
    fn new(s: &Situation, ball: DVec2, target: DVec2) -> Self {
        let keeper = &s.world.keeper;
        let rel = target - ball;
        let length = rel.length();
        let u = rel / length;
        let k_rel = keeper.pos - ball;
        let away = keeper.pos.x < 6.0
            || keeper.pos.y.abs() > PENALTY_AREA_HALF_WIDTH
            || k_rel.dot(u) < -1.0;
        let first = (!away).then(|| ((k_rel.perp_dot(u).abs()).floor() as usize).max(1));
        Line { length, u, first }
    }
}

/// The shot search's view of the keeper.
struct Keeper<'a> {
    player: &'a Player,
    /// Its body direction as a unit vector.
    facing: DVec2,
    /// Distance from the shooter to the keeper.
    from_shooter: f64,
    /// What [`keeper_verdict`] reads of the keeper at each cycle below
    /// [`NEAR_CYCLES`], the same for every course of the search.
    near: [Near; NEAR_CYCLES],
}

/// Cycles of a course for which [`Keeper::near`] holds the keeper's tests.
const NEAR_CYCLES: usize = 32;

/// The keeper at one cycle of a course ([`Keeper::near`]).
#[derive(Clone, Copy, Default)]
struct Near {
    /// Where it drifts to.
    drift: DVec2,
    /// The squared distances beyond which it neither catches the ball nor
    /// comes close, with the ball inside its penalty area and outside.
    far_in_sq: f64,
    far_out_sq: f64,
}

impl Near {
    /// Keeper `k0`, `from_shooter` from the shooter, at cycle `c`.
    fn new(k0: &Player, from_shooter: f64, c: usize) -> Self {
        let far = |in_area: bool| {
            let control = if in_area {
                KEEPER_CONTROL_AREA
            } else {
                KICKABLE_AREA
            };
            let margin = if in_area { 0.02 * from_shooter } else { 0.0 };
            let far = (dash_distance(c) + 0.9 * control) / 0.999 + margin;
            far * far
        };
        Near {
            drift: k0.pos + k0.vel * DRIFT[c.min(DRIFT.len() - 1)],
            far_in_sq: far(true),
            far_out_sq: far(false),
        }
    }
}

impl<'a> Keeper<'a> {
    fn new(s: &'a Situation) -> Self {
        let player = &s.world.keeper;
        let to_keeper = player.pos - s.me().pos;
        Keeper::at(player, to_keeper.length())
    }

    /// The keeper `player`, `from_shooter` from the shooter.
    fn at(player: &'a Player, from_shooter: f64) -> Self {
        let mut near = [Near::default(); NEAR_CYCLES];
        for (c, n) in near.iter_mut().enumerate() {
            *n = Near::new(player, from_shooter, c);
        }
        Keeper {
            player,
            facing: unit(player.body),
            from_shooter,
            near,
        }
    }
}

/// The keeper test of a course along `line` from `ball` at `speed` (spec
/// 6.2.1 step 3): `None` if the keeper catches the ball, else whether it
/// never even gets close.
fn keeper_verdict(keeper: &Keeper, ball: DVec2, line: &Line, speed: f64) -> Option<bool> {
    // A course too slow to reach the target (or of no speed) is, to HFO,
    // one step to the goal: `calc_length_geom_series` returns -1 for it,
    // and -1 <= 1.
    if speed <= GEOM_SERIES_EPS || 1.0 + line.length * (BALL_DECAY - 1.0) / speed <= GEOM_SERIES_EPS
    {
        return Some(true);
    }
    let ratio = 0.06 * line.length / speed;
    let Some(first) = line.first else {
        return Some(true);
    };
    let steps = ceil_usize((1.0 - ratio).ln() / BALL_DECAY.ln());
    if steps <= 1 {
        return Some(true);
    }
    let k0 = keeper.player;
    let mut never = true;
    let (mut ball_travel, mut decay_pow) = (0.0, 1.0);
    for c in 1..steps {
        ball_travel += speed * decay_pow;
        decay_pow *= BALL_DECAY;
        if c < first {
            continue;
        }
        let b = ball + line.u * ball_travel;
        if b.x > PITCH_HALF_LENGTH {
            break;
        }
        let in_area = b.x >= PENALTY_AREA_X && b.y.abs() <= PENALTY_AREA_HALF_WIDTH;
        let control = if in_area {
            KEEPER_CONTROL_AREA
        } else {
            KICKABLE_AREA
        };
        let margin = if in_area {
            0.02 * keeper.from_shooter
        } else {
            0.0
        };
        // Beyond `far` the keeper neither catches nor comes close (the tests below).
        let near = match keeper.near.get(c) {
            Some(&near) => near,
            None => Near::new(k0, keeper.from_shooter, c),
        };
        let (k, far_sq) = (
            near.drift,
            if in_area {
                near.far_in_sq
            } else {
                near.far_out_sq
            },
        );
        let dist_sq = b.distance_squared(k);
        if dist_sq > far_sq {
            continue;
        }
        let dist = dist_sq.sqrt() - margin;
        if dist - control - 0.15 < 0.001 {
            return None;
        }
        let mut dash_dist = dist - 0.9 * control;
        if c > 1 {
            dash_dist *= 0.999;
        }
        let n_dash = dash_cycles(dash_dist);
        if n_dash > c {
            continue; // too far even without turning: neither caught nor close
        }
        let n_turn = turn_cycles(keeper, b - k, dist, control);
        let n = n_turn + n_dash + usize::from(n_turn > 0);
        let bonus: isize = if in_area { 0 } else { -1 };
        if n as isize <= c as isize + bonus {
            return None;
        }
        if in_area && n <= c + 1 {
            never = false;
        }
    }
    Some(never)
}

/// cos(15°): the smallest turn threshold of `predict_player_turn_cycle`.
const COS_15_DEG: f64 = 0.965_925_826_289_068_3;

/// agent2d's `predict_player_turn_cycle` for the keeper facing `rel`.
fn turn_cycles(keeper: &Keeper, rel: DVec2, dist: f64, control: f64) -> usize {
    let ratio = (control + 0.1) / dist;
    // Facing well inside the threshold (a margin far above rounding): no
    // turn, decided by cosines without the angles' atan2 and asin.
    let mut cos = rel.dot(keeper.facing) / rel.length();
    if dist < 5.0 {
        cos = cos.abs();
    }
    if ratio < 1.0 && cos > COS_15_DEG.min((1.0 - ratio * ratio).sqrt()) + 1e-9 {
        return 0;
    }
    turn_cycles_by_angle(keeper.player, rel, dist, ratio)
}

/// [`turn_cycles`] from the angles; `ratio` is `(control + 0.1) / dist`.
fn turn_cycles_by_angle(player: &Player, rel: DVec2, dist: f64, ratio: f64) -> usize {
    let mut angle = angle_diff(direction(rel), player.body);
    if dist < 5.0 && angle > FRAC_PI_2 {
        angle = PI - angle;
    }
    let threshold = 15f64.to_radians().max(asin_clamped(ratio));
    let mut speed = player.vel.length();
    let mut n = 0;
    while angle > threshold && n < 10 {
        angle -= max_turn(speed);
        speed *= PLAYER_DECAY;
        n += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::analysis::Analysis;
    use crate::sim::config::EnvConfig;
    use crate::sim::memory::AgentMemory;
    use crate::sim::world::World;

    /// One attacker at `x` on the axis with the ball at its feet, the keeper at `keeper`.
    fn world(x: f64, keeper: DVec2) -> World {
        let mut w = World::new(1);
        w.offense[0] = Player::new(DVec2::new(x, 0.0), 0.0);
        w.ball.pos = DVec2::new(x + 0.6, 0.0);
        w.keeper.pos = keeper;
        w
    }

    fn situation<'a>(
        w: &'a World,
        a: &'a Analysis,
        config: &'a EnvConfig,
        memory: &'a AgentMemory,
    ) -> Situation<'a> {
        Situation {
            world: w,
            analysis: a,
            config,
            agent: 0,
            memory,
        }
    }

    #[test]
    fn without_a_course_shoot_kicks_to_the_stale_course() {
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let w = world(5.0, GOAL_CENTER);
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        assert!(
            search(&s, Want::Best).first.is_none(),
            "the keeper reaches every course"
        );
        assert_eq!(command(&s), (zero_course(&s), None), "the zero course");
        let stale = ShotCourse {
            target: DVec2::new(PITCH_HALF_LENGTH, -5.5),
            speed: 2.2,
        };
        let remembered = AgentMemory {
            last_shot: Some(stale),
            ..AgentMemory::default()
        };
        let s = situation(&w, &a, &config, &remembered);
        let kick = smart_kick(s.me(), &w, stale.target, stale.speed, 0.99 * stale.speed);
        assert_eq!(command(&s), (kick, None));
        assert_ne!(kick, zero_course(&s));
    }

    #[test]
    fn the_zero_course_stops_the_ball_or_sends_it_along_0_degrees() {
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let mut w = world(5.0, GOAL_CENTER);
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        // A ball at rest at the agent's feet: a kick of no power.
        match zero_course(&s) {
            Command::Kick { power, .. } => assert!(power.abs() < 1e-9, "{power}"),
            other => panic!("{other:?}"),
        }
        // A rolling ball: the kick takes its speed away.
        w.ball.vel = DVec2::new(0.3, -0.2);
        let s = situation(&w, &a, &config, &memory);
        let Command::Kick { power, dir } = zero_course(&s) else {
            panic!("a kick");
        };
        let accel = unit(s.me().body + dir) * power * kick_rate(s.me(), w.ball.pos);
        assert!((w.ball.vel + accel).length() < 1e-9, "{accel}");
        // Too fast to stop in one kick: as fast as one kick can, along 0°.
        w.ball.vel = DVec2::new(2.8, 0.5);
        let s = situation(&w, &a, &config, &memory);
        let Command::Kick { power, dir } = zero_course(&s) else {
            panic!("a kick");
        };
        let accel = unit(s.me().body + dir) * power * kick_rate(s.me(), w.ball.pos);
        let vel = w.ball.vel + accel;
        assert!(vel.y.abs() < 1e-9 && vel.x > 2.8, "{vel}");
    }

    #[test]
    fn a_course_too_slow_to_reach_the_goal_is_one_step_to_it() {
        // From 55 m no speed reaches the goal line: HFO counts each course
        // as one step to the goal, which the keeper never reaches.
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let w = world(-3.0, GOAL_CENTER);
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        let search = search(&s, Want::Best);
        let best = search.best.expect("every course is feasible");
        assert!(best.keeper_never_reaches);
        assert_eq!(best.speed, BALL_SPEED_MAX);
        let first = search.first.expect("a first course");
        assert!(first.target.y < 0.0, "from the left post");
    }

    #[test]
    fn searches_report_their_first_course() {
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let w = world(40.0, GOAL_CENTER);
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        let (_, first) = command(&s);
        let first = first.expect("a course from 12 m");
        // HFO lists courses from the left post, slowest first.
        assert!(first.target.y < 0.0);
        assert_eq!(check(&s), Some(first));
        // Beyond 30 m only SHOOT's own search looks (the keeper is out of play).
        let w = world(20.0, DVec2::new(0.0, 30.0));
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        assert!(command(&s).1.is_some());
        assert_eq!(check(&s), None);
    }

    #[test]
    fn keeper_needing_one_dash_too_many_never_reaches() {
        // agent2d maybeGoalieCatch skips a cycle c once the keeper needs more
        // than c dashes: here it needs c + 1 at best, so the course stays
        // "never reaches" (it would not if c + 1 dashes counted).
        let mut world = World::new(3);
        world.offense[0] = Player::new(DVec2::new(38.0, 0.0), 0.0);
        world.offense[1].pos = DVec2::new(10.0, 15.0);
        world.offense[2].pos = DVec2::new(10.0, -15.0);
        world.ball.pos = DVec2::new(38.6, 0.0);
        let k = DVec2::new(41.5, 3.0);
        world.keeper = Player::new(k, direction(world.ball.pos - k));
        let analysis = Analysis::new(&world);
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let s = Situation {
            world: &world,
            analysis: &analysis,
            config: &config,
            agent: 0,
            memory: &memory,
        };
        let keeper = Keeper::new(&s);
        let ball = world.ball.pos;
        let line = Line::new(&s, ball, DVec2::new(52.5, 5.0));
        for speed in [2.1, 2.7, 3.0] {
            assert_eq!(keeper_verdict(&keeper, ball, &line, speed), Some(true));
        }
    }

    proptest::proptest! {
        #[test]
        fn facing_within_the_threshold_by_cosine_agrees_with_the_angles(
            body in -PI..PI,
            dir in -PI..PI,
            dist in 1.0..20.0f64,
            speed in 0.0..1.0f64,
            control in proptest::sample::select(vec![KICKABLE_AREA, KEEPER_CONTROL_AREA]),
        ) {
            let mut player = Player::new(DVec2::new(45.0, 0.0), body);
            player.vel = unit(dir + 1.0) * speed;
            let rel = unit(dir) * (dist + 0.3);
            let keeper = Keeper::at(&player, 10.0);
            let ratio = (control + 0.1) / dist;
            proptest::prop_assert_eq!(
                turn_cycles(&keeper, rel, dist, control),
                turn_cycles_by_angle(&player, rel, dist, ratio)
            );
        }
    }

    #[test]
    fn in_the_goalie_catch_mode_searches_stop_at_one_full_power_kick() {
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let mut w = world(38.0, DVec2::new(50.0, 0.0));
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        assert_eq!(speed_limit(&s), BALL_SPEED_MAX);
        let fastest = |s: &Situation| search(s, Want::Best).best.map(|c| c.speed);
        assert_eq!(fastest(&s), Some(BALL_SPEED_MAX));
        w.catch_mode = true;
        let s = situation(&w, &a, &config, &memory);
        let limit = MAX_KICK_POWER * kick_rate(s.me(), w.ball.pos);
        assert_eq!(speed_limit(&s), limit);
        assert!(fastest(&s).is_some_and(|v| v <= limit));
        // Beyond the server's kickable area the kick rate is 0: the one
        // speed tried is 0, which HFO's geometric series counts as one
        // step to the goal.
        w.ball.pos.x = 38.0 + KICKABLE_AREA + 0.01;
        let s = situation(&w, &a, &config, &memory);
        assert_eq!(speed_limit(&s), 0.0);
        assert_eq!(fastest(&s), Some(0.0));
    }

    #[test]
    fn dribble_in_the_goalie_catch_mode_only_shoots() {
        let (config, memory) = (EnvConfig::default(), AgentMemory::default());
        let mut w = world(38.0, DVec2::new(51.0, 6.0));
        w.catch_mode = true;
        let a = Analysis::new(&w);
        let s = situation(&w, &a, &config, &memory);
        let (kick, first) = strict_check(&s);
        let Command::Kick { power, .. } = kick else {
            panic!("a shot, not {kick:?}");
        };
        assert!(power > 90.0, "one hard kick: {power}");
        assert!(first.is_some());
        // Beyond 30 m of the goal centre there is no command at all.
        let far = world(20.0, DVec2::new(51.0, 6.0));
        let s = situation(&far, &a, &config, &memory);
        assert_eq!(strict_check(&s), (Command::None, None));
    }
}
