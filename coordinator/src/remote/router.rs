//! `coordinator router`: a zenoh router for experiments spread over hosts,
//! refusing peers without the experiment's secret.

use std::path::{Path, PathBuf};

use crate::error::Error;

/// Routes on `listen` until SIGINT or SIGTERM; with `secret_file`, only
/// peers holding that secret may join; `zenoh_config` is a zenoh
/// configuration file (JSON5) to start from.
pub fn serve_router(
    listen: Vec<String>,
    secret_file: Option<&Path>,
    zenoh_config: Option<PathBuf>,
) -> Result<(), Error> {
    let transport =
        |what: &str, e: &dyn std::fmt::Display| Error::Transport(format!("{what}: {e}"));
    let secret = secret_file
        .map(node::secret::Secret::load)
        .transpose()
        .map_err(|e| transport("the secret file", &e))?;
    let net = node::net::NetConfig {
        mode: "router".to_owned(),
        ..node::net::NetConfig::peer(listen, Vec::new())
    }
    .with_secret(secret)
    .with_base(zenoh_config);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| transport("starting the router's runtime", &e))?;
    runtime.block_on(async {
        let session = node::net::open(&net)
            .await
            .map_err(|e| transport("opening the router", &e))?;
        eprintln!("router {} on {}", session.zid(), net.endpoints());
        let mut terminate =
            tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate())
                .map_err(|e| transport("waiting for SIGTERM", &e))?;
        tokio::select! {
            _ = tokio::signal::ctrl_c() => {}
            _ = terminate.recv() => {}
        }
        session
            .close()
            .await
            .map_err(|e| transport("closing the router", &e))
    })
}
