//! An independent exact reference for the 3D scenes: the face whose plane
//! is nearest at each pixel centre.
//!
//! Coverage is the `i128` pixel rule of [`reference`](crate::reference).
//! Depth is not taken from a plane equation (as scanvert's faces and the
//! z-buffer do) but by barycentric interpolation over three vertices of
//! the face that span a triangle in screen space: with `e₁ = v_j − v₀`,
//! `e₂ = v_k − v₀`, `D = e₁ × e₂ ≠ 0` and `q = P − v₀` for the pixel
//! centre `P`,
//!
//! ```text
//! z(P) = (z₀·D + (q × e₂)·Δz₁ + (e₁ × q)·Δz₂) / D
//! ```
//!
//! kept as an exact fraction (numerator and `|D|` in `i128`) and compared
//! by cross-multiplication. Every vertex is checked to satisfy the same
//! formula (the faces are planar by construction). Of the faces covering a
//! pixel the nearest wins; at equal depth the earlier one (scanvert's tie
//! rule for faces of one segment, and a z-buffer's with a strict test).

use crate::reference::{covers, pixel_box};
use scanvert::fixed::{Vertex, Vertex3};

/// Screen cross product of `(ax, ay)` and `(bx, by)`.
fn cross(a: (i128, i128), b: (i128, i128)) -> i128 {
    a.0 * b.1 - a.1 * b.0
}

/// A face's depth as a barycentric form over three of its vertices.
#[derive(Clone, Copy, Debug)]
struct Bary {
    o: (i128, i128, i128),
    e1: (i128, i128, i128),
    e2: (i128, i128, i128),
    /// `e₁ × e₂`, its sign folded into `sign`.
    den: i128,
    sign: i128,
}

impl Bary {
    /// The form of `face`, or `None` when all its vertices are collinear
    /// in screen space (it covers no pixel then, being planar).
    fn of(face: &[Vertex3]) -> Option<Bary> {
        let u = |v: &Vertex3| {
            (
                v.x.units() as i128,
                v.y.units() as i128,
                v.z.units() as i128,
            )
        };
        let o = u(&face[0]);
        let d = |p: (i128, i128, i128)| (p.0 - o.0, p.1 - o.1, p.2 - o.2);
        for j in 1..face.len() {
            for k in j + 1..face.len() {
                let (e1, e2) = (d(u(&face[j])), d(u(&face[k])));
                let den = cross((e1.0, e1.1), (e2.0, e2.1));
                if den != 0 {
                    let b = Bary {
                        o,
                        e1,
                        e2,
                        den: den.abs(),
                        sign: den.signum(),
                    };
                    for v in face {
                        let p = u(v);
                        assert_eq!(
                            b.depth(p.0, p.1),
                            (p.2 * b.den, b.den),
                            "face {face:?} is not planar"
                        );
                    }
                    return Some(b);
                }
            }
        }
        None
    }

    /// Depth at `(x, y)` in units, as `(numerator, denominator > 0)`.
    fn depth(&self, x: i128, y: i128) -> (i128, i128) {
        let q = (x - self.o.0, y - self.o.1);
        let s = cross(q, (self.e2.0, self.e2.1));
        let t = cross((self.e1.0, self.e1.1), q);
        let num = self.o.2 * self.den + self.sign * (s * self.e1.2 + t * self.e2.2);
        (num, self.den)
    }
}

/// The face shown at each pixel of a `w × h` frame (row-major): its index
/// in `faces`, or `None` for the background.
pub fn winners(faces: &[Vec<Vertex3>], w: u16, h: u16) -> Vec<Option<u32>> {
    let mut best: Vec<Option<(u32, i128, i128)>> = vec![None; w as usize * h as usize];
    for (k, face) in faces.iter().enumerate() {
        let Some(b) = Bary::of(face) else { continue };
        let flat: Vec<Vertex> = face.iter().map(|v| Vertex { x: v.x, y: v.y }).collect();
        let (x0, y0, x1, y1) = pixel_box(&flat, 1, w, h);
        for j in y0..y1 {
            for i in x0..x1 {
                if !covers(&flat, i, j) {
                    continue;
                }
                let (n, d) = b.depth(16 * i as i128 + 8, 16 * j as i128 + 8);
                let cell = &mut best[j as usize * w as usize + i as usize];
                // Strictly nearer only: at equal depth the earlier stays.
                if !matches!(*cell, Some((_, bn, bd)) if n * bd >= bn * d) {
                    *cell = Some((k as u32, n, d));
                }
            }
        }
    }
    best.into_iter().map(|c| c.map(|c| c.0)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use scanvert::fixed::Coord;

    fn v(x: i32, y: i32, z: i32) -> Vertex3 {
        let c = |u: i32| Coord::from_bits(u as i16);
        Vertex3 {
            x: c(x),
            y: c(y),
            z: c(z),
        }
    }

    #[test]
    fn nearer_wins_ties_go_to_the_earlier_and_planes_cross() {
        // Two 4 × 1 px strips over the same pixels: one at depth 0, one
        // rising one unit of depth per unit to the right, from −16; at the
        // pixel centres x = 8, 24, 40, 56 it is at −8, 8, 24, 40, so it is
        // nearer over the first pixel only.
        let flat = vec![v(0, 0, 0), v(0, 16, 0), v(64, 16, 0), v(64, 0, 0)];
        let tilt = vec![v(0, 0, -16), v(0, 16, -16), v(64, 16, 48), v(64, 0, 48)];
        let r = winners(&[flat.clone(), tilt.clone()], 4, 1);
        assert_eq!(r, vec![Some(1), Some(0), Some(0), Some(0)]);
        // Moved right by half a pixel, it is at depth 0 on the centre of
        // pixel 1, a tie, which the earlier face keeps either way.
        let tilt2 = vec![v(8, 0, -16), v(8, 16, -16), v(72, 16, 48), v(72, 0, 48)];
        let r = winners(&[flat.clone(), tilt2.clone()], 4, 1);
        assert_eq!(r[1], Some(0), "tie: the earlier");
        let r = winners(&[tilt2, flat], 4, 1);
        assert_eq!(r[1], Some(0), "tie: the earlier");
    }

    #[test]
    #[should_panic(expected = "not planar")]
    fn non_planar_faces_are_refused() {
        Bary::of(&[v(0, 0, 0), v(0, 16, 0), v(16, 16, 0), v(16, 0, 5)]);
    }
}
