//! The port to embedded-graphics, both ways.
//!
//! - [`DrawTargetPort`] lets the controller render into any
//!   embedded-graphics [`DrawTarget`], such as a display driver. Every span
//!   becomes one [`fill_solid`](DrawTarget::fill_solid) of a one-row
//!   rectangle, so the driver receives rectangles (one address window and
//!   one burst of pixels each), never single pixels: about one call per
//!   span. A row of run-length runs, as a shaded renderer emits them,
//!   becomes one [`fill_contiguous`](DrawTarget::fill_contiguous) with
//!   [`fill_run_row`].
//! - [`FrameBuffer`] is a [`DrawTarget`], so that embedded-graphics
//!   primitives, images and text can be drawn into the same frame as a
//!   scene.
//!
//! ```
//! use embedded_graphics_core::draw_target::DrawTarget;
//! use embedded_graphics_core::geometry::{Point, Size};
//! use embedded_graphics_core::primitives::Rectangle;
//! use scanvert::prelude::*;
//! use scanvert::DrawTargetPort;
//!
//! let mut bytes = [0u8; 64];
//! let mut w = Writer::new(&mut bytes, 32, 16)?;
//! w.color(Rgb888::RED)?;
//! w.poly([(2, 2), (30, 8), (4, 14)].map(|(x, y)| Vertex::from_px(x, y).unwrap()))?;
//! let list = DisplayList::new_checked(w.finish()).unwrap();
//! let mut edges = [Edge::EMPTY; 8];
//!
//! // Any DrawTarget will do; here it is scanvert's own frame buffer.
//! let mut pixels = [Rgb565::BLACK; 32 * 16];
//! let mut fb = FrameBuffer::new(&mut pixels, 32, 16).unwrap();
//! let mut port = DrawTargetPort::new(&mut fb);
//! Controller::new(Rasterizer::new(&mut edges)).render(&list, &mut port).unwrap();
//!
//! // And embedded-graphics draws into the same frame.
//! fb.fill_solid(&Rectangle::new(Point::new(0, 0), Size::new(4, 4)), Rgb565::GREEN).unwrap();
//! assert_eq!(fb.pixel(10, 8), Some(Rgb565::RED));
//! assert_eq!(fb.pixel(1, 1), Some(Rgb565::GREEN));
//! # Ok::<(), scanvert::display_list::WriteError>(())
//! ```
//!
//! # Method names
//! [`FrameBuffer`] has two `size` methods ([`SpanTarget::size`] and
//! [`OriginDimensions::size`]) and two `clear` methods
//! ([`SpanTarget::clear`] and [`DrawTarget::clear`]). Where both traits
//! are in scope, name the one meant: `DrawTarget::clear(&mut fb, c)`. Both
//! `clear`s write the same pixels.

use crate::port::framebuffer::{FrameBuffer, MAX_SIDE};
use crate::port::{Span, SpanTarget};
use core::convert::Infallible;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// A [`SpanTarget`] over any embedded-graphics [`DrawTarget`], borrowed:
/// spans become [`fill_solid`](DrawTarget::fill_solid) calls.
///
/// The port borrows the target (`DrawTargetPort::new(&mut display)`), so
/// the display stays the caller's and can be drawn into directly again
/// once the port is dropped.
///
/// Frame pixel `(x, y)` is the target's point `(x, y)`. The frame is the
/// target's bounding box extended to the origin: from `(0, 0)` to the
/// box's bottom-right corner, each side cut to 0..=4096
/// ([`MAX_SIDE`]). Pixels outside the box are discarded by the target,
/// as every `DrawTarget` must.
#[derive(Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DrawTargetPort<'d, D: ?Sized> {
    target: &'d mut D,
}

impl<'d, D: DrawTarget + ?Sized> DrawTargetPort<'d, D> {
    /// A port into `target`.
    pub fn new(target: &'d mut D) -> Self {
        DrawTargetPort { target }
    }

    /// The target.
    pub fn get_ref(&self) -> &D {
        self.target
    }

    /// The target, for drawing into it directly.
    pub fn get_mut(&mut self) -> &mut D {
        self.target
    }

    /// The borrow of the target, for the rest of its lifetime.
    pub fn into_inner(self) -> &'d mut D {
        self.target
    }

    /// Writes one row of run-length runs with one
    /// [`fill_contiguous`](DrawTarget::fill_contiguous): see
    /// [`fill_run_row`].
    pub fn fill_run_row<I>(&mut self, y: u16, x0: u16, runs: I) -> Result<(), D::Error>
    where
        I: IntoIterator<Item = (u16, D::Color)>,
        I::IntoIter: Clone,
    {
        fill_run_row(self.target, y, x0, runs)
    }
}

/// One side of the frame: from 0 to the far edge of the box, cut to
/// 0..=4096. `origin` is an `i32` and `extent` a `u32`, so their sum is
/// done in `i64`, where it cannot overflow.
fn side(origin: i32, extent: u32) -> u16 {
    let end = (origin as i64 + extent as i64).clamp(0, MAX_SIDE as i64);
    end as u16
}

impl<D: DrawTarget + ?Sized> SpanTarget for DrawTargetPort<'_, D> {
    type Color = D::Color;
    type Error = D::Error;
    /// A display's window: every pixel written reaches it.
    const OVERDRAW_IS_CHEAP: bool = false;

    fn size(&self) -> (u16, u16) {
        let b = self.target.bounding_box();
        (
            side(b.top_left.x, b.size.width),
            side(b.top_left.y, b.size.height),
        )
    }

    /// One `fill_solid` of the one-row rectangle of `span`; nothing for an
    /// empty span.
    #[inline]
    fn fill_span(&mut self, span: Span, color: D::Color) -> Result<(), D::Error> {
        if span.is_empty() {
            return Ok(());
        }
        let area = Rectangle::new(
            Point::new(span.x0 as i32, span.y as i32),
            Size::new(span.len() as u32, 1),
        );
        self.target.fill_solid(&area, color)
    }

    /// The target's own [`clear`](DrawTarget::clear): one call.
    fn clear(&mut self, color: D::Color) -> Result<(), D::Error> {
        self.target.clear(color)
    }
}

/// Writes a row of run-length runs, `(length, colour)` from left to
/// right starting at `(x0, y)`, to `target` with a single
/// [`fill_contiguous`](DrawTarget::fill_contiguous) of the one-row
/// rectangle the runs cover, so a display driver sets one address window
/// for the whole row.
///
/// Runs of length 0 are skipped. The lengths are summed in a `u32` with
/// saturation (at most 65,535 runs of 65,535 pixels fit exactly), and the
/// iterator is cloned once for that sum. Pixels outside the target are
/// discarded by it.
#[doc(hidden)]
pub fn fill_run_row<D, I>(target: &mut D, y: u16, x0: u16, runs: I) -> Result<(), D::Error>
where
    D: DrawTarget + ?Sized,
    I: IntoIterator<Item = (u16, D::Color)>,
    I::IntoIter: Clone,
{
    let runs = runs.into_iter();
    let total = runs
        .clone()
        .fold(0u32, |n, (len, _)| n.saturating_add(len as u32));
    if total == 0 {
        return Ok(());
    }
    let area = Rectangle::new(Point::new(x0 as i32, y as i32), Size::new(total, 1));
    let colors = runs.flat_map(|(len, color)| core::iter::repeat_n(color, len as usize));
    target.fill_contiguous(&area, colors)
}

impl<C: PixelColor> OriginDimensions for FrameBuffer<'_, C> {
    fn size(&self) -> Size {
        Size::new(self.width() as u32, self.height() as u32)
    }
}

/// The pixels a drawing may write: columns `0..w` of rows `y0..y1`
/// (the whole frame for a frame buffer, the band's rows for a
/// [`Band`](crate::port::band::Band)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Window {
    pub(crate) w: u16,
    pub(crate) y0: u16,
    pub(crate) y1: u16,
}

impl Window {
    /// The part of `area` inside the window, as `(x0, y0, x1, y1)` (ends
    /// exclusive), or `None` when they do not meet. The corners are
    /// computed in `i64`: an `i32` plus a `u32` cannot overflow there.
    fn visible(self, area: &Rectangle) -> Option<(u16, u16, u16, u16)> {
        let (x, y) = (area.top_left.x as i64, area.top_left.y as i64);
        let (top, bottom) = (self.y0 as i64, self.y1 as i64);
        let x0 = x.clamp(0, self.w as i64);
        let y0 = y.clamp(top, bottom);
        let x1 = (x + area.size.width as i64).clamp(0, self.w as i64);
        let y1 = (y + area.size.height as i64).clamp(top, bottom);
        (x0 < x1 && y0 < y1).then_some((x0 as u16, y0 as u16, x1 as u16, y1 as u16))
    }
}

/// [`DrawTarget::draw_iter`] into `target` as one span a pixel, the
/// pixels outside `win` discarded.
pub(crate) fn draw_iter<T, I>(target: &mut T, win: Window, pixels: I) -> Result<(), T::Error>
where
    T: SpanTarget + ?Sized,
    I: IntoIterator<Item = Pixel<T::Color>>,
{
    for Pixel(p, color) in pixels {
        if let (Ok(x), Ok(y)) = (u16::try_from(p.x), u16::try_from(p.y)) {
            // x < w <= 4096, so x + 1 cannot overflow.
            if x < win.w && y >= win.y0 && y < win.y1 {
                target.fill_span(
                    Span {
                        y,
                        x0: x,
                        x1: x + 1,
                    },
                    color,
                )?;
            }
        }
    }
    Ok(())
}

/// [`DrawTarget::fill_contiguous`] into `target` as one span per stretch
/// of equal colours, the pixels outside `win` discarded.
pub(crate) fn fill_contiguous<T, I>(
    target: &mut T,
    win: Window,
    area: &Rectangle,
    colors: I,
) -> Result<(), T::Error>
where
    T: SpanTarget + ?Sized,
    I: IntoIterator<Item = T::Color>,
{
    let Some((x0, y0, x1, y1)) = win.visible(area) else {
        return Ok(());
    };
    // Colours run row-major over all of `area`; those of pixels outside
    // the window are skipped. `area` is at least one pixel in each
    // direction here, and every offset below is at most its width or
    // height (a `u32`), so it fits a `u64` and a `usize` index does not
    // need to: `nth` takes a `usize`, so large skips go in steps.
    let mut colors = colors.into_iter();
    let left = (x0 as i64 - area.top_left.x as i64) as u64;
    let right = area.size.width as u64 - (x1 as i64 - area.top_left.x as i64) as u64;
    let above = (y0 as i64 - area.top_left.y as i64) as u64;
    // above <= 4096 + 2^31 and width < 2^32: the product is below 2^64.
    if !skip(&mut colors, above.saturating_mul(area.size.width as u64)) {
        return Ok(());
    }
    for y in y0..y1 {
        if !skip(&mut colors, left) {
            return Ok(());
        }
        let mut run: Option<(u16, T::Color)> = None;
        for x in x0..x1 {
            let Some(c) = colors.next() else {
                if let Some((start, rc)) = run {
                    target.fill_span(
                        Span {
                            y,
                            x0: start,
                            x1: x,
                        },
                        rc,
                    )?;
                }
                return Ok(());
            };
            match run {
                Some((_, rc)) if rc == c => {}
                Some((start, rc)) => {
                    target.fill_span(
                        Span {
                            y,
                            x0: start,
                            x1: x,
                        },
                        rc,
                    )?;
                    run = Some((x, c));
                }
                None => run = Some((x, c)),
            }
        }
        if let Some((start, rc)) = run {
            target.fill_span(Span { y, x0: start, x1 }, rc)?;
        }
        if y + 1 < y1 && !skip(&mut colors, right) {
            return Ok(());
        }
    }
    Ok(())
}

/// [`DrawTarget::fill_solid`] into `target` as one span a row of `area`
/// inside `win`.
pub(crate) fn fill_solid<T>(
    target: &mut T,
    win: Window,
    area: &Rectangle,
    color: T::Color,
) -> Result<(), T::Error>
where
    T: SpanTarget + ?Sized,
{
    if let Some((x0, y0, x1, y1)) = win.visible(area) {
        for y in y0..y1 {
            target.fill_span(Span { y, x0, x1 }, color)?;
        }
    }
    Ok(())
}

/// embedded-graphics drawing into the frame buffer. Pixels outside the
/// frame are discarded; nothing can fail.
///
/// Everything is written as spans: [`fill_solid`](DrawTarget::fill_solid)
/// one span a row, [`fill_contiguous`](DrawTarget::fill_contiguous) one
/// span per stretch of equal colours, [`draw_iter`](DrawTarget::draw_iter)
/// one span a pixel.
impl<C: PixelColor> DrawTarget for FrameBuffer<'_, C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        let win = self.window();
        draw_iter(self, win, pixels)
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = C>,
    {
        let win = self.window();
        fill_contiguous(self, win, area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        let win = self.window();
        fill_solid(self, win, area, color)
    }

    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        SpanTarget::clear(self, color)
    }
}

impl<C: PixelColor> FrameBuffer<'_, C> {
    /// The whole frame, as the window of its drawing.
    fn window(&self) -> Window {
        Window {
            w: self.width(),
            y0: 0,
            y1: self.height(),
        }
    }
}

/// Drops `n` items of `it`; `false` if it ran out first.
fn skip<I: Iterator>(it: &mut I, mut n: u64) -> bool {
    while n > 0 {
        let step = n.min(usize::MAX as u64);
        // `step` >= 1 fits a usize; `nth(k)` drops k + 1 items.
        if it.nth(step as usize - 1).is_none() {
            return false;
        }
        n -= step;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::Controller;
    use crate::display_list::{DisplayList, Writer};
    use crate::fixed::Vertex;
    use crate::raster::edge::Edge;
    use crate::raster::scan::Rasterizer;
    use embedded_graphics::mock_display::MockDisplay;
    use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
    use embedded_graphics::primitives::{Circle, PointsIter, Primitive, PrimitiveStyle, Triangle};
    use embedded_graphics::text::Text;
    use embedded_graphics::Drawable;
    use embedded_graphics_core::pixelcolor::{BinaryColor, Rgb565, Rgb888, RgbColor};

    const W: usize = 64;
    const H: usize = 48;

    /// A display driver that keeps the pixels and counts what it is
    /// asked to do.
    struct Counting {
        pixels: [Rgb565; W * H],
        draw_iter_pixels: u32,
        fill_solid: u32,
        fill_contiguous: u32,
        clear: u32,
    }

    impl Counting {
        fn new() -> Self {
            Counting {
                pixels: [Rgb565::BLACK; W * H],
                draw_iter_pixels: 0,
                fill_solid: 0,
                fill_contiguous: 0,
                clear: 0,
            }
        }
        fn put(&mut self, p: Point, c: Rgb565) {
            if (0..W as i32).contains(&p.x) && (0..H as i32).contains(&p.y) {
                self.pixels[p.y as usize * W + p.x as usize] = c;
            }
        }
    }

    impl OriginDimensions for Counting {
        fn size(&self) -> Size {
            Size::new(W as u32, H as u32)
        }
    }

    impl DrawTarget for Counting {
        type Color = Rgb565;
        type Error = Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
            &mut self,
            pixels: I,
        ) -> Result<(), Infallible> {
            for Pixel(p, c) in pixels {
                self.draw_iter_pixels += 1;
                self.put(p, c);
            }
            Ok(())
        }
        fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
            &mut self,
            area: &Rectangle,
            colors: I,
        ) -> Result<(), Infallible> {
            self.fill_contiguous += 1;
            for (p, c) in area.points().zip(colors) {
                self.put(p, c);
            }
            Ok(())
        }
        fn fill_solid(&mut self, area: &Rectangle, color: Rgb565) -> Result<(), Infallible> {
            self.fill_solid += 1;
            for p in area.points() {
                self.put(p, color);
            }
            Ok(())
        }
        fn clear(&mut self, color: Rgb565) -> Result<(), Infallible> {
            self.clear += 1;
            self.pixels.fill(color);
            Ok(())
        }
    }

    fn px(x: i16, y: i16) -> Vertex {
        Vertex::from_bits(x, y)
    }

    /// A scene of a clear, a clip and three polygons (one concave, one
    /// partly outside the frame), in Q12.4.
    fn scene(buf: &mut [u8]) -> &[u8] {
        let mut w = Writer::new(buf, W as u16, H as u16).unwrap();
        w.clear(Rgb888::new(0x10, 0x20, 0x30)).unwrap();
        w.color(Rgb888::RED).unwrap();
        w.poly([px(40, 40), px(900, 100), px(300, 700)]).unwrap();
        w.color(Rgb888::GREEN).unwrap();
        w.poly([
            px(200, 200),
            px(1000, 180),
            px(600, 420),
            px(990, 760),
            px(180, 740),
        ])
        .unwrap();
        w.color(Rgb888::BLUE).unwrap();
        w.poly([px(-300, 500), px(1400, 600), px(700, 1000)])
            .unwrap();
        w.finish()
    }

    #[test]
    fn a_driver_gets_one_fill_solid_per_span_and_the_same_pixels() {
        let mut buf = [0u8; 256];
        let list = DisplayList::new_checked(scene(&mut buf)).unwrap();
        let mut edges = [Edge::EMPTY; 8];

        let mut driver = Counting::new();
        let mut port = DrawTargetPort::new(&mut driver);
        let stats = Controller::new(Rasterizer::new(&mut edges))
            .render(&list, &mut port)
            .unwrap();
        assert!(stats.spans > 50);
        assert_eq!(driver.fill_solid, stats.spans);
        assert_eq!(driver.clear, stats.clears);
        assert_eq!(driver.draw_iter_pixels, 0);
        assert_eq!(driver.fill_contiguous, 0);

        let mut pixels = [Rgb565::BLACK; W * H];
        let mut fb = FrameBuffer::new(&mut pixels, W as u16, H as u16).unwrap();
        Controller::new(Rasterizer::new(&mut edges))
            .render(&list, &mut fb)
            .unwrap();
        assert!(fb.pixels() == &driver.pixels[..]);
    }

    #[test]
    fn the_port_frame_reaches_from_the_origin_to_the_box_corner() {
        let mut mock: MockDisplay<BinaryColor> = MockDisplay::new();
        assert_eq!(DrawTargetPort::new(&mut mock).size(), (64, 64));
        assert_eq!(side(-10, 5), 0);
        assert_eq!(side(i32::MAX, u32::MAX), MAX_SIDE);
        assert_eq!(side(100, 28), 128);
    }

    #[test]
    fn a_row_of_runs_is_one_fill_contiguous() {
        let mut d = Counting::new();
        let (r, g, b) = (Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE);
        fill_run_row(&mut d, 3, 10, [(2, r), (0, g), (3, g), (1, b)]).unwrap();
        fill_run_row(&mut d, 4, 0, [(0, r)]).unwrap();
        assert_eq!(d.fill_contiguous, 1);
        let row = &d.pixels[3 * W..4 * W];
        assert_eq!(
            &row[9..17],
            &[Rgb565::BLACK, r, r, g, g, g, b, Rgb565::BLACK]
        );

        // Through the port, and off the right edge: the driver discards.
        let mut d = Counting::new();
        DrawTargetPort::new(&mut d)
            .fill_run_row(0, 62, [(1, r), (5, g)])
            .unwrap();
        assert_eq!(d.fill_contiguous, 1);
        assert_eq!(&d.pixels[62..64], &[r, g]);
    }

    /// `item` drawn by embedded-graphics into the frame buffer equals the
    /// same drawn into embedded-graphics' own mock display.
    fn same_as_mock<T: Drawable<Color = BinaryColor>>(item: &T) {
        let mut mock: MockDisplay<BinaryColor> = MockDisplay::new();
        mock.set_allow_overdraw(true);
        mock.set_allow_out_of_bounds_drawing(true);
        item.draw(&mut mock).unwrap();
        let mut pixels = [BinaryColor::Off; 64 * 64];
        let mut fb = FrameBuffer::new(&mut pixels, 64, 64).unwrap();
        item.draw(&mut fb).unwrap();
        let mut lit = 0;
        for y in 0..64u16 {
            for x in 0..64u16 {
                let want = mock
                    .get_pixel(Point::new(x as i32, y as i32))
                    .unwrap_or(BinaryColor::Off);
                assert_eq!(fb.pixel(x, y), Some(want), "pixel ({x}, {y})");
                lit += (want == BinaryColor::On) as u32;
            }
        }
        assert!(lit > 20);
    }

    #[test]
    fn primitives_and_text_match_the_mock_display() {
        let on = BinaryColor::On;
        same_as_mock(
            &Circle::new(Point::new(-8, 20), 30).into_styled(PrimitiveStyle::with_fill(on)),
        );
        same_as_mock(
            &Triangle::new(Point::new(10, 2), Point::new(60, 12), Point::new(30, 40))
                .into_styled(PrimitiveStyle::with_stroke(on, 3)),
        );
        same_as_mock(&Text::new(
            "Hi 42",
            Point::new(20, 55),
            MonoTextStyle::new(&FONT_6X10, on),
        ));
    }

    #[test]
    fn fill_contiguous_keeps_the_colour_order_when_clipped() {
        // A 4 × 3 area at (62, -1): only (62..64, 0..2) is inside; the
        // colours are numbered in row-major order over the whole area.
        let mut pixels = [Rgb565::BLACK; 64 * 64];
        let mut fb = FrameBuffer::new(&mut pixels, 64, 64).unwrap();
        let colors = (0u8..12).map(|i| Rgb565::new(i, 0, 0));
        fb.fill_contiguous(&Rectangle::new(Point::new(62, -1), Size::new(4, 3)), colors)
            .unwrap();
        assert_eq!(fb.pixel(62, 0), Some(Rgb565::new(4, 0, 0)));
        assert_eq!(fb.pixel(63, 0), Some(Rgb565::new(5, 0, 0)));
        assert_eq!(fb.pixel(62, 1), Some(Rgb565::new(8, 0, 0)));
        assert_eq!(fb.pixel(63, 1), Some(Rgb565::new(9, 0, 0)));
        assert_eq!(fb.pixel(61, 0), Some(Rgb565::BLACK));

        // Too few colours, and huge or far-off areas: no panic.
        let far = [
            Rectangle::new(
                Point::new(i32::MIN, i32::MIN),
                Size::new(u32::MAX, u32::MAX),
            ),
            Rectangle::new(Point::new(i32::MAX, 0), Size::new(u32::MAX, 1)),
            Rectangle::new(Point::new(-5, -5), Size::new(0, 10)),
        ];
        for area in far {
            fb.fill_contiguous(&area, core::iter::repeat_n(Rgb565::RED, 3))
                .unwrap();
            fb.fill_solid(&area, Rgb565::RED).unwrap();
        }
        fb.draw_iter([
            Pixel(Point::new(-1, 0), Rgb565::RED),
            Pixel(Point::new(65_535, 0), Rgb565::RED),
            Pixel(Point::new(3, 3), Rgb565::RED),
        ])
        .unwrap();
        assert_eq!(fb.pixel(3, 3), Some(Rgb565::RED));
    }
}
