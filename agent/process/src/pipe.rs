//! A learner in a child process of its own (docs/learners.md): the agent
//! framework stays here, the learner answers over the child's standard
//! input and output, one JSON object per line.
//!
//! Queries (`start`, `values`, `choose`) wait for one answer line, within
//! the learner timeout; `learn`, `end_episode` and `replay` are sent
//! without an answer, and a learner that fails in them says so on its next
//! answer line. Any fault ends the process with one line naming the agent,
//! the learner and the cause; the child is killed with it.

use std::io::{BufRead, BufReader, BufWriter, Read, Write};
use std::path::PathBuf;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, sync_channel};
use std::time::Duration;

use agent::{ActionValues, AgentRng, Experience, Learner, Seen, Step};
use proto::Action;
use serde::Deserialize;
use serde_json::{Value, json};

/// The longest answer line accepted from a learner.
const MAX_LINE: u64 = 1 << 20;

/// How long a learner may take to start (imports, a model on a GPU) and
/// answer `start`, if longer than its timeout: within the coordinator's
/// 10 s for a reset, so that the agent names the cause.
const START_TIMEOUT: Duration = Duration::from_secs(8);

/// How to start an agent's learner process.
#[derive(Clone, Debug, PartialEq)]
pub struct LearnerCommand {
    /// Program and arguments.
    pub argv: Vec<String>,
    /// Its working directory (default: the agent's).
    pub dir: Option<PathBuf>,
    /// How long one answer may take.
    pub timeout: Duration,
}

/// The learner process of agent `agent` for one run.
#[derive(Debug)]
pub struct PipeLearner {
    agent: u8,
    command: LearnerCommand,
    child: Child,
    input: BufWriter<ChildStdin>,
    answers: Receiver<std::io::Result<String>>,
}

/// What `start` answers: who the learner is.
#[derive(Deserialize)]
struct Hello {
    name: String,
    #[serde(default)]
    version: String,
}

impl PipeLearner {
    /// Starts `command` for agent `agent` of `team_size` in run `run`, with
    /// `seed` for its own random choices, and waits for its `start` answer.
    pub fn start(
        command: &LearnerCommand,
        agent: u8,
        team_size: u8,
        run: u32,
        seed: u64,
    ) -> Result<Self, String> {
        let (program, args) = command
            .argv
            .split_first()
            .ok_or("the learner command is empty")?;
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
                "agent {agent}: cannot start its learner `{}`: {e}",
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
        let mut learner = Self {
            agent,
            command: command.clone(),
            child,
            input: BufWriter::new(input),
            answers,
        };
        let within = command.timeout.max(START_TIMEOUT);
        let hello: Hello = learner.query_within(
            within,
            "start",
            json!({
                "op": "start", "agent": agent, "team_size": team_size, "run": run,
                "seed": seed, "features": proto::STATE_FEATURES,
                "actions": Action::ALL.iter().map(|a| a.name()).collect::<Vec<_>>(),
            }),
        );
        tracing::info!(
            agent,
            name = hello.name,
            version = hello.version,
            "learner started"
        );
        Ok(learner)
    }

    /// Sends one request line.
    fn send(&mut self, what: &str, request: &Value) {
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

    /// The failure a learner reported before it went, if it did.
    fn reported_failure(&mut self) -> Option<String> {
        std::iter::from_fn(|| self.answers.recv_timeout(Duration::from_millis(100)).ok())
            .filter_map(|line| serde_json::from_str::<Failure>(&line.ok()?).ok())
            .map(|f| f.error)
            .next()
    }

    /// Sends a query and reads its answer within the learner timeout, or
    /// fails naming the cause.
    fn query<T: for<'de> Deserialize<'de>>(&mut self, what: &str, request: Value) -> T {
        self.query_within(self.command.timeout, what, request)
    }

    /// The same within `limit`.
    fn query_within<T: for<'de> Deserialize<'de>>(
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

    /// Ends the agent process: one line naming the agent, the learner and
    /// the cause; the child is killed first.
    fn fail(&mut self, cause: &str) -> ! {
        let _ = self.child.kill();
        let _ = self.child.wait();
        node::cli::exit_with_error(format_args!(
            "agent {}: its learner `{}` {cause}",
            self.agent,
            self.command.argv.join(" ")
        ))
    }

    /// A state as the learner reads it.
    fn state(at: Seen<'_>) -> Value {
        json!({ "state": at.state, "index": at.index })
    }
}

/// An answer saying the learner failed.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Failure {
    error: String,
}

/// The answer to `values`: Q(s, a) by action index, `null` where unlearned.
#[derive(Deserialize)]
struct Values {
    q: [Option<f64>; Action::ALL.len()],
}

/// The answer to `choose`.
#[derive(Deserialize)]
struct Choice {
    action: usize,
}

/// A transition as the learner reads it.
fn transition((from, reward, next): &Experience<'_>) -> Value {
    json!({
        "state": from.at.state, "action": from.action.index(), "reward": reward,
        "next_state": next.map(|n: Step<'_>| n.at.state),
        "next_action": next.map(|n| n.action.index()),
    })
}

impl Learner for PipeLearner {
    fn values(&mut self, at: Seen<'_>) -> ActionValues {
        let mut request = Self::state(at);
        request["op"] = "values".into();
        let Values { q } = self.query("values", request);
        let mut values = ActionValues::default();
        for (a, q) in Action::ALL.iter().zip(q) {
            let Some(q) = q else { continue };
            if !q.is_finite() {
                self.fail(&format!("valued {} at {q}, not a finite number", a.name()));
            }
            values.q[a.index()] = q;
            values.learned |= 1 << a.index();
        }
        values
    }

    fn choose(&mut self, at: Seen<'_>, _rng: &mut AgentRng) -> Action {
        let mut request = Self::state(at);
        request["op"] = "choose".into();
        let Choice { action } = self.query("choose", request);
        match Action::ALL.get(action) {
            Some(&a) if a != Action::Move => a,
            _ => self.fail(&format!(
                "chose action {action}; a kicker's actions are 1 to {} (SHOOT, DRIBBLE, PASS_NEAR, PASS_FAR)",
                Action::ALL.len() - 1
            )),
        }
    }

    fn learn(&mut self, step: Experience<'_>) {
        let mut request = transition(&step);
        request["op"] = "learn".into();
        self.send("learn", &request);
    }

    fn end_episode(&mut self) {
        self.send("end_episode", &json!({ "op": "end_episode" }));
    }

    fn replay(&mut self, episode: &[Experience<'_>]) {
        let episode: Vec<Value> = episode.iter().map(transition).collect();
        self.send("replay", &json!({ "op": "replay", "episode": episode }));
    }

    fn table(&self) -> Option<Vec<ActionValues>> {
        None
    }

    fn restore(&mut self, _: Vec<ActionValues>) -> Result<(), String> {
        Err(format!(
            "agent {}'s learner `{}` keeps its learned state itself: it cannot load a snapshot",
            self.agent,
            self.command.argv.join(" ")
        ))
    }
}

impl Drop for PipeLearner {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
