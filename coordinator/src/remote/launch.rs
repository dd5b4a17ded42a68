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
    /// Starts `program` with `args`, named `name` in messages.
    pub fn spawn(&mut self, name: &str, program: &Path, args: &[String]) -> Result<(), Error> {
        let child = Command::new(program)
            .args(args)
            .stdin(Stdio::null())
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

    /// The first process that has already exited, with its status.
    pub fn exited(&mut self) -> Option<String> {
        self.processes.iter_mut().find_map(|(name, child)| {
            let status = child.try_wait().ok().flatten()?;
            Some(format!("{name} exited ({status})"))
        })
    }

    /// Waits up to `grace` for every process to exit, then kills the rest.
    pub fn reap(&mut self, grace: Duration) {
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

impl Drop for Children {
    fn drop(&mut self) {
        for (_, child) in &mut self.processes {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

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
