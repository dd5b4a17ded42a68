//! What one experiment is: the protocol's numbers, the simulator's settings
//! and one [`AgentSpec`] per agent, with validation that names the bad key.

use std::ops::RangeInclusive;
use std::path::Path;

use agent::{Algorithm, ObservationSet, Profile};
use env_server::EnvConfig;
use proto::Simulator;
use serde::{Deserialize, Serialize};

pub use crate::agent_spec::{AgentSpec, ChildSpec};
use crate::error::ConfigError;
use crate::membership::{self, MembershipEvent};
use crate::transport::Transport;

/// Default confidence level of the reported intervals (the paper's captions).
pub const DEFAULT_CI_LEVEL: f64 = 0.95;

fn default_ci_level() -> f64 {
    DEFAULT_CI_LEVEL
}

/// Accepted runs R.
pub const RUNS: RangeInclusive<u64> = 1..=100_000;
/// Accepted training episodes N per run.
pub const EPISODES: RangeInclusive<u64> = 0..=100_000_000;
/// Accepted evaluation intervals K.
pub const EVAL_EVERY: RangeInclusive<u64> = 1..=100_000_000;
/// Accepted episodes M per evaluation.
pub const EVAL_EPISODES: RangeInclusive<u64> = 1..=1_000_000;
/// At most this many evaluations per run.
pub const MAX_EVAL_POINTS: u64 = 1_000_000;

/// `Ok` when `value` lies in `range`, else an error naming `key` and the range.
pub fn check_range(key: &str, value: u64, range: RangeInclusive<u64>) -> Result<(), ConfigError> {
    if range.contains(&value) {
        Ok(())
    } else {
        Err(ConfigError::new(
            key,
            format!("must be {} to {}, got {value}", range.start(), range.end()),
        ))
    }
}

/// One experiment: docs/algorithms.md section 4 for one configuration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExperimentConfig {
    /// Independent runs R, each with its own derived seeds.
    pub runs: u64,
    /// Training episodes N per run.
    pub episodes: u64,
    /// An evaluation every K training episodes (and before the first).
    pub eval_every: u64,
    /// Episodes M of one evaluation.
    pub eval_episodes: u64,
    /// The experiment seed every run's seeds derive from.
    pub seed: u64,
    /// Level of the confidence intervals of the summary, in (0, 1).
    #[serde(default = "default_ci_level")]
    pub ci_level: f64,
    /// Where agents and simulator live (part of the identity: over zenoh
    /// the timeouts change results).
    #[serde(default)]
    pub transport: Transport,
    /// The simulator's settings.
    #[serde(default)]
    pub env: EnvConfig,
    /// One agent per offense player, by id.
    pub team: Vec<AgentSpec>,
    /// Newcomers taking slots during training, in the order they happen.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub events: Vec<MembershipEvent>,
}

impl Default for ExperimentConfig {
    /// The paper's protocol: 50 runs of 5000 episodes, an evaluation of 100
    /// episodes every 20, three NoAdvice agents.
    fn default() -> Self {
        let env = EnvConfig::default();
        Self {
            runs: 50,
            episodes: 5000,
            eval_every: 20,
            eval_episodes: 100,
            seed: 1,
            ci_level: DEFAULT_CI_LEVEL,
            transport: Transport::InProcess,
            team: vec![AgentSpec::of(Algorithm::default(), Profile::Paper); env.offense],
            env,
            events: Vec::new(),
        }
    }
}

impl ExperimentConfig {
    /// Returns the first invalid value, naming its key and what is accepted
    /// ([`RUNS`], [`EPISODES`], [`EVAL_EVERY`], [`EVAL_EPISODES`],
    /// [`MAX_EVAL_POINTS`]).
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range("runs", self.runs, RUNS)?;
        check_range("episodes", self.episodes, EPISODES)?;
        check_range("eval_every", self.eval_every, EVAL_EVERY)?;
        check_range("eval_episodes", self.eval_episodes, EVAL_EPISODES)?;
        let points = self.episodes / self.eval_every + 2;
        if points > MAX_EVAL_POINTS {
            return Err(ConfigError::new(
                "eval_every",
                format!(
                    "{} episodes evaluated every {} make {points} evaluations, at most \
                     {MAX_EVAL_POINTS}: evaluate less often",
                    self.episodes, self.eval_every
                ),
            ));
        }
        if !(self.ci_level > 0.0 && self.ci_level < 1.0) {
            return Err(ConfigError::new(
                "ci_level",
                format!("must be in (0, 1), e.g. 0.95, got {}", self.ci_level),
            ));
        }
        self.transport.validate()?;
        self.env.validate().map_err(env_error)?;
        let real_hfo = self.transport.zenoh().map(|z| z.simulator) == Some(Simulator::RealHfo);
        if let Some(setting) = self.env.unlike_real_hfo().filter(|_| real_hfo) {
            return Err(ConfigError::new(
                format!("env.{setting}"),
                "is a setting of our simulator, which the real HFO cannot play: leave it at its default",
            ));
        }
        if self.team.len() != self.env.offense {
            return Err(ConfigError::new(
                "team",
                format!(
                    "has {} agents, env.offense is {}: one agent per offense player",
                    self.team.len(),
                    self.env.offense
                ),
            ));
        }
        for (i, spec) in self.team.iter().enumerate() {
            spec.config
                .validate()
                .map_err(|e| ConfigError::new(format!("team[{i}].{}", e.key), e.reason))?;
            self.check_children(spec)
                .map_err(|e| ConfigError::new(format!("team[{i}].{}", e.key), e.reason))?;
        }
        membership::validate(&self.events, self.team.len(), self.episodes)?;
        for (k, event) in self.events.iter().enumerate() {
            let spec = event.newcomer(&self.team[event.slot]);
            let key = |key: &str, reason: String| {
                ConfigError::new(format!("events[{k}].newcomer.{key}"), reason)
            };
            (spec.config.validate()).map_err(|e| key(&e.key, e.reason))?;
            self.check_children(&spec)
                .map_err(|e| key(&e.key, e.reason))?;
        }
        Ok(())
    }

    /// An agent's learner and strategy, processes or objects, and what it
    /// observes can run as given; errors name the agent's key.
    fn check_children(&self, spec: &AgentSpec) -> Result<(), ConfigError> {
        let in_process = self.transport == Transport::InProcess;
        let real_hfo = self.transport.zenoh().map(|z| z.simulator) == Some(Simulator::RealHfo);
        if real_hfo && spec.config.learner.observation() == ObservationSet::Hfo {
            let reason = "`hfo`: the real HFO's backend gives the paper's state only; use `paper`, \
                          or our simulator";
            return Err(ConfigError::new("observation", reason));
        }
        let plugin = spec.plugin.clone().unwrap_or_default();
        if spec.learner.is_some() && in_process {
            let reason = "a learner process is its agent's: run with --transport zenoh";
            return Err(ConfigError::new("learner", reason));
        }
        if spec.plugin.is_some() && !in_process {
            let reason = "a learner or strategy given as an object runs in process only: use \
                          transport in-process, or give it as a process \
                          (`learner = { command = [...] }`) over zenoh";
            return Err(ConfigError::new("plugin", reason));
        }
        if spec.learner.is_some() && plugin.learner.is_some() {
            let reason = "an agent has one learner: a process or an object, not both";
            return Err(ConfigError::new("learner", reason));
        }
        let external = spec.config.algorithm.name().is_external();
        let given = spec.strategy_process.is_some() || plugin.strategy.is_some();
        let reason = match (&spec.strategy_process, external) {
            _ if given && !external => {
                "a strategy process or object makes the decisions of algorithm `external`: \
                 set `algorithm = \"external\"`"
            }
            _ if !given && external => {
                "algorithm `external` needs its strategy: \
                 `strategy_process = { command = [\"python3\", \"my_strategy.py\"] }`, or \
                 an object from Python (`strategy=`)"
            }
            (Some(_), true) if plugin.strategy.is_some() => {
                "an agent has one strategy: a process or an object, not both"
            }
            (Some(_), true) if in_process => {
                "a strategy process is its agent's: run with --transport zenoh"
            }
            _ => return Ok(()),
        };
        Err(ConfigError::new("strategy_process", reason))
    }

    /// The training episodes after which an evaluation takes place: 0, K,
    /// 2K, ... and N itself (when N is not a multiple of K, the last
    /// interval is shorter).
    pub fn eval_points(&self) -> Vec<u64> {
        let step = self.eval_every.max(1);
        let mut points: Vec<u64> = (0..=self.episodes / step).map(|p| p * step).collect();
        if self.episodes % step != 0 {
            points.push(self.episodes);
        }
        points
    }

    /// Episodes played by one run: training plus every evaluation.
    pub fn episodes_per_run(&self) -> u64 {
        self.episodes + self.eval_points().len() as u64 * self.eval_episodes
    }
}

/// Names the key of a rejected simulator setting.
fn env_error(e: env_server::EnvConfigError) -> ConfigError {
    use env_server::EnvConfigError as E;
    let key = match &e {
        E::Offense(_) => "env.offense".to_owned(),
        E::ZeroLimit(k) => format!("env.{k}"),
    };
    ConfigError::new(key, e.to_string())
}

/// A team file: `[[agent]]` tables in TOML, or `{"agent": [...]}` in JSON,
/// and the `[[event]]`s of an open team.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TeamFile {
    agent: Vec<serde_json::Map<String, serde_json::Value>>,
    #[serde(default)]
    event: Vec<serde_json::Value>,
}

/// What a team file describes: the agents by id and the membership events.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TeamSpec {
    /// One agent per slot.
    pub agents: Vec<AgentSpec>,
    /// Newcomers taking slots during training.
    pub events: Vec<MembershipEvent>,
}

/// A TOML error of `text` with the line it points at.
pub(crate) fn toml_error(text: &str, e: &toml::de::Error) -> String {
    match e.span() {
        Some(span) => {
            let line = 1 + text[..span.start.min(text.len())].matches('\n').count();
            format!("line {line}: {}", e.message())
        }
        None => e.message().to_owned(),
    }
}

/// Reads a team file (TOML, or JSON when the name ends in `.json`): one
/// `agent` entry per agent, by id, and its `event`s. Relative `load` paths
/// are taken from the file's directory.
pub fn load_team_file(path: &Path) -> Result<TeamSpec, ConfigError> {
    let key = "team";
    let text = std::fs::read_to_string(path)
        .map_err(|e| ConfigError::new(key, format!("cannot read {}: {e}", path.display())))?;
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let parsed: Result<TeamFile, String> = if is_json {
        serde_json::from_str(&text).map_err(|e| e.to_string())
    } else {
        toml::from_str(&text).map_err(|e| toml_error(&text, &e))
    };
    let file = parsed.map_err(|e| {
        let e = e.split_whitespace().collect::<Vec<_>>().join(" ");
        ConfigError::new(key, format!("{}: {e}", path.display()))
    })?;
    let base = path.parent().unwrap_or(Path::new(""));
    TeamSpec::from_file(file, base, &path.display().to_string())
}

impl TeamSpec {
    /// The team of a team file's tables as JSON, `{"agent": [...], "event":
    /// [...]}`; relative paths are taken from `base`, and errors start with
    /// `origin` (what gave the tables).
    pub fn from_json(
        tables: serde_json::Value,
        base: &Path,
        origin: &str,
    ) -> Result<TeamSpec, ConfigError> {
        let file: TeamFile = serde_json::from_value(tables)
            .map_err(|e| ConfigError::new("team", format!("{origin}: {e}")))?;
        TeamSpec::from_file(file, base, origin)
    }

    fn from_file(file: TeamFile, base: &Path, origin: &str) -> Result<TeamSpec, ConfigError> {
        let in_file =
            |key: String, reason: String| ConfigError::new(key, format!("{origin}: {reason}"));
        let mut team = TeamSpec::default();
        for (i, table) in file.agent.into_iter().enumerate() {
            let mut spec =
                AgentSpec::try_from(table).map_err(|r| in_file(format!("team[{i}]"), r))?;
            spec.resolve(base)
                .map_err(|(key, r)| in_file(format!("team[{i}].{key}"), r))?;
            team.agents.push(spec);
        }
        for (k, value) in file.event.into_iter().enumerate() {
            let mut event: MembershipEvent = serde_json::from_value(value)
                .map_err(|e| in_file(format!("event[{k}]"), e.to_string()))?;
            if let Some(spec) = &mut event.newcomer {
                spec.resolve(base)
                    .map_err(|(key, r)| in_file(format!("event[{k}].newcomer.{key}"), r))?;
            }
            team.events.push(event);
        }
        Ok(team)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agent_spec::fnv64;
    use agent::{AdHoc, AgentConfig};
    use std::path::PathBuf;

    fn key_of(config: ExperimentConfig) -> String {
        config.validate().unwrap_err().key
    }

    #[test]
    fn defaults_are_the_papers() {
        let c = ExperimentConfig::default();
        c.validate().unwrap();
        assert_eq!(
            (c.runs, c.episodes, c.eval_every, c.eval_episodes),
            (50, 5000, 20, 100)
        );
        assert_eq!(c.ci_level, 0.95);
        assert_eq!(c.team.len(), 3);
        let points = c.eval_points();
        assert_eq!(points.len(), 251);
        assert_eq!((points[0], points[1], points[250]), (0, 20, 5000));
        assert_eq!(c.episodes_per_run(), 5000 + 251 * 100);
    }

    #[test]
    fn eval_points_end_at_n() {
        let c = ExperimentConfig {
            episodes: 50,
            eval_every: 20,
            ..ExperimentConfig::default()
        };
        assert_eq!(c.eval_points(), vec![0, 20, 40, 50]);
        let c = ExperimentConfig {
            episodes: 0,
            ..ExperimentConfig::default()
        };
        assert_eq!(c.eval_points(), vec![0]);
    }

    #[test]
    fn bad_values_name_their_key() {
        let base = ExperimentConfig::default;
        assert_eq!(key_of(ExperimentConfig { runs: 0, ..base() }), "runs");
        assert_eq!(
            key_of(ExperimentConfig {
                eval_every: 0,
                ..base()
            }),
            "eval_every"
        );
        assert_eq!(
            key_of(ExperimentConfig {
                eval_episodes: 0,
                ..base()
            }),
            "eval_episodes"
        );
        for level in [0.0, 1.0, f64::NAN, 95.0] {
            assert_eq!(
                key_of(ExperimentConfig {
                    ci_level: level,
                    ..base()
                }),
                "ci_level"
            );
        }
        let mut c = base();
        c.env.offense = 7;
        assert_eq!(key_of(c), "env.offense");
        let mut c = base();
        c.env.frames_per_trial = 0;
        assert_eq!(key_of(c), "env.frames_per_trial");
        let mut c = base();
        c.team.pop();
        assert_eq!(key_of(c), "team");
        let mut c = base();
        c.team[2].config.epsilon = 2.0;
        assert_eq!(key_of(c), "team[2].epsilon");
        let mut c = base();
        c.team[1].config = AgentConfig::of("adhoc-visit".parse().unwrap(), Profile::Paper);
        c.team[1].config.algorithm.get_mut::<AdHoc>().unwrap().v_g = -1.0;
        let e = c.validate().unwrap_err();
        assert_eq!(e.key, "team[1].v_g");
        assert!(e.to_string().contains(">= 0"), "{e}");
    }

    #[test]
    fn agent_specs_are_flat_tables() {
        let spec: AgentSpec = toml::from_str(
            "algorithm = \"ad-hoc-td\"\nask_budget = 0\nepsilon = 0\nload = \"expert.snapshot\"\n",
        )
        .unwrap();
        assert_eq!(spec.config.algorithm.name().name(), "adhoc-td");
        assert_eq!(
            spec.config.algorithm.get::<AdHoc>(),
            Some(&AdHoc {
                ask_budget: 0,
                ..AdHoc::td()
            })
        );
        assert_eq!(spec.config.epsilon, 0.0);
        assert_eq!(spec.load, Some(PathBuf::from("expert.snapshot")));
        assert!(!spec.keep_counters);
        // Round trip through JSON, as config.json stores it.
        let json = serde_json::to_string(&spec).unwrap();
        assert_eq!(serde_json::from_str::<AgentSpec>(&json).unwrap(), spec);
        // A typo is an error naming the key.
        let err = toml::from_str::<AgentSpec>("alhpa = 0.2\n").unwrap_err();
        assert!(err.to_string().contains("alhpa"), "{err}");
        let err = serde_json::from_str::<AgentSpec>(r#"{"load": 3}"#).unwrap_err();
        assert!(err.to_string().contains("load"), "{err}");
        // `learner` names the agent's own learner, or is a learner process.
        let named: AgentSpec = toml::from_str("learner = \"ensemble\"\nheads = 3\n").unwrap();
        assert_eq!(
            (named.config.learner.name(), named.learner),
            ("ensemble", None)
        );
        let process: AgentSpec =
            toml::from_str("learner = { command = [\"python3\", \"l.py\"] }\n").unwrap();
        assert_eq!(process.learner.unwrap().command, ["python3", "l.py"]);
        // So is a key of another algorithm, with the algorithms it belongs to.
        let err = toml::from_str::<AgentSpec>(
            "mistake_correcting = true
",
        )
        .unwrap_err();
        let err = err.to_string();
        assert!(err.contains("`mistake_correcting`"), "{err}");
        assert!(
            err.contains("adhoc-visit, adhoc-td, torrey, early-advising"),
            "{err}"
        );
    }

    #[test]
    fn experiment_config_round_trips_through_json() {
        let mut c = ExperimentConfig::default();
        c.team[2] = AgentSpec {
            load: Some("a/b.snapshot".into()),
            keep_counters: true,
            ..AgentSpec::of("torrey".parse().unwrap(), Profile::Paper)
        };
        let json = serde_json::to_string(&c).unwrap();
        assert_eq!(serde_json::from_str::<ExperimentConfig>(&json).unwrap(), c);
    }

    #[test]
    fn team_files_in_toml_and_json() {
        let dir = tempfile::tempdir().unwrap();
        let toml_path = dir.path().join("team.toml");
        std::fs::write(
            &toml_path,
            "[[agent]]\nalgorithm = \"ad-hoc-td\"\n\n[[agent]]\nalgorithm = \"ad-hoc-td\"\n\n\
             [[agent]]\nalgorithm = \"adhoc-td\"\nask_budget = 0\nload = \"expert.snapshot\"\n",
        )
        .unwrap();
        let team = load_team_file(&toml_path).unwrap().agents;
        assert_eq!(team.len(), 3);
        assert_eq!(team[0].config.algorithm.get::<AdHoc>(), Some(&AdHoc::td()));
        let expert = AdHoc {
            ask_budget: 0,
            ..AdHoc::td()
        };
        assert_eq!(team[2].config.algorithm.get::<AdHoc>(), Some(&expert));
        assert_eq!(team[2].load, Some(dir.path().join("expert.snapshot")));

        let json_path = dir.path().join("team.json");
        std::fs::write(
            &json_path,
            r#"{"agent": [{"strategy": "torrey"}, {"load": "/abs.snapshot"}]}"#,
        )
        .unwrap();
        let team = load_team_file(&json_path).unwrap().agents;
        assert_eq!(team[0].config.algorithm.name().name(), "torrey");
        assert_eq!(team[1].config.algorithm.name().name(), "no-advice");
        assert_eq!(team[1].load, Some(PathBuf::from("/abs.snapshot")));

        std::fs::write(&toml_path, "[[agent]]\nalgorithm = \"best\"\n").unwrap();
        let e = load_team_file(&toml_path).unwrap_err();
        assert_eq!(e.key, "team[0]");
        assert!(e.reason.contains("best"), "{e}");
        assert!(!e.to_string().contains('\n'), "{e}");
        std::fs::write(&toml_path, "[[agent]]\n[[agent]]\nask_budget = 0\n").unwrap();
        let e = load_team_file(&toml_path).unwrap_err();
        assert_eq!(e.key, "team[1]");
        assert!(e.reason.contains("`ask_budget`"), "{e}");
        assert!(e.reason.contains("no-advice"), "{e}");
        assert!(!e.to_string().contains('\n'), "{e}");
        let e = load_team_file(&dir.path().join("missing.toml")).unwrap_err();
        assert!(e.reason.contains("missing.toml"), "{e}");
    }

    #[test]
    fn a_learner_process_is_resolved_digested_and_checked() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("mine.py"), "print()\n").unwrap();
        let path = dir.path().join("team.toml");
        let learner = "learner = { command = [\"python3\", \"mine.py\"], source = \"mine.py\" }";
        std::fs::write(
            &path,
            format!("[[agent]]\n[[agent]]\n[[agent]]\n{learner}\n"),
        )
        .unwrap();
        let team = load_team_file(&path).unwrap().agents;
        let spec = team[2].learner.clone().unwrap();
        assert_eq!(spec.command, ["python3", "mine.py"]);
        assert_eq!(spec.dir.as_deref(), Some(dir.path()));
        assert_eq!(
            spec.source_fnv64.unwrap(),
            format!("{:016x}", fnv64(b"print()\n"))
        );
        // config.json carries it, and reads back the same.
        let map = serde_json::Map::from(team[2].clone());
        assert_eq!(AgentSpec::try_from(map).unwrap(), team[2]);

        let config = |transport, load: Option<&str>| ExperimentConfig {
            transport,
            team: vec![
                AgentSpec::default(),
                AgentSpec::default(),
                AgentSpec {
                    load: load.map(PathBuf::from),
                    ..team[2].clone()
                },
            ],
            ..ExperimentConfig::default()
        };
        let zenoh = || Transport::Zenoh(Default::default());
        config(zenoh(), None).validate().unwrap();
        // A learner with snapshot hooks loads its own state.
        config(zenoh(), Some("a.snapshot")).validate().unwrap();
        let bad = config(Transport::InProcess, None);
        assert_eq!(bad.validate().unwrap_err().key, "team[2].learner");
        for (text, says) in [
            ("learner = { command = [] }", "must name a program"),
            (
                "learner = { command = [\"x\"], source = \"gone.py\" }",
                "gone.py",
            ),
            ("learner = [\"x\"]", "must be a table with `command`"),
        ] {
            std::fs::write(&path, format!("[[agent]]\n{text}\n")).unwrap();
            let e = load_team_file(&path).unwrap_err();
            assert!(e.reason.contains(says), "{e}");
        }
    }

    #[test]
    fn objects_run_in_process_and_strategies_only_for_external() {
        use crate::plugin::PluginSpec;
        let with = |plugin: PluginSpec, algorithm: Algorithm, transport| ExperimentConfig {
            transport,
            team: vec![
                AgentSpec::default(),
                AgentSpec::default(),
                AgentSpec {
                    plugin: Some(plugin),
                    ..AgentSpec::of(algorithm, Profile::Paper)
                },
            ],
            ..ExperimentConfig::default()
        };
        let learner = PluginSpec {
            learner: Some("mine 1".into()),
            strategy: None,
        };
        let strategy = PluginSpec {
            learner: None,
            strategy: Some("mine 1".into()),
        };
        let zenoh = Transport::Zenoh(Default::default());
        let (td, external) = ("adhoc-td".parse().unwrap(), "external".parse().unwrap());
        with(learner.clone(), td, Transport::InProcess)
            .validate()
            .unwrap();
        with(strategy.clone(), external, Transport::InProcess)
            .validate()
            .unwrap();
        let key = |c: ExperimentConfig| c.validate().unwrap_err().key;
        assert_eq!(key(with(learner, td, zenoh)), "team[2].plugin");
        let not_external = with(strategy, td, Transport::InProcess);
        assert_eq!(key(not_external), "team[2].strategy_process");
    }
}
