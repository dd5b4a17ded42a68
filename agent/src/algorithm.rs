//! The one vocabulary of advising algorithms, shared by the command line, team
//! and study files and `config.json`: a name of the list every method is
//! registered in once (`strategy::ALGORITHMS`).

use std::fmt;
use std::hash::{Hash, Hasher};
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::method::{LearnerNeed, Registration};
use crate::strategy::ALGORITHMS;

/// An advising algorithm, named in kebab-case (`adhoc-td`) wherever it is
/// written or read; [`Algorithm::all`] lists them.
#[derive(Clone, Copy)]
pub struct Algorithm(&'static Registration);

/// An algorithm name that is not one of [`Algorithm::all`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown algorithm `{0}` (expected one of: {names})", names = Algorithm::list())]
pub struct UnknownAlgorithm(pub String);

impl Algorithm {
    /// Every algorithm: the paper's, in the order it presents them, then
    /// the field's since, then `external`.
    pub fn all() -> impl Iterator<Item = Algorithm> {
        ALGORITHMS.iter().map(Algorithm)
    }

    /// The name as written on the command line and in files.
    pub fn name(self) -> &'static str {
        self.0.name
    }

    /// Older spellings still accepted when reading (never written).
    pub fn aliases(self) -> &'static [&'static str] {
        self.0.aliases
    }

    /// One line on what it does.
    pub fn about(self) -> &'static str {
        self.0.about
    }

    /// What it needs of its agents' learner.
    pub fn learner_need(self) -> LearnerNeed {
        self.0.learner
    }

    /// Whether its agents communicate (advice, values or shared episodes).
    pub fn communicates(self) -> bool {
        self.0.communicates
    }

    /// Whether its agents learn from the episodes others share (which
    /// carry the paper's states only).
    pub fn shares_episodes(self) -> bool {
        self.0.shares_episodes
    }

    /// Whether its decisions are given from outside: `external`, made by a
    /// strategy process (a team file's `strategy_process`) or, in process,
    /// [`Agent::with_strategy`](crate::Agent::with_strategy).
    pub fn is_external(self) -> bool {
        self.0.external
    }

    /// Whether its settings have `key` (e.g. `mistake_correcting`).
    pub fn has_setting(self, key: &str) -> bool {
        (self.0.defaults)(crate::Profile::Paper)
            .table()
            .contains_key(key)
    }

    /// Every name, comma-separated (for messages).
    pub fn list() -> String {
        let names: Vec<&str> = Self::all().map(Algorithm::name).collect();
        names.join(", ")
    }

    pub(crate) fn registration(self) -> &'static Registration {
        self.0
    }
}

impl Default for Algorithm {
    /// `no-advice`, the first.
    fn default() -> Self {
        Algorithm(&ALGORITHMS[0])
    }
}

impl PartialEq for Algorithm {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for Algorithm {}

impl Hash for Algorithm {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.name().hash(state);
    }
}

impl fmt::Debug for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Algorithm {
    type Err = UnknownAlgorithm;

    /// A name or one of its aliases.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::all()
            .find(|a| a.name() == s || a.aliases().contains(&s))
            .ok_or_else(|| UnknownAlgorithm(s.to_owned()))
    }
}

impl Serialize for Algorithm {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Algorithm {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_aliases_parse_and_display() {
        for algorithm in Algorithm::all() {
            assert_eq!(algorithm.name().parse::<Algorithm>(), Ok(algorithm));
            assert_eq!(algorithm.to_string(), algorithm.name());
            for alias in algorithm.aliases() {
                assert_eq!(alias.parse::<Algorithm>(), Ok(algorithm));
            }
        }
        let td: Algorithm = "ad-hoc-td".parse().unwrap();
        assert_eq!(td.name(), "adhoc-td");
        let e = "best".parse::<Algorithm>().unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown algorithm `best` (expected one of: no-advice, adhoc-visit, adhoc-td, \
             torrey, episode-sharing, random, early-advising, random-advising, advice-reuse, peer-learning, rcmp, psaf, \
             advice-imitation, ef-ontl, external)"
        );
    }

    #[test]
    fn names_are_unique_and_kebab_case() {
        let names: Vec<&str> = Algorithm::all()
            .flat_map(|a| std::iter::once(a.name()).chain(a.aliases().iter().copied()))
            .collect();
        for (i, name) in names.iter().enumerate() {
            assert!(!names[..i].contains(name), "{name} twice");
            assert!(
                name.bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-'),
                "{name}"
            );
        }
        assert_eq!(Algorithm::default().name(), "no-advice");
    }

    #[test]
    fn serde_writes_the_name_and_reads_aliases() {
        let visit: Algorithm = "adhoc-visit".parse().unwrap();
        let json = serde_json::to_string(&visit).unwrap();
        assert_eq!(json, r#""adhoc-visit""#);
        let read: Algorithm = serde_json::from_str(r#""ad-hoc-visit""#).unwrap();
        assert_eq!(read, visit);
        let err = serde_json::from_str::<Algorithm>(r#""best""#).unwrap_err();
        assert!(err.to_string().contains("best"), "{err}");
        let bytes = postcard::to_allocvec(&visit).unwrap();
        assert_eq!(postcard::from_bytes::<Algorithm>(&bytes).unwrap(), visit);
    }
}
