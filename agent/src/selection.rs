//! Action choice: greedy with either tie rule, epsilon-greedy exploration,
//! the random baseline's draw and the majority vote over advice.

use proto::Action::{self, Dribble, PassFar, PassNear, Shoot};
use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

use crate::fidelity::VoteTies;

/// Number of actions, indexed by [`Action::index`].
pub const ACTIONS: usize = Action::ALL.len();

/// Every agent's own random generator.
pub type AgentRng = Xoshiro256PlusPlus;

/// The authors' exploration draw: 1/3 Shoot, 1/3 Dribble, 1/6 each pass.
pub const EXPLORATION_DRAW: [Action; 6] = [Shoot, Dribble, Dribble, Shoot, PassFar, PassNear];

/// The random baseline's draw with the ball (the authors' `Dummy`).
pub const RANDOM_DRAW: [Action; 6] = [Dribble, Dribble, Shoot, Shoot, PassFar, PassNear];

/// True with probability `p`; draws nothing when `p` is 0 or 1.
pub fn chance(rng: &mut AgentRng, p: f64) -> bool {
    p >= 1.0 || (p > 0.0 && rng.random::<f64>() < p)
}

/// Kick actions of maximal value, in [`Action::KICK_TIE_ORDER`]; returns the
/// array and how many of its first slots are filled (at least one).
fn best_kicks(q: &[f64; ACTIONS]) -> ([Action; 4], usize) {
    let best = Action::KICK_TIE_ORDER
        .iter()
        .map(|a| q[a.index()])
        .fold(f64::NEG_INFINITY, f64::max);
    let mut ties = [Shoot; 4];
    let mut n = 0;
    for a in Action::KICK_TIE_ORDER {
        if q[a.index()] == best {
            ties[n] = a;
            n += 1;
        }
    }
    // All values NaN: fall back to the first action.
    (ties, n.max(1))
}

/// Greedy kick action, ties to the first in Shoot, Dribble, PassFar, PassNear
/// (evaluation, and every advisor's answer).
pub fn greedy_first(q: &[f64; ACTIONS]) -> Action {
    best_kicks(q).0[0]
}

/// Greedy kick action, ties broken uniformly at random (training).
pub fn greedy_random(q: &[f64; ACTIONS], rng: &mut AgentRng) -> Action {
    let (ties, n) = best_kicks(q);
    if n == 1 {
        ties[0]
    } else {
        ties[rng.random_range(0..n)]
    }
}

/// Training choice with the ball: with probability `epsilon` a draw from
/// [`EXPLORATION_DRAW`], else [`greedy_random`].
pub fn epsilon_greedy(q: &[f64; ACTIONS], epsilon: f64, rng: &mut AgentRng) -> Action {
    if chance(rng, epsilon) {
        EXPLORATION_DRAW[rng.random_range(0..EXPLORATION_DRAW.len())]
    } else {
        greedy_random(q, rng)
    }
}

/// The authors' majority-vote tie order (see [`VoteTies::Fixed`]).
pub const VOTE_TIE_ORDER: [Action; 4] = [PassFar, Shoot, Dribble, PassNear];

/// Gamma(advice): the most frequent action, ties broken by `ties`; `None`
/// without votes.
pub fn majority(
    votes: impl IntoIterator<Item = Action>,
    ties: VoteTies,
    rng: &mut AgentRng,
) -> Option<Action> {
    let mut counts = [0usize; ACTIONS];
    for a in votes {
        counts[a.index()] += 1;
    }
    let top = *counts.iter().max()?;
    if top == 0 {
        return None;
    }
    let tied = |a: &Action| counts[a.index()] == top;
    if ties == VoteTies::Fixed
        && let Some(&first) = VOTE_TIE_ORDER.iter().find(|a| tied(a))
    {
        return Some(first);
    }
    let mut best = [Shoot; ACTIONS];
    let mut n = 0;
    for a in Action::ALL.iter().filter(|a| tied(a)) {
        best[n] = *a;
        n += 1;
    }
    Some(if n == 1 {
        best[0]
    } else {
        best[rng.random_range(0..n)]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    /// Q indexed Move, Shoot, Dribble, PassNear, PassFar.
    const FLAT: [f64; ACTIONS] = [9.0, 0.0, 0.0, 0.0, 0.0];

    #[test]
    fn greedy_ignores_move_and_breaks_ties_in_order() {
        assert_eq!(greedy_first(&FLAT), Shoot);
        // PassNear and PassFar tie at 0.3: PassFar comes first in the tie order.
        assert_eq!(greedy_first(&[0.0, 0.1, 0.2, 0.3, 0.3]), PassFar);
        assert_eq!(greedy_first(&[0.0, -1.0, 0.5, 0.0, 0.0]), Dribble);
    }

    #[test]
    fn training_ties_reach_every_tied_action() {
        let mut rng = AgentRng::seed_from_u64(7);
        let mut seen = [false; ACTIONS];
        for _ in 0..200 {
            seen[greedy_random(&FLAT, &mut rng).index()] = true;
        }
        assert_eq!(seen, [false, true, true, true, true]);
        // A strict maximum never draws.
        let before = rng.clone();
        assert_eq!(greedy_random(&[0.0, 0.0, 1.0, 0.0, 0.0], &mut rng), Dribble);
        assert_eq!(rng, before);
    }

    #[test]
    fn exploration_follows_the_authors_draw() {
        // epsilon = 1: Shoot and Dribble 2/6 each, each pass 1/6.
        let mut rng = AgentRng::seed_from_u64(1);
        let mut counts = [0u32; ACTIONS];
        for _ in 0..60_000 {
            counts[epsilon_greedy(&[0.0, 5.0, 0.0, 0.0, 0.0], 1.0, &mut rng).index()] += 1;
        }
        let share = |a: Action| f64::from(counts[a.index()]) / 60_000.0;
        assert!((share(Shoot) - 1.0 / 3.0).abs() < 0.01);
        assert!((share(Dribble) - 1.0 / 3.0).abs() < 0.01);
        assert!((share(PassNear) - 1.0 / 6.0).abs() < 0.01);
        assert!((share(PassFar) - 1.0 / 6.0).abs() < 0.01);
        // epsilon = 0: always greedy.
        assert_eq!(
            epsilon_greedy(&[0.0, 5.0, 0.0, 0.0, 0.0], 0.0, &mut rng),
            Shoot
        );
    }

    #[test]
    fn majority_vote_with_a_tie() {
        // Clear majority: Dribble 2 votes vs Shoot 1.
        let mut rng = AgentRng::seed_from_u64(0);
        for ties in [VoteTies::Random, VoteTies::Fixed] {
            let clear = majority([Dribble, Shoot, Dribble], ties, &mut rng);
            assert_eq!(clear, Some(Dribble));
            assert_eq!(majority([], ties, &mut rng), None);
        }
        // Tie Shoot 1 - PassFar 1: the seed decides, the same seed the same way.
        let tie = [PassFar, Shoot];
        let pick =
            |seed| majority(tie, VoteTies::Random, &mut AgentRng::seed_from_u64(seed)).unwrap();
        let outcomes: Vec<Action> = (0..32).map(pick).collect();
        assert!(outcomes.contains(&Shoot) && outcomes.contains(&PassFar));
        assert!(outcomes.iter().all(|a| tie.contains(a)));
        assert_eq!(outcomes, (0..32).map(pick).collect::<Vec<_>>());
    }

    #[test]
    fn fixed_vote_ties_follow_the_authors_order_without_drawing() {
        let mut rng = AgentRng::seed_from_u64(5);
        let before = rng.clone();
        let vote = |votes: &[Action], rng: &mut AgentRng| {
            majority(votes.iter().copied(), VoteTies::Fixed, rng)
        };
        assert_eq!(vote(&[Shoot, PassFar], &mut rng), Some(PassFar));
        assert_eq!(vote(&[PassNear, Shoot], &mut rng), Some(Shoot));
        assert_eq!(vote(&[PassNear, Dribble], &mut rng), Some(Dribble));
        assert_eq!(
            vote(&[Dribble, PassNear, PassNear], &mut rng),
            Some(PassNear)
        );
        assert_eq!(rng, before);
    }

    #[test]
    fn chance_draws_only_when_uncertain() {
        let mut rng = AgentRng::seed_from_u64(3);
        let before = rng.clone();
        assert!(chance(&mut rng, 1.0) && !chance(&mut rng, 0.0));
        assert_eq!(rng, before);
    }
}
