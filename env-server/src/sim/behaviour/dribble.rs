//! DRIBBLE (spec 6.3): turn to face forward if badly oriented (kicking the
//! ball aside first if it would get away), else the short dribble that
//! agent2d's field evaluator rates above the current state, else hold the
//! ball. HFO never shoots here: the chain action's
//! command replaces any shot `doPreprocess` queued.

use super::body::{player_reach_cycle, predict_turn_cycles, turn_to_point};
use super::hold::hold_ball;
use super::kick::{kick_to_velocity, max_one_kick_speed};
use super::situation::Situation;
use crate::sim::geom::{angle_diff, asin_clamped, direction, normalize_angle, polar, unit};
use crate::sim::kinematics::{dash_cycles, decay_sum, max_turn};
use crate::sim::params::*;
use crate::sim::physics::{Command, max_kick_accel, update_stamina};
use crate::sim::world::{Player, World};
use glam::DVec2;
use std::f64::consts::PI;

/// Stamina a planned dribble dash keeps in reserve (`recover_dec_thr`·8000 + 300,
/// agent2d ShortDribbleGenerator::createSelfCache).
const DASH_STAMINA_RESERVE: f64 = 0.3 * STAMINA_MAX + 300.0;

/// A short-dribble candidate: the kick's first ball velocity and the trap point.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    first_vel: DVec2,
    ball_end: DVec2,
}

/// The DRIBBLE command of a kickable agent.
pub(super) fn command(s: &Situation) -> Command {
    let me = s.me();
    let ball = &s.world.ball;
    let forward = DVec2::new(42.0, 0.0);
    let keeper_near = s.world.keeper.pos.distance(me.pos) < 4.0;
    if angle_diff(me.body, direction(forward - me.pos)) >= 110f64.to_radians() && !keeper_near {
        let face = DVec2::new(42.0, 0.5 * me.pos.y);
        let self_next = me.pos + me.vel;
        let ball_next = ball.pos + ball.vel;
        let keep = KICKABLE_AREA - 0.1 * me.vel.length() - 0.05 * ball.vel.length() - 0.2;
        if self_next.distance(ball_next) < keep {
            return turn_to_point(me, face);
        }
        if let Some(vel) = keep_ball_vel(me, s.world) {
            return kick_to_velocity(me, ball, vel)
                .unwrap_or_else(|| hold_ball(me, s.world, Some(face), None));
        }
    }
    let mut candidates: Vec<Candidate> = (0..16).flat_map(|a| kick_candidates(s, me, a)).collect();
    // ShortDribbleGenerator sorts by distance to the goal; the first of equals wins.
    candidates.sort_by(|a, b| {
        let d = |c: &Candidate| c.ball_end.distance(GOAL_CENTER);
        d(a).total_cmp(&d(b))
    });
    let (holder, holder_is_me) = current_holder(s);
    let mut best = evaluate(s, ball.pos, holder, holder_is_me);
    let mut choice = None;
    for c in candidates {
        let value = evaluate(s, c.ball_end, c.ball_end, true);
        if value > best {
            best = value;
            choice = Some(c);
        }
    }
    choice
        .and_then(|c| kick_to_velocity(me, ball, c.first_vel))
        .unwrap_or_else(|| hold_ball(me, s.world, None, None))
}

/// agent2d's `Bhv_ChainAction::getKeepBallVel`: the ball velocity that
/// keeps the ball 0.735 m from where the player will be in two cycles, in
/// one of 12 directions, one kick's worth, the keeper latest to get there
/// (then the slowest); `None` when no direction can be kicked.
fn keep_ball_vel(me: &Player, world: &World) -> Option<DVec2> {
    let ball = &world.ball;
    let keep_dist = PLAYER_SIZE + 0.5 * KICKABLE_MARGIN + BALL_SIZE;
    let next = me.pos + me.vel;
    let next2 = next + me.vel * PLAYER_DECAY;
    let max_accel = max_kick_accel(me, ball.pos);
    let keeper = &world.keeper;
    let keeper_near = keeper.pos.distance(me.pos) <= 10.0;
    let mut best: Option<(DVec2, usize, f64)> = None;
    for a in 0..12 {
        let keep = next2 + polar(keep_dist, f64::from(a) * PI / 6.0);
        if keep.x.abs() > PITCH_HALF_LENGTH - 0.2 || keep.y.abs() > PITCH_HALF_WIDTH - 0.2 {
            continue;
        }
        let ball_move = keep - ball.pos;
        let speed = ball_move.length() / (1.0 + BALL_DECAY);
        if max_one_kick_speed(direction(ball_move), ball.vel, max_accel) < speed {
            continue;
        }
        let vel = ball_move.normalize_or_zero() * speed;
        let ball_next = ball.pos + vel;
        let target = if next.distance(ball_next) < PLAYER_SIZE + BALL_SIZE {
            ball_next - vel * (0.1 * BALL_DECAY)
        } else {
            keep
        };
        // A keeper more than 10 m away, or already there (step 0), counts
        // as never getting there.
        let step = match keeper_near {
            true => player_reach_cycle(keeper, target, KICKABLE_AREA),
            false => 0,
        };
        let step = if step == 0 { 1000 } else { step };
        let better = best.is_none_or(|(_, best_step, best_speed)| {
            step > best_step || (step == best_step && best_speed > speed)
        });
        if better {
            best = Some((vel, step, speed));
        }
    }
    best.map(|(vel, ..)| vel)
}

/// The ball holder of the current state (agent2d PredictState::init): the
/// teammate nearest to the ball if strictly nearer than this agent, else this
/// agent. Returns its position and whether it is this agent.
fn current_holder(s: &Situation) -> (DVec2, bool) {
    let me = s.me().pos;
    let ball = s.world.ball.pos;
    let mate = (0..s.world.offense.len())
        .filter(|&j| j != s.agent)
        .map(|j| s.world.offense[j].pos)
        .min_by(|a, b| {
            a.distance_squared(ball)
                .total_cmp(&b.distance_squared(ball))
        });
    match mate {
        Some(p) if p.distance_squared(ball) < me.distance_squared(ball) => (p, false),
        _ => (me, true),
    }
}

/// agent2d's SampleFieldEvaluator (spec 6.3.2) for the ball at `ball` and its
/// holder at `holder`.
fn evaluate(s: &Situation, ball: DVec2, holder: DVec2, holder_is_me: bool) -> f64 {
    if ball.x > PITCH_HALF_LENGTH - 0.1 && ball.y.abs() < GOAL_HALF_WIDTH + 2.0 {
        return 1e7;
    }
    if ball.x.abs() > PITCH_HALF_LENGTH || ball.y.abs() > PITCH_HALF_WIDTH {
        return f64::NEG_INFINITY;
    }
    let mut value = ball.x + (40.0 - ball.distance(GOAL_CENTER)).max(0.0);
    if can_shoot_from(holder, &s.world.keeper) {
        value += if holder_is_me { 1.5e6 } else { 1e6 };
    }
    value
}

/// `FieldAnalyzer::can_shoot_from` (20° clearance) (spec 6.3.2): some
/// direction into the goal clears the keeper's inertia point by 20° plus its
/// hide angle; a keeper more than 20 m away does not count.
fn can_shoot_from(from: DVec2, keeper: &Player) -> bool {
    if from.distance(GOAL_CENTER) > 17.0 {
        return false;
    }
    if keeper.pos.distance(from) > 20.0 {
        return true;
    }
    let minus = direction(DVec2::new(PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH + 0.5) - from);
    let plus = direction(DVec2::new(PITCH_HALF_LENGTH, GOAL_HALF_WIDTH - 0.5) - from);
    let width = angle_diff(plus, minus);
    let step = (width / 10.0).max(2f64.to_radians());
    let inertia = keeper.final_drift();
    let keeper_dir = direction(inertia - from);
    let hide = asin_clamped(CATCH_AREA_LENGTH / inertia.distance(from));
    let threshold = 20f64.to_radians();
    let mut a = 0.0;
    while a < width + 0.001f64.to_radians() {
        if angle_diff(minus + a, keeper_dir) - hide >= threshold {
            return true;
        }
        a += step;
    }
    false
}

/// Kick-turns-dashes candidates along body + 22.5°·a for 4, 3 and 2 dashes
/// (agent2d ShortDribbleGenerator::createCourses, spec 6.3.1).
fn kick_candidates<'a>(
    s: &'a Situation<'a>,
    me: &'a Player,
    a: usize,
) -> impl Iterator<Item = Candidate> + 'a {
    let rel_angle = a as f64 * PI / 8.0;
    let raw_dir = me.body + rel_angle;
    let backward = me.pos.x < 16.0 && normalize_angle(raw_dir).abs() > 100f64.to_radians();
    let mut left = normalize_angle(rel_angle).abs();
    let mut speed = me.vel.length() * PLAYER_DECAY; // the first cycle is the kick
    let mut n_turn = 0;
    while left > 10f64.to_radians() && n_turn < 3 {
        left = (left - max_turn(speed)).max(0.0);
        speed *= PLAYER_DECAY;
        n_turn += 1;
    }
    let dir = if rel_angle < PI {
        raw_dir - left
    } else {
        raw_dir + left
    };
    let ok = n_turn < 3 && !backward;
    let cache = if ok {
        self_cache(me, dir, n_turn)
    } else {
        Vec::new()
    };
    [4usize, 3, 2]
        .into_iter()
        .filter(move |_| ok)
        .filter_map(move |n_dash| kick_candidate(s, me, dir, n_turn, n_dash, &cache))
}

/// The kicker's positions after the kick cycle, each turn and each of 4
/// stamina-safe full dashes along `dir` (agent2d ShortDribbleGenerator::createSelfCache).
fn self_cache(me: &Player, dir: f64, n_turn: usize) -> Vec<DVec2> {
    let mut stamina = *me;
    let mut pos = me.pos;
    let mut vel = me.vel;
    let mut cache = Vec::with_capacity(1 + n_turn + 4);
    for _ in 0..=n_turn {
        pos += vel;
        vel *= PLAYER_DECAY;
        cache.push(pos);
        update_stamina(&mut stamina);
    }
    for _ in 0..4 {
        let power = (stamina.stamina - DASH_STAMINA_RESERVE).clamp(0.0, MAX_DASH_POWER);
        vel += polar(power * DASH_POWER_RATE * stamina.effort, dir);
        pos += vel;
        vel *= PLAYER_DECAY;
        cache.push(pos);
        stamina.stamina = (stamina.stamina - power).max(0.0);
        update_stamina(&mut stamina);
    }
    cache
}

/// One course of ShortDribbleGenerator::simulateKickTurnsDashes, if feasible.
fn kick_candidate(
    s: &Situation,
    me: &Player,
    dir: f64,
    n_turn: usize,
    n_dash: usize,
    cache: &[DVec2],
) -> Option<Candidate> {
    let ball = &s.world.ball;
    let trap = cache[n_turn + n_dash] + polar(PLAYER_SIZE + 0.2 * KICKABLE_MARGIN + BALL_SIZE, dir);
    if trap.x.abs() > PITCH_HALF_LENGTH - 1.0 || trap.y.abs() > PITCH_HALF_WIDTH - 1.0 {
        return None;
    }
    let cycles = 1 + n_turn + n_dash;
    let first_vel = (trap - ball.pos) / decay_sum(BALL_DECAY, cycles as u32);
    if first_vel.length() > BALL_SPEED_MAX
        || (first_vel - ball.vel).length() > max_kick_accel(me, ball.pos)
    {
        return None;
    }
    if (ball.pos + first_vel).distance(cache[0]) < PLAYER_SIZE + BALL_SIZE + 0.1 {
        return None;
    }
    if keeper_gets_there_first(s, me, trap, cycles) {
        return None;
    }
    Some(Candidate {
        first_vel,
        ball_end: trap,
    })
}

/// Whether the keeper reaches the trap point in time
/// (agent2d ShortDribbleGenerator::checkOpponent, spec 6.3.1).
fn keeper_gets_there_first(s: &Situation, me: &Player, trap: DVec2, cycles: usize) -> bool {
    let keeper = &s.world.keeper;
    let ball = s.world.ball.pos;
    let behind = (keeper.pos - ball).dot(unit(direction(trap - ball))) < -4.0;
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
    if dist - control < 0.001 {
        return true;
    }
    let n_dash = dash_cycles(dist - 0.5 * control - 0.2);
    let n_turn = predict_turn_cycles(keeper, direction(trap - drift), dist, control);
    let steps = if n_turn == 0 {
        n_dash
    } else {
        n_turn + n_dash + 1
    };
    steps as i64 <= cycles as i64 + opponent_bonus(keeper, trap)
}

/// Cycles a dribble may take beyond the keeper's reach estimate: +1 for a
/// trap point at x < 30, +1 more at x < 0; a keeper frozen by its tackle
/// counts as 5 cycles slower instead (ShortDribbleGenerator::checkOpponent).
fn opponent_bonus(keeper: &Player, trap: DVec2) -> i64 {
    if keeper.tackle_freeze > 0 {
        return -5;
    }
    i64::from(trap.x < 30.0) + i64::from(trap.x < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::analysis::Analysis;
    use crate::sim::config::EnvConfig;
    use crate::sim::memory::AgentMemory;
    use crate::sim::world::World;

    fn with_situation<T>(world: &World, f: impl FnOnce(&Situation) -> T) -> T {
        let analysis = Analysis::new(world);
        let config = EnvConfig::default();
        f(&Situation {
            world,
            analysis: &analysis,
            config: &config,
            agent: 0,
            memory: &AgentMemory::default(),
        })
    }

    #[test]
    fn facing_backwards_the_dribbler_kicks_the_ball_aside_to_keep_it() {
        // Bhv_ChainAction::doTurnToForward: the ball too far to just turn,
        // no keeper within 4 m: one kick puts the ball 0.735 m from where
        // the player will be two cycles on, as slowly as possible.
        let mut world = World::new(1);
        world.offense[0] = Player::new(DVec2::new(20.0, 0.0), PI);
        world.ball.pos = DVec2::new(19.0, 0.0);
        world.keeper.pos = DVec2::new(45.0, 0.0);
        let cmd = with_situation(&world, command);
        assert!(matches!(cmd, Command::Kick { .. }), "{cmd:?}");
        let vel = keep_ball_vel(&world.offense[0], &world).expect("a keep velocity");
        let keep = world.ball.pos + vel * (1.0 + BALL_DECAY);
        assert!(
            (keep.distance(world.offense[0].pos) - 0.735).abs() < 1e-9,
            "{keep}"
        );
        // The slowest: the keep point nearest the ball, ahead of the body.
        assert!(keep.x < 20.0 && vel.length() < 0.2, "{vel}");
    }

    #[test]
    fn dribble_never_dashes() {
        // HFO compiles the dash-only candidates out: a rolling ball ahead of
        // the dribbler is kicked, held or turned with, never chased by a dash.
        let mut world = World::new(3);
        world.offense[1].pos = DVec2::new(10.0, 15.0);
        world.offense[2].pos = DVec2::new(10.0, -15.0);
        for i in 0..12 {
            for j in 0..6 {
                let me = DVec2::new(15.0 + 2.0 * i as f64, -6.0 + 2.0 * j as f64);
                world.offense[0] = Player::new(me, 0.0);
                world.offense[0].vel = DVec2::new(0.6, 0.0);
                world.ball.pos = me + DVec2::new(0.7, 0.0);
                world.ball.vel = DVec2::new(0.2 + 0.1 * j as f64, 0.0);
                let cmd = with_situation(&world, command);
                assert!(!matches!(cmd, Command::Dash { .. }), "{me}: {cmd:?}");
            }
        }
    }

    #[test]
    fn a_tackling_keeper_counts_five_cycles_slower() {
        let mut world = World::new(3);
        world.offense[0] = Player::new(DVec2::new(40.0, 0.0), 0.0);
        world.ball.pos = DVec2::new(40.7, 0.0);
        world.keeper = Player::new(DVec2::new(47.0, 0.0), PI);
        let trap = DVec2::new(44.0, 0.0);
        // Three dashes bring the keeper within reach of a 5-cycle dribble.
        assert!(with_situation(&world, |s| keeper_gets_there_first(
            s,
            s.me(),
            trap,
            5
        )));
        // Frozen by its tackle, it would need 3 + 5 > 5 cycles.
        world.keeper.tackle_freeze = 4;
        assert!(!with_situation(&world, |s| keeper_gets_there_first(
            s,
            s.me(),
            trap,
            5
        )));
    }

    #[test]
    fn can_shoot_from_looks_at_the_keeper_inertia_point() {
        let from = DVec2::new(36.0, 0.0);
        let mut keeper = Player::new(DVec2::new(50.0, 0.0), PI);
        assert!(!can_shoot_from(from, &keeper));
        // Drifting 1.67 m sideways opens the far half of the goal.
        keeper.vel = DVec2::new(0.0, 1.0);
        assert!(can_shoot_from(from, &keeper));
        // A keeper more than 20 m away never blocks.
        let far = Player::new(DVec2::new(52.0, 20.0), PI);
        assert!(can_shoot_from(DVec2::new(35.7, 0.0), &far));
    }

    #[test]
    fn current_state_is_rated_at_the_holder() {
        let mut world = World::new(3);
        world.keeper = Player::new(DVec2::new(52.0, 20.0), PI);
        world.offense[0].pos = DVec2::new(35.7, 0.0); // 16.8 m from the goal
        world.ball.pos = DVec2::new(34.9, 0.0); // 17.6 m: no shot from the ball
        world.offense[1].pos = DVec2::new(10.0, 15.0);
        world.offense[2].pos = DVec2::new(10.0, -15.0);
        let ball = world.ball.pos;
        let base = ball.x + 40.0 - ball.distance(GOAL_CENTER);
        with_situation(&world, |s| {
            let (holder, mine) = current_holder(s);
            assert!(mine && holder == s.me().pos);
            assert!((evaluate(s, ball, holder, mine) - base - 1.5e6).abs() < 1e-6);
        });
        // A teammate nearer to the ball holds it: the bonus drops to 1e6.
        world.offense[2].pos = DVec2::new(35.6, 0.3);
        with_situation(&world, |s| {
            let (holder, mine) = current_holder(s);
            assert!(!mine && holder == DVec2::new(35.6, 0.3));
            assert!((evaluate(s, ball, holder, mine) - base - 1e6).abs() < 1e-6);
        });
    }
}
