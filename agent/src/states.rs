//! The framework's index of the states an agent met in training: each
//! tile-coded key gets the next dense index, with its visit count n(s).

use std::collections::HashMap;
use std::hash::{BuildHasher, Hasher};

/// A key that occurs twice where keys must be unique (a saved table).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("state key {0:#x} occurs twice")]
pub(crate) struct DuplicateKey(pub u64);

/// Every state met in training: its key, by dense index, and n(s).
///
/// Keys live in a `Vec` in the order they were met, so that learners and
/// traces refer to states by index without hashing; the map only
/// translates keys.
#[derive(Clone, Debug, Default)]
pub(crate) struct StateIndex {
    index: HashMap<u64, usize, KeyHasherBuilder>,
    keys: Vec<u64>,
    visits: Vec<u64>,
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

    /// Counts one training step in index `i`.
    pub(crate) fn visit(&mut self, i: usize) {
        self.visits[i] += 1;
    }

    /// An index of `(key, visits)` rows, indexed in their order.
    pub(crate) fn from_rows(
        rows: impl ExactSizeIterator<Item = (u64, u64)>,
    ) -> Result<Self, DuplicateKey> {
        let mut states = Self::default();
        states.index.reserve(rows.len());
        for (key, visits) in rows {
            let before = states.len();
            let i = states.index_or_insert(key);
            if states.len() == before {
                return Err(DuplicateKey(key));
            }
            states.visits[i] = visits;
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
        s.visit(b);
        s.visit(b);
        assert_eq!((s.len(), s.visits(b), s.key(b)), (2, 2, 10));
        assert_eq!(s.get(20), None);
        let rebuilt = StateIndex::from_rows([(10, 2), (30, 0)].into_iter()).unwrap();
        assert_eq!((rebuilt.get(10), rebuilt.visits(0)), (Some(0), 2));
        let dup = StateIndex::from_rows([(1, 0), (1, 0)].into_iter()).unwrap_err();
        assert_eq!(dup, DuplicateKey(1));
    }
}
