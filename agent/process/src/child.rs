//! A child process of the agent that answers over its standard input and
//! output, one JSON object per line: a learner (docs/learners.md) or a
//! strategy (docs/strategies.md).
//!
//! Queries wait for one answer line within the child's timeout; other
//! requests are sent without an answer, and a child that fails in them says
//! so on its next answer line. Any fault ends the agent process with one
//! line naming the agent, the child and the cause; the child is killed
//! with it.

use std::io::{BufRead, BufReader, BufWriter, Read, Write};
use std::path::PathBuf;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, sync_channel};
use std::time::Duration;

use proto::Action;
use serde::Deserialize;
use serde_json::{Value, json};

/// The longest answer line accepted from a child (a learner's saved state
/// travels in one).
const MAX_LINE: u64 = 1 << 26;

/// How long a child may take to start (imports, a model on a GPU) and
/// answer `start`, if longer than its timeout: within the coordinator's
/// 30 s for a reset, so that the agent names the cause. `import torch`
/// alone takes 4 to 8 s on a busy 2-core machine (docs/learners.md).
const START_TIMEOUT: Duration = Duration::from_secs(25);

/// How to start one of an agent's child processes.
#[derive(Clone, Debug, PartialEq)]
pub struct ChildCommand {
    /// Program and arguments.
    pub argv: Vec<String>,
    /// Its working directory (default: the agent's).
    pub dir: Option<PathBuf>,
    /// How long one answer may take.
    pub timeout: Duration,
}

/// The child processes an agent starts at each reset, each optional.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChildCommands {
    /// A learner in place of SARSA(lambda).
    pub learner: Option<ChildCommand>,
    /// A strategy: the advising decisions of algorithm `external`.
    pub strategy: Option<ChildCommand>,
}

/// A running child of agent `agent`, in the role `role` ("learner" or
/// "strategy").
#[derive(Debug)]
pub struct JsonChild {
    agent: u8,
    role: &'static str,
    command: ChildCommand,
    child: Child,
    input: BufWriter<ChildStdin>,
    answers: Receiver<std::io::Result<String>>,
}

/// An answer saying the child failed.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Failure {
    error: String,
}

impl JsonChild {
    /// Starts `command` as agent `agent`'s `role`.
    pub fn spawn(command: &ChildCommand, agent: u8, role: &'static str) -> Result<Self, String> {
        let (program, args) = command
            .argv
            .split_first()
            .ok_or_else(|| format!("the {role} command is empty"))?;
        let mut process = Command::new(program);
        process
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit());
        if let Some(dir) = &command.dir {
            process.current_dir(dir);
        }
        let mut child = process.spawn().map_err(|e| {
            format!(
                "agent {agent}: cannot start its {role} `{}`: {e}",
                command.argv.join(" ")
            )
        })?;
        let (Some(input), Some(output)) = (child.stdin.take(), child.stdout.take()) else {
            unreachable!("both pipes were requested")
        };
        let (send, answers) = sync_channel(64);
        std::thread::spawn(move || {
            let mut output = BufReader::new(output);
            loop {
                let mut line = String::new();
                let read = Read::take(&mut output, MAX_LINE).read_line(&mut line);
                let done = !matches!(read, Ok(n) if n > 0);
                if send.send(read.map(|_| line)).is_err() || done {
                    return;
                }
            }
        });
        Ok(Self {
            agent,
            role,
            command: command.clone(),
            child,
            input: BufWriter::new(input),
            answers,
        })
    }

    /// Starts `command` as agent `agent`'s `role` for run `run` of a team
    /// of `team_size`, sends it `start` (the run, `seed` for its own random
    /// choices, the action names, and `extra`'s fields) and waits for its
    /// answer, within the start time.
    pub fn start<T: for<'de> Deserialize<'de>>(
        command: &ChildCommand,
        role: &'static str,
        (agent, team_size, run, seed): (u8, u8, u32, u64),
        extra: Value,
    ) -> Result<(Self, T), String> {
        let mut child = Self::spawn(command, agent, role)?;
        let mut request = json!({
            "op": "start", "agent": agent, "team_size": team_size, "run": run, "seed": seed,
            "actions": Action::ALL.iter().map(|a| a.name()).collect::<Vec<_>>(),
        });
        if let (Some(request), Value::Object(extra)) = (request.as_object_mut(), extra) {
            request.extend(extra);
        }
        let hello = child.query_within(command.timeout.max(START_TIMEOUT), "start", request);
        Ok((child, hello))
    }

    /// Sends one request line.
    pub fn send(&mut self, what: &str, request: &Value) {
        let sent = serde_json::to_writer(&mut self.input, request)
            .map_err(std::io::Error::from)
            .and_then(|()| self.input.write_all(b"\n"))
            .and_then(|()| self.input.flush());
        if let Err(e) = sent {
            if let Some(error) = self.reported_failure() {
                self.fail(&format!("raised {error}"));
            }
            let cause = self.exit_cause().unwrap_or_else(|| e.to_string());
            self.fail(&format!("{cause} before taking `{what}`"));
        }
    }

    /// The failure a child reported before it went, if it did.
    fn reported_failure(&mut self) -> Option<String> {
        std::iter::from_fn(|| self.answers.recv_timeout(Duration::from_millis(100)).ok())
            .filter_map(|line| serde_json::from_str::<Failure>(&line.ok()?).ok())
            .map(|f| f.error)
            .next()
    }

    /// Sends a query and reads its answer within the child's timeout, or
    /// fails naming the cause.
    pub fn query<T: for<'de> Deserialize<'de>>(&mut self, what: &str, request: Value) -> T {
        self.query_within(self.command.timeout, what, request)
    }

    /// The same within `limit`.
    pub fn query_within<T: for<'de> Deserialize<'de>>(
        &mut self,
        limit: Duration,
        what: &str,
        request: Value,
    ) -> T {
        self.send(what, &request);
        let line = match self.answers.recv_timeout(limit) {
            Ok(Ok(line)) if !line.is_empty() => line,
            Ok(Ok(_)) | Err(RecvTimeoutError::Disconnected) => {
                let cause = self
                    .exit_cause()
                    .unwrap_or_else(|| "closed its output".into());
                self.fail(&format!("{cause} before answering `{what}`"))
            }
            Ok(Err(e)) => self.fail(&format!("answer to `{what}` is not readable: {e}")),
            Err(RecvTimeoutError::Timeout) => {
                self.fail(&format!("did not answer `{what}` within {limit:?}"))
            }
        };
        if let Ok(Failure { error }) = serde_json::from_str::<Failure>(&line) {
            self.fail(&format!("raised {error}"));
        }
        serde_json::from_str(&line).unwrap_or_else(|e| {
            let line = line.trim_end();
            let shown: String = line.chars().take(120).collect();
            self.fail(&format!("answered `{what}` with `{shown}`: {e}"))
        })
    }

    /// How the child ended, if it has.
    fn exit_cause(&mut self) -> Option<String> {
        // Give an exiting child a moment to be reaped.
        for _ in 0..50 {
            if let Ok(Some(status)) = self.child.try_wait() {
                return Some(format!("exited ({status})"));
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        None
    }

    /// Ends the agent process: one line naming the agent, the child and
    /// the cause; the child is killed first.
    pub fn fail(&mut self, cause: &str) -> ! {
        let _ = self.child.kill();
        let _ = self.child.wait();
        node::cli::exit_with_error(format_args!(
            "agent {}: its {} `{}` {cause}",
            self.agent,
            self.role,
            self.command.argv.join(" ")
        ))
    }

    /// The agent it serves.
    pub fn agent(&self) -> u8 {
        self.agent
    }

    /// The command, as one line (for messages).
    pub fn command_line(&self) -> String {
        self.command.argv.join(" ")
    }
}

impl Drop for JsonChild {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
