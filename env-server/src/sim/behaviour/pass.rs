//! PASS (spec 6.4): the best safe direct, lead or through pass to a
//! teammate, or no command when there is none.

use super::situation::Situation;
use super::smart_kick::{kick_one_step, planned_kick, smart_kick};
use crate::sim::geom::{direction, polar, unit};
use crate::sim::params::*;
use crate::sim::physics::{Command, kick_rate};
use crate::sim::world::Player;
use glam::DVec2;

/// A pass route: receive point and first speed.
#[derive(Clone, Copy, Debug)]
struct Route {
    target: DVec2,
    speed: f64,
}

/// The PASS command of a kickable agent; `receiver` restricts the routes to
/// one teammate (HFO itself ignores the requested receiver).
pub(super) fn command(s: &Situation, receiver: Option<usize>) -> Command {
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
    let (me, world) = (s.me(), s.world);
    match best {
        // Force_Pass in the goalie-catch mode (spec 4.5): one kick, else
        // Body_KickOneStep at most as fast as one full-power kick.
        Some((_, r)) if world.catch_mode => {
            planned_kick(me, world, r.target, (r.speed, 0.96 * r.speed), 1).unwrap_or_else(|| {
                let speed = r.speed.min(MAX_KICK_POWER * kick_rate(me, world.ball.pos));
                kick_one_step(me, world, r.target, speed)
            })
        }
        Some((_, r)) => smart_kick(me, world, r.target, r.speed, 0.96 * r.speed),
        None => Command::None,
    }
}

/// Cycles a ball moving at `speed` needs to travel `dist`, or `None` if it
/// stops short (librcsc `calc_length_geom_series`).
fn ball_cycles(dist: f64, speed: f64) -> Option<f64> {
    let ratio = 1.0 - (1.0 - BALL_DECAY) * dist / speed;
    (ratio > 0.0).then(|| ratio.ln() / BALL_DECAY.ln())
}

/// Whether the keeper can cut the ball's path to `target` kicked at `speed`
/// (the path test of `verify_direct_pass` and `verify_through_pass`): in
/// coordinates along the pass from the ball's next position, a keeper
/// between it and the target's distance must be farther from the line than
/// the kickable area plus 0.1 m, and need more cycles at 1 m/cycle to cover
/// that than the ball (at its next speed) needs to pass it.
fn keeper_near_path(s: &Situation, target: DVec2, speed: f64) -> bool {
    let ball = s.world.ball.pos;
    let dir = direction(target - ball);
    let u = unit(dir);
    let rel = s.world.keeper.pos - ball - u * speed;
    let along = rel.dot(u);
    if along <= 0.0 || along >= target.distance(ball) {
        return false;
    }
    let across = rel.perp_dot(u).abs() - KICKABLE_AREA - 0.1;
    across < 0.0 || ball_cycles(along, speed * BALL_DECAY).is_none_or(|n| across < n)
}

/// `create_direct_pass` (spec 6.4 step 2). Its back-pass test (a receiver
/// less than 5 m ahead must lie within 40° of straight ahead unless it is
/// beyond the defence line) never rejects: librcsc's `PlayerObject` shadows
/// the angle `angleFromSelf()` returns, which stays 0° (spec 6.4).
fn direct_passes(s: &Situation, mate: &Player, consider: &mut impl FnMut(Route)) {
    let me = s.me();
    let ball = s.world.ball.pos;
    let r = mate.pos;
    let d_self = r.distance(me.pos);
    if r.x.abs() > 49.5 || r.y.abs() > 31.0 || !(6.0..=40.0).contains(&d_self) {
        return;
    }
    // The receiver's position one cycle of velocity ahead, divided by the
    // player decay (`create_direct_pass` with a velocity seen this cycle).
    let receive = r + mate.vel / PLAYER_DECAY;
    let dist = receive.distance(ball);
    let Some(speed) = (0..=6)
        .map(|k| 1.5 - 0.1 * k as f64)
        .map(|end| end + 0.0638 * dist)
        .find(|&v0| v0 <= BALL_SPEED_MAX)
    else {
        return;
    };
    let spread = KICKABLE_AREA / dist;
    let base = direction(receive - ball);
    let aims = [
        (0.0, speed),
        (spread, 0.94 * speed),
        (-spread, 0.94 * speed),
    ];
    for (offset, v0) in aims {
        let target = ball + polar(dist, base + offset);
        if direct_pass_safe(s, target, v0) {
            consider(Route { target, speed: v0 });
        }
    }
}

/// `verify_direct_pass`: the keeper is ignored when the pass direction is
/// more than 100° from its `angleFromSelf()`, which is always 0° (see
/// `direct_passes`); otherwise it must be at least 3 m from the target and
/// off the ball's path.
fn direct_pass_safe(s: &Situation, target: DVec2, speed: f64) -> bool {
    let keeper = s.world.keeper.pos;
    if direction(target - s.world.ball.pos).abs() > 100f64.to_radians() {
        return true;
    }
    keeper.distance(target) >= 3.0 && !keeper_near_path(s, target, speed)
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
            let angle = base + sign * k as f64 * step;
            if !seen_lately(s, angle) {
                continue;
            }
            let target = ball + polar(dist, angle);
            if !inside_shrunk_pitch(target) || lead_back_pass(target, me.pos.x, r.x) {
                continue;
            }
            if through_pass_safe(s, mate, target, speed) {
                consider(Route { target, speed });
            }
        }
    }
}

/// `create_lead_pass` ignores back passes: 6 m behind the receiver, or, at
/// x < 0, behind the passer or 3 m behind the receiver.
fn lead_back_pass(target: DVec2, passer_x: f64, receiver_x: f64) -> bool {
    target.x < receiver_x - 6.0
        || (target.x < 0.0 && (target.x < passer_x || target.x < receiver_x - 3.0))
}

/// `create_through_pass` (spec 6.4 step 4); its receiver-angle test (over
/// 135°) never rejects, as `angleFromSelf()` is 0° (see `direct_passes`).
fn through_passes(s: &Situation, mate: &Player, consider: &mut impl FnMut(Route)) {
    let me = s.me();
    let ball = s.world.ball.pos;
    let r = mate.pos;
    let line = s.world.offside_line;
    if r.x > line - 0.5
        || r.x < me.pos.x - 10.0
        || (r.y - me.pos.y).abs() > 35.0
        || (line < 30.0 && r.x < line - 15.0)
    {
        return;
    }
    for theta in [-20.0f64, -10.0, 0.0, 10.0, 20.0] {
        for l in [5.0, 9.0, 13.0, 17.0, 21.0, 25.0] {
            let target = r + polar(l, theta.to_radians());
            let dist = target.distance(ball);
            if !inside_shrunk_pitch(target)
                || target.x < me.pos.x + 3.0
                || !seen_lately(s, direction(target - ball))
                || dist > 45.0
                || dist < l
            {
                continue;
            }
            let receiver_cycles = target.distance(r);
            let speed = (0..4)
                .map(|i| 0.81 - 0.1 * i as f64)
                .map(|end| end + 0.0638 * dist)
                .find(|&v0| {
                    v0 <= BALL_SPEED_MAX
                        && ball_cycles(dist, v0).is_some_and(|n| receiver_cycles <= n)
                });
            if let Some(speed) = speed
                && through_pass_safe(s, mate, target, speed)
            {
                consider(Route { target, speed });
            }
        }
    }
}

/// The lead and through passes' direction check: the passer has looked
/// within 10° either side of `angle` (radians) lately, every 5° bin within 9
/// cycles and their average within 3 (`dirRangeCount(angle, 20)`).
fn seen_lately(s: &Situation, angle: f64) -> bool {
    let (max, average) = s.memory.sight.range_count(angle.to_degrees(), 20.0);
    max <= 9 && average <= 3
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

/// `evaluate_routes` (spec 6.4 step 6): 0.95 per cycle since the passer
/// last looked within 10° of the pass direction.
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
    let (max_count, _) = s
        .memory
        .sight
        .range_count(direction(q - me.pos).to_degrees(), 20.0);
    score * 0.95f64.powi(i32::from(max_count))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::analysis::Analysis;
    use crate::sim::config::EnvConfig;
    use crate::sim::memory::AgentMemory;
    use crate::sim::view::Sight;
    use crate::sim::world::World;

    /// Passer 0 at (10, 0) with the ball at its feet, teammate 1 at `mate`,
    /// the keeper at `keeper`.
    fn world(mate: DVec2, keeper: DVec2) -> World {
        let mut w = World::new(2);
        w.offense[0] = Player::new(DVec2::new(10.0, 0.0), 0.0);
        w.offense[1] = Player::new(mate, 0.0);
        w.ball.pos = DVec2::new(10.6, 0.0);
        w.keeper.pos = keeper;
        w.offside_line = 40.0;
        w
    }

    /// `f` applied to agent 0's situation in `w`.
    fn in_situation<R>(w: &World, f: impl FnOnce(&Situation) -> R) -> R {
        remembering(w, &AgentMemory::default(), f)
    }

    /// `f` applied to agent 0's situation in `w` with its memory `memory`.
    fn remembering<R>(w: &World, memory: &AgentMemory, f: impl FnOnce(&Situation) -> R) -> R {
        let (a, config) = (Analysis::new(w), EnvConfig::default());
        f(&Situation {
            world: w,
            analysis: &a,
            config: &config,
            agent: 0,
            memory,
        })
    }

    fn direct_routes(w: &World) -> Vec<Route> {
        let mut routes = Vec::new();
        in_situation(w, |s| {
            direct_passes(s, &w.offense[1], &mut |r| routes.push(r))
        });
        routes
    }

    #[test]
    fn a_direct_pass_aims_at_the_receiver_plus_its_velocity_over_the_decay() {
        let mut w = world(DVec2::new(20.0, 12.0), DVec2::new(50.0, 0.0));
        w.offense[1].vel = DVec2::new(0.3, -0.2);
        let routes = direct_routes(&w);
        let aim = DVec2::new(20.75, 11.5);
        assert!(routes[0].target.distance(aim) < 1e-9, "{routes:?}");
    }

    #[test]
    fn the_keeper_rejects_each_direct_target_within_3_m_of_it() {
        // Receive point (30.6, 0), the keeper just beyond it, off the path:
        // 3.4 m from it, but 2.9 m from the candidate one kickable area to
        // its left.
        let w = world(DVec2::new(30.6, 0.0), DVec2::new(33.4, 1.9));
        let routes = direct_routes(&w);
        assert_eq!(routes.len(), 2, "{routes:?}");
        assert!(
            routes
                .iter()
                .all(|r| r.target.distance(w.keeper.pos) >= 3.0)
        );
    }

    #[test]
    fn the_keeper_cuts_a_pass_it_reaches_before_the_ball_passes() {
        // Ball at (10.6, 0) to (30.6, 0) at 2.0: 10 m along from the ball's
        // next position the ball needs 6.2 cycles, the keeper |y| - 1.185.
        let keeper_at = |y: f64| world(DVec2::new(30.6, 0.0), DVec2::new(22.6, y));
        let near = |w: &World| in_situation(w, |s| keeper_near_path(s, DVec2::new(30.6, 0.0), 2.0));
        assert!(near(&keeper_at(7.0)));
        assert!(!near(&keeper_at(8.0)));
        assert!(!near(&keeper_at(-8.0)));
    }

    #[test]
    fn a_direct_pass_may_go_sideways_or_back_as_angle_from_self_is_0() {
        // Teammates beside and behind the passer at x < 10: agent2d's back
        // pass test would cancel them if librcsc's angleFromSelf() worked.
        for mate in [DVec2::new(9.0, 9.0), DVec2::new(2.0, -4.0)] {
            let routes = direct_routes(&world(mate, DVec2::new(50.0, 0.0)));
            assert_eq!(routes.len(), 3, "{mate}: {routes:?}");
        }
    }

    #[test]
    fn the_keeper_is_ignored_for_a_direct_pass_more_than_100_degrees_off_0() {
        // The keeper 1 m from each receive point: it rejects a forward pass,
        // not a pass back towards our goal (the angle is the pass's own).
        let forward = world(DVec2::new(30.6, 0.0), DVec2::new(31.6, 0.0));
        assert!(direct_routes(&forward).is_empty());
        let back = world(DVec2::new(2.0, -4.0), DVec2::new(1.0, -4.0));
        assert_eq!(direct_routes(&back).len(), 3);
    }

    #[test]
    fn lead_and_through_passes_go_only_where_the_passer_looked_lately() {
        let routes = |count| {
            let w = world(DVec2::new(20.0, 12.0), DVec2::new(50.0, 0.0));
            let memory = AgentMemory {
                sight: Sight::with_counts(count),
                ..AgentMemory::default()
            };
            let mut n = 0;
            remembering(&w, &memory, |s| {
                lead_passes(s, &w.offense[1], &mut |_| n += 1);
                through_passes(s, &w.offense[1], &mut |_| n += 1);
            });
            n
        };
        assert!(routes(0) > 0);
        assert!(routes(3) > 0);
        assert_eq!(routes(4), 0, "average over 3");
        assert_eq!(routes(10), 0);
    }

    #[test]
    fn lead_passes_never_go_back_over_x_0_behind_the_passer() {
        assert!(lead_back_pass(DVec2::new(-0.5, 5.0), 2.0, -1.0));
        assert!(lead_back_pass(DVec2::new(-0.5, 5.0), -1.0, 3.0));
        assert!(!lead_back_pass(DVec2::new(-0.5, 5.0), -1.0, 2.0));
        assert!(lead_back_pass(DVec2::new(10.0, 5.0), 0.0, 16.5));
        assert!(!lead_back_pass(DVec2::new(10.0, 5.0), 20.0, 15.0));
    }

    #[test]
    fn in_the_goalie_catch_mode_a_pass_is_one_kick() {
        // The ball behind the passer: play-on's smart kick first moves it
        // around the body; after a catch Force_Pass kicks it away at once.
        let mut w = world(DVec2::new(25.0, 10.0), DVec2::new(50.0, 0.0));
        w.ball.pos = DVec2::new(9.4, 0.0);
        let kicked = |w: &World| match in_situation(w, |s| command(s, None)) {
            Command::Kick { power, dir } => {
                let rate = kick_rate(&w.offense[0], w.ball.pos);
                w.ball.vel + polar(power * rate, w.offense[0].body + dir)
            }
            other => panic!("a kick, not {other:?}"),
        };
        let towards_mate = direction(w.offense[1].pos - w.ball.pos);
        let play_on = kicked(&w);
        w.catch_mode = true;
        let one_kick = kicked(&w);
        let off = |v: DVec2| crate::sim::geom::angle_diff(direction(v), towards_mate).to_degrees();
        assert!(off(play_on) > 10.0, "{play_on}");
        assert!(off(one_kick) < 5.0, "{one_kick}");
        assert!(one_kick.length() > play_on.length());
    }
}
