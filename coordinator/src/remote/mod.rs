//! The zenoh transport: env-server and every agent as separate processes.
//!
//! [`Network`] joins the experiment's zenoh network, starts (or, with
//! `attach`, finds) the processes and watches their liveliness;
//! [`RemoteBackend`] drives one run through it with the control messages of
//! `docs/protocol.md`.

mod backend;
mod launch;
mod network;

pub use backend::RemoteBackend;
pub use network::{Network, NetworkOptions};
