//! A Rust simulator of RoboCup 2D Half Field Offense: K offense agents
//! choosing HFO's high-level actions against agent2d's goalkeeper.
//!
//! The specification is `docs/hfo-sim-spec.md` ("spec N" in comments).
//! [`Env`] runs episodes with the settings of [`EnvConfig`]: it takes one
//! [`Action`](proto::Action) per agent each step and offers a read-only
//! view of the [`World`], the [`Outcome`], the paper's state and HFO's
//! [`features`]. The simulation core is private (`src/sim/`); the
//! [`tools`] built on it (scripted policies, rollouts, pictures) are
//! public.

#![warn(missing_docs, unreachable_pub)]

mod sim;
pub mod tools;

pub use sim::config::{EnvConfig, EnvConfigError, EvaluationMemory, MAX_OFFENSE};
pub use sim::env::Env;
pub use sim::features;
pub use sim::memory::{AgentMemory, ShotCourse};
pub use sim::params;
pub use sim::physics::Command;
pub use sim::referee::Outcome;
pub use sim::view::Sight;
pub use sim::world::{Ball, Player, World};
pub use tools::rollout::{RolloutSummary, rollout};
pub use tools::run_envs::RunEnvs;
pub use tools::scripted::ScriptedPolicy;
