//! The simulation core. Modules follow one cycle's data flow: [`world`]
//! holds the state, [`analysis`] derives what every behaviour reads (reach
//! cycles, formation), [`behaviour`] turns actions into body commands,
//! [`view`] moves the attackers' necks and counts where they looked,
//! [`physics`] executes the commands, [`referee`] ends episodes and
//! [`features`] describes the state to the agents; [`env`](mod@env) ties
//! them together, with the settings of [`config`].

pub mod analysis;
pub mod behaviour;
pub mod config;
pub mod env;
pub mod features;
pub mod formation;
pub mod geom;
pub mod kinematics;
pub mod memory;
pub mod params;
pub mod physics;
pub mod referee;
pub mod self_intercept;
pub mod view;
pub mod world;
