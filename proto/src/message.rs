//! The messages every process exchanges, and the header they all carry.

use std::fmt;
use std::hash::Hasher;

use serde::{Deserialize, Serialize};

use crate::action::{Action, State};
use crate::features::Features;
use crate::traffic::{MessageCounters, MessageKind};

/// Version of the wire protocol; bumped on every incompatible change.
pub const PROTOCOL_VERSION: u16 = 13;

/// Where a message belongs: protocol version, experiment, run, episode, frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Header {
    /// [`PROTOCOL_VERSION`] of the sender.
    pub version: u16,
    /// Experiment id (see [`experiment_id`]).
    pub experiment: u64,
    /// Run index.
    pub run: u32,
    /// Episode index within the run (training and evaluation episodes alike).
    pub episode: u32,
    /// Frame (agent decision) within the episode.
    pub frame: u32,
}

impl Header {
    /// A header of this protocol version.
    pub fn new(experiment: u64, run: u32, episode: u32, frame: u32) -> Self {
        Header {
            version: PROTOCOL_VERSION,
            experiment,
            run,
            episode,
            frame,
        }
    }
}

/// A stable 64-bit id of an experiment name (FNV-1a), carried in every header.
pub fn experiment_id(name: &str) -> u64 {
    let mut h = fnv::FnvHasher::default();
    h.write(name.as_bytes());
    h.finish()
}

/// Whether an episode trains the agents or evaluates them frozen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mode {
    /// Learning, exploring and asking for advice.
    Training,
    /// Frozen: greedy play, nothing learned, asked or given.
    Evaluation,
}

/// What env-server plays an experiment's episodes on: our simulator, or
/// the real HFO behind it (`env-server serve --real-hfo`). A Reset that
/// names the other one is refused, so an experiment never mixes them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Simulator {
    /// This project's simulator, `env_server::Env`: deterministic.
    #[default]
    Ours,
    /// The real HFO (rcssserver, agent2d's goalkeeper) as a child process
    /// of env-server: not deterministic.
    RealHfo,
}

impl Simulator {
    /// The name as files and the command line write it.
    pub fn name(self) -> &'static str {
        match self {
            Simulator::Ours => "ours",
            Simulator::RealHfo => "real-hfo",
        }
    }
}

/// One message: a header and its body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Envelope {
    /// Where the message belongs.
    pub header: Header,
    /// What it says.
    pub body: Body,
}

/// What a message says.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Body {
    /// env-server -> agent: its observations of consecutive frames, the
    /// first of the header's frame, at most [`MAX_FRAMES_PER_MESSAGE`]:
    /// every frame since its last message, up to one where some agent can
    /// kick or the episode ends.
    Observations(Vec<AgentFrame>),
    /// agent -> env-server: the action of an agent that was asked to act.
    Action(ActionChoice),
    /// agent -> agents in G: a request for advice (query payload).
    AdviceRequest(AdviceRequest),
    /// advisor -> advisee: the reply to a request (query reply).
    AdviceReply(AdviceReply),
    /// agent -> agent: transitions of a goal episode (EpisodeSharing).
    SharedEpisode(SharedEpisode),
    /// coordinator -> process: a command (query payload).
    Control(Control),
    /// process -> coordinator: the answer to a command (query reply).
    ControlReply(ControlReply),
    /// advisor -> advisee: the reply of a method that shares values instead
    /// of actions (query reply).
    ValuesReply(ValuesReply),
    /// advisor -> every agent: its give budget is spent; it will answer no
    /// more requests (with `announce_exhausted`).
    Exhausted(Exhausted),
    /// agent -> agents in G: a request for advice with HFO's features of
    /// the state, from an agent whose observations carry them (query
    /// payload).
    FeaturedRequest(FeaturedRequest),
    /// agent -> agent: experience its strategy sends unasked at an
    /// episode's end, learned as one batch (at most [`MAX_BATCH`]
    /// transitions).
    ExperienceBatch(ExperienceBatch),
    /// advisee -> advisor: how a decision on its advice turned out (sent
    /// only by a strategy that reports advice outcomes).
    AdviceOutcome(AdviceOutcome),
}

/// One agent's observation of a frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AgentFrame {
    /// The observing agent.
    pub agent: u8,
    /// Training or evaluation episode.
    pub mode: Mode,
    /// The paper's 6 features.
    pub state: State,
    /// HFO's features of the state, for an agent whose learner reads them
    /// (env-server's `Reset` names those agents); none for the others.
    pub features: Features,
    /// Whether the agent can kick (and so has a decision to make).
    pub can_kick: bool,
    /// Field positions of every offense agent, by id (for distance-based G).
    pub positions: Vec<[f64; 2]>,
    /// Reward of the transition that led here.
    pub reward: f64,
    /// How the episode ended, on the frame that ends it (no action
    /// expected then); `None` before.
    pub outcome: Option<EpisodeOutcome>,
}

impl AgentFrame {
    /// Whether this frame ends the episode.
    pub fn is_terminal(&self) -> bool {
        self.outcome.is_some()
    }
}

/// The most frames one observation message may carry.
pub const MAX_FRAMES_PER_MESSAGE: usize = 64;

/// An agent's chosen action for a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ActionChoice {
    /// The acting agent.
    pub agent: u8,
    /// Its action.
    pub action: Action,
}

/// A request for advice about a state.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdviceRequest {
    /// The asking agent.
    pub from: u8,
    /// Its state.
    pub state: State,
    /// What the request carries beside the state.
    pub along: Along,
}

/// A request for advice about a state, with HFO's features of it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FeaturedRequest {
    /// The request.
    pub request: AdviceRequest,
    /// The asker's features of its state.
    pub features: Features,
}

/// What a request carries beside the state. (Encoded as the
/// `Option<Action>` of the intended action was, plus one variant.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Along {
    /// Nothing.
    #[default]
    Nothing,
    /// Its intended action (Mistake Correcting).
    Intended(Action),
    /// How often it took each action in the state, m(s, a) by action index
    /// (PSAF's partaker, whose sharers compare their confidence with it).
    ActionVisits([u32; 5]),
}

impl Along {
    /// The intended action, if carried.
    pub fn intended(self) -> Option<Action> {
        match self {
            Along::Intended(action) => Some(action),
            _ => None,
        }
    }

    /// The asker's visits by action, if carried.
    pub fn action_visits(self) -> Option<[u32; 5]> {
        match self {
            Along::ActionVisits(visits) => Some(visits),
            _ => None,
        }
    }
}

/// What an advisor answers to a request: advice, none, or none because its
/// give budget is spent. (Encoded as `Option<Action>` was, plus one value.)
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum AdviceAnswer {
    /// No advice: the advisor is not confident, or agrees (Mistake
    /// Correcting), or does not advise now.
    Declined,
    /// The advised action.
    Advice(Action),
    /// No advice: its give budget is spent.
    Exhausted,
    /// A recommended action with what the advisor says of itself (peer
    /// learning's value of an agent).
    Recommendation(Action, f32),
}

/// An advisor's answer to a request.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdviceReply {
    /// The answering agent.
    pub from: u8,
    /// Its answer.
    pub answer: AdviceAnswer,
}

/// A sharer's values of a state: what a value-sharing advisor answers.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SharedValues {
    /// Q(s, a) by action index.
    pub q: [f64; 5],
    /// Bit `a` set where Q(s, a) is learned.
    pub learned: u8,
    /// The sharer's visits n(s).
    pub visits: u64,
}

impl SharedValues {
    /// Whether the values can be taken: finite, and learned bits of the
    /// five actions only.
    pub fn is_valid(&self) -> bool {
        self.q.iter().all(|q| q.is_finite()) && self.learned < 1 << 5
    }
}

/// What a value-sharing advisor answers: its values, none, or none because
/// its give budget is spent. (Encoded as `Option<SharedValues>` was, plus
/// one value.)
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ValuesAnswer {
    /// No values: the sharer is not confident.
    Declined,
    /// Its values of the state.
    Values(SharedValues),
    /// No values: its give budget is spent.
    Exhausted,
    /// Its best action in the state and that action's value, max_a Q(s, a)
    /// (PSAF's sharer).
    Best(Action, f64),
}

/// A value-sharing advisor's answer to a request.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ValuesReply {
    /// The answering agent.
    pub from: u8,
    /// Its answer.
    pub answer: ValuesAnswer,
}

/// An advisor's announcement that its give budget is spent.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Exhausted {
    /// The announcing agent.
    pub from: u8,
}

/// One transition of a shared episode.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SharedTransition {
    /// State.
    pub state: State,
    /// Action taken.
    pub action: Action,
    /// Reward received.
    pub reward: f64,
    /// Next state and action, `None` at the terminal step.
    pub next: Option<(State, Action)>,
}

/// Transitions of a goal episode sent to one receiver.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SharedEpisode {
    /// The sharing agent.
    pub from: u8,
    /// The receiver.
    pub to: u8,
    /// The transitions, in order.
    pub transitions: Vec<SharedTransition>,
}

impl SharedTransition {
    /// A transition from its parts as a program outside Rust writes them
    /// (actions by [`Action::index`]), or why it is none: an action out of
    /// range, a next state without a next action or the reverse, a number
    /// that is not finite.
    pub fn from_parts(
        state: State,
        action: usize,
        reward: f64,
        (next_state, next_action): (Option<State>, Option<usize>),
    ) -> Result<Self, String> {
        let action_of = |a: usize| {
            (Action::ALL.get(a).copied())
                .ok_or_else(|| format!("action {a}, not one of 0 to {}", Action::ALL.len() - 1))
        };
        let next = match (next_state, next_action) {
            (Some(s), Some(a)) => Some((s, action_of(a)?)),
            (None, None) => None,
            _ => return Err("a next state without a next action, or the reverse".into()),
        };
        let transition = SharedTransition {
            state,
            action: action_of(action)?,
            reward,
            next,
        };
        match transition.is_finite() {
            true => Ok(transition),
            false => Err("a state or reward that is not a finite number".into()),
        }
    }

    /// Whether its states and reward are finite numbers.
    pub fn is_finite(&self) -> bool {
        let next = self.next.iter().flat_map(|(s, _)| s);
        (self.state.iter().chain(next)).all(|x| x.is_finite()) && self.reward.is_finite()
    }
}

/// The most transitions one [`ExperienceBatch`] may carry; a longer one is
/// malformed.
pub const MAX_BATCH: usize = 4096;

/// Experience one agent sends another unasked, which the receiver's learner
/// learns as one batch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ExperienceBatch {
    /// The sending agent.
    pub from: u8,
    /// The receiver.
    pub to: u8,
    /// The transitions, at most [`MAX_BATCH`], every number finite.
    pub transitions: Vec<SharedTransition>,
    /// What the sender notes of each transition: one per transition, or
    /// none.
    pub notes: Vec<TransitionNote>,
    /// The sender's standing, if it tells one.
    pub standing: Option<Standing>,
}

impl ExperienceBatch {
    /// Why it cannot be taken, if it cannot: more than [`MAX_BATCH`]
    /// transitions, notes neither one per transition nor none, notes
    /// spanning more than [`MAX_BATCH_FRAMES`] frames in all or a note of
    /// no frame, or a number that is not finite.
    pub fn check(&self) -> Result<(), String> {
        check_batch(&self.transitions, &self.notes, self.standing.as_ref())
    }
}

/// Why a batch of `transitions` with `notes` and `standing` cannot travel,
/// if it cannot ([`ExperienceBatch::check`]'s rules).
pub fn check_batch(
    transitions: &[SharedTransition],
    notes: &[TransitionNote],
    standing: Option<&Standing>,
) -> Result<(), String> {
    let n = transitions.len();
    if n > MAX_BATCH {
        return Err(format!(
            "an experience batch of {n} transitions, more than {MAX_BATCH}"
        ));
    }
    if !notes.is_empty() && notes.len() != n {
        return Err(format!(
            "an experience batch of {n} transitions with {} notes",
            notes.len()
        ));
    }
    if notes.iter().any(|t| t.frames == 0) {
        return Err("an experience batch with a note of no frame".into());
    }
    let frames: u64 = notes.iter().map(|t| u64::from(t.frames)).sum();
    if frames > MAX_BATCH_FRAMES {
        return Err(format!(
            "an experience batch whose notes span {frames} frames, more than \
             {MAX_BATCH_FRAMES}"
        ));
    }
    let finite = transitions.iter().all(SharedTransition::is_finite)
        && notes.iter().all(|t| t.uncertainty.is_finite())
        && standing.is_none_or(Standing::is_finite);
    match finite {
        true => Ok(()),
        false => Err("an experience batch with a number that is not finite".into()),
    }
}

/// The most frames the notes of one [`ExperienceBatch`] may span in all.
pub const MAX_BATCH_FRAMES: u64 = 1 << 18;

/// What a sender notes of one transition of a batch (EF-OnTL's tuple): the
/// frames the decision spans, and its uncertainty of it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransitionNote {
    /// The frames from its kick to the next decision, at least 1.
    pub frames: u32,
    /// The sender's uncertainty of it (finite).
    pub uncertainty: f64,
}

/// What an agent tells its teammates of itself at a transfer event
/// (EF-OnTL).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Standing {
    /// Its training episodes so far.
    pub episodes: u64,
    /// The mean uncertainty of the experience it keeps; none while it keeps
    /// none.
    pub uncertainty: Option<f64>,
    /// Its mean episode return over its recent training episodes.
    pub mean_return: f64,
}

impl Standing {
    /// Whether its numbers are finite.
    pub fn is_finite(&self) -> bool {
        self.uncertainty.is_none_or(f64::is_finite) && self.mean_return.is_finite()
    }
}

/// An advisee's report to an advisor of how a decision on which it gave
/// advice turned out.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdviceOutcome {
    /// The advisee.
    pub from: u8,
    /// The advisor.
    pub to: u8,
    /// Whether the advisee played the action it advised.
    pub followed: bool,
    /// The decision's advantage, r + gamma V(s') - V(s) under the
    /// advisee's values (finite).
    pub advantage: f64,
}

/// The longest wait a [`Control::Reset`] may set (ms): a minute.
pub const MAX_WAIT_MS: u64 = 60_000;

/// The longest stall limit a [`Control::Reset`] may set (ms): ten minutes.
pub const MAX_STALL_MS: u64 = 600_000;

/// A coordinator's command to env-server or an agent. Its `Debug` form
/// gives the size of byte payloads, not the bytes.
#[derive(Clone, PartialEq, Serialize, Deserialize)]
pub enum Control {
    /// Start run `header.run` afresh: new learner (agents) or simulator (env-server)
    /// from `config` and `seed`, waiting `wait_ms` for others.
    Reset {
        /// Seed of the process's random stream for this run.
        seed: u64,
        /// The process's settings (`AgentConfig` or `EnvConfig`), encoded
        /// with [`encode_settings`](crate::encode_settings).
        config: Vec<u8>,
        /// How long the process waits for others in this run (ms): an agent
        /// for advice after asking, env-server for a kicker's action before
        /// Move. Part of the experiment's recorded settings; 1 to
        /// [`MAX_WAIT_MS`].
        wait_ms: u64,
        /// env-server: how long a kicker may go on sending no action, frame
        /// after frame, before the episode is abandoned (ms; `wait_ms` to
        /// [`MAX_STALL_MS`]). Agents ignore it.
        stall_ms: u64,
        /// env-server: the simulator the experiment was configured for,
        /// refused when the server plays another. Agents ignore it.
        simulator: Simulator,
        /// env-server: the agents whose observations carry HFO's
        /// features, bit i for agent i. Agents ignore it.
        features: u8,
    },
    /// env-server: play episode `header.episode` in `mode` and report its result.
    PlayEpisode {
        /// Training or evaluation.
        mode: Mode,
        /// Reseed the simulator first (evaluation points use their own seeds).
        seed: Option<u64>,
    },
    /// Agent: replace its learned state with a snapshot, sent in parts
    /// ([`parts`](crate::parts)); it loads once the last has come.
    Load {
        /// This part's index, from 0.
        part: u32,
        /// How many parts the snapshot has.
        parts: u32,
        /// Part `part` of the bytes of a snapshot file (`agent::Snapshot::encode`).
        bytes: Vec<u8>,
    },
    /// Report counters, budgets and the digest of the learned state.
    Report,
    /// Agent: send part `part` of its learned state (the bytes of a
    /// snapshot file, in parts); part 0 takes the snapshot, the others
    /// come from it.
    Snapshot {
        /// The part wanted, from 0.
        part: u32,
    },
    /// Exit cleanly.
    Stop,
}

impl fmt::Debug for Control {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Control::Reset {
                seed,
                config,
                wait_ms,
                stall_ms,
                simulator,
                features,
            } => f
                .debug_struct("Reset")
                .field("seed", seed)
                .field("config", &ByteCount(config.len()))
                .field("wait_ms", wait_ms)
                .field("stall_ms", stall_ms)
                .field("simulator", simulator)
                .field("features", features)
                .finish(),
            Control::PlayEpisode { mode, seed } => f
                .debug_struct("PlayEpisode")
                .field("mode", mode)
                .field("seed", seed)
                .finish(),
            Control::Load { part, parts, bytes } => f
                .debug_struct("Load")
                .field("part", part)
                .field("parts", parts)
                .field("bytes", &ByteCount(bytes.len()))
                .finish(),
            Control::Report => f.write_str("Report"),
            Control::Snapshot { part } => f.debug_struct("Snapshot").field("part", part).finish(),
            Control::Stop => f.write_str("Stop"),
        }
    }
}

/// The size of a byte payload, as `Debug` shows it.
struct ByteCount(usize);

impl fmt::Debug for ByteCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "<{} bytes>", self.0)
    }
}

/// The answer to a [`Control`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ControlReply {
    /// Done.
    Ok,
    /// Result of a played episode.
    Episode(EpisodeResult),
    /// An agent's report.
    Agent(Box<AgentReport>),
    /// env-server's report.
    Server(Box<ServerReport>),
    /// Part of an agent's learned state, the bytes of a snapshot file.
    Snapshot {
        /// How many parts the snapshot has.
        parts: u32,
        /// The part asked for.
        bytes: Vec<u8>,
    },
    /// The command failed; the text says why.
    Error(String),
    /// The simulator (the real HFO, a child process) failed during the
    /// episode, which was abandoned; env-server starts it afresh for the
    /// next `PlayEpisode`. The text says why.
    SimulatorFailed(String),
}

/// How an episode ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum EpisodeOutcome {
    /// Goal.
    Goal,
    /// Captured by the keeper.
    Captured,
    /// Out of bounds.
    OutOfBounds,
    /// Out of time.
    OutOfTime,
}

impl EpisodeOutcome {
    /// Its name as a strategy written outside Rust reads it.
    pub fn name(self) -> &'static str {
        match self {
            EpisodeOutcome::Goal => "goal",
            EpisodeOutcome::Captured => "captured",
            EpisodeOutcome::OutOfBounds => "out_of_bounds",
            EpisodeOutcome::OutOfTime => "out_of_time",
        }
    }

    /// The paper's team reward at the end: +1 goal, -1 captured or out of
    /// bounds, 0 out of time.
    pub fn reward(self) -> f64 {
        match self {
            EpisodeOutcome::Goal => 1.0,
            EpisodeOutcome::Captured | EpisodeOutcome::OutOfBounds => -1.0,
            EpisodeOutcome::OutOfTime => 0.0,
        }
    }
}

/// Result of one episode played by env-server.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct EpisodeResult {
    /// How it ended.
    pub outcome: EpisodeOutcome,
    /// Agent decisions taken.
    pub frames: u32,
    /// Awaited actions that did not come within the step timeout (played as
    /// Move).
    pub actions_timed_out: u32,
}

/// An agent's counters and the digest of its learned state.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AgentReport {
    /// The agent.
    pub agent: u8,
    /// Digest of the Q-table and visit counts.
    pub digest: u64,
    /// Ask budget spent (advised steps).
    pub ask_spent: u64,
    /// Give budget spent (advice given, or transitions shared).
    pub give_spent: u64,
    /// Advice requests sent.
    pub advice_requests: u64,
    /// Advice replies received (with or without advice).
    pub advice_replies_received: u64,
    /// Advice given to others.
    pub advice_given: u64,
    /// What became of its requests: answered, declined, futile, lost; and
    /// the decisions that reused kept advice (`agent::RequestOutcomes`).
    pub request_outcomes: [u64; 5],
    /// Messages and bytes by kind and direction.
    pub messages: MessageCounters,
    /// Round-trip times of advice requests (ms), one per request with a reply.
    pub advice_rtt_ms: Vec<f32>,
    /// Teammates currently seen alive.
    pub alive_peers: Vec<u8>,
    /// Decisions it acted on each teammate's advice, by teammate id.
    pub advised_by: Vec<u64>,
}

/// env-server's counters.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ServerReport {
    /// Frames stepped.
    pub frames: u64,
    /// Actions that did not arrive within the step timeout (the fallback was used).
    pub actions_timed_out: u64,
    /// Messages and bytes by kind and direction.
    pub messages: MessageCounters,
}

impl MessageKind {
    /// The kind of a message body.
    pub fn of(body: &Body) -> Self {
        match body {
            Body::Observations(_) => MessageKind::Observation,
            Body::Action(_) => MessageKind::Action,
            Body::AdviceRequest(_) | Body::FeaturedRequest(_) => MessageKind::AdviceRequest,
            Body::AdviceReply(_) => MessageKind::AdviceReply,
            Body::ValuesReply(_) => MessageKind::ValuesReply,
            Body::Exhausted(_) => MessageKind::Exhausted,
            Body::SharedEpisode(_) => MessageKind::SharedEpisode,
            Body::ExperienceBatch(_) => MessageKind::ExperienceBatch,
            Body::AdviceOutcome(_) => MessageKind::AdviceOutcome,
            Body::Control(_) => MessageKind::Control,
            Body::ControlReply(_) => MessageKind::ControlReply,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn experiment_ids_are_fnv_1a() {
        // The published FNV-1a 64 test vectors.
        assert_eq!(experiment_id(""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(experiment_id("a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(experiment_id("foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn commands_show_the_size_of_their_payloads() {
        let reset = Control::Reset {
            seed: 3,
            config: vec![1, 2],
            wait_ms: 5,
            stall_ms: 10,
            simulator: Simulator::Ours,
            features: 0b101,
        };
        assert_eq!(
            format!("{reset:?}"),
            "Reset { seed: 3, config: <2 bytes>, wait_ms: 5, stall_ms: 10, simulator: Ours, \
             features: 5 }"
        );
        let load = Control::Load {
            part: 0,
            parts: 1,
            bytes: vec![0; 1000],
        };
        assert_eq!(
            format!("{load:?}"),
            "Load { part: 0, parts: 1, bytes: <1000 bytes> }"
        );
        let play = Control::PlayEpisode {
            mode: Mode::Training,
            seed: None,
        };
        assert_eq!(
            format!("{play:?}"),
            "PlayEpisode { mode: Training, seed: None }"
        );
        assert_eq!(format!("{:?}", Control::Stop), "Stop");
    }
}
