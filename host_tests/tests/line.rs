//! `line`: the library's pixels against the exact reference of the line
//! rule (`testkit::line_reference`), pixel for pixel, through the
//! whole path (`Writer` → `DisplayList::new_checked` → `Controller::render`
//! → port), and the per-row generator `raster::line::Line` on its own.
//!
//! Hard cases: horizontal, vertical and 45° lines, end points on pixel
//! centres and on pixel edges, 1/16 px long, 4000 px long, far outside the
//! frame, both directions, under random clip registers; lines joined end
//! to end; a line scene through `scanvert render`.

use host_tests::harness::{vertex, CountingTarget};
use proptest::prelude::*;
use scanvert::controller::Controller;
use scanvert::display_list::{Command, DisplayList, Writer};
use scanvert::raster::clip::ClipRect;
use scanvert::raster::edge::Edge;
use scanvert::raster::line::Line;
use scanvert::raster::scan::Rasterizer;
use testkit::line_reference::{line_clipped, line_pixels};
use testkit::reference::Window;

type P = (i32, i32);

/// Renders the lines, each under its clip registers, through the
/// controller; returns the target.
fn render(lines: &[(P, P, Window)], width: u16, height: u16) -> CountingTarget {
    let mut buf = vec![0u8; 16 + 18 * lines.len()];
    let mut w = Writer::new(&mut buf, width, height).expect("frame");
    for &(a, b, win) in lines {
        w.clip(win.to_clip_window()).expect("room");
        w.line(vertex(a), vertex(b)).expect("room");
    }
    let bytes = w.finish().to_vec();
    let list = DisplayList::new_checked(&bytes).expect("valid");
    assert_eq!(list.version(), 2, "a list with a line is version 2");
    let mut edges = [Edge::EMPTY; 4];
    let mut target = CountingTarget::new(width, height);
    let stats = Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut target)
        .expect("render");
    let written: u64 = target.spans.iter().map(|s| s.len() as u64).sum();
    assert_eq!(stats.pixels, written, "Stats::pixels");
    assert_eq!(stats.spans as usize, target.spans.len(), "Stats::spans");
    target
}

/// The pixels the library writes for one line, sorted by row then
/// column, checking that none is written twice and that each row gets
/// one span.
fn library(a: P, b: P, win: Window, width: u16, height: u16) -> Vec<(i32, i32)> {
    let t = render(&[(a, b, win)], width, height);
    assert!(t.overdrawn().is_empty(), "overdraw {:?}", t.overdrawn());
    let mut rows: Vec<u16> = t.spans.iter().map(|s| s.y).collect();
    assert!(
        rows.windows(2).all(|w| w[0] < w[1]),
        "rows top to bottom, once: {rows:?}"
    );
    rows.dedup();
    let mut v: Vec<(i32, i32)> = t
        .spans
        .iter()
        .flat_map(|s| (s.x0..s.x1).map(move |x| (x as i32, s.y as i32)))
        .collect();
    v.sort_unstable_by_key(|&(i, j)| (j, i));
    v
}

fn check(a: P, b: P, win: Window, width: u16, height: u16) -> Result<(), TestCaseError> {
    let want = line_clipped(a, b, win, width, height);
    let got = library(a, b, win, width, height);
    prop_assert_eq!(&got, &want, "line {:?}–{:?} under {:?}", a, b, win);
    // The generator alone, through its per-row interface, agrees.
    let clip = ClipRect::from_window(win.to_clip_window(), width, height);
    match Line::new(vertex(a), vertex(b), &clip) {
        None => prop_assert!(want.is_empty()),
        Some(mut l) => {
            prop_assert_eq!(l.row(), l.top());
            prop_assert!(l.top() < l.end());
            let mut rows = 0;
            while let Some((x0, x1)) = l.span() {
                prop_assert!(x0 < x1);
                rows += 1;
                l.step();
            }
            prop_assert_eq!(l.row(), l.end());
            prop_assert_eq!(rows, l.end() - l.top());
            prop_assert_eq!(want.first().map(|p| p.1), Some(l.top()));
        }
    }
    Ok(())
}

const W: u16 = 64;
const H: u16 = 48;

fn near(side: u16) -> impl Strategy<Value = i32> {
    -16 * 16..(side as i32 + 16) * 16
}

/// Any Q12.4 coordinate, extremes likely.
fn anywhere() -> impl Strategy<Value = i32> {
    prop_oneof![
        4 => i16::MIN as i32..=i16::MAX as i32,
        1 => prop::sample::select(vec![i16::MIN as i32, i16::MIN as i32 + 1, -8, 0, 8, i16::MAX as i32 - 1, i16::MAX as i32]),
    ]
}

/// A coordinate on a pixel centre or a pixel edge near a side.
fn on_grid(side: u16) -> impl Strategy<Value = i32> {
    (-4..side as i32 + 4, prop::bool::ANY)
        .prop_map(|(k, centre)| 16 * k + if centre { 8 } else { 0 })
}

fn window() -> impl Strategy<Value = Window> {
    let b = -8i16..72;
    prop_oneof![
        3 => Just(Window::full(W, H)),
        3 => (b.clone(), b.clone(), b.clone(), b).prop_map(|(x0, y0, x1, y1)| Window { x0, y0, x1, y1 }),
        1 => Just(Window { x0: i16::MIN, y0: i16::MIN, x1: i16::MAX, y1: i16::MAX }),
    ]
}

/// A second end point related to the first: the same row or column,
/// 45°, 1/16 px away, or anywhere near.
fn related(a: P) -> impl Strategy<Value = P> {
    let fit = |v: i32| v.clamp(i16::MIN as i32, i16::MAX as i32);
    prop_oneof![
        near(W).prop_map(move |x| (x, a.1)),
        near(H).prop_map(move |y| (a.0, y)),
        (-900i32..900).prop_map(move |d| (fit(a.0 + d), fit(a.1 + d))),
        (-900i32..900).prop_map(move |d| (fit(a.0 + d), fit(a.1 - d))),
        (-1i32..=1, -1i32..=1).prop_map(move |(dx, dy)| (fit(a.0 + dx), fit(a.1 + dy))),
        (near(W), near(H)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn near_the_frame(a in (near(W), near(H)), b in (near(W), near(H)), win in window()) {
        check(a, b, win, W, H)?;
        check(b, a, win, W, H)?;
    }

    #[test]
    fn on_centres_and_edges(a in (on_grid(W), on_grid(H)), b in (on_grid(W), on_grid(H)), win in window()) {
        check(a, b, win, W, H)?;
        check(b, a, win, W, H)?;
    }

    #[test]
    fn special_directions((a, b) in (near(W), near(H)).prop_flat_map(|a| (Just(a), related(a))), win in window()) {
        check(a, b, win, W, H)?;
        check(b, a, win, W, H)?;
    }

    #[test]
    fn anywhere_in_range(a in (anywhere(), anywhere()), b in (anywhere(), anywhere()), win in window()) {
        check(a, b, win, W, H)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// 4000 px long (from x ≈ −2048 to x ≈ +2000, the Q12.4 range),
    /// nearly horizontal or nearly vertical, crossing a frame 2048 long.
    #[test]
    fn four_thousand_pixels_long(
        x in -32768i32..=-31233, y in 0i32..64 * 16, slope in -64i32 * 16..=64 * 16,
        vertical in prop::bool::ANY, win in prop_oneof![Just(None), (0i16..2048, 0i16..2048).prop_map(Some)],
    ) {
        let (a, b) = ((x, y), (x + 4000 * 16, y + slope));
        let (a, b, w, h) = if vertical {
            ((a.1, a.0), (b.1, b.0), 64, 2048)
        } else {
            (a, b, 2048, 64)
        };
        let win = match win {
            None => Window::full(w, h),
            Some((lo, hi)) if vertical => Window { x0: 0, y0: lo.min(hi), x1: 63, y1: lo.max(hi) },
            Some((lo, hi)) => Window { x0: lo.min(hi), y0: 0, x1: lo.max(hi), y1: 63 },
        };
        check(a, b, win, w, h)?;
        check(b, a, win, w, h)?;
    }

    /// A polyline monotone along one major axis never hits a pixel twice.
    #[test]
    fn joined_end_to_end(
        ys in prop::collection::vec(near(H), 4), steps in prop::collection::vec(16i32..400, 3), x in near(W),
    ) {
        let mut pts = vec![(x, ys[0])];
        for (k, s) in steps.iter().enumerate() {
            let prev = pts[k];
            // Keep each piece x-major: |dy| ≤ dx.
            let dy = (ys[k + 1] - prev.1).clamp(-s, *s);
            pts.push((prev.0 + s, prev.1 + dy));
        }
        let win = Window::full(W, H);
        let lines: Vec<(P, P, Window)> = pts.windows(2).map(|p| (p[0], p[1], win)).collect();
        let t = render(&lines, W, H);
        prop_assert!(t.overdrawn().is_empty(), "{:?}: {:?}", pts, t.overdrawn());
        let want: usize = lines.iter().map(|&(a, b, w)| line_clipped(a, b, w, W, H).len()).sum();
        prop_assert_eq!(t.coverage().count(), want);
    }
}

#[test]
fn hard_cases() {
    let full = Window::full(W, H);
    let cases: &[(P, P)] = &[
        // Horizontal, vertical, 45° both ways.
        ((8, 8), (1000, 8)),
        ((8, 8), (8, 700)),
        ((0, 0), (700, 700)),
        ((0, 700), (700, 0)),
        // On pixel edges, a y exactly on a boundary.
        ((0, 16), (64, 48)),
        ((16, 0), (48, 64)),
        // 1/16 px long, on and off centres, each axis.
        ((24, 24), (25, 24)),
        ((23, 24), (24, 24)),
        ((24, 24), (24, 25)),
        ((24, 23), (24, 24)),
        // Far outside, crossing the frame.
        ((-32768, -32768), (32767, 32767)),
        ((-32768, 32767), (32767, -32768)),
        ((-32768, 100), (32767, 101)),
        ((100, -32768), (101, 32767)),
        // Wholly outside.
        ((-3000, -3000), (-10, -2000)),
    ];
    for &(a, b) in cases {
        check(a, b, full, W, H).unwrap();
        check(b, a, full, W, H).unwrap();
    }
    // The example of the line rule: from centre to centre, row 2.
    assert_eq!(line_pixels((24, 40), (88, 40)).len(), 4);
}

#[test]
fn line_round_trips_and_is_2d() {
    let a = scanvert_sim::text::assemble("frame 8 8\nline 0.5 1 7.0625 -2\n").expect("assembles");
    let list = DisplayList::new_checked(&a.bytes).expect("valid");
    let cmds: Vec<_> = list.commands().map(|(_, c)| c).collect();
    assert!(
        matches!(cmds[0], Command::Line(p, q) if p == vertex((8, 16)) && q == vertex((113, -32)))
    );
    assert!(!cmds[0].is_3d());
    let text = scanvert_sim::text::disassemble(&list);
    // 7.0625 in the fewest decimals that assemble to it.
    assert_eq!(text, "frame 8 8\nline 0.5 1 7.06 -2\n");
    assert_eq!(scanvert_sim::text::assemble(&text).unwrap().bytes, a.bytes);
    // Three operands, or a coordinate out of range: an error naming the line.
    for bad in [
        "frame 8 8\n\nline 1 2 3\n",
        "frame 8 8\n\nline 1 2 3 2048\n",
    ] {
        let e = scanvert_sim::text::assemble(bad).expect_err("refused");
        assert_eq!(e.line, 3, "{bad:?}");
    }
    // A version-1 list holding the line opcode is refused at its offset.
    let mut bytes = a.bytes.clone();
    bytes[4] = 1;
    let e = DisplayList::new_checked(&bytes).expect_err("version 1 has no line");
    assert_eq!(e.offset, 16);
    assert_eq!(
        e.kind,
        scanvert::display_list::ErrorKind::UnknownOpcode(0x12)
    );
}

/// A line scene through `scanvert render`: the PNG holds exactly the
/// reference's pixels, lines over a polygon in painter's order, clipped.
#[test]
fn scanvert_render_draws_a_line_scene() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("line_cli");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (src, png) = (dir.join("lines.dl"), dir.join("lines.png"));
    let scene = "\
frame 32 24
clear #000000
color #0000ff
poly 4 4 28 4 28 20 4 20
color #ff0000
line 1.5 1.5 30.5 22.5     # x-major, down to the right
color #00ff00
line 16 0 14.25 23.9375    # y-major, nearly vertical, over the red one
clip 0 0 31 11
color #ffffff
line 30 2 2 21             # clipped to the top half
";
    std::fs::write(&src, scene).expect("write scene");
    let args: Vec<String> = [
        "render",
        src.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    scanvert_sim::cli::run(&args).expect("renders");
    let (w, h, rgb) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    assert_eq!((w, h), (32, 24));
    // The expected frame, painted from the references in list order.
    let mut want = vec![(0u8, 0u8, 0u8); 32 * 24];
    let full = Window::full(32, 24);
    let poly = [(64, 64), (448, 64), (448, 320), (64, 320)];
    let cov = testkit::reference::rasterize(&poly, full, 32, 24);
    for j in 0..24 {
        for i in 0..32 {
            if cov.get(i, j) {
                want[(j * 32 + i) as usize] = (0, 0, 255);
            }
        }
    }
    let top = Window {
        x0: 0,
        y0: 0,
        x1: 31,
        y1: 11,
    };
    for (a, b, win, c) in [
        ((24, 24), (488, 360), full, (255, 0, 0)),
        ((256, 0), (228, 383), full, (0, 255, 0)),
        ((480, 32), (32, 336), top, (255, 255, 255)),
    ] {
        for (i, j) in line_clipped(a, b, win, 32, 24) {
            want[(j * 32 + i) as usize] = c;
        }
    }
    let got: Vec<(u8, u8, u8)> = rgb.chunks_exact(3).map(|p| (p[0], p[1], p[2])).collect();
    for (k, (g, e)) in got.iter().zip(&want).enumerate() {
        assert_eq!(g, e, "pixel ({}, {})", k % 32, k / 32);
    }
}

proptest! {
    /// Any `line` goes text → binary → text → binary unchanged.
    #[test]
    fn text_form_round_trips(c in prop::array::uniform4(i16::MIN..=i16::MAX)) {
        let f = |u: i16| scanvert_sim::text::format_coord(scanvert::fixed::Coord::from_bits(u));
        let text = format!("frame 4 4\nline {} {} {} {}\n", f(c[0]), f(c[1]), f(c[2]), f(c[3]));
        let a = scanvert_sim::text::assemble(&text).expect("assembles");
        let list = DisplayList::new_checked(&a.bytes).expect("valid");
        prop_assert_eq!(scanvert_sim::text::disassemble(&list), text.clone());
        let again = scanvert_sim::text::assemble(&text).expect("assembles");
        prop_assert_eq!(again.bytes, a.bytes);
    }
}
