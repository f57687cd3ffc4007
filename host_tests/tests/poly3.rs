//! `poly3` against the exact reference (`testkit::reference3d`), pixel
//! for pixel, through the whole path (`Writer` → `DisplayList` →
//! `Controller::render` with 3D storage → frame buffer), in both ways of
//! resolving intersecting spans.
//!
//! Scenes are random `poly3`s, 1 to 12 per frame, of either winding (the
//! back-facing ones are culled), some under clip registers:
//! * triangles with any depth at each vertex;
//! * planar polygons of 3 to 8 vertices, convex, concave or
//!   self-intersecting, on a grid of 1, 4 or 16 sixteenths, with a depth
//!   that is an exact affine function of the grid position.
//!
//! In *layered* scenes every polygon lies in a depth layer of its own
//! (layers at least 1/16 apart, in random order in the list): no mismatch
//! is allowed. In *interpenetrating* scenes the depths overlap freely, and
//! no mismatch is allowed either: the counts over 200 of them are printed
//! too.

use host_tests::harness3d::{compare, Mismatch};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestRunner};
use scanvert::visible::sweep::Resolve;
use testkit::reference::Window;
use testkit::reference3d::Poly3;

const W: u16 = 64;
const H: u16 = 48;

/// A polygon in screen space before depth: `(x, y)` in units, and the
/// plane as `z = p·a + q·b` over grid indices `(a, b)` (or `None` for a
/// triangle with free depths `zs`).
#[derive(Debug, Clone)]
struct Shape {
    xy: Vec<(i32, i32)>,
    grid: Vec<(i32, i32)>,
    slope: (i32, i32),
    zs: Vec<i32>,
    triangle: bool,
}

impl Shape {
    /// The depths, before they are shifted into place.
    fn depths(&self) -> Vec<i32> {
        if self.triangle {
            self.zs.clone()
        } else {
            self.grid
                .iter()
                .map(|&(a, b)| self.slope.0 * a + self.slope.1 * b)
                .collect()
        }
    }
}

/// A shape near the frame: a triangle with free depths (spread over
/// `spread`), or a planar polygon on a grid.
fn shape(spread: i32) -> impl Strategy<Value = Shape> {
    let triangle = (
        prop::collection::vec((-128..(W as i32 + 8) * 16, -128..(H as i32 + 8) * 16), 3),
        prop::collection::vec(-spread..=spread, 3),
    )
        .prop_map(|(xy, zs)| Shape {
            xy,
            grid: Vec::new(),
            slope: (0, 0),
            zs,
            triangle: true,
        });
    let planar = (
        prop::sample::select(vec![1, 4, 16]),
        (-128..(W as i32) * 16, -128..(H as i32) * 16),
        prop::collection::vec((0..48i32, 0..40i32), 3..=8),
        (-6..=6i32, -6..=6i32),
    )
        .prop_map(|(g, (ox, oy), pts, slope)| {
            // Grid indices scaled so that the polygon spans a similar size
            // whatever the grid.
            let k = 16 / g;
            let grid: Vec<(i32, i32)> = pts.iter().map(|&(a, b)| (a * k, b * k)).collect();
            let xy = grid
                .iter()
                .map(|&(a, b)| (ox + a * g, oy + b * g))
                .collect();
            // Slopes in units per grid step: scaled down on fine grids so
            // that the depths stay in range.
            let slope = (slope.0 * g, slope.1 * g);
            Shape {
                xy,
                grid,
                slope,
                zs: Vec::new(),
                triangle: false,
            }
        });
    prop_oneof![triangle, planar]
}

/// Clip registers: mostly the whole frame.
fn clip() -> impl Strategy<Value = Option<Window>> {
    let (w, h) = (W as i16, H as i16);
    prop_oneof![
        4 => Just(None),
        1 => (-4..w + 4, -4..h + 4, -4..w + 4, -4..h + 4).prop_map(|(x0, y0, x1, y1)| Some(Window { x0, y0, x1, y1 })),
    ]
}

/// `shape` placed with its smallest depth at `base`, or `None` when its
/// depths do not fit in `base..=top` (or in Q12.4).
fn place(s: &Shape, base: i32, top: i32, flip: bool, clip: Option<Window>) -> Option<Poly3> {
    let z = s.depths();
    let lo = *z.iter().min()?;
    let mut poly: Vec<(i32, i32, i32)> =
        s.xy.iter()
            .zip(&z)
            .map(|(&(x, y), &z)| (x, y, z - lo + base))
            .collect();
    if poly
        .iter()
        .any(|p| p.2 > top || p.2 > i16::MAX as i32 || p.2 < i16::MIN as i32)
    {
        return None;
    }
    if flip {
        poly.reverse();
    }
    Some(Poly3 { poly, clip })
}

/// Scenes whose polygons lie in separate depth layers, in random order.
fn layered() -> impl Strategy<Value = Vec<Poly3>> {
    (1usize..=12)
        .prop_flat_map(|n| {
            (
                prop::collection::vec((shape(2000), any::<bool>(), clip(), 1..64i32), n),
                Just((0..n).collect::<Vec<usize>>()).prop_shuffle(),
            )
        })
        .prop_filter_map("depths do not fit their layer", |(shapes, order)| {
            let n = shapes.len() as i32;
            let thick = 64000 / n;
            let mut out = Vec::new();
            for (k, (s, flip, clip, gap)) in shapes.iter().enumerate() {
                let layer = order[k] as i32;
                let base = -32000 + layer * thick;
                // Layers are `gap` apart at least: depths in base..=top.
                out.push(place(s, base, base + thick - gap, *flip, *clip)?);
            }
            Some(out)
        })
}

/// Scenes whose depths overlap freely.
fn interpenetrating() -> impl Strategy<Value = Vec<Poly3>> {
    prop::collection::vec(
        (shape(12000), any::<bool>(), clip(), -1500..1500i32),
        1..=12,
    )
    .prop_map(|shapes| {
        shapes
            .iter()
            .filter_map(|(s, flip, clip, base)| place(s, *base, i16::MAX as i32, *flip, *clip))
            .filter(|p| p.poly.len() >= 3)
            .collect()
    })
}

const MODES: [Resolve; 4] = [
    Resolve::Bisect,
    Resolve::Crossing,
    Resolve::Paint,
    Resolve::Auto,
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// Separate depth layers: every pixel is the reference's.
    #[test]
    fn layered_scenes_match_the_reference_exactly(scene in layered()) {
        for mode in MODES {
            let (m, first) = compare(&scene, W, H, mode);
            prop_assert_eq!(m.mismatched, 0, "{:?}: {:?} of {} covered differ, first {:?}", mode, m.mismatched, m.covered, first);
        }
    }

    /// Interpenetrating: every pixel is the reference's too.
    #[test]
    fn interpenetrating_scenes_match_the_reference_exactly(scene in interpenetrating()) {
        for mode in MODES {
            let (m, first) = compare(&scene, W, H, mode);
            prop_assert_eq!(m.mismatched, 0, "{:?}: {:?}, first {:?}", mode, m, first);
        }
    }
}

/// The mismatch rate over many interpenetrating scenes, per mode, printed
/// (`cargo test -p host-tests --test poly3 -- --nocapture`).
#[test]
fn interpenetrating_mismatch_rate_is_measured() {
    let mut runner = TestRunner::new(Config {
        cases: 1,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = interpenetrating();
    let mut total = [Mismatch::default(); 3];
    let mut scenes = 0;
    for _ in 0..200 {
        let scene = strategy.new_tree(&mut runner).expect("scene").current();
        scenes += 1;
        for (t, mode) in total.iter_mut().zip(MODES) {
            let (m, _) = compare(&scene, W, H, mode);
            t.covered += m.covered;
            t.mismatched += m.mismatched;
            t.intersecting += m.intersecting;
            t.exact += m.exact;
        }
    }
    for (t, mode) in total.iter().zip(MODES) {
        println!(
            "poly3 {mode:?}: {} scenes, {} covered pixels, {} mismatched: {:.3} per 1000 ({} intersecting spans, {} exact compares)",
            scenes,
            t.covered,
            t.mismatched,
            t.per_mille(),
            t.intersecting,
            t.exact
        );
        assert_eq!(t.mismatched, 0, "{mode:?}");
    }
}
