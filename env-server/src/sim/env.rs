//! The HFO environment: episode start, the per-cycle loop and the agents' view
//! of it (spec 2.1, 4.2, 4.4, Appendix D).

use crate::sim::analysis::{Analysis, update_offside_line};
use crate::sim::behaviour::keeper::{self, KeeperMemory};
use crate::sim::behaviour::{BodyDecision, Situation, offense_command};
use crate::sim::config::{EnvConfig, EnvConfigError, MAX_OFFENSE};
use crate::sim::features;
use crate::sim::geom::uniform;
use crate::sim::memory::AgentMemory;
use crate::sim::params::*;
use crate::sim::physics::{self, BALL_BODY, Command, PLAYER_BODY};
use crate::sim::referee::{Outcome, Referee};
use crate::sim::view::{self, Neck, Outlook};
use crate::sim::world::{Player, World};
use glam::DVec2;
use proto::{Action, State};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f64::consts::PI;

/// The attackers' start offsets around the ball, in units of 10.5 m (spec 4.2).
const START_OFFSETS: [(f64, f64); 10] = [
    (-1.0, -1.0),
    (-1.0, 1.0),
    (1.0, 1.0),
    (1.0, -1.0),
    (0.0, 2.0),
    (0.0, -2.0),
    (-2.0, -2.0),
    (-2.0, 2.0),
    (2.0, 2.0),
    (2.0, -2.0),
];

/// Cycles the attackers stay idle at the start of every episode (spec 4.4).
const IDLE_CYCLES: u32 = 2;

/// The simulator: one world, the agents' memories, the referee and the
/// random stream.
#[derive(Clone, Debug)]
pub struct Env {
    config: EnvConfig,
    world: World,
    /// Every offense agent's memory, which survives episode resets.
    memories: Vec<AgentMemory>,
    referee: Referee,
    keeper_memory: KeeperMemory,
    offsets: [(f64, f64); 10],
    rng: Xoshiro256PlusPlus,
    /// Commands of the last cycle: offense agents, then the keeper.
    commands: [Command; MAX_OFFENSE + 1],
    outcome: Outcome,
}

impl Env {
    /// A simulator with `config`, drawing every random choice from `seed`.
    /// Call [`Env::reset`] to start the first episode.
    pub fn new(config: EnvConfig, seed: u64) -> Result<Self, EnvConfigError> {
        config.validate()?;
        let world = World::new(config.offense);
        let referee = Referee::new(config.frames_per_trial, config.untouched_time);
        Ok(Env {
            world,
            memories: vec![AgentMemory::default(); config.offense],
            referee,
            keeper_memory: KeeperMemory {
                since_catch: u32::MAX,
            },
            offsets: START_OFFSETS,
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
            commands: [Command::None; MAX_OFFENSE + 1],
            outcome: Outcome::InGame,
            config,
        })
    }

    /// The settings.
    pub fn config(&self) -> &EnvConfig {
        &self.config
    }

    /// The current state.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Every offense agent's memory, in agent order.
    pub fn memories(&self) -> &[AgentMemory] {
        &self.memories
    }

    /// Makes the agents remember what those of `other`, a simulator of the
    /// same team, remember.
    pub(crate) fn remember_as(&mut self, other: &Env) {
        self.memories.clone_from(&other.memories);
    }

    /// Number of offense agents.
    pub fn offense(&self) -> usize {
        self.config.offense
    }

    /// Agent decisions taken so far in this episode (the authors' "frames").
    pub fn frame(&self) -> u32 {
        self.referee.cycle.saturating_sub(IDLE_CYCLES)
    }

    /// Outcome of the last step (`InGame` while the episode goes on).
    pub fn outcome(&self) -> Outcome {
        self.outcome
    }

    /// Body commands of the last cycle: offense agents in order, then the keeper.
    pub fn last_commands(&self) -> &[Command] {
        &self.commands[..=self.config.offense]
    }

    /// Starts a new episode (spec 4.2) and runs the two idle cycles; the
    /// first decision follows.
    pub fn reset(&mut self) {
        let rng = &mut self.rng;
        let ball = DVec2::new(
            uniform(rng, 0.0, 0.2 * PITCH_HALF_LENGTH),
            uniform(
                rng,
                -0.4 * 2.0 * PITCH_HALF_WIDTH,
                0.4 * 2.0 * PITCH_HALF_WIDTH,
            ),
        );
        self.offsets.shuffle(rng);
        let unit = 0.1 * 2.0 * PITCH_HALF_LENGTH;
        for (player, (ox, oy)) in self.world.offense.iter_mut().zip(self.offsets) {
            let x = ball.x + unit * (uniform(rng, 0.0, 1.0) + ox);
            let y = ball.y + unit * (uniform(rng, 0.0, 1.0) + oy);
            player.place(DVec2::new(
                x.clamp(-0.1, PITCH_HALF_LENGTH),
                y.clamp(-0.4 * 2.0 * PITCH_HALF_WIDTH, 0.4 * 2.0 * PITCH_HALF_WIDTH),
            ));
        }
        self.world.keeper.place(GOAL_CENTER);
        self.world.ball.pos = ball;
        self.world.ball.vel = DVec2::ZERO;
        self.world.catch_ban = 0;
        self.world.catch_mode = false;
        self.world.offside_line = 0.0;
        self.keeper_memory = KeeperMemory {
            since_catch: u32::MAX,
        };
        self.referee.reset(ball);
        self.outcome = Outcome::InGame;
        for _ in 0..IDLE_CYCLES {
            self.cycle(None);
        }
    }

    /// Runs one cycle with every agent's chosen action (an agent that cannot
    /// kick should choose `Move`) and returns the outcome.
    ///
    /// # Panics
    /// If `actions` does not hold one action per offense agent.
    pub fn step(&mut self, actions: &[Action]) -> Outcome {
        assert_eq!(
            actions.len(),
            self.config.offense,
            "one action per offense agent"
        );
        self.cycle(Some(actions));
        self.outcome
    }

    /// Whether agent `agent` can kick (its own 1.03 m test).
    pub fn can_kick(&self, agent: usize) -> bool {
        self.world.agent_kickable(agent)
    }

    /// The paper's 6-feature state of agent `agent`.
    pub fn state(&self, agent: usize) -> State {
        features::paper_state(&self.world, &features::goal_openings(&self.world), agent)
    }

    /// The paper's 6-feature states of every agent, in order (each player's
    /// goal opening computed once).
    pub fn states(&self) -> impl Iterator<Item = State> + '_ {
        let openings = features::goal_openings(&self.world);
        (0..self.config.offense)
            .map(move |agent| features::paper_state(&self.world, &openings, agent))
    }

    /// HFO's high-level feature vector of agent `agent` (spec 5.3), in HFO's
    /// order and normalisation;
    /// [`feature_count`](crate::features::feature_count) long.
    pub fn features(&self, agent: usize) -> Vec<f64> {
        features::high_level(&self.world, agent)
    }

    /// Today's HFO high-level feature vector of agent `agent` (spec 5.5), in
    /// HFO's order and normalisation;
    /// [`current_feature_count`](crate::features::current_feature_count) long.
    /// Its last-action feature is +1 when the agent's last step issued a
    /// body command (HFO's actions report success when they do), -1 after a
    /// reset or a step that issued none.
    pub fn current_features(&self, agent: usize) -> Vec<f64> {
        let acted = self.commands[agent] != Command::None;
        features::current_high_level(&self.world, agent, acted)
    }

    /// One server cycle (spec 2.1); `None` means the attackers are idle.
    fn cycle(&mut self, actions: Option<&[Action]>) {
        update_offside_line(&mut self.world);
        for p in &mut self.world.offense {
            update_recover_mode(p);
        }
        let analysis = Analysis::new(&self.world);
        self.see_before_decisions();
        let necks = self.decide_offense(&analysis, actions);
        self.look_after_decisions(&analysis, actions, &necks);
        self.world.view_phase = (self.world.view_phase + 1) % 3;
        let n = self.config.offense;
        self.commands[n] = if self.world.keeper.tackle_freeze > 0 {
            Command::None
        } else {
            keeper::command(&self.world, &analysis, &self.keeper_memory)
        };
        let accels = self.apply_commands();
        self.move_objects(&accels);
        physics::resolve_collisions(&mut self.world, &mut self.rng);
        self.outcome = self.referee.judge(&self.world);
        for p in self
            .world
            .offense
            .iter_mut()
            .chain([&mut self.world.keeper])
        {
            physics::update_stamina(p);
            p.tackle_freeze = p.tackle_freeze.saturating_sub(1);
        }
        self.world.catch_ban = self.world.catch_ban.saturating_sub(1);
    }

    /// Every attacker's view up to its decision: counts age, and the sees
    /// due before the think message arrive (spec 6.6).
    fn see_before_decisions(&mut self) {
        let phase = self.world.view_phase;
        for (p, memory) in self.world.offense.iter().zip(&mut self.memories) {
            let sight = &mut memory.sight;
            sight.before_decision(phase, p.body.to_degrees() + sight.neck, view::moved(p.vel));
        }
    }

    /// Every attacker's body command for `actions` (none while idle or
    /// frozen by a tackle), and the neck action each leaves; the courses
    /// of this cycle's shot searches go to the agents' memories.
    fn decide_offense(
        &mut self,
        analysis: &Analysis,
        actions: Option<&[Action]>,
    ) -> [Neck; MAX_OFFENSE] {
        let mut searched = [None; MAX_OFFENSE];
        let mut necks = [Neck::Scan; MAX_OFFENSE];
        // The world with the ball held still, made for the first agent that sees it so.
        let mut still: Option<(World, Analysis)> = None;
        for agent in 0..self.config.offense {
            let idle = BodyDecision {
                command: Command::None,
                shot: None,
                neck: Neck::Scan,
            };
            let decision = match actions {
                _ if self.world.offense[agent].tackle_freeze > 0 => idle,
                None => idle,
                Some(a) => {
                    let (world, analysis) = if sees_ball_held(&self.world, agent) {
                        let (w, a) = still.get_or_insert_with(|| ball_held_still(&self.world));
                        (&*w, &*a)
                    } else {
                        (&self.world, analysis)
                    };
                    offense_command(
                        &Situation {
                            world,
                            analysis,
                            config: &self.config,
                            agent,
                            memory: &self.memories[agent],
                        },
                        a[agent],
                    )
                }
            };
            (self.commands[agent], searched[agent], necks[agent]) =
                (decision.command, decision.shot, decision.neck);
        }
        for (memory, course) in self.memories.iter_mut().zip(searched) {
            if course.is_some() {
                memory.last_shot = course;
            }
        }
        necks
    }

    /// Every attacker's view and neck actions after its body command, with
    /// the sees due after the think message (spec 6.6).
    fn look_after_decisions(
        &mut self,
        analysis: &Analysis,
        actions: Option<&[Action]>,
        necks: &[Neck; MAX_OFFENSE],
    ) {
        let phase = self.world.view_phase;
        for agent in 0..self.config.offense {
            let outlook = outlook(&self.world, analysis, agent, self.commands[agent]);
            let dribbled = actions.is_some_and(|a| a[agent] == Action::Dribble)
                && self.world.agent_kickable(agent);
            let p = &self.world.offense[agent];
            let (body, moved) = (p.body.to_degrees(), view::moved(p.vel));
            let sight = &mut self.memories[agent].sight;
            sight.chain_ready |= dribbled;
            sight.act(phase, necks[agent], &outlook, body, moved);
        }
    }

    /// Executes the commands (spec 2.1 step 2): kicks, tackles and the catch
    /// act on the current positions first, then dashes and turns. Returns the
    /// pending accelerations: the ball's, then every player's (offense, keeper).
    fn apply_commands(&mut self) -> [DVec2; MAX_OFFENSE + 2] {
        let n = self.config.offense;
        let mut accels = [DVec2::ZERO; MAX_OFFENSE + 2];
        for (i, command) in self.commands[..=n].iter().enumerate() {
            match *command {
                Command::Kick { power, dir } => {
                    let p = self.world.players().nth(i).expect("player index");
                    physics::kick(
                        p,
                        &self.world.ball,
                        &mut accels[0],
                        power,
                        dir,
                        &mut self.rng,
                    );
                }
                Command::Tackle { dir, foul } => {
                    // The server's foul needs an opponent that can kick the ball.
                    let opponent_kickable = if i < n {
                        self.world.keeper_kickable()
                    } else {
                        self.world.any_attacker_kickable()
                    };
                    let ball = self.world.ball;
                    let p = if i < n {
                        &mut self.world.offense[i]
                    } else {
                        &mut self.world.keeper
                    };
                    physics::tackle(
                        p,
                        &ball,
                        &mut accels[0],
                        (dir, foul),
                        opponent_kickable,
                        &mut self.rng,
                    );
                }
                _ => {}
            }
        }
        self.keeper_memory.since_catch = self.keeper_memory.since_catch.saturating_add(1);
        if self.commands[n] == Command::Catch {
            self.keeper_memory.since_catch = 0;
            // HFO's server announces the catch but plays on (spec 4.5).
            self.world.catch_mode |= physics::catch(&mut self.world);
        }
        let players = self
            .world
            .offense
            .iter_mut()
            .chain([&mut self.world.keeper]);
        for ((p, command), accel) in players.zip(&self.commands).zip(&mut accels[1..]) {
            match *command {
                Command::Dash { power, dir } => physics::dash(p, accel, power, dir),
                Command::Turn { moment } => physics::turn(p, moment, &mut self.rng),
                _ => {}
            }
        }
        accels
    }

    /// Moves the ball and every player (spec 2.1 step 3), in a fixed order.
    fn move_objects(&mut self, accels: &[DVec2; MAX_OFFENSE + 2]) {
        let rng = &mut self.rng;
        let ball = &mut self.world.ball;
        physics::move_object(&mut ball.pos, &mut ball.vel, accels[0], BALL_BODY, rng);
        let players = self
            .world
            .offense
            .iter_mut()
            .chain([&mut self.world.keeper]);
        for (p, accel) in players.zip(&accels[1..]) {
            physics::move_object(&mut p.pos, &mut p.vel, *accel, PLAYER_BODY, rng);
        }
    }
}

/// agent2d's recover mode of an attacker (spec 6.1.4): entered when its
/// stamina runs low, left once it has recovered well above that.
fn update_recover_mode(p: &mut Player) {
    if p.stamina < RECOVER_MODE_ENTER {
        p.recover_mode = true;
    } else if p.stamina > RECOVER_MODE_LEAVE {
        p.recover_mode = false;
    }
}

/// Whether agent `agent` takes the keeper to be on a moving ball that it
/// cannot kick itself: librcsc then holds the ball still in its world model
/// (`setOpponentControlEffect`), [`ball_held_still`].
fn sees_ball_held(world: &World, agent: usize) -> bool {
    world.keeper_kickable_seen_by(agent)
        && !world.agent_kickable(agent)
        && world.ball.vel != DVec2::ZERO
}

/// The world of an agent that [`sees_ball_held`], and its analysis.
fn ball_held_still(world: &World) -> (World, Analysis) {
    let believed = world.with_ball_still();
    let analysis = Analysis::new(&believed);
    (believed, analysis)
}

/// What agent `agent`'s view and neck actions see after its body command
/// `command` (librcsc's queued next position and body, without noise).
fn outlook(world: &World, analysis: &Analysis, agent: usize, command: Command) -> Outlook {
    let p = &world.offense[agent];
    let ball = world.ball.pos;
    let (mut next_pos, mut next_body) = (p.pos + p.vel, p.body);
    match command {
        Command::Dash { power, dir } => {
            let (mut player, mut accel) = (*p, DVec2::ZERO);
            physics::dash(&mut player, &mut accel, power, dir);
            next_pos += accel;
        }
        Command::Turn { moment } => {
            next_body += moment.clamp(-PI, PI) / (1.0 + INERTIA_MOMENT * p.vel.length());
        }
        _ => {}
    }
    let first = analysis.own_reach[agent]
        .min(analysis.mate_reach(agent))
        .min(analysis.keeper_reach)
        .min(100);
    let mate_ball_dist = (world.offense.iter().enumerate())
        .filter(|&(j, _)| j != agent)
        .map(|(_, m)| m.pos.distance(ball))
        .fold(1000.0, f64::min);
    Outlook {
        next_pos,
        next_body: next_body.to_degrees(),
        next_ball: ball + world.ball.vel,
        reach_point: world.ball_inertia(first as u32),
        mate_ball_dist,
        keeper_ball_dist: world.keeper.pos.distance(ball),
        ball_dist: p.pos.distance(ball),
        drift_pos: p.pos + p.vel,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_attacker_that_takes_the_keeper_to_be_on_the_ball_holds_it_still() {
        let mut w = World::new(2);
        w.keeper = Player::new(DVec2::new(45.0, 0.0), PI);
        w.ball.pos = DVec2::new(44.0, 0.0);
        w.ball.vel = DVec2::new(-0.5, 0.2);
        w.offense[0] = Player::new(DVec2::new(40.0, 0.0), 0.0);
        w.offense[1] = Player::new(DVec2::new(43.5, 0.5), 0.0);
        assert!(sees_ball_held(&w, 0), "the keeper is on the ball");
        let (believed, analysis) = ball_held_still(&w);
        assert_eq!(believed.ball.vel, DVec2::ZERO);
        assert_eq!(analysis.path_len, 6, "a resting ball's path");
        // An agent that can kick the ball itself sees it move.
        assert!(!sees_ball_held(&w, 1));
        w.keeper.pos = DVec2::new(46.0, 0.0);
        assert!(!sees_ball_held(&w, 0));
    }

    /// After its tackle's own cycle the server ignores a player for 9 more
    /// cycles (`tackle_cycles = 10`); the keeper, who always commands
    /// something, is silent exactly that long.
    #[test]
    fn tackle_freeze_silences_the_keeper_for_nine_cycles() {
        let mut env = Env::new(EnvConfig::default(), 1).expect("valid config");
        env.reset();
        let n = env.offense();
        let moves = vec![Action::Move; n];
        // The state right after a tackle's cycle.
        env.world.keeper.tackle_freeze = TACKLE_CYCLES - 1;
        for _ in 0..9 {
            assert_eq!(env.step(&moves), Outcome::InGame);
            assert_eq!(env.last_commands()[n], Command::None);
        }
        env.step(&moves);
        assert_ne!(env.last_commands()[n], Command::None);
    }

    #[test]
    fn the_last_action_feature_tells_whether_a_body_command_was_issued() {
        let mut env = Env::new(EnvConfig::default(), 1).expect("valid config");
        env.reset();
        let last = features::current_feature_count(env.offense()) - 2;
        // HFO's NOOPs between episodes fail.
        assert!((0..3).all(|a| env.current_features(a)[last] == -1.0));
        // MOVE runs to the formation or the ball; SHOOT without the ball does nothing.
        assert!((0..3).all(|a| !env.can_kick(a)));
        env.step(&[Action::Move, Action::Shoot, Action::Move]);
        assert_eq!(env.current_features(0)[last], 1.0);
        assert_eq!(env.current_features(1)[last], -1.0);
    }

    #[test]
    fn shot_searches_refresh_the_stale_course_across_episodes() {
        let config = EnvConfig {
            offense: 1,
            ..EnvConfig::default()
        };
        let mut env = Env::new(config, 1).expect("valid config");
        env.reset();
        assert_eq!(env.memories[0].last_shot, None);
        env.world.offense[0] = Player::new(DVec2::new(40.0, 0.0), 0.0);
        env.world.ball.pos = DVec2::new(40.6, 0.0);
        env.world.ball.vel = DVec2::ZERO;
        env.step(&[Action::Dribble]);
        let remembered = env.memories[0].last_shot;
        assert!(remembered.is_some(), "DRIBBLE's check within 30 m");
        env.reset();
        assert_eq!(env.memories[0].last_shot, remembered);
    }

    #[test]
    fn a_catch_whose_ball_escapes_plays_on_in_the_goalie_catch_mode() {
        let mut env = Env::new(EnvConfig::default(), 1).expect("valid config");
        env.reset();
        for (i, p) in env.world.offense.iter_mut().enumerate() {
            p.place(DVec2::new(5.0, -20.0 + 20.0 * i as f64));
        }
        env.world.keeper = Player::new(DVec2::new(48.0, 0.0), PI);
        env.world.ball.pos = DVec2::new(47.2, 0.3);
        env.world.ball.vel = DVec2::new(-2.5, 0.0);
        let moves = vec![Action::Move; env.offense()];
        assert_eq!(env.step(&moves), Outcome::InGame);
        assert_eq!(env.last_commands()[env.offense()], Command::Catch);
        assert!(env.world.catch_mode);
        for _ in 0..10 {
            if env.step(&moves).is_terminal() {
                break;
            }
            assert_ne!(env.last_commands()[env.offense()], Command::Catch);
        }
        env.reset();
        assert!(!env.world.catch_mode);
    }
}
