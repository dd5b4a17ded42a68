//! Joining the zenoh network: the session settings, opening a session with
//! a one-line error, and free loopback ports.

use std::fmt::Display;
use std::path::PathBuf;

use serde_json::{Value, json};
use zenoh::Session;

use crate::secret::Secret;

/// How a process joins the zenoh network.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NetConfig {
    /// Endpoints to listen on, e.g. `tcp/127.0.0.1:7447` (`:0` picks a free port).
    pub listen: Vec<String>,
    /// Endpoints to connect to (a router, or a peer that listens).
    pub connect: Vec<String>,
    /// `"peer"` (default) or `"client"` (behind a router).
    pub mode: String,
    /// The experiment's credentials; `None` joins without authentication.
    pub secret: Option<Secret>,
    /// A zenoh configuration file (JSON5) to start from, e.g. TLS
    /// certificates and access control (deploy/tls/); the settings above
    /// are set on top of it.
    pub base: Option<PathBuf>,
}

impl NetConfig {
    /// A peer listening on `listen` and connecting to `connect`.
    pub fn peer(listen: Vec<String>, connect: Vec<String>) -> Self {
        NetConfig {
            listen,
            connect,
            mode: "peer".to_owned(),
            secret: None,
            base: None,
        }
    }

    /// These settings with `secret`'s authentication.
    pub fn with_secret(self, secret: Option<Secret>) -> Self {
        Self { secret, ..self }
    }

    /// These settings on top of the zenoh configuration file `base`.
    pub fn with_base(self, base: Option<PathBuf>) -> Self {
        Self { base, ..self }
    }

    /// A loopback peer listening on `127.0.0.1:<port>` (0: any free port)
    /// and connecting to `connect`.
    pub fn loopback_peer(port: u16, connect: Vec<String>) -> Self {
        Self::peer(vec![format!("tcp/127.0.0.1:{port}")], connect)
    }

    /// The zenoh settings, as (key, value) pairs: multicast scouting
    /// off, gossip on (peers learn each other's listeners through the ones
    /// they connect to; of two peers only the one with the greater id opens
    /// their link, since two authenticated handshakes crossing each other
    /// can kill both links), opening fails after 5 s if a configured
    /// endpoint cannot be reached, and with a secret, user/password
    /// authentication both ways.
    pub fn settings(&self) -> Vec<(&'static str, Value)> {
        let mut settings = vec![
            ("mode", json!(self.mode)),
            ("listen/endpoints", json!(self.listen)),
            ("connect/endpoints", json!(self.connect)),
            ("connect/timeout_ms", json!(5000)),
            ("connect/exit_on_failure", json!(true)),
            ("scouting/multicast/enabled", json!(false)),
            ("scouting/gossip/enabled", json!(true)),
            ("scouting/gossip/autoconnect_strategy", json!("greater-zid")),
        ];
        if let Some(secret) = &self.secret {
            settings.push(("transport/auth/usrpwd", secret.usrpwd_setting()));
        }
        settings
    }

    /// The zenoh configuration: the base file's, if any, with
    /// [`settings`](Self::settings) on top.
    pub fn to_config(&self) -> Result<zenoh::Config, JoinError> {
        let invalid = |e: &dyn Display| {
            JoinError(format!(
                "invalid network settings ({}): {}",
                self.endpoints(),
                describe(e)
            ))
        };
        let mut config = match &self.base {
            Some(path) => zenoh::Config::from_file(path).map_err(|e| {
                JoinError(format!(
                    "invalid zenoh configuration file {}: {}",
                    path.display(),
                    describe(&e)
                ))
            })?,
            None => zenoh::Config::default(),
        };
        for (key, value) in self.settings() {
            // JSON is JSON5.
            config
                .insert_json5(key, &value.to_string())
                .map_err(|e| invalid(&format!("{key} = {value}: {e}")))?;
        }
        Ok(config)
    }

    /// The endpoints for messages: `listen A, B; connect C` (`none` for an empty list).
    pub fn endpoints(&self) -> String {
        let list = |v: &[String]| match v {
            [] => "none".to_owned(),
            v => v.join(", "),
        };
        format!(
            "listen {}; connect {}",
            list(&self.listen),
            list(&self.connect)
        )
    }
}

/// Why a process could not join the zenoh network; displays as one line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct JoinError(String);

/// Opens a zenoh session with `net`'s settings; the error names the
/// endpoints and says what went wrong, on one line.
pub async fn open(net: &NetConfig) -> Result<Session, JoinError> {
    zenoh::open(net.to_config()?).await.map_err(|e| {
        JoinError(format!(
            "cannot join the zenoh network ({}): {}",
            net.endpoints(),
            describe(&e)
        ))
    })
}

/// A zenoh error's text on one line, without the source locations zenoh
/// appends to every cause (` at /path/to/file.rs:123.`).
pub fn describe(error: &dyn Display) -> String {
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
    out.split_whitespace().collect::<Vec<_>>().join(" ")
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

/// zenoh's runtime setting for the experiment's processes: its five
/// runtimes (app, acc, tx, rx, net) handed over to one, with one worker.
/// A message's callback, the sends it makes and the reads that follow then
/// run on one thread instead of waking one another's (docs/speed.md).
pub const ONE_RUNTIME: &str = "(app: (worker_threads: 1), acc: (handover: app), \
                               tx: (handover: app), rx: (handover: app), net: (handover: app))";

/// Makes zenoh use [`ONE_RUNTIME`] in this process, unless the environment
/// already sets `ZENOH_RUNTIME`. Call early in `main`, while no other
/// thread runs.
pub fn use_one_runtime() {
    if std::env::var_os("ZENOH_RUNTIME").is_none() {
        // SAFETY: no other thread runs yet, so none reads the environment
        // while it changes.
        unsafe { std::env::set_var("ZENOH_RUNTIME", ONE_RUNTIME) };
    }
}

/// A loopback TCP port that was free a moment ago (bound, read, released).
pub fn free_port() -> std::io::Result<u16> {
    let listener = std::net::TcpListener::bind("127.0.0.1:0")?;
    Ok(listener.local_addr()?.port())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_go_on_top_of_a_base_file() {
        let c = NetConfig::loopback_peer(7447, vec!["tcp/127.0.0.1:7000".into()]);
        let config = c.to_config().unwrap();
        let get = |config: &zenoh::Config, key| config.get_json(key).unwrap();
        assert_eq!(
            get(&config, "listen/endpoints"),
            r#"["tcp/127.0.0.1:7447"]"#
        );
        assert_eq!(
            get(&config, "connect/endpoints"),
            r#"["tcp/127.0.0.1:7000"]"#
        );
        assert_eq!(get(&config, "scouting/multicast/enabled"), "false");
        assert_eq!(
            c.endpoints(),
            "listen tcp/127.0.0.1:7447; connect tcp/127.0.0.1:7000"
        );
        assert_eq!(
            NetConfig::peer(Vec::new(), Vec::new()).endpoints(),
            "listen none; connect none"
        );

        let dir = tempfile::tempdir().unwrap();
        let base = dir.path().join("zenoh.json5");
        std::fs::write(
            &base,
            r#"{ listen: { endpoints: ["tcp/127.0.0.1:1"] }, transport: { link: { tls: { enable_mtls: true } } } }"#,
        )
        .unwrap();
        let config = c.clone().with_base(Some(base)).to_config().unwrap();
        assert_eq!(
            get(&config, "listen/endpoints"),
            r#"["tcp/127.0.0.1:7447"]"#
        );
        assert_eq!(get(&config, "transport/link/tls/enable_mtls"), "true");

        let missing = dir.path().join("missing.json5");
        let e = c.with_base(Some(missing.clone())).to_config().unwrap_err();
        assert!(
            e.to_string().starts_with(&format!(
                "invalid zenoh configuration file {}",
                missing.display()
            )),
            "{e}"
        );
    }

    #[test]
    fn source_locations_and_line_breaks_are_left_out() {
        let e = "Can not bind tcp/127.0.0.1:1: [Address in use (os error 98) at /x/zenoh-link-commons-1.10.2/src/tcp.rs:61.] at /y/unicast.rs:338.";
        assert_eq!(
            describe(&e),
            "Can not bind tcp/127.0.0.1:1: [Address in use (os error 98)]"
        );
        let text = "Can not create a new TCP listener bound to tcp/127.0.0.1:7447: \
                    Address in use at /r/zenoh-link-tcp/src/unicast.rs:412.\n - Caused by x at a.rs:3.";
        assert_eq!(
            describe(&text),
            "Can not create a new TCP listener bound to tcp/127.0.0.1:7447: Address in use - Caused by x"
        );
        assert_eq!(describe(&"look at this"), "look at this");
        assert_eq!(describe(&"at /a.rs:1"), "at /a.rs:1");
    }

    #[test]
    fn free_ports_can_be_bound() {
        let port = free_port().unwrap();
        assert_ne!(port, 0);
        std::net::TcpListener::bind(("127.0.0.1", port)).unwrap();
    }

    #[tokio::test(flavor = "multi_thread")]
    async fn only_peers_with_the_secret_can_join() {
        let dir = tempfile::tempdir().unwrap();
        let secret = Secret::create(&dir.path().join("secret")).unwrap();
        let port = free_port().unwrap();
        let host = NetConfig::loopback_peer(port, Vec::new()).with_secret(Some(secret.clone()));
        let _host = open(&host).await.unwrap();
        let guest = NetConfig::loopback_peer(0, vec![format!("tcp/127.0.0.1:{port}")]);
        open(&guest.clone().with_secret(Some(secret)))
            .await
            .unwrap();
        let e = open(&guest).await.unwrap_err().to_string();
        assert!(e.starts_with("cannot join the zenoh network"), "{e}");
        let other = Secret::create(&dir.path().join("other")).unwrap();
        assert!(open(&guest.with_secret(Some(other))).await.is_err());
    }

    #[tokio::test(flavor = "multi_thread")]
    async fn bad_settings_are_one_line_errors() {
        let net = NetConfig::peer(vec!["foo".into()], Vec::new());
        let e = open(&net).await.unwrap_err().to_string();
        assert!(
            e.starts_with("invalid network settings (listen foo; connect none): "),
            "{e}"
        );
        assert!(!e.contains(".rs:") && !e.contains('\n'), "{e}");
    }
}
