//! Back-face culling: a face is drawn only from the side where its first
//! three vertices run counter-clockwise as displayed.
//!
//! With y down, counter-clockwise as displayed means a negative shoelace
//! sum (the rule of the text form's `poly3`). The test is made in view
//! space, on the first three vertices as transformed, where it is exact:
//!
//! * **perspective**: the projections `(x/z, y/z)` of three points have
//!   the shoelace sum `det[v₀; v₁; v₂] / (z₀ z₁ z₂)`, so for points in
//!   front of the eye its sign is that of `det[v₀; v₁; v₂] = v₀ · n`, with
//!   `n = (v₁ − v₀) × (v₂ − v₀)`. This sign is that of the eye's side of the
//!   face's plane, so it holds for the whole face, also when some of its
//!   vertices lie behind the eye and the near clip replaces them;
//! * **orthographic**: the shoelace sum is `k² · n_z`.
//!
//! A face is front-facing when that value is negative, and culled
//! otherwise. A zero value (the eye in the face's plane, or the first three
//! vertices in a line) is an edge-on face and is culled.
//!
//! `n` is also the face's normal for lighting: it points out of the front
//! side, toward the eye for a visible face.
//!
//! # Widths
//!
//! View-space coordinates are below 2³⁰, so the differences are below 2³¹,
//! each product of the cross product below 2⁶² and each component of `n`
//! below 2⁶³ (`i64`). `v₀ · n` is below 3 · 2⁹³ (`i128`, three multiplies
//! per face).

use super::project::Projection;

/// `(v₁ − v₀) × (v₂ − v₀)` of view-space vertices (each below 2³⁰, so the
/// differences fit `i32` and the products are 32 × 32 bits).
#[inline]
pub(super) fn normal(v0: [i64; 3], v1: [i64; 3], v2: [i64; 3]) -> [i64; 3] {
    let d = |p: [i64; 3], k: usize| (p[k] - v0[k]) as i32 as i64;
    let a = [d(v1, 0), d(v1, 1), d(v1, 2)];
    let b = [d(v2, 0), d(v2, 1), d(v2, 2)];
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `true` when the face through `v0` with normal `n` shows its front.
///
/// For perspective the sign of `v₀ · n` is found from `n` shifted right to
/// 31 bits (`n = 2ᵏ·n' + ρ`, `0 ≤ ρ < 2ᵏ`): `v₀ · n = 2ᵏ (v₀ · n') + v₀ · ρ`
/// with `|v₀ · ρ| < 2ᵏ Σ|v₀|`, so `v₀ · n'` (`i64`) decides unless it is
/// within `Σ|v₀|` of zero; then the exact `i128` product does.
#[inline]
pub(super) fn is_front(projection: &Projection, v0: [i64; 3], n: [i64; 3]) -> bool {
    match projection {
        Projection::Perspective(_) => {
            let m = n.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
            let k = (64 - m.leading_zeros()).saturating_sub(31);
            // |v₀| < 2³⁰, |n'| ≤ 2³¹: each product below 2⁶¹.
            let approx: i64 = (0..3).map(|i| v0[i] * (n[i] >> k)).sum();
            let slack: i64 = v0.iter().map(|c| c.abs()).sum();
            if k == 0 || approx.abs() > slack {
                approx < 0
            } else {
                let det: i128 = (0..3).map(|i| v0[i] as i128 * n[i] as i128).sum();
                det < 0
            }
        }
        Projection::Orthographic(_) => n[2] < 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::project::{Orthographic, Perspective};
    use crate::geometry::transform::Q16;

    fn persp() -> Projection {
        Perspective::new(Q16::from_int(100), Q16::ONE, Q16::from_int(100))
            .unwrap()
            .into()
    }

    fn ortho() -> Projection {
        Orthographic::new(Q16::ONE, Q16::ONE, Q16::from_int(100))
            .unwrap()
            .into()
    }

    #[test]
    fn counter_clockwise_as_displayed_is_front() {
        // On screen (y down): (0,0) → (0,1) → (1,1) turns counter-clockwise.
        let (a, b, c) = ([0, 0, 10], [0, 1, 10], [1, 1, 10]);
        let n = normal(a, b, c);
        assert_eq!(n, [0, 0, -1]);
        assert!(is_front(&persp(), a, n));
        assert!(is_front(&ortho(), a, n));
        let n = normal(a, c, b);
        assert!(!is_front(&persp(), a, n));
        assert!(!is_front(&ortho(), a, n));
    }

    #[test]
    fn edge_on_and_degenerate_are_culled() {
        // The eye lies in the plane x = 0 of this face.
        let (a, b, c) = ([0, 0, 10], [0, 5, 10], [0, 0, 20]);
        let n = normal(a, b, c);
        assert!(!is_front(&persp(), a, n));
        assert!(!is_front(&persp(), a, normal(a, c, b)));
        let line = normal([0, 0, 10], [1, 1, 10], [2, 2, 10]);
        assert_eq!(line, [0, 0, 0]);
        assert!(!is_front(&persp(), [0, 0, 10], line) && !is_front(&ortho(), [0, 0, 10], line));
    }

    #[test]
    fn the_fast_sign_agrees_with_the_exact_one() {
        let p = persp();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let v = ((seed >> 20) as i64 % (1 << 30)) >> (seed % 29);
            if seed & 32 == 0 {
                v
            } else {
                -v
            }
        };
        for i in 0..40_000 {
            let (a, b) = ([next(), next(), next()], [next(), next(), next()]);
            // Every other face nearly holds the eye: c is close to the
            // plane through the origin, a and b.
            let c = if i % 2 == 0 {
                [next(), next(), next()]
            } else {
                let t = next() % 7;
                [0, 1, 2].map(|k| {
                    ((a[k] * t + b[k] * (7 - t)) / 7 + next() % 3)
                        .clamp(-(1 << 30) + 1, (1 << 30) - 1)
                })
            };
            let n = normal(a, b, c);
            let det: i128 = (0..3).map(|k| a[k] as i128 * n[k] as i128).sum();
            assert_eq!(is_front(&p, a, n), det < 0, "{a:?} {b:?} {c:?}");
        }
        // Exactly edge-on faces far out (the plane y = 0 holds the eye): the
        // slow path decides, in both windings; one unit off, it flips.
        let e = (1i64 << 30) - 1;
        let (a, b, c) = ([e, 0, e], [-e, 0, e], [e, 0, 1]);
        assert!(!is_front(&p, a, normal(a, b, c)));
        assert!(!is_front(&p, a, normal(a, c, b)));
        let b1 = [-e, 1, e];
        assert_ne!(
            is_front(&p, a, normal(a, b1, c)),
            is_front(&p, a, normal(a, c, b1))
        );
    }

    #[test]
    fn extremes_fit() {
        let e = (1i64 << 30) - 1;
        let n = normal([-e, -e, -e], [e, e, -e], [e, -e, e]);
        let _ = is_front(&persp(), [-e, -e, -e], n);
        let n = normal([e, -e, e], [-e, e, e], [-e, -e, -e]);
        let _ = is_front(&persp(), [e, -e, e], n);
    }
}
