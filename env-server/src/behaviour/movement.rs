//! MOVE (spec 6.1): tackle if agent2d would, chase the ball if this agent
//! gets there first, otherwise go to the formation position.

use super::Situation;
use super::body::{go_to_point, intercept, turn_to_point};
use super::tackle::{self, Tackler};
use crate::params::*;
use crate::physics::Command;
use glam::DVec2;

/// Where an attacker with the ball, or with the ball coming to it, faces.
pub fn forward_point(y: f64) -> DVec2 {
    DVec2::new(50.5, 0.75 * y)
}

/// The MOVE command of offense agent `s.agent`.
pub fn command(s: &Situation) -> Command {
    if let Some(cmd) = tackle::command(s.world, s.analysis, Tackler::Attacker(s.agent)) {
        return cmd;
    }
    let me = s.me();
    if s.world.agent_kickable(s.agent) {
        return turn_to_point(me, forward_point(me.pos.y));
    }
    let self_min = s.analysis.own_reach[s.agent];
    let mate_min = s.analysis.mate_reach(s.agent);
    let opp_min = s.analysis.keeper_reach;
    let chase = self_min <= 3 || (self_min <= mate_min && self_min < opp_min + 3);
    if chase && !s.world.teammate_kickable(s.agent) {
        return intercept(
            me,
            s.world,
            s.analysis,
            self_min,
            KICKABLE_AREA,
            forward_point(me.pos.y),
        );
    }
    let target = s.analysis.home[s.agent];
    let tolerance = (0.1 * me.pos.distance(s.world.ball.pos)).max(1.0);
    go_to_point(me, target, tolerance, dash_power(s))
        .unwrap_or_else(|| turn_to_point(me, s.world.ball.pos))
}

/// agent2d's positioning dash power (spec 6.1.4).
fn dash_power(s: &Situation) -> f64 {
    let me = s.me();
    let ball = &s.world.ball;
    let inc = STAMINA_INC_MAX * me.recovery;
    let self_min = s.analysis.own_reach[s.agent];
    let mate_min = s.analysis.mate_reach(s.agent);
    let opp_min = s.analysis.keeper_reach;
    if me.recover_mode {
        (inc - 25.0).max(0.0)
    } else if s.world.teammate_kickable(s.agent) && ball.pos.distance(me.pos) < 20.0 {
        (1.1 * inc).min(MAX_DASH_POWER)
    } else if me.pos.x > s.world.offside_line {
        MAX_DASH_POWER
    } else if ball.pos.x > 25.0
        && ball.pos.x > me.pos.x + 10.0
        && self_min + 6 < opp_min
        && mate_min + 6 < opp_min
    {
        (0.5 * inc).clamp(10.0, MAX_DASH_POWER)
    } else {
        (1.7 * inc).min(MAX_DASH_POWER)
    }
}
