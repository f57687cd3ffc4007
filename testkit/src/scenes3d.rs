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
}
