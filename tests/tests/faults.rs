//! Fault injection into a real experiment over loopback zenoh: env-server,
//! three agents and the coordinator as processes, and one fault per trial:
//! an agent or env-server killed, or stopped and resumed; the coordinator
//! killed, terminated or interrupted at a random moment from its start-up on;
//! or the zenoh router that every process of an attached experiment connects
//! to restarted mid-run; or, in an open team with `--restart-agents`,
//! newcomers joining at random episodes while a random agent is killed at a
//! random moment (or none is).
//!
//! Every trial must end within a bound (no hang), leave no process of its
//! experiment behind (no orphan), leave only result files that parse (no
//! corrupted file) and, unless the coordinator died of a signal it cannot
//! handle, nothing in its temporary directory; a run that fails says why on
//! its last line.
//!
//! CI plays one trial of each kind. The long mode plays N random trials:
//!
//! ```sh
//! ADV_FAULTS=100 cargo test --release -p integration-tests --test faults -- --nocapture
//! ```
//!
//! `ADV_FAULT_SEED` (default 1) picks the trials and their moments;
//! `ADV_FAULT_KIND` (a fault's name, e.g. `OpenTeam`) draws only that one.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use integration_tests::{bin, cmdline, processes_with};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// The stall limit of every trial: a kicker silent this long ends the run.
const STALL_LIMIT_MS: u64 = 3000;
/// How long a trial may take to end once its fault is in place.
const END_BOUND: Duration = Duration::from_secs(90);
/// How long the processes of an ended experiment may take to exit.
const ORPHAN_BOUND: Duration = Duration::from_secs(5);

/// What happens to the experiment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Fault {
    /// SIGKILL agent 1.
    KillAgent,
    /// SIGSTOP agent 1, then SIGCONT after the pause.
    StopAgent,
    /// SIGKILL env-server.
    KillServer,
    /// SIGSTOP env-server, then SIGCONT after the pause.
    StopServer,
    /// SIGKILL the coordinator.
    KillCoordinator,
    /// SIGTERM the coordinator.
    TermCoordinator,
    /// SIGINT the coordinator (Ctrl-C).
    InterruptCoordinator,
    /// Stop the router (SIGTERM) and start it again on its port after the
    /// pause; env-server and the agents were started by hand and the
    /// coordinator attached to them, all connecting only to the router.
    RestartRouter,
    /// An open team with `--restart-agents`: newcomers join at random
    /// episodes, and a random agent (or none) is killed at a random moment.
    OpenTeam,
}

const FAULTS: [Fault; 9] = [
    Fault::KillAgent,
    Fault::StopAgent,
    Fault::KillServer,
    Fault::StopServer,
    Fault::KillCoordinator,
    Fault::TermCoordinator,
    Fault::InterruptCoordinator,
    Fault::RestartRouter,
    Fault::OpenTeam,
];

/// One trial: a fault, when it strikes and how long a stop lasts.
#[derive(Clone, Debug)]
struct Trial {
    fault: Fault,
    /// After the coordinator starts (its faults) or after the target
    /// process appears (the others).
    delay: Duration,
    pause: Duration,
    /// An open team's joins: (training episode, slot, newcomer algorithm).
    joins: Vec<(u64, usize, &'static str)>,
    /// An open team's agent killed, if any.
    victim: Option<u8>,
}

impl Trial {
    fn random(fault: Fault, rng: &mut Xoshiro256PlusPlus) -> Self {
        let delay = match fault {
            // From the very start: before, during and after the spawns.
            Fault::KillCoordinator
            | Fault::TermCoordinator
            | Fault::InterruptCoordinator
            | Fault::RestartRouter => rng.random_range(0..3000),
            // Over the whole run: start-up, training, joins, evaluations.
            Fault::OpenTeam => rng.random_range(0..10_000),
            _ => rng.random_range(0..1500),
        };
        let (mut joins, mut victim) = (Vec::new(), None);
        if fault == Fault::OpenTeam {
            for _ in 0..rng.random_range(1..=3) {
                let newcomer = ["adhoc-td", "peer-learning"][rng.random_range(0..2)];
                joins.push((
                    rng.random_range(1..EPISODES),
                    rng.random_range(0..3),
                    newcomer,
                ));
            }
            joins.sort_unstable();
            joins.dedup_by_key(|(episode, slot, _)| (*episode, *slot));
            victim = rng.random_bool(0.75).then(|| rng.random_range(0..3));
        }
        Self {
            fault,
            delay: Duration::from_millis(delay),
            // Within and beyond the stall limit.
            pause: Duration::from_millis(rng.random_range(200..2 * STALL_LIMIT_MS)),
            joins,
            victim,
        }
    }

    /// The team file of an open team's trial.
    fn team_file(&self) -> String {
        let mut text = "[[agent]]\nalgorithm = \"adhoc-td\"\n".repeat(3);
        for (episode, slot, algorithm) in &self.joins {
            text.push_str(&format!(
                "[[event]]\nepisode = {episode}\nslot = {slot}\nnewcomer = {{ algorithm = \"{algorithm}\" }}\n"
            ));
        }
        text
    }
}

/// Training episodes of a trial's run.
const EPISODES: u64 = 200;

/// What a trial ended in; anything but `Ok` fails the suite.
#[derive(Debug, PartialEq, Eq)]
enum Verdict {
    Ok(String),
    Hang,
    Orphans(Vec<String>),
    Corrupted(String),
    Leftovers(Vec<String>),
    Unclear(String),
}

fn signal(pid: u32, name: &str) {
    // The process may already be gone: that is not the suite's concern.
    let _ = Command::new("kill")
        .args([&format!("-{name}"), &pid.to_string()])
        .stderr(Stdio::null())
        .status();
}

/// The pid of the experiment's process whose command line holds `part`.
fn find(experiment: &str, part: &str, deadline: Instant) -> Option<u32> {
    while Instant::now() < deadline {
        if let Some(pid) = processes_with(experiment)
            .into_iter()
            .find(|&pid| cmdline(pid).contains(part))
        {
            return Some(pid);
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    None
}

/// Starts the coordinator of `experiment` with `extra` arguments (an
/// attached experiment's, or an open team's) or else `--algorithm adhoc-td`.
fn start(experiment: &str, out: &Path, tmp: &Path, stderr: File, extra: &[String]) -> Child {
    let team = if extra.is_empty() {
        ["--algorithm", "adhoc-td"].map(String::from).to_vec()
    } else {
        extra.to_vec()
    };
    Command::new(bin("coordinator"))
        .env("TMPDIR", tmp)
        .args(["run", "--runs", "1"])
        .args(team)
        .args([
            "--episodes",
            &EPISODES.to_string(),
            "--eval-every",
            "100",
            "--eval-episodes",
            "10",
        ])
        .args(["--transport", "zenoh", "--experiment", experiment])
        .args(["--stall-limit-ms", &STALL_LIMIT_MS.to_string(), "--quiet"])
        .arg("--out")
        .arg(out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(stderr)
        .spawn()
        .expect("start the coordinator")
}

fn wait(child: &mut Child, bound: Duration) -> Option<ExitStatus> {
    let deadline = Instant::now() + bound;
    while Instant::now() < deadline {
        if let Some(status) = child.try_wait().expect("wait for the coordinator") {
            return Some(status);
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    None
}

/// A router on a loopback port, and env-server and three agents started by
/// hand that connect only to it, all with the experiment's secret: what a
/// coordinator started with [`Attached::coordinator_args`] attaches to.
struct Attached {
    router: Child,
    processes: Vec<Child>,
    port: u16,
    secret: PathBuf,
    dir: PathBuf,
}

impl Attached {
    fn start(experiment: &str, dir: &Path) -> Self {
        let secret = dir.join("secret");
        let made = Command::new(bin("coordinator"))
            .arg("secret")
            .arg(&secret)
            .status()
            .expect("run coordinator secret");
        assert!(made.success(), "coordinator secret: {made}");
        let port = node::net::free_port().expect("a free loopback port");
        let mut attached = Attached {
            router: Self::router(port, &secret, dir),
            processes: Vec::new(),
            port,
            secret,
            dir: dir.to_path_buf(),
        };
        let server = ["serve", "--experiment", experiment].map(String::from);
        attached.spawn("env-server", &server, "env-server");
        for id in 0..3 {
            let id = id.to_string();
            let agent = ["--experiment", experiment, "--id", &id, "--team-size", "3"];
            attached.spawn("agent", &agent.map(String::from), &format!("agent-{id}"));
        }
        attached
    }

    fn router(port: u16, secret: &Path, dir: &Path) -> Child {
        let router = Command::new(bin("coordinator"))
            .args(["router", "--listen", &format!("tcp/127.0.0.1:{port}")])
            .arg("--secret-file")
            .arg(secret)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(File::create(dir.join("router.log")).expect("router log"))
            .spawn()
            .expect("start the router");
        let deadline = Instant::now() + Duration::from_secs(30);
        while std::net::TcpStream::connect(("127.0.0.1", port)).is_err() {
            assert!(
                Instant::now() < deadline,
                "the router does not listen on port {port}"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        router
    }

    /// The endpoints and secret every process of the experiment gets.
    fn common_args(&self) -> Vec<String> {
        vec![
            "--listen".into(),
            "tcp/127.0.0.1:0".into(),
            "--connect".into(),
            format!("tcp/127.0.0.1:{}", self.port),
            "--secret-file".into(),
            self.secret.display().to_string(),
        ]
    }

    fn spawn(&mut self, program: &str, args: &[String], log: &str) {
        let child = Command::new(bin(program))
            .args(args)
            .args(self.common_args())
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(File::create(self.dir.join(format!("{log}.log"))).expect("log file"))
            .spawn()
            .unwrap_or_else(|e| panic!("start {program}: {e}"));
        self.processes.push(child);
    }

    fn coordinator_args(&self) -> Vec<String> {
        let algorithm = ["--algorithm", "adhoc-td", "--attach"].map(String::from);
        [algorithm.to_vec(), self.common_args()].concat()
    }

    /// SIGTERM to the router, then a new one on its port after `pause`.
    fn restart_router(&mut self, pause: Duration) {
        signal(self.router.id(), "TERM");
        let _ = self.router.wait();
        std::thread::sleep(pause);
        self.router = Self::router(self.port, &self.secret, &self.dir);
    }
}

impl Drop for Attached {
    /// Attached processes outlive their coordinator by design: the trial
    /// stops them itself.
    fn drop(&mut self) {
        for child in self.processes.iter_mut().chain([&mut self.router]) {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Plays `trial` as experiment `name` in `dir`: starts the coordinator,
/// injects the fault at its moment, waits for the end within the bound,
/// then collects what the checks need. One sequence, read top to bottom.
fn play(trial: &Trial, name: &str, dir: &Path) -> Verdict {
    let out = dir.join("out");
    let stderr_path = dir.join("stderr");
    let mut attached = (trial.fault == Fault::RestartRouter).then(|| Attached::start(name, dir));
    let mut attach = attached
        .as_ref()
        .map(Attached::coordinator_args)
        .unwrap_or_default();
    if trial.fault == Fault::OpenTeam {
        let team = dir.join("team.toml");
        std::fs::write(&team, trial.team_file()).expect("team file");
        attach = [
            "--team".into(),
            team.display().to_string(),
            "--restart-agents".into(),
        ]
        .into_iter()
        .chain(["--snapshot-every", "20"].map(String::from))
        .collect();
    }
    let stderr = File::create(&stderr_path).expect("stderr file");
    let tmp = dir.join("tmp");
    std::fs::create_dir_all(&tmp).expect("temporary directory");
    let mut coordinator = start(name, &out, &tmp, stderr, &attach);
    let started = Instant::now();
    let victim = trial.victim.map(|id| format!("--id\u{0}{id}\u{0}"));
    let target = match trial.fault {
        Fault::KillAgent | Fault::StopAgent => Some("--id\u{0}1\u{0}"),
        Fault::KillServer | Fault::StopServer => Some("serve\u{0}"),
        Fault::OpenTeam => victim.as_deref(),
        _ => None,
    };
    match target {
        None if trial.fault == Fault::OpenTeam => {}
        None if trial.fault == Fault::RestartRouter => {
            std::thread::sleep(trial.delay);
            if let Some(attached) = attached.as_mut() {
                attached.restart_router(trial.pause);
            }
        }
        None => {
            std::thread::sleep(trial.delay);
            let name = match trial.fault {
                Fault::KillCoordinator => "KILL",
                Fault::TermCoordinator => "TERM",
                _ => "INT",
            };
            signal(coordinator.id(), name);
        }
        Some(part) => {
            if let Some(pid) = find(name, part, started + Duration::from_secs(30)) {
                std::thread::sleep(trial.delay);
                if matches!(
                    trial.fault,
                    Fault::KillAgent | Fault::KillServer | Fault::OpenTeam
                ) {
                    signal(pid, "KILL");
                } else {
                    signal(pid, "STOP");
                    std::thread::sleep(trial.pause);
                    signal(pid, "CONT");
                }
            }
        }
    }
    let Some(status) = wait(&mut coordinator, END_BOUND) else {
        let _ = coordinator.kill();
        let _ = coordinator.wait();
        kill_all(name);
        return Verdict::Hang;
    };
    drop(attached);
    let deadline = Instant::now() + ORPHAN_BOUND;
    while !processes_with(name).is_empty() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(50));
    }
    let left = processes_with(name);
    if !left.is_empty() {
        let names = left
            .iter()
            .map(|&p| cmdline(p).replace('\0', " "))
            .collect();
        kill_all(name);
        return Verdict::Orphans(names);
    }
    if let Err(e) = check_files(&out) {
        return Verdict::Corrupted(e);
    }
    // An exit code means the coordinator ended by itself or by its signal
    // handler: either way its generated secret's directory must be gone.
    let leftovers: Vec<String> = std::fs::read_dir(&tmp)
        .expect("temporary directory")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    if status.code().is_some() && !leftovers.is_empty() {
        return Verdict::Leftovers(leftovers);
    }
    let stderr = std::fs::read_to_string(&stderr_path).unwrap_or_default();
    let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
    match (status.code(), last) {
        (Some(0), _) => Verdict::Ok(format!("finished{}", restarts(&out))),
        // A signal before the handlers are installed, i.e. before any spawn.
        (None, _)
            if target.is_none()
                && !matches!(trial.fault, Fault::RestartRouter | Fault::OpenTeam) =>
        {
            Verdict::Ok(format!("{status}"))
        }
        (Some(code), Some(line)) if line.starts_with("error:") || line.contains("stopping") => {
            Verdict::Ok(format!("exit {code}: {line}"))
        }
        _ => Verdict::Unclear(format!("{status}, stderr: {stderr}")),
    }
}

/// The causes of the agent restarts the run in `out` recorded, as
/// `; restarted: <cause> | ...`, or nothing.
fn restarts(out: &Path) -> String {
    let run = std::fs::read_to_string(out.join("run-0.json")).unwrap_or_default();
    let run: serde_json::Value = serde_json::from_str(&run).unwrap_or_default();
    let causes: Vec<&str> = (run["restarts"].as_array().into_iter().flatten())
        .filter_map(|r| r["cause"].as_str())
        .collect();
    if causes.is_empty() {
        String::new()
    } else {
        format!("; restarted: {}", causes.join(" | "))
    }
}

fn kill_all(experiment: &str) {
    for pid in processes_with(experiment) {
        signal(pid, "KILL");
    }
}

/// Every result file parses: JSON files as JSON, CSV files with one field
/// count. Leftover temporary files are allowed (they never block a rerun).
fn check_files(dir: &Path) -> Result<(), String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries {
        let path = entry.map_err(|e| e.to_string())?.path();
        let name = path.file_name().unwrap_or_default().to_string_lossy();
        if name.starts_with(node::files::TEMP_PREFIX) {
            continue;
        }
        if path.is_dir() {
            check_files(&path)?;
            continue;
        }
        let text = std::fs::read_to_string(&path).map_err(|e| format!("{name}: {e}"))?;
        let fail = |why: String| format!("{}: {why}", path.display());
        match path.extension().and_then(|e| e.to_str()) {
            Some("json") => {
                serde_json::from_str::<serde_json::Value>(&text)
                    .map_err(|e| fail(e.to_string()))?;
            }
            Some("csv") => {
                let fields = |line: &str| line.split(',').count();
                let mut lines = text.lines();
                let header = lines.next().map(fields).unwrap_or(0);
                if !text.ends_with('\n') || lines.any(|l| fields(l) != header) {
                    return Err(fail("a partial or ragged row".into()));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

#[test]
fn every_fault_ends_bounded_without_orphans_or_corrupted_files() {
    let count: usize = std::env::var("ADV_FAULTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(FAULTS.len());
    let seed: u64 = std::env::var("ADV_FAULT_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let tmp = tempfile::tempdir().unwrap();
    let mut failures = Vec::new();
    let kinds: Vec<Fault> = match std::env::var("ADV_FAULT_KIND") {
        Ok(kind) => FAULTS
            .into_iter()
            .filter(|f| format!("{f:?}") == kind)
            .collect(),
        Err(_) => FAULTS.to_vec(),
    };
    assert!(!kinds.is_empty(), "ADV_FAULT_KIND names none of {FAULTS:?}");
    // The short mode plays each fault once, the long mode draws them.
    let faults: Vec<Fault> = if count == FAULTS.len() {
        FAULTS.to_vec()
    } else {
        (0..count)
            .map(|_| kinds[rng.random_range(0..kinds.len())])
            .collect()
    };
    for (i, &fault) in faults.iter().enumerate() {
        let trial = Trial::random(fault, &mut rng);
        let dir = tmp.path().join(format!("trial-{i}"));
        std::fs::create_dir_all(&dir).unwrap();
        let name = format!("fault-{}-{i}", std::process::id());
        let began = Instant::now();
        let verdict = play(&trial, &name, &dir);
        eprintln!(
            "trial {i}: {:?} after {:?} (pause {:?}, joins {:?}, killed {:?}): {verdict:?} in {:.1} s",
            trial.fault,
            trial.delay,
            trial.pause,
            trial.joins,
            trial.victim,
            began.elapsed().as_secs_f64()
        );
        if !matches!(verdict, Verdict::Ok(_)) {
            failures.push((i, trial, verdict));
        }
    }
    let count_of = |f: &dyn Fn(&Verdict) -> bool| failures.iter().filter(|(_, _, v)| f(v)).count();
    eprintln!(
        "{count} faults (seed {seed}): {} hangs, {} orphans, {} corrupted, {} leftovers, {} unclear",
        count_of(&|v| *v == Verdict::Hang),
        count_of(&|v| matches!(v, Verdict::Orphans(_))),
        count_of(&|v| matches!(v, Verdict::Corrupted(_))),
        count_of(&|v| matches!(v, Verdict::Leftovers(_))),
        count_of(&|v| matches!(v, Verdict::Unclear(_))),
    );
    assert!(failures.is_empty(), "{failures:#?}");
}
