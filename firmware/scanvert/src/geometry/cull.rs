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

/// `(v₁ − v₀) × (v₂ − v₀)` of view-space vertices.
#[inline]
pub(crate) fn normal(v0: [i64; 3], v1: [i64; 3], v2: [i64; 3]) -> [i64; 3] {
    let a = [v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]];
    let b = [v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]];
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `true` when the face through `v0` with normal `n` shows its front.
#[inline]
pub(crate) fn is_front(projection: &Projection, v0: [i64; 3], n: [i64; 3]) -> bool {
    match projection {
        Projection::Perspective(_) => {
            let det = v0[0] as i128 * n[0] as i128
                + v0[1] as i128 * n[1] as i128
                + v0[2] as i128 * n[2] as i128;
            det < 0
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
    fn extremes_fit() {
        let e = (1i64 << 30) - 1;
        let n = normal([-e, -e, -e], [e, e, -e], [e, -e, e]);
        let _ = is_front(&persp(), [-e, -e, -e], n);
        let n = normal([e, -e, e], [-e, e, e], [-e, -e, -e]);
        let _ = is_front(&persp(), [e, -e, e], n);
    }
}
