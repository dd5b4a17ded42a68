//! Tools built on the simulator: baseline policies, rollouts and their
//! statistics, pictures, and a run's simulators.

pub mod decisions;
pub mod policy;
pub mod render;
pub mod rollout;
pub mod simulators;
pub mod tally;
