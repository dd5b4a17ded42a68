//! A study: several experiments of one protocol, from a preset or a TOML file.

use std::collections::BTreeMap;
use std::path::Path;

use agent::{Advises, AgentConfig, Algorithm, Profile};
use env_server::EvaluationMemory;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::config::{AgentSpec, EPISODES, ExperimentConfig, check_range};
use crate::error::ConfigError;
use crate::membership::MembershipEvent;
use crate::transport::Transport;

/// The presets shipped with the project (`coordinator/presets/*.toml`).
pub const PRESETS: [(&str, &str); 18] = [
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
    (
        "fidelity-sensitivity",
        include_str!("../../presets/fidelity-sensitivity.toml"),
    ),
    (
        "advice-network",
        include_str!("../../presets/advice-network.toml"),
    ),
    (
        "advising-methods",
        include_str!("../../presets/advising-methods.toml"),
    ),
    ("newcomer", include_str!("../../presets/newcomer.toml")),
    ("untrusted", include_str!("../../presets/untrusted.toml")),
    ("real-hfo", include_str!("../../presets/real-hfo.toml")),
    ("frontier", include_str!("../../presets/frontier.toml")),
    (
        "frontier-announced",
        include_str!("../../presets/frontier-announced.toml"),
    ),
    (
        "methods-expert",
        include_str!("../../presets/methods-expert.toml"),
    ),
    (
        "methods-mistake-correcting",
        include_str!("../../presets/methods-mistake-correcting.toml"),
    ),
    (
        "methods-sensitivity",
        include_str!("../../presets/methods-sensitivity.toml"),
    ),
    ("neural", include_str!("../../presets/neural.toml")),
    (
        "deep-advising",
        include_str!("../../presets/deep-advising.toml"),
    ),
    (
        "deep-advising-expert",
        include_str!("../../presets/deep-advising-expert.toml"),
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
    /// The fidelity profile of every agent (entries may change single
    /// settings) and the default confidence level.
    #[serde(default)]
    pub profile: Profile,
    /// Confidence level of intervals and tests (default: the profile's).
    #[serde(default)]
    pub ci_level: Option<f64>,
    /// The entry every other is compared with in the report, unless it
    /// names its own.
    #[serde(default)]
    pub baseline: Option<String>,
    /// What the agents of each evaluation block's simulator remember at
    /// its start (docs/fidelity.md, item 9).
    #[serde(default)]
    pub evaluation_memory: EvaluationMemory,
    /// A pretraining stage that produces an expert agent.
    #[serde(default)]
    pub pretrain: Option<Pretrain>,
    /// The experiments.
    #[serde(rename = "entry")]
    pub entries: Vec<StudyEntry>,
}

fn default_seed() -> u64 {
    1
}

/// Pretraining: one run of a homogeneous team whose agent `expert` is saved.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pretrain {
    /// The pretraining team's algorithm.
    pub algorithm: Algorithm,
    /// Training episodes.
    pub episodes: u64,
    /// Index of the agent saved as the expert.
    pub expert: usize,
    /// Its agents' settings beyond the study profile's defaults, as an
    /// entry's (any key of a team file's `[[agent]]` table). With a
    /// `learner`, the expert keeps that learner in every entry, whatever
    /// the entry's agents learn with.
    #[serde(flatten)]
    pub settings: Map<String, Value>,
}

/// One experiment of the study.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StudyEntry {
    /// Name: the experiment's directory and its label in figures (default:
    /// its algorithm's name, unless another entry has that name).
    #[serde(default)]
    pub name: String,
    /// The team's algorithm.
    pub algorithm: Algorithm,
    /// The pretraining's expert replaces agent `pretrain.expert`: it starts
    /// from the expert's snapshot with an ask budget of 0 (Torrey's student,
    /// which has none, shows its states to its teacher as the authors'
    /// expert does).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub expert: bool,
    /// Newcomers taking slots during training (`[[entry.event]]`, as a
    /// team file's `[[event]]`).
    #[serde(default, rename = "event", skip_serializing_if = "Vec::is_empty")]
    pub events: Vec<MembershipEvent>,
    /// What each agent answers as an advisor, by slot (none: all honest).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub advises: Vec<Advises>,
    /// Settings swept: each key (a team file's, `network.loss` for a key
    /// of a table) with its values; the entry stands for one entry per
    /// value, all keys' `k`-th values together (read, then expanded).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sweep: BTreeMap<String, Vec<Value>>,
    /// The entry a swept entry was expanded from: its group in the
    /// frontier (default: its own name).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// The entry it is compared with (default: the study's baseline).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub baseline: Option<String>,
    /// The agents' settings beyond the study profile's defaults: any key of
    /// a team file's `[[agent]]` table (`v_g`, `mistake_correcting`,
    /// `network`, `ask_budget`, a fidelity rule...).
    #[serde(flatten)]
    pub settings: Map<String, Value>,
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
        let mut config: Self = toml::from_str(text).map_err(|e| {
            let e = crate::config::toml_error(text, &e);
            ConfigError::new("config", format!("{origin}: {e}"))
        })?;
        config.ci_level = Some(config.ci_level());
        let entries = std::mem::take(&mut config.entries);
        for (i, entry) in entries.into_iter().enumerate() {
            config.entries.extend(entry.expand(i)?);
        }
        config.name_entries()?;
        Ok(config)
    }

    /// Names each entry without a name after its algorithm, unless another
    /// entry has or would take that name.
    fn name_entries(&mut self) -> Result<(), ConfigError> {
        for i in 0..self.entries.len() {
            if !self.entries[i].name.is_empty() {
                continue;
            }
            let name = self.entries[i].algorithm.name();
            let taken = (self.entries.iter().enumerate()).find(|(j, e)| {
                *j != i && (e.name == name || e.name.is_empty() && e.algorithm.name() == name)
            });
            if let Some((j, _)) = taken {
                return Err(ConfigError::new(
                    format!("entry[{i}].name"),
                    format!(
                        "missing, and its algorithm's name `{name}` would be entry[{j}]'s too: \
                         give each a name"
                    ),
                ));
            }
            self.entries[i].name = name.to_owned();
        }
        Ok(())
    }

    /// The study as `study.json` records it.
    pub fn json(&self) -> serde_json::Value {
        serde_json::to_value(self).expect("a study serialises")
    }

    /// The study as the analysis reads it from `study.json`.
    pub fn record(&self) -> analysis::Study {
        serde_json::from_value(self.json()).expect("the analysis reads every study's record")
    }

    /// The confidence level: as given, else the profile's.
    pub fn ci_level(&self) -> f64 {
        self.ci_level.unwrap_or(self.profile.ci_level())
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
        if let Some(p) = &self.pretrain {
            if p.expert >= TEAM {
                return Err(ConfigError::new(
                    "pretrain.expert",
                    format!("must be below the team size {TEAM}, got {}", p.expert),
                ));
            }
            check_range("pretrain.episodes", p.episodes, 1..=*EPISODES.end())?;
            agent_config(p.algorithm, &p.settings, self.profile)
                .and_then(|config| config.validate())
                .map_err(|err| ConfigError::new(format!("pretrain.{}", err.key), err.reason))?;
        }
        for (i, e) in self.entries.iter().enumerate() {
            if self.entries[..i].iter().any(|o| o.name == e.name) {
                return Err(ConfigError::new(
                    format!("entry[{i}].name"),
                    format!("'{}' appears twice", e.name),
                ));
            }
            let ok = !e.name.is_empty()
                && !e.name.starts_with('.')
                && (e.name.bytes()).all(|b| b.is_ascii_alphanumeric() || b"-_.".contains(&b));
            if !ok {
                return Err(ConfigError::new(
                    format!("entry[{i}].name"),
                    "use letters, digits, '-', '_' and '.' (not first)",
                ));
            }
            e.config(self.profile)
                .map_err(|err| ConfigError::new(format!("entry[{i}].{}", err.key), err.reason))?;
            if !e.advises.is_empty() && e.advises.len() != TEAM {
                return Err(ConfigError::new(
                    format!("entry[{i}].advises"),
                    format!("one behaviour per agent: {TEAM}, got {}", e.advises.len()),
                ));
            }
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
        (self.record().check_baselines()).map_err(|e| ConfigError::new(e.key, e.reason))?;
        Ok(())
    }

    /// The experiment of `entry`; `expert` is the pretrained snapshot when it has one.
    pub fn experiment(&self, entry: &StudyEntry, expert: Option<&Path>) -> ExperimentConfig {
        let mut spec = AgentSpec::of(entry.algorithm, self.profile);
        // `validate` rejects the keys the algorithm does not have.
        if let Ok(config) = entry.config(self.profile) {
            spec.config = config;
        }
        let mut team = vec![spec; TEAM];
        for (agent, &advises) in team.iter_mut().zip(&entry.advises) {
            agent.config.advises = advises;
        }
        if let (true, Some(p)) = (entry.expert, &self.pretrain) {
            let agent = &mut team[p.expert];
            if p.settings.contains_key("learner") {
                agent.config.learner = self.pretrained(p).config.learner;
            }
            // The expert asks nothing in a method with an ask budget; Torrey's
            // student has none and shows its states, as the authors' expert.
            if agent.config.algorithm.setting("ask_budget").is_some() {
                (agent.config.algorithm)
                    .set("ask_budget", 0)
                    .expect("an ask budget takes 0");
            }
            agent.load = expert
                .map(Path::to_path_buf)
                .or_else(|| Some("expert.snapshot".into()));
        }
        let mut config = ExperimentConfig {
            runs: self.runs,
            episodes: self.episodes,
            eval_every: self.eval_every,
            eval_episodes: self.eval_episodes,
            seed: self.seed,
            ci_level: self.ci_level(),
            transport: self.transport.clone(),
            team,
            events: entry.events.clone(),
            ..ExperimentConfig::default()
        };
        config.env.evaluation_memory = self.evaluation_memory;
        config
    }

    /// An agent of the pretraining team (its settings checked by `validate`).
    fn pretrained(&self, p: &Pretrain) -> AgentSpec {
        let mut spec = AgentSpec::of(p.algorithm, self.profile);
        if let Ok(config) = agent_config(p.algorithm, &p.settings, self.profile) {
            spec.config = config;
        }
        spec
    }

    /// The pretraining experiment: one run, evaluated only at its start and end.
    pub fn pretraining(&self, p: &Pretrain) -> ExperimentConfig {
        let mut config = ExperimentConfig {
            runs: 1,
            episodes: p.episodes,
            eval_every: p.episodes,
            eval_episodes: self.eval_episodes,
            seed: self.seed,
            ci_level: self.ci_level(),
            transport: self.transport.clone(),
            team: vec![self.pretrained(p); TEAM],
            ..ExperimentConfig::default()
        };
        config.env.evaluation_memory = self.evaluation_memory;
        config
    }
}

/// The configuration of an agent of `algorithm` under `profile`'s
/// defaults with `settings` (an error naming a key the algorithm does not
/// have). A key whose value is null is not given.
fn agent_config(
    algorithm: Algorithm,
    settings: &Map<String, Value>,
    profile: Profile,
) -> Result<AgentConfig, agent::AgentConfigError> {
    let mut table = Map::new();
    table.insert("algorithm".into(), algorithm.name().into());
    table.insert("profile".into(), profile.name().into());
    for (key, value) in settings.iter().filter(|(_, v)| !v.is_null()) {
        table.insert(key.clone(), value.clone());
    }
    AgentConfig::from_table(table)
}

impl StudyEntry {
    /// Its agents' configuration: the defaults of `profile` for its
    /// algorithm, with the entry's own keys (an error naming a key the
    /// algorithm does not have). A key whose value is null is not given.
    pub fn config(&self, profile: Profile) -> Result<AgentConfig, agent::AgentConfigError> {
        agent_config(self.algorithm, &self.settings, profile)
    }

    /// The entries this one stands for: itself, or one per swept value.
    fn expand(self, i: usize) -> Result<Vec<StudyEntry>, ConfigError> {
        if self.sweep.is_empty() {
            return Ok(vec![self]);
        }
        let bad =
            |key: &str, reason: String| ConfigError::new(format!("entry[{i}].sweep.{key}"), reason);
        let count = self.sweep.values().map(Vec::len).max().unwrap_or(0);
        for (key, values) in &self.sweep {
            if values.is_empty() {
                return Err(bad(
                    key,
                    "an empty list of values: give at least one".into(),
                ));
            }
            if values.len() != count {
                return Err(bad(
                    key,
                    format!(
                        "{} values, where another swept key has {count}: keys swept together need as many",
                        values.len()
                    ),
                ));
            }
            if let Some(v) = values.iter().find(|v| v.is_null() || v.is_array()) {
                return Err(bad(
                    key,
                    format!("{v} is not a value (a finite number, a string, a table)"),
                ));
            }
        }
        let base = if self.name.is_empty() {
            self.algorithm.name().to_owned()
        } else {
            self.name.clone()
        };
        (0..count)
            .map(|k| {
                let mut entry = StudyEntry {
                    sweep: BTreeMap::new(),
                    group: Some(self.group.clone().unwrap_or_else(|| base.clone())),
                    ..self.clone()
                };
                let mut name = base.clone();
                for (key, values) in &self.sweep {
                    set_path(&mut entry.settings, key, values[k].clone());
                    name.push_str(&format!(
                        "-{}-{}",
                        key.replace('.', "_"),
                        value_name(&values[k])
                    ));
                }
                entry.name = name;
                Ok(entry)
            })
            .collect()
    }
}

/// Sets `key` (a dotted path into tables) of `settings` to `value`.
fn set_path(settings: &mut Map<String, Value>, key: &str, value: Value) {
    match key.split_once('.') {
        None => {
            settings.insert(key.to_owned(), value);
        }
        Some((first, rest)) => {
            let inner = settings
                .entry(first.to_owned())
                .or_insert_with(|| Value::Object(Map::new()));
            if !inner.is_object() {
                *inner = Value::Object(Map::new());
            }
            if let Value::Object(map) = inner {
                set_path(map, rest, value);
            }
        }
    }
}

/// A swept value as part of an entry's name: its text, without what a
/// directory name should not hold.
fn value_name(value: &Value) -> String {
    let text = match value {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use agent::{Fidelity, TorreyUnknownState};

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
    fn the_profile_reaches_every_agent_and_entries_change_single_settings() {
        let study = StudyConfig::preset("fidelity-sensitivity").unwrap();
        assert_eq!((study.profile, study.ci_level()), (Profile::Authors, 0.9));
        let team = |name: &str| {
            let entry = study.entries.iter().find(|e| e.name == name).unwrap();
            study.experiment(entry, None).team
        };
        let torrey = &team("torrey")[0].config;
        assert_eq!(torrey.fidelity, Fidelity::of(Profile::Authors));
        let silent = &team("torrey-unknown-silent")[2].config;
        assert_eq!(
            silent.fidelity,
            Fidelity {
                torrey_unknown_state: TorreyUnknownState::Silent,
                ..Fidelity::of(Profile::Authors)
            }
        );
        let v_g = |name: &str| team(name)[1].config.algorithm.setting("v_g").unwrap();
        assert_eq!(
            (v_g("adhoc-visit"), v_g("adhoc-visit-vg-0-5")),
            (0.2.into(), 0.5.into())
        );
        // The paper presets follow the authors; the quick one the paper.
        for name in ["paper-scratch", "paper-mistake-correcting", "paper-expert"] {
            assert_eq!(StudyConfig::preset(name).unwrap().profile, Profile::Authors);
        }
        let quick = StudyConfig::preset("quick").unwrap();
        assert_eq!((quick.profile, quick.ci_level()), (Profile::Paper, 0.95));
    }

    #[test]
    fn a_sweep_stands_for_one_entry_per_value() {
        let base = "name = \"t\"\nruns = 2\nepisodes = 100\neval_every = 20\neval_episodes = 10\n";
        let text = format!(
            "{base}[[entry]]\nalgorithm = \"early-advising\"\nsweep = {{ ask_budget = [10, 100], give_budget = [10, 100] }}\n\
             [[entry]]\nname = \"lossy\"\nalgorithm = \"adhoc-td\"\nsweep = {{ \"network.loss\" = [0.25] }}\n"
        );
        let study = StudyConfig::parse(&text, "t").unwrap();
        study.validate().unwrap();
        let names: Vec<&str> = study.entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "early-advising-ask_budget-10-give_budget-10",
                "early-advising-ask_budget-100-give_budget-100",
                "lossy-network_loss-0.25"
            ]
        );
        let budget = |i: usize| {
            let config = study.entries[i].config(Profile::Paper).unwrap();
            (
                config.algorithm.setting("ask_budget"),
                config.algorithm.setting("give_budget"),
            )
        };
        assert_eq!(budget(1), (Some(100.into()), Some(100.into())));
        assert_eq!(study.entries[0].group.as_deref(), Some("early-advising"));
        let lossy = study.entries[2].config(Profile::Paper).unwrap();
        assert_eq!(lossy.network.unwrap().loss, 0.25);
        // What study.json records reads back as the same study, not swept again.
        let again: StudyConfig = serde_json::from_value(study.json()).unwrap();
        assert_eq!(again.entries, study.entries);

        let err = |sweep: &str| {
            let text = format!("{base}[[entry]]\nalgorithm = \"torrey\"\nsweep = {sweep}\n");
            StudyConfig::parse(&text, "t")
                .and_then(|s| s.validate())
                .unwrap_err()
                .to_string()
        };
        let e = err("{ ask_budget = [1, 2] }");
        assert!(
            e.contains("entry[0].ask_budget") && e.contains("does not apply to algorithm torrey"),
            "{e}"
        );
        let e = err("{ give_budget = [] }");
        assert!(
            e.contains("entry[0].sweep.give_budget") && e.contains("empty"),
            "{e}"
        );
        let e = err("{ importance_threshold = [nan] }");
        assert!(e.contains("entry[0].sweep.importance_threshold"), "{e}");
        let e = err("{ give_budget = [1, 2], importance_threshold = [0.1] }");
        assert!(e.contains("as many"), "{e}");
        let e = err("{ give_budget = [1, 1] }");
        assert!(e.contains("appears twice"), "{e}");
    }

    #[test]
    fn an_entry_learns_with_a_dqn_by_name_and_its_bad_settings_name_their_key() {
        let base = "name = \"t\"\nruns = 2\nepisodes = 100\neval_every = 20\neval_episodes = 10\n";
        let entry = "[[entry]]\nname = \"dqn\"\nalgorithm = \"adhoc-td\"\nlearner = \"dqn\"\n";
        let study = StudyConfig::parse(&format!("{base}{entry}hidden = [32]\n"), "t").unwrap();
        study.validate().unwrap();
        let team = study.experiment(&study.entries[0], None).team;
        let learner = &team[2].config.learner;
        let agent::LearnerSettings::Dqn(dqn) = learner else {
            panic!("{learner:?}");
        };
        assert_eq!((dqn.hidden.as_slice(), dqn.heads), (&[32][..], 1));
        let err = |keys: &str| {
            StudyConfig::parse(&format!("{base}{entry}{keys}\n"), "t")
                .and_then(|s| s.validate())
                .unwrap_err()
                .to_string()
        };
        let e = err("hidden = [2000]");
        assert!(
            e.contains("entry[0].team[0].hidden") && e.contains("1 to 1024 units wide, got 2000"),
            "{e}"
        );
        let e = err("lr = -1.0");
        assert!(
            e.contains("entry[0].team[0].lr") && e.contains("in (0, 1]"),
            "{e}"
        );
        let e = err("batch = 100\nreplay = 50");
        assert!(
            e.contains("entry[0].team[0].batch") && e.contains("replay (50)"),
            "{e}"
        );
        let e = StudyConfig::parse(
            &format!("{base}[[entry]]\nalgorithm = \"adhoc-td\"\nlearner = \"deep\"\n"),
            "t",
        )
        .and_then(|s| s.validate())
        .unwrap_err()
        .to_string();
        assert!(e.contains("unknown learner `deep`"), "{e}");
    }

    #[test]
    fn the_neural_preset_compares_each_learner_with_its_own_no_advice() {
        let neural = StudyConfig::preset("neural").unwrap();
        let record = neural.record();
        let compared: Vec<(&str, Option<&str>)> = (record.entries.iter())
            .map(|e| (e.name.as_str(), record.baseline_of(e)))
            .collect();
        assert_eq!(
            compared,
            [
                ("no-advice-sarsa", None),
                ("adhoc-visit-sarsa", Some("no-advice-sarsa")),
                ("adhoc-td-sarsa", Some("no-advice-sarsa")),
                ("no-advice-dqn", None),
                ("adhoc-visit-dqn", Some("no-advice-dqn")),
                ("adhoc-td-dqn", Some("no-advice-dqn")),
            ]
        );
        let learner = |i: usize| neural.experiment(&neural.entries[i], None).team[0].clone();
        assert!(matches!(
            learner(5).config.learner,
            agent::LearnerSettings::Dqn(_)
        ));
        // Its SARSA(λ) entries are paper-scratch's.
        let paper = StudyConfig::preset("paper-scratch").unwrap();
        assert_eq!(
            learner(2),
            paper.experiment(&paper.entries[2], None).team[0]
        );
    }

    #[test]
    fn a_value_of_the_wrong_type_names_its_line() {
        let text = "name = \"t\"\nruns = 2\nepisodes = 100\neval_every = 20\neval_episodes = 10\n\
                    [[entry]]\nname = \"a\"\nbaseline = 3\nalgorithm = \"no-advice\"\n";
        let e = StudyConfig::parse(text, "s.toml").unwrap_err().to_string();
        assert!(
            e.contains("s.toml: line 8: invalid type: integer `3`"),
            "{e}"
        );
    }

    #[test]
    fn a_pretrained_expert_keeps_the_learner_its_pretraining_names() {
        let study = StudyConfig::preset("deep-advising-expert").unwrap();
        let dqn = |spec: &AgentSpec| match &spec.config.learner {
            agent::LearnerSettings::Dqn(d) => d.heads,
            other => panic!("{other:?}"),
        };
        let pretraining = study.pretraining(study.pretrain.as_ref().unwrap());
        assert!(pretraining.team.iter().all(|a| dqn(a) == 1));
        let rcmp = study.entries.iter().find(|e| e.name == "rcmp").unwrap();
        let team = study.experiment(rcmp, None).team;
        // rcmp's learners have 5 heads; the expert keeps its one-head DQN.
        assert_eq!(team.iter().map(dqn).collect::<Vec<_>>(), [5, 5, 1]);
        assert_eq!(
            team[2].config.algorithm.setting("ask_budget"),
            Some(0.into())
        );
        // Without a learner in [pretrain], the expert learns as its team.
        let methods = StudyConfig::preset("methods-expert").unwrap();
        let rcmp = methods.entries.iter().find(|e| e.name == "rcmp").unwrap();
        let team = methods.experiment(rcmp, None).team;
        assert!(team.iter().all(|a| a.config.learner.name() == "ensemble"));
        // A bad key of the pretraining names it.
        let text = "name = \"t\"\nruns = 2\nepisodes = 100\neval_every = 20\neval_episodes = 10\n\
                    [pretrain]\nalgorithm = \"no-advice\"\nepisodes = 10\nexpert = 2\nhidden = [0]\n\
                    learner = \"dqn\"\n[[entry]]\nalgorithm = \"no-advice\"\nexpert = true\n";
        let e = StudyConfig::parse(text, "t")
            .unwrap()
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("pretrain.hidden"), "{e}");
    }

    #[test]
    fn an_entry_names_its_own_baseline_and_bad_ones_are_refused() {
        let base = "name = \"t\"\nruns = 2\nepisodes = 100\neval_every = 20\neval_episodes = 10\n\
                    baseline = \"a\"\n[[entry]]\nname = \"a\"\nalgorithm = \"no-advice\"\n\
                    [[entry]]\nname = \"b\"\nalgorithm = \"no-advice\"\nlearner = \"dqn\"\n";
        let c = "[[entry]]\nname = \"c\"\nalgorithm = \"adhoc-td\"\n";
        let study = StudyConfig::parse(&format!("{base}{c}baseline = \"b\"\n"), "t").unwrap();
        study.validate().unwrap();
        let record = study.record();
        let compared: Vec<Option<&str>> = (record.entries.iter())
            .map(|e| record.baseline_of(e))
            .collect();
        assert_eq!(compared, [None, None, Some("b")]);
        // It reads back from study.json, and a study without it writes none.
        let again: StudyConfig = serde_json::from_value(study.json()).unwrap();
        assert_eq!(again.entries, study.entries);
        let paper = StudyConfig::preset("paper-scratch").unwrap().json();
        let entries = paper["entry"].as_array().unwrap();
        assert!(entries.iter().all(|e| e.get("baseline").is_none()));

        let err = |text: &str| {
            StudyConfig::parse(text, "t")
                .and_then(|s| s.validate())
                .unwrap_err()
                .to_string()
        };
        let e = err(&format!("{base}{c}baseline = \"z\"\n"));
        assert!(
            e.contains("`entry[2].baseline`") && e.contains("no entry is named 'z'"),
            "{e}"
        );
        let e = err(&format!("{base}{c}baseline = \"c\"\n"));
        assert!(e.contains("'c' is this entry"), "{e}");
        // A chain: b is c's baseline and has its own.
        let chained = base.replace("\"dqn\"\n", "\"dqn\"\nbaseline = \"a\"\n");
        let e = err(&format!("{chained}{c}baseline = \"b\"\n"));
        assert!(
            e.contains("`entry[1].baseline`") && e.contains("'b' is a baseline itself"),
            "{e}"
        );
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
        let v_g = err(&format!(
            "{base}[[entry]]\nname = \"a\"\nalgorithm = \"torrey\"\nv_g = 0.5\n"
        ));
        assert!(v_g.contains("entry[0].v_g"), "{v_g}");
        assert!(
            err(&format!(
                "{base}[[entry]]\nname = \"a\"\nalgorithm = \"ad-hoc-td\"\n\n[[entry]]\nname = \"a\"\nalgorithm = \"adhoc-td\"\n"
            ))
            .contains("appears twice"),
            "the old spelling still reads"
        );
        // An entry without a name takes its algorithm's, unless two would.
        let named = StudyConfig::parse(
            &format!(
                "{base}[[entry]]\nalgorithm = \"adhoc-td\"\n[[entry]]\nalgorithm = \"torrey\"\n"
            ),
            "t",
        )
        .unwrap();
        assert_eq!(named.entries[0].name, "adhoc-td");
        let twice = err(&format!(
            "{base}[[entry]]\nalgorithm = \"adhoc-td\"\n[[entry]]\nalgorithm = \"adhoc-td\"\n"
        ));
        assert!(
            twice.contains("entry[0].name") && twice.contains("adhoc-td"),
            "{twice}"
        );
        assert!(
            StudyConfig::preset("paper-everything")
                .unwrap_err()
                .to_string()
                .contains("quick")
        );
    }
}
