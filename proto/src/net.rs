//! zenoh session settings as JSON5 text, so that processes share one
//! definition without this crate depending on zenoh.

/// How a process joins the zenoh network.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NetConfig {
    /// Endpoints to listen on, e.g. `tcp/127.0.0.1:7447` (`:0` picks a free port).
    pub listen: Vec<String>,
    /// Endpoints to connect to (a router, or a peer that listens).
    pub connect: Vec<String>,
    /// `"peer"` (default) or `"client"` (behind a router).
    pub mode: String,
}

impl NetConfig {
    /// A loopback peer listening on `127.0.0.1:<port>` (0: any free port)
    /// and connecting to `connect`.
    pub fn loopback_peer(port: u16, connect: Vec<String>) -> Self {
        NetConfig {
            listen: vec![format!("tcp/127.0.0.1:{port}")],
            connect,
            mode: "peer".to_owned(),
        }
    }

    /// The zenoh configuration: multicast scouting off, gossip on (peers
    /// learn each other's listeners through the ones they connect to), and
    /// opening fails after 5 s if a configured endpoint cannot be reached.
    pub fn to_json5(&self) -> String {
        let list = |v: &[String]| {
            v.iter()
                .map(|e| format!("{e:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        format!(
            r#"{{ mode: {mode:?}, listen: {{ endpoints: [{listen}] }}, connect: {{ endpoints: [{connect}], timeout_ms: 5000, exit_on_failure: true }}, scouting: {{ multicast: {{ enabled: false }}, gossip: {{ enabled: true }} }} }}"#,
            mode = self.mode,
            listen = list(&self.listen),
            connect = list(&self.connect),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json5_lists_endpoints() {
        let c = NetConfig::loopback_peer(7447, vec!["tcp/127.0.0.1:7000".into()]);
        let j = c.to_json5();
        assert!(
            j.contains(r#"listen: { endpoints: ["tcp/127.0.0.1:7447"] }"#),
            "{j}"
        );
        assert!(
            j.contains(r#"connect: { endpoints: ["tcp/127.0.0.1:7000"],"#),
            "{j}"
        );
        assert!(j.contains("multicast: { enabled: false }"));
    }
}
