//! Starting and stopping the env-server and agent processes on this host.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::error::Error;

/// The processes this coordinator started; killed when dropped.
#[derive(Debug, Default)]
pub struct Children {
    processes: Vec<(String, Child)>,
}

impl Children {
    /// Starts `program` with `args`, named `name` in messages. On Linux
    /// the child is killed when this coordinator dies, however it dies.
    pub fn spawn(&mut self, name: &str, program: &Path, args: &[String]) -> Result<(), Error> {
        let mut command = Command::new(program);
        command.args(args).stdin(Stdio::null());
        die_with_parent(&mut command);
        let child = command
            .spawn()
            .map_err(|e| Error::io("start", program, e))?;
        tracing::debug!(name, pid = child.id(), "started");
        self.processes.push((name.to_owned(), child));
        Ok(())
    }

    /// Whether no process was started.
    pub fn is_empty(&self) -> bool {
        self.processes.is_empty()
    }

    /// What became of the process named `name` within `limit`: `Some(status)`
    /// once it exited, `None` while it runs or when this coordinator did not
    /// start it. (A killed process closes its sockets, which its peers see
    /// at once, a moment before it has exited.)
    pub fn exit_status(&mut self, name: &str, limit: Duration) -> Option<std::process::ExitStatus> {
        let (_, child) = self.processes.iter_mut().find(|(n, _)| n == name)?;
        let deadline = Instant::now() + limit;
        loop {
            match child.try_wait() {
                Ok(Some(status)) => return Some(status),
                Ok(None) if Instant::now() < deadline => {
                    std::thread::sleep(Duration::from_millis(10))
                }
                _ => return None,
            }
        }
    }

    /// Whether this coordinator started the process named `name`.
    pub fn started(&self, name: &str) -> bool {
        self.processes.iter().any(|(n, _)| n == name)
    }

    /// The first process that has already exited, with its status.
    pub fn exited(&mut self) -> Option<String> {
        self.processes.iter_mut().find_map(|(name, child)| {
            let status = child.try_wait().ok().flatten()?;
            Some(format!("{name} exited ({status})"))
        })
    }

    /// Asks every process to stop (SIGTERM), waits up to `grace` for them to
    /// exit, then kills the rest.
    pub fn reap(&mut self, grace: Duration) {
        for (_, child) in &mut self.processes {
            terminate(child);
        }
        let deadline = Instant::now() + grace;
        for (name, child) in &mut self.processes {
            while matches!(child.try_wait(), Ok(None)) && Instant::now() < deadline {
                std::thread::sleep(Duration::from_millis(20));
            }
            if matches!(child.try_wait(), Ok(None)) {
                tracing::warn!(name, "did not stop in time; killing it");
                let _ = child.kill();
            }
            let _ = child.wait();
        }
        self.processes.clear();
    }
}

/// Sends SIGTERM to a child that is still running.
#[cfg(unix)]
fn terminate(child: &mut Child) {
    if matches!(child.try_wait(), Ok(None))
        && let Ok(pid) = libc::pid_t::try_from(child.id())
    {
        // SAFETY: plain kill(2) on our own child, which has not been reaped.
        unsafe {
            libc::kill(pid, libc::SIGTERM);
        }
    }
}

#[cfg(not(unix))]
fn terminate(_: &mut Child) {}

impl Drop for Children {
    fn drop(&mut self) {
        for (_, child) in &mut self.processes {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Makes the child receive SIGKILL when the thread that started it ends
/// (Linux `PR_SET_PDEATHSIG`), and exit at once if the parent already died
/// before that was set. The coordinator starts its processes from the main
/// thread, which lives as long as the coordinator.
#[cfg(target_os = "linux")]
fn die_with_parent(command: &mut Command) {
    use std::os::unix::process::CommandExt;
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
