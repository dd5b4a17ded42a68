//! An attacker's Body_Intercept (spec 6.1.3): where it intercepts the ball,
//! librcsc's `Body_Intercept2009::getBestIntercept`
//! (rcsc/action/body_intercept2009.cpp, lines 225-757, field-player mode)
//! over the cycles of its self-interception cache
//! (`SelfInterceptV13::predict`, rcsc/player/self_intercept_v13.cpp), and
//! the turn or dash that takes it there.

use super::body::{go_to_point, turn_to_direction, turn_to_point};
use crate::sim::analysis::Analysis;
use crate::sim::geom::{angle_diff, asin_clamped, direction};
use crate::sim::kinematics::decay_pow;
use crate::sim::params::*;
use crate::sim::physics::Command;
use crate::sim::self_intercept::{Interception, SHORT_STEPS};
use crate::sim::world::{Player, World};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// Where `getBestIntercept` measures the distance to the goal (line 240).
const GOAL: DVec2 = DVec2::new(65.0, 0.0);
/// `realSpeedMax() * 0.9` (line 250): 0.9 × the default player type's top
/// speed under full dashes, 0.6/(1 − 0.4) = 1 m/cycle (librcsc
/// rcsc/common/player_type.cpp lines 389-396).
const THROUGH_SPEED: f64 = 0.9 * MAX_DASH_POWER * DASH_POWER_RATE / (1.0 - PLAYER_DECAY);

/// What `getBestIntercept` reads of one cache entry.
struct InterceptCandidate {
    entry: Interception,
    /// Ball position at the entry's cycle.
    ball: DVec2,
    /// Ball velocity at the entry's cycle.
    vel: DVec2,
    /// Player's inertia point at the entry's cycle.
    drift: DVec2,
}

/// The best candidate of one of `getBestIntercept`'s kinds: the highest
/// score (the first of equals).
#[derive(Default)]
struct Best<'a> {
    found: Option<(&'a InterceptCandidate, f64)>,
}

impl<'a> Best<'a> {
    fn offer(&mut self, c: &'a InterceptCandidate, score: f64) {
        if self.found.is_none_or(|(_, s)| score > s) {
            self.found = Some((c, score));
        }
    }

    fn get(&self) -> Option<&'a InterceptCandidate> {
        self.found.map(|(c, _)| c)
    }
}

/// Where an attacker with the ball, or with the ball coming to it, faces.
pub(super) fn forward_point(y: f64) -> DVec2 {
    DVec2::new(50.5, 0.75 * y)
}

/// Body_Intercept (spec 6.1.3) for offense agent `agent`: towards the
/// interception `getBestIntercept` picks from its cache; `face` is where to
/// look when the ball comes to the player.
///
/// Simplified: from the chosen cycle on, the turn and the full dash follow
/// 6.1.2's others' rule with the own estimate's margin (0.15 m up to cycle
/// 5, 0.2 m later) instead of the cache entry's turns, power and direction
/// and librcsc's `doWaitTurn` and `doInertiaDash`.
pub(super) fn intercept(world: &World, analysis: &Analysis, agent: usize, face: DVec2) -> Command {
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

/// The interception attacker `p` goes for (`getBestIntercept`, field-player
/// mode), given its self-interception cache ([`crate::sim::self_intercept::predict_from`]);
/// `None` for an empty cache.
///
/// Each entry whose ball point lies inside the pitch less 1 m (lines 296-301)
/// and before the keeper (`opp_min`, the attackers' estimate of its reach)
/// is sorted into one kind (lines 367-530), in this order:
/// - *attacker*: the ball still moving forward faster than 0.5 m/cycle in x
///   and 0.9 m/cycle in all, a forward dash, x < 47 and x past 35 or the
///   offside line, before 0.95·`opp_min`; score goal closeness ×
///   exp(−(47 − x)²/200), highest wins;
/// - (the rest before 0.7·`opp_min`) *no turn*: earliest wins;
/// - *forward*: ball x-velocity > 0.1, speed > 0.6, 5 cycles before the
///   keeper; nearest the goal wins;
/// - *nearest*: the ball nearest the player's inertia point.
///
/// The choice among the kinds follows lines 586-753.
fn best_interception(
    p: &Player,
    world: &World,
    analysis: &Analysis,
    cache: &[Interception],
) -> Option<Interception> {
    let first = cache.first()?;
    let candidates: Vec<InterceptCandidate> = cache
        .iter()
        .map(|&entry| InterceptCandidate {
            entry,
            ball: analysis.ball_at(entry.cycle),
            vel: world.ball.vel * decay_pow(BALL_DECAY, entry.cycle as u32),
            drift: p.drift(entry.cycle as u32),
        })
        .collect();
    let opp_min = analysis.keeper_reach as f64;
    let (mut attacker, mut noturn, mut forward, mut nearest) = (
        Best::default(),
        Best::default(),
        Best::default(),
        Best::default(),
    );
    for c in &candidates {
        let (b, v) = (c.ball, c.vel);
        if b.x.abs() > PITCH_HALF_LENGTH - 1.0 || b.y.abs() > PITCH_HALF_WIDTH - 1.0 {
            continue;
        }
        let cycle = c.entry.cycle as f64;
        let is_attacker = v.x > 0.5
            && v.length_squared() > THROUGH_SPEED * THROUGH_SPEED
            && !c.entry.back()
            && b.x < 47.0
            && (b.x > 35.0 || b.x > world.offside_line);
        if cycle >= opp_min * if is_attacker { 0.95 } else { 0.7 } {
            continue;
        }
        if is_attacker {
            let closeness = 100.0 - b.distance(GOAL).min(100.0);
            let x_gap = 47.0 - b.x;
            attacker.offer(c, closeness / 100.0 * libm::exp(-x_gap * x_gap / 200.0));
        } else if c.entry.turns == 0 {
            noturn.offer(c, -cycle);
        } else if v.x > 0.1 && cycle <= opp_min - 5.0 && v.length_squared() > 0.36 {
            forward.offer(c, 10_000.0 - b.distance_squared(GOAL).min(10_000.0));
        } else {
            nearest.offer(c, -c.drift.distance_squared(b));
        }
    }
    let pick = |c: &InterceptCandidate| Some(c.entry);
    if let Some(a) = attacker.get() {
        return pick(a);
    }
    if let (Some(n), Some(f)) = (noturn.get(), forward.get()) {
        // Lines 597-629: a no-turn point on a ball still running forward.
        if n.vel.x > 0.1 && (n.vel.length() > THROUGH_SPEED || n.entry.cycle <= f.entry.cycle + 2) {
            return pick(n);
        }
    }
    if let Some(f) = forward.get() {
        return pick(f);
    }
    // Lines 641-654: the fastest point when late or slow (outside agent2d's
    // own penalty area, which HFO's attackers never defend).
    let fastest = &candidates[0];
    let fastest_ok = fastest.ball.x > -33.0 || fastest.ball.y.abs() > 20.0;
    if fastest_ok && (first.cycle >= 10 || fastest.vel.length() < 1.2) {
        return Some(*first);
    }
    match (noturn.get(), nearest.get()) {
        (Some(n), Some(m)) => pick(noturn_or_nearest(n, m)),
        (Some(n), None) => pick(n),
        (None, Some(m)) => pick(m),
        (None, None) => Some(chance(p, world, opp_min, cache).unwrap_or(*first)),
    }
}

/// Lines 656-732: between the earliest no-turn point `n` and the nearest
/// other point `m`.
fn noturn_or_nearest<'a>(
    n: &'a InterceptCandidate,
    m: &'a InterceptCandidate,
) -> &'a InterceptCandidate {
    if n.drift.distance_squared(n.ball) < m.drift.distance_squared(m.ball) {
        return n;
    }
    if m.entry.cycle <= n.entry.cycle + 2 {
        let m_speed = m.vel.length();
        if m_speed < 0.7 {
            return m;
        }
        if m.entry.ball_dist < KICKABLE_AREA - 0.4
            && m.entry.ball_dist < n.entry.ball_dist
            && n.vel.x < 0.5
            && n.vel.length_squared() > 1.0
            && n.ball.x > m.ball.x
        {
            return m;
        }
        if m_speed > 0.7 && m.drift.distance(m.ball) < KICKABLE_AREA {
            return m;
        }
    }
    n
}

/// Lines 734-754: near the goal with a fast ball running forward and every
/// entry ruled out, the last one within 3 cycles of the first and 2 cycles
/// before the keeper.
fn chance(p: &Player, world: &World, opp_min: f64, cache: &[Interception]) -> Option<Interception> {
    let first = cache.first()?.cycle;
    let vel = world.ball.vel;
    let ahead = direction(vel).abs() < 100f64.to_radians();
    if p.pos.x <= 40.0 || vel.length() <= 1.8 || !ahead || first <= 1 {
        return None;
    }
    cache
        .iter()
        .rev()
        .find(|c| c.cycle <= first + 3 && c.cycle as f64 <= opp_min - 2.0)
        .copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::analysis::update_offside_line;
    use crate::sim::self_intercept;
    use std::f64::consts::FRAC_PI_4;

    /// A world with the ball at `ball` moving at `vel`, attacker 0 at `mate`
    /// facing the goal, the others far from the play and the keeper in goal.
    fn scene(ball: DVec2, vel: DVec2, mate: DVec2) -> (World, Analysis) {
        let mut w = World::new(3);
        w.offense[0] = Player::new(mate, 0.0);
        w.offense[1].place(DVec2::new(0.0, -25.0));
        w.offense[2].place(DVec2::new(0.0, 25.0));
        w.keeper = Player::new(DVec2::new(51.0, 0.0), std::f64::consts::PI);
        w.ball.pos = ball;
        w.ball.vel = vel;
        update_offside_line(&mut w);
        let a = Analysis::new(&w);
        (w, a)
    }

    /// The interception attacker 0 picks.
    fn best(w: &World, a: &Analysis) -> Interception {
        let p = &w.offense[0];
        best_interception(
            p,
            w,
            a,
            &self_intercept::predict(p, &w.ball, a.path(), false),
        )
        .expect("a reachable ball")
    }

    #[test]
    fn a_teammate_runs_on_to_a_long_shot() {
        // A shot from x = 25 at 2 m/cycle passes 4 m from a teammate at
        // x = 34: it could meet the ball earliest at x = 33.9 (cycle 5) by
        // turning back across, but runs on to meet it past x = 35.
        let (w, a) = scene(
            DVec2::new(25.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(34.0, -4.0),
        );
        assert_eq!(a.own_reach[0], 5);
        assert!(a.ball_at(a.own_reach[0]).x < 34.0);
        let best = best(&w, &a);
        assert!(a.ball_at(best.cycle).x > 35.0, "{best:?}");
        // Its first command turns it goalwards, not back towards the ball.
        let me = &w.offense[0];
        let cmd = intercept(&w, &a, 0, forward_point(me.pos.y));
        let Command::Turn { moment } = cmd else {
            panic!("expected a turn, got {cmd:?}");
        };
        assert!(moment > 0.0 && moment < FRAC_PI_4, "{moment}");
    }

    #[test]
    fn a_slow_or_backward_ball_is_met_earliest() {
        let mate = DVec2::new(30.0, -3.0);
        for vel in [DVec2::new(0.8, 0.0), DVec2::new(-1.0, 0.3)] {
            let (w, a) = scene(DVec2::new(27.0, 0.0), vel, mate);
            let cache = self_intercept::predict(&w.offense[0], &w.ball, a.path(), false);
            assert!(cache.len() > 3, "{vel}: several points to choose from");
            assert_eq!(cache[0].cycle, a.own_reach[0]);
            assert_eq!(best(&w, &a).cycle, a.own_reach[0], "{vel}");
        }
    }

    #[test]
    fn the_cache_holds_ten_cycles_from_the_first_long_step() {
        // A slow ball far away: first reachable after cycle 5, then 10 cycles.
        let (w, a) = scene(
            DVec2::new(20.0, 0.0),
            DVec2::new(0.5, 0.0),
            DVec2::new(30.0, 0.0),
        );
        let cycles: Vec<usize> = self_intercept::predict(&w.offense[0], &w.ball, a.path(), false)
            .iter()
            .map(|c| c.cycle)
            .collect();
        let first = a.own_reach[0];
        assert!(first > SHORT_STEPS);
        assert_eq!(cycles, (first..first + 10).collect::<Vec<_>>());
    }
}
