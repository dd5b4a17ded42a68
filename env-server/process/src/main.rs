//! `env-server`: run the HFO simulator from the command line: rollouts,
//! episode pictures ([`picture`]), and the simulator as a process stepping
//! episodes for remote agents ([`serve`]).

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use env_server::tools::render;
use env_server::tools::rollout::{EnvReuse, rollout_on};
use env_server::{EnvConfig, ScriptedPolicy};
use node::cli::{ConnectionArgs, exit_with_error, init_tracing, parse_or_exit};
use std::path::PathBuf;

mod picture;
mod serve;

#[derive(Parser)]
#[command(
    version,
    about = "Half Field Offense simulator (1-4 offense agents vs a goalkeeper)"
)]
struct EnvServerCli {
    #[command(subcommand)]
    command: EnvServerCommand,
}

#[derive(Subcommand)]
enum EnvServerCommand {
    /// Play episodes under a scripted policy and summarise them.
    Rollout {
        /// Policy: random, shoot, dribble, pass or uniform.
        #[arg(long, default_value = "random")]
        policy: ScriptedPolicy,
        /// Number of episodes (at least 1).
        #[arg(long, default_value_t = 1000, value_parser = at_least_one)]
        episodes: u64,
        /// Seed of every random choice.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Number of offense agents (1 to 4).
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(1..=4))]
        offense: u8,
        /// Simulator settings as JSON (`EnvConfig` fields; missing ones keep their defaults).
        #[arg(long, value_name = "FILE")]
        env_config: Option<PathBuf>,
        /// Play every episode on a new simulator, as the first episode of a
        /// freshly started HFO server (default: one long-lived simulator).
        #[arg(long)]
        fresh: bool,
        /// Print one JSON object instead of a readable summary.
        #[arg(long)]
        json: bool,
    },
    /// Play one episode of a rollout and draw it as an SVG or PNG picture.
    Render {
        /// Policy: random, shoot, dribble, pass or uniform.
        #[arg(long, default_value = "random")]
        policy: ScriptedPolicy,
        /// Seed of the rollout the episode belongs to.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Which episode of that rollout to draw (1 is the first).
        #[arg(long, default_value_t = 1, value_parser = at_least_one)]
        episode: u64,
        /// Output file, ending in .svg or .png (a picture) or .rcg (an
        /// rcssserver game log for rcssmonitor or soccerwindow2).
        #[arg(long)]
        out: PathBuf,
        /// Number of offense agents (1 to 4).
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u8).range(1..=4))]
        offense: u8,
        /// Simulator settings as JSON (`EnvConfig` fields; missing ones keep their defaults).
        #[arg(long, value_name = "FILE")]
        env_config: Option<PathBuf>,
    },
    /// Step the simulator for remote agents over zenoh until a Stop command
    /// (docs/protocol.md).
    Serve {
        #[command(flatten)]
        connection: ConnectionArgs,
        #[command(flatten)]
        real_hfo: RealHfoArgs,
    },
}

/// Where the real HFO is, for a server that plays it instead of ours.
#[derive(clap::Args)]
struct RealHfoArgs {
    /// Play the real HFO built in DIR (env-server/oracle/build_hfo.sh DIR)
    /// instead of our simulator: its runs are not deterministic.
    #[arg(long, value_name = "DIR")]
    real_hfo: Option<PathBuf>,
    /// With --real-hfo: the Python interpreter of HFO's launcher and
    /// players [default: DIR/venv/bin/python].
    #[arg(long, value_name = "FILE", requires = "real_hfo")]
    hfo_python: Option<PathBuf>,
    /// With --real-hfo: the directory holding the harness `hfo_oracle`
    /// [default: this source tree's env-server/oracle].
    #[arg(long, value_name = "DIR", requires = "real_hfo")]
    hfo_harness: Option<PathBuf>,
}

impl RealHfoArgs {
    /// Where the real HFO is, when asked for.
    fn install(self) -> Option<serve::RealHfoInstall> {
        let hfo_dir = self.real_hfo?;
        Some(serve::RealHfoInstall {
            python: self
                .hfo_python
                .unwrap_or_else(|| hfo_dir.join("venv").join("bin").join("python")),
            harness: self.hfo_harness.unwrap_or_else(|| {
                PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../oracle"))
            }),
            hfo_dir,
        })
    }
}

fn main() {
    node::net::use_one_runtime();
    // Without RUST_LOG: errors, and this program's warnings (missing actions).
    init_tracing("error,env_server=warn");
    let cli: EnvServerCli = parse_or_exit();
    if let Err(e) = run(cli) {
        exit_with_error(format_args!("{e:#}"));
    }
}

fn run(cli: EnvServerCli) -> Result<()> {
    match cli.command {
        EnvServerCommand::Rollout {
            policy,
            episodes,
            seed,
            offense,
            json,
            env_config,
            fresh,
        } => {
            let config = EnvConfig {
                offense: offense.into(),
                ..load_env_config(env_config.as_deref())?
            };
            let simulators = if fresh {
                EnvReuse::Fresh
            } else {
                EnvReuse::One
            };
            let s = rollout_on(config, policy, episodes, seed, simulators)?;
            if json {
                println!("{}", serde_json::to_string(&s)?);
            } else {
                let pct = |n: u64| 100.0 * n as f64 / s.episodes as f64;
                println!(
                    "policy {} · {} offense · seed {} · {} episodes",
                    s.policy, s.offense, s.seed, s.episodes
                );
                println!(
                    "  goals          {:6.2} %   mean frames to goal {:.1}",
                    s.goal_pct, s.mean_frames_to_goal
                );
                println!("  captured       {:6.2} %", pct(s.outcomes.captured));
                println!("  out of bounds  {:6.2} %", pct(s.outcomes.out_of_bounds));
                println!("  out of time    {:6.2} %", pct(s.outcomes.out_of_time));
                println!("  mean frames    {:6.1}", s.mean_frames);
                let shots: Vec<String> = s
                    .decisions
                    .shots
                    .iter()
                    .map(|b| match b.to_m {
                        Some(to) => format!("{}-{to} m {}/{}", b.from_m, b.goals, b.released),
                        None => format!(">={} m {}/{}", b.from_m, b.goals, b.released),
                    })
                    .collect();
                println!("  shots scored   {}", shots.join(", "));
                println!("  speed          {:.0} frames/s", s.frames_per_sec);
            }
        }
        EnvServerCommand::Render {
            policy,
            seed,
            episode,
            out,
            offense,
            env_config,
        } => {
            picture::Format::of(&out)?;
            let config = EnvConfig {
                offense: offense.into(),
                ..load_env_config(env_config.as_deref())?
            };
            let trace = render::record_episode(config, policy, seed, episode)?;
            picture::write_picture(&trace, &out)?;
            println!("wrote {}: {}", out.display(), trace.summary());
        }
        EnvServerCommand::Serve {
            connection,
            real_hfo,
        } => serve::run(connection, real_hfo.install())?,
    }
    Ok(())
}

/// Reads simulator settings from a JSON file, or the defaults without one.
fn load_env_config(path: Option<&std::path::Path>) -> Result<EnvConfig> {
    let Some(path) = path else {
        return Ok(EnvConfig::default());
    };
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read env config {}", path.display()))?;
    let config: EnvConfig = serde_json::from_str(&text)
        .with_context(|| format!("invalid env config {}", path.display()))?;
    config.validate()?;
    Ok(config)
}

/// Parses a count that must be at least 1.
fn at_least_one(s: &str) -> Result<u64, String> {
    match s.parse::<u64>() {
        Ok(0) => Err("must be at least 1".to_owned()),
        Ok(n) => Ok(n),
        Err(_) => Err("expected a whole number of at least 1".to_owned()),
    }
}
