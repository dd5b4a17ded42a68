//! A study's runs split among processes: `--shard K/N`.

use std::fmt;
use std::str::FromStr;

/// One of `N` shares of a study's runs (`K/N`, `K` from 1 to `N`): counting
/// the runs of the study entry by entry, run by run, from 0, the runs whose
/// position is `K - 1` modulo `N`. Shares never overlap and together cover
/// every run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    k: u64,
    n: u64,
}

/// The most shards a study may be split into.
pub const MAX_SHARDS: u64 = 100_000;

impl Shard {
    /// Whether run `run` of the experiment whose first run is at position
    /// `first` in the study belongs to this share.
    pub fn owns(&self, first: u64, run: u64) -> bool {
        (first + run) % self.n == self.k - 1
    }

    /// Whether this is the first share (the one that pretrains).
    pub fn is_first(&self) -> bool {
        self.k == 1
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl FromStr for Shard {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || {
            format!("'{s}' is not a shard: expected K/N with 1 <= K <= N <= {MAX_SHARDS}, e.g. 2/8")
        };
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (k, n): (u64, u64) = (k.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?);
        if k == 0 || k > n || n > MAX_SHARDS {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_cover_every_run_once() {
        let shards: Vec<Shard> = (1..=3).map(|k| format!("{k}/3").parse().unwrap()).collect();
        for first in [0, 5, 10] {
            for run in 0..5 {
                let owners = shards.iter().filter(|s| s.owns(first, run)).count();
                assert_eq!(owners, 1, "run {run} of the entry starting at {first}");
            }
        }
        assert_eq!(shards[1].to_string(), "2/3");
        assert!(shards[0].is_first() && !shards[2].is_first());
    }

    #[test]
    fn bad_shards_are_refused() {
        for bad in ["0/3", "4/3", "3", "a/b", "1/0", "-1/2", "1/100001", ""] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert!(e.contains("expected K/N"), "{bad}: {e}");
        }
        assert_eq!("1/1".parse::<Shard>().unwrap().to_string(), "1/1");
    }
}
