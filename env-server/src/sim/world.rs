//! The world state: ball, offense players and goalkeeper (plain data, no behaviour).

use crate::sim::kinematics::decay_sum;
use crate::sim::params::*;
use glam::DVec2;

/// The ball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Centre position.
    pub pos: DVec2,
    /// Velocity as observed (already decayed).
    pub vel: DVec2,
}

/// One player's body and stamina.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Player {
    /// Centre position.
    pub pos: DVec2,
    /// Velocity as observed (already decayed).
    pub vel: DVec2,
    /// Body direction (radians, global).
    pub body: f64,
    /// Stamina, `0..=8000`.
    pub stamina: f64,
    /// Dash effort, `0.6..=1`.
    pub effort: f64,
    /// Stamina recovery, `0.5..=1`.
    pub recovery: f64,
    /// agent2d's positioning "recover mode" flag (spec 6.1.4).
    pub recover_mode: bool,
    /// Cycles left during which the server ignores this player's commands
    /// after a tackle (rcssserver `Player::tackle`, spec 3.5).
    pub tackle_freeze: u32,
}

impl Player {
    /// A rested player at `pos` facing `body`.
    pub(crate) fn new(pos: DVec2, body: f64) -> Self {
        Player {
            pos,
            vel: DVec2::ZERO,
            body,
            stamina: STAMINA_MAX,
            effort: 1.0,
            recovery: 1.0,
            recover_mode: false,
            tackle_freeze: 0,
        }
    }

    /// Places the player at `pos` at rest with full stamina, keeping its body angle.
    pub(crate) fn place(&mut self, pos: DVec2) {
        *self = Player::new(pos, self.body);
    }

    /// Where the player drifts to after `n` cycles without commands.
    pub(crate) fn drift(&self, n: u32) -> DVec2 {
        self.pos + self.vel * decay_sum(PLAYER_DECAY, n)
    }

    /// Where the player comes to rest without commands.
    pub(crate) fn final_drift(&self) -> DVec2 {
        self.pos + self.vel / (1.0 - PLAYER_DECAY)
    }
}

/// Everything that moves on the field, and the state of play around it.
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    /// The ball.
    pub ball: Ball,
    /// The offense players, indexed by agent.
    pub offense: Vec<Player>,
    /// The goalkeeper.
    pub keeper: Player,
    /// Cycles left before the keeper may catch again.
    pub catch_ban: u32,
    /// Whether every player's world model is in librcsc's `GoalieCatch_`
    /// mode: set by a catch that did not end the episode, until the episode
    /// ends (spec 4.5).
    pub catch_mode: bool,
    /// agent2d's offside line as the attackers see it (spec 6.1.1).
    pub offside_line: f64,
    /// The cycle within rcssserver's 3-cycle period of visual ticks.
    pub view_phase: u8,
}

impl World {
    /// A world with `offense` players at the origin facing the goal and the keeper on its line.
    pub(crate) fn new(offense: usize) -> Self {
        World {
            ball: Ball {
                pos: DVec2::ZERO,
                vel: DVec2::ZERO,
            },
            offense: vec![Player::new(DVec2::ZERO, 0.0); offense],
            keeper: Player::new(GOAL_CENTER, std::f64::consts::PI),
            catch_ban: 0,
            catch_mode: false,
            offside_line: 0.0,
            view_phase: 0,
        }
    }

    /// Every player: the offense in order, then the keeper.
    pub fn players(&self) -> impl Iterator<Item = &Player> {
        self.offense.iter().chain([&self.keeper])
    }

    /// Whether offense agent `i` can kick by its own (1.03 m) test.
    pub(crate) fn agent_kickable(&self, i: usize) -> bool {
        self.offense[i].pos.distance(self.ball.pos) <= AGENT_KICKABLE_AREA
    }

    /// Whether some offense player other than `except` has the ball in its server kickable area.
    pub(crate) fn teammate_kickable(&self, except: usize) -> bool {
        self.offense
            .iter()
            .enumerate()
            .any(|(j, p)| j != except && p.pos.distance(self.ball.pos) <= KICKABLE_AREA)
    }

    /// Whether the keeper has the ball in its kickable area.
    pub(crate) fn keeper_kickable(&self) -> bool {
        self.keeper.pos.distance(self.ball.pos) <= KICKABLE_AREA
    }

    /// Whether attacker `i` takes the keeper to be on the ball (librcsc's
    /// `existKickableOpponent`): a keeper not frozen by a tackle within its
    /// kickable area plus 2 % of the ball's and of the keeper's distances
    /// from the attacker (each at most 0.25 m), librcsc's allowance for
    /// errors of sight.
    pub(crate) fn keeper_kickable_seen_by(&self, i: usize) -> bool {
        let (me, k, ball) = (self.offense[i].pos, &self.keeper, self.ball.pos);
        let error = |d: f64| (0.02 * d).min(0.25);
        k.tackle_freeze == 0
            && k.pos.distance(ball)
                < KICKABLE_AREA + error(me.distance(ball)) + error(me.distance(k.pos))
    }

    /// Whether the keeper takes an attacker to be on the ball (librcsc's
    /// `existKickableOpponent`, which looks only at the opponent nearest the
    /// ball that is not frozen by a tackle): that attacker within its
    /// kickable area plus 2 % of the ball's and of its own distance from
    /// the keeper (each at most 0.25 m).
    pub(crate) fn attacker_kickable_seen_by_keeper(&self) -> bool {
        let (k, ball) = (self.keeper.pos, self.ball.pos);
        let error = |d: f64| (0.02 * d).min(0.25);
        self.offense
            .iter()
            .filter(|p| p.tackle_freeze == 0)
            .min_by(|a, b| {
                a.pos
                    .distance_squared(ball)
                    .total_cmp(&b.pos.distance_squared(ball))
            })
            .is_some_and(|p| {
                p.pos.distance(ball)
                    < KICKABLE_AREA + error(k.distance(ball)) + error(k.distance(p.pos))
            })
    }

    /// This world with the ball held still: what librcsc's world model
    /// holds while its owner takes an opponent to be on the ball
    /// (`BallObject::setOpponentControlEffect`).
    pub(crate) fn with_ball_still(&self) -> World {
        let mut still = self.clone();
        still.ball.vel = DVec2::ZERO;
        still
    }

    /// Whether any offense player has the ball in its server kickable area.
    pub(crate) fn any_attacker_kickable(&self) -> bool {
        self.offense
            .iter()
            .any(|p| p.pos.distance(self.ball.pos) <= KICKABLE_AREA)
    }

    /// Ball position after `n` cycles without kicks.
    pub(crate) fn ball_inertia(&self, n: u32) -> DVec2 {
        self.ball.pos + self.ball.vel * decay_sum(BALL_DECAY, n)
    }

    /// Where the ball comes to rest without kicks.
    pub(crate) fn ball_final(&self) -> DVec2 {
        self.ball.pos + self.ball.vel / (1.0 - BALL_DECAY)
    }
}
