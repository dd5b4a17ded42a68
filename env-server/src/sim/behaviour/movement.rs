//! MOVE (spec 6.1): tackle if agent2d would, chase the ball if this agent
//! gets there first, otherwise go to the formation position.

use super::body::{go_to_point, turn_to_point};
use super::intercept::{forward_point, intercept};
use super::situation::Situation;
use super::tackle::{self, Tackler};
use crate::sim::params::*;
use crate::sim::physics::Command;
use crate::sim::view::Neck;

/// The MOVE command of offense agent `s.agent` and its neck action:
/// Bhv_BasicTackle's field scan, Neck_OffensiveInterceptNeck when it chases
/// the ball, otherwise the ball when the keeper holds it within 18 m, else
/// the field scan (spec 6.6).
pub(super) fn command(s: &Situation) -> (Command, Neck) {
    if let Some(cmd) = tackle::command(s.world, s.analysis, Tackler::Attacker(s.agent)) {
        return (cmd, Neck::Scan);
    }
    let me = s.me();
    let keeper_kickable = s.world.keeper_kickable_seen_by(s.agent);
    // Neck_OffensiveInterceptNeck: towards ball and keeper when the keeper
    // can kick; the scan once the agent's action chain exists, else nothing.
    let intercept_neck = if keeper_kickable {
        Neck::TurnToBall
    } else if s.memory.sight.chain_ready {
        Neck::Scan
    } else {
        Neck::Keep
    };
    if s.world.agent_kickable(s.agent) {
        return (turn_to_point(me, forward_point(me.pos.y)), intercept_neck);
    }
    let self_min = s.analysis.own_reach[s.agent];
    let mate_min = s.analysis.mate_reach(s.agent);
    let opp_min = s.analysis.keeper_reach;
    let chase = self_min <= 3 || (self_min <= mate_min && self_min < opp_min + 3);
    if chase && !s.world.teammate_kickable(s.agent) {
        let cmd = intercept(s.world, s.analysis, s.agent, forward_point(me.pos.y));
        return (cmd, intercept_neck);
    }
    let target = s.analysis.home[s.agent];
    let ball_dist = me.pos.distance(s.world.ball.pos);
    let tolerance = (0.1 * ball_dist).max(1.0);
    let cmd = go_to_point(me, target, tolerance, dash_power(s))
        .unwrap_or_else(|| turn_to_point(me, s.world.ball.pos));
    let neck = if keeper_kickable && ball_dist < 18.0 {
        Neck::TurnToBall
    } else {
        Neck::Scan
    };
    (cmd, neck)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::analysis::Analysis;
    use crate::sim::config::EnvConfig;
    use crate::sim::memory::AgentMemory;
    use crate::sim::world::{Player, World};
    use glam::DVec2;

    /// MOVE of agent 0 standing `gap` metres behind a resting ball, facing it.
    fn move_with_ball_at(gap: f64) -> Command {
        let mut w = World::new(3);
        w.ball.pos = DVec2::new(20.0, 0.0);
        w.offense[0] = Player::new(DVec2::new(20.0 - gap, 0.0), 0.0);
        w.offense[1].pos = DVec2::new(10.0, 15.0);
        w.offense[2].pos = DVec2::new(10.0, -15.0);
        w.offside_line = 20.0;
        let (analysis, config) = (Analysis::new(&w), EnvConfig::default());
        let s = Situation {
            world: &w,
            analysis: &analysis,
            config: &config,
            agent: 0,
            memory: &AgentMemory::default(),
        };
        command(&s).0
    }

    #[test]
    fn a_ball_just_outside_the_agents_kickable_test_is_chased() {
        // At 1.05 m the server would accept a kick but the agent's own test
        // (1.03 m) says no: it must step in, not stand there for good.
        let cmd = move_with_ball_at(1.05);
        assert!(matches!(cmd, Command::Dash { .. }), "{cmd:?}");
        assert!(matches!(move_with_ball_at(1.0), Command::Turn { .. }));
    }
}
