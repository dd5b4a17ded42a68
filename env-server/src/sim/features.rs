//! HFO's high-level feature set of the authors' version (spec 5.3) and the
//! paper's 6-feature view (spec 5.4, docs/algorithms.md section 1).

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
}
