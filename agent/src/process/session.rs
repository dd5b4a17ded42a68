//! Joining the zenoh network, and making sure this agent id is free.

use std::time::Duration;

use anyhow::{Result, anyhow, bail};
use proto::keys::{Keys, Role};
use proto::net::NetConfig;
use zenoh::Session;
use zenoh::sample::SampleKind;

/// How long to watch for another process holding this agent's token.
const UNIQUE_WINDOW: Duration = Duration::from_millis(500);

/// Opens a peer session with `net`'s endpoints.
pub async fn open(net: &NetConfig) -> Result<Session> {
    let endpoints = format!(
        "listen {}, connect [{}]",
        net.listen.join(" "),
        net.connect.join(" ")
    );
    let config = zenoh::Config::from_json5(&net.to_json5())
        .map_err(|e| anyhow!("invalid network settings ({endpoints}): {}", describe(&e)))?;
    zenoh::open(config).await.map_err(|e| {
        anyhow!(
            "cannot join the zenoh network ({endpoints}): {}",
            describe(&e)
        )
    })
}

/// A zenoh error's text without the source locations zenoh appends
/// (` at /path/to/file.rs:123.`).
pub fn describe(error: &dyn std::fmt::Display) -> String {
    let text = error.to_string();
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(at) = rest.find(" at ") {
        out.push_str(&rest[..at]);
        let tail = &rest[at + 4..];
        match location_len(tail) {
            Some(n) => rest = &tail[n..],
            None => {
                out.push_str(" at ");
                rest = tail;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The length of a leading `path.rs:123` (and a following `.`), if any.
fn location_len(s: &str) -> Option<usize> {
    let word = s.find(char::is_whitespace).unwrap_or(s.len());
    let (path, line) = s[..word].split_once(".rs:")?;
    let digits = line.bytes().take_while(u8::is_ascii_digit).count();
    if path.is_empty() || digits == 0 {
        return None;
    }
    let end = path.len() + 4 + digits;
    Some(end + usize::from(s[end..].starts_with('.')))
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn source_locations_are_left_out() {
        let e = "Can not bind tcp/127.0.0.1:1: [Address in use (os error 98) at /x/zenoh-link-commons-1.10.2/src/tcp.rs:61.] at /y/unicast.rs:338.";
        assert_eq!(
            describe(&e),
            "Can not bind tcp/127.0.0.1:1: [Address in use (os error 98)]"
        );
        assert_eq!(describe(&"look at this"), "look at this");
        assert_eq!(describe(&"at /a.rs:1"), "at /a.rs:1");
    }
}
