//! One agent of an experiment as files and `config.json` write it: its
//! configuration, the snapshot it starts from, and its learner and strategy
//! processes.

use std::path::{Path, PathBuf};

use agent::{AgentConfig, Algorithm, Profile};
use serde::{Deserialize, Serialize};

use crate::plugin::PluginSpec;

/// One agent of the team: its configuration (with its strategy) and,
/// optionally, a saved snapshot it starts from.
///
/// In a file it is one flat table: every [`AgentConfig`] key, plus `load`
/// (path of a snapshot), `keep_counters`, `learner`, `strategy_process` and
/// `plugin` (recorded, never read from a file).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "serde_json::Map<String, serde_json::Value>")]
#[serde(into = "serde_json::Map<String, serde_json::Value>")]
pub struct AgentSpec {
    /// Its settings: learner, algorithm, fidelity rules, network conditions.
    pub config: AgentConfig,
    /// A snapshot (see `agent::Snapshot`) the agent starts every run from.
    pub load: Option<PathBuf>,
    /// Keep the snapshot's communication counters (spent budgets). By default
    /// they start at zero: the loaded agent brings its Q-table, visit counts
    /// and finished-episode count, with fresh budgets.
    pub keep_counters: bool,
    /// A learner process in place of the agent's own learner
    /// (docs/learners.md).
    pub learner: Option<ChildSpec>,
    /// A strategy process making algorithm `external`'s decisions
    /// (docs/strategies.md).
    pub strategy_process: Option<ChildSpec>,
    /// A learner or strategy given as an object in process
    /// ([`crate::plugin`]): what the results record of it.
    pub plugin: Option<PluginSpec>,
}

/// A learner or a strategy that runs as a child of its agent's
/// process: the command, where it runs, and what it is made of, so that
/// results stay attributable.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChildSpec {
    /// Program and arguments, e.g. `["python3", "my_learner.py"]`.
    pub command: Vec<String>,
    /// Its working directory: the team file's, unless given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dir: Option<PathBuf>,
    /// Its source file, whose digest is recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<PathBuf>,
    /// FNV-1a (64-bit, hex) of `source`'s bytes when the team was read.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source_fnv64: Option<String>,
}

impl ChildSpec {
    /// Resolves `dir` and `source` from `base` (the team file's directory)
    /// and records the source's digest; `key` names it in errors.
    pub(crate) fn resolve(&mut self, base: &Path, key: &str) -> Result<(), String> {
        if self.command.is_empty() {
            return Err(format!(
                "`{key}.command` must name a program, e.g. [\"python3\", \"{key}.py\"]"
            ));
        }
        let dir = base.join(self.dir.take().unwrap_or_default());
        if let Some(source) = &self.source {
            let path = dir.join(source);
            let bytes = std::fs::read(&path)
                .map_err(|e| format!("cannot read {key}.source {}: {e}", path.display()))?;
            self.source_fnv64 = Some(format!("{:016x}", fnv64(&bytes)));
        }
        // A team file in the current directory: the learner runs there too.
        self.dir = (!dir.as_os_str().is_empty()).then_some(dir);
        Ok(())
    }
}

/// FNV-1a, 64 bits.
pub(crate) fn fnv64(bytes: &[u8]) -> u64 {
    use std::hash::Hasher;
    let mut hasher = fnv::FnvHasher::default();
    hasher.write(bytes);
    hasher.finish()
}

impl TryFrom<serde_json::Map<String, serde_json::Value>> for AgentSpec {
    type Error = String;

    fn try_from(mut map: serde_json::Map<String, serde_json::Value>) -> Result<Self, String> {
        let load = match map.remove("load") {
            None | Some(serde_json::Value::Null) => None,
            Some(serde_json::Value::String(s)) => Some(PathBuf::from(s)),
            Some(other) => return Err(format!("`load` must be a path string, got {other}")),
        };
        let keep_counters = match map.remove("keep_counters") {
            None => false,
            Some(serde_json::Value::Bool(b)) => b,
            Some(other) => return Err(format!("`keep_counters` must be a boolean, got {other}")),
        };
        // `learner` names a learner of the agent's own (its settings), or
        // is a table: a learner process.
        let named = matches!(map.get("learner"), Some(serde_json::Value::String(_)));
        let mut child = |key: &str| match map.remove(key) {
            None | Some(serde_json::Value::Null) => Ok(None),
            Some(value) => serde_json::from_value(value).map(Some).map_err(|e| {
                format!(
                    "`{key}` must be a table with `command` (and optionally `dir`, `source`): {e}"
                )
            }),
        };
        let learner = if named { None } else { child("learner")? };
        let strategy_process = child("strategy_process")?;
        let plugin =
            match map.remove("plugin") {
                None | Some(serde_json::Value::Null) => None,
                Some(value) => Some(serde_json::from_value(value).map_err(|e| {
                    format!("`plugin` must be a table of `learner`, `strategy`: {e}")
                })?),
            };
        let config = serde_json::from_value(serde_json::Value::Object(map))
            .map_err(|e| format!("agent config: {e}"))?;
        Ok(Self {
            config,
            load,
            keep_counters,
            learner,
            strategy_process,
            plugin,
        })
    }
}

impl From<AgentSpec> for serde_json::Map<String, serde_json::Value> {
    fn from(spec: AgentSpec) -> Self {
        let mut map = match serde_json::to_value(&spec.config) {
            Ok(serde_json::Value::Object(map)) => map,
            _ => unreachable!("an agent config serialises to a JSON object"),
        };
        if let Some(path) = spec.load {
            map.insert(
                "load".into(),
                serde_json::Value::String(path.to_string_lossy().into_owned()),
            );
        }
        if spec.keep_counters {
            map.insert("keep_counters".into(), serde_json::Value::Bool(true));
        }
        for (key, child) in [
            ("learner", spec.learner),
            ("strategy_process", spec.strategy_process),
        ] {
            // A learner process stands in for the learner the settings name.
            if let Some(child) = child {
                let child = serde_json::to_value(child).expect("a child spec serialises");
                map.insert(key.into(), child);
            }
        }
        if let Some(plugin) = spec.plugin {
            let plugin = serde_json::to_value(plugin).expect("a plugin spec serialises");
            map.insert("plugin".into(), plugin);
        }
        map
    }
}

impl AgentSpec {
    /// Takes its relative paths (`load`, its child processes') from `base`,
    /// a team file's directory; the error names the key.
    pub(crate) fn resolve(&mut self, base: &Path) -> Result<(), (&'static str, String)> {
        if let Some(load) = &self.load
            && load.is_relative()
        {
            self.load = Some(base.join(load));
        }
        for (key, child) in [
            ("learner", &mut self.learner),
            ("strategy_process", &mut self.strategy_process),
        ] {
            if let Some(child) = child {
                child.resolve(base, key).map_err(|reason| (key, reason))?;
            }
        }
        Ok(())
    }

    /// An agent running `algorithm` from scratch with the constants and
    /// fidelity settings of `profile`.
    pub fn of(algorithm: Algorithm, profile: Profile) -> Self {
        Self {
            config: AgentConfig::of(algorithm, profile),
            ..Self::default()
        }
    }
}
