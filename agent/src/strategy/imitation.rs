//! Advice imitation and reuse (AIR; Ilhan, Gow & Perez-Liebana, "Learning
//! on a Budget via Teacher Imitation", arXiv 2104.08440, and its AR
//! "Action Advising with Advice Imitation in Deep Reinforcement Learning",
//! arXiv 2104.08441; docs/algorithms.md section 7): an agent imitates the
//! advice it collected with a behavioural-cloning network
//! ([`Cloning`]) and, where that network's Monte Carlo dropout uncertainty
//! is low, plays the imitated action instead of its own, at no cost of
//! budget. Facts from the authors' code, github:ercumentilhan/
//! advice-imitation-reuse at `0e46155` (`code/executor.py`), and the later
//! framework of the same author, github:ercumentilhan/deep-rl-action-advising
//! at `81f272e` (`code/constants/config_sets/ale.py`), as research-57 §2
//! read them:
//!
//! - collection (`executor.py` l.228-257): `uncertainty` (AIR) asks at every
//!   training step with the ball until the first imitation, then where the
//!   cloning network's uncertainty is above its threshold; `early` (AR) at
//!   every one; both while the ask budget lasts. A sample is the agent's
//!   observation (what its DQN reads) and the advised kick it played;
//! - imitation (l.264-303): a round when `period_samples` new samples
//!   arrived, or after `period_steps` steps with at least half as many;
//!   its iterations `initial` for the first round and for the round that
//!   holds the whole budget, `periodic` otherwise; the threshold autoset
//!   (the 90th percentile, l.595-651) after every round. The published
//!   config leaves the period at 0 (a round every step); the later
//!   framework's values are taken (`ale.py` l.324-327): `period_samples`
//!   = budget / 10, `period_steps` = 2 x budget for AIR; AR's, one round
//!   when the budget is spent (l.264-266). The iterations scale with the
//!   budget: the paper's 200,000 and 50,000 for 25,000 samples, 8 and 2
//!   per unit of `ask_budget` by default (8000 and 2000 at 1000);
//! - reuse (l.305-333, 484-496): per training episode, on with probability
//!   p_reuse, 0.5 falling linearly to 0.1 between two training-episode
//!   counts (the paper's env steps 500k and 2M of 5M: 10 % and 40 % of a
//!   run, 500 and 2000 of the paper's 5000 episodes); in such an episode,
//!   at a training step with the ball where it does not ask, after the
//!   first imitation, it plays the network's greedy kick where its
//!   uncertainty is below the threshold (`extended` reuse: any such step).
//!   Advised and reused steps are learned as any other.
//!
//! Every draw comes from the agent's generator (the episode's reuse draw
//! and the cloning network's seed, drawn once) or from the network's own
//! generator, seeded from it.

use proto::{Action, State};
use rand::Rng;
use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, AskContext, GiveContext, Replies, ReuseContext};
use crate::advice::{PAPER_BUDGET, Reachable, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::cloning::{Cloning, CloningSettings};
use crate::config_error::{AgentConfigError, require_non_negative};
use crate::exchange::Advice;
use crate::fidelity::{Fidelity, Profile, VoteTies};
use crate::learner::ActionValues;
use crate::learner_settings::{DqnSettings, LearnerSettings};
use crate::method::{LearnerNeed, Method, Seat};
use crate::selection::{AgentRng, chance, majority};

/// The authors' budget (`constants/ale.py` l.107-176), to which their
/// iteration counts belong.
const PAPER_AIR_BUDGET: f64 = 25_000.0;
/// The authors' iterations of the first and the final imitation round
/// (`training-iterations-init`, `ale.py` l.130, 145, 160, 179).
const PAPER_INITIAL_ITERATIONS: f64 = 200_000.0;
/// The authors' iterations of AIR's periodic rounds (`ale.py` l.180).
const PAPER_PERIODIC_ITERATIONS: f64 = 50_000.0;
/// p_reuse before its decay and after it (`executor.py` l.59-67).
pub(crate) const P_REUSE_START: f64 = 0.5;
pub(crate) const P_REUSE_END: f64 = 0.1;
/// The threshold's percentile over the correctly imitated samples
/// (`executor.py` l.595-651).
pub(crate) const THRESHOLD_PERCENTILE: f64 = 90.0;

/// Which steps collect advice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Collection {
    /// AIR's: every training step with the ball until the first imitation,
    /// then where the cloning network's uncertainty is above its threshold;
    /// imitation rounds every tenth of the budget.
    #[default]
    Uncertainty,
    /// AR's (early advising): every training step with the ball; one
    /// imitation round, when the budget is spent.
    Early,
}

/// The settings of advice imitation and reuse (Ilhan, Gow &
/// Perez-Liebana, arXiv 2104.08440).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdviceImitation {
    /// Advisee budget: advice collected, steps acted on advice (default
    /// 1000).
    pub ask_budget: u64,
    /// Advisor budget: answers given about visited states (default 1000).
    pub give_budget: u64,
    /// The reachable set G (default everyone).
    pub reachable: Reachable,
    /// Which steps ask: `uncertainty` (AIR, default) or `early` (AR).
    pub collection: Collection,
    /// Training episodes after which p_reuse starts falling from 0.5
    /// (default 500: the paper's 500k of 5M steps, of 5000 episodes).
    pub reuse_decay_from: u64,
    /// Training episodes at which p_reuse reaches 0.1, at least
    /// `reuse_decay_from` (default 2000: the paper's 2M of 5M steps).
    pub reuse_decay_to: u64,
    /// Iterations of the first and the final imitation round per unit of
    /// `ask_budget`, finite and >= 0 (default 8: the paper's 200,000 for
    /// 25,000).
    pub initial_iterations_per_advice: f64,
    /// Iterations of the periodic rounds per unit of `ask_budget`, finite
    /// and >= 0 (default 2: the paper's 50,000 for 25,000).
    pub periodic_iterations_per_advice: f64,
    /// The most iterations of a round trained at one step with the ball,
    /// at least 1 (default 200, about 60 ms here): a round is spread over
    /// the steps that follow it, so that an agent process answers within
    /// the env's step timeout; the authors train a round at once.
    pub iterations_per_step: u64,
}

impl Default for AdviceImitation {
    fn default() -> Self {
        Self {
            ask_budget: PAPER_BUDGET,
            give_budget: PAPER_BUDGET,
            reachable: Reachable::Everyone,
            collection: Collection::Uncertainty,
            reuse_decay_from: 500,
            reuse_decay_to: 2000,
            initial_iterations_per_advice: PAPER_INITIAL_ITERATIONS / PAPER_AIR_BUDGET,
            periodic_iterations_per_advice: PAPER_PERIODIC_ITERATIONS / PAPER_AIR_BUDGET,
            iterations_per_step: 200,
        }
    }
}

impl AdviceImitation {
    /// The first invalid setting, naming its key.
    pub(crate) fn validate(&self) -> Result<(), AgentConfigError> {
        require_non_negative(
            "initial_iterations_per_advice",
            self.initial_iterations_per_advice,
        )?;
        require_non_negative(
            "periodic_iterations_per_advice",
            self.periodic_iterations_per_advice,
        )?;
        if self.iterations_per_step == 0 {
            return Err(AgentConfigError::new(
                "iterations_per_step",
                "must be at least 1 (the iterations of a round trained at one step)",
            ));
        }
        if self.reuse_decay_to < self.reuse_decay_from {
            return Err(AgentConfigError::new(
                "reuse_decay_to",
                format!(
                    "must be at least reuse_decay_from ({}), got {}",
                    self.reuse_decay_from, self.reuse_decay_to
                ),
            ));
        }
        self.reachable.validate()
    }

    /// The iterations of a round of `per_advice` iterations per unit of
    /// budget, rounded up.
    fn iterations(&self, per_advice: f64) -> u64 {
        (per_advice * self.ask_budget as f64).ceil() as u64
    }

    /// The schedule's clock, fresh.
    pub(crate) fn schedule(&self) -> Schedule {
        let (period_samples, period_steps) = match self.collection {
            Collection::Uncertainty => ((self.ask_budget / 10).max(1), Some(2 * self.ask_budget)),
            Collection::Early => (self.ask_budget.max(1), None),
        };
        Schedule {
            budget: self.ask_budget,
            period_samples,
            period_steps,
            initial: self.iterations(self.initial_iterations_per_advice),
            periodic: self.iterations(self.periodic_iterations_per_advice),
            rounds: 0,
            samples: 0,
            samples_since: 0,
            steps_since: 0,
        }
    }

    /// p_reuse after `episodes` training episodes.
    pub(crate) fn p_reuse(&self, episodes: u64) -> f64 {
        p_reuse(episodes, self.reuse_decay_from, self.reuse_decay_to)
    }
}

/// `advice-imitation`: imitate the advice collected, reuse the imitation
/// where it is sure.
pub(crate) struct AdviceImitationMethod;

impl Method for AdviceImitationMethod {
    type Settings = AdviceImitation;
    const NAME: &'static str = "advice-imitation";
    const ABOUT: &'static str = "imitate the advice collected with a network of its own and \
         reuse it where the imitation is sure (Ilhan, Gow & Perez-Liebana's AIR)";
    const LEARNER: LearnerNeed = LearnerNeed::Network;

    fn defaults(_: Profile) -> AdviceImitation {
        AdviceImitation::default()
    }

    fn validate(settings: &AdviceImitation) -> Result<(), AgentConfigError> {
        settings.validate()
    }

    fn strategy(settings: &AdviceImitation, fidelity: &Fidelity) -> Box<dyn AdvisingStrategy> {
        let learner = LearnerSettings::for_need(LearnerNeed::Network);
        Self::strategy_for(settings, fidelity, &Seat::of(&learner))
    }

    /// Its cloning network's hidden layers are its DQN's.
    fn strategy_for(
        settings: &AdviceImitation,
        _: &Fidelity,
        seat: &Seat<'_>,
    ) -> Box<dyn AdvisingStrategy> {
        let hidden = match seat.learner {
            LearnerSettings::Dqn(dqn) => dqn.hidden.clone(),
            _ => DqnSettings::default().hidden,
        };
        Box::new(Imitating {
            air: Imitator::new(settings, &hidden),
            settings: settings.clone(),
        })
    }
}

/// p_reuse after `episodes` training episodes: 0.5 until `from`, then
/// falling linearly to 0.1 at `to`, 0.1 after (`executor.py` l.379-384,
/// there per env step).
pub(crate) fn p_reuse(episodes: u64, from: u64, to: u64) -> f64 {
    if episodes <= from {
        P_REUSE_START
    } else if episodes >= to {
        P_REUSE_END
    } else {
        let done = (episodes - from) as f64 / (to - from) as f64;
        P_REUSE_START - (P_REUSE_START - P_REUSE_END) * done
    }
}

/// The imitation schedule's clock (`executor.py` l.264-303): samples and
/// steps since the last round, rounds done.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Schedule {
    budget: u64,
    period_samples: u64,
    period_steps: Option<u64>,
    initial: u64,
    periodic: u64,
    /// Imitation rounds done.
    rounds: u64,
    /// Samples collected.
    samples: u64,
    samples_since: u64,
    steps_since: u64,
}

impl Schedule {
    /// Whether it imitated at least once.
    pub(crate) fn imitated(&self) -> bool {
        self.rounds > 0
    }

    /// Imitation rounds done.
    #[cfg(test)]
    pub(crate) fn rounds(&self) -> u64 {
        self.rounds
    }

    /// One sample collected.
    pub(crate) fn collected(&mut self) {
        self.samples += 1;
        self.samples_since += 1;
    }

    /// One training step with the ball.
    pub(crate) fn stepped(&mut self) {
        self.steps_since += 1;
    }

    /// The iterations of the round due now, if one is: `period_samples`
    /// new samples, or `period_steps` steps and half as many; the first
    /// round and the one that holds the whole budget `initial`, the others
    /// `periodic`. None without a new sample.
    pub(crate) fn due(&self) -> Option<u64> {
        if self.samples_since == 0 {
            return None;
        }
        let by_samples = self.samples_since >= self.period_samples;
        let by_steps = self.period_steps.is_some_and(|p| {
            self.steps_since >= p && 2 * self.samples_since >= self.period_samples
        });
        let iterations = if self.rounds == 0 || self.samples >= self.budget {
            self.initial
        } else {
            self.periodic
        };
        (by_samples || by_steps).then_some(iterations)
    }

    /// A round done: the counts since start again.
    pub(crate) fn round_done(&mut self) {
        self.rounds += 1;
        self.samples_since = 0;
        self.steps_since = 0;
    }
}

/// What the network reads of a state: the features its DQN reads, HFO's
/// where the observation carries them, else the paper's six.
pub(crate) fn observation(state: &State, features: &[f32]) -> Vec<f32> {
    if features.is_empty() {
        state.iter().map(|&v| v as f32).collect()
    } else {
        features.to_vec()
    }
}

/// One agent's advice imitation and reuse: its settings, its schedule, its
/// cloning network (made at its first sample, of that sample's width), and
/// what it decided at the step in hand.
#[derive(Debug)]
pub(crate) struct Imitator {
    settings: AdviceImitation,
    network: CloningSettings,
    schedule: Schedule,
    cloning: Option<Cloning>,
    /// The seed of the cloning network, drawn from the agent's generator
    /// at its first step.
    seed: Option<u64>,
    /// This episode's reuse draw, once made.
    reuse_episode: Option<bool>,
    /// The observation of the step in hand, and whether it asks there.
    step: Option<(Vec<f32>, bool)>,
    /// The observation of a request in flight, kept for its advice.
    pending: Option<Vec<f32>>,
    /// The iterations left of the round in progress.
    owed: Option<u64>,
}

impl Imitator {
    /// An imitator of `settings` whose cloning network has hidden layers
    /// `hidden` (the agent's DQN's) and the authors' other settings.
    pub(crate) fn new(settings: &AdviceImitation, hidden: &[u32]) -> Self {
        let network = CloningSettings {
            hidden: hidden.to_vec(),
            ..CloningSettings::default()
        };
        Self::with_network(settings, network)
    }

    /// An imitator of `settings` whose cloning network has `network`'s
    /// settings.
    pub(crate) fn with_network(settings: &AdviceImitation, network: CloningSettings) -> Self {
        Self {
            schedule: settings.schedule(),
            settings: settings.clone(),
            network,
            cloning: None,
            seed: None,
            reuse_episode: None,
            step: None,
            pending: None,
            owed: None,
        }
    }

    /// Its schedule.
    #[cfg(test)]
    pub(crate) fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// Its cloning network, once it holds a sample.
    #[cfg(test)]
    pub(crate) fn cloning(&self) -> Option<&Cloning> {
        self.cloning.as_ref()
    }

    /// An episode begins: its reuse is drawn anew, nothing is in hand.
    pub(crate) fn begin_episode(&mut self) {
        self.reuse_episode = None;
        self.step = None;
        self.pending = None;
    }

    /// A training step with the ball at observation `x`, after
    /// `episodes` training episodes with `spent` of its ask budget spent:
    /// the round due first, then whether it asks (kept for
    /// [`asks`](Self::asks)), then, where it does not, the kick it reuses,
    /// if any.
    pub(crate) fn step(
        &mut self,
        x: Vec<f32>,
        spent: u64,
        episodes: u64,
        rng: &mut AgentRng,
    ) -> Option<Action> {
        self.pending = None;
        if self.seed.is_none() {
            self.seed = Some(rng.random());
        }
        self.schedule.stepped();
        self.imitate();
        let mut uncertainty = None;
        let asks = spent < self.settings.ask_budget
            && match self.settings.collection {
                Collection::Early => true,
                Collection::Uncertainty => match self.cloning.as_mut() {
                    Some(bc) if self.schedule.imitated() => {
                        let u = bc.uncertainty(&x);
                        uncertainty = Some(u);
                        u > bc.threshold()
                    }
                    _ => true,
                },
            };
        let reused = if asks || !self.schedule.imitated() {
            None
        } else {
            let p = self.settings.p_reuse(episodes);
            let on = *self.reuse_episode.get_or_insert_with(|| chance(rng, p));
            match self.cloning.as_mut() {
                Some(bc) if on => {
                    let u = uncertainty.unwrap_or_else(|| bc.uncertainty(&x));
                    (u < bc.threshold()).then(|| bc.greedy(&x))
                }
                _ => None,
            }
        };
        self.step = Some((x, asks));
        reused
    }

    /// The round due trains, at most `iterations_per_step` of its
    /// iterations at this step; once all are done, the threshold is
    /// autoset and the round counts.
    fn imitate(&mut self) {
        let owed = self.owed.or_else(|| self.schedule.due());
        let Some((owed, cloning)) = owed.zip(self.cloning.as_mut()) else {
            return;
        };
        let now = owed.min(self.settings.iterations_per_step);
        cloning.train(now);
        self.owed = (owed > now).then_some(owed - now);
        if self.owed.is_none() {
            cloning.autoset_threshold(THRESHOLD_PERCENTILE);
            self.schedule.round_done();
        }
    }

    /// Whether the step in hand asks (as [`step`](Self::step) decided);
    /// if it does, its observation waits for the advice.
    pub(crate) fn asks(&mut self) -> bool {
        match self.step.take() {
            Some((x, true)) => {
                self.pending = Some(x);
                true
            }
            _ => false,
        }
    }

    /// The advice played for the request in flight: `action`, or none;
    /// a kick played on advice is a sample.
    pub(crate) fn advised(&mut self, action: Option<Action>) {
        let (Some(x), Some(action)) = (self.pending.take(), action) else {
            return;
        };
        if !action.is_kick() {
            return;
        }
        let (network, seed) = (&self.network, self.seed.unwrap_or_default());
        let width = x.len();
        self.cloning
            .get_or_insert_with(|| Cloning::new(network, width, seed))
            .add(&x, action);
        self.schedule.collected();
    }
}

/// The decisions of `advice-imitation` for one agent.
#[derive(Debug)]
struct Imitating {
    settings: AdviceImitation,
    air: Imitator,
}

impl AdvisingStrategy for Imitating {
    /// The round due, then the collection rule, then, where it does not
    /// ask, the imitated kick in a reuse episode where the cloning
    /// network is sure.
    fn reuse(
        &mut self,
        at: &ReuseContext<'_>,
        _values: &mut dyn FnMut() -> ActionValues,
        rng: &mut AgentRng,
    ) -> Option<Action> {
        let x = observation(at.state, at.features);
        (self.air).step(x, at.counters.ask_spent, at.training_episodes, rng)
    }

    /// As the step in hand decided (AIR's collection rule).
    fn asks(&mut self, _at: &AskContext<'_>, _rng: &mut AgentRng) -> bool {
        self.air.asks()
    }

    fn advisors(&self, me: usize, team_size: usize, positions: &[[f64; 2]], out: &mut Vec<usize>) {
        reachable_set(&self.settings.reachable, me, team_size, positions, out);
    }

    /// Every request about a visited state, while the give budget lasts.
    fn gives(&mut self, at: &GiveContext<'_>, _rng: &mut AgentRng) -> bool {
        at.visited_within(self.settings.give_budget)
    }

    /// The majority vote, whose kick becomes a sample.
    fn follow(
        &mut self,
        replies: &Replies<'_>,
        ties: VoteTies,
        rng: &mut AgentRng,
    ) -> Option<Advice> {
        let vote = majority(replies.advice.iter().map(|a| a.action), ties, rng);
        let followed = vote.and_then(|action| replies.from_whom(action));
        self.air.advised(followed.map(|a| a.action));
        followed
    }

    fn exhausted(&self, counters: &AdviceCounters) -> bool {
        counters.advice_given >= self.settings.give_budget
    }

    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.advice_given
    }

    fn begin_episode(&mut self, _mode: proto::Mode) {
        self.air.begin_episode();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn settings(collection: Collection, budget: u64) -> AdviceImitation {
        AdviceImitation {
            ask_budget: budget,
            collection,
            ..AdviceImitation::default()
        }
    }

    #[test]
    fn the_defaults_scale_the_papers_iterations_to_the_budget() {
        let d = AdviceImitation::default();
        assert_eq!(
            (
                d.initial_iterations_per_advice,
                d.periodic_iterations_per_advice
            ),
            (8.0, 2.0)
        );
        let s = d.schedule();
        assert_eq!((s.initial, s.periodic), (8000, 2000));
        assert_eq!((s.period_samples, s.period_steps), (100, Some(2000)));
        let paper = settings(Collection::Uncertainty, 25_000).schedule();
        assert_eq!((paper.initial, paper.periodic), (200_000, 50_000));
        let small = AdviceImitation {
            ask_budget: 30,
            initial_iterations_per_advice: 0.5,
            ..AdviceImitation::default()
        };
        // 0.5 x 30 = 15; 2 x 30 = 60; a tenth of 30 is 3.
        let s = small.schedule();
        assert_eq!((s.initial, s.periodic, s.period_samples), (15, 60, 3));
        d.validate().unwrap();
    }

    #[test]
    fn the_first_round_comes_after_a_tenth_of_the_budget() {
        let mut s = settings(Collection::Uncertainty, 1000).schedule();
        for _ in 0..99 {
            s.stepped();
            s.collected();
            assert_eq!(s.due(), None);
        }
        s.collected();
        assert_eq!(s.due(), Some(8000));
        s.round_done();
        assert!(s.imitated());
        assert_eq!(s.due(), None);
        // The next after a hundred more: periodic.
        for _ in 0..100 {
            s.collected();
        }
        assert_eq!(s.due(), Some(2000));
    }

    #[test]
    fn a_round_also_comes_after_twice_the_budget_in_steps_with_half_a_period() {
        let mut s = settings(Collection::Uncertainty, 1000).schedule();
        for _ in 0..100 {
            s.collected();
        }
        s.round_done();
        for _ in 0..49 {
            s.collected();
        }
        for _ in 0..2000 {
            s.stepped();
        }
        // 2000 steps, 49 samples: fewer than half of 100.
        assert_eq!(s.due(), None);
        s.collected();
        assert_eq!(s.due(), Some(2000));
        s.round_done();
        // Steps alone never make a round.
        for _ in 0..5000 {
            s.stepped();
        }
        assert_eq!(s.due(), None);
    }

    #[test]
    fn the_round_that_holds_the_whole_budget_has_the_initial_iterations() {
        let mut s = settings(Collection::Uncertainty, 1000).schedule();
        let mut rounds = Vec::new();
        for _ in 0..1000 {
            s.collected();
            if let Some(n) = s.due() {
                rounds.push(n);
                s.round_done();
            }
        }
        assert_eq!(rounds.len(), 10);
        assert_eq!(rounds[0], 8000);
        assert!(rounds[1..9].iter().all(|&n| n == 2000), "{rounds:?}");
        assert_eq!(rounds[9], 8000);
        assert_eq!(s.rounds(), 10);
    }

    #[test]
    fn early_collection_imitates_once_when_the_budget_is_spent() {
        let mut s = settings(Collection::Early, 1000).schedule();
        for _ in 0..999 {
            s.collected();
            for _ in 0..10 {
                s.stepped();
            }
            assert_eq!(s.due(), None);
        }
        s.collected();
        assert_eq!(s.due(), Some(8000));
    }

    #[test]
    fn a_round_is_spread_over_the_steps_that_follow() {
        // A budget of 10: the first round (80 iterations) after one sample,
        // 30 iterations at most per step: done at the third step.
        let s = AdviceImitation {
            ask_budget: 10,
            iterations_per_step: 30,
            ..AdviceImitation::default()
        };
        let mut air = Imitator::new(&s, &[8]);
        let mut rng = AgentRng::seed_from_u64(3);
        let x = vec![0.1; 6];
        air.step(x.clone(), 0, 0, &mut rng);
        assert!(air.asks());
        air.advised(Some(Action::Shoot));
        for _ in 0..2 {
            air.step(x.clone(), 1, 0, &mut rng);
            assert!(!air.schedule().imitated());
        }
        air.step(x, 1, 0, &mut rng);
        assert!(air.schedule().imitated());
        assert_eq!(air.owed, None);
    }

    #[test]
    fn it_reads_hfos_features_where_given_else_the_six() {
        let state = [0.5, -0.25, 0.0, 1.0, -1.0, 0.125];
        assert_eq!(
            observation(&state, &[]),
            [0.5, -0.25, 0.0, 1.0, -1.0, 0.125]
        );
        assert_eq!(observation(&state, &[0.3; 27]), [0.3; 27]);
    }

    #[test]
    fn p_reuse_falls_linearly_from_a_half_to_a_tenth() {
        let d = AdviceImitation::default();
        assert_eq!(d.p_reuse(0), 0.5);
        assert_eq!(d.p_reuse(500), 0.5);
        assert!((d.p_reuse(1250) - 0.3).abs() < 1e-12);
        assert!((d.p_reuse(875) - 0.4).abs() < 1e-12);
        assert_eq!(d.p_reuse(2000), 0.1);
        assert_eq!(d.p_reuse(1_000_000), 0.1);
        // A step at 7 when both ends meet.
        assert_eq!((p_reuse(7, 7, 7), p_reuse(8, 7, 7)), (0.5, 0.1));
    }

    #[test]
    fn bad_settings_name_their_key() {
        let key = |s: AdviceImitation| s.validate().unwrap_err().key;
        let d = AdviceImitation::default;
        assert_eq!(
            key(AdviceImitation {
                reuse_decay_to: 499,
                ..d()
            }),
            "reuse_decay_to"
        );
        assert_eq!(
            key(AdviceImitation {
                initial_iterations_per_advice: -1.0,
                ..d()
            }),
            "initial_iterations_per_advice"
        );
        assert_eq!(
            key(AdviceImitation {
                periodic_iterations_per_advice: f64::NAN,
                ..d()
            }),
            "periodic_iterations_per_advice"
        );
        assert_eq!(
            key(AdviceImitation {
                iterations_per_step: 0,
                ..d()
            }),
            "iterations_per_step"
        );
        assert_eq!(
            key(AdviceImitation {
                reachable: Reachable::WithinDistance(-1.0),
                ..d()
            }),
            "reachable"
        );
    }

    /// The toy mapping of the cloning network's tests: the sign of the
    /// first two numbers picks the kick.
    fn toy(i: usize) -> (Vec<f32>, Action) {
        let slot = i % 4;
        let sign = |bit: usize| if slot >> bit & 1 == 1 { 0.6 } else { -0.6 };
        let jitter = (i % 7) as f32 * 0.02;
        let x = vec![sign(0) + jitter, sign(1) - jitter, 0.1, -0.1, 0.0, 0.2];
        (x, crate::dqn::KICKS[slot])
    }

    fn small(budget: u64) -> AdviceImitation {
        AdviceImitation {
            ask_budget: budget,
            initial_iterations_per_advice: 300.0 / budget as f64,
            periodic_iterations_per_advice: 50.0 / budget as f64,
            // A round at once, as the authors train it.
            iterations_per_step: 300,
            ..AdviceImitation::default()
        }
    }

    /// A small network that learns the toy in a few hundred iterations.
    fn imitator(settings: &AdviceImitation, hidden: &[u32]) -> Imitator {
        let network = CloningSettings {
            hidden: hidden.to_vec(),
            lr: 1e-2,
            passes: 30,
            ..CloningSettings::default()
        };
        Imitator::with_network(settings, network)
    }

    /// Plays `n` advised steps of the toy mapping: it asks each, and is
    /// advised the toy's kick.
    fn advise(air: &mut Imitator, from: usize, n: usize, spent: &mut u64, rng: &mut AgentRng) {
        for i in from..from + n {
            let (x, a) = toy(i);
            assert_eq!(air.step(x, *spent, 0, rng), None);
            assert!(air.asks(), "step {i} asks");
            air.advised(Some(a));
            *spent += 1;
        }
    }

    #[test]
    fn it_asks_unconditionally_until_it_imitated_then_above_the_threshold() {
        let mut rng = AgentRng::seed_from_u64(1);
        let mut air = imitator(&small(200), &[32, 32]);
        let mut spent = 0;
        advise(&mut air, 0, 20, &mut spent, &mut rng);
        assert!(!air.schedule().imitated());
        assert_eq!(air.cloning().unwrap().samples(), 20);
        // The next step trains the first round (300 iterations) first.
        let (x, _) = toy(3);
        air.step(x.clone(), spent, 0, &mut rng);
        assert!(air.schedule().imitated());
        let threshold = air.cloning().unwrap().threshold();
        assert_ne!(threshold, 0.01, "autoset");
        // It asks exactly where the uncertainty (as a copy of its network
        // measures it, drawing the same masks) is above the threshold: more
        // often far from what it imitated than at the inputs it learned.
        let (mut known, mut far) = ((0, 0), (0, 0));
        for i in 0..40 {
            let near = toy(i).0;
            let away: Vec<f32> = (0..6)
                .map(|j| if (i + j) % 2 == 0 { 4.0 } else { -4.0 })
                .collect();
            for (x, count) in [(near, &mut known), (away, &mut far)] {
                let bc = air.cloning().unwrap();
                let mut copy = Cloning::new(&air.network, 6, 0);
                copy.load(&bc.save()).unwrap();
                let above = copy.uncertainty(&x) > bc.threshold();
                assert_eq!(air.step(x, spent, 0, &mut rng), None);
                assert_eq!(air.asks(), above);
                air.advised(None);
                count.0 += usize::from(above);
                count.1 += 1;
            }
        }
        assert!(known.0 < far.0, "asked {known:?} near, {far:?} far");
        // Without budget it never asks.
        air.step(toy(0).0, 200, 0, &mut rng);
        assert!(!air.asks());
    }

    #[test]
    fn it_reuses_the_imitated_kick_where_sure_in_a_reuse_episode() {
        let mut rng = AgentRng::seed_from_u64(2);
        let budget = 20;
        let early = AdviceImitation {
            collection: Collection::Early,
            ..small(budget)
        };
        let mut air = imitator(&early, &[32, 32]);
        let mut spent = 0;
        advise(&mut air, 0, 20, &mut spent, &mut rng);
        // One round when the budget is spent, at the next step. With the
        // budget spent, it never asks; p_reuse 0.5 per episode.
        assert_eq!(spent, budget);
        let mut episodes_reusing = 0;
        let mut reused = 0;
        let mut right = 0;
        for episode in 0..40 {
            air.begin_episode();
            let mut any = false;
            for i in 0..10 {
                let (x, a) = toy(i);
                if let Some(kick) = air.step(x, spent, episode, &mut rng) {
                    any = true;
                    reused += 1;
                    right += usize::from(kick == a);
                }
                assert!(!air.asks());
            }
            episodes_reusing += usize::from(any);
        }
        assert!(air.schedule().imitated());
        assert!(
            (8..=32).contains(&episodes_reusing),
            "{episodes_reusing} of 40 episodes reused"
        );
        assert!(
            reused > 0 && right * 2 > reused,
            "{right} of {reused} right"
        );
    }

    #[test]
    fn no_reuse_before_the_first_imitation_nor_while_it_asks() {
        let mut rng = AgentRng::seed_from_u64(3);
        let mut air = imitator(
            &AdviceImitation {
                collection: Collection::Early,
                ..small(50)
            },
            &[16],
        );
        let mut spent = 0;
        advise(&mut air, 0, 49, &mut spent, &mut rng);
        assert!(!air.schedule().imitated());
        advise(&mut air, 49, 1, &mut spent, &mut rng);
        // Spent: the round comes at the next step, which cannot ask.
        air.step(toy(0).0, spent, 0, &mut rng);
        assert!(!air.asks());
        assert_eq!(air.schedule().rounds(), 1);
    }

    #[test]
    fn one_seed_makes_the_same_decisions() {
        let play = |seed| {
            let mut rng = AgentRng::seed_from_u64(seed);
            let mut air = imitator(&small(30), &[16]);
            let mut spent = 0;
            advise(&mut air, 0, 3, &mut spent, &mut rng);
            let mut out = Vec::new();
            for e in 0..10 {
                air.begin_episode();
                for i in 0..8 {
                    out.push(air.step(toy(i).0, 30, e, &mut rng));
                }
            }
            (out, air.cloning().unwrap().save())
        };
        assert_eq!(play(4), play(4));
        assert_ne!(play(4).1, play(5).1);
    }
}
