//! Shared episodes (EpisodeSharing) and batches of experience waiting to be
//! learned.
//!
//! The in-process team learns a goal episode's transitions, or a batch,
//! after every agent has ended that episode and before the next one begins.
//! Over the network a share may overtake the receiver's own terminal frame,
//! or arrive after it has begun an evaluation episode; so a share of
//! episode `e` waits until the receiver has finished `e` itself and is not
//! evaluating (frozen agents learn nothing).

use agent::Transition;
use proto::DropReason;

/// Received shares of one kind (`T`: a shared episode's transitions, or a
/// batch) not yet learned (with their episode and sender), and the last
/// episode seen per sender.
#[derive(Clone, Debug)]
pub struct PendingShares<T = Vec<Transition>> {
    queue: Vec<(u32, usize, T)>,
    last: Vec<Option<u32>>,
}

impl<T> Default for PendingShares<T> {
    fn default() -> Self {
        Self {
            queue: Vec::new(),
            last: Vec::new(),
        }
    }
}

impl<T> PendingShares<T> {
    /// Queues the share of `episode` from agent `from`; a sender shares at
    /// most once per episode, so a second share of the same or an earlier
    /// episode is a duplicate or stale.
    pub fn push(&mut self, from: usize, episode: u32, share: T) -> Result<(), DropReason> {
        if self.last.len() <= from {
            self.last.resize(from + 1, None);
        }
        match self.last[from] {
            Some(e) if e == episode => return Err(DropReason::Duplicate),
            Some(e) if e > episode => return Err(DropReason::Stale),
            _ => {}
        }
        self.last[from] = Some(episode);
        self.queue.push((episode, from, share));
        Ok(())
    }

    /// The shares to learn now, with their senders, in arrival order: those
    /// of episodes up to `finished` (the receiver's last finished episode),
    /// when `training`.
    pub fn take_ready(&mut self, finished: Option<u32>, training: bool) -> Vec<(usize, T)> {
        let Some(finished) = finished.filter(|_| training) else {
            return Vec::new();
        };
        let (ready, waiting): (Vec<_>, Vec<_>) = std::mem::take(&mut self.queue)
            .into_iter()
            .partition(|(episode, ..)| *episode <= finished);
        self.queue = waiting;
        ready.into_iter().map(|(_, from, t)| (from, t)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action;

    fn transitions(reward: f64) -> Vec<Transition> {
        vec![Transition {
            state: [0.0; 6],
            action: Action::Move,
            reward,
            next: None,
        }]
    }

    #[test]
    fn shares_wait_for_the_own_terminal_frame_and_training() {
        let mut p = PendingShares::default();
        p.push(1, 4, transitions(1.0)).unwrap();
        p.push(2, 5, transitions(2.0)).unwrap();
        assert!(
            p.take_ready(Some(3), true).is_empty(),
            "episode 4 not finished"
        );
        assert!(p.take_ready(Some(4), false).is_empty(), "evaluating");
        assert_eq!(p.take_ready(Some(4), true), vec![(1, transitions(1.0))]);
        assert!(p.take_ready(None, true).is_empty());
        assert_eq!(p.take_ready(Some(6), true), vec![(2, transitions(2.0))]);
        assert!(p.take_ready(Some(6), true).is_empty());
    }

    #[test]
    fn repeated_and_older_shares_are_dropped() {
        let mut p = PendingShares::default();
        p.push(1, 4, transitions(1.0)).unwrap();
        assert_eq!(p.push(1, 4, transitions(1.0)), Err(DropReason::Duplicate));
        assert_eq!(p.push(1, 3, transitions(1.0)), Err(DropReason::Stale));
        // Another sender of the same episode is fine.
        p.push(0, 4, transitions(0.5)).unwrap();
        assert_eq!(p.take_ready(Some(4), true).len(), 2);
    }
}
