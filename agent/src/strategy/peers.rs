//! Peer learning (Derstroff et al., "Peer Learning: Learning Complex
//! Policies in Groups from Scratch via Action Recommendations", AAAI 2024;
//! docs/algorithms.md section 7): at a decision every peer recommends an
//! action (sampled from its policy), the agent picks whose to follow (its
//! own choice included) by a softmax over its trust in each, the value
//! each says of itself and its own value of each action, follows that peer
//! for a few decisions, and learns its trust from the advantage of what it
//! played.

use rand::Rng;
use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Outcome, Replies};
use super::trust::Trust;
use crate::advice::{Reachable, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::config_error::{AgentConfigError, require, require_unit};
use crate::exchange::Advice;
use crate::fidelity::{Fidelity, Profile, VoteTies};
use crate::method::Method;
use crate::selection::AgentRng;

/// The settings of peer learning (Derstroff et al., AAAI 2024, as its
/// code kramerlab/PeerLearning runs it: `run_peer.py` with the flags of the
/// paper's runs): whom to follow, among the peers' suggestions and its own
/// choice, by trust, the peers' own values and the critic's value of each.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeerLearning {
    /// Advisee budget: steps acted on a peer's suggestion (default none:
    /// the paper's runs have no budget).
    pub ask_budget: Option<u64>,
    /// Advisor budget: suggestions given (default none).
    pub give_budget: Option<u64>,
    /// The peers asked (default everyone).
    pub reachable: Reachable,
    /// The softmax temperature T of the choice among the candidates,
    /// finite and > 0 (default 1, the paper's).
    pub temperature: f64,
    /// The learning rate of trust, in [0, 1] (default 0.001, the paper's).
    pub trust_lr: f64,
    /// Decisions a chosen peer (or its own choice) is followed for, at
    /// least 1 (default 10, the paper's).
    pub follow_steps: u32,
    /// Weigh each candidate by the agent's own value of its action,
    /// Q(s, a) (the paper's critic, `--use-critic`; default on).
    pub use_critic: bool,
    /// Weigh each candidate by what it says of itself, its trust in its
    /// own choices (the paper's agent value, `--use-agent-value`; default
    /// on).
    pub use_agent_value: bool,
    /// Peers suggest their exploring choice, sampled from their policy
    /// (`--peers-sample-with-noise`; default on); off, their greedy action.
    pub sample_suggestions: bool,
}

impl Default for PeerLearning {
    fn default() -> Self {
        Self {
            ask_budget: None,
            give_budget: None,
            reachable: Reachable::Everyone,
            temperature: 1.0,
            trust_lr: 0.001,
            follow_steps: 10,
            use_critic: true,
            use_agent_value: true,
            sample_suggestions: true,
        }
    }
}

/// `peer-learning`: follow suggestions by trust, value and critic.
pub(crate) struct PeerLearningMethod;

impl Method for PeerLearningMethod {
    type Settings = PeerLearning;
    const NAME: &'static str = "peer-learning";
    const ABOUT: &'static str = "follow the suggestions of peers by trust learned from outcomes (Derstroff et al., AAAI 2024)";

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

    /// Chooses among its own choice and the suggestions: each candidate's
    /// score is the sum of its trust, its agent value (what it says of
    /// itself) and the critic's value of its action, each term divided by
    /// its largest magnitude among the candidates (the code's
    /// normalisation); the candidate is drawn from e^(score / T). Without
    /// its own choice (no critic), the terms it has.
    fn choose(&self, replies: &Replies<'_>, rng: &mut AgentRng) -> Option<Advice> {
        let s = &self.settings;
        let advice = replies.advice;
        let said = |advisor: usize| {
            (replies.advisor_values.iter())
                .find(|(j, _)| *j == advisor)
                .map_or(0.0, |(_, v)| *v)
        };
        // Candidate 0 is its own choice, then the suggestions in order.
        let mut terms: Vec<Vec<f64>> = vec![
            std::iter::once(self.trust.own())
                .chain(advice.iter().map(|a| self.trust.of(a.advisor)))
                .collect(),
        ];
        if s.use_agent_value {
            terms.push(
                std::iter::once(self.trust.own())
                    .chain(advice.iter().map(|a| said(a.advisor)))
                    .collect(),
            );
        }
        if let (true, Some(own)) = (s.use_critic, replies.own) {
            terms.push(
                std::iter::once(own.action)
                    .chain(advice.iter().map(|a| a.action))
                    .map(|action| own.values.q[action.index()])
                    .collect(),
            );
        }
        let scores: Vec<f64> = (0..=advice.len())
            .map(|k| terms.iter().map(|t| normalised(t)[k]).sum())
            .collect();
        let top = scores.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let weights: Vec<f64> = (scores.iter())
            .map(|x| ((x - top) / s.temperature).exp())
            .collect();
        let total: f64 = weights.iter().sum();
        let mut draw = rng.random::<f64>() * total;
        for (k, w) in weights.iter().enumerate() {
            draw -= w;
            if draw < 0.0 {
                return k.checked_sub(1).map(|k| advice[k]);
            }
        }
        advice.last().copied()
    }
}

/// `values` each divided by their largest magnitude (as they are when all
/// are 0).
fn normalised(values: &[f64]) -> Vec<f64> {
    let scale = values.iter().map(|v| v.abs()).fold(0.0, f64::max);
    values
        .iter()
        .map(|v| if scale > 0.0 { v / scale } else { *v })
        .collect()
}

impl AdvisingStrategy for Peers {
    /// With ask budget left, unless it is following its own choice.
    fn asks(&mut self, at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        if self
            .settings
            .ask_budget
            .is_some_and(|b| at.counters.ask_spent >= b)
        {
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

    /// Every request, while the give budget (if any) lasts: a peer always
    /// suggests.
    /// A followed peer that cannot be asked is followed no more: the next
    /// request goes to the others.
    fn advisors_unreachable(&mut self) {
        if matches!(self.following, Following::Peer { .. }) {
            self.following = Following::Nobody;
        }
    }

    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        self.settings
            .give_budget
            .is_none_or(|b| at.counters.advice_given < b)
    }

    fn suggests_its_choice(&self) -> bool {
        self.settings.sample_suggestions
    }

    /// Its trust in its own choices: what it says of itself.
    fn advisor_value(&self) -> Option<f64> {
        self.settings.use_agent_value.then(|| self.trust.own())
    }

    fn weighs_own_choice(&self) -> bool {
        self.settings.use_critic
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
        let chosen = self.choose(replies, rng);
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
        self.settings
            .give_budget
            .is_some_and(|b| counters.advice_given >= b)
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strategy::OwnChoice;
    use proto::Action::{Dribble, Shoot};
    use rand::SeedableRng;

    fn replies(advice: &[Advice]) -> Replies<'_> {
        Replies {
            key: 1,
            advice,
            ..Replies::default()
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
        assert!(
            peers.trust.of(1) > 0.9 && peers.trust.of(2) < -0.9,
            "{peers:?}"
        );
        // Softmax at temperature 1 over trust scaled to [-1, 1]: e^1 : e^0 :
        // e^-1, so advisor 1 is followed about two times in three.
        assert!(
            followed[1] > 600 && followed[1] > 5 * followed[2],
            "{followed:?}"
        );
    }

    #[test]
    fn a_followed_peer_that_cannot_be_asked_is_followed_no_more() {
        let mut peers = Peers::new(PeerLearning::default());
        peers.following = Following::Peer {
            advisor: 1,
            left: 5,
        };
        peers.advisors_unreachable();
        let mut out = Vec::new();
        peers.advisors(0, 3, &[], &mut out);
        assert_eq!(out, vec![1, 2], "the whole team again");
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

    #[test]
    fn the_critic_prefers_the_suggestion_it_values_most() {
        let settings = PeerLearning {
            temperature: 0.01,
            ..PeerLearning::default()
        };
        let mut peers = Peers::new(settings);
        let mut rng = AgentRng::seed_from_u64(3);
        let (good, bad) = (
            Advice {
                advisor: 1,
                action: Shoot,
            },
            Advice {
                advisor: 2,
                action: Dribble,
            },
        );
        let mut values = crate::learner::ActionValues::default();
        values.q[Shoot.index()] = 1.0;
        values.q[Dribble.index()] = -1.0;
        let own = OwnChoice {
            action: proto::Action::PassNear,
            values,
        };
        let advice = [bad, good];
        let mut asked = replies(&advice);
        asked.own = Some(own);
        for _ in 0..20 {
            assert_eq!(peers.choose(&asked, &mut rng), Some(good));
        }
        // What a peer says of itself weighs too: the bad one claims much.
        let said = [(2, 5.0), (1, -5.0)];
        asked.advisor_values = &said;
        assert!(peers.weighs_own_choice() && peers.suggests_its_choice());
        peers.settings.use_critic = false;
        assert_eq!(peers.choose(&asked, &mut rng), Some(bad));
    }
}
