//! A frame buffer of 16-bit pixels packed two to a `u32` word, written a
//! word at a time.
//!
//! On a 32-bit core a span of `FrameBuffer<Rgb565>` is stored a half-word
//! per pixel (`strh`). Here the frame is a slice of `u32` words, two pixels
//! to a word, and a span is stored as whole words in groups of 16, 8, 4
//! or 2 (double-word stores on a Cortex-M4; a span shorter than 32 words is
//! two groups of one size that overlap, with no loop), with a half-word
//! merged into its word at an odd start or end. On the Cortex-M4 the image
//! measures it in `docs/performance.md` (on-target section).
//!
//! # Layout
//! Pixels are numbered row-major, `i = y · width + x`, with no padding
//! between rows; pixel `i` is the low half of word `i / 2` when `i` is even
//! and the high half when it is odd. In little-endian memory, the order of
//! every 32-bit core this crate targets, the words' bytes are then exactly
//! the pixels' bytes in order, as a `[u16]` frame would hold them, so a
//! display controller or DMA reads the same memory, and
//! [`PackedFrameBuffer::checksum`] equals
//! [`frame_checksum`](crate::port::checksum::frame_checksum) of the same
//! pixels. Any width works; an odd width only makes half of the rows start
//! in the middle of a word.

use crate::port::checksum::Checksum;
use crate::port::framebuffer::MAX_SIDE;
use crate::port::{RowRun, Span, SpanTarget};
use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::{PixelColor, Rgb565};

/// A `width × height` frame of 16-bit pixels over a slice of words the
/// caller owns, two pixels to a word (see the module docs for the layout).
///
/// # Guarantees
/// `1 <= width, height <= 4096` and the slice holds at least
/// [`words_len(width, height)`](Self::words_len) words, so every in-range
/// pixel access is in bounds.
///
/// ```
/// use scanvert::pixelcolor::{Rgb565, RgbColor};
/// use scanvert::port::{PackedFrameBuffer, Span, SpanTarget};
/// let mut words = [0u32; PackedFrameBuffer::<Rgb565>::words_len(5, 2)];
/// let mut fb = PackedFrameBuffer::new(&mut words, 5, 2).unwrap();
/// fb.fill_span(Span { y: 1, x0: 0, x1: 4 }, Rgb565::RED).unwrap();
/// assert_eq!(fb.pixel(3, 1), Some(Rgb565::RED));
/// assert_eq!(fb.pixel(4, 1), Some(Rgb565::BLACK));
/// ```
#[derive(Debug)]
pub struct PackedFrameBuffer<'a, C = Rgb565> {
    words: &'a mut [u32],
    width: u16,
    height: u16,
    _color: core::marker::PhantomData<C>,
}

/// A pixel's raw 16 bits.
#[inline(always)]
fn bits<C: Into<RawU16>>(c: C) -> u32 {
    c.into().into_inner() as u32
}

impl<'a, C> PackedFrameBuffer<'a, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    /// Words needed for a `width × height` frame: half the pixels, rounded
    /// up.
    pub const fn words_len(width: u16, height: u16) -> usize {
        (width as usize * height as usize).div_ceil(2)
    }

    /// Wraps `words` as a `width × height` frame, or `None` when a side is
    /// 0 or over [`MAX_SIDE`], or the slice is too short. The words are
    /// used as they are (all zero is a black frame).
    pub fn new(words: &'a mut [u32], width: u16, height: u16) -> Option<Self> {
        let ok = (1..=MAX_SIDE).contains(&width)
            && (1..=MAX_SIDE).contains(&height)
            && words.len() >= Self::words_len(width, height);
        ok.then_some(PackedFrameBuffer {
            words,
            width,
            height,
            _color: core::marker::PhantomData,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The frame's words, [`words_len`](Self::words_len) of them.
    pub fn words(&self) -> &[u32] {
        &self.words[..Self::words_len(self.width, self.height)]
    }

    /// The pixel at `(x, y)`, or `None` outside the frame.
    pub fn pixel(&self, x: u16, y: u16) -> Option<C> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = y as usize * self.width as usize + x as usize;
        let w = *self.words.get(i / 2)?;
        Some(C::from(RawU16::new((w >> (16 * (i % 2))) as u16)))
    }

    /// The pixels, row-major, `width × height` of them.
    pub fn pixels(&self) -> impl Iterator<Item = C> + '_ {
        let n = self.width as usize * self.height as usize;
        self.words()
            .iter()
            .flat_map(|&w| [w as u16, (w >> 16) as u16])
            .take(n)
            .map(|p| C::from(RawU16::new(p)))
    }

    /// The frame checksum of the pixels, equal to
    /// [`frame_checksum`](crate::port::checksum::frame_checksum) of the
    /// same pixels in a `[C]`.
    pub fn checksum(&self) -> u32 {
        let n = self.width as usize * self.height as usize;
        let words = self.words();
        let mut c = Checksum::default();
        let (whole, last) = words.split_at(n / 2);
        for w in whole {
            c.write(&w.to_le_bytes());
        }
        if n % 2 == 1 {
            if let Some(w) = last.first() {
                c.write(&(*w as u16).to_le_bytes());
            }
        }
        c.value()
    }
}

/// Stores `v` in every word of `run` as groups of 16, 8, 4 or 2 words
/// (double-word stores on the Cortex-M4): a run shorter than 32 words,
/// most spans, is two groups of one size that overlap, with no loop. A
/// longer one is, on Thumb-2 cores, groups of 32 words stored eight
/// registers at a time ([`store_multiple`](super::store_multiple)), and
/// elsewhere a loop of groups of 16; either ends with a last group that
/// overlaps the one before it.
#[inline(always)]
pub(crate) fn fill_words(run: &mut [u32], v: u32) {
    let n = run.len();
    if n >= 16 {
        let group = [v; 16];
        if n >= 32 {
            #[cfg(scanvert_stm)]
            {
                super::store_multiple::fill(run, v);
                return;
            }
            #[cfg(not(scanvert_stm))]
            for q in run.chunks_exact_mut(16) {
                q.copy_from_slice(&group);
            }
        } else {
            run[..16].copy_from_slice(&group);
        }
        run[n - 16..].copy_from_slice(&group);
    } else if n >= 8 {
        both_ends::<8>(run, v);
    } else if n >= 4 {
        both_ends::<4>(run, v);
    } else if n >= 2 {
        both_ends::<2>(run, v);
    } else if let Some(w) = run.first_mut() {
        *w = v;
    }
}

/// Stores `v` in the first `N` and the last `N` words of `run` (`N ≤
/// run.len() ≤ 2N`): every word, the two groups overlapping. The last
/// group first: stored in the other order, the last `N / 2` words of a
/// group of 8 are the same stores as the end of a group of 4, which LLVM
/// then shares between the two sizes' branches as four single-word
/// stores and a jump; in this order a group of 8 is 8 double-word
/// stores.
#[inline(always)]
fn both_ends<const N: usize>(run: &mut [u32], v: u32) {
    let group = [v; N];
    let n = run.len();
    run[n - N..].copy_from_slice(&group);
    run[..N].copy_from_slice(&group);
}

/// Writes pixels `a..b` (`a < b`, both at most `2 · words.len()`) of the
/// packed pixels in `words` with the pixel pair `v` (`c | c << 16`). The
/// words it touches are checked against the slice once: a wrong span
/// writes nothing and never panics.
#[inline(always)]
pub(crate) fn fill_pixels(words: &mut [u32], a: usize, b: usize, v: u32) {
    let Some(mut run) = words.get_mut(a / 2..b.div_ceil(2)) else {
        return;
    };
    if a % 2 == 1 {
        // The high half of the first word.
        if let Some((w, rest)) = core::mem::take(&mut run).split_first_mut() {
            *w = (*w & 0x0000_ffff) | (v & 0xffff_0000);
            run = rest;
        }
    }
    if b % 2 == 1 {
        // The low half of the last word.
        if let Some((w, rest)) = core::mem::take(&mut run).split_last_mut() {
            *w = (*w & 0xffff_0000) | (v & 0x0000_ffff);
            run = rest;
        }
    }
    fill_words(run, v);
}

impl<C> SpanTarget for PackedFrameBuffer<'_, C>
where
    C: PixelColor + Into<RawU16> + From<RawU16>,
{
    type Color = C;
    type Error = Infallible;

    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }

    #[inline]
    fn fill_span(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        if span.y < self.height {
            let x1 = span.x1.min(self.width);
            if span.x0 < x1 {
                let c = bits(color);
                let row = span.y as usize * self.width as usize;
                fill_pixels(
                    self.words,
                    row + span.x0 as usize,
                    row + x1 as usize,
                    c | c << 16,
                );
            }
        }
        Ok(())
    }

    /// Without `fill_span`'s checks: the row and the end are the
    /// caller's. A span past the frame writes other pixels of the words
    /// (the next row's), never past the slice, and never panics.
    #[inline(always)]
    fn fill_span_inside(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let c = bits(color);
        let row = span.y as usize * self.width as usize;
        fill_pixels(
            self.words,
            row + span.x0 as usize,
            row + span.x1 as usize,
            c | c << 16,
        );
        Ok(())
    }

    /// The row's address worked out once, and the runs stored as one
    /// sequence of words (`packed_band::fill_runs`).
    /// A row past the frame writes other pixels of the words, never past
    /// the slice, as in `fill_span_inside`. Out of line: called once a
    /// row, its loop keeps its own registers.
    #[inline(never)]
    fn fill_runs_inside(&mut self, y: u16, x0: u16, runs: &[RowRun<C>]) -> Result<(), Infallible> {
        let base = y as usize * self.width as usize;
        crate::port::packed_band::fill_runs(
            self.words,
            base + x0 as usize,
            runs.iter().map(|r| {
                let c = bits(r.color);
                (base + r.x1 as usize, c | c << 16)
            }),
        );
        Ok(())
    }

    #[inline(always)]
    fn row_start(&self, y: u16) -> usize {
        y as usize * self.width as usize
    }

    #[inline(always)]
    fn row_stride(&self) -> usize {
        self.width as usize
    }

    #[inline(always)]
    fn fill_row_inside(
        &mut self,
        row: usize,
        x0: u16,
        x1: u16,
        color: C,
    ) -> Result<(), Infallible> {
        let c = bits(color);
        fill_pixels(
            self.words,
            row + x0 as usize,
            row + x1 as usize,
            c | c << 16,
        );
        Ok(())
    }

    // Not inlined: called once a rectangle, and kept out of the scan
    // converter's loops, whose registers it would crowd.
    #[inline(never)]
    fn fill_rect(&mut self, span: Span, height: u16, color: C) -> Result<(), Infallible> {
        let y1 = (span.y as usize + height as usize).min(self.height as usize);
        let x1 = span.x1.min(self.width);
        if span.y as usize >= y1 || span.x0 >= x1 {
            return Ok(());
        }
        let c = bits(color);
        let v = c | c << 16;
        let w = self.width as usize;
        let a = span.y as usize * w + span.x0 as usize;
        let n = (x1 - span.x0) as usize;
        if w % 2 == 1 {
            // Rows alternate between starting on a low and a high half.
            for row in 0..y1 - span.y as usize {
                let r = a + row * w;
                fill_pixels(self.words, r, r + n, v);
            }
            return Ok(());
        }
        // An even width: every row has the same halves at its ends, and
        // the same words, `w / 2` further on each row.
        let head = a % 2; // 1: the first pixel is a high half
        let body = (n - head) / 2; // whole words
        let tail = (n - head) % 2; // 1: the last pixel is a low half
        let touched = head + body + tail;
        let stride = w / 2;
        let first = a / 2;
        let last = first + (y1 - 1 - span.y as usize) * stride + touched;
        let Some(region) = self.words.get_mut(first..last) else {
            return Ok(());
        };
        // Column by column: the first words, the whole words, the last
        // words, each loop with few values live.
        if head == 1 {
            for h in region.iter_mut().step_by(stride) {
                *h = (*h & 0x0000_ffff) | (v & 0xffff_0000);
            }
        }
        if let Some(body_region) = region.get_mut(head..) {
            for row in body_region.chunks_mut(stride) {
                if let Some(words) = row.get_mut(..body) {
                    fill_words(words, v);
                }
            }
        }
        if tail == 1 {
            if let Some(tails) = region.get_mut(head + body..) {
                for t in tails.iter_mut().step_by(stride) {
                    *t = (*t & 0xffff_0000) | (v & 0x0000_ffff);
                }
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        let c = bits(color);
        let n = self.width as usize * self.height as usize;
        fill_pixels(self.words, 0, n, c | c << 16);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::port::checksum::frame_checksum;
    use crate::port::framebuffer::FrameBuffer;

    fn px(v: u16) -> Rgb565 {
        Rgb565::from(RawU16::new(v))
    }

    /// Every span of a few frames, odd widths too, against `FrameBuffer`:
    /// the same pixels, the words outside the frame untouched.
    #[test]
    fn spans_write_what_frame_buffer_writes() {
        for (w, h) in [(1u16, 3u16), (2, 2), (5, 3), (8, 2), (13, 3)] {
            let n = PackedFrameBuffer::<Rgb565>::words_len(w, h);
            let mut k = 0u16;
            for y in 0..h + 1 {
                for x0 in 0..w + 2 {
                    for x1 in 0..w + 3 {
                        k = k.wrapping_mul(31).wrapping_add(7);
                        let c = px(k);
                        let mut words_buf = [0x5a5a_a5a5u32; 24];
                        let words = &mut words_buf[..n + 2];
                        let mut pixels_buf = [px(0xa5a5); 48];
                        let pixels = &mut pixels_buf[..w as usize * h as usize];
                        // Both start from the same pattern.
                        for (i, p) in pixels.iter_mut().enumerate() {
                            *p = px((words[i / 2] >> (16 * (i % 2))) as u16);
                        }
                        let mut fb = FrameBuffer::new(pixels, w, h).unwrap();
                        fb.fill_span(Span { y, x0, x1 }, c).unwrap();
                        let mut pk = PackedFrameBuffer::new(words, w, h).unwrap();
                        pk.fill_span(Span { y, x0, x1 }, c).unwrap();
                        assert!(
                            pk.pixels().eq(fb.pixels().iter().copied()),
                            "{w}x{h} span {y} {x0}..{x1}"
                        );
                        assert_eq!(pk.checksum(), frame_checksum(fb.pixels()));
                        // Past the frame: the padding half of an odd frame
                        // and the words beyond it are never written.
                        if (w as usize * h as usize) % 2 == 1 {
                            assert_eq!(words[n - 1] >> 16, 0x5a5a);
                        }
                        assert_eq!(words[n..], [0x5a5a_a5a5; 2]);
                    }
                }
            }
        }
    }

    /// Every rectangle of a few frames, odd widths too, against the same
    /// spans written one by one, and against `FrameBuffer`'s rectangles.
    #[test]
    fn rectangles_write_what_their_spans_write() {
        for (w, h) in [(1u16, 3u16), (2, 4), (5, 3), (8, 3), (7, 4)] {
            let n = PackedFrameBuffer::<Rgb565>::words_len(w, h);
            let mut k = 0u16;
            for y in 0..h + 1 {
                for height in 0..h + 2 {
                    for x0 in 0..w + 1 {
                        for x1 in 0..w + 2 {
                            k = k.wrapping_mul(31).wrapping_add(7);
                            let c = px(k);
                            let span = Span { y, x0, x1 };
                            let mut by_rect = [0x5a5a_a5a5u32; 24];
                            let mut by_span = by_rect;
                            let mut pk =
                                PackedFrameBuffer::new(&mut by_rect[..n + 2], w, h).unwrap();
                            pk.fill_rect(span, height, c).unwrap();
                            let mut ps =
                                PackedFrameBuffer::new(&mut by_span[..n + 2], w, h).unwrap();
                            for row in y..y + height {
                                ps.fill_span(Span { y: row, ..span }, c).unwrap();
                            }
                            let mut pixels_buf = [px(0); 48];
                            let pixels = &mut pixels_buf[..w as usize * h as usize];
                            for (i, p) in pixels.iter_mut().enumerate() {
                                *p = px((0x5a5a_a5a5u32 >> (16 * (i % 2))) as u16);
                            }
                            let mut fb = FrameBuffer::new(pixels, w, h).unwrap();
                            fb.fill_rect(span, height, c).unwrap();
                            assert!(
                                pk.pixels().eq(fb.pixels().iter().copied()),
                                "{w}x{h} rect {span:?} {height}"
                            );
                            assert_eq!(by_rect, by_span, "{w}x{h} rect {span:?} {height}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn clear_and_pixel_access() {
        let mut words = [0u32; 9];
        let mut pk = PackedFrameBuffer::new(&mut words, 3, 5).unwrap();
        pk.clear(px(0x1234)).unwrap();
        assert!(pk.pixels().all(|p| p == px(0x1234)));
        assert_eq!(pk.pixels().count(), 15);
        assert_eq!(pk.pixel(2, 4), Some(px(0x1234)));
        assert_eq!((pk.pixel(3, 0), pk.pixel(0, 5)), (None, None));
        assert_eq!(pk.words().len(), 8);
        assert_eq!(pk.words()[6], 0x1234_1234);
        // Pixel 14, the last, is the low half of word 7; the high half is
        // padding, left as it was, and so is the word beyond.
        assert_eq!(words[7], 0x0000_1234);
        assert_eq!(words[8], 0);
        let mut short = [0u32; 7];
        assert!(PackedFrameBuffer::<Rgb565>::new(&mut short, 3, 5).is_none());
        assert!(PackedFrameBuffer::<Rgb565>::new(&mut words, 0, 5).is_none());
    }

    /// Every span inside a few frames, odd widths too: `fill_span_inside`
    /// writes what `fill_span` writes, and nothing else.
    #[test]
    fn spans_inside_write_what_fill_span_writes() {
        for (w, h) in [(1u16, 3u16), (2, 2), (5, 3), (8, 2), (13, 3)] {
            let n = PackedFrameBuffer::<Rgb565>::words_len(w, h);
            let mut k = 0u16;
            for y in 0..h {
                for x0 in 0..w {
                    for x1 in x0 + 1..=w {
                        k = k.wrapping_mul(31).wrapping_add(7);
                        let c = px(k);
                        let span = Span { y, x0, x1 };
                        let mut inside = [0x5a5a_a5a5u32; 24];
                        let mut checked = inside;
                        PackedFrameBuffer::new(&mut inside[..n + 2], w, h)
                            .unwrap()
                            .fill_span_inside(span, c)
                            .unwrap();
                        PackedFrameBuffer::new(&mut checked[..n + 2], w, h)
                            .unwrap()
                            .fill_span(span, c)
                            .unwrap();
                        assert_eq!(inside, checked, "{w}x{h} span {span:?}");
                    }
                }
            }
        }
    }

    /// A span that breaks `fill_span_inside`'s condition never panics.
    #[test]
    fn spans_outside_never_panic() {
        for (w, h) in [(1u16, 3u16), (5, 3), (8, 2)] {
            let n = PackedFrameBuffer::<Rgb565>::words_len(w, h);
            for y in [0, h - 1, h, h + 1, u16::MAX] {
                for (x0, x1) in [(0, w + 3), (w, w + 1), (3, 1), (u16::MAX - 1, u16::MAX)] {
                    let mut words = [0x5a5a_a5a5u32; 24];
                    PackedFrameBuffer::new(&mut words[..n], w, h)
                        .unwrap()
                        .fill_span_inside(Span { y, x0, x1 }, px(9))
                        .unwrap();
                    assert_eq!(words[n..], [0x5a5a_a5a5; 24][n..]);
                }
            }
        }
    }

    #[test]
    fn fill_words_writes_exactly_its_run() {
        for len in 0..70 {
            for at in 0..5 {
                let mut w = [0u32; 80];
                fill_words(&mut w[at..at + len], 9);
                for (i, &v) in w.iter().enumerate() {
                    assert_eq!(v == 9, (at..at + len).contains(&i), "{len} {at} {i}");
                }
            }
        }
    }
}
