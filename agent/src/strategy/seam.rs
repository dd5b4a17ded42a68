//! The seam between the advising framework and an advising method: the
//! decisions a method makes ([`AdvisingStrategy`]) and what each sees.

use std::fmt;

use proto::{Action, EpisodeOutcome, Mode, SharedValues, State};

use crate::advice_counters::AdviceCounters;
use crate::exchange::{Advice, Batch, BestValue, Share, Transition, ValuesAdvice};
use crate::fidelity::{AdvisorTies, VoteTies};
use crate::learner::ActionValues;
use crate::selection::{ACTIONS, AgentRng, greedy_first, greedy_random, majority};

/// What an advisee knows when it decides whether to ask about a state.
#[derive(Clone, Copy, Debug)]
pub struct AskContext<'a> {
    /// The state: the paper's features.
    pub state: &'a State,
    /// HFO's features of it, where its observations carry them (empty
    /// otherwise).
    pub features: &'a [f32],
    /// The state was not advised yet in this episode.
    pub fresh: bool,
    /// Visits n(s) of the state.
    pub visits: u64,
    /// Training episodes finished so far.
    pub training_episodes: u64,
    /// The agent's counters.
    pub counters: &'a AdviceCounters,
    /// Its learner's uncertainty in the state, for a method that
    /// [`asks_by_uncertainty`](AdvisingStrategy::asks_by_uncertainty)
    /// (`None` otherwise, or from a learner that cannot tell).
    pub uncertainty: Option<f64>,
    /// Its learner's values in the state, for a method that
    /// [`asks_by_values`](AdvisingStrategy::asks_by_values) (`None`
    /// otherwise).
    pub values: Option<ActionValues>,
}

/// What an advisee knows at a training step with the ball, before it
/// decides whether to ask: where it is and how far it got.
#[derive(Clone, Copy, Debug)]
pub struct ReuseContext<'a> {
    /// The key of the state (the tile-coded state).
    pub key: u64,
    /// The state: the paper's features.
    pub state: &'a State,
    /// HFO's features of it, where its observations carry them (empty
    /// otherwise).
    pub features: &'a [f32],
    /// Training episodes finished so far.
    pub training_episodes: u64,
    /// The agent's counters.
    pub counters: &'a AdviceCounters,
}

/// What an advisor knows when it decides whether to answer.
#[derive(Clone, Copy, Debug)]
pub struct GiveContext<'a> {
    /// The asker's id.
    pub asker: usize,
    /// The asker's state: the paper's features.
    pub state: &'a State,
    /// HFO's features of it, where the request carries them (empty
    /// otherwise).
    pub features: &'a [f32],
    /// Its visits n(s) of the advisee's state (0 for a state it never met).
    pub visits: u64,
    /// How often it took each action there, m(s, a) by action index.
    pub action_visits: [u32; ACTIONS],
    /// Its learner's values there (all unlearned for a state it never met).
    pub values: &'a ActionValues,
    /// The asker's m(s, a), where its request carries them (a strategy
    /// that [`shares_best`](AdvisingStrategy::shares_best)).
    pub asker_visits: Option<[u32; ACTIONS]>,
    /// Its counters.
    pub counters: &'a AdviceCounters,
}

/// What an agent knows when an episode ends.
#[derive(Clone, Copy, Debug)]
pub struct EndContext<'a> {
    /// The reward of its terminal step (+1 goal, -1 captured or out, 0
    /// time-out).
    pub final_reward: f64,
    /// How the episode ended.
    pub outcome: EpisodeOutcome,
    /// The episode's return: the sum of the rewards the agent was given,
    /// one per frame after the first, and `final_reward` (undiscounted; a
    /// DQN folds the same rewards from kick to kick, discounted).
    pub episode_return: f64,
    /// The agent's id.
    pub me: usize,
    /// Its team's size.
    pub team_size: usize,
    /// Its counters.
    pub counters: &'a AdviceCounters,
}

/// What an agent sends its teammates unasked at an episode's end: for each
/// receiver, in order, what it sends.
pub type Sends = Vec<(usize, Share)>;

/// What arrived for one request: the advice (any number, possibly none,
/// in the order of the advisors asked) about the state of key `key`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Replies<'a> {
    /// The key of the state asked about (the tile-coded state).
    pub key: u64,
    /// The advice that arrived, with who gave it.
    pub advice: &'a [Advice],
    /// The values shared, with who shared them.
    pub values: &'a [ValuesAdvice],
    /// The best values shared, with who shared them.
    pub best: &'a [BestValue],
    /// What the advisors that recommended said of themselves, by advisor.
    pub advisor_values: &'a [(usize, f64)],
    /// The agent's own choice and its values in the state, for a strategy
    /// that [`weighs_own_choice`](AdvisingStrategy::weighs_own_choice).
    pub own: Option<OwnChoice>,
}

/// Shared values an advisee takes into its learner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Adopted {
    /// A sharer's whole row: its values replace the advisee's.
    Row(SharedValues),
    /// A sharer's best action and its value: it replaces the advisee's value
    /// of that action, and the advisee then plays greedily (PSAF).
    Best {
        /// The action.
        action: Action,
        /// Its value.
        value: f64,
    },
}

/// An agent's own choice in a state and its values there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OwnChoice {
    /// The action it would play (its learner's exploring choice).
    pub action: Action,
    /// Its values in the state.
    pub values: ActionValues,
}

impl Replies<'_> {
    /// The first piece of advice of `action`.
    pub fn from_whom(&self, action: Action) -> Option<Advice> {
        self.advice.iter().find(|a| a.action == action).copied()
    }
}

impl GiveContext<'_> {
    /// Whether it visited the state and has answers left of `give_budget`:
    /// the rule of the methods whose advisors answer whatever they know.
    pub fn visited_within(&self, give_budget: u64) -> bool {
        self.counters.advice_given < give_budget && self.visits > 0
    }
}

/// How a training decision with the ball turned out, once learned from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    /// The advisor whose advice was played, `None` for its own choice.
    pub advisor: Option<usize>,
    /// Its advantage under the values just learned: r + gamma V(s') - V(s),
    /// V a state's best learned kick action's value where the agent chose
    /// (its action's where it could only move; V(s') is 0 at the episode's
    /// end).
    pub advantage: f64,
}

/// The decisions of an advising method, made for one agent. Every random
/// draw comes from the agent's generator, in the order the calls happen, so
/// a method is as reproducible as the framework around it.
pub trait AdvisingStrategy: fmt::Debug + Send {
    /// Whether the agent learns (every method but the random baseline).
    fn learns(&self) -> bool {
        true
    }

    /// Advisee: an action to play without asking at a training step with
    /// the ball, `at` (advice it stored, or imitated, and reuses);
    /// `values()` asks its learner for its values there, only if needed;
    /// `None` goes on to [`asks`](Self::asks).
    fn reuse(
        &mut self,
        _at: &ReuseContext<'_>,
        _values: &mut dyn FnMut() -> ActionValues,
        _rng: &mut AgentRng,
    ) -> Option<Action> {
        None
    }

    /// Whether [`asks`](Self::asks) needs its learner's uncertainty.
    fn asks_by_uncertainty(&self) -> bool {
        false
    }

    /// Whether [`asks`](Self::asks) needs its learner's values
    /// ([`AskContext::values`]); asking the learner costs time.
    fn asks_by_values(&self) -> bool {
        false
    }

    /// Advisee: whether a training step with the ball asks for advice.
    /// Never, by default.
    fn asks(&mut self, _at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        false
    }

    /// Advisee: fills `out` with whom agent `me` of a team of `team_size`
    /// asks (`positions`: every agent's field position by id); the framework
    /// then leaves out whoever is not reachable now. Nobody, by default.
    fn advisors(&self, _me: usize, _n: usize, _positions: &[[f64; 2]], out: &mut Vec<usize>) {
        out.clear();
    }

    /// Advisee: none of the advisors it named can be asked now (out of
    /// reach, or their give budgets announced spent). Nothing, by default.
    fn advisors_unreachable(&mut self) {}

    /// Whether it runs in Mistake Correcting mode: the advisee sends its
    /// intended action along and advisors answer only when they disagree.
    fn mistake_correcting(&self) -> bool {
        false
    }

    /// Whether a Mistake Correcting advisee's intended action is its
    /// learner's greedy action (else its learner's own choice).
    fn intends_greedy(&self) -> bool {
        false
    }

    /// Advisor: whether it answers with its values of the state (a
    /// value-sharing method) instead of an action.
    fn shares_values(&self) -> bool {
        false
    }

    /// Sharer: whether it shares only its best action and that action's
    /// value (PSAF) rather than all its values of the state; its requests
    /// then carry its visits by action. No, by default.
    fn shares_best(&self) -> bool {
        false
    }

    /// Advisee: the shared values it takes into its learner for the state
    /// asked about, where it visited the state `visits` times; none by
    /// default.
    fn adopt(&mut self, _replies: &Replies<'_>, _visits: u64) -> Option<Adopted> {
        None
    }

    /// Advisor: whether it answers about a state.
    /// Never, by default.
    fn gives(&mut self, _at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        false
    }

    /// Advisor: whether it recommends its learner's own exploring choice
    /// (peer learning's suggestion, sampled from its policy) rather than
    /// [`advice`](Self::advice). No, by default.
    fn suggests_its_choice(&self) -> bool {
        false
    }

    /// Advisor: what it says of itself with each recommendation (peer
    /// learning's value of an agent); none by default.
    fn advisor_value(&self) -> Option<f64> {
        None
    }

    /// Advisee: whether [`follow`](Self::follow) weighs its own choice and
    /// values ([`Replies::own`]); the framework then draws its choice first
    /// and plays it when no advice is followed.
    fn weighs_own_choice(&self) -> bool {
        false
    }

    /// Advisor: the action it advises where its learner holds `values`:
    /// its greedy action, ties broken as `ties` says.
    fn advice(&mut self, values: &ActionValues, ties: AdvisorTies, rng: &mut AgentRng) -> Action {
        match ties {
            AdvisorTies::First => greedy_first(&values.q),
            AdvisorTies::Random => greedy_random(&values.q, rng),
        }
    }

    /// Advisee: the advice it follows given what arrived for its request:
    /// the majority vote, ties broken as `ties` says (credited to the first
    /// advisor who gave it); `None` plays its own choice.
    fn follow(
        &mut self,
        replies: &Replies<'_>,
        ties: VoteTies,
        rng: &mut AgentRng,
    ) -> Option<Advice> {
        let vote = majority(replies.advice.iter().map(|a| a.action), ties, rng)?;
        replies.from_whom(vote)
    }

    /// Whether it learns about its advisors from outcomes (then the agent
    /// computes each decision's [`Outcome`]; asking its learner costs time).
    fn learns_from_outcomes(&self) -> bool {
        false
    }

    /// What it learns about its advisors from how a decision turned out.
    fn learn_outcome(&mut self, _outcome: &Outcome) {}

    /// Advisee: whether it tells each advisor whose advice arrived how the
    /// decision turned out (one message per advisor and decision, received
    /// by its [`advice_outcome`](Self::advice_outcome)). No, by default.
    fn reports_advice_outcomes(&self) -> bool {
        false
    }

    /// Advisor: `asker` reports a decision on which it gave advice:
    /// whether it played the action advised, and the decision's advantage
    /// under the asker's values (as [`Outcome::advantage`]).
    fn advice_outcome(&mut self, _asker: usize, _followed: bool, _advantage: f64) {}

    /// The budget the paper plots (advice given, or transitions shared).
    fn spent_budget(&self, counters: &AdviceCounters) -> u64;

    /// Advisor: whether its give budget is spent, so that it answers no
    /// more (its replies say so, and with `announce_exhausted` it tells
    /// everyone once). Never, by default.
    fn exhausted(&self, _counters: &AdviceCounters) -> bool {
        false
    }

    /// An episode in `mode` begins (the previous one may have been
    /// abandoned).
    fn begin_episode(&mut self, _mode: Mode) {}

    /// Whether it wants the transitions its agent learns now (then
    /// [`learned`](Self::learned) receives each). No, by default.
    fn records_transitions(&self, _counters: &AdviceCounters) -> bool {
        false
    }

    /// A training transition its agent just learned.
    fn learned(&mut self, _transition: &Transition) {}

    /// A training episode ended, its last step learned: what the agent
    /// sends its teammates unasked (shared episodes, batches of
    /// experience), counted as transitions shared. Nothing, by default.
    fn end_episode(&mut self, _end: &EndContext<'_>) -> Sends {
        Sends::new()
    }

    /// An evaluation episode ended (frozen: nothing is sent).
    fn end_evaluation(&mut self, _end: &EndContext<'_>) {}

    /// A batch of experience arrived from agent `from`, in a training
    /// episode's end: what its learner learns of it as one batch, if it
    /// can. `None` (by default): the batch's transitions as they came.
    fn received(&mut self, _from: usize, _batch: &Batch) -> Option<Vec<Transition>> {
        None
    }
}
