//! The frame-buffer port: where spans of pixels leave the rasteriser.
//!
//! The unit of work is the horizontal span, as on the write port of the
//! dual-port frame-buffer RAM that the graphic controller drives. A target
//! implements two methods; a plain in-memory implementation is
//! [`FrameBuffer`], and the simulator's
//! dual-port RAM is another.

pub mod band;
#[cfg(feature = "embedded-graphics")]
pub mod band_draw_target;
pub mod checksum;
#[cfg(feature = "embedded-graphics")]
pub mod draw_target;
pub mod framebuffer;

pub use checksum::Checksum;
pub use framebuffer::FrameBuffer;

use embedded_graphics_core::pixelcolor::PixelColor;

/// A horizontal run of pixels `x0..x1` (end exclusive) on row `y`.
///
/// # Guarantees
/// Spans handed to a [`SpanTarget`] by this crate are non-empty
/// (`x0 < x1`) and lie inside the target: `x1 <= width`, `y < height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Span {
    /// Row.
    pub y: u16,
    /// First pixel.
    pub x0: u16,
    /// One past the last pixel.
    pub x1: u16,
}

impl Span {
    /// Number of pixels.
    #[inline]
    pub const fn len(&self) -> usize {
        self.x1.saturating_sub(self.x0) as usize
    }

    /// `true` when the span holds no pixel.
    #[inline]
    pub const fn is_empty(&self) -> bool {
        self.x1 <= self.x0
    }
}

/// A frame buffer that takes horizontal spans.
///
/// Implementations may rely on the [`Span`] guarantees for spans that
/// come from this crate, but must not panic on any span: a span outside the
/// target is discarded (or clipped) without error, as embedded-graphics asks
/// of a `DrawTarget`.
pub trait SpanTarget {
    /// The pixel format.
    type Color: PixelColor;
    /// What a write can fail with; `core::convert::Infallible` for memory.
    type Error;

    /// Width and height in pixels. Both are at most 4096.
    fn size(&self) -> (u16, u16);

    /// Writes `color` to every pixel of `span`.
    fn fill_span(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error>;

    /// Writes `color` to every pixel. The default fills the rows one span
    /// each; memory-mapped targets override it with one fill.
    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        let (w, h) = self.size();
        if w == 0 {
            return Ok(());
        }
        for y in 0..h {
            self.fill_span(Span { y, x0: 0, x1: w }, color)?;
        }
        Ok(())
    }
}

impl<T: SpanTarget + ?Sized> SpanTarget for &mut T {
    type Color = T::Color;
    type Error = T::Error;
    #[inline]
    fn size(&self) -> (u16, u16) {
        (**self).size()
    }
    #[inline]
    fn fill_span(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error> {
        (**self).fill_span(span, color)
    }
    #[inline]
    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        (**self).clear(color)
    }
}
