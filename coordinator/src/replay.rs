//! One evaluation episode of an experiment's team, recorded: what a
//! researcher looks at (an animated picture, the paths, an rcssserver log
//! for rcssmonitor or soccerwindow2; `env_server::tools`).

use agent::{Mode, Team};
use env_server::Env;
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
