//! The coordinator's side of the zenoh network: session, processes, liveliness.

use std::collections::HashSet;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use node::net::NetConfig;
use node::secret::Secret;
use proto::keys::{Keys, Role};
use proto::{
    Body, Control, ControlReply, Direction, Envelope, Header, MessageCounters, MessageKind,
};
use tokio::sync::watch;
use zenoh::liveliness::LivelinessToken;
use zenoh::pubsub::Subscriber;
use zenoh::query::{ConsolidationMode, QueryTarget};
use zenoh::sample::SampleKind;

use super::launch::{Children, find_binary};
use crate::error::{ConfigError, Error};
use crate::transport::{Auth, Endpoints, ZenohSettings};

/// The joined network and the processes of the experiment.
pub struct Network {
    settings: ZenohSettings,
    runtime: tokio::runtime::Runtime,
    session: zenoh::Session,
    keys: Keys,
    experiment: u64,
    roles: Vec<Role>,
    alive: Arc<Mutex<HashSet<Role>>>,
    /// The first process whose token disappeared; control waits watch it.
    lost: Arc<watch::Sender<Option<Role>>>,
    children: Arc<Mutex<Children>>,
    counters: Mutex<MessageCounters>,
    secret: Option<Secret>,
    /// The private directory of a generated secret, removed when dropped.
    secret_dir: Option<tempfile::TempDir>,
    _token: LivelinessToken,
    _watch: Subscriber<()>,
}

impl std::fmt::Debug for Network {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Network")
            .field("keys", &self.keys)
            .field("roles", &self.roles)
            .finish()
    }
}

fn net_error(message: impl Into<String>) -> Error {
    Error::Transport(message.into())
}

/// The experiment's secret, and the private directory of a generated one.
fn secret(options: &Endpoints) -> Result<(Option<Secret>, Option<tempfile::TempDir>), Error> {
    match &options.auth {
        Auth::Off => Ok((None, None)),
        Auth::File(path) => Ok((
            Some(Secret::load(path).map_err(|e| ConfigError::new("secret_file", e.to_string()))?),
            None,
        )),
        Auth::Generated if options.attach => Err(ConfigError::new(
            "secret_file",
            "--attach needs --secret-file, the secret the attached processes were started with (or --no-auth)",
        )
        .into()),
        Auth::Generated => {
            let dir = tempfile::Builder::new()
                .prefix("adv-secret-")
                .tempdir()
                .map_err(|e| net_error(format!("cannot create a private directory for the secret: {e}")))?;
            let secret = Secret::create(&dir.path().join("secret"))
                .map_err(|e| net_error(e.to_string()))?;
            Ok((Some(secret), Some(dir)))
        }
    }
}

impl Network {
    /// Joins the network of `settings.endpoints.experiment`, starts
    /// env-server and `agents` agent processes (unless attaching) and waits
    /// until every one of them is alive.
    pub fn start(settings: &ZenohSettings, agents: usize) -> Result<Self, Error> {
        let options = &settings.endpoints;
        let keys = Keys::new(&options.experiment)
            .map_err(|e| ConfigError::new("experiment", e.to_string()))?;
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .map_err(|e| net_error(format!("cannot start the async runtime: {e}")))?;
        // Always listen: a peer that cannot be reached is never linked to a
        // peer that waits for it to open the link.
        let port = match options.port {
            0 => node::net::free_port().map_err(|e| Error::io("bind", "127.0.0.1:0", e))?,
            p => p,
        };
        let listen = match (&options.listen, options.attach) {
            (Some(endpoint), true) => endpoint.clone(),
            (Some(_), false) => {
                return Err(ConfigError::new(
                    "listen",
                    "a listen endpoint is for --attach; the processes this coordinator starts use its loopback --port",
                )
                .into());
            }
            (None, _) => format!("tcp/127.0.0.1:{port}"),
        };
        let (secret, secret_dir) = secret(options)?;
        let net = NetConfig::peer(vec![listen], options.connect.clone())
            .with_secret(secret.clone())
            .with_base(options.zenoh_config.clone());
        let session = runtime
            .block_on(node::net::open(&net))
            .map_err(|e| net_error(e.to_string()))?;
        let roles: Vec<Role> = std::iter::once(Role::Server)
            .chain((0..agents).map(|i| Role::Agent(i as u8)))
            .collect();
        let alive = Arc::new(Mutex::new(HashSet::new()));
        let lost = Arc::new(watch::Sender::new(None));
        let watch = {
            let (alive, lost, keys) = (alive.clone(), lost.clone(), keys.clone());
            let key = keys.alive_all();
            runtime
                .block_on(async {
                    session
                        .liveliness()
                        .declare_subscriber(key)
                        .history(true)
                        .callback(move |sample| {
                            let Some(role) = keys.role_of_alive(sample.key_expr().as_str()) else {
                                return;
                            };
                            let mut alive = alive.lock().expect("liveliness set");
                            if sample.kind() == SampleKind::Put {
                                alive.insert(role);
                            } else if alive.remove(&role) {
                                tracing::warn!(%role, "lost");
                                lost.send_if_modified(|first| {
                                    first.is_none() && first.replace(role).is_none()
                                });
                            }
                        })
                        .await
                })
                .map_err(|e| net_error(format!("cannot watch liveliness: {e}")))?
        };
        let token = runtime
            .block_on(async {
                session
                    .liveliness()
                    .declare_token(keys.alive(Role::Coordinator))
                    .await
            })
            .map_err(|e| net_error(format!("cannot declare liveliness: {e}")))?;
        let network = Network {
            settings: settings.clone(),
            runtime,
            session,
            experiment: proto::experiment_id(&options.experiment),
            keys,
            roles,
            alive,
            lost,
            children: Arc::new(Mutex::new(Children::default())),
            counters: Mutex::new(MessageCounters::default()),
            secret,
            secret_dir,
            _token: token,
            _watch: watch,
        };
        if !options.attach {
            // Give liveliness history a moment, then refuse a busy experiment.
            std::thread::sleep(Duration::from_millis(200));
            if let Some(role) = network.roles.iter().find(|r| network.is_alive(**r)) {
                return Err(net_error(format!(
                    "experiment {} already has a running {role}; choose another --experiment",
                    options.experiment
                )));
            }
            let connect = format!("tcp/127.0.0.1:{port}");
            network.stop_on_signals()?;
            network.launch(agents, &connect)?;
        }
        network.wait_for_everyone(options)?;
        Ok(network)
    }

    fn launch(&self, agents: usize, connect: &str) -> Result<(), Error> {
        let options = &self.settings.endpoints;
        let server = find_binary(options.bin_dir.as_deref(), "env-server")?;
        let agent = find_binary(options.bin_dir.as_deref(), "agent")?;
        let auth: Vec<String> = match &self.secret {
            Some(secret) => vec!["--secret-file".into(), secret.path().display().to_string()],
            None => vec!["--no-auth".into()],
        };
        let common = |extra: &[String]| {
            let mut args: Vec<String> = extra.to_vec();
            args.extend([
                "--experiment".into(),
                options.experiment.clone(),
                "--connect".into(),
                connect.to_owned(),
            ]);
            args.extend(auth.iter().cloned());
            args
        };
        let mut children = self.children.lock().expect("children");
        children.spawn(
            "env-server",
            &server,
            &common(&["serve".into(), "--exit-with-coordinator".into()]),
        )?;
        for i in 0..agents {
            children.spawn(
                &format!("agent {i}"),
                &agent,
                &common(&[
                    "--id".into(),
                    i.to_string(),
                    "--team-size".into(),
                    agents.to_string(),
                    "--exit-with-coordinator".into(),
                ]),
            )?;
        }
        Ok(())
    }

    fn wait_for_everyone(&self, options: &Endpoints) -> Result<(), Error> {
        let deadline = Instant::now() + options.startup_timeout;
        loop {
            let missing: Vec<String> = self
                .roles
                .iter()
                .filter(|r| !self.is_alive(**r))
                .map(|r| r.to_string())
                .collect();
            if missing.is_empty() {
                // Declarations propagate asynchronously: let queryables settle.
                std::thread::sleep(Duration::from_millis(100));
                self.lost.send_replace(None);
                return Ok(());
            }
            if let Some(exited) = self.children.lock().expect("children").exited() {
                return Err(net_error(format!(
                    "{exited} before joining experiment {}",
                    options.experiment
                )));
            }
            if Instant::now() > deadline {
                return Err(net_error(format!(
                    "{} did not join experiment {} within {:?}",
                    missing.join(", "),
                    options.experiment,
                    options.startup_timeout
                )));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// On SIGINT (Ctrl-C) or SIGTERM: stop every process this coordinator
    /// started, remove the generated secret's directory, then exit 130 or
    /// 143. Installed before the first process starts.
    fn stop_on_signals(&self) -> Result<(), Error> {
        use tokio::signal::unix::{SignalKind, signal};
        let _guard = self.runtime.enter();
        let listen =
            |kind| signal(kind).map_err(|e| net_error(format!("cannot handle signals: {e}")));
        let (mut interrupt, mut terminate) = (
            listen(SignalKind::interrupt())?,
            listen(SignalKind::terminate())?,
        );
        let children = self.children.clone();
        let secret_dir = self.secret_dir.as_ref().map(|d| d.path().to_owned());
        self.runtime.spawn(async move {
            let (name, code) = tokio::select! {
                _ = interrupt.recv() => ("interrupted", 130),
                _ = terminate.recv() => ("terminated", 143),
            };
            eprintln!("{name}: stopping the experiment's processes");
            children
                .lock()
                .expect("children")
                .reap(Duration::from_millis(500));
            // `exit` runs no destructors: the directory would outlive us.
            if let Some(dir) = secret_dir
                && let Err(e) = std::fs::remove_dir_all(&dir)
            {
                eprintln!("cannot remove {}: {e}", dir.display());
            }
            std::process::exit(code);
        });
        Ok(())
    }

    /// Why `role` counts as lost: its process exited (with its status), or
    /// its liveliness token expired while the process still runs.
    pub fn loss(&self, role: Role) -> String {
        let name = match role {
            Role::Server => "env-server".to_owned(),
            Role::Agent(i) => format!("agent {i}"),
            Role::Coordinator => "coordinator".to_owned(),
        };
        let mut children = self.children.lock().expect("children");
        match children.exit_status(&name, Duration::from_millis(500)) {
            Some(status) => format!("{role} is gone: its process exited ({status})"),
            None if children.started(&name) => format!(
                "{role} stopped answering: its liveliness token expired while its process \
                 still runs (stopped or overloaded?)"
            ),
            None => format!("{role} is gone (its liveliness token disappeared)"),
        }
    }

    /// The settings it was started with.
    pub fn settings(&self) -> &ZenohSettings {
        &self.settings
    }

    /// Whether `role`'s liveliness token is currently seen.
    pub fn is_alive(&self, role: Role) -> bool {
        self.alive.lock().expect("liveliness set").contains(&role)
    }

    /// The first process whose token disappeared after everyone joined.
    pub fn lost(&self) -> Option<Role> {
        *self.lost.borrow()
    }

    /// Experiment id carried in every header.
    pub fn experiment(&self) -> u64 {
        self.experiment
    }

    /// Sends `control` to `role` and returns its reply; gives up at once when
    /// a process of the experiment is lost meanwhile.
    pub fn control(
        &self,
        role: Role,
        header: Header,
        control: Control,
        timeout: Duration,
    ) -> Result<ControlReply, String> {
        let what = format!("{control:?}");
        let bytes = proto::encode(&Envelope {
            header,
            body: Body::Control(control),
        });
        self.count(Direction::Sent, MessageKind::Control, bytes.len());
        let key = self.keys.control(role);
        let mut lost = self.lost.subscribe();
        let gone = |role: Role| self.loss(role);
        if let Some(gone_role) = *lost.borrow_and_update() {
            return Err(gone(gone_role));
        }
        let sent = Instant::now();
        let reply = self.runtime.block_on(async {
            let replies = self
                .session
                .get(&key)
                .payload(bytes)
                .consolidation(ConsolidationMode::None)
                .target(QueryTarget::All)
                .timeout(timeout)
                .await
                .map_err(|e| format!("cannot send {what} to {role}: {e}"))?;
            loop {
                let reply = tokio::select! {
                    reply = replies.recv_async() => match reply {
                        Ok(reply) => reply,
                        Err(_) => break,
                    },
                    Ok(()) = lost.changed() => match *lost.borrow_and_update() {
                        Some(gone_role) => return Err(gone(gone_role)),
                        None => continue,
                    },
                };
                let Ok(sample) = reply.result() else { continue };
                let payload = sample.payload().to_bytes();
                match proto::decode(&payload, self.experiment) {
                    Ok(Envelope {
                        body: Body::ControlReply(r),
                        ..
                    }) => {
                        self.count(
                            Direction::Received,
                            MessageKind::ControlReply,
                            payload.len(),
                        );
                        return Ok(r);
                    }
                    Ok(_) => self
                        .counters
                        .lock()
                        .expect("counters")
                        .record_drop(proto::DropReason::Stale),
                    Err(e) => self.counters.lock().expect("counters").drop_undecodable(&e),
                }
            }
            // All routes answered without a reply: say so, not the timeout.
            let waited = sent.elapsed();
            Err(if waited + Duration::from_millis(100) < timeout {
                format!(
                    "{role} did not answer {what}: the query ended after {waited:.1?} with no \
                     reply (no route to {role})"
                )
            } else {
                format!("{role} did not answer {what} within {timeout:?}")
            })
        })?;
        match reply {
            ControlReply::Error(e) => Err(format!("{role}: {e}")),
            r => Ok(r),
        }
    }

    fn count(&self, direction: Direction, kind: MessageKind, bytes: usize) {
        self.counters
            .lock()
            .expect("counters")
            .record(direction, kind, bytes);
    }

    /// Stops every process this coordinator started (attached ones keep running).
    pub fn stop(&self) {
        // Not held across the stops below: describing a loss locks it too.
        if self.children.lock().expect("children").is_empty() {
            return;
        }
        // The stop goes to every process still there, whoever was lost.
        self.lost.send_replace(None);
        for role in &self.roles {
            if self.is_alive(*role) {
                let _ = self.control(
                    *role,
                    Header::new(self.experiment, 0, 0, 0),
                    Control::Stop,
                    Duration::from_millis(500),
                );
            }
        }
        self.children
            .lock()
            .expect("children")
            .reap(Duration::from_secs(2));
    }
}

impl Drop for Network {
    fn drop(&mut self) {
        self.stop();
    }
}
