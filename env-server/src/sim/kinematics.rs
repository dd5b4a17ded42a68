//! How far the ball and the players move: velocity decay series, the
//! full-dash distance table and the turn limit.

use crate::sim::geom::ceil_usize;
use crate::sim::params::{BALL_DECAY, INERTIA_MOMENT, PLAYER_DECAY};

/// Sum of the geometric series `v0 + v0·d + ... ` over `n` terms: distance a
/// decaying object travels in `n` cycles per unit of initial speed.
pub(crate) fn decay_sum(decay: f64, n: u32) -> f64 {
    (1.0 - decay_pow(decay, n)) / (1.0 - decay)
}

/// `decay.powi(n)`, bit for bit, from a table for the ball's and the
/// players' decay.
pub(crate) fn decay_pow(decay: f64, n: u32) -> f64 {
    let table = if decay == PLAYER_DECAY {
        &PLAYER_POWERS
    } else if decay == BALL_DECAY {
        &BALL_POWERS
    } else {
        return decay.powi(n as i32);
    };
    match table.get(n as usize) {
        Some(&pow) => pow,
        None => decay.powi(n as i32),
    }
}

/// Powers tabulated by [`decay_pow`].
const POWERS: usize = 128;
const PLAYER_POWERS: [f64; POWERS] = powers(PLAYER_DECAY);
const BALL_POWERS: [f64; POWERS] = powers(BALL_DECAY);

/// `base.powi(n)` for every `n` below [`POWERS`], computed as compiler-builtins'
/// `__powidf2` (which `powi` calls) does: square and multiply.
const fn powers(base: f64) -> [f64; POWERS] {
    let mut table = [1.0; POWERS];
    let mut n = 0;
    while n < POWERS {
        let (mut a, mut bits, mut product) = (base, n, 1.0);
        loop {
            if bits & 1 != 0 {
                product *= a;
            }
            bits >>= 1;
            if bits == 0 {
                break;
            }
            a *= a;
        }
        table[n] = product;
        n += 1;
    }
    table
}

/// Distance a player covers with `n` consecutive full-power dashes from rest,
/// for `n = 0..=10` (librcsc's `cyclesToReachDistance` table); +1.0 per further cycle.
const DASH_DISTANCE: [f64; 11] = [
    0.0, 0.600, 1.440, 2.376, 3.350, 4.340, 5.336, 6.334, 7.334, 8.334, 9.333,
];

/// Distance covered by `n` full-power dashes from rest.
pub(crate) fn dash_distance(n: usize) -> f64 {
    match DASH_DISTANCE.get(n) {
        Some(d) => *d,
        None => DASH_DISTANCE[10] + (n - 10) as f64,
    }
}

/// Fewest full-power dashes from rest that cover `dist` (0 for `dist <= 0`).
pub(crate) fn dash_cycles(dist: f64) -> usize {
    if dist <= 0.0 {
        return 0;
    }
    match DASH_DISTANCE.iter().position(|&d| d >= dist) {
        Some(n) => n,
        None => 10 + ceil_usize(dist - DASH_DISTANCE[10]),
    }
}

/// Largest effective turn (radians) of a player moving at `speed`.
pub(crate) fn max_turn(speed: f64) -> f64 {
    std::f64::consts::PI / (1.0 + INERTIA_MOMENT * speed)
}

/// Entries of [`DRIFT`]: cycles 0 to 30.
const DRIFT_LEN: usize = 31;

/// Precomputed `(1 - 0.4^t) / 0.6`: a player's drift per unit velocity after t cycles.
pub(crate) const DRIFT: [f64; DRIFT_LEN] = {
    let mut d = [0.0; DRIFT_LEN];
    let mut pow = 1.0;
    let mut t = 0;
    while t < DRIFT_LEN {
        d[t] = (1.0 - pow) / (1.0 - PLAYER_DECAY);
        pow *= PLAYER_DECAY;
        t += 1;
    }
    d
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dash_table_round_trips() {
        assert_eq!(dash_cycles(0.0), 0);
        assert_eq!(dash_cycles(0.6), 1);
        assert_eq!(dash_cycles(0.61), 2);
        assert_eq!(dash_cycles(9.333), 10);
        assert_eq!(dash_cycles(10.0), 11);
        assert_eq!(dash_distance(12), 11.333);
    }

    #[test]
    fn decay_powers_are_powi_bit_for_bit() {
        for decay in [PLAYER_DECAY, BALL_DECAY] {
            for n in 0..POWERS as u32 + 3 {
                let powi = std::hint::black_box(decay).powi(std::hint::black_box(n) as i32);
                assert_eq!(decay_pow(decay, n).to_bits(), powi.to_bits(), "{decay}^{n}");
            }
        }
    }

    #[test]
    fn decay_sum_matches_spec_distances() {
        // A ball kicked at 3.0 travels 13.3 m in 5 cycles and 23.1 m in 10 (spec 2.2).
        assert!((3.0 * decay_sum(0.94, 5) - 13.3).abs() < 0.05);
        assert!((3.0 * decay_sum(0.94, 10) - 23.1).abs() < 0.05);
    }
}
