//! Rollouts: episodes played under a scripted policy from one seed, on one
//! long-lived simulator or each on a new one, and their summary.

use crate::sim::config::{EnvConfig, EnvConfigError};
use crate::sim::env::Env;
use crate::sim::referee::Outcome;
use crate::tools::decision_stats::{DecisionRecorder, DecisionStats};
use crate::tools::scripted::{ScriptedPolicy, play_episode, policy_rng};
use crate::tools::tally::{Moments, OutcomeCounts};
use rand::{RngCore, SeedableRng};
use rand_xoshiro::SplitMix64;
use serde::Serialize;
use std::time::Instant;

/// Summary of a rollout.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RolloutSummary {
    /// Which simulator played (`ours`; the real-HFO oracle writes `hfo`).
    pub simulator: &'static str,
    /// Policy name.
    pub policy: String,
    /// Offense agents.
    pub offense: usize,
    /// Seed of the run.
    pub seed: u64,
    /// Whether every episode was played on a new simulator.
    pub fresh_simulators: bool,
    /// Episodes played.
    pub episodes: u64,
    /// Percentage of episodes ending in a goal.
    pub goal_pct: f64,
    /// Mean agent decisions ("frames") per episode.
    pub mean_frames: f64,
    /// Mean frames of the goal episodes (0 when there was none).
    pub mean_frames_to_goal: f64,
    /// Outcome counts.
    pub outcomes: OutcomeCounts,
    /// Per-decision statistics.
    pub decisions: DecisionStats,
    /// Standard deviations of the means above, for their intervals.
    pub sd: Spread,
    /// Total agent decisions.
    pub frames: u64,
    /// Decisions per second of wall time (simulator and policy).
    pub frames_per_sec: f64,
}

/// Sample standard deviations of a rollout's per-episode means.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Spread {
    /// Of the frames per episode.
    pub frames: f64,
    /// Of the frames of the goal episodes.
    pub frames_to_goal: f64,
    /// Of the possessions per episode.
    pub possessions_per_episode: f64,
}

/// Where a rollout plays its episodes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvReuse {
    /// All on one simulator seeded with the rollout's seed, whose agents
    /// remember from episode to episode, as one long-lived HFO server's.
    #[default]
    One,
    /// Each on a new simulator (seeded from a SplitMix64 stream of the
    /// rollout's seed): every episode is the first of a fresh HFO server.
    Fresh,
}

/// Plays `episodes` episodes under `policy` with `seed` on one simulator.
pub fn rollout(
    config: EnvConfig,
    policy: ScriptedPolicy,
    episodes: u64,
    seed: u64,
) -> Result<RolloutSummary, EnvConfigError> {
    rollout_on(config, policy, episodes, seed, EnvReuse::One)
}

/// Plays `episodes` episodes under `policy` with `seed` on `simulators`;
/// the policy draws from one stream throughout.
pub fn rollout_on(
    config: EnvConfig,
    policy: ScriptedPolicy,
    episodes: u64,
    seed: u64,
    simulators: EnvReuse,
) -> Result<RolloutSummary, EnvConfigError> {
    let offense = config.offense;
    let mut env = Env::new(config.clone(), seed)?;
    let mut episode_seeds = SplitMix64::seed_from_u64(seed);
    let mut rng = policy_rng(seed);
    let mut outcomes = OutcomeCounts::default();
    let mut decisions = DecisionRecorder::default();
    let (mut frames, mut goal_frames) = (0u64, 0u64);
    let (mut frame_moments, mut goal_moments) = (Moments::default(), Moments::default());
    let start = Instant::now();
    for _ in 0..episodes {
        if simulators == EnvReuse::Fresh {
            env = Env::new(config.clone(), episode_seeds.next_u64())?;
        }
        let (outcome, n) = play_episode(&mut env, policy, &mut rng, |env, actions| {
            decisions.observe(env, actions)
        });
        outcomes.add(outcome);
        frames += u64::from(n);
        frame_moments.add(f64::from(n));
        if outcome == Outcome::Goal {
            goal_frames += u64::from(n);
            goal_moments.add(f64::from(n));
        }
    }
    let secs = start.elapsed().as_secs_f64();
    let ratio = |a: u64, b: u64| if b == 0 { 0.0 } else { a as f64 / b as f64 };
    Ok(RolloutSummary {
        simulator: "ours",
        policy: policy.name().to_owned(),
        offense,
        seed,
        fresh_simulators: simulators == EnvReuse::Fresh,
        episodes,
        goal_pct: 100.0 * ratio(outcomes.goal, episodes),
        mean_frames: ratio(frames, episodes),
        mean_frames_to_goal: ratio(goal_frames, outcomes.goal),
        outcomes,
        decisions: decisions.stats(),
        sd: Spread {
            frames: frame_moments.sd(),
            frames_to_goal: goal_moments.sd(),
            possessions_per_episode: decisions.possessions_sd(),
        },
        frames,
        frames_per_sec: if secs > 0.0 {
            frames as f64 / secs
        } else {
            0.0
        },
    })
}
