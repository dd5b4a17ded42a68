//! The two methods that never advise: SARSA(lambda) alone (NoAdvice) and
//! the authors' random baseline, which does not learn either. They never
//! ask nor give: the seam's defaults.

use serde::{Deserialize, Serialize};

use super::seam::AdvisingStrategy;
use crate::advice_counters::AdviceCounters;
use crate::fidelity::{Fidelity, Profile};
use crate::method::Method;

/// The settings of a method that has none.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NoSettings {}

/// `no-advice`: SARSA(lambda) alone.
pub(crate) struct NoAdvice;

impl Method for NoAdvice {
    type Settings = NoSettings;
    const NAME: &'static str = "no-advice";
    const ABOUT: &'static str = "learning alone, the paper's baseline";
    const COMMUNICATES: bool = false;

    fn defaults(_: Profile) -> NoSettings {
        NoSettings {}
    }

    fn strategy(_: &NoSettings, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Alone { learns: true })
    }
}

/// `random`: the authors' random baseline, which never learns.
pub(crate) struct RandomPolicy;

impl Method for RandomPolicy {
    type Settings = NoSettings;
    const NAME: &'static str = "random";
    const ABOUT: &'static str = "random actions, never learning (the authors' baseline)";
    const COMMUNICATES: bool = false;

    fn defaults(_: Profile) -> NoSettings {
        NoSettings {}
    }

    fn strategy(_: &NoSettings, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Alone { learns: false })
    }
}

/// `external`: decisions given from outside (a strategy process, or
/// [`Agent::with_strategy`](crate::Agent::with_strategy)); until given,
/// NoAdvice's.
pub(crate) struct External;

impl Method for External {
    type Settings = NoSettings;
    const NAME: &'static str = "external";
    const ABOUT: &'static str = "decisions given from outside: a strategy process or object";
    const EXTERNAL: bool = true;

    fn defaults(_: Profile) -> NoSettings {
        NoSettings {}
    }

    fn strategy(_: &NoSettings, _: &Fidelity) -> Box<dyn AdvisingStrategy> {
        Box::new(Alone { learns: true })
    }
}

/// NoAdvice, or the random baseline when it does not `learn`.
#[derive(Clone, Copy, Debug)]
struct Alone {
    /// False for the random baseline.
    learns: bool,
}

impl AdvisingStrategy for Alone {
    fn learns(&self) -> bool {
        self.learns
    }

    fn spent_budget(&self, _counters: &AdviceCounters) -> u64 {
        0
    }
}
