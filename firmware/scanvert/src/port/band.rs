//! Bands of rows: rendering without a frame buffer.
//!
//! The scan-line design finishes each row before the next, so a frame can
//! be produced top to bottom a few rows at a time into a small buffer, each
//! band shipped (to an SPI panel, by DMA) before the next is drawn. The
//! caller owns one buffer of `rows × width` pixels; the library fills it
//! with rows `y..y + rows` and hands it to a [`BandTarget`] to ship, then
//! fills it again with the next band.
//!
//! # Why the library holds the buffer
//!
//! The band's buffer is a plain slice the caller lends for the whole frame
//! ([`Controller::render_bands`](crate::controller::Controller::render_bands),
//! [`Scene::draw_bands`](crate::scene::Scene::draw_bands)), and the
//! provider only ships. A provider that lent a buffer per band would have
//! to hand out a `&mut` slice that outlives its own call, which with no
//! `alloc` and no `unsafe` means the provider owns the memory anyway; the
//! one case that needs two buffers (draw one while the other is on its way
//! by DMA) is served by an [`AsyncBandTarget`] and
//! [`FramePass::draw_async`](crate::frame::FramePass::draw_async), which
//! alternate two buffers the caller lends, or by
//! [`FramePass::draw_band`](crate::frame::FramePass::draw_band), one band
//! at a time into the buffer of the caller's choice.
//!
//! # Rows no command writes
//!
//! A band is a fresh buffer: before anything is drawn into it, every pixel
//! of it is set to the frame's *background*. For a display list that is
//! the colour of its last `clear`, or black when it has none (the content
//! of a fresh frame buffer, as the simulator starts with); for a scene it
//! is the background given to the call. So a frame rendered band by band
//! is, pixel for pixel, the frame rendered whole into a black (or
//! background-filled) frame buffer.
//!
//! # Errors
//!
//! A band of 0 rows, a buffer shorter than `rows × width`, a band that
//! starts above the last one's end (bands come from one top-to-bottom
//! pass) or below the frame are [`BandError`]s, found before anything is
//! drawn into the band. Rows between the last band and the next are
//! skipped: passed over without being resolved or drawn (a scene's active
//! list jumps over them at once).

use crate::port::draw_target::{self, Window};
use crate::port::{Span, SpanTarget};
use core::convert::Infallible;
use core::fmt;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::PixelColor;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// Where finished bands go: a panel's link, a DMA channel, or the rows of
/// a larger image.
pub trait BandTarget {
    /// The pixel format of the band.
    type Color: PixelColor;
    /// What shipping can fail with.
    type Error;

    /// Ships rows `y..y + rows` of the frame: `pixels` holds them row by
    /// row, `rows × width` pixels. The slice is the caller's band buffer;
    /// it is filled again with the next band once this returns.
    fn ship(&mut self, y: u16, rows: u16, pixels: &[Self::Color]) -> Result<(), Self::Error>;
}

/// Where finished bands go when shipping takes time the drawing can use:
/// a DMA transfer, through `embedded-hal-async`
/// ([`AsyncPanel`](crate::port::panel::AsyncPanel)).
///
/// A band is shipped in two steps. [`begin`](Self::begin) says where it
/// goes (a panel's address window) and is awaited to the end; then the
/// first poll of [`send`](Self::send)'s future starts the transfer of the
/// pixels. [`FramePass::draw_async`](crate::frame::FramePass::draw_async)
/// draws the next band between that first poll and awaiting the rest, so
/// a band is drawn while the last one is on its way.
pub trait AsyncBandTarget {
    /// The pixel format of the band.
    type Color: PixelColor;
    /// What shipping can fail with.
    type Error;

    /// Makes ready for rows `y..y + rows` of `width` pixels each.
    fn begin(
        &mut self,
        y: u16,
        rows: u16,
        width: u16,
    ) -> impl core::future::Future<Output = Result<(), Self::Error>>;

    /// Sends the band's pixels, row by row. The slice is not written
    /// until the future completes.
    fn send(
        &mut self,
        pixels: &[Self::Color],
    ) -> impl core::future::Future<Output = Result<(), Self::Error>>;
}

/// The index of row `y`'s first pixel in a band of rows from `y0`, rows
/// of `width` pixels (or words of two): wrapped for a row above the band
/// to one past any slice's end, so that the slice's check refuses it
/// (`65535 · 65535 + 65535` fits a 32-bit `usize`; with a narrower one
/// the product wraps, never panics). Every band's `row_start` and its
/// writes inside.
#[inline(always)]
pub(crate) fn band_row_start(y: u16, y0: u16, width: u16) -> usize {
    (y.wrapping_sub(y0) as usize).wrapping_mul(width as usize)
}

impl<B: BandTarget + ?Sized> BandTarget for &mut B {
    type Color = B::Color;
    type Error = B::Error;
    fn ship(&mut self, y: u16, rows: u16, pixels: &[Self::Color]) -> Result<(), Self::Error> {
        (**self).ship(y, rows, pixels)
    }
}

/// Why a band could not be drawn. Nothing is drawn into the band.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BandError {
    /// A band of no rows.
    NoRows,
    /// The buffer holds fewer than `rows × width` pixels.
    Buffer {
        /// Pixels the buffer holds.
        len: usize,
        /// Pixels the band needs.
        needed: usize,
    },
    /// The band starts above the end of the last one: rows come from one
    /// pass, top to bottom.
    Order {
        /// The first row the next band may start at.
        next: u16,
        /// The row asked for.
        y: u16,
    },
    /// The band starts at or below the frame's last row.
    Outside {
        /// The row asked for.
        y: u16,
        /// The frame's height.
        height: u16,
    },
}

impl fmt::Display for BandError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BandError::NoRows => f.write_str("a band needs at least one row"),
            BandError::Buffer { len, needed } => write!(
                f,
                "the band buffer holds {len} pixels; the band needs {needed}"
            ),
            BandError::Order { next, y } => write!(
                f,
                "band at row {y} requested after rows up to {next} were drawn: bands go top to bottom"
            ),
            BandError::Outside { y, height } => {
                write!(f, "band at row {y} is outside the frame of {height} rows")
            }
        }
    }
}

impl core::error::Error for BandError {}

/// Why a frame could not be rendered band by band.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BandsError<R, E> {
    /// The band or its buffer is wrong; nothing was drawn into it.
    Band(BandError),
    /// The frame's work could not be prepared or resolved (as the
    /// full-frame path reports it).
    Render(R),
    /// The provider failed to ship the band at row `y`.
    Ship {
        /// The band's first row.
        y: u16,
        /// The provider's error.
        error: E,
    },
}

impl<R: fmt::Display, E: fmt::Debug> fmt::Display for BandsError<R, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BandsError::Band(e) => write!(f, "{e}"),
            BandsError::Render(e) => write!(f, "{e}"),
            BandsError::Ship { y, error } => {
                write!(f, "shipping the band at row {y} failed: {error:?}")
            }
        }
    }
}

impl<R: fmt::Display + fmt::Debug, E: fmt::Debug> core::error::Error for BandsError<R, E> {}

impl<R, E> From<BandError> for BandsError<R, E> {
    fn from(e: BandError) -> Self {
        BandsError::Band(e)
    }
}

/// Rows `y0..y0 + rows` of a `width × height` frame over the caller's
/// buffer, as a [`SpanTarget`] of the whole frame's size: spans on the
/// band's rows are written, all others dropped. Every stage draws into it
/// as into a frame buffer.
///
/// # Guarantees
/// `rows ≥ 1`, `y0 + rows ≤ height` and the buffer holds `rows × width`
/// pixels, checked by [`Band::new`].
#[derive(Debug)]
pub struct Band<'b, C> {
    pixels: &'b mut [C],
    width: u16,
    height: u16,
    y0: u16,
    rows: u16,
}

impl<'b, C: PixelColor> Band<'b, C> {
    /// The band of rows `y0..y0 + rows` of a `width × height` frame over
    /// `pixels`. The band is cut at the frame's last row.
    pub fn new(
        pixels: &'b mut [C],
        (width, height): (u16, u16),
        y0: u16,
        rows: u16,
    ) -> Result<Self, BandError> {
        if rows == 0 {
            return Err(BandError::NoRows);
        }
        if y0 >= height {
            return Err(BandError::Outside { y: y0, height });
        }
        let rows = rows.min(height - y0);
        let needed = rows as usize * width as usize;
        if pixels.len() < needed {
            return Err(BandError::Buffer {
                len: pixels.len(),
                needed,
            });
        }
        Ok(Band {
            pixels: &mut pixels[..needed],
            width,
            height,
            y0,
            rows,
        })
    }

    /// The band's first row.
    pub fn y(&self) -> u16 {
        self.y0
    }

    /// Rows in the band (after cutting at the frame's end).
    pub fn rows(&self) -> u16 {
        self.rows
    }

    /// One past the band's last row.
    pub fn end(&self) -> u16 {
        self.y0 + self.rows
    }

    /// The band's pixels, row by row.
    pub fn pixels(&self) -> &[C] {
        self.pixels
    }
}

impl<C: PixelColor> SpanTarget for Band<'_, C> {
    type Color = C;
    type Error = core::convert::Infallible;

    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }

    #[inline]
    fn fill_span(&mut self, span: Span, color: C) -> Result<(), Self::Error> {
        let Some(row) = span.y.checked_sub(self.y0).filter(|&r| r < self.rows) else {
            return Ok(());
        };
        let x1 = span.x1.min(self.width);
        if span.x0 < x1 {
            let base = row as usize * self.width as usize;
            if let Some(run) = self
                .pixels
                .get_mut(base + span.x0 as usize..base + x1 as usize)
            {
                crate::port::framebuffer::fill_run(run, color);
            }
        }
        Ok(())
    }

    /// Without `fill_span`'s clipping of the end. The row is checked by
    /// the slice alone: the pixels are cut to the band's rows, so a row
    /// above the band (wrapped to a large one) or below it starts past
    /// their end (`65535 · 65535 + 65535` fits a 32-bit `usize`; with a
    /// narrower one the sums wrap, never panic).
    #[inline(always)]
    fn fill_span_inside(&mut self, span: Span, color: C) -> Result<(), Self::Error> {
        let base = band_row_start(span.y, self.y0, self.width);
        let (x0, x1) = (
            base.wrapping_add(span.x0 as usize),
            base.wrapping_add(span.x1 as usize),
        );
        if let Some(run) = self.pixels.get_mut(x0..x1) {
            crate::port::framebuffer::fill_run(run, color);
        }
        Ok(())
    }

    /// The index of row `y`'s first pixel in the band (wrapping for a
    /// row above it, so that the slice's check refuses it).
    #[inline(always)]
    fn row_start(&self, y: u16) -> usize {
        band_row_start(y, self.y0, self.width)
    }

    #[inline(always)]
    fn row_stride(&self) -> usize {
        self.width as usize
    }

    /// As `fill_span_inside`, from the row's start.
    #[inline(always)]
    fn fill_row_inside(
        &mut self,
        row: usize,
        x0: u16,
        x1: u16,
        color: C,
    ) -> Result<(), Self::Error> {
        crate::port::framebuffer::fill_row_at(self.pixels, row, x0, x1, color);
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Self::Error> {
        self.pixels.fill(color);
        Ok(())
    }
}

/// A layer's `background` duty done by a fill: the band gets the
/// background, when there is one, before the layer draws.
pub(crate) fn fill_background<C: PixelColor>(band: &mut Band<'_, C>, background: Option<C>) {
    if let Some(c) = background {
        match SpanTarget::clear(band, c) {
            Ok(()) => {}
            Err(e) => match e {},
        }
    }
}

/// Checks a band of rows `y..y + rows` of a frame `height` rows high
/// whose next row to draw is `next`: at least one row, inside the frame,
/// not above the last band's end.
pub(crate) fn check_band(y: u16, rows: u16, next: u16, height: u16) -> Result<(), BandError> {
    if rows == 0 {
        return Err(BandError::NoRows);
    }
    if y >= height {
        return Err(BandError::Outside { y, height });
    }
    if y < next {
        return Err(BandError::Order { next, y });
    }
    Ok(())
}

/// Checks that a buffer of `len` pixels holds a band of `rows` rows of a
/// `width × height` frame (or the whole frame, when it is lower).
pub(crate) fn check_buffer(
    rows: u16,
    (width, height): (u16, u16),
    len: usize,
) -> Result<(), BandError> {
    if rows == 0 {
        return Err(BandError::NoRows);
    }
    let needed = rows.min(height) as usize * width as usize;
    if len < needed {
        return Err(BandError::Buffer { len, needed });
    }
    Ok(())
}

/// Rows of a frame to draw again: one bit per row, in caller memory
/// ([`DirtyRows::words`] `u32`s for a frame's height).
#[derive(Debug)]
pub struct DirtyRows<'d> {
    bits: &'d mut [u32],
    height: u16,
}

impl<'d> DirtyRows<'d> {
    /// `u32`s needed for `height` rows.
    pub const fn words(height: u16) -> usize {
        (height as usize).div_ceil(32)
    }

    /// No row marked, over `bits`; `None` when it holds fewer than
    /// [`words`](Self::words)`(height)`.
    pub fn new(bits: &'d mut [u32], height: u16) -> Option<Self> {
        let bits = bits.get_mut(..Self::words(height))?;
        bits.fill(0);
        Some(DirtyRows { bits, height })
    }

    /// Rows in the frame.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// Marks rows `y0..y1`, cut to the frame.
    pub fn mark(&mut self, y0: i32, y1: i32) {
        let (y0, y1) = (y0.max(0), y1.min(self.height as i32));
        for y in y0..y1 {
            self.bits[y as usize / 32] |= 1 << (y % 32);
        }
    }

    /// Marks every row.
    pub fn mark_all(&mut self) {
        self.mark(0, self.height as i32);
    }

    /// Unmarks every row.
    pub fn clear(&mut self) {
        self.bits.fill(0);
    }

    /// `true` when row `y` is marked.
    pub fn is_marked(&self, y: u16) -> bool {
        y < self.height && self.bits[y as usize / 32] & (1 << (y % 32)) != 0
    }

    /// Rows marked.
    pub fn count(&self) -> usize {
        self.bits.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// The marked rows as runs `(y0, y1)`, top to bottom.
    pub fn runs(&self) -> impl Iterator<Item = (u16, u16)> + '_ {
        let mut y = 0u16;
        core::iter::from_fn(move || {
            while y < self.height && !self.is_marked(y) {
                y += 1;
            }
            if y >= self.height {
                return None;
            }
            let y0 = y;
            while y < self.height && self.is_marked(y) {
                y += 1;
            }
            Some((y0, y))
        })
    }
}

/// A 64-bit mix of words (splitmix64 steps), for row hashes.
pub(crate) struct Mix(u64);

impl Mix {
    pub(crate) fn new() -> Mix {
        Mix(0x9e37_79b9_7f4a_7c15)
    }

    pub(crate) fn add(&mut self, v: u64) {
        let mut z = (self.0 ^ v).wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        self.0 = z ^ (z >> 31);
    }

    pub(crate) fn finish(&self) -> u64 {
        self.0
    }

    /// `a` followed by `b`: an order-dependent chain of hashes.
    pub(crate) fn chain(a: u64, b: u64) -> u64 {
        let mut m = Mix(a);
        m.add(b);
        m.finish()
    }
}

/// The band's size is the frame's: embedded-graphics places a drawing in
/// frame coordinates, and the band keeps the part on its rows.
impl<C: PixelColor> OriginDimensions for Band<'_, C> {
    fn size(&self) -> Size {
        Size::new(self.width as u32, self.height as u32)
    }
}

/// embedded-graphics drawing into a band: every primitive, font and image
/// draws into the band's rows of the frame, with no frame buffer. Pixels
/// outside the band's rows (or the frame) are discarded, so drawing the
/// same into every band of a pass draws it into the frame, pixel for
/// pixel as into a [`FrameBuffer`](crate::port::framebuffer::FrameBuffer).
///
/// [`fill_solid`](DrawTarget::fill_solid) and
/// [`fill_contiguous`](DrawTarget::fill_contiguous) cut their rectangle
/// to the band first: one of no row of the band costs a rectangle test
/// (`fill_contiguous` still steps its colour iterator past the rows
/// above the band, which embedded-graphics' iterators cannot jump).
/// [`draw_iter`](DrawTarget::draw_iter) tests each pixel. Nothing can
/// fail.
impl<C: PixelColor> DrawTarget for Band<'_, C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        let win = self.window();
        draw_target::draw_iter(self, win, pixels)
    }

    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = C>,
    {
        let win = self.window();
        draw_target::fill_contiguous(self, win, area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        let win = self.window();
        draw_target::fill_solid(self, win, area, color)
    }

    /// Fills the band's rows: the part of the frame it holds.
    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        SpanTarget::clear(self, color)
    }
}

impl<C> Band<'_, C> {
    /// The band's rows, as the window of its drawing.
    fn window(&self) -> Window {
        Window {
            w: self.width,
            y0: self.y0,
            y1: self.y0 + self.rows,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every span of a frame clipped to its width, into bands of every
    /// start and height: `fill_span_inside` writes what `fill_span` writes.
    #[test]
    fn spans_inside_write_what_fill_span_writes() {
        use embedded_graphics_core::pixelcolor::Gray8;
        let (w, h) = (7u16, 6u16);
        for y0 in 0..h {
            for rows in 1..=h - y0 {
                for y in 0..h {
                    for x0 in 0..w {
                        for x1 in x0 + 1..=w {
                            let span = Span { y, x0, x1 };
                            let mut inside = [Gray8::new(0); 42];
                            let mut checked = inside;
                            Band::new(&mut inside, (w, h), y0, rows)
                                .unwrap()
                                .fill_span_inside(span, Gray8::new(9))
                                .unwrap();
                            Band::new(&mut checked, (w, h), y0, rows)
                                .unwrap()
                                .fill_span(span, Gray8::new(9))
                                .unwrap();
                            assert_eq!(inside, checked, "band {y0}+{rows}, {span:?}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_band_takes_only_its_rows() {
        let mut px = [0u8; 12].map(|_| embedded_graphics_core::pixelcolor::BinaryColor::Off);
        let mut b = Band::new(&mut px, (4, 10), 8, 5).unwrap();
        assert_eq!((b.y(), b.rows(), b.end()), (8, 2, 10));
        use embedded_graphics_core::pixelcolor::BinaryColor::On;
        for y in 0..12 {
            b.fill_span(Span { y, x0: 1, x1: 9 }, On).unwrap();
        }
        let on = b.pixels().iter().filter(|&&c| c == On).count();
        assert_eq!(on, 6);
        assert_eq!(
            Band::new(&mut px, (4, 10), 0, 0).unwrap_err(),
            BandError::NoRows
        );
        assert_eq!(
            Band::new(&mut px, (4, 10), 0, 4).unwrap_err(),
            BandError::Buffer {
                len: 12,
                needed: 16
            }
        );
        assert_eq!(
            Band::new(&mut px, (4, 10), 10, 1).unwrap_err(),
            BandError::Outside { y: 10, height: 10 }
        );
    }
}
