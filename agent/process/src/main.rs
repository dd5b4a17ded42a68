//! `agent`: one learning agent as a process, talking to env-server, its
//! teammates and the coordinator over zenoh (docs/protocol.md).
//!
//! [`frames`] steps observations in order where they arrive, in zenoh's
//! callback, and leaves a frame that asks for advice ([`ask`]) to its
//! stream task, which waits without holding the learner; shared episodes
//! are queued in the learner as they arrive; [`advise`] answers other
//! agents' requests in its callback meanwhile; [`control`] answers the
//! coordinator; [`alive`] follows liveliness tokens. They share one
//! [`context::Context`]; [`serve`] declares everything and waits for the end.

mod advise;
mod alive;
mod ask;
mod child;
mod conditions;
mod context;
mod control;
mod frames;
mod learner_pipe;
mod learning;
mod order;
mod serve;
mod shares;
mod strategy_pipe;
mod unique;

use anyhow::{Result, bail};
use clap::Parser;
use node::cli::{ConnectionArgs, exit_with_error, init_tracing, parse_or_exit};

use std::path::PathBuf;
use std::time::Duration;

use child::{ChildCommand, ChildCommands};
use context::Exit;
use serve::Settings;

#[derive(Parser)]
#[command(
    version,
    about = "One ad hoc advising agent: learns from env-server's observations, asks and gives advice over zenoh"
)]
struct AgentCli {
    #[command(flatten)]
    connection: ConnectionArgs,
    /// This agent's id, below the team size.
    #[arg(long, value_name = "I")]
    id: u8,
    /// Agents in the team.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(1..))]
    team_size: u8,
    /// Working directory of the learner command (default: this one's).
    #[arg(long, value_name = "DIR", requires = "learner")]
    learner_dir: Option<PathBuf>,
    /// How long the learner process may take to answer (ms).
    #[arg(long, value_name = "MS", default_value_t = 1000,
          value_parser = clap::value_parser!(u64).range(1..=proto::MAX_WAIT_MS))]
    learner_timeout_ms: u64,
    /// Make algorithm `external`'s advising decisions with this command's
    /// process, one shell-quoted line, e.g. `--strategy "python3
    /// my_strategy.py"` (docs/strategies.md).
    #[arg(long, value_name = "COMMAND")]
    strategy: Option<String>,
    /// Working directory of the strategy command (default: this one's).
    #[arg(long, value_name = "DIR", requires = "strategy")]
    strategy_dir: Option<PathBuf>,
    /// How long the strategy process may take to answer (ms).
    #[arg(long, value_name = "MS", default_value_t = 1000,
          value_parser = clap::value_parser!(u64).range(1..=proto::MAX_WAIT_MS))]
    strategy_timeout_ms: u64,
    /// Learn with this command's process instead of SARSA(lambda), e.g.
    /// `-- python3 my_learner.py` (docs/learners.md).
    #[arg(last = true, value_name = "COMMAND")]
    learner: Vec<String>,
}

fn main() {
    node::net::use_one_runtime();
    init_tracing("off");
    let cli: AgentCli = parse_or_exit();
    let code = match run(cli) {
        Ok(Exit::Stopped) => 0,
        Ok(Exit::CoordinatorGone) => {
            eprintln!("error: the coordinator left the experiment; stopping");
            1
        }
        Err(e) => exit_with_error(format_args!("{e:#}")),
    };
    // Exit at once: zenoh's background threads need no orderly shutdown
    // once the session is closed.
    std::process::exit(code)
}

/// The program and arguments of a `--strategy` line.
fn strategy_argv(line: &str) -> Result<Vec<String>> {
    match shlex::split(line) {
        Some(argv) if !argv.is_empty() => Ok(argv),
        _ => bail!(
            "--strategy `{line}` is not a command line: expected a program and its arguments, \
             quoted as a shell would, e.g. \"python3 my_strategy.py\""
        ),
    }
}

/// Checks the settings and runs the agent until it stops.
fn run(cli: AgentCli) -> Result<Exit> {
    let keys = cli.connection.keys()?;
    if cli.id >= cli.team_size {
        bail!(
            "agent id {} is not below the team size {}",
            cli.id,
            cli.team_size
        );
    }
    let settings = Settings {
        net: cli.connection.net()?,
        name: cli.connection.experiment,
        keys,
        id: cli.id,
        team_size: cli.team_size,
        exit_with_coordinator: cli.connection.exit_with_coordinator,
        children: ChildCommands {
            learner: (!cli.learner.is_empty()).then(|| ChildCommand {
                argv: cli.learner,
                dir: cli.learner_dir,
                timeout: Duration::from_millis(cli.learner_timeout_ms),
            }),
            strategy: match cli.strategy {
                None => None,
                Some(line) => Some(ChildCommand {
                    argv: strategy_argv(&line)?,
                    dir: cli.strategy_dir,
                    timeout: Duration::from_millis(cli.strategy_timeout_ms),
                }),
            },
        },
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    let exit = runtime.block_on(serve::run(settings));
    // Tasks still waiting on the closed session are dropped unawaited.
    runtime.shutdown_background();
    exit
}
