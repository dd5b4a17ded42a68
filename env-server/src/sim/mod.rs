//! The simulation core: the state, the agents' and the keeper's
//! behaviours, the server's models and the referee, tied together by
//! [`env::Env`].

pub(crate) mod analysis;
pub(crate) mod behaviour;
pub(crate) mod config;
pub(crate) mod env;
pub mod features;
pub(crate) mod formation;
pub(crate) mod geom;
pub(crate) mod kinematics;
pub(crate) mod memory;
pub mod params;
pub(crate) mod physics;
pub(crate) mod referee;
pub(crate) mod self_intercept;
pub(crate) mod view;
pub(crate) mod world;
