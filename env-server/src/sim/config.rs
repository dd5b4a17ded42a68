//! The simulator's settings ([`EnvConfig`], with SHOOT's [`LongShot`]) and
//! their validation: what the behaviours and the environment read, apart
//! from both.

use crate::sim::params::BALL_SPEED_MAX;
use serde::{Deserialize, Serialize};

/// Most offense agents the simulator supports.
pub const MAX_OFFENSE: usize = 4;

/// Settings of the simulated task; the defaults are the paper's setup.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EnvConfig {
    /// Number of offense agents (1 to 4).
    pub offense: usize,
    /// Cycles after which a trial ends out of time (`--frames-per-trial`).
    pub frames_per_trial: u32,
    /// Cycles without a touch after which a trial ends out of time.
    pub untouched_time: u32,
    /// Pass to the teammate the action names instead of HFO's best pass to anyone.
    pub pass_to_named_receiver: bool,
    /// SHOOT's stand-in when no course is feasible.
    pub long_shot: LongShot,
}

impl Default for EnvConfig {
    fn default() -> Self {
        EnvConfig {
            offense: 3,
            frames_per_trial: 200,
            untouched_time: 100,
            pass_to_named_receiver: false,
            long_shot: LongShot::default(),
        }
    }
}

/// A rejected simulator setting.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum EnvConfigError {
    /// The offense count is outside the supported range.
    #[error("offense must be between 1 and {MAX_OFFENSE}, got {0}")]
    Offense(usize),
    /// A time limit is zero.
    #[error("{0} must be at least 1")]
    ZeroLimit(&'static str),
    /// The long-shot speed cannot be kicked.
    #[error("long_shot.speed must be in (0, 3], got {0}")]
    LongShotSpeed(f64),
    /// The long-shot minimum speed is not in (0, speed].
    #[error("long_shot.min_speed must be in (0, long_shot.speed], got {0}")]
    LongShotMinSpeed(f64),
    /// The long-shot width is not positive.
    #[error("long_shot.sigma_deg must be positive, got {0}")]
    LongShotSigma(f64),
}

impl EnvConfig {
    /// Checks every setting, naming the first bad one.
    pub fn validate(&self) -> Result<(), EnvConfigError> {
        if !(1..=MAX_OFFENSE).contains(&self.offense) {
            return Err(EnvConfigError::Offense(self.offense));
        }
        if self.frames_per_trial == 0 {
            return Err(EnvConfigError::ZeroLimit("frames_per_trial"));
        }
        if self.untouched_time == 0 {
            return Err(EnvConfigError::ZeroLimit("untouched_time"));
        }
        let speed = self.long_shot.speed;
        if !(speed > 0.0 && speed <= BALL_SPEED_MAX) {
            return Err(EnvConfigError::LongShotSpeed(speed));
        }
        let min_speed = self.long_shot.min_speed;
        if !(min_speed > 0.0 && min_speed <= speed) {
            return Err(EnvConfigError::LongShotMinSpeed(min_speed));
        }
        if self.long_shot.sigma_deg.is_nan() || self.long_shot.sigma_deg <= 0.0 {
            return Err(EnvConfigError::LongShotSigma(self.long_shot.sigma_deg));
        }
        Ok(())
    }
}

/// How SHOOT kicks when no course is feasible and the agent never had one to
/// remember (spec 6.2.2); its defaults were calibrated on the first
/// simulator's always-SHOOT rollouts.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LongShot {
    /// Desired first speed of the fallback shot (m/cycle).
    pub speed: f64,
    /// Slowest first speed worth kicking; below it the agent holds the ball.
    pub min_speed: f64,
    /// Width (degrees) of the keeper-avoidance term used to pick the target.
    pub sigma_deg: f64,
}

impl Default for LongShot {
    fn default() -> Self {
        LongShot {
            speed: 1.85,
            min_speed: 1.2,
            sigma_deg: 10.0,
        }
    }
}
