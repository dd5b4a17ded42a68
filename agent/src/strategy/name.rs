//! The one vocabulary of strategy names, shared by the command line, team and
//! study files and `config.json`.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// The name of a strategy, spelled in kebab-case (`adhoc-td`) wherever it is
/// written or read.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "&'static str")]
pub enum StrategyName {
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
}

/// A strategy name that is not one of [`StrategyName::ALL`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown strategy `{0}` (expected one of: {names})", names = StrategyName::list())]
pub struct UnknownStrategy(pub String);

impl StrategyName {
    /// Every strategy, in the order the paper presents them.
    pub const ALL: [StrategyName; 6] = [
        StrategyName::NoAdvice,
        StrategyName::AdHocVisit,
        StrategyName::AdHocTd,
        StrategyName::Torrey,
        StrategyName::EpisodeSharing,
        StrategyName::Random,
    ];

    /// The name as written on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            StrategyName::NoAdvice => "no-advice",
            StrategyName::AdHocVisit => "adhoc-visit",
            StrategyName::AdHocTd => "adhoc-td",
            StrategyName::Torrey => "torrey",
            StrategyName::EpisodeSharing => "episode-sharing",
            StrategyName::Random => "random",
        }
    }

    /// Older spellings still accepted when reading (never written).
    pub fn aliases(self) -> &'static [&'static str] {
        match self {
            StrategyName::AdHocVisit => &["ad-hoc-visit"],
            StrategyName::AdHocTd => &["ad-hoc-td"],
            _ => &[],
        }
    }

    /// Whether the strategy has a Mistake Correcting mode.
    pub fn supports_mistake_correcting(self) -> bool {
        matches!(
            self,
            StrategyName::AdHocVisit | StrategyName::AdHocTd | StrategyName::Torrey
        )
    }

    /// Whether it is one of the two ad hoc methods.
    pub fn is_ad_hoc(self) -> bool {
        matches!(self, StrategyName::AdHocVisit | StrategyName::AdHocTd)
    }

    /// Whether its agents communicate (advice or shared episodes).
    pub fn communicates(self) -> bool {
        !matches!(self, StrategyName::NoAdvice | StrategyName::Random)
    }

    /// Every name, comma-separated (for messages).
    pub fn list() -> String {
        let names: Vec<&str> = Self::ALL.iter().map(|n| n.name()).collect();
        names.join(", ")
    }
}

impl fmt::Display for StrategyName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for StrategyName {
    type Err = UnknownStrategy;

    /// A name or one of its aliases.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|n| n.name() == s || n.aliases().contains(&s))
            .ok_or_else(|| UnknownStrategy(s.to_owned()))
    }
}

impl TryFrom<String> for StrategyName {
    type Error = UnknownStrategy;

    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

impl From<StrategyName> for &'static str {
    fn from(name: StrategyName) -> Self {
        name.name()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_aliases_parse_and_display() {
        for name in StrategyName::ALL {
            assert_eq!(name.name().parse::<StrategyName>(), Ok(name));
            assert_eq!(name.to_string(), name.name());
            for alias in name.aliases() {
                assert_eq!(alias.parse::<StrategyName>(), Ok(name));
            }
        }
        assert_eq!(
            "ad-hoc-td".parse::<StrategyName>(),
            Ok(StrategyName::AdHocTd)
        );
        let e = "best".parse::<StrategyName>().unwrap_err().to_string();
        assert_eq!(
            e,
            "unknown strategy `best` (expected one of: no-advice, adhoc-visit, adhoc-td, \
             torrey, episode-sharing, random)"
        );
    }

    #[test]
    fn serde_writes_the_name_and_reads_aliases() {
        let json = serde_json::to_string(&StrategyName::AdHocVisit).unwrap();
        assert_eq!(json, r#""adhoc-visit""#);
        let read: StrategyName = serde_json::from_str(r#""ad-hoc-visit""#).unwrap();
        assert_eq!(read, StrategyName::AdHocVisit);
        let err = serde_json::from_str::<StrategyName>(r#""best""#).unwrap_err();
        assert!(err.to_string().contains("best"), "{err}");
    }
}
