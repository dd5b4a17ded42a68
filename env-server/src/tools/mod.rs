//! Tools built on the simulator: baseline policies, rollouts and their
//! statistics, pictures, and a run's simulators.

pub mod baseline;
pub mod decision_stats;
pub mod render;
pub mod rollout;
pub mod run_envs;
pub mod tally;
