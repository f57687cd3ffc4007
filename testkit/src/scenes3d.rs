//! The benchmark's 3D scenes, generated deterministically: `n` faces at
//! 512 × 256, seen from a few views, in two versions that share the
//! screen-space shapes and differ only in depth.
//!
//! * **2D version** (`layered`): every face parallel to the screen, each
//!   at a depth of its own.
//! * **3D version** (`tilted`): the same outlines with tilted planes whose
//!   depth ranges overlap, so that some faces pass through others.
//!
//! The faces are triangles and parallelograms (`o, o+u, o+u+v, o+v`), so
//! that every face is exactly planar in Q12.4 integers; their size falls
//! with `n` so that the summed area of the faces stays about
//! [`DEPTH_COMPLEXITY`] frames, and the picture stays about as full
//! whatever the number of faces. A view pans the whole scene by a
//! fraction of a pixel and a few pixels, as when the eye moves: every face
//! changes, and every face is cut again.

use crate::reference3d::shoelace;
use crate::rng::Rng;
use scanvert::fixed::{Coord, Vertex3};

/// Frame width.
pub const W: u16 = 512;
/// Frame height.
pub const H: u16 = 256;
/// Faces per scene.
pub const SIZES: [usize; 6] = [10, 30, 100, 170, 300, 1000];
/// Views per scene: a pass draws each once.
pub const VIEWS: usize = 4;
/// Summed face area over the frame's area, aimed at.
pub const DEPTH_COMPLEXITY: u64 = 2;

/// Which of the two versions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Version {
    /// Faces parallel to the screen, layered.
    Layered,
    /// Tilted faces, some interpenetrating.
    Tilted,
}

impl Version {
    /// Name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Version::Layered => "2D version (faces parallel to the screen, layered)",
            Version::Tilted => "3D version (tilted faces, some interpenetrating)",
        }
    }

    /// Short name.
    pub fn short(self) -> &'static str {
        match self {
            Version::Layered => "2D",
            Version::Tilted => "3D",
        }
    }
}

/// One scene: the faces of each view, front-facing, in Q12.4.
#[derive(Debug)]
pub struct Scene {
    /// Which version.
    pub version: Version,
    /// Faces per view.
    pub faces: usize,
    /// `views[v][k]`: face `k` in view `v`.
    pub views: Vec<Vec<Vec<Vertex3>>>,
}

impl Scene {
    /// Most vertices of one face.
    pub fn max_vertices(&self) -> usize {
        self.views.iter().flatten().map(Vec::len).max().unwrap_or(0)
    }
}

/// A point or vector in units of 1/16: `(x, y, z)`.
pub(crate) type V3 = (i32, i32, i32);

/// `a + b`.
pub(crate) fn add(a: V3, b: V3) -> V3 {
    (a.0 + b.0, a.1 + b.1, a.2 + b.2)
}

/// `⌊√v⌋`.
fn isqrt(v: u64) -> i32 {
    let mut r = (v as f64).sqrt() as u64;
    while r * r > v {
        r -= 1;
    }
    while (r + 1) * (r + 1) <= v {
        r += 1;
    }
    r as i32
}

/// One outline in screen space: origin and two edge vectors, in units,
/// and whether it is a parallelogram (else a triangle).
struct Outline {
    o: (i32, i32),
    u: (i32, i32),
    v: (i32, i32),
    quad: bool,
}

/// `n` outlines whose mean area is about `DEPTH_COMPLEXITY · W · H / n`,
/// and their size `s` in units.
fn outlines(rng: &mut Rng, n: usize) -> (Vec<Outline>, i32) {
    // Mean area in units² of a face; with `u` uniform in a square of
    // half-side `s` (none shorter than s/2) and `v` about as long as `u`,
    // nearly perpendicular, a parallelogram's mean area is about 0.8 s²
    // and a triangle's half that: 0.6 s² on average.
    let area = DEPTH_COMPLEXITY * W as u64 * H as u64 * 256 / n as u64;
    let s = isqrt(area * 10 / 6).max(48);
    let shapes = (0..n)
        .map(|k| {
            let u = loop {
                let u = (rng.range(-s, s + 1), rng.range(-s, s + 1));
                if 4 * (u.0 as i64 * u.0 as i64 + u.1 as i64 * u.1 as i64) >= s as i64 * s as i64 {
                    break u;
                }
            };
            // v: u turned by a right angle, scaled by 6/8..14/8, jittered.
            let p = rng.range(6, 15);
            let j = s / 4;
            let v = (
                -u.1 * p / 8 + rng.range(-j, j + 1),
                u.0 * p / 8 + rng.range(-j, j + 1),
            );
            // The centre anywhere over the frame widened by a quarter of
            // the size, so that some faces are cut by the frame's sides.
            let (cx, cy) = (
                rng.range(-s / 4, W as i32 * 16 + s / 4),
                rng.range(-s / 4, H as i32 * 16 + s / 4),
            );
            let quad = k % 2 == 1;
            let o = if quad {
                (cx - (u.0 + v.0) / 2, cy - (u.1 + v.1) / 2)
            } else {
                (cx - (u.0 + v.0) / 3, cy - (u.1 + v.1) / 3)
            };
            Outline { o, u, v, quad }
        })
        .collect();
    (shapes, s)
}

/// The scene of `n` faces in `version` (the outlines are the same in both
/// versions).
pub fn scene(version: Version, n: usize) -> Scene {
    let mut shape_rng = Rng(0x3d5c_e4e5_0000_0000 ^ n as u64);
    let (shapes, s) = outlines(&mut shape_rng, n);
    let mut depth_rng = Rng(0x0dee_9000_1234_5678 ^ (n as u64) << 20);
    let mut world: Vec<Vec<V3>> = Vec::with_capacity(n);
    for (k, sh) in shapes.iter().enumerate() {
        let (uz, vz, oz) = match version {
            Version::Layered => {
                // A depth of its own: a random multiple of n, plus k.
                let z =
                    depth_rng.range(-30_000 / n as i32, 30_000 / n as i32) * n as i32 + k as i32;
                (0, 0, z)
            }
            Version::Tilted => {
                // Slopes up to about 1.2 units of depth per unit of
                // screen along each edge vector; the origin's depth is
                // drawn from ±2 sizes, narrow enough that neighbours
                // often overlap in depth, at every size.
                let lu = sh.u.0.abs().max(sh.u.1.abs());
                let lv = sh.v.0.abs().max(sh.v.1.abs());
                let uz = depth_rng.range(-lu * 6 / 5, lu * 6 / 5 + 1);
                let vz = depth_rng.range(-lv * 6 / 5, lv * 6 / 5 + 1);
                let room = (30_000 - uz.abs() - vz.abs()).clamp(1, 2 * s);
                (uz, vz, depth_rng.range(-room, room + 1))
            }
        };
        let o = (sh.o.0, sh.o.1, oz);
        let u = (sh.u.0, sh.u.1, uz);
        let v = (sh.v.0, sh.v.1, vz);
        let mut p = if sh.quad {
            vec![o, add(o, u), add(add(o, u), v), add(o, v)]
        } else {
            vec![o, add(o, u), add(o, v)]
        };
        if shoelace(&p) > 0 {
            p.reverse();
        }
        world.push(p);
    }
    // View v pans by v · (5⅝, 2¼) px.
    let views = (0..VIEWS as i32)
        .map(|v| {
            world
                .iter()
                .map(|p| {
                    p.iter()
                        .map(|&(x, y, z)| vertex3(x + 90 * v, y + 36 * v, z))
                        .collect()
                })
                .collect()
        })
        .collect();
    Scene {
        version,
        faces: n,
        views,
    }
}

/// A Q12.4 vertex from units; every generated coordinate fits `i16`.
fn vertex3(x: i32, y: i32, z: i32) -> Vertex3 {
    let c = |v: i32| Coord::from_bits(i16::try_from(v).expect("scene coordinates fit Q12.4"));
    Vertex3 {
        x: c(x),
        y: c(y),
        z: c(z),
    }
}

/// Depth complexities of the sweep at a fixed face count
/// ([`depth_scene`]).
pub const DEPTHS: [usize; 6] = [1, 2, 4, 8, 16, 40];
/// Faces per scene of the depth-complexity sweep.
pub const DEPTH_FACES: usize = 170;

/// Views pan the scene right and down by up to this much (units): the
/// layers of [`depth_scene`] reach this far beyond the frame's left and
/// top, and [`DEPTH_PAD_FAR`] beyond its right and bottom.
const DEPTH_PAD_NEAR: (i32, i32) = (20 * 16, 10 * 16);
/// See [`DEPTH_PAD_NEAR`].
const DEPTH_PAD_FAR: i32 = 2 * 16;

/// `n` faces (`n ≥ depth`) whose depth complexity is `depth` at every
/// pixel of every view: `depth` layers, each a tiling of the frame (and a
/// margin the views' pan needs) by about `n / depth` parallelograms, so
/// that by the pixel rule every pixel is covered by exactly one face of
/// each layer.
///
/// A layer is cut in a grid turned by its own angle (between about 7° and
/// 27°, either way): bands along the turned rows, each cut into pieces by
/// slanted sides, band and piece boundaries jittered; pieces of
/// neighbouring bands meet in T-junctions. Every piece is a parallelogram
/// `o, o+u, o+u+v, o+v` with integer `u` and `v`, so that it is exactly
/// planar in Q12.4 whatever the depths of `u` and `v`. The **layered**
/// version gives every face a depth of its own; the **tilted** version
/// the same outlines with tilted planes whose depth ranges overlap, as in
/// [`scene`]. The views pan as in [`scene`].
pub fn depth_scene(version: Version, n: usize, depth: usize) -> Scene {
    assert!(depth >= 1 && n >= depth, "at least one face a layer");
    let seed = (n as u64) << 8 ^ depth as u64;
    let mut shape_rng = Rng(0x7e55_e11a_7e00_0001 ^ seed << 24);
    let mut depth_rng = Rng(0x0dee_9000_5eed_0002 ^ seed << 32);
    let (x0, y0) = (-DEPTH_PAD_NEAR.0, -DEPTH_PAD_NEAR.1);
    let (x1, y1) = (W as i32 * 16 + DEPTH_PAD_FAR, H as i32 * 16 + DEPTH_PAD_FAR);
    let padded = (x1 - x0) as u64 * (y1 - y0) as u64;
    // Mean size of a face, units: the side of a square of its area.
    let s = isqrt(padded * depth as u64 / n as u64).max(16);
    let mut world: Vec<Vec<V3>> = Vec::with_capacity(n);
    for layer in 0..depth {
        let m = n / depth + usize::from(layer < n % depth);
        for (o, u, v) in tiling(&mut shape_rng, m, (x0, y0, x1, y1)) {
            let k = world.len();
            let (uz, vz, oz) = match version {
                Version::Layered => {
                    let z = depth_rng.range(-30_000 / n as i32, 30_000 / n as i32) * n as i32
                        + k as i32;
                    (0, 0, z)
                }
                Version::Tilted => {
                    let lu = u.0.abs().max(u.1.abs());
                    let lv = v.0.abs().max(v.1.abs());
                    let uz = depth_rng.range(-lu * 6 / 5, lu * 6 / 5 + 1);
                    let vz = depth_rng.range(-lv * 6 / 5, lv * 6 / 5 + 1);
                    let room = (30_000 - uz.abs() - vz.abs()).clamp(1, 2 * s);
                    (uz, vz, depth_rng.range(-room, room + 1))
                }
            };
            let o = (o.0, o.1, oz);
            let u = (u.0, u.1, uz);
            let v = (v.0, v.1, vz);
            let mut p = vec![o, add(o, u), add(add(o, u), v), add(o, v)];
            if shoelace(&p) > 0 {
                p.reverse();
            }
            world.push(p);
        }
    }
    let views = (0..VIEWS as i32)
        .map(|v| {
            world
                .iter()
                .map(|p| {
                    p.iter()
                        .map(|&(x, y, z)| vertex3(x + 90 * v, y + 36 * v, z))
                        .collect()
                })
                .collect()
        })
        .collect();
    Scene {
        version,
        faces: n,
        views,
    }
}

/// `m` parallelograms `(o, u, v)` (units) that tile the rectangle
/// `(x0, y0, x1, y1)` and a little more: see [`depth_scene`].
#[allow(clippy::type_complexity)]
fn tiling(
    rng: &mut Rng,
    m: usize,
    (x0, y0, x1, y1): (i32, i32, i32, i32),
) -> Vec<((i32, i32), (i32, i32), (i32, i32))> {
    // The turned grid: skew coordinates (X, Y) are the point
    // O + X·e1 + Y·e2 with e1 = (a, b), e2 = (−b, a), about a pixel long.
    let a = rng.range(14, 17);
    let b = rng.range(2, 8) * if rng.below(2) == 0 { 1 } else { -1 };
    let org = (rng.range(0, 16), rng.range(0, 16));
    let at = |x: i32, y: i32| (org.0 + x * a - y * b, org.1 + x * b + y * a);
    let len2 = (a * a + b * b) as f64;
    let skew = |(px, py): (i32, i32)| {
        let (dx, dy) = ((px - org.0) as f64, (py - org.1) as f64);
        (
            (dx * a as f64 + dy * b as f64) / len2,
            (-dx * b as f64 + dy * a as f64) / len2,
        )
    };
    let rect: Vec<(f64, f64)> = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
        .into_iter()
        .map(skew)
        .collect();
    let ylo = rect
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .floor() as i32
        - 1;
    let yhi = rect
        .iter()
        .map(|p| p.1)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil() as i32
        + 1;
    let area = (x1 - x0) as f64 * (y1 - y0) as f64 / len2;
    let side = (area / m as f64).sqrt();
    let rows = (((yhi - ylo) as f64 / side).round() as usize).clamp(1, m);
    // Band boundaries, jittered inside.
    let band = (yhi - ylo) / rows as i32;
    let ys: Vec<i32> = (0..=rows)
        .map(|i| {
            let y = ylo + ((yhi - ylo) as i64 * i as i64 / rows as i64) as i32;
            if i == 0 || i == rows {
                y
            } else {
                y + rng.range(-band / 4, band / 4 + 1)
            }
        })
        .collect();
    // Each band's extent over the rectangle, and its share of the pieces.
    let extent: Vec<(f64, f64)> = ys
        .windows(2)
        .map(|w| x_extent(&rect, w[0] as f64, w[1] as f64))
        .collect();
    let total: f64 = extent.iter().map(|e| (e.1 - e.0).max(0.0)).sum();
    let mut cuts = Vec::with_capacity(rows);
    let mut acc = 0.0;
    let mut given = 0usize;
    for e in &extent {
        acc += (e.1 - e.0).max(0.0);
        let upto = ((m as f64 * acc / total).round() as usize).min(m);
        cuts.push(upto - given);
        given = upto;
    }
    while let Some(z) = cuts.iter().position(|&c| c == 0) {
        let big = (0..rows).max_by_key(|&i| cuts[i]).unwrap_or(0);
        cuts[big] -= 1;
        cuts[z] += 1;
    }
    let mut out = Vec::with_capacity(m);
    for (i, (&c, e)) in cuts.iter().zip(&extent).enumerate() {
        let (ya, yb) = (ys[i], ys[i + 1]);
        let w = (((e.1 - e.0) / c as f64) as i32).max(3);
        let slant = rng.range(-w / 3, w / 3 + 1);
        let xa = e.0.floor() as i32 - slant.abs() - 1;
        let xb = e.1.ceil() as i32 + slant.abs() + 1;
        let xs: Vec<i32> = (0..=c)
            .map(|k| {
                let x = xa + ((xb - xa) as i64 * k as i64 / c as i64) as i32;
                if k == 0 || k == c {
                    x
                } else {
                    x + rng.range(-w / 4, w / 4 + 1)
                }
            })
            .collect();
        for k in 0..c {
            let o = at(xs[k], ya);
            let u = (at(xs[k + 1], ya).0 - o.0, at(xs[k + 1], ya).1 - o.1);
            let v = (at(xs[k] + slant, yb).0 - o.0, at(xs[k] + slant, yb).1 - o.1);
            out.push((o, u, v));
        }
    }
    out
}

/// The least and greatest `x` of the convex polygon `poly` between the
/// lines `y = ya` and `y = yb`.
fn x_extent(poly: &[(f64, f64)], ya: f64, yb: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut take = |x: f64| {
        lo = lo.min(x);
        hi = hi.max(x);
    };
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        if (ya..=yb).contains(&p.1) {
            take(p.0);
        }
        for y in [ya, yb] {
            if (p.1 - y) * (q.1 - y) < 0.0 {
                take(p.0 + (q.0 - p.0) * (y - p.1) / (q.1 - p.1));
            }
        }
    }
    (lo, hi)
}

/// The depth-complexity sweep: both versions at every depth of
/// [`DEPTHS`], [`DEPTH_FACES`] faces each, with the depth aimed at.
pub fn depth_all() -> Vec<(usize, Scene)> {
    [Version::Layered, Version::Tilted]
        .iter()
        .flat_map(|&v| {
            DEPTHS
                .iter()
                .map(move |&d| (d, depth_scene(v, DEPTH_FACES, d)))
        })
        .collect()
}

/// Both versions at every size, in report order.
pub fn all() -> Vec<Scene> {
    [Version::Layered, Version::Tilted]
        .iter()
        .flat_map(|&v| SIZES.iter().map(move |&n| scene(v, n)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenes_are_deterministic_front_facing_and_share_outlines() {
        let a = scene(Version::Tilted, 30);
        let b = scene(Version::Tilted, 30);
        let flat = scene(Version::Layered, 30);
        assert_eq!(a.views, b.views);
        for (p, q) in a.views[1].iter().zip(&flat.views[1]) {
            let units: Vec<V3> = p
                .iter()
                .map(|v| (v.x.units(), v.y.units(), v.z.units()))
                .collect();
            assert!(shoelace(&units) < 0, "front-facing");
            let xy = |v: &Vertex3| (v.x.units(), v.y.units());
            assert_eq!(
                p.iter().map(xy).collect::<Vec<_>>(),
                q.iter().map(xy).collect::<Vec<_>>()
            );
            assert!(q.iter().all(|v| v.z == q[0].z), "constant depth");
        }
        let mut zs: Vec<i32> = flat.views[0].iter().map(|p| p[0].z.units()).collect();
        zs.sort_unstable();
        zs.dedup();
        assert_eq!(zs.len(), 30, "a depth of its own per face");
    }

    #[test]
    fn every_pixel_of_a_depth_scene_is_covered_depth_times() {
        use crate::reference::covers;
        for (n, depth) in [(12, 1), (20, 2), (9, 3)] {
            let s = depth_scene(Version::Tilted, n, depth);
            let flat = depth_scene(Version::Layered, n, depth);
            assert_eq!(s.views[0].len(), n);
            for view in [0, VIEWS - 1] {
                let mut count = vec![0usize; W as usize * H as usize];
                for (p, q) in s.views[view].iter().zip(&flat.views[view]) {
                    let units: Vec<V3> = p
                        .iter()
                        .map(|v| (v.x.units(), v.y.units(), v.z.units()))
                        .collect();
                    assert!(shoelace(&units) < 0, "front-facing");
                    assert_eq!(p.len(), 4);
                    // A parallelogram: exactly planar.
                    assert_eq!(add(units[0], units[2]), add(units[1], units[3]));
                    let xy: Vec<(i32, i32)> = units.iter().map(|v| (v.0, v.1)).collect();
                    let xy_flat: Vec<(i32, i32)> =
                        q.iter().map(|v| (v.x.units(), v.y.units())).collect();
                    assert_eq!(xy, xy_flat, "the versions share outlines");
                    let (bx0, by0, bx1, by1) = crate::reference::pixel_box(&xy, 1, W, H);
                    for j in by0..by1 {
                        for i in bx0..bx1 {
                            count[j as usize * W as usize + i as usize] +=
                                covers(&xy, i, j) as usize;
                        }
                    }
                }
                assert!(count.iter().all(|&c| c == depth), "n {n} depth {depth}");
            }
        }
    }
}
