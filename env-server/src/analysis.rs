//! What every behaviour reads each cycle, computed once per cycle from the
//! exact state: the ball's future path, every player's reach cycle (spec
//! 6.1.2) and the attackers' formation targets (spec 6.1.1).

use crate::formation::{catch_home, home_positions};
use crate::geom::{direction, unit};
use crate::params::*;
use crate::short_reach::{SHORT_STEPS, short_steps};
use crate::world::{Ball, Player, World};
use glam::DVec2;

/// Most offense agents the simulator supports.
pub const MAX_OFFENSE: usize = 4;
/// Longest ball path considered by the intercept table.
const CACHE_LEN: usize = 31;
/// Longest self-interception prediction (librcsc `InterceptTable::MAX_CYCLE`).
pub const MAX_CYCLE: usize = 30;
/// Reach cycles beyond which a player is considered unable to get the ball.
pub const NO_REACH: usize = 1000;

/// Uniform numbers of the offense players for each team size (HFO's order [11, 7, 8, 9, ...], sorted).
pub fn offense_unums(offense: usize) -> &'static [u8] {
    const UNUMS: [&[u8]; MAX_OFFENSE + 1] = [&[], &[11], &[7, 11], &[7, 8, 11], &[7, 8, 9, 11]];
    UNUMS[offense]
}

/// The per-cycle analysis of a world.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// Ball positions b_0, b_1, ... without kicks (spec 6.1.2).
    pub ball_path: [DVec2; CACHE_LEN],
    /// Number of valid entries of `ball_path`.
    pub path_len: usize,
    /// Reach cycle of each offense agent as the other players estimate it.
    pub reach: [usize; MAX_OFFENSE],
    /// Reach cycle of each offense agent as it estimates its own (`self_min`).
    pub own_reach: [usize; MAX_OFFENSE],
    /// Reach cycle of the goalkeeper as the attackers estimate it.
    pub keeper_reach: usize,
    /// Reach cycle of the goalkeeper as it estimates its own (`self_min`).
    pub keeper_own_reach: usize,
    /// Formation target of each offense agent after the offside clip.
    pub home: [DVec2; MAX_OFFENSE],
}

impl Analysis {
    /// Analyses `world` (whose offside line must be up to date).
    pub fn new(world: &World) -> Self {
        let (ball_path, path_len) = ball_path(world);
        let path = &ball_path[..path_len];
        let n = world.offense.len();
        let mut reach = [NO_REACH; MAX_OFFENSE];
        let mut own_reach = [NO_REACH; MAX_OFFENSE];
        for ((r, o), p) in reach.iter_mut().zip(&mut own_reach).zip(&world.offense) {
            *r = reach_cycles(p, path, None).0;
            *o = own_reach_cycle(p, &world.ball, path, *r, None);
        }
        let keeper_control = Some(KEEPER_CONTROL_AREA);
        let keeper_reach = reach_cycles(&world.keeper, path, keeper_control).0;
        let keeper_own_reach = own_reach_cycle(
            &world.keeper,
            &world.ball,
            path,
            keeper_reach,
            keeper_control,
        );
        let mut analysis = Analysis {
            ball_path,
            path_len,
            reach,
            own_reach,
            keeper_reach,
            keeper_own_reach,
            home: [DVec2::ZERO; MAX_OFFENSE],
        };
        let ball_step = reach[..n]
            .iter()
            .copied()
            .chain([keeper_reach])
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

    /// The ball's predicted path.
    pub fn path(&self) -> &[DVec2] {
        &self.ball_path[..self.path_len]
    }

    /// Ball position after `t` cycles (the last known point beyond the path).
    pub fn ball_at(&self, t: usize) -> DVec2 {
        self.ball_path[t.min(self.path_len - 1)]
    }

    /// Fastest reach cycle among agent `i`'s teammates.
    pub fn mate_reach(&self, i: usize) -> usize {
        self.reach
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &r)| r)
            .min()
            .unwrap_or(NO_REACH)
    }

    /// Fastest reach cycle of any attacker (the keeper's `opp_min`).
    pub fn attacker_reach(&self) -> usize {
        self.reach.iter().copied().min().unwrap_or(NO_REACH)
    }
}

/// Updates agent2d's offside line as the attackers see it (spec 6.1.1 step 3).
pub fn update_offside_line(world: &mut World) {
    let prev = world.offside_line;
    let fallback = if prev > 5.0 && prev <= 13.0 {
        prev - 1.0
    } else {
        0.0
    };
    world.offside_line = fallback.max(world.ball.pos.x + world.ball.vel.x);
}

fn ball_path(world: &World) -> ([DVec2; CACHE_LEN], usize) {
    let mut path = [DVec2::ZERO; CACHE_LEN];
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
    (path, len)
}

/// Precomputed `(1 - 0.4^t) / 0.6`: a player's drift per unit velocity after t cycles.
pub(crate) const DRIFT: [f64; CACHE_LEN] = {
    let mut d = [0.0; CACHE_LEN];
    let mut pow = 1.0;
    let mut t = 0;
    while t < CACHE_LEN {
        d[t] = (1.0 - pow) / (1.0 - PLAYER_DECAY);
        pow *= PLAYER_DECAY;
        t += 1;
    }
    d
};

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

/// Whose estimate of a reach cycle (spec 6.1.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimate {
    /// Another player's (librcsc `PlayerIntercept`): the full control area.
    Other,
    /// The player's own (librcsc `SelfInterceptV13`): once it must move, the
    /// ball has to come 0.15 m inside the control area within 5 cycles
    /// (`control_area_buf`), 0.2 m later (its long-step buffer).
    Own,
}

impl Estimate {
    /// Margin inside the control area for a reach at cycle `t`.
    pub(crate) fn buffer(self, t: usize) -> f64 {
        match self {
            Estimate::Other => 0.0,
            Estimate::Own if t <= 5 => 0.15,
            Estimate::Own => 0.2,
        }
    }
}

/// Reach cycles of player `p` for the ball path `path` (spec 6.1.2), as the
/// others estimate it and as it estimates its own; `keeper_control` is the
/// keeper's control area inside its penalty area. A ball already under
/// control is reached at once by the others' estimate; by the player's own
/// only if it can kick it by its own test (1.03 m).
pub fn reach_cycles(p: &Player, path: &[DVec2], keeper_control: Option<f64>) -> (usize, usize) {
    let scan = Scan::new(p, path, keeper_control);
    // Whatever the own estimate accepts the others' accepts too: the own
    // scan goes on from where the others' first accepts.
    let first = scan.run(0, Estimate::Other);
    let own = scan.run(first.min(path.len()), Estimate::Own);
    // PlayerIntercept starts at the cycles the player needs at full speed to
    // cover its lateral offset from the ball's line of travel.
    let lateral = path.get(1).map_or(0.0, |&b1| {
        let rel = p.pos - path[0];
        rel.perp_dot(unit(direction(b1 - path[0]))).abs()
    });
    let skip = (lateral / REAL_SPEED_MAX).floor() as usize;
    let other = if first >= skip {
        first
    } else {
        scan.run(skip.min(path.len()), Estimate::Other)
    };
    (other, own)
}

/// A player's own reach cycle (`self_min`) given the others' estimate
/// `other`; `keeper_control` as for [`reach_cycles`], and only for the keeper.
/// 0 if it can kick the ball by its own test (1.03 m), else the first cycle
/// of librcsc's short-step prediction ([`short_steps`]), else the long-step
/// rule from cycle 6 on.
fn own_reach_cycle(
    p: &Player,
    ball: &Ball,
    path: &[DVec2],
    other: usize,
    keeper_control: Option<f64>,
) -> usize {
    if p.pos.distance(path[0]) <= AGENT_KICKABLE_AREA {
        return 0;
    }
    let short = short_steps(p, ball, MAX_CYCLE.min(path.len()), keeper_control.is_some());
    match short.iter().flatten().next() {
        Some(first) => first.cycle,
        None => Scan::new(p, path, keeper_control)
            .run(other.max(SHORT_STEPS + 1).min(path.len()), Estimate::Own),
    }
}

/// One player's walk along the ball path.
struct Scan<'a> {
    p: &'a Player,
    path: &'a [DVec2],
    keeper_control: Option<f64>,
    facing: DVec2,
}

impl<'a> Scan<'a> {
    fn new(p: &'a Player, path: &'a [DVec2], keeper_control: Option<f64>) -> Self {
        Scan {
            p,
            path,
            keeper_control,
            facing: unit(p.body),
        }
    }

    /// The reach cycle by `estimate`, walking from cycle `start` (at least
    /// the path's length if the walk runs off its end).
    fn run(&self, start: usize, estimate: Estimate) -> usize {
        let (p, path, facing) = (self.p, self.path, self.facing);
        for (t, &ball) in path.iter().enumerate().skip(start) {
            let (rel, control) = reach_vector(p, t, ball, self.keeper_control);
            let reach = control + dash_distance(t);
            if rel.length_squared() > reach * reach {
                continue; // out of reach even without turning
            }
            let d = rel.length();
            if estimate == Estimate::Own && t == 0 {
                // Only a ball the player can kick by its own test is reached
                // at once (`InterceptTable::predictSelf`).
                if d <= AGENT_KICKABLE_AREA {
                    return 0;
                }
                continue;
            }
            if d <= control && estimate == Estimate::Other {
                return t;
            }
            let gap = d - control + estimate.buffer(t);
            if gap <= 0.0 {
                return t;
            }
            let n_turn = turn_count(facing, rel, d, control);
            if t >= n_turn && gap <= dash_distance(t - n_turn) {
                return t;
            }
        }
        let last = path.len() - 1;
        let (rel, control) = reach_vector(p, last, path[last], self.keeper_control);
        let d = rel.length();
        let gap = d - control + estimate.buffer(last.max(6));
        if gap <= 0.0 {
            return path.len();
        }
        path.len()
            .max(turn_count(facing, rel, d, control) + dash_cycles(gap))
    }
}

/// One way for a player to get the ball at a given cycle (librcsc
/// `InterceptInfo`, one entry of the self-interception cache).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interception {
    /// Cycle at which the ball is reached.
    pub cycle: usize,
    /// Turns before the dashes (0 or 1).
    pub turns: usize,
    /// Dashes after the turn.
    pub dashes: usize,
    /// Whether the dashes go backwards.
    pub back: bool,
    /// Distance from the player's final position to the ball
    /// (`InterceptInfo::ballDist`).
    pub ball_dist: f64,
}

/// How one player gets the ball on one ball path (spec 6.1.2), cycle by
/// cycle; the player's facing is computed once for all cycles.
pub struct Reach<'a> {
    p: &'a Player,
    path: &'a [DVec2],
    facing: DVec2,
    keeper_control: Option<f64>,
    estimate: Estimate,
}

impl<'a> Reach<'a> {
    /// Player `p` on `path`; `keeper_control` is the keeper's control area
    /// inside its penalty area, `estimate` whose margin applies.
    pub fn new(
        p: &'a Player,
        path: &'a [DVec2],
        keeper_control: Option<f64>,
        estimate: Estimate,
    ) -> Self {
        Reach {
            p,
            path,
            facing: unit(p.body),
            keeper_control,
            estimate,
        }
    }

    /// How the player gets the ball at cycle `t`, if it can by the rule of
    /// spec 6.1.2 under the estimate's margin; beyond the path, how it
    /// reaches the ball's resting point (librcsc `SelfInterceptV13::predictFinal`).
    ///
    /// As librcsc's `canReachAfterDash`, the player dashes along its body (or
    /// along the line to the ball after a turn): if the dashes carry it past the
    /// ball (within 0.1 m) it stops on that line, and `ball_dist` is the ball's
    /// distance from the line; otherwise it is the distance left after the dashes.
    pub fn at(&self, t: usize) -> Option<Interception> {
        let Reach {
            p,
            path,
            facing,
            keeper_control,
            estimate,
        } = *self;
        let final_point = t >= path.len();
        let i = t.min(path.len() - 1);
        let (rel, control) = reach_vector(p, i, path[i], keeper_control);
        let d = rel.length();
        let gap = d - control;
        let turns = if gap > 0.0 {
            turn_count(facing, rel, d, control)
        } else {
            0
        };
        let needed = gap + estimate.buffer(t);
        if !final_point && needed > 0.0 && (t < turns || needed > dash_distance(t - turns)) {
            return None;
        }
        let dashes = if final_point {
            dash_cycles(gap)
        } else {
            t - turns
        };
        let back = turns == 0 && rel.dot(facing) < 0.0;
        let line = match (turns, back) {
            (0, false) => facing,
            (0, true) => -facing,
            _ => rel / d,
        };
        let along = rel.dot(line);
        let run = dash_distance(dashes);
        let ball_dist = if dashes == 0 {
            d
        } else if along - 0.1 <= run {
            rel.perp_dot(line).abs()
        } else {
            (rel - line * run).length()
        };
        Some(Interception {
            cycle: t.max(turns + dashes),
            turns,
            dashes,
            back,
            ball_dist,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

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
        // Beyond 5 cycles the margin is 0.2 m.
        w.ball.pos = DVec2::new(KICKABLE_AREA + dash_distance(7) - 0.17, 0.0);
        let a = Analysis::new(&w);
        assert_eq!((a.reach[0], a.own_reach[0]), (7, 8));
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
