//! Tools built on the simulator: baseline policies, rollouts and their
//! statistics, pictures.

pub mod decisions;
pub mod policy;
pub mod render;
pub mod rollout;
pub mod tally;
