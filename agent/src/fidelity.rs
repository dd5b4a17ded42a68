//! Where the paper's text and the authors' published code disagree, the rule
//! an agent follows: one setting per difference, and two profiles that set
//! them all (docs/fidelity.md gives each item's paper text, authors' code and
//! why).

use std::fmt;

use serde::{Deserialize, Serialize};

/// A coherent set of [`Fidelity`] settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Profile {
    /// The paper's text where it speaks (AdHocVisit's v_g 0.5), our own
    /// rules where it is silent.
    #[default]
    Paper,
    /// What the authors' code (f-leno/AdHoc_AAMAS-17), which made the
    /// published curves, does.
    Authors,
}

impl Profile {
    /// Both profiles.
    pub const ALL: [Profile; 2] = [Profile::Paper, Profile::Authors];

    /// The name as written in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Profile::Paper => "paper",
            Profile::Authors => "authors",
        }
    }

    /// AdHocVisit's default giving scale v_g: 0.5 in the paper, 0.2 in the
    /// authors' runs (docs/fidelity.md, item 4).
    pub fn visit_v_g(self) -> f64 {
        match self {
            Profile::Paper => 0.5,
            Profile::Authors => 0.2,
        }
    }

    /// The default confidence level of intervals and tests: the paper's
    /// captions say 95 %, the authors' processing used 90 %.
    pub fn ci_level(self) -> f64 {
        match self {
            Profile::Paper => 0.95,
            Profile::Authors => 0.90,
        }
    }
}

impl fmt::Display for Profile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Profile {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Profile::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| format!("unknown profile `{s}` (expected paper or authors)"))
    }
}

/// What Torrey's teacher does in a state where it has no entry for any kick
/// action.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TorreyUnknownState {
    /// Its importance counts as 0: no advice.
    Silent,
    /// Its importance is |(-inf) - (+inf)| = inf: it advises its greedy
    /// answer over all-zero values (torrey.py, `state_importance`).
    Advise,
}

/// The intended action a Mistake Correcting Torrey student sends along (and
/// plays when no advice comes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TorreyIntent {
    /// Its epsilon-greedy choice, as the ad hoc advisees.
    EpsilonGreedy,
    /// Its greedy choice (torrey.py: `select_action(..., noAdvice=True)`).
    Greedy,
}

/// How an advisor's answer, its greedy kick action, breaks ties.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AdvisorTies {
    /// The first in Shoot, Dribble, PassFar, PassNear.
    First,
    /// Uniformly at random, as a training agent's greedy choice (sarsa.py).
    Random,
}

/// How the advisee's majority vote over several answers breaks ties.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum VoteTies {
    /// Uniformly at random.
    Random,
    /// PassFar, then Shoot, Dribble, PassNear: the iteration order of the
    /// authors' `max(set(advised), key=advised.count)` (adhoc.py).
    Fixed,
}

/// The next action an EpisodeSharing receiver bootstraps on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SharedBootstrap {
    /// The action the sharer took next.
    SharerAction,
    /// Move: episodesharing.py passes the 6 features where the raw ones are
    /// expected, so the receiver's "next action" is always Move.
    Move,
}

/// One setting per difference between the paper and the authors' code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fidelity {
    /// The profile the settings started from (recorded; the settings below
    /// decide).
    pub profile: Profile,
    /// Torrey's teacher in a state without kick entries.
    pub torrey_unknown_state: TorreyUnknownState,
    /// Torrey's Mistake Correcting intended action.
    pub torrey_intent: TorreyIntent,
    /// Ties in an advisor's answer.
    pub advisor_ties: AdvisorTies,
    /// Ties in the advisee's majority vote.
    pub vote_ties: VoteTies,
    /// EpisodeSharing's bootstrap action.
    pub shared_bootstrap: SharedBootstrap,
}

impl Fidelity {
    /// Every setting as `profile` has it.
    pub fn of(profile: Profile) -> Self {
        match profile {
            Profile::Paper => Self {
                profile,
                torrey_unknown_state: TorreyUnknownState::Silent,
                torrey_intent: TorreyIntent::EpsilonGreedy,
                advisor_ties: AdvisorTies::First,
                vote_ties: VoteTies::Random,
                shared_bootstrap: SharedBootstrap::SharerAction,
            },
            Profile::Authors => Self {
                profile,
                torrey_unknown_state: TorreyUnknownState::Advise,
                torrey_intent: TorreyIntent::Greedy,
                advisor_ties: AdvisorTies::Random,
                vote_ties: VoteTies::Fixed,
                shared_bootstrap: SharedBootstrap::Move,
            },
        }
    }
}

impl Default for Fidelity {
    fn default() -> Self {
        Self::of(Profile::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profiles_differ_in_every_setting() {
        let (p, a) = (Fidelity::of(Profile::Paper), Fidelity::of(Profile::Authors));
        assert_ne!(p.torrey_unknown_state, a.torrey_unknown_state);
        assert_ne!(p.torrey_intent, a.torrey_intent);
        assert_ne!(p.advisor_ties, a.advisor_ties);
        assert_ne!(p.vote_ties, a.vote_ties);
        assert_ne!(p.shared_bootstrap, a.shared_bootstrap);
        assert_eq!(
            (Profile::Paper.visit_v_g(), Profile::Authors.visit_v_g()),
            (0.5, 0.2)
        );
        assert_eq!("authors".parse::<Profile>(), Ok(Profile::Authors));
        assert!(
            "author"
                .parse::<Profile>()
                .unwrap_err()
                .contains("paper or authors")
        );
    }
}
