//! Starting and stopping the env-server and agent processes on this host.

use std::path::{Path, PathBuf};
use std::process::{ExitStatus, Stdio};
use std::sync::Mutex;
use std::time::Duration;

use node::sync::lock;
use tokio::process::{Child, Command};
use tokio::runtime::Handle;
use tokio::sync::watch;
use tokio::time::timeout;

use crate::error::Error;

/// How long a killed process may take to be reaped.
const KILL_WAIT: Duration = Duration::from_secs(2);

/// The processes this coordinator started. A task of the runtime awaits each
/// one, sends it the signals asked for and records its exit; a process still
/// running when the runtime shuts down is killed.
#[derive(Debug)]
pub struct Children {
    runtime: Handle,
    /// Names of the processes started, in order.
    names: Mutex<Vec<String>>,
    /// The signal for every process still running: SIGTERM, then SIGKILL.
    signal: watch::Sender<Option<libc::c_int>>,
    /// The processes that exited, in the order they did, with their status.
    exits: watch::Sender<Vec<(String, ExitStatus)>>,
}

impl Children {
    /// No process yet; those started will be awaited on `runtime`.
    pub fn new(runtime: Handle) -> Self {
        Self {
            runtime,
            names: Mutex::default(),
            signal: watch::Sender::new(None),
            exits: watch::Sender::new(Vec::new()),
        }
    }

    /// Starts `program` with `args`, named `name` in messages. On Linux
    /// the child is killed when this coordinator dies, however it dies.
    pub fn spawn(&self, name: &str, program: &Path, args: &[String]) -> Result<(), Error> {
        let mut command = Command::new(program);
        command.args(args).stdin(Stdio::null()).kill_on_drop(true);
        die_with_parent(&mut command);
        // A child is awaited through the runtime it was started in.
        let _runtime = self.runtime.enter();
        let child = command
            .spawn()
            .map_err(|e| Error::io("start", program, e))?;
        tracing::debug!(name, pid = child.id(), "started");
        lock(&self.names).push(name.to_owned());
        self.runtime.spawn(supervise(
            name.to_owned(),
            child,
            self.signal.subscribe(),
            self.exits.clone(),
        ));
        Ok(())
    }

    /// Whether no process was started.
    pub fn is_empty(&self) -> bool {
        lock(&self.names).is_empty()
    }

    /// Whether this coordinator started the process named `name`.
    pub fn started(&self, name: &str) -> bool {
        lock(&self.names).iter().any(|n| n == name)
    }

    /// What became of the process named `name` within `limit`: `Some(status)`
    /// once it exited, `None` while it runs or when this coordinator did not
    /// start it. (A killed process closes its sockets, which its peers see
    /// at once, a moment before it has exited.)
    pub async fn exit_status(&self, name: &str, limit: Duration) -> Option<ExitStatus> {
        if !self.started(name) {
            return None;
        }
        let mut exits = self.exits.subscribe();
        let exited = exits.wait_for(|exits| exits.iter().any(|(n, _)| n == name));
        let exits = timeout(limit, exited).await.ok()?.ok()?;
        exits.iter().find(|(n, _)| n == name).map(|(_, s)| *s)
    }

    /// Resolves once one of the processes `names` has exited (or at once if
    /// one has): its index in `names` and its status; never if none does.
    pub async fn first_exit_of(&self, names: &[String]) -> (usize, ExitStatus) {
        let mut exits = self.exits.subscribe();
        loop {
            let found = (exits.borrow_and_update().iter())
                .find_map(|(name, status)| Some((names.iter().position(|n| n == name)?, *status)));
            if let Some(found) = found {
                return found;
            }
            if exits.changed().await.is_err() {
                return std::future::pending().await;
            }
        }
    }

    /// Asks every process to stop (SIGTERM), waits up to `grace` for them to
    /// exit, then kills the rest and waits up to `KILL_WAIT` for them.
    pub async fn reap(&self, grace: Duration) {
        let names = std::mem::take(&mut *lock(&self.names));
        let mut exits = self.exits.subscribe();
        let all_exited = |exits: &Vec<(String, ExitStatus)>| {
            names.iter().all(|n| exits.iter().any(|(e, _)| e == n))
        };
        self.signal.send_replace(Some(libc::SIGTERM));
        if timeout(grace, exits.wait_for(all_exited)).await.is_ok() {
            return;
        }
        for name in names
            .iter()
            .filter(|n| !exits.borrow().iter().any(|(e, _)| e == *n))
        {
            tracing::warn!(name, "did not stop in time; killing it");
        }
        self.signal.send_replace(Some(libc::SIGKILL));
        if timeout(KILL_WAIT, exits.wait_for(all_exited))
            .await
            .is_err()
        {
            tracing::warn!("a killed process was still not reaped after {KILL_WAIT:?}");
        }
    }
}

/// Awaits `child`, sending it every signal asked for meanwhile, and records
/// its exit in `exits`.
async fn supervise(
    name: String,
    mut child: Child,
    mut signal: watch::Receiver<Option<libc::c_int>>,
    exits: watch::Sender<Vec<(String, ExitStatus)>>,
) {
    let status = loop {
        tokio::select! {
            status = child.wait() => break status,
            Ok(()) = signal.changed() => {
                let signal = *signal.borrow_and_update();
                // `id` is none once the child is reaped, which only this task does.
                if let (Some(signal), Some(pid)) = (signal, child.id())
                    && let Ok(pid) = libc::pid_t::try_from(pid)
                {
                    // SAFETY: plain kill(2) on our own child, which has not been reaped.
                    unsafe {
                        libc::kill(pid, signal);
                    }
                }
            }
        }
    };
    match status {
        Ok(status) => {
            tracing::debug!(name, %status, "exited");
            exits.send_modify(|exits| exits.push((name, status)));
        }
        Err(e) => tracing::warn!(name, "cannot await the process: {e}"),
    }
}

/// Makes the child receive SIGKILL when the thread that started it ends
/// (Linux `PR_SET_PDEATHSIG`), and exit at once if the parent already died
/// before that was set. The coordinator starts its processes from the main
/// thread, which lives as long as the coordinator.
#[cfg(target_os = "linux")]
fn die_with_parent(command: &mut Command) {
    // SAFETY: the closure runs in the child between fork and exec and only
    // makes async-signal-safe calls (getppid, prctl, _exit).
    let parent = unsafe { libc::getpid() };
    unsafe {
        command.pre_exec(move || {
            if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            if libc::getppid() != parent {
                libc::_exit(1);
            }
            Ok(())
        });
    }
}

#[cfg(not(target_os = "linux"))]
fn die_with_parent(_: &mut Command) {}

/// Where the `env-server` and `agent` executables are: `dir` if given, else
/// next to this executable (or its parent, for test binaries in `deps/`).
pub fn find_binary(dir: Option<&Path>, name: &str) -> Result<PathBuf, Error> {
    let file = format!("{name}{}", std::env::consts::EXE_SUFFIX);
    let candidates: Vec<PathBuf> = match dir {
        Some(d) => vec![d.join(&file)],
        None => {
            let exe =
                std::env::current_exe().map_err(|e| Error::io("locate", "the coordinator", e))?;
            exe.ancestors()
                .skip(1)
                .take(2)
                .map(|d| d.join(&file))
                .collect()
        }
    };
    candidates
        .iter()
        .find(|p| p.is_file())
        .cloned()
        .ok_or_else(|| Error::Transport(format!(
                "cannot find the {name} executable (looked at {}); build it with `cargo build --release` or pass --bin-dir",
                candidates.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ")
            )))
}
