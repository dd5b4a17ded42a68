//! The schedule of one run (docs/algorithms.md section 4): an evaluation
//! before training, then K training episodes and an evaluation, ..., through N.

use std::time::Instant;

use agent::Mode;
use env_server::Outcome;

use crate::backend::{AgentStats, Backend};
use crate::error::Error;
use crate::experiment::Experiment;
use crate::membership::{Join, Restart, SimulatorRestart};
use crate::provenance::PlayedWith;

/// The measurements of one evaluation.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EvalPoint {
    /// Training episodes played before it.
    pub episode: u64,
    /// Evaluation episodes played (M).
    pub episodes: u64,
    /// Evaluation episodes ending in a goal.
    pub goals: u64,
    /// Goal percentage, `100 * goals / episodes`.
    pub goal_pct: f64,
    /// Mean frames of the goal episodes; `None` without a goal.
    pub time_to_goal: Option<f64>,
    /// Every agent's budgets and communication so far, by id.
    pub agents: Vec<AgentStats>,
    /// The paper's spent budget: give budget spent, averaged over agents.
    pub spent_budget: f64,
    /// Awaited actions played as Move because they missed the step timeout,
    /// over the run so far (training and evaluation; 0 in process).
    #[serde(default)]
    pub actions_timed_out: u64,
}

/// What a run cost: the frames it played and the wall time they took. Saved
/// with the run; the times vary from one machine and moment to another.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Timing {
    /// Agent decisions in training episodes.
    pub training_frames: u64,
    /// Wall time of the training episodes (s).
    pub training_s: f64,
    /// Agent decisions in evaluation episodes.
    pub evaluation_frames: u64,
    /// Wall time of the evaluations (s).
    pub evaluation_s: f64,
}

impl Timing {
    /// Adds another run's timing.
    pub fn add(&mut self, other: &Timing) {
        self.training_frames += other.training_frames;
        self.training_s += other.training_s;
        self.evaluation_frames += other.evaluation_frames;
        self.evaluation_s += other.evaluation_s;
    }

    /// Training decisions per second of one thread's time.
    pub fn training_frames_per_sec(&self) -> f64 {
        rate(self.training_frames, self.training_s)
    }

    /// Evaluation decisions per second of one thread's time.
    pub fn evaluation_frames_per_sec(&self) -> f64 {
        rate(self.evaluation_frames, self.evaluation_s)
    }

    /// Decisions per second of one thread's time, training and evaluation.
    pub fn frames_per_sec(&self) -> f64 {
        rate(
            self.training_frames + self.evaluation_frames,
            self.training_s + self.evaluation_s,
        )
    }
}

fn rate(frames: u64, secs: f64) -> f64 {
    if secs > 0.0 {
        frames as f64 / secs
    } else {
        0.0
    }
}

/// The results of one run (saved as `run-<k>.json` once it is complete).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunResult {
    /// The run's index.
    pub run: u64,
    /// Its evaluations, in order.
    pub points: Vec<EvalPoint>,
    /// What it cost (absent from the files of older versions).
    #[serde(default)]
    pub timing: Timing,
    /// Every agent's advice round-trip times (ms) over the run; empty in process.
    pub advice_rtt_ms: Vec<Vec<f32>>,
    /// Who advised whom over the run: row i, column j, the decisions agent
    /// i (its slot's agents) acted on agent j's advice; absent when no
    /// advice was acted on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub advice_matrix: Vec<Vec<u64>>,
    /// Agents restarted after their process died (none without
    /// `restart_agents`, or without a crash).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub restarts: Vec<Restart>,
    /// The simulator's restarts after it failed (only the real HFO fails).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub simulator_restarts: Vec<SimulatorRestart>,
    /// The newcomers that joined, in order (none in a fixed team).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joins: Vec<Join>,
    /// The code and simulator that played it (absent from the files of
    /// versions before 4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub played_with: Option<PlayedWith>,
}

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
        played_with: Some(PlayedWith::this_build(config.transport.simulator())),
    })
}

/// Adds `more` to `row`, element by element (an empty `row` becomes `more`).
fn add(row: &mut Vec<u64>, more: &[u64]) {
    row.resize(row.len().max(more.len()), 0);
    for (n, m) in row.iter_mut().zip(more) {
        *n += m;
    }
}
