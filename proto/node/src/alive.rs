//! Following the coordinator's liveliness token (docs/protocol.md,
//! "Liveness"): a process the coordinator started exits once that
//! coordinator is gone, but not before it was ever seen.

use std::sync::atomic::{AtomicBool, Ordering};

/// Whether the coordinator that was seen has left. Shared freely: zenoh
/// callbacks and tasks can update it through `&self`.
#[derive(Debug, Default)]
pub struct CoordinatorPresence {
    seen: AtomicBool,
}

impl CoordinatorPresence {
    /// Records one sample of the coordinator's token (`present`: it was
    /// declared, else undeclared); true when a coordinator seen before is gone.
    pub fn left(&self, present: bool) -> bool {
        if present {
            self.seen.store(true, Ordering::Relaxed);
            false
        } else {
            self.seen.load(Ordering::Relaxed)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_coordinator_seen_before_can_leave() {
        let p = CoordinatorPresence::default();
        assert!(!p.left(false), "never seen: not gone");
        assert!(!p.left(true));
        assert!(p.left(false));
        assert!(!p.left(true), "back again");
    }
}
