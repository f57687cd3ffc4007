//! The band of words (`PackedBand`, two RGB565 pixels a word in the
//! panel's wire order) against the band of pixels (`Band<Rgb565>`): every
//! span, rectangle and embedded-graphics drawing on odd and even widths
//! and band starts writes the same pixels, and the padding half of an
//! odd band is never written; every list under `scenes/` and
//! `firmware/image/scenes/` (and generated 2D and 3D lists), rendered in
//! bands of 1, 7 and 16 rows by both resolves, decodes to exactly the
//! pixels of the same render into `Band<Rgb565>`; a scene's pass does too.
//! The words are decoded here from their bytes as a panel reads them:
//! high byte first.

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle};
use embedded_graphics::text::Text;
use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use proptest::prelude::*;
use scanvert::port::band::{Band, BandError, BandTarget, BandsError};
use scanvert::port::packed_band::{PackedBand, PackedBandTarget};
use scanvert::port::{PackedFrameBuffer, RowRun, Span, SpanTarget};
use scanvert::scene::DEFAULT_FONT;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::cli::Scene;
use scanvert_sim::memory::ListMemory;
use std::path::{Path, PathBuf};

fn px(v: u16) -> Rgb565 {
    Rgb565::from(RawU16::new(v))
}

/// The pixels of wire bytes: each pixel high byte first.
fn decode(bytes: &[u8]) -> Vec<Rgb565> {
    bytes
        .chunks_exact(2)
        .map(|b| px(u16::from_be_bytes([b[0], b[1]])))
        .collect()
}

/// The bytes of words in little-endian memory order.
fn le_bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}

/// A band of pixels and a band of words over the same rows, both from
/// the same pattern; `f` draws the same into each. Asserts they hold the
/// same pixels and that the padding half of an odd band's last word and
/// the words after the band are untouched.
fn same<F: Fn(&mut dyn FnMut(&mut dyn Draw))>(
    w: u16,
    h: u16,
    y0: u16,
    rows: u16,
    f: F,
    what: &str,
) {
    same_but(w, h, y0, rows, f, what, false)
}

/// [`same`], the padding half allowed to change when `padding`.
fn same_but<F>(w: u16, h: u16, y0: u16, rows: u16, f: F, what: &str, padding: bool)
where
    F: Fn(&mut dyn FnMut(&mut dyn Draw)),
{
    let rows = rows.min(h - y0);
    let n = w as usize * rows as usize;
    let nw = PackedBand::<Rgb565>::words_len(w, rows);
    let pattern = |i: usize| px((i as u16).wrapping_mul(0x9e37) ^ 0x5aa5);
    let mut pixels: Vec<Rgb565> = (0..n).map(pattern).collect();
    let mut words = vec![0xdead_beefu32; nw + 2];
    for i in 0..n {
        let p = RawU16::from(pattern(i)).into_inner().swap_bytes() as u32;
        let shift = 16 * (i % 2);
        words[i / 2] = (words[i / 2] & !(0xffff << shift)) | (p << shift);
    }
    let mut band = Band::new(&mut pixels, (w, h), y0, rows).unwrap();
    f(&mut |d: &mut dyn Draw| d.pixels(&mut band));
    let mut packed = PackedBand::<Rgb565>::new(&mut words, (w, h), y0, rows).unwrap();
    f(&mut |d: &mut dyn Draw| d.words(&mut packed));
    assert!(packed.pixels().eq(pixels.iter().copied()), "{what}");
    let bytes = le_bytes(&words[..nw]);
    assert_eq!(decode(&bytes[..2 * n]), pixels, "{what}");
    if n % 2 == 1 && !padding {
        assert_eq!(words[nw - 1] >> 16, 0xdead, "padding half, {what}");
    }
    assert_eq!(words[nw..], [0xdead_beef; 2], "{what}");
}

/// One drawing, into either band.
trait Draw {
    fn pixels(&mut self, band: &mut Band<'_, Rgb565>);
    fn words(&mut self, band: &mut PackedBand<'_, Rgb565>);
}

/// A drawing through a generic function of the target.
struct With<F>(F);

impl<F> Draw for With<F>
where
    F: FnMut(&mut dyn Target),
{
    fn pixels(&mut self, band: &mut Band<'_, Rgb565>) {
        (self.0)(band)
    }
    fn words(&mut self, band: &mut PackedBand<'_, Rgb565>) {
        (self.0)(band)
    }
}

/// What a drawing uses of a band.
trait Target {
    fn span(&mut self, s: Span, c: Rgb565);
    fn inside(&mut self, s: Span, c: Rgb565);
    /// `inside` from the row's start (`row_start`, `fill_row_inside`).
    fn row(&mut self, s: Span, c: Rgb565);
    fn rect(&mut self, s: Span, h: u16, c: Rgb565);
    fn clear(&mut self, c: Rgb565);
    fn eg(&mut self) -> &mut dyn EgTarget;
}

trait EgTarget {
    fn solid(&mut self, r: &Rectangle, c: Rgb565);
    fn contiguous(&mut self, r: &Rectangle, cs: &[Rgb565]);
    fn shapes(&mut self);
}

macro_rules! target {
    ($t:ty) => {
        impl Target for $t {
            fn span(&mut self, s: Span, c: Rgb565) {
                self.fill_span(s, c).unwrap()
            }
            fn inside(&mut self, s: Span, c: Rgb565) {
                self.fill_span_inside(s, c).unwrap()
            }
            fn row(&mut self, s: Span, c: Rgb565) {
                let r = self.row_start(s.y);
                self.fill_row_inside(r, s.x0, s.x1, c).unwrap()
            }
            fn rect(&mut self, s: Span, h: u16, c: Rgb565) {
                self.fill_rect(s, h, c).unwrap()
            }
            fn clear(&mut self, c: Rgb565) {
                SpanTarget::clear(self, c).unwrap()
            }
            fn eg(&mut self) -> &mut dyn EgTarget {
                self
            }
        }
        impl EgTarget for $t {
            fn solid(&mut self, r: &Rectangle, c: Rgb565) {
                self.fill_solid(r, c).unwrap()
            }
            fn contiguous(&mut self, r: &Rectangle, cs: &[Rgb565]) {
                self.fill_contiguous(r, cs.iter().copied()).unwrap()
            }
            fn shapes(&mut self) {
                let style = MonoTextStyle::new(&FONT_6X10, Rgb565::YELLOW);
                Text::new("Hg", Point::new(1, 8), style).draw(self).unwrap();
                Circle::new(Point::new(-2, 1), 9)
                    .into_styled(PrimitiveStyle::with_stroke(Rgb565::CYAN, 1))
                    .draw(self)
                    .unwrap();
            }
        }
    };
}
target!(Band<'_, Rgb565>);
target!(PackedBand<'_, Rgb565>);

const SIZES: [(u16, u16); 6] = [(1, 4), (2, 3), (5, 4), (7, 5), (8, 3), (13, 4)];

/// Every span (odd and even starts and ends, past the end of the row,
/// on every row and off the band) and every clipped-inside span, also
/// written from its row's start.
#[test]
fn every_span_writes_what_a_band_of_pixels_writes() {
    for (w, h) in SIZES {
        for y0 in 0..h {
            for rows in 1..=h - y0 {
                for y in 0..h + 1 {
                    for x0 in 0..w + 1 {
                        for x1 in x0..w + 2 {
                            let c = px(x0 * 977 + x1 * 131 + y * 7);
                            let s = Span { y, x0, x1 };
                            let what = format!("{w}x{h} band {y0}+{rows} span {s:?}");
                            same(
                                w,
                                h,
                                y0,
                                rows,
                                |d| d(&mut With(|t: &mut dyn Target| t.span(s, c))),
                                &what,
                            );
                            if y < h && x0 < x1 && x1 <= w {
                                // A row below the band may write the
                                // padding half, which is no pixel.
                                let below = y >= y0 + rows;
                                same_but(
                                    w,
                                    h,
                                    y0,
                                    rows,
                                    |d| d(&mut With(|t: &mut dyn Target| t.inside(s, c))),
                                    &what,
                                    below,
                                );
                                same_but(
                                    w,
                                    h,
                                    y0,
                                    rows,
                                    |d| d(&mut With(|t: &mut dyn Target| t.row(s, c))),
                                    &what,
                                    below,
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

/// Every rectangle, clear, and embedded-graphics drawing.
#[test]
fn rectangles_clears_and_drawings_write_what_a_band_of_pixels_writes() {
    for (w, h) in SIZES {
        for y0 in 0..h {
            for rows in 1..=h - y0 {
                let what = format!("{w}x{h} band {y0}+{rows}");
                same(
                    w,
                    h,
                    y0,
                    rows,
                    |d| d(&mut With(|t: &mut dyn Target| t.clear(px(0x1234)))),
                    &what,
                );
                same(
                    w,
                    h,
                    y0,
                    rows,
                    |d| d(&mut With(|t: &mut dyn Target| t.eg().shapes())),
                    &what,
                );
                for y in 0..h + 1 {
                    for height in 0..h + 2 - y {
                        for x0 in 0..w + 1 {
                            for x1 in x0..w + 2 {
                                let c = px(x0 * 977 + x1 * 131 + y * 7 + height);
                                let s = Span { y, x0, x1 };
                                let what = format!("{what} rect {s:?} x{height}");
                                same(
                                    w,
                                    h,
                                    y0,
                                    rows,
                                    |d| d(&mut With(|t: &mut dyn Target| t.rect(s, height, c))),
                                    &what,
                                );
                                let r = Rectangle::new(
                                    Point::new(x0 as i32 - 1, y as i32 - 1),
                                    Size::new((x1 - x0) as u32, height as u32),
                                );
                                let cs: Vec<Rgb565> = (0..64)
                                    .map(|i| px([0x1111, 0x2222, 0xf00f][i % 3 / 2 + i % 2]))
                                    .collect();
                                same(
                                    w,
                                    h,
                                    y0,
                                    rows,
                                    |d| d(&mut With(|t: &mut dyn Target| t.eg().solid(&r, c))),
                                    &what,
                                );
                                same(
                                    w,
                                    h,
                                    y0,
                                    rows,
                                    |d| {
                                        d(&mut With(|t: &mut dyn Target| {
                                            t.eg().contiguous(&r, &cs)
                                        }))
                                    },
                                    &what,
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn bad_bands_are_the_errors_of_a_band_of_pixels() {
    let mut words = [0u32; 5];
    let new = |words: &mut [u32], y0, rows| {
        PackedBand::<Rgb565>::new(words, (3, 8), y0, rows).map(|b| (b.y(), b.rows(), b.end()))
    };
    assert_eq!(new(&mut words, 0, 0), Err(BandError::NoRows));
    assert_eq!(
        new(&mut words, 8, 1),
        Err(BandError::Outside { y: 8, height: 8 })
    );
    // 4 rows of 3: 12 pixels, 6 words; 5 hold 10 pixels.
    assert_eq!(
        new(&mut words, 0, 4),
        Err(BandError::Buffer {
            len: 10,
            needed: 12
        })
    );
    // 3 rows: 9 pixels in 5 words; cut at the frame's end.
    assert_eq!(new(&mut words, 0, 3), Ok((0, 3, 3)));
    assert_eq!(new(&mut words, 6, 9), Ok((6, 2, 8)));
}

/// Bands of words shipped into a whole image, decoded from their bytes,
/// checking they come top to bottom with the words the band holds.
struct Collect {
    width: usize,
    pixels: Vec<Rgb565>,
    next: u16,
}

impl PackedBandTarget for Collect {
    type Color = Rgb565;
    type Error = ();
    fn ship_words(&mut self, y: u16, rows: u16, width: u16, words: &[u32]) -> Result<(), ()> {
        assert_eq!(y, self.next, "bands in order, none missing");
        assert_eq!(width as usize, self.width);
        let n = rows as usize * self.width;
        assert_eq!(words.len(), n.div_ceil(2));
        self.pixels.extend(decode(&le_bytes(words)[..2 * n]));
        self.next = y + rows;
        Ok(())
    }
}

/// Bands of pixels shipped into a whole image.
struct CollectPixels(Vec<Rgb565>);

impl BandTarget for CollectPixels {
    type Color = Rgb565;
    type Error = ();
    fn ship(&mut self, _: u16, _: u16, px: &[Rgb565]) -> Result<(), ()> {
        self.0.extend_from_slice(px);
        Ok(())
    }
}

/// The list rendered in bands of `rows` into pixels and into words.
fn both(s: &Scene, rows: u16, mode: Resolve) -> (Vec<Rgb565>, Vec<Rgb565>) {
    let list = s.list();
    let (w, h) = (list.width(), list.height());
    let band_rows = rows.min(h) as usize;
    let mut memory = ListMemory::for_bands(&list).expect("memory");
    let (c, table) = memory.band_parts();
    let mut pixels = CollectPixels(Vec::new());
    let mut band = vec![Rgb565::BLACK; band_rows * w as usize];
    c.with_resolve(mode)
        .render_bands(&list, table, rows, &mut band, &mut pixels)
        .expect("pixel bands");
    let mut memory = ListMemory::for_bands(&list).expect("memory");
    let (c, table) = memory.band_parts();
    let mut words = vec![0u32; (band_rows * w as usize).div_ceil(2)];
    let mut out = Collect {
        width: w as usize,
        pixels: Vec::new(),
        next: 0,
    };
    c.with_resolve(mode)
        .render_bands_packed(&list, table, rows, &mut words, &mut out)
        .expect("word bands");
    assert_eq!(out.next, h);
    (pixels.0, out.pixels)
}

fn lists_under(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("scenes") {
        let p = e.expect("entry").path();
        if p.is_dir() {
            lists_under(&p, out);
        } else if p.extension().is_some_and(|x| x == "dl" || x == "scvl") {
            out.push(p);
        }
    }
}

#[test]
fn every_repository_list_is_the_same_in_bands_of_words() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    lists_under(&root.join("scenes"), &mut files);
    lists_under(&root.join("firmware/image/scenes"), &mut files);
    assert!(files.len() >= 20, "{files:?}");
    for f in files {
        let s = Scene::load(&f).expect("loads");
        for mode in [Resolve::Crossing, Resolve::Paint] {
            for rows in [1, 7, 16] {
                let (a, b) = both(&s, rows, mode);
                let diff = a.iter().zip(&b).filter(|(p, q)| p != q).count();
                assert!(
                    a.len() == b.len() && diff == 0,
                    "{} rows {rows} {mode:?}: {diff} differ",
                    f.display()
                );
            }
        }
    }
}

#[test]
fn a_short_buffer_of_words_is_refused_before_drawing() {
    let s = Scene::from_bytes(
        Path::new("w.dl"),
        b"frame 5 4\ncolor #ff0000\npoly 0 0 5 0 5 4\n".to_vec(),
    )
    .expect("scene");
    let list = s.list();
    let mut memory = ListMemory::for_bands(&list).expect("memory");
    let (mut c, table) = memory.band_parts();
    // 3 rows of 5: 15 pixels, 8 words.
    let mut words = [0u32; 7];
    let mut out = Collect {
        width: 5,
        pixels: Vec::new(),
        next: 0,
    };
    let e = c
        .render_bands_packed(&list, table, 3, &mut words, &mut out)
        .unwrap_err();
    assert_eq!(
        e,
        BandsError::Band(BandError::Buffer {
            len: 14,
            needed: 15
        })
    );
    assert!(out.pixels.is_empty());
}

/// The demo scene's pass, band by band into words and into pixels.
#[test]
fn a_scenes_pass_is_the_same_in_bands_of_words() {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let w = WIDTH as usize;
    for step in steps(8).into_iter().step_by(3) {
        with_scene(step, |scene, bg| {
            for rows in [1u16, 7, 16] {
                let mut pixels = Vec::new();
                let mut band = vec![Rgb565::BLACK; rows as usize * w];
                {
                    let mut pass = scene.bands(Resolve::Paint, bg, DEFAULT_FONT).expect("pass");
                    let mut y = 0;
                    while y < HEIGHT {
                        let n = pass.draw(y, rows, &mut band).expect("band");
                        pixels.extend_from_slice(&band[..n as usize * w]);
                        y += n;
                    }
                }
                let mut got = Vec::new();
                let mut words = vec![0u32; (rows as usize * w).div_ceil(2)];
                let mut pass = scene.bands(Resolve::Paint, bg, DEFAULT_FONT).expect("pass");
                let mut y = 0;
                while y < HEIGHT {
                    let n = pass.draw_packed(y, rows, &mut words).expect("band");
                    got.extend(decode(&le_bytes(&words)[..2 * n as usize * w]));
                    y += n;
                }
                assert!(got == pixels, "{step:?} rows {rows}");
            }
        })
        .expect("demo scene");
    }
}

/// A random list in text form at an odd or even width: clears, clip
/// windows, colours, polygons, lines and 3D faces.
fn list_text() -> impl Strategy<Value = String> {
    let coord = |side: i32| (-8 * 16..(side + 8) * 16).prop_map(|u| u as f64 / 16.0);
    let poly = prop::collection::vec((coord(48), coord(32)), 3..9).prop_map(|v| {
        let mut s = String::from("poly");
        for (x, y) in v {
            s += &format!(" {x} {y}");
        }
        s
    });
    let line = (coord(48), coord(32), coord(48), coord(32))
        .prop_map(|(a, b, c, d)| format!("line {a} {b} {c} {d}"));
    let face = prop::collection::vec((coord(48), coord(32), 1i32..200), 3..6).prop_map(|v| {
        let mut s = String::from("poly3");
        for (x, y, z) in v {
            s += &format!(" {x} {y} {}", z as f64 / 8.0);
        }
        s
    });
    let cmd = prop_oneof![
        1 => (0u32..0xffffff).prop_map(|c| format!("clear #{c:06x}")),
        2 => (-5i32..50, -5i32..35, -5i32..55, -5i32..40)
            .prop_map(|(a, b, c, d)| format!("clip {a} {b} {c} {d}")),
        3 => (0u32..0xffffff).prop_map(|c| format!("color #{c:06x}")),
        6 => poly,
        4 => line,
    ];
    let faces = prop::collection::vec(
        (
            (0u32..0xffffff).prop_map(|c| format!("color #{c:06x}")),
            face,
        ),
        0..8,
    );
    (
        1u16..=48,
        1u16..=32,
        prop::collection::vec(cmd, 0..16),
        faces,
    )
        .prop_map(|(w, h, cmds, faces)| {
            let mut s = format!("frame {w} {h}\n");
            for c in cmds {
                s += &c;
                s.push('\n');
            }
            for (c, f) in faces {
                s += &format!("{c}\n{f}\n");
            }
            s
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn generated_lists_are_the_same_in_bands_of_words(
        text in list_text(),
        rows in prop_oneof![Just(1u16), Just(7), Just(16), 1u16..40],
        paint in any::<bool>(),
    ) {
        let s = Scene::from_bytes(Path::new("gen.dl"), text.as_bytes().to_vec());
        // Lists the reader refuses (a 3D face after 2D needing a plane it
        // cannot have, say) are not this test's matter.
        if let Ok(s) = s {
            let mode = if paint { Resolve::Paint } else { Resolve::Crossing };
            let (a, b) = both(&s, rows, mode);
            prop_assert!(a == b, "{}", text);
        }
    }
}

/// Bands of pixels shipped into a panel that keeps its pixels.
struct PixelPanel(Vec<Rgb565>, usize);

impl BandTarget for PixelPanel {
    type Color = Rgb565;
    type Error = ();
    fn ship(&mut self, y: u16, _: u16, px: &[Rgb565]) -> Result<(), ()> {
        let at = y as usize * self.1;
        self.0[at..at + px.len()].copy_from_slice(px);
        Ok(())
    }
}

/// Bands of words shipped into a panel that keeps its pixels, decoded
/// from their bytes.
struct WordPanel(Vec<Rgb565>, usize);

impl PackedBandTarget for WordPanel {
    type Color = Rgb565;
    type Error = ();
    fn ship_words(&mut self, y: u16, rows: u16, width: u16, words: &[u32]) -> Result<(), ()> {
        assert_eq!(width as usize, self.1);
        let n = rows as usize * self.1;
        let at = y as usize * self.1;
        self.0[at..at + n].copy_from_slice(&decode(&le_bytes(words)[..2 * n]));
        Ok(())
    }
}

/// A frame pass over a scene and two drawables, whole and by its marked
/// rows, into words and into pixels: the same panel after every frame.
#[test]
fn a_frame_pass_of_layers_is_the_same_in_bands_of_words() {
    use scanvert::frame::{DrawableLayer, FramePass, Layer, PackedLayer};
    use scanvert::port::band::DirtyRows;
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let w = WIDTH as usize;
    let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
    let dot =
        |x| Circle::new(Point::new(x, 41), 9).into_styled(PrimitiveStyle::with_fill(Rgb565::RED));
    for rows in [1u16, 7, 16] {
        let mut clock_a = DrawableLayer::new(Text::new("12:00", Point::new(3, 10), style));
        let mut clock_b = DrawableLayer::new(Text::new("12:00", Point::new(3, 10), style));
        let mut dot_a = DrawableLayer::new(dot(11));
        let mut dot_b = DrawableLayer::new(dot(11));
        let mut pass_a = FramePass::new((WIDTH, HEIGHT), Rgb565::BLUE);
        let mut pass_b = FramePass::new((WIDTH, HEIGHT), Rgb565::BLUE);
        let mut pixels = PixelPanel(vec![Rgb565::BLACK; w * HEIGHT as usize], w);
        let mut words = WordPanel(vec![Rgb565::BLACK; w * HEIGHT as usize], w);
        let mut band = vec![Rgb565::BLACK; rows as usize * w];
        let mut band_words = vec![0u32; (rows as usize * w).div_ceil(2)];
        for (k, step) in steps(3).into_iter().enumerate() {
            with_scene(step, |scene, bg| {
                let mut s = scene.bands(Resolve::Paint, bg, DEFAULT_FONT).expect("pass");
                {
                    let mut layers: [&mut dyn Layer<Rgb565>; 3] =
                        [&mut s, &mut clock_a, &mut dot_a];
                    if k == 0 {
                        pass_a
                            .draw(&mut layers, rows, &mut band, &mut pixels)
                            .expect("pixels");
                    } else {
                        let mut bits = [0u32; DirtyRows::words(HEIGHT)];
                        let mut dirty = DirtyRows::new(&mut bits, HEIGHT).unwrap();
                        dirty.mark(30, 90);
                        pass_a
                            .draw_marked(&mut layers, &mut dirty, rows, &mut band, &mut pixels)
                            .expect("pixels");
                    }
                }
                let mut s = scene.bands(Resolve::Paint, bg, DEFAULT_FONT).expect("pass");
                let mut layers: [&mut dyn PackedLayer<Rgb565>; 3] =
                    [&mut s, &mut clock_b, &mut dot_b];
                if k == 0 {
                    pass_b
                        .draw_packed(&mut layers, rows, &mut band_words, &mut words)
                        .expect("words");
                } else {
                    let mut bits = [0u32; DirtyRows::words(HEIGHT)];
                    let mut dirty = DirtyRows::new(&mut bits, HEIGHT).unwrap();
                    dirty.mark(30, 90);
                    pass_b
                        .draw_marked_packed(
                            &mut layers,
                            &mut dirty,
                            rows,
                            &mut band_words,
                            &mut words,
                        )
                        .expect("words");
                }
            })
            .expect("demo scene");
            assert!(pixels.0 == words.0, "rows {rows}, frame {k}");
            dot_a.set(dot(20 + 9 * k as i32));
            dot_b.set(dot(20 + 9 * k as i32));
        }
    }
}

/// A row's runs as `(length, colour)` from a start column, cut at the
/// width: the `RowRun`s handed in one call.
fn runs_of(x0: u16, width: u16, parts: &[(u16, u16)]) -> Vec<RowRun<Rgb565>> {
    let (mut runs, mut x) = (Vec::new(), x0);
    for &(len, c) in parts {
        let x1 = (x + len).min(width);
        if x1 <= x {
            break;
        }
        runs.push(RowRun { x1, color: px(c) });
        x = x1;
    }
    runs
}

/// The spans that `runs` from `x0` stand for.
fn spans_of(x0: u16, runs: &[RowRun<Rgb565>]) -> Vec<(u16, u16, Rgb565)> {
    let mut x = x0;
    runs.iter()
        .map(|r| {
            let s = (x, r.x1, r.color);
            x = r.x1;
            s
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, failure_persistence: None, ..ProptestConfig::default() })]

    /// `fill_runs_inside` of the packed band and the packed frame: the
    /// words of one call are those of a `fill_span_inside` a run, on odd
    /// and even widths, band starts and columns, over words as they were
    /// (the half-words next to the row's ends kept).
    #[test]
    fn a_rows_runs_in_one_call_write_what_a_span_each_writes(
        width in 1u16..48,
        (y0, rows, row) in (0u16..3, 1u16..4).prop_flat_map(|(y0, rows)| (Just(y0), Just(rows), y0..y0 + rows)),
        start in 0u16..48,
        parts in prop::collection::vec((1u16..12, any::<u16>()), 1..20),
        seed in any::<u32>(),
    ) {
        let x0 = start % width;
        let runs = runs_of(x0, width, &parts);
        let spans = spans_of(x0, &runs);
        let height = y0 + rows;
        let n = PackedBand::<Rgb565>::words_len(width, rows);
        let words: Vec<u32> = (0..n as u32).map(|i| seed.rotate_left(i).wrapping_mul(0x9e37_79b9)).collect();
        let (mut one, mut each) = (words.clone(), words.clone());
        PackedBand::<Rgb565>::new(&mut one, (width, height), y0, rows)
            .unwrap()
            .fill_runs_inside(row, x0, &runs)
            .unwrap();
        let mut band = PackedBand::<Rgb565>::new(&mut each, (width, height), y0, rows).unwrap();
        for &(a, b, c) in &spans {
            band.fill_span_inside(Span { y: row, x0: a, x1: b }, c).unwrap();
        }
        prop_assert_eq!(one, each);

        let n = PackedFrameBuffer::<Rgb565>::words_len(width, height);
        let words: Vec<u32> = (0..n as u32).map(|i| seed.rotate_right(i).wrapping_mul(0x85eb_ca6b)).collect();
        let (mut one, mut each) = (words.clone(), words.clone());
        PackedFrameBuffer::<Rgb565>::new(&mut one, width, height)
            .unwrap()
            .fill_runs_inside(row, x0, &runs)
            .unwrap();
        let mut frame = PackedFrameBuffer::<Rgb565>::new(&mut each, width, height).unwrap();
        for &(a, b, c) in &spans {
            frame.fill_span_inside(Span { y: row, x0: a, x1: b }, c).unwrap();
        }
        prop_assert_eq!(one, each);
    }

    /// Runs that break `fill_runs_inside`'s conditions (ends going back,
    /// past the width, empty, rows off the band or the frame) write
    /// inside the words and never panic.
    #[test]
    fn wrong_runs_never_panic(
        width in 1u16..20,
        y in 0u16..12,
        x0 in 0u16..40,
        ends in prop::collection::vec(0u16..60, 0..12),
    ) {
        let runs: Vec<RowRun<Rgb565>> = ends.iter().map(|&x1| RowRun { x1, color: Rgb565::RED }).collect();
        let mut words = vec![0u32; PackedBand::<Rgb565>::words_len(width, 3)];
        let mut band = PackedBand::<Rgb565>::new(&mut words, (width, 8), 2, 3).unwrap();
        band.fill_runs_inside(y, x0, &runs).unwrap();
        let mut words = vec![0u32; PackedFrameBuffer::<Rgb565>::words_len(width, 4)];
        let mut frame = PackedFrameBuffer::<Rgb565>::new(&mut words, width, 4).unwrap();
        frame.fill_runs_inside(y, x0, &runs).unwrap();
    }
}
