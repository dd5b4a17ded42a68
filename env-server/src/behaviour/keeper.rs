//! agent2d's base goalkeeper (spec section 7): catch, chase, or position on
//! the line x = 49.8 between the ball and a point behind the goal.

use super::body::{BackDash, go_to_point, intercept, stop_dash, turn_to_direction, turn_to_point};
use super::tackle::{self, Tackler};
use crate::analysis::{Analysis, reach_cycle};
use crate::geom::{angle_diff, decay_sum, direction, normalize_angle, unit};
use crate::params::*;
use crate::physics::Command;
use crate::world::{Player, World};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// How close to the ball's path the keeper aims when it intercepts (m).
///
/// agent2d scores several interception candidates; our simplification
/// (spec 6.1.3) aims to put the ball within this distance, tighter than the
/// 1.3 m catchable area because a fast ball passes a keeper who catches at
/// arm's length (the catch does not stop the ball in HFO). Calibrated, see
/// docs/calibration.md.
const INTERCEPT_AIM: f64 = 0.6;

/// What the keeper remembers between cycles.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KeeperMemory {
    /// Cycles since its last catch command (saturating).
    pub since_catch: u32,
}

/// The keeper's command this cycle.
pub fn command(world: &World, analysis: &Analysis, memory: &KeeperMemory) -> Command {
    let k = &world.keeper;
    let ball = world.ball.pos;
    let ball_dist = k.pos.distance(ball);
    let catchable_spot = (37.0..=PITCH_HALF_LENGTH).contains(&ball.x)
        && ball.y.abs() <= PENALTY_AREA_HALF_WIDTH - 1.0;
    if memory.since_catch > 5 && ball_dist < KEEPER_CONTROL_AREA - 0.05 && catchable_spot {
        return Command::Catch;
    }
    // Bhv_GoalieChaseBall and Bhv_GoalieBasicMove both begin with Bhv_BasicTackle.
    if let Some(cmd) = tackle::command(world, analysis, Tackler::Keeper) {
        return cmd;
    }
    let view = View::new(world, analysis);
    if view.is_chase_situation() {
        return view.chase();
    }
    view.basic_move()
}

/// The keeper's reading of the current cycle.
struct View<'a> {
    world: &'a World,
    analysis: &'a Analysis,
    keeper: &'a Player,
    ball_dist: f64,
    ball_next: DVec2,
    /// Keeper's reach cycle.
    self_min: usize,
    /// Fastest attacker's reach cycle.
    opp_min: usize,
    /// Ball point where the keeper would intercept.
    intercept_point: DVec2,
    /// Margin by which that point must be inside the penalty area.
    pen_thr: f64,
    attacker_kickable: bool,
}

impl<'a> View<'a> {
    fn new(world: &'a World, analysis: &'a Analysis) -> Self {
        let keeper = &world.keeper;
        let ball_dist = keeper.pos.distance(world.ball.pos);
        View {
            world,
            analysis,
            keeper,
            ball_dist,
            ball_next: world.ball.pos + world.ball.vel,
            self_min: analysis.keeper_reach,
            opp_min: analysis.attacker_reach(),
            intercept_point: analysis.ball_at(analysis.keeper_reach),
            pen_thr: (0.1 * ball_dist + 1.0).max(1.0),
            attacker_kickable: world.any_attacker_kickable(),
        }
    }

    /// `Bhv_GoalieChaseBall::is_ball_chase_situation` (spec 7.2).
    fn is_chase_situation(&self) -> bool {
        let (self_min, opp_min) = (self.self_min, self.opp_min);
        if self.ball_next.x > 44.5 && self.ball_next.y.abs() < 10.01 {
            if self.ball_dist < 3.0 && self_min <= 3 {
                return true;
            }
            return !(self_min > opp_min + 3 && opp_min < 7);
        }
        if self.is_shot_on_goal() && self_min < opp_min {
            return true;
        }
        let i = self.intercept_point;
        if i.y.abs() > PENALTY_AREA_HALF_WIDTH - self.pen_thr || i.x < PENALTY_AREA_X + self.pen_thr
        {
            return false;
        }
        if opp_min + 2 <= self_min {
            return false;
        }
        let keeper_to_i = self.keeper.pos.distance(i);
        !self
            .world
            .offense
            .iter()
            .any(|a| a.pos.distance(i) < keeper_to_i - 2.0)
    }

    /// Whether the ball, left alone, crosses the goal line near the goal.
    fn ball_heads_for_goal(&self) -> bool {
        let ball = &self.world.ball;
        if ball.vel.x <= 0.0 || self.world.ball_final().x <= 50.5 {
            return false;
        }
        let y_at_line = ball.pos.y + ball.vel.y * (PITCH_HALF_LENGTH - ball.pos.x) / ball.vel.x;
        y_at_line.abs() < 9.01
    }

    /// `is_ball_shoot_moving` (spec 7.2 step 2).
    fn is_shot_on_goal(&self) -> bool {
        let ball = &self.world.ball;
        if self.ball_dist > 30.0 || ball.pos.x < 34.5 || self.attacker_kickable {
            return false;
        }
        if ball.vel.x.abs() < 0.1 && ball.pos.x > 46.0 && ball.pos.y.abs() < 9.01 {
            return true;
        }
        if ball.vel.x <= 0.0
            || ball.pos.x <= 40.0
            || ball.pos.y.abs() >= 15.0
            || ball.vel.length() <= 0.5
        {
            return false;
        }
        let y_at_line = ball.pos.y + ball.vel.y * (PITCH_HALF_LENGTH - ball.pos.x) / ball.vel.x;
        y_at_line.abs() < 9.01 && self.world.ball_final().x > 50.5
    }

    fn intercept(&self) -> Command {
        let path = self.analysis.path();
        let mut reach = reach_cycle(self.keeper, path, Some(INTERCEPT_AIM));
        if self.ball_heads_for_goal() && reach < path.len() {
            // Against a ball heading for goal, wait on its path as close to the
            // goal line as possible instead of running out to meet it.
            let last_in_front = path
                .iter()
                .rposition(|b| b.x < PITCH_HALF_LENGTH - 1.0)
                .unwrap_or(reach);
            reach = reach.max(last_in_front);
        }
        intercept(
            self.keeper,
            self.world,
            self.analysis,
            reach,
            (INTERCEPT_AIM, BackDash::Any),
            self.world.ball.pos,
        )
    }

    /// `Bhv_GoalieChaseBall::execute` after its tackle (spec 7.3).
    fn chase(&self) -> Command {
        let i = self.intercept_point;
        let inside = i.x > PENALTY_AREA_X + self.pen_thr
            && i.x < PITCH_HALF_LENGTH + 1.0
            && i.y.abs() < PENALTY_AREA_HALF_WIDTH - self.pen_thr;
        if inside {
            return self.intercept();
        }
        let ball = &self.world.ball;
        let k = self.keeper.pos;
        let line_point = (ball.vel.x.abs() > 1e-6).then(|| {
            let t = (k.x - ball.pos.x) / ball.vel.x;
            DVec2::new(k.x, ball.pos.y + ball.vel.y * t)
        });
        let passes_close = ball.vel.length() > 1e-6 && {
            let u = ball.vel.normalize();
            (k - ball.pos).perp_dot(u).abs() < 1.04
        };
        let crossing = match line_point {
            Some(x) if !passes_close && x.y.abs() <= 10.01 => x,
            _ => {
                if self.attacker_kickable {
                    return self.basic_move();
                }
                if self.self_min <= self.opp_min + 2 && i.x < PITCH_HALF_LENGTH + 2.0 {
                    return self.intercept();
                }
                return go_to_catch_point(self.keeper, ball.pos);
            }
        };
        if crossing.x.abs() > 53.8 || crossing.x < 37.3 || crossing.y.abs() > 18.86 {
            if self.self_min <= self.opp_min {
                return self.intercept();
            }
            return self.basic_move();
        }
        if self.keeper.final_drift().distance(crossing) < (0.2 + 0.1 * self.ball_dist).max(0.5) {
            return stop_dash(self.keeper);
        }
        let mut target = crossing;
        if ball.pos.x < 35.0 {
            target.y = if ball.pos.y * target.y < 0.0 {
                0.0
            } else {
                target.y / 2.0
            };
        }
        go_to_catch_point(self.keeper, target)
    }

    /// `getTargetPoint` (spec 7.4).
    fn target_point(&self) -> DVec2 {
        let n = if self.attacker_kickable {
            0
        } else {
            self.opp_min
        };
        let b = self.world.ball_inertia(n.min(1000) as u32);
        let near_post = |post_y: f64| direction(DVec2::new(PITCH_HALF_LENGTH, post_y) - b);
        let (lo, hi) = (40f64.to_radians(), FRAC_PI_2);
        if b.y < -10.01 && (lo..=hi).contains(&near_post(-GOAL_HALF_WIDTH)) {
            return DVec2::new(51.5, -7.011);
        }
        if b.y > 10.01 && (-hi..=-lo).contains(&near_post(GOAL_HALF_WIDTH)) {
            return DVec2::new(51.5, 7.011);
        }
        if b.x > 44.5 && b.y.abs() > 9.01 {
            return DVec2::new(49.8, 6.91f64.copysign(b.y));
        }
        let mut p = if self.attacker_kickable {
            b
        } else {
            let m = self.opp_min.min(5) as u32;
            b + self.world.ball.vel * decay_sum(BALL_DECAY, m)
        };
        p.x = p.x.min(59.4);
        let behind = DVec2::new(59.5, 0.0);
        let y = p.y + (49.8 - p.x) * (behind.y - p.y) / (behind.x - p.x);
        DVec2::new(49.8, y.clamp(-6.51, 6.51))
    }

    /// `getBasicDashPower` (spec 7.4).
    fn dash_power(&self, target: DVec2) -> f64 {
        let k = self.keeper;
        let ball = &self.world.ball;
        if (k.pos.x - target.x).abs() > 3.0 {
            return MAX_DASH_POWER;
        }
        if ball.pos.x < 30.0 {
            return if k.stamina < 7200.0 { 22.5 } else { 45.0 };
        }
        if ball.pos.x < 36.0 {
            return if ball.pos.y.abs() > 20.0 {
                45.0
            } else if ball.vel.x < -1.0 {
                22.5
            } else if self.opp_min <= 3 {
                MAX_DASH_POWER
            } else if k.stamina < 5600.0 {
                31.5
            } else {
                60.0
            };
        }
        if ball.pos.y.abs() < 15.0 || ball.pos.y * k.pos.y < 0.0 {
            MAX_DASH_POWER
        } else {
            45.0
        }
    }

    /// `Bhv_GoalieBasicMove` after its tackle (spec 7.4).
    fn basic_move(&self) -> Command {
        let k = self.keeper;
        let ball = self.world.ball.pos;
        let mut target = self.target_point();
        let power = self.dash_power(target);
        let tolerance = (0.1 * self.ball_dist).max(0.5);
        // More than 60° off the goal axis, seen from the goal centre (cos 60° = 0.5).
        let from_goal = ball - GOAL_CENTER;
        let ball_off_axis = -from_goal.x < 0.5 * from_goal.length();
        // Deep cross: hold the near-post spot facing the field.
        if target.y.abs() >= 6.21 && ball_off_axis {
            return go_to_point(k, target, tolerance, power).unwrap_or_else(|| {
                turn_to_direction(
                    k,
                    if ball.y > 0.0 {
                        -170f64.to_radians()
                    } else {
                        170f64.to_radians()
                    },
                )
            });
        }
        let to_target = target - k.pos;
        if to_target.length() < tolerance && k.vel.dot(to_target) < 0.0 && k.vel.length() > 0.05 {
            return stop_dash(k);
        }
        // Dangerous: an attacker on the ball in front of goal; shift, never step out.
        let nearest = self
            .world
            .offense
            .iter()
            .min_by(|a, b| a.pos.distance(ball).total_cmp(&b.pos.distance(ball)));
        if let Some(att) = nearest
            && (target.x - k.pos.x).abs() > 0.5
            && self.ball_next.x > 41.5
            && self.ball_next.y.abs() < 8.01
            && att.pos.distance(ball) < 2.0
        {
            target = DVec2::new((att.pos.x + 2.5).max(k.pos.x), target.y);
            return go_to_y(k, target, self.ball_dist, power)
                .or_else(|| go_to_point(k, target, tolerance, MAX_DASH_POWER))
                .unwrap_or_else(|| turn_to_point(k, ball));
        }
        let correct_x = (target.x - k.pos.x).abs() >= 0.5
            && ((!self.attacker_kickable && self.opp_min >= 4) || self.ball_dist > 18.0);
        if correct_x && let Some(cmd) = go_to_point(k, target, 0.5, power) {
            return cmd;
        }
        let side = if self.ball_next.y > k.pos.y {
            FRAC_PI_2
        } else {
            -FRAC_PI_2
        };
        let body_off = angle_diff(k.body, side) > 5f64.to_radians();
        if body_off && !ball_off_axis && (self.opp_min > 7 || self.ball_dist > 20.0) {
            return turn_to_direction(k, side);
        }
        if let Some(cmd) = go_to_y(k, target, self.ball_dist, power) {
            return cmd;
        }
        if body_off {
            return turn_to_direction(k, side);
        }
        Command::Turn { moment: 0.0 }
    }
}

/// Rule 7 of spec 7.4: correct y along a body parallel to the goal line.
fn go_to_y(k: &Player, target: DVec2, ball_dist: f64, power: f64) -> Option<Command> {
    let dy = target.y - k.pos.y;
    if dy.abs() < (0.08 * ball_dist).max(0.5) {
        return None;
    }
    let parallel =
        angle_diff(k.body, FRAC_PI_2).min(angle_diff(k.body, -FRAC_PI_2)) < 7f64.to_radians();
    if !parallel {
        return go_to_point(k, target, 0.5, power);
    }
    let forward = unit(k.body);
    let needed = (target - k.final_drift()).dot(forward);
    let dash = (needed.abs() * (1.0 - PLAYER_DECAY) / (DASH_POWER_RATE * k.effort)).min(power);
    Some(Command::Dash {
        power: dash.copysign(needed),
        dir: 0.0,
    })
}

/// "Go to catch point" (spec 7.3): dash straight at `target` if facing it (or
/// its back), otherwise turn.
fn go_to_catch_point(k: &Player, target: DVec2) -> Command {
    let rel = target - k.pos;
    let e = normalize_angle(direction(rel) - k.body);
    let buf = (1.17 / rel.length().max(1e-6)).atan();
    if e.abs() < buf {
        Command::Dash {
            power: MAX_DASH_POWER,
            dir: 0.0,
        }
    } else if e.abs() > PI - buf {
        Command::Dash {
            power: -MAX_DASH_POWER,
            dir: 0.0,
        }
    } else if e.abs() < FRAC_PI_2 {
        turn_to_direction(k, k.body + e)
    } else {
        turn_to_direction(k, k.body + e - PI.copysign(e))
    }
}
