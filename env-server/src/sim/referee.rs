//! HFO's referee (spec 4.3): goal, out of bounds, captured, out of time.

use crate::sim::params::*;
use crate::sim::world::World;
use glam::DVec2;
use serde::Serialize;

/// How a cycle left the episode: HFO's statuses (without its
/// `SERVER_DOWN`), captured meaning `CAPTURED_BY_DEFENSE`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The episode goes on.
    InGame,
    /// The ball crossed the goal line through the goal mouth.
    Goal,
    /// The goalkeeper got within its kickable area of the ball.
    Captured,
    /// The ball left the HFO area (one cycle late, as HFO does).
    OutOfBounds,
    /// The frame limit or the untouched-ball limit was reached.
    OutOfTime,
}

impl Outcome {
    /// Whether the episode is over.
    pub fn is_terminal(self) -> bool {
        self != Outcome::InGame
    }

    /// The paper's team reward: +1 goal, -1 captured or out of bounds, else 0.
    pub fn reward(self) -> f64 {
        match self {
            Outcome::Goal => 1.0,
            Outcome::Captured | Outcome::OutOfBounds => -1.0,
            Outcome::InGame | Outcome::OutOfTime => 0.0,
        }
    }

    /// How the episode ended, as the messages say it; `None` while it goes
    /// on.
    pub fn ended(self) -> Option<proto::EpisodeOutcome> {
        use proto::EpisodeOutcome as Ended;
        match self {
            Outcome::InGame => None,
            Outcome::Goal => Some(Ended::Goal),
            Outcome::Captured => Some(Ended::Captured),
            Outcome::OutOfBounds => Some(Ended::OutOfBounds),
            Outcome::OutOfTime => Some(Ended::OutOfTime),
        }
    }
}

/// The referee's memory within an episode.
#[derive(Clone, Debug)]
pub(crate) struct Referee {
    /// Cycles since the field was reset (k of spec 4.4).
    pub(crate) cycle: u32,
    prev_ball: DVec2,
    untouched: u32,
    max_cycles: u32,
    untouched_limit: u32,
}

/// The goal line as the referee tests it (52.5 + ball radius).
const GOAL_LINE_X: f64 = PITCH_HALF_LENGTH + BALL_SIZE;
/// Half width of the goal mouth as the referee tests it (7.01 + post radius).
const GOAL_MOUTH_HALF: f64 = GOAL_HALF_WIDTH + GOAL_POST_RADIUS;

impl Referee {
    /// A referee for trials of `max_cycles` cycles and the untouched-ball limit.
    pub(crate) fn new(max_cycles: u32, untouched_limit: u32) -> Self {
        Referee {
            cycle: 0,
            prev_ball: DVec2::ZERO,
            untouched: 0,
            max_cycles,
            untouched_limit,
        }
    }

    /// Starts a new trial with the ball at `ball`.
    pub(crate) fn reset(&mut self, ball: DVec2) {
        self.cycle = 0;
        self.prev_ball = ball;
        self.untouched = 0;
    }

    /// Advances time by one cycle and judges the new state (spec 4.3 order).
    pub(crate) fn judge(&mut self, world: &World) -> Outcome {
        self.cycle += 1;
        let prev = self.prev_ball;
        let ball = world.ball.pos;
        self.prev_ball = ball;
        if crossed_goal_line(prev, ball) {
            return Outcome::Goal;
        }
        if !in_hfo_area(prev) {
            return Outcome::OutOfBounds;
        }
        if self.untouched > self.untouched_limit || self.cycle > self.max_cycles {
            return Outcome::OutOfTime;
        }
        self.untouched += 1;
        if world
            .offense
            .iter()
            .any(|p| p.pos.distance(ball) < KICKABLE_AREA)
        {
            self.untouched = 0;
        }
        if world.keeper.pos.distance(ball) < KICKABLE_AREA {
            return Outcome::Captured;
        }
        Outcome::InGame
    }
}

/// rcssserver's `crossGoalLine` for the attacked goal.
fn crossed_goal_line(prev: DVec2, ball: DVec2) -> bool {
    if prev.x == ball.x || ball.x <= GOAL_LINE_X || prev.x > GOAL_LINE_X {
        return false;
    }
    if prev.x > PITCH_HALF_LENGTH && prev.y.abs() > GOAL_MOUTH_HALF {
        return false;
    }
    let t = (GOAL_LINE_X - prev.x) / (ball.x - prev.x);
    let y = prev.y + t * (ball.y - prev.y);
    y.abs() <= GOAL_MOUTH_HALF
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world_with_ball(x: f64, y: f64) -> World {
        let mut w = World::new(1);
        w.offense[0].pos = DVec2::new(20.0, 20.0);
        w.keeper.pos = DVec2::new(30.0, -30.0);
        w.ball.pos = DVec2::new(x, y);
        w
    }

    #[test]
    fn goal_only_through_the_mouth() {
        assert!(crossed_goal_line(
            DVec2::new(52.0, 0.0),
            DVec2::new(53.0, 1.0)
        ));
        assert!(!crossed_goal_line(
            DVec2::new(52.0, 8.0),
            DVec2::new(53.0, 8.0)
        ));
        assert!(!crossed_goal_line(
            DVec2::new(52.0, 0.0),
            DVec2::new(52.5, 0.0)
        ));
    }

    #[test]
    fn out_of_bounds_is_one_cycle_late() {
        let mut r = Referee::new(200, 100);
        r.reset(DVec2::new(10.0, 33.5));
        assert_eq!(r.judge(&world_with_ball(10.0, 34.5)), Outcome::InGame);
        assert_eq!(r.judge(&world_with_ball(10.0, 35.0)), Outcome::OutOfBounds);
    }

    #[test]
    fn untouched_ball_times_out_at_cycle_102() {
        let mut r = Referee::new(200, 100);
        let w = world_with_ball(10.0, 0.0);
        r.reset(w.ball.pos);
        for k in 1..102 {
            assert_eq!(r.judge(&w), Outcome::InGame, "cycle {k}");
        }
        assert_eq!(r.judge(&w), Outcome::OutOfTime);
        assert_eq!(r.cycle, 102);
    }

    #[test]
    fn only_the_game_in_play_is_not_terminal() {
        use Outcome::*;
        let all = [InGame, Goal, Captured, OutOfBounds, OutOfTime];
        assert_eq!(
            all.map(Outcome::is_terminal),
            [false, true, true, true, true]
        );
    }

    #[test]
    fn keeper_near_ball_captures() {
        let mut r = Referee::new(200, 100);
        let mut w = world_with_ball(45.0, 0.0);
        w.keeper.pos = DVec2::new(46.0, 0.0);
        r.reset(w.ball.pos);
        assert_eq!(r.judge(&w), Outcome::Captured);
    }
}
