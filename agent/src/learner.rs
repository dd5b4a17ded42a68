//! The seam between the advising framework and a learner.
//!
//! The framework ([`crate::Agent`]) owns what the paper's advising needs of
//! every agent whatever it learns with: the tile-coded state index and its
//! visit counts n(s), the budgets, the ask and give probabilities, the
//! states advised this episode, the votes, Mistake Correcting and the
//! fidelity rules. A [`Learner`] owns how the agent acts and learns: its
//! choice with exploration, its action values of a state (which AdHocTD's
//! and Torrey's spread and every advisor's greedy answer read), learning
//! from a transition, and its learned state. SARSA(λ) over the tile-coded
//! state ([`crate::TabularSarsa`]) is one; a learner in another process is
//! another (docs/learners.md).

use std::fmt;

use proto::{Action, State};

use crate::selection::{ACTIONS, AgentRng};

/// What a learner holds of one state: Q(s, a) by [`Action::index`], and
/// which of them it has learned (bit `a.index()`): the authors' "(s, a) is
/// in the Q-table". An action never learned has no value for the spread.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ActionValues {
    /// Q(s, a), indexed by [`Action::index`]; 0 until learned.
    pub q: [f64; ACTIONS],
    /// Bit `a.index()` is set once Q(s, a) has been learned.
    pub learned: u8,
}

impl ActionValues {
    /// Whether Q(s, a) is learned.
    pub fn is_learned(&self, a: Action) -> bool {
        self.learned & (1 << a.index()) != 0
    }

    /// Whether any kick action is learned.
    pub fn any_kick_learned(&self) -> bool {
        Action::KICK_TIE_ORDER.iter().any(|&a| self.is_learned(a))
    }

    /// `max_a Q - min_a Q` over the learned kick actions; 0 with fewer than
    /// two (the authors' rule, shared by AdHocTD and Torrey).
    pub fn kick_spread(&self) -> f64 {
        let mut learned = Action::KICK_TIE_ORDER
            .iter()
            .filter(|&&a| self.is_learned(a))
            .map(|&a| self.q[a.index()]);
        let Some(first) = learned.next() else {
            return 0.0;
        };
        let (lo, hi) = learned.fold((first, first), |(lo, hi), q| (lo.min(q), hi.max(q)));
        hi - lo
    }
}

/// One state as the framework hands it to its learner: the paper's six
/// features, HFO's where the agent's observations carry them, and the
/// framework's index of its tile-coded key (0, 1, 2, ... in the order
/// training first met the states; `None` for a state training never met,
/// as in an evaluation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seen<'a> {
    /// The paper's features.
    pub state: &'a State,
    /// HFO's features ([`proto::Features`]); empty where the agent (or the
    /// asker it advises) is not given them.
    pub features: &'a [f32],
    /// The framework's index of the state, if training met it.
    pub index: Option<usize>,
}

/// An action taken in a state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step<'a> {
    /// Where.
    pub at: Seen<'a>,
    /// What.
    pub action: Action,
}

/// One transition: a step, its reward, and the next step (`None` when the
/// episode ended with it).
pub type Experience<'a> = (Step<'a>, f64, Option<Step<'a>>);

/// How an agent acts and learns; the framework decides everything about
/// advice around it.
pub trait Learner: fmt::Debug + Send {
    /// Its values in `at`; none learned where it knows nothing.
    fn values(&mut self, at: Seen<'_>) -> ActionValues;

    /// Its own choice in `at`, where the agent can kick and trains:
    /// exploring (SARSA's epsilon-greedy draws from the agent's `rng`).
    fn choose(&mut self, at: Seen<'_>, rng: &mut AgentRng) -> Action;

    /// Learns one transition of its own; both states are indexed.
    fn learn(&mut self, transition: Experience<'_>);

    /// The episode ended: forget what ties its steps together (traces).
    fn end_episode(&mut self);

    /// Learns a teammate's goal episode (EpisodeSharing) apart from its own
    /// steps; every state is indexed.
    fn replay(&mut self, episode: &[Experience<'_>]);

    /// Learns a teammate's experience as one batch (one update on all of
    /// it), apart from its own; a state is indexed where the agent's
    /// training met it. False for a learner that cannot learn a batch (by
    /// default).
    fn learn_batch(&mut self, _batch: &[Experience<'_>]) -> bool {
        false
    }

    /// Its values of every indexed state in index order, for a snapshot;
    /// `None` for a learner that keeps its learned state itself.
    fn table(&self) -> Option<Vec<ActionValues>>;

    /// Starts again from a snapshot's values, one per indexed state in
    /// index order; an error says why it cannot.
    fn restore(&mut self, values: Vec<ActionValues>) -> Result<(), String>;

    /// Its own state as bytes, for a learner that keeps it itself (a
    /// learner process with snapshot hooks); `None` by default: its values
    /// are its [`table`](Self::table).
    fn save_state(&self) -> Option<Vec<u8>> {
        None
    }

    /// Starts again from its own state saved by
    /// [`save_state`](Self::save_state); an error says why it cannot.
    fn load_state(&mut self, _state: &[u8]) -> Result<(), String> {
        Err("this learner keeps no state of its own: a snapshot with a learner's state is not for it".into())
    }

    /// Takes `values` as its own in `at` (a value-sharing method's shared
    /// values); false for a learner that cannot.
    fn absorb(&mut self, _at: Seen<'_>, _values: ActionValues) -> bool {
        false
    }

    /// How uncertain its values in `at` are (an ensemble's disagreement),
    /// for the methods that ask by it; `None` for a learner that cannot
    /// tell.
    fn uncertainty(&mut self, _at: Seen<'_>) -> Option<f64> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(q: [f64; ACTIONS], learned: &[Action]) -> ActionValues {
        let learned = learned.iter().fold(0, |m, a| m | 1 << a.index());
        ActionValues { q, learned }
    }

    #[test]
    fn the_spread_counts_only_learned_kick_actions() {
        use Action::*;
        // q indexed Move, Shoot, Dribble, PassNear, PassFar.
        let q = [5.0, 0.4, -0.2, 0.9, 0.0];
        // Unlearned PassNear (0.9) and Move (5.0) are skipped: 0.4 - (-0.2) = 0.6.
        assert!((values(q, &[Move, Shoot, Dribble]).kick_spread() - 0.6).abs() < 1e-15);
        // All four kicks: 0.9 - (-0.2) = 1.1.
        let all = values(q, &[Shoot, Dribble, PassNear, PassFar]);
        assert!((all.kick_spread() - 1.1).abs() < 1e-15);
        // One learned kick (plus Move): spread 0.
        assert_eq!(values(q, &[Move, PassNear]).kick_spread(), 0.0);
        assert_eq!(values(q, &[]).kick_spread(), 0.0);
        assert!(!values(q, &[Move]).any_kick_learned());
    }
}
