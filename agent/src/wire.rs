//! Conversions between the library's types and the wire protocol's.

use crate::agent::Mode;

impl From<proto::Mode> for Mode {
    fn from(mode: proto::Mode) -> Self {
        match mode {
            proto::Mode::Training => Mode::Training,
            proto::Mode::Evaluation => Mode::Evaluation,
        }
    }
}

impl From<Mode> for proto::Mode {
    fn from(mode: Mode) -> Self {
        match mode {
            Mode::Training => proto::Mode::Training,
            Mode::Evaluation => proto::Mode::Evaluation,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_round_trip() {
        for mode in [Mode::Training, Mode::Evaluation] {
            assert_eq!(Mode::from(proto::Mode::from(mode)), mode);
        }
    }
}
