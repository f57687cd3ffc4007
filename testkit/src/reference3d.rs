//! The exact 3D reference, written from the `poly3` rules of
//! `docs/display-list.md` and nothing else.
//!
//! It shares no code with `scanvert::visible` (no trapezoid, no stepper,
//! no plane equation, no fixed point). Every pixel is decided on its own:
//!
//! 1. a `poly3` is drawn only when the shoelace sum of its vertices,
//!    `Σ (xₖ·yₖ₊₁ − xₖ₊₁·yₖ)`, is negative ([`drawn`]);
//! 2. it covers pixel `(i, j)` by the pixel rule
//!    ([`reference::covers`](crate::reference::covers)) inside the clip
//!    registers in force at its place in the list (cut to the frame);
//! 3. of the drawn `poly3`s covering a pixel, the one nearest at the pixel
//!    centre wins; at equal depth, the earlier one (the list's tie rule,
//!    which is also a z-buffer's with a strict test). A polygon that a
//!    scene's point or line became ([`resolve_lifted`]) is compared at its
//!    depth less [`LINE_BIAS`] units: moved toward the eye, so that it
//!    shows on a face it lies on.
//!
//! Depth is not taken from a plane equation (as scanvert's faces and a
//! z-buffer do) but by barycentric interpolation over three vertices of
//! the polygon that span a triangle in screen space (the first pair of
//! edge vectors from vertex 0 that are not parallel): with
//! `e₁ = v_j − v₀`, `e₂ = v_k − v₀`, `D = e₁ × e₂ ≠ 0` and `q = P − v₀`
//! for the pixel centre `P`,
//!
//! ```text
//! z(P) = (z₀·D + (q × e₂)·Δz₁ + (e₁ × q)·Δz₂) / D
//! ```
//!
//! kept as an exact fraction (numerator and `|D|` in `i128`) and compared
//! by cross-multiplication. Every vertex is checked to satisfy the same
//! formula: the reference refuses (panics on) polygons that are not
//! planar, since the rules define only planar ones. A polygon whose
//! vertices are all collinear in screen space covers no pixel.

use crate::reference::{covers, pixel_box, Window};
use scanvert::fixed::Vertex3;

/// One `poly3` of a scene: vertices in units of 1/16 (`x, y, z`), and the
/// clip registers in force for it.
#[derive(Debug, Clone)]
pub struct Poly3 {
    /// The vertices, each coordinate within `i16`.
    pub poly: Vec<(i32, i32, i32)>,
    /// The clip registers in force (`None`: the whole frame).
    pub clip: Option<Window>,
}

impl Poly3 {
    /// The polygon through `face` (the library's vertices), unclipped.
    pub fn from_vertices(face: &[Vertex3]) -> Poly3 {
        Poly3 {
            poly: face
                .iter()
                .map(|v| (v.x.units(), v.y.units(), v.z.units()))
                .collect(),
            clip: None,
        }
    }
}

/// The shoelace sum `Σ (xₖ·yₖ₊₁ − xₖ₊₁·yₖ)`: twice the signed area in
/// screen space, negative when counter-clockwise as displayed (y down).
pub fn shoelace(poly: &[(i32, i32, i32)]) -> i128 {
    let mut s: i128 = 0;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        s += a.0 as i128 * b.1 as i128 - b.0 as i128 * a.1 as i128;
    }
    s
}

/// `true` when the rules draw the polygon: its shoelace sum is negative.
pub fn drawn(poly: &[(i32, i32, i32)]) -> bool {
    shoelace(poly) < 0
}

/// Screen cross product of `(ax, ay)` and `(bx, by)`.
fn cross(a: (i128, i128), b: (i128, i128)) -> i128 {
    a.0 * b.1 - a.1 * b.0
}

/// A polygon's depth as a barycentric form over three of its vertices.
#[derive(Clone, Copy, Debug)]
struct Bary {
    o: (i128, i128, i128),
    e1: (i128, i128, i128),
    e2: (i128, i128, i128),
    /// `|e₁ × e₂|`, its sign kept in `sign`.
    den: i128,
    sign: i128,
}

impl Bary {
    /// The form of `poly`, or `None` when all its vertices are collinear
    /// in screen space. Panics when a vertex is off the plane.
    fn of(poly: &[(i32, i32, i32)]) -> Option<Bary> {
        let u = |p: &(i32, i32, i32)| (p.0 as i128, p.1 as i128, p.2 as i128);
        let o = u(poly.first()?);
        let d = |p: (i128, i128, i128)| (p.0 - o.0, p.1 - o.1, p.2 - o.2);
        for j in 1..poly.len() {
            for k in j + 1..poly.len() {
                let (e1, e2) = (d(u(&poly[j])), d(u(&poly[k])));
                let den = cross((e1.0, e1.1), (e2.0, e2.1));
                if den != 0 {
                    let b = Bary {
                        o,
                        e1,
                        e2,
                        den: den.abs(),
                        sign: den.signum(),
                    };
                    for p in poly {
                        let p = u(p);
                        assert_eq!(
                            b.depth(p.0, p.1),
                            (p.2 * b.den, b.den),
                            "vertex {p:?} is off the plane of {poly:?}"
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

/// How far the rules of `docs/display-list.md` move a point or a line
/// toward the eye, in units of depth (1/16 of a Q12.4 unit): 16 units of
/// Q12.4 depth.
pub const LINE_BIAS: i128 = 16 * 16;

/// The winner at every pixel of a `width × height` frame (row-major): the
/// index of the `poly3` in `polys` that the rules show there, or `None`.
pub fn resolve(polys: &[Poly3], width: u32, height: u32) -> Vec<Option<usize>> {
    resolve_lifted(polys, &[], width, height)
}

/// [`resolve`] where `polys[k]` stands for (a part of) a point or a line
/// of a scene when `lifted[k]` is `true` (missing: `false`): its depth at
/// a pixel centre is taken less [`LINE_BIAS`].
pub fn resolve_lifted(
    polys: &[Poly3],
    lifted: &[bool],
    width: u32,
    height: u32,
) -> Vec<Option<usize>> {
    let (w, h) = (width as u16, height as u16);
    let full = Window::full(w, h);
    let mut best: Vec<Option<(usize, i128, i128)>> = vec![None; width as usize * height as usize];
    for (k, p) in polys.iter().enumerate() {
        if !drawn(&p.poly) {
            continue;
        }
        let Some(b) = Bary::of(&p.poly) else { continue };
        let bias = match lifted.get(k) {
            Some(true) => LINE_BIAS,
            _ => 0,
        };
        let flat: Vec<(i32, i32)> = p.poly.iter().map(|v| (v.0, v.1)).collect();
        let win = p.clip.unwrap_or(full);
        let (x0, y0, x1, y1) = pixel_box(&flat, 1, w, h);
        for j in y0..y1 {
            for i in x0..x1 {
                if !win.contains(i, j) || !covers(&flat, i, j) {
                    continue;
                }
                let (n, d) = b.depth(16 * i as i128 + 8, 16 * j as i128 + 8);
                // z − bias = (n − bias·d) / d.
                let n = n - bias * d;
                let cell = &mut best[j as usize * width as usize + i as usize];
                // Strictly nearer only: at equal depth the earlier stays.
                if !matches!(*cell, Some((_, bn, bd)) if n * bd >= bn * d) {
                    *cell = Some((k, n, d));
                }
            }
        }
    }
    best.into_iter().map(|c| c.map(|c| c.0)).collect()
}

/// [`resolve`] for unclipped faces in the library's vertices, as face
/// indices in `u32`.
pub fn winners(faces: &[Vec<Vertex3>], w: u16, h: u16) -> Vec<Option<u32>> {
    let polys: Vec<Poly3> = faces.iter().map(|f| Poly3::from_vertices(f)).collect();
    resolve(&polys, w as u32, h as u32)
        .into_iter()
        .map(|c| c.map(|k| k as u32))
        .collect()
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
    fn tilted_planes_cross_between_pixel_centres() {
        // Two 4 × 1 px strips over the same pixels: one at depth 0, one
        // rising one unit of depth per unit to the right, from −16; at the
        // pixel centres x = 8, 24, 40, 56 it is at −8, 8, 24, 40, so it is
        // nearer over the first pixel only.
        let strip = |x: i32, z0: i32, z1: i32| Poly3 {
            poly: vec![(x, 0, z0), (x, 16, z0), (x + 64, 16, z1), (x + 64, 0, z1)],
            clip: None,
        };
        let flat = strip(0, 0, 0);
        let r = resolve(&[flat.clone(), strip(0, -16, 48)], 4, 1);
        assert_eq!(r, vec![Some(1), Some(0), Some(0), Some(0)]);
        // Moved right by half a pixel, it is at depth 0 on the centre of
        // pixel 1, a tie, which the earlier keeps either way.
        let r = resolve(&[flat.clone(), strip(8, -16, 48)], 4, 1);
        assert_eq!(r[1], Some(0), "tie: the earlier");
        let r = resolve(&[strip(8, -16, 48), flat], 4, 1);
        assert_eq!(r[1], Some(0), "tie: the earlier");
    }

    #[test]
    fn points_and_lines_are_moved_toward_the_eye_by_the_bias() {
        let px = |x: i32, y: i32, z: i32| (x * 16, y * 16, z);
        let face = |z: i32| Poly3 {
            poly: vec![px(0, 0, z), px(0, 2, z), px(2, 2, z), px(2, 0, z)],
            clip: None,
        };
        let b = LINE_BIAS as i32;
        // Whether a line's polygon `d` units behind a face shows, listed
        // before or after the face.
        let shows = |d: i32, line_first: bool| {
            let (f, l) = (face(1000), face(1000 + d));
            let (polys, lifted, line) = match line_first {
                false => (vec![f, l], [false, true], 1),
                true => (vec![l, f], [true, false], 0),
            };
            resolve_lifted(&polys, &lifted, 2, 2)[0] == Some(line)
        };
        for (d, want) in [(-5, true), (0, true), (b - 1, true), (b + 1, false)] {
            assert_eq!(shows(d, false), want, "{d}");
            assert_eq!(shows(d, true), want, "{d}");
        }
        // Exactly the bias behind: a tie, which the earlier wins.
        assert!(!shows(b, false) && shows(b, true));
        // Unmarked, the rule is the plain one.
        assert_eq!(resolve(&[face(1000), face(1000)], 2, 2)[0], Some(0));
    }

    #[test]
    fn clip_registers_and_edge_on_polygons() {
        let px = |x: i32, y: i32, z: i32| (x * 16, y * 16, z * 16);
        let sq = vec![px(0, 0, 1), px(0, 4, 1), px(4, 4, 1), px(4, 0, 1)];
        let clip = Window {
            x0: 1,
            y0: 1,
            x1: 2,
            y1: 1,
        };
        let r = resolve(
            &[Poly3 {
                poly: sq,
                clip: Some(clip),
            }],
            4,
            4,
        );
        let set: Vec<usize> = (0..16).filter(|&k| r[k].is_some()).collect();
        assert_eq!(set, vec![5, 6]);
        let edge_on = vec![px(0, 0, 0), px(1, 1, 5), px(3, 3, 1)];
        assert_eq!(Bary::of(&edge_on).map(|b| b.den), None);
    }

    /// Every pixel against every polygon, in list order: what [`resolve`]
    /// must give, whatever boxes it visits.
    fn pixel_by_pixel(polys: &[Poly3], w: u32, h: u32) -> Vec<Option<usize>> {
        let full = Window::full(w as u16, h as u16);
        let mut out = Vec::new();
        for j in 0..h as i32 {
            for i in 0..w as i32 {
                let mut best: Option<(usize, (i128, i128))> = None;
                for (k, p) in polys.iter().enumerate() {
                    let flat: Vec<(i32, i32)> = p.poly.iter().map(|v| (v.0, v.1)).collect();
                    if !drawn(&p.poly)
                        || !p.clip.unwrap_or(full).contains(i, j)
                        || !covers(&flat, i, j)
                    {
                        continue;
                    }
                    let Some(b) = Bary::of(&p.poly) else { continue };
                    let z = b.depth(16 * i as i128 + 8, 16 * j as i128 + 8);
                    if best.is_none_or(|(_, bz)| z.0 * bz.1 < bz.0 * z.1) {
                        best = Some((k, z));
                    }
                }
                out.push(best.map(|b| b.0));
            }
        }
        out
    }

    #[test]
    fn boxes_miss_no_pixel_on_a_clipped_scene() {
        use crate::rng::Rng;
        use crate::scenes3d::{scene, Version, H, W};
        let s = scene(Version::Tilted, 10);
        let mut rng = Rng(0x7e57_c11b);
        let mut polys: Vec<Poly3> = s.views[2].iter().map(|f| Poly3::from_vertices(f)).collect();
        for (k, p) in polys.iter_mut().enumerate() {
            if k % 3 == 1 {
                let (x0, y0) = (rng.range(-20, 300) as i16, rng.range(-20, 200) as i16);
                p.clip = Some(Window {
                    x0,
                    y0,
                    x1: x0 + rng.range(-5, 400) as i16,
                    y1: y0 + rng.range(-5, 200) as i16,
                });
            }
        }
        // Two copies of one face: the earlier keeps every pixel.
        polys.push(polys[0].clone());
        let got = resolve(&polys, W as u32, H as u32);
        assert!(got.iter().filter(|c| c.is_some()).count() > 10_000);
        assert!(!got.contains(&Some(polys.len() - 1)));
        assert_eq!(got, pixel_by_pixel(&polys, W as u32, H as u32));
    }

    #[test]
    #[should_panic(expected = "off the plane")]
    fn non_planar_polygons_are_refused() {
        Bary::of(&[(0, 0, 0), (0, 16, 0), (16, 16, 0), (16, 0, 5)]);
    }
}
