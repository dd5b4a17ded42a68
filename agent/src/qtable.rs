//! The Q-table: one entry per state key holding the five action values, which
//! actions have an entry ("tried") and the visit count n(s).

use std::collections::HashMap;
use std::hash::{BuildHasher, Hasher};

use proto::Action;
use serde::{Deserialize, Serialize};

/// Number of actions, indexed by [`Action::index`].
pub const ACTIONS: usize = Action::ALL.len();

/// Everything learned about one state key.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Entry {
    /// Q(s, a), indexed by [`Action::index`]; 0 until updated.
    pub q: [f64; ACTIONS],
    /// Bit `a.index()` is set once Q(s, a) has been updated (the authors'
    /// "(s, a) is in the Q-table").
    pub tried: u8,
    /// n(s): training steps taken in this state.
    pub visits: u64,
}

impl Entry {
    /// Whether Q(s, a) has an entry.
    pub fn is_tried(&self, a: Action) -> bool {
        self.tried & (1 << a.index()) != 0
    }

    /// Whether any kick action has an entry.
    pub fn any_kick_tried(&self) -> bool {
        Action::KICK_TIE_ORDER.iter().any(|&a| self.is_tried(a))
    }

    /// `max_a Q - min_a Q` over the kick actions that have an entry; 0 with
    /// fewer than two (the authors' rule, shared by AdHocTD and Torrey).
    pub fn kick_spread(&self) -> f64 {
        let mut tried = Action::KICK_TIE_ORDER
            .iter()
            .filter(|&&a| self.is_tried(a))
            .map(|&a| self.q[a.index()]);
        let Some(first) = tried.next() else {
            return 0.0;
        };
        let (lo, hi) = tried.fold((first, first), |(lo, hi), q| (lo.min(q), hi.max(q)));
        hi - lo
    }
}

/// Index of an entry; stays valid for the table's lifetime (entries are
/// never removed).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct EntryId(usize);

/// Keys of a saved table that occur twice.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("state key {0:#x} occurs twice")]
pub(crate) struct DuplicateKey(pub u64);

/// Q-table keyed by the tile-coded state key.
///
/// Entries live in a `Vec` in insertion order, so traces can refer to them by
/// index without hashing; the map only translates keys.
#[derive(Clone, Debug, Default)]
pub struct QTable {
    index: HashMap<u64, usize, KeyHasherBuilder>,
    keys: Vec<u64>,
    entries: Vec<Entry>,
}

impl QTable {
    /// An empty table.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Number of states with an entry.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether no state has an entry.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The entry of a state key, if any.
    pub fn get(&self, key: u64) -> Option<&Entry> {
        self.index.get(&key).map(|&i| &self.entries[i])
    }

    /// The id of a state key's entry, inserting an empty one if missing.
    pub(crate) fn id_or_insert(&mut self, key: u64) -> EntryId {
        let next = self.entries.len();
        let i = *self.index.entry(key).or_insert(next);
        if i == next {
            self.keys.push(key);
            self.entries.push(Entry::default());
        }
        EntryId(i)
    }

    /// The entry behind an id.
    pub(crate) fn entry(&self, id: EntryId) -> &Entry {
        &self.entries[id.0]
    }

    pub(crate) fn entry_mut(&mut self, id: EntryId) -> &mut Entry {
        &mut self.entries[id.0]
    }

    /// All entries sorted by key (for saving and digests).
    pub fn sorted_entries(&self) -> Vec<(u64, Entry)> {
        let mut all: Vec<_> = self
            .keys
            .iter()
            .copied()
            .zip(self.entries.iter().copied())
            .collect();
        all.sort_unstable_by_key(|&(k, _)| k);
        all
    }

    /// Rebuilds a table from `(key, entry)` pairs.
    pub(crate) fn from_entries(pairs: Vec<(u64, Entry)>) -> Result<Self, DuplicateKey> {
        let mut table = Self::new();
        table.index.reserve(pairs.len());
        for (key, entry) in pairs {
            let before = table.len();
            let id = table.id_or_insert(key);
            if table.len() == before {
                return Err(DuplicateKey(key));
            }
            *table.entry_mut(id) = entry;
        }
        Ok(table)
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

    fn entry(q: [f64; ACTIONS], tried: &[Action]) -> Entry {
        let tried = tried.iter().fold(0, |m, a| m | 1 << a.index());
        Entry {
            q,
            tried,
            visits: 0,
        }
    }

    #[test]
    fn spread_counts_only_tried_kick_actions() {
        use Action::*;
        // q indexed Move, Shoot, Dribble, PassNear, PassFar.
        let q = [5.0, 0.4, -0.2, 0.9, 0.0];
        // Untried PassNear (0.9) and Move (5.0) are skipped: 0.4 - (-0.2) = 0.6.
        assert!((entry(q, &[Move, Shoot, Dribble]).kick_spread() - 0.6).abs() < 1e-15);
        // All four kicks: 0.9 - (-0.2) = 1.1.
        assert!((entry(q, &[Shoot, Dribble, PassNear, PassFar]).kick_spread() - 1.1).abs() < 1e-15);
        // One tried kick (plus Move): spread 0.
        assert_eq!(entry(q, &[Move, PassNear]).kick_spread(), 0.0);
        assert_eq!(entry(q, &[]).kick_spread(), 0.0);
    }

    #[test]
    fn ids_are_stable_and_sorting_is_by_key() {
        let mut t = QTable::new();
        let a = t.id_or_insert(30);
        let b = t.id_or_insert(10);
        assert_eq!(t.id_or_insert(30), a);
        t.entry_mut(b).visits = 7;
        assert_eq!(t.len(), 2);
        assert_eq!(t.get(10).unwrap().visits, 7);
        assert!(t.get(20).is_none());
        let keys: Vec<u64> = t.sorted_entries().iter().map(|&(k, _)| k).collect();
        assert_eq!(keys, vec![10, 30]);
        let rebuilt = QTable::from_entries(t.sorted_entries()).unwrap();
        assert_eq!(rebuilt.sorted_entries(), t.sorted_entries());
        let dup = vec![(1, Entry::default()), (1, Entry::default())];
        assert_eq!(QTable::from_entries(dup).unwrap_err(), DuplicateKey(1));
    }
}
