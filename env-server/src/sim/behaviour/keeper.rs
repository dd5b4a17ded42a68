//! agent2d's base goalkeeper (spec section 7): catch, chase, or position on
//! the line x = 49.8 between the ball and a point behind the goal.

use super::body::{go_to_point, stop_dash, turn_to_direction, turn_to_point};
use super::tackle::{self, Tackler};
use crate::sim::analysis::Analysis;
use crate::sim::geom::{angle_diff, direction, normalize_angle, unit};
use crate::sim::kinematics::{decay_pow, decay_sum};
use crate::sim::params::*;
use crate::sim::physics::{Command, dash_dir_rate};
use crate::sim::self_intercept::Interception;
use crate::sim::world::{Player, World};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// The keeper's command when it has nothing to do.
const IDLE: Command = Command::Turn { moment: 0.0 };

/// What the keeper remembers between cycles.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct KeeperMemory {
    /// Cycles since its last catch command (saturating).
    pub(crate) since_catch: u32,
}

/// The keeper's command this cycle.
pub(crate) fn command(world: &World, analysis: &Analysis, memory: &KeeperMemory) -> Command {
    // While the keeper takes an attacker to be on the ball its world model
    // holds the ball still (librcsc `setOpponentControlEffect`), and so do
    // its reach, its intercept and its positioning.
    if world.attacker_kickable_seen_by_keeper() && world.ball.vel != DVec2::ZERO {
        let believed = world.with_ball_still();
        return decide(&believed, &Analysis::for_keeper(&believed), memory);
    }
    decide(world, analysis, memory)
}

/// [`command`] on the keeper's view of the world.
fn decide(world: &World, analysis: &Analysis, memory: &KeeperMemory) -> Command {
    let k = &world.keeper;
    let ball = world.ball.pos;
    let ball_dist = k.pos.distance(ball);
    let catchable_spot = (37.0..=PITCH_HALF_LENGTH).contains(&ball.x)
        && ball.y.abs() <= PENALTY_AREA_HALF_WIDTH - 1.0;
    // In the goalie-catch mode agent2d's keeper runs Bhv_GoalieFreeKick,
    // which without the ball only positions: no catch, no chase (spec 4.5).
    let play_on = !world.catch_mode;
    if play_on && memory.since_catch > 5 && ball_dist < KEEPER_CONTROL_AREA - 0.05 && catchable_spot
    {
        return Command::Catch;
    }
    // Bhv_GoalieChaseBall and Bhv_GoalieBasicMove both begin with Bhv_BasicTackle.
    if let Some(cmd) = tackle::command(world, analysis, Tackler::Keeper) {
        return cmd;
    }
    let view = View::new(world, analysis);
    if play_on && view.is_chase_situation() {
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
        let attacker_kickable = world.attacker_kickable_seen_by_keeper();
        View {
            world,
            analysis,
            keeper,
            ball_dist,
            ball_next: world.ball.pos + world.ball.vel,
            self_min: analysis.keeper_own_reach,
            opp_min: if attacker_kickable {
                0
            } else {
                analysis.attacker_reach()
            },
            intercept_point: analysis.ball_at(analysis.keeper_own_reach),
            pen_thr: (0.1 * ball_dist + 1.0).max(1.0),
            attacker_kickable,
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

    /// librcsc `Body_Intercept2009::execute` for the keeper (spec 7.3.1);
    /// `save_recovery` keeps its stamina above the recovery threshold.
    fn intercept(&self, save_recovery: bool) -> Command {
        let k = self.keeper;
        let ball = self.world.ball.pos;
        // `doKickableOpponentCheck`: step into an attacker on the ball that
        // stands farther from the goal than the keeper.
        if self.ball_dist < 2.0 && self.attacker_kickable {
            let att = self
                .world
                .offense
                .iter()
                .min_by(|a, b| a.pos.distance(ball).total_cmp(&b.pos.distance(ball)));
            if let Some(att) = att {
                let attack = att.pos + att.vel;
                let me = k.pos + k.vel;
                if attack.distance_squared(GOAL_CENTER) > me.distance_squared(GOAL_CENTER) {
                    return go_to_point(k, attack, 0.1, MAX_DASH_POWER).unwrap_or(IDLE);
                }
            }
        }
        if self.self_min > 100 {
            return go_to_point(k, self.world.ball_final(), 2.0, MAX_DASH_POWER).unwrap_or(IDLE);
        }
        let best = self.best_interception();
        let target = self.analysis.ball_at(best.cycle);
        // agent2d's face point (50.5, 0.75·y) in the keeper's own frame.
        let face = DVec2::new(-50.5, 0.75 * k.pos.y);
        if best.dashes == 0 {
            return turn_to_point(k, face);
        }
        if best.turns > 0 {
            // The body, or for a backward run its back, to the target.
            let mut angle = direction(target - k.drift(best.cycle as u32));
            if best.back() {
                angle += PI;
            }
            return turn_to_direction(k, angle);
        }
        if let Some(cmd) = self.wait_turn(target, best) {
            return cmd;
        }
        // The entry's own first dash: its power and direction (the
        // omni-directional dashes of the short step go sideways).
        let consumed = if best.back() {
            -2.0 * best.power
        } else {
            best.power
        };
        if save_recovery && k.stamina - consumed < 0.3 * STAMINA_MAX + 1.0 {
            return IDLE;
        }
        if best.cycle == 1 {
            return Command::Dash {
                power: best.power,
                dir: best.dir,
            };
        }
        self.inertia_dash(target, best)
            .unwrap_or_else(|| turn_to_point(k, face))
    }

    /// librcsc `Body_Intercept2009::doWaitTurn`: when no attacker is within
    /// 3 m, the attackers need 5 cycles more, and the ball comes within
    /// reach of where the keeper drifts to, turn (to face across the ball's
    /// approach) instead of dashing. Its one-step case needs a turn entry,
    /// which `intercept` has already turned for.
    fn wait_turn(&self, target: DVec2, best: Interception) -> Option<Command> {
        let k = self.keeper;
        let ball = &self.world.ball;
        if self
            .world
            .offense
            .iter()
            .any(|a| a.pos.distance(k.pos) < 3.0)
        {
            return None;
        }
        if best.cycle + 5 > self.opp_min {
            return None;
        }
        let my_inertia = k.drift(best.cycle as u32);
        let target_dist = (target - my_inertia).length();
        let ball_travel = ball.vel.length() * decay_sum(BALL_DECAY, best.cycle as u32);
        let ball_noise = ball_travel * BALL_RAND;
        let mut extra_buf = 0.1 * (best.cycle as f64 - 1.0).clamp(0.0, 4.0);
        let diff = angle_diff(direction(ball.vel), k.body);
        if diff < 10f64.to_radians() || diff > 170f64.to_radians() {
            extra_buf = 0.0;
        }
        // Full state: the ball is seen every cycle (seenPosCount 0).
        let dist_buf = KICKABLE_AREA - 0.3 + extra_buf;
        if target_dist > dist_buf {
            return None;
        }
        let face = if best.cycle > 2 {
            // The ball's direction turned by 90°, or by -90° when that
            // faces the goal (x below the keeper's in its own frame).
            let to_ball = ball.pos - my_inertia;
            let p = my_inertia + DVec2::from_angle(FRAC_PI_2).rotate(to_ball);
            if p.x > my_inertia.x {
                my_inertia + DVec2::from_angle(-FRAC_PI_2).rotate(to_ball)
            } else {
                p
            }
        } else {
            // (50.5, 0.9·y) in the keeper's frame.
            DVec2::new(-50.5, 0.9 * k.pos.y)
        };
        let face_angle = direction(face - my_inertia);
        // librcsc rotates by +face_angle (not -): the |y| it tests is the
        // same in either frame.
        let faced = DVec2::from_angle(face_angle).rotate(target - my_inertia);
        if faced.y.abs() > KICKABLE_AREA - ball_noise - 0.2 {
            return None;
        }
        Some(turn_to_point(k, face))
    }

    /// The keeper's interception (librcsc `Body_Intercept2009::getBestIntercept`,
    /// goalie mode, spec 7.3.1): among the cycles its self-interception cache
    /// holds, the one that meets the ball farthest out, else the earliest.
    fn best_interception(&self) -> Interception {
        let cache = self.analysis.keeper_cache(self.world);
        let mut goalie: Option<(f64, Interception)> = None;
        let mut aggressive: Option<(f64, Interception)> = None;
        for &c in &cache {
            let (t, b) = (c.cycle, self.analysis.ball_at(c.cycle));
            if b.x.abs() > PITCH_HALF_LENGTH - 1.0 || b.y.abs() > PITCH_HALF_WIDTH - 1.0 {
                continue;
            }
            // The ball reached on the keeper's running line without a turn,
            // or exactly on it after one.
            let on_line =
                |area: f64| (c.turns == 0 && c.ball_dist < 0.5 * area) || c.ball_dist < 0.01;
            let deep = b.x > PENALTY_AREA_X + 1.0 && b.y.abs() < PENALTY_AREA_HALF_WIDTH - 1.0;
            let shallow = b.x < PENALTY_AREA_X + 1.0 || b.y.abs() > PENALTY_AREA_HALF_WIDTH - 1.0;
            // Deep in the area, two cycles before the attackers: the point
            // farthest from the goal.
            if deep && t + 1 < self.opp_min && on_line(KEEPER_CONTROL_AREA) {
                let score = b.distance_squared(GOAL_CENTER);
                if goalie.is_none_or(|(s, _)| score > s) {
                    goalie = Some((score, c));
                }
            }
            // Near or beyond the area's edge, five cycles before the attackers
            // (the keeper has no teammates): the point farthest up the field.
            if shallow && t + 5 < self.opp_min && on_line(KICKABLE_AREA) {
                let score = -b.x;
                if aggressive.is_none_or(|(s, _)| score > s) {
                    aggressive = Some((score, c));
                }
            }
        }
        if let Some((_, c)) = aggressive.or(goalie) {
            return c;
        }
        self.field_player_interception(&cache)
    }

    /// The rest of librcsc `Body_Intercept2009::getBestIntercept` (after its
    /// goalie modes): the no-turn, forward and nearest candidates among the
    /// entries before 0.7 of the attackers' reach, in the keeper's frame
    /// (x and y mirrored). Its "attacker" class needs the ball beyond the
    /// keeper's x = 35 or its offside line (never below 0): never in HFO.
    fn field_player_interception(&self, cache: &[Interception]) -> Interception {
        let ball = &self.world.ball;
        let k = self.keeper;
        let ball_at = |t: usize| self.analysis.ball_at(t);
        let ball_vel = |t: usize| ball.vel * decay_pow(BALL_DECAY, t as u32);
        // (65, 0) in the keeper's frame.
        let goal_pos = DVec2::new(-65.0, 0.0);
        let speed_max = 0.9 * REAL_SPEED_MAX;
        let opp_min = self.opp_min;
        let mut noturn: Option<(f64, Interception)> = None;
        let mut forward: Option<(f64, Interception)> = None;
        let mut nearest: Option<(f64, Interception)> = None;
        for &c in cache {
            let (t, b, v) = (c.cycle, ball_at(c.cycle), ball_vel(c.cycle));
            if b.x.abs() > PITCH_HALF_LENGTH - 1.0 || b.y.abs() > PITCH_HALF_WIDTH - 1.0 {
                continue;
            }
            if t as f64 >= opp_min as f64 * 0.7 {
                continue;
            }
            if c.turns == 0 {
                let score = t as f64;
                if noturn.is_none_or(|(s, _)| score < s) {
                    noturn = Some((score, c));
                }
                continue;
            }
            if -v.x > 0.1 && t + 5 <= opp_min && v.length_squared() > 0.6 * 0.6 {
                let score = 100.0 * 100.0 - (100.0f64 * 100.0).min(b.distance_squared(goal_pos));
                if forward.is_none_or(|(s, _)| score > s) {
                    forward = Some((score, c));
                }
                continue;
            }
            let d = k.drift(t as u32).distance_squared(b);
            if nearest.is_none_or(|(s, _)| d < s) {
                nearest = Some((d, c));
            }
        }
        let noturn = noturn.map(|(_, c)| c);
        let forward = forward.map(|(_, c)| c);
        let nearest = nearest.map(|(_, c)| c);
        if let (Some(n), Some(f)) = (noturn, forward) {
            let nv = ball_vel(n.cycle);
            if -nv.x > 0.1 && (nv.length() > speed_max || n.cycle <= f.cycle + 2) {
                return n;
            }
        }
        if let Some(f) = forward {
            return f;
        }
        let fastest = cache[0];
        let fastest_pos = ball_at(fastest.cycle);
        if (fastest_pos.x < 33.0 || fastest_pos.y.abs() > 20.0)
            && (fastest.cycle >= 10 || ball_vel(fastest.cycle).length() < 1.2)
        {
            return fastest;
        }
        match (noturn, nearest) {
            (Some(n), Some(m)) => {
                let (n_ball, m_ball) = (ball_at(n.cycle), ball_at(m.cycle));
                let m_self = k.drift(m.cycle as u32);
                if k.drift(n.cycle as u32).distance_squared(n_ball)
                    < m_self.distance_squared(m_ball)
                {
                    return n;
                }
                if m.cycle <= n.cycle + 2 {
                    let m_speed = ball_vel(m.cycle).length();
                    if m_speed < 0.7 {
                        return m;
                    }
                    let nv = ball_vel(n.cycle);
                    if m.ball_dist < KICKABLE_AREA - 0.4
                        && m.ball_dist < n.ball_dist
                        && -nv.x < 0.5
                        && nv.length_squared() > 1.0
                        && n_ball.x < m_ball.x
                    {
                        return m;
                    }
                    if m_speed > 0.7 && m_self.distance(m_ball) < KICKABLE_AREA {
                        return m;
                    }
                }
                n
            }
            (Some(n), None) => n,
            (None, Some(m)) => m,
            // Its "chance" candidates need the keeper beyond x = 40 of its
            // frame (here x < -40): never.
            (None, None) => fastest,
        }
    }

    /// librcsc `Body_Intercept2009::doInertiaDash` for the keeper: dash
    /// towards `target` at `full` power, or with just the power that arrives
    /// in time when the ball is slow and near; `None` (look at the field)
    /// when from cycle 4 on it is already there along its body.
    fn inertia_dash(&self, target: DVec2, best: Interception) -> Option<Command> {
        let k = self.keeper;
        let forward = unit(k.body);
        let along = (target - k.pos).dot(forward);
        let ball_speed = self.world.ball.vel.length() * decay_pow(BALL_DECAY, best.cycle as u32);
        let accel_max = DASH_POWER_RATE * k.effort * MAX_DASH_POWER;
        let mut power = best.power;
        if ball_speed < 1.5 * KICKABLE_AREA
            && best.dir.abs() < 5f64.to_radians()
            && along.abs() < KICKABLE_AREA + 0.8 * accel_max
        {
            let first_speed = (along / decay_sum(PLAYER_DECAY, best.cycle as u32))
                .clamp(-PLAYER_SPEED_MAX, PLAYER_SPEED_MAX);
            power = ((first_speed - k.vel.dot(forward))
                / (DASH_POWER_RATE * k.effort)
                / dash_dir_rate(best.dir))
            .clamp(-MAX_DASH_POWER, MAX_DASH_POWER);
        }
        if best.cycle >= 4 && (along.abs() < 0.5 || power.abs() < 5.0) {
            return None;
        }
        Some(Command::Dash {
            power,
            dir: best.dir,
        })
    }

    /// `Bhv_GoalieChaseBall::execute` after its tackle (spec 7.3).
    fn chase(&self) -> Command {
        let i = self.intercept_point;
        let inside = i.x > PENALTY_AREA_X + self.pen_thr
            && i.x < PITCH_HALF_LENGTH + 1.0
            && i.y.abs() < PENALTY_AREA_HALF_WIDTH - self.pen_thr;
        let ball = &self.world.ball;
        let k = self.keeper.pos;
        // Distance from the keeper to the ball's line (none for a ball at rest).
        let line_dist = if ball.vel.length() > 1e-6 {
            (k - ball.pos).perp_dot(ball.vel.normalize()).abs()
        } else {
            f64::INFINITY
        };
        if inside {
            return self.intercept(line_dist < KEEPER_CONTROL_AREA);
        }
        let line_point = (ball.vel.x.abs() > 1e-6).then(|| {
            let t = (k.x - ball.pos.x) / ball.vel.x;
            DVec2::new(k.x, ball.pos.y + ball.vel.y * t)
        });
        let passes_close = line_dist < 0.8 * KEEPER_CONTROL_AREA;
        let crossing = match line_point {
            Some(x) if !passes_close && x.y.abs() <= 10.01 => x,
            _ => {
                if self.attacker_kickable {
                    return self.basic_move();
                }
                let in_area = i.x > PENALTY_AREA_X + self.pen_thr
                    && i.x < PITCH_HALF_LENGTH + 2.0
                    && i.y.abs() < PENALTY_AREA_HALF_WIDTH - self.pen_thr;
                if self.self_min <= self.opp_min + 2 && in_area {
                    return self.intercept(false);
                }
                return go_to_catch_point(self.keeper, ball.pos);
            }
        };
        // Body_Intercept without stamina saving always acts.
        if crossing.x.abs() > 53.8 || crossing.x < 37.3 || crossing.y.abs() > 18.86 {
            return self.intercept(false);
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
        // `doCorrectBodyDir`: face the half of the field (the sign of
        // ball_next.y, not the ball's side of the keeper) unless an attacker
        // is within 7 m of the ball (and the ball within 20 m, and the y
        // error 1 m or more or an attacker on the ball).
        let side = if self.ball_next.y > 0.0 {
            FRAC_PI_2
        } else {
            -FRAC_PI_2
        };
        let body_off = angle_diff(k.body, side) >= 5f64.to_radians();
        let nearest_attacker = self
            .world
            .offense
            .iter()
            .map(|a| a.pos.distance(ball))
            .fold(100.0, f64::min);
        let free = nearest_attacker > 7.0
            || self.ball_dist > 20.0
            || ((target.y - k.pos.y).abs() < 1.0 && !self.attacker_kickable);
        if body_off && !ball_off_axis && free {
            return turn_to_direction(k, side);
        }
        if let Some(cmd) = go_to_y(k, target, self.ball_dist, power) {
            return cmd;
        }
        // Its second call: the same danger-area (60°) test, no attacker test.
        if body_off && !ball_off_axis {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A keeper at `keeper` facing `body`, the ball at `ball` moving at
    /// `vel`, and three attackers far from the play.
    fn scene(keeper: DVec2, body: f64, ball: DVec2, vel: DVec2) -> (World, Analysis) {
        let mut w = World::new(3);
        for (i, a) in w.offense.iter_mut().enumerate() {
            a.place(DVec2::new(5.0, -20.0 + 20.0 * i as f64));
        }
        w.keeper = Player::new(keeper, body);
        w.ball.pos = ball;
        w.ball.vel = vel;
        let a = Analysis::new(&w);
        (w, a)
    }

    #[test]
    fn with_an_attacker_on_the_ball_the_keeper_holds_the_ball_still() {
        // An attacker dribbling at the keeper: the keeper decides as if the
        // ball did not move (librcsc's setOpponentControlEffect), which for
        // some of these states is not what the moving ball would make it do.
        let memory = KeeperMemory { since_catch: 100 };
        let mut differs = 0;
        for i in 0..8 {
            for j in 0..5 {
                let ball = DVec2::new(40.0 + i as f64, -4.0 + 2.0 * j as f64);
                let (mut w, _) = scene(DVec2::new(49.5, 0.0), PI, ball, DVec2::new(0.8, 0.1));
                w.offense[0].place(ball - DVec2::new(1.1, 0.0));
                assert!(w.attacker_kickable_seen_by_keeper());
                let cmd = command(&w, &Analysis::new(&w), &memory);
                let still = w.with_ball_still();
                assert_eq!(
                    cmd,
                    decide(&still, &Analysis::new(&still), &memory),
                    "{ball}"
                );
                differs += usize::from(cmd != decide(&w, &Analysis::new(&w), &memory));
            }
        }
        assert!(differs > 0);
    }

    #[test]
    fn the_keeper_counts_an_attacker_on_the_ball_with_its_margin_of_sight() {
        // librcsc: within 1.085 m plus 2 % of the keeper's distances from
        // the ball and from the attacker (each at most 0.25 m).
        let (mut w, _) = scene(
            DVec2::new(50.0, 0.0),
            PI,
            DVec2::new(40.0, 0.0),
            DVec2::ZERO,
        );
        w.offense[0].place(DVec2::new(38.7, 0.0));
        assert!(
            w.attacker_kickable_seen_by_keeper(),
            "1.3 m < 1.085 + 0.2 + 0.226"
        );
        assert!(!w.any_attacker_kickable());
        w.offense[0].place(DVec2::new(38.4, 0.0));
        assert!(!w.attacker_kickable_seen_by_keeper());
        // Only the attacker nearest the ball counts; one frozen by its
        // tackle is passed over.
        w.offense[1].place(DVec2::new(39.5, 0.0));
        w.offense[1].tackle_freeze = 3;
        w.offense[2].place(DVec2::new(40.0, 1.2));
        assert!(w.attacker_kickable_seen_by_keeper());
    }

    /// The cache entries the goalie rule of `getBestIntercept` accepts.
    fn goalie_candidates(view: &View) -> Vec<Interception> {
        view.analysis
            .keeper_cache(view.world)
            .into_iter()
            .filter(|c| (c.turns == 0 && c.ball_dist < 0.65) || c.ball_dist < 0.01)
            .collect()
    }

    #[test]
    fn keeper_meets_a_ball_moving_away_as_far_out_as_it_can() {
        // A loose ball rolling out of the goal mouth: the keeper reaches it at
        // once but takes it where it is farthest from the goal.
        let (w, a) = scene(
            DVec2::new(50.0, 0.0),
            PI,
            DVec2::new(49.0, 0.3),
            DVec2::new(-1.0, 0.0),
        );
        let view = View::new(&w, &a);
        let best = view.best_interception();
        let candidates = goalie_candidates(&view);
        assert!(
            best.cycle > view.self_min + 5,
            "{best:?} vs {}",
            view.self_min
        );
        let dist = |c: &Interception| a.ball_at(c.cycle).distance(GOAL_CENTER);
        assert!(candidates.iter().all(|c| dist(c) <= dist(&best)));
        assert!(a.ball_at(best.cycle).x > PENALTY_AREA_X + 1.0);
    }

    #[test]
    fn keeper_meets_a_shot_where_it_runs_onto_its_line() {
        // A shot across the keeper: its first reach needs a turn and leaves
        // the ball 0.4 m short; one cycle later the turned keeper runs onto
        // the ball's line.
        let (w, a) = scene(
            DVec2::new(49.8, 0.0),
            PI,
            DVec2::new(36.0, 2.0),
            DVec2::new(2.4, 0.0),
        );
        let view = View::new(&w, &a);
        let best = view.best_interception();
        assert_eq!(view.self_min, 5);
        assert_eq!((best.cycle, best.turns), (6, 1));
        assert!(best.ball_dist < 0.01);
        // It turns towards that point first.
        assert!(matches!(view.intercept(false), Command::Turn { .. }));
    }

    #[test]
    fn keeper_takes_its_earliest_reach_when_an_attacker_is_close() {
        // Same loose ball with an attacker one step from its path: no point is
        // two cycles ahead of it, so the keeper takes its earliest reach.
        let (mut w, _) = scene(
            DVec2::new(50.0, 0.0),
            PI,
            DVec2::new(49.0, 0.3),
            DVec2::new(-1.0, 0.0),
        );
        w.offense[0].place(DVec2::new(44.0, 1.8));
        let a = Analysis::new(&w);
        let view = View::new(&w, &a);
        assert!(view.opp_min <= view.self_min + 4);
        assert_eq!(view.best_interception().cycle, view.self_min);
    }

    #[test]
    fn after_a_catch_the_keeper_only_positions() {
        // A ball rolling past the keeper within its catch area: in play-on it
        // catches; in the goalie-catch mode it neither catches nor chases but
        // takes its basic position.
        let (mut w, a) = scene(
            DVec2::new(48.0, 0.0),
            PI,
            DVec2::new(47.5, 0.5),
            DVec2::new(-0.8, 0.0),
        );
        let memory = KeeperMemory {
            since_catch: u32::MAX,
        };
        assert_eq!(command(&w, &a, &memory), Command::Catch);
        w.catch_mode = true;
        let view = View::new(&w, &a);
        assert!(view.is_chase_situation());
        assert_eq!(command(&w, &a, &memory), view.basic_move());
    }
}
