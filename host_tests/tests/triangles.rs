//! Triangles, which the scan converter fills as two runs of two edges
//! with no edge slots, sort or walk: pixel for pixel against the exact
//! reference through every port (`FrameBuffer`, `PackedFrameBuffer` of
//! even and odd widths, a counting target, the simulator's write port),
//! under random clip registers; the same spans in the same order and the
//! same counts as the walk of their edges (the path of any other
//! polygon); and the same frame in bands. Random triangles, and
//! degenerate ones: collinear, with repeated vertices, flat, vertical,
//! thin slivers, and reaching far outside the frame.

use embedded_graphics_core::pixelcolor::{BinaryColor, Rgb565, RgbColor};
use host_tests::harness::{assert_same, build_list, render_poly, vertex, CountingTarget, Draw};
use proptest::prelude::*;
use scanvert::controller::Controller;
use scanvert::display_list::DisplayList;
use scanvert::port::{FrameBuffer, PackedFrameBuffer};
use scanvert::raster::clip::{ClipRect, ClipWindow};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::cli::{render_scene, render_scene_bands_with, Scene};
use scanvert_sim::dual_port::DualPortRam;
use std::path::Path;
use testkit::reference::{rasterize, Coverage, Window};

type Poly = Vec<(i32, i32)>;

/// One triangle under `window`, rendered through the controller into
/// every port; each must cover exactly the reference's pixels.
fn check(poly: &[(i32, i32)], window: Window, w: u16, h: u16) {
    let want = rasterize(poly, window, w.into(), h.into());
    let what = (poly, window, w, h);
    // A counting target: no pixel twice, the counts its spans.
    assert_same(&render_poly(poly, window, w, h).coverage(), &want, &what);

    let draw = Draw {
        clip: Some(window),
        poly: poly.to_vec(),
    };
    let bytes = build_list(&[draw], w, h);
    let list = DisplayList::new_checked(&bytes).expect("valid list");
    let mut edges = [Edge::EMPTY; 8];

    let mut pixels = vec![BinaryColor::Off; w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut fb)
        .expect("render");
    let got = Coverage::from_fn(w.into(), h.into(), |i, j| {
        fb.pixel(i as u16, j as u16) == Some(BinaryColor::On)
    });
    assert_same(&got, &want, &what);

    // Packed: the list's default colour is white, the frame starts black;
    // one guard word past the frame must stay as it was.
    let n = PackedFrameBuffer::<Rgb565>::words_len(w, h);
    let mut words = vec![0u32; n + 1];
    words[n] = 0xdead_beef;
    let mut pk = PackedFrameBuffer::<Rgb565>::new(&mut words, w, h).expect("frame");
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut pk)
        .expect("render");
    let got = Coverage::from_fn(w.into(), h.into(), |i, j| {
        pk.pixel(i as u16, j as u16) == Some(Rgb565::WHITE)
    });
    assert_same(&got, &want, &what);
    if (w as usize * h as usize) % 2 == 1 {
        assert_eq!(words[n - 1] >> 16, 0, "the padding half of {what:?}");
    }
    assert_eq!(words[n], 0xdead_beef, "past the frame for {what:?}");

    let mut ram = DualPortRam::new(w, h);
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut ram.write_port())
        .expect("render");
    let got = Coverage::from_fn(w.into(), h.into(), |i, j| {
        ram.contents()[j as usize * w as usize + i as usize] == Rgb565::WHITE
    });
    assert_same(&got, &want, &what);
    assert_eq!(ram.write_counters().pixels_written, want.count() as u64);
}

/// The triangle straight through `Rasterizer::fill`, its vertices from an
/// iterator of exactly three (the triangle's path) and from one that does
/// not say how many (the walk of its edges): the same spans in the same
/// order and the same counts, with as many edge slots as vertices and
/// with many.
fn same_as_the_walk(poly: &[(i32, i32)], window: Window, w: u16, h: u16) {
    let what = (poly, window, w, h);
    let clip = ClipRect::from_window(
        ClipWindow {
            x0: window.x0,
            y0: window.y0,
            x1: window.x1,
            y1: window.y1,
        },
        w,
        h,
    );
    for slots in [3, 64] {
        let mut edges = vec![Edge::EMPTY; slots];
        let mut path = CountingTarget::new(w, h);
        let exact = poly.iter().map(|&p| vertex(p));
        assert_eq!(exact.size_hint(), (3, Some(3)));
        let a = Rasterizer::new(&mut edges)
            .fill(exact, &clip, BinaryColor::On, &mut path)
            .expect("fill");
        let mut walk = CountingTarget::new(w, h);
        let unsized_ = poly.iter().map(|&p| vertex(p)).filter(|_| true);
        let b = Rasterizer::new(&mut edges)
            .fill(unsized_, &clip, BinaryColor::On, &mut walk)
            .expect("fill");
        assert_eq!(path.spans, walk.spans, "spans of {what:?}, {slots} slots");
        assert_eq!(a, b, "counts of {what:?}, {slots} slots");
    }
}

/// The first pixel where the band render with `rows` differs from the
/// full render, if any.
fn differs_in_bands(
    poly: &[(i32, i32)],
    window: Window,
    w: u16,
    h: u16,
    rows: u16,
) -> Option<usize> {
    let draw = Draw {
        clip: Some(window),
        poly: poly.to_vec(),
    };
    let bytes = build_list(&[draw], w, h);
    let s = Scene::from_bytes(Path::new("triangle.scvl"), bytes).expect("scene");
    let full = render_scene(&s).expect("full render");
    let band = render_scene_bands_with(&s, rows, Resolve::default()).expect("band render");
    let (a, b) = (full.ram.contents(), band.ram.contents());
    a.iter().zip(b).position(|(p, q)| p != q)
}

/// A coordinate near a frame side, on the pixel grid or any sixteenth.
fn near(side: u16) -> impl Strategy<Value = i32> {
    let s = side as i32;
    prop_oneof![(-4..s + 4).prop_map(|p| 16 * p), (-4 * 16..(s + 4) * 16),]
}

/// Anywhere in Q12.4 (far outside a small frame).
fn far() -> impl Strategy<Value = i32> {
    i16::MIN as i32..=i16::MAX as i32
}

/// Triangles: random, reaching far out, and degenerate (collinear,
/// repeated vertices, flat, vertical, slivers a unit wide).
fn triangle(w: u16, h: u16) -> impl Strategy<Value = Poly> {
    let point = move || (near(w), near(h));
    let random = prop::collection::vec(point(), 3);
    let outside = (point(), point(), (far(), far())).prop_map(|(a, b, c)| vec![a, b, c]);
    let collinear = (point(), point(), -3..=3i32).prop_map(|(a, b, k)| {
        let c = (a.0 + k * (b.0 - a.0) / 2, a.1 + k * (b.1 - a.1) / 2);
        vec![a, b, c]
    });
    let repeated = (point(), point(), 0..3usize).prop_map(|(a, b, k)| {
        let mut p = vec![a, a, b];
        p.rotate_left(k);
        p
    });
    let flat = (near(w), near(w), near(w), near(h))
        .prop_map(|(x0, x1, x2, y)| vec![(x0, y), (x1, y), (x2, y)]);
    let vertical = (near(w), near(h), near(h), near(h))
        .prop_map(|(x, y0, y1, y2)| vec![(x, y0), (x, y1), (x, y2)]);
    let sliver = (point(), point(), -1..=1i32, -1..=1i32)
        .prop_map(|(a, b, dx, dy)| vec![a, b, (b.0 + dx, b.1 + dy)]);
    prop_oneof![
        4 => random,
        1 => outside,
        1 => collinear,
        1 => repeated,
        1 => flat,
        1 => vertical,
        2 => sliver,
    ]
}

fn window(w: u16, h: u16) -> impl Strategy<Value = Window> {
    let (w, h) = (w as i16, h as i16);
    prop_oneof![
        Just(Window::full(w as u16, h as u16)),
        (-4..w + 4, -4..h + 4, -4..w + 4, -4..h + 4).prop_map(|(x0, y0, x1, y1)| Window {
            x0,
            y0,
            x1,
            y1
        }),
    ]
}

fn case() -> impl Strategy<Value = (Poly, Window, u16, u16)> {
    (prop::sample::select(vec![(32u16, 24u16), (33, 20), (31, 17), (1, 9), (2, 5)]))
        .prop_flat_map(|(w, h)| (triangle(w, h), window(w, h), Just(w), Just(h)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn triangles_match_the_reference((poly, window, w, h) in case()) {
        check(&poly, window, w, h);
        same_as_the_walk(&poly, window, w, h);
    }

    #[test]
    fn triangles_are_the_same_in_bands(
        (poly, window, w, h) in case(),
        rows in prop_oneof![Just(1u16), Just(7), Just(16), 1u16..30],
    ) {
        prop_assert_eq!(differs_in_bands(&poly, window, w, h, rows), None);
    }
}

/// Triangles at the range's corners and on pixel centres, each under the
/// whole frame and a narrow clip.
#[test]
fn hard_triangles() {
    let (w, h) = (33u16, 20u16);
    let (lo, hi) = (i16::MIN as i32, i16::MAX as i32);
    let cases: [Poly; 8] = [
        vec![(lo, lo), (hi, lo), (lo, hi)],
        vec![(lo, lo), (hi, hi), (lo, hi)],
        vec![(hi, lo), (lo, hi), (hi, hi)],
        // Vertices on pixel centres: crossings exactly on them.
        vec![(8, 8), (16 * 30 + 8, 16 * 3 + 8), (16 * 5 + 8, 16 * 18 + 8)],
        // The middle vertex exactly on a row centre, left and right.
        vec![(0, 0), (16 * 20, 16 * 7 + 8), (16 * 3, 16 * 19)],
        vec![(16 * 30, 0), (16 * 2, 16 * 7 + 8), (16 * 25, 16 * 19)],
        // A sliver one unit wide across the frame.
        vec![(-40, -40), (16 * 40, 16 * 25), (16 * 40 + 1, 16 * 25)],
        // Flat top and flat bottom.
        vec![(16, 16), (16 * 30, 16), (16 * 15, 16 * 19)],
    ];
    let narrow = Window {
        x0: 5,
        y0: 3,
        x1: 21,
        y1: 14,
    };
    for poly in &cases {
        for window in [Window::full(w, h), narrow] {
            check(poly, window, w, h);
            same_as_the_walk(poly, window, w, h);
            for rows in [1, 7, 16] {
                assert_eq!(
                    differs_in_bands(poly, window, w, h, rows),
                    None,
                    "{poly:?} {rows}"
                );
            }
        }
    }
}
