//! HFO's game statuses as its Python interface names and numbers them
//! (`hfo.IN_GAME` = 0, ..., `hfo.OUT_OF_TIME` = 4).

use env_server::Outcome;

/// The names of the statuses, indexed by [`code`].
pub(crate) const NAMES: [&str; 5] = [
    "IN_GAME",
    "GOAL",
    "CAPTURED_BY_DEFENSE",
    "OUT_OF_BOUNDS",
    "OUT_OF_TIME",
];

/// HFO's number of `outcome`.
pub(crate) fn code(outcome: Outcome) -> i8 {
    match outcome {
        Outcome::InGame => 0,
        Outcome::Goal => 1,
        Outcome::Captured => 2,
        Outcome::OutOfBounds => 3,
        Outcome::OutOfTime => 4,
    }
}

/// HFO's name of `outcome`.
pub(crate) fn name(outcome: Outcome) -> &'static str {
    NAMES[code(outcome) as usize]
}
