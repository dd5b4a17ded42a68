//! Making sure this agent id is free in the experiment.

use std::time::Duration;

use anyhow::{Result, anyhow, bail};
use node::net::describe;
use proto::keys::{Keys, Role};
use zenoh::Session;
use zenoh::sample::SampleKind;

/// How long to watch for another process holding this agent's token.
const UNIQUE_WINDOW: Duration = Duration::from_secs(1);

/// Fails if another process already holds agent `id`'s liveliness token.
///
/// Peers learn of each other through gossip after the session opens, so a
/// single look right away can miss a token: this one watches for it during
/// [`UNIQUE_WINDOW`], before this agent declares its own.
pub async fn ensure_unique(session: &Session, keys: &Keys, name: &str, id: u8) -> Result<()> {
    let tokens = session
        .liveliness()
        .declare_subscriber(keys.alive(Role::Agent(id)))
        .history(true)
        .await
        .map_err(|e| anyhow!("cannot look for other agents: {}", describe(&e)))?;
    let seen = tokio::time::timeout(UNIQUE_WINDOW, async {
        while let Ok(sample) = tokens.recv_async().await {
            if sample.kind() == SampleKind::Put {
                return true;
            }
        }
        false
    })
    .await;
    if seen == Ok(true) {
        bail!("agent id {id} is already running in experiment {name}");
    }
    Ok(())
}
