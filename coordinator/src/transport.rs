//! Where an experiment's agents and simulator live: one value, recorded in
//! `config.json` with everything that can change results.
//!
//! In a file: `transport = "in-process"`, `transport = "zenoh"` (default
//! timeouts) or `[transport.zenoh]` with `advice_timeout_ms`,
//! `step_timeout_ms`, `stall_limit_ms` and `simulator` (`"real-hfo"`: the
//! real HFO instead of ours). How to reach the processes ([`Endpoints`]) changes no
//! result and is not recorded.

use std::path::PathBuf;
use std::time::Duration;

use proto::Simulator;
use serde::{Deserialize, Serialize};

use crate::error::ConfigError;

/// Where agents and simulator live.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", try_from = "TransportFile")]
#[allow(
    clippy::large_enum_variant,
    reason = "one value per experiment, cloned a few times, never on a hot path"
)]
pub enum Transport {
    /// Simulator and agents as library calls in the run's thread: fast and
    /// bit-for-bit deterministic.
    #[default]
    InProcess,
    /// env-server and every agent as separate processes talking over zenoh.
    Zenoh(ZenohSettings),
}

/// The zenoh transport's settings: its timeouts and simulator (recorded:
/// they change results) and its endpoints (not recorded).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ZenohSettings {
    /// How long an agent waits for advice after asking (ms).
    pub advice_timeout_ms: u64,
    /// How long env-server waits for a kicker's action before Move (ms).
    pub step_timeout_ms: u64,
    /// How long a kicker may send no action, frame after frame, before its
    /// run ends with an error (ms).
    pub stall_limit_ms: u64,
    /// Restart an agent process that dies from its latest snapshot
    /// instead of ending the run, and start again one that dies before
    /// joining (recorded only when on).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub restart_agents: bool,
    /// With `restart_agents`: a snapshot of every agent every this many
    /// training episodes (recorded only when not the default).
    #[serde(
        alias = "checkpoint_every",
        skip_serializing_if = "is_default_snapshot_every"
    )]
    pub snapshot_every: u64,
    /// What env-server plays: our simulator or the real HFO (recorded,
    /// with whether it is deterministic, only when the real HFO).
    #[serde(skip_serializing_if = "is_ours", with = "simulator_record")]
    pub simulator: Simulator,
    /// How to reach the processes.
    #[serde(skip)]
    pub endpoints: Endpoints,
}

impl Default for ZenohSettings {
    fn default() -> Self {
        Self {
            advice_timeout_ms: 5,
            step_timeout_ms: 1000,
            stall_limit_ms: 10_000,
            restart_agents: false,
            snapshot_every: DEFAULT_SNAPSHOT_EVERY,
            simulator: Simulator::Ours,
            endpoints: Endpoints::default(),
        }
    }
}

/// Training episodes between the snapshots of a run whose agents restart.
pub const DEFAULT_SNAPSHOT_EVERY: u64 = 100;

fn is_default_snapshot_every(every: &u64) -> bool {
    *every == DEFAULT_SNAPSHOT_EVERY
}

fn is_ours(simulator: &Simulator) -> bool {
    *simulator == Simulator::Ours
}

/// The simulator as results record it, `{"name": "real-hfo",
/// "deterministic": false}`; files may give the name alone.
mod simulator_record {
    use proto::Simulator;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    #[serde(untagged)]
    enum Record {
        Full {
            name: Simulator,
            deterministic: bool,
        },
        Name(Simulator),
    }

    pub fn serialize<S: Serializer>(name: &Simulator, s: S) -> Result<S::Ok, S::Error> {
        let deterministic = *name == Simulator::Ours;
        Record::Full {
            name: *name,
            deterministic,
        }
        .serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Simulator, D::Error> {
        match Record::deserialize(d)? {
            Record::Full { name, .. } | Record::Name(name) => Ok(name),
        }
    }
}

/// How the coordinator reaches an experiment's processes.
#[derive(Clone, Debug, PartialEq)]
pub struct Endpoints {
    /// Experiment name: the key prefix `adv/<name>` of every message.
    pub experiment: String,
    /// Loopback port the coordinator listens on (0: any free port).
    pub port: u16,
    /// With `attach`, the endpoint the coordinator listens on instead of the
    /// loopback port. Of two peers only one opens their link (see
    /// `node::net::NetConfig::settings`), so every process must be able to
    /// reach this endpoint.
    pub listen: Option<String>,
    /// Endpoints to connect to (a zenoh router for multi-host setups).
    pub connect: Vec<String>,
    /// Drive processes already running instead of starting them.
    pub attach: bool,
    /// Directory of the `env-server` and `agent` executables (default: next
    /// to the coordinator's).
    pub bin_dir: Option<PathBuf>,
    /// How the processes authenticate each other.
    pub auth: Auth,
    /// With `attach`, a zenoh configuration file to start from (TLS,
    /// access control: deploy/tls/).
    pub zenoh_config: Option<PathBuf>,
    /// How long to wait for every process to join.
    pub startup_timeout: Duration,
    /// With the real HFO: where it is built (`env-server serve --real-hfo`).
    pub hfo_dir: Option<PathBuf>,
    /// With the real HFO: its Python interpreter (default: its venv's).
    pub hfo_python: Option<PathBuf>,
}

impl Default for Endpoints {
    fn default() -> Self {
        Self {
            experiment: "adv".to_owned(),
            port: 0,
            listen: None,
            connect: Vec::new(),
            attach: false,
            bin_dir: None,
            auth: Auth::Generated,
            zenoh_config: None,
            startup_timeout: Duration::from_secs(30),
            hfo_dir: None,
            hfo_python: None,
        }
    }
}

/// How an experiment's processes authenticate each other (zenoh's
/// user/password authentication with a shared secret file).
#[derive(Clone, Debug, PartialEq)]
pub enum Auth {
    /// A new secret in a private temporary file, handed to the processes the
    /// coordinator starts (cannot drive attached processes).
    Generated,
    /// The secret in this file, shared with every process.
    File(PathBuf),
    /// None: anyone who can reach the endpoints can join.
    Off,
}

/// The names `--transport` accepts.
pub const TRANSPORT_NAMES: [&str; 2] = ["zenoh", "in-process"];

impl Transport {
    /// The transport named `name` (one of [`TRANSPORT_NAMES`]); `zenoh`
    /// takes `settings`.
    pub fn named(name: &str, settings: ZenohSettings) -> Result<Self, ConfigError> {
        match name {
            "in-process" => Ok(Transport::InProcess),
            "zenoh" => Ok(Transport::Zenoh(settings)),
            other => Err(ConfigError::new(
                "transport",
                format!("unknown transport '{other}', expected in-process or zenoh"),
            )),
        }
    }

    /// The name, one of [`TRANSPORT_NAMES`].
    pub fn name(&self) -> &'static str {
        match self {
            Transport::InProcess => "in-process",
            Transport::Zenoh(_) => "zenoh",
        }
    }

    /// The zenoh settings, over zenoh.
    pub fn zenoh(&self) -> Option<&ZenohSettings> {
        match self {
            Transport::InProcess => None,
            Transport::Zenoh(settings) => Some(settings),
        }
    }

    /// What env-server plays: ours in process.
    pub fn simulator(&self) -> Simulator {
        self.zenoh().map_or(Simulator::Ours, |z| z.simulator)
    }

    /// Whether agents are processes whose messages are counted.
    pub fn communicates(&self) -> bool {
        self.zenoh().is_some()
    }

    /// The same transport for another experiment name (a study's entries
    /// each get their own processes and keys).
    pub fn for_experiment(&self, suffix: &str) -> Self {
        let mut t = self.clone();
        if let Transport::Zenoh(z) = &mut t {
            z.endpoints.experiment = format!("{}-{suffix}", z.endpoints.experiment);
        }
        t
    }

    /// Rejects timeouts outside 1 ms to [`proto::MAX_WAIT_MS`].
    pub fn validate(&self) -> Result<(), ConfigError> {
        let Transport::Zenoh(z) = self else {
            return Ok(());
        };
        for (key, value, range) in [
            (
                "advice_timeout_ms",
                z.advice_timeout_ms,
                1..=proto::MAX_WAIT_MS,
            ),
            ("step_timeout_ms", z.step_timeout_ms, 1..=proto::MAX_WAIT_MS),
            ("snapshot_every", z.snapshot_every, 1..=u64::MAX),
            (
                "stall_limit_ms",
                z.stall_limit_ms,
                z.step_timeout_ms..=proto::MAX_STALL_MS,
            ),
        ] {
            if !range.contains(&value) {
                return Err(ConfigError::new(
                    format!("transport.zenoh.{key}"),
                    format!(
                        "must be {} to {} ms, got {value}",
                        range.start(),
                        range.end()
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// What a file may say: a name, or the zenoh table.
#[derive(Deserialize)]
#[serde(untagged)]
#[allow(
    clippy::large_enum_variant,
    reason = "read once per file, straight into a `Transport`"
)]
enum TransportFile {
    Name(String),
    Zenoh { zenoh: ZenohSettings },
}

impl TryFrom<TransportFile> for Transport {
    type Error = ConfigError;

    fn try_from(file: TransportFile) -> Result<Self, ConfigError> {
        match file {
            TransportFile::Name(name) => Transport::named(&name, ZenohSettings::default()),
            TransportFile::Zenoh { zenoh } => Ok(Transport::Zenoh(zenoh)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize)]
    struct File {
        transport: Transport,
    }

    fn parse(toml_text: &str) -> Result<Transport, String> {
        toml::from_str::<File>(toml_text)
            .map(|f| f.transport)
            .map_err(|e| e.to_string())
    }

    #[test]
    fn files_name_or_configure_the_transport() {
        assert_eq!(
            parse("transport = \"in-process\"").unwrap(),
            Transport::InProcess
        );
        assert_eq!(
            parse("transport = \"zenoh\"").unwrap(),
            Transport::Zenoh(ZenohSettings::default())
        );
        let t = parse("[transport.zenoh]\nadvice_timeout_ms = 9\n").unwrap();
        let Transport::Zenoh(z) = t else {
            panic!("zenoh expected")
        };
        assert_eq!((z.advice_timeout_ms, z.step_timeout_ms), (9, 1000));
        assert!(parse("transport = \"pigeon\"").is_err());
    }

    #[test]
    fn the_record_holds_timeouts_not_endpoints() {
        let mut z = ZenohSettings::default();
        z.endpoints.port = 7447;
        let json = serde_json::to_value(Transport::Zenoh(z)).unwrap();
        assert_eq!(
            json,
            serde_json::json!({"zenoh": {
                "advice_timeout_ms": 5,
                "step_timeout_ms": 1000,
                "stall_limit_ms": 10000
            }})
        );
        assert_eq!(
            serde_json::to_value(Transport::InProcess).unwrap(),
            serde_json::json!("in-process")
        );
        let back: Transport = serde_json::from_value(json).unwrap();
        assert_eq!(back, Transport::Zenoh(ZenohSettings::default()));
    }

    #[test]
    fn the_real_hfo_is_recorded_as_not_deterministic() {
        let t = parse("[transport.zenoh]\nsimulator = \"real-hfo\"\n").unwrap();
        assert_eq!(t.zenoh().unwrap().simulator, Simulator::RealHfo);
        let json = serde_json::to_value(&t).unwrap();
        assert_eq!(
            json["zenoh"]["simulator"],
            serde_json::json!({"name": "real-hfo", "deterministic": false})
        );
        let back: Transport = serde_json::from_value(json).unwrap();
        assert_eq!(back, t);
        assert!(parse("[transport.zenoh]\nsimulator = \"rcssserver\"\n").is_err());
    }

    #[test]
    fn zero_timeouts_are_refused() {
        let t = Transport::Zenoh(ZenohSettings {
            step_timeout_ms: 0,
            ..ZenohSettings::default()
        });
        assert_eq!(
            t.validate().unwrap_err().key,
            "transport.zenoh.step_timeout_ms"
        );
    }
}
