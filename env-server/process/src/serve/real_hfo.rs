//! The real HFO as a served run's simulator: `python -m hfo_oracle backend`
//! (`env-server/oracle/hfo_oracle/backend.py`), a child process that runs
//! HFO's rcssserver, agent2d's goalkeeper and one HFO player per agent,
//! stepped with one line each way per command over its standard input and
//! output (docs/protocol.md, "The real HFO"). Every wait for it has a limit
//! and names what it waited for; its lines are bounded and checked.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, sync_channel};
use std::time::{Duration, Instant};

use env_server::{EnvConfig, Outcome};
use proto::{Action, Features, State};
use serde::Deserialize;

use super::simulator::ServedSimulator;

/// How long the real HFO may take to start and play out its warm-up trial.
const STARTUP_WAIT: Duration = Duration::from_secs(120);
/// How long one command may take (a step, or an episode's begin, which
/// plays out an abandoned trial of at most a few hundred cycles).
const COMMAND_WAIT: Duration = Duration::from_secs(30);
/// How long the backend may take to stop once asked.
const STOP_WAIT: Duration = Duration::from_secs(5);
/// The longest line the backend may write (a frame is a few hundred bytes).
const MAX_LINE: u64 = 64 * 1024;

/// Where the real HFO and its harness are on this host (`env-server serve
/// --real-hfo DIR`).
#[derive(Clone, Debug)]
pub struct RealHfoInstall {
    /// A tree built by `env-server/oracle/build_hfo.sh` (`bin/HFO`).
    pub hfo_dir: PathBuf,
    /// The interpreter of HFO's launcher and players (with numpy).
    pub python: PathBuf,
    /// The directory holding the package `hfo_oracle` (`env-server/oracle`).
    pub harness: PathBuf,
}

impl RealHfoInstall {
    /// Checks that every piece is where it is said to be, naming the first
    /// that is missing and how to get it.
    pub fn check(&self) -> Result<(), String> {
        let launcher = self.hfo_dir.join("bin").join("HFO");
        if !launcher.is_file() {
            return Err(format!(
                "no real HFO at {}: {} is missing; build it with env-server/oracle/build_hfo.sh {}",
                self.hfo_dir.display(),
                launcher.display(),
                self.hfo_dir.display()
            ));
        }
        // A bare name (`python3`) is looked up in PATH when started.
        let bare = self.python.components().count() == 1;
        if !bare && !self.python.is_file() {
            return Err(format!(
                "no Python interpreter at {} for the real HFO (build_hfo.sh makes DIR/venv/bin/python)",
                self.python.display()
            ));
        }
        let package = self.harness.join("hfo_oracle").join("backend.py");
        if !package.is_file() {
            return Err(format!(
                "no real-HFO harness at {} ({} is missing): pass --hfo-harness with the \
                 repository's env-server/oracle directory",
                self.harness.display(),
                package.display()
            ));
        }
        Ok(())
    }
}

/// One line of the backend: a frame, or why it stopped.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Line {
    Frame(Frame),
    Error { error: String },
}

/// The current frame as the backend reports it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Frame {
    frame: u32,
    outcome: Status,
    kick: Vec<bool>,
    states: Vec<State>,
    pos: Vec<[f64; 2]>,
}

/// How the step that led to a frame ended, as the backend names it.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum Status {
    InGame,
    Goal,
    Captured,
    OutOfBounds,
    OutOfTime,
}

impl From<Status> for Outcome {
    fn from(status: Status) -> Outcome {
        match status {
            Status::InGame => Outcome::InGame,
            Status::Goal => Outcome::Goal,
            Status::Captured => Outcome::Captured,
            Status::OutOfBounds => Outcome::OutOfBounds,
            Status::OutOfTime => Outcome::OutOfTime,
        }
    }
}

/// The real HFO of one run: its backend process and current frame. A
/// backend that failed is replaced by a new one at the next episode.
#[derive(Debug)]
pub struct RealHfo {
    backend: Backend,
    /// What a new backend is started with.
    launch: Launch,
    /// Backends started after a failure.
    restarts: u64,
    /// Whether the backend failed (its episode was abandoned).
    failed: bool,
    frame: Option<Frame>,
}

/// Where and with what settings a run's backend starts.
#[derive(Debug)]
struct Launch {
    install: RealHfoInstall,
    offense: usize,
    frames_per_trial: u32,
    untouched_time: u32,
    seed: u64,
}

/// One backend process, stepped over its standard input and output.
#[derive(Debug)]
struct Backend {
    child: Child,
    stdin: Option<ChildStdin>,
    /// Its lines, read by a thread of their own.
    lines: Receiver<Result<String, String>>,
    /// Whether it has answered once (it has started).
    started: bool,
}

impl RealHfo {
    /// Starts the backend for a run with settings `config` (which the real
    /// HFO must be able to play) and `seed`; it starts HFO meanwhile, and
    /// the first episode waits for it.
    pub fn start(install: &RealHfoInstall, config: &EnvConfig, seed: u64) -> Result<Self, String> {
        if let Some(setting) = config.unlike_real_hfo() {
            return Err(format!(
                "the real HFO cannot play env.{setting} as set: it is a setting of our simulator"
            ));
        }
        install.check()?;
        let launch = Launch {
            install: install.clone(),
            offense: config.offense,
            frames_per_trial: config.frames_per_trial,
            untouched_time: config.untouched_time,
            seed,
        };
        Ok(RealHfo {
            backend: Backend::spawn(&launch, seed)?,
            launch,
            restarts: 0,
            failed: false,
            frame: None,
        })
    }

    /// Sends `command` and waits for the frame it answers; an error marks
    /// the backend failed.
    fn command(&mut self, command: &str, what: &str) -> Result<&Frame, String> {
        match self.backend.command(command, what, self.launch.offense) {
            Ok(frame) => Ok(self.frame.insert(frame)),
            Err(e) => {
                self.failed = true;
                Err(e)
            }
        }
    }

    /// Replaces a failed backend by a new one, seeded anew.
    fn restart(&mut self) -> Result<(), String> {
        self.restarts += 1;
        let seed = self.launch.seed.wrapping_add(self.restarts);
        tracing::warn!(
            restarts = self.restarts,
            "the real HFO's backend failed: starting a new one"
        );
        self.backend = Backend::spawn(&self.launch, seed)?;
        self.failed = false;
        self.frame = None;
        Ok(())
    }

    fn current(&self) -> &Frame {
        self.frame
            .as_ref()
            .expect("the server asks for a frame only after reset")
    }
}

impl Backend {
    /// Starts `python -m hfo_oracle backend` as `launch` says, with `seed`.
    fn spawn(launch: &Launch, seed: u64) -> Result<Self, String> {
        let install = &launch.install;
        let mut child = Command::new(&install.python)
            .args(["-m", "hfo_oracle", "backend", "--hfo-dir"])
            .arg(&install.hfo_dir)
            .arg("--python")
            .arg(&install.python)
            .args([
                format!("--offense={}", launch.offense),
                format!("--frames-per-trial={}", launch.frames_per_trial),
                format!("--untouched-time={}", launch.untouched_time),
                format!("--seed={seed}"),
            ])
            .env("PYTHONPATH", python_path(&install.harness))
            .env("PYTHONDONTWRITEBYTECODE", "1")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot start {}: {e}", install.python.display()))?;
        let stdin = child.stdin.take();
        let stdout = child
            .stdout
            .take()
            .ok_or("the backend has no standard output")?;
        let (sender, lines) = sync_channel(1);
        std::thread::Builder::new()
            .name("real-hfo-lines".to_owned())
            .spawn(move || read_lines(stdout, |line| sender.send(line).is_ok()))
            .map_err(|e| format!("cannot start the real HFO's reader thread: {e}"))?;
        Ok(Backend {
            child,
            stdin,
            lines,
            started: false,
        })
    }

    /// Sends `command` and waits for the frame of `offense` players it
    /// answers.
    fn command(&mut self, command: &str, what: &str, offense: usize) -> Result<Frame, String> {
        let stdin = self.stdin.as_mut().ok_or("the real HFO was stopped")?;
        if writeln!(stdin, "{command}")
            .and_then(|()| stdin.flush())
            .is_err()
        {
            return Err(self.ended(what));
        }
        let wait = if self.started {
            COMMAND_WAIT
        } else {
            STARTUP_WAIT
        };
        let text = match self.lines.recv_timeout(wait) {
            Ok(line) => line?,
            Err(RecvTimeoutError::Timeout) => {
                return Err(format!(
                    "the real HFO did not answer within {wait:?} while {what}"
                ));
            }
            Err(RecvTimeoutError::Disconnected) => return Err(self.ended(what)),
        };
        self.started = true;
        let frame: Frame = match serde_json::from_str(&text) {
            Ok(Line::Frame(frame)) => frame,
            Ok(Line::Error { error }) => return Err(format!("the real HFO: {error}")),
            Err(e) => {
                return Err(format!(
                    "the real HFO answered {} with a line that is not a frame ({e})",
                    what
                ));
            }
        };
        let n = offense;
        if (frame.kick.len(), frame.states.len(), frame.pos.len()) != (n, n, n) {
            return Err(format!(
                "the real HFO reported a frame of {} players, expected {n}",
                frame.states.len()
            ));
        }
        Ok(frame)
    }

    /// The backend closed its pipes while `what`: how it ended, once it
    /// has (waiting up to [`STOP_WAIT`]).
    fn ended(&mut self, what: &str) -> String {
        let status = match self.wait_exit(STOP_WAIT) {
            Some(status) => status.to_string(),
            None => "still running".to_owned(),
        };
        format!("the real HFO's backend ended ({status}) while {what}")
    }

    /// The backend's exit status, once it has exited within `limit`.
    fn wait_exit(&mut self, limit: Duration) -> Option<std::process::ExitStatus> {
        let deadline = Instant::now() + limit;
        loop {
            match self.child.try_wait() {
                Ok(Some(status)) => return Some(status),
                Ok(None) if Instant::now() < deadline => {
                    std::thread::sleep(Duration::from_millis(20));
                }
                _ => return None,
            }
        }
    }
}

impl ServedSimulator for RealHfo {
    fn offense(&self) -> usize {
        self.launch.offense
    }

    /// Begins an episode, on a new backend if the last one failed.
    fn reset(&mut self) -> Result<(), String> {
        if self.failed {
            self.restart()?;
        }
        self.command("R", "beginning an episode").map(|_| ())
    }

    fn step(&mut self, actions: &[Action]) -> Result<Outcome, String> {
        let mut command = String::from("S");
        command.extend(actions.iter().map(|a| match a {
            Action::Move => 'M',
            Action::Shoot => 'S',
            Action::Dribble => 'D',
            Action::PassNear => 'N',
            Action::PassFar => 'F',
        }));
        let what = format!("stepping frame {}", self.frame());
        self.command(&command, &what).map(|f| f.outcome.into())
    }

    fn frame(&self) -> u32 {
        self.frame.as_ref().map_or(0, |f| f.frame)
    }

    fn can_kick(&self, agent: usize) -> bool {
        self.current().kick[agent]
    }

    fn state(&self, agent: usize) -> State {
        self.current().states[agent]
    }

    /// None: the backend sends the paper's state only.
    fn features(&self, _agent: usize) -> Option<Features> {
        None
    }

    fn positions(&self) -> Vec<[f64; 2]> {
        self.current().pos.clone()
    }
}

impl Drop for Backend {
    /// Asks the backend to quit, then terminates it (either way it stops
    /// HFO first), and kills it if it lingers still.
    fn drop(&mut self) {
        if let Some(mut stdin) = self.stdin.take() {
            let _ = writeln!(stdin, "Q");
        }
        if self.wait_exit(STOP_WAIT).is_some() {
            return;
        }
        tracing::warn!("the real HFO's backend did not stop within {STOP_WAIT:?}; terminating it");
        if let Ok(pid) = libc::pid_t::try_from(self.child.id()) {
            // SAFETY: plain kill(2) on our own child, which has not been reaped.
            unsafe {
                libc::kill(pid, libc::SIGTERM);
            }
        }
        if self.wait_exit(STOP_WAIT).is_some() {
            return;
        }
        tracing::warn!("the real HFO's backend did not stop on SIGTERM; killing it");
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Hands every line of `from` to `give` until it refuses, the input ends, or
/// a line is longer than [`MAX_LINE`] (handed over as an error).
fn read_lines(from: impl Read, mut give: impl FnMut(Result<String, String>) -> bool) {
    let mut reader = BufReader::new(from);
    loop {
        let mut line = String::new();
        let read = reader.by_ref().take(MAX_LINE).read_line(&mut line);
        let item = match read {
            Ok(0) => return,
            Ok(_) if !line.ends_with('\n') && line.len() as u64 >= MAX_LINE => Err(format!(
                "the real HFO wrote a line longer than {MAX_LINE} bytes"
            )),
            Ok(_) => Ok(line),
            Err(e) => Err(format!("cannot read the real HFO's output: {e}")),
        };
        let failed = item.is_err();
        if !give(item) || failed {
            return;
        }
    }
}

/// `PYTHONPATH` with `harness` first.
fn python_path(harness: &Path) -> std::ffi::OsString {
    let mut path = harness.as_os_str().to_owned();
    if let Some(rest) = std::env::var_os("PYTHONPATH").filter(|p| !p.is_empty()) {
        path.push(":");
        path.push(rest);
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A harness directory whose `hfo_oracle` backend is `main`, a Python
    /// script, with the real HFO's `bin/HFO` stood in by an empty file.
    fn fake_install(dir: &Path, main: &str) -> RealHfoInstall {
        let package = dir.join("hfo_oracle");
        std::fs::create_dir_all(&package).unwrap();
        std::fs::write(package.join("__init__.py"), "").unwrap();
        std::fs::write(package.join("backend.py"), "").unwrap();
        std::fs::write(package.join("__main__.py"), main).unwrap();
        std::fs::create_dir_all(dir.join("bin")).unwrap();
        std::fs::write(dir.join("bin").join("HFO"), "").unwrap();
        RealHfoInstall {
            hfo_dir: dir.to_path_buf(),
            python: PathBuf::from("python3"),
            harness: dir.to_path_buf(),
        }
    }

    /// A backend that answers every command with `reply(command)`, a Python
    /// expression, then goes on.
    fn backend(reply: &str) -> String {
        format!(
            "import sys\nfor line in sys.stdin:\n    c = line.strip()\n    if c == 'Q':\n        break\n    \
             print({reply}, flush=True)\n"
        )
    }

    fn frame(frame: u32, outcome: &str, kick: [bool; 3]) -> String {
        let kick: Vec<String> = kick.iter().map(|k| k.to_string()).collect();
        format!(
            r#"'{{"frame": {frame}, "outcome": "{outcome}", "kick": [{}], "states": [[1,0,0,0,0,0],[-1,0.5,0,0,0,0],[-1,0,0,0,0,0]], "pos": [[40,0],[30,-8],[30,10]]}}'"#,
            kick.join(",")
        )
    }

    fn start(main: &str) -> (tempfile::TempDir, Result<RealHfo, String>) {
        let dir = tempfile::tempdir().unwrap();
        let install = fake_install(dir.path(), main);
        let hfo = RealHfo::start(&install, &EnvConfig::default(), 7);
        (dir, hfo)
    }

    #[test]
    fn a_backend_is_stepped_one_line_each_way() {
        // Frame 0 on R; a goal on the step that names agent 0's SHOOT.
        let reply = format!(
            "{} if c == 'R' else ({} if c == 'SSMM' else {})",
            frame(0, "in-game", [true, false, false]),
            frame(1, "goal", [false; 3]),
            frame(1, "in-game", [false; 3])
        );
        let (_dir, hfo) = start(&backend(&reply));
        let mut hfo = hfo.unwrap();
        hfo.reset().unwrap();
        assert_eq!((hfo.frame(), hfo.offense()), (0, 3));
        assert!(hfo.can_kick(0) && !hfo.can_kick(1));
        assert_eq!(hfo.state(1), [-1.0, 0.5, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(hfo.positions()[2], [30.0, 10.0]);
        let shoot = [Action::Shoot, Action::Move, Action::Move];
        assert_eq!(hfo.step(&shoot).unwrap(), Outcome::Goal);
        assert_eq!(hfo.frame(), 1);
    }

    #[test]
    fn what_goes_wrong_is_said() {
        let cases = [
            (backend("'not a frame'"), "not a frame"),
            (
                backend(r#"'{"error": "HFO did not ask for player 1"}'"#),
                "did not ask for player 1",
            ),
            (
                "import sys\nsys.exit(3)\n".to_owned(),
                "backend ended (exit status: 3)",
            ),
            (
                backend(&frame(0, "in-game", [false; 3]).replace("[[1,0,0,0,0,0],", "[")),
                "frame of 2 players, expected 3",
            ),
            (backend(&frame(0, "kicked-off", [false; 3])), "not a frame"),
        ];
        for (main, expected) in cases {
            let (_dir, hfo) = start(&main);
            let error = hfo.unwrap().reset().unwrap_err();
            assert!(error.contains(expected), "{error}");
        }
    }

    #[test]
    fn a_failed_backend_is_replaced_at_the_next_episode() {
        // Each launch notes its seed; the first one ends at its first step.
        let main = format!(
            "import os, sys\n\
             seeds = os.path.join(os.path.dirname(__file__), 'seeds')\n\
             first = not os.path.exists(seeds)\n\
             open(seeds, 'a').write(sys.argv[-1] + '\\n')\n\
             for line in sys.stdin:\n    c = line.strip()\n    \
             if c == 'Q' or (first and c.startswith('S')):\n        break\n    \
             print({}, flush=True)\n",
            frame(0, "in-game", [true, false, false])
        );
        let (dir, hfo) = start(&main);
        let mut hfo = hfo.unwrap();
        let shoot = [Action::Shoot, Action::Move, Action::Move];
        hfo.reset().unwrap();
        let error = hfo.step(&shoot).unwrap_err();
        assert!(error.contains("backend ended"), "{error}");
        hfo.reset().unwrap();
        assert_eq!(hfo.step(&shoot).unwrap(), Outcome::InGame);
        let seeds = std::fs::read_to_string(dir.path().join("hfo_oracle").join("seeds")).unwrap();
        assert_eq!(seeds, "--seed=7\n--seed=8\n");
    }

    #[test]
    fn a_missing_piece_is_named_before_anything_starts() {
        let dir = tempfile::tempdir().unwrap();
        let mut install = fake_install(dir.path(), "");
        std::fs::remove_file(dir.path().join("bin").join("HFO")).unwrap();
        let error = RealHfo::start(&install, &EnvConfig::default(), 1).unwrap_err();
        assert!(
            error.contains("bin/HFO is missing") && error.contains("build_hfo.sh"),
            "{error}"
        );
        std::fs::write(dir.path().join("bin").join("HFO"), "").unwrap();
        install.python = dir.path().join("no-python");
        let error = RealHfo::start(&install, &EnvConfig::default(), 1).unwrap_err();
        assert!(error.contains("no Python interpreter"), "{error}");
        let named = EnvConfig {
            pass_to_named_receiver: true,
            ..EnvConfig::default()
        };
        let error = RealHfo::start(&install, &named, 1).unwrap_err();
        assert!(error.contains("env.pass_to_named_receiver"), "{error}");
    }

    #[test]
    fn lines_are_bounded() {
        let long = vec![b'x'; MAX_LINE as usize + 10];
        let mut got = Vec::new();
        read_lines(&long[..], |line| {
            got.push(line);
            true
        });
        assert_eq!(got.len(), 1);
        assert!(got[0].as_ref().unwrap_err().contains("longer than"));
        let mut got = Vec::new();
        read_lines(&b"a\nb\n"[..], |line| {
            got.push(line.unwrap());
            true
        });
        assert_eq!(got, ["a\n", "b\n"]);
    }
}
