//! An exact reference for `poly3`, written from the spec
//! (`shared/specs/text-form.md`) and nothing else.
//!
//! It shares no code with `scanvert::visible::trapezoid`, `segment` or `visible`:
//! no trapezoid, no stepper, no fixed point. Every pixel is decided on its
//! own:
//!
//! 1. a `poly3` is drawn only when the shoelace sum of its vertices,
//!    `Σ (xₖ·yₖ₊₁ − xₖ₊₁·yₖ)`, is negative;
//! 2. it covers pixel `(i, j)` by the pixel rule
//!    ([`reference::covers`](crate::reference::covers)) inside the clip
//!    registers in force at its place in the list (cut to the frame);
//! 3. of the drawn `poly3`s covering a pixel, the one whose plane has the
//!    smallest depth at the pixel centre wins; at equal depth, the earlier
//!    one (the project's documented tie rule).
//!
//! The plane of a polygon is found from two edge vectors at its first
//! vertex that are not parallel in screen space (the first such pair),
//! as `n = (v_j − v₀) × (v_k − v₀)` in exact integers, and every vertex is
//! checked to lie on it: the reference refuses (panics on) polygons that
//! are not planar, since the spec only defines planar ones. Depths at
//! pixel centres are compared as exact fractions, cross-multiplied in
//! `i128`.

use crate::reference::{covers, Window};
use std::cmp::Ordering;

/// One `poly3` of a scene: vertices in units of 1/16 (`x, y, z`), and the
/// clip registers in force for it.
#[derive(Debug, Clone)]
pub struct Poly3 {
    /// The vertices, each coordinate within `i16`.
    pub poly: Vec<(i32, i32, i32)>,
    /// The clip registers in force (`None`: the whole frame).
    pub clip: Option<Window>,
}

/// `true` when the spec draws the polygon: its shoelace sum is negative.
pub fn drawn(poly: &[(i32, i32, i32)]) -> bool {
    let mut s: i128 = 0;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        s += a.0 as i128 * b.1 as i128 - b.0 as i128 * a.1 as i128;
    }
    s < 0
}

/// A plane `a·x + b·y + c·z = d` with `c > 0`, in units.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RefPlane {
    a: i128,
    b: i128,
    c: i128,
    d: i128,
}

impl RefPlane {
    /// The plane through a planar polygon that is not edge-on in screen
    /// space; `None` when it is edge-on (every pair of edge vectors from
    /// the first vertex is parallel in screen space). Panics when the
    /// vertices are not planar.
    pub fn of(poly: &[(i32, i32, i32)]) -> Option<RefPlane> {
        let o = poly[0];
        let vec = |p: (i32, i32, i32)| {
            (
                p.0 as i128 - o.0 as i128,
                p.1 as i128 - o.1 as i128,
                p.2 as i128 - o.2 as i128,
            )
        };
        let mut n = None;
        'search: for j in 1..poly.len() {
            for k in j + 1..poly.len() {
                let (u, v) = (vec(poly[j]), vec(poly[k]));
                let c = u.0 * v.1 - u.1 * v.0;
                if c != 0 {
                    n = Some((u.1 * v.2 - u.2 * v.1, u.2 * v.0 - u.0 * v.2, c));
                    break 'search;
                }
            }
        }
        let (mut a, mut b, mut c) = n?;
        if c < 0 {
            (a, b, c) = (-a, -b, -c);
        }
        let d = a * o.0 as i128 + b * o.1 as i128 + c * o.2 as i128;
        for p in poly {
            assert_eq!(
                a * p.0 as i128 + b * p.1 as i128 + c * p.2 as i128,
                d,
                "vertex {p:?} is off the plane of {poly:?}"
            );
        }
        Some(RefPlane { a, b, c, d })
    }

    /// The depth at the centre of pixel `(i, j)` as `num / den`, `den > 0`.
    pub fn depth(&self, i: i32, j: i32) -> (i128, i128) {
        let (x, y) = (16 * i as i128 + 8, 16 * j as i128 + 8);
        (self.d - self.a * x - self.b * y, self.c)
    }
}

/// Compares two fractions with positive denominators.
fn cmp_frac((n1, d1): (i128, i128), (n2, d2): (i128, i128)) -> Ordering {
    (n1 * d2).cmp(&(n2 * d1))
}

/// The winner at every pixel of a `width × height` frame: the index of the
/// `poly3` in `polys` that the spec shows there, or `None`.
pub fn resolve(polys: &[Poly3], width: u32, height: u32) -> Vec<Option<usize>> {
    let planes: Vec<Option<RefPlane>> = polys
        .iter()
        .map(|p| {
            if drawn(&p.poly) {
                RefPlane::of(&p.poly)
            } else {
                None
            }
        })
        .collect();
    let flat: Vec<Vec<(i32, i32)>> = polys
        .iter()
        .map(|p| p.poly.iter().map(|v| (v.0, v.1)).collect())
        .collect();
    let full = Window::full(width as u16, height as u16);
    let mut out = vec![None; (width * height) as usize];
    for j in 0..height as i32 {
        for i in 0..width as i32 {
            let mut best: Option<(usize, (i128, i128))> = None;
            for (k, p) in polys.iter().enumerate() {
                let Some(plane) = planes[k] else { continue };
                let win = p.clip.unwrap_or(full);
                if !win.contains(i, j) || !covers(&flat[k], i, j) {
                    continue;
                }
                let z = plane.depth(i, j);
                // Strictly nearer only: at equal depth the earlier stays.
                if best.is_none_or(|(_, bz)| cmp_frac(z, bz).is_lt()) {
                    best = Some((k, z));
                }
            }
            out[(j as u32 * width + i as u32) as usize] = best.map(|b| b.0);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearer_plane_wins_and_ties_go_to_the_earlier() {
        let px = |x: i32, y: i32, z: i32| (x * 16, y * 16, z * 16);
        // Counter-clockwise as displayed (y down): drawn.
        let far = Poly3 {
            poly: vec![px(0, 0, 9), px(0, 4, 9), px(4, 4, 9), px(4, 0, 9)],
            clip: None,
        };
        let near = Poly3 {
            poly: vec![px(1, 1, 2), px(1, 3, 2), px(3, 3, 2), px(3, 1, 2)],
            clip: None,
        };
        let tie = Poly3 {
            poly: vec![px(0, 0, 9), px(0, 2, 9), px(2, 2, 9), px(2, 0, 9)],
            clip: None,
        };
        let r = resolve(&[far.clone(), near, tie], 4, 4);
        assert_eq!(r[0], Some(0), "tie: the earlier");
        assert_eq!(r[5], Some(1));
        assert_eq!(r[15], Some(0));
        let mut back = far;
        back.poly.reverse();
        assert_eq!(resolve(&[back], 4, 4)[0], None, "culled");
    }

    #[test]
    #[should_panic(expected = "off the plane")]
    fn non_planar_polygons_are_refused() {
        RefPlane::of(&[(0, 0, 0), (0, 16, 0), (16, 16, 0), (16, 0, 5)]);
    }
}
