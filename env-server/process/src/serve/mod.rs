//! `env-server serve`: the simulator as a process that steps episodes for
//! remote agents over zenoh, following `docs/protocol.md`.
//!
//! [`link`] is the zenoh plumbing (session, token, queryable, subscriber,
//! publishers), [`episode`] the simulator side of a run without any I/O
//! (which simulator plays, what each agent observes, which actions are
//! awaited), and [`server`] what ties them together: actions handled in
//! zenoh's callback, queries and the step deadline in an event loop. They
//! belong to the binary, so the `env_server` library stays free of zenoh
//! and tokio.

mod episode;
mod link;
mod server;

use anyhow::{Context, Result};
use node::cli::ConnectionArgs;
use std::time::Duration;

/// Serves the simulator until a `Stop` command; errors are the start-up
/// failures (bad name or endpoint, port in use, unreachable peer) and a
/// zenoh session that fails underneath.
pub fn run(connection: ConnectionArgs) -> Result<()> {
    let keys = connection.keys()?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    let result = runtime.block_on(async {
        let (link, inbox) = link::Link::open(&connection, keys).await?;
        server::run(link, inbox).await
    });
    runtime.shutdown_timeout(Duration::from_secs(1));
    result
}
