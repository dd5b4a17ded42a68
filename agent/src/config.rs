//! Every constant of the learner and of the advising strategies (docs/algorithms.md
//! sections 1-3), with the paper's defaults, and its validation.

use proto::STATE_FEATURES;
use serde::{Deserialize, Serialize};

/// Which learner and advising strategy an agent runs (docs/algorithms.md 1-3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StrategyKind {
    /// SARSA(lambda) alone.
    #[default]
    NoAdvice,
    /// Ad hoc advising with the visit-based confidence `Psi = log2 n(s)`.
    AdHocVisit,
    /// Ad hoc advising with `Psi = sqrt(n(s)) * spread of Q(s, .)`.
    AdHocTd,
    /// Importance advising from the fixed teacher `(i + 1) mod n`.
    Torrey,
    /// Tan's episode sharing after goal episodes, with a budget.
    EpisodeSharing,
    /// The authors' random baseline: never learns, never advises.
    Random,
}

impl StrategyKind {
    /// Whether the strategy learns a Q-table (everything but `Random`).
    pub fn learns(self) -> bool {
        self != StrategyKind::Random
    }

    /// Whether the Mistake Correcting option applies to this strategy.
    pub fn supports_mistake_correcting(self) -> bool {
        matches!(
            self,
            StrategyKind::AdHocVisit | StrategyKind::AdHocTd | StrategyKind::Torrey
        )
    }
}

/// The reachable set G(s): whom an ad hoc advisee asks.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reachable {
    /// Every other agent of the team, in id order.
    #[default]
    Everyone,
    /// These agent ids, in the given order (the asking agent itself is skipped).
    Agents(Vec<usize>),
    /// Teammates whose field position is within this distance (metres).
    WithinDistance(f64),
}

/// Lower edge of the first tile: features are normalised to [-1, 1].
pub const TILE_ORIGIN: f64 = -1.0;

/// Every constant of one agent, with the paper's defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AgentConfig {
    /// Learning rate alpha, in (0, 1].
    pub alpha: f64,
    /// Discount factor gamma, in [0, 1].
    pub gamma: f64,
    /// Trace decay lambda, in [0, 1].
    pub lambda: f64,
    /// Exploration probability epsilon, in [0, 1].
    pub epsilon: f64,
    /// Tiles per feature; `6 * tiles_per_feature` must fit 64 bits.
    pub tiles_per_feature: u32,
    /// Width of one tile.
    pub tile_width: f64,
    /// Distance between the lower edges of consecutive tiles.
    pub tile_step: f64,
    /// Traces below this value are dropped, in (0, 1).
    pub trace_threshold: f64,
    /// Ad hoc advisee budget b_ask.
    pub ask_budget: u64,
    /// Ad hoc advisor budget b_give.
    pub give_budget: u64,
    /// Scaling v_a of P_ask.
    pub v_a: f64,
    /// Scaling v_g of P_give for AdHocVisit.
    pub v_g_visit: f64,
    /// Scaling v_g of P_give for AdHocTD.
    pub v_g_td: f64,
    /// Torrey's importance threshold t.
    pub torrey_threshold: f64,
    /// Torrey teacher budget.
    pub torrey_budget: u64,
    /// EpisodeSharing budget (one unit per transition per receiver).
    pub sharing_budget: u64,
    /// The strategy this agent runs.
    pub strategy: StrategyKind,
    /// Mistake Correcting (AdHocVisit, AdHocTD, Torrey only): the advisee sends
    /// its own epsilon-greedy choice along, and plays it when no advice comes.
    pub mistake_correcting: bool,
    /// The reachable set G of an ad hoc advisee.
    pub reachable: Reachable,
}

impl Default for AgentConfig {
    fn default() -> Self {
        Self {
            alpha: 0.1,
            gamma: 0.9,
            lambda: 0.9,
            epsilon: 0.1,
            tiles_per_feature: 10,
            tile_width: 0.5,
            tile_step: 0.2,
            trace_threshold: 1e-4,
            ask_budget: 1000,
            give_budget: 1000,
            v_a: 0.5,
            v_g_visit: 0.5,
            v_g_td: 1.5,
            torrey_threshold: 0.01,
            torrey_budget: 1000,
            sharing_budget: 1000,
            strategy: StrategyKind::NoAdvice,
            mistake_correcting: false,
            reachable: Reachable::Everyone,
        }
    }
}

/// A configuration value out of its allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("invalid agent config `{key}`: {reason}")]
pub struct ConfigError {
    /// The offending key, as spelled in the configuration.
    pub key: &'static str,
    /// What is wrong with its value.
    pub reason: String,
}

impl ConfigError {
    pub(crate) fn new(key: &'static str, reason: impl Into<String>) -> Self {
        Self {
            key,
            reason: reason.into(),
        }
    }
}

/// `Ok` when `value` is finite and `ok`, else an error saying what `value`
/// must be.
fn require(key: &'static str, value: f64, rule: &str, ok: bool) -> Result<(), ConfigError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(ConfigError::new(
            key,
            format!("must be {rule}, got {value}"),
        ))
    }
}

/// A probability-like value in [0, 1].
fn require_unit(key: &'static str, value: f64) -> Result<(), ConfigError> {
    require(key, value, "in [0, 1]", (0.0..=1.0).contains(&value))
}

/// A finite value >= 0.
fn require_non_negative(key: &'static str, value: f64) -> Result<(), ConfigError> {
    require(key, value, "finite and >= 0", value >= 0.0)
}

impl AgentConfig {
    /// Returns the first invalid value, naming its key.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let (alpha, threshold) = (self.alpha, self.trace_threshold);
        require("alpha", alpha, "in (0, 1]", alpha > 0.0 && alpha <= 1.0)?;
        require_unit("gamma", self.gamma)?;
        require_unit("lambda", self.lambda)?;
        require_unit("epsilon", self.epsilon)?;
        require(
            "trace_threshold",
            threshold,
            "in (0, 1)",
            threshold > 0.0 && threshold < 1.0,
        )?;
        self.validate_tiles()?;
        require_non_negative("v_a", self.v_a)?;
        require_non_negative("v_g_visit", self.v_g_visit)?;
        require_non_negative("v_g_td", self.v_g_td)?;
        require_non_negative("torrey_threshold", self.torrey_threshold)?;
        if self.mistake_correcting && !self.strategy.supports_mistake_correcting() {
            return Err(ConfigError::new(
                "mistake_correcting",
                format!(
                    "only for ad-hoc-visit, ad-hoc-td and torrey, not {:?}",
                    self.strategy
                ),
            ));
        }
        if let Reachable::WithinDistance(d) = self.reachable {
            require_non_negative("reachable", d)?;
        }
        Ok(())
    }

    fn validate_tiles(&self) -> Result<(), ConfigError> {
        let tiles = self.tiles_per_feature as usize;
        if tiles == 0 {
            return Err(ConfigError::new("tiles_per_feature", "must be at least 1"));
        }
        if tiles * STATE_FEATURES > 64 {
            return Err(ConfigError::new(
                "tiles_per_feature",
                format!("{STATE_FEATURES} features x {tiles} tiles do not fit a 64-bit state key"),
            ));
        }
        require(
            "tile_width",
            self.tile_width,
            "finite and > 0",
            self.tile_width > 0.0,
        )?;
        require(
            "tile_step",
            self.tile_step,
            "finite and > 0",
            self.tile_step > 0.0,
        )?;
        if self.tile_step > self.tile_width {
            return Err(ConfigError::new(
                "tile_step",
                format!(
                    "{} exceeds tile_width {}: the tiles leave gaps",
                    self.tile_step, self.tile_width
                ),
            ));
        }
        let top = TILE_ORIGIN + self.tile_step * (tiles - 1) as f64 + self.tile_width;
        if top < 1.0 {
            return Err(ConfigError::new(
                "tiles_per_feature",
                format!("the last tile ends at {top}: the tiles do not cover [-1, 1]"),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key_of(config: AgentConfig) -> &'static str {
        config.validate().unwrap_err().key
    }

    #[test]
    fn defaults_are_the_papers_and_valid() {
        let c = AgentConfig::default();
        c.validate().unwrap();
        assert_eq!(
            (c.alpha, c.gamma, c.lambda, c.epsilon),
            (0.1, 0.9, 0.9, 0.1)
        );
        assert_eq!(
            (c.tiles_per_feature, c.tile_width, c.tile_step),
            (10, 0.5, 0.2)
        );
        assert_eq!(
            (
                c.ask_budget,
                c.give_budget,
                c.torrey_budget,
                c.sharing_budget
            ),
            (1000, 1000, 1000, 1000)
        );
        assert_eq!(
            (c.v_a, c.v_g_visit, c.v_g_td, c.torrey_threshold),
            (0.5, 0.5, 1.5, 0.01)
        );
    }

    #[test]
    fn bad_values_name_their_key() {
        let base = AgentConfig::default;
        assert_eq!(
            key_of(AgentConfig {
                alpha: 0.0,
                ..base()
            }),
            "alpha"
        );
        assert_eq!(
            key_of(AgentConfig {
                alpha: 1.5,
                ..base()
            }),
            "alpha"
        );
        assert_eq!(
            key_of(AgentConfig {
                gamma: f64::NAN,
                ..base()
            }),
            "gamma"
        );
        assert_eq!(
            key_of(AgentConfig {
                epsilon: -0.1,
                ..base()
            }),
            "epsilon"
        );
        assert_eq!(
            key_of(AgentConfig {
                trace_threshold: 1.0,
                ..base()
            }),
            "trace_threshold"
        );
        assert_eq!(
            key_of(AgentConfig {
                tiles_per_feature: 0,
                ..base()
            }),
            "tiles_per_feature"
        );
        // 6 x 11 = 66 bits > 64.
        assert_eq!(
            key_of(AgentConfig {
                tiles_per_feature: 11,
                ..base()
            }),
            "tiles_per_feature"
        );
        assert_eq!(
            key_of(AgentConfig {
                tile_width: 0.0,
                ..base()
            }),
            "tile_width"
        );
        assert_eq!(
            key_of(AgentConfig {
                tile_step: 0.6,
                ..base()
            }),
            "tile_step"
        );
        // 5 tiles of step 0.2: the last ends at -1 + 0.8 + 0.5 = 0.3 < 1.
        assert_eq!(
            key_of(AgentConfig {
                tiles_per_feature: 5,
                ..base()
            }),
            "tiles_per_feature"
        );
        assert_eq!(
            key_of(AgentConfig {
                v_g_td: -1.0,
                ..base()
            }),
            "v_g_td"
        );
        assert_eq!(
            key_of(AgentConfig {
                mistake_correcting: true,
                ..base()
            }),
            "mistake_correcting"
        );
        let far = Reachable::WithinDistance(f64::INFINITY);
        assert_eq!(
            key_of(AgentConfig {
                reachable: far,
                ..base()
            }),
            "reachable"
        );
        let msg = AgentConfig {
            alpha: 2.0,
            ..base()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert_eq!(
            msg,
            "invalid agent config `alpha`: must be in (0, 1], got 2"
        );
    }

    #[test]
    fn the_papers_five_tiles_are_valid() {
        // Five tiles of width 0.5 spread over [-1, 1]: step 2/5 = 0.4, last tile [0.6, 1.1].
        let c = AgentConfig {
            tiles_per_feature: 5,
            tile_step: 0.4,
            ..AgentConfig::default()
        };
        c.validate().unwrap();
    }

    #[test]
    fn serde_uses_defaults_and_rejects_unknown_keys() {
        let c: AgentConfig =
            serde_json::from_str(r#"{"strategy": "ad-hoc-td", "reachable": {"agents": [1, 2]}}"#)
                .unwrap();
        assert_eq!(c.strategy, StrategyKind::AdHocTd);
        assert_eq!(c.reachable, Reachable::Agents(vec![1, 2]));
        assert_eq!(c.alpha, 0.1);
        let err = serde_json::from_str::<AgentConfig>(r#"{"alhpa": 0.2}"#).unwrap_err();
        assert!(err.to_string().contains("alhpa"), "{err}");
    }
}
