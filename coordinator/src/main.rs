//! `coordinator`: run advising experiments from the command line.

use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use agent::{Algorithm, Latency, Profile};
use analysis::published::published_gains;
use analysis::report::gains_table;
use analysis::stats::aggregates::score_aggregates;
use anyhow::Result;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand};
use coordinator::request::{Agents, RunRequest};
use coordinator::study::{PRESETS, StudyConfig, StudyOptions};
use coordinator::transport::{Auth, TRANSPORT_NAMES};
use coordinator::{
    Endpoints, Estimate, Experiment, ExperimentDir, RunOptions, Transport, ZenohSettings,
    load_team_file, run_experiment,
};
use env_server::EvaluationMemory;
use proto::Simulator;

#[derive(Parser)]
#[command(
    version,
    about = "Ad hoc advising experiments: training, frozen evaluations, many runs, statistics"
)]
struct CoordinatorCli {
    #[command(subcommand)]
    command: CoordinatorCommand,
}

#[derive(Subcommand)]
enum CoordinatorCommand {
    /// Run one configuration: R runs of N training episodes, an evaluation of
    /// M episodes before training and every K episodes.
    Run(RunArgs),
    /// Run a study: every algorithm of a preset or study file, statistics,
    /// figures and REPORT.md; resumes in the same directory.
    Study(StudyArgs),
    /// Play one evaluation episode of a team (its agents from their
    /// snapshots, greedy, learning nothing) and write it: an animation (.svg,
    /// or .html) or an rcssserver game log for rcssmonitor or soccerwindow2
    /// (.rcg).
    Replay(ReplayArgs),
    /// Write a new random experiment secret to FILE (mode 600), for
    /// processes started by hand: give every one `--secret-file FILE`.
    Secret {
        /// Where to write it; must not exist.
        file: PathBuf,
    },
    /// Run a zenoh router, the rendezvous of processes on many hosts
    /// (deploy/README.md), until Ctrl-C or SIGTERM.
    Router(RouterArgs),
    /// Gains over a baseline in the authors' published results
    /// (f-leno/AdHoc_AAMAS-17's ProcessedFiles/), computed as a study's
    /// report computes them, with Welch's intervals (the runs are unpaired);
    /// prints a Markdown table.
    PublishedGains {
        /// The directory holding one directory per algorithm.
        #[arg(long, value_name = "DIR")]
        results: PathBuf,
        /// The baseline's directory name, e.g. SARSATile.
        #[arg(long)]
        baseline: String,
        /// Confidence level of the intervals (the authors': 0.90).
        #[arg(long, value_name = "LEVEL", default_value_t = 0.9)]
        level: f64,
        /// The algorithms' directory names, e.g. AdHocTD AdHocVisit.
        #[arg(required = true)]
        algorithms: Vec<String>,
    },
    /// Mean, IQM and probability of improvement over a baseline of per-run
    /// scores, with the stratified bootstrap intervals a study's report
    /// gives them (Agarwal et al. 2021); prints JSON. The scores: a JSON
    /// object mapping each algorithm to its runs' scores, e.g.
    /// {"no-advice": [20.5, 31.0], "AdHocTD": [25.0, 40.5]}.
    Aggregate {
        /// The scores' file.
        #[arg(long, value_name = "FILE")]
        scores: PathBuf,
        /// The algorithm the others are compared with.
        #[arg(long)]
        baseline: String,
        /// Confidence level of the intervals.
        #[arg(long, value_name = "LEVEL", default_value_t = 0.95)]
        level: f64,
    },
}

#[derive(Args)]
#[command(group = clap::ArgGroup::new("agents").required(true).args(["algorithm", "team"]))]
struct ReplayArgs {
    /// Algorithm of every agent, from scratch.
    #[arg(long, value_name = "NAME", value_parser = algorithm_names())]
    algorithm: Option<Algorithm>,
    /// Team file whose agents `load` their snapshots (e.g. --save-agents').
    #[arg(long, value_name = "FILE")]
    team: Option<PathBuf>,
    /// Fidelity profile of the agents with --algorithm.
    #[arg(
        long,
        value_name = "PROFILE",
        default_value = "paper",
        conflicts_with = "team"
    )]
    profile: Profile,
    /// Seed of the simulator.
    #[arg(long, value_name = "S", default_value_t = 1)]
    seed: u64,
    /// Which evaluation episode on that simulator (1 is the first).
    #[arg(long, value_name = "K", default_value_t = 1,
          value_parser = clap::value_parser!(u64).range(1..))]
    episode: u64,
    /// Output file, ending in .svg, .html or .rcg.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

#[derive(Args)]
struct RouterArgs {
    /// zenoh endpoint to listen on (repeatable), e.g. tcp/0.0.0.0:7447.
    #[arg(long, value_name = "ENDPOINT", required = true)]
    listen: Vec<String>,
    /// The experiment's secret file; peers without it are refused.
    #[arg(long, value_name = "FILE", required_unless_present = "no_auth")]
    secret_file: Option<PathBuf>,
    /// Accept every peer that reaches the endpoints.
    #[arg(long, conflicts_with = "secret_file")]
    no_auth: bool,
    /// A zenoh configuration file (JSON5) to start from, e.g. TLS
    /// certificates and access control (deploy/tls/).
    #[arg(long, value_name = "FILE")]
    zenoh_config: Option<PathBuf>,
}

#[derive(Args)]
#[command(group = clap::ArgGroup::new("which").required(true).args(["preset", "config"]))]
struct StudyArgs {
    /// A preset: a study file of coordinator/presets/, by name.
    #[arg(long, value_name = "NAME", value_parser = preset_names())]
    preset: Option<String>,
    /// A study file (TOML, the format of coordinator/presets/*.toml).
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Override the runs of every experiment.
    #[arg(long, value_name = "R")]
    runs: Option<u64>,
    /// Override the training episodes of every experiment.
    #[arg(long, value_name = "N")]
    episodes: Option<u64>,
    /// Override where agents and simulator live: in-process or zenoh.
    #[arg(long, value_parser = TRANSPORT_NAMES)]
    transport: Option<String>,
    /// Worker threads for in-process runs, 1 to 1024 (default: one per core).
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u64).range(1..=1024))]
    threads: Option<u64>,
    /// Output directory: one directory per experiment, figures, REPORT.md.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Play only share K of N of the runs into --out, and no statistics
    /// (K from 1 to N; shards may run at the same time, on one host or many
    /// sharing the directory; the first also pretrains). Then the same
    /// command without --shard plays what is missing and writes REPORT.md.
    #[arg(long, value_name = "K/N")]
    shard: Option<coordinator::study::Shard>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    #[command(flatten)]
    network: NetworkArgs,
}

#[derive(Args)]
#[command(group = clap::ArgGroup::new("agents").required(true).args(["algorithm", "team"]))]
#[command(args_override_self = true)]
struct RunArgs {
    /// Algorithm of every agent (a homogeneous team).
    #[arg(long, value_name = "NAME", value_parser = algorithm_names())]
    algorithm: Option<Algorithm>,
    /// Team file (TOML, or JSON by extension): one `[[agent]]` table per agent
    /// with its algorithm, constants and an optional `load` snapshot path.
    #[arg(long, value_name = "FILE")]
    team: Option<PathBuf>,
    /// Mistake Correcting: advisees send their intended action along
    /// (adhoc-visit, adhoc-td and torrey only).
    #[arg(long, conflicts_with = "team")]
    mistake_correcting: bool,
    /// The learner of every agent with --algorithm, with its defaults
    /// (docs/learners.md); default: the one the algorithm needs (sarsa, or
    /// dqn with 5 heads for rcmp). A team file names each agent's.
    #[arg(long, value_name = "NAME", value_parser = agent::LearnerSettings::NAMES,
          conflicts_with = "team")]
    learner: Option<String>,
    /// Independent runs R.
    #[arg(long, value_name = "R", default_value_t = 50)]
    runs: u64,
    /// Training episodes N per run.
    #[arg(long, value_name = "N", default_value_t = 5000)]
    episodes: u64,
    /// Evaluate every K training episodes (and before the first).
    #[arg(long, value_name = "K", default_value_t = 20)]
    eval_every: u64,
    /// Episodes M of one evaluation.
    #[arg(long, value_name = "M", default_value_t = 100)]
    eval_episodes: u64,
    /// Experiment seed; every run's seeds derive from it.
    #[arg(long, value_name = "S", default_value_t = 1)]
    seed: u64,
    /// Fidelity profile of the agents with --algorithm: the paper's text
    /// (paper) or the authors' published code (authors); docs/fidelity.md.
    #[arg(
        long,
        value_name = "PROFILE",
        default_value = "paper",
        conflicts_with = "team"
    )]
    profile: Profile,
    /// Confidence level of the summary's intervals (default: the profile's,
    /// 0.95 for paper, 0.90 for authors).
    #[arg(long, value_name = "LEVEL")]
    ci_level: Option<f64>,
    /// Offense agents (the paper: 3); with --team, the team's size.
    #[arg(long)]
    offense: Option<usize>,
    /// What the agents of each evaluation block's simulator remember at its
    /// start: the training simulator's memories, as HFO (carried), or
    /// nothing (fresh); docs/fidelity.md, item 9.
    #[arg(long, value_name = "MEMORY", default_value = "carried")]
    evaluation_memory: EvaluationMemory,
    /// Worker threads, one run each at a time, 1 to 1024 (default: one per core).
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u64).range(1..=1024))]
    threads: Option<u64>,
    /// Where agents and simulator live: separate processes over zenoh, or
    /// library calls in this process (in-process: fast, bit-for-bit deterministic).
    #[arg(long, value_parser = TRANSPORT_NAMES, default_value = "zenoh")]
    transport: String,
    /// Network conditions of every agent's advice messages: the latency of
    /// each, fixed:MS, uniform:MIN,MAX or lognormal:MEDIAN,SIGMA (ms), in
    /// both transports (docs/algorithms.md section 6).
    #[arg(long, value_name = "DIST")]
    advice_latency: Option<Latency>,
    /// With network conditions: the probability that an advice message is
    /// lost (0 to 1). Either option sets the conditions, whose advice
    /// timeout is --advice-timeout-ms in both transports.
    #[arg(long, value_name = "P")]
    advice_loss: Option<f64>,
    #[command(flatten)]
    network: NetworkArgs,
    /// Output directory: config.json, run-<k>.csv, summary.json.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Also save every agent at the end of each run, as run-<k>-agent-<i>.snapshot.
    #[arg(long, value_name = "DIR")]
    save_agents: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// Settings of the zenoh transport.
#[derive(Args)]
struct NetworkArgs {
    /// Experiment name, the key prefix adv/<NAME> of every message
    /// (default: one unique to this invocation).
    #[arg(long, value_name = "NAME")]
    experiment: Option<String>,
    /// Loopback port this coordinator listens on for its processes (0: any free port).
    #[arg(long, default_value_t = 0)]
    port: u16,
    /// With --attach: the endpoint this coordinator listens on, reachable
    /// from every process's host (default: a free loopback port).
    #[arg(
        long,
        value_name = "ENDPOINT",
        requires = "attach",
        conflicts_with = "port"
    )]
    listen: Option<String>,
    /// zenoh endpoint to connect to, e.g. a router (repeatable).
    #[arg(long, value_name = "ENDPOINT")]
    connect: Vec<String>,
    /// Drive env-server and agents already running (e.g. on other hosts)
    /// instead of starting them here.
    #[arg(long)]
    attach: bool,
    /// Directory of the env-server and agent executables (default: next to this one).
    #[arg(long, value_name = "DIR")]
    bin_dir: Option<PathBuf>,
    /// The experiment's secret file (one `user:password` line, mode 600);
    /// needed with --attach. Default: a new secret in a private temporary
    /// file, handed to the processes this coordinator starts.
    #[arg(long, value_name = "FILE")]
    secret_file: Option<PathBuf>,
    /// Join and start processes without authentication: anyone who can
    /// reach the endpoints can then read and send every message.
    #[arg(long, conflicts_with = "secret_file")]
    no_auth: bool,
    /// With --attach: a zenoh configuration file (JSON5) to start from, e.g.
    /// TLS certificates and access control (deploy/tls/).
    #[arg(long, value_name = "FILE", requires = "attach")]
    zenoh_config: Option<PathBuf>,
    /// How long an agent waits for advice (ms; default 5).
    #[arg(long, value_name = "MS")]
    advice_timeout_ms: Option<u64>,
    /// How long env-server waits for a kicker's action before Move (ms; default 1000).
    #[arg(long, value_name = "MS")]
    step_timeout_ms: Option<u64>,
    /// How long a kicker may send no action, frame after frame, before the
    /// run ends with an error (ms; default 10000).
    #[arg(long, value_name = "MS")]
    stall_limit_ms: Option<u64>,
    /// Restart an agent process that dies from its latest snapshot and go
    /// on, recording the gap; one that dies before joining, at start-up too,
    /// is started again, 3 times per slot at most (default: a lost agent
    /// ends the run).
    #[arg(long)]
    restart_agents: bool,
    /// With --restart-agents: snapshot every agent every this many
    /// training episodes (default 100; `--checkpoint-every` before 0.3).
    #[arg(long, value_name = "N", requires = "restart_agents", alias = "checkpoint-every",
          value_parser = clap::value_parser!(u64).range(1..))]
    snapshot_every: Option<u64>,
    /// How long to wait for every process to join (s, 1 to 3600).
    #[arg(long, value_name = "S", default_value_t = 30,
          value_parser = clap::value_parser!(u64).range(1..=3600))]
    startup_timeout: u64,
    /// What env-server plays: our simulator (ours), or the real HFO
    /// (real-hfo: over zenoh, not deterministic; docs/calibration.md).
    #[arg(long, value_name = "SIMULATOR", value_parser = ["ours", "real-hfo"])]
    simulator: Option<String>,
    /// With --simulator real-hfo: the real HFO's directory, built by
    /// env-server/oracle/build_hfo.sh DIR.
    #[arg(long, value_name = "DIR", env = "HFO_DIR")]
    hfo_dir: Option<PathBuf>,
    /// With --simulator real-hfo: its Python interpreter (default: DIR/venv/bin/python).
    #[arg(long, value_name = "FILE")]
    hfo_python: Option<PathBuf>,
}

impl NetworkArgs {
    /// The zenoh settings: `base`'s timeouts unless overridden, and the
    /// endpoints of this invocation.
    fn zenoh(&self, base: Option<&ZenohSettings>) -> ZenohSettings {
        let unique = || {
            let nanos = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.subsec_nanos());
            format!("exp-{}-{nanos}", std::process::id())
        };
        let base = base.cloned().unwrap_or_default();
        ZenohSettings {
            advice_timeout_ms: self.advice_timeout_ms.unwrap_or(base.advice_timeout_ms),
            step_timeout_ms: self.step_timeout_ms.unwrap_or(base.step_timeout_ms),
            stall_limit_ms: self.stall_limit_ms.unwrap_or(base.stall_limit_ms),
            restart_agents: self.restart_agents || base.restart_agents,
            snapshot_every: self.snapshot_every.unwrap_or(base.snapshot_every),
            simulator: self.simulator().unwrap_or(base.simulator),
            endpoints: Endpoints {
                experiment: self.experiment.clone().unwrap_or_else(unique),
                port: self.port,
                listen: self.listen.clone(),
                connect: self.connect.clone(),
                attach: self.attach,
                bin_dir: self.bin_dir.clone(),
                auth: match (&self.secret_file, self.no_auth) {
                    (Some(file), _) => Auth::File(file.clone()),
                    (None, true) => Auth::Off,
                    (None, false) => Auth::Generated,
                },
                zenoh_config: self.zenoh_config.clone(),
                startup_timeout: std::time::Duration::from_secs(self.startup_timeout),
                hfo_dir: self.hfo_dir.clone(),
                hfo_python: self.hfo_python.clone(),
            },
        }
    }

    /// The simulator `--simulator` names, if it does.
    fn simulator(&self) -> Option<Simulator> {
        self.simulator.as_deref().map(|name| match name {
            "real-hfo" => Simulator::RealHfo,
            _ => Simulator::Ours,
        })
    }

    /// The transport named `name` (or `current`'s kind; zenoh for the real
    /// HFO), with these settings.
    fn transport(&self, name: Option<&str>, current: &Transport) -> Result<Transport> {
        let real_hfo = self.simulator() == Some(Simulator::RealHfo);
        let name = match name {
            Some("in-process") if real_hfo => anyhow::bail!(
                "--simulator real-hfo: env-server plays the real HFO over zenoh, \
                 not in process; use --transport zenoh"
            ),
            Some(name) => name,
            None if real_hfo => "zenoh",
            None => current.name(),
        };
        Ok(Transport::named(name, self.zenoh(current.zenoh()))?)
    }
}

fn main() -> ExitCode {
    node::cli::init_tracing("error");
    let cli: CoordinatorCli = node::cli::parse_or_exit();
    // A router forwards for many peers: it keeps zenoh's usual runtimes.
    if !matches!(cli.command, CoordinatorCommand::Router(_)) {
        node::net::use_one_runtime();
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => node::cli::exit_with_error(e),
    }
}

fn run(cli: CoordinatorCli) -> Result<()> {
    match cli.command {
        CoordinatorCommand::Run(args) => run_one(args),
        CoordinatorCommand::Study(args) => run_study(args),
        CoordinatorCommand::Replay(args) => replay(args),
        CoordinatorCommand::Secret { file } => {
            node::secret::Secret::create(&file)?;
            Ok(())
        }
        CoordinatorCommand::Router(args) => run_router(args),
        CoordinatorCommand::PublishedGains {
            results,
            baseline,
            level,
            algorithms,
        } => {
            if !(level > 0.0 && level < 1.0) {
                anyhow::bail!("--level must be in (0, 1), got {level}");
            }
            let gains = published_gains(&results, &baseline, &algorithms, level)?;
            print!("{}", gains_table(&gains));
            Ok(())
        }
        CoordinatorCommand::Aggregate {
            scores,
            baseline,
            level,
        } => aggregate(&scores, &baseline, level),
    }
}

/// Prints the aggregate statistics of the scores in `path` as JSON.
fn aggregate(path: &std::path::Path, baseline: &str, level: f64) -> Result<()> {
    if !(level > 0.0 && level < 1.0) {
        anyhow::bail!("--level must be in (0, 1), got {level}");
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow::anyhow!("cannot read {}: {e}", path.display()))?;
    let scores: BTreeMap<String, Vec<f64>> = serde_json::from_str(&text).map_err(|e| {
        anyhow::anyhow!(
            "{}: expected an object of arrays of scores: {e}",
            path.display()
        )
    })?;
    let report = score_aggregates(&scores, baseline, level)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    println!("{}", serde_json::to_string_pretty(&report)?);
    Ok(())
}

fn replay(args: ReplayArgs) -> Result<()> {
    let format = coordinator::replay::TraceFile::of(&args.out)?;
    let agents = match (&args.team, args.algorithm) {
        (Some(path), _) => Agents::Team(load_team_file(path)?),
        (None, Some(algorithm)) => Agents::Algorithm {
            algorithm,
            mistake_correcting: false,
        },
        (None, None) => unreachable!("clap requires --algorithm or --team"),
    };
    let request = RunRequest {
        runs: 1,
        episodes: 0,
        profile: args.profile,
        ..RunRequest::new(agents)
    };
    let label = match &args.team {
        Some(path) => format!("team {}", path.display()),
        None => request.label(),
    };
    let experiment = Experiment::prepare(request.config()?)?;
    let trace =
        coordinator::replay::record_evaluation(&experiment, args.seed, args.episode, &label)?;
    format.write(&trace, &args.out)?;
    println!("wrote {}: {}", args.out.display(), trace.summary());
    Ok(())
}

fn run_router(args: RouterArgs) -> Result<()> {
    coordinator::remote::serve_router(args.listen, args.secret_file.as_deref(), args.zenoh_config)?;
    Ok(())
}

fn run_study(args: StudyArgs) -> Result<()> {
    let mut study = match (&args.preset, &args.config) {
        (Some(name), _) => StudyConfig::preset(name)?,
        (None, Some(path)) => StudyConfig::load(path)?,
        (None, None) => unreachable!("clap requires --preset or --config"),
    };
    if let Some(runs) = args.runs {
        study.runs = runs;
    }
    if let Some(episodes) = args.episodes {
        study.episodes = episodes;
    }
    study.transport = args
        .network
        .transport(args.transport.as_deref(), &study.transport)?;
    let options = StudyOptions {
        threads: args
            .threads
            .map_or_else(coordinator::runner::default_threads, |t| t as usize),
        progress: !args.quiet && std::io::stderr().is_terminal(),
        shard: args.shard,
        stop: None,
    };
    let outcome = coordinator::study::run_study(&study, &args.out, &options)?;
    let wall = outcome.wall.as_secs_f64();
    match &outcome.report {
        Some(report) => println!("study {} -> {} ({wall:.1} s)", study.name, report.display()),
        None => println!(
            "study {} shard {}: {} runs played into {} ({wall:.1} s); \
             without --shard, the statistics and REPORT.md once every shard is done",
            study.name,
            args.shard.map(|s| s.to_string()).unwrap_or_default(),
            outcome.runs_played,
            args.out.display()
        ),
    }
    Ok(())
}

/// `--algorithm`: every algorithm's name, its aliases accepted.
fn algorithm_names() -> impl TypedValueParser<Value = Algorithm> {
    let names = Algorithm::all().map(|n| {
        PossibleValue::new(n.name())
            .aliases(n.aliases())
            .help(n.about())
    });
    PossibleValuesParser::new(names).try_map(|name| name.parse::<Algorithm>())
}

/// The names of `coordinator::study::PRESETS`, the presets `--preset` takes.
fn preset_names() -> PossibleValuesParser {
    PossibleValuesParser::new(PRESETS.map(|(name, _)| name))
}

fn run_one(args: RunArgs) -> Result<()> {
    let agents = match (&args.team, args.algorithm) {
        (Some(path), _) => Agents::Team(load_team_file(path)?),
        (None, Some(algorithm)) => Agents::Algorithm {
            algorithm,
            mistake_correcting: args.mistake_correcting,
        },
        (None, None) => unreachable!("clap requires --algorithm or --team"),
    };
    let request = RunRequest {
        runs: args.runs,
        episodes: args.episodes,
        eval_every: args.eval_every,
        eval_episodes: args.eval_episodes,
        seed: args.seed,
        profile: args.profile,
        ci_level: args.ci_level,
        offense: args.offense,
        evaluation_memory: args.evaluation_memory,
        transport: args
            .network
            .transport(Some(&args.transport), &Transport::InProcess)?,
        advice_latency: args.advice_latency,
        advice_loss: args.advice_loss,
        advice_timeout_ms: args.network.advice_timeout_ms,
        learner: args.learner,
        ..RunRequest::new(agents)
    };
    let label = match &args.team {
        Some(path) => format!("team {}", path.display()),
        None => request.label(),
    };
    let config = request.config()?;
    let experiment = Experiment::prepare(config)?;
    let out = ExperimentDir::check(&args.out, &experiment.record())?;
    let options = RunOptions {
        threads: args
            .threads
            .map_or_else(coordinator::runner::default_threads, |t| t as usize),
        save_agents: args.save_agents,
        progress: !args.quiet && std::io::stderr().is_terminal(),
        bar: None,
        stop: None,
    };
    let report = run_experiment(&experiment, &out, &options)?;
    let c = experiment.config();
    let level = 100.0 * c.ci_level;
    println!(
        "{label}: {} runs x {} episodes -> {}",
        report.summary.runs,
        c.episodes,
        report.summary_path.display()
    );
    let points = &report.summary.eval_points;
    for p in [points.first(), points.last()].into_iter().flatten() {
        println!(
            "  episode {:>5}: goal_pct {}  time_to_goal {}  spent_budget {}",
            p.episode,
            show(&p.goal_pct, level),
            show(&p.time_to_goal, level),
            show(&p.spent_budget, level),
        );
    }
    let t = &report.timing;
    println!(
        "  frames_per_sec: training {:.0}, evaluation {:.0} (per thread); wall {:.2} s",
        t.training_frames_per_sec(),
        t.evaluation_frames_per_sec(),
        report.wall.as_secs_f64()
    );
    Ok(())
}

/// `mean [low, high] (level% CI)`, or what is known of it.
fn show(e: &Estimate, level: f64) -> String {
    match e.ci_low {
        Some(_) => format!("{e} ({level}% CI)"),
        None => e.to_string(),
    }
}
