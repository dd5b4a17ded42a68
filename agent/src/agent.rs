//! One learning agent: its per-frame API (advisee side), its advisor side and
//! its learned state.

use proto::{
    Action, AdviceAnswer, Along, EpisodeOutcome, Features, MAX_BATCH, Mode, SharedValues, State,
    ValuesAnswer,
};
use rand::{Rng, SeedableRng};

use crate::advice_counters::{AdviceCounters, RequestOutcomes};
use crate::config::AgentConfig;
use crate::config_error::AgentConfigError;
use crate::exchange::{
    Advice, AdviceExchange, AdviceReport, Answer, Answers, Batch, Share, Transition,
};
use crate::fidelity::SharedBootstrap;
use crate::learner::{ActionValues, Experience, Learner, Seen, Step};
use crate::learner_settings::ObservationSet;
use crate::learners::learner_of;
use crate::link::Link;
use crate::method::Seat;
use crate::persist::{Entry, PersistError, Snapshot};
use crate::selection::{ACTIONS, AgentRng, RANDOM_DRAW, greedy_first, greedy_random};
use crate::states::StateIndex;
use crate::strategy::{
    Adopted, AdvisingStrategy, AskContext, EndContext, GiveContext, Outcome, OwnChoice, Replies,
    ReuseContext, Sends,
};
use crate::tiles::{Tiling, TilingParams};

/// What an agent sees in one simulator frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observation {
    /// The 6 features of docs/algorithms.md section 1, each in [-1, 1].
    pub state: State,
    /// HFO's features of the state, for an agent whose learner reads them
    /// (`observation = "hfo"`); [`Features::NONE`] for the others.
    pub features: Features,
    /// Whether the agent can kick the ball (it chooses a kick action only then).
    pub can_kick: bool,
    /// Field position, used only by
    /// [`Reachable::WithinDistance`](crate::Reachable::WithinDistance).
    pub position: [f64; 2],
}

/// The previous step, closed by the next frame's reward and state.
#[derive(Clone, Copy, Debug)]
struct OpenStep {
    index: usize,
    action: Action,
    state: State,
    features: Features,
    /// The advisor whose advice it played, if any.
    advisor: Option<usize>,
}

impl OpenStep {
    /// Where it was taken.
    fn at(&self) -> Seen<'_> {
        Seen {
            state: &self.state,
            features: self.features.as_slice(),
            index: Some(self.index),
        }
    }

    fn step(&self) -> Step<'_> {
        Step {
            at: self.at(),
            action: self.action,
        }
    }
}

/// A frame waiting for advice: everything [`Agent::act_complete`] needs to
/// finish it.
#[derive(Clone, Copy, Debug)]
struct InFlight {
    key: u64,
    index: usize,
    state: State,
    features: Features,
    reward: f64,
    intended: Option<Action>,
    /// Advisors asked.
    asked: u64,
}

/// The first half of a frame (see [`Agent::act_begin`]).
#[derive(Clone, Debug, PartialEq)]
#[allow(
    clippy::large_enum_variant,
    reason = "made and matched once a frame; boxing the features would allocate every request"
)]
pub enum Decision {
    /// The action for this frame; the frame is complete.
    Act(Action),
    /// Ask these advisors about `state` (with what the request carries
    /// `along`), then pass their advice to [`Agent::act_complete`].
    Ask {
        /// The advisors, in the order of the reachable set.
        to: Vec<usize>,
        /// The advisee's state.
        state: State,
        /// HFO's features of it, where the advisee's observations carry
        /// them.
        features: Features,
        /// What the request carries: its own choice in Mistake Correcting
        /// mode, its visits by action for PSAF, else nothing.
        along: Along,
    },
}

/// What an advisor knows of a state it is asked about.
#[derive(Clone, Copy, Debug, Default)]
struct Known {
    /// n(s).
    visits: u64,
    /// m(s, a) by action index.
    action_visits: [u32; ACTIONS],
    /// Its learner's values there.
    values: ActionValues,
    /// The state's index, where training met it.
    index: Option<usize>,
}

/// A learning agent (or the random baseline) with its advising strategy:
/// the advising framework around a [`Learner`] (its configuration's
/// `learner`, SARSA(lambda) by default).
///
/// Drive it per episode: [`begin_episode`](Self::begin_episode), one
/// [`act`](Self::act) per simulator frame, [`end_episode`](Self::end_episode)
/// at the terminal frame, then [`share_episode`](Self::share_episode).
/// A transport that cannot call the advisors in place splits each frame in
/// [`act_begin`](Self::act_begin) and [`act_complete`](Self::act_complete)
/// and ships shared episodes and batches from
/// [`take_shared`](Self::take_shared); reports of advice outcomes, from a
/// strategy that sends them, from [`take_reports`](Self::take_reports)
/// after every frame.
#[derive(Debug)]
pub struct Agent {
    id: usize,
    team_size: usize,
    config: AgentConfig,
    /// The decisions of its advising method.
    strategy: Box<dyn AdvisingStrategy>,
    tiling: Tiling,
    states: StateIndex,
    learner: Box<dyn Learner>,
    rng: AgentRng,
    mode: Mode,
    pending: Option<OpenStep>,
    in_flight: Option<InFlight>,
    advised: Vec<u64>,
    /// Decisions acted on each advisor's advice, by advisor id.
    advised_by: Vec<u64>,
    reach: Vec<usize>,
    answers: Answers,
    /// What it sends unasked after the episode that just ended.
    outbox: Sends,
    /// The sum of the rewards of this episode's frames after the first;
    /// `None` before its first frame.
    episode_return: Option<f64>,
    /// The advice that arrived for the open step, for a strategy that
    /// reports advice outcomes.
    open_advice: Vec<Advice>,
    /// Reports of advice outcomes to send.
    reports: Vec<AdviceReport>,
    training_episodes: u64,
    counters: AdviceCounters,
    /// What became of its requests.
    outcomes: RequestOutcomes,
    /// Whether it told everyone that its give budget is spent.
    announced: bool,
    /// An announcement to send.
    announcement: bool,
    /// The advisors that announced their give budget spent, by id.
    exhausted_peers: Vec<bool>,
    link: Option<Link>,
}

impl Agent {
    /// Agent `id` of a team of `team_size` learning with its configuration's
    /// learner, its generator seeded with `seed`.
    pub fn new(
        id: usize,
        team_size: usize,
        config: AgentConfig,
        seed: u64,
    ) -> Result<Self, AgentConfigError> {
        let learner = learner_of(&config, team_size, seed);
        Self::with_learner(id, team_size, config, seed, learner)
    }

    /// Agent `id` of a team of `team_size` learning with `learner`; the
    /// learner's own settings in `config` (alpha, gamma, lambda, epsilon,
    /// trace threshold) are then the learner's affair.
    pub fn with_learner(
        id: usize,
        team_size: usize,
        config: AgentConfig,
        seed: u64,
        learner: Box<dyn Learner>,
    ) -> Result<Self, AgentConfigError> {
        let tiling = Tiling::new(&config)?;
        if id >= team_size {
            return Err(AgentConfigError::new(
                "team_size",
                format!("agent id {id} is not below the team size {team_size}"),
            ));
        }
        config.algorithm.check_team(team_size)?;
        if config.learner.observation() == ObservationSet::Hfo
            && team_size > proto::MAX_FEATURE_TEAM
        {
            return Err(AgentConfigError::new(
                "observation",
                format!(
                    "`hfo` is given to teams of at most {} agents, this one has {team_size}",
                    proto::MAX_FEATURE_TEAM
                ),
            ));
        }
        if let Some(network) = &config.network {
            network.validate()?;
        }
        let seat = Seat {
            learner: &config.learner,
            gamma: config.gamma,
            seed,
        };
        Ok(Self {
            link: config.network.map(|n| Link::new(n, seed)),
            strategy: config.algorithm.build_for(&config.fidelity, &seat),
            id,
            team_size,
            config,
            tiling,
            states: StateIndex::default(),
            learner,
            rng: AgentRng::seed_from_u64(seed),
            mode: Mode::Training,
            pending: None,
            in_flight: None,
            advised: Vec::new(),
            advised_by: vec![0; team_size],
            reach: Vec::with_capacity(team_size),
            answers: Answers::default(),
            outbox: Sends::new(),
            episode_return: None,
            open_advice: Vec::new(),
            reports: Vec::new(),
            training_episodes: 0,
            counters: AdviceCounters::default(),
            outcomes: RequestOutcomes::default(),
            announced: false,
            announcement: false,
            exhausted_peers: vec![false; team_size],
        })
    }

    /// The same agent with its advising decisions made by `strategy`
    /// instead of its configuration's: how a method defined outside this
    /// crate joins a team ([`AdvisingStrategy`]). `config.algorithm` stays
    /// what the results record.
    pub fn with_strategy(mut self, strategy: Box<dyn AdvisingStrategy>) -> Self {
        self.strategy = strategy;
        self
    }

    /// This agent's id (its index in the team).
    pub fn id(&self) -> usize {
        self.id
    }

    /// Number of agents in its team.
    pub fn team_size(&self) -> usize {
        self.team_size
    }

    /// The configuration it was built with.
    pub fn config(&self) -> &AgentConfig {
        &self.config
    }

    /// The mode of the current episode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The link its advice messages go out on, under its network
    /// conditions (none without them).
    pub fn link(&self) -> Option<&Link> {
        self.link.as_ref()
    }

    /// Decisions it acted on each advisor's advice, by advisor id (advice
    /// followed; values taken are not an advisor's).
    pub fn advised_by(&self) -> &[u64] {
        &self.advised_by
    }

    /// Communication and budget counters.
    pub fn counters(&self) -> &AdviceCounters {
        &self.counters
    }

    /// What became of its advice requests.
    pub fn request_outcomes(&self) -> &RequestOutcomes {
        &self.outcomes
    }

    /// Whether it has an announcement to send: its give budget is spent
    /// and its settings say `announce_exhausted` (taken once).
    pub fn take_announcement(&mut self) -> bool {
        std::mem::take(&mut self.announcement)
    }

    /// Agent `peer` announced its give budget spent: it is asked no more.
    pub fn hear_exhausted(&mut self, peer: usize) {
        if let Some(e) = self.exhausted_peers.get_mut(peer) {
            *e = true;
        }
    }

    /// Agent `peer` joined afresh (a newcomer, a restart): it is asked
    /// again until it announces otherwise.
    pub fn peer_joined(&mut self, peer: usize) {
        if let Some(e) = self.exhausted_peers.get_mut(peer) {
            *e = false;
        }
    }

    /// Training episodes finished so far.
    pub fn training_episodes(&self) -> u64 {
        self.training_episodes
    }

    /// What it holds of `state`: its learner's values and its visit count
    /// (`None` for a state training never met).
    pub fn entry(&mut self, state: &State) -> Option<Entry> {
        let index = self.states.get(self.tiling.key(state))?;
        let values = self.learner.values(Seen {
            state,
            features: &[],
            index: Some(index),
        });
        Some(Entry {
            q: values.q,
            tried: values.learned,
            visits: self.states.visits(index),
        })
    }

    /// Number of states training met.
    pub fn states_met(&self) -> usize {
        self.states.len()
    }

    /// The state key of `state` under this agent's tiling.
    pub fn key(&self, state: &State) -> u64 {
        self.tiling.key(state)
    }

    /// The budget the paper plots: advice given (ad hoc advisor, Torrey
    /// teacher) or transitions shared (EpisodeSharing); 0 otherwise.
    pub fn spent_budget(&self) -> u64 {
        self.strategy.spent_budget(&self.counters)
    }

    /// Starts an episode in `mode`; forgets the previous episode's trace,
    /// advised states, unsent shares and reports.
    pub fn begin_episode(&mut self, mode: Mode) {
        self.mode = mode;
        self.reset_episode();
        self.outbox.clear();
        self.reports.clear();
        self.strategy.begin_episode(mode);
    }

    fn reset_episode(&mut self) {
        self.pending = None;
        self.in_flight = None;
        self.learner.end_episode();
        self.advised.clear();
        self.episode_return = None;
        self.open_advice.clear();
    }

    fn training(&self) -> bool {
        self.mode == Mode::Training && self.strategy.learns()
    }

    /// One frame: closes the previous step with `reward` (ignored on the
    /// episode's first frame) and the new state, and returns the action for
    /// this frame (`Move` when the agent cannot kick).
    ///
    /// `positions` holds every agent's field position by id (only needed by
    /// [`Reachable::WithinDistance`](crate::Reachable::WithinDistance));
    /// `exchange` reaches the advisors.
    /// The same as [`act_begin`](Self::act_begin) with everyone reachable,
    /// then, if asked to, [`act_complete`](Self::act_complete) with the
    /// answers `exchange` collects.
    pub fn act(
        &mut self,
        obs: &Observation,
        reward: f64,
        positions: &[[f64; 2]],
        exchange: &mut dyn AdviceExchange,
    ) -> Action {
        match self.act_begin(obs, reward, positions, &|_| true) {
            Decision::Act(action) => action,
            Decision::Ask {
                to,
                state,
                features,
                along,
            } => {
                let mut answers = std::mem::take(&mut self.answers);
                answers.clear();
                let replies = exchange.ask(self.id, &to, &state, &features, along, &mut answers);
                let action = self.act_complete(&answers, replies);
                self.answers = answers;
                action
            }
        }
    }

    /// The first half of [`act`](Self::act): either the frame's action, or
    /// the advisors to ask first. `reachable(j)` says whether agent `j` can
    /// be asked now (e.g. its liveliness token is seen); the others are left
    /// out of the reachable set.
    ///
    /// After [`Decision::Ask`] the frame stays open until
    /// [`act_complete`](Self::act_complete); the agent may advise others
    /// meanwhile. A new `act_begin`, [`begin_episode`](Self::begin_episode),
    /// [`end_episode`](Self::end_episode) or [`restore`](Self::restore)
    /// abandons it.
    pub fn act_begin(
        &mut self,
        obs: &Observation,
        reward: f64,
        positions: &[[f64; 2]],
        reachable: &dyn Fn(usize) -> bool,
    ) -> Decision {
        self.in_flight = None;
        self.episode_return = Some(self.episode_return.map_or(0.0, |r| r + reward));
        if !self.strategy.learns() {
            return Decision::Act(self.random_action(obs.can_kick));
        }
        let key = self.tiling.key(&obs.state);
        let seen = |index| Seen {
            state: &obs.state,
            features: obs.features.as_slice(),
            index,
        };
        if self.mode == Mode::Evaluation {
            if !obs.can_kick {
                return Decision::Act(Action::Move);
            }
            let at = seen(self.states.get(key));
            return Decision::Act(greedy_first(&self.learner.values(at).q));
        }
        let index = self.states.index_or_insert(key);
        let at = seen(Some(index));
        let open = |action| OpenStep {
            index,
            action,
            state: obs.state,
            features: obs.features,
            advisor: None,
        };
        if !obs.can_kick {
            self.step(open(Action::Move), reward);
            return Decision::Act(Action::Move);
        }
        if let Some(action) = self.reused(key, at) {
            self.step(open(action), reward);
            return Decision::Act(action);
        }
        if self.asks(key, index, at) {
            self.fill_reach(positions, reachable);
            if !self.reach.is_empty() {
                let intended = (self.strategy.mistake_correcting()).then(|| self.intent(at));
                self.counters.advice_requests += 1;
                self.in_flight = Some(InFlight {
                    key,
                    index,
                    state: obs.state,
                    features: obs.features,
                    reward,
                    intended,
                    asked: self.reach.len() as u64,
                });
                let along = match intended {
                    Some(action) => Along::Intended(action),
                    None if self.strategy.shares_best() => {
                        Along::ActionVisits(self.states.action_visits(index))
                    }
                    None => Along::Nothing,
                };
                return Decision::Ask {
                    to: self.reach.clone(),
                    state: obs.state,
                    features: obs.features,
                    along,
                };
            }
        }
        let action = self.choose(at);
        self.step(open(action), reward);
        Decision::Act(action)
    }

    /// The second half of a frame that asked: `answers` holds what arrived
    /// (in any number, possibly none) in `replies` replies (with or without
    /// advice). Values its strategy adopts go into its learner first (one
    /// unit of its ask budget); with advice to follow it plays it (one unit
    /// of its ask budget), else, after a best value, its greedy action, else
    /// its intended or epsilon-greedy action; then
    /// the frame completes as in [`act`](Self::act). Without a frame
    /// waiting for advice it returns `Move` and changes nothing.
    pub fn act_complete(&mut self, answers: &Answers, replies: u64) -> Action {
        let Some(f) = self.in_flight.take() else {
            return Action::Move;
        };
        self.counters.advice_replies_received += replies;
        self.outcomes.count(f.asked, replies, answers);
        let ties = self.config.fidelity.vote_ties;
        let at = Seen {
            state: &f.state,
            features: f.features.as_slice(),
            index: Some(f.index),
        };
        // A strategy that weighs its own choice gets it drawn first.
        let own = self.strategy.weighs_own_choice().then(|| OwnChoice {
            values: self.learner.values(at),
            action: f.intended.unwrap_or_else(|| self.choose(at)),
        });
        let replies = Replies {
            key: f.key,
            advice: &answers.advice,
            values: &answers.values,
            best: &answers.best,
            advisor_values: &answers.advisor_values,
            own,
        };
        let visits = self.states.visits(f.index);
        let adopted = self.strategy.adopt(&replies, visits);
        let greedy = adopted.and_then(|adopted| self.adopt(&f, adopted));
        let followed = self.strategy.follow(&replies, ties, &mut self.rng);
        let action = match followed {
            Some(advice) => {
                self.counters.ask_spent += 1;
                self.advised.push(f.key);
                if let Some(n) = self.advised_by.get_mut(advice.advisor) {
                    *n += 1;
                }
                advice.action
            }
            None => match (greedy, own) {
                (Some(action), _) => action,
                (None, Some(own)) => own.action,
                (None, None) => f.intended.unwrap_or_else(|| self.choose(at)),
            },
        };
        let this = OpenStep {
            index: f.index,
            action,
            state: f.state,
            features: f.features,
            advisor: followed.map(|advice| advice.advisor),
        };
        self.step(this, f.reward);
        if self.strategy.reports_advice_outcomes() {
            self.open_advice.extend_from_slice(&answers.advice);
        }
        action
    }

    /// Takes adopted values into its learner, one unit of its ask budget
    /// when the learner can take them; after a best value (PSAF), its
    /// greedy action on its values now, which it then plays.
    fn adopt(&mut self, f: &InFlight, adopted: Adopted) -> Option<Action> {
        let at = Seen {
            state: &f.state,
            features: f.features.as_slice(),
            index: Some(f.index),
        };
        let values = match adopted {
            Adopted::Row(shared) => ActionValues {
                q: shared.q,
                learned: shared.learned,
            },
            Adopted::Best { action, value } => {
                let mut values = self.learner.values(at);
                values.q[action.index()] = value;
                values.learned |= 1 << action.index();
                values
            }
        };
        if !self.learner.absorb(at, values) {
            return None;
        }
        self.counters.ask_spent += 1;
        self.advised.push(f.key);
        let q = self.learner.values(at).q;
        matches!(adopted, Adopted::Best { .. }).then(|| greedy_random(&q, &mut self.rng))
    }

    /// Completes a training frame: learns the previous step towards
    /// `this` one, counts the visit and keeps this step open.
    fn step(&mut self, this: OpenStep, reward: f64) {
        if let Some(prev) = self.pending.take() {
            self.learn(prev, reward, Some(this));
        }
        self.states.visit(this.index, this.action);
        self.pending = Some(this);
    }

    /// The terminal frame of an episode that ended with `outcome`: a
    /// training episode learns its last step with target the outcome's
    /// reward alone, counts as finished, and gets ready what its strategy
    /// sends unasked (one unit of sharing per transition per receiver); an
    /// evaluation episode's end is told to its strategy.
    pub fn end_episode(&mut self, outcome: EpisodeOutcome) {
        let final_reward = outcome.reward();
        if self.training()
            && let Some(prev) = self.pending.take()
        {
            self.learn(prev, final_reward, None);
        }
        let end = EndContext {
            final_reward,
            outcome,
            episode_return: self.episode_return.unwrap_or(0.0) + final_reward,
            me: self.id,
            team_size: self.team_size,
            counters: &self.counters,
        };
        if self.training() {
            self.outbox = bounded(self.strategy.end_episode(&end));
            let sent: usize = (self.outbox.iter())
                .map(|(_, share)| share.transitions().len())
                .sum();
            self.counters.shared_sent += sent as u64;
        } else if self.mode == Mode::Evaluation {
            self.strategy.end_evaluation(&end);
        }
        if self.mode == Mode::Training {
            self.training_episodes += 1;
        }
        self.reset_episode();
    }

    /// After [`end_episode`](Self::end_episode): sends what its strategy
    /// sends unasked (EpisodeSharing's goal episodes, batches).
    pub fn share_episode(&mut self, exchange: &mut dyn AdviceExchange) {
        for (to, share) in self.take_shared() {
            exchange.share(self.id, to, &share);
        }
    }

    /// What [`share_episode`](Self::share_episode) sends, as data: what
    /// goes to each receiver, in order; counted as shared when the episode
    /// ended. Empty unless a training episode just ended with something to
    /// send.
    pub fn take_shared(&mut self) -> Sends {
        std::mem::take(&mut self.outbox)
    }

    /// The reports of advice outcomes to send, one per advisor whose advice
    /// arrived for a decision learned since the last call (a strategy that
    /// [`reports_advice_outcomes`](AdvisingStrategy::reports_advice_outcomes)).
    pub fn take_reports(&mut self) -> Vec<AdviceReport> {
        std::mem::take(&mut self.reports)
    }

    /// Advisor side: agent `asker` reports how a decision on its advice
    /// turned out; its strategy is told.
    pub fn hear_advice_outcome(&mut self, asker: usize, followed: bool, advantage: f64) {
        self.strategy.advice_outcome(asker, followed, advantage);
    }

    /// Advisor side: its answer to agent `asker`'s request about `state`
    /// (with the asker's HFO `features` of it, if it sent them), as its
    /// method answers: an action ([`advise`](Self::advise)) or, for a
    /// value-sharing method, its values ([`share_values`](Self::share_values));
    /// none, and why, otherwise.
    pub fn answer(
        &mut self,
        asker: usize,
        state: &State,
        features: &[f32],
        along: Along,
    ) -> Answer {
        let exhausted = self.training() && self.strategy.exhausted(&self.counters);
        match (self.strategy.shares_values(), exhausted) {
            (true, true) => Answer::Values(ValuesAnswer::Exhausted),
            (false, true) => Answer::Action(AdviceAnswer::Exhausted),
            (true, false) => {
                Answer::Values(self.share_values(asker, state, features, along.action_visits()))
            }
            (false, false) => Answer::Action(
                match self.advise(asker, state, features, along.intended()) {
                    None => AdviceAnswer::Declined,
                    Some(action) => match self.strategy.advisor_value() {
                        Some(value) => AdviceAnswer::Recommendation(action, value as f32),
                        None => AdviceAnswer::Advice(action),
                    },
                },
            ),
        }
    }

    /// Counts one answer given; with `announce_exhausted`, the first that
    /// spends the give budget has everyone told.
    fn gave(&mut self) {
        self.counters.advice_given += 1;
        self.note_exhaustion();
    }

    /// Readies the announcement when the give budget is spent and it has
    /// not announced yet.
    fn note_exhaustion(&mut self) {
        if self.config.announce_exhausted
            && !self.announced
            && self.strategy.exhausted(&self.counters)
        {
            self.announced = true;
            self.announcement = true;
        }
    }

    /// What it knows of `state` (nothing where training never met it) when
    /// its strategy is willing to give about it now to agent `asker`, which
    /// took each action there `asker_visits` times (if it says); `None`
    /// outside training or when it is not.
    fn willing(
        &mut self,
        asker: usize,
        state: &State,
        features: &[f32],
        asker_visits: Option<[u32; ACTIONS]>,
    ) -> Option<Known> {
        if !self.training() {
            return None;
        }
        let index = self.states.get(self.tiling.key(state));
        let known = match index {
            Some(i) => Known {
                visits: self.states.visits(i),
                action_visits: self.states.action_visits(i),
                values: self.learner.values(Seen {
                    state,
                    features,
                    index: Some(i),
                }),
                index,
            },
            None => Known::default(),
        };
        let at = GiveContext {
            asker,
            state,
            features,
            visits: known.visits,
            action_visits: known.action_visits,
            values: &known.values,
            asker_visits,
            counters: &self.counters,
        };
        self.strategy.gives(&at, &mut self.rng).then_some(known)
    }

    /// Advisor side (Algorithm 2, or Torrey's teacher): the advice for
    /// advisee `asker`'s `state` (with its HFO features, if it sent them),
    /// or `None`. The answer is its greedy kick action, ties broken as its
    /// fidelity says. With `intended` (Mistake Correcting) it answers, and
    /// spends budget, only when its action differs.
    pub fn advise(
        &mut self,
        asker: usize,
        state: &State,
        features: &[f32],
        intended: Option<Action>,
    ) -> Option<Action> {
        let known = self.willing(asker, state, features, None)?;
        let ties = self.config.fidelity.advisor_ties;
        let honest = if self.strategy.suggests_its_choice() {
            let at = Seen {
                state,
                features,
                index: known.index,
            };
            self.learner.choose(at, &mut self.rng)
        } else {
            (self.strategy).advice(&known.values, ties, &mut self.rng)
        };
        let answer = self
            .config
            .advises
            .answer(honest, &known.values, &mut self.rng);
        if intended == Some(answer) {
            return None;
        }
        self.gave();
        Some(answer)
    }

    /// Sharer side (a value-sharing method): its values and visits of
    /// advisee `asker`'s `state` and HFO features (or only its best action
    /// and that action's value, as its strategy shares; `asker_visits`: the
    /// advisee's visits by action, if sent), or why none; one unit of its
    /// give budget.
    pub fn share_values(
        &mut self,
        asker: usize,
        state: &State,
        features: &[f32],
        asker_visits: Option<[u32; ACTIONS]>,
    ) -> ValuesAnswer {
        let Some(known) = self.willing(asker, state, features, asker_visits) else {
            return ValuesAnswer::Declined;
        };
        self.gave();
        if self.strategy.shares_best() {
            let best = greedy_first(&known.values.q);
            return ValuesAnswer::Best(best, known.values.q[best.index()]);
        }
        ValuesAnswer::Values(SharedValues {
            q: known.values.q,
            learned: known.values.learned,
            visits: known.visits,
        })
    }

    /// Replays a received goal episode as SARSA(lambda) updates with a fresh
    /// trace (separate from the agent's own), bootstrapping on the sharer's
    /// next actions or on Move, as its fidelity says.
    pub fn receive_shared(&mut self, transitions: &[Transition]) {
        if !self.training() {
            return;
        }
        self.counters.shared_received += transitions.len() as u64;
        let bootstrap = self.config.fidelity.shared_bootstrap;
        let indices: Vec<(usize, Option<usize>)> = transitions
            .iter()
            .map(|t| {
                let from = self.states.index_or_insert(self.tiling.key(&t.state));
                let next = t
                    .next
                    .map(|(s, _)| self.states.index_or_insert(self.tiling.key(&s)));
                (from, next)
            })
            .collect();
        let episode: Vec<Experience<'_>> = transitions
            .iter()
            .zip(&indices)
            .map(|(t, &(from, next))| {
                let from = Step {
                    at: Seen {
                        state: &t.state,
                        features: &[],
                        index: Some(from),
                    },
                    action: t.action,
                };
                let next = t.next.as_ref().zip(next).map(|((s, a), index)| Step {
                    at: Seen {
                        state: s,
                        features: &[],
                        index: Some(index),
                    },
                    action: match bootstrap {
                        SharedBootstrap::SharerAction => *a,
                        SharedBootstrap::Move => Action::Move,
                    },
                });
                (from, t.reward, next)
            })
            .collect();
        self.learner.replay(&episode);
    }

    /// Takes a batch of agent `from`'s experience in training: its strategy
    /// is told, then its learner learns as one batch what the strategy
    /// chooses (by default the batch's transitions; each state indexed
    /// where training met it, the sender's next actions as they were);
    /// counted as transitions received. Whether its learner learned it
    /// (false outside training, for a learner that cannot, or when its
    /// strategy chose nothing).
    pub fn receive_batch(&mut self, from: usize, batch: &Batch) -> bool {
        if !self.training() {
            return false;
        }
        self.counters.shared_received += batch.transitions.len() as u64;
        let chosen = self.strategy.received(from, batch);
        let transitions = match chosen.as_deref() {
            Some([]) => return false,
            Some(chosen) => chosen,
            None => &batch.transitions,
        };
        let index = |s: &State| self.states.get(self.tiling.key(s));
        let seen = |state, index| Seen {
            state,
            features: &[],
            index,
        };
        let batch: Vec<Experience<'_>> = (transitions.iter())
            .map(|t| {
                let from = Step {
                    at: seen(&t.state, index(&t.state)),
                    action: t.action,
                };
                let next = (t.next.as_ref()).map(|(s, a)| Step {
                    at: seen(s, index(s)),
                    action: *a,
                });
                (from, t.reward, next)
            })
            .collect();
        self.learner.learn_batch(&batch)
    }

    /// The advice its strategy reuses instead of asking, if any.
    fn reused(&mut self, key: u64, at: Seen<'_>) -> Option<Action> {
        let context = ReuseContext {
            key,
            state: at.state,
            features: at.features,
            training_episodes: self.training_episodes,
            counters: &self.counters,
        };
        let learner = &mut self.learner;
        let mut values = || learner.values(at);
        let reused = self.strategy.reuse(&context, &mut values, &mut self.rng);
        self.outcomes.reused += u64::from(reused.is_some());
        reused
    }

    /// Whether a training step with the ball (`at` state `index`) asks for
    /// advice, as its strategy decides.
    fn asks(&mut self, key: u64, index: usize, at: Seen<'_>) -> bool {
        let uncertainty = if self.strategy.asks_by_uncertainty() {
            self.learner.uncertainty(at)
        } else {
            None
        };
        let values = (self.strategy.asks_by_values()).then(|| self.learner.values(at));
        let at = AskContext {
            state: at.state,
            features: at.features,
            values,
            uncertainty,
            fresh: !self.advised.contains(&key),
            visits: self.states.visits(index),
            training_episodes: self.training_episodes,
            counters: &self.counters,
        };
        self.strategy.asks(&at, &mut self.rng)
    }

    /// Whom to ask among the `reachable` agents not announced spent, as its
    /// strategy decides (e.g. G(s)); the strategy hears when none of those
    /// it named is left.
    fn fill_reach(&mut self, positions: &[[f64; 2]], reachable: &dyn Fn(usize) -> bool) {
        (self.strategy).advisors(self.id, self.team_size, positions, &mut self.reach);
        let named = !self.reach.is_empty();
        let exhausted = &self.exhausted_peers;
        self.reach
            .retain(|&j| reachable(j) && !exhausted.get(j).copied().unwrap_or(false));
        if named && self.reach.is_empty() {
            self.strategy.advisors_unreachable();
        }
    }

    /// The intended action a Mistake Correcting advisee sends along: its
    /// learner's choice, or its greedy action for a strategy that intends
    /// greedily.
    fn intent(&mut self, at: Seen<'_>) -> Action {
        if self.strategy.intends_greedy() {
            greedy_random(&self.learner.values(at).q, &mut self.rng)
        } else {
            self.choose(at)
        }
    }

    /// Its learner's own choice in a training state with the ball.
    fn choose(&mut self, at: Seen<'_>) -> Action {
        self.learner.choose(at, &mut self.rng)
    }

    fn random_action(&mut self, can_kick: bool) -> Action {
        if can_kick {
            RANDOM_DRAW[self.rng.random_range(0..RANDOM_DRAW.len())]
        } else {
            Action::Move
        }
    }

    /// Learns one step, and tells its strategy (and the advisors whose
    /// advice arrived for it, if it reports to them) when it wants to know.
    fn learn(&mut self, prev: OpenStep, reward: f64, next: Option<OpenStep>) {
        self.learner
            .learn((prev.step(), reward, next.as_ref().map(OpenStep::step)));
        if prev.action.is_kick() && self.strategy.learns_from_outcomes() {
            self.tell_outcome(&prev, reward, next.as_ref());
        }
        if !self.open_advice.is_empty() {
            self.report_outcomes(&prev, reward, next.as_ref());
        }
        if self.strategy.records_transitions(&self.counters) {
            self.strategy.learned(&Transition {
                state: prev.state,
                action: prev.action,
                reward,
                next: next.map(|n| (n.state, n.action)),
            });
        }
    }

    /// Tells the strategy how a decision turned out: its advantage under
    /// the values just learned, r + gamma V(s') - V(s) (peer learning's
    /// Eq. 8 with `use_advantage`), so that an action worse than the best
    /// one known there counts against whoever advised it.
    fn tell_outcome(&mut self, prev: &OpenStep, reward: f64, next: Option<&OpenStep>) {
        let outcome = Outcome {
            advisor: prev.advisor,
            advantage: self.advantage(prev, reward, next),
        };
        self.strategy.learn_outcome(&outcome);
    }

    /// Readies a report for every advisor whose advice arrived for `prev`:
    /// whether it played that advice, and the decision's advantage.
    fn report_outcomes(&mut self, prev: &OpenStep, reward: f64, next: Option<&OpenStep>) {
        let advantage = self.advantage(prev, reward, next);
        let reports = std::mem::take(&mut self.open_advice).into_iter();
        self.reports.extend(reports.map(|a| AdviceReport {
            advisor: a.advisor,
            followed: a.action == prev.action,
            advantage,
        }));
    }

    /// A decision's advantage under the values just learned, r + gamma
    /// V(s') - V(s).
    fn advantage(&mut self, prev: &OpenStep, reward: f64, next: Option<&OpenStep>) -> f64 {
        let ahead = next.map_or(0.0, |n| self.state_value(n));
        reward + self.config.gamma * ahead - self.state_value(prev)
    }

    /// V of a step's state under its learner's values: the best learned
    /// kick action's value where it chose among them (its own action's if it
    /// learned none), its action's value where it could only move.
    fn state_value(&mut self, step: &OpenStep) -> f64 {
        let values = self.learner.values(step.at());
        let own = values.q[step.action.index()];
        if !step.action.is_kick() {
            return own;
        }
        (Action::KICK_TIE_ORDER.iter())
            .filter(|&&a| values.is_learned(a))
            .map(|&a| values.q[a.index()])
            .reduce(f64::max)
            .unwrap_or(own)
    }

    /// The learned state: every state met with its visit count and its
    /// learner's values (all unlearned for a learner that keeps its values
    /// itself), counters and finished training episodes.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            learner_state: self.learner.save_state(),
            ..self.framework_state()
        }
    }

    /// Its snapshot without a learner's own state (asked of no child).
    fn framework_state(&self) -> Snapshot {
        let values = self.learner.table().unwrap_or_default();
        let mut entries: Vec<(u64, Entry)> = (0..self.states.len())
            .map(|i| {
                let v = values.get(i).copied().unwrap_or_default();
                let entry = Entry {
                    q: v.q,
                    tried: v.learned,
                    visits: self.states.visits(i),
                };
                (self.states.key(i), entry)
            })
            .collect();
        entries.sort_unstable_by_key(|&(key, _)| key);
        Snapshot {
            tiling: self.tiling.params(),
            entries,
            counters: self.counters,
            training_episodes: self.training_episodes,
            learner_state: None,
        }
    }

    /// Replaces the learned state with a snapshot made under the same tiling;
    /// the current episode is forgotten.
    pub fn restore(&mut self, snapshot: Snapshot) -> Result<(), PersistError> {
        let current: TilingParams = self.tiling.params();
        if snapshot.tiling != current {
            return Err(PersistError::Incompatible {
                saved: snapshot.tiling,
                current,
            });
        }
        snapshot.check()?;
        let rows = (snapshot.entries.iter()).map(|(key, e)| (*key, e.visits, greedy_first(&e.q)));
        let states =
            StateIndex::from_rows(rows).map_err(|e| PersistError::Invalid(e.to_string()))?;
        let values = (snapshot.entries.iter())
            .map(|(_, e)| ActionValues {
                q: e.q,
                learned: e.tried,
            })
            .collect();
        let own = self.config.learner.name();
        match &snapshot.learner_state {
            Some(state) if crate::dqn::holds_dqn_state(state) && own != "dqn" => Err(format!(
                "it holds a DQN's network (saved by an agent of learner dqn), and this agent \
                 learns with {own}: load it into an agent of learner = \"dqn\" with the same \
                 hidden layers and heads"
            )),
            Some(state) => self.learner.load_state(state),
            None => self.learner.restore(values),
        }
        .map_err(PersistError::Invalid)?;
        self.states = states;
        self.counters = snapshot.counters;
        self.training_episodes = snapshot.training_episodes;
        self.announced = false;
        self.note_exhaustion();
        self.begin_episode(self.mode);
        Ok(())
    }

    /// A stable digest of the learned state the framework holds (see
    /// [`Snapshot::digest`]; a learner's own state is not asked for).
    pub fn digest(&self) -> u64 {
        self.framework_state().digest()
    }
}

/// What a strategy sends, within the wire's bounds: a batch cut to its
/// first [`MAX_BATCH`] transitions (and notes), its notes dropped unless
/// the wire takes them (one per transition, each of a frame or more,
/// [`proto::MAX_BATCH_FRAMES`] in all, finite), its standing dropped
/// unless finite; a second batch to the same receiver dropped.
fn bounded(sends: Sends) -> Sends {
    let mut batched = Vec::new();
    (sends.into_iter())
        .filter_map(|(to, share)| match share {
            Share::Batch(_) if batched.contains(&to) => None,
            Share::Batch(mut batch) => {
                batched.push(to);
                batch.transitions.truncate(MAX_BATCH);
                batch.notes.truncate(MAX_BATCH);
                let frames: u64 = batch.notes.iter().map(|n| u64::from(n.frames)).sum();
                let notes_fit = batch.notes.len() == batch.transitions.len()
                    && frames <= proto::MAX_BATCH_FRAMES
                    && (batch.notes.iter()).all(|n| n.frames > 0 && n.uncertainty.is_finite());
                if !notes_fit {
                    batch.notes.clear();
                }
                batch.standing = batch.standing.filter(proto::Standing::is_finite);
                Some((to, Share::Batch(batch)))
            }
            episode => Some((to, episode)),
        })
        .collect()
}

#[cfg(test)]
mod tests;
