//! What an advisor answers with: its method's honest advice or, to study
//! advisors that cannot be trusted, a wrong action (docs/algorithms.md
//! section 8).

use std::fmt;
use std::str::FromStr;

use proto::Action;
use rand::Rng;
use serde::{Deserialize, Serialize};

use crate::learner::ActionValues;
use crate::selection::AgentRng;

/// An advisor's behaviour, written `honest`, `worst`, `random` or
/// `fixed:<action>` (a kick action: `fixed:shoot`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Advises {
    /// Its method's advice (the default).
    #[default]
    Honest,
    /// Its own worst kick action there (ties to the first in the
    /// framework's tie order; an unlearned value counts as 0).
    Worst,
    /// A kick action drawn uniformly from its generator.
    Random,
    /// Always this kick action.
    Fixed(Action),
}

impl Advises {
    /// The action it answers where its method advises `honest` and its
    /// learner holds `values`.
    pub fn answer(self, honest: Action, values: &ActionValues, rng: &mut AgentRng) -> Action {
        match self {
            Advises::Honest => honest,
            Advises::Worst => {
                let value = |a: &Action| values.q[a.index()];
                let lowest = Action::KICK_TIE_ORDER
                    .iter()
                    .map(value)
                    .fold(f64::INFINITY, f64::min);
                (Action::KICK_TIE_ORDER.into_iter())
                    .find(|a| value(a) == lowest)
                    .unwrap_or(honest)
            }
            Advises::Random => {
                Action::KICK_TIE_ORDER[rng.random_range(0..Action::KICK_TIE_ORDER.len())]
            }
            Advises::Fixed(action) => action,
        }
    }
}

impl fmt::Display for Advises {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Advises::Honest => f.write_str("honest"),
            Advises::Worst => f.write_str("worst"),
            Advises::Random => f.write_str("random"),
            Advises::Fixed(a) => write!(f, "fixed:{}", a.name()),
        }
    }
}

impl FromStr for Advises {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let expected = "expected honest, worst, random or fixed:<action> with a kick action \
                        (shoot, dribble, pass-near, pass-far)";
        match s {
            "honest" => Ok(Advises::Honest),
            "worst" => Ok(Advises::Worst),
            "random" => Ok(Advises::Random),
            _ => {
                let fixed = (s.strip_prefix("fixed:"))
                    .and_then(|name| Action::ALL.into_iter().find(|a| a.name() == name))
                    .filter(|a| a.is_kick());
                fixed
                    .map(Advises::Fixed)
                    .ok_or_else(|| format!("`{s}`: {expected}"))
            }
        }
    }
}

impl TryFrom<String> for Advises {
    type Error = String;

    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<Advises> for String {
    fn from(a: Advises) -> String {
        a.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn wrong_advice_is_the_worst_a_random_or_a_fixed_kick() {
        let values = ActionValues {
            q: [0.0, 0.5, -0.2, 0.9, -0.2],
            learned: 0b11111,
        };
        let mut rng = AgentRng::seed_from_u64(3);
        let honest = Action::PassNear;
        assert_eq!(Advises::Honest.answer(honest, &values, &mut rng), honest);
        // Dribble and PassFar tie at -0.2: Dribble comes first in the tie order.
        assert_eq!(
            Advises::Worst.answer(honest, &values, &mut rng),
            Action::Dribble
        );
        let fixed = Advises::Fixed(Action::Shoot);
        assert_eq!(fixed.answer(honest, &values, &mut rng), Action::Shoot);
        let drawn: std::collections::HashSet<Action> = (0..200)
            .map(|_| Advises::Random.answer(honest, &values, &mut rng))
            .collect();
        assert_eq!(drawn.len(), 4);
        assert!(drawn.iter().all(|a| a.is_kick()));
    }

    #[test]
    fn spellings_round_trip_and_bad_ones_say_what_is_expected() {
        for a in [
            Advises::Honest,
            Advises::Worst,
            Advises::Random,
            Advises::Fixed(Action::PassFar),
        ] {
            assert_eq!(a.to_string().parse::<Advises>(), Ok(a));
        }
        for bad in ["fixed:move", "fixed:SHOOT", "liar"] {
            let e = bad.parse::<Advises>().unwrap_err();
            assert!(e.contains("expected honest, worst, random"), "{e}");
        }
    }
}
