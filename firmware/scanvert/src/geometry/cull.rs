//! Back-face culling: a face is drawn only from the side where the whole
//! polygon runs counter-clockwise as displayed.
//!
//! With y down, counter-clockwise as displayed means a negative shoelace
//! sum (the rule of the text form's `poly3`). The test is made in view
//! space, on the polygon as transformed, where it is exact. Its
//! orientation is Newell's normal,
//!
//! ```text
//! N = Σₖ (vₖ − v₀) × (vₖ₊₁ − v₀)
//! ```
//!
//! twice the vector area of the polygon: for a planar polygon it is
//! normal to its plane, and points out of the side from which the polygon
//! runs counter-clockwise (in a right-handed frame). Then
//!
//! * **perspective**: the projections `(x/z, y/z)` of a planar polygon
//!   have a shoelace sum of the sign of `v₀ · N` (for a triangle it is
//!   `det[v₀; v₁; v₂] / (z₀ z₁ z₂)` with `det[v₀; v₁; v₂] = v₀ · N`; a
//!   polygon is a fan of triangles from `v₀` in its plane, whose
//!   projected sums add up). This sign is that of the eye's side of the
//!   face's plane, so it holds for the whole face, also when some of its
//!   vertices lie behind the eye and the near clip replaces them;
//! * **orthographic**: the shoelace sum is `k² · N_z`.
//!
//! A face is front-facing when that value is negative, and culled
//! otherwise. A zero value (the eye in the face's plane, a polygon without
//! area, or a self-intersecting one whose loops cancel) is an edge-on face
//! and is culled.
//!
//! The whole polygon decides, not its first three vertices: a concave
//! face that starts at a reflex corner has `(v₁ − v₀) × (v₂ − v₀)`
//! pointing the other way, and would be lost. Where the first three
//! vertices form a convex corner of a planar polygon, the two rules agree.
//!
//! The normal for lighting is `(v₁ − v₀) × (v₂ − v₀)` turned to the front
//! side (`light_normal`), or Newell's normal where the first three
//! vertices lie in a line; it points out of the front side, toward the
//! eye for a visible face.
//!
//! # Widths
//!
//! View-space coordinates are below 2³⁰, so the differences are below 2³¹,
//! each product of a cross product below 2⁶² and each component of one
//! cross product below 2⁶³ (`i64`). Newell's sum of `n` of them is below
//! `n · 2⁶³` (`i128`), and `v₀ · N` below `3 · n · 2⁹³`: exact in `i128` for
//! polygons of fewer than 2³² vertices (a pipeline's `N` is far below).

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

/// Newell's normal `Σ (vₖ − v₀) × (vₖ₊₁ − v₀)` of view-space vertices
/// (each below 2³⁰): twice the polygon's vector area, exact.
pub(crate) fn newell(v: &[[i64; 3]]) -> [i128; 3] {
    let mut n = [0i128; 3];
    let Some((&v0, rest)) = v.split_first() else {
        return n;
    };
    for w in rest.windows(2) {
        let c = normal(v0, w[0], w[1]);
        for k in 0..3 {
            n[k] += c[k] as i128;
        }
    }
    n
}

/// `true` when the polygon through `v0` with Newell normal `n` shows its
/// front (see the [module](self) docs): the sign of `v₀ · N` for
/// perspective, of `N_z` for orthographic. Exact: each product is below
/// `n · 2⁹³` (module docs).
#[inline]
pub(crate) fn is_front(projection: &Projection, v0: [i64; 3], n: [i128; 3]) -> bool {
    match projection {
        Projection::Perspective(_) => {
            let det: i128 = (0..3).map(|i| v0[i] as i128 * n[i]).sum();
            det < 0
        }
        Projection::Orthographic(_) => n[2] < 0,
    }
}

/// [`is_front`] for a triangle, whose Newell normal is its one corner
/// `n = (v₁ − v₀) × (v₂ − v₀)` (each component below 2⁶³, module docs),
/// in 32 × 32-bit products: each component is split as `n = h · 2³² + l`
/// with `l` its low word taken as signed (`−2³¹ ≤ l < 2³¹`, so `h =
/// ⌊(n + 2³¹) / 2³²⌋`, within `i32`: `|n| ≤ 2⁶³ − 2³⁴ + 8`). Then `v₀ · n
/// = H · 2³² + L` with `H = Σ v₀ h` and `L = Σ v₀ l`, each product below
/// 2⁶¹ and each sum below `3 · 2⁶¹`: exact in `i64`, one multiply and
/// add a term. `H · 2³² + L = (H + ⌊L / 2³²⌋) · 2³² + (L mod 2³²)`, whose
/// last term lies in `0..2³²`: the sign of `v₀ · n` is that of `H +
/// ⌊L / 2³²⌋` (negative exactly when it is).
#[inline]
pub(crate) fn is_front_triangle(projection: &Projection, v0: [i64; 3], n: [i64; 3]) -> bool {
    match projection {
        Projection::Perspective(_) => {
            let mut high = 0i64;
            let mut low = 0i64;
            for k in 0..3 {
                // View-space coordinates are below 2³⁰ (module docs).
                let v = v0[k] as i32 as i64;
                let l = n[k] as i32 as i64;
                // ⌊(n + 2³¹) / 2³²⌋ without the sum's overflow.
                let h = (((n[k] >> 31) + 1) >> 1) as i32 as i64;
                high += v * h;
                low += v * l;
            }
            high + (low >> 32) < 0
        }
        Projection::Orthographic(_) => n[2] < 0,
    }
}

/// The normal to light a face with: `corner = (v₁ − v₀) × (v₂ − v₀)`
/// when it points the way of Newell's `n`, negated when it points the
/// other way (the first corner is a reflex one), and `n` shifted into
/// `i64` when the first three vertices lie in a line. So a face whose
/// first corner is convex is lit exactly as by its first three vertices.
pub(crate) fn light_normal(corner: [i64; 3], n: [i128; 3]) -> [i64; 3] {
    // `n` to below 2³⁰ a component, `corner` too: the dot product of the
    // two is below 3 · 2⁶⁰ (i64), and for a planar face (parallel vectors) its sign is
    // that of the exact one.
    let shrink = |v: [i128; 3]| {
        let m = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
        let k = (128 - m.leading_zeros()).saturating_sub(30);
        v.map(|c| (c >> k) as i64)
    };
    let a = shrink(n);
    if corner == [0; 3] {
        return a;
    }
    let b = shrink(corner.map(i128::from));
    let dot: i64 = (0..3).map(|k| a[k] * b[k]).sum();
    if dot < 0 {
        corner.map(|c| -c)
    } else {
        corner
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

    /// Facing of a polygon by the module's rule.
    fn front(p: &Projection, v: &[[i64; 3]]) -> bool {
        is_front(p, v[0], newell(v))
    }

    /// The triangle test in 32-bit parts agrees with the `i128` one, at
    /// the extremes of the view-space range and between them.
    #[test]
    fn the_triangle_test_is_the_general_one() {
        const M: i64 = (1 << 30) - 1;
        let picks = [
            -M,
            -M + 1,
            -(1 << 29),
            -12_345,
            -1,
            0,
            1,
            7,
            1 << 20,
            M - 1,
            M,
        ];
        let mut next = crate::rng::xorshift64(0x2545_f491_4f6c_dd1d);
        for p in [persp(), ortho()] {
            for _ in 0..20_000 {
                let mut pick = || {
                    let r = next();
                    if r & 1 == 0 {
                        picks[(r >> 8) as usize % picks.len()]
                    } else {
                        (r >> 8) as i64 % (M + 1)
                    }
                };
                let t = [
                    [pick(), pick(), pick()],
                    [pick(), pick(), pick()],
                    [pick(), pick(), pick()],
                ];
                let n = normal(t[0], t[1], t[2]);
                assert_eq!(newell(&t), n.map(i128::from));
                assert_eq!(is_front_triangle(&p, t[0], n), front(&p, &t), "{t:?}");
                if n != [0; 3] {
                    assert_eq!(light_normal(n, n.map(i128::from)), n);
                }
            }
        }
    }

    /// The triangle's split test against `i128` where the low words
    /// matter: corners of every size below 2³⁰, nearly edge-on faces (a
    /// third corner on the line of two others, moved by a unit), and
    /// normals whose components sit about multiples of 2³¹.
    #[test]
    fn split_facing_test_is_the_wide_one() {
        let mut next = crate::rng::xorshift64(0x9e37_79b9_7f4a_7c15);
        let p = persp();
        for _ in 0..200_000 {
            let r = next();
            let bits = 1 + (r % 30) as u32;
            let mut pick = || {
                let r = next();
                ((r >> 2) as i64 % (1 << bits)) * if r & 1 == 0 { 1 } else { -1 }
            };
            let a = [pick(), pick(), pick()];
            let b = [pick(), pick(), pick()];
            let mut c = [pick(), pick(), pick()];
            if r & 0x100 != 0 {
                // On the line through a and b (inside the range), nudged.
                let t = [a, b].map(|w| w.map(|x| x / 2));
                c = [0, 1, 2].map(|k| t[0][k] + t[1][k] + (next() % 3) as i64 - 1);
            }
            let t = [a, b, c];
            let n = normal(a, b, c);
            assert_eq!(is_front_triangle(&p, a, n), front(&p, &t), "{t:?}");
        }
    }

    #[test]
    fn counter_clockwise_as_displayed_is_front() {
        // On screen (y down): (0,0) → (0,1) → (1,1) turns counter-clockwise.
        let (a, b, c) = ([0, 0, 10], [0, 1, 10], [1, 1, 10]);
        assert_eq!(normal(a, b, c), [0, 0, -1]);
        assert_eq!(newell(&[a, b, c]), [0, 0, -1]);
        assert!(front(&persp(), &[a, b, c]));
        assert!(front(&ortho(), &[a, b, c]));
        assert!(!front(&persp(), &[a, c, b]));
        assert!(!front(&ortho(), &[a, c, b]));
    }

    #[test]
    fn edge_on_and_degenerate_are_culled() {
        // The eye lies in the plane x = 0 of this face.
        let (a, b, c) = ([0, 0, 10], [0, 5, 10], [0, 0, 20]);
        assert!(!front(&persp(), &[a, b, c]));
        assert!(!front(&persp(), &[a, c, b]));
        let line = [[0, 0, 10], [1, 1, 10], [2, 2, 10]];
        assert_eq!(newell(&line), [0, 0, 0]);
        assert!(!front(&persp(), &line) && !front(&ortho(), &line));
        // A bow tie whose two loops cancel.
        let tie = [[0, 0, 10], [2, 2, 10], [2, 0, 10], [0, 2, 10]];
        assert_eq!(newell(&tie), [0, 0, 0]);
        assert!(!front(&persp(), &tie));
        assert_eq!(newell(&[]), [0; 3]);
    }

    /// An arrow head, counter-clockwise as displayed, listed so that the
    /// corner of its first three vertices is the reflex one (at `v₁`).
    const ARROW: [[i64; 3]; 4] = [[3, -3, 10], [0, 2, 10], [-3, -3, 10], [0, 5, 10]];

    #[test]
    fn a_concave_face_from_its_reflex_corner_is_front() {
        let [a, b, c, _] = ARROW;
        // The first corner alone would say back.
        assert!(normal(a, b, c)[2] > 0);
        assert!(newell(&ARROW)[2] < 0);
        assert!(front(&persp(), &ARROW) && front(&ortho(), &ARROW));
        let mut back = ARROW;
        back.reverse();
        assert!(!front(&persp(), &back) && !front(&ortho(), &back));
        // Every rotation of the list, the same answer.
        for k in 0..4 {
            let mut r = ARROW;
            r.rotate_left(k);
            assert!(front(&persp(), &r), "{k}");
        }
        // Lit by the front side's normal.
        let n = light_normal(normal(a, b, c), newell(&ARROW));
        assert!(n[2] < 0);
    }

    #[test]
    fn agrees_with_the_first_corner_when_it_is_convex() {
        let mut rng = crate::rng::xorshift64(0x2545_f491_4f6c_dd1d);
        let mut next = || {
            let seed = rng();
            let v = ((seed >> 20) as i64 % (1 << 30)) >> (seed % 29);
            if seed & 32 == 0 {
                v
            } else {
                -v
            }
        };
        for _ in 0..20_000 {
            // A triangle: its only corner is convex.
            let (a, b, c) = (
                [next(), next(), next()],
                [next(), next(), next()],
                [next(), next(), next()],
            );
            let n3 = normal(a, b, c);
            let det: i128 = (0..3).map(|k| a[k] as i128 * n3[k] as i128).sum();
            assert_eq!(front(&persp(), &[a, b, c]), det < 0);
            assert_eq!(front(&ortho(), &[a, b, c]), n3[2] < 0);
            assert_eq!(light_normal(n3, newell(&[a, b, c])), n3);
        }
        // Exactly edge-on faces far out (the plane y = 0 holds the eye):
        // culled in both windings; one unit off, it flips.
        let e = (1i64 << 30) - 1;
        let (a, b, c) = ([e, 0, e], [-e, 0, e], [e, 0, 1]);
        assert!(!front(&persp(), &[a, b, c]));
        assert!(!front(&persp(), &[a, c, b]));
        let b1 = [-e, 1, e];
        assert_ne!(front(&persp(), &[a, b1, c]), front(&persp(), &[a, c, b1]));
    }

    #[test]
    fn extremes_fit() {
        let e = (1i64 << 30) - 1;
        let big = [[-e, -e, -e], [e, e, -e], [e, -e, e], [-e, e, e], [e, e, e]];
        let many: [[i64; 3]; 64] = core::array::from_fn(|k| big[k % 5]);
        // Newell's normal in its other form, the cyclic sum of vₖ × vₖ₊₁,
        // each product widened to i128 first.
        let cross = |a: [i64; 3], b: [i64; 3]| {
            let (a, b) = (a.map(i128::from), b.map(i128::from));
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let mut want = [0i128; 3];
        for k in 0..many.len() {
            let c = cross(many[k], many[(k + 1) % many.len()]);
            for i in 0..3 {
                want[i] += c[i];
            }
        }
        assert_eq!(newell(&many), want);
        let det: i128 = (0..3).map(|i| many[0][i] as i128 * want[i]).sum();
        assert_eq!(front(&persp(), &many), det < 0);
        assert_eq!(front(&ortho(), &many), want[2] < 0);
        // The corner's normal, turned to Newell's side.
        let corner = normal(big[0], big[1], big[2]);
        let (c0, c1, c2) = (
            cross(big[0], big[1]),
            cross(big[1], big[2]),
            cross(big[2], big[0]),
        );
        let triangle: [i128; 3] = core::array::from_fn(|i| c0[i] + c1[i] + c2[i]);
        assert_eq!(corner.map(i128::from), triangle);
        let lit = light_normal(corner, want);
        assert!(lit == corner || lit == corner.map(|c| -c), "{lit:?}");
        // `want` is below 2⁷⁰ a component: the dot product with it cut by
        // 2⁴⁰ is off by less than 3 · 2⁶² from the exact one over 2⁴⁰,
        // far below its size here, so its sign is the exact one's.
        let dot: i128 = (0..3).map(|i| lit[i] as i128 * (want[i] >> 40)).sum();
        assert!(dot.unsigned_abs() > 3 << 62, "{dot} too near 0 to decide");
        assert!(dot > 0, "{lit:?} points away from {want:?}");
    }
}
