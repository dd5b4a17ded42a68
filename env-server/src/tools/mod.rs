//! Tools built on the simulator: scripted policies, rollouts and their
//! statistics, pictures, game logs for the monitors, and a run's simulators.

pub mod decision_stats;
pub mod fingerprint;
pub mod rcg;
pub mod render;
pub mod rollout;
pub mod run_envs;
pub mod scripted;
pub mod tally;
