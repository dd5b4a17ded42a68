//! An agent's learned state as bytes (the snapshot file format, written and
//! read by the caller) and a stable digest.
//!
//! Layout: magic `ADVQTAB\0` | format version (u16 LE) | body length (u64 LE)
//! | postcard body | FNV-1a 64 of the body (u64 LE). Version 1's body holds
//! the tiling, the entries, the counters and the finished episodes; version
//! 2's, written only for a learner that keeps its state itself (a learner
//! process), holds those and then the learner's own bytes.

use std::hash::Hasher;

use fnv::FnvHasher;
use serde::{Deserialize, Serialize};

use crate::advice_counters::AdviceCounters;
use crate::selection::ACTIONS;
use crate::tiles::TilingParams;

const MAGIC: [u8; 8] = *b"ADVQTAB\0";

/// Version of the file format of a snapshot without a learner's own state;
/// files of versions other than it and [`LEARNER_STATE_FORMAT_VERSION`] are
/// refused.
pub const SNAPSHOT_FORMAT_VERSION: u16 = 1;

/// Version of the file format of a snapshot that carries a learner's own
/// state (its body: version 1's, then those bytes).
pub const LEARNER_STATE_FORMAT_VERSION: u16 = 2;

const HEADER: usize = MAGIC.len() + 2 + 8;
const CHECKSUM: usize = 8;

/// Why a snapshot could not be encoded, decoded or restored.
#[derive(Debug, thiserror::Error)]
pub enum PersistError {
    /// The file does not start with the snapshot magic.
    #[error("not an agent snapshot (bad magic header)")]
    NotASnapshot,
    /// The file was written in another format version.
    #[error("snapshot format version {found}, this build reads version {expected}")]
    UnsupportedVersion {
        /// Version in the file.
        found: u16,
        /// Version this build reads.
        expected: u16,
    },
    /// The file is shorter or longer than its header says.
    #[error("snapshot is {found} bytes, its header says {expected}: truncated or padded")]
    Length {
        /// Size announced by the header.
        expected: u64,
        /// Actual size.
        found: u64,
    },
    /// The body does not match its checksum.
    #[error("snapshot checksum mismatch: the file is corrupt")]
    Checksum,
    /// The body could not be encoded or decoded.
    #[error("snapshot body: {0}")]
    Codec(#[from] postcard::Error),
    /// The body decoded but holds impossible values.
    #[error("invalid snapshot: {0}")]
    Invalid(String),
    /// The snapshot was made under another tiling; its keys mean nothing here.
    #[error("snapshot tiling {saved:?} differs from the agent's {current:?}")]
    Incompatible {
        /// Tiling of the snapshot.
        saved: TilingParams,
        /// Tiling of the agent.
        current: TilingParams,
    },
}

/// What a snapshot holds of one state: the learner's values and the
/// framework's visit count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Entry {
    /// Q(s, a), indexed by [`proto::Action::index`]; 0 until updated.
    pub q: [f64; ACTIONS],
    /// Bit `a.index()` is set once Q(s, a) has been updated (the authors'
    /// "(s, a) is in the Q-table").
    pub tried: u8,
    /// n(s): training steps taken in this state.
    pub visits: u64,
}

/// An agent's learned state (see [`crate::Agent::snapshot`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The tiling that gives the keys their meaning.
    pub tiling: TilingParams,
    /// Q-table entries with visit counts, sorted by key.
    pub entries: Vec<(u64, Entry)>,
    /// AdviceCounters, including the spent budgets.
    pub counters: AdviceCounters,
    /// Training episodes finished.
    pub training_episodes: u64,
    /// The learner's own state, for a learner that keeps it itself (a
    /// learner process with snapshot hooks); its values are then not in
    /// `entries`.
    #[serde(skip)]
    pub learner_state: Option<Vec<u8>>,
}

/// The file checksum of `bytes`: FNV-1a, 64 bits.
fn checksum(bytes: &[u8]) -> u64 {
    let mut h = FnvHasher::default();
    h.write(bytes);
    h.finish()
}

/// A snapshot file holding `body`: the header (magic, format version,
/// length), `body` and its checksum, as [`Snapshot::encode`] writes around
/// its postcard body. For tools that build or fuzz snapshot files.
pub fn snapshot_file(body: &[u8]) -> Vec<u8> {
    file_of(SNAPSHOT_FORMAT_VERSION, body)
}

/// The file of `body` in format `version`.
fn file_of(version: u16, body: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + body.len() + CHECKSUM);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(body);
    out.extend_from_slice(&checksum(body).to_le_bytes());
    out
}

impl Snapshot {
    /// FNV-1a over every learned value in key order (Q values by their bits):
    /// equal digests mean equal learned state, across runs and platforms.
    pub fn digest(&self) -> u64 {
        let t = self.tiling;
        let mut h = FnvHasher::default();
        let word = |h: &mut FnvHasher, x: u64| h.write(&x.to_le_bytes());
        word(&mut h, u64::from(t.tiles_per_feature));
        word(&mut h, t.tile_width.to_bits());
        word(&mut h, t.tile_step.to_bits());
        for (key, e) in &self.entries {
            word(&mut h, *key);
            for q in e.q {
                word(&mut h, q.to_bits());
            }
            h.write(&[e.tried]);
            word(&mut h, e.visits);
        }
        if let Some(state) = &self.learner_state {
            h.write(state);
        }
        let c = self.counters;
        for x in [
            c.advice_requests,
            c.advice_replies_received,
            c.ask_spent,
            c.advice_given,
            c.shared_sent,
            c.shared_received,
            self.training_episodes,
        ] {
            word(&mut h, x);
        }
        h.finish()
    }

    /// Rejects impossible values (a tiling without tiles or with a
    /// non-finite or non-positive width or step, tried bits beyond the five
    /// actions, non-finite Q values).
    pub fn check(&self) -> Result<(), PersistError> {
        let t = self.tiling;
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if t.tiles_per_feature == 0 || !positive(t.tile_width) || !positive(t.tile_step) {
            return Err(PersistError::Invalid(format!("impossible tiling {t:?}")));
        }
        for (key, e) in &self.entries {
            if e.tried >> ACTIONS != 0 || e.q.iter().any(|q| !q.is_finite()) {
                return Err(PersistError::Invalid(format!(
                    "entry {key:#x} holds impossible values"
                )));
            }
        }
        Ok(())
    }

    /// The file image: header, body and checksum (version 2 with a
    /// learner's own state).
    pub fn encode(&self) -> Result<Vec<u8>, PersistError> {
        Ok(match &self.learner_state {
            None => snapshot_file(&postcard::to_allocvec(self)?),
            Some(state) => file_of(
                LEARNER_STATE_FORMAT_VERSION,
                &postcard::to_allocvec(&(self, state))?,
            ),
        })
    }

    /// Parses a file image, checking magic, version, length and checksum.
    pub fn decode(bytes: &[u8]) -> Result<Self, PersistError> {
        let magic_len = bytes.len().min(MAGIC.len());
        if bytes[..magic_len] != MAGIC[..magic_len] {
            return Err(PersistError::NotASnapshot);
        }
        let too_short = || PersistError::Length {
            expected: HEADER as u64,
            found: bytes.len() as u64,
        };
        let version = u16::from_le_bytes(read_array(bytes, MAGIC.len()).ok_or_else(too_short)?);
        if ![SNAPSHOT_FORMAT_VERSION, LEARNER_STATE_FORMAT_VERSION].contains(&version) {
            return Err(PersistError::UnsupportedVersion {
                found: version,
                expected: SNAPSHOT_FORMAT_VERSION,
            });
        }
        let body_len =
            u64::from_le_bytes(read_array(bytes, MAGIC.len() + 2).ok_or_else(too_short)?);
        let expected = body_len.saturating_add((HEADER + CHECKSUM) as u64);
        if expected != bytes.len() as u64 {
            return Err(PersistError::Length {
                expected,
                found: bytes.len() as u64,
            });
        }
        let body = &bytes[HEADER..bytes.len() - CHECKSUM];
        let sum =
            u64::from_le_bytes(read_array(bytes, bytes.len() - CHECKSUM).ok_or_else(too_short)?);
        if checksum(body) != sum {
            return Err(PersistError::Checksum);
        }
        let (mut snapshot, mut rest): (Self, _) = postcard::take_from_bytes(body)?;
        if version == LEARNER_STATE_FORMAT_VERSION {
            let (state, after): (Vec<u8>, _) = postcard::take_from_bytes(rest)?;
            (snapshot.learner_state, rest) = (Some(state), after);
        }
        if !rest.is_empty() {
            return Err(PersistError::Invalid(format!(
                "{} bytes after the body",
                rest.len()
            )));
        }
        snapshot.check()?;
        Ok(snapshot)
    }
}

/// `N` bytes at `at`, if present.
fn read_array<const N: usize>(bytes: &[u8], at: usize) -> Option<[u8; N]> {
    bytes.get(at..at.checked_add(N)?)?.try_into().ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::AgentConfig;

    fn sample() -> Snapshot {
        let entry = |q0: f64, visits| Entry {
            q: [q0, 0.5, -0.25, 0.0, 1e-3],
            tried: 0b00111,
            visits,
        };
        Snapshot {
            tiling: TilingParams::of(&AgentConfig::default()),
            entries: vec![(3, entry(0.1, 4)), (1 << 40, entry(-0.7, 1))],
            counters: AdviceCounters {
                advice_requests: 5,
                advice_given: 2,
                ..AdviceCounters::default()
            },
            training_episodes: 12,
            learner_state: None,
        }
    }

    #[test]
    fn a_learners_own_state_makes_a_version_2_file_that_reads_back() {
        let plain = sample().encode().unwrap();
        let with_state = Snapshot {
            learner_state: Some(vec![1, 2, 3, 250]),
            ..sample()
        };
        let bytes = with_state.encode().unwrap();
        assert_eq!(
            u16::from_le_bytes([bytes[8], bytes[9]]),
            LEARNER_STATE_FORMAT_VERSION
        );
        assert_eq!(
            u16::from_le_bytes([plain[8], plain[9]]),
            SNAPSHOT_FORMAT_VERSION
        );
        assert_eq!(Snapshot::decode(&bytes).unwrap(), with_state);
        assert_ne!(with_state.digest(), sample().digest());
    }

    #[test]
    fn encode_decode_round_trip() {
        let s = sample();
        let loaded = Snapshot::decode(&s.encode().unwrap()).unwrap();
        assert_eq!(loaded, s);
        assert_eq!(loaded.digest(), s.digest());
    }

    #[test]
    fn an_impossible_tiling_is_refused() {
        // Found by the `snapshot` fuzz target: a NaN tile width decoded and
        // passed the check.
        for (width, step) in [(f64::NAN, 0.1), (0.5, 0.0), (f64::INFINITY, 0.1)] {
            let mut s = sample();
            s.tiling.tile_width = width;
            s.tiling.tile_step = step;
            assert!(s.check().unwrap_err().to_string().contains("tiling"));
        }
        assert!(sample().check().is_ok());
    }

    #[test]
    fn bad_files_give_clear_errors() {
        let good = sample().encode().unwrap();

        let mut version = good.clone();
        version[8..10].copy_from_slice(&3u16.to_le_bytes());
        let err = Snapshot::decode(&version).unwrap_err();
        assert!(
            matches!(
                err,
                PersistError::UnsupportedVersion {
                    found: 3,
                    expected: 1
                }
            ),
            "{err}"
        );

        let truncated = &good[..good.len() - 3];
        assert!(matches!(
            Snapshot::decode(truncated),
            Err(PersistError::Length { .. })
        ));
        assert!(matches!(
            Snapshot::decode(&good[..12]),
            Err(PersistError::Length { .. })
        ));
        assert!(matches!(
            Snapshot::decode(&good[..5]),
            Err(PersistError::Length { .. })
        ));

        let mut flipped = good.clone();
        flipped[HEADER + 4] ^= 0x40;
        assert!(matches!(
            Snapshot::decode(&flipped),
            Err(PersistError::Checksum)
        ));

        assert!(matches!(
            Snapshot::decode(b"PK\x03\x04 zip"),
            Err(PersistError::NotASnapshot)
        ));
        assert!(matches!(
            Snapshot::decode(&[]),
            Err(PersistError::Length { .. })
        ));
    }

    #[test]
    fn well_formed_body_with_impossible_values_is_refused() {
        let mut s = sample();
        s.entries[0].1.tried = 0b1000_0000;
        let err = Snapshot::decode(&s.encode().unwrap()).unwrap_err();
        assert!(matches!(err, PersistError::Invalid(_)), "{err}");
    }

    #[test]
    fn digest_sees_every_value() {
        let s = sample();
        let mut t = sample();
        t.entries[1].1.visits += 1;
        assert_ne!(s.digest(), t.digest());
        let mut u = sample();
        u.entries[0].1.q[4] = f64::from_bits(u.entries[0].1.q[4].to_bits() + 1);
        assert_ne!(s.digest(), u.digest());
        let mut v = sample();
        v.counters.shared_received = 1;
        assert_ne!(s.digest(), v.digest());
    }
}
