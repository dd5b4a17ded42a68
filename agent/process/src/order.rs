//! The position of an agent in its observation stream: which observations
//! are new, which are stale or duplicate (docs/protocol.md, "Receiving").

use proto::DropReason;

/// Whether an accepted observation starts an episode.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Position {
    /// The first frame seen of a later episode: begin it.
    NewEpisode,
    /// A later frame of the current episode.
    SameEpisode,
}

/// Where the observations of one run stand.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ObservationOrder {
    /// The last accepted (episode, frame).
    last: Option<(u32, u32)>,
    /// The last episode whose terminal frame was accepted.
    finished: Option<u32>,
}

impl ObservationOrder {
    /// The position of an agent that joins a run at `episode` (a newcomer,
    /// or a restart): the episodes before it count as finished.
    pub fn joining_at(episode: u32) -> Self {
        Self {
            last: None,
            finished: episode.checked_sub(1),
        }
    }

    /// Accepts frame `frame` of episode `episode` if it comes after
    /// everything seen so far; a terminal frame finishes its episode, after
    /// which nothing more of that episode is accepted.
    pub fn accept(
        &mut self,
        episode: u32,
        frame: u32,
        terminal: bool,
    ) -> Result<Position, DropReason> {
        let position = match self.last {
            Some(last) if last == (episode, frame) => return Err(DropReason::Duplicate),
            Some(last) if (episode, frame) < last => return Err(DropReason::Stale),
            _ if self.finished.is_some_and(|f| episode <= f) => return Err(DropReason::Stale),
            Some((e, _)) if e == episode => Position::SameEpisode,
            _ => Position::NewEpisode,
        };
        self.last = Some((episode, frame));
        if terminal {
            self.finished = Some(episode);
        }
        Ok(position)
    }

    /// The last episode whose terminal frame was accepted.
    pub fn finished(&self) -> Option<u32> {
        self.finished
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use DropReason::{Duplicate, Stale};
    use Position::{NewEpisode, SameEpisode};

    #[test]
    fn frames_in_order_start_and_finish_episodes() {
        let mut s = ObservationOrder::default();
        assert_eq!(s.accept(0, 0, false), Ok(NewEpisode));
        assert_eq!(s.accept(0, 1, false), Ok(SameEpisode));
        assert_eq!(s.finished(), None);
        assert_eq!(s.accept(0, 2, true), Ok(SameEpisode));
        assert_eq!(s.finished(), Some(0));
        // Episodes may be skipped (another agent's) or start past frame 0.
        assert_eq!(s.accept(2, 3, false), Ok(NewEpisode));
        // A one-frame episode: new and terminal at once.
        assert_eq!(s.accept(3, 0, true), Ok(NewEpisode));
        assert_eq!(s.finished(), Some(3));
    }

    #[test]
    fn an_agent_joining_at_an_episode_counts_the_earlier_ones_finished() {
        let mut s = ObservationOrder::joining_at(30);
        assert_eq!(s.finished(), Some(29));
        assert_eq!(s.accept(29, 5, false), Err(Stale));
        assert_eq!(s.accept(30, 0, false), Ok(NewEpisode));
        assert_eq!(ObservationOrder::joining_at(0), ObservationOrder::default());
    }

    #[test]
    fn repeated_earlier_and_finished_frames_are_dropped() {
        let mut s = ObservationOrder::default();
        s.accept(1, 0, false).unwrap();
        s.accept(1, 4, false).unwrap();
        assert_eq!(s.accept(1, 4, false), Err(Duplicate));
        assert_eq!(s.accept(1, 2, false), Err(Stale));
        assert_eq!(s.accept(0, 9, false), Err(Stale));
        s.accept(1, 5, true).unwrap();
        assert_eq!(s.accept(1, 5, true), Err(Duplicate));
        assert_eq!(
            s.accept(1, 6, false),
            Err(Stale),
            "after its terminal frame"
        );
        // Drops change nothing.
        assert_eq!(s.accept(2, 0, false), Ok(NewEpisode));
    }
}
