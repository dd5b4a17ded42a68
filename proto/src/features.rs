//! HFO's high-level features of one agent's state (docs/python.md, "The
//! `hfo` set"): what an agent whose learner reads them gets beside the
//! paper's six.

use std::fmt;

use serde::de::{Error as _, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The most attackers whose features are sent (env-server's `MAX_OFFENSE`).
pub const MAX_FEATURE_TEAM: usize = 4;

/// The length of today's HFO high-level set for `team_size` attackers
/// against one keeper: `10 + 6T + 3 + 2`, T = `team_size - 1` teammates
/// (27 for 3).
pub const fn hfo_feature_count(team_size: usize) -> usize {
    10 + 6 * team_size.saturating_sub(1) + 5
}

/// The longest feature vector: that of [`MAX_FEATURE_TEAM`] attackers (33).
pub const MAX_FEATURES: usize = hfo_feature_count(MAX_FEATURE_TEAM);

/// HFO's features of one state, or none (empty) for an agent whose learner
/// reads the paper's six only. Of fixed capacity, so that it is `Copy` and
/// nothing decoded can make it longer than [`MAX_FEATURES`].
#[derive(Clone, Copy)]
pub struct Features {
    len: u8,
    values: [f32; MAX_FEATURES],
}

impl Features {
    /// No features.
    pub const NONE: Features = Features {
        len: 0,
        values: [0.0; MAX_FEATURES],
    };

    /// `values`, if there are at most [`MAX_FEATURES`].
    pub fn new(values: &[f32]) -> Option<Self> {
        Self::collect(values.iter().copied())
    }

    /// `values` rounded to `f32` (as Python's `hfo` observation is), if
    /// there are at most [`MAX_FEATURES`].
    pub fn from_f64(values: &[f64]) -> Option<Self> {
        Self::collect(values.iter().map(|&x| x as f32))
    }

    fn collect(values: impl Iterator<Item = f32>) -> Option<Self> {
        let mut features = Self::NONE;
        for x in values {
            *features.values.get_mut(usize::from(features.len))? = x;
            features.len += 1;
        }
        Some(features)
    }

    /// The features.
    pub fn as_slice(&self) -> &[f32] {
        &self.values[..usize::from(self.len)]
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

impl Default for Features {
    fn default() -> Self {
        Self::NONE
    }
}

impl PartialEq for Features {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl fmt::Debug for Features {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

impl Serialize for Features {
    /// As a sequence of its values (one byte when empty, in postcard).
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.as_slice())
    }
}

impl<'de> Deserialize<'de> for Features {
    /// A sequence of at most [`MAX_FEATURES`] values; a longer one is an
    /// error as soon as its first extra value is read.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Values;
        impl<'de> Visitor<'de> for Values {
            type Value = Features;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "at most {MAX_FEATURES} features")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Features, A::Error> {
                let mut features = Features::NONE;
                while let Some(x) = seq.next_element::<f32>()? {
                    let Some(slot) = features.values.get_mut(usize::from(features.len)) else {
                        return Err(A::Error::invalid_length(MAX_FEATURES + 1, &self));
                    };
                    *slot = x;
                    features.len += 1;
                }
                Ok(features)
            }
        }
        deserializer.deserialize_seq(Values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_hfos() {
        // 10 + 6T + 3O + 2 with one opponent: 15, 21, 27, 33.
        let counts: Vec<usize> = (1..=4).map(hfo_feature_count).collect();
        assert_eq!(counts, [15, 21, 27, 33]);
        assert_eq!(MAX_FEATURES, 33);
    }

    #[test]
    fn they_travel_bounded() {
        let none = postcard::to_allocvec(&Features::NONE).unwrap();
        assert_eq!(none, [0], "one byte when empty");
        let values: Vec<f32> = (0..27).map(|i| i as f32 / 4.0).collect();
        let f = Features::new(&values).unwrap();
        let bytes = postcard::to_allocvec(&f).unwrap();
        let back: Features = postcard::from_bytes(&bytes).unwrap();
        assert_eq!(back.as_slice(), &values[..]);
        assert_eq!(
            Features::from_f64(&[0.1, -2.0]).unwrap().as_slice(),
            [0.1f32, -2.0]
        );
        // One more than the most is refused, built or decoded.
        let long = vec![0.5f32; MAX_FEATURES + 1];
        assert!(Features::new(&long).is_none());
        let bytes = postcard::to_allocvec(&long).unwrap();
        assert!(postcard::from_bytes::<Features>(&bytes).is_err());
        // A length prefix of billions with few bytes behind it fails too.
        let huge = [0xff, 0xff, 0xff, 0xff, 0x0f, 0, 0, 0, 0];
        assert!(postcard::from_bytes::<Features>(&huge).is_err());
    }
}
