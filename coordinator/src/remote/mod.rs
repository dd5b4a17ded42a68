//! The zenoh transport: env-server and every agent as separate processes.
//!
//! [`Network`] joins the experiment's zenoh network, starts (or, with
//! `attach`, finds) the processes and watches their liveliness;
//! [`RemoteBackend`] drives one run through it with the control messages of
//! `docs/protocol.md`.

mod launch;
mod network;
mod run;

pub use network::Network;
pub use run::RemoteBackend;
