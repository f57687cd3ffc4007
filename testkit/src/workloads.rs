//! The 2D workloads W1–W5 of the benchmark (and of the firmware image's
//! scenes `w1` … `w5`), and the benchmark's W6 (slivers, host only),
//! generated deterministically.

use crate::rng::Rng;
use scanvert::fixed::Vertex;

/// What one operation of a workload is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Draw every polygon of the set once per pass.
    Polygons,
    /// Clear the whole frame once per pass.
    Clear,
}

/// One workload: a frame and a set of polygons drawn once per pass.
#[derive(Debug)]
pub struct Workload {
    /// Short name, `W1` …
    pub id: &'static str,
    /// What it is, for the report.
    pub what: &'static str,
    /// Frame width in pixels.
    pub width: u16,
    /// Frame height in pixels.
    pub height: u16,
    /// What a pass does.
    pub kind: Kind,
    /// The polygons, in Q12.4 (empty for clears).
    pub polys: Vec<Vec<Vertex>>,
}

impl Workload {
    /// Operations per pass: polygons, or one clear.
    pub fn ops_per_pass(&self) -> usize {
        match self.kind {
            Kind::Polygons => self.polys.len(),
            Kind::Clear => 1,
        }
    }

    /// Most vertices in one polygon.
    pub fn max_vertices(&self) -> usize {
        self.polys.iter().map(Vec::len).max().unwrap_or(0)
    }

    /// Unit of the rate column.
    pub fn unit(&self) -> &'static str {
        match self.kind {
            Kind::Polygons if self.id == "W3" => "triangles/s",
            Kind::Polygons => "polygons/s",
            Kind::Clear => "clears/s",
        }
    }
}

/// A vertex from a position in pixels, rounded to the nearest 1/16.
fn at(x: f64, y: f64) -> Vertex {
    Vertex::from_bits((x * 16.0).round() as i16, (y * 16.0).round() as i16)
}

/// W1: a 30 × 30 square, each copy one pixel down and right of the last,
/// wrapping around inside 256 × 256 (226 positions).
pub fn w1() -> Workload {
    let polys = (0..226)
        .map(|k| {
            let o = k as f64;
            vec![
                at(o, o),
                at(o + 30.0, o),
                at(o + 30.0, o + 30.0),
                at(o, o + 30.0),
            ]
        })
        .collect();
    Workload {
        id: "W1",
        what: "30×30 square, moved 1 px down-right per copy (wrapping), 256×256",
        width: 256,
        height: 256,
        kind: Kind::Polygons,
        polys,
    }
}

/// W2: clears of 256 × 256.
pub fn w2() -> Workload {
    Workload {
        id: "W2",
        what: "clear of 256×256",
        width: 256,
        height: 256,
        kind: Kind::Clear,
        polys: Vec::new(),
    }
}

/// W3: 10,000 random triangles, each inside a 40 × 40 px box, in
/// 512 × 256; vertices on the 1/16 px grid; no zero-area triangle. The
/// same triangles on every run ([`Rng`]).
pub fn w3() -> Workload {
    let mut rng = Rng(0x05ca_1ab1_e0dd_c0de);
    let mut polys = Vec::with_capacity(10_000);
    while polys.len() < 10_000 {
        let (ox, oy) = (rng.below(512 - 40 + 1) * 16, rng.below(256 - 40 + 1) * 16);
        let mut v =
            || Vertex::from_bits((ox + rng.below(641)) as i16, (oy + rng.below(641)) as i16);
        let t = [v(), v(), v()];
        let area = (t[1].x.units() - t[0].x.units()) * (t[2].y.units() - t[0].y.units())
            - (t[2].x.units() - t[0].x.units()) * (t[1].y.units() - t[0].y.units());
        if area != 0 {
            polys.push(t.to_vec());
        }
    }
    Workload {
        id: "W3",
        what: "10,000 random triangles, each within 40×40 px, 512×256",
        width: 512,
        height: 256,
        kind: Kind::Polygons,
        polys,
    }
}

/// W4: the W1 square rotated by 17° about its centre, vertices rounded to
/// 1/16 px; moved 1 px down-right per copy, wrapping so it stays inside.
pub fn w4() -> Workload {
    let (s, c) = 17f64.to_radians().sin_cos();
    let polys = (0..218)
        .map(|k| {
            let m = 19.0 + k as f64; // centre; the corners reach 18.7 px out
            [(-15.0, -15.0), (15.0, -15.0), (15.0, 15.0), (-15.0, 15.0)]
                .iter()
                .map(|&(x, y)| at(m + c * x - s * y, m + s * x + c * y))
                .collect()
        })
        .collect();
    Workload {
        id: "W4",
        what: "W1's square rotated by 17°, moved 1 px down-right per copy, 256×256",
        width: 256,
        height: 256,
        kind: Kind::Polygons,
        polys,
    }
}

/// W5: one convex 12-gon covering most of 512 × 256.
pub fn w5() -> Workload {
    let poly = (0..12)
        .map(|k| {
            let a = (k as f64 + 0.25) * std::f64::consts::TAU / 12.0;
            at(256.0 + 252.0 * a.cos(), 128.0 + 126.0 * a.sin())
        })
        .collect();
    Workload {
        id: "W5",
        what: "one convex 12-gon covering most of 512×256",
        width: 512,
        height: 256,
        kind: Kind::Polygons,
        polys: vec![poly],
    }
}

/// W6: 2,000 slivers, triangles 40 to 120 px long and 1 to 2 px wide at
/// the base, at any angle, in 512 × 256; vertices on the 1/16 px grid; no
/// zero-area triangle. Timed by the benchmark on the host only (the
/// firmware image embeds W1–W5).
pub fn w6() -> Workload {
    let mut rng = Rng(0x5117_e125_0bad_cafe);
    let mut polys = Vec::with_capacity(2_000);
    while polys.len() < 2_000 {
        let a = rng.below(3600) as f64 / 3600.0 * std::f64::consts::TAU;
        let (s, c) = a.sin_cos();
        let len = rng.range(40, 121) as f64;
        let wide = rng.range(16, 33) as f64 / 16.0;
        // The sliver's middle, so that it stays inside the frame.
        let (mx, my) = (256.0 + c * len / 2.0, 128.0 + s * len / 2.0);
        let (hx, hy) = (
            (256.0 - 4.0 - len / 2.0).max(0.0),
            (128.0 - 4.0 - len / 2.0).max(0.0),
        );
        let ox = rng.range(-(hx as i32), hx as i32 + 1) as f64;
        let oy = rng.range(-(hy as i32), hy as i32 + 1) as f64;
        let (bx, by) = (mx - c * len + ox, my - s * len + oy);
        let t = [
            at(bx, by),
            at(bx - s * wide, by + c * wide),
            at(bx + c * len - s * wide / 2.0, by + s * len + c * wide / 2.0),
        ];
        let area = (t[1].x.units() - t[0].x.units()) * (t[2].y.units() - t[0].y.units())
            - (t[2].x.units() - t[0].x.units()) * (t[1].y.units() - t[0].y.units());
        if area != 0 {
            polys.push(t.to_vec());
        }
    }
    Workload {
        id: "W6",
        what: "2,000 slivers, 40–120 px long, 1–2 px wide, any angle, 512×256",
        width: 512,
        height: 256,
        kind: Kind::Polygons,
        polys,
    }
}

/// All 2D workloads of the firmware image, in order.
pub fn all() -> Vec<Workload> {
    vec![w1(), w2(), w3(), w4(), w5()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slivers_lie_inside_their_frame_and_are_thin() {
        let wl = w6();
        assert_eq!(wl.polys.len(), 2_000);
        for p in &wl.polys {
            for v in p {
                let (x, y) = (v.x.units(), v.y.units());
                assert!((0..16 * wl.width as i32).contains(&x), "{p:?}");
                assert!((0..16 * wl.height as i32).contains(&y), "{p:?}");
            }
            // Twice the area over the longest side: at most 2 px (32
            // units) wide, up to the rounding of the vertices.
            let u = |k: usize| (p[k].x.units() as f64, p[k].y.units() as f64);
            let (a, b, c) = (u(0), u(1), u(2));
            let area2 = ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)).abs();
            let side = |p: (f64, f64), q: (f64, f64)| (q.0 - p.0).hypot(q.1 - p.1);
            let long = side(a, b).max(side(b, c)).max(side(c, a));
            assert!(area2 > 0.0 && area2 / long <= 33.0, "{p:?}");
        }
    }
}
