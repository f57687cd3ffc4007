//! Hand-picked hard cases, each compared pixel for pixel with the exact
//! reference rasteriser (and, where small, with a picture).

use embedded_graphics_core::pixelcolor::BinaryColor;
use host_tests::harness::{
    assert_same, render_counting, render_poly, CountingEdge, CountingTarget, Draw,
};
use scanvert::controller::RenderError;
use scanvert::raster::clip::{ClipRect, ClipWindow};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::{FillError, Rasterizer};
use testkit::reference::{assert_pattern, rasterize, Window};

const W: u16 = 64;
const H: u16 = 48;
/// One pixel in units.
const PX: i32 = 16;
const MIN: i32 = i16::MIN as i32;
const MAX: i32 = i16::MAX as i32;

/// Renders `poly` under `win` on a `w × h` frame and asserts the library's
/// pixels are the reference's; returns the target for further checks.
#[track_caller]
fn check(poly: &[(i32, i32)], win: Window, w: u16, h: u16) -> CountingTarget {
    let target = render_poly(poly, win, w, h);
    let want = rasterize(poly, win, w.into(), h.into());
    assert_same(&target.coverage(), &want, &(poly, win, (w, h)));
    target
}

/// [`check`] on the whole 64 × 48 frame, in both windings.
#[track_caller]
fn check_full(poly: &[(i32, i32)]) -> CountingTarget {
    let mut rev = poly.to_vec();
    rev.reverse();
    check(&rev, Window::full(W, H), W, H);
    check(poly, Window::full(W, H), W, H)
}

fn px(x: i32, y: i32) -> (i32, i32) {
    (PX * x, PX * y)
}

#[test]
fn pixel_centres_on_left_and_top_edges_are_in_on_right_and_bottom_edges_out() {
    // x from 0.5 to 3.5, y from 0.5 to 2.5: the edges pass through centres.
    let r = [(8, 8), (56, 8), (56, 40), (8, 40)];
    let t = check(&r, Window::full(5, 4), 5, 4);
    assert_pattern(&t.coverage(), &["###..", "###..", ".....", "....."]);
}

#[test]
fn slivers_thinner_than_a_pixel() {
    // A vertical sliver 1/8 px wide around the centres of column 2.
    let s = [(39, 0), (41, 0), (41, 4 * PX), (39, 4 * PX)];
    let t = check(&s, Window::full(4, 4), 4, 4);
    assert_pattern(&t.coverage(), &["..#.", "..#.", "..#.", "..#."]);
    // The same sliver between two columns of centres covers nothing.
    let s = [(41, 0), (47, 0), (47, 4 * PX), (41, 4 * PX)];
    assert_eq!(check(&s, Window::full(4, 4), 4, 4).coverage().count(), 0);
    // Long thin triangles at many slopes, 1/16 to 15/16 px thick at the
    // wide end, slid by sixteenths across the frame.
    for thick in 1..16 {
        for shift in 0..16 {
            let y = 20 * PX + shift;
            check_full(&[
                (-4 * PX, y),
                (70 * PX, y + 9 * PX),
                (70 * PX, y + 9 * PX + thick),
            ]);
            check_full(&[
                (3 * PX + shift, -PX),
                (3 * PX + shift + thick, -PX),
                (40 * PX, 50 * PX),
            ]);
            check_full(&[
                (shift, shift),
                (64 * PX, 48 * PX + shift),
                (64 * PX - thick, 48 * PX + shift),
            ]);
        }
    }
}

#[test]
fn the_benchmarks_slivers_match_the_reference() {
    // W6: triangles 40 to 120 px long and 1 to 2 px wide at any angle, in
    // every order of their edges' first rows (the three rotations of each
    // triangle, in both windings).
    let wl = testkit::workloads::w6();
    for p in wl.polys.iter().step_by(40) {
        let p = testkit::reference::units(p);
        for k in 0..3 {
            let mut q = p.clone();
            q.rotate_left(k);
            check(&q, Window::full(wl.width, wl.height), wl.width, wl.height);
            q.reverse();
            check(&q, Window::full(wl.width, wl.height), wl.width, wl.height);
        }
    }
}

#[test]
fn edges_one_sixteenth_from_horizontal() {
    // Rectangles whose top and bottom edges rise or fall by 1/16 over the
    // frame (or over 4000 px), at every sub-pixel height: a row centre is
    // exactly on the edge at one end and not at the other.
    for base in 0..32 {
        let (top, bot) = (10 * PX + base, 30 * PX + base);
        for (dl, dr) in [(0, 1), (1, 0), (0, -1), (-1, 0)] {
            check_full(&[
                (0, top + dl),
                (64 * PX, top + dr),
                (64 * PX, bot + dr),
                (0, bot + dl),
            ]);
            check_full(&[
                (MIN, top + dl),
                (MAX, top + dr),
                (MAX, bot + dr),
                (MIN, bot + dl),
            ]);
            check_full(&[(2 * PX, top + dl), (2 * PX + 1, top + dr), (60 * PX, bot)]);
        }
    }
}

#[test]
fn edges_4000_px_long_match_the_reference() {
    // Triangles with two vertices 4000 px apart, sweeping their slope so
    // that the long edges cross the frame at every angle.
    let far = 2000 * PX;
    for k in 0..=40 {
        let d = k * 100 * PX;
        check_full(&[(-far, -far + d), (far, far - d), (far, far)]);
        check_full(&[(-far + d, -far), (far - d, far), (-far, far)]);
        check_full(&[(-far, 24 * PX + k), (far, 24 * PX - k), (32 * PX, far)]);
        check_full(&[(-far, 24 * PX - k), (far, 24 * PX + k), (32 * PX, -far)]);
    }
}

#[test]
fn vertices_exactly_on_pixel_centres() {
    let c = |i: i32, j: i32| (PX * i + 8, PX * j + 8);
    // A diamond through the centres of (3,0), (6,3), (3,6), (0,3): the
    // left and top vertices are in, the right and bottom ones out.
    let d = [c(3, 0), c(6, 3), c(3, 6), c(0, 3)];
    let t = check(&d, Window::full(7, 7), 7, 7);
    assert_pattern(
        &t.coverage(),
        &[
            ".......", // the top vertex's two crossings cancel
            "..##...", ".####..", "######.", ".####..", "..##...", ".......",
        ],
    );
    for i in 0..8 {
        for j in 0..8 {
            check_full(&[c(i, j), c(40 - i, 3 + j), c(20 + i, 40 - j)]);
            check_full(&[c(i, j), c(i + 30, j), c(i + 30, j + 20), c(i, j + 20)]);
        }
    }
}

#[test]
fn repeated_and_collinear_vertices_change_nothing() {
    let plain = vec![px(5, 5), px(40, 8), px(30, 40), px(8, 30)];
    let want = check_full(&plain).coverage();
    // Every vertex doubled.
    let doubled: Vec<_> = plain.iter().flat_map(|&v| [v, v]).collect();
    assert_eq!(check_full(&doubled).coverage(), want);
    // Midpoints inserted on every edge (exact: even coordinates).
    let mut mids = Vec::new();
    for k in 0..plain.len() {
        let (a, b) = (plain[k], plain[(k + 1) % plain.len()]);
        mids.push(a);
        mids.push(((a.0 + b.0) / 2, (a.1 + b.1) / 2));
    }
    assert_eq!(check_full(&mids).coverage(), want);
    // A collinear vertex that overshoots and comes back along the same
    // line: the doubled-back part cancels.
    let spike = vec![
        px(5, 5),
        px(40, 8),
        px(52, 9),
        px(40, 8),
        px(30, 40),
        px(8, 30),
    ];
    assert_eq!(check_full(&spike).coverage(), want);
}

#[test]
fn zero_area_polygons_draw_nothing() {
    let cases: Vec<Vec<(i32, i32)>> = vec![
        vec![px(10, 10); 3],
        vec![px(10, 10), px(10, 10), px(10, 10), px(10, 10), px(10, 10)],
        vec![px(1, 1), px(30, 20), px(59, 39)],
        vec![px(1, 1), px(59, 39), px(30, 20), px(1, 1)],
        vec![px(10, 3), px(10, 40), px(10, 20)],
        vec![(8, 8), (8, 40 * PX + 8), (8, 8)],
        vec![px(3, 10), px(60, 10), px(30, 10)],
        vec![(MIN, MIN), (MAX, MAX), (0, 0)],
        vec![px(2, 2), px(50, 2), px(50, 40), px(50, 2)],
    ];
    for p in &cases {
        let t = check_full(p);
        assert!(t.spans.is_empty(), "{p:?} wrote {:?}", t.spans);
    }
}

#[test]
fn polygons_outside_the_frame_or_the_window_draw_nothing() {
    let tri = |dx: i32, dy: i32| vec![px(dx, dy), px(dx + 30, dy + 5), px(dx + 10, dy + 30)];
    for (dx, dy) in [
        (-2000, 10),
        (2000, 10),
        (10, -2000),
        (10, 2000),
        (-40, 10),
        (64, 0),
        (0, 48),
        (-31, -31),
    ] {
        let t = check_full(&tri(dx, dy));
        assert!(t.spans.is_empty(), "{dx},{dy}");
    }
    // In the frame, but beside, above or below the window.
    let p = tri(2, 2);
    for win in [
        Window {
            x0: 40,
            y0: 0,
            x1: 63,
            y1: 47,
        },
        Window {
            x0: 0,
            y0: 40,
            x1: 63,
            y1: 47,
        },
        Window {
            x0: 0,
            y0: 0,
            x1: 1,
            y1: 1,
        },
        Window {
            x0: 20,
            y0: 20,
            x1: 10,
            y1: 30,
        },
        Window {
            x0: -100,
            y0: -100,
            x1: -1,
            y1: 47,
        },
        Window {
            x0: 64,
            y0: 0,
            x1: 2000,
            y1: 47,
        },
    ] {
        let t = check(&p, win, W, H);
        assert!(t.spans.is_empty(), "{win:?}");
    }
}

#[test]
fn corners_of_the_coordinate_range() {
    // The whole range as a square covers every pixel whose centre is at
    // most 2047.5: columns and rows 0..2048 of any frame.
    let all = [(MIN, MIN), (MAX, MIN), (MAX, MAX), (MIN, MAX)];
    assert_eq!(check_full(&all).coverage().count(), W as usize * H as usize);
    for (w, h) in [(4096, 2), (2, 4096), (1, 1), (2049, 1)] {
        let t = check(&all, Window::full(w, h), w, h);
        let side = |s: u16| s.min(2048) as usize;
        assert_eq!(t.coverage().count(), side(w) * side(h));
    }
    // Every triangle on 16 extreme and central points, both windings.
    let vals = [MIN, MIN + 1, 8, MAX];
    let pts: Vec<(i32, i32)> = vals
        .iter()
        .flat_map(|&x| vals.iter().map(move |&y| (x, y)))
        .collect();
    for a in 0..pts.len() {
        for b in a + 1..pts.len() {
            for c in b + 1..pts.len() {
                check_full(&[pts[a], pts[b], pts[c]]);
            }
        }
    }
    // Long edges from the corners into the far corner of a 4096-wide frame.
    for &(x, y) in &[(MAX, MAX), (MAX, MIN), (MIN, MAX)] {
        check(
            &[(MIN, MIN), (x, y), (0, MAX)],
            Window::full(4096, 3),
            4096,
            3,
        );
        check(
            &[(MIN, MIN), (x, y), (MAX, 0)],
            Window::full(3, 4096),
            3,
            4096,
        );
    }
}

#[test]
fn a_4000_px_tall_polygon_clipped_to_3_rows_costs_3_rows() {
    // A quad 4000 px tall with sloped sides; the window keeps rows 10..=12.
    let quad = [
        px(-1000, -2000),
        px(1000, -2000),
        px(1500, 2000),
        px(-1500, 2000),
    ];
    let win = Window {
        x0: 0,
        y0: 10,
        x1: 63,
        y1: 12,
    };
    let t = check(&quad, win, W, H);
    assert_eq!(t.spans.len(), 3, "one span per row in the window");
    assert_eq!(t.rows_touched(), 3);

    // The edge stepper's own work: two edges set up (the horizontal ones
    // take no slot) and stepped once per row between the window's rows.
    let steps = |win: ClipWindow| {
        let clip = ClipRect::from_window(win, W, H);
        let mut slots = [CountingEdge::EMPTY; 8];
        let mut target = CountingTarget::new(W, H);
        CountingEdge::reset();
        Rasterizer::new(&mut slots)
            .fill(
                quad.iter().copied().map(host_tests::harness::vertex),
                &clip,
                BinaryColor::On,
                &mut target,
            )
            .unwrap();
        (CountingEdge::counts(), target.spans.len())
    };
    let three = ClipWindow {
        x0: 0,
        y0: 10,
        x1: 63,
        y1: 12,
    };
    let ((setups, row_steps), spans) = steps(three);
    assert_eq!((setups, spans), (2, 3));
    assert!(row_steps <= 2 * 3, "{row_steps} edge steps for 3 rows");
    // Forty rows cost about forty rows: the work follows the window.
    let forty = ClipWindow {
        x0: 0,
        y0: 4,
        x1: 63,
        y1: 43,
    };
    let ((setups, row_steps), spans) = steps(forty);
    assert_eq!((setups, spans), (2, 40));
    assert!(
        (2 * 39..=2 * 40).contains(&row_steps),
        "{row_steps} edge steps for 40 rows"
    );
}

#[test]
fn more_vertices_than_edge_slots_is_a_capacity_error_and_draws_nothing() {
    // A clear, a small polygon, then one of 9 vertices, with 8 slots: the
    // list is refused before the clear, so nothing at all is written.
    let nine: Vec<(i32, i32)> = (0..9)
        .map(|k| px(10 + 3 * k, if k % 2 == 0 { 5 } else { 30 }))
        .collect();
    let small = Draw {
        clip: None,
        poly: vec![px(1, 1), px(20, 1), px(1, 20)],
    };
    let big = Draw {
        clip: None,
        poly: nine.clone(),
    };
    let (t, result) = render_counting(&[small.clone(), big.clone()], W, H, 8);
    match result {
        Err(RenderError::Capacity {
            vertices,
            capacity,
            offset,
        }) => {
            assert_eq!((vertices, capacity), (9, 8));
            assert_eq!(offset, 16 + 3 + 4 * 3, "offset of the second poly");
        }
        other => panic!("expected a capacity error, got {other:?}"),
    }
    assert!(t.spans.is_empty(), "wrote {:?}", t.spans);
    // With 9 slots the same list renders, matching the reference.
    let (t, result) = render_counting(&[big], W, H, 9);
    result.expect("fits in 9 slots");
    assert_same(
        &t.coverage(),
        &rasterize(&nine, Window::full(W, H), W.into(), H.into()),
        &nine,
    );

    // The rasteriser on its own refuses when more edges cross the clip
    // rows than it has slots, and writes nothing.
    let clip = ClipRect::full(W, H);
    let mut slots = [Edge::EMPTY; 5];
    let mut target = CountingTarget::new(W, H);
    let r = Rasterizer::new(&mut slots).fill(
        nine.iter().copied().map(host_tests::harness::vertex),
        &clip,
        BinaryColor::On,
        &mut target,
    );
    assert_eq!(r, Err(FillError::Capacity { capacity: 5 }));
    assert!(target.spans.is_empty());
}

#[test]
fn a_target_smaller_than_the_lists_frame_gets_only_its_own_pixels() {
    use scanvert::controller::Controller;
    use scanvert::display_list::DisplayList;
    // A list for 64 × 48 into a 20 × 10 target: the frame is cut to the
    // target, every span stays inside it (the counting target checks), and
    // the pixels are the reference's on a 20 × 10 frame.
    let poly = vec![px(-5, -5), px(60, 3), px(30, 45), px(2, 30)];
    let win = Window {
        x0: 3,
        y0: 2,
        x1: 40,
        y1: 40,
    };
    let bytes = host_tests::harness::build_list(
        &[Draw {
            clip: Some(win),
            poly: poly.clone(),
        }],
        W,
        H,
    );
    let list = DisplayList::new_checked(&bytes).unwrap();
    let mut edges = [Edge::EMPTY; 8];
    let mut target = CountingTarget::new(20, 10);
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut target)
        .unwrap();
    assert_same(&target.coverage(), &rasterize(&poly, win, 20, 10), &poly);
}
