//! The zenoh transport: env-server and every agent as separate processes.
//!
//! [`ZenohTeam`] joins the experiment's zenoh network, starts (or, with
//! `attach`, finds) the processes and watches their liveliness;
//! [`RemoteBackend`] drives one run through it with the control messages of
//! `docs/protocol.md`.

mod launch;
mod processes;
mod router;
mod run;

pub use processes::{StartedAgain, ZenohTeam};
pub use router::serve_router;
pub use run::RemoteBackend;
