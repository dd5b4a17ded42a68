//! The schedule of one run (docs/algorithms.md section 4): an evaluation
//! before training, then K training episodes and an evaluation, ..., through N.

use std::time::Instant;

use agent::Mode;
use env_server::Outcome;

use analysis::{EvalPoint, Join, RunResult, Timing};

use crate::backend::Backend;
use crate::error::Error;
use crate::experiment::Experiment;
use crate::provenance::played_with;

/// Plays run `run` of `experiment` on `backend`: `on_point` receives every
/// evaluation as soon as it is measured, `progress` the frames of every
/// episode just played (an error from it ends the run).
pub fn play_run(
    experiment: &Experiment,
    backend: &mut dyn Backend,
    run: u64,
    mut on_point: impl FnMut(&EvalPoint) -> Result<(), Error>,
    progress: &(dyn Fn(u64) -> Result<(), Error> + Sync),
) -> Result<RunResult, Error> {
    let config = experiment.config();
    let mut timing = Timing::default();
    let mut points = Vec::new();
    let mut trained = 0u64;
    let mut timed_out = 0u64;
    let mut joins = Vec::new();
    // By slot, the advice acted on by the agents that left it.
    let mut departed = vec![Vec::new(); config.team.len()];
    for (index, at) in config.eval_points().into_iter().enumerate() {
        let start = Instant::now();
        while trained < at {
            let episode = backend.play_episode(Mode::Training)?;
            timed_out += u64::from(episode.actions_timed_out);
            timing.training_frames += u64::from(episode.frames);
            trained += 1;
            progress(u64::from(episode.frames))?;
            for (event, e) in config.events.iter().enumerate() {
                if e.episode == trained {
                    // Who advised the agent that leaves stays in its slot's row.
                    let row = backend.advice_matrix()?.swap_remove(e.slot);
                    add(&mut departed[e.slot], &row);
                    let wait_ms = backend.replace(experiment, event)?;
                    tracing::info!(
                        run,
                        episode = trained,
                        slot = e.slot,
                        wait_ms,
                        "newcomer joined"
                    );
                    joins.push(Join {
                        episode: trained,
                        slot: e.slot,
                        event,
                        wait_ms,
                    });
                }
            }
        }
        timing.training_s += start.elapsed().as_secs_f64();

        let start = Instant::now();
        backend.begin_evaluation(experiment.evaluation_seed(run, index as u64))?;
        let (mut goals, mut goal_frames) = (0u64, 0u64);
        for _ in 0..config.eval_episodes {
            let episode = backend.play_episode(Mode::Evaluation)?;
            timed_out += u64::from(episode.actions_timed_out);
            timing.evaluation_frames += u64::from(episode.frames);
            progress(u64::from(episode.frames))?;
            if episode.outcome == Outcome::Goal {
                goals += 1;
                goal_frames += u64::from(episode.frames);
            }
        }
        timing.evaluation_s += start.elapsed().as_secs_f64();

        let agents = backend.agent_stats()?;
        let spent: u64 = agents.iter().map(|a| a.give_spent).sum();
        let point = EvalPoint {
            episode: at,
            episodes: config.eval_episodes,
            goals,
            goal_pct: 100.0 * goals as f64 / config.eval_episodes as f64,
            time_to_goal: (goals > 0).then(|| goal_frames as f64 / goals as f64),
            spent_budget: spent as f64 / agents.len().max(1) as f64,
            agents,
            actions_timed_out: timed_out,
        };
        on_point(&point)?;
        points.push(point);
    }
    let mut advice_matrix = backend.advice_matrix()?;
    for (row, left) in advice_matrix.iter_mut().zip(&departed) {
        add(row, left);
    }
    if advice_matrix.iter().flatten().all(|&n| n == 0) {
        advice_matrix.clear();
    }
    Ok(RunResult {
        run,
        points,
        timing,
        advice_rtt_ms: backend.advice_rtt_ms(),
        advice_matrix,
        restarts: backend.restarts(),
        simulator_restarts: backend.simulator_restarts(),
        joins,
        played_with: Some(played_with(config.transport.simulator())),
    })
}

/// Adds `more` to `row`, element by element (an empty `row` becomes `more`).
fn add(row: &mut Vec<u64>, more: &[u64]) {
    row.resize(row.len().max(more.len()), 0);
    for (n, m) in row.iter_mut().zip(more) {
        *n += m;
    }
}
