//! `env-server serve`: the simulator as a process that steps episodes for
//! remote agents over zenoh, following `docs/protocol.md`.
//!
//! [`link`] is the zenoh plumbing (session, token, queryable, subscriber,
//! publishers), [`episode`] the simulator side of a run without any I/O
//! (which simulator plays, what each agent observes, which actions are
//! awaited), and [`server`] the event loop tying them together. They
//! belong to the binary, so the `env_server` library stays free of zenoh
//! and tokio.

mod episode;
mod link;
mod server;

use anyhow::{Context, Result};
use node::cli::ConnectionArgs;
use std::time::Duration;

/// The settings of `env-server serve`.
#[derive(Clone, Debug)]
pub struct Options {
    /// The experiment, the endpoints, and whether to exit with the coordinator.
    pub connection: ConnectionArgs,
    /// How long to wait for a kicker's action before falling back to Move.
    pub step_timeout: Duration,
}

/// Serves the simulator until a `Stop` command; errors are the start-up
/// failures (bad name or endpoint, port in use, unreachable peer) and a
/// zenoh session that fails underneath.
pub fn run(options: Options) -> Result<()> {
    let keys = options.connection.keys()?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    let result = runtime.block_on(async {
        let (link, inbox) = link::Link::open(&options, keys).await?;
        server::Server::new(link, options.step_timeout)
            .run(inbox)
            .await
    });
    runtime.shutdown_timeout(Duration::from_secs(1));
    result
}
