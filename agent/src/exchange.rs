//! The advising seam: how an agent reaches the others, whatever the transport.
//!
//! Budgets, probabilities and votes live in the agent ([`crate::Agent::advise`],
//! [`crate::Agent::receive_shared`]); an exchange only carries messages.

use proto::{Action, State};

/// One step of a shared episode, `(s, a, r, s', a')`: the wire type itself,
/// so that a transport ships shared episodes as they are.
pub use proto::SharedTransition as Transition;

/// One piece of advice and who gave it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Advice {
    /// The advisor's id.
    pub advisor: usize,
    /// The action it advises.
    pub action: Action,
}

/// Carries advice requests and shared episodes between agents.
pub trait AdviceExchange {
    /// Asks every agent of `to`, in order, for advice on `state` (with the
    /// asker's `intended` action in Mistake Correcting mode) and appends each
    /// piece of advice to `answers`; returns the replies that arrived, with
    /// or without advice (an advisor without advice replies all the same).
    fn ask(
        &mut self,
        from: usize,
        to: &[usize],
        state: &State,
        intended: Option<Action>,
        answers: &mut Vec<Advice>,
    ) -> u64;

    /// Delivers transitions of `from`'s goal episode to agent `to`, in order.
    fn share(&mut self, from: usize, to: usize, transitions: &[Transition]);
}

/// An exchange that reaches nobody: no advice arrives and shares are dropped.
#[derive(Clone, Copy, Debug, Default)]
pub struct Isolated;

impl AdviceExchange for Isolated {
    fn ask(
        &mut self,
        _: usize,
        _: &[usize],
        _: &State,
        _: Option<Action>,
        _: &mut Vec<Advice>,
    ) -> u64 {
        0
    }

    fn share(&mut self, _: usize, _: usize, _: &[Transition]) {}
}
