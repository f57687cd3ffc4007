//! Property tests: the library's pixels against the exact reference
//! rasteriser, pixel for pixel, through the whole path (`Writer` →
//! `DisplayList::new_checked` → `Controller::render` → port).
//!
//! Polygons are convex (hulls of random points), star-shaped (concave,
//! simple) and raw vertex soups (self-intersecting), 3 to 12 vertices, with
//! coordinates near a 64 × 48 frame or anywhere in Q12.4, under random clip
//! registers (full, inside, partly outside, inverted, empty, extreme).

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use host_tests::harness::{
    assert_same, build_list, render_counting, render_framebuffer, render_poly, Draw,
    DEFAULT_CAPACITY,
};
use proptest::prelude::*;
use scanvert::controller::Controller;
use scanvert::display_list::DisplayList;
use scanvert::port::PackedFrameBuffer;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use testkit::reference::{rasterize, Coverage, Window};

const W: u16 = 64;
const H: u16 = 48;

type Poly = Vec<(i32, i32)>;

/// A coordinate near a frame side of `side` pixels: a pixel margin of 16
/// around it, any sixteenth.
fn near(side: u16) -> impl Strategy<Value = i32> {
    -16 * 16..(side as i32 + 16) * 16
}

/// Any Q12.4 coordinate, with the extremes and zero made likely.
fn anywhere() -> impl Strategy<Value = i32> {
    prop_oneof![
        4 => i16::MIN as i32..=i16::MAX as i32,
        1 => prop::sample::select(vec![i16::MIN as i32, i16::MIN as i32 + 1, -8, 0, 8, i16::MAX as i32 - 1, i16::MAX as i32]),
    ]
}

fn point(
    x: impl Strategy<Value = i32> + 'static,
    y: impl Strategy<Value = i32> + 'static,
) -> BoxedStrategy<(i32, i32)> {
    (x, y).boxed()
}

/// Vertex soups: any order, so usually self-intersecting.
fn soup(p: impl Strategy<Value = (i32, i32)>) -> impl Strategy<Value = Poly> {
    prop::collection::vec(p, 3..=12)
}

fn cross(o: (i32, i32), a: (i32, i32), b: (i32, i32)) -> i64 {
    (a.0 as i64 - o.0 as i64) * (b.1 as i64 - o.1 as i64)
        - (a.1 as i64 - o.1 as i64) * (b.0 as i64 - o.0 as i64)
}

/// The convex hull (Andrew's monotone chain), counter-clockwise in a
/// y-up sense; the points themselves when fewer than 3 remain.
fn hull(mut pts: Poly) -> Poly {
    pts.sort_unstable();
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut h: Poly = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let it: Box<dyn Iterator<Item = &(i32, i32)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in it {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Convex polygons, either winding.
fn convex(p: impl Strategy<Value = (i32, i32)>) -> impl Strategy<Value = Poly> {
    (prop::collection::vec(p, 3..=12), any::<bool>()).prop_filter_map(
        "hull of fewer than 3 points",
        |(pts, rev)| {
            let mut h = hull(pts);
            if rev {
                h.reverse();
            }
            (h.len() >= 3).then_some(h)
        },
    )
}

/// Star-shaped (generally concave, simple) polygons around `centre`:
/// vertices at increasing angles and random radii up to `r`.
fn star(centre: impl Strategy<Value = (i32, i32)>, r: i32) -> impl Strategy<Value = Poly> {
    (
        centre,
        prop::collection::vec((0u32..3600, 1..=r), 3..=12),
        any::<bool>(),
    )
        .prop_map(|(c, mut spokes, rev)| {
            spokes.sort_unstable_by_key(|s| s.0);
            let mut p: Poly = spokes
                .into_iter()
                .map(|(a, rad)| {
                    let t = a as f64 * std::f64::consts::PI / 1800.0;
                    let x = c.0 as f64 + rad as f64 * t.cos();
                    let y = c.1 as f64 + rad as f64 * t.sin();
                    let clamp = |v: f64| (v.round() as i32).clamp(i16::MIN as i32, i16::MAX as i32);
                    (clamp(x), clamp(y))
                })
                .collect();
            if rev {
                p.reverse();
            }
            p
        })
}

/// Any polygon kind with coordinates from `p`.
fn polygon(
    p: BoxedStrategy<(i32, i32)>,
    centre: BoxedStrategy<(i32, i32)>,
    r: i32,
) -> BoxedStrategy<Poly> {
    prop_oneof![convex(p.clone()), star(centre, r), soup(p)].boxed()
}

/// Clip registers: the whole frame, random windows around the frame (in
/// either order, so some inverted), degenerate and extreme ones.
fn window(w: u16, h: u16) -> impl Strategy<Value = Window> {
    let (w, h) = (w as i16, h as i16);
    let around = (-8..w + 8, -8..h + 8, -8..w + 8, -8..h + 8).prop_map(|(x0, y0, x1, y1)| Window {
        x0,
        y0,
        x1,
        y1,
    });
    let inside = (0..w, 0..h, 0..w, 0..h).prop_map(|(a, b, c, d)| Window {
        x0: a.min(c),
        y0: b.min(d),
        x1: a.max(c),
        y1: b.max(d),
    });
    let extreme = prop::sample::select(vec![
        Window {
            x0: i16::MIN,
            y0: i16::MIN,
            x1: i16::MAX,
            y1: i16::MAX,
        },
        Window {
            x0: i16::MAX,
            y0: i16::MAX,
            x1: i16::MIN,
            y1: i16::MIN,
        },
        Window {
            x0: w,
            y0: 0,
            x1: i16::MAX,
            y1: h,
        },
        Window {
            x0: i16::MIN,
            y0: -1,
            x1: -1,
            y1: h,
        },
        Window {
            x0: 0,
            y0: 0,
            x1: 0,
            y1: 0,
        },
        Window {
            x0: w - 1,
            y0: h - 1,
            x1: w - 1,
            y1: h - 1,
        },
    ]);
    prop_oneof![2 => Just(Window::full(w as u16, h as u16)), 3 => inside, 3 => around, 1 => extreme]
}

fn check(poly: &[(i32, i32)], win: Window, w: u16, h: u16) -> Result<(), TestCaseError> {
    let got = render_poly(poly, win, w, h).coverage();
    let want = rasterize(poly, win, w.into(), h.into());
    if got != want {
        assert_same(&got, &want, &(poly, win, (w, h)));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Small coordinates: polygons around and across a 64 × 48 frame.
    #[test]
    fn small_polygons_match_the_reference(
        poly in polygon(point(near(W), near(H)), point(near(W), near(H)), 48 * 16),
        win in window(W, H),
    ) {
        check(&poly, win, W, H)?;
    }

    /// Coordinates anywhere in Q12.4: long edges crossing the frame at
    /// steep and shallow slopes, and the corners of the range.
    #[test]
    fn polygons_spanning_the_whole_range_match_the_reference(
        poly in polygon(point(anywhere(), anywhere()), point(near(W), near(H)), i16::MAX as i32),
        win in window(W, H),
    ) {
        check(&poly, win, W, H)?;
    }

    /// Some vertices in the frame, some far away: every edge that reaches
    /// the frame is long and nearly anywhere in slope.
    #[test]
    fn mixed_near_and_far_vertices_match_the_reference(
        poly in polygon(
            prop_oneof![point(near(W), near(H)), point(anywhere(), anywhere())].boxed(),
            point(near(W), near(H)),
            4000 * 16,
        ),
        win in window(W, H),
    ) {
        check(&poly, win, W, H)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Other frame shapes, up to a side of 4096: one row, one column,
    /// long thin frames.
    #[test]
    fn other_frame_sizes_match_the_reference(
        (w, h, poly) in prop_oneof![
            (1u16..=100, 1u16..=100),
            Just((1u16, 1u16)),
            (1u16..=4096, 1u16..=3),
            (1u16..=3, 1u16..=4096),
        ].prop_flat_map(|(w, h)| {
            let near_frame = |side: u16| -64..=((side as i32 + 4) * 16).min(i16::MAX as i32);
            let poly = prop_oneof![
                1 => soup(point(anywhere(), anywhere())),
                3 => soup(point(near_frame(w), near_frame(h))),
            ];
            (Just(w), Just(h), poly)
        }),
        full in any::<bool>(),
        (x0, y0, x1, y1) in (-8i16..2100, -8i16..2100, -8i16..2100, -8i16..2100),
    ) {
        let win = if full { Window::full(w, h) } else { Window { x0, y0, x1, y1 } };
        check(&poly, win, w, h)?;
    }

    /// The same, through the in-memory `FrameBuffer<BinaryColor>` port.
    #[test]
    fn frame_buffer_port_matches_the_reference(
        poly in polygon(point(near(W), near(H)), point(near(W), near(H)), 48 * 16),
        win in window(W, H),
    ) {
        let got = render_framebuffer(&poly, win, W, H);
        let want = rasterize(&poly, win, W.into(), H.into());
        assert_same(&got, &want, &(&poly, win));
    }

    /// The same, through the two-pixels-a-word `PackedFrameBuffer` (the
    /// Cortex-M4 image's target), whose rows the scan converter walks by
    /// their start (`SpanTarget::row_start`): an even width (every row
    /// starts on a word) and an odd one. The words past the frame, and the
    /// padding half of an odd frame, are never written.
    #[test]
    fn packed_frame_buffer_port_matches_the_reference(
        poly in polygon(point(near(W), near(H)), point(near(W), near(H)), 48 * 16),
        win in window(W, H),
        odd in any::<bool>(),
    ) {
        let (w, h) = if odd { (W - 1, H - 1) } else { (W, H) };
        let draw = Draw { clip: Some(win), poly: poly.clone() };
        let bytes = build_list(&[draw], w, h);
        let list = DisplayList::new_checked(&bytes).expect("valid list");
        let mut edges = [Edge::EMPTY; DEFAULT_CAPACITY];
        let n = PackedFrameBuffer::<Rgb565>::words_len(w, h);
        let mut words = vec![0u32; n + 1];
        words[n] = 0xdead_beef;
        let mut pk = PackedFrameBuffer::<Rgb565>::new(&mut words, w, h).expect("frame");
        Controller::new(Rasterizer::new(&mut edges)).render(&list, &mut pk).expect("render");
        let got = Coverage::from_fn(w.into(), h.into(), |i, j| {
            pk.pixel(i as u16, j as u16) == Some(Rgb565::WHITE)
        });
        let want = rasterize(&poly, win, w.into(), h.into());
        assert_same(&got, &want, &(&poly, win, (w, h)));
        if (w as usize * h as usize) % 2 == 1 {
            prop_assert_eq!(words[n - 1] >> 16, 0);
        }
        prop_assert_eq!(words[n], 0xdead_beef);
    }

    /// Several polygons in one list, each under its own clip registers (or
    /// the previous ones): every pixel is written once per polygon that
    /// covers it, so the registers carry from command to command.
    #[test]
    fn scenes_of_several_polygons_write_each_pixel_once_per_cover(
        draws in prop::collection::vec(
            (prop::option::of(window(W, H)), polygon(point(near(W), near(H)), point(near(W), near(H)), 40 * 16)),
            1..6,
        ),
    ) {
        let draws: Vec<Draw> = draws.into_iter().map(|(clip, poly)| Draw { clip, poly }).collect();
        let (target, result) = render_counting(&draws, W, H, DEFAULT_CAPACITY);
        result.expect("render");
        let mut clip = Window::full(W, H);
        let mut expect = vec![0u32; W as usize * H as usize];
        for d in &draws {
            clip = d.clip.unwrap_or(clip);
            let c = rasterize(&d.poly, clip, W.into(), H.into());
            for j in 0..H as u32 {
                for i in 0..W as u32 {
                    expect[(j * W as u32 + i) as usize] += c.get(i, j) as u32;
                }
            }
        }
        for j in 0..H as u32 {
            for i in 0..W as u32 {
                prop_assert_eq!(target.writes(i, j), expect[(j * W as u32 + i) as usize], "pixel ({}, {})", i, j);
            }
        }
    }
}
