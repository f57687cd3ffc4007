//! The compact trapezoid record keeps each edge by its ends and rebuilds
//! the exact stepper when the trapezoid enters the active list. These
//! check, on random polygons and clips, that the stepper so rebuilt is the
//! one the cut sets up for the trapezoid's rows (`Edge::new` on the
//! edge's ends), that stepping it down to any row gives the crossing of
//! the stepper set up on that row, and that its pixel on every row is the
//! exact `⌈x − ½⌉` computed from the ends with rationals.

use proptest::prelude::*;
use scanvert::fixed::{Coord, Vertex3};
use scanvert::raster::clip::{ClipRect, ClipWindow};
use scanvert::raster::edge::Edge;
use scanvert::visible::store::{Face, Segment, StoreMemory, TrapezoidStore};
use scanvert::visible::trapezoid::{EdgeSlot, Polygon, Side, Trapezoid};

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// `⌈n / d⌉`, `d > 0`.
fn ceil_div(n: i128, d: i128) -> i128 {
    -((-n).div_euclid(d))
}

/// The exact pixel of the crossing of the edge `a → b` (units, `a` the
/// upper end) with the centre line of row `j`: `⌈x − ½⌉` in pixels.
fn exact_pixel(side: &Side, j: i32) -> i32 {
    let (a, b) = side.ends();
    let (x0, y0) = (a.x.units() as i128, a.y.units() as i128);
    let (x1, y1) = (b.x.units() as i128, b.y.units() as i128);
    let dy = y1 - y0;
    let yc = 16 * j as i128 + 8;
    // x = x0 + (yc − y0)·dx/dy units; ⌈(x − 8)/16⌉ pixels.
    let num = x0 * dy + (yc - y0) * (x1 - x0) - 8 * dy;
    ceil_div(num, 16 * dy) as i32
}

/// Checks one side against the stepper set up on each of its rows and
/// the exact crossing.
fn check_side(side: &Side) -> Result<(), TestCaseError> {
    let (top, end) = side.rows();
    prop_assert!(top < end);
    let (a, b) = side.ends();
    let mut e = side.edge();
    prop_assert_eq!(Some(e), Edge::new(a, b, (top, end)));
    prop_assert_eq!((e.top(), e.end()), (top, end));
    for j in top..end {
        // Set up on row j, or stepped there from the top: the same
        // crossing (so the same error counter, `x·dy` minus the exact
        // crossing), and the same slope.
        let f = Edge::new(a, b, (j, end));
        prop_assert_eq!(
            f.map(|f| (f.units(), f.end())),
            Some((e.units(), end)),
            "row {}",
            j
        );
        e.load_pixel();
        prop_assert_eq!(e.pixel(), exact_pixel(side, j), "row {}", j);
        e.step();
    }
    Ok(())
}

fn v3(x: i16, y: i16, z: i16) -> Vertex3 {
    Vertex3 {
        x: Coord::from_bits(x),
        y: Coord::from_bits(y),
        z: Coord::from_bits(z),
    }
}

/// A coordinate: inside a small frame, on a coarse grid (shared rows and
/// crossings on row centres), or anywhere in the format.
fn coord(frame: i16) -> impl Strategy<Value = i16> {
    prop_oneof![
        3 => -64..frame * 16 + 64,
        1 => (-4..frame + 4).prop_map(|v| v * 16),
        1 => any::<i16>(),
    ]
}

fn polygon() -> impl Strategy<Value = Vec<Vertex3>> {
    prop::collection::vec((coord(48), coord(40), any::<i16>()), 3..9)
        .prop_map(|v| v.into_iter().map(|(x, y, z)| v3(x, y, z)).collect())
}

fn clip() -> impl Strategy<Value = ClipRect> {
    prop_oneof![
        Just(ClipRect::full(48, 40)),
        Just(ClipRect::full(4096, 4096)),
        (0i16..48, 0i16..40, 0i16..48, 0i16..40).prop_map(|(x0, y0, w, h)| {
            ClipRect::from_window(
                ClipWindow {
                    x0,
                    y0,
                    x1: x0 + w,
                    y1: y0 + h,
                },
                48,
                40,
            )
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Every side the cut hands over rebuilds the stepper it sets up, which
    /// steps through the exact crossings.
    #[test]
    fn rebuilt_steppers_are_the_cut_s_and_exact(poly in polygon(), clip in clip()) {
        let mut slots = [EdgeSlot::EMPTY; 8];
        let p = Polygon::load(&mut slots, poly.iter().copied(), &clip).unwrap();
        let mut sides = Vec::new();
        p.cut(|l, r| {
            sides.push((l, r));
            Ok::<(), ()>(())
        })
        .unwrap();
        for (l, r) in &sides {
            prop_assert_eq!(l.rows(), r.rows());
            check_side(l)?;
            check_side(r)?;
        }
    }

    /// The store's records give back the steppers of the sides they were
    /// made from, on the same rows, and the face holds the plane's depth.
    #[test]
    fn stored_records_rebuild_the_cut_s_steppers(poly in polygon(), clip in clip()) {
        let mut edges = [EdgeSlot::EMPTY; 8];
        let p = Polygon::load(&mut edges, poly.iter().copied(), &clip).unwrap();
        let plane = p.plane().copied();
        let mut sides = Vec::new();
        p.cut(|l, r| {
            sides.push((l, r));
            Ok::<(), ()>(())
        })
        .unwrap();

        let (w, h) = (clip.x1().max(1), clip.y1().max(1));
        let mut traps = vec![Trapezoid::EMPTY; 64];
        let mut faces = [Face::EMPTY; 2];
        let mut segs = [Segment::EMPTY; 1];
        let mut rows = vec![0u16; h as usize];
        let mut slots = [EdgeSlot::EMPTY; 8];
        let mut store = TrapezoidStore::new(
            StoreMemory {
                trapezoids: &mut traps,
                faces: &mut faces,
                segments: &mut segs,
                rows: &mut rows,
                edges: &mut slots,
            },
            w,
            h,
        )
        .unwrap();
        let n = store.add_polygon(0, poly.iter().copied(), Rgb888::CYAN, &clip).unwrap();
        // Faces with fewer than two edges set up store nothing.
        prop_assert!(n as usize <= sides.len());
        if n == 0 {
            return Ok(());
        }
        prop_assert_eq!(n as usize, sides.len());
        // The segment's chain is newest first.
        let stored: Vec<Trapezoid> = store.segment_trapezoids(0).map(|(_, t)| *t).collect();
        for (t, (l, r)) in stored.iter().rev().zip(&sides) {
            prop_assert_eq!(t.left_side(), *l);
            prop_assert_eq!(t.right_side(), *r);
            prop_assert_eq!(t.left(), l.edge());
            prop_assert_eq!(t.right(), r.edge());
            prop_assert_eq!((t.top(), t.end()), l.rows());
            let face = store.face(t.face()).unwrap();
            prop_assert_eq!(Some(face.depth()), plane.map(|p| p.depth()));
            prop_assert_eq!(face.color(), Rgb888::CYAN);
        }
    }
}
