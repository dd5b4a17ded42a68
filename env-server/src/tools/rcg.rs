//! A recorded episode as an rcssserver game log (`.rcg`, text format version
//! 5), for the monitors HFO users know (rcssmonitor, soccerwindow2), and a
//! reader of the frames such a log shows.
//!
//! The log holds the header `ULG5`, the server parameters the monitors draw
//! the field with, the play mode, the team names, then one `show` line per
//! recorded state: the ball and every player (the offense as the left team
//! with HFO's uniform numbers, the keeper as the right team's goalie with
//! number one) at their positions, as librcsc's version 5 reader parses
//! them (absent players are left out, which it accepts). The trace holds
//! positions only: velocities, body and neck directions are written as 0.

use std::fmt::Write as _;

use glam::DVec2;

use crate::sim::formation::offense_unums;
use crate::sim::params::{BALL_SIZE, GOAL_HALF_WIDTH, PLAYER_SIZE};
use crate::tools::render::Trace;

/// A player's state flags in a show line: standing, and the goalie's flag.
const STAND: u32 = 0x1;
const GOALIE: u32 = 0x8;

/// The team names written in the log.
pub const TEAMS: [&str; 2] = ["HFO_Offense", "HFO_Defense"];

/// One `show` line read back: the cycle, the ball and every player.
#[derive(Clone, Debug, PartialEq)]
pub struct ShowFrame {
    /// The cycle (the recorded state's index).
    pub time: u32,
    /// The ball's position.
    pub ball: DVec2,
    /// Every player: its side (`'l'` or `'r'`), uniform number and position.
    pub players: Vec<(char, u8, DVec2)>,
}

/// Why a log could not be read.
#[derive(Debug, thiserror::Error)]
pub enum RcgError {
    /// The log does not start with the version 5 header.
    #[error("not an rcg log of version 5 (its first line is not `ULG5`)")]
    NotUlg5,
    /// A show line does not parse.
    #[error("line {line}: {why}")]
    Show {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        why: String,
    },
}

/// The log of `trace`.
pub fn to_rcg(trace: &Trace) -> String {
    let mut log = String::from("ULG5\n");
    let _ = writeln!(
        log,
        "(server_param (goal_width {:.2})(ball_size {BALL_SIZE})(player_size {PLAYER_SIZE})\
         (half_time 300)(nr_normal_halfs 2)(nr_extra_halfs 2))",
        2.0 * GOAL_HALF_WIDTH
    );
    log.push_str("(player_param (player_types 1))\n");
    log.push_str("(player_type (id 0))\n");
    log.push_str("(playmode 0 play_on)\n");
    let _ = writeln!(log, "(team 0 {} {} 0 0)", TEAMS[0], TEAMS[1]);
    let unums = offense_unums(trace.offense.len());
    for (time, ball) in trace.ball.iter().enumerate() {
        let _ = write!(log, "(show {time} ((b) {:.4} {:.4} 0 0)", ball.x, ball.y);
        for (path, unum) in trace.offense.iter().zip(unums) {
            player(&mut log, 'l', *unum, STAND, path[time]);
        }
        player(&mut log, 'r', 1, STAND | GOALIE, trace.keeper[time]);
        log.push_str(")\n");
    }
    log
}

/// One player of a show line.
fn player(log: &mut String, side: char, unum: u8, state: u32, at: DVec2) {
    let _ = write!(
        log,
        " (({side} {unum}) 0 {state:#x} {:.4} {:.4} 0 0 0 0 (v h 90) (s 8000 1 1 130600) \
         (c 0 0 0 0 0 0 0 0 0 0 0))",
        at.x, at.y
    );
}

/// The show lines of a version 5 log, in order.
pub fn read_shows(log: &str) -> Result<Vec<ShowFrame>, RcgError> {
    let mut lines = log.lines();
    if lines.next() != Some("ULG5") {
        return Err(RcgError::NotUlg5);
    }
    let mut shows = Vec::new();
    for (k, text) in lines.enumerate().filter(|(_, l)| l.starts_with("(show ")) {
        let fail = |why: &str| RcgError::Show {
            line: k + 2,
            why: why.to_owned(),
        };
        shows.push(read_show(text).ok_or_else(|| fail("not a show line of this format"))?);
    }
    Ok(shows)
}

/// One show line: `(show T ((b) x y vx vy) ((s n) type state x y ...) ...)`.
fn read_show(text: &str) -> Option<ShowFrame> {
    let rest = text.strip_prefix("(show ")?;
    let (time, rest) = rest.split_once(' ')?;
    let time = time.parse().ok()?;
    // Each object starts at `((`: the ball's `(b)` or a player's `(side unum)`.
    let mut objects = rest.split("((").skip(1);
    let ball = objects.next()?.strip_prefix("b) ")?;
    let ball = xy(ball.split_whitespace())?;
    let players = objects
        .map(|o| {
            let (id, fields) = o.split_once(") ")?;
            let (side, unum) = id.split_once(' ')?;
            let side = side.chars().next().filter(|c| matches!(c, 'l' | 'r'))?;
            let mut fields = fields.split_whitespace().skip(2);
            Some((side, unum.parse().ok()?, xy(&mut fields)?))
        })
        .collect::<Option<Vec<_>>>()?;
    Some(ShowFrame {
        time,
        ball,
        players,
    })
}

/// The first two numbers of `fields`, as a position.
fn xy<'a>(mut fields: impl Iterator<Item = &'a str>) -> Option<DVec2> {
    let x = fields.next()?.parse().ok()?;
    let y = fields.next()?.trim_end_matches(')').parse().ok()?;
    Some(DVec2::new(x, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::config::EnvConfig;
    use crate::tools::render::record_episode;
    use crate::tools::scripted::ScriptedPolicy;

    #[test]
    fn an_episode_reads_back_from_its_log() {
        let trace = record_episode(EnvConfig::default(), ScriptedPolicy::Random, 3, 2).unwrap();
        let log = to_rcg(&trace);
        let shows = read_shows(&log).unwrap();
        assert_eq!(shows.len(), trace.ball.len());
        let close = |a: DVec2, b: DVec2| (a - b).abs().max_element() < 1e-4;
        for (k, show) in shows.iter().enumerate() {
            assert_eq!(show.time as usize, k);
            assert!(close(show.ball, trace.ball[k]));
            let unums = [7, 8, 11];
            for (i, &(side, unum, at)) in show.players[..3].iter().enumerate() {
                assert_eq!((side, unum), ('l', unums[i]));
                assert!(close(at, trace.offense[i][k]));
            }
            assert_eq!(show.players[3].0, 'r');
            assert!(close(show.players[3].2, trace.keeper[k]));
        }
    }

    #[test]
    fn what_is_not_a_log_is_refused() {
        assert!(matches!(read_shows("ULG4\n"), Err(RcgError::NotUlg5)));
        let broken = "ULG5\n(show 1 ((b) x 0 0 0))\n";
        assert!(matches!(
            read_shows(broken),
            Err(RcgError::Show { line: 2, .. })
        ));
    }
}
