//! A Rust simulator of RoboCup 2D Half Field Offense: K offense agents
//! choosing HFO's high-level actions against agent2d's goalkeeper.
//!
//! The specification is `docs/hfo-sim-spec.md` ("spec N" in comments). The
//! simulation core is in [`sim`], the [`tools`] built on it (baseline
//! policies, rollouts, pictures) apart.

pub mod sim;
pub mod tools;

pub use sim::config::{ConfigError, EnvConfig, LongShot};
pub use sim::env::Env;
pub use sim::referee::Outcome;
pub use tools::policy::BaselinePolicy;
pub use tools::rollout::{RolloutSummary, rollout};
