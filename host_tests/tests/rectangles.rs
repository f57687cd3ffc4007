//! Polygons with vertical edges (rectangles, rectilinear polygons, and
//! trapezoids with vertical sides), where the scan converter writes a
//! rectangle at a time (`SpanTarget::fill_rect`) between two vertical
//! edges: pixel for pixel against the exact reference, through every port
//! (`FrameBuffer`, `PackedFrameBuffer` of even and odd widths, a counting
//! target on the trait's default, the simulator's write port), under random
//! clip registers. And quadrilaterals of every kind, which the controller
//! fills without the walk of their edges (a rectangle from its corners, a
//! quad monotone in `y` as two chains): the same spans, counts and errors
//! as the walk, and the reference's pixels.

use embedded_graphics_core::pixelcolor::{BinaryColor, Rgb565, RgbColor};
use host_tests::harness::{
    assert_same, build_list, render_counting, render_poly, vertex, CountingTarget, Draw,
};
use proptest::prelude::*;
use scanvert::controller::{Controller, RenderError};
use scanvert::display_list::DisplayList;
use scanvert::port::{FrameBuffer, PackedFrameBuffer};
use scanvert::raster::clip::{ClipRect, ClipWindow};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::{FillError, Rasterizer};
use scanvert_sim::dual_port::DualPortRam;
use testkit::reference::{rasterize, Coverage, Window};

type Poly = Vec<(i32, i32)>;

/// One polygon under `window`, rendered into every port; each must cover
/// exactly the reference's pixels.
fn check(poly: &[(i32, i32)], window: Window, w: u16, h: u16) {
    let want = rasterize(poly, window, w.into(), h.into());
    let what = (poly, window, w, h);
    // The trait's default `fill_rect`: one span a row, counted.
    assert_same(&render_poly(poly, window, w, h).coverage(), &want, &what);

    let bytes = build_list(
        &[Draw {
            clip: Some(window),
            poly: poly.to_vec(),
        }],
        w,
        h,
    );
    let list = DisplayList::new_checked(&bytes).expect("valid list");
    let mut edges = [Edge::EMPTY; 64];
    let mut render = |target: &mut dyn FnMut(&mut Controller<'_>)| {
        let mut c = Controller::new(Rasterizer::new(&mut edges));
        target(&mut c);
    };

    let mut pixels = vec![BinaryColor::Off; w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
    render(&mut |c| {
        c.render(&list, &mut fb).expect("render");
    });
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
    render(&mut |c| {
        c.render(&list, &mut pk).expect("render");
    });
    let got = Coverage::from_fn(w.into(), h.into(), |i, j| {
        pk.pixel(i as u16, j as u16) == Some(Rgb565::WHITE)
    });
    assert_same(&got, &want, &what);
    if (w as usize * h as usize) % 2 == 1 {
        assert_eq!(words[n - 1] >> 16, 0, "the padding half of {what:?}");
    }
    assert_eq!(words[n], 0xdead_beef, "past the frame for {what:?}");

    let mut ram = DualPortRam::new(w, h);
    render(&mut |c| {
        c.render(&list, &mut ram.write_port()).expect("render");
    });
    let got = Coverage::from_fn(w.into(), h.into(), |i, j| {
        ram.contents()[j as usize * w as usize + i as usize] == Rgb565::WHITE
    });
    assert_same(&got, &want, &what);
    assert_eq!(ram.write_counters().pixels_written, want.count() as u64);
}

/// A coordinate near a frame side, on the pixel grid or any sixteenth.
fn near(side: u16) -> impl Strategy<Value = i32> {
    let s = side as i32;
    prop_oneof![(-4..s + 4).prop_map(|p| 16 * p), (-4 * 16..(s + 4) * 16),]
}

/// Rectangles, either winding, starting at any corner.
fn rectangle(w: u16, h: u16) -> impl Strategy<Value = Poly> {
    (near(w), near(h), near(w), near(h), 0..4usize, any::<bool>()).prop_map(
        |(x0, y0, x1, y1, start, rev)| {
            let mut p = vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1)];
            p.rotate_left(start);
            if rev {
                p.reverse();
            }
            p
        },
    )
}

/// Rectilinear polygons: alternating horizontal and vertical moves, closed
/// by a last vertical and horizontal move (so usually self-intersecting).
fn rectilinear(w: u16, h: u16) -> impl Strategy<Value = Poly> {
    prop::collection::vec((near(w), near(h)), 2..=6).prop_map(|steps| {
        let mut p = Vec::new();
        let (mut x, mut y) = steps[0];
        p.push((x, y));
        for &(nx, ny) in &steps[1..] {
            x = nx;
            p.push((x, y));
            y = ny;
            p.push((x, y));
        }
        p.push((steps[0].0, y));
        p
    })
}

/// Trapezoids with two vertical sides and slanted top and bottom.
fn vertical_sided(w: u16, h: u16) -> impl Strategy<Value = Poly> {
    (near(w), near(w), near(h), near(h), near(h), near(h))
        .prop_map(|(x0, x1, a, b, c, d)| vec![(x0, a), (x1, b), (x1, c), (x0, d)])
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
    (prop::sample::select(vec![(32u16, 24u16), (33, 20), (31, 17), (1, 9), (2, 5)])).prop_flat_map(
        |(w, h)| {
            (
                prop_oneof![rectangle(w, h), rectilinear(w, h), vertical_sided(w, h)],
                window(w, h),
                Just(w),
                Just(h),
            )
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn polygons_with_vertical_edges_match_the_reference((poly, window, w, h) in case()) {
        check(&poly, window, w, h);
    }
}

#[test]
fn hard_cases() {
    let px = |x: i32, y: i32| (16 * x, 16 * y);
    let full = |w: u16, h: u16| Window::full(w, h);
    // The whole frame, even and odd widths; a one-pixel column and row.
    for (w, h) in [(32u16, 24u16), (33, 7), (1, 1), (3, 1)] {
        let (wi, hi) = (w as i32, h as i32);
        check(
            &[px(0, 0), px(wi, 0), px(wi, hi), px(0, hi)],
            full(w, h),
            w,
            h,
        );
        check(
            &[
                px(-5, -5),
                px(wi + 5, -5),
                px(wi + 5, hi + 5),
                px(-5, hi + 5),
            ],
            full(w, h),
            w,
            h,
        );
        check(
            &[px(0, 0), px(1, 0), px(1, hi), px(0, hi)],
            full(w, h),
            w,
            h,
        );
        check(
            &[px(wi - 1, 0), px(wi, 0), px(wi, hi), px(wi - 1, hi)],
            full(w, h),
            w,
            h,
        );
    }
    // Sides exactly on and just off pixel centres.
    check(&[(8, 8), (24, 8), (24, 40), (8, 40)], full(8, 8), 8, 8);
    check(&[(9, 8), (23, 8), (23, 40), (9, 40)], full(8, 8), 8, 8);
    check(&[(7, 7), (25, 7), (25, 41), (7, 41)], full(8, 8), 8, 8);
    // Zero width, zero height.
    check(&[px(3, 1), px(3, 1), px(3, 6), px(3, 6)], full(8, 8), 8, 8);
    check(&[px(1, 3), px(6, 3), px(6, 3), px(1, 3)], full(8, 8), 8, 8);
    // Two rectangles in one self-intersecting polygon, touching and
    // overlapping (even-odd: the overlap is empty).
    check(
        &[
            px(1, 1),
            px(5, 1),
            px(5, 5),
            px(3, 5),
            px(3, 3),
            px(7, 3),
            px(7, 7),
            px(1, 7),
        ],
        full(9, 9),
        9,
        9,
    );
    // Clipped on every side, odd width, odd starts and ends.
    let win = Window {
        x0: 3,
        y0: 2,
        x1: 6,
        y1: 5,
    };
    check(&[px(0, 0), px(9, 0), px(9, 9), px(0, 9)], win, 9, 9);
    // Wide frames, as far right as Q12.4 reaches, odd and even widths.
    for w in [2047u16, 2048] {
        check(
            &[px(1, 1), px(2047, 1), px(2047, 3), px(1, 3)],
            full(w, 4),
            w,
            4,
        );
        check(
            &[px(2, 0), px(2046, 0), px(2046, 4), px(2, 4)],
            full(w, 4),
            w,
            4,
        );
    }
}

/// A quad through the controller, which fills an axis-aligned rectangle
/// from its corners and a quad monotone in `y` as two chains of edges
/// with no walk, and straight through `Rasterizer::fill`, which sets up
/// every polygon's edges: the same spans in the same order and the same
/// counts, with many edge slots and with only as many as the quad's
/// vertices (the controller's own limit).
fn same_as_the_edges(poly: &[(i32, i32)], window: Window, w: u16, h: u16, slots: usize) {
    let what = (poly, window, w, h, slots);
    let draw = Draw {
        clip: Some(window),
        poly: poly.to_vec(),
    };
    let (listed, stats) = render_counting(&[draw], w, h, slots);

    let mut edges = vec![Edge::EMPTY; slots];
    let mut direct = CountingTarget::new(w, h);
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
    let counts = Rasterizer::new(&mut edges).fill(
        poly.iter().map(|&p| vertex(p)),
        &clip,
        BinaryColor::On,
        &mut direct,
    );
    match (stats, counts) {
        (Ok(stats), Ok(counts)) => {
            assert_eq!(listed.spans, direct.spans, "spans of {what:?}");
            assert_eq!(stats.spans, counts.spans, "span count of {what:?}");
            assert_eq!(stats.pixels, counts.pixels as u64, "pixels of {what:?}");
        }
        (Err(RenderError::Capacity { capacity, .. }), Err(FillError::Capacity { capacity: c })) => {
            assert_eq!(capacity, c, "{what:?}");
            assert!(listed.spans.is_empty() && direct.spans.is_empty());
        }
        (a, b) => panic!("{what:?}: controller {a:?}, fill {b:?}"),
    }
}

/// Quads of every kind: rectangles (either winding, any first corner,
/// zero width or height included), rectangles with one corner moved by a
/// unit (not axis-aligned), vertical-sided trapezoids, and random
/// convex, concave, self-intersecting and degenerate quads.
fn quad(w: u16, h: u16) -> impl Strategy<Value = Poly> {
    let nudged =
        (rectangle(w, h), 0..4usize, -1..=1i32, -1..=1i32).prop_map(|(mut p, k, dx, dy)| {
            p[k].0 += dx;
            p[k].1 += dy;
            p
        });
    let flat = (near(w), near(h), near(w))
        .prop_map(|(x0, y, x1)| vec![(x0, y), (x1, y), (x1, y), (x0, y)]);
    // Squares turned by any angle about any centre (W4's kind), either
    // winding, any first corner.
    let turned = (
        near(w),
        near(h),
        1..16 * 20i32,
        0..64i32,
        0..4usize,
        any::<bool>(),
    )
        .prop_map(|(cx, cy, r, a, start, rev)| {
            let t = a as f64 * std::f64::consts::TAU / 64.0;
            let (dx, dy) = ((r as f64 * t.cos()) as i32, (r as f64 * t.sin()) as i32);
            let mut p = vec![
                (cx + dx, cy + dy),
                (cx - dy, cy + dx),
                (cx - dx, cy - dy),
                (cx + dy, cy - dx),
            ];
            p.rotate_left(start);
            if rev {
                p.reverse();
            }
            p
        });
    prop_oneof![
        rectangle(w, h),
        nudged,
        flat,
        vertical_sided(w, h),
        turned,
        prop::collection::vec((near(w), near(h)), 4),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn quads_fill_as_their_edges_do(
        (poly, window, w, h, slots) in (prop::sample::select(vec![(32u16, 24u16), (33, 20), (1, 9)]))
            .prop_flat_map(|(w, h)| (quad(w, h), window(w, h), Just(w), Just(h), prop_oneof![Just(64usize), Just(4)]))
    ) {
        same_as_the_edges(&poly, window, w, h, slots);
        check(&poly, window, w, h);
    }
}
