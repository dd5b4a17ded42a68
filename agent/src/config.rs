//! Every constant of one agent: the learner's (docs/algorithms.md section 1)
//! and its strategy's (sections 2-3), with the paper's defaults, and their
//! validation.

mod table;

use proto::STATE_FEATURES;

use crate::advises::Advises;
use crate::algorithm_settings::AlgorithmSettings;
use crate::config_error::{AgentConfigError, require, require_unit};
use crate::fidelity::Fidelity;
use crate::learner_settings::{LearnerSettings, ObservationSet};
use crate::link::NetworkConditions;
use crate::method::LearnerNeed;

/// Lower edge of the first tile: features are normalised to [-1, 1].
pub const TILE_ORIGIN: f64 = -1.0;

/// Every constant of one agent, with the paper's defaults.
///
/// Human-readable formats (JSON, TOML) see one flat table: the learner's
/// shared keys below, `learner` and its own keys when it is not the
/// algorithm's default, `algorithm` (an [`Algorithm`](crate::Algorithm);
/// read as `strategy` too) and the keys of that algorithm's settings, then
/// `profile` and the [`Fidelity`] settings (named as its fields; they apply
/// to every algorithm), `network` and `advises`. Missing keys take their
/// defaults, the fidelity settings and AdHocVisit's `v_g` those of
/// `profile`; an unknown key, or a key of another algorithm or learner, is
/// an error naming it. Binary formats (postcard) carry the same table as
/// JSON text.
#[derive(Clone, Debug, PartialEq)]
pub struct AgentConfig {
    /// Learning rate alpha, in (0, 1].
    pub alpha: f64,
    /// Discount factor gamma, in [0, 1].
    pub gamma: f64,
    /// EligibilityTrace decay lambda, in [0, 1].
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
    /// The learner and its own settings.
    pub learner: LearnerSettings,
    /// The advising algorithm and its settings.
    pub algorithm: AlgorithmSettings,
    /// The rules where the paper and the authors' code differ.
    pub fidelity: Fidelity,
    /// Network conditions of its advice messages; none: every message
    /// arrives at once.
    pub network: Option<NetworkConditions>,
    /// What it answers as an advisor: honest advice, or wrong advice.
    pub advises: Advises,
    /// Tell every agent once when its give budget is spent, so that they
    /// ask it no more (default off: the paper's agents keep asking).
    pub announce_exhausted: bool,
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
            learner: LearnerSettings::Sarsa,
            algorithm: AlgorithmSettings::default(),
            fidelity: Fidelity::default(),
            network: None,
            advises: Advises::Honest,
            announce_exhausted: false,
        }
    }
}

impl AgentConfig {
    /// Returns the first invalid value, naming its key.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
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
        if let Some(network) = &self.network {
            network.validate()?;
        }
        self.learner.validate()?;
        let algorithm = self.algorithm.name();
        if self.learner.observation() == ObservationSet::Hfo && algorithm.shares_episodes() {
            return Err(AgentConfigError::new(
                "observation",
                format!(
                    "`hfo` cannot learn from algorithm {algorithm}'s shared episodes, which \
                     carry the paper's six features only: use `paper`"
                ),
            ));
        }
        // An agent that never asks (an expert's ask budget of 0) needs no
        // uncertainty.
        let asks = self.algorithm.setting("ask_budget") != Some(0.into());
        let need = algorithm.learner_need();
        if asks && !self.learner.meets(need) {
            let what = match need {
                LearnerNeed::Network => {
                    "a neural learner that learns a batch by a gradient step (dqn)"
                }
                _ => {
                    "a learner that measures its uncertainty (ensemble, or dqn with heads of 2 or more)"
                }
            };
            return Err(AgentConfigError::new(
                "learner",
                format!(
                    "algorithm {algorithm} needs {what}, not {}",
                    self.learner.name()
                ),
            ));
        }
        self.algorithm.validate()
    }

    /// The paper's defaults with `algorithm` (and its learner) under the
    /// defaults of `profile`.
    pub fn of(algorithm: crate::Algorithm, profile: crate::Profile) -> Self {
        Self {
            learner: LearnerSettings::for_need(algorithm.learner_need()),
            algorithm: AlgorithmSettings::of(algorithm, profile),
            fidelity: Fidelity::of(profile),
            ..Self::default()
        }
    }

    fn validate_tiles(&self) -> Result<(), AgentConfigError> {
        let tiles = self.tiles_per_feature as usize;
        if tiles == 0 {
            return Err(AgentConfigError::new(
                "tiles_per_feature",
                "must be at least 1",
            ));
        }
        if tiles * STATE_FEATURES > 64 {
            return Err(AgentConfigError::new(
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
            return Err(AgentConfigError::new(
                "tile_step",
                format!(
                    "{} exceeds tile_width {}: the tiles leave gaps",
                    self.tile_step, self.tile_width
                ),
            ));
        }
        let top = TILE_ORIGIN + self.tile_step * (tiles - 1) as f64 + self.tile_width;
        if top < 1.0 {
            return Err(AgentConfigError::new(
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
    use crate::advice::Reachable;
    use crate::strategy::AdHoc;

    fn key_of(config: AgentConfig) -> String {
        config.validate().unwrap_err().key
    }

    /// `name`'s settings with its `AdHoc` changed by `change`.
    fn ad_hoc(name: &str, change: impl FnOnce(&mut AdHoc)) -> AlgorithmSettings {
        let mut settings = AlgorithmSettings::named(name).unwrap();
        change(settings.get_mut::<AdHoc>().unwrap());
        settings
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
        assert_eq!(c.algorithm.name().name(), "no-advice");
        assert_eq!(c.learner, LearnerSettings::Sarsa);
    }

    #[test]
    fn bad_values_name_their_key() {
        type Change = fn(&mut AgentConfig);
        let cases: [(Change, &str); 14] = [
            (|c| c.alpha = 0.0, "alpha"),
            (|c| c.alpha = 1.5, "alpha"),
            (|c| c.gamma = f64::NAN, "gamma"),
            (|c| c.epsilon = -0.1, "epsilon"),
            (|c| c.trace_threshold = 1.0, "trace_threshold"),
            (|c| c.tiles_per_feature = 0, "tiles_per_feature"),
            // 6 x 11 = 66 bits > 64.
            (|c| c.tiles_per_feature = 11, "tiles_per_feature"),
            (|c| c.tile_width = 0.0, "tile_width"),
            (|c| c.tile_step = 0.6, "tile_step"),
            // 5 tiles of step 0.2: the last ends at -1 + 0.8 + 0.5 = 0.3 < 1.
            (|c| c.tiles_per_feature = 5, "tiles_per_feature"),
            (
                |c| c.algorithm = ad_hoc("adhoc-td", |a| a.v_g = -1.0),
                "v_g",
            ),
            (
                |c| {
                    let far = Reachable::WithinDistance(f64::INFINITY);
                    c.algorithm = ad_hoc("adhoc-visit", |a| a.reachable = far);
                },
                "reachable",
            ),
            (
                |c| c.algorithm = AlgorithmSettings::named("rcmp").unwrap(),
                "learner",
            ),
            (
                |c| {
                    c.learner = LearnerSettings::Ensemble {
                        heads: 1,
                        mask_probability: 0.5,
                    }
                },
                "heads",
            ),
        ];
        for (change, key) in cases {
            let mut config = AgentConfig::default();
            change(&mut config);
            assert_eq!(key_of(config), key);
        }
        let config = AgentConfig {
            alpha: 2.0,
            ..AgentConfig::default()
        };
        let msg = config.validate().unwrap_err().to_string();
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
        assert_eq!(c.algorithm.name().name(), "adhoc-td");
        let a = c.algorithm.get::<AdHoc>().unwrap();
        assert_eq!(a.reachable, Reachable::Agents(vec![1, 2]));
        assert_eq!((a.v_g, a.ask_budget), (1.5, 1000));
        assert_eq!(c.alpha, 0.1);
        let err = serde_json::from_str::<AgentConfig>(r#"{"alhpa": 0.2}"#).unwrap_err();
        assert!(err.to_string().contains("alhpa"), "{err}");
    }
}
