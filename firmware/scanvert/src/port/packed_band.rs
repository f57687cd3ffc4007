//! A band of 16-bit pixels packed two to a `u32` word, in the panel's
//! wire order: the band as an SPI panel takes it, ready for DMA.
//!
//! A [`Band`](super::band::Band) of `Rgb565` is stored a half-word a
//! pixel (`strh`, about 1.1 Cortex-M4 instructions a pixel in a band,
//! `docs/performance-log.md`), and its `u16`s sit in memory low byte
//! first, while an ST7789 or ILI9341 panel takes RGB565 high byte first.
//! A [`PackedBand`] is a band of the same rows over a slice of `u32`
//! words the caller owns: every span is written as whole words, as
//! [`PackedFrameBuffer`] writes them (its fills are the ones called here),
//! and the words hold the pixels already in the panel's byte order.
//!
//! # Layout and byte order
//!
//! The band's pixels are numbered row-major from its first row, `i =
//! (y − y0) · width + x`, with no padding between rows (an odd width
//! makes every other row start in the middle of a word). Pixel `i` is in
//! word `i / 2`; with `p` its raw 16 bits (`RawU16`, for `Rgb565`
//! `rrrrrggggggbbbbb`), word `k`'s bytes in little-endian order,
//! `k.to_le_bytes()`, are
//!
//! | byte | 0 | 1 | 2 | 3 |
//! |---|---|---|---|---|
//! | holds | `p[2k] >> 8` | `p[2k] & 0xff` | `p[2k+1] >> 8` | `p[2k+1] & 0xff` |
//!
//! that is, the word is `swap_bytes(p[2k]) | swap_bytes(p[2k+1]) << 16`.
//! On a little-endian core (every core this crate targets: Cortex-M,
//! RV32) the memory of the slice is then the byte stream
//! `p[0] high, p[0] low, p[1] high, p[1] low, …`: big-endian RGB565, the
//! order an SPI panel reads in 8-bit transfers. A DMA channel sends the
//! band's words as `2 · rows · width` bytes from the slice's start, with
//! no conversion (`bytemuck::cast_slice::<u32, u8>` gives those bytes as
//! a `&[u8]`, for a HAL that takes one). When `rows · width` is odd, the
//! high half of the last word is not a pixel: it is not sent.
//! [`PackedBand::wire_bytes`] yields the same bytes on any core.
//!
//! # Limits
//!
//! The band needs [`PackedBand::words_len`]`(width, rows)` words: half its
//! pixels, rounded up (a 240-pixel, 16-row band: 1,920 words, 7.5 KiB, as
//! a `[Rgb565]` band). The pixel format is any 16-bit one
//! (`Into<RawU16> + From<RawU16>`).

use crate::port::band::{band_row_start, BandError};
use crate::port::draw_target::{self, Window};
use crate::port::packed::{fill_pixels, fill_words, PackedFrameBuffer};
use crate::port::runs::Rows;
use crate::port::{RowRun, Span, SpanTarget};
use core::convert::Infallible;
use core::marker::PhantomData;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::{PixelColor, Rgb565};
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// Where finished packed bands go: an SPI panel's DMA channel, or the
/// rows of a larger image.
pub trait PackedBandTarget {
    /// The pixel format of the band.
    type Color: PixelColor + Into<RawU16> + From<RawU16>;
    /// What shipping can fail with.
    type Error;

    /// Ships rows `y..y + rows` of a frame `width` pixels wide: `words`,
    /// [`PackedBand::words_len`]`(width, rows)` of them, hold the
    /// `rows × width` pixels in wire order (see the [module](self) docs:
    /// as bytes, `2 · rows · width` of them from the start). The slice is
    /// the caller's band buffer; it is filled again with the next band
    /// once this returns.
    fn ship_words(
        &mut self,
        y: u16,
        rows: u16,
        width: u16,
        words: &[u32],
    ) -> Result<(), Self::Error>;
}

impl<B: PackedBandTarget + ?Sized> PackedBandTarget for &mut B {
    type Color = B::Color;
    type Error = B::Error;
    fn ship_words(
        &mut self,
        y: u16,
        rows: u16,
        width: u16,
        words: &[u32],
    ) -> Result<(), Self::Error> {
        (**self).ship_words(y, rows, width, words)
    }
}

/// A pixel's raw bits in wire order, twice: the word of two such pixels.
#[inline(always)]
fn wire_pair<C: Into<RawU16>>(c: C) -> u32 {
    let w = c.into().into_inner().swap_bytes() as u32;
    w | w << 16
}

/// The pixel of wire-order half-word `h`.
#[inline]
fn from_wire<C: From<RawU16>>(h: u16) -> C {
    C::from(RawU16::new(h.swap_bytes()))
}

/// Writes runs of packed pixels one after the other from pixel `a` of
/// `words`: each `(b, v)` of `runs` covers the pixels from the end of the
/// one before it (`a` for the first) up to `b`, exclusive, with the pixel
/// pair `v` (`c | c << 16`). Where a run ends in the middle of a word,
/// the word is stored once, with the next run's first pixel (or, after
/// the last run, merged with the pixel in memory). Pixels past the slice
/// are not written: wrong runs (one that does not end past the one
/// before it) may write other pixels of the slice, and never panic.
#[inline(always)]
pub(crate) fn fill_runs(words: &mut [u32], mut a: usize, runs: impl Iterator<Item = (usize, u32)>) {
    // The low half of word `a / 2` while `a` is odd: the pixel before
    // `a`, as memory holds it or as the run before left it.
    let mut low = match words.get(a / 2) {
        Some(w) if a % 2 == 1 => *w & 0x0000_ffff,
        _ => 0,
    };
    for (b, v) in runs {
        if a % 2 == 1 {
            if let Some(w) = words.get_mut(a / 2) {
                *w = low | (v & 0xffff_0000);
            }
            a += 1;
        }
        // `a` is even here, and so is `whole`: the run's words are
        // whole, with no half to merge at either end.
        let whole = b & !1;
        if a < whole {
            if let Some(run) = words.get_mut(a / 2..whole / 2) {
                fill_words(run, v);
            }
        }
        low = v & 0x0000_ffff;
        a = b;
    }
    if a % 2 == 1 {
        if let Some(w) = words.get_mut(a / 2) {
            *w = (*w & 0xffff_0000) | low;
        }
    }
}

/// Rows `y0..y0 + rows` of a `width × height` frame over the caller's
/// words, two pixels a word in wire order (see the [module](self) docs),
/// as a [`SpanTarget`] of the whole frame's size: spans on the band's rows
/// are written, all others dropped. Every stage that draws into a
/// [`Band`](super::band::Band) draws into it, pixel for pixel the same.
///
/// # Guarantees
/// `rows ≥ 1`, `y0 + rows ≤ height`, and the slice is cut to
/// [`words_len`](Self::words_len)`(width, rows)` words, checked by
/// [`PackedBand::new`].
///
/// ```
/// use scanvert::pixelcolor::{Rgb565, RgbColor};
/// use scanvert::port::packed_band::PackedBand;
/// use scanvert::port::{Span, SpanTarget};
/// // Rows 4 and 5 of a 3 × 8 frame: 6 pixels, 3 words.
/// let mut words = [0u32; PackedBand::<Rgb565>::words_len(3, 2)];
/// let mut band = PackedBand::new(&mut words, (3, 8), 4, 2).unwrap();
/// band.fill_span(Span { y: 5, x0: 0, x1: 2 }, Rgb565::RED).unwrap();
/// assert_eq!(band.pixel(1, 5), Some(Rgb565::RED));
/// // Red is 0xf800: high byte first on the wire.
/// let bytes: Vec<u8> = band.wire_bytes().collect();
/// assert_eq!(bytes, [0, 0, 0, 0, 0, 0, 0xf8, 0, 0xf8, 0, 0, 0]);
/// ```
#[derive(Debug)]
pub struct PackedBand<'b, C = Rgb565> {
    words: &'b mut [u32],
    width: u16,
    height: u16,
    y0: u16,
    rows: u16,
    _color: PhantomData<C>,
}

impl<'b, C> PackedBand<'b, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    /// Words for a band of `rows` rows of `width` pixels: half the pixels,
    /// rounded up.
    pub const fn words_len(width: u16, rows: u16) -> usize {
        (width as usize * rows as usize).div_ceil(2)
    }

    /// The band of rows `y0..y0 + rows` of a `width × height` frame over
    /// `words`, cut at the frame's last row. Its pixels are as the words
    /// hold them. Errors as [`Band::new`](super::band::Band::new): the
    /// buffer's length is given in pixels (twice its words).
    pub fn new(
        words: &'b mut [u32],
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
        let n = Self::words_len(width, rows);
        if words.len() < n {
            return Err(BandError::Buffer {
                len: words.len().saturating_mul(2),
                needed: rows as usize * width as usize,
            });
        }
        Ok(PackedBand {
            words: &mut words[..n],
            width,
            height,
            y0,
            rows,
            _color: PhantomData,
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

    /// The band's words, [`words_len`](Self::words_len)`(width, rows)` of
    /// them, in wire order: what a [`PackedBandTarget`] is shipped.
    pub fn words(&self) -> &[u32] {
        self.words
    }

    /// The pixel at `(x, y)` of the frame, or `None` off the band.
    pub fn pixel(&self, x: u16, y: u16) -> Option<C> {
        let row = y.checked_sub(self.y0).filter(|&r| r < self.rows)?;
        if x >= self.width {
            return None;
        }
        let i = row as usize * self.width as usize + x as usize;
        let w = *self.words.get(i / 2)?;
        Some(from_wire((w >> (16 * (i % 2))) as u16))
    }

    /// The band's pixels, row by row, `rows × width` of them.
    pub fn pixels(&self) -> impl Iterator<Item = C> + '_ {
        let n = self.rows as usize * self.width as usize;
        self.words
            .iter()
            .flat_map(|&w| [w as u16, (w >> 16) as u16])
            .take(n)
            .map(from_wire)
    }

    /// The bytes a panel is sent for the band, `2 · rows · width` of them:
    /// each pixel high byte first. On a little-endian core they are the
    /// words' memory.
    pub fn wire_bytes(&self) -> impl Iterator<Item = u8> + '_ {
        let n = 2 * self.rows as usize * self.width as usize;
        self.words.iter().flat_map(|w| w.to_le_bytes()).take(n)
    }

    /// The band's rows as a packed frame of their own, for its
    /// rectangles; `None` for a frame of no columns.
    fn rows_frame(&mut self) -> Option<PackedFrameBuffer<'_, C>> {
        PackedFrameBuffer::new(self.words, self.width, self.rows)
    }

    /// The band's rows, as the window of its drawing.
    fn window(&self) -> Window {
        Window {
            w: self.width,
            y0: self.y0,
            y1: self.y0 + self.rows,
        }
    }
}

impl<C> SpanTarget for PackedBand<'_, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    type Color = C;
    type Error = Infallible;

    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }

    /// Inlined into the band walk, which writes every span through it: as
    /// a call (the span stored for it, the walk's registers saved and
    /// reloaded around it) a short span of W3 cost about 16 Cortex-M4
    /// instructions more (`docs/performance-log.md`).
    #[inline(always)]
    fn fill_span(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let Some(row) = span.y.checked_sub(self.y0).filter(|&r| r < self.rows) else {
            return Ok(());
        };
        let x1 = span.x1.min(self.width);
        if span.x0 < x1 {
            let base = row as usize * self.width as usize;
            fill_pixels(
                self.words,
                base + span.x0 as usize,
                base + x1 as usize,
                wire_pair(color),
            );
        }
        Ok(())
    }

    /// Without `fill_span`'s clipping of the end. The row is checked by
    /// the slice alone, as [`Band`](super::band::Band) checks it: the
    /// words are cut to the band's rows, so a row above the band (wrapped
    /// to a large one) or below it starts past their end (at most the
    /// padding half of an odd band's last word, never a pixel of it).
    #[inline(always)]
    fn fill_span_inside(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let base = band_row_start(span.y, self.y0, self.width);
        let (a, b) = (
            base.wrapping_add(span.x0 as usize),
            base.wrapping_add(span.x1 as usize),
        );
        if a < b {
            fill_pixels(self.words, a, b, wire_pair(color));
        }
        Ok(())
    }

    /// The band's row `y − y0` (wrapped, as in `fill_span_inside`, for a
    /// row outside the band: its words start past the slice's end).
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
    ) -> Result<(), Infallible> {
        let (a, b) = (row.wrapping_add(x0 as usize), row.wrapping_add(x1 as usize));
        if a < b {
            fill_pixels(self.words, a, b, wire_pair(color));
        }
        Ok(())
    }

    /// The row's address worked out once, and the runs stored as one
    /// sequence of words (`fill_runs`). The row is checked by the slice
    /// alone, as in [`fill_span_inside`](Self::fill_span_inside). Out of
    /// line: called once a row, its loop keeps its own registers.
    #[inline(never)]
    fn fill_runs_inside(&mut self, y: u16, x0: u16, runs: &[RowRun<C>]) -> Result<(), Infallible> {
        let base = band_row_start(y, self.y0, self.width);
        fill_runs(
            self.words,
            base.wrapping_add(x0 as usize),
            runs.iter()
                .map(|r| (base.wrapping_add(r.x1 as usize), wire_pair(r.color))),
        );
        Ok(())
    }

    /// The rectangle cut to the band's rows, written by
    /// [`PackedFrameBuffer`]'s rectangle fill over the band; one row of
    /// it (a band of one row, or the rectangle's edge) as a span.
    fn fill_rect(&mut self, span: Span, height: u16, color: C) -> Result<(), Infallible> {
        let top = span.y.max(self.y0);
        let bottom = (span.y as u32 + height as u32).min(self.end() as u32);
        if top as u32 + 1 == bottom {
            self.fill_span(Span { y: top, ..span }, color)?;
        } else if (top as u32) < bottom {
            let y0 = self.y0;
            // The frame of the band's rows stores a pixel's raw bits as
            // they are: given the wire order's, it writes the wire order.
            let c = C::from(RawU16::new(wire_pair(color) as u16));
            if let Some(mut rows) = self.rows_frame() {
                let at = Span {
                    y: top - y0,
                    ..span
                };
                rows.fill_rect(at, (bottom - top as u32) as u16, c)?;
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        let n = self.rows as usize * self.width as usize;
        fill_pixels(self.words, 0, n, wire_pair(color));
        Ok(())
    }
}

impl<C> Rows for PackedBand<'_, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    fn first(&self) -> u16 {
        self.y0
    }
    fn count(&self) -> u16 {
        self.rows
    }
}

/// The band's size is the frame's: embedded-graphics places a drawing in
/// frame coordinates, and the band keeps the part on its rows.
impl<C> OriginDimensions for PackedBand<'_, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    fn size(&self) -> Size {
        Size::new(self.width as u32, self.height as u32)
    }
}

/// embedded-graphics drawing into a packed band, as into a
/// [`Band`](super::band::Band): pixels outside the band's rows (or the
/// frame) are discarded. [`fill_solid`](DrawTarget::fill_solid) and
/// [`fill_contiguous`](DrawTarget::fill_contiguous) cut their rectangle
/// to the band first (a span a row); [`draw_iter`](DrawTarget::draw_iter)
/// tests each pixel.
/// Nothing can fail.
impl<C> DrawTarget for PackedBand<'_, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
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
