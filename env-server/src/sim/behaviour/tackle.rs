//! agent2d's opportunistic tackle (spec 6.1 step 1, 7.3 step 1): HFO's
//! `Bhv_BasicTackle` (src/bhv_basic_tackle.cpp, protocol v14) with the
//! direction of its `TackleGenerator` (src/chain_action/tackle_generator.cpp).

use super::body::predict_turn_cycles;
use crate::sim::analysis::{Analysis, NO_REACH};
use crate::sim::geom::{angle_diff, ceil_usize, direction, normalize_angle, unit};
use crate::sim::kinematics::{dash_cycles, decay_sum};
use crate::sim::params::*;
use crate::sim::physics::{Command, tackle_accel, tackle_probability};
use crate::sim::world::{Player, World};
use glam::DVec2;
use std::f64::consts::{PI, TAU};

/// The lowest success probability at which agent2d tackles (both roles use 0.8).
const MIN_PROBABILITY: f64 = 0.8;
/// Tackle directions TackleGenerator tries, evenly over the full circle.
const ANGLE_DIVS: usize = 40;

/// Who considers tackling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Tackler {
    /// Offense agent `i` (Bhv_BasicMove).
    Attacker(usize),
    /// The goalkeeper (Bhv_GoalieChaseBall, Bhv_GoalieBasicMove).
    Keeper,
}

/// `Bhv_BasicTackle::execute`: the tackle command if the tackle succeeds with
/// probability >= 0.8 and is needed, aimed by `TackleGenerator`.
pub(crate) fn command(world: &World, analysis: &Analysis, tackler: Tackler) -> Option<Command> {
    let ball = &world.ball;
    // The tackler's own frame: its goal at x = -52.5 (the keeper's is rotated by 180°).
    let (me, frame, self_min, mate_min, opp_min, opponent_kickable) = match tackler {
        Tackler::Attacker(i) => (
            &world.offense[i],
            1.0,
            analysis.own_reach[i],
            analysis.mate_reach(i),
            analysis.keeper_reach,
            world.keeper_kickable_seen_by(i),
        ),
        Tackler::Keeper => {
            let kickable = world.attacker_kickable_seen_by_keeper();
            let opp_min = if kickable {
                0
            } else {
                analysis.attacker_reach()
            };
            (
                &world.keeper,
                -1.0,
                analysis.keeper_own_reach,
                NO_REACH,
                opp_min,
                kickable,
            )
        }
    };
    let mut prob = tackle_probability(me, ball.pos, TACKLE_EXPONENT);
    // librcsc's foul probability is 0 unless the opponents' reach cycle is 0
    // (SelfObject::updateKickableState): for the keeper in its area, within
    // its catchable area (1.3 m). agent2d fouls only outside its own area.
    let foul_prob = if opp_min == 0 {
        tackle_probability(me, ball.pos, FOUL_EXPONENT)
    } else {
        0.0
    };
    let own_ball = ball.pos * frame;
    let outside_own_area =
        own_ball.x > -PENALTY_AREA_X + 0.5 || own_ball.y.abs() > PENALTY_AREA_HALF_WIDTH + 0.5;
    let foul = outside_own_area && prob < foul_prob;
    if foul {
        prob = foul_prob;
    }
    if prob < MIN_PROBABILITY {
        return None;
    }
    let their_goal = GOAL_CENTER * frame;
    let needed = opponent_kickable
        || ball_into_own_goal(world, self_min, frame)
        || (opp_min + 3 < self_min && opp_min + 3 < mate_min)
        || (self_min >= 5
            && ball.pos.distance(their_goal) < 10.0
            && angle_diff(direction(their_goal - me.pos), me.body) < 45f64.to_radians());
    if !needed || me.pos.distance(ball.pos) <= AGENT_KICKABLE_AREA {
        // TackleGenerator proposes nothing to a player who can kick.
        return None;
    }
    let opponents: Vec<&Player> = match tackler {
        Tackler::Attacker(_) => vec![&world.keeper],
        Tackler::Keeper => world.offense.iter().collect(),
    };
    let dir = best_direction(me, world, &opponents, frame);
    Some(Command::Tackle {
        dir: normalize_angle(dir - me.body),
        foul,
    })
}

/// Bhv_BasicTackle's "ball will be in our goal": the ball's point after
/// `self_min` cycles is behind the own goal line and its ray crosses that
/// line within a metre of the goal mouth.
fn ball_into_own_goal(world: &World, self_min: usize, frame: f64) -> bool {
    let reach = world.ball_inertia(self_min.min(1000) as u32) * frame;
    let (pos, vel) = (world.ball.pos * frame, world.ball.vel * frame);
    if reach.x >= -PITCH_HALF_LENGTH || vel.x >= 0.0 {
        return false;
    }
    let t = (-PITCH_HALF_LENGTH - pos.x) / vel.x;
    t >= 0.0 && (pos.y + vel.y * t).abs() < GOAL_HALF_WIDTH + 1.0
}

/// `TackleGenerator::calculate`: the global tackle direction among 40 whose
/// resulting ball velocity scores best (`evaluate`).
fn best_direction(me: &Player, world: &World, opponents: &[&Player], frame: f64) -> f64 {
    let ball = &world.ball;
    let mut best = (f64::NEG_INFINITY, 0.0);
    for a in 0..ANGLE_DIVS {
        let dir = -PI + TAU * a as f64 / ANGLE_DIVS as f64;
        let vel = (ball.vel + tackle_accel(me, ball.pos, dir)).clamp_length_max(BALL_SPEED_MAX);
        let score = evaluate(ball.pos, vel, opponents, frame);
        if score > best.0 {
            best = (score, me.body + dir);
        }
    }
    best.1
}

/// `TackleGenerator::evaluate` of the ball leaving `pos` with `vel`, in the
/// tackler's frame: a shot into the opponent goal from within 20 m scores
/// up to 10⁶; a ball into the own goal is penalised; otherwise the score grows
/// with the angle away from the own goal, the closeness of the ball's resting
/// point (or exit point) to a touchline and the opponents' time to reach it.
fn evaluate(pos: DVec2, vel: DVec2, opponents: &[&Player], frame: f64) -> f64 {
    let speed = vel.length();
    let speed_gauss = (-speed * speed / (2.0 * (0.5 * BALL_SPEED_MAX).powi(2))).exp();
    let (p, v) = (pos * frame, vel * frame);
    let end = p + v / (1.0 - BALL_DECAY);
    let crossing = |x: f64| {
        ((p.x - x) * (end.x - x) <= 0.0 && end.x != p.x)
            .then(|| (p.y + (end.y - p.y) * (x - p.x) / (end.x - p.x)).abs())
    };
    if end.x > PITCH_HALF_LENGTH
        && p.distance(GOAL_CENTER) < 20.0
        && let Some(y) = crossing(PITCH_HALF_LENGTH).filter(|y| *y < GOAL_HALF_WIDTH)
    {
        let goal_width = 2.0 * GOAL_HALF_WIDTH;
        return 1e6 * (1.0 - speed_gauss) * (-y * y / (2.0 * goal_width * goal_width)).exp();
    }
    if end.x < -PITCH_HALF_LENGTH
        && let Some(y) = crossing(-PITCH_HALF_LENGTH).filter(|y| *y < GOAL_HALF_WIDTH + 1.0)
    {
        let off = y - GOAL_HALF_WIDTH;
        return -1e4 * (-off * off / (2.0 * GOAL_HALF_WIDTH * GOAL_HALF_WIDTH)).exp()
            + 1e4 * speed_gauss;
    }
    let step = opponents_reach_step(pos, vel, opponents);
    let mut last = p + v * decay_sum(BALL_DECAY, step as u32);
    if let Some(t) = pitch_exit(p, last - p).filter(|t| *t <= 1.0) {
        last = p + (last - p) * t;
    }
    let own_goal_diff = angle_diff(direction(-GOAL_CENTER - p), direction(v)).to_degrees();
    let goal_angle_rate = 1.0 - (-own_goal_diff.powi(2) / (2.0 * 40f64.powi(2))).exp();
    let y_rate = if last.y.abs() > PITCH_HALF_WIDTH - 0.1 {
        1.0
    } else {
        (-(last.y.abs() - PITCH_HALF_WIDTH).powi(2) / (2.0 * (0.7 * PITCH_HALF_WIDTH).powi(2)))
            .exp()
    };
    let opp_rate = 1.0 - (-(step as f64).powi(2) / (2.0 * 30f64.powi(2))).exp();
    1e4 * goal_angle_rate * y_rate * opp_rate
}

/// The parameter `t >= 0` at which `p + t·d` leaves the pitch, for `p` on it.
fn pitch_exit(p: DVec2, d: DVec2) -> Option<f64> {
    let half = DVec2::new(PITCH_HALF_LENGTH, PITCH_HALF_WIDTH);
    if p.x.abs() > half.x || p.y.abs() > half.y || d == DVec2::ZERO {
        return None;
    }
    let axis = |p: f64, d: f64, h: f64| {
        if d > 0.0 {
            (h - p) / d
        } else if d < 0.0 {
            (-h - p) / d
        } else {
            f64::INFINITY
        }
    };
    Some(axis(p.x, d.x, half.x).min(axis(p.y, d.y, half.y)))
}

/// `TackleGenerator::predictOpponentsReachStep` (global frame, which the
/// centred pitch makes equivalent): the first cycle an opponent reaches the
/// ball, or 1000 if none does before it leaves the pitch (or within 50 cycles).
fn opponents_reach_step(pos: DVec2, vel: DVec2, opponents: &[&Player]) -> usize {
    let mut first = 50;
    let end = pos + vel / (1.0 - BALL_DECAY);
    if (end.x.abs() > PITCH_HALF_LENGTH || end.y.abs() > PITCH_HALF_WIDTH)
        && let Some(t) = pitch_exit(pos, vel)
    {
        first = ball_move_step(vel.length(), t * vel.length());
    }
    let min = opponents.iter().fold(first, |min, o| {
        min.min(opponent_reach_step(o, pos, vel, min))
    });
    if min == first { 1000 } else { min }
}

/// librcsc `ServerParam::ballMoveStep`: cycles a ball at `speed` needs to roll
/// `dist` (0 if it never gets there).
fn ball_move_step(speed: f64, dist: f64) -> usize {
    if speed <= 1e-6 || dist <= 1e-6 {
        return 0;
    }
    let ratio = 1.0 - dist * (1.0 - BALL_DECAY) / speed;
    if ratio <= 1e-6 {
        return 0;
    }
    ceil_usize(ratio.ln() / BALL_DECAY.ln())
}

/// `TackleGenerator::predictOpponentReachStep`: the first cycle below
/// `max_cycle` at which opponent `o` can reach the ball (1000 if none).
fn opponent_reach_step(o: &Player, pos: DVec2, vel: DVec2, max_cycle: usize) -> usize {
    let angle = direction(vel);
    // FieldAnalyzer::estimate_min_reach_cycle.
    let rel = (o.pos - pos).rotate(unit(-angle));
    let min_cycle = if rel.x < -1.0 {
        10
    } else {
        ((rel.y.abs() / REAL_SPEED_MAX).floor() as usize).max(1)
    };
    for cycle in min_cycle..max_cycle {
        let ball = pos + vel * decay_sum(BALL_DECAY, cycle as u32);
        if ball.x.abs() > PITCH_HALF_LENGTH || ball.y.abs() > PITCH_HALF_WIDTH {
            return 1000;
        }
        let at = o.drift(cycle as u32);
        let dist = at.distance(ball);
        if dist - KICKABLE_AREA < 0.001 {
            return cycle;
        }
        let dash_dist = if cycle > 1 {
            dist - KICKABLE_AREA - 0.5
        } else {
            dist
        };
        if dash_dist > REAL_SPEED_MAX * cycle as f64 {
            continue;
        }
        let n_dash = dash_cycles(dash_dist);
        if n_dash > cycle {
            continue;
        }
        let n_turn = predict_turn_cycles(o, direction(ball - at), dist, KICKABLE_AREA);
        let mut n_step = if n_turn == 0 {
            n_dash
        } else {
            n_turn + n_dash + 1
        };
        if o.tackle_freeze > 0 {
            n_step += 5;
        }
        if n_step <= cycle {
            return cycle;
        }
    }
    1000
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::physics::Command;

    /// A world with the keeper, three attackers far away, and the ball at rest.
    fn world(keeper: DVec2, keeper_body: f64, ball: DVec2) -> World {
        let mut w = World::new(3);
        w.keeper = Player::new(keeper, keeper_body);
        for (i, p) in w.offense.iter_mut().enumerate() {
            *p = Player::new(DVec2::new(5.0, -20.0 + 20.0 * i as f64), 0.0);
        }
        w.ball.pos = ball;
        w
    }

    fn ball_vel(w: &World, p: &Player, cmd: Command) -> DVec2 {
        let Command::Tackle { dir, .. } = cmd else {
            panic!("no tackle: {cmd:?}");
        };
        w.ball.vel + tackle_accel(p, w.ball.pos, dir)
    }

    #[test]
    fn keeper_clears_towards_the_touchline_from_an_attacker_on_the_ball() {
        // Keeper out of its area facing the field, ball 1.2 m ahead, an attacker on it.
        let mut w = world(DVec2::new(35.0, 3.0), PI, DVec2::new(33.8, 3.0));
        w.offense[0].pos = DVec2::new(33.0, 3.5);
        let a = Analysis::new(&w);
        let cmd = command(&w, &a, Tackler::Keeper).expect("tackle");
        let v = ball_vel(&w, &w.keeper, cmd);
        assert!(v.x < 0.0 && v.y.abs() > -v.x, "{v}");
        // Outside its area with an attacker on the ball, the keeper fouls.
        assert!(matches!(cmd, Command::Tackle { foul: true, .. }));
        // Nobody on the ball and nothing urgent: no tackle.
        w.offense[0].pos = DVec2::new(20.0, 3.0);
        assert_eq!(command(&w, &Analysis::new(&w), Tackler::Keeper), None);
    }

    #[test]
    fn attacker_tackles_into_the_goal_mouth() {
        // The keeper reaches the rolling ball long before the attacker behind it.
        let mut w = world(DVec2::new(50.0, 1.0), PI, DVec2::new(43.2, -4.0));
        w.ball.vel = DVec2::new(0.0, 1.2);
        w.offense[0] = Player::new(DVec2::new(42.0, -4.5), 0.0);
        let a = Analysis::new(&w);
        let cmd = command(&w, &a, Tackler::Attacker(0)).expect("tackle");
        let v = ball_vel(&w, &w.offense[0], cmd);
        let y = w.ball.pos.y + v.y * (PITCH_HALF_LENGTH - w.ball.pos.x) / v.x;
        assert!(y.abs() < GOAL_HALF_WIDTH, "{v} crosses at {y}");
        let v = v.clamp_length_max(BALL_SPEED_MAX);
        assert!(evaluate(w.ball.pos, v, &[&w.keeper], 1.0) > 1e5);
        assert!(matches!(cmd, Command::Tackle { foul: false, .. }));
    }

    #[test]
    fn an_attacker_fouls_a_keeper_within_its_catchable_area() {
        // The ball 1.6 m ahead of the attacker, rolling on to the keeper:
        // 0.74 by the tackle exponent, 0.89 by the foul one. The keeper 1.2 m
        // from the ball in its area is not on the ball by the kickable area,
        // but its reach cycle is 0, more than 3 cycles before the attackers'.
        let mut w = world(DVec2::new(47.2, 0.0), PI, DVec2::new(46.0, 0.0));
        w.ball.vel = DVec2::new(0.8, 0.0);
        w.offense[0] = Player::new(DVec2::new(44.4, 0.0), 0.0);
        let a = Analysis::new(&w);
        assert!(!w.keeper_kickable());
        assert_eq!(a.keeper_reach, 0);
        assert!(a.own_reach[0] > 3, "{}", a.own_reach[0]);
        let cmd = command(&w, &a, Tackler::Attacker(0));
        assert!(
            matches!(cmd, Some(Command::Tackle { foul: true, .. })),
            "{cmd:?}"
        );
        // 1.4 m away the keeper needs a cycle: no foul, and 0.74 is too little.
        w.keeper.pos.x = 47.4;
        let a = Analysis::new(&w);
        assert_eq!(command(&w, &a, Tackler::Attacker(0)), None);
    }

    #[test]
    fn a_keeper_seen_on_the_ball_makes_the_tackle_needed() {
        // The keeper 1.10 m from the ball and 2.34 m from the attacker 1.3 m
        // behind it: not kickable for the server, but within librcsc's
        // allowance (1.085 + 0.02 · 1.3 + 0.02 · 2.34), so the attacker tackles.
        let mut w = world(DVec2::new(46.0, 0.45), PI, DVec2::new(45.0, 0.0));
        w.offense[0] = Player::new(DVec2::new(43.7, 0.0), 0.0);
        assert!(!w.keeper_kickable());
        assert!(w.keeper_kickable_seen_by(0));
        let a = Analysis::new(&w);
        assert!(command(&w, &a, Tackler::Attacker(0)).is_some());
        // Frozen by its own tackle, it is not counted.
        w.keeper.tackle_freeze = 3;
        assert!(!w.keeper_kickable_seen_by(0));
    }
}
