//! The server's zenoh side: the session, its liveliness token, the control
//! queryable, the action subscriber and one observation publisher per agent.
//!
//! Queries are handed over through an unbounded channel fed by zenoh's
//! callback, so the event loop can wait on them and on the step deadline;
//! actions are handled in their subscriber's callback ([`Link::listen`]).

use anyhow::{Result, anyhow};
use node::alive::CoordinatorPresence;
use node::cli::ConnectionArgs;
use node::net::describe;
use proto::keys::{Keys, Role};
use tokio::sync::mpsc::{UnboundedReceiver, unbounded_channel};
use zenoh::liveliness::LivelinessToken;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::qos::CongestionControl;
use zenoh::query::{Query, Queryable};
use zenoh::sample::Sample;
use zenoh::{Session, Wait};

/// What the event loop waits for, in arrival order per source.
pub struct Inbox {
    /// Control queries on `ctl/server`.
    pub queries: UnboundedReceiver<Query>,
    /// Signals that the coordinator left (with `exit_with_coordinator`).
    pub coordinator_gone: UnboundedReceiver<()>,
}

/// An open session with every declaration of env-server.
pub struct Link {
    session: Session,
    keys: Keys,
    experiment: u64,
    control_key: String,
    publishers: Vec<Publisher<'static>>,
    // Held for their lifetime: dropping them undeclares them.
    _queryable: Queryable<()>,
    _watch: Option<Subscriber<()>>,
}

/// The action subscriber and the liveliness token, held while serving.
pub struct Listening {
    _subscriber: Subscriber<()>,
    _token: LivelinessToken,
}

impl Link {
    /// Opens the session and declares the control queryable (the action
    /// subscriber and the token come with [`listen`](Self::listen)).
    pub async fn open(connection: &ConnectionArgs, keys: Keys) -> Result<(Self, Inbox)> {
        let session = node::net::open(&connection.net()?).await?;
        let control_key = keys.control(Role::Server);
        let (query_tx, queries) = unbounded_channel();
        let queryable = session
            .declare_queryable(control_key.clone())
            .callback(move |query| {
                // The receiver only goes away when the server stops.
                let _ = query_tx.send(query);
            })
            .await
            .map_err(|e| zenoh_error("declare the control queryable", &e))?;
        let (gone_tx, coordinator_gone) = unbounded_channel();
        let watch = match connection.exit_with_coordinator {
            false => None,
            true => {
                let coordinator = CoordinatorPresence::default();
                let watch = session
                    .liveliness()
                    .declare_subscriber(keys.alive(Role::Coordinator))
                    .history(true)
                    .callback(move |sample| {
                        let present = sample.kind() == zenoh::sample::SampleKind::Put;
                        if coordinator.left(present) {
                            let _ = gone_tx.send(());
                        }
                    })
                    .await
                    .map_err(|e| zenoh_error("watch the coordinator", &e))?;
                Some(watch)
            }
        };
        let link = Link {
            session,
            keys,
            experiment: proto::experiment_id(&connection.experiment),
            control_key,
            publishers: Vec::new(),
            _queryable: queryable,
            _watch: watch,
        };
        Ok((
            link,
            Inbox {
                queries,
                coordinator_gone,
            },
        ))
    }

    /// Declares the action subscriber, whose samples go to `on_action` on
    /// zenoh's receiving thread, and, last, the liveliness token (so a
    /// process that sees the token finds everything declared).
    pub fn listen(&self, on_action: impl Fn(Sample) + Send + Sync + 'static) -> Result<Listening> {
        let subscriber = self
            .session
            .declare_subscriber(self.keys.actions())
            .callback(on_action)
            .wait()
            .map_err(|e| zenoh_error("subscribe to the actions", &e))?;
        let token = self
            .session
            .liveliness()
            .declare_token(self.keys.alive(Role::Server))
            .wait()
            .map_err(|e| zenoh_error("declare the liveliness token", &e))?;
        Ok(Listening {
            _subscriber: subscriber,
            _token: token,
        })
    }

    /// The experiment id carried in every header.
    pub fn experiment(&self) -> u64 {
        self.experiment
    }

    /// Declares one observation publisher per agent of a team of `n`
    /// (nothing to do when the team size is unchanged).
    pub fn set_team(&mut self, n: usize) -> Result<()> {
        if self.publishers.len() == n {
            return Ok(());
        }
        self.publishers.clear();
        for i in 0..n {
            let id = u8::try_from(i).map_err(|_| anyhow!("team of {n} agents is too large"))?;
            let publisher = self
                .session
                .declare_publisher(self.keys.observation(id))
                // Every agent must see every frame: wait rather than drop.
                .congestion_control(CongestionControl::Block)
                .wait()
                .map_err(|e| zenoh_error("declare an observation publisher", &e))?;
            self.publishers.push(publisher);
        }
        Ok(())
    }

    /// Publishes `bytes` to agent `agent`.
    pub fn publish(&self, agent: usize, bytes: Vec<u8>) -> Result<()> {
        let publisher = self
            .publishers
            .get(agent)
            .ok_or_else(|| anyhow!("no observation publisher for agent {agent}"))?;
        publisher
            .put(bytes)
            .wait()
            .map_err(|e| zenoh_error("publish an observation", &e))
    }

    /// Replies to a control query on the server's own control key.
    pub fn reply(&self, query: &Query, bytes: Vec<u8>) -> Result<()> {
        query
            .reply(self.control_key.as_str(), bytes)
            .wait()
            .map_err(|e| zenoh_error("reply to a control query", &e))
    }

    /// Closes the session (undeclaring everything).
    pub fn close(&self) -> Result<()> {
        self.session
            .close()
            .wait()
            .map_err(|e| zenoh_error("close the zenoh session", &e))
    }
}

/// A zenoh failure while doing `what`, on one line.
fn zenoh_error(what: &str, error: &zenoh::Error) -> anyhow::Error {
    anyhow!("cannot {what}: {}", describe(error))
}
