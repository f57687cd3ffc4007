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
                    run.fill(color);
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
