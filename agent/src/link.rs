//! Network conditions for advice traffic (docs/algorithms.md section 6): each
//! request and reply is lost or delayed by a drawn latency. Each draw comes
//! from a generator of its own, seeded by the sender's seed and the message
//! itself (never a learner's generator), so that the in-process model and the
//! zenoh transport draw the same fates.

use std::fmt;
use std::str::FromStr;

use rand::{Rng, RngCore, SeedableRng};
use rand_xoshiro::SplitMix64;
use serde::{Deserialize, Serialize};

use crate::config_error::{AgentConfigError, require, require_unit};
use crate::selection::AgentRng;

/// The longest latency or advice timeout accepted (ms): one minute, the
/// protocol's longest wait.
const MAX_NETWORK_MS: f64 = proto::MAX_WAIT_MS as f64;

/// A message's one-way latency distribution, in milliseconds.
///
/// Written as a string: `fixed:MS`, `uniform:MIN,MAX` or
/// `lognormal:MEDIAN,SIGMA` (the log-normal's median in ms and the standard
/// deviation of its logarithm).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum Latency {
    /// Always `ms`.
    Fixed(f64),
    /// Uniform on `[min, max]`.
    Uniform(f64, f64),
    /// `median * exp(sigma * z)`, `z` standard normal.
    LogNormal(f64, f64),
}

impl Latency {
    fn validate(&self) -> Result<(), AgentConfigError> {
        let in_range = |ms: f64| (0.0..=MAX_NETWORK_MS).contains(&ms);
        let rule = "in [0, 60000] ms";
        match *self {
            Latency::Fixed(ms) => require("network.latency", ms, rule, in_range(ms)),
            Latency::Uniform(min, max) => {
                require("network.latency", min, rule, in_range(min))?;
                require(
                    "network.latency",
                    max,
                    "in [min, 60000] ms",
                    in_range(max) && max >= min,
                )
            }
            Latency::LogNormal(median, sigma) => {
                require("network.latency", median, rule, in_range(median))?;
                require(
                    "network.latency",
                    sigma,
                    "a log-normal sigma in [0, 5]",
                    (0.0..=5.0).contains(&sigma),
                )
            }
        }
    }

    /// The median latency (ms).
    pub fn median_ms(&self) -> f64 {
        match *self {
            Latency::Fixed(ms) => ms,
            Latency::Uniform(min, max) => (min + max) / 2.0,
            Latency::LogNormal(median, _) => median,
        }
    }

    fn draw(&self, rng: &mut AgentRng) -> f64 {
        match *self {
            Latency::Fixed(ms) => ms,
            Latency::Uniform(min, max) => min + (max - min) * rng.random::<f64>(),
            Latency::LogNormal(median, sigma) => median * (sigma * standard_normal(rng)).exp(),
        }
    }
}

/// A standard normal draw (Box-Muller, the cosine branch).
fn standard_normal(rng: &mut AgentRng) -> f64 {
    // 1 - u lies in (0, 1]: its logarithm is finite.
    let u: f64 = 1.0 - rng.random::<f64>();
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

impl fmt::Display for Latency {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Latency::Fixed(ms) => write!(f, "fixed:{ms}"),
            Latency::Uniform(min, max) => write!(f, "uniform:{min},{max}"),
            Latency::LogNormal(median, sigma) => write!(f, "lognormal:{median},{sigma}"),
        }
    }
}

impl From<Latency> for String {
    fn from(latency: Latency) -> Self {
        latency.to_string()
    }
}

impl FromStr for Latency {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let expected = "expected fixed:MS, uniform:MIN,MAX or lognormal:MEDIAN,SIGMA (ms)";
        let (kind, args) = s
            .split_once(':')
            .ok_or_else(|| format!("latency `{s}`: {expected}"))?;
        let numbers: Vec<f64> = args
            .split(',')
            .map(|a| a.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("latency `{s}`: {e}; {expected}"))?;
        match (kind, numbers.as_slice()) {
            ("fixed", &[ms]) => Ok(Latency::Fixed(ms)),
            ("uniform", &[min, max]) => Ok(Latency::Uniform(min, max)),
            ("lognormal", &[median, sigma]) => Ok(Latency::LogNormal(median, sigma)),
            _ => Err(format!("latency `{s}`: {expected}")),
        }
    }
}

impl TryFrom<String> for Latency {
    type Error = String;

    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

/// The conditions an agent's outgoing advice messages (its requests and its
/// replies) meet, and how long it waits for replies.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NetworkConditions {
    /// One-way latency of each message.
    pub latency: Latency,
    /// Probability that a message is lost.
    pub loss: f64,
    /// The advice timeout (ms): a reply that arrives later than this after
    /// its request was sent is lost to the asker.
    pub timeout_ms: f64,
}

impl Default for NetworkConditions {
    /// No latency, no loss, the zenoh transport's default advice timeout.
    fn default() -> Self {
        Self {
            latency: Latency::Fixed(0.0),
            loss: 0.0,
            timeout_ms: 5.0,
        }
    }
}

impl NetworkConditions {
    /// Checks every value's range, naming the first one out of it.
    pub fn validate(&self) -> Result<(), AgentConfigError> {
        self.latency.validate()?;
        require_unit("network.loss", self.loss)?;
        require(
            "network.timeout_ms",
            self.timeout_ms,
            "in (0, 60000] ms",
            self.timeout_ms > 0.0 && self.timeout_ms <= MAX_NETWORK_MS,
        )
    }
}

/// Which leg of an advice round trip a message is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leg {
    /// An advisee's request to one advisor.
    Request,
    /// An advisor's reply to one advisee.
    Reply,
}

/// One advice message: the asker's episode and frame (as in its request's
/// header), the sender and the receiver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Message {
    /// Episode within the run, training and evaluation alike.
    pub episode: u32,
    /// Frame within the episode.
    pub frame: u32,
    /// The sending agent.
    pub from: usize,
    /// The receiving agent.
    pub to: usize,
    /// Request or reply.
    pub leg: Leg,
}

/// One agent's outgoing link: its conditions and the seed of its draws.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link {
    conditions: NetworkConditions,
    seed: u64,
}

/// Mixed into an agent's seed for its link's draws (the agent's own
/// generator is seeded with the seed itself).
const LINK_STREAM: u64 = 0x6e65_7477_6f72_6b21;

impl Link {
    /// The link of the agent seeded with `agent_seed`.
    pub fn new(conditions: NetworkConditions, agent_seed: u64) -> Self {
        Self {
            conditions,
            seed: splitmix64(agent_seed ^ LINK_STREAM),
        }
    }

    /// The advice timeout (ms).
    pub fn timeout_ms(&self) -> f64 {
        self.conditions.timeout_ms
    }

    /// `message`'s one-way delay in ms, or `None` when it is lost. The same
    /// message always meets the same fate.
    pub fn delay(&self, message: Message) -> Option<f64> {
        let c = &self.conditions;
        if c.loss == 0.0 && c.latency == Latency::Fixed(0.0) {
            return Some(0.0);
        }
        let leg = match message.leg {
            Leg::Request => 0,
            Leg::Reply => 1,
        };
        let key = (u64::from(message.episode) << 32) | u64::from(message.frame);
        let pair = ((message.from as u64) << 33) | ((message.to as u64) << 1) | leg;
        let mut rng = AgentRng::seed_from_u64(splitmix64(splitmix64(self.seed ^ key) ^ pair));
        if rng.random::<f64>() < c.loss {
            return None;
        }
        Some(c.latency.draw(&mut rng))
    }
}

/// SplitMix64's first output from state `x` (Steele, Lea & Flood 2014).
fn splitmix64(x: u64) -> u64 {
    SplitMix64::seed_from_u64(x).next_u64()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(frame: u32, leg: Leg) -> Message {
        Message {
            episode: 3,
            frame,
            from: 0,
            to: 2,
            leg,
        }
    }

    fn link(latency: &str, loss: f64) -> Link {
        let conditions = NetworkConditions {
            latency: latency.parse().unwrap(),
            loss,
            timeout_ms: 5.0,
        };
        conditions.validate().unwrap();
        Link::new(conditions, 42)
    }

    #[test]
    fn latency_strings_round_trip_and_bad_ones_say_what_is_expected() {
        for s in ["fixed:2.5", "uniform:1,4", "lognormal:2,0.5"] {
            assert_eq!(s.parse::<Latency>().unwrap().to_string(), s);
        }
        for bad in ["2", "fixed:", "fixed:1,2", "gauss:1,2", "uniform:a,b"] {
            let e = bad.parse::<Latency>().unwrap_err();
            assert!(e.contains("expected fixed:MS"), "{bad}: {e}");
        }
    }

    #[test]
    fn out_of_range_values_name_their_key() {
        let bad = |f: fn(&mut NetworkConditions)| {
            let mut c = NetworkConditions::default();
            f(&mut c);
            c.validate().unwrap_err().key
        };
        assert_eq!(bad(|c| c.loss = 1.5), "network.loss");
        assert_eq!(bad(|c| c.loss = f64::NAN), "network.loss");
        assert_eq!(bad(|c| c.timeout_ms = 0.0), "network.timeout_ms");
        assert_eq!(bad(|c| c.timeout_ms = 1e9), "network.timeout_ms");
        assert_eq!(bad(|c| c.latency = Latency::Fixed(-1.0)), "network.latency");
        assert_eq!(
            bad(|c| c.latency = Latency::Uniform(3.0, 2.0)),
            "network.latency"
        );
        assert_eq!(
            bad(|c| c.latency = Latency::LogNormal(2.0, 9.0)),
            "network.latency"
        );
        NetworkConditions::default().validate().unwrap();
    }

    #[test]
    fn a_message_always_meets_the_same_fate_and_legs_differ() {
        let l = link("lognormal:2,1", 0.3);
        let fates: Vec<_> = (0..200)
            .map(|f| l.delay(message(f, Leg::Request)))
            .collect();
        let again: Vec<_> = (0..200)
            .map(|f| l.delay(message(f, Leg::Request)))
            .collect();
        assert_eq!(fates, again);
        let replies: Vec<_> = (0..200).map(|f| l.delay(message(f, Leg::Reply))).collect();
        assert_ne!(fates, replies);
    }

    #[test]
    fn draws_follow_the_distributions() {
        let n = 20_000;
        let draws = |l: &Link| -> Vec<Option<f64>> {
            (0..n).map(|f| l.delay(message(f, Leg::Request))).collect()
        };
        let lost = draws(&link("fixed:1", 0.2))
            .iter()
            .filter(|d| d.is_none())
            .count();
        assert!((lost as f64 / n as f64 - 0.2).abs() < 0.015, "{lost}");
        let uniform: Vec<f64> = draws(&link("uniform:1,3", 0.0))
            .into_iter()
            .flatten()
            .collect();
        assert!(uniform.iter().all(|&d| (1.0..=3.0).contains(&d)));
        let mean = uniform.iter().sum::<f64>() / n as f64;
        assert!((mean - 2.0).abs() < 0.02, "{mean}");
        let mut log: Vec<f64> = draws(&link("lognormal:2,0.5", 0.0))
            .into_iter()
            .flatten()
            .collect();
        log.sort_by(f64::total_cmp);
        let median = log[n as usize / 2];
        assert!((median - 2.0).abs() < 0.05, "{median}");
        assert!(draws(&link("fixed:0", 0.0)).iter().all(|&d| d == Some(0.0)));
    }
}
