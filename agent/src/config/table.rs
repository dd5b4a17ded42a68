//! The two serde forms of [`AgentConfig`]: one flat table for human-readable
//! formats (JSON, TOML), the plain structure for binary ones (postcard, which
//! is not self-describing).

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::AgentConfig;
use crate::advice::Reachable;
use crate::advises::Advises;
use crate::algorithm::Algorithm;
use crate::fidelity::{
    AdvisorTies, Fidelity, Profile, SharedBootstrap, TorreyIntent, TorreyUnknownState, VoteTies,
};
use crate::link::NetworkConditions;
use crate::strategy::{
    AdHoc, Budgeted, PeerLearning, Psaf, Rcmp, Reuse, ReuseRule, Strategy, Torrey,
};

impl Serialize for AgentConfig {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        if serializer.is_human_readable() {
            Table::from(self).serialize(serializer)
        } else {
            Plain::serialize(self, serializer)
        }
    }
}

impl<'de> Deserialize<'de> for AgentConfig {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        if deserializer.is_human_readable() {
            Table::deserialize(deserializer)?
                .into_config()
                .map_err(D::Error::custom)
        } else {
            Plain::deserialize(deserializer)
        }
    }
}

/// The binary form: every field in order, the strategy as an enum.
#[derive(Serialize, Deserialize)]
#[serde(remote = "AgentConfig")]
struct Plain {
    alpha: f64,
    gamma: f64,
    lambda: f64,
    epsilon: f64,
    tiles_per_feature: u32,
    tile_width: f64,
    tile_step: f64,
    trace_threshold: f64,
    strategy: Strategy,
    fidelity: Fidelity,
    network: Option<NetworkConditions>,
    advises: Advises,
}

/// The flat table: the learner's keys, `algorithm`, and the keys of that
/// algorithm (named as the fields of its variant); the others are absent.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct Table {
    alpha: f64,
    gamma: f64,
    lambda: f64,
    epsilon: f64,
    tiles_per_feature: u32,
    tile_width: f64,
    tile_step: f64,
    trace_threshold: f64,
    /// Read as `strategy` too, its spelling before 0.2.
    #[serde(alias = "strategy")]
    algorithm: Algorithm,
    #[serde(skip_serializing_if = "Option::is_none")]
    v_a: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    v_g: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ask_budget: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    give_budget: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mistake_correcting: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    importance_threshold: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sharing_budget: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    reachable: Option<Reachable>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ask_probability: Option<f64>,
    /// Written only when on, so that results from before it keep their identity.
    #[serde(skip_serializing_if = "Option::is_none")]
    backoff: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    reuse_rule: Option<ReuseRule>,
    #[serde(skip_serializing_if = "Option::is_none")]
    q_change_threshold: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    reuse_decay: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    temperature: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    trust_lr: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    follow_steps: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    heads: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mask_probability: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    uncertainty_threshold: Option<f64>,
    profile: Profile,
    #[serde(skip_serializing_if = "Option::is_none")]
    torrey_unknown_state: Option<TorreyUnknownState>,
    #[serde(skip_serializing_if = "Option::is_none")]
    torrey_intent: Option<TorreyIntent>,
    #[serde(skip_serializing_if = "Option::is_none")]
    advisor_ties: Option<AdvisorTies>,
    #[serde(skip_serializing_if = "Option::is_none")]
    vote_ties: Option<VoteTies>,
    #[serde(skip_serializing_if = "Option::is_none")]
    shared_bootstrap: Option<SharedBootstrap>,
    #[serde(skip_serializing_if = "Option::is_none")]
    network: Option<NetworkConditions>,
    /// Written only when not honest, so that results from before it keep
    /// their identity.
    #[serde(skip_serializing_if = "Option::is_none")]
    advises: Option<Advises>,
}

impl Default for Table {
    /// The learner's defaults; no strategy or fidelity key given.
    fn default() -> Self {
        Table {
            torrey_unknown_state: None,
            torrey_intent: None,
            advisor_ties: None,
            vote_ties: None,
            shared_bootstrap: None,
            ..Table::from(&AgentConfig::default())
        }
    }
}

impl From<&AgentConfig> for Table {
    fn from(c: &AgentConfig) -> Self {
        let mut table = Table {
            alpha: c.alpha,
            gamma: c.gamma,
            lambda: c.lambda,
            epsilon: c.epsilon,
            tiles_per_feature: c.tiles_per_feature,
            tile_width: c.tile_width,
            tile_step: c.tile_step,
            trace_threshold: c.trace_threshold,
            algorithm: c.strategy.name(),
            v_a: None,
            v_g: None,
            ask_budget: None,
            give_budget: None,
            mistake_correcting: None,
            importance_threshold: None,
            sharing_budget: None,
            reachable: None,
            ask_probability: None,
            backoff: None,
            reuse_rule: None,
            q_change_threshold: None,
            reuse_decay: None,
            temperature: None,
            trust_lr: None,
            follow_steps: None,
            heads: None,
            mask_probability: None,
            uncertainty_threshold: None,
            profile: c.fidelity.profile,
            torrey_unknown_state: Some(c.fidelity.torrey_unknown_state),
            torrey_intent: Some(c.fidelity.torrey_intent),
            advisor_ties: Some(c.fidelity.advisor_ties),
            vote_ties: Some(c.fidelity.vote_ties),
            shared_bootstrap: Some(c.fidelity.shared_bootstrap),
            network: c.network,
            advises: (c.advises != Advises::Honest).then_some(c.advises),
        };
        let ad_hoc = |table: &mut Table, a: &AdHoc| {
            table.v_a = Some(a.v_a);
            table.v_g = Some(a.v_g);
            table.ask_budget = Some(a.ask_budget);
            table.give_budget = Some(a.give_budget);
            table.reachable = Some(a.reachable.clone());
            table.backoff = a.backoff.then_some(true);
            table.trust_lr = a.trust_lr;
        };
        match &c.strategy {
            Strategy::AdHoc(a) => {
                ad_hoc(&mut table, a);
                table.mistake_correcting = Some(a.mistake_correcting);
            }
            Strategy::Psaf(p) => {
                table.v_a = Some(p.v_a);
                table.v_g = Some(p.v_g);
                table.ask_budget = Some(p.ask_budget);
                table.give_budget = Some(p.give_budget);
                table.reachable = Some(p.reachable.clone());
            }
            Strategy::Rcmp(r) => {
                table.heads = Some(r.heads);
                table.mask_probability = Some(r.mask_probability);
                table.uncertainty_threshold = Some(r.uncertainty_threshold);
                table.ask_budget = Some(r.ask_budget);
                table.give_budget = Some(r.give_budget);
                table.reachable = Some(r.reachable.clone());
            }
            Strategy::PeerLearning(p) => {
                table.ask_budget = Some(p.ask_budget);
                table.give_budget = Some(p.give_budget);
                table.reachable = Some(p.reachable.clone());
                table.temperature = Some(p.temperature);
                table.trust_lr = Some(p.trust_lr);
                table.follow_steps = Some(p.follow_steps);
            }
            Strategy::AdviceReuse(a, r) => {
                ad_hoc(&mut table, a);
                table.reuse_rule = Some(r.reuse_rule);
                table.q_change_threshold = Some(r.q_change_threshold);
                table.reuse_decay = Some(r.reuse_decay);
            }
            Strategy::Torrey(t) => {
                table.importance_threshold = Some(t.importance_threshold);
                table.give_budget = Some(t.give_budget);
                table.mistake_correcting = Some(t.mistake_correcting);
            }
            Strategy::EpisodeSharing { sharing_budget } => {
                table.sharing_budget = Some(*sharing_budget);
            }
            Strategy::EarlyAdvising(b) | Strategy::RandomAdvising(b) => {
                table.ask_budget = Some(b.ask_budget);
                table.give_budget = Some(b.give_budget);
                table.reachable = Some(b.reachable.clone());
                // Early advising asks at every step: its probability is no setting.
                if matches!(c.strategy, Strategy::RandomAdvising(_)) {
                    table.ask_probability = Some(b.ask_probability);
                }
            }
            Strategy::NoAdvice | Strategy::Random | Strategy::External => {}
        }
        table
    }
}

/// Moves a key's value, when given, into its field.
fn take<T>(key: &mut Option<T>, field: &mut T) {
    if let Some(value) = key.take() {
        *field = value;
    }
}

impl Table {
    /// The configuration, with the profile's constants for the strategy and
    /// fidelity keys left out; a key the strategy does not have is an error
    /// naming it.
    fn into_config(mut self) -> Result<AgentConfig, String> {
        let mut strategy = Strategy::of(self.algorithm, self.profile);
        let mut fidelity = Fidelity::of(self.profile);
        take(
            &mut self.torrey_unknown_state,
            &mut fidelity.torrey_unknown_state,
        );
        take(&mut self.torrey_intent, &mut fidelity.torrey_intent);
        take(&mut self.advisor_ties, &mut fidelity.advisor_ties);
        take(&mut self.vote_ties, &mut fidelity.vote_ties);
        take(&mut self.shared_bootstrap, &mut fidelity.shared_bootstrap);
        match &mut strategy {
            Strategy::AdHoc(a) => {
                self.take_ad_hoc(a);
                take(&mut self.mistake_correcting, &mut a.mistake_correcting);
            }
            Strategy::Psaf(Psaf {
                v_a,
                v_g,
                ask_budget,
                give_budget,
                reachable,
            }) => {
                take(&mut self.v_a, v_a);
                take(&mut self.v_g, v_g);
                take(&mut self.ask_budget, ask_budget);
                take(&mut self.give_budget, give_budget);
                take(&mut self.reachable, reachable);
            }
            Strategy::Rcmp(Rcmp {
                heads,
                mask_probability,
                uncertainty_threshold,
                ask_budget,
                give_budget,
                reachable,
            }) => {
                take(&mut self.heads, heads);
                take(&mut self.mask_probability, mask_probability);
                take(&mut self.uncertainty_threshold, uncertainty_threshold);
                take(&mut self.ask_budget, ask_budget);
                take(&mut self.give_budget, give_budget);
                take(&mut self.reachable, reachable);
            }
            Strategy::PeerLearning(PeerLearning {
                ask_budget,
                give_budget,
                reachable,
                temperature,
                trust_lr,
                follow_steps,
            }) => {
                take(&mut self.ask_budget, ask_budget);
                take(&mut self.give_budget, give_budget);
                take(&mut self.reachable, reachable);
                take(&mut self.temperature, temperature);
                take(&mut self.trust_lr, trust_lr);
                take(&mut self.follow_steps, follow_steps);
            }
            Strategy::AdviceReuse(a, r) => {
                self.take_ad_hoc(a);
                let Reuse {
                    reuse_rule,
                    q_change_threshold,
                    reuse_decay,
                } = r;
                take(&mut self.reuse_rule, reuse_rule);
                take(&mut self.q_change_threshold, q_change_threshold);
                take(&mut self.reuse_decay, reuse_decay);
            }
            Strategy::Torrey(Torrey {
                importance_threshold,
                give_budget,
                mistake_correcting,
            }) => {
                take(&mut self.importance_threshold, importance_threshold);
                take(&mut self.give_budget, give_budget);
                take(&mut self.mistake_correcting, mistake_correcting);
            }
            Strategy::EpisodeSharing { sharing_budget } => {
                take(&mut self.sharing_budget, sharing_budget);
            }
            Strategy::EarlyAdvising(Budgeted {
                ask_budget,
                give_budget,
                reachable,
                ..
            }) => {
                take(&mut self.ask_budget, ask_budget);
                take(&mut self.give_budget, give_budget);
                take(&mut self.reachable, reachable);
            }
            Strategy::RandomAdvising(Budgeted {
                ask_probability,
                ask_budget,
                give_budget,
                reachable,
            }) => {
                take(&mut self.ask_probability, ask_probability);
                take(&mut self.ask_budget, ask_budget);
                take(&mut self.give_budget, give_budget);
                take(&mut self.reachable, reachable);
            }
            Strategy::NoAdvice | Strategy::Random | Strategy::External => {}
        }
        if let Some(key) = self
            .strategy_keys()
            .find_map(|(key, given)| given.then_some(key))
        {
            let owners: Vec<&str> = Algorithm::ALL
                .into_iter()
                .filter(|&name| has_key(name, key))
                .map(Algorithm::name)
                .collect();
            return Err(format!(
                "key `{key}` does not apply to algorithm {}; it belongs to {}",
                self.algorithm,
                owners.join(", ")
            ));
        }
        Ok(AgentConfig {
            alpha: self.alpha,
            gamma: self.gamma,
            lambda: self.lambda,
            epsilon: self.epsilon,
            tiles_per_feature: self.tiles_per_feature,
            tile_width: self.tile_width,
            tile_step: self.tile_step,
            trace_threshold: self.trace_threshold,
            strategy,
            fidelity,
            network: self.network,
            advises: self.advises.unwrap_or_default(),
        })
    }

    /// Moves the keys every ad hoc method has into `a`.
    fn take_ad_hoc(&mut self, a: &mut AdHoc) {
        let AdHoc {
            confidence: _,
            v_a,
            v_g,
            ask_budget,
            give_budget,
            mistake_correcting: _,
            reachable,
            backoff,
            trust_lr,
        } = a;
        take(&mut self.v_a, v_a);
        take(&mut self.v_g, v_g);
        take(&mut self.ask_budget, ask_budget);
        take(&mut self.give_budget, give_budget);
        take(&mut self.reachable, reachable);
        take(&mut self.backoff, backoff);
        if let Some(lr) = self.trust_lr.take() {
            *trust_lr = Some(lr);
        }
    }

    /// Every strategy key and whether it is present.
    fn strategy_keys(&self) -> impl Iterator<Item = (&'static str, bool)> {
        [
            ("v_a", self.v_a.is_some()),
            ("v_g", self.v_g.is_some()),
            ("ask_budget", self.ask_budget.is_some()),
            ("give_budget", self.give_budget.is_some()),
            ("mistake_correcting", self.mistake_correcting.is_some()),
            ("importance_threshold", self.importance_threshold.is_some()),
            ("sharing_budget", self.sharing_budget.is_some()),
            ("reachable", self.reachable.is_some()),
            ("ask_probability", self.ask_probability.is_some()),
            ("backoff", self.backoff.is_some()),
            ("reuse_rule", self.reuse_rule.is_some()),
            ("q_change_threshold", self.q_change_threshold.is_some()),
            ("reuse_decay", self.reuse_decay.is_some()),
            ("temperature", self.temperature.is_some()),
            ("trust_lr", self.trust_lr.is_some()),
            ("follow_steps", self.follow_steps.is_some()),
            ("heads", self.heads.is_some()),
            ("mask_probability", self.mask_probability.is_some()),
            (
                "uncertainty_threshold",
                self.uncertainty_threshold.is_some(),
            ),
        ]
        .into_iter()
    }
}

/// Whether strategy `name` has the strategy key `key`.
fn has_key(name: Algorithm, key: &str) -> bool {
    let mut strategy = Strategy::from(name);
    // `backoff` and `trust_lr` are written only when on: count them as the
    // ad hoc methods' keys.
    if let Strategy::AdHoc(a) | Strategy::AdviceReuse(a, _) = &mut strategy {
        a.backoff = true;
        a.trust_lr = Some(0.1);
    }
    let config = AgentConfig {
        strategy,
        ..AgentConfig::default()
    };
    Table::from(&config)
        .strategy_keys()
        .any(|(k, given)| given && k == key)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::Latency;
    use crate::strategy::Confidence;

    /// One configuration of every strategy, none with only its defaults.
    fn every_strategy() -> Vec<AgentConfig> {
        let with = |strategy| AgentConfig {
            alpha: 0.2,
            epsilon: 0.05,
            strategy,
            ..AgentConfig::default()
        };
        vec![
            with(Strategy::NoAdvice),
            with(Strategy::AdHoc(AdHoc {
                v_a: 0.25,
                ask_budget: 7,
                reachable: Reachable::Agents(vec![2, 0]),
                ..AdHoc::visit()
            })),
            with(Strategy::AdHoc(AdHoc {
                v_g: 3.0,
                give_budget: 0,
                mistake_correcting: true,
                reachable: Reachable::WithinDistance(12.5),
                ..AdHoc::new(Confidence::Td)
            })),
            with(Strategy::Torrey(Torrey {
                importance_threshold: 0.5,
                give_budget: 3,
                mistake_correcting: true,
            })),
            with(Strategy::EpisodeSharing { sharing_budget: 9 }),
            with(Strategy::Random),
            with(Strategy::External),
            with(Strategy::EarlyAdvising(Budgeted {
                ask_budget: 5,
                ..Budgeted::new(1.0)
            })),
            with(Strategy::AdHoc(AdHoc {
                backoff: true,
                ..AdHoc::visit()
            })),
            with(Strategy::AdviceReuse(
                AdHoc {
                    give_budget: 4,
                    ..AdHoc::td()
                },
                Reuse {
                    reuse_rule: ReuseRule::Decay,
                    reuse_decay: 0.5,
                    ..Reuse::default()
                },
            )),
            with(Strategy::PeerLearning(PeerLearning {
                temperature: 0.5,
                follow_steps: 3,
                ..PeerLearning::default()
            })),
            with(Strategy::Rcmp(Rcmp {
                heads: 3,
                uncertainty_threshold: 0.2,
                ..Rcmp::default()
            })),
            with(Strategy::Psaf(Psaf {
                v_g: 0.25,
                ..Psaf::default()
            })),
            with(Strategy::RandomAdvising(Budgeted {
                ask_probability: 0.3,
                reachable: Reachable::Agents(vec![2]),
                ..Budgeted::new(0.5)
            })),
            AgentConfig {
                fidelity: Fidelity {
                    vote_ties: VoteTies::Random,
                    ..Fidelity::of(Profile::Authors)
                },
                ..with(Strategy::of(Algorithm::AdHocVisit, Profile::Authors))
            },
        ]
    }

    #[test]
    fn every_strategy_round_trips_through_postcard_json_and_toml() {
        for config in every_strategy() {
            let name = config.strategy.name();
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

    #[test]
    fn the_table_shows_only_the_strategys_keys() {
        let keys = |name: Algorithm| {
            let config = AgentConfig {
                strategy: Strategy::from(name),
                ..AgentConfig::default()
            };
            let serde_json::Value::Object(map) = serde_json::to_value(&config).unwrap() else {
                panic!("a table expected");
            };
            let learner = [
                "alpha",
                "gamma",
                "lambda",
                "epsilon",
                "tiles_per_feature",
                "tile_width",
                "tile_step",
                "trace_threshold",
                "algorithm",
                "profile",
                "torrey_unknown_state",
                "torrey_intent",
                "advisor_ties",
                "vote_ties",
                "shared_bootstrap",
            ];
            let mut own: Vec<String> = map
                .keys()
                .filter(|k| !learner.contains(&k.as_str()))
                .cloned()
                .collect();
            own.sort();
            assert_eq!(map["algorithm"], name.name());
            own
        };
        assert!(keys(Algorithm::NoAdvice).is_empty());
        assert!(keys(Algorithm::Random).is_empty());
        let ad_hoc = [
            "ask_budget",
            "give_budget",
            "mistake_correcting",
            "reachable",
            "v_a",
            "v_g",
        ];
        assert_eq!(keys(Algorithm::AdHocVisit), ad_hoc);
        assert_eq!(keys(Algorithm::AdHocTd), ad_hoc);
        assert_eq!(
            keys(Algorithm::Torrey),
            ["give_budget", "importance_threshold", "mistake_correcting"]
        );
        assert_eq!(keys(Algorithm::EpisodeSharing), ["sharing_budget"]);
    }

    #[test]
    fn missing_keys_take_the_papers_constants() {
        let c: AgentConfig = toml::from_str("algorithm = \"adhoc-visit\"\nv_a = 0\n").unwrap();
        assert_eq!(
            c.strategy,
            Strategy::AdHoc(AdHoc {
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
        let Strategy::AdHoc(a) = &c.strategy else {
            panic!("ad hoc expected");
        };
        assert_eq!(a.v_g, 0.2);
        let text = "algorithm = \"adhoc-visit\"\nprofile = \"authors\"\nv_g = 0.5\n\
                    advisor_ties = \"first\"\n";
        let c: AgentConfig = toml::from_str(text).unwrap();
        assert_eq!(c.fidelity.advisor_ties, AdvisorTies::First);
        assert_eq!(c.fidelity.vote_ties, VoteTies::Fixed);
        assert_eq!(c.strategy, Strategy::AdHoc(AdHoc::visit()));
        // Without a profile: the paper's.
        let c: AgentConfig = toml::from_str("algorithm = \"adhoc-visit\"\n").unwrap();
        assert_eq!(c.fidelity, Fidelity::of(Profile::Paper));
        let e = toml::from_str::<AgentConfig>("vote_ties = \"alphabetical\"\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("random") && e.contains("fixed"), "{e}");
    }

    #[test]
    fn a_key_of_another_strategy_is_an_error_naming_it_and_its_strategies() {
        let err = |text: &str| toml::from_str::<AgentConfig>(text).unwrap_err().to_string();
        let e = err("mistake_correcting = true\n");
        assert!(
            e.contains(
                "key `mistake_correcting` does not apply to algorithm no-advice; \
                 it belongs to adhoc-visit, adhoc-td, torrey"
            ),
            "{e}"
        );
        let e = err("algorithm = \"torrey\"\nsharing_budget = 3\n");
        assert!(
            e.contains(
                "`sharing_budget` does not apply to algorithm torrey; it belongs to episode-sharing"
            ),
            "{e}"
        );
        let e = err("algorithm = \"episode-sharing\"\nv_g = 1\n");
        assert!(e.contains("it belongs to adhoc-visit, adhoc-td"), "{e}");
        let e = err("algorithm = \"best\"\n");
        assert!(e.contains("unknown algorithm `best`"), "{e}");
        let e = serde_json::from_str::<AgentConfig>(r#"{"strategy": "random", "v_a": 1}"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`v_a` does not apply to algorithm random"),
            "{e}"
        );
    }
}
