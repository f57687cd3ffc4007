//! A frame buffer in caller-owned memory.

use crate::port::{Span, SpanTarget};
use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::{PixelColor, Rgb565};

/// Largest width or height of a frame, in pixels.
pub const MAX_SIDE: u16 = 4096;

/// A `width × height` frame buffer over a slice the caller owns, row-major,
/// one `C` per pixel.
///
/// # Guarantees
/// `1 <= width, height <= 4096` and the slice holds at least
/// `width * height` pixels, so every in-range pixel access is in bounds.
#[derive(Debug)]
pub struct FrameBuffer<'a, C: PixelColor = Rgb565> {
    pixels: &'a mut [C],
    width: u16,
    height: u16,
}

impl<'a, C: PixelColor> FrameBuffer<'a, C> {
    /// Pixels needed for a `width × height` frame.
    pub const fn buffer_len(width: u16, height: u16) -> usize {
        width as usize * height as usize
    }

    /// Wraps `pixels` as a `width × height` frame, or `None` when a side is
    /// 0 or over [`MAX_SIDE`], or the slice is too short.
    pub fn new(pixels: &'a mut [C], width: u16, height: u16) -> Option<Self> {
        let ok = (1..=MAX_SIDE).contains(&width)
            && (1..=MAX_SIDE).contains(&height)
            && pixels.len() >= Self::buffer_len(width, height);
        ok.then_some(FrameBuffer {
            pixels,
            width,
            height,
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

    /// The pixel at `(x, y)`, or `None` outside the frame.
    pub fn pixel(&self, x: u16, y: u16) -> Option<C> {
        if x < self.width && y < self.height {
            self.pixels
                .get(y as usize * self.width as usize + x as usize)
                .copied()
        } else {
            None
        }
    }

    /// The pixels, row-major, `width * height` of them.
    pub fn pixels(&self) -> &[C] {
        let n = Self::buffer_len(self.width, self.height);
        &self.pixels[..n]
    }

    /// Row `y`, or `None` outside the frame.
    pub fn row(&self, y: u16) -> Option<&[C]> {
        let w = self.width as usize;
        let start = y as usize * w;
        (y < self.height).then(|| &self.pixels[start..start + w])
    }
}

/// Fills one run of pixels.
///
/// `slice::fill` vectorises into a loop of wide stores, a loop of narrower
/// ones and a tail, whose set-up costs more than the stores on runs of a
/// few dozen pixels, the common length of a polygon's span. Runs of 8 to 63
/// pixels are written instead as copies of 8 pixels (16 bytes of RGB565),
/// the last copy overlapping the one before it, so that no tail loop is
/// left; shorter runs still use `slice::fill`. So do longer ones on
/// 64-bit hosts, where `slice::fill` is at the memory limit; on 32-bit
/// targets (Cortex-M, RV32) the copies of 8 stay cheaper at any length,
/// where `slice::fill`'s loop depends on what the compiler makes of its
/// caller (in a band, about 0.7 Cortex-M4 instructions a pixel more).
/// `docs/performance-log.md` has the measurements.
#[inline(always)]
pub(crate) fn fill_run<C: Copy>(run: &mut [C], color: C) {
    const LONGEST: usize = match cfg!(target_pointer_width = "64") {
        true => 64,
        false => usize::MAX,
    };
    let n = run.len();
    if (8..LONGEST).contains(&n) {
        let splat = [color; 8];
        // Whole chunks need no bounds check; the last, overlapping copy
        // covers the tail.
        for c in run.chunks_exact_mut(8) {
            c.copy_from_slice(&splat);
        }
        if !n.is_multiple_of(8) {
            run[n - 8..].copy_from_slice(&splat);
        }
    } else {
        run.fill(color);
    }
}

/// [`fill_run`] of the columns `x0..x1` of the row that starts at index
/// `row` of `pixels` (a target's `fill_row_inside`): nothing where they
/// are not all in the slice.
#[inline(always)]
pub(crate) fn fill_row_at<C: Copy>(pixels: &mut [C], row: usize, x0: u16, x1: u16, color: C) {
    let (a, b) = (row.wrapping_add(x0 as usize), row.wrapping_add(x1 as usize));
    if let Some(run) = pixels.get_mut(a..b) {
        fill_run(run, color);
    }
}

impl<C: PixelColor> SpanTarget for FrameBuffer<'_, C> {
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
                let base = span.y as usize * self.width as usize;
                // In bounds by the guarantee on `pixels.len()`; `get_mut`
                // keeps a wrong span from ever panicking.
                if let Some(run) = self
                    .pixels
                    .get_mut(base + span.x0 as usize..base + x1 as usize)
                {
                    fill_run(run, color);
                }
            }
        }
        Ok(())
    }

    /// Without `fill_span`'s checks: the row and the end are the
    /// caller's. A span past the frame writes other pixels (the next
    /// row's) or nothing, never past the slice, and never panics.
    #[inline(always)]
    fn fill_span_inside(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let base = span.y as usize * self.width as usize;
        if let Some(run) = self
            .pixels
            .get_mut(base + span.x0 as usize..base + span.x1 as usize)
        {
            fill_run(run, color);
        }
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
        fill_row_at(self.pixels, row, x0, x1, color);
        Ok(())
    }

    fn fill_rect(&mut self, span: Span, height: u16, color: C) -> Result<(), Infallible> {
        let y1 = (span.y as usize + height as usize).min(self.height as usize);
        let x1 = span.x1.min(self.width);
        if (span.y as usize) < y1 && span.x0 < x1 {
            let w = self.width as usize;
            let (a, b) = (span.x0 as usize, x1 as usize);
            // Rows y..y1, the last one cut after x1: in bounds by the
            // guarantee on `pixels.len()`.
            let region = self.pixels.get_mut(span.y as usize * w..(y1 - 1) * w + b);
            if let Some(region) = region {
                for row in region.chunks_mut(w) {
                    if let Some(run) = row.get_mut(a..b) {
                        fill_run(run, color);
                    }
                }
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        let n = Self::buffer_len(self.width, self.height);
        self.pixels[..n].fill(color);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every span inside a few frames: `fill_span_inside` writes what
    /// `fill_span` writes; spans outside never panic nor leave the slice.
    #[test]
    fn spans_inside_write_what_fill_span_writes() {
        let px = |k: u16| Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(k));
        for (w, h) in [(1u16, 3u16), (2, 2), (5, 3), (13, 3)] {
            let n = w as usize * h as usize;
            let mut k = 0u16;
            for y in 0..h {
                for x0 in 0..w {
                    for x1 in x0 + 1..=w {
                        k = k.wrapping_mul(31).wrapping_add(7);
                        let span = Span { y, x0, x1 };
                        let mut inside = [px(0x5a5a); 40];
                        let mut checked = inside;
                        FrameBuffer::new(&mut inside[..n], w, h)
                            .unwrap()
                            .fill_span_inside(span, px(k))
                            .unwrap();
                        FrameBuffer::new(&mut checked[..n], w, h)
                            .unwrap()
                            .fill_span(span, px(k))
                            .unwrap();
                        assert_eq!(inside, checked, "{w}x{h} span {span:?}");
                    }
                }
            }
            for y in [0, h - 1, h, u16::MAX] {
                for (x0, x1) in [(0, w + 3), (w, w + 1), (3, 1), (u16::MAX - 1, u16::MAX)] {
                    let mut pixels = [px(0x5a5a); 40];
                    FrameBuffer::new(&mut pixels[..n], w, h)
                        .unwrap()
                        .fill_span_inside(Span { y, x0, x1 }, px(9))
                        .unwrap();
                    assert_eq!(pixels[n..], [px(0x5a5a); 40][n..]);
                }
            }
        }
    }

    #[test]
    fn fill_run_writes_exactly_its_run() {
        for len in 0..140 {
            for x0 in 0..10 {
                let mut px = [0u16; 160];
                fill_run(&mut px[x0..x0 + len], 7);
                for (i, &p) in px.iter().enumerate() {
                    assert_eq!(
                        p == 7,
                        (x0..x0 + len).contains(&i),
                        "len {len} x0 {x0} px {i}"
                    );
                }
            }
        }
    }
}
