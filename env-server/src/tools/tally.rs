//! Running tallies of a rollout: outcome counts and a sample's moments.

use crate::sim::referee::Outcome;
use serde::Serialize;

/// Counts of each terminal outcome.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct OutcomeCounts {
    /// Goals.
    pub goal: u64,
    /// Balls captured by the keeper.
    pub captured: u64,
    /// Balls out of bounds.
    pub out_of_bounds: u64,
    /// Time-outs.
    pub out_of_time: u64,
}

impl OutcomeCounts {
    /// Counts one more episode ending in `outcome`.
    pub(crate) fn add(&mut self, outcome: Outcome) {
        match outcome {
            Outcome::Goal => self.goal += 1,
            Outcome::Captured => self.captured += 1,
            Outcome::OutOfBounds => self.out_of_bounds += 1,
            Outcome::OutOfTime => self.out_of_time += 1,
            Outcome::InGame => {}
        }
    }
}

/// Running sum and sum of squares of a sample.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Moments {
    n: u64,
    sum: f64,
    squares: f64,
}

impl Moments {
    /// Adds one value.
    pub(crate) fn add(&mut self, x: f64) {
        self.n += 1;
        self.sum += x;
        self.squares += x * x;
    }

    /// The sample standard deviation (0 below two values).
    pub(crate) fn sd(&self) -> f64 {
        if self.n < 2 {
            return 0.0;
        }
        let n = self.n as f64;
        ((self.squares - self.sum * self.sum / n) / (n - 1.0))
            .max(0.0)
            .sqrt()
    }
}
