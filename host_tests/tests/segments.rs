//! Segments: regenerating one segment redoes only that segment's work,
//! leaves the other segments' trapezoids untouched, and the frame is the
//! same as one built from scratch.

use embedded_graphics_core::pixelcolor::Rgb888;
use host_tests::harness3d::vertex3;
use scanvert::raster::clip::ClipRect;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Counters, Face, Segment, StoreMemory, TrapezoidStore};
use scanvert::visible::sweep::{Active, Resolve, Workspace};
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};

const W: u16 = 96;
const H: u16 = 64;
const SEGMENTS: usize = 5;

/// Segment `s`'s polygons in version `version`: a small grid of bars.
fn polygons(s: usize, version: i32) -> Vec<Vec<(i32, i32, i32)>> {
    let mut out = Vec::new();
    for k in 0..6 {
        let x = (s as i32 * 18 + k % 3 * 5) * 16;
        let y = (4 + k / 3 * 24) * 16;
        let z = 1000 + 500 * s as i32 - 300 * k + 77 * version;
        let h = (8 + (k + version) % 9) * 16;
        // A quad leaning in depth (planar) and a triangle across it.
        out.push(vec![
            (x, y, z),
            (x, y + h, z + 64),
            (x + 96, y + h, z + 64 - 32),
            (x + 96, y, z - 32),
        ]);
        out.push(vec![
            (x - 40, y + 20, z + 400),
            (x + 30, y + h + 30, z - 900),
            (x + 140, y + 10, z + 50),
        ]);
    }
    out
}

struct Memory {
    traps: Vec<Trapezoid>,
    faces: Vec<Face>,
    segs: Vec<Segment>,
    rows: Vec<u16>,
    edges: Vec<EdgeSlot>,
}

impl Memory {
    /// Room for every segment's polygons: a face each, and a trapezoid per
    /// edge at most (a polygon is cut at its vertices' rows).
    fn new() -> Self {
        let all = (0..SEGMENTS).flat_map(|s| polygons(s, 0));
        let (faces, edges, most) = all.fold((0, 0, 0), |(f, e, m), p| {
            (f + 1, e + p.len(), m.max(p.len()))
        });
        Memory {
            traps: vec![Trapezoid::EMPTY; edges],
            faces: vec![Face::EMPTY; faces],
            segs: vec![Segment::EMPTY; SEGMENTS],
            rows: vec![0; H as usize],
            edges: vec![EdgeSlot::EMPTY; most],
        }
    }

    fn store(&mut self) -> TrapezoidStore<'_> {
        TrapezoidStore::new(
            StoreMemory {
                trapezoids: &mut self.traps,
                faces: &mut self.faces,
                segments: &mut self.segs,
                rows: &mut self.rows,
                edges: &mut self.edges,
            },
            W,
            H,
        )
        .unwrap()
    }
}

fn fill(store: &mut TrapezoidStore<'_>, s: usize, version: i32) {
    let clip = ClipRect::full(W, H);
    for (k, p) in polygons(s, version).iter().enumerate() {
        let color = Rgb888::new(s as u8 * 40, k as u8 * 10, 200);
        store
            .add_polygon(s, p.iter().copied().map(vertex3), color, &clip)
            .unwrap();
    }
}

/// The frame as colours, row-major.
fn picture(store: &TrapezoidStore<'_>) -> Vec<Option<Rgb888>> {
    // Every trapezoid of the store may overlap one row.
    let mut active = vec![Active::EMPTY; store.len()];
    let mut runs = vec![Run::EMPTY; W as usize];
    let mut out = Vec::new();
    Workspace::new(&mut active, &mut runs)
        .resolve(store, Resolve::default(), |_, runs| {
            for r in runs {
                let c = (!r.is_background()).then(|| store.face(r.ink()).unwrap().color());
                out.extend(std::iter::repeat_n(c, r.len() as usize));
            }
            Ok::<(), ()>(())
        })
        .unwrap();
    out
}

#[test]
fn regenerating_one_segment_redoes_only_that_one() {
    let mut mem = Memory::new();
    let mut store = mem.store();
    for s in 0..SEGMENTS {
        fill(&mut store, s, 0);
    }
    let before: Vec<Counters> = store.segments().iter().map(Segment::counters).collect();
    let kept: Vec<Vec<(u16, Trapezoid)>> = (0..SEGMENTS)
        .map(|s| store.segment_trapezoids(s).map(|(i, t)| (i, *t)).collect())
        .collect();

    // Frame 2: segment 3 changed.
    store.clear_segment(3).unwrap();
    fill(&mut store, 3, 1);

    let after: Vec<Counters> = store.segments().iter().map(Segment::counters).collect();
    for s in 0..SEGMENTS {
        if s == 3 {
            assert_eq!(after[s].clears, before[s].clears + 1);
            assert_eq!(after[s].polygons, before[s].polygons + 12);
            let rebuilt = after[s].trapezoids - before[s].trapezoids;
            assert_eq!(rebuilt, store.segment(s).unwrap().trapezoids());
            println!(
                "segment 3 regenerated: {rebuilt} trapezoids cut; the other {} segments: 0 (they hold {})",
                SEGMENTS - 1,
                store.len() as u32 - rebuilt
            );
        } else {
            assert_eq!(after[s], before[s], "segment {s} did work");
            // The very same slots, bit for bit.
            let now: Vec<(u16, Trapezoid)> =
                store.segment_trapezoids(s).map(|(i, t)| (i, *t)).collect();
            assert_eq!(now.len(), kept[s].len());
            for ((i, t), (j, u)) in now.iter().zip(&kept[s]) {
                assert_eq!(i, j);
                assert_eq!(t.left(), u.left());
                assert_eq!(t.right(), u.right());
                assert_eq!(t.columns(), u.columns());
                assert_eq!(t.face(), u.face());
            }
        }
    }
    let total = store.counters();
    assert_eq!(
        total.trapezoids,
        before.iter().map(|c| c.trapezoids).sum::<u32>() + store.segment(3).unwrap().trapezoids()
    );

    // The frame equals one built from scratch with segment 3 at version 1.
    let got = picture(&store);
    let mut mem2 = Memory::new();
    let mut fresh = mem2.store();
    for s in 0..SEGMENTS {
        fill(&mut fresh, s, (s == 3) as i32);
    }
    assert_eq!(got, picture(&fresh));
    assert!(got.iter().any(Option::is_some));
}

#[test]
fn a_full_store_empties_only_the_segment_being_filled() {
    let mut mem = Memory::new();
    mem.traps.truncate(20);
    let mut store = mem.store();
    fill(&mut store, 0, 0);
    let n0 = store.segment(0).unwrap().trapezoids();
    let clip = ClipRect::full(W, H);
    let mut failed = false;
    for p in polygons(1, 0).iter().chain(&polygons(2, 0)) {
        if store
            .add_polygon(
                1,
                p.iter().copied().map(vertex3),
                Rgb888::new(1, 1, 1),
                &clip,
            )
            .is_err()
        {
            failed = true;
            break;
        }
    }
    assert!(failed, "20 slots must run out");
    assert_eq!(store.segment(1).unwrap().trapezoids(), 0);
    assert_eq!(store.segment(0).unwrap().trapezoids(), n0);
    assert_eq!(store.len() as u32, n0);
    // Still consistent: the frame draws segment 0 alone.
    assert!(picture(&store).iter().any(Option::is_some));
}
