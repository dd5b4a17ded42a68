//! A study: several experiments of one protocol, from a preset or a TOML file.

use std::path::Path;

use agent::{Strategy, StrategyName};
use serde::{Deserialize, Serialize};

use crate::config::{AgentSpec, DEFAULT_CI_LEVEL, ExperimentConfig};
use crate::error::ConfigError;
use crate::transport::Transport;

/// The presets shipped with the project (`coordinator/presets/*.toml`).
pub const PRESETS: [(&str, &str); 4] = [
    ("quick", include_str!("../../presets/quick.toml")),
    (
        "paper-scratch",
        include_str!("../../presets/paper-scratch.toml"),
    ),
    (
        "paper-mistake-correcting",
        include_str!("../../presets/paper-mistake-correcting.toml"),
    ),
    (
        "paper-expert",
        include_str!("../../presets/paper-expert.toml"),
    ),
];

/// What a study runs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyConfig {
    /// Short name.
    pub name: String,
    /// One line on what it reproduces.
    #[serde(default)]
    pub description: String,
    /// Runs R of every experiment.
    pub runs: u64,
    /// Training episodes N per run.
    pub episodes: u64,
    /// Evaluation every K training episodes.
    pub eval_every: u64,
    /// Episodes M per evaluation.
    pub eval_episodes: u64,
    /// Study seed; every experiment uses it (runs are paired across algorithms).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Where agents and simulator live.
    #[serde(default)]
    pub transport: Transport,
    /// Confidence level of intervals and tests.
    #[serde(default = "default_ci_level")]
    pub ci_level: f64,
    /// The entry every other is compared with in the report.
    #[serde(default)]
    pub baseline: Option<String>,
    /// A pretraining stage that produces an expert agent.
    #[serde(default)]
    pub pretrain: Option<Pretrain>,
    /// The experiments.
    #[serde(rename = "entry")]
    pub entries: Vec<Entry>,
}

fn default_seed() -> u64 {
    1
}

fn default_ci_level() -> f64 {
    DEFAULT_CI_LEVEL
}

/// Pretraining: one run of a homogeneous team whose agent `expert` is saved.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pretrain {
    /// The pretraining team's algorithm.
    pub algorithm: StrategyName,
    /// Training episodes.
    pub episodes: u64,
    /// Index of the agent saved as the expert.
    pub expert: usize,
}

/// One experiment of the study.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    /// Name: the experiment's directory and its label in figures.
    pub name: String,
    /// The team's algorithm.
    pub algorithm: StrategyName,
    /// Advisees send their intended action along.
    #[serde(default)]
    pub mistake_correcting: bool,
    /// The pretraining's expert replaces agent `pretrain.expert`: it starts
    /// from the expert's tables and never asks.
    #[serde(default)]
    pub expert: bool,
}

/// Team size of every study (the paper's 3 offense agents).
const TEAM: usize = 3;

impl StudyConfig {
    /// The preset `name`.
    pub fn preset(name: &str) -> Result<Self, ConfigError> {
        let (_, text) = PRESETS.iter().find(|(n, _)| *n == name).ok_or_else(|| {
            let names: Vec<&str> = PRESETS.iter().map(|(n, _)| *n).collect();
            ConfigError::new(
                "preset",
                format!(
                    "unknown preset '{name}' (expected one of: {})",
                    names.join(", ")
                ),
            )
        })?;
        Self::parse(text, name)
    }

    /// A study file.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            ConfigError::new("config", format!("cannot read {}: {e}", path.display()))
        })?;
        Self::parse(&text, &path.display().to_string())
    }

    fn parse(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let config: Self = toml::from_str(text)
            .map_err(|e| ConfigError::new("config", format!("{origin}: {}", e.message())))?;
        Ok(config)
    }

    /// Checks every setting and every experiment, naming the first bad key.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.episodes == 0 {
            return Err(ConfigError::new("episodes", "must be at least 1, got 0"));
        }
        if self.eval_every > self.episodes {
            return Err(ConfigError::new(
                "eval_every",
                format!(
                    "must not exceed episodes ({}), got {}",
                    self.episodes, self.eval_every
                ),
            ));
        }
        if self.entries.is_empty() {
            return Err(ConfigError::new(
                "entry",
                "a study needs at least one [[entry]]",
            ));
        }
        for (i, e) in self.entries.iter().enumerate() {
            if self.entries[..i].iter().any(|o| o.name == e.name) {
                return Err(ConfigError::new(
                    format!("entry[{i}].name"),
                    format!("'{}' appears twice", e.name),
                ));
            }
            let ok = !e.name.is_empty()
                && e.name
                    .bytes()
                    .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_');
            if !ok {
                return Err(ConfigError::new(
                    format!("entry[{i}].name"),
                    "use letters, digits, '-' and '_'",
                ));
            }
            e.strategy()
                .map_err(|err| ConfigError::new(format!("entry[{i}].{}", err.key), err.reason))?;
            if e.expert && self.pretrain.is_none() {
                return Err(ConfigError::new(
                    format!("entry[{i}].expert"),
                    "needs a [pretrain] stage",
                ));
            }
            self.experiment(e, None)
                .validate()
                .map_err(|err| ConfigError::new(format!("entry[{i}].{}", err.key), err.reason))?;
        }
        if let Some(b) = &self.baseline
            && self.entries.iter().all(|e| &e.name != b)
        {
            return Err(ConfigError::new(
                "baseline",
                format!("no entry is named '{b}'"),
            ));
        }
        if let Some(p) = &self.pretrain {
            if p.expert >= TEAM {
                return Err(ConfigError::new(
                    "pretrain.expert",
                    format!("must be below the team size {TEAM}, got {}", p.expert),
                ));
            }
            if p.episodes == 0 {
                return Err(ConfigError::new("pretrain.episodes", "must be at least 1"));
            }
        }
        Ok(())
    }

    /// The experiment of `entry`; `expert` is the pretrained snapshot when it has one.
    pub fn experiment(&self, entry: &Entry, expert: Option<&Path>) -> ExperimentConfig {
        let mut spec = AgentSpec::of(entry.algorithm);
        // `validate` rejects Mistake Correcting where the strategy has no such mode.
        if let Ok(strategy) = entry.strategy() {
            spec.config.strategy = strategy;
        }
        let mut team = vec![spec; TEAM];
        if let (true, Some(p)) = (entry.expert, &self.pretrain) {
            let agent = &mut team[p.expert];
            if let Strategy::AdHoc(a) = &mut agent.config.strategy {
                a.ask_budget = 0;
            }
            agent.load = expert
                .map(Path::to_path_buf)
                .or_else(|| Some("expert.qtable".into()));
        }
        ExperimentConfig {
            runs: self.runs,
            episodes: self.episodes,
            eval_every: self.eval_every,
            eval_episodes: self.eval_episodes,
            seed: self.seed,
            ci_level: self.ci_level,
            transport: self.transport.clone(),
            team,
            ..ExperimentConfig::default()
        }
    }

    /// The pretraining experiment: one run, evaluated only at its start and end.
    pub fn pretraining(&self, p: &Pretrain) -> ExperimentConfig {
        ExperimentConfig {
            runs: 1,
            episodes: p.episodes,
            eval_every: p.episodes,
            eval_episodes: self.eval_episodes,
            seed: self.seed,
            ci_level: self.ci_level,
            transport: self.transport.clone(),
            team: vec![AgentSpec::of(p.algorithm); TEAM],
            ..ExperimentConfig::default()
        }
    }
}

impl Entry {
    /// The team's strategy: the paper's constants, with Mistake Correcting
    /// when asked for (an error for a strategy without that mode).
    pub fn strategy(&self) -> Result<Strategy, agent::ConfigError> {
        let mut strategy = Strategy::from(self.algorithm);
        strategy.set_mistake_correcting(self.mistake_correcting)?;
        Ok(strategy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_parse_and_validate() {
        for (name, _) in PRESETS {
            let s = StudyConfig::preset(name).unwrap();
            s.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(s.name, name);
        }
        let paper = StudyConfig::preset("paper-scratch").unwrap();
        assert_eq!(
            (
                paper.runs,
                paper.episodes,
                paper.eval_every,
                paper.eval_episodes
            ),
            (50, 5000, 20, 100)
        );
        assert_eq!(paper.entries.len(), 6);
    }

    #[test]
    fn bad_studies_name_the_key() {
        let err = |text: &str| {
            StudyConfig::parse(text, "t")
                .and_then(|s| s.validate())
                .unwrap_err()
                .to_string()
        };
        let base = "name = \"t\"\nruns = 2\nepisodes = 100\neval_every = 20\neval_episodes = 10\n";
        assert!(
            err(&format!(
                "{base}colour = 1\n[[entry]]\nname = \"a\"\nalgorithm = \"no-advice\"\n"
            ))
            .contains("colour")
        );
        let zero = base.replace("runs = 2", "runs = 0");
        assert!(
            err(&format!(
                "{zero}[[entry]]\nname = \"a\"\nalgorithm = \"no-advice\"\n"
            ))
            .contains("runs")
        );
        let wide = base.replace("eval_every = 20", "eval_every = 200");
        assert!(
            err(&format!(
                "{wide}[[entry]]\nname = \"a\"\nalgorithm = \"no-advice\"\n"
            ))
            .contains("eval_every")
        );
        assert!(
            err(&format!(
                "{base}[[entry]]\nname = \"a\"\nalgorithm = \"best\"\n"
            ))
            .contains("best")
        );
        assert!(err(base).contains("entry"));
        let mc = err(&format!(
            "{base}[[entry]]\nname = \"a\"\nalgorithm = \"no-advice\"\nmistake_correcting = true\n"
        ));
        assert!(mc.contains("entry[0].mistake_correcting"), "{mc}");
        assert!(
            err(&format!(
                "{base}[[entry]]\nname = \"a\"\nalgorithm = \"ad-hoc-td\"\n\n[[entry]]\nname = \"a\"\nalgorithm = \"adhoc-td\"\n"
            ))
            .contains("appears twice"),
            "the old spelling still reads"
        );
        assert!(
            StudyConfig::preset("paper-everything")
                .unwrap_err()
                .to_string()
                .contains("quick")
        );
    }
}
