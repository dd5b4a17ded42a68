//! The behaviours that turn high-level actions into one body command per
//! cycle (spec sections 6 and 7). Every behaviour re-plans from scratch on
//! the current state; what is carried between cycles is each agent's last
//! shot course (spec 6.2.2) and view (spec 6.6), its memory.

mod body;
mod dribble;
mod hold;
mod intercept;
pub(crate) mod keeper;
mod kick;
mod kick_table;
mod movement;
mod pass;
mod shoot;
mod situation;
mod smart_kick;
pub(crate) mod tackle;

use crate::sim::memory::ShotCourse;
use crate::sim::physics::Command;
use crate::sim::view::Neck;
use proto::Action;

pub(crate) use situation::Situation;

/// What a behaviour decides for the acting agent this cycle.
pub(crate) struct BodyDecision {
    /// The body command.
    pub(crate) command: Command,
    /// The first course of a non-empty shot search it ran (spec 6.2.2).
    pub(crate) shot: Option<ShotCourse>,
    /// The neck action it leaves (spec 6.6).
    pub(crate) neck: Neck,
}

/// What `action` makes the acting agent do this cycle. Kick actions issue
/// nothing when the agent cannot kick (spec 6.0); they and SHOOT, PASS and
/// DRIBBLE keep HFO's default neck action, the field scan.
pub(crate) fn offense_command(s: &Situation, action: Action) -> BodyDecision {
    let decide = |command, shot| BodyDecision {
        command,
        shot,
        neck: Neck::Scan,
    };
    if action != Action::Move && !s.world.agent_kickable(s.agent) {
        return decide(Command::None, None);
    }
    match action {
        Action::Move => {
            let (command, neck) = movement::command(s);
            BodyDecision {
                command,
                shot: move_shot_check(s),
                neck,
            }
        }
        Action::Shoot => {
            let (command, shot) = shoot::command(s);
            decide(command, shot)
        }
        Action::Dribble if s.world.catch_mode => {
            let (command, shot) = shoot::strict_check(s);
            decide(command, shot)
        }
        // `doPreprocess`'s Bhv_StrictCheckShoot; its kick is overridden (spec 6.0).
        Action::Dribble => decide(dribble::command(s), shoot::check(s)),
        Action::PassNear | Action::PassFar => {
            let receiver = s
                .config
                .pass_to_named_receiver
                .then(|| s.teammate_by_distance(action == Action::PassFar))
                .flatten();
            decide(pass::command(s, receiver), None)
        }
    }
}

/// MOVE's shot search: Bhv_BasicMove intercepts with Neck_OffensiveInterceptNeck,
/// which looks for a shot when the agent reaches the ball within a cycle and
/// neither a teammate nor the keeper can kick it.
fn move_shot_check(s: &Situation) -> Option<ShotCourse> {
    let keeper_kickable = s.world.keeper_kickable_seen_by(s.agent);
    (s.analysis.own_reach[s.agent] <= 1 && !s.world.teammate_kickable(s.agent) && !keeper_kickable)
        .then(|| shoot::check(s))
        .flatten()
}
