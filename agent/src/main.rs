//! `agent`: one learning agent as a process, talking to env-server, its
//! teammates and the coordinator over zenoh (docs/protocol.md).

mod process;

use std::time::Duration;

use anyhow::{Result, bail};
use clap::Parser;
use proto::keys::Keys;
use proto::net::NetConfig;

use process::{Exit, Settings};

#[derive(Parser)]
#[command(
    version,
    about = "One ad hoc advising agent: learns from env-server's observations, asks and gives advice over zenoh"
)]
struct Cli {
    /// Experiment name (letters, digits, '-', '_'), shared by all its processes.
    #[arg(long, value_name = "NAME")]
    experiment: String,
    /// This agent's id, below the team size.
    #[arg(long, value_name = "I")]
    id: u8,
    /// Agents in the team.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(1..))]
    team_size: u8,
    /// zenoh endpoint to listen on (port 0: any free port).
    #[arg(long, value_name = "ENDPOINT", default_value = "tcp/127.0.0.1:0")]
    listen: String,
    /// zenoh endpoint to connect to (the coordinator, or a router); repeatable.
    #[arg(long, value_name = "ENDPOINT")]
    connect: Vec<String>,
    /// How long to wait for advice after asking, in milliseconds.
    #[arg(long, value_name = "MS", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..))]
    advice_timeout_ms: u64,
    /// Exit when the coordinator that was seen leaves (for processes a
    /// coordinator starts itself; services keep running).
    #[arg(long)]
    exit_with_coordinator: bool,
}

fn main() {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("off"));
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .init();
    let code = match Cli::try_parse() {
        Ok(cli) => match run(cli) {
            Ok(Exit::Stopped) => 0,
            Ok(Exit::CoordinatorGone) => {
                eprintln!("error: the coordinator left the experiment; stopping");
                1
            }
            Err(e) => {
                eprintln!("error: {}", one_line(&format!("{e:#}")));
                2
            }
        },
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            0
        }
        Err(e) => {
            eprintln!("{}", one_line(&e.to_string()));
            2
        }
    };
    // Exit at once: zenoh's background threads need no orderly shutdown
    // once the session is closed.
    std::process::exit(code)
}

/// Folds a multi-line message into one line, without clap's usage hints.
fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty() && !l.starts_with("For more information") && !l.starts_with("Usage:")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Checks the settings and runs the agent until it stops.
fn run(cli: Cli) -> Result<Exit> {
    let keys = Keys::new(&cli.experiment)?;
    if cli.id >= cli.team_size {
        bail!(
            "agent id {} is not below the team size {}",
            cli.id,
            cli.team_size
        );
    }
    let settings = Settings {
        name: cli.experiment,
        keys,
        id: cli.id,
        team_size: cli.team_size,
        net: NetConfig {
            listen: vec![cli.listen],
            connect: cli.connect,
            mode: "peer".to_owned(),
        },
        advice_timeout: Duration::from_millis(cli.advice_timeout_ms),
        exit_with_coordinator: cli.exit_with_coordinator,
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    let exit = runtime.block_on(process::run(settings));
    // Tasks still waiting on the closed session are dropped unawaited.
    runtime.shutdown_background();
    exit
}
