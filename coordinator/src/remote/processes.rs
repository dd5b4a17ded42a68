//! The coordinator's side of the zenoh network: session, processes, liveliness.

use std::collections::HashSet;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use node::net::NetConfig;
use node::secret::Secret;
use node::sync::lock;
use proto::keys::{Keys, Role};
use proto::{
    Body, Control, ControlReply, Direction, Envelope, Header, MessageCounters, MessageKind,
    Simulator,
};
use tokio::sync::watch;
use tokio::time::timeout_at;
use zenoh::liveliness::LivelinessToken;
use zenoh::pubsub::Subscriber;
use zenoh::query::{ConsolidationMode, QueryTarget};
use zenoh::sample::SampleKind;

use super::launch::{Children, find_binary};
use crate::config::AgentSpec;
use crate::error::{ConfigError, Error};
use crate::transport::{Auth, Endpoints, ZenohSettings};

/// Under the restart policy, how many times an agent process that exits
/// before joining is started again in its slot, per start-up (of the team,
/// of a newcomer or of a restarted agent); one more exit ends the run.
const START_RETRIES: usize = 3;
/// How long a query that found no route waits to see its process lost.
const LOSS_WAIT: Duration = Duration::from_secs(3);

/// An agent process that exited before joining and was started again in
/// its slot under the restart policy.
#[derive(Debug)]
pub struct StartedAgain {
    /// Its slot.
    pub slot: usize,
    /// How it was lost: it exited, with its status, before joining.
    pub cause: String,
    /// When its exit was seen.
    pub found: Instant,
}

/// The joined network and the processes of the experiment.
pub struct ZenohTeam {
    settings: ZenohSettings,
    runtime: tokio::runtime::Runtime,
    session: zenoh::Session,
    keys: Keys,
    experiment: u64,
    roles: Vec<Role>,
    /// The roles whose liveliness tokens are seen.
    alive: watch::Sender<HashSet<Role>>,
    /// The first process whose token disappeared; control waits watch it.
    lost: watch::Sender<Option<Role>>,
    /// Roles leaving on purpose (a membership event): not a loss.
    leaving: Arc<Mutex<HashSet<Role>>>,
    /// Per agent slot, the processes that took it after the first
    /// (newcomers and restarts).
    newcomers: Mutex<Vec<usize>>,
    /// The agent processes started again during the team's start-up, until
    /// the first run takes them.
    started_again: Mutex<Vec<StartedAgain>>,
    /// The loopback port this coordinator listens on for its processes.
    port: u16,
    children: Arc<Children>,
    counters: Mutex<MessageCounters>,
    secret: Option<Secret>,
    /// The private directory of a generated secret, removed when dropped.
    secret_dir: Option<tempfile::TempDir>,
    _token: LivelinessToken,
    _watch: Subscriber<()>,
}

impl std::fmt::Debug for ZenohTeam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ZenohTeam")
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
            let (secret, dir) = Secret::generate().map_err(|e| net_error(e.to_string()))?;
            Ok((Some(secret), Some(dir)))
        }
    }
}

/// The endpoint this coordinator listens on: the one given to attach, else
/// loopback `port`. Always listen: a peer that cannot be reached is never
/// linked to a peer that waits for it to open the link.
fn listen_endpoint(options: &Endpoints, port: u16) -> Result<String, Error> {
    match (&options.listen, options.attach) {
        (Some(endpoint), true) => Ok(endpoint.clone()),
        (Some(_), false) => Err(ConfigError::new(
            "listen",
            "a listen endpoint is for --attach; the processes this coordinator starts use its loopback --port",
        )
        .into()),
        (None, _) => Ok(format!("tcp/127.0.0.1:{port}")),
    }
}

/// Follows the liveliness tokens of the experiment `keys` into `alive`; the
/// first role whose token disappears goes into `lost`, unless it is
/// `leaving`.
async fn follow_liveliness(
    session: &zenoh::Session,
    keys: &Keys,
    alive: watch::Sender<HashSet<Role>>,
    lost: watch::Sender<Option<Role>>,
    leaving: Arc<Mutex<HashSet<Role>>>,
) -> Result<Subscriber<()>, Error> {
    let keys_of = keys.clone();
    session
        .liveliness()
        .declare_subscriber(keys.alive_all())
        .history(true)
        .callback(move |sample| {
            let Some(role) = keys_of.role_of_alive(sample.key_expr().as_str()) else {
                return;
            };
            let mut removed = false;
            alive.send_if_modified(|alive| match sample.kind() {
                SampleKind::Put => alive.insert(role),
                SampleKind::Delete => {
                    removed = alive.remove(&role);
                    removed
                }
            });
            if removed && lock(&leaving).contains(&role) {
                tracing::info!(%role, "left");
            } else if removed {
                tracing::warn!(%role, "lost");
                lost.send_if_modified(|first| first.is_none() && first.replace(role).is_none());
            }
        })
        .await
        .map_err(|e| net_error(format!("cannot watch liveliness: {e}")))
}

/// Refuses an experiment that already has a process of `roles` or a
/// coordinator: asks which of its liveliness tokens exist now, within the
/// startup timeout. (Tokens of peers not linked yet are not seen, but the
/// peer or router this session connected to answers with its own and, a
/// router, with every one it knows.)
async fn refuse_a_busy_experiment(
    session: &zenoh::Session,
    keys: &Keys,
    roles: &[Role],
    options: &Endpoints,
) -> Result<(), Error> {
    let replies = session
        .liveliness()
        .get(keys.alive_all())
        .timeout(options.startup_timeout)
        .await
        .map_err(|e| net_error(format!("cannot query liveliness: {e}")))?;
    let mut running = HashSet::new();
    while let Ok(reply) = replies.recv_async().await {
        let Ok(sample) = reply.result() else {
            return Err(net_error(format!(
                "the query for the processes of experiment {} got no complete answer within {:?}",
                options.experiment, options.startup_timeout
            )));
        };
        running.extend(keys.role_of_alive(sample.key_expr().as_str()));
    }
    let mut candidates = roles.iter().chain([&Role::Coordinator]);
    match candidates.find(|r| running.contains(*r)) {
        Some(role) => Err(net_error(format!(
            "experiment {} already has a running {role}; choose another --experiment",
            options.experiment
        ))),
        None => Ok(()),
    }
}

impl ZenohTeam {
    /// Joins the network of `settings.endpoints.experiment`, starts
    /// env-server and the agent processes of `team` (unless attaching) and waits
    /// until every one of them is alive and answers control queries.
    pub fn start(settings: &ZenohSettings, team: &[AgentSpec]) -> Result<Self, Error> {
        let options = &settings.endpoints;
        let port = match options.port {
            0 => node::net::free_port().map_err(|e| Error::io("bind", "127.0.0.1:0", e))?,
            p => p,
        };
        let network = Self::join(settings, team.len(), port)?;
        if !options.attach {
            network.stop_on_signals()?;
            network.launch(team)?;
        }
        network.wait_for_everyone(team)?;
        Ok(network)
    }

    /// Opens the session (listening on loopback `port` unless attaching),
    /// follows the liveliness of env-server and `agents` agents, refuses an
    /// experiment that already runs (unless attaching) and declares this
    /// coordinator's token.
    fn join(settings: &ZenohSettings, agents: usize, port: u16) -> Result<Self, Error> {
        let options = &settings.endpoints;
        let keys = Keys::new(&options.experiment)
            .map_err(|e| ConfigError::new("experiment", e.to_string()))?;
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .map_err(|e| net_error(format!("cannot start the async runtime: {e}")))?;
        let listen = listen_endpoint(options, port)?;
        let (secret, secret_dir) = secret(options)?;
        let net = NetConfig::peer(vec![listen], options.connect.clone())
            .with_secret(secret.clone())
            .with_base(options.zenoh_config.clone());
        let roles: Vec<Role> = std::iter::once(Role::Server)
            .chain((0..agents).map(|i| Role::Agent(i as u8)))
            .collect();
        let alive = watch::Sender::new(HashSet::new());
        let lost = watch::Sender::new(None);
        let leaving = Arc::new(Mutex::new(HashSet::new()));
        let (session, watch, token) = runtime.block_on(async {
            let session = node::net::open(&net)
                .await
                .map_err(|e| net_error(e.to_string()))?;
            let watch = follow_liveliness(
                &session,
                &keys,
                alive.clone(),
                lost.clone(),
                leaving.clone(),
            )
            .await?;
            if !options.attach {
                // Before this coordinator's token, whose key another's has too.
                refuse_a_busy_experiment(&session, &keys, &roles, options).await?;
            }
            let token = session
                .liveliness()
                .declare_token(keys.alive(Role::Coordinator))
                .await
                .map_err(|e| net_error(format!("cannot declare liveliness: {e}")))?;
            Ok::<_, Error>((session, watch, token))
        })?;
        Ok(ZenohTeam {
            children: Arc::new(Children::new(runtime.handle().clone())),
            settings: settings.clone(),
            runtime,
            session,
            experiment: proto::experiment_id(&options.experiment),
            keys,
            roles,
            alive,
            lost,
            leaving,
            newcomers: Mutex::new(vec![0; agents]),
            started_again: Mutex::default(),
            port,
            counters: Mutex::new(MessageCounters::default()),
            secret,
            secret_dir,
            _token: token,
            _watch: watch,
        })
    }

    /// Starts env-server and one agent per member of `team` (with its
    /// learner and strategy commands, if any), connecting to this
    /// coordinator's loopback port.
    fn launch(&self, team: &[AgentSpec]) -> Result<(), Error> {
        let options = &self.settings.endpoints;
        let server = find_binary(options.bin_dir.as_deref(), "env-server")?;
        let mut serve = vec!["serve".into(), "--exit-with-coordinator".into()];
        if self.settings.simulator == Simulator::RealHfo {
            let dir = options.hfo_dir.as_ref().ok_or_else(|| {
                ConfigError::new(
                    "hfo_dir",
                    "the real HFO is not located: pass --hfo-dir DIR (or set HFO_DIR), \
                     DIR built by env-server/oracle/build_hfo.sh",
                )
            })?;
            serve.extend(["--real-hfo".into(), dir.display().to_string()]);
            if let Some(python) = &options.hfo_python {
                serve.extend(["--hfo-python".into(), python.display().to_string()]);
            }
        }
        self.children
            .spawn("env-server", &server, &self.common_args(&serve))?;
        for (i, spec) in team.iter().enumerate() {
            self.spawn_agent(i, team.len(), spec)?;
        }
        Ok(())
    }

    /// The arguments every process this coordinator starts gets after
    /// `extra`: the experiment, this coordinator's endpoint, the secret.
    fn common_args(&self, extra: &[String]) -> Vec<String> {
        let mut args: Vec<String> = extra.to_vec();
        args.extend([
            "--experiment".into(),
            self.settings.endpoints.experiment.clone(),
            "--connect".into(),
            format!("tcp/127.0.0.1:{}", self.port),
        ]);
        match &self.secret {
            Some(secret) => {
                args.extend(["--secret-file".into(), secret.path().display().to_string()])
            }
            None => args.push("--no-auth".into()),
        }
        args
    }

    /// Starts the process of agent `i` of a team of `n` as `spec` says,
    /// named as [`agent_name`](Self::agent_name) says.
    fn spawn_agent(&self, i: usize, n: usize, spec: &AgentSpec) -> Result<(), Error> {
        let agent = find_binary(self.settings.endpoints.bin_dir.as_deref(), "agent")?;
        let mut args = self.common_args(&[
            "--id".into(),
            i.to_string(),
            "--team-size".into(),
            n.to_string(),
            "--exit-with-coordinator".into(),
        ]);
        // A child may take as long to answer as env-server waits for an action.
        let timeout = self.settings.step_timeout_ms.to_string();
        if let Some(strategy) = &spec.strategy_process {
            let line =
                shlex::try_join(strategy.command.iter().map(String::as_str)).map_err(|e| {
                    ConfigError::new(format!("team[{i}].strategy_process"), e.to_string())
                })?;
            args.extend([
                "--strategy".into(),
                line,
                "--strategy-timeout-ms".into(),
                timeout.clone(),
            ]);
            if let Some(dir) = &strategy.dir {
                args.extend(["--strategy-dir".into(), dir.display().to_string()]);
            }
        }
        if let Some(learner) = &spec.learner {
            args.extend(["--learner-timeout-ms".into(), timeout]);
            if let Some(dir) = &learner.dir {
                args.extend(["--learner-dir".into(), dir.display().to_string()]);
            }
            args.push("--".into());
            args.extend(learner.command.iter().cloned());
        }
        self.children.spawn(&self.agent_name(i), &agent, &args)
    }

    /// The name of agent `i`'s current process: `agent <i>`, then
    /// `agent <i> (process <k>)` for the k-th that took its slot since (a
    /// newcomer or a restart).
    fn agent_name(&self, i: usize) -> String {
        match lock(&self.newcomers).get(i).copied().unwrap_or(0) {
            0 => format!("agent {i}"),
            k => format!("agent {i} (process {})", k + 1),
        }
    }

    /// Agent `slot`'s process was lost: once it has exited, starts `spec`
    /// in its place and waits until it has joined, as [`admit`](Self::admit)
    /// does; the loss is cleared. Returns how it was lost and the processes
    /// started again before one joined.
    pub fn restart(
        &self,
        slot: usize,
        spec: &AgentSpec,
    ) -> Result<(String, Vec<StartedAgain>), Error> {
        let name = self.agent_name(slot);
        let cause = self.loss(Role::Agent(slot as u8));
        if !self.children.started(&name) {
            return Err(net_error(format!(
                "{cause}; it was not started by this coordinator, so it cannot be restarted"
            )));
        }
        let exited = self
            .runtime
            .block_on(self.children.exit_status(&name, Duration::from_secs(2)));
        if exited.is_none() {
            return Err(net_error(format!(
                "{cause}; its process still runs, so it is not restarted"
            )));
        }
        let again = self.admit(slot, spec)?;
        Ok((cause, again))
    }

    /// Agent `slot`'s process leaves the running experiment: it is asked to
    /// stop, and its exit and the end of its liveliness are awaited (not a
    /// loss). Only for processes this coordinator started.
    pub fn retire(&self, slot: usize) -> Result<(), String> {
        let (role, name) = (Role::Agent(slot as u8), self.agent_name(slot));
        if !self.children.started(&name) {
            return Err(format!(
                "{name} was not started by this coordinator: membership events replace only \
                 the processes it starts (not with --attach)"
            ));
        }
        lock(&self.leaving).insert(role);
        let header = Header::new(self.experiment, 0, 0, 0);
        self.control(role, header, Control::Stop, Duration::from_secs(2))?;
        let limit = self.settings.endpoints.startup_timeout;
        let gone = self.runtime.block_on(async {
            self.children.exit_status(&name, limit).await?;
            let mut alive = self.alive.subscribe();
            let token_gone = alive.wait_for(|a| !a.contains(&role));
            timeout_at(tokio::time::Instant::now() + limit, token_gone)
                .await
                .ok()
                .map(|_| ())
        });
        lock(&self.leaving).remove(&role);
        match gone {
            Some(_) => Ok(()),
            None => Err(format!(
                "{name} did not leave within {limit:?} of being asked to stop"
            )),
        }
    }

    /// Starts the newcomer `spec` in agent `slot`'s place and waits, within
    /// the startup timeout, until it has joined; under the restart policy a
    /// process of it that exits first is started again (see
    /// [`join_or_start_again`](Self::join_or_start_again)), and those are
    /// returned. A loss of the slot seen meanwhile is cleared.
    pub fn admit(&self, slot: usize, spec: &AgentSpec) -> Result<Vec<StartedAgain>, Error> {
        self.start_next(slot, spec)?;
        let role = Role::Agent(slot as u8);
        let again = self.join_or_start_again(&[role], |_| spec)?;
        self.lost
            .send_if_modified(|lost| *lost == Some(role) && lost.take().is_some());
        Ok(again)
    }

    /// Starts `spec` as the next process of agent `slot`, named as
    /// [`agent_name`](Self::agent_name) says.
    fn start_next(&self, slot: usize, spec: &AgentSpec) -> Result<(), Error> {
        if let Some(k) = lock(&self.newcomers).get_mut(slot) {
            *k += 1;
        }
        self.spawn_agent(slot, self.roles.len() - 1, spec)
    }

    /// Waits until every process has joined, as
    /// [`join_or_start_again`](Self::join_or_start_again) says (`team`:
    /// what each agent process is started as); keeps those started again
    /// for the first run to record.
    fn wait_for_everyone(&self, team: &[AgentSpec]) -> Result<(), Error> {
        let again = self.join_or_start_again(&self.roles, |slot| &team[slot])?;
        *lock(&self.started_again) = again;
        self.lost.send_replace(None);
        Ok(())
    }

    /// Waits, within the startup timeout, until every one of `roles` has
    /// joined: its liveliness token is seen and its control queryable
    /// reachable. Fails at once if a process this coordinator started for
    /// one of them exits first; but under the restart policy an agent's is
    /// started again as `spec_of` its slot says, at most
    /// [`START_RETRIES`] times per slot, and the wait begins anew with a
    /// whole startup timeout. Returns the processes started again.
    fn join_or_start_again<'s>(
        &self,
        roles: &[Role],
        spec_of: impl Fn(usize) -> &'s AgentSpec,
    ) -> Result<Vec<StartedAgain>, Error> {
        let options = &self.settings.endpoints;
        let mut again: Vec<StartedAgain> = Vec::new();
        loop {
            let names: Vec<String> = roles.iter().map(|r| self.process_name(*r)).collect();
            let deadline = tokio::time::Instant::now() + options.startup_timeout;
            let exited = self.runtime.block_on(async {
                tokio::select! {
                    joined = self.joined(deadline, roles) => joined.map(|()| None),
                    exited = self.children.first_exit_of(&names) => Ok(Some(exited)),
                }
            })?;
            let Some((k, status)) = exited else {
                return Ok(again);
            };
            let cause = format!(
                "{} exited ({status}) before joining experiment {}",
                names[k], options.experiment
            );
            let (Role::Agent(slot), true) = (roles[k], self.settings.restart_agents) else {
                return Err(net_error(cause));
            };
            let slot = usize::from(slot);
            if again.iter().filter(|a| a.slot == slot).count() == START_RETRIES {
                return Err(net_error(format!(
                    "{cause}; its slot was already started again {START_RETRIES} times, \
                     the most per start-up"
                )));
            }
            tracing::warn!(slot, %cause, "starting the agent again");
            let found = Instant::now();
            self.start_next(slot, spec_of(slot))?;
            again.push(StartedAgain { slot, cause, found });
        }
    }

    /// Resolves once every role's token is seen and its control queryable
    /// is reachable (zenoh's matching status of a querier on its key), or
    /// fails at `deadline` naming those missing and what they miss.
    async fn joined(&self, deadline: tokio::time::Instant, roles: &[Role]) -> Result<(), Error> {
        let options = &self.settings.endpoints;
        let did_not_join = |missing: &[Role], what: &str| {
            let missing: Vec<String> = missing.iter().map(Role::to_string).collect();
            net_error(format!(
                "{} did not join experiment {} within {:?} ({what})",
                missing.join(", "),
                options.experiment,
                options.startup_timeout
            ))
        };
        let mut alive = self.alive.subscribe();
        let everyone = alive.wait_for(|alive| roles.iter().all(|r| alive.contains(r)));
        if timeout_at(deadline, everyone).await.is_err() {
            let missing: Vec<Role> = roles
                .iter()
                .copied()
                .filter(|r| !self.is_alive(*r))
                .collect();
            return Err(did_not_join(&missing, "no liveliness token seen"));
        }
        // A process declares its queryables before its token, but they may
        // reach this session after it.
        for &role in roles {
            let querier = self
                .session
                .declare_querier(self.keys.control(role))
                .await
                .map_err(|e| net_error(format!("cannot declare a querier: {e}")))?;
            let listener = querier
                .matching_listener()
                .await
                .map_err(|e| net_error(format!("cannot follow the control queryables: {e}")))?;
            let reachable = async {
                while let Ok(status) = listener.recv_async().await {
                    if status.matching() {
                        return;
                    }
                }
                std::future::pending().await
            };
            if timeout_at(deadline, reachable).await.is_err() {
                return Err(did_not_join(&[role], "its control queryable not reachable"));
            }
        }
        Ok(())
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
            children.reap(Duration::from_millis(500)).await;
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
        self.runtime.block_on(self.describe_loss(role))
    }

    /// The name of `role`'s current process.
    fn process_name(&self, role: Role) -> String {
        match role {
            Role::Server => "env-server".to_owned(),
            Role::Agent(i) => self.agent_name(i.into()),
            Role::Coordinator => "coordinator".to_owned(),
        }
    }

    async fn describe_loss(&self, role: Role) -> String {
        let name = self.process_name(role);
        let exit = self.children.exit_status(&name, Duration::from_millis(500));
        match exit.await {
            Some(status) => format!("{role} is gone: its process exited ({status})"),
            None if self.children.started(&name) => format!(
                "{role} stopped answering: its liveliness token expired while its process \
                 still runs (stopped or overloaded?)"
            ),
            None => format!("{role} is gone (its liveliness token disappeared)"),
        }
    }

    /// The agent processes started again during the team's start-up (for
    /// the first run to record; none after).
    pub fn take_started_again(&self) -> Vec<StartedAgain> {
        std::mem::take(&mut lock(&self.started_again))
    }

    /// The settings it was started with.
    pub fn settings(&self) -> &ZenohSettings {
        &self.settings
    }

    /// Whether `role`'s liveliness token is currently seen.
    pub fn is_alive(&self, role: Role) -> bool {
        self.alive.borrow().contains(&role)
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
    /// a process of the experiment is lost meanwhile (with `restart_agents`,
    /// only when `role` or env-server is: another agent is restarted).
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
        let fatal = |gone: Role| {
            !self.settings.restart_agents || gone == role || !matches!(gone, Role::Agent(_))
        };
        if let Some(gone_role) = *lost.borrow_and_update()
            && fatal(gone_role)
        {
            return Err(self.loss(gone_role));
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
                        Some(gone_role) if fatal(gone_role) => {
                            return Err(self.describe_loss(gone_role).await)
                        }
                        _ => continue,
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
                    Ok(_) => lock(&self.counters).record_drop(proto::DropReason::Stale),
                    Err(proto::DecodeError::Version { found, expected }) => {
                        return Err(format!(
                            "{role} speaks protocol version {found}, this coordinator {expected}: \
                             every process of an experiment must run the same build"
                        ));
                    }
                    Err(e) => lock(&self.counters).drop_undecodable(&e),
                }
            }
            // All routes answered without a reply: say so, not the timeout.
            let waited = sent.elapsed();
            Err(if waited + Duration::from_millis(100) < timeout {
                // A route goes a moment before the liveliness token does.
                let gone = tokio::time::timeout(LOSS_WAIT, lost.wait_for(|g| g.is_some_and(fatal)))
                    .await
                    .ok()
                    .and_then(|gone| gone.ok().and_then(|g| *g));
                if let Some(gone_role) = gone {
                    return Err(self.describe_loss(gone_role).await);
                }
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
        lock(&self.counters).record(direction, kind, bytes);
    }

    /// Stops every process this coordinator started (attached ones keep running).
    pub fn stop(&self) {
        if self.children.is_empty() {
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
        self.runtime
            .block_on(self.children.reap(Duration::from_secs(2)));
    }
}

impl Drop for ZenohTeam {
    fn drop(&mut self) {
        self.stop();
    }
}
