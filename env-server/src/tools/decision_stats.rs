//! Per-decision statistics of a rollout, in the schema the real-HFO oracle
//! writes too (`env-server/oracle/`): shot success by release distance,
//! what follows a pass and a dribble, possessions per episode.
//!
//! A *kick* is a cycle in which an offense player with the ball in its
//! server kickable area at the start of the cycle kicked. A kick
//! *releases* the ball when, after the cycle, the ball is outside that area.
//! A shot is a kick under SHOOT; its distance is the ball's distance from
//! the goal centre at the kick.

use glam::DVec2;
use proto::Action;
use serde::Serialize;

use crate::sim::config::MAX_OFFENSE;
use crate::sim::env::Env;
use crate::sim::params::{GOAL_CENTER, KICKABLE_AREA};
use crate::sim::physics::Command;
use crate::sim::referee::Outcome;
use crate::tools::tally::{Moments, OutcomeCounts};

/// Lower edges of the shot-distance bins (m); the last bin is open.
const SHOT_BINS: [f64; 6] = [0.0, 10.0, 15.0, 20.0, 25.0, 30.0];

/// Released shots from one distance bin and the goals that followed them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ShotBin {
    /// Lower edge (m).
    pub from_m: f64,
    /// Upper edge (m); `None` for the last, open bin.
    pub to_m: Option<f64>,
    /// Shots released from this distance.
    pub released: u64,
    /// Of those, shots after which the episode ended in a goal with no later
    /// offense kick.
    pub goals: u64,
}

/// What came first after a kick: another kick, or the end of the episode.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Aftermath {
    /// A teammate kicked next.
    pub teammate: u64,
    /// The same player kicked next.
    pub same: u64,
    /// The episode ended first, by outcome.
    #[serde(flatten)]
    pub ended: OutcomeCounts,
}

/// The per-decision statistics of a rollout.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DecisionStats {
    /// Released shots by distance from the goal centre.
    pub shots: Vec<ShotBin>,
    /// What followed a pass that released the ball.
    pub after_pass: Aftermath,
    /// What followed every dribble kick.
    pub after_dribble: Aftermath,
    /// Mean runs of consecutive kicks by the same player per episode.
    pub possessions_per_episode: f64,
}

/// A kick whose aftermath is not known yet.
#[derive(Clone, Copy, Debug)]
struct Open {
    kicker: usize,
    pass: bool,
}

/// Accumulates [`DecisionStats`] over episodes, fed after the reset and
/// after every step.
#[derive(Clone, Debug)]
pub(crate) struct DecisionRecorder {
    shots: Vec<ShotBin>,
    after_pass: Aftermath,
    after_dribble: Aftermath,
    possessions: u64,
    episodes: u64,
    /// Possessions of each finished episode.
    per_episode: Moments,
    /// Possessions of the episode in play.
    current: u64,
    /// At the start of the coming cycle: the ball, and who has it in reach.
    ball: DVec2,
    in_reach: [bool; MAX_OFFENSE],
    /// The bin of the last released shot, if no offense kick followed it.
    shot: Option<usize>,
    open: Option<Open>,
    last_kicker: Option<usize>,
}

impl Default for DecisionRecorder {
    fn default() -> Self {
        let shots = SHOT_BINS
            .iter()
            .enumerate()
            .map(|(i, &from_m)| ShotBin {
                from_m,
                to_m: SHOT_BINS.get(i + 1).copied(),
                ..ShotBin::default()
            })
            .collect();
        Self {
            shots,
            after_pass: Aftermath::default(),
            after_dribble: Aftermath::default(),
            possessions: 0,
            episodes: 0,
            per_episode: Moments::default(),
            current: 0,
            ball: DVec2::ZERO,
            in_reach: [false; MAX_OFFENSE],
            shot: None,
            open: None,
            last_kicker: None,
        }
    }
}

impl DecisionRecorder {
    /// Feeds the env after its reset (`actions` empty) or after a step with
    /// `actions`.
    pub(crate) fn observe(&mut self, env: &Env, actions: &[Action]) {
        if actions.is_empty() {
            self.episodes += 1;
            (self.shot, self.open, self.last_kicker) = (None, None, None);
            self.current = 0;
        }
        let world = env.world();
        let commands = env.last_commands();
        for (i, &action) in actions.iter().enumerate() {
            let kicked = matches!(commands[i], Command::Kick { .. }) && self.in_reach[i];
            if kicked {
                let released = world.ball.pos.distance(world.offense[i].pos) > KICKABLE_AREA;
                self.kick(i, action, released);
            }
        }
        let outcome = env.outcome();
        if outcome.is_terminal() {
            self.end(outcome);
        }
        self.ball = world.ball.pos;
        for (reach, p) in self.in_reach.iter_mut().zip(&world.offense) {
            *reach = world.ball.pos.distance(p.pos) <= KICKABLE_AREA;
        }
    }

    fn kick(&mut self, kicker: usize, action: Action, released: bool) {
        if let Some(open) = self.open.take() {
            let after = self.aftermath(open.pass);
            if open.kicker == kicker {
                after.same += 1;
            } else {
                after.teammate += 1;
            }
        }
        self.shot = None;
        if self.last_kicker != Some(kicker) {
            self.possessions += 1;
            self.current += 1;
            self.last_kicker = Some(kicker);
        }
        match action {
            Action::Shoot if released => {
                let distance = self.ball.distance(GOAL_CENTER);
                let bin = SHOT_BINS.iter().rposition(|&edge| distance >= edge);
                let bin = bin.unwrap_or(0);
                self.shots[bin].released += 1;
                self.shot = Some(bin);
            }
            Action::PassNear | Action::PassFar if released => {
                self.open = Some(Open { kicker, pass: true });
            }
            Action::Dribble => {
                self.open = Some(Open {
                    kicker,
                    pass: false,
                })
            }
            _ => {}
        }
    }

    fn aftermath(&mut self, pass: bool) -> &mut Aftermath {
        if pass {
            &mut self.after_pass
        } else {
            &mut self.after_dribble
        }
    }

    fn end(&mut self, outcome: Outcome) {
        self.per_episode.add(self.current as f64);
        if let Some(open) = self.open.take() {
            self.aftermath(open.pass).ended.add(outcome);
        }
        if let (Some(bin), Outcome::Goal) = (self.shot.take(), outcome) {
            self.shots[bin].goals += 1;
        }
    }

    /// The sample standard deviation of the possessions per episode.
    pub(crate) fn possessions_sd(&self) -> f64 {
        self.per_episode.sd()
    }

    /// The statistics so far.
    pub(crate) fn stats(&self) -> DecisionStats {
        DecisionStats {
            shots: self.shots.clone(),
            after_pass: self.after_pass,
            after_dribble: self.after_dribble,
            possessions_per_episode: if self.episodes == 0 {
                0.0
            } else {
                self.possessions as f64 / self.episodes as f64
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::config::EnvConfig;
    use crate::tools::scripted::{ScriptedPolicy, play_episode, policy_rng};

    fn recorded(policy: ScriptedPolicy, episodes: u32) -> (DecisionStats, Vec<Outcome>) {
        let mut env = Env::new(EnvConfig::default(), 3).unwrap();
        let mut rng = policy_rng(3);
        let mut recorder = DecisionRecorder::default();
        let outcomes = (0..episodes)
            .map(|_| play_episode(&mut env, policy, &mut rng, |e, a| recorder.observe(e, a)).0)
            .collect();
        (recorder.stats(), outcomes)
    }

    #[test]
    fn shot_goals_are_at_most_the_goals_and_the_releases() {
        let (stats, outcomes) = recorded(ScriptedPolicy::Shoot, 300);
        let goals = outcomes.iter().filter(|o| **o == Outcome::Goal).count() as u64;
        let released: u64 = stats.shots.iter().map(|b| b.released).sum();
        let scored: u64 = stats.shots.iter().map(|b| b.goals).sum();
        assert!(released > 0);
        assert!(stats.shots.iter().all(|b| b.goals <= b.released));
        // A goal needs a last offense kick; under always-SHOOT it is a shot.
        assert!(scored <= goals, "{scored} > {goals}");
        assert!(scored > 0);
        assert_eq!(stats.shots.len(), 6);
        assert_eq!((stats.shots[5].from_m, stats.shots[5].to_m), (30.0, None));
        assert_eq!(stats.after_pass, Aftermath::default());
    }

    #[test]
    fn every_pass_and_dribble_has_one_aftermath() {
        let (stats, _) = recorded(ScriptedPolicy::Random, 300);
        let total = |a: &Aftermath| {
            let e = &a.ended;
            a.teammate + a.same + e.captured + e.out_of_bounds + e.goal + e.out_of_time
        };
        assert!(total(&stats.after_pass) > 0);
        assert!(total(&stats.after_dribble) > 0);
        assert!(stats.after_dribble.same > 0);
        assert!(stats.possessions_per_episode >= 1.0);
        // Only dribble-only play: no pass ever.
        let (dribbles, _) = recorded(ScriptedPolicy::Dribble, 100);
        assert_eq!(total(&dribbles.after_pass), 0);
        assert_eq!(dribbles.shots.iter().map(|b| b.released).sum::<u64>(), 0);
    }

    #[test]
    fn a_later_kick_takes_the_goal_from_the_shot() {
        let mut r = DecisionRecorder {
            ball: GOAL_CENTER - DVec2::new(12.0, 0.0),
            ..DecisionRecorder::default()
        };
        r.kick(0, Action::Shoot, true);
        assert_eq!(r.shots[1].released, 1);
        r.kick(1, Action::Dribble, false);
        assert_eq!(r.possessions, 2);
        r.end(Outcome::Goal);
        assert_eq!(
            r.shots[1].goals, 0,
            "a later kick makes the shot not the scorer"
        );
        assert_eq!(r.after_dribble.ended.goal, 1);
    }
}
