//! One evaluation episode of an experiment's team, recorded: what a
//! researcher looks at (an animated picture, the paths, an rcssserver log
//! for rcssmonitor or soccerwindow2; `env_server::tools`).

use std::path::Path;

use agent::{Mode, Team};
use env_server::Env;
use env_server::tools::rcg;
use env_server::tools::render::Trace;

use crate::error::{ConfigError, Error};
use crate::experiment::Experiment;
use crate::in_process::Players;

/// Plays evaluation episode `episode` (1-based) of `experiment`'s team (its
/// agents as a run starts them: from their snapshots, greedy, learning
/// nothing) on a simulator seeded `seed`, and records it; `played_by`
/// names the team in the pictures.
pub fn record_evaluation(
    experiment: &Experiment,
    seed: u64,
    episode: u64,
    played_by: &str,
) -> Result<Trace, Error> {
    if episode == 0 {
        return Err(ConfigError::new("episode", "episodes are numbered from 1").into());
    }
    let config = experiment.config();
    let mut env =
        Env::new(config.env.clone(), seed).map_err(|e| ConfigError::new("env", e.to_string()))?;
    let mut team = Team::new(experiment.agents(0)?).map_err(|e| Error::run(0, e))?;
    let plugins: Vec<_> = experiment.plugins().cloned().collect();
    let mut observations = Vec::new();
    let mut trace = Trace::new(played_by.to_owned(), seed, episode, config.env.offense);
    for k in 1..=episode {
        let players = Players {
            team: &mut team,
            plugins: &plugins,
            run: 0,
        };
        let recording = k == episode;
        players.play(&mut env, Mode::Evaluation, &mut observations, |env| {
            if recording {
                trace.observe(env);
            }
        })?;
    }
    Ok(trace)
}

/// What a trace is written as, told by the file's name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceFile {
    /// `.svg`: the animation.
    Svg,
    /// `.html`: the animation in a page.
    Html,
    /// `.rcg`: an rcssserver game log.
    Rcg,
}

impl TraceFile {
    /// The format `path`'s name asks for, or an error naming the accepted ones.
    pub fn of(path: &Path) -> Result<Self, Error> {
        match path.extension().and_then(|e| e.to_str()) {
            Some("svg") => Ok(Self::Svg),
            Some("html") => Ok(Self::Html),
            Some("rcg") => Ok(Self::Rcg),
            _ => {
                let reason = format!(
                    "{}: the name must end in .svg, .html or .rcg",
                    path.display()
                );
                Err(ConfigError::new("out", reason).into())
            }
        }
    }

    /// Writes `trace` to `path` in this format.
    pub fn write(self, trace: &Trace, path: &Path) -> Result<(), Error> {
        let text = match self {
            Self::Svg => trace.to_animated_svg(),
            Self::Html => format!(
                "<!doctype html><title>{}</title>\n{}\n",
                trace.summary(),
                trace.to_animated_svg()
            ),
            Self::Rcg => rcg::to_rcg(trace),
        };
        crate::store::write_atomically(path, text.as_bytes())
    }
}
