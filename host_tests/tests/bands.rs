//! Rendering band by band, with no frame buffer: every list and scene
//! rendered with bands of 1, 7, 16 and 64 rows and of the frame's height
//! must equal the full-frame render pixel for pixel (2D lists of polygons
//! and lines with clip windows and several `clear`s, generated 2D lists
//! with lines, 3D lists with labels,
//! the repository's scenes, and the 3D demo scene, also drawn by two
//! threads taking every other band, a part of the frame each, or bands
//! claimed from a shared counter); and the band path's typed errors.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use proptest::prelude::*;
use scanvert::controller::Controller;
use scanvert::port::band::{BandError, BandTarget, BandsError};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::scene::DEFAULT_FONT;
use scanvert::visible::rle::Run;
use scanvert::visible::sweep::{Active, Resolve, Workspace};
use scanvert_sim::cli::{render_scene, render_scene_bands_with, Scene};
use scanvert_sim::memory::ListMemory;
use std::path::Path;

fn scene(text: &str) -> Scene {
    Scene::from_bytes(Path::new("bands.dl"), text.as_bytes().to_vec()).expect("scene reads")
}

/// The first pixel where the band render with `rows`, its 3D layer
/// resolved by `mode`, differs from the full render (the default mode),
/// if any, with the number of differing pixels.
fn differs(s: &Scene, rows: u16, mode: Resolve) -> Option<(usize, usize)> {
    let full = render_scene(s).expect("full render");
    let band = render_scene_bands_with(s, rows, mode).expect("band render");
    let (a, b) = (full.ram.contents(), band.ram.contents());
    assert_eq!(a.len(), b.len());
    let first = a.iter().zip(b).position(|(p, q)| p != q)?;
    Some((first, a.iter().zip(b).filter(|(p, q)| p != q).count()))
}

/// The modes band renders are checked in: the default sweep, and
/// painting each band in turn.
const MODES: [Resolve; 3] = [Resolve::Crossing, Resolve::Paint, Resolve::Auto];

fn all_heights_match(s: &Scene) {
    let h = s.list().height();
    for mode in MODES {
        for rows in [1, 7, 16, 64, h, h + 5] {
            assert_eq!(differs(s, rows, mode), None, "band rows {rows}, {mode:?}");
        }
    }
}

const FLAT: &str = "\
frame 70 50
color #ff0000
poly 2 2 60 5 30 45
clear #203040
color #00ff00
poly 5 5 65 10 10 48.5 40 20
clip 10 8 50 30
color #0000ff
poly 0 0 70 0 70 50 0 50
poly 20 -10 80 25 -5 60 30.0625 12.5
clip 60 40 20 10
color #ffffff
poly 0 0 70 0 70 50
clip -10 -10 100 100
color #ff8000
poly 33 33 34 33 34 34
poly 12 40 68 44 12 49 68 41
clear #102030
color #808080
poly 1 1 3 1 3 3 1 3
clip 3 3 66 46
poly 35 0 69 25 35 49.9 0 25
color #00ffff
poly 0 12 70 12.4 70 12.6 0 13
";

/// Lines among polygons, in painter's order both ways, under clips that
/// cut them (partly, wholly, empty), in every direction and slope, long
/// ones far outside the frame, lines of one pixel and of none, and lines
/// before the last `clear` (covered).
const LINES: &str = "\
frame 64 48
color #ff0000
line 0 0 64 48
clear #102030
color #ffff00
line 0 0 64 48
line 64 0 0 48
color #00ff00
poly 10 10 50 12 30 40
color #ff00ff
line 5 20 60 22
line 30 -100 31.5 200
line -1000 30.5 1000 33
line 20.5 5 20.5 45
line 2 46.5 62 46.5
line 40 40 40 40
line 8.5 8.5 8.5625 8.5
color #0000ff
poly 25 15 45 15 45 35 25 35
color #ffffff
line 40 2 2 30
line 63.9 47.9 0.1 0.1
clip 15 12 50 36
color #00ffff
line 0 24 64 24.9
line 0 0 64 48
line 64 10 0 40
line 32 0 33 48
line 0 13 64 13
poly 0 30 64 30 64 34 0 34
color #808000
line 0 31 64 33
clip 70 0 80 10
line 0 0 64 48
clip 20 20 20 30
line 0 0 64 48
clip -10 -10 100 100
color #ff8000
line 63 0 63.5 47.5
line 0.25 47.75 63.75 0.25
";

const NO_CLEAR: &str = "\
frame 40 30
clip 5 5 34 24
color #c0c0c0
poly -5 -5 45 -5 45 35 -5 35
color #ff00ff
poly 10 2 30 15 10 28
";

const THREE_D: &str = "\
frame 96 64
clear #101820
color #404040
poly 0 40 96 40 96 64 0 64
clip 0 0 60 63
color #e0e000
poly3 10 10 50  10 50 50  50 30 50
clip -1 -1 200 200
perspective 60 1 100
lookat 3 2.5 5  0 0 0
light 1 2 3 70
segment 1
color #ff0000
face -1 -1 1  1 -1 1  1 1 1  -1 1 1
face 1 -1 -1  -1 -1 -1  -1 1 -1  1 1 -1
face 1 -1 1  1 -1 -1  1 1 -1  1 1 1
face -1 -1 -1  -1 -1 1  -1 1 1  -1 1 -1
face -1 1 1  1 1 1  1 1 -1  -1 1 -1
face -1 -1 -1  1 -1 -1  1 -1 1  -1 -1 1
segment 2
push
translate 0 1.6 0
color #00ff00
face 0 0 0
pop
color #ffffff
label -200 0 0 far off to the left
label 1 1 1 hi
label -1 1.2 1 a longer label across rows
clip 20 20 70 50
color #00c0ff
poly3 0 0 30  96 0 30  0 64 30
clear #000040
color #ff8080
poly 80 0 96 0 96 16
";

#[test]
fn a_2d_list_with_clips_and_clears_is_the_same_in_bands() {
    all_heights_match(&scene(FLAT));
}

#[test]
fn lines_among_polygons_with_clips_are_the_same_in_bands() {
    all_heights_match(&scene(LINES));
    // The lines are drawn in the full render and in bands alike.
    let full = render_scene(&scene(LINES)).expect("full render");
    assert!(full.stats.spans > 100, "{:?}", full.stats);
}

#[test]
fn lines_over_no_clear_and_after_a_3d_layer_are_the_same_in_bands() {
    let text = format!(
        "{}color #ffffff\nline 0 0 40 30\nline 40 0 0 30\nline 3 28 37 2.5\n",
        NO_CLEAR
    );
    all_heights_match(&scene(&text));
    let text = format!(
        "{}color #00ff00\nline 0 0 96 64\nclip 10 10 50 40\nline 96 0 0 64\nline 48 0 48 64\n",
        THREE_D
    );
    all_heights_match(&scene(&text));
}

#[test]
fn rows_no_command_writes_are_black_as_in_a_fresh_frame() {
    all_heights_match(&scene(NO_CLEAR));
}

#[test]
fn a_3d_list_with_labels_clips_and_clears_is_the_same_in_bands() {
    all_heights_match(&scene(THREE_D));
}

#[test]
fn the_repository_scenes_are_the_same_in_bands() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = vec![
        root.join("scenes/demo.dl"),
        root.join("scenes/fill-rules.dl"),
    ];
    for e in std::fs::read_dir(root.join("firmware/image/scenes")).expect("scenes") {
        let p = e.expect("entry").path();
        if p.extension().is_some_and(|x| x == "scvl") {
            files.push(p);
        }
    }
    assert!(files.len() >= 5, "{files:?}");
    for f in files {
        let s = Scene::load(&f).expect("loads");
        let h = s.list().height();
        for mode in MODES {
            for rows in [1, 16, h] {
                let d = differs(&s, rows, mode);
                assert_eq!(d, None, "{} band rows {rows}, {mode:?}", f.display());
            }
        }
    }
}

/// Bands shipped into a whole image, checking they come top to bottom,
/// one after the other.
struct Collect {
    width: usize,
    pixels: Vec<Rgb565>,
    next: u16,
    bands: usize,
}

impl BandTarget for Collect {
    type Color = Rgb565;
    type Error = ();
    fn ship(&mut self, y: u16, rows: u16, px: &[Rgb565]) -> Result<(), ()> {
        assert_eq!(y, self.next, "bands in order, none missing");
        assert_eq!(px.len(), rows as usize * self.width);
        self.pixels.extend_from_slice(px);
        self.next = y + rows;
        self.bands += 1;
        Ok(())
    }
}

/// A provider that fails at its second band.
struct Fails(u32);

impl BandTarget for Fails {
    type Color = Rgb565;
    type Error = &'static str;
    fn ship(&mut self, _: u16, _: u16, _: &[Rgb565]) -> Result<(), &'static str> {
        self.0 += 1;
        if self.0 == 2 {
            Err("link down")
        } else {
            Ok(())
        }
    }
}

/// Points of a 3D scene at one place, and faces staggered each a little
/// right of and nearer than the last, ending on one column (or nearly): hundreds on a
/// row, in every resolve and in bands, the earliest in front where they
/// are at one depth.
#[test]
fn faces_at_one_place_and_ending_on_one_column_are_the_same_in_bands() {
    use scanvert_sim::cli::render_scene_with;
    use std::fmt::Write as _;
    let mut points = String::from("frame 40 30\nperspective 50 1 100\nlookat 0 0 10  0 0 0\n");
    points.push_str("thickness 6\ncolor #ff0000\nface 0 0 -5\ncolor #00ff00\n");
    let mut faces = String::from("frame 60 30\nperspective 50 1 100\nlookat 0 0 10  0 0 0\n");
    for k in 0..300 {
        points.push_str("face 0 0 -5\n");
        // Each 1/64 unit right of the last and 1/4096 nearer.
        let (x, z) = (-4.0 + k as f64 / 64.0, k as f64 / 4096.0);
        let _ = writeln!(faces, "color #{:06x}", 0x100 * k + 0x40);
        let _ = writeln!(faces, "face {x} -3 {z}  4 -3 {z}  4 3 {z}  {x} 3 {z}");
    }
    for text in [&points, &faces] {
        let s = scene(text);
        all_heights_match(&s);
        let full = render_scene(&s).expect("full render");
        for mode in [Resolve::Bisect, Resolve::Paint] {
            let other = render_scene_with(&s, mode).expect("render");
            assert!(other.ram.contents() == full.ram.contents(), "{mode:?}");
        }
    }
    // The first point shows, not the 300 after it.
    let full = render_scene(&scene(&points)).expect("full render");
    let px = full.ram.contents();
    assert!(px.contains(&Rgb565::RED));
    assert!(!px.contains(&Rgb565::GREEN));
}

#[test]
fn bad_bands_are_typed_errors() {
    let s = scene(FLAT);
    let list = s.list();
    let (w, h) = (list.width() as usize, list.height());
    let need = list.table_needs();
    let mut edges = vec![Edge::EMPTY; 8];
    let mut polys = vec![TablePolygon::EMPTY; need.polygons];
    let mut index = vec![0u32; 2 * need.polygons];
    let mut tedges = vec![Edge::EMPTY; need.edges];
    let mut tlines = vec![None; need.lines];
    let mut c = Controller::new(Rasterizer::new(&mut edges));
    macro_rules! table {
        () => {
            TableMemory {
                polygons: &mut polys,
                index: &mut index,
                edges: &mut tedges,
                lines: &mut tlines,
            }
        };
    }
    let mut band = vec![Rgb565::BLACK; 4 * w];
    let mut out = Collect {
        width: w,
        pixels: Vec::new(),
        next: 0,
        bands: 0,
    };
    assert_eq!(
        c.render_bands(&list, table!(), 0, &mut band, &mut out),
        Err(BandsError::Band(BandError::NoRows))
    );
    assert_eq!(
        c.render_bands(&list, table!(), 5, &mut band, &mut out),
        Err(BandsError::Band(BandError::Buffer {
            len: 4 * w,
            needed: 5 * w
        }))
    );
    assert_eq!(out.bands, 0, "nothing shipped");
    assert_eq!(
        c.render_bands(&list, table!(), 4, &mut band, &mut Fails(0)),
        Err(BandsError::Ship {
            y: 4,
            error: "link down"
        })
    );
    // Too small a table.
    let (mut p1, mut l1, mut e1) = (
        vec![TablePolygon::EMPTY; 2],
        vec![0u32; 4],
        vec![Edge::EMPTY; 64],
    );
    let small = TableMemory {
        polygons: &mut p1,
        index: &mut l1,
        edges: &mut e1,
        lines: &mut [],
    };
    assert!(matches!(
        c.render_bands(&list, small, 4, &mut band, &mut out),
        Err(BandsError::Render(
            scanvert::controller::PrepareError::Table(
                scanvert::raster::table::TableError::Polygons { capacity: 2, .. }
            )
        ))
    ));
    // Too few line slots: the list's first line after its last clear
    // that has a pixel in its clip, at its offset.
    let ls = scene(LINES);
    let lines_list = ls.list();
    let need = lines_list.table_needs();
    assert_eq!(need.lines, 21, "every line after the last clear");
    let (mut p2, mut l2, mut e2, mut n2) = (
        vec![TablePolygon::EMPTY; need.polygons],
        vec![0u32; 2 * need.polygons],
        vec![Edge::EMPTY; need.edges],
        vec![None; 3],
    );
    let few = TableMemory {
        polygons: &mut p2,
        index: &mut l2,
        edges: &mut e2,
        lines: &mut n2,
    };
    let mut lw = vec![Rgb565::BLACK; 4 * lines_list.width() as usize];
    let e = c
        .render_bands(&lines_list, few, 4, &mut lw, &mut out)
        .expect_err("three line slots");
    assert!(
        matches!(
            e,
            BandsError::Render(scanvert::controller::PrepareError::Table(
                scanvert::raster::table::TableError::Lines { capacity: 3, .. }
            ))
        ),
        "{e:?}"
    );
    if let BandsError::Render(p) = e {
        let at = lines_list
            .commands()
            .filter(|(_, c)| matches!(c, scanvert::display_list::Command::Line(..)))
            .nth(4)
            .map(|(o, _)| o);
        assert_eq!(Some(p.offset()), at, "the fourth line after the clear");
    }
    // The pull API: out of order, outside, and a band skipping rows.
    let mut bands = c.bands(&list, table!()).expect("prepared");
    assert_eq!(bands.draw(10, 4, &mut band), Ok(4));
    assert_eq!(
        bands.draw(12, 4, &mut band),
        Err(BandsError::Band(BandError::Order { next: 14, y: 12 }))
    );
    assert_eq!(
        bands.draw(h, 4, &mut band),
        Err(BandsError::Band(BandError::Outside { y: h, height: h }))
    );
    assert_eq!(
        bands.draw(20, 0, &mut band),
        Err(BandsError::Band(BandError::NoRows))
    );
    assert_eq!(bands.draw(h - 1, 4, &mut band), Ok(1), "cut at the end");
    // Every band through render_bands is the full frame's rows.
    let full = render_scene(&s).expect("full");
    c.render_bands(&list, table!(), 3, &mut band, &mut out)
        .expect("renders");
    assert_eq!(out.pixels, full.ram.contents());
}

/// The demo's memory for the visible surfaces, per worker.
struct Work {
    active: Vec<Active>,
    runs: Vec<Run>,
}

impl Work {
    /// A workspace for a scene with at most `most` trapezoids on a row
    /// (`Scene::check`).
    fn new(most: usize) -> Work {
        Work {
            active: vec![Active::EMPTY; most],
            runs: vec![Run::EMPTY; scanvert_sim::demo::WIDTH as usize],
        }
    }
    fn workspace(&mut self) -> Workspace<'_> {
        Workspace::new(&mut self.active, &mut self.runs)
    }
}

#[test]
fn the_demo_scene_is_the_same_in_bands_and_on_two_threads() {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let w = WIDTH as usize;
    for step in steps(12).into_iter().step_by(3) {
        with_scene(step, |scene, bg| {
            let px = demo_full_frame(scene, bg);
            for rows in [1, 7, 16, 64, HEIGHT] {
                let mut band = vec![Rgb565::BLACK; rows as usize * w];
                let mut out = Collect {
                    width: w,
                    pixels: Vec::new(),
                    next: 0,
                    bands: 0,
                };
                scene
                    .draw_bands(
                        Resolve::default(),
                        bg,
                        DEFAULT_FONT,
                        rows,
                        &mut band,
                        &mut out,
                    )
                    .expect("bands");
                let diff = px.iter().zip(&out.pixels).filter(|(a, b)| a != b).count();
                assert_eq!(diff, 0, "{step:?} band rows {rows}");
            }
            // Two workers sharing the scene, each with its own workspace
            // and pass: every other band of 16 rows each, the rows above
            // a split and the others, and bands claimed from a counter.
            let most = scene.check().expect("fits") as usize;
            let scene = &*scene;
            let shares = [Share::Alternate, Share::Claim]
                .into_iter()
                .chain([1, 16, 128, 140, HEIGHT - 1].map(Share::Split));
            for share in shares {
                let whole = two_workers(scene, most, bg, share);
                assert!(whole == px, "{step:?}: two workers, {share:?}");
            }
        })
        .expect("demo scene");
    }
}

/// How two workers share the 16-row bands of a frame.
#[derive(Clone, Copy, Debug)]
enum Share {
    /// Every other band, worker `k` from band `k`.
    Alternate,
    /// Worker 0 the rows above this one, worker 1 the others, each in
    /// bands of 16 rows from its first row (the last of worker 0's cut at
    /// the split).
    Split(u16),
    /// Each band claimed by the first worker to ask for it, from a shared
    /// counter (so in increasing order on each).
    Claim,
}

/// The frame drawn by two threads sharing `scene`'s 16-row bands as
/// `share` says, each in a workspace of its own, stepping over the other's
/// rows; each row is drawn by exactly one of them.
fn two_workers<const D: usize, const M: usize>(
    scene: &scanvert::scene::Scene<'_, D, M>,
    most: usize,
    bg: Rgb565,
    share: Share,
) -> Vec<Rgb565> {
    use scanvert_sim::demo::{HEIGHT, WIDTH};
    use std::sync::atomic::{AtomicU16, Ordering};
    let (w, rows) = (WIDTH as usize, 16u16);
    let bands = HEIGHT.div_ceil(rows);
    let next = AtomicU16::new(0);
    let halves: Vec<Vec<(u16, Vec<Rgb565>)>> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..2u16)
            .map(|k| {
                let next = &next;
                s.spawn(move || {
                    let mut work = Work::new(most);
                    let mut ws = work.workspace();
                    let mut pass = scene
                        .bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT)
                        .expect("pass");
                    let mut got = Vec::new();
                    let mut draw = |y: u16, n: u16| {
                        let mut band = vec![Rgb565::BLACK; n as usize * w];
                        let n = pass.draw(y, n, &mut band).expect("band");
                        band.truncate(n as usize * w);
                        got.push((y, band));
                    };
                    match share {
                        Share::Alternate => {
                            for b in (k..bands).step_by(2) {
                                draw(b * rows, rows);
                            }
                        }
                        Share::Split(at) if k == 0 => {
                            for y in (0..at).step_by(rows as usize) {
                                draw(y, rows.min(at - y));
                            }
                        }
                        Share::Split(at) => {
                            for y in (at..HEIGHT).step_by(rows as usize) {
                                draw(y, rows);
                            }
                        }
                        Share::Claim => loop {
                            let b = next.fetch_add(1, Ordering::Relaxed);
                            if b >= bands {
                                break;
                            }
                            draw(b * rows, rows);
                        },
                    }
                    got
                })
            })
            .collect();
        workers
            .into_iter()
            .map(|h| h.join().expect("worker"))
            .collect()
    });
    let mut whole = vec![Rgb565::RED; w * HEIGHT as usize];
    let mut drawn = vec![0u32; HEIGHT as usize];
    for (y, band) in halves.into_iter().flatten() {
        let n = band.len() / w;
        drawn[y as usize..y as usize + n]
            .iter_mut()
            .for_each(|d| *d += 1);
        whole[y as usize * w..y as usize * w + band.len()].copy_from_slice(&band);
    }
    assert!(drawn.iter().all(|&n| n == 1), "{share:?}: {drawn:?}");
    whole
}

/// A random 2D list in text form: clears, clip windows (some partly or
/// wholly outside the frame, some empty), colours, polygons and lines
/// (some far outside the frame, some of no length).
fn list_text() -> impl Strategy<Value = String> {
    let coord = |side: i32| (-8 * 16..(side + 8) * 16).prop_map(|u| u as f64 / 16.0);
    let poly = prop::collection::vec((coord(48), coord(32)), 3..9).prop_map(|v| {
        let mut s = String::from("poly");
        for (x, y) in v {
            s += &format!(" {x} {y}");
        }
        s
    });
    // Convex polygons (vertices on an ellipse at increasing angles), so
    // that one edge ends where the next begins, in bands or across them.
    let convex = (
        coord(48),
        coord(32),
        1i32..40 * 16,
        1i32..30 * 16,
        prop::collection::vec(0u32..3600, 3..9),
    )
        .prop_map(|(cx, cy, rx, ry, mut angles)| {
            angles.sort_unstable();
            let mut s = String::from("poly");
            for a in angles {
                let t = a as f64 * std::f64::consts::PI / 1800.0;
                let x = (16.0 * cx + rx as f64 * t.cos()).round() / 16.0;
                let y = (16.0 * cy + ry as f64 * t.sin()).round() / 16.0;
                s += &format!(" {x} {y}");
            }
            s
        });
    let far = |side: i32| (-200 * 16..(side + 200) * 16).prop_map(|u| u as f64 / 16.0);
    let line = prop_oneof![
        3 => (coord(48), coord(32), coord(48), coord(32)),
        1 => (far(48), far(32), far(48), far(32)),
        1 => (coord(48), coord(32)).prop_map(|(x, y)| (x, y, x, y)),
    ]
    .prop_map(|(a, b, c, d)| format!("line {a} {b} {c} {d}"));
    let cmd = prop_oneof![
        1 => (0u32..0xffffff).prop_map(|c| format!("clear #{c:06x}")),
        2 => (-5i32..50, -5i32..35, -5i32..55, -5i32..40)
            .prop_map(|(a, b, c, d)| format!("clip {a} {b} {c} {d}")),
        3 => (0u32..0xffffff).prop_map(|c| format!("color #{c:06x}")),
        8 => poly,
        6 => convex,
        6 => line,
    ];
    (1u16..=48, 1u16..=32, prop::collection::vec(cmd, 0..24)).prop_map(|(w, h, cmds)| {
        let mut s = format!("frame {w} {h}\n");
        for c in cmds {
            s += &c;
            s.push('\n');
        }
        s
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn generated_2d_lists_are_the_same_in_bands(text in list_text(), rows in prop_oneof![Just(1u16), Just(7), Just(16), 1u16..40]) {
        let s = scene(&text);
        prop_assert_eq!(differs(&s, rows, Resolve::default()), None, "{}", text);
        // The spans and pixels counted are the full frame's too.
        let full = render_scene(&s).expect("full render");
        let band = render_scene_bands_with(&s, rows, Resolve::default()).expect("band render");
        prop_assert_eq!(
            (band.stats.spans, band.stats.pixels),
            (full.stats.spans, full.stats.pixels),
            "{}", text
        );
    }
}

/// A panel that keeps its own pixels: shipped rows overwrite its rows.
struct Panel {
    width: usize,
    pixels: Vec<Rgb565>,
    rows: u32,
}

impl BandTarget for Panel {
    type Color = Rgb565;
    type Error = ();
    fn ship(&mut self, y: u16, rows: u16, px: &[Rgb565]) -> Result<(), ()> {
        let at = y as usize * self.width;
        self.pixels[at..at + px.len()].copy_from_slice(px);
        self.rows += rows as u32;
        Ok(())
    }
}

#[test]
fn the_demo_through_partial_updates_keeps_the_panel_equal_to_full_renders() {
    for exact in [true, false] {
        partial_frames(exact);
    }
}

/// The demo through partial frames, rows marked by row hashes (`exact`) or
/// by the rows rebuilt segments cover.
fn partial_frames(exact: bool) {
    use scanvert::scene::DirtyRows;
    use scanvert_sim::demo::{drive, HEIGHT, WIDTH};
    use std::cell::RefCell;
    let w = WIDTH as usize;
    let mut bits = vec![0u32; DirtyRows::words(HEIGHT)];
    let dirty = RefCell::new(DirtyRows::new(&mut bits, HEIGHT).expect("bits"));
    dirty.borrow_mut().mark_all(); // the panel starts unknown
    let mut panel = Panel {
        width: w,
        pixels: vec![Rgb565::RED; w * HEIGHT as usize],
        rows: 0,
    };
    let mut band = vec![Rgb565::BLACK; 16 * w];
    let mut shipped = Vec::new();
    let mut scratch = vec![0u64; 2 * HEIGHT as usize];
    drive(
        12,
        |scene, procs| {
            let n = if exact { scratch.len() } else { 0 };
            scene.update_marking(
                procs,
                DEFAULT_FONT,
                &mut dirty.borrow_mut(),
                &mut scratch[..n],
            )
        },
        |scene, step, _, bg| {
            let mut d = dirty.borrow_mut();
            panel.rows = 0;
            let (_, rows) = scene
                .draw_marked(
                    Resolve::default(),
                    bg,
                    DEFAULT_FONT,
                    &d,
                    16,
                    &mut band,
                    &mut panel,
                )
                .expect("partial frame");
            assert_eq!(rows, panel.rows);
            d.clear();
            let px = demo_full_frame(scene, bg);
            let diff = px.iter().zip(&panel.pixels).filter(|(a, b)| a != b).count();
            assert_eq!(diff, 0, "{step:?}: the panel differs from the full render");
            shipped.push((step, rows));
        },
    )
    .expect("demo runs");
    // The threshold-only frames (the camera still) ship fewer rows than a
    // frame; the camera's frames ship the rows the scene covers.
    let frame_bytes = w * HEIGHT as usize * 2;
    for (i, (step, rows)) in shipped.iter().enumerate() {
        let bytes = *rows as usize * w * 2;
        println!(
            "exact {exact}: frame {i}: threshold {}, camera {}°: {rows} rows, {bytes} bytes of {frame_bytes}",
            step.threshold, step.orbit
        );
        if exact && (1..4).contains(&i) {
            assert!(bytes < frame_bytes, "frame {i}");
        }
    }
}

/// Renders every other band of `rows` starting with band `k` of `list`
/// with memory of its own (sized as the CLI sizes it), skipping the
/// others; returns `(y, pixels)` of each band drawn.
fn every_other_band(s: &Scene, rows: u16, k: u16) -> Vec<(u16, Vec<Rgb565>)> {
    let list = s.list();
    let (w, h) = (list.width() as usize, list.height());
    let mut memory = ListMemory::for_bands(&list).expect("sized");
    let (mut c, table) = memory.band_parts();
    let mut pass = c.bands(&list, table).expect("prepared");
    let mut out = Vec::new();
    let mut y = k * rows;
    while y < h {
        let mut band = vec![Rgb565::GREEN; rows as usize * w];
        let n = pass.draw(y, rows, &mut band).expect("band");
        band.truncate(n as usize * w);
        out.push((y, band));
        y += 2 * rows;
    }
    out
}

#[test]
fn two_passes_each_skipping_the_others_bands_make_the_frame() {
    for text in [FLAT, NO_CLEAR, THREE_D, LINES] {
        let s = scene(text);
        let full = render_scene(&s).expect("full");
        let w = s.list().width() as usize;
        for rows in [1, 3, 7, 16] {
            let mut whole = vec![Rgb565::RED; full.ram.contents().len()];
            for k in 0..2 {
                for (y, band) in every_other_band(&s, rows, k) {
                    let at = y as usize * w;
                    whole[at..at + band.len()].copy_from_slice(&band);
                }
            }
            assert!(whole == full.ram.contents(), "band rows {rows}\n{text}");
        }
    }
}

/// `THREE_D` written into `dir`, a way to run `scanvert render` on it
/// into an image with more options, and the PNG it writes with none.
#[allow(clippy::type_complexity)]
fn render_three_d(
    dir: &Path,
) -> (
    impl Fn(&Path, &[&str]) -> Result<String, scanvert_sim::cli::CliError>,
    Vec<u8>,
) {
    std::fs::create_dir_all(dir).expect("dir");
    let src = dir.join("three.dl");
    std::fs::write(&src, THREE_D).expect("scene");
    let run = move |out: &Path, extra: &[&str]| {
        let mut args: Vec<String> = [
            "render",
            src.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        args.extend(extra.iter().map(|s| s.to_string()));
        scanvert_sim::cli::run(&args)
    };
    let full = dir.join("full.png");
    run(&full, &[]).expect("full render");
    let want = std::fs::read(&full).expect("png");
    (run, want)
}

#[test]
fn the_command_line_writes_the_same_image_in_bands_and_refuses_bad_counts() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bands_cli");
    let (run, want) = render_three_d(&dir);
    for n in ["1", "7", "16", "64", "65", "100000"] {
        let out = dir.join(format!("band-{n}.png"));
        run(&out, &["--band-rows", n]).expect("band render");
        assert_eq!(std::fs::read(&out).expect("png"), want, "--band-rows {n}");
    }
    for bad in [
        &["--band-rows", "0"][..],
        &["--band-rows", "x"],
        &["--band-rows", "-1"],
        &["--band-rows"],
    ] {
        let out = dir.join("bad.png");
        let _ = std::fs::remove_file(&out);
        let e = run(&out, bad).expect_err("refused");
        assert_eq!(e.status, scanvert_sim::cli::EXIT_USAGE, "{bad:?}");
        assert!(e.message.contains("--band-rows"), "{}", e.message);
        assert!(!out.exists(), "no image for {bad:?}");
    }
}

#[test]
fn the_command_line_writes_the_same_image_in_every_resolve_mode_and_refuses_others() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("resolve_cli");
    let (run, want) = render_three_d(&dir);
    for mode in ["crossing", "bisect", "paint"] {
        for bands in [&[][..], &["--band-rows", "7"]] {
            let out = dir.join(format!("{mode}-{}.png", bands.len()));
            let mut extra = vec!["--resolve", mode];
            extra.extend_from_slice(bands);
            run(&out, &extra).expect("render");
            assert_eq!(std::fs::read(&out).expect("png"), want, "{extra:?}");
        }
    }
    for bad in [
        &["--resolve", "sweep"][..],
        &["--resolve"],
        &["--resolve", "paint", "--race", "168"],
    ] {
        let out = dir.join("bad.png");
        let _ = std::fs::remove_file(&out);
        let e = run(&out, bad).expect_err("refused");
        assert_eq!(e.status, scanvert_sim::cli::EXIT_USAGE, "{bad:?}");
        assert!(e.message.contains("--resolve"), "{}", e.message);
        assert!(!out.exists(), "no image for {bad:?}");
    }
}

/// After `Scene::check`, a pass in another workspace compares its
/// capacity with the number the scene found: one slot short is the same
/// typed error as before, and enough draws the same frame.
#[test]
fn a_checked_scene_sizes_other_workspaces_by_its_count() {
    use scanvert::visible::VisibleError;
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    with_scene(steps(1)[0], |scene, bg| {
        let w = WIDTH as usize;
        let px = demo_full_frame(scene, bg);
        let most = scene.check().expect("fits") as usize;
        let mut short = Work::new(most - 1);
        let mut ws = short.workspace();
        let r = scene.bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT);
        assert!(
            matches!(r, Err(VisibleError::Active { capacity }) if capacity == most - 1),
            "one slot short"
        );
        let mut work = Work::new(most);
        let mut ws = work.workspace();
        let mut pass = scene
            .bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT)
            .expect("pass");
        let mut band = vec![Rgb565::BLACK; 16 * w];
        let mut y = 0;
        while y < HEIGHT {
            let n = pass.draw(y, 16, &mut band).expect("band");
            let at = y as usize * w;
            assert!(
                band[..n as usize * w] == px[at..at + n as usize * w],
                "row {y}"
            );
            y += n;
        }
    })
    .expect("demo scene");
}

/// Long skips: one pass over the demo's frames drawing bands of 1 to 7
/// rows with gaps of 1 to 255 rows between them (the active list jumped
/// over each gap at once), and a pass drawing only the first and the last
/// row: every band drawn is the full frame's rows.
#[test]
fn bands_after_long_skips_are_the_full_frames_rows() {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let w = WIDTH as usize;
    for step in steps(12).into_iter().step_by(4) {
        with_scene(step, |scene, bg| {
            let px = demo_full_frame(scene, bg);
            let most = scene.check().expect("fits") as usize;
            let mut work = Work::new(most);
            let mut band = vec![Rgb565::BLACK; 7 * w];
            let plans = [1u16, 2, 5, 16, 33, 64, 100, 150, 200]
                .map(|gap| (gap, gap % 7 + 1))
                .into_iter()
                .chain([(HEIGHT - 2, 1)]);
            for ((gap, rows), mode) in plans.flat_map(|p| MODES.map(|m| (p, m))) {
                let mut ws = work.workspace();
                let mut pass = scene
                    .bands_in(&mut ws, mode, bg, DEFAULT_FONT)
                    .expect("pass");
                // From row 0 when the gap is the frame's less 2: rows 0
                // and HEIGHT - 1.
                let mut y = if gap == HEIGHT - 2 { 0 } else { gap };
                while y < HEIGHT {
                    let n = pass.draw(y, rows, &mut band).expect("band");
                    let at = y as usize * w;
                    assert!(
                        band[..n as usize * w] == px[at..at + n as usize * w],
                        "{step:?}: gap {gap}, rows {y}..{}, {mode:?}",
                        y + n
                    );
                    y += n + gap;
                }
            }
        })
        .expect("demo scene");
    }
}

/// The demo scene's full frame, drawn into a frame buffer.
fn demo_full_frame<const D: usize, const M: usize>(
    scene: &mut scanvert::Scene<'_, D, M>,
    bg: Rgb565,
) -> Vec<Rgb565> {
    use scanvert_sim::demo::{HEIGHT, WIDTH};
    let mut px = vec![Rgb565::BLACK; WIDTH as usize * HEIGHT as usize];
    let mut fb = FrameBuffer::new(&mut px, WIDTH, HEIGHT).expect("fb");
    scene
        .draw(Resolve::default(), Some(bg), DEFAULT_FONT, &mut fb)
        .expect("draws");
    px
}
