//! The framework's index of the states an agent met in training: each
//! tile-coded key gets the next dense index, with its visit count n(s) and
//! how often each action was taken there, m(s, a).

use std::collections::HashMap;

use proto::Action;

use crate::selection::ACTIONS;
use std::hash::{BuildHasher, Hasher};

/// A key that occurs twice where keys must be unique (a saved table).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("state key {0:#x} occurs twice")]
pub(crate) struct DuplicateKey(pub u64);

/// Every state met in training: its key, by dense index, n(s) and m(s, a).
///
/// Keys live in a `Vec` in the order they were met, so that learners and
/// traces refer to states by index without hashing; the map only
/// translates keys.
#[derive(Clone, Debug, Default)]
pub(crate) struct StateIndex {
    index: HashMap<u64, usize, KeyHasherBuilder>,
    keys: Vec<u64>,
    visits: Vec<u64>,
    action_visits: Vec<[u32; ACTIONS]>,
}

impl StateIndex {
    /// Number of states met.
    pub(crate) fn len(&self) -> usize {
        self.keys.len()
    }

    /// The index of a key, if it was met.
    pub(crate) fn get(&self, key: u64) -> Option<usize> {
        self.index.get(&key).copied()
    }

    /// The index of a key, giving it the next one if it is new.
    pub(crate) fn index_or_insert(&mut self, key: u64) -> usize {
        let next = self.keys.len();
        let i = *self.index.entry(key).or_insert(next);
        if i == next {
            self.keys.push(key);
            self.visits.push(0);
            self.action_visits.push([0; ACTIONS]);
        }
        i
    }

    /// The key of index `i`.
    pub(crate) fn key(&self, i: usize) -> u64 {
        self.keys[i]
    }

    /// n(s) of index `i`.
    pub(crate) fn visits(&self, i: usize) -> u64 {
        self.visits[i]
    }

    /// m(s, a) of index `i`, by action index.
    pub(crate) fn action_visits(&self, i: usize) -> [u32; ACTIONS] {
        self.action_visits[i]
    }

    /// Counts one training step taking `action` in index `i`.
    pub(crate) fn visit(&mut self, i: usize, action: Action) {
        self.visits[i] += 1;
        let m = &mut self.action_visits[i][action.index()];
        *m = m.saturating_add(1);
    }

    /// An index of `(key, visits, greedy action)` rows, indexed in their
    /// order. A saved table keeps n(s), not its split over the actions:
    /// each state's n(s) counts as m(s, a) of the action it values most.
    pub(crate) fn from_rows(
        rows: impl ExactSizeIterator<Item = (u64, u64, Action)>,
    ) -> Result<Self, DuplicateKey> {
        let mut states = Self::default();
        states.index.reserve(rows.len());
        for (key, visits, greedy) in rows {
            let before = states.len();
            let i = states.index_or_insert(key);
            if states.len() == before {
                return Err(DuplicateKey(key));
            }
            states.visits[i] = visits;
            states.action_visits[i][greedy.index()] = u32::try_from(visits).unwrap_or(u32::MAX);
        }
        Ok(states)
    }
}

/// Hashes a `u64` key with the murmur3 finaliser: fixed (no per-process seed)
/// and well mixed in every bit, which tile keys with long constant runs need.
#[derive(Clone, Copy, Debug, Default)]
struct KeyHasherBuilder;

impl BuildHasher for KeyHasherBuilder {
    type Hasher = KeyHasher;

    fn build_hasher(&self) -> KeyHasher {
        KeyHasher(0)
    }
}

#[derive(Clone, Copy, Debug)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 ^= x;
    }

    fn finish(&self) -> u64 {
        let mut x = self.0;
        x ^= x >> 33;
        x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
        x ^= x >> 33;
        x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        x ^ (x >> 33)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_are_stable_and_in_the_order_met() {
        let mut s = StateIndex::default();
        let a = s.index_or_insert(30);
        let b = s.index_or_insert(10);
        assert_eq!((a, b), (0, 1));
        assert_eq!(s.index_or_insert(30), a);
        s.visit(b, Action::Shoot);
        s.visit(b, Action::Dribble);
        assert_eq!((s.len(), s.visits(b), s.key(b)), (2, 2, 10));
        assert_eq!(s.action_visits(b), [0, 1, 1, 0, 0]);
        assert_eq!(s.get(20), None);
        let rows = [(10, 2, Action::PassFar), (30, 0, Action::Move)];
        let rebuilt = StateIndex::from_rows(rows.into_iter()).unwrap();
        assert_eq!((rebuilt.get(10), rebuilt.visits(0)), (Some(0), 2));
        assert_eq!(
            rebuilt.action_visits(0),
            [0, 0, 0, 0, 2],
            "n(s) to its greedy action"
        );
        let dup = [(1, 0, Action::Move), (1, 0, Action::Move)];
        let dup = StateIndex::from_rows(dup.into_iter()).unwrap_err();
        assert_eq!(dup, DuplicateKey(1));
    }
}
