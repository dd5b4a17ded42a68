//! Peer learning (Derstroff et al., "Peer Learning: Learning Complex
//! Policies in Groups from Scratch via Action Recommendations", AAAI 2024;
//! docs/algorithms.md section 7): at a decision every peer recommends an
//! action, the agent picks whose recommendation to follow (its own
//! included) by a softmax over its trust in each, follows that peer for a
//! few decisions, and learns its trust from the advantage of what it played.

use rand::Rng;
use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Outcome, Replies};
use super::trust::Trust;
use crate::advice::{PAPER_BUDGET, Reachable, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require, require_unit};
use crate::exchange::Advice;
use crate::fidelity::{Fidelity, Profile, VoteTies};
use crate::method::Method;
use crate::selection::AgentRng;

/// The settings of peer learning (Derstroff et al., AAAI 2024): whom to
/// follow by trust learned from outcomes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeerLearning {
    /// Advisee budget: steps acted on a peer's recommendation (default 1000).
    pub ask_budget: u64,
    /// Advisor budget: recommendations given (default 1000).
    pub give_budget: u64,
    /// The peers asked (default everyone).
    pub reachable: Reachable,
    /// The softmax temperature T of the choice among recommendations,
    /// finite and > 0 (default 1, the paper's).
    pub temperature: f64,
    /// The learning rate of trust, in [0, 1] (default 0.001, the paper's).
    pub trust_lr: f64,
    /// Decisions a chosen peer (or its own choice) is followed for, at
    /// least 1 (default 10, the paper's).
    pub follow_steps: u32,
}

impl Default for PeerLearning {
    fn default() -> Self {
        Self {
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
            temperature: 1.0,
            trust_lr: 0.001,
            follow_steps: 10,
        }
    }
}

/// `peer-learning`: follow recommendations by trust learned from outcomes.
pub(crate) struct PeerLearningMethod;

impl Method for PeerLearningMethod {
    type Settings = PeerLearning;
    const NAME: &'static str = "peer-learning";
    const ABOUT: &'static str =
        "follow recommendations by trust learned from outcomes (Derstroff et al., AAAI 2024)";

    fn defaults(_: Profile) -> PeerLearning {
        PeerLearning::default()
    }

    fn validate(p: &PeerLearning) -> Result<(), AgentConfigError> {
        require(
            "temperature",
            p.temperature,
            "finite and > 0",
            p.temperature > 0.0,
        )?;
        require_unit("trust_lr", p.trust_lr)?;
        if p.follow_steps == 0 {
            return Err(AgentConfigError::new("follow_steps", "must be at least 1"));
        }
        p.reachable.validate()
    }

    fn strategy(settings: &PeerLearning, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Peers::new(settings.clone()))
    }
}

/// Whom the agent follows, and for how many more decisions.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Following {
    /// Nobody: the next decision asks every peer and chooses anew.
    Nobody,
    /// Its own choice.
    Itself { left: u32 },
    /// The advisor `advisor`, asked alone.
    Peer { advisor: usize, left: u32 },
}

/// Peer learning for one agent: its settings, trust and current choice.
#[derive(Clone, Debug)]
struct Peers {
    settings: PeerLearning,
    trust: Trust,
    following: Following,
}

impl Peers {
    pub fn new(settings: PeerLearning) -> Self {
        Self {
            settings,
            trust: Trust::default(),
            following: Following::Nobody,
        }
    }

    /// Its trust in `advisor` (0 for one never followed).
    pub fn trust(&self, advisor: usize) -> f64 {
        self.trust.of(advisor)
    }

    /// Chooses among its own choice (`None`) and the `advice`, by a softmax
    /// of their trust (scaled by the largest magnitude) over the temperature.
    fn choose(&self, advice: &[Advice], rng: &mut AgentRng) -> Option<Advice> {
        let weight = self.trust.weigh(advice, self.settings.temperature);
        let own = weight(self.trust.own());
        let total = own
            + advice
                .iter()
                .map(|a| weight(self.trust(a.advisor)))
                .sum::<f64>();
        let mut draw = rng.random::<f64>() * total - own;
        if draw < 0.0 {
            return None;
        }
        for a in advice {
            draw -= weight(self.trust(a.advisor));
            if draw < 0.0 {
                return Some(*a);
            }
        }
        advice.last().copied()
    }
}

impl AdvisingStrategy for Peers {
    /// With ask budget left, unless it is following its own choice.
    fn asks(&mut self, at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        if at.counters.ask_spent >= self.settings.ask_budget {
            self.following = Following::Nobody;
            return false;
        }
        match self.following {
            Following::Itself { left } => {
                self.following = match left {
                    0 | 1 => Following::Nobody,
                    _ => Following::Itself { left: left - 1 },
                };
                false
            }
            _ => true,
        }
    }

    /// The peer it follows, else its reachable set.
    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        match self.following {
            Following::Peer { advisor, .. } => {
                out.clear();
                out.push(advisor);
            }
            _ => reachable_set(&self.settings.reachable, me, team_size, positions, out),
        }
    }

    /// Every request about a visited state, while the give budget lasts.
    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        at.visited_within(self.settings.give_budget)
    }

    /// The followed peer's advice while it lasts and arrives; else a new
    /// choice among the recommendations and its own, followed for
    /// `follow_steps` decisions.
    fn follow(
        &mut self,
        replies: &Replies<'_>,
        _ties: VoteTies,
        rng: &mut AgentRng,
    ) -> Option<Advice> {
        if let Following::Peer { advisor, left } = self.following
            && let Some(advice) = replies.advice.iter().find(|a| a.advisor == advisor)
        {
            self.following = match left {
                0 | 1 => Following::Nobody,
                _ => Following::Peer {
                    advisor,
                    left: left - 1,
                },
            };
            return Some(*advice);
        }
        let left = self.settings.follow_steps.saturating_sub(1);
        let chosen = self.choose(replies.advice, rng);
        self.following = match (chosen, left) {
            (_, 0) => Following::Nobody,
            (None, left) => Following::Itself { left },
            (Some(a), left) => Following::Peer {
                advisor: a.advisor,
                left,
            },
        };
        chosen
    }

    fn learns_from_outcomes(&self) -> bool {
        true
    }

    /// Moves the trust in whoever it followed towards the advantage.
    fn learn_outcome(&mut self, outcome: &Outcome) {
        self.trust.learn(outcome, self.settings.trust_lr);
    }

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        counters.advice_given >= self.settings.give_budget
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proto::Action::{Dribble, Shoot};
    use rand::SeedableRng;

    fn replies(advice: &[Advice]) -> Replies<'_> {
        Replies {
            key: 1,
            advice,
            values: &[],
        }
    }

    #[test]
    fn trust_moves_towards_the_better_advisor() {
        let settings = PeerLearning {
            trust_lr: 0.05,
            follow_steps: 1,
            ..PeerLearning::default()
        };
        let mut peers = Peers::new(settings);
        let mut rng = AgentRng::seed_from_u64(5);
        let advice = [
            Advice {
                advisor: 1,
                action: Shoot,
            },
            Advice {
                advisor: 2,
                action: Dribble,
            },
        ];
        let mut followed = [0usize; 3];
        for round in 0..2000 {
            let chosen = peers.follow(&replies(&advice), VoteTies::Random, &mut rng);
            let advisor = chosen.map(|a| a.advisor);
            // Following advisor 1 pays, advisor 2 costs, its own is neutral.
            let advantage = match advisor {
                Some(1) => 1.0,
                Some(_) => -1.0,
                None => 0.0,
            };
            peers.learn_outcome(&Outcome { advisor, advantage });
            if round >= 1000 {
                followed[advisor.unwrap_or(0)] += 1;
            }
        }
        assert!(peers.trust(1) > 0.9 && peers.trust(2) < -0.9, "{peers:?}");
        // Softmax at temperature 1 over trust scaled to [-1, 1]: e^1 : e^0 :
        // e^-1, so advisor 1 is followed about two times in three.
        assert!(
            followed[1] > 600 && followed[1] > 5 * followed[2],
            "{followed:?}"
        );
    }

    #[test]
    fn a_chosen_peer_is_followed_for_its_steps_then_chosen_anew() {
        let settings = PeerLearning {
            follow_steps: 3,
            ..PeerLearning::default()
        };
        let mut peers = Peers::new(settings);
        peers.trust = Trust::set(vec![0.0, 1.0, -1.0], -1.0);
        let mut rng = AgentRng::seed_from_u64(1);
        let one = Advice {
            advisor: 1,
            action: Shoot,
        };
        let two = Advice {
            advisor: 2,
            action: Dribble,
        };
        // Find a draw that picks advisor 1, then it is asked alone twice.
        while peers.follow(&replies(&[one, two]), VoteTies::Random, &mut rng) != Some(one) {}
        let mut out = Vec::new();
        peers.advisors(0, 3, &[], &mut out);
        assert_eq!(out, vec![1]);
        assert_eq!(
            peers.follow(&replies(&[one]), VoteTies::Random, &mut rng),
            Some(one)
        );
        assert_eq!(
            peers.follow(&replies(&[one]), VoteTies::Random, &mut rng),
            Some(one)
        );
        peers.advisors(0, 3, &[], &mut out);
        assert_eq!(out, vec![1, 2], "chosen anew among everyone");
    }
}
