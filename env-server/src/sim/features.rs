//! HFO's high-level feature sets: the authors' version (spec 5.3), today's
//! LARG/HFO version (spec 5.5) and the paper's 6-feature view (spec 5.4,
//! docs/algorithms.md section 1).

use crate::sim::config::MAX_OFFENSE;
use crate::sim::formation::offense_unums;
use crate::sim::geom::direction;
use crate::sim::params::*;
use crate::sim::world::World;
use glam::DVec2;
use proto::State;
use std::f64::consts::{FRAC_PI_4, PI};

/// `norm(v, lo, hi)`: clamps `v` to `[lo, hi]` and maps it to `[-1, 1]`.
fn norm(v: f64, lo: f64, hi: f64) -> f64 {
    2.0 * (v.clamp(lo, hi) - lo) / (hi - lo) - 1.0
}

fn norm_dist(d: f64) -> f64 {
    norm(d, 0.0, MAX_HFO_DISTANCE)
}

fn norm_angle(a: f64) -> f64 {
    a / PI
}

fn norm_open_angle(a: f64) -> f64 {
    norm(a, 0.0, PI)
}

/// `calcLargestOpenAngle` (spec 5.2) with the keeper as the only blocker.
fn largest_open_angle(from: DVec2, bottom: f64, top: f64, keeper: DVec2, max_dist: f64) -> f64 {
    let d = from.distance(keeper);
    if d >= max_dist {
        return (top - bottom).max(0.0);
    }
    let phi = direction(keeper - from);
    let h = libm::atan2(KICKABLE_AREA / 2.0, d);
    if phi + h < bottom || phi - h > top {
        return (top - bottom).max(0.0);
    }
    ((phi - h) - bottom).max(top - (phi + h)).max(0.0)
}

/// Largest open angle of the goal mouth seen from `p` (radians).
fn goal_opening(p: DVec2, keeper: DVec2) -> f64 {
    let bottom = direction(DVec2::new(PITCH_HALF_LENGTH, -GOAL_HALF_WIDTH) - p);
    let top = direction(DVec2::new(PITCH_HALF_LENGTH, GOAL_HALF_WIDTH) - p);
    largest_open_angle(p, bottom, top, keeper, 99999.0)
}

/// Largest open pass angle from `from` to `to` (±45° around the line).
fn pass_opening(from: DVec2, to: DVec2, keeper: DVec2) -> f64 {
    let dir = direction(to - from);
    largest_open_angle(
        from,
        dir - FRAC_PI_4,
        dir + FRAC_PI_4,
        keeper,
        from.distance(to),
    )
}

/// Number of high-level features for a team of `offense` players against one keeper.
pub fn feature_count(offense: usize) -> usize {
    10 + 6 * (offense - 1) + 3
}

/// Indices of the raw uniform-number features (not normalised, spec 5.1).
pub fn unum_feature_indices(offense: usize) -> impl Iterator<Item = usize> {
    let t = offense - 1;
    (0..t)
        .map(move |j| 10 + 3 * t + 3 * j + 2)
        .chain([10 + 6 * t + 2])
}

/// The full high-level feature vector of offense agent `agent` (spec 5.3);
/// teammates appear in ascending uniform number.
pub(crate) fn high_level(world: &World, agent: usize) -> Vec<f64> {
    let me = &world.offense[agent];
    let s = me.pos;
    let k = world.keeper.pos;
    let b = world.ball.pos;
    let unums = offense_unums(world.offense.len());
    let mates: Vec<usize> = (0..world.offense.len()).filter(|&j| j != agent).collect();
    let mut f = Vec::with_capacity(feature_count(world.offense.len()));
    f.extend([
        norm(s.x, FEATURE_X_RANGE.0, FEATURE_X_RANGE.1),
        norm(s.y, FEATURE_Y_RANGE.0, FEATURE_Y_RANGE.1),
        norm_angle(me.body),
        norm_dist(s.distance(b)),
        norm_angle(direction(b - s)),
        if world.agent_kickable(agent) {
            1.0
        } else {
            -1.0
        },
        norm_dist(s.distance(GOAL_CENTER)),
        norm_angle(direction(GOAL_CENTER - s)),
        norm_open_angle(goal_opening(s, k)),
        norm_dist(s.distance(k)),
    ]);
    let mate_pos = |j: &usize| world.offense[*j].pos;
    f.extend(
        mates
            .iter()
            .map(|j| norm_open_angle(goal_opening(mate_pos(j), k))),
    );
    f.extend(mates.iter().map(|j| norm_dist(mate_pos(j).distance(k))));
    f.extend(
        mates
            .iter()
            .map(|j| norm_open_angle(pass_opening(s, mate_pos(j), k))),
    );
    for j in &mates {
        let m = mate_pos(j);
        f.extend([
            norm_dist(s.distance(m)),
            norm_angle(direction(m - s)),
            f64::from(unums[*j]),
        ]);
    }
    f.extend([norm_dist(s.distance(k)), norm_angle(direction(k - s)), 1.0]);
    f
}

/// HFO's largest distance in today's feature set, `sqrt(52.5² + 68²)`: the
/// half length with the full width (HFO: src/feature_extractor.cpp at b8b2a1d).
const MAX_CURRENT_DISTANCE: f64 = 85.908_381_430_451_83;

/// HFO's `observedStaminaMax`, the stamina feature's upper bound.
const OBSERVED_STAMINA_MAX: f64 = 8000.0;

/// Number of features of today's HFO high-level set (spec 5.5) for a team
/// of `offense` players against one keeper: `10 + 6T + 3O + 2`.
pub fn current_feature_count(offense: usize) -> usize {
    feature_count(offense) + 2
}

/// Indices of the raw uniform-number features of today's set.
pub fn current_unum_feature_indices(offense: usize) -> impl Iterator<Item = usize> {
    let t = offense - 1;
    (0..t)
        .map(move |j| 10 + 3 * t + 3 * j + 2)
        .chain([10 + 6 * t + 2])
}

/// Agent `agent`'s teammates nearest first, as librcsc's
/// `teammatesFromSelf` lists them (ties in agent order): the order of
/// today's HFO feature set.
pub fn teammates_from_self(world: &World, agent: usize) -> Vec<usize> {
    let me = world.offense[agent].pos;
    let mut mates: Vec<usize> = (0..world.offense.len()).filter(|&j| j != agent).collect();
    mates.sort_by(|&a, &b| {
        let d = |j: usize| world.offense[j].pos.distance(me);
        d(a).total_cmp(&d(b))
    });
    mates
}

/// Today's HFO high-level feature vector of offense agent `agent` (spec 5.5;
/// HFO: src/highlevel_feature_extractor.cpp at b8b2a1d): positions instead
/// of distance and angle for the ball and the other players, teammates
/// nearest first, distances over [`MAX_CURRENT_DISTANCE`], and at the end
/// whether the agent's last action succeeded and its stamina.
pub(crate) fn current_high_level(
    world: &World,
    agent: usize,
    last_action_succeeded: bool,
) -> Vec<f64> {
    let me = &world.offense[agent];
    let (s, k, b) = (me.pos, world.keeper.pos, world.ball.pos);
    let norm_x = |x: f64| norm(x, FEATURE_X_RANGE.0, FEATURE_X_RANGE.1);
    let norm_y = |y: f64| norm(y, FEATURE_Y_RANGE.0, FEATURE_Y_RANGE.1);
    let norm_dist = |d: f64| norm(d, 0.0, MAX_CURRENT_DISTANCE);
    let norm_angle = |a: f64| norm(a, -PI, PI);
    let unums = offense_unums(world.offense.len());
    let mates = teammates_from_self(world, agent);
    let pos = |j: &usize| world.offense[*j].pos;
    let sign = |b: bool| if b { 1.0 } else { -1.0 };
    let mut f = Vec::with_capacity(current_feature_count(world.offense.len()));
    f.extend([
        norm_x(s.x),
        norm_y(s.y),
        norm_angle(me.body),
        norm_x(b.x),
        norm_y(b.y),
        sign(world.agent_kickable(agent)),
        norm_dist(s.distance(GOAL_CENTER)),
        norm_angle(direction(GOAL_CENTER - s)),
        norm_open_angle(goal_opening(s, k)),
        norm_dist(s.distance(k)),
    ]);
    f.extend(
        mates
            .iter()
            .map(|j| norm_open_angle(goal_opening(pos(j), k))),
    );
    f.extend(mates.iter().map(|j| norm_dist(pos(j).distance(k))));
    f.extend(
        mates
            .iter()
            .map(|j| norm_open_angle(pass_opening(s, pos(j), k))),
    );
    for j in &mates {
        f.extend([norm_x(pos(j).x), norm_y(pos(j).y), f64::from(unums[*j])]);
    }
    f.extend([norm_x(k.x), norm_y(k.y), 1.0]);
    f.extend([
        sign(last_action_succeeded),
        norm(me.stamina, 0.0, OBSERVED_STAMINA_MAX),
    ]);
    f
}

/// The goal opening (normalised) of every offense player, for [`paper_state`].
pub(crate) fn goal_openings(world: &World) -> [f64; MAX_OFFENSE] {
    let mut openings = [0.0; MAX_OFFENSE];
    for (o, p) in openings.iter_mut().zip(&world.offense) {
        *o = norm_open_angle(goal_opening(p.pos, world.keeper.pos));
    }
    openings
}

/// The paper's 6-feature state of agent `agent`: able to kick, goal distance,
/// goal angle, goal opening, then the goal openings of the nearest and the
/// farthest teammate (docs/algorithms.md section 1; -1 when there is no
/// teammate); `openings` are [`goal_openings`] of `world`.
pub(crate) fn paper_state(world: &World, openings: &[f64; MAX_OFFENSE], agent: usize) -> State {
    let me = world.offense[agent].pos;
    let mut nearest: Option<(f64, usize)> = None;
    let mut farthest: Option<(f64, usize)> = None;
    for (j, p) in world.offense.iter().enumerate() {
        if j == agent {
            continue;
        }
        let d = p.pos.distance(me);
        if nearest.is_none_or(|(n, _)| d < n) {
            nearest = Some((d, j));
        }
        if farthest.is_none_or(|(f, _)| d > f) {
            farthest = Some((d, j));
        }
    }
    let opening = |m: Option<(f64, usize)>| m.map_or(-1.0, |(_, j)| openings[j]);
    [
        if world.agent_kickable(agent) {
            1.0
        } else {
            -1.0
        },
        norm_dist(me.distance(GOAL_CENTER)),
        norm_angle(direction(GOAL_CENTER - me)),
        openings[agent],
        opening(nearest),
        opening(farthest),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn goal_opening_without_blocker_is_post_to_post() {
        let far_keeper = DVec2::new(-50.0, 0.0);
        let p = DVec2::new(42.5, 0.0);
        let full = 2.0 * (7.01f64 / 10.0).atan();
        assert!((goal_opening(p, far_keeper) - full).abs() < 1e-12);
    }

    #[test]
    fn keeper_in_the_middle_halves_the_opening() {
        let p = DVec2::new(42.5, 0.0);
        let keeper = DVec2::new(52.0, 0.0);
        let h = (KICKABLE_AREA / 2.0).atan2(9.5);
        let half = (7.01f64 / 10.0).atan();
        assert!((goal_opening(p, keeper) - (half - h)).abs() < 1e-12);
    }

    #[test]
    fn three_v_one_has_25_features_with_raw_unums() {
        let mut w = World::new(3);
        for (i, p) in w.offense.iter_mut().enumerate() {
            p.pos = DVec2::new(10.0 * i as f64, 5.0);
        }
        let f = high_level(&w, 0);
        assert_eq!(f.len(), 25);
        assert_eq!(
            unum_feature_indices(3).collect::<Vec<_>>(),
            vec![18, 21, 24]
        );
        assert_eq!((f[18], f[21], f[24]), (8.0, 11.0, 1.0));
        let g = high_level(&w, 2);
        assert_eq!((g[18], g[21]), (7.0, 8.0));
    }

    #[test]
    fn current_distances_are_normalised_by_half_length_and_full_width() {
        assert!((MAX_CURRENT_DISTANCE - 52.5f64.hypot(68.0)).abs() < 1e-12);
    }

    /// A 3v1 world: agent 0 at (30, 0) facing the goal with the ball at its
    /// feet, agent 1 far away at (10, -20), agent 2 near at (35, 5), the
    /// keeper on its line.
    fn three_v_one() -> World {
        let mut w = World::new(3);
        w.offense[0].pos = DVec2::new(30.0, 0.0);
        w.offense[1].pos = DVec2::new(10.0, -20.0);
        w.offense[2].pos = DVec2::new(35.0, 5.0);
        w.offense[0].stamina = 6000.0;
        w.ball.pos = DVec2::new(30.5, 0.0);
        w.keeper.pos = DVec2::new(52.0, 1.0);
        w
    }

    #[test]
    fn current_set_has_hfo_layout_with_teammates_nearest_first() {
        let w = three_v_one();
        assert_eq!(teammates_from_self(&w, 0), vec![2, 1]);
        assert_eq!(teammates_from_self(&w, 1), vec![0, 2]);
        let f = current_high_level(&w, 0, true);
        assert_eq!(f.len(), 10 + 6 * 2 + 3 + 2);
        assert_eq!(current_feature_count(3), f.len());
        assert_eq!(
            current_unum_feature_indices(3).collect::<Vec<_>>(),
            vec![18, 21, 24]
        );
        // Teammate blocks: the nearest (unum 11, agent 2) first.
        assert_eq!((f[18], f[21], f[24]), (11.0, 8.0, 1.0));
        let m = w.offense[2].pos;
        let k = w.keeper.pos;
        let s = w.offense[0].pos;
        assert_eq!(f[10], norm_open_angle(goal_opening(m, k)));
        assert_eq!(f[12], norm(m.distance(k), 0.0, MAX_CURRENT_DISTANCE));
        assert_eq!(f[14], norm_open_angle(pass_opening(s, m, k)));
        assert_eq!(f[16], norm(m.x, -5.25, 57.75));
        assert_eq!(f[17], norm(m.y, -37.4, 37.4));
    }

    #[test]
    fn current_set_values_on_a_hand_built_world() {
        let w = three_v_one();
        let f = current_high_level(&w, 0, true);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        // Self position and body: x 30 over [-5.25, 57.75], y 0, facing +x.
        assert!(close(f[0], 2.0 * 35.25 / 63.0 - 1.0));
        assert!(close(f[1], 0.0));
        assert!(close(f[2], 0.0));
        // The ball's position, not its distance and angle.
        assert!(close(f[3], 2.0 * 35.75 / 63.0 - 1.0));
        assert!(close(f[4], 0.0));
        assert_eq!(f[5], 1.0, "the ball is 0.5 m away");
        // Goal centre 22.5 m straight ahead.
        assert!(close(f[6], 2.0 * 22.5 / MAX_CURRENT_DISTANCE - 1.0));
        assert!(close(f[7], 0.0));
        assert_eq!(
            f[8],
            norm_open_angle(goal_opening(w.offense[0].pos, w.keeper.pos))
        );
        let keeper_dist = w.offense[0].pos.distance(w.keeper.pos);
        assert!(close(f[9], 2.0 * keeper_dist / MAX_CURRENT_DISTANCE - 1.0));
        // The keeper's block: position and unum 1.
        assert!(close(f[22], 2.0 * 57.25 / 63.0 - 1.0));
        assert!(close(f[23], 2.0 * 38.4 / 74.8 - 1.0));
        // Last action and stamina 6000 of 8000.
        assert_eq!(f[25], 1.0);
        assert!(close(f[26], 0.5));
        let g = current_high_level(&w, 1, false);
        assert_eq!((g[5], g[25]), (-1.0, -1.0));
        assert_eq!(g[26], 1.0, "a rested player");
    }

    #[test]
    fn current_set_of_a_lone_attacker_has_no_teammate_block() {
        let mut w = World::new(1);
        w.offense[0].pos = DVec2::new(60.0, -40.0);
        w.offense[0].body = PI;
        let f = current_high_level(&w, 0, false);
        assert_eq!(f.len(), 15);
        assert_eq!(
            current_unum_feature_indices(1).collect::<Vec<_>>(),
            vec![12]
        );
        // Clamped to the box, as HFO's normalize does.
        assert_eq!((f[0], f[1], f[2]), (1.0, -1.0, 1.0));
        assert_eq!(f[12], 1.0);
    }
}
