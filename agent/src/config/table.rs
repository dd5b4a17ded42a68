//! [`AgentConfig`] as one flat table, the form of every file: the learner's
//! shared keys, the learner's own, the algorithm's, the fidelity rules, the
//! network conditions. Binary formats (postcard) carry the same table as
//! JSON text, so there is one form to keep right.

use serde::de::{DeserializeOwned, Error as _};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use serde_json::Value;

use super::AgentConfig;
use crate::advises::Advises;
use crate::algorithm::Algorithm;
use crate::algorithm_settings::{AlgorithmSettings, not_a_setting};
use crate::config_error::AgentConfigError;
use crate::fidelity::{Fidelity, Profile};
use crate::learner_settings::LearnerSettings;
use crate::method::Table;

impl Serialize for AgentConfig {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        if !serializer.is_human_readable() {
            let json = serde_json::to_string(self).map_err(serde::ser::Error::custom)?;
            return serializer.serialize_str(&json);
        }
        let table = self.table();
        let mut map = serializer.serialize_map(Some(table.len()))?;
        for (key, value) in &table {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for AgentConfig {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let table = if deserializer.is_human_readable() {
            Table::deserialize(deserializer)?
        } else {
            let json = String::deserialize(deserializer)?;
            serde_json::from_str(&json).map_err(D::Error::custom)?
        };
        AgentConfig::from_table(table).map_err(D::Error::custom)
    }
}

/// The learner's keys every agent has.
const SHARED_KEYS: [&str; 8] = [
    "alpha",
    "gamma",
    "lambda",
    "epsilon",
    "tiles_per_feature",
    "tile_width",
    "tile_step",
    "trace_threshold",
];

impl AgentConfig {
    /// The flat table, in the order files show it: the shared keys, the
    /// learner's, the algorithm's, the fidelity rules, then the network
    /// conditions and what it advises when given.
    fn table(&self) -> Vec<(String, Value)> {
        let shared = [
            Value::from(self.alpha),
            Value::from(self.gamma),
            Value::from(self.lambda),
            Value::from(self.epsilon),
            Value::from(self.tiles_per_feature),
            Value::from(self.tile_width),
            Value::from(self.tile_step),
            Value::from(self.trace_threshold),
        ];
        let mut table: Vec<(String, Value)> = SHARED_KEYS
            .iter()
            .map(|k| (*k).to_owned())
            .zip(shared)
            .collect();
        let default_learner = LearnerSettings::for_need(self.algorithm.name().learner_need());
        if self.learner != LearnerSettings::Sarsa || self.learner != default_learner {
            table.extend(object(&self.learner));
        }
        table.push(("algorithm".into(), self.algorithm.name().name().into()));
        table.extend(self.algorithm.written());
        table.extend(object(&self.fidelity));
        if let Some(network) = &self.network {
            table.push(("network".into(), to_value(network)));
        }
        if self.advises != Advises::Honest {
            table.push(("advises".into(), to_value(&self.advises)));
        }
        if self.announce_exhausted {
            table.push(("announce_exhausted".into(), true.into()));
        }
        table
    }

    /// The configuration of a flat table (a team file's `[[agent]]`
    /// table), with the defaults of its `profile` (the paper's without one)
    /// for the keys left out; a key of no setting of this agent is an error
    /// naming it.
    pub fn from_table(mut table: Table) -> Result<Self, AgentConfigError> {
        let d = AgentConfig::default();
        let profile: Profile = take(&mut table, "profile")?.unwrap_or_default();
        let algorithm: Algorithm = match take(&mut table, "algorithm")? {
            Some(a) => a,
            // Its spelling before 0.2.
            None => take(&mut table, "strategy")?.unwrap_or_default(),
        };
        let learner = match take::<String>(&mut table, "learner")? {
            Some(name) => LearnerSettings::named_for(&name, algorithm.learner_need())?,
            None => LearnerSettings::for_need(algorithm.learner_need()),
        };
        let config = AgentConfig {
            alpha: take(&mut table, "alpha")?.unwrap_or(d.alpha),
            gamma: take(&mut table, "gamma")?.unwrap_or(d.gamma),
            lambda: take(&mut table, "lambda")?.unwrap_or(d.lambda),
            epsilon: take(&mut table, "epsilon")?.unwrap_or(d.epsilon),
            tiles_per_feature: take(&mut table, "tiles_per_feature")?
                .unwrap_or(d.tiles_per_feature),
            tile_width: take(&mut table, "tile_width")?.unwrap_or(d.tile_width),
            tile_step: take(&mut table, "tile_step")?.unwrap_or(d.tile_step),
            trace_threshold: take(&mut table, "trace_threshold")?.unwrap_or(d.trace_threshold),
            learner: overlay(learner, &mut table, &["learner"])?,
            fidelity: overlay(Fidelity::of(profile), &mut table, &["profile"])?,
            network: take(&mut table, "network")?,
            advises: take(&mut table, "advises")?.unwrap_or_default(),
            announce_exhausted: take(&mut table, "announce_exhausted")?.unwrap_or_default(),
            algorithm: AlgorithmSettings::from_table(algorithm, profile, &mut table)?,
        };
        match table.keys().next() {
            None => Ok(config),
            Some(key) => Err(foreign_key(&config, key)),
        }
    }
}

/// The error for `key`, a setting of no part of `config`: of another
/// learner, of other algorithms, or of nothing.
fn foreign_key(config: &AgentConfig, key: &str) -> AgentConfigError {
    let learners: Vec<&str> = (LearnerSettings::NAMES.iter())
        .filter(|name| {
            let learner = LearnerSettings::named(name).expect("a learner of NAMES");
            object(&learner).iter().any(|(k, _)| k == key)
        })
        .copied()
        .collect();
    if learners.is_empty() {
        return not_a_setting(config.algorithm.name(), key);
    }
    AgentConfigError::new(
        key,
        format!(
            "does not apply to learner {}; it belongs to learner {}",
            config.learner.name(),
            learners.join(", ")
        ),
    )
}

/// `value` as JSON.
fn to_value(value: &impl Serialize) -> Value {
    serde_json::to_value(value).expect("settings serialise to JSON")
}

/// The keys of `value`, which serialises as an object, in its order.
fn object(value: &impl Serialize) -> Vec<(String, Value)> {
    match to_value(value) {
        Value::Object(map) => map.into_iter().collect(),
        other => unreachable!("an object expected, not {other}"),
    }
}

/// Takes `key` out of `table` as a `T`; the error names it.
fn take<T: DeserializeOwned>(table: &mut Table, key: &str) -> Result<Option<T>, AgentConfigError> {
    table
        .remove(key)
        .map(|v| {
            let null = v.is_null();
            serde_json::from_value(v).map_err(|e| value_error(key, null, e))
        })
        .transpose()
}

/// The error of `key`'s value; a null one is what a file's NaN or infinity
/// becomes in the table (JSON has neither), so it says so.
fn value_error(key: &str, null: bool, e: serde_json::Error) -> AgentConfigError {
    if null {
        return AgentConfigError::new(key, "must be a finite number, got NaN, infinity or null");
    }
    AgentConfigError::new(key, e.to_string())
}

/// `defaults` with the keys of `table` it has (but `kept`, which stay its
/// own), which are taken out of `table`.
fn overlay<T: Serialize + DeserializeOwned>(
    defaults: T,
    table: &mut Table,
    kept: &[&str],
) -> Result<T, AgentConfigError> {
    let mut own: Table = object(&defaults).into_iter().collect();
    let keys: Vec<String> = (own.keys())
        .filter(|k| !kept.contains(&k.as_str()) && table.contains_key(*k))
        .cloned()
        .collect();
    for key in keys {
        let value = table.remove(&key).expect("a key of the table");
        let null = value.is_null();
        own.insert(key.clone(), value);
        serde_json::from_value::<T>(Value::Object(own.clone()))
            .map_err(|e| value_error(&key, null, e))?;
    }
    Ok(serde_json::from_value(Value::Object(own)).expect("checked key by key"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::advice::Reachable;
    use crate::fidelity::{AdvisorTies, VoteTies};
    use crate::learner_settings::ObservationSet;
    use crate::link::Latency;
    use crate::method::LearnerNeed;
    use crate::strategy::{AdHoc, AdviceReuse, ReuseRule, Torrey};

    /// `name`'s paper settings changed key by key.
    fn with(name: &str, keys: &[(&str, Value)]) -> AgentConfig {
        let mut config = AgentConfig {
            alpha: 0.2,
            epsilon: 0.05,
            ..AgentConfig::of(name.parse().unwrap(), Profile::Paper)
        };
        for (key, value) in keys {
            config.algorithm.set(key, value.clone()).unwrap();
        }
        config
    }

    /// One configuration of every algorithm, most not with only their
    /// defaults.
    fn every_algorithm() -> Vec<AgentConfig> {
        let mut configs: Vec<AgentConfig> = Algorithm::all().map(|a| with(a.name(), &[])).collect();
        configs.extend([
            with(
                "adhoc-visit",
                &[
                    ("v_a", 0.25.into()),
                    ("ask_budget", 7.into()),
                    ("reachable", serde_json::json!({"agents": [2, 0]})),
                    ("backoff", true.into()),
                ],
            ),
            with(
                "adhoc-td",
                &[
                    ("mistake_correcting", true.into()),
                    ("reachable", serde_json::json!({"within-distance": 12.5})),
                    ("trust_lr", 0.05.into()),
                ],
            ),
            with("torrey", &[("importance_threshold", 0.5.into())]),
            with("episode-sharing", &[("sharing_budget", 9.into())]),
            with("advice-reuse", &[("reuse_rule", "decay".into())]),
            with("peer-learning", &[("follow_steps", 3.into())]),
            with("random-advising", &[("ask_probability", 0.3.into())]),
            AgentConfig {
                learner: LearnerSettings::Ensemble {
                    heads: 3,
                    mask_probability: 0.25,
                },
                ..with("rcmp", &[("uncertainty_threshold", 0.2.into())])
            },
            AgentConfig {
                learner: LearnerSettings::Dqn(crate::DqnSettings {
                    hidden: vec![32, 16, 8],
                    lr: 3e-4,
                    epsilon_decay: 0,
                    ..crate::DqnSettings::default()
                }),
                ..with("adhoc-td", &[])
            },
            AgentConfig {
                learner: LearnerSettings::named_for("dqn", LearnerNeed::Uncertainty).unwrap(),
                ..with("rcmp", &[])
            },
            AgentConfig {
                fidelity: Fidelity {
                    vote_ties: VoteTies::Random,
                    ..Fidelity::of(Profile::Authors)
                },
                ..AgentConfig::of("adhoc-visit".parse().unwrap(), Profile::Authors)
            },
        ]);
        configs
    }

    #[test]
    fn every_algorithm_round_trips_through_postcard_json_and_toml() {
        for config in every_algorithm() {
            let name = config.algorithm.name();
            config.validate().unwrap();
            let bytes = postcard::to_allocvec(&config).unwrap();
            let back: AgentConfig = postcard::from_bytes(&bytes).unwrap();
            assert_eq!(back, config, "postcard, {name}");

            let json = serde_json::to_string(&config).unwrap();
            let back: AgentConfig = serde_json::from_str(&json).unwrap();
            assert_eq!(back, config, "JSON, {name}: {json}");
            assert!(!json.contains("null"), "{json}");

            let text = toml::to_string(&config).unwrap();
            let back: AgentConfig = toml::from_str(&text).unwrap();
            assert_eq!(back, config, "TOML, {name}: {text}");
        }
    }

    /// The keys of `name`'s table that are not every agent's.
    fn own_keys(config: &AgentConfig) -> Vec<String> {
        let Value::Object(map) = serde_json::to_value(config).unwrap() else {
            panic!("a table expected");
        };
        let common = [
            "algorithm",
            "profile",
            "torrey_unknown_state",
            "torrey_intent",
            "advisor_ties",
            "vote_ties",
            "shared_bootstrap",
        ];
        map.keys()
            .filter(|k| !SHARED_KEYS.contains(&k.as_str()) && !common.contains(&k.as_str()))
            .cloned()
            .collect()
    }

    #[test]
    fn the_table_shows_only_the_algorithms_keys() {
        let keys = |name: &str| own_keys(&with(name, &[]));
        assert!(keys("no-advice").is_empty());
        assert!(keys("random").is_empty());
        let ad_hoc = [
            "ask_budget",
            "give_budget",
            "mistake_correcting",
            "reachable",
            "v_a",
            "v_g",
        ];
        assert_eq!(keys("adhoc-visit"), ad_hoc);
        assert_eq!(keys("adhoc-td"), ad_hoc);
        assert_eq!(
            keys("torrey"),
            ["give_budget", "importance_threshold", "mistake_correcting"]
        );
        assert_eq!(keys("episode-sharing"), ["sharing_budget"]);
        // RCMP's learner, not the default one, is written with its keys.
        assert_eq!(
            keys("rcmp"),
            [
                "ask_budget",
                "batch",
                "epsilon_decay",
                "epsilon_end",
                "epsilon_start",
                "give_budget",
                "heads",
                "hidden",
                "learner",
                "lr",
                "mask_probability",
                "mistake_correcting",
                "observation",
                "reachable",
                "replay",
                "target_every",
                "train_every",
                "uncertainty_threshold",
                "warmup"
            ]
        );
    }

    #[test]
    fn the_table_is_in_the_order_of_the_files() {
        let config = with("adhoc-td", &[]);
        let json = serde_json::to_string(&config).unwrap();
        let at = |key: &str| json.find(&format!("\"{key}\"")).unwrap();
        assert!(at("alpha") < at("trace_threshold"));
        assert!(at("trace_threshold") < at("algorithm"));
        assert!(at("algorithm") < at("v_a"));
        assert!(at("v_a") < at("profile"));
        assert!(at("profile") < at("shared_bootstrap"));
    }

    #[test]
    fn missing_keys_take_the_papers_constants() {
        let c: AgentConfig = toml::from_str("algorithm = \"adhoc-visit\"\nv_a = 0\n").unwrap();
        assert_eq!(
            c.algorithm.get::<AdHoc>(),
            Some(&AdHoc {
                v_a: 0.0,
                ..AdHoc::visit()
            })
        );
        let c: AgentConfig = toml::from_str("epsilon = 0\n").unwrap();
        assert_eq!(
            c,
            AgentConfig {
                epsilon: 0.0,
                ..AgentConfig::default()
            }
        );
        let c: AgentConfig = toml::from_str("algorithm = \"advice-reuse\"\n").unwrap();
        let reuse = c.algorithm.get::<AdviceReuse>().unwrap();
        assert_eq!((reuse.reuse_rule, reuse.v_g), (ReuseRule::QChange, 1.5));
        let c: AgentConfig = toml::from_str("algorithm = \"torrey\"\n").unwrap();
        assert_eq!(c.algorithm.get::<Torrey>(), Some(&Torrey::default()));
    }

    #[test]
    fn the_learner_is_the_agents_setting() {
        let c: AgentConfig =
            toml::from_str("algorithm = \"rcmp\"\nlearner = \"ensemble\"\nheads = 3\n").unwrap();
        assert_eq!(
            c.learner,
            LearnerSettings::Ensemble {
                heads: 3,
                mask_probability: 0.5
            }
        );
        // RCMP learns with a DQN of 5 heads unless told otherwise.
        let c: AgentConfig = toml::from_str("algorithm = \"rcmp\"\n").unwrap();
        assert!(matches!(&c.learner, LearnerSettings::Dqn(d) if d.heads == 5));
        let c: AgentConfig =
            toml::from_str("algorithm = \"adhoc-td\"\nlearner = \"ensemble\"\n").unwrap();
        assert_eq!(c.learner.name(), "ensemble");
        let err = |text: &str| toml::from_str::<AgentConfig>(text).unwrap_err().to_string();
        let e = err("heads = 3\n");
        assert!(
            e.contains("`heads`: does not apply to learner sarsa; it belongs to learner ensemble"),
            "{e}"
        );
        let e = err("learner = \"deep\"\n");
        assert!(e.contains("unknown learner `deep`"), "{e}");
        let rcmp_sarsa: AgentConfig =
            toml::from_str("algorithm = \"rcmp\"\nlearner = \"sarsa\"\n").unwrap();
        assert_eq!(rcmp_sarsa.validate().unwrap_err().key, "learner");
    }

    #[test]
    fn a_dqn_is_named_with_its_keys_and_checked_by_key() {
        let read = |text: &str| toml::from_str::<AgentConfig>(text);
        let c = read("algorithm = \"adhoc-td\"\nlearner = \"dqn\"\n").unwrap();
        assert_eq!(
            c.learner,
            LearnerSettings::Dqn(crate::DqnSettings::default())
        );
        c.validate().unwrap();
        let c = read("learner = \"dqn\"\nhidden = 32\nlr = 0.01\nbatch = 16\n").unwrap();
        let LearnerSettings::Dqn(dqn) = &c.learner else {
            panic!("{c:?}");
        };
        assert_eq!(
            (dqn.hidden.as_slice(), dqn.lr, dqn.batch),
            (&[32][..], 0.01, 16)
        );
        // An algorithm that asks by uncertainty gets heads; one head is refused.
        let c = read("algorithm = \"rcmp\"\nlearner = \"dqn\"\n").unwrap();
        assert!(c.learner.meets(LearnerNeed::Uncertainty), "{c:?}");
        c.validate().unwrap();
        let one = read("algorithm = \"rcmp\"\nlearner = \"dqn\"\nheads = 1\n").unwrap();
        let e = one.validate().unwrap_err();
        assert_eq!(e.key, "learner");
        assert!(e.reason.contains("dqn with heads of 2 or more"), "{e}");
        // Each bad value names its key and what it expects.
        let refused = |keys: &str, key: &str, expected: &str| {
            let text = format!("algorithm = \"adhoc-td\"\nlearner = \"dqn\"\n{keys}\n");
            let e = match read(&text) {
                Err(e) => e.to_string(),
                Ok(c) => c.validate().unwrap_err().to_string(),
            };
            assert!(e.contains(&format!("`{key}`")), "{keys}: {e}");
            assert!(e.contains(expected), "{keys}: {e}");
        };
        refused("hidden = 0", "hidden", "1 to 1024 units wide, got 0");
        refused(
            "hidden = [64, 2000]",
            "hidden",
            "1 to 1024 units wide, got 2000",
        );
        refused("hidden = []", "hidden", "1 to 4 layer widths, got 0");
        refused(
            "hidden = [8, 8, 8, 8, 8]",
            "hidden",
            "1 to 4 layer widths, got 5",
        );
        refused("hidden = -3", "hidden", "a list of layer widths");
        refused("lr = -0.001", "lr", "in (0, 1], got -0.001");
        refused(
            "lr = nan",
            "lr",
            "a finite number, got NaN, infinity or null",
        );
        refused(
            "lr = inf",
            "lr",
            "a finite number, got NaN, infinity or null",
        );
        refused(
            "gamma = nan",
            "gamma",
            "a finite number, got NaN, infinity or null",
        );
        refused("epsilon_start = 1.5", "epsilon_start", "in [0, 1], got 1.5");
        refused("epsilon_end = -0.1", "epsilon_end", "in [0, 1], got -0.1");
        refused("mask_probability = 0", "mask_probability", "in (0, 1]");
        refused(
            "batch = 64\nreplay = 32",
            "batch",
            "1 to replay (32), got 64",
        );
        refused("batch = 0", "batch", "got 0");
        refused("replay = 0", "replay", "1 to 1000000 transitions, got 0");
        refused("target_every = 0", "target_every", "at least 1, got 0");
        refused("train_every = 0", "train_every", "at least 1, got 0");
        refused("heads = 17", "heads", "1 to 16, got 17");
        // HFO's features: for a DQN, not for the tabular learners, nor with
        // shared episodes, which carry the paper's state only.
        let hfo = read("learner = \"dqn\"\nobservation = \"hfo\"\n").unwrap();
        hfo.validate().unwrap();
        assert_eq!(hfo.learner.observation(), ObservationSet::Hfo);
        let e = read("observation = \"hfo\"\n").unwrap_err().to_string();
        assert_eq!(
            e.trim_end(),
            "invalid agent config `observation`: does not apply to learner sarsa; it belongs \
             to learner dqn"
        );
        let sharing = "algorithm = \"episode-sharing\"\nlearner = \"dqn\"\nobservation = \"hfo\"\n";
        let e = read(sharing).unwrap().validate().unwrap_err().to_string();
        assert_eq!(
            e,
            "invalid agent config `observation`: `hfo` cannot learn from algorithm \
             episode-sharing's shared episodes, which carry the paper's six features only: use \
             `paper`"
        );
        refused(
            "observation = \"authors\"",
            "observation",
            "unknown variant `authors`",
        );
        let e = read("learner = \"dqnn\"\n").unwrap_err().to_string();
        assert!(
            e.contains("`learner`: unknown learner `dqnn` (expected one of: sarsa, ensemble, dqn)"),
            "{e}"
        );
        // The DQN's keys belong to it alone.
        let e = read("hidden = 64\n").unwrap_err().to_string();
        assert!(
            e.contains("`hidden`: does not apply to learner sarsa; it belongs to learner dqn"),
            "{e}"
        );
    }

    #[test]
    fn network_conditions_read_write_and_travel() {
        let text =
            "algorithm = \"adhoc-td\"\nnetwork = { latency = \"uniform:1,4\", loss = 0.1 }\n";
        let c: AgentConfig = toml::from_str(text).unwrap();
        let n = c.network.unwrap();
        assert_eq!(
            (n.latency, n.loss, n.timeout_ms),
            (Latency::Uniform(1.0, 4.0), 0.1, 5.0)
        );
        // The flat table and the binary form both keep them.
        let json = serde_json::to_string(&c).unwrap();
        assert!(
            json.contains(r#""network":{"latency":"uniform:1,4","loss":0.1,"timeout_ms":5.0}"#),
            "{json}"
        );
        assert_eq!(serde_json::from_str::<AgentConfig>(&json).unwrap(), c);
        let bytes = postcard::to_allocvec(&c).unwrap();
        assert_eq!(postcard::from_bytes::<AgentConfig>(&bytes).unwrap(), c);
        // Without conditions the table has no `network` key.
        let plain = serde_json::to_string(&AgentConfig::default()).unwrap();
        assert!(!plain.contains("network"));
        let e = toml::from_str::<AgentConfig>("network = { jitter = 1 }\n").unwrap_err();
        assert!(e.to_string().contains("jitter"), "{e}");
    }

    #[test]
    fn the_profile_sets_the_defaults_and_keys_override_it() {
        let c: AgentConfig =
            toml::from_str("algorithm = \"adhoc-visit\"\nprofile = \"authors\"\n").unwrap();
        assert_eq!(c.fidelity, Fidelity::of(Profile::Authors));
        assert_eq!(c.algorithm.get::<AdHoc>().unwrap().v_g, 0.2);
        let text = "algorithm = \"adhoc-visit\"\nprofile = \"authors\"\nv_g = 0.5\n\
                    advisor_ties = \"first\"\n";
        let c: AgentConfig = toml::from_str(text).unwrap();
        assert_eq!(c.fidelity.advisor_ties, AdvisorTies::First);
        assert_eq!(c.fidelity.vote_ties, VoteTies::Fixed);
        assert_eq!(c.algorithm.get::<AdHoc>(), Some(&AdHoc::visit()));
        // Without a profile: the paper's.
        let c: AgentConfig = toml::from_str("algorithm = \"adhoc-visit\"\n").unwrap();
        assert_eq!(c.fidelity, Fidelity::of(Profile::Paper));
        let e = toml::from_str::<AgentConfig>("vote_ties = \"alphabetical\"\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("random") && e.contains("fixed"), "{e}");
    }

    #[test]
    fn a_key_of_another_algorithm_is_an_error_naming_it_and_its_algorithms() {
        let err = |text: &str| toml::from_str::<AgentConfig>(text).unwrap_err().to_string();
        let e = err("mistake_correcting = true\n");
        assert!(
            e.contains(
                "`mistake_correcting`: does not apply to algorithm no-advice; \
                 it belongs to adhoc-visit, adhoc-td, torrey"
            ),
            "{e}"
        );
        let e = err("algorithm = \"torrey\"\nsharing_budget = 3\n");
        assert!(
            e.contains(
                "`sharing_budget`: does not apply to algorithm torrey; it belongs to episode-sharing"
            ),
            "{e}"
        );
        let e = err("algorithm = \"episode-sharing\"\nv_g = 1\n");
        assert!(
            e.contains("it belongs to adhoc-visit, adhoc-td, advice-reuse, psaf"),
            "{e}"
        );
        let e = err("algorithm = \"best\"\n");
        assert!(e.contains("unknown algorithm `best`"), "{e}");
        let e = err("alhpa = 0.2\n");
        assert!(e.contains("`alhpa`: not a setting"), "{e}");
        let e = err("algorithm = \"adhoc-td\"\nv_a = \"high\"\n");
        assert!(e.contains("`v_a`: invalid type"), "{e}");
        let e = serde_json::from_str::<AgentConfig>(r#"{"strategy": "random", "v_a": 1}"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`v_a`: does not apply to algorithm random"),
            "{e}"
        );
    }

    #[test]
    fn an_algorithms_setting_is_set_by_its_key() {
        let mut s = AlgorithmSettings::named("adhoc-td").unwrap();
        s.set("ask_budget", 0).unwrap();
        assert_eq!(s.get::<AdHoc>().unwrap().ask_budget, 0);
        assert!(s.set("ask_budget", -1).is_err());
        assert_eq!(s.set("heads", 3).unwrap_err().key, "heads");
        assert!(!s.mistake_correcting());
        s.set("mistake_correcting", true).unwrap();
        assert!(s.mistake_correcting());
        assert_eq!(s.reachable(), Some(Reachable::Everyone));
        let e = AlgorithmSettings::named("no-advice")
            .unwrap()
            .set("mistake_correcting", true)
            .unwrap_err();
        assert_eq!(e.key, "mistake_correcting");
        assert!(e.reason.contains("no-advice"), "{e}");
    }
}
