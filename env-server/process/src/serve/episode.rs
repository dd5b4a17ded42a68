//! The simulator side of a run, without any I/O: the run's simulators, the
//! episode being played, the observations it shows and the actions it
//! awaits. Mirrors the in-process backend of the coordinator: one training
//! simulator per run seeded at Reset, and an evaluation simulator replaced
//! by a fresh one whenever `PlayEpisode` carries a seed.

use env_server::analysis::MAX_OFFENSE;
use env_server::{Env, EnvConfig, Outcome};
use proto::{
    Action, ActionChoice, Body, Envelope, EpisodeOutcome, EpisodeResult, Header, Mode, Observation,
    State,
};

/// The simulators of one run.
#[derive(Debug)]
pub struct Simulators {
    config: EnvConfig,
    training: Env,
    evaluation: Option<Env>,
}

impl Simulators {
    /// The simulators of a run with settings `config` (an `EnvConfig`
    /// encoded with `proto::encode_settings`), the training one seeded with
    /// `seed`; the error is one line.
    pub fn new(config: &[u8], seed: u64) -> Result<Self, String> {
        let config: EnvConfig =
            proto::decode_settings(config).map_err(|e| format!("invalid env config: {e}"))?;
        let training =
            Env::new(config.clone(), seed).map_err(|e| format!("invalid env config: {e}"))?;
        Ok(Simulators {
            config,
            training,
            evaluation: None,
        })
    }

    /// Number of offense agents.
    pub fn offense(&self) -> usize {
        self.config.offense
    }

    /// The simulator of an episode in `mode`: `seed` first replaces the
    /// evaluation simulator by a fresh one; evaluation needs one.
    pub fn prepare(&mut self, mode: Mode, seed: Option<u64>) -> Result<&mut Env, String> {
        if let Some(seed) = seed {
            let env = Env::new(self.config.clone(), seed).map_err(|e| e.to_string())?;
            self.evaluation = Some(env);
        }
        self.env(mode)
            .ok_or_else(|| "evaluation episode before any evaluation seed".to_owned())
    }

    /// The simulator of `mode`, if there is one (see [`Simulators::prepare`]).
    pub fn env(&mut self, mode: Mode) -> Option<&mut Env> {
        match mode {
            Mode::Training => Some(&mut self.training),
            Mode::Evaluation => self.evaluation.as_mut(),
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
    /// Starts an episode on `env` (which resets it) at frame 0 of `header`.
    pub fn start(env: &mut Env, header: Header, mode: Mode) -> Self {
        env.reset();
        let mut episode = Episode {
            header: Header { frame: 0, ..header },
            mode,
            offense: env.offense(),
            kickers: 0,
            awaited: 0,
            actions: [Action::Move; MAX_OFFENSE],
            reward: 0.0,
            outcome: Outcome::InGame,
            timed_out: 0,
        };
        episode.await_kickers(env);
        episode
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

    /// Writes agent `agent`'s observation of the current frame, whose state
    /// is `state`, into `obs`. The terminal frame carries the final reward
    /// and no decision.
    pub fn observe(&self, env: &Env, agent: usize, state: State, obs: &mut Observation) {
        obs.agent = agent as u8;
        obs.mode = self.mode;
        obs.state = state;
        obs.can_kick = self.kickers & (1 << agent) != 0;
        obs.positions.clear();
        obs.positions
            .extend(env.world().offense.iter().map(|p| [p.pos.x, p.pos.y]));
        obs.reward = self.reward;
        obs.terminal = self.is_over();
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
    pub fn step(&mut self, env: &mut Env) {
        let outcome = env.step(&self.actions[..self.offense]);
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
    }

    /// The result, once the episode is over.
    pub fn result(&self) -> Option<EpisodeResult> {
        let outcome = match self.outcome {
            Outcome::InGame => return None,
            Outcome::Goal => EpisodeOutcome::Goal,
            Outcome::Captured => EpisodeOutcome::Captured,
            Outcome::OutOfBounds => EpisodeOutcome::OutOfBounds,
            Outcome::OutOfTime => EpisodeOutcome::OutOfTime,
        };
        Some(EpisodeResult {
            outcome,
            frames: self.header.frame,
            actions_timed_out: self.timed_out,
        })
    }

    fn await_kickers(&mut self, env: &Env) {
        self.kickers = (0..self.offense)
            .filter(|&i| env.can_kick(i))
            .fold(0, |m, i| m | 1 << i);
        self.awaited = self.kickers;
    }
}

/// One observation envelope, reused for every agent and frame.
pub struct ObservationSlot(Envelope);

impl ObservationSlot {
    /// An empty slot.
    pub fn new(experiment: u64) -> Self {
        ObservationSlot(Envelope {
            header: Header::new(experiment, 0, 0, 0),
            body: Body::Observation(Observation {
                agent: 0,
                mode: Mode::Training,
                state: [0.0; proto::STATE_FEATURES],
                can_kick: false,
                positions: Vec::with_capacity(MAX_OFFENSE),
                reward: 0.0,
                terminal: false,
            }),
        })
    }

    /// Agent `agent`'s observation of `episode`'s current frame, whose
    /// state is `state` (from [`Env::states`]), encoded.
    pub fn encode(&mut self, episode: &Episode, env: &Env, agent: usize, state: State) -> Vec<u8> {
        let Envelope { header, body } = &mut self.0;
        *header = episode.header;
        let Body::Observation(obs) = body else {
            unreachable!("the slot always holds an observation")
        };
        episode.observe(env, agent, state, obs);
        proto::encode(&self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(run: u32, episode: u32, frame: u32) -> Header {
        Header::new(1, run, episode, frame)
    }

    /// An episode on a fresh simulator, stepped until some agent can kick.
    fn episode_with_kicker() -> (Env, Episode, usize) {
        let mut env = Env::new(EnvConfig::default(), 5).unwrap();
        let mut episode = Episode::start(&mut env, header(2, 3, 0), Mode::Training);
        while !episode.is_waiting() {
            assert!(!episode.is_over(), "no kicker before the episode ended");
            episode.step(&mut env);
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

    #[test]
    fn plays_like_the_simulator_alone() {
        // Kickers shoot, the others move: the same episode as stepping the
        // simulator directly with the same seed.
        let mut env = Env::new(EnvConfig::default(), 11).unwrap();
        let mut e = Episode::start(&mut env, header(0, 0, 0), Mode::Training);
        let mut direct = Env::new(EnvConfig::default(), 11).unwrap();
        direct.reset();
        let mut slot = ObservationSlot::new(1);
        while !e.is_over() {
            assert_eq!(e.header.frame, direct.frame());
            let bytes = slot.encode(&e, &env, 0, env.state(0));
            let Body::Observation(obs) = proto::decode(&bytes, 1).unwrap().body else {
                panic!("not an observation")
            };
            assert_eq!(obs.state, direct.state(0));
            assert!(!obs.terminal);
            let kickers: Vec<usize> = e.missing().collect();
            for &k in &kickers {
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
            e.step(&mut env);
        }
        let result = e.result().unwrap();
        assert_eq!(result.frames, direct.frame());
        let bytes = slot.encode(&e, &env, 1, env.state(1));
        let Body::Observation(obs) = proto::decode(&bytes, 1).unwrap().body else {
            panic!("not an observation")
        };
        assert!(obs.terminal && !obs.can_kick);
        assert_eq!(obs.reward, direct.outcome().reward());
    }

    fn settings(config: &EnvConfig) -> Vec<u8> {
        proto::encode_settings(config).unwrap()
    }

    #[test]
    fn evaluation_needs_a_seed_first() {
        let mut s = Simulators::new(&settings(&EnvConfig::default()), 1).unwrap();
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
        let e = Simulators::new(&settings(&nine), 1).unwrap_err();
        assert!(e.contains("offense"), "{e}");
        let mut long = settings(&EnvConfig::default());
        long.push(1);
        for bytes in [&b"{"[..], &long] {
            let e = Simulators::new(bytes, 1).unwrap_err();
            assert!(e.starts_with("invalid env config: "), "{e}");
        }
    }
}
