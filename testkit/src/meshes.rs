//! Triangle meshes of a known size for the mesh workloads: an icosphere,
//! a torus, a terrain height field and the Utah teapot, each from about
//! 100 to about 20,000 triangles.
//!
//! Every mesh is a list of vertices (`f64`, y up) and of triangles of
//! 0-based indices, wound counter-clockwise seen from outside (the
//! convention of OBJ and STL, and of `f`). The sphere, the torus and the
//! terrain (its height field closed by walls down to a flat base) are
//! closed: every edge is shared by exactly two triangles, once in each
//! direction ([`Mesh::is_closed`]). The teapot is Newell's 32 Bézier
//! patches tessellated as they are, and they do not close: the lid sits
//! in the rim with a gap, and the handle and spout pass through the body;
//! its triangles are wound outward patch by patch.
//!
//! Turning a mesh into a display list is the importer's
//! (`scanvert_sim::import::list`, which fits the view to the mesh): this
//! module has [`Mesh::faces`] and [`Mesh::vertices_f32`] in the form it
//! takes, [`Mesh::obj`] for a Wavefront OBJ file, and [`faces_form`],
//! which rewrites a list's `v`/`f` lines as the `face` lines through the
//! same coordinates.

mod teapot_data;

use std::collections::HashMap;
use std::fmt::Write;

/// A triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, y up.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles of indices into `vertices`, counter-clockwise seen from
    /// outside.
    pub triangles: Vec<[u32; 3]>,
}

/// The four generators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A subdivided icosahedron on the unit sphere: `20 · 4^level`
    /// triangles.
    Icosphere,
    /// A torus about the y axis (radii 1 and 0.4): `2 · rings · segments`
    /// triangles.
    Torus,
    /// A height field on an `n × n` grid over `[-1, 1]²`, with walls and
    /// a base: `2n² + 12n` triangles.
    Terrain,
    /// The Utah teapot, each patch `n × n`: `64n² − 8n` triangles (the
    /// ones that collapse at the lid's and the bottom's centres dropped).
    Teapot,
}

impl Kind {
    /// Every generator, in the order the measurements use.
    pub const ALL: [Kind; 4] = [Kind::Icosphere, Kind::Torus, Kind::Terrain, Kind::Teapot];

    /// Its name, lower case.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Icosphere => "icosphere",
            Kind::Torus => "torus",
            Kind::Terrain => "terrain",
            Kind::Teapot => "teapot",
        }
    }

    /// The generator's parameter for each size of the sweep, from about
    /// 100 to about 20,000 triangles (the teapot from 240).
    pub fn sweep(self) -> &'static [u32] {
        match self {
            Kind::Icosphere => &[1, 2, 3, 4, 5],
            Kind::Torus => &[8, 16, 32, 64, 128],
            Kind::Terrain => &[5, 12, 24, 48, 96],
            Kind::Teapot => &[2, 4, 8, 12, 17],
        }
    }

    /// The mesh of parameter `p` (the icosphere's level, the torus's
    /// rings — its segments are `⌊5p/8⌋` — the terrain's grid, or the
    /// teapot's divisions of a patch).
    pub fn make(self, p: u32) -> Mesh {
        match self {
            Kind::Icosphere => icosphere(p),
            Kind::Torus => torus(p, p * 5 / 8),
            Kind::Terrain => terrain(p),
            Kind::Teapot => teapot(p),
        }
    }
}

impl Mesh {
    /// The vertices as `f32`, as a model file holds them.
    pub fn vertices_f32(&self) -> Vec<[f32; 3]> {
        self.vertices.iter().map(|v| v.map(|c| c as f32)).collect()
    }

    /// The triangles as faces of any size.
    pub fn faces(&self) -> Vec<Vec<u32>> {
        self.triangles.iter().map(|t| t.to_vec()).collect()
    }

    /// The mesh as a Wavefront OBJ file.
    pub fn obj(&self, comment: &str) -> String {
        let mut s = format!("# {comment}\n");
        for v in self.vertices_f32() {
            let _ = writeln!(s, "v {} {} {}", v[0], v[1], v[2]);
        }
        for t in &self.triangles {
            let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        s
    }

    /// `true` when every directed edge appears exactly once and its
    /// reverse exactly once: the surface is closed and consistently
    /// wound.
    pub fn is_closed(&self) -> bool {
        let mut count: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &self.triangles {
            for k in 0..3 {
                *count.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        count
            .iter()
            .all(|(&(a, b), &n)| n == 1 && count.get(&(b, a)) == Some(&1))
    }

    /// Six times the signed volume, `Σ v₀ · (v₁ × v₂)`: positive for a
    /// closed mesh wound counter-clockwise seen from outside.
    pub fn volume6(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize]);
                dot(a, cross(b, c))
            })
            .sum()
    }

    /// Adds vertex `v`, or finds it if a vertex of its coordinates to
    /// 2⁻³⁰ is there, through `seen`.
    fn weld(&mut self, seen: &mut HashMap<[i64; 3], u32>, v: [f64; 3]) -> u32 {
        let key = v.map(|c| (c * (1u64 << 30) as f64).round() as i64);
        *seen.entry(key).or_insert_with(|| {
            self.vertices.push(v);
            (self.vertices.len() - 1) as u32
        })
    }

    /// Adds triangle `t` unless two of its corners are one vertex.
    fn push(&mut self, t: [u32; 3]) {
        if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
            self.triangles.push(t);
        }
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn normalised(v: [f64; 3]) -> [f64; 3] {
    let n = dot(v, v).sqrt();
    v.map(|c| c / n)
}

/// The icosahedron subdivided `level` times (each triangle into four,
/// the new vertices pushed out to the unit sphere): `20 · 4^level`
/// triangles, `10 · 4^level + 2` vertices.
pub fn icosphere(level: u32) -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut m = Mesh {
        vertices: [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .map(normalised)
        .to_vec(),
        triangles: vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ],
    };
    for _ in 0..level {
        let mut middle: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::with_capacity(m.triangles.len() * 4);
        let old = std::mem::take(&mut m.triangles);
        for [a, b, c] in old {
            let mut mid = |i: u32, j: u32| {
                let key = (i.min(j), i.max(j));
                *middle.entry(key).or_insert_with(|| {
                    let (p, q) = (m.vertices[i as usize], m.vertices[j as usize]);
                    m.vertices
                        .push(normalised([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                    (m.vertices.len() - 1) as u32
                })
            };
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        m.triangles = next;
    }
    m
}

/// A torus about the y axis, radius 1 to the tube's centre and 0.4 of
/// the tube: `rings` around the axis, `segments` around the tube, `2 ·
/// rings · segments` triangles.
pub fn torus(rings: u32, segments: u32) -> Mesh {
    let (n, s) = (rings.max(3), segments.max(3));
    let mut m = Mesh::default();
    for i in 0..n {
        let a = i as f64 / n as f64 * std::f64::consts::TAU;
        for j in 0..s {
            let b = j as f64 / s as f64 * std::f64::consts::TAU;
            let d = 1.0 + 0.4 * b.cos();
            m.vertices.push([d * a.cos(), 0.4 * b.sin(), -d * a.sin()]);
        }
    }
    let at = |i: u32, j: u32| (i % n) * s + (j % s);
    for i in 0..n {
        for j in 0..s {
            m.triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            m.triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    m
}

/// A 64-bit mix of `(i, j)` (SplitMix64's finaliser): the terrain's
/// deterministic roughness.
fn hash(i: u32, j: u32) -> u64 {
    let mut z = (u64::from(i) << 32 | u64::from(j)).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A height field on an `n × n` grid over `x, z ∈ [-1, 1]`: hills of a
/// few sines and a hashed roughness of each grid point, heights in about
/// `[-0.35, 0.35]`; closed by a wall down from each edge of the border to
/// a base at `y = -0.6` and the base (a fan from its centre): `2n² + 12n`
/// triangles.
pub fn terrain(n: u32) -> Mesh {
    let n = n.max(1);
    let mut m = Mesh::default();
    let coord = |i: u32| -1.0 + 2.0 * i as f64 / n as f64;
    for i in 0..=n {
        for j in 0..=n {
            let (x, z) = (coord(i), coord(j));
            let rough = (hash(i, j) >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let y = 0.2 * (2.7 * x).sin() * (1.9 * z).cos()
                + 0.1 * (4.3 * (x + z)).sin()
                + 0.05 * rough;
            m.vertices.push([x, y, z]);
        }
    }
    let at = |i: u32, j: u32| i * (n + 1) + j;
    for i in 0..n {
        for j in 0..n {
            m.triangles.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            m.triangles.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
        }
    }
    // The border's directed edges: those of the top whose reverse is not
    // there. A wall takes each reversed, so it faces out.
    let mut edges: HashMap<(u32, u32), ()> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            edges.insert((t[k], t[(k + 1) % 3]), ());
        }
    }
    let mut border: Vec<(u32, u32)> = edges
        .keys()
        .filter(|&&(a, b)| !edges.contains_key(&(b, a)))
        .copied()
        .collect();
    border.sort_unstable();
    let base = -0.6;
    let mut below: HashMap<u32, u32> = HashMap::new();
    let mut bottom = |m: &mut Mesh, v: u32| {
        *below.entry(v).or_insert_with(|| {
            let p = m.vertices[v as usize];
            m.vertices.push([p[0], base, p[2]]);
            (m.vertices.len() - 1) as u32
        })
    };
    m.vertices.push([0.0, base, 0.0]);
    let centre = (m.vertices.len() - 1) as u32;
    for (a, b) in border {
        let (a2, b2) = (bottom(&mut m, a), bottom(&mut m, b));
        m.triangles.push([b, a, a2]);
        m.triangles.push([b, a2, b2]);
        m.triangles.push([centre, b2, a2]);
    }
    m
}

/// Bernstein weights of degree 3 at `t`.
fn bernstein(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

/// The Utah teapot (Newell's data, [`teapot_data`]), y up, each of its 32
/// bicubic patches evaluated on an `n × n` grid of its parameters (in
/// `f64`) and cut into two triangles a cell. Points that agree to 2⁻³⁰
/// (on the patches' shared borders, and along a row of control points
/// that is one point, where the weights' rounding differs) are welded
/// into one vertex; triangles whose corners weld together (at the lid's knob and the
/// bottom's centre, where a patch's row of control points is one point)
/// are dropped. `64n² − 8n` triangles. Not closed (see the module).
pub fn teapot(n: u32) -> Mesh {
    let n = n.max(1);
    let mut m = Mesh::default();
    let mut seen = HashMap::new();
    let mut grid = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for patch in &teapot_data::PATCHES {
        let p = |r: usize, c: usize| teapot_data::POINTS[patch[r * 4 + c] as usize - 1];
        grid.clear();
        for i in 0..=n {
            let bu = bernstein(i as f64 / n as f64);
            for j in 0..=n {
                let bv = bernstein(j as f64 / n as f64);
                let mut v = [0.0; 3];
                for (r, wu) in bu.iter().enumerate() {
                    for (c, wv) in bv.iter().enumerate() {
                        let q = p(r, c);
                        for k in 0..3 {
                            v[k] += wu * wv * q[k];
                        }
                    }
                }
                // z up to y up: a turn of −90° about x.
                let id = m.weld(&mut seen, [v[0], v[2], -v[1]]);
                grid.push(id);
            }
        }
        let at = |i: u32, j: u32| grid[(i * (n + 1) + j) as usize];
        for i in 0..n {
            for j in 0..n {
                // The data's patches run clockwise seen from outside in
                // (u, v) order: the cells are wound the other way.
                m.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
                m.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            }
        }
    }
    m
}

/// The `face` form of a text display list: every `v` line dropped, and
/// every `f` line written as the `face` through the coordinates of the
/// `v` lines it names (1-based, or negative from the last), as the text
/// of those lines has them. The vertex table starts empty at each
/// `segment`. Other lines are kept.
pub fn faces_form(list: &str) -> String {
    let mut table: Vec<&str> = Vec::new();
    let mut out = String::with_capacity(list.len() * 2);
    for line in list.lines() {
        let body = line.split('#').next().unwrap_or("").trim();
        let mut words = body.split_whitespace();
        match words.next() {
            Some("v") => {
                table.push(body[1..].trim());
                continue;
            }
            Some("f") => {
                out.push_str("face");
                for w in words {
                    let i: i64 = w.parse().expect("an index");
                    let k = if i < 0 { table.len() as i64 + i } else { i - 1 };
                    out.push(' ');
                    out.push_str(table[k as usize]);
                }
                out.push('\n');
                continue;
            }
            Some("segment") => table.clear(),
            _ => {}
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The outward normal of triangle `t` of `m`, not normalised.
pub fn normal(m: &Mesh, t: [u32; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|i| m.vertices[i as usize]);
    cross(sub(b, a), sub(c, a))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sizes_are_as_documented() {
        for l in 0..4 {
            let m = icosphere(l);
            assert_eq!(m.triangles.len(), 20 << (2 * l));
            assert_eq!(m.vertices.len(), 10 * (1 << (2 * l)) + 2);
        }
        assert_eq!(torus(8, 6).triangles.len(), 96);
        for n in [1, 3, 10] {
            assert_eq!(terrain(n).triangles.len() as u32, 2 * n * n + 12 * n);
        }
        for n in [1, 2, 5] {
            assert_eq!(teapot(n).triangles.len() as u32, 64 * n * n - 8 * n);
        }
        for k in Kind::ALL {
            let sizes: Vec<usize> = k
                .sweep()
                .iter()
                .map(|&p| k.make(p).triangles.len())
                .collect();
            assert!(
                sizes[0] <= 250 && *sizes.last().unwrap() >= 18_000,
                "{k:?} {sizes:?}"
            );
        }
    }

    #[test]
    fn the_closed_meshes_are_closed_and_wound_outward() {
        for m in [
            icosphere(0),
            icosphere(3),
            torus(9, 5),
            torus(40, 14),
            terrain(1),
            terrain(7),
        ] {
            assert!(m.is_closed());
            assert!(m.volume6() > 0.0);
        }
    }

    #[test]
    fn the_teapot_is_wound_outward_and_open() {
        let m = teapot(6);
        assert!(!m.is_closed());
        // Its body's triangles face away from the axis.
        let (mut out, mut body) = (0, 0);
        for &t in &m.triangles {
            let c = t
                .map(|i| m.vertices[i as usize])
                .iter()
                .fold([0.0; 3], |s, v| [s[0] + v[0], s[1] + v[1], s[2] + v[2]]);
            let (x, y, z) = (c[0] / 3.0, c[1] / 3.0, c[2] / 3.0);
            if (0.3..2.3).contains(&y) && z.abs() > 0.7 {
                body += 1;
                out += (dot(normal(&m, t), [x, 0.0, z]) > 0.0) as usize;
            }
        }
        assert!(body > 100 && out == body, "{out} of {body}");
        assert!(m.volume6() > 0.0);
    }

    #[test]
    fn faces_form_writes_the_named_coordinates() {
        let list = "frame 8 8\nv 1 2 3\nv 4 5 6\nv 7 8 9\nf 1 -2 3\nsegment 2\nv 0 0 0\nf 1\n";
        assert_eq!(
            faces_form(list),
            "frame 8 8\nface 1 2 3 4 5 6 7 8 9\nsegment 2\nface 0 0 0\n"
        );
    }
}
