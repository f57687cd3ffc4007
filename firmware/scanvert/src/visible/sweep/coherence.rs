//! How much of a frame coherence between rows could reuse, counted; the
//! test checks that the counts are consistent, and prints them (`cargo
//! test -p scanvert --release coherence -- --nocapture`, the figures
//! `docs/performance-log.md` quotes). For each row of the 170-face
//! `poly3` scenes (`testkit::poly3_scenes`, the image's `poly3-layered`
//! and `poly3-tilted`) and the first view of the benchmark's 170-, 300-
//! and 1000-face scenes (`testkit::scenes3d`), it resolves the row with
//! [`Sweep::draw`] and compares it with the row above:
//!
//! * *rows*: the same live trapezoids with pixels, their `l` and `r` in
//!   the same order (ties kept), and no intersecting span on the row
//!   above: the rows whose runs would be the row above's with their ends
//!   stepped, if every front still held;
//! * *runs*: runs whose two ends are the same trapezoids' ends, whose
//!   covers where they start are the same trapezoids, and with the same
//!   ends of trapezoids in between in the same order, as a run of the row
//!   above (a test per run), and of those the runs that also show the
//!   same face;
//! * *trapezoid-rows*: live trapezoids with pixels on a row, those of them
//!   whose face shows on the row, and the trapezoids that never show;
//! * the rows with an intersecting span.

extern crate std;

use super::*;
use crate::fixed::{ceil_px, Coord, Vertex3};
use crate::raster::clip::ClipRect;
use crate::visible::store::{Face, Segment, StoreMemory};
use crate::visible::trapezoid::EdgeSlot;
use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use std::collections::HashMap;
use std::vec;
use std::vec::Vec;

/// Records the spans of a row: `(x0, x1, colour)`.
struct Rec {
    size: (u16, u16),
    spans: Vec<(i32, i32, u32)>,
}

impl SpanTarget for Rec {
    type Color = Rgb888;
    type Error = Infallible;
    fn size(&self) -> (u16, u16) {
        self.size
    }
    fn fill_span(&mut self, s: Span, c: Rgb888) -> Result<(), Infallible> {
        let c = (c.r() as u32) << 16 | (c.g() as u32) << 8 | c.b() as u32;
        self.spans.push((s.x0 as i32, s.x1 as i32, c));
        Ok(())
    }
}

/// An end of a trapezoid on a row: pixel, `0` for `r` or `1` for `l`,
/// trapezoid.
type End = (i32, u8, usize);

/// The ends of a row in order, each with whether it is at the pixel of
/// the one before.
fn order(ends: &[End]) -> Vec<(u8, usize, bool)> {
    ends.iter()
        .enumerate()
        .map(|(i, e)| (e.1, e.2, i > 0 && ends[i - 1].0 == e.0))
        .collect()
}

/// What a run is made of: its covers where it starts, the ends at its
/// start, at its end, and in between.
type Shape = (Vec<usize>, Vec<usize>, Vec<usize>, Vec<(u8, usize, bool)>);

#[derive(Default)]
struct Counts {
    rows: u32,
    spans: u32,
    runs: u32,
    live_same: u32,
    rows_same: u32,
    spans_same: u32,
    runs_shape: u32,
    runs_face: u32,
    trapezoid_rows: u32,
    trapezoid_rows_shown: u32,
    never_shown: u32,
    rows_crossed: u32,
}

/// The pools of a store for a test scene.
pub(super) struct Pools {
    traps: Vec<Trapezoid>,
    faces: Vec<Face>,
    segs: [Segment; 1],
    rows: Vec<u16>,
    slots: Vec<EdgeSlot>,
}

impl Pools {
    /// Pools for `n` faces on `h` rows.
    pub(super) fn new(n: usize, h: u16) -> Pools {
        Pools {
            traps: vec![Trapezoid::EMPTY; 16 * n + 64],
            faces: vec![Face::EMPTY; n + 1],
            segs: [Segment::EMPTY; 1],
            rows: vec![0u16; h as usize],
            slots: vec![EdgeSlot::EMPTY; 64],
        }
    }

    /// A `w × h` store of `polys`, in segment 0, face `k` in a colour of
    /// its own (so that no two faces merge). Every other triangle is
    /// added as a mesh's are (a run of triangles whose depth is left for
    /// later), so that each scene has both kinds of face.
    pub(super) fn store<P: AsRef<[Vertex3]>>(
        &mut self,
        polys: &[P],
        w: u16,
        h: u16,
    ) -> TrapezoidStore<'_> {
        let mut store = TrapezoidStore::new(
            StoreMemory {
                trapezoids: &mut self.traps,
                faces: &mut self.faces,
                segments: &mut self.segs,
                rows: &mut self.rows,
                edges: &mut self.slots,
            },
            w,
            h,
        )
        .unwrap();
        let clip = ClipRect::full(w, h);
        for (k, p) in polys.iter().enumerate() {
            let c = Rgb888::new((k >> 8) as u8 + 1, k as u8, 7);
            match p.as_ref() {
                &[a, b, d] if k % 2 == 1 => {
                    store.triangle_run(0, &clip, true, |r| r.triangle([a, b, d], c))
                }
                v => store.add_polygon(0, v.iter().copied(), c, &clip),
            }
            .unwrap();
        }
        store
    }
}

fn count(polys: &[Vec<Vertex3>], w: u16, h: u16) -> Counts {
    let mut pools = Pools::new(polys.len(), h);
    let store = pools.store(polys, w, h);
    let tr: Vec<Trapezoid> = (0..store.len() as u16)
        .map(|t| *store.trapezoid(t).unwrap())
        .collect();
    let mut edges: Vec<Option<(Edge, Edge)>> = vec![None; tr.len()];
    let mut active = vec![Active::EMPTY; tr.len() + 1];
    let mut runs = vec![Run::EMPTY; w as usize];
    let mut ws = Workspace::new(&mut active, &mut runs);
    let mut sweep = Sweep::new(&mut ws, Resolve::Crossing);
    let mut c = Counts::default();
    let (mut last_ends, mut last_live, mut last_crossed) = (Vec::new(), Vec::new(), true);
    let mut last_runs: HashMap<Shape, u32> = HashMap::new();
    let mut shown = vec![false; tr.len()];
    for y in 0..h as i32 {
        let (mut live, mut ends, mut pixels) = (Vec::new(), Vec::new(), Vec::new());
        for (t, tp) in tr.iter().enumerate() {
            if y < tp.top() || y >= tp.end() {
                edges[t] = None;
                continue;
            }
            let e = edges[t].get_or_insert((tp.left(), tp.right()));
            if y > tp.top() {
                e.0.step();
                e.1.step();
            }
            let (l, r) = (ceil_px(e.0.units()), ceil_px(e.1.units()));
            let (x0, x1) = tp.columns();
            let (l, r) = (l.max(x0 as i32), r.min(x1 as i32));
            live.push(t);
            if l < r {
                pixels.push((l, r, t));
                ends.push((l, 1u8, t));
                ends.push((r, 0u8, t));
            }
        }
        ends.sort();
        let before = sweep.stats();
        let mut rec = Rec {
            size: (w, h),
            spans: Vec::new(),
        };
        sweep
            .draw(&store, &mut ws, 1, &mut rec, Some(Rgb888::BLACK))
            .unwrap();
        let after = sweep.stats();
        let resolved = |s: VisibleStats| s.empty + s.single + s.multiple + s.intersecting;
        let spans = resolved(after) - resolved(before);
        c.rows += 1;
        c.spans += spans;
        c.runs += rec.spans.len() as u32;
        if live == last_live {
            c.live_same += 1;
            if !last_crossed && order(&ends) == order(&last_ends) {
                c.rows_same += 1;
                c.spans_same += spans;
            }
        }
        // A trapezoid shows on the row when a span of its face's colour
        // (each face has its own) overlaps its pixels.
        for &(l, r, t) in &pixels {
            let colour = store.face(tr[t].face).map_or(0, |f| f.color_bits());
            c.trapezoid_rows += 1;
            if rec
                .spans
                .iter()
                .any(|&(a, b, k)| k == colour && a < r && b > l)
            {
                c.trapezoid_rows_shown += 1;
                shown[t] = true;
            }
        }
        let mut shapes = HashMap::new();
        for &(a, b, colour) in &rec.spans {
            let at = |x: i32| -> Vec<usize> {
                ends.iter()
                    .filter(|e| e.0 == x)
                    .map(|e| 2 * e.2 + e.1 as usize)
                    .collect()
            };
            let (starts, stops) = (at(a), at(b));
            if (a > 0 && starts.is_empty()) || (b < w as i32 && stops.is_empty()) {
                continue; // an end at a crossing point
            }
            let covers: Vec<usize> = ends
                .iter()
                .filter(|e| e.1 == 1 && e.0 <= a)
                .filter(|e| ends.iter().any(|f| f.1 == 0 && f.2 == e.2 && f.0 > a))
                .map(|e| e.2)
                .collect();
            let inner = ends
                .iter()
                .enumerate()
                .filter(|(_, e)| a < e.0 && e.0 < b)
                .map(|(i, e)| (e.1, e.2, i > 0 && ends[i - 1].0 == e.0))
                .collect();
            let shape: Shape = (covers, starts, stops, inner);
            if let Some(&was) = last_runs.get(&shape) {
                c.runs_shape += 1;
                c.runs_face += (was == colour) as u32;
            }
            shapes.insert(shape, colour);
        }
        last_runs = shapes;
        (last_ends, last_live) = (ends, live);
        last_crossed = after.intersecting > before.intersecting;
        c.rows_crossed += last_crossed as u32;
    }
    c.never_shown = shown.iter().filter(|s| !**s).count() as u32;
    c
}

/// A named scene: its faces and its frame.
pub(super) type Named = (std::string::String, Vec<Vec<Vertex3>>, u16, u16);

/// The 170-face lists of the image and the first view of the
/// benchmark's 170-, 300- and 1000-face scenes.
pub(super) fn scenes() -> Vec<Named> {
    let mut scenes: Vec<Named> = Vec::new();
    let v3 = |(x, y, z): (i32, i32, i32)| Vertex3 {
        x: Coord::from_bits(x as i16),
        y: Coord::from_bits(y as i16),
        z: Coord::from_bits(z as i16),
    };
    for (name, polys) in testkit::poly3_scenes::all().into_iter().take(2) {
        let faces = polys
            .iter()
            .filter(|p| testkit::reference3d::drawn(&p.poly))
            .map(|p| p.poly.iter().copied().map(v3).collect())
            .collect();
        let (w, h) = (testkit::poly3_scenes::W, testkit::poly3_scenes::H);
        scenes.push((std::format!("poly3 {name}"), faces, w, h));
    }
    use testkit::scenes3d::{scene, Version};
    for n in [170, 300, 1000] {
        for v in [Version::Layered, Version::Tilted] {
            let s = scene(v, n);
            let faces = s.views[0]
                .iter()
                .map(|f| {
                    f.iter()
                        .map(|p| {
                            v3((
                                p.x.to_bits().into(),
                                p.y.to_bits().into(),
                                p.z.to_bits().into(),
                            ))
                        })
                        .collect()
                })
                .collect();
            let (w, h) = (testkit::scenes3d::W, testkit::scenes3d::H);
            scenes.push((std::format!("{} {n}", v.short()), faces, w, h));
        }
    }
    scenes
}

/// `part` of `all` in per mille.
fn per_mille(part: u32, all: u32) -> u32 {
    part * 1000 / all.max(1)
}

#[test]
fn coherence_between_rows() {
    let scenes = scenes();
    std::println!("scene | rows | spans | runs | rows, same live set | rows as above | their spans | runs shaped as above | of those, same face | trapezoid-rows | shown | trapezoids never shown | rows with an intersecting span");
    for (name, faces, w, h) in &scenes {
        let c = count(faces, *w, *h);
        std::println!(
            "{name} | {} | {} | {} | {} | {} | {} ({}‰) | {} ({}‰) | {} ({}‰) | {} | {} | {} | {}",
            c.rows,
            c.spans,
            c.runs,
            c.live_same,
            c.rows_same,
            c.spans_same,
            per_mille(c.spans_same, c.spans),
            c.runs_shape,
            per_mille(c.runs_shape, c.runs),
            c.runs_face,
            per_mille(c.runs_face, c.runs),
            c.trapezoid_rows,
            c.trapezoid_rows_shown,
            c.never_shown,
            c.rows_crossed,
        );
        // Each count is a part of the one it refines.
        assert_eq!(c.rows, u32::from(*h), "{name}");
        assert!(c.rows_same <= c.live_same && c.live_same < c.rows, "{name}");
        assert!(c.spans_same <= c.spans, "{name}");
        assert!(
            c.runs_face <= c.runs_shape && c.runs_shape < c.runs,
            "{name}"
        );
        assert!(c.trapezoid_rows_shown <= c.trapezoid_rows, "{name}");
        assert!(c.rows_crossed < c.rows, "{name}");
        // A layered scene has no intersecting span, a tilted one has.
        let tilted = name.contains("tilted") || name.starts_with("3D");
        assert_eq!(c.rows_crossed > 0, tilted, "{name}");
    }
}
