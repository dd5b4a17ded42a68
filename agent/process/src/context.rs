//! What every task of the process shares: the zenoh session, the keys, the
//! learner, the traffic accounting, the live agents and the stop signal.

use std::collections::BTreeSet;
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;

use agent::Link;
use node::sync::lock;
use proto::keys::Keys;
use proto::{Body, Direction, DropReason, Envelope, Header, MessageCounters, MessageKind};
use tokio::sync::{Notify, watch};
use zenoh::Session;

use crate::child::ChildCommands;
use crate::learning::{Learning, Progress};

/// Messages of this run, and the advice round trips.
#[derive(Clone, Debug, Default)]
pub struct Traffic {
    /// Messages and bytes by kind and direction, and drops by reason.
    pub messages: MessageCounters,
    /// Round-trip time of every advice request that got a reply (ms).
    pub rtt_ms: Vec<f32>,
}

/// Why the process stops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// `Control::Stop`.
    Stopped,
    /// The coordinator's liveliness token disappeared.
    CoordinatorGone,
}

/// The process's shared context.
#[derive(Debug)]
/// Snapshots travelling in parts (`proto::parts`).
#[derive(Default)]
pub struct Transfers {
    /// The snapshot being loaded, part by part.
    pub loading: proto::parts::Gathering,
    /// The snapshot being sent: its bytes and the (run, episode) it was
    /// taken after.
    pub sending: Option<((u32, u32), Vec<u8>)>,
}

pub struct Context {
    /// The zenoh session.
    pub session: Session,
    /// The experiment's keys.
    pub keys: Keys,
    /// Its id, carried in every header.
    pub experiment: u64,
    /// This agent's id.
    pub id: u8,
    /// How long to wait for advice in the current run, and the network
    /// conditions of this agent's advice messages (set by its reset).
    advice: Mutex<(Duration, Option<Link>)>,
    learner: Mutex<Learning>,
    transfers: Mutex<Transfers>,
    traffic: Mutex<Traffic>,
    alive: Mutex<BTreeSet<u8>>,
    progress: watch::Sender<Progress>,
    exit: Mutex<Option<Exit>>,
    stop: Notify,
}

impl Context {
    /// The context of agent `id` of a team of `team_size` in experiment
    /// `name`, with its learner and strategy processes `children` where given.
    pub fn new(
        session: Session,
        name: &str,
        keys: Keys,
        (id, team_size): (u8, u8),
        children: ChildCommands,
    ) -> Self {
        Self {
            session,
            keys,
            experiment: proto::experiment_id(name),
            id,
            advice: Mutex::new((Duration::ZERO, None)),
            learner: Mutex::new(Learning::new(id, team_size, children)),
            transfers: Mutex::new(Transfers::default()),
            traffic: Mutex::new(Traffic::default()),
            alive: Mutex::new(BTreeSet::new()),
            progress: watch::Sender::new(Progress::default()),
            exit: Mutex::new(None),
            stop: Notify::new(),
        }
    }

    /// How long to wait for advice in the current run, and the link its
    /// advice messages go out on (none without network conditions).
    pub fn advice(&self) -> (Duration, Option<Link>) {
        *lock(&self.advice)
    }

    /// Sets the advice timeout and link of the run that starts.
    pub fn set_advice(&self, timeout: Duration, link: Option<Link>) {
        *lock(&self.advice) = (timeout, link);
    }

    /// The learner, locked: never hold it across an `.await`.
    pub fn learner(&self) -> MutexGuard<'_, Learning> {
        lock(&self.learner)
    }

    /// The snapshots on their way in and out, locked.
    pub fn transfers(&self) -> MutexGuard<'_, Transfers> {
        lock(&self.transfers)
    }

    /// The traffic accounting, locked.
    pub fn traffic(&self) -> MutexGuard<'_, Traffic> {
        lock(&self.traffic)
    }

    /// Publishes the learner's progress (call with the learner locked, so
    /// that progress never goes back).
    pub fn publish_progress(&self, learner: &Learning) {
        self.progress.send_replace(learner.progress());
    }

    /// A receiver of the learner's progress.
    pub fn watch_progress(&self) -> watch::Receiver<Progress> {
        self.progress.subscribe()
    }

    /// Decodes received bytes of this experiment; undecodable ones are
    /// counted as dropped and logged.
    pub fn decode(&self, bytes: &[u8]) -> Option<Envelope> {
        match proto::decode(bytes, self.experiment) {
            Ok(envelope) => Some(envelope),
            Err(e) => {
                tracing::debug!(error = %e, "dropped an undecodable message");
                self.traffic().messages.drop_undecodable(&e);
                None
            }
        }
    }

    /// Counts an accepted received message.
    pub fn accepted(&self, kind: MessageKind, bytes: usize) {
        self.traffic()
            .messages
            .record(Direction::Received, kind, bytes);
    }

    /// Counts and logs a dropped received message.
    pub fn dropped(&self, reason: DropReason, header: Option<&Header>) {
        tracing::debug!(?reason, ?header, "dropped a message");
        self.traffic().messages.record_drop(reason);
    }

    /// Encodes a message to send and counts it.
    pub fn encode(&self, header: Header, body: Body) -> Vec<u8> {
        let kind = MessageKind::of(&body);
        let bytes = proto::encode(&Envelope { header, body });
        self.traffic()
            .messages
            .record(Direction::Sent, kind, bytes.len());
        bytes
    }

    /// Marks agent `j`'s liveliness token as seen or gone.
    pub fn set_alive(&self, j: u8, alive: bool) {
        let mut set = lock(&self.alive);
        if alive {
            set.insert(j);
        } else {
            set.remove(&j);
        }
    }

    /// The agents whose liveliness token is seen (this one included).
    pub fn alive(&self) -> BTreeSet<u8> {
        lock(&self.alive).clone()
    }

    /// Asks the process to stop (the first reason wins).
    pub fn stop(&self, exit: Exit) {
        lock(&self.exit).get_or_insert(exit);
        self.stop.notify_one();
    }

    /// Waits until [`stop`](Self::stop) is called, and says why.
    pub async fn stopped(&self) -> Exit {
        self.stop.notified().await;
        lock(&self.exit).unwrap_or(Exit::Stopped)
    }
}
