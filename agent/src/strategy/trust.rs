//! Trust in advisors learned from outcomes, shared by peer learning and the
//! ad hoc methods' `trust_lr`: a running estimate of the advantage of the
//! decisions made on each advisor's advice, and of the agent's own.

use super::seam::Outcome;
use crate::exchange::Advice;

/// An agent's trust in each advisor and in its own choice.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Trust {
    /// By advisor id, 0 until followed.
    advisors: Vec<f64>,
    own: f64,
}

impl Trust {
    /// Its trust in `advisor` (0 for one never followed).
    pub fn of(&self, advisor: usize) -> f64 {
        self.advisors.get(advisor).copied().unwrap_or(0.0)
    }

    /// Its trust in its own choice.
    pub fn own(&self) -> f64 {
        self.own
    }

    /// Moves the trust in whoever decided (the advisor followed, or
    /// itself) toward the decision's advantage, at rate `lr`.
    pub fn learn(&mut self, outcome: &Outcome, lr: f64) {
        let trust = match outcome.advisor {
            Some(j) => {
                if self.advisors.len() <= j {
                    self.advisors.resize(j + 1, 0.0);
                }
                &mut self.advisors[j]
            }
            None => &mut self.own,
        };
        *trust += lr * (outcome.advantage - *trust);
    }

    /// The weight of a trust among the advisors of `advice` and itself:
    /// e^(trust / s / `temperature`), s the largest magnitude of their
    /// trust (every weight 1 while none is learned).
    pub fn weigh(&self, advice: &[Advice], temperature: f64) -> impl Fn(f64) -> f64 {
        let scale =
            (advice.iter().map(|a| self.of(a.advisor).abs())).fold(self.own.abs(), f64::max);
        move |trust| {
            let value = if scale > 0.0 { trust / scale } else { 0.0 };
            (value / temperature).exp()
        }
    }

    /// Trust as given (tests).
    #[cfg(test)]
    pub fn set(advisors: Vec<f64>, own: f64) -> Self {
        Self { advisors, own }
    }
}
