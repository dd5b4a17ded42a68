//! What the strategy decides for its agent: whether it learns, asks, answers,
//! whom it asks, what it shares and which budget the paper plots.
//!
//! The random draws happen here, in the order docs/algorithms.md gives them.

use super::settings::{AdHoc, Confidence, Strategy, Torrey};
use crate::advice::{p_ask, p_give, psi_td, psi_visit, reachable_set};
use crate::advice_counters::AdviceCounters;
use crate::fidelity::TorreyUnknownState;
use crate::learner::ActionValues;
use crate::selection::{AgentRng, chance};

/// What an advisee knows when it decides whether to ask about a state.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AskContext<'a> {
    /// The state was not advised yet in this episode.
    pub fresh: bool,
    /// Visits n(s) of the state.
    pub visits: u64,
    /// Training episodes finished so far.
    pub training_episodes: u64,
    /// The agent's counters.
    pub counters: &'a AdviceCounters,
}

impl Strategy {
    /// Whether the agent learns a Q-table (everything but `Random`).
    pub fn learns(&self) -> bool {
        !matches!(self, Strategy::Random)
    }

    /// The budget the paper plots: advice given (ad hoc advisor, Torrey
    /// teacher) or transitions shared (EpisodeSharing); 0 otherwise.
    pub fn spent_budget(&self, counters: &AdviceCounters) -> u64 {
        match self {
            Strategy::AdHoc(_) | Strategy::Torrey(_) => counters.advice_given,
            Strategy::EpisodeSharing { .. } => counters.shared_sent,
            Strategy::NoAdvice | Strategy::Random => 0,
        }
    }

    /// Transitions still to share: the EpisodeSharing budget left (0 for
    /// every other strategy). The agent records its episode while it is not 0.
    pub fn sharing_allowance(&self, counters: &AdviceCounters) -> u64 {
        match self {
            Strategy::EpisodeSharing { sharing_budget } => {
                sharing_budget.saturating_sub(counters.shared_sent)
            }
            _ => 0,
        }
    }

    /// Whether a training step with the ball asks for advice (Algorithm 1,
    /// or Torrey's student at every fresh state). Draws only for an ad hoc
    /// advisee with budget left after its first episode.
    pub(crate) fn asks(&self, at: AskContext<'_>, rng: &mut AgentRng) -> bool {
        match self {
            Strategy::AdHoc(a) => {
                at.fresh
                    && at.counters.ask_spent < a.ask_budget
                    && at.training_episodes >= 1
                    && chance(rng, p_ask(at.visits, a.v_a))
            }
            Strategy::Torrey(_) => at.fresh,
            Strategy::NoAdvice | Strategy::EpisodeSharing { .. } | Strategy::Random => false,
        }
    }

    /// Advisor side: whether it is confident enough about a state (visited
    /// `visits` times, where its learner holds `values`; both zero when it
    /// never saw the state) to answer (Algorithm 2, or Torrey's importance;
    /// `unknown` says what Torrey's teacher does where it has no kick
    /// entry). Draws only for an ad hoc advisor with budget left and a
    /// visited state.
    pub(crate) fn confident(
        &self,
        visits: u64,
        values: &ActionValues,
        counters: &AdviceCounters,
        unknown: TorreyUnknownState,
        rng: &mut AgentRng,
    ) -> bool {
        match self {
            Strategy::AdHoc(AdHoc {
                confidence,
                v_g,
                give_budget,
                ..
            }) => {
                let psi = match confidence {
                    Confidence::Visit => psi_visit(visits),
                    Confidence::Td => psi_td(visits, values.kick_spread()),
                };
                counters.advice_given < *give_budget && visits > 0 && chance(rng, p_give(psi, *v_g))
            }
            Strategy::Torrey(Torrey {
                importance_threshold,
                give_budget,
                ..
            }) => {
                let importance = match unknown {
                    TorreyUnknownState::Advise if !values.any_kick_learned() => f64::INFINITY,
                    _ => values.kick_spread(),
                };
                counters.advice_given < *give_budget && importance > *importance_threshold
            }
            Strategy::NoAdvice | Strategy::EpisodeSharing { .. } | Strategy::Random => false,
        }
    }

    /// Fills `out` with whom agent `me` of a team of `team_size` asks:
    /// Torrey's fixed teacher `(me + 1) mod n`, else the ad hoc G(s).
    pub(crate) fn advisors(
        &self,
        me: usize,
        team_size: usize,
        positions: &[[f64; 2]],
        out: &mut Vec<usize>,
    ) {
        out.clear();
        match self {
            Strategy::Torrey(_) => {
                let teacher = (me + 1) % team_size;
                out.extend((teacher != me).then_some(teacher));
            }
            Strategy::AdHoc(a) => reachable_set(&a.reachable, me, team_size, positions, out),
            Strategy::NoAdvice | Strategy::EpisodeSharing { .. } | Strategy::Random => {}
        }
    }
}
