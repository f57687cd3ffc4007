//! Segment attributes: visibility, highlight and placement, each checked
//! against a scene built without the attribute (the segment left out,
//! its colour changed, the placement's transforms at the start of its
//! procedure), in the full frame and in bands, with the procedures run
//! counted (none for any attribute), and the rows marked for a partial
//! frame covering every changed pixel.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::display_list::Axis;
use scanvert::geometry::{Angle, Perspective, Pipeline, Point3, View, Viewport, Q16};
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::label::DEFAULT_FONT;
use scanvert::scene::{
    Builder, Capacities, DirtyRows, Placement, Procedure, Scene, SceneError, Update,
};
use scanvert::visible::sweep::Resolve;
use scanvert_sim::memory::SceneHeap;
use std::cell::Cell;

const W: u16 = 96;
const H: u16 = 72;
type B<'s, 'a> = Builder<'s, 'a, 8, 32>;

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

fn p(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(q(x), q(y), q(z))
}

fn heap() -> SceneHeap {
    SceneHeap::new(Capacities {
        trapezoids: 2048,
        faces: 256,
        segments: 3,
        rows: H as usize,
        edges: 32,
        active: 256,
        runs: W as usize,
        labels: 8,
        text: 64,
    })
}

fn scene(mem: &mut SceneHeap) -> Scene<'_, 8, 32> {
    let persp = Perspective::from_fov(Angle::from_degrees(60), W, q(1.0), q(100.0)).unwrap();
    let pipe = Pipeline::<8, 32>::new(persp, Viewport::centred(W, H).unwrap());
    let mut s = Scene::new(mem.memory(), pipe).unwrap();
    s.set_view(&View::look_at(p(2.0, 3.0, 12.0), p(0.0, 0.0, 0.0)).unwrap())
        .unwrap();
    s
}

/// How segment 1 is drawn in the reference scenes.
#[derive(Clone, Copy)]
enum Box1 {
    Shown(Rgb888),
    Placed(Placement),
    Left,
}

/// Segment 0: a ground plate. Segment 1: a box under its own transforms,
/// with a label. Segment 2: a mesh of two triangles.
fn build(b: &mut B<'_, '_>, s: usize, box1: Box1, runs: &Cell<u32>) -> Result<(), SceneError> {
    runs.set(runs.get() + 1);
    match s {
        0 => b
            .face(
                &[
                    p(-5.0, -1.0, 4.0),
                    p(5.0, -1.0, 4.0),
                    p(5.0, -1.0, -4.0),
                    p(-5.0, -1.0, -4.0),
                ],
                Rgb888::new(90, 90, 90),
            )
            .map(|_| ()),
        1 => {
            let color = match box1 {
                Box1::Left => return Ok(()),
                Box1::Shown(c) => c,
                Box1::Placed(pl) => {
                    pl.apply(b.stack_mut())?;
                    Rgb888::new(40, 80, 220)
                }
            };
            b.push()?;
            b.translate(q(-1.0), q(0.5), q(0.0))?;
            b.rotate(Axis::Y, Angle::from_degrees(25))?;
            b.scale(q(1.5), q(1.0), q(1.0))?;
            let (a, z) = (1.0, 1.0);
            let faces = [
                [p(-a, -a, z), p(a, -a, z), p(a, a, z), p(-a, a, z)],
                [p(a, -a, z), p(a, -a, -z), p(a, a, -z), p(a, a, z)],
                [p(-a, a, z), p(a, a, z), p(a, a, -z), p(-a, a, -z)],
                [p(-a, -a, -z), p(-a, -a, z), p(-a, a, z), p(-a, a, -z)],
            ];
            for f in &faces {
                b.face(f, color)?;
            }
            b.face(&[p(-a, a + 0.5, z), p(a, a + 0.5, -z)], color)?;
            b.pop()?;
            b.label(p(0.0, 2.0, 0.0), "box", Rgb888::WHITE).map(|_| ())
        }
        _ => {
            let v = [
                p(2.0, -1.0, 1.0),
                p(4.0, -1.0, 1.0),
                p(4.0, 2.0, 0.0),
                p(2.0, 2.0, 0.0),
            ];
            let mut slots = [scanvert::geometry::ViewPoint::default(); 4];
            b.mesh(
                &v,
                &[0, 1, 2, 0, 2, 3],
                3,
                Rgb888::new(30, 200, 60),
                &mut slots,
            )
            .map(|_| ())
        }
    }
}

/// Builds every stale segment of `scene`, segment 1 as `box1`.
fn update(scene: &mut Scene<'_, 8, 32>, box1: Box1, runs: &Cell<u32>) -> Update {
    let mut p0 = |b: &mut B<'_, '_>| build(b, 0, box1, runs);
    let mut p1 = |b: &mut B<'_, '_>| build(b, 1, box1, runs);
    let mut p2 = |b: &mut B<'_, '_>| build(b, 2, box1, runs);
    let procs: &mut [&mut dyn Procedure<8, 32>] = &mut [&mut p0, &mut p1, &mut p2];
    scene.update(procs).expect("update")
}

fn full(scene: &mut Scene<'_, 8, 32>) -> Vec<Rgb565> {
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
    scene
        .draw(
            Resolve::default(),
            Some(Rgb565::BLACK),
            DEFAULT_FONT,
            &mut fb,
        )
        .expect("draw");
    px
}

/// A panel that keeps its pixels; shipped rows overwrite them.
struct Panel(Vec<Rgb565>);

impl BandTarget for Panel {
    type Color = Rgb565;
    type Error = ();
    fn ship(&mut self, y: u16, _rows: u16, px: &[Rgb565]) -> Result<(), ()> {
        let at = y as usize * W as usize;
        self.0[at..at + px.len()].copy_from_slice(px);
        Ok(())
    }
}

fn banded(scene: &mut Scene<'_, 8, 32>, rows: u16, resolve: Resolve) -> Vec<Rgb565> {
    let mut panel = Panel(vec![Rgb565::RED; W as usize * H as usize]);
    let mut band = vec![Rgb565::BLACK; rows as usize * W as usize];
    scene
        .draw_bands(
            resolve,
            Rgb565::BLACK,
            DEFAULT_FONT,
            rows,
            &mut band,
            &mut panel,
        )
        .expect("bands");
    panel.0
}

/// The picture of a fresh scene with segment 1 as `box1`.
fn reference(box1: Box1) -> Vec<Rgb565> {
    let mut mem = heap();
    let mut s = scene(&mut mem);
    update(&mut s, box1, &Cell::new(0));
    full(&mut s)
}

/// `scene`'s picture, whole, in bands of 16 and 5 rows, and painted,
/// equals `want`.
fn check(scene: &mut Scene<'_, 8, 32>, want: &[Rgb565], what: &str) {
    let got = full(scene);
    let diff = got.iter().zip(want).filter(|(a, b)| a != b).count();
    assert_eq!(diff, 0, "{what}: full frame");
    for (rows, mode) in [
        (16, Resolve::default()),
        (5, Resolve::Paint),
        (7, Resolve::Crossing),
    ] {
        let got = banded(scene, rows, mode);
        let diff = got.iter().zip(want).filter(|(a, b)| a != b).count();
        assert_eq!(diff, 0, "{what}: bands of {rows}, {mode:?}");
    }
}

const BLUE: Rgb888 = Rgb888::new(40, 80, 220);

#[test]
fn hide_show_highlight_and_place_run_no_procedure_and_draw_the_references() {
    let mut mem = heap();
    let mut records = vec![0u8; 4096];
    let mut s = scene(&mut mem);
    s.keep_records(&mut records);
    let runs = Cell::new(0);
    let u = update(&mut s, Box1::Shown(BLUE), &runs);
    assert_eq!((u.regenerated, runs.get()), (3, 3));
    let shown = reference(Box1::Shown(BLUE));
    check(&mut s, &shown, "as built");
    runs.set(0);

    // Hidden: the picture without it; shown again: as it was.
    assert_eq!(s.set_visible(1, false).unwrap().regenerated, 0);
    assert!(s.is_hidden(1));
    check(&mut s, &reference(Box1::Left), "hidden");
    assert_eq!(update(&mut s, Box1::Shown(BLUE), &runs).regenerated, 0);
    s.set_visible(1, true).unwrap();
    check(&mut s, &shown, "shown");

    // Highlighted: as built in that colour; cleared: as it was.
    let yellow = Rgb888::new(250, 220, 0);
    s.set_highlight(1, Some(yellow)).unwrap();
    assert_eq!(s.highlight(1), Some(yellow));
    check(&mut s, &reference(Box1::Shown(yellow)), "highlighted");
    s.set_highlight(1, None).unwrap();
    check(&mut s, &shown, "highlight cleared");

    // Placed: as built with the placement's transforms first.
    let pl = Placement {
        translate: p(0.5, -0.25, -2.0),
        rotate: [
            Angle::from_degrees(10),
            Angle::from_degrees(-40),
            Angle::ZERO,
        ],
        scale: p(0.75, 1.25, 1.0),
    };
    let u = s.place(1, pl).unwrap();
    assert_eq!((u.regenerated, u.recut), (0, 1));
    assert!(u.trapezoids > 0 && u.labels == 1, "{u:?}");
    assert_eq!(s.placement(1), pl);
    check(&mut s, &reference(Box1::Placed(pl)), "placed");
    // The mesh segment too: recorded as faces, the same pixels.
    let u = s
        .place(2, Placement::translation(q(-1.0), q(0.0), q(1.0)))
        .unwrap();
    assert_eq!((u.regenerated, u.recut), (0, 1));
    s.place(2, Placement::IDENTITY).unwrap();
    check(&mut s, &reference(Box1::Placed(pl)), "mesh placed and back");

    // Hidden and highlighted while placed, and back.
    s.set_highlight(1, Some(yellow)).unwrap();
    s.set_visible(1, false).unwrap();
    check(
        &mut s,
        &reference(Box1::Left),
        "placed, highlighted, hidden",
    );
    s.set_visible(1, true).unwrap();
    s.set_highlight(1, None).unwrap();
    s.place(1, Placement::IDENTITY).unwrap();
    check(&mut s, &shown, "back where it was");
    assert_eq!(runs.get(), 0, "no procedure ran");
    assert_eq!(update(&mut s, Box1::Shown(BLUE), &runs).regenerated, 0);

    // A camera move rebuilds the shown segments with their placements and
    // leaves the hidden one stale until it is shown.
    s.place(1, pl).unwrap();
    s.set_visible(1, false).unwrap();
    s.set_view(&View::look_at(p(-3.0, 4.0, 11.0), p(0.0, 0.0, 0.0)).unwrap())
        .unwrap();
    let u = update(&mut s, Box1::Shown(BLUE), &runs);
    assert_eq!((u.regenerated, u.hidden, runs.get()), (2, 1, 2));
    s.set_visible(1, true).unwrap();
    let u = update(&mut s, Box1::Shown(BLUE), &runs);
    assert_eq!((u.regenerated, u.hidden), (1, 0));
    let mut mem2 = heap();
    let mut r = scene(&mut mem2);
    r.set_view(&View::look_at(p(-3.0, 4.0, 11.0), p(0.0, 0.0, 0.0)).unwrap())
        .unwrap();
    update(&mut r, Box1::Placed(pl), &Cell::new(0));
    let want = full(&mut r);
    check(&mut s, &want, "rebuilt with its placement");
    assert!(s.records_needed() > 0 && s.records_needed() <= 4096);
}

#[test]
fn marked_rows_cover_every_pixel_an_attribute_changes() {
    let mut mem = heap();
    let mut records = vec![0u8; 4096];
    let mut s = scene(&mut mem);
    s.keep_records(&mut records);
    let runs = Cell::new(0);
    update(&mut s, Box1::Shown(BLUE), &runs);
    let mut panel = Panel(full(&mut s));
    let mut bits = vec![0u32; DirtyRows::words(H)];
    let mut band = vec![Rgb565::BLACK; 8 * W as usize];
    let pl = Placement::translation(q(1.5), q(-0.5), q(0.0));
    type Change = fn(&mut Scene<'_, 8, 32>, Placement);
    let changes: [(&str, Change); 6] = [
        ("hide", |s, _| {
            s.set_visible(1, false).unwrap();
        }),
        ("show", |s, _| {
            s.set_visible(1, true).unwrap();
        }),
        ("highlight", |s, _| {
            s.set_highlight(1, Some(Rgb888::new(255, 0, 255))).unwrap();
        }),
        ("place", |s, pl| {
            s.place(1, pl).unwrap();
        }),
        ("clear", |s, _| {
            s.set_highlight(1, None).unwrap();
        }),
        ("home", |s, _| {
            s.place(1, Placement::IDENTITY).unwrap();
        }),
    ];
    for (what, change) in changes {
        let mut dirty = DirtyRows::new(&mut bits, H).unwrap();
        s.marking(1, DEFAULT_FONT, &mut dirty, |s| change(s, pl));
        // Only rows the segment reaches were marked.
        let marked: u32 = dirty.runs().map(|(a, b)| u32::from(b - a)).sum();
        assert!(marked < u32::from(H), "{what}: {marked} rows");
        s.draw_marked(
            Resolve::default(),
            Rgb565::BLACK,
            DEFAULT_FONT,
            &dirty,
            8,
            &mut band,
            &mut panel,
        )
        .expect("marked");
        let want = full(&mut s);
        let diff = want.iter().zip(&panel.0).filter(|(a, b)| a != b).count();
        assert_eq!(diff, 0, "{what}: the panel differs from a full render");
    }
    assert_eq!(runs.get(), 3);
}

#[test]
fn unknown_segments_and_missing_records_are_typed_errors() {
    let mut mem = heap();
    let mut s = scene(&mut mem);
    let runs = Cell::new(0);
    update(&mut s, Box1::Shown(BLUE), &runs);
    assert!(matches!(s.set_visible(3, false), Err(SceneError::Store(_))));
    assert!(matches!(
        s.set_highlight(9, None),
        Err(SceneError::Store(_))
    ));
    assert!(matches!(
        s.place(3, Placement::IDENTITY),
        Err(SceneError::Store(_))
    ));
    // No record buffer: a placement has nowhere to live.
    assert_eq!(
        s.place(1, Placement::IDENTITY),
        Err(SceneError::Records { capacity: 0 })
    );
    // A buffer too small for a segment's commands (room for the three
    // headers and segment 0's plate): the record is given up, and placing
    // the segment runs its procedure at the next update.
    let mut small = vec![0u8; 3 * scanvert::scene::record::HEADER + 55 + 10];
    s.keep_records(&mut small);
    runs.set(0);
    update(&mut s, Box1::Shown(BLUE), &runs);
    assert_eq!(runs.get(), 3);
    let pl = Placement::translation(q(0.5), q(0.0), q(0.0));
    let u = s.place(1, pl).unwrap();
    assert_eq!((u.regenerated, u.recut), (0, 0));
    assert!(s.is_stale(1));
    runs.set(0);
    let u = update(&mut s, Box1::Shown(BLUE), &runs);
    assert_eq!((u.regenerated, runs.get()), (1, 1));
    let got = full(&mut s);
    let want = reference(Box1::Placed(pl));
    assert_eq!(got.iter().zip(&want).filter(|(a, b)| a != b).count(), 0);
}

// ---- The text and binary forms ----

use scanvert::display_list::{DisplayList, ErrorKind, Opcode};
use scanvert_sim::cli::{render_scene, render_scene_bands_with, Scene as ListScene};
use scanvert_sim::text::{assemble, disassemble};
use std::path::Path;

/// The pixels of `text` rendered whole, and the same in bands of 7 and
/// 16 rows (checked equal).
fn render(text: &str) -> Vec<Rgb565> {
    let s = ListScene::from_bytes(Path::new("attributes.dl"), text.as_bytes().to_vec())
        .expect("list reads");
    let full = render_scene(&s).expect("renders").ram.contents().to_vec();
    for (rows, mode) in [(7, Resolve::Crossing), (16, Resolve::Paint)] {
        let band = render_scene_bands_with(&s, rows, mode).expect("bands");
        assert_eq!(band.ram.contents(), &full[..], "bands of {rows}");
    }
    full
}

/// A list of two segments; `head` goes after the camera, `one` and
/// `two` at the start of segments 1 and 2, `colour2` is segment 2's
/// colour.
fn list(head: &str, one: &str, two: &str, colour2: &str) -> String {
    format!(
        "frame 80 60
perspective 60 1 100
lookat 2 3 12  0 0 0
{head}
segment 1
{one}
color #3050e0
push
translate -1 0.5 0
rotate y 25
face -1 -1 1  1 -1 1  1 1 1  -1 1 1
face 1 -1 1  1 -1 -1  1 1 -1  1 1 1
face -1 1 1  1 1 1  1 1 -1  -1 1 -1
pop
face -2 1.5 0  2 1.5 0
segment 2
{two}
color {colour2}
v 2 -1 1
v 4 -1 1
v 4 2 0
v 2 2 0
f 1 2 3
f 1 3 4
poly3 2 2 40  20 2 40  10 12 40
"
    )
}

#[test]
fn list_attributes_draw_what_the_lists_without_them_draw() {
    let plain = render(&list("", "", "", "#20c040"));
    assert_ne!(plain, render(&list("hide 1", "", "", "#20c040")));
    // Hidden: as if segment 1 had no faces.
    let no_one = list("", "hide 1", "", "#20c040")
        .replace("face -1 -1 1", "# face")
        .replace("face 1 -1 1", "# face")
        .replace("face -1 1 1", "# face")
        .replace("face -2 1.5 0", "# face")
        .replace("hide 1", "");
    assert_eq!(render(&list("hide 1", "", "", "#20c040")), render(&no_one));
    // Wherever the attribute stands, and the last of each kind wins.
    assert_eq!(render(&list("", "", "hide 1", "#20c040")), render(&no_one));
    assert_eq!(render(&list("hide 1\nshow 1", "", "", "#20c040")), plain);
    // Highlighted: as if drawn in that colour (no light here).
    assert_eq!(
        render(&list("highlight 2 #ffcc00", "", "", "#20c040")),
        render(&list("", "", "", "#ffcc00"))
    );
    assert_eq!(
        render(&list(
            "highlight 2 #ffcc00\nhighlight 2 off",
            "",
            "",
            "#20c040"
        )),
        plain
    );
    // Placed: as if its transforms started the segment.
    assert_eq!(
        render(&list(
            "place 1 0.5 -0.25 -2  10 -40 0  0.75 1.25 1",
            "",
            "",
            "#20c040"
        )),
        render(&list(
            "",
            "translate 0.5 -0.25 -2\nrotate x 10\nrotate y -40\nscale 0.75 1.25 1",
            "",
            "#20c040"
        ))
    );
    assert_eq!(
        render(&list("place 2 -1 0 1", "", "", "#20c040")),
        render(&list("", "", "translate -1 0 1", "#20c040"))
    );
    // An attribute of a segment the list does not start changes nothing.
    assert_eq!(
        render(&list("hide 9\nplace 7 1 1 1", "", "", "#20c040")),
        plain
    );
}

#[test]
fn list_attributes_round_trip_and_bad_ones_name_their_line_or_byte() {
    let text = "frame 16 16
hide 1
show 65535
highlight 2 #ffcc00 # a comment after the colour
highlight 3 off
place 1 1 2 3
place 1 1 2 3  0 90 0.5
place 1 1 2 3  0 0 0  2 1 1
segment 1
";
    let a = assemble(text).expect("assembles");
    let list = DisplayList::new_checked(&a.bytes).expect("reads");
    let back = disassemble(&list);
    assert_eq!(assemble(&back).expect("again").bytes, a.bytes, "{back}");
    assert!(back.contains("highlight 2 #ffcc00\n"), "{back}");
    assert!(back.contains("highlight 3 off\n"), "{back}");
    assert!(back.contains("place 1 1 2 3\n"), "{back}");
    assert!(back.contains("place 1 1 2 3 0 0 0 2 1 1\n"), "{back}");

    for (bad, line) in [
        ("frame 8 8\nhide\n", 2),
        ("frame 8 8\n\nshow 65536\n", 3),
        ("frame 8 8\nhighlight 1 #ffcc0\n", 2),
        ("frame 8 8\nhighlight 1 on\n", 2),
        ("frame 8 8\nhighlight 1\n", 2),
        ("frame 8 8\nplace 1 1 2\n", 2),
        ("frame 8 8\nplace 1 1 2 3 4\n", 2),
        ("frame 8 8\nplace 1 1 2 3 0 0 0 1 1\n", 2),
        ("frame 8 8\nplace -1 1 2 3\n", 2),
    ] {
        let e = assemble(bad)
            .err()
            .unwrap_or_else(|| panic!("{bad:?} assembles"));
        assert_eq!(e.line, line, "{bad:?}: {e}");
    }

    // Binary: a highlight's flag over 1, or off with a colour, is a bad
    // operand at its opcode; a place cut short is truncated there.
    let a = assemble("frame 8 8\nsegment 1\nhighlight 1 off\n").unwrap();
    let at = a.bytes.len() - 7;
    assert_eq!(a.bytes[at], Opcode::Highlight as u8);
    for (k, v) in [(3, 2u8), (4, 1), (6, 9)] {
        let mut b = a.bytes.clone();
        b[at + k] = v;
        let e = DisplayList::new_checked(&b).unwrap_err();
        assert_eq!(
            (e.offset, e.kind),
            (at, ErrorKind::BadOperand(Opcode::Highlight))
        );
    }
    let a = assemble("frame 8 8\nplace 1 1 2 3\n").unwrap();
    let mut b = a.bytes[..a.bytes.len() - 1].to_vec();
    let body = (b.len() - 16) as u32;
    b[12..16].copy_from_slice(&body.to_le_bytes());
    let e = DisplayList::new_checked(&b).unwrap_err();
    assert_eq!((e.offset, e.kind), (16, ErrorKind::Truncated));
}
