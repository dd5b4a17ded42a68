//! The simulator side of a run, without any I/O of its own: the run's
//! simulators, the episode being played, the observations it shows and the
//! actions it awaits. Its simulators are the in-process backend's
//! (`RunEnvs`: one training simulator per run seeded at Reset, and an
//! evaluation block begun whenever `PlayEpisode` carries a seed), or the
//! real HFO (one server for the whole run, seeds only at its start).

use env_server::MAX_OFFENSE;
use env_server::{EnvConfig, Outcome, RunEnvs};
use proto::{
    Action, ActionChoice, AgentFrame, Body, Envelope, EpisodeResult, Features, Header, Mode,
    Simulator,
};

use super::real_hfo::{RealHfo, RealHfoInstall};
use super::simulator::ServedSimulator;

/// The simulators of one run.
#[derive(Debug)]
#[allow(
    clippy::large_enum_variant,
    reason = "one per run, made at its reset and never moved after"
)]
pub enum ServedRun {
    /// Ours: a training simulator and the current evaluation block's.
    Ours(RunEnvs),
    /// The real HFO, one server for training and evaluation alike; whether
    /// an evaluation block began.
    RealHfo(RealHfo, bool),
}

impl ServedRun {
    /// The simulators of a run with settings `config` (an `EnvConfig`
    /// encoded with `proto::encode_settings`), the training one seeded with
    /// `seed`, on the simulator `kind`, which must be the one this server
    /// plays (the real HFO when `real_hfo` says where it is), whose agents
    /// of `features` (bit `i` for agent `i`) are given HFO's features,
    /// which only ours computes; the error is one line.
    pub fn new(
        config: &[u8],
        seed: u64,
        (kind, features): (Simulator, u8),
        real_hfo: Option<&RealHfoInstall>,
    ) -> Result<Self, String> {
        let config: EnvConfig =
            proto::decode_settings(config).map_err(|e| format!("invalid env config: {e}"))?;
        config
            .validate()
            .map_err(|e| format!("invalid env config: {e}"))?;
        if u32::from(features) >> config.offense != 0 {
            return Err(format!(
                "HFO's features are asked for agents {features:#b} of a team of {}",
                config.offense
            ));
        }
        if features != 0 && kind == Simulator::RealHfo {
            return Err("the real HFO's backend gives the paper's state only: \
                        observation = \"hfo\" needs our simulator"
                .to_owned());
        }
        match (kind, real_hfo) {
            (Simulator::Ours, None) => RunEnvs::new(config, seed)
                .map(ServedRun::Ours)
                .map_err(|e| format!("invalid env config: {e}")),
            (Simulator::RealHfo, Some(install)) => {
                let hfo = RealHfo::start(install, &config, seed)?;
                Ok(ServedRun::RealHfo(hfo, false))
            }
            (Simulator::RealHfo, None) => Err(
                "the experiment plays the real HFO, this env-server our simulator: \
                 start it with --real-hfo DIR"
                    .to_owned(),
            ),
            (Simulator::Ours, Some(_)) => Err(
                "the experiment plays our simulator, this env-server the real HFO \
                 (--real-hfo): start it without"
                    .to_owned(),
            ),
        }
    }

    /// Number of offense agents.
    pub fn offense(&self) -> usize {
        match self {
            ServedRun::Ours(envs) => envs.offense(),
            ServedRun::RealHfo(hfo, _) => hfo.offense(),
        }
    }

    /// The simulator of an episode in `mode`: `seed` first begins a new
    /// evaluation block (the real HFO plays on, unseeded); evaluation needs
    /// one.
    pub fn prepare(
        &mut self,
        mode: Mode,
        seed: Option<u64>,
    ) -> Result<&mut dyn ServedSimulator, String> {
        if let Some(seed) = seed {
            match self {
                ServedRun::Ours(envs) => envs.begin_evaluation(seed),
                ServedRun::RealHfo(_, evaluating) => *evaluating = true,
            }
        }
        self.env(mode)
            .ok_or_else(|| "evaluation episode before any evaluation seed".to_owned())
    }

    /// The simulator of `mode`, if there is one (see [`ServedRun::prepare`]).
    pub fn env(&mut self, mode: Mode) -> Option<&mut dyn ServedSimulator> {
        match self {
            ServedRun::Ours(envs) => envs.env(mode).map(|env| env as &mut dyn ServedSimulator),
            ServedRun::RealHfo(hfo, evaluating) => match mode {
                Mode::Training => Some(hfo),
                Mode::Evaluation if *evaluating => Some(hfo),
                Mode::Evaluation => None,
            },
        }
    }
}

/// What became of an offered action.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Offer {
    /// Taken as the agent's action for this frame.
    Accepted,
    /// Not of the current run, episode and frame.
    Stale,
    /// The agent's action for this frame was already taken.
    Duplicate,
    /// From an agent that has no decision to make this frame.
    Unexpected,
}

/// An episode being played: its position in the stream and the actions of
/// the current frame.
#[derive(Debug)]
pub struct Episode {
    /// Run, episode and current frame.
    pub header: Header,
    /// Training or evaluation.
    pub mode: Mode,
    offense: usize,
    /// Agents given HFO's features (bit `i` for agent `i`).
    features: u8,
    /// Agents that can kick this frame (bit `i` for agent `i`).
    kickers: u8,
    /// Kickers whose action has not arrived yet.
    awaited: u8,
    actions: [Action; MAX_OFFENSE],
    /// Reward of the transition that led to the current frame.
    reward: f64,
    outcome: Outcome,
    /// Awaited actions that did not come in time, over the episode.
    timed_out: u32,
}

impl Episode {
    /// Starts an episode on `env` (which resets it) at frame 0 of `header`,
    /// giving the agents of `features` (bit `i` for agent `i`) HFO's
    /// features.
    pub fn start(
        env: &mut dyn ServedSimulator,
        header: Header,
        mode: Mode,
        features: u8,
    ) -> Result<Self, String> {
        env.reset()?;
        let mut episode = Episode {
            header: Header { frame: 0, ..header },
            mode,
            offense: env.offense(),
            features,
            kickers: 0,
            awaited: 0,
            actions: [Action::Move; MAX_OFFENSE],
            reward: 0.0,
            outcome: Outcome::InGame,
            timed_out: 0,
        };
        episode.await_kickers(env);
        Ok(episode)
    }

    /// Whether the episode has reached its terminal frame.
    pub fn is_over(&self) -> bool {
        self.outcome.is_terminal()
    }

    /// Whether some kicker's action has not arrived yet.
    pub fn is_waiting(&self) -> bool {
        self.awaited != 0
    }

    /// The agents whose action has not arrived yet.
    pub fn missing(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.offense).filter(|i| self.awaited & (1 << i) != 0)
    }

    /// The step timeout passed: the missing actions count as timed out and
    /// stay Move.
    pub fn time_out(&mut self) {
        self.timed_out += self.awaited.count_ones();
        self.awaited = 0;
    }

    /// Agent `agent`'s observation of the current frame, with HFO's
    /// features if it is given them. The terminal frame carries the final
    /// reward, how the episode ended and no decision.
    pub fn observe(&self, env: &dyn ServedSimulator, agent: usize) -> AgentFrame {
        let features = match self.features >> agent & 1 {
            1 => env.features(agent).unwrap_or_default(),
            _ => Features::NONE,
        };
        AgentFrame {
            agent: agent as u8,
            mode: self.mode,
            state: env.state(agent),
            features,
            can_kick: self.kickers & (1 << agent) != 0,
            positions: env.positions(),
            reward: self.reward,
            outcome: self.outcome.ended(),
        }
    }

    /// Offers an action received with `header`.
    pub fn offer(&mut self, header: &Header, choice: &ActionChoice) -> Offer {
        let h = &self.header;
        if (header.run, header.episode, header.frame) != (h.run, h.episode, h.frame) {
            return Offer::Stale;
        }
        let bit = 1u8.checked_shl(u32::from(choice.agent)).unwrap_or(0);
        if usize::from(choice.agent) >= self.offense || self.kickers & bit == 0 {
            return Offer::Unexpected;
        }
        if self.awaited & bit == 0 {
            return Offer::Duplicate;
        }
        self.awaited &= !bit;
        self.actions[usize::from(choice.agent)] = choice.action;
        Offer::Accepted
    }

    /// Steps `env` with the actions received, Move for every agent whose
    /// action is missing or who could not kick, and moves to the next frame.
    pub fn step(&mut self, env: &mut dyn ServedSimulator) -> Result<(), String> {
        let outcome = env.step(&self.actions[..self.offense])?;
        self.outcome = outcome;
        self.reward = outcome.reward();
        self.header.frame = env.frame();
        self.actions = [Action::Move; MAX_OFFENSE];
        if outcome.is_terminal() {
            self.kickers = 0;
            self.awaited = 0;
        } else {
            self.await_kickers(env);
        }
        Ok(())
    }

    /// The result, once the episode is over.
    pub fn result(&self) -> Option<EpisodeResult> {
        Some(EpisodeResult {
            outcome: self.outcome.ended()?,
            frames: self.header.frame,
            actions_timed_out: self.timed_out,
        })
    }

    fn await_kickers(&mut self, env: &dyn ServedSimulator) {
        self.kickers = (0..self.offense)
            .filter(|&i| env.can_kick(i))
            .fold(0, |m, i| m | 1 << i);
        self.awaited = self.kickers;
    }
}

/// Each agent's observations of the frames not sent yet, sent as one
/// message per agent (docs/protocol.md, "Frames").
#[derive(Debug, Default)]
pub struct Batches {
    /// Run, episode and frame of the first observation held.
    first: Option<Header>,
    /// Per agent, its observations in frame order.
    frames: Vec<Vec<AgentFrame>>,
}

impl Batches {
    /// Adds every agent's observation of `episode`'s current frame on `env`.
    pub fn push(&mut self, episode: &Episode, env: &dyn ServedSimulator) {
        self.first.get_or_insert(episode.header);
        self.frames.resize_with(env.offense(), Vec::new);
        for (agent, frames) in self.frames.iter_mut().enumerate() {
            frames.push(episode.observe(env, agent));
        }
    }

    /// Whether one more frame would not fit in a message.
    pub fn is_full(&self) -> bool {
        self.frames
            .first()
            .is_some_and(|f| f.len() >= proto::MAX_FRAMES_PER_MESSAGE)
    }

    /// Each agent's message with the frames held, encoded, in agent order
    /// (none when no frame is held); the batches are left empty.
    pub fn take(&mut self) -> Vec<Vec<u8>> {
        let Some(first) = self.first.take() else {
            return Vec::new();
        };
        self.frames
            .iter_mut()
            .map(|frames| {
                let envelope = Envelope {
                    header: first,
                    body: Body::Observations(std::mem::take(frames)),
                };
                proto::encode(&envelope)
            })
            .collect()
    }

    /// Drops the frames held (an episode abandoned).
    pub fn clear(&mut self) {
        self.first = None;
        self.frames.iter_mut().for_each(Vec::clear);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use env_server::Env;
    use proto::State;

    fn header(run: u32, episode: u32, frame: u32) -> Header {
        Header::new(1, run, episode, frame)
    }

    /// An episode on a fresh simulator, stepped until some agent can kick.
    fn episode_with_kicker() -> (Env, Episode, usize) {
        let mut env = Env::new(EnvConfig::default(), 5).unwrap();
        let mut episode = Episode::start(&mut env, header(2, 3, 0), Mode::Training, 0).unwrap();
        while !episode.is_waiting() {
            assert!(!episode.is_over(), "no kicker before the episode ended");
            episode.step(&mut env).unwrap();
        }
        let kicker = episode.missing().next().unwrap();
        (env, episode, kicker)
    }

    #[test]
    fn actions_are_sorted_out() {
        let (_, mut e, k) = episode_with_kicker();
        let f = e.header.frame;
        let shoot = |agent| ActionChoice {
            agent: agent as u8,
            action: Action::Shoot,
        };
        assert_eq!(e.offer(&header(1, 3, f), &shoot(k)), Offer::Stale);
        assert_eq!(e.offer(&header(2, 2, f), &shoot(k)), Offer::Stale);
        assert_eq!(e.offer(&header(2, 3, f + 1), &shoot(k)), Offer::Stale);
        let other = (0..3).find(|&i| e.missing().all(|m| m != i)).unwrap();
        assert_eq!(e.offer(&header(2, 3, f), &shoot(other)), Offer::Unexpected);
        assert_eq!(e.offer(&header(2, 3, f), &shoot(9)), Offer::Unexpected);
        assert_eq!(e.offer(&header(2, 3, f), &shoot(200)), Offer::Unexpected);
        assert_eq!(e.offer(&header(2, 3, f), &shoot(k)), Offer::Accepted);
        assert_eq!(e.offer(&header(2, 3, f), &shoot(k)), Offer::Duplicate);
        assert!(e.missing().all(|m| m != k));
    }

    /// Agent `agent`'s message among `messages`, decoded.
    fn decoded(messages: &[Vec<u8>], agent: usize) -> (Header, Vec<AgentFrame>) {
        let envelope = proto::decode(&messages[agent], 1).unwrap();
        let Body::Observations(frames) = envelope.body else {
            panic!("not observations")
        };
        (envelope.header, frames)
    }

    #[test]
    fn plays_like_the_simulator_alone() {
        // Kickers shoot, the others move: the same episode as stepping the
        // simulator directly with the same seed. The frames are batched up
        // to each decision, as the server sends them.
        let mut env = Env::new(EnvConfig::default(), 11).unwrap();
        let mut e = Episode::start(&mut env, header(0, 0, 0), Mode::Training, 0).unwrap();
        let mut direct = Env::new(EnvConfig::default(), 11).unwrap();
        direct.reset();
        let mut batches = Batches::default();
        let mut pending = Vec::new();
        let mut messages = 0;
        loop {
            assert_eq!(e.header.frame, direct.frame());
            batches.push(&e, &env);
            pending.push((direct.frame(), direct.state(0)));
            if e.is_over() || e.is_waiting() {
                let sent = batches.take();
                assert_eq!(sent.len(), 3);
                assert!(batches.take().is_empty(), "taking empties the batches");
                let (first, frames) = decoded(&sent, 0);
                assert_eq!(first.frame, pending[0].0);
                let states: Vec<State> = frames.iter().map(|o| o.state).collect();
                let expected: Vec<State> = pending.drain(..).map(|(_, s)| s).collect();
                assert_eq!(states, expected);
                let last = frames.last().unwrap();
                assert!(frames[..frames.len() - 1].iter().all(|o| !o.is_terminal()));
                assert_eq!(last.is_terminal(), e.is_over());
                messages += 1;
            }
            if e.is_over() {
                break;
            }
            for k in e.missing().collect::<Vec<_>>() {
                let choice = ActionChoice {
                    agent: k as u8,
                    action: Action::Shoot,
                };
                let header = e.header;
                assert_eq!(e.offer(&header, &choice), Offer::Accepted);
            }
            let actions: Vec<Action> = (0..3)
                .map(|i| {
                    if direct.can_kick(i) {
                        Action::Shoot
                    } else {
                        Action::Move
                    }
                })
                .collect();
            direct.step(&actions);
            e.step(&mut env).unwrap();
        }
        let result = e.result().unwrap();
        assert_eq!(result.frames, direct.frame());
        assert!(
            messages > 1 && messages < result.frames,
            "{messages} messages"
        );
        let sent = {
            batches.push(&e, &env);
            batches.take()
        };
        let (_, frames) = decoded(&sent, 1);
        let obs = &frames[0];
        assert!(obs.is_terminal() && !obs.can_kick);
        assert_eq!(obs.reward, direct.outcome().reward());
    }

    #[test]
    fn hfos_features_go_to_the_agents_named_only() {
        let mut env = Env::new(EnvConfig::default(), 5).unwrap();
        let e = Episode::start(&mut env, header(0, 0, 0), Mode::Training, 0b010).unwrap();
        let seen: Vec<AgentFrame> = (0..3).map(|i| e.observe(&env, i)).collect();
        assert!(seen[0].features.is_empty() && seen[2].features.is_empty());
        let hfo: Vec<f32> = (env.current_features(1).iter())
            .map(|&x| x as f32)
            .collect();
        assert_eq!(seen[1].features.as_slice(), &hfo[..]);
        assert_eq!(seen[1].state, env.state(1));
        // proto's count is the simulator's, for every team it plays.
        assert_eq!(proto::MAX_FEATURE_TEAM, MAX_OFFENSE);
        for n in 1..=MAX_OFFENSE {
            let count = env_server::features::current_feature_count(n);
            assert_eq!(proto::hfo_feature_count(n), count);
        }
        // Agents beyond the team, and the real HFO, are refused.
        let default = settings(&EnvConfig::default());
        let e = ServedRun::new(&default, 1, (Simulator::Ours, 0b1000), None).unwrap_err();
        assert_eq!(
            e,
            "HFO's features are asked for agents 0b1000 of a team of 3"
        );
        let e = ServedRun::new(&default, 1, (Simulator::RealHfo, 0b1), None).unwrap_err();
        assert!(
            e.contains("observation = \"hfo\" needs our simulator"),
            "{e}"
        );
    }

    #[test]
    fn a_batch_is_full_at_the_message_limit() {
        let mut env = Env::new(EnvConfig::default(), 3).unwrap();
        let e = Episode::start(&mut env, header(1, 2, 0), Mode::Evaluation, 0).unwrap();
        let mut batches = Batches::default();
        for _ in 0..proto::MAX_FRAMES_PER_MESSAGE {
            assert!(!batches.is_full());
            batches.push(&e, &env);
        }
        assert!(batches.is_full());
        batches.clear();
        assert!(!batches.is_full());
        assert!(batches.take().is_empty());
    }

    fn ours(config: &[u8]) -> Result<ServedRun, String> {
        ServedRun::new(config, 1, (Simulator::Ours, 0), None)
    }

    fn settings(config: &EnvConfig) -> Vec<u8> {
        proto::encode_settings(config).unwrap()
    }

    #[test]
    fn evaluation_needs_a_seed_first() {
        let mut s = ours(&settings(&EnvConfig::default())).unwrap();
        assert!(s.prepare(Mode::Evaluation, None).is_err());
        assert!(s.prepare(Mode::Training, None).is_ok());
        assert!(s.prepare(Mode::Evaluation, Some(4)).is_ok());
        assert!(s.prepare(Mode::Evaluation, None).is_ok());
    }

    #[test]
    fn bad_settings_are_refused() {
        let nine = EnvConfig {
            offense: 9,
            ..EnvConfig::default()
        };
        let e = ours(&settings(&nine)).unwrap_err();
        assert!(e.contains("offense"), "{e}");
        let mut long = settings(&EnvConfig::default());
        long.push(1);
        for bytes in [&b"{"[..], &long] {
            let e = ours(bytes).unwrap_err();
            assert!(e.starts_with("invalid env config: "), "{e}");
        }
    }
}
