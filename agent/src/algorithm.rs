//! The one vocabulary of advising algorithms, shared by the command line, team
//! and study files and `config.json`.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// An advising algorithm, named in kebab-case (`adhoc-td`) wherever it is
/// written or read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "&'static str")]
pub enum Algorithm {
    /// `no-advice`: SARSA(lambda) alone.
    #[default]
    NoAdvice,
    /// `adhoc-visit`: ad hoc advising with the visit-based confidence.
    AdHocVisit,
    /// `adhoc-td`: ad hoc advising with the TD-based confidence.
    AdHocTd,
    /// `torrey`: importance advising from a fixed teacher.
    Torrey,
    /// `episode-sharing`: Tan's episode sharing after goal episodes.
    EpisodeSharing,
    /// `random`: the random-policy baseline.
    Random,
    /// `early-advising`: ask at every step until the budget is spent (Ilhan
    /// et al.'s baseline).
    EarlyAdvising,
    /// `random-advising`: ask with a fixed probability while the budget
    /// lasts (Ilhan et al.'s baseline).
    RandomAdvising,
    /// `advice-reuse`: AdHocTD whose advisee reuses stored advice (Zhu et
    /// al., JAAMAS 2023).
    AdviceReuse,
    /// `peer-learning`: follow recommendations by trust learned from
    /// outcomes (Derstroff et al., AAAI 2024).
    PeerLearning,
    /// `rcmp`: ask where an ensemble's heads disagree (da Silva et al.,
    /// AAAI 2020).
    Rcmp,
    /// `psaf`: share values instead of actions (Zhu et al., AAMAS 2019).
    Psaf,
    /// `external`: decisions given from outside: a strategy process (a
    /// team file's `strategy_process`) or, in process,
    /// [`Agent::with_strategy`](crate::Agent::with_strategy).
    External,
}

/// An algorithm name that is not one of [`Algorithm::ALL`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown algorithm `{0}` (expected one of: {names})", names = Algorithm::list())]
pub struct UnknownAlgorithm(pub String);

impl Algorithm {
    /// Every algorithm: the paper's, in the order it presents them, then
    /// the field's since.
    pub const ALL: [Algorithm; 13] = [
        Algorithm::NoAdvice,
        Algorithm::AdHocVisit,
        Algorithm::AdHocTd,
        Algorithm::Torrey,
        Algorithm::EpisodeSharing,
        Algorithm::Random,
        Algorithm::EarlyAdvising,
        Algorithm::RandomAdvising,
        Algorithm::AdviceReuse,
        Algorithm::PeerLearning,
        Algorithm::Rcmp,
        Algorithm::Psaf,
        Algorithm::External,
    ];

    /// The name as written on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::NoAdvice => "no-advice",
            Algorithm::AdHocVisit => "adhoc-visit",
            Algorithm::AdHocTd => "adhoc-td",
            Algorithm::Torrey => "torrey",
            Algorithm::EpisodeSharing => "episode-sharing",
            Algorithm::Random => "random",
            Algorithm::EarlyAdvising => "early-advising",
            Algorithm::RandomAdvising => "random-advising",
            Algorithm::AdviceReuse => "advice-reuse",
            Algorithm::PeerLearning => "peer-learning",
            Algorithm::Rcmp => "rcmp",
            Algorithm::Psaf => "psaf",
            Algorithm::External => "external",
        }
    }

    /// Older spellings still accepted when reading (never written).
    pub fn aliases(self) -> &'static [&'static str] {
        match self {
            Algorithm::AdHocVisit => &["ad-hoc-visit"],
            Algorithm::AdHocTd => &["ad-hoc-td"],
            _ => &[],
        }
    }

    /// Whether the algorithm has a Mistake Correcting mode.
    pub fn supports_mistake_correcting(self) -> bool {
        matches!(
            self,
            Algorithm::AdHocVisit | Algorithm::AdHocTd | Algorithm::Torrey
        )
    }

    /// Whether it is one of the two ad hoc methods.
    pub fn is_ad_hoc(self) -> bool {
        matches!(self, Algorithm::AdHocVisit | Algorithm::AdHocTd)
    }

    /// Whether its agents communicate (advice or shared episodes).
    pub fn communicates(self) -> bool {
        !matches!(self, Algorithm::NoAdvice | Algorithm::Random)
    }

    /// Every name, comma-separated (for messages).
    pub fn list() -> String {
        let names: Vec<&str> = Self::ALL.iter().map(|n| n.name()).collect();
        names.join(", ")
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
        Self::ALL
            .into_iter()
            .find(|n| n.name() == s || n.aliases().contains(&s))
            .ok_or_else(|| UnknownAlgorithm(s.to_owned()))
    }
}

impl TryFrom<String> for Algorithm {
    type Error = UnknownAlgorithm;

    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

impl From<Algorithm> for &'static str {
    fn from(name: Algorithm) -> Self {
        name.name()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_aliases_parse_and_display() {
        for name in Algorithm::ALL {
            assert_eq!(name.name().parse::<Algorithm>(), Ok(name));
            assert_eq!(name.to_string(), name.name());
            for alias in name.aliases() {
                assert_eq!(alias.parse::<Algorithm>(), Ok(name));
            }
        }
        assert_eq!("ad-hoc-td".parse::<Algorithm>(), Ok(Algorithm::AdHocTd));
        let e = "best".parse::<Algorithm>().unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown algorithm `best` (expected one of: no-advice, adhoc-visit, adhoc-td, \
             torrey, episode-sharing, random, early-advising, random-advising, advice-reuse, peer-learning, rcmp, psaf, \
             external)"
        );
    }

    #[test]
    fn serde_writes_the_name_and_reads_aliases() {
        let json = serde_json::to_string(&Algorithm::AdHocVisit).unwrap();
        assert_eq!(json, r#""adhoc-visit""#);
        let read: Algorithm = serde_json::from_str(r#""ad-hoc-visit""#).unwrap();
        assert_eq!(read, Algorithm::AdHocVisit);
        let err = serde_json::from_str::<Algorithm>(r#""best""#).unwrap_err();
        assert!(err.to_string().contains("best"), "{err}");
    }
}
