//! `env-server serve`: the simulator as a process that steps episodes for
//! remote agents over zenoh, following `docs/protocol.md`.
//!
//! [`link`] is the zenoh plumbing (session, token, queryable, subscriber,
//! publishers), [`simulator`] what the server needs of a simulator, ours
//! or [`real_hfo`] (the real HFO, a child process), [`episode`] the
//! simulator side of a run (which simulator plays, what each agent
//! observes, which actions are awaited), and [`server`] what ties them
//! together: actions handled in
//! zenoh's callback, queries and the step deadline in an event loop. They
//! belong to the binary, so the `env_server` library stays free of zenoh
//! and tokio.

mod episode;
mod link;
mod real_hfo;
mod server;
mod simulator;

use anyhow::{Context, Result};
use node::cli::ConnectionArgs;
use std::time::Duration;

pub use real_hfo::RealHfoInstall;

/// Serves the simulator, ours or the real HFO where `real_hfo` says, until
/// a `Stop` command; errors are the start-up failures (bad name or
/// endpoint, port in use, unreachable peer, a real HFO that is not where it
/// is said to be) and a zenoh session that fails underneath.
pub fn run(connection: ConnectionArgs, real_hfo: Option<RealHfoInstall>) -> Result<()> {
    if let Some(install) = &real_hfo {
        install.check().map_err(anyhow::Error::msg)?;
    }
    let keys = connection.keys()?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    let result = runtime.block_on(async {
        let (link, inbox) = link::Link::open(&connection, keys).await?;
        server::run(link, inbox, real_hfo).await
    });
    runtime.shutdown_timeout(Duration::from_secs(1));
    result
}
