//! One frame pass over a stack of layers (`scanvert::frame`): display
//! lists (2D and 3D), embedded-graphics drawables, in bands of every
//! height and in runs of changed rows, against the same layers drawn one
//! after the other into a whole frame buffer; and the rows a display
//! list's edit changes, found by `DisplayList::mark_changes`.

use embedded_graphics::mono_font::ascii::{FONT_6X10, FONT_9X18_BOLD};
use embedded_graphics::mono_font::MonoTextStyle;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle, RoundedRectangle};
use embedded_graphics::text::Text;
use embedded_graphics_core::pixelcolor::Rgb565;
use proptest::prelude::*;
use scanvert::display_list::{DisplayList, ScratchTooSmall};
use scanvert::frame::{DrawableLayer, FramePass, Layer};
use scanvert::port::band::{BandTarget, DirtyRows};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert_sim::cli::Scene;
use scanvert_sim::memory::ListMemory;
use std::path::Path;

/// A panel that keeps what it is sent.
struct Panel {
    width: usize,
    pixels: Vec<Rgb565>,
    rows: u32,
}

impl BandTarget for Panel {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn ship(&mut self, y: u16, rows: u16, px: &[Rgb565]) -> Result<(), Self::Error> {
        let at = y as usize * self.width;
        self.pixels[at..at + px.len()].copy_from_slice(px);
        self.rows += rows as u32;
        Ok(())
    }
}

fn list_of(text: &str) -> Scene {
    Scene::from_bytes(Path::new("frame.dl"), text.as_bytes().to_vec()).expect("list reads")
}

/// `lists` rendered whole one over the other into a black frame buffer
/// of `w × h`, then `draw` into it.
fn whole(
    lists: &[&DisplayList<'_>],
    (w, h): (u16, u16),
    draw: impl Fn(&mut FrameBuffer<'_, Rgb565>),
) -> Vec<Rgb565> {
    let mut px = vec![Rgb565::BLACK; w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut px, w, h).unwrap();
    for list in lists {
        let mut mem = ListMemory::for_list(list).expect("sized");
        mem.controller().render(list, &mut fb).expect("renders");
    }
    draw(&mut fb);
    px
}

type Text6 = Text<'static, MonoTextStyle<'static, Rgb565>>;

fn hud(
    shift: i32,
) -> (
    Text6,
    Text6,
    embedded_graphics::primitives::Styled<Circle, PrimitiveStyle<Rgb565>>,
) {
    let small = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
    let bold = MonoTextStyle::new(&FONT_9X18_BOLD, Rgb565::YELLOW);
    (
        Text::new("layers: 2D, 3D, text", Point::new(2 + shift, 10), small),
        Text::new("42", Point::new(100, 60 + shift), bold),
        Circle::new(Point::new(120 + shift, 20), 25)
            .into_styled(PrimitiveStyle::with_stroke(Rgb565::CYAN, 3)),
    )
}

#[test]
fn stacked_layers_in_bands_equal_the_layers_drawn_whole() {
    // The 2D demo under the 3D cube scene (on the demo's frame; its own
    // `clear` would cover the demo: it is left out), then drawables over
    // both.
    let demo = list_of(&std::fs::read_to_string("../scenes/demo.dl").unwrap());
    let cube_text = std::fs::read_to_string("../scenes/cube.dl").unwrap();
    let cube_text: String = cube_text
        .lines()
        .filter(|l| !l.trim_start().starts_with("clear"))
        .map(|l| match l.trim_start().starts_with("frame") {
            true => "frame 320 200\n".to_string(),
            false => format!("{l}\n"),
        })
        .collect();
    let (demo_list, cube) = (demo.list(), list_of(&cube_text));
    let cube_list = cube.list();
    assert_eq!(
        (demo_list.width(), demo_list.height()),
        (cube_list.width(), cube_list.height()),
        "the two scenes share a frame"
    );
    let size = (demo_list.width(), demo_list.height());
    let (t, n, c) = hud(0);
    let want = whole(&[&demo_list, &cube_list], size, |fb| {
        t.draw(fb).unwrap();
        n.draw(fb).unwrap();
        c.draw(fb).unwrap();
    });
    for rows in [1, 7, 16, size.1] {
        let mut demo_mem = ListMemory::for_bands(&demo_list).expect("sized");
        let (mut c1, t1) = demo_mem.band_parts();
        let mut a = c1.bands(&demo_list, t1).expect("prepared");
        let mut cube_mem = ListMemory::for_bands(&cube_list).expect("sized");
        let (mut c2, t2) = cube_mem.band_parts();
        let mut b = c2.bands(&cube_list, t2).expect("prepared");
        let (mut l1, mut l2, mut l3) = (
            DrawableLayer::new(t),
            DrawableLayer::new(n),
            DrawableLayer::new(c),
        );
        let mut panel = Panel {
            width: size.0 as usize,
            pixels: vec![Rgb565::RED; want.len()],
            rows: 0,
        };
        let mut band = vec![Rgb565::GREEN; rows as usize * size.0 as usize];
        let layers: &mut [&mut dyn Layer<Rgb565>] =
            &mut [&mut a, &mut b, &mut l1, &mut l2, &mut l3];
        FramePass::new(size, Rgb565::BLACK)
            .draw(layers, rows, &mut band, &mut panel)
            .expect("draws");
        let bad = panel
            .pixels
            .iter()
            .zip(&want)
            .filter(|(p, q)| p != q)
            .count();
        assert_eq!(bad, 0, "bands of {rows} rows");
        assert_eq!(panel.rows, size.1 as u32);
    }
}

#[test]
fn drawables_that_move_send_only_their_rows_and_the_panel_stays_whole() {
    let size = (160u16, 96u16);
    let w = size.0 as usize;
    let (t, n, c) = hud(0);
    let (mut l1, mut l2, mut l3) = (
        DrawableLayer::new(t),
        DrawableLayer::new(n),
        DrawableLayer::new(c),
    );
    let mut box_layer = DrawableLayer::new(
        RoundedRectangle::with_equal_corners(
            Rectangle::new(Point::new(10, 70), Size::new(50, 20)),
            Size::new(6, 6),
        )
        .into_styled(PrimitiveStyle::with_fill(Rgb565::BLUE)),
    );
    let mut panel = Panel {
        width: w,
        pixels: vec![Rgb565::RED; w * size.1 as usize],
        rows: 0,
    };
    let mut band = vec![Rgb565::BLACK; 8 * w];
    let mut bits = [0u32; DirtyRows::words(96)];
    let bg = Rgb565::new(1, 2, 3);
    let mut pass = FramePass::new(size, bg);
    {
        let layers: &mut [&mut dyn Layer<Rgb565>] =
            &mut [&mut l1, &mut l2, &mut l3, &mut box_layer];
        pass.draw(layers, 8, &mut band, &mut panel).unwrap();
    }
    for step in 1..12 {
        let (t, n, c) = hud(step);
        l2.set(n);
        l3.set(c);
        if step % 3 == 0 {
            l1.set(t);
        }
        if step == 5 {
            box_layer.hide();
        }
        if step == 8 {
            box_layer.show();
        }
        let mut dirty = DirtyRows::new(&mut bits, size.1).unwrap();
        panel.rows = 0;
        let layers: &mut [&mut dyn Layer<Rgb565>] =
            &mut [&mut l1, &mut l2, &mut l3, &mut box_layer];
        let sent = pass
            .draw_marked(layers, &mut dirty, 8, &mut band, &mut panel)
            .unwrap();
        assert_eq!(sent, panel.rows);
        assert!(sent < size.1 as u32, "step {step}: only the changed rows");
        let mut want = vec![bg; panel.pixels.len()];
        let mut fb = FrameBuffer::new(&mut want, size.0, size.1).unwrap();
        l1.get().draw(&mut fb).unwrap();
        l2.get().draw(&mut fb).unwrap();
        l3.get().draw(&mut fb).unwrap();
        if box_layer.is_shown() {
            box_layer.get().draw(&mut fb).unwrap();
        }
        assert!(
            panel.pixels == want,
            "step {step}: the panel is the whole frame"
        );
    }
}

/// A random 2D command.
fn command() -> impl Strategy<Value = String> {
    let coord = |side: i32| (-4 * 16..(side + 4) * 16).prop_map(|u| u as f64 / 16.0);
    prop_oneof![
        1 => (0u32..0xffffff).prop_map(|c| format!("clear #{c:06x}")),
        2 => (-2i32..40, -2i32..30, 0i32..44, 0i32..34).prop_map(|(a, b, c, d)| format!("clip {a} {b} {c} {d}")),
        3 => (0u32..0xffffff).prop_map(|c| format!("color #{c:06x}")),
        8 => prop::collection::vec((coord(40), coord(30)), 3..7).prop_map(|v| {
            v.iter().fold(String::from("poly"), |s, (x, y)| format!("{s} {x} {y}"))
        }),
        5 => (coord(40), coord(30), coord(40), coord(30)).prop_map(|(a, b, c, d)| format!("line {a} {b} {c} {d}")),
    ]
}

fn text_of(cmds: &[String]) -> String {
    cmds.iter()
        .fold(String::from("frame 40 30\n"), |s, c| s + c + "\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    /// A list edited (a command replaced, inserted or removed): every row
    /// whose pixels changed is marked, and the panel, sent the marked
    /// rows only, is the edited list's frame.
    #[test]
    fn a_list_edit_marks_every_changed_row(
        cmds in prop::collection::vec(command(), 1..16),
        edit in (0usize..16, 0u8..3, command()),
        rows in 1u16..12,
    ) {
        let mut edited = cmds.clone();
        let at = edit.0 % cmds.len();
        match edit.1 {
            0 => edited[at] = edit.2,
            1 => edited.insert(at, edit.2),
            _ => { edited.remove(at); }
        }
        let (a, b) = (list_of(&text_of(&cmds)), list_of(&text_of(&edited)));
        let (la, lb) = (a.list(), b.list());
        let before = whole(&[&la], (40, 30), |_| {});
        let after = whole(&[&lb], (40, 30), |_| {});
        let mut bits = [0u32; 1];
        let mut dirty = DirtyRows::new(&mut bits, 30).unwrap();
        let mut scratch = [0u64; 60];
        lb.mark_changes(&la, &mut dirty, &mut scratch).unwrap();
        for y in 0..30usize {
            if before[y * 40..(y + 1) * 40] != after[y * 40..(y + 1) * 40] {
                prop_assert!(dirty.is_marked(y as u16), "row {} changed, not marked", y);
            }
        }
        // The pass sends `before` whole, then the marked rows of `after`.
        let mut panel = Panel { width: 40, pixels: vec![Rgb565::RED; 40 * 30], rows: 0 };
        let mut band = vec![Rgb565::BLACK; rows as usize * 40];
        let mut pass = FramePass::new((40, 30), Rgb565::BLACK);
        let mut mem = ListMemory::for_bands(&la).expect("sized");
        let (mut c, t) = mem.band_parts();
        let mut layer = c.bands(&la, t).expect("prepared");
        pass.draw(&mut [&mut layer], rows, &mut band, &mut panel).unwrap();
        prop_assert!(panel.pixels == before);
        let mut mem = ListMemory::for_bands(&lb).expect("sized");
        let (mut c, t) = mem.band_parts();
        let mut layer = c.bands(&lb, t).expect("prepared");
        pass.draw_marked(&mut [&mut layer], &mut dirty, rows, &mut band, &mut panel)
            .unwrap();
        prop_assert!(panel.pixels == after);
    }
}

#[test]
fn an_unchanged_list_marks_nothing_and_a_short_scratch_is_an_error() {
    let text = "frame 40 30\nclear #102030\ncolor #ff0000\npoly 1 1 30 4 9 20\nline 0 29 39 0\n";
    let (a, b) = (list_of(text), list_of(text));
    let mut bits = [0u32; 1];
    let mut dirty = DirtyRows::new(&mut bits, 30).unwrap();
    b.list()
        .mark_changes(&a.list(), &mut dirty, &mut [0u64; 60])
        .unwrap();
    assert_eq!(dirty.count(), 0);
    // One polygon moved down by 2 px: its rows before and after, a row
    // of margin each side, no more.
    let moved = list_of(&text.replace("poly 1 1 30 4 9 20", "poly 1 3 30 6 9 22"));
    moved
        .list()
        .mark_changes(&a.list(), &mut dirty, &mut [0u64; 60])
        .unwrap();
    let marked: Vec<u16> = (0..30).filter(|&y| dirty.is_marked(y)).collect();
    assert_eq!(marked.first(), Some(&0));
    assert!(marked.len() <= 24, "{marked:?}");
    assert_eq!(
        b.list()
            .mark_changes(&a.list(), &mut dirty, &mut [0u64; 59]),
        Err(ScratchTooSmall {
            len: 59,
            needed: 60
        })
    );
}

/// A drawable anchored at a 3D point lands where a label anchored there
/// does, moves with the view (its rows marked, old and new), and hides
/// when the point goes behind the eye.
#[test]
fn a_drawable_anchored_at_a_3d_point_follows_it() {
    use scanvert::geometry::{Angle, Perspective, Pipeline, Point3, View, Viewport, Q16};
    use scanvert::scene::label::to_pixels;
    let (w, h) = (96u16, 64u16);
    let persp = Perspective::from_fov(
        Angle::from_degrees(60),
        w,
        Q16::from_int(1),
        Q16::from_int(50),
    )
    .unwrap();
    let mut pipe = Pipeline::<4, 16>::new(persp, Viewport::centred(w, h).unwrap());
    let at = Point3::new(Q16::from_bits(40_000), Q16::from_int(1), Q16::from_int(-2));
    let marker = Rectangle::new(Point::zero(), Size::new(5, 3))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::YELLOW));
    let mut layer = DrawableLayer::new(marker);
    let mut bits = [0u32; DirtyRows::words(64)];
    let mut dirty = DirtyRows::new(&mut bits, h).unwrap();
    let mut origin = Point::zero();
    let mut panel = Panel {
        width: w as usize,
        pixels: vec![Rgb565::BLACK; w as usize * h as usize],
        rows: 0,
    };
    let mut band = vec![Rgb565::BLACK; 8 * w as usize];
    let mut pass = FramePass::new((w, h), Rgb565::BLACK);
    for (eye_x, eye_z) in [(0, 10), (3, 8), (-2, 12), (0, -5)] {
        pipe.set_view(
            &View::look_at(
                Point3::from_int(eye_x, 0, eye_z),
                Point3::from_int(0, 0, -20),
            )
            .unwrap(),
        )
        .unwrap();
        let before = origin;
        origin = layer.anchor(&pipe, at, origin);
        let a = pipe.project_point(at).unwrap();
        let mut want = vec![Rgb565::BLACK; w as usize * h as usize];
        if a.in_front {
            // The label's anchor, whole pixels: the marker's corner.
            let (x, y) = to_pixels(a);
            assert_eq!(origin, Point::new(x, y), "eye at ({eye_x}, {eye_z})");
            let mut fb = FrameBuffer::new(&mut want, w, h).unwrap();
            marker.translate(origin).draw(&mut fb).unwrap();
        } else {
            assert_eq!(origin, before, "behind the eye: the anchor stays");
        }
        dirty.clear();
        let layers: &mut [&mut dyn Layer<Rgb565>] = &mut [&mut layer];
        pass.draw_marked(layers, &mut dirty, 8, &mut band, &mut panel)
            .unwrap();
        assert!(panel.pixels == want, "eye at ({eye_x}, {eye_z})");
    }
}

/// A panel that refuses to be sent anything while `fail` is set.
struct Flaky {
    panel: Panel,
    fail: bool,
}

impl BandTarget for Flaky {
    type Color = Rgb565;
    type Error = ();
    fn ship(&mut self, y: u16, rows: u16, px: &[Rgb565]) -> Result<(), ()> {
        if self.fail {
            return Err(());
        }
        self.panel.ship(y, rows, px).map_err(|_| ())
    }
}

type Dot = embedded_graphics::primitives::Styled<Circle, PrimitiveStyle<Rgb565>>;

/// One frame of `layer` through `pass`, its marks only; checks that the
/// panel then shows the whole frame, and returns the rows sent.
fn marked_frame(
    pass: &mut FramePass<Rgb565>,
    layer: &mut DrawableLayer<Dot>,
    dirty: &mut DirtyRows<'_>,
    flaky: &mut Flaky,
) -> Result<u32, ()> {
    let (w, h) = pass.size();
    let mut band = vec![Rgb565::BLACK; 8 * w as usize];
    dirty.clear();
    flaky.panel.rows = 0;
    let sent = pass
        .draw_marked(&mut [&mut *layer], dirty, 8, &mut band, flaky)
        .map_err(|_| ())?;
    let mut want = vec![pass.background(); w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut want, w, h).unwrap();
    layer.get().draw(&mut fb).unwrap();
    assert!(flaky.panel.pixels == want, "the panel is the whole frame");
    assert_eq!(sent, flaky.panel.rows);
    Ok(sent)
}

/// The background is a change like any other: the pass marks every row
/// on its first frame, after its background changes and after a frame
/// that failed to reach the panel; otherwise only the layers' marks.
#[test]
fn the_pass_marks_the_background_its_first_frame_and_a_failed_one() {
    let (w, h) = (48u16, 40u16);
    let dot =
        |x| Circle::new(Point::new(x, 12), 7).into_styled(PrimitiveStyle::with_fill(Rgb565::RED));
    let mut layer = DrawableLayer::new(dot(4));
    let mut flaky = Flaky {
        panel: Panel {
            width: w as usize,
            pixels: vec![Rgb565::GREEN; w as usize * h as usize],
            rows: 0,
        },
        fail: false,
    };
    let mut bits = [0u32; DirtyRows::words(40)];
    let mut dirty = DirtyRows::new(&mut bits, h).unwrap();
    let mut pass = FramePass::new((w, h), Rgb565::BLACK);
    let mut frame =
        |pass: &mut FramePass<Rgb565>, layer: &mut DrawableLayer<Dot>, flaky: &mut Flaky| {
            marked_frame(pass, layer, &mut dirty, flaky)
        };
    // The first frame: the panel's pixels are unknown.
    assert_eq!(frame(&mut pass, &mut layer, &mut flaky), Ok(40));
    // Nothing changed: nothing is sent.
    assert_eq!(frame(&mut pass, &mut layer, &mut flaky), Ok(0));
    // The dot moves: the rows it was and is on only.
    layer.set(dot(20));
    assert_eq!(frame(&mut pass, &mut layer, &mut flaky), Ok(7));
    // The same background set again is no change.
    pass.set_background(Rgb565::BLACK);
    assert_eq!(frame(&mut pass, &mut layer, &mut flaky), Ok(0));
    // A new background: every row.
    pass.set_background(Rgb565::BLUE);
    assert_eq!(frame(&mut pass, &mut layer, &mut flaky), Ok(40));
    // A frame that fails, then one that is sent: every row again.
    layer.set(dot(30));
    flaky.fail = true;
    assert!(frame(&mut pass, &mut layer, &mut flaky).is_err());
    flaky.fail = false;
    assert_eq!(frame(&mut pass, &mut layer, &mut flaky), Ok(40));
}
