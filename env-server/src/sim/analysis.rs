//! What every behaviour reads each cycle, computed once per cycle from the
//! exact state: the ball's future path, every player's reach cycle (spec
//! 6.1.2) and the attackers' formation targets (spec 6.1.1).

use crate::sim::config::MAX_OFFENSE;
use crate::sim::formation::{catch_home, home_positions, offense_unums};
use crate::sim::geom::{direction, unit};
use crate::sim::kinematics::{DRIFT, dash_cycles, dash_distance};
use crate::sim::params::*;
use crate::sim::self_intercept::{self, Found, Interception};
use crate::sim::world::{Player, World};
use glam::DVec2;

/// Longest ball path considered by the intercept table.
const CACHE_LEN: usize = 31;
/// Reach cycles beyond which a player is considered unable to get the ball.
pub(crate) const NO_REACH: usize = 1000;

/// The per-cycle analysis of a world.
#[derive(Clone, Debug)]
pub(crate) struct Analysis {
    /// Ball positions b_0, b_1, ... without kicks (spec 6.1.2).
    pub(crate) ball_path: [DVec2; CACHE_LEN],
    /// Number of valid entries of `ball_path`.
    pub(crate) path_len: usize,
    /// The ball's heading as the own estimates read it ([`self_intercept::heading`]).
    heading: DVec2,
    /// Reach cycle of each offense agent as the other players estimate it.
    pub(crate) reach: [usize; MAX_OFFENSE],
    /// Reach cycle of each offense agent as it estimates its own (`self_min`).
    pub(crate) own_reach: [usize; MAX_OFFENSE],
    /// Where each offense agent's own reach was found.
    own_found: [Found; MAX_OFFENSE],
    /// Reach cycle of the goalkeeper as the attackers estimate it.
    pub(crate) keeper_reach: usize,
    /// Reach cycle of the goalkeeper as it estimates its own (`self_min`).
    pub(crate) keeper_own_reach: usize,
    /// Where the goalkeeper's own reach was found.
    keeper_own_found: Found,
    /// Formation target of each offense agent after the offside clip.
    pub(crate) home: [DVec2; MAX_OFFENSE],
}

impl Analysis {
    /// Analyses `world` (whose offside line must be up to date).
    pub(crate) fn new(world: &World) -> Self {
        let mut analysis = Analysis::for_keeper(world);
        let path = &analysis.ball_path[..analysis.path_len];
        for (i, p) in world.offense.iter().enumerate() {
            (analysis.own_reach[i], analysis.own_found[i]) =
                self_intercept::reach(p, &world.ball, analysis.heading, path, false);
        }
        let n = world.offense.len();
        let ball_step = analysis.reach[..n]
            .iter()
            .copied()
            .chain([analysis.keeper_reach])
            .min()
            .unwrap_or(NO_REACH);
        let focus = world.ball_inertia(ball_step.min(NO_REACH) as u32);
        let homes = home_positions(focus);
        // Player 9 (only in 4v1) mirrors the centre forward 11.
        let mirrored = (n == MAX_OFFENSE).then(|| home_positions(DVec2::new(focus.x, -focus.y))[2]);
        for (i, &unum) in offense_unums(n).iter().enumerate() {
            let home = match unum {
                _ if world.catch_mode => catch_home(unum),
                7 => homes[0],
                8 => homes[1],
                9 => mirrored.map_or(homes[2], |m| DVec2::new(m.x, -m.y)),
                _ => homes[2],
            };
            let mut max_x = world.offside_line;
            let mate = analysis.mate_reach(i);
            if mate < 50 {
                max_x = max_x.max(analysis.ball_at(mate).x);
            }
            max_x -= 1.0;
            analysis.home[i] = DVec2::new(home.x.min(max_x), home.y);
        }
        analysis
    }

    /// What the keeper reads of `world`: the ball's path, every reach cycle
    /// as the others see it and the keeper's own; the attackers' own reach
    /// (`NO_REACH`) and formation targets (zero) are left out.
    pub(crate) fn for_keeper(world: &World) -> Self {
        // Filled in place: the path is the largest part.
        let mut analysis = Analysis {
            ball_path: [DVec2::ZERO; CACHE_LEN],
            path_len: 0,
            heading: self_intercept::heading(&world.ball),
            reach: [NO_REACH; MAX_OFFENSE],
            own_reach: [NO_REACH; MAX_OFFENSE],
            own_found: [Found::Nothing; MAX_OFFENSE],
            keeper_reach: NO_REACH,
            keeper_own_reach: NO_REACH,
            keeper_own_found: Found::Nothing,
            home: [DVec2::ZERO; MAX_OFFENSE],
        };
        analysis.path_len = ball_path(world, &mut analysis.ball_path);
        let path = &analysis.ball_path[..analysis.path_len];
        let path_heading = path_heading(path);
        for (r, p) in analysis.reach.iter_mut().zip(&world.offense) {
            *r = reach_cycle(p, path, path_heading, None);
        }
        (analysis.keeper_own_reach, analysis.keeper_own_found) =
            self_intercept::reach(&world.keeper, &world.ball, analysis.heading, path, true);
        let keeper_control = Some(KEEPER_CONTROL_AREA);
        analysis.keeper_reach = reach_cycle(&world.keeper, path, path_heading, keeper_control);
        analysis
    }

    /// Offense agent `agent`'s self-interception cache in `world`, the
    /// world this analysis was made of ([`self_intercept::predict_from`]).
    pub(crate) fn own_cache(&self, world: &World, agent: usize) -> Vec<Interception> {
        let p = &world.offense[agent];
        let found = self.own_found[agent];
        self_intercept::predict_from(p, &world.ball, self.heading, self.path(), false, found)
    }

    /// The goalkeeper's self-interception cache in `world`, the world this
    /// analysis was made of.
    pub(crate) fn keeper_cache(&self, world: &World) -> Vec<Interception> {
        let (k, path, found) = (&world.keeper, self.path(), self.keeper_own_found);
        self_intercept::predict_from(k, &world.ball, self.heading, path, true, found)
    }

    /// The ball's predicted path.
    pub(crate) fn path(&self) -> &[DVec2] {
        &self.ball_path[..self.path_len]
    }

    /// The path's heading as the others' estimates read it ([`reach_cycle`]).
    #[cfg(test)]
    pub(crate) fn path_heading(&self) -> Option<DVec2> {
        path_heading(self.path())
    }

    /// Ball position after `t` cycles (the last known point beyond the path).
    pub(crate) fn ball_at(&self, t: usize) -> DVec2 {
        self.ball_path[t.min(self.path_len - 1)]
    }

    /// Fastest reach cycle among agent `i`'s teammates.
    pub(crate) fn mate_reach(&self, i: usize) -> usize {
        self.reach
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &r)| r)
            .min()
            .unwrap_or(NO_REACH)
    }

    /// Fastest reach cycle of any attacker (the keeper's `opp_min`).
    pub(crate) fn attacker_reach(&self) -> usize {
        self.reach.iter().copied().min().unwrap_or(NO_REACH)
    }
}

/// Updates agent2d's offside line as the attackers see it (spec 6.1.1 step 3).
pub(crate) fn update_offside_line(world: &mut World) {
    let prev = world.offside_line;
    let fallback = if prev > 5.0 && prev <= 13.0 {
        prev - 1.0
    } else {
        0.0
    };
    world.offside_line = fallback.max(world.ball.pos.x + world.ball.vel.x);
}

/// Fills `path` with the ball's path without kicks; returns its length.
fn ball_path(world: &World, path: &mut [DVec2; CACHE_LEN]) -> usize {
    let (mut pos, mut vel) = (world.ball.pos, world.ball.vel);
    let mut len = 0;
    while len < CACHE_LEN {
        path[len] = pos;
        len += 1;
        let outside = pos.x.abs() > PITCH_HALF_LENGTH + 5.0 || pos.y.abs() > PITCH_HALF_WIDTH + 5.0;
        if (len > 5 && vel.length_squared() < 1e-4) || outside {
            break;
        }
        pos += vel;
        vel *= BALL_DECAY;
    }
    len
}

/// cos(12°): the smallest turn threshold of the reach estimate.
const COS_12_DEG: f64 = 0.978_147_600_733_805_6;

/// Vector from where player `p` drifts to after `t` cycles to the ball at
/// `b`, and the control area there (spec 6.1.2).
fn reach_vector(p: &Player, t: usize, b: DVec2, keeper_control: Option<f64>) -> (DVec2, f64) {
    let control = match keeper_control {
        Some(c) if in_penalty_area(b) => c,
        _ => KICKABLE_AREA,
    };
    (b - (p.pos + p.vel * DRIFT[t.min(CACHE_LEN - 1)]), control)
}

/// Turns (0 or 1) before dashing: one unless the body (or its back, for a
/// ball less than 5 m away) points at the ball within max(12°, asin(c/d)).
fn turn_count(facing: DVec2, rel: DVec2, d: f64, control: f64) -> usize {
    let mut cos = rel.dot(facing) / d;
    if d < 5.0 {
        cos = cos.abs(); // a short backward dash needs no turn
    }
    let ratio = control / d;
    usize::from(cos < COS_12_DEG.min((1.0 - ratio * ratio).sqrt()))
}

/// The unit vector from the first point of `path` to the second, if any.
fn path_heading(path: &[DVec2]) -> Option<DVec2> {
    path.get(1).map(|&b1| unit(direction(b1 - path[0])))
}

/// Reach cycle of player `p` for the ball path `path`, whose heading is
/// `heading` ([`path_heading`]), as the other players estimate it
/// (librcsc `PlayerIntercept`, spec 6.1.2); `keeper_control` is the
/// keeper's control area inside its penalty area. A ball under control is
/// reached at once. The walk starts at the cycles the player needs at full
/// speed to cover its offset from the ball's line of travel.
fn reach_cycle(
    p: &Player,
    path: &[DVec2],
    heading: Option<DVec2>,
    keeper_control: Option<f64>,
) -> usize {
    let lateral = heading.map_or(0.0, |h| (p.pos - path[0]).perp_dot(h).abs());
    let skip = (lateral / REAL_SPEED_MAX).floor() as usize;
    let facing = unit(p.body);
    for (t, &ball) in path.iter().enumerate().skip(skip) {
        let (rel, control) = reach_vector(p, t, ball, keeper_control);
        let reach = control + dash_distance(t);
        if rel.length_squared() > reach * reach {
            continue; // out of reach even without turning
        }
        let d = rel.length();
        let gap = d - control;
        if gap <= 0.0 {
            return t;
        }
        let n_turn = turn_count(facing, rel, d, control);
        if t >= n_turn && gap <= dash_distance(t - n_turn) {
            return t;
        }
    }
    let last = path.len() - 1;
    let (rel, control) = reach_vector(p, last, path[last], keeper_control);
    let d = rel.length();
    let gap = d - control;
    if gap <= 0.0 {
        return path.len();
    }
    path.len()
        .max(turn_count(facing, rel, d, control) + dash_cycles(gap))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::self_intercept::{heading, predict, reach};
    use std::f64::consts::PI;

    /// Attacker 0 at `me` (position, velocity) facing `body_deg` degrees,
    /// the ball at `ball` (position, velocity), the keeper in goal.
    fn scene(ball: [f64; 4], me: [f64; 4], body_deg: f64) -> World {
        let mut w = World::new(1);
        w.ball.pos = DVec2::new(ball[0], ball[1]);
        w.ball.vel = DVec2::new(ball[2], ball[3]);
        w.offense[0] = Player::new(DVec2::new(me[0], me[1]), body_deg.to_radians());
        w.offense[0].vel = DVec2::new(me[2], me[3]);
        w.keeper = Player::new(DVec2::new(50.0, 2.8), std::f64::consts::FRAC_PI_2);
        w
    }

    #[test]
    fn others_run_straight_at_a_ball_kicked_on_beside_the_body() {
        // A state from HFO's logs where its dribbler's self_min was 5 (the
        // self-interception tests): running straight at the ball, as the
        // others' estimate does, takes 2 cycles or fewer.
        let w = scene(
            [44.6709, 5.4471, 0.6549, 0.1775],
            [43.5482, 5.2586, 0.1476, -0.0176],
            -6.261,
        );
        let a = Analysis::new(&w);
        assert!(reach_cycle(&w.offense[0], a.path(), a.path_heading(), None) <= 2);
        assert_eq!(a.own_reach[0], 5);
    }

    #[test]
    fn the_cache_resumed_from_the_own_reach_equals_a_full_search() {
        let (mut short, mut long) = (false, false);
        for (i, vel) in [(0.0, 0.0), (1.5, 0.3), (-0.8, 0.5), (2.5, -0.4), (0.4, 0.0)]
            .into_iter()
            .enumerate()
        {
            let near = [(28.5, 0.8), (26.0, -1.5), (29.5, 0.0), (27.0, 2.2)];
            let far = [(30.0, -3.0), (35.0, 8.0), (20.0, 12.0), (45.0, -10.0)];
            for me in near.into_iter().chain(far) {
                let body = 70.0 * i as f64;
                let w = scene([27.0, 0.0, vel.0, vel.1], [me.0, me.1, 0.1, 0.0], body);
                let a = Analysis::new(&w);
                let p = &w.offense[0];
                let (_, found) = reach(p, &w.ball, heading(&w.ball), a.path(), false);
                short |= matches!(found, Found::Short(_));
                long |= matches!(found, Found::Long(_));
                assert_eq!(a.own_cache(&w, 0), predict(p, &w.ball, a.path(), false));
                assert_eq!(
                    a.keeper_cache(&w),
                    predict(&w.keeper, &w.ball, a.path(), true)
                );
            }
        }
        assert!(short && long, "both kinds of resumption are tried");
    }

    #[test]
    fn after_a_catch_the_attackers_take_the_static_formation() {
        let mut w = World::new(3);
        w.ball.pos = DVec2::new(40.0, 5.0);
        for (i, p) in w.offense.iter_mut().enumerate() {
            p.place(DVec2::new(30.0, -10.0 + 10.0 * i as f64));
        }
        w.offside_line = 40.0;
        let play_on = Analysis::new(&w).home;
        w.catch_mode = true;
        let home = Analysis::new(&w).home;
        assert_ne!(home, play_on);
        let want = [(10.0, -12.0), (10.0, 12.0), (20.0, 0.0)];
        for (h, (x, y)) in home.iter().zip(want) {
            assert_eq!(*h, DVec2::new(x, y));
        }
        // The offside clip still applies: a resting ball at x = 12.
        w.offside_line = 12.0;
        w.ball.pos = DVec2::new(12.0, 5.0);
        let home = Analysis::new(&w).home;
        assert_eq!(home[0], DVec2::new(10.0, -12.0));
        assert_eq!(home[2], DVec2::new(11.0, 0.0));
    }

    #[test]
    fn others_start_at_the_cycles_that_cover_the_lateral_offset() {
        // The keeper 1.2 m beside a ball rolling past, within its catchable
        // area: PlayerIntercept starts at cycle floor(1.2 / 1.0) = 1.
        let mut w = World::new(1);
        w.offense[0] = Player::new(DVec2::new(10.0, 0.0), 0.0);
        w.keeper = Player::new(DVec2::new(45.0, 1.2), PI);
        w.ball.pos = DVec2::new(45.0, 0.0);
        w.ball.vel = DVec2::new(0.5, 0.0);
        assert_eq!(Analysis::new(&w).keeper_reach, 1);
        // The same offset along the ball's line: reached at once.
        w.keeper.pos = DVec2::new(46.2, 0.0);
        assert_eq!(Analysis::new(&w).keeper_reach, 0);
    }

    #[test]
    fn reach_of_a_resting_ball_follows_the_dash_table() {
        let mut w = World::new(1);
        w.ball.pos = DVec2::new(10.0, 0.0);
        w.offense[0] = Player::new(DVec2::ZERO, 0.0);
        let a = Analysis::new(&w);
        // Gap 10 - 1.085 = 8.915 m needs 10 dashes (9.333 m), facing the ball.
        assert_eq!(a.reach[0], 10);
        // Facing away adds one turn.
        w.offense[0].body = std::f64::consts::PI;
        assert_eq!(Analysis::new(&w).reach[0], 11);
    }

    #[test]
    fn own_estimate_needs_the_ball_inside_the_control_area() {
        // librcsc's SelfInterceptV13 wants the ball 0.15 m inside the
        // kickable area; PlayerIntercept, the others' view, does not.
        let mut w = World::new(1);
        w.offense[0] = Player::new(DVec2::ZERO, 0.0);
        w.ball.pos = DVec2::new(KICKABLE_AREA + dash_distance(2) - 0.1, 0.0);
        let a = Analysis::new(&w);
        assert_eq!((a.reach[0], a.own_reach[0]), (2, 3));
        // A resting ball farther away: librcsc's ball path ends after 5
        // cycles, so the own estimate is its final point, the dashes that
        // cover the distance less the kickable area, like the others'.
        w.ball.pos = DVec2::new(KICKABLE_AREA + dash_distance(7) - 0.17, 0.0);
        let a = Analysis::new(&w);
        assert_eq!((a.reach[0], a.own_reach[0]), (7, 7));
        // The keeper's own estimate too.
        w.keeper = Player::new(DVec2::new(50.0, 0.0), PI);
        w.ball.pos = DVec2::new(50.0 - KEEPER_CONTROL_AREA - dash_distance(2) + 0.1, 0.0);
        let a = Analysis::new(&w);
        assert_eq!((a.keeper_reach, a.keeper_own_reach), (2, 3));
    }

    #[test]
    fn kickable_player_reaches_at_once() {
        let mut w = World::new(3);
        w.ball.pos = DVec2::new(20.0, 0.0);
        w.offense[1].pos = DVec2::new(19.2, 0.0);
        let a = Analysis::new(&w);
        assert_eq!((a.reach[1], a.own_reach[1]), (0, 0));
        assert_eq!(a.mate_reach(0), 0);
    }

    #[test]
    fn own_estimate_reaches_at_once_only_by_the_agents_kickable_test() {
        // 1.05 m: within the server's kickable area (1.085), so the others
        // count the ball as reached, but not within the agent's own 1.03 m.
        let mut w = World::new(3);
        w.ball.pos = DVec2::new(20.0, 0.0);
        w.offense[1].pos = DVec2::new(18.95, 0.0);
        let a = Analysis::new(&w);
        assert_eq!(a.reach[1], 0);
        assert_eq!(a.own_reach[1], 1);
    }
}
