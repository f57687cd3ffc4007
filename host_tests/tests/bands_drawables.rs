//! embedded-graphics drawables into bands: every primitive, font and
//! image drawn into each band of a pass gives, row for row, what
//! embedded-graphics draws into a whole frame.
//!
//! The reference is a plain `Vec` frame with a `DrawTarget` written here
//! (one pixel at a time, no clipping shortcut), not the library's frame
//! buffer, so that both of the library's paths are checked against an
//! independent one.

use embedded_graphics::image::{Image, ImageRaw};
use embedded_graphics::mono_font::ascii::{FONT_10X20, FONT_6X10};
use embedded_graphics::mono_font::MonoTextStyle;
use embedded_graphics::pixelcolor::raw::LittleEndian;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{
    Circle, Ellipse, Line, PrimitiveStyle, PrimitiveStyleBuilder, Rectangle, RoundedRectangle,
    Triangle,
};
use embedded_graphics::text::Text;
use embedded_graphics_core::pixelcolor::Rgb565;
use scanvert::port::band::Band;
use scanvert::port::framebuffer::FrameBuffer;

const W: u16 = 96;
const H: u16 = 64;
const BG: Rgb565 = Rgb565::new(2, 4, 6);

/// A frame that takes every pixel on its own.
struct Reference {
    px: Vec<Rgb565>,
}

impl OriginDimensions for Reference {
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl DrawTarget for Reference {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            if (0..W as i32).contains(&p.x) && (0..H as i32).contains(&p.y) {
                self.px[p.y as usize * W as usize + p.x as usize] = c;
            }
        }
        Ok(())
    }
}

/// A 12×8 image, its pixels all different, in RGB565 little-endian.
fn image_bytes() -> Vec<u8> {
    (0..12 * 8u16)
        .flat_map(|i| (i.wrapping_mul(2654) ^ 0x5a5a).to_le_bytes())
        .collect()
}

/// Draws the scene (text in two fonts, a circle, a rounded rectangle, an
/// image, and more, some partly off the frame) into `d`, at an offset.
fn scene<D: DrawTarget<Color = Rgb565>>(d: &mut D, (dx, dy): (i32, i32), img: &[u8]) {
    let at = |x: i32, y: i32| Point::new(x + dx, y + dy);
    let ok = |r: Result<_, D::Error>| assert!(r.is_ok());
    let small = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
    let large = MonoTextStyle::new(&FONT_10X20, Rgb565::YELLOW);
    ok(Text::new("Hello, band!", at(3, 9), small)
        .draw(d)
        .map(|_| ()));
    ok(Text::new("42 °C", at(30, 40), large).draw(d).map(|_| ()));
    ok(Circle::new(at(50, 5), 30)
        .into_styled(
            PrimitiveStyleBuilder::new()
                .fill_color(Rgb565::RED)
                .stroke_color(Rgb565::GREEN)
                .stroke_width(3)
                .build(),
        )
        .draw(d));
    ok(RoundedRectangle::with_equal_corners(
        Rectangle::new(at(-6, 30), Size::new(40, 28)),
        Size::new(9, 9),
    )
    .into_styled(PrimitiveStyle::with_fill(Rgb565::BLUE))
    .draw(d));
    let raw: ImageRaw<Rgb565, LittleEndian> = ImageRaw::new(img, 12);
    ok(Image::new(&raw, at(80, 55)).draw(d));
    ok(Image::new(&raw, at(10, 20)).draw(d));
    ok(Ellipse::new(at(60, 30), Size::new(40, 12))
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::CYAN, 1))
        .draw(d));
    ok(Line::new(at(0, 63), at(95, 0))
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::MAGENTA, 2))
        .draw(d));
    ok(Triangle::new(at(70, 60), at(90, 40), at(99, 70))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::CSS_ORANGE))
        .draw(d));
    ok(Rectangle::new(at(40, -5), Size::new(8, 200))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::CSS_PURPLE))
        .draw(d));
}

/// The scene through bands of `rows` rows: each band cleared, drawn, and
/// its rows copied out.
fn in_bands(rows: u16, off: (i32, i32), img: &[u8]) -> Vec<Rgb565> {
    let mut out = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut buf = vec![Rgb565::BLACK; rows as usize * W as usize];
    let mut y = 0;
    while y < H {
        let mut band = Band::new(&mut buf, (W, H), y, rows).unwrap();
        band.clear(BG).unwrap();
        scene(&mut band, off, img);
        let (start, n) = (band.y() as usize * W as usize, band.pixels().len());
        out[start..start + n].copy_from_slice(band.pixels());
        y = band.end();
    }
    out
}

#[test]
fn drawables_in_bands_equal_a_full_frame() {
    let img = image_bytes();
    for off in [(0, 0), (-7, 13), (20, -9), (3, 1)] {
        let mut reference = Reference {
            px: vec![BG; W as usize * H as usize],
        };
        scene(&mut reference, off, &img);
        // The library's own frame buffer, as embedded-graphics draws into it.
        let mut fb_px = vec![BG; W as usize * H as usize];
        let mut fb = FrameBuffer::new(&mut fb_px, W, H).unwrap();
        scene(&mut fb, off, &img);
        assert!(fb_px == reference.px, "frame buffer, offset {off:?}");
        for rows in [1, 7, 16, H, H + 5] {
            let got = in_bands(rows, off, &img);
            let bad = got
                .iter()
                .zip(&reference.px)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(bad, 0, "bands of {rows} rows, offset {off:?}");
        }
    }
}

/// A band no drawable reaches keeps its background, and a drawing whose
/// rectangle misses the band writes nothing.
#[test]
fn a_band_keeps_only_its_rows() {
    let mut buf = vec![BG; 4 * W as usize];
    let mut band = Band::new(&mut buf, (W, H), 20, 4).unwrap();
    Rectangle::new(Point::new(0, 0), Size::new(W as u32, 20))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::RED))
        .draw(&mut band)
        .unwrap();
    Rectangle::new(Point::new(0, 24), Size::new(W as u32, 40))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::RED))
        .draw(&mut band)
        .unwrap();
    assert!(band.pixels().iter().all(|&c| c == BG));
    Rectangle::new(Point::new(5, 10), Size::new(3, 12))
        .into_styled(PrimitiveStyle::with_fill(Rgb565::RED))
        .draw(&mut band)
        .unwrap();
    let red: Vec<_> = (0..4 * W as usize)
        .filter(|&i| band.pixels()[i] == Rgb565::RED)
        .map(|i| (i % W as usize, 20 + i / W as usize))
        .collect();
    assert_eq!(red, [(5, 20), (6, 20), (7, 20), (5, 21), (6, 21), (7, 21)]);
    assert_eq!(
        band.bounding_box(),
        Rectangle::new(Point::zero(), Size::new(W as u32, H as u32))
    );
}
