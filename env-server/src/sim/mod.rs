//! The simulation core. Modules follow one cycle's data flow: [`world`]
//! holds the state and [`memory`] what each agent remembers, [`analysis`]
//! derives what every behaviour reads (reach cycles, with
//! [`self_intercept`], and [`formation`] targets), [`behaviour`] turns
//! actions into body commands, [`view`] moves the attackers' necks and
//! counts where they looked, [`physics`] executes the commands, [`referee`]
//! ends episodes and [`features`] describes the state to the agents;
//! [`env`](mod@env) ties them together, with the settings of [`config`].
//! [`params`] holds the server's constants, [`geom`] and [`kinematics`]
//! the arithmetic they all share.

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
