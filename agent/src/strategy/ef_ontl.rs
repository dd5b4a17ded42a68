//! Expert-free online transfer learning, EF-OnTL (Castagna & Dusparic,
//! arXiv 2303.01170; docs/algorithms.md section 7): agents learning at the
//! same time transfer experience without an expert. Every `interval`
//! training episodes each agent tells its teammates its standing (how sure
//! its sars-RND is of what it keeps, and how it played lately); at the
//! next episode's end each picks the teacher among the standings it holds,
//! and the teacher sends every other agent the tuples it keeps with its
//! uncertainty of each; a receiver learns, by one gradient step of its DQN,
//! the `transfer_batch` of them whose sender's uncertainty is lowest
//! against its own (delta-confidence). Nobody asks or answers.
//!
//! The rules are the authors' library's, github:acastagn/EF-OnTL at
//! `4b3e42a` (research-57 section 3): the sars-RND (`crate::rnd`,
//! `SARSrnd.py`), the transfer buffer and delta-confidence
//! (`crate::transfer`, `transferBuffer.py`, `transferCoreEngine.py`
//! l.68-72, 91-96), the teacher choice (`transferCoreEngine.py` l.38-56)
//! and the receiver's one step (`agents/dueling_network.py` l.433-451).
//! Here every agent decides for itself from the messages it holds:
//! nothing central chooses.
//!
//! A tuple is one of the DQN's decisions, as its replay stores them (kick
//! to kick: the frames it moves without the ball folded into the kick's
//! discounted reward), so the agent folds the frames it learns as its DQN
//! does.
//!
//! What travels is a batch message (`proto::ExperienceBatch`): the tuples
//! as transitions, each with its note (the frames it spans, the sender's
//! uncertainty), and the sender's standing; the receiver's DQN learns the
//! chosen tuples' frames ([`Tuple::frames`]) by one gradient step.

use std::collections::VecDeque;

use proto::{Action, MAX_BATCH, MAX_BATCH_FRAMES, Standing, State, TransitionNote};
use serde::{Deserialize, Serialize};

use super::seam::{AdvisingStrategy, EndContext, Sends};
use crate::advice_counters::AdviceCounters;
use crate::config_error::AgentConfigError;
use crate::dqn::{KICKS, kick_slot};
use crate::exchange::{Batch, Share, Transition};
use crate::fidelity::{Fidelity, Profile};
use crate::learner_settings::LearnerSettings;
use crate::method::{LearnerNeed, Method, Seat};
use crate::rnd::{Rnd, RndSettings, Sars};
use crate::transfer::TransferBuffer;

/// The most tuples one message carries (the wire's bound on a batch).
const MAX_TUPLES: usize = MAX_BATCH;

/// The most tuples an agent keeps.
pub(crate) const MAX_BUFFER: u64 = 1_000_000;

/// How the agents pick the teacher of a transfer event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TeacherRule {
    /// The lowest mean stored uncertainty of its kept tuples (the
    /// library's `avg_uncertainty`).
    Uncertainty,
    /// The highest mean episode return over the last `interval` training
    /// episodes (the library's `best_performance`).
    Performance,
}

/// The settings of EF-OnTL (Castagna & Dusparic, arXiv 2303.01170), as
/// team files write them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EfOntl {
    /// Training episodes between transfer events, F, at least 1 (default
    /// 100).
    pub interval: u64,
    /// The tuples an agent keeps, its last N decisions (default 1000).
    pub buffer: u64,
    /// The tuples a receiver learns from at a transfer, B, 1 to `buffer`
    /// and at most 4096 (default 100).
    pub transfer_batch: u64,
    /// The tuples the teacher sends each receiver, its lowest-uncertainty
    /// ones, `transfer_batch` to `buffer` and at most 4096 (default none:
    /// all it keeps, which the library's rule picks among).
    pub candidates: Option<u64>,
    /// How the teacher is picked (default `uncertainty`).
    pub selection: TeacherRule,
}

impl Default for EfOntl {
    fn default() -> Self {
        Self {
            interval: 100,
            buffer: 1000,
            transfer_batch: 100,
            candidates: None,
            selection: TeacherRule::Uncertainty,
        }
    }
}

impl EfOntl {
    /// The first invalid setting, naming its key.
    pub(crate) fn validate(&self) -> Result<(), AgentConfigError> {
        let bad = |key: &str, reason: String| Err(AgentConfigError::new(key, reason));
        let (b, n) = (self.transfer_batch, self.buffer);
        if self.interval == 0 {
            return bad(
                "interval",
                "must be at least 1 (training episodes between transfers)".into(),
            );
        }
        if !(1..=MAX_BUFFER).contains(&n) {
            return bad("buffer", format!("must be 1 to {MAX_BUFFER}, got {n}"));
        }
        if b == 0 || b > MAX_TUPLES as u64 {
            return bad(
                "transfer_batch",
                format!("must be 1 to {MAX_TUPLES} (the tuples a batch message carries), got {b}"),
            );
        }
        if b > n {
            return bad(
                "transfer_batch",
                format!("must be at most `buffer` ({n}), got {b}"),
            );
        }
        match self.candidates {
            Some(c) if c < b || c > n.min(MAX_TUPLES as u64) => bad(
                "candidates",
                format!(
                    "must be `transfer_batch` ({b}) to `buffer` ({n}) and at most {MAX_TUPLES}, \
                     got {c}"
                ),
            ),
            None if n > MAX_TUPLES as u64 => bad(
                "buffer",
                format!(
                    "{n} tuples do not fit a batch message ({MAX_TUPLES}): set `candidates`, the \
                     tuples sent"
                ),
            ),
            _ => Ok(()),
        }
    }

    /// The tuples the teacher sends each receiver.
    fn sent(&self) -> usize {
        self.candidates.unwrap_or(self.buffer) as usize
    }
}

/// `ef-ontl`: expert-free online transfer learning.
pub(crate) struct EfOntlMethod;

impl Method for EfOntlMethod {
    type Settings = EfOntl;
    const NAME: &'static str = "ef-ontl";
    const ABOUT: &'static str = "expert-free online transfer: every interval episodes the surest \
                                 agent sends the experience its teammates are least sure of \
                                 (Castagna & Dusparic, 2023)";
    const LEARNER: LearnerNeed = LearnerNeed::Network;
    /// What it sends carries the paper's six features only.
    const SHARES_EPISODES: bool = true;

    fn defaults(_: Profile) -> EfOntl {
        EfOntl::default()
    }

    fn validate(settings: &EfOntl) -> Result<(), AgentConfigError> {
        settings.validate()
    }

    fn strategy(settings: &EfOntl, fidelity: &Fidelity) -> Box<dyn AdvisingStrategy> {
        let learner = LearnerSettings::for_need(LearnerNeed::Network);
        Self::strategy_for(settings, fidelity, &Seat::of(&learner))
    }

    /// It folds decisions with its agent's discount; its sars-RND's
    /// weights come from its agent's seed.
    fn strategy_for(settings: &EfOntl, _: &Fidelity, seat: &Seat<'_>) -> Box<dyn AdvisingStrategy> {
        Box::new(Transferrer(Transfers::new(settings, seat.gamma, seat.seed)))
    }
}

/// An EF-OnTL agent's decisions: its side of the transfers.
#[derive(Debug)]
struct Transferrer(Transfers);

impl AdvisingStrategy for Transferrer {
    /// The tuples it received (candidates, of which it learned
    /// `transfer_batch` at each transfer).
    fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        counters.shared_received
    }

    fn begin_episode(&mut self, _mode: proto::Mode) {
        self.0.begin_episode();
    }

    /// Always: its sars-RND learns every decision.
    fn records_transitions(&self, _counters: &AdviceCounters) -> bool {
        true
    }

    fn learned(&mut self, transition: &Transition) {
        self.0.learned(transition);
    }

    fn end_episode(&mut self, end: &EndContext<'_>) -> Sends {
        (self
            .0
            .end_episode(end.me, end.team_size, end.episode_return))
        .into_iter()
        .map(|(to, batch)| (to, Share::Batch(batch)))
        .collect()
    }

    /// The frames of the tuples it chose, for its DQN to fold as its own
    /// decisions and learn by one step.
    fn received(&mut self, from: usize, batch: &Batch) -> Option<Vec<Transition>> {
        let chosen = self.0.received(from, batch);
        Some(chosen.iter().flat_map(Tuple::frames).collect())
    }
}

/// The teacher among `standings` (each with its agent's id, in any order)
/// by `rule`, ties to the lowest id; none while some agent among them has
/// played fewer than `ep_start_sharing` training episodes (the library's
/// check, applied to both rules), or when none qualifies (no agent keeps a
/// tuple, by uncertainty).
pub(crate) fn teacher(
    rule: TeacherRule,
    standings: &[(usize, Standing)],
    ep_start_sharing: u64,
) -> Option<usize> {
    if standings.iter().any(|(_, s)| s.episodes < ep_start_sharing) {
        return None;
    }
    let mut ranked: Vec<(usize, f64)> = (standings.iter())
        .filter_map(|&(id, s)| match rule {
            TeacherRule::Uncertainty => s.uncertainty.map(|u| (id, u)),
            TeacherRule::Performance => Some((id, -s.mean_return)),
        })
        .collect();
    ranked.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    ranked.first().map(|&(id, _)| id)
}

/// One decision as it travels: the paper's state, the kick, the discounted
/// reward to the next decision, the next decision's state and kick (none
/// at the episode's end), the frames it spans, and the sender's stored
/// uncertainty of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tuple {
    pub(crate) state: State,
    pub(crate) action: Action,
    pub(crate) reward: f64,
    pub(crate) next: Option<(State, Action)>,
    pub(crate) frames: u32,
    pub(crate) uncertainty: f64,
}

impl Tuple {
    /// A tuple that arrived: `t` with its `note`; none unless its action
    /// and the next decision's are kicks.
    fn arrived(t: &Transition, note: &TransitionNote) -> Option<Self> {
        let kicks = t.action.is_kick() && t.next.is_none_or(|(_, a)| a.is_kick());
        kicks.then_some(Tuple {
            state: t.state,
            action: t.action,
            reward: t.reward,
            next: t.next,
            frames: note.frames,
            uncertainty: note.uncertainty,
        })
    }

    /// It as it travels: a transition and its note.
    fn sent(&self) -> (Transition, TransitionNote) {
        let t = Transition {
            state: self.state,
            action: self.action,
            reward: self.reward,
            next: self.next,
        };
        let note = TransitionNote {
            frames: self.frames,
            uncertainty: self.uncertainty,
        };
        (t, note)
    }

    /// Its sars-RND input, as the DQN reads it (numbers as `f32`, the
    /// next state zeros at the episode's end).
    fn row(&self) -> Vec<f32> {
        let state = f32s(&self.state);
        let next = self
            .next
            .map_or([0.0; proto::STATE_FEATURES], |(s, _)| f32s(&s));
        Sars {
            state: &state,
            slot: kick_slot(self.action).expect("a tuple's action is a kick"),
            reward: self.reward as f32,
            next: &next,
        }
        .row()
    }

    /// Its frames as the receiver's DQN folds them into one decision: the
    /// kick with the whole reward, then (for a decision of k frames) k - 1
    /// frames of Move without reward at the next state, the last leading
    /// to the next kick; folded, the reward stays and the discount is
    /// gamma^k, as the sender's DQN stored it.
    pub(crate) fn frames(&self) -> Vec<Transition> {
        let Some((next, kick)) = self.next else {
            return vec![Transition {
                state: self.state,
                action: self.action,
                reward: self.reward,
                next: None,
            }];
        };
        let k = self.frames.max(1) as usize;
        let moving = |state, reward, then| Transition {
            state,
            action: Action::Move,
            reward,
            next: Some((next, then)),
        };
        let mut frames = Vec::with_capacity(k);
        let first_then = if k == 1 { kick } else { Action::Move };
        frames.push(Transition {
            action: self.action,
            ..moving(self.state, self.reward, first_then)
        });
        for i in 1..k {
            frames.push(moving(
                next,
                0.0,
                if i + 1 == k { kick } else { Action::Move },
            ));
        }
        frames
    }
}

/// The paper's state as the DQN reads it (`f32`), back in `f64`.
fn f32s(state: &State) -> [f32; proto::STATE_FEATURES] {
    state.map(|x| x as f32)
}

/// A state rounded as the DQN reads it.
fn rounded(state: &State) -> State {
    f32s(state).map(f64::from)
}

/// The kick being folded: its state and action, the discounted reward
/// since, the discount of what follows and the frames folded.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Open {
    state: State,
    action: Action,
    reward: f64,
    discount: f64,
    frames: u32,
}

/// Folds an agent's frames into decisions as its DQN does (`Dqn::close`):
/// from a kick to the next kick or the episode's end, the frames it moves
/// without the ball folded into the kick's discounted reward; the moves
/// before its first kick of an episode belong to none.
#[derive(Clone, Debug)]
pub(crate) struct Folder {
    gamma: f64,
    open: Option<Open>,
}

impl Folder {
    /// A folder for discount `gamma` per frame.
    pub(crate) fn new(gamma: f64) -> Self {
        Self { gamma, open: None }
    }

    /// Forgets the decision open (an episode begins).
    pub(crate) fn clear(&mut self) {
        self.open = None;
    }

    /// Folds frame `t` in: the decision it closes, if it closes one (its
    /// uncertainty 0, for the caller to set).
    pub(crate) fn fold(&mut self, t: &Transition) -> Option<Tuple> {
        if t.action.is_kick() {
            self.open = Some(Open {
                state: t.state,
                action: t.action,
                reward: 0.0,
                discount: 1.0,
                frames: 0,
            });
        }
        let open = self.open.as_mut()?;
        open.reward += open.discount * t.reward;
        open.discount *= self.gamma;
        open.frames = open.frames.saturating_add(1);
        let next = match t.next {
            None => None,
            Some((state, action)) if action.is_kick() => Some((state, action)),
            Some(_) => return None,
        };
        let open = self.open.take()?;
        Some(Tuple {
            state: rounded(&open.state),
            action: open.action,
            reward: open.reward,
            next: next.map(|(s, a)| (rounded(&s), a)),
            frames: open.frames,
            uncertainty: 0.0,
        })
    }
}

/// Mixed into an agent's seed for its sars-RND's weights.
pub(crate) const RND_STREAM: u64 = 0x4546_4f6e_544c_726e;

/// One agent's side of EF-OnTL: its sars-RND and the tuples it keeps, its
/// recent returns, the standings it holds and its schedule.
#[derive(Debug)]
pub(crate) struct Transfers {
    settings: EfOntl,
    folder: Folder,
    rnd: Rnd,
    buffer: TransferBuffer,
    /// Per kept tuple, oldest first: the frames it spans and the next
    /// decision's kick, none at the episode's end (what the buffer's rows
    /// do not say).
    links: VecDeque<(u32, Option<Action>)>,
    /// Its last `interval` training episodes' returns.
    returns: VecDeque<f64>,
    /// Training episodes ended.
    episodes: u64,
    /// The standings held for the coming teacher choice, its own first.
    standings: Vec<(usize, Standing)>,
}

impl Transfers {
    /// Agent `me`'s side, under `settings`, folding with discount `gamma`,
    /// its sars-RND's weights drawn from `seed` (the agent's, mixed).
    pub(crate) fn new(settings: &EfOntl, gamma: f64, seed: u64) -> Self {
        let width = proto::STATE_FEATURES;
        Self {
            settings: settings.clone(),
            folder: Folder::new(gamma),
            rnd: Rnd::new(&RndSettings::default(), width, seed ^ RND_STREAM),
            buffer: TransferBuffer::new(settings.buffer as usize, width),
            links: VecDeque::new(),
            returns: VecDeque::new(),
            episodes: 0,
            standings: Vec::new(),
        }
    }

    /// An episode begins: no decision is open.
    pub(crate) fn begin_episode(&mut self) {
        self.folder.clear();
    }

    /// A training frame its agent learned: the decision it closes is
    /// learned by the sars-RND and kept with the uncertainty before.
    pub(crate) fn learned(&mut self, t: &Transition) {
        let Some(tuple) = self.folder.fold(t) else {
            return;
        };
        let row = tuple.row();
        let uncertainty = self.rnd.learn(&row);
        let discount = match tuple.next {
            Some(_) => (self.folder.gamma).powi(tuple.frames as i32) as f32,
            None => 0.0,
        };
        if self.buffer.len() == self.settings.buffer as usize {
            self.links.pop_front();
        }
        self.buffer.push(&row, discount, uncertainty);
        self.links
            .push_back((tuple.frames, tuple.next.map(|(_, a)| a)));
    }

    /// Its standing now.
    fn standing(&self) -> Standing {
        let n = self.returns.len().max(1) as f64;
        Standing {
            episodes: self.episodes,
            uncertainty: self.buffer.mean_uncertainty(),
            mean_return: self.returns.iter().sum::<f64>() / n,
        }
    }

    /// The `i`th oldest kept tuple.
    fn tuple(&self, i: usize) -> Tuple {
        let (sars, _) = self.buffer.get(i);
        let (frames, kick) = self.links[i];
        let state = |x: &[f32]| -> State { std::array::from_fn(|j| f64::from(x[j])) };
        Tuple {
            state: state(sars.state),
            action: KICKS[sars.slot],
            reward: f64::from(sars.reward),
            next: kick.map(|kick| (state(sars.next), kick)),
            frames,
            uncertainty: self.buffer.uncertainty(i),
        }
    }

    /// The tuples the teacher sends: its lowest-uncertainty `candidates`
    /// (all it keeps by default), oldest first, as many as span at most
    /// [`MAX_BATCH_FRAMES`] frames in all (the wire's bound, which 4096
    /// tuples reach only at 64 frames each on average); none while it keeps
    /// fewer than `transfer_batch` (the library skips such a transfer).
    fn candidates(&self) -> Vec<Tuple> {
        let n = self.buffer.len();
        if n < self.settings.transfer_batch as usize {
            return Vec::new();
        }
        let mut chosen: Vec<usize> = (0..n).collect();
        if self.settings.sent() < n {
            chosen.sort_by(|&i, &j| {
                let (u, v) = (self.buffer.uncertainty(i), self.buffer.uncertainty(j));
                u.total_cmp(&v).then(i.cmp(&j))
            });
            chosen.truncate(self.settings.sent());
            chosen.sort_unstable();
        }
        let mut frames = 0;
        (chosen.into_iter())
            .map(|i| self.tuple(i))
            .take_while(|t| {
                frames += u64::from(t.frames);
                frames <= MAX_BATCH_FRAMES
            })
            .collect()
    }

    /// A training episode of return `episode_return` ended for agent `me`
    /// of a team of `team_size`: what it sends each teammate. At the end of
    /// the episode after an event, the teacher chosen from the standings
    /// held sends its candidates (if it is the teacher); at an event
    /// (every `interval` episodes) it sends its standing. Both go in one
    /// batch per receiver.
    pub(crate) fn end_episode(
        &mut self,
        me: usize,
        team_size: usize,
        episode_return: f64,
    ) -> Vec<(usize, Batch)> {
        let f = self.settings.interval;
        self.episodes += 1;
        self.returns.push_back(episode_return);
        if self.returns.len() > f as usize {
            self.returns.pop_front();
        }
        let mut batch = Batch::default();
        let after_event = self.episodes > f && (self.episodes - 1).is_multiple_of(f);
        if after_event {
            let held = std::mem::take(&mut self.standings);
            if teacher(self.settings.selection, &held, f) == Some(me) {
                let sent = self.candidates().iter().map(Tuple::sent).unzip();
                (batch.transitions, batch.notes) = sent;
            }
        }
        if self.episodes.is_multiple_of(f) {
            let standing = self.standing();
            self.standings = vec![(me, standing)];
            batch.standing = Some(standing);
        }
        if batch.standing.is_none() && batch.transitions.is_empty() {
            return Vec::new();
        }
        (0..team_size)
            .filter(|&j| j != me)
            .map(|j| (j, batch.clone()))
            .collect()
    }

    /// A batch arrived from agent `from`: its standing is held for the
    /// coming choice (in place of an older one of the same agent), and of
    /// its tuples (its transitions with their notes; those whose action or
    /// next action is no kick left out) the `transfer_batch` with the
    /// lowest sender's minus own uncertainty are returned, in that order,
    /// to learn as one batch (none if it brought fewer). The sars-RND does
    /// not learn them.
    pub(crate) fn received(&mut self, from: usize, batch: &Batch) -> Vec<Tuple> {
        if let Some(standing) = batch.standing {
            self.standings.retain(|(id, _)| *id != from);
            self.standings.push((from, standing));
        }
        let tuples: Vec<Tuple> = (batch.transitions.iter().zip(&batch.notes))
            .filter_map(|(t, note)| Tuple::arrived(t, note))
            .collect();
        if tuples.is_empty() {
            return Vec::new();
        }
        let mut arrived = TransferBuffer::new(tuples.len(), proto::STATE_FEATURES);
        for t in &tuples {
            arrived.push(&t.row(), 0.0, t.uncertainty);
        }
        (arrived.select_by_delta(&self.rnd, self.settings.transfer_batch as usize))
            .into_iter()
            .map(|i| tuples[i])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    impl Transfers {
        /// The tuples it keeps.
        fn kept(&self) -> usize {
            self.buffer.len()
        }

        /// Its sars-RND's uncertainty of a tuple now.
        fn uncertainty_of(&self, tuple: &Tuple) -> f64 {
            self.rnd.uncertainty(&tuple.row())
        }
    }

    fn standing(episodes: u64, uncertainty: Option<f64>, mean_return: f64) -> Standing {
        Standing {
            episodes,
            uncertainty,
            mean_return,
        }
    }

    #[test]
    fn the_teacher_by_uncertainty_is_the_surest_ties_to_the_lowest_id() {
        let by = TeacherRule::Uncertainty;
        let held = [
            (2, standing(100, Some(0.3), 1.0)),
            (0, standing(100, Some(0.5), 0.0)),
            (1, standing(100, Some(0.2), -1.0)),
        ];
        assert_eq!(teacher(by, &held, 100), Some(1));
        let tied = [
            (2, standing(100, Some(0.2), 0.0)),
            (1, standing(100, Some(0.2), 0.0)),
            (0, standing(100, Some(0.4), 0.0)),
        ];
        assert_eq!(teacher(by, &tied, 100), Some(1));
        // One that keeps nothing is no candidate; none if none keeps any.
        let empty = [
            (0, standing(100, None, 1.0)),
            (1, standing(100, Some(0.9), 0.0)),
        ];
        assert_eq!(teacher(by, &empty, 100), Some(1));
        assert_eq!(teacher(by, &empty[..1], 100), None);
        assert_eq!(teacher(by, &[], 100), None);
    }

    #[test]
    fn the_teacher_by_performance_has_the_best_mean_return_ties_to_the_lowest_id() {
        let by = TeacherRule::Performance;
        let held = [
            (0, standing(100, Some(0.1), 0.2)),
            (1, standing(100, None, 0.6)),
            (2, standing(100, Some(0.5), -0.3)),
        ];
        assert_eq!(teacher(by, &held, 100), Some(1));
        // The team shares its outcome: equal returns, the lowest id.
        let shared = [
            (2, standing(100, Some(0.1), 0.4)),
            (1, standing(100, Some(0.2), 0.4)),
        ];
        assert_eq!(teacher(by, &shared, 100), Some(1));
    }

    #[test]
    fn no_teacher_while_an_agent_has_played_fewer_than_ep_start_sharing() {
        for by in [TeacherRule::Uncertainty, TeacherRule::Performance] {
            let held = [
                (0, standing(100, Some(0.1), 1.0)),
                (1, standing(99, Some(0.2), 0.0)),
            ];
            assert_eq!(teacher(by, &held, 100), None);
            assert_eq!(teacher(by, &held, 99), Some(0));
        }
    }

    fn settings(edit: impl FnOnce(&mut EfOntl)) -> Result<(), AgentConfigError> {
        let mut s = EfOntl::default();
        edit(&mut s);
        s.validate()
    }

    #[test]
    fn bad_settings_are_refused_naming_their_key() {
        assert_eq!(settings(|_| ()), Ok(()));
        let key = |e: Result<(), AgentConfigError>| e.unwrap_err().key;
        assert_eq!(key(settings(|s| s.interval = 0)), "interval");
        let e = settings(|s| s.interval = 0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid agent config `interval`: must be at least 1 (training episodes between \
             transfers)"
        );
        let e = settings(|s| {
            s.transfer_batch = 5000;
            s.buffer = 10_000;
            s.candidates = Some(4096);
        })
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid agent config `transfer_batch`: must be 1 to 4096 (the tuples a batch \
             message carries), got 5000"
        );
        assert_eq!(key(settings(|s| s.transfer_batch = 0)), "transfer_batch");
        assert_eq!(key(settings(|s| s.transfer_batch = 1001)), "transfer_batch");
        assert_eq!(key(settings(|s| s.buffer = 0)), "buffer");
        assert_eq!(key(settings(|s| s.buffer = 5000)), "buffer");
        assert_eq!(
            settings(|s| {
                s.buffer = 5000;
                s.candidates = Some(4096);
            }),
            Ok(())
        );
        assert_eq!(key(settings(|s| s.candidates = Some(99))), "candidates");
        assert_eq!(key(settings(|s| s.candidates = Some(1001))), "candidates");
        assert_eq!(settings(|s| s.candidates = Some(100)), Ok(()));
        assert_eq!(settings(|s| s.interval = 1), Ok(()));
    }

    /// A frame of the paper's state `v` everywhere.
    fn frame(v: f64, action: Action, reward: f64, next: Option<(f64, Action)>) -> Transition {
        Transition {
            state: [v; 6],
            action,
            reward,
            next: next.map(|(w, a)| ([w; 6], a)),
        }
    }

    #[test]
    fn frames_fold_kick_to_kick_as_the_dqn_folds_them() {
        use Action::*;
        let gamma = 0.9;
        let mut folder = Folder::new(gamma);
        // Moves before the first kick belong to no decision.
        assert_eq!(
            folder.fold(&frame(0.1, Move, 0.5, Some((0.2, Shoot)))),
            None
        );
        assert_eq!(
            folder.fold(&frame(0.2, Dribble, 1.0, Some((0.3, Move)))),
            None
        );
        assert_eq!(folder.fold(&frame(0.3, Move, 2.0, Some((0.4, Move)))), None);
        let closed = folder.fold(&frame(0.4, Move, 4.0, Some((0.5, PassFar))));
        let tuple = closed.unwrap();
        assert_eq!(tuple.state, rounded(&[0.2; 6]));
        assert_eq!(tuple.action, Dribble);
        assert_eq!(tuple.reward, 1.0 + 0.9 * 2.0 + 0.9 * 0.9 * 4.0);
        assert_eq!(tuple.next, Some((rounded(&[0.5; 6]), PassFar)));
        assert_eq!(tuple.frames, 3);
        // The episode's end closes the open kick.
        assert_eq!(
            folder.fold(&frame(0.5, PassFar, 0.0, Some((0.6, Move)))),
            None
        );
        let end = folder.fold(&frame(0.6, Move, -1.0, None)).unwrap();
        assert_eq!(
            (end.action, end.reward, end.next, end.frames),
            (PassFar, -0.9, None, 2)
        );
        // Its frames, folded again, give the same decision.
        for t in [tuple, end] {
            let mut again = Folder::new(gamma);
            let frames = t.frames();
            assert_eq!(frames.len(), if t.next.is_some() { 3 } else { 1 });
            let refolded: Vec<Tuple> = frames.iter().filter_map(|f| again.fold(f)).collect();
            assert_eq!(refolded.len(), 1);
            let r = refolded[0];
            assert_eq!((r.state, r.action, r.next), (t.state, t.action, t.next));
            assert_eq!(r.reward.to_bits(), t.reward.to_bits());
            assert_eq!(r.frames, if t.next.is_some() { t.frames } else { 1 });
        }
    }

    /// The frames as the framework hands them to a learner.
    fn experiences(frames: &[Transition]) -> Vec<crate::learner::Experience<'_>> {
        use crate::learner::{Seen, Step};
        let step = |state, action| Step {
            at: Seen {
                state,
                features: &[],
                index: None,
            },
            action,
        };
        (frames.iter())
            .map(|t| {
                let next = t.next.as_ref().map(|(s, a)| step(s, *a));
                (step(&t.state, t.action), t.reward, next)
            })
            .collect()
    }

    #[test]
    fn a_tuples_frames_make_the_dqn_store_the_decision_its_own_frames_did() {
        use crate::learner::Learner;
        use Action::*;
        let gamma = 0.9;
        let f = |v: f64| [v, -v, v / 2.0, 0.3, -0.7, v * v];
        let (s0, s1, s2) = (f(0.1), f(0.37), f(-0.55));
        let m = f(0.9);
        // Kick, three moves, kick, one move, kick, the end.
        let episode = [
            (s0, Dribble, 0.0, Some((m, Move))),
            (m, Move, 0.25, Some((m, Move))),
            (m, Move, -0.5, Some((m, Move))),
            (m, Move, 0.125, Some((s1, PassNear))),
            (s1, PassNear, 0.0, Some((m, Move))),
            (m, Move, 0.5, Some((s2, Shoot))),
            (s2, Shoot, 1.0, None),
        ]
        .map(|(state, action, reward, next)| Transition {
            state,
            action,
            reward,
            next,
        });
        let mut folder = Folder::new(gamma);
        let tuples: Vec<Tuple> = episode.iter().filter_map(|t| folder.fold(t)).collect();
        assert_eq!(
            tuples.iter().map(|t| t.frames).collect::<Vec<_>>(),
            [4, 2, 1]
        );
        let settings = crate::learner_settings::DqnSettings::default();
        let mut own = crate::Dqn::new(&settings, gamma, 6, 3);
        let mut sent = crate::Dqn::new(&settings, gamma, 6, 3);
        own.replay(&experiences(&episode));
        let frames: Vec<Transition> = tuples.iter().flat_map(Tuple::frames).collect();
        sent.replay(&experiences(&frames));
        assert_eq!(own.save_state(), sent.save_state());
        assert_ne!(
            own.save_state(),
            crate::Dqn::new(&settings, gamma, 6, 3).save_state()
        );
    }

    /// A team's agent with interval `f` and `edit`ed settings.
    fn transfers(f: u64, seed: u64, edit: impl FnOnce(&mut EfOntl)) -> Transfers {
        let mut s = EfOntl {
            interval: f,
            buffer: 8,
            transfer_batch: 3,
            ..EfOntl::default()
        };
        edit(&mut s);
        s.validate().unwrap();
        Transfers::new(&s, 0.95, seed)
    }

    /// Plays one episode of `kicks` decisions of state `v`, `v + 0.01`, ...
    fn play(t: &mut Transfers, v: f64, kicks: usize) {
        use Action::*;
        t.begin_episode();
        for k in 0..kicks {
            let x = v + 0.01 * k as f64;
            let last = k + 1 == kicks;
            t.learned(&frame(x, Shoot, 0.0, Some((x, Move))));
            let next = (!last).then_some((x + 0.01, Dribble));
            t.learned(&frame(x, Move, if last { 1.0 } else { 0.0 }, next));
        }
    }

    #[test]
    fn an_agent_keeps_its_last_decisions_with_their_uncertainty_before_learning_them() {
        let mut t = transfers(2, 1, |_| ());
        let fresh = t.rnd.uncertainty(&play_tuple(0.3).row());
        play(&mut t, 0.3, 1);
        assert_eq!(t.kept(), 1);
        let kept = t.tuple(0);
        assert_eq!(kept.row(), play_tuple(0.3).row());
        assert_eq!((kept.next, kept.frames), (None, 2));
        assert_eq!(kept.uncertainty.to_bits(), fresh.to_bits());
        assert!(t.uncertainty_of(&kept) < fresh, "learned");
        for e in 0..5 {
            play(&mut t, e as f64 / 10.0, 3);
        }
        assert_eq!(t.kept(), 8);
        // 16 decisions, the last 8 kept: the oldest is the third
        // episode's second.
        let oldest = t.tuple(0);
        assert_eq!(oldest.state, rounded(&[0.21; 6]));
        assert_eq!(oldest.next, Some((rounded(&[0.22; 6]), Action::Dribble)));
        assert_eq!(oldest.frames, 2);
    }

    fn play_tuple(v: f64) -> Tuple {
        Tuple {
            state: rounded(&[v; 6]),
            action: Action::Shoot,
            reward: 0.95,
            next: None,
            frames: 2,
            uncertainty: 0.0,
        }
    }

    #[test]
    fn standings_go_out_every_interval_and_the_teacher_sends_at_the_next_end() {
        let f = 3;
        let mut team: Vec<Transfers> = (0..3).map(|i| transfers(f, i, |_| ())).collect();
        let mut sent = Vec::new();
        for episode in 1..=8u64 {
            let mut post = Vec::new();
            for (me, t) in team.iter_mut().enumerate() {
                // Agent 2 learns far more than the others: the surest.
                let kicks = if me == 2 { 40 } else { 1 };
                for _ in 0..kicks {
                    play(t, 0.5, 1);
                }
                for (to, parcel) in t.end_episode(me, 3, 0.0) {
                    post.push((me, to, parcel));
                }
            }
            for (from, to, parcel) in post {
                let learned = team[to].received(from, &parcel);
                sent.push((
                    episode,
                    from,
                    to,
                    parcel.standing.is_some(),
                    parcel.transitions.len(),
                ));
                assert!(learned.len() == 3 || parcel.transitions.is_empty());
            }
        }
        let of = |e: u64| -> Vec<(usize, usize, bool, usize)> {
            (sent.iter().filter(|s| s.0 == e))
                .map(|s| (s.1, s.2, s.3, s.4))
                .collect()
        };
        assert!(of(1).is_empty() && of(2).is_empty());
        let standings = vec![
            (0, 1, true, 0),
            (0, 2, true, 0),
            (1, 0, true, 0),
            (1, 2, true, 0),
            (2, 0, true, 0),
            (2, 1, true, 0),
        ];
        assert_eq!(of(3), standings);
        // Agent 2, the surest, sends all it keeps (8) to the others.
        assert_eq!(of(4), vec![(2, 0, false, 8), (2, 1, false, 8)]);
        assert!(of(5).is_empty());
        assert_eq!(of(6), standings);
        assert_eq!(of(7), vec![(2, 0, false, 8), (2, 1, false, 8)]);
    }

    #[test]
    fn with_interval_1_a_parcel_carries_the_standing_and_the_tuples() {
        let mut team: Vec<Transfers> = (0..2).map(|i| transfers(1, i, |_| ())).collect();
        for (me, t) in team.iter_mut().enumerate() {
            play(t, 0.2, 4 * me + 3);
            assert_eq!(t.end_episode(me, 2, 1.0).len(), 1);
        }
        let parcel = {
            let sent = team[1].end_episode(1, 2, 1.0);
            assert_eq!(sent.len(), 1);
            sent[0].1.clone()
        };
        // Agent 1 held no standing of agent 0: it chose itself.
        assert!(parcel.standing.is_some());
        assert_eq!(parcel.transitions.len(), 7);
    }

    #[test]
    fn a_lost_standing_leaves_its_agent_out_of_the_choice() {
        let f = 1;
        let mut a = transfers(f, 1, |_| ());
        play(&mut a, 0.1, 3);
        a.end_episode(0, 3, 0.0);
        // Agent 1, surer, is heard of; agent 2, surest, is lost.
        let heard = Batch {
            standing: Some(standing(1, Some(1e-9), 0.0)),
            ..Batch::default()
        };
        a.received(1, &heard);
        let sent = a.end_episode(0, 3, 0.0);
        assert!(sent.iter().all(|(_, p)| p.transitions.is_empty()));
        // Next time nobody else is heard of: it teaches.
        let sent = a.end_episode(0, 3, 0.0);
        assert!(
            sent.iter().all(|(_, p)| p.transitions.len() == 3),
            "{sent:?}"
        );
    }

    #[test]
    fn the_candidates_are_the_lowest_uncertainty_tuples_oldest_first() {
        let mut t = transfers(1, 4, |s| s.candidates = Some(3));
        for i in 0..6 {
            play(&mut t, i as f64 / 10.0, 1);
        }
        let all: Vec<f64> = (0..6).map(|i| t.buffer.uncertainty(i)).collect();
        let mut order: Vec<usize> = (0..6).collect();
        order.sort_by(|&i, &j| all[i].total_cmp(&all[j]));
        let mut lowest = order[..3].to_vec();
        lowest.sort_unstable();
        let sent: Vec<f64> = t.candidates().iter().map(|c| c.uncertainty).collect();
        let expected: Vec<f64> = lowest.iter().map(|&i| all[i]).collect();
        assert_eq!(sent, expected);
        // Fewer kept than transfer_batch: nothing.
        let mut few = transfers(1, 4, |_| ());
        play(&mut few, 0.1, 2);
        assert!(few.candidates().is_empty());
    }

    /// `tuples` as a batch carries them.
    fn batch_of(tuples: &[Tuple]) -> Batch {
        let (transitions, notes) = tuples.iter().map(Tuple::sent).unzip();
        Batch {
            transitions,
            notes,
            standing: None,
        }
    }

    #[test]
    fn the_receiver_learns_the_b_most_negative_gaps_by_its_own_rnd() {
        let mut receiver = transfers(1, 9, |s| s.transfer_batch = 2);
        let tuples: Vec<Tuple> = (0..5).map(|i| play_tuple(i as f64 / 10.0)).collect();
        let theirs: Vec<f64> = tuples.iter().map(|t| receiver.uncertainty_of(t)).collect();
        // Stored uncertainty = the receiver's + delta.
        let delta = [0.3, -0.2, 0.0, -0.5, -0.1];
        let sent: Vec<Tuple> = (tuples.iter().zip(theirs.iter().zip(delta)))
            .map(|(t, (u, d))| Tuple {
                uncertainty: u + d,
                ..*t
            })
            .collect();
        let parcel = batch_of(&sent);
        let learned = receiver.received(0, &parcel);
        // Deltas -0.5 (index 3), then -0.2 (index 1).
        assert_eq!(learned, vec![sent[3], sent[1]]);
        // Its sars-RND did not learn them.
        let after: Vec<f64> = tuples.iter().map(|t| receiver.uncertainty_of(t)).collect();
        assert_eq!(after, theirs);
        // Fewer than B arrived: none learned.
        let one = batch_of(&sent[..1]);
        assert!(receiver.received(0, &one).is_empty());
    }
}
