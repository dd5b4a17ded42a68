//! Learning agents for "ad hoc advising among simultaneously learning agents"
//! (da Silva, Glatt & Costa, AAMAS 2017): tile coding, a Q-table, SARSA(lambda)
//! and the advising strategies, exactly as in `docs/algorithms.md`.
//!
//! The library does no I/O besides saving and loading snapshots and knows no
//! transport: agents reach each other through [`AdviceExchange`], which
//! [`Team`] implements in process with direct calls. A networked agent
//! splits each frame in [`Agent::act_begin`] and [`Agent::act_complete`]
//! around its advice requests and ships [`Agent::take_shared`]'s episodes
//! and batches and [`Agent::take_reports`]' reports.
//!
//! Driving a [`Team`]: one training episode, then one evaluation episode
//! (frozen: greedy play, nothing learned, asked or given).
//! ```
//! use agent::{Agent, AgentConfig, EpisodeOutcome, Features, Mode, Observation, Profile, Team};
//! use proto::Action;
//!
//! let config = AgentConfig::of("adhoc-td".parse()?, Profile::Paper);
//! let agents = (0..3).map(|i| Agent::new(i, 3, config.clone(), 100 + i as u64)).collect::<Result<_, _>>()?;
//! let mut team = Team::new(agents)?;
//! let obs = |kicker: bool| Observation {
//!     state: [0.0; 6],
//!     features: Features::NONE, // HFO's features, for a learner that reads them
//!     can_kick: kicker,
//!     position: [0.0, 0.0],
//! };
//! for mode in [Mode::Training, Mode::Evaluation] {
//!     team.begin_episode(mode);
//!     let mut frame = [obs(true), obs(false), obs(false)]; // the simulator's reset
//!     let mut reward = 0.0; // ignored on the first frame
//!     for _ in 0..3 {
//!         let actions = team.act(&frame, reward)?; // closes the last step, picks actions
//!         assert_eq!(actions[2], Action::Move); // only a kicker chooses
//!         // Step the simulator with `actions`; it returns the next frame and
//!         // the shared reward (0 until the terminal step).
//!         (frame, reward) = ([obs(false), obs(true), obs(false)], 0.0);
//!     }
//!     team.end_episode(EpisodeOutcome::Goal); // its reward: +1 goal, -1 captured or out, 0 time-out
//! }
//! let spent: Vec<u64> = team.agents().iter().map(Agent::spent_budget).collect();
//! # assert_eq!(spent.len(), 3);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

mod advice;
mod advice_counters;
mod advises;
mod agent;
mod algorithm;
mod algorithm_settings;
mod cloning;
mod config;
mod config_error;
mod dqn;
mod ensemble;
mod exchange;
mod fidelity;
mod learner;
mod learner_settings;
mod learners;
mod link;
mod method;
mod net;
mod persist;
mod rnd;
mod sarsa;
mod selection;
mod states;
mod strategy;
mod team;
mod tiles;
mod transfer;

pub use advice::{Reachable, p_ask, p_give, psi_td, psi_visit};
pub use advice_counters::{AdviceCounters, RequestOutcomes};
pub use advises::Advises;
pub use agent::{Agent, Decision, Observation};
pub use algorithm::{Algorithm, UnknownAlgorithm};
pub use algorithm_settings::AlgorithmSettings;
pub use config::AgentConfig;
pub use config_error::AgentConfigError;
pub use dqn::Dqn;
pub use ensemble::EnsembleSarsa;
pub use exchange::{
    Advice, AdviceExchange, AdviceReport, Answer, Answers, Batch, BestValue, Isolated, Share,
    Transition, ValuesAdvice,
};
pub use fidelity::{
    AdvisorTies, Fidelity, Profile, SharedBootstrap, TorreyIntent, TorreyUnknownState, VoteTies,
};
pub use learner::{ActionValues, Experience, Learner, Seen, Step};
pub use learner_settings::{
    DqnSettings, LearnerSettings, MAX_DQN_HEADS, MAX_HIDDEN_LAYERS, MAX_HIDDEN_WIDTH, MAX_REPLAY,
    ObservationSet,
};
pub use link::{Latency, Leg, Link, Message, NetworkConditions};
pub use method::{LearnerNeed, Seat};
pub use persist::{Entry, PersistError, SNAPSHOT_FORMAT_VERSION, Snapshot, snapshot_file};
pub use proto::{EpisodeOutcome, Features, MAX_BATCH, Mode, Standing, TransitionNote};
pub use sarsa::TabularSarsa;
pub use selection::{ACTIONS, AgentRng};
pub use strategy::{
    AdHoc, Adopted, AdviceImitation, AdviceReuse, AdvisingStrategy, AskContext, Collection,
    Confidence, EarlyAdvising, EfOntl, EndContext, EpisodeSharing, GiveContext, NoSettings,
    Outcome, OwnChoice, PeerLearning, Psaf, PsafShares, RandomAdvising, Rcmp, Replies,
    ReuseContext, ReuseRule, Sends, TeacherRule, Torrey,
};
pub use team::{AdvisingTraffic, Team, TeamError};
pub use tiles::TilingParams;
