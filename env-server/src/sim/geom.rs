//! Small 2D helpers on top of `glam::DVec2`: angles, polar vectors, uniform draws.

use glam::DVec2;
use rand::Rng;
use std::f64::consts::{PI, TAU};

/// Wraps an angle (radians) into `(-π, π]`.
pub(crate) fn normalize_angle(a: f64) -> f64 {
    let mut a = if a.abs() <= 3.0 * PI { a } else { a % TAU };
    if a > PI {
        a -= TAU;
    } else if a <= -PI {
        a += TAU;
    }
    a
}

// Trigonometry goes through the pure-Rust `libm` crate: faster than the
// system library here and bit-identical on every platform.

/// The vector of length `r` in direction `angle`.
pub(crate) fn polar(r: f64, angle: f64) -> DVec2 {
    let (s, c) = libm::sincos(angle);
    DVec2::new(r * c, r * s)
}

/// The unit vector in direction `angle`.
pub(crate) fn unit(angle: f64) -> DVec2 {
    polar(1.0, angle)
}

/// Global direction of `v` (radians).
pub(crate) fn direction(v: DVec2) -> f64 {
    libm::atan2(v.y, v.x)
}

/// `asin(x)` for `x` clamped to at most 1.
pub(crate) fn asin_clamped(x: f64) -> f64 {
    libm::asin(x.min(1.0))
}

/// Absolute angle between two directions, in `[0, π]`.
pub(crate) fn angle_diff(a: f64, b: f64) -> f64 {
    normalize_angle(a - b).abs()
}

/// A uniform draw in `[lo, hi)`.
pub(crate) fn uniform(rng: &mut impl Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// Noise vector `polar(U(0, max), U(-π, π))`, as rcssserver adds to velocities and kicks.
pub(crate) fn polar_noise(rng: &mut impl Rng, max: f64) -> DVec2 {
    if max <= 0.0 {
        return DVec2::ZERO;
    }
    let r = uniform(rng, 0.0, max);
    let a = uniform(rng, -PI, PI);
    polar(r, a)
}

/// `x.ceil() as usize` without the call to `ceil` that targets without
/// SSE4.1 make (bit for bit the same, 0 for negative `x`).
pub(crate) fn ceil_usize(x: f64) -> usize {
    let floor = x as usize;
    floor + usize::from((floor as f64) < x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_wrap() {
        assert!((normalize_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((normalize_angle(-PI) - PI).abs() < 1e-12);
        assert!((angle_diff(PI - 0.1, -PI + 0.1) - 0.2).abs() < 1e-12);
    }

    proptest::proptest! {
        #[test]
        fn ceil_usize_is_ceil(x in -10.0..1e6f64, whole in 0..1_000_000u32) {
            proptest::prop_assert_eq!(ceil_usize(x), x.ceil() as usize);
            let w = f64::from(whole);
            proptest::prop_assert_eq!(ceil_usize(w), whole as usize);
        }
    }
}
