//! The frame-buffer port: where spans of pixels leave the rasteriser.
//!
//! The unit of work is the horizontal span, as on the write port of the
//! dual-port frame-buffer RAM that the graphic controller drives. A target
//! implements two methods; a plain in-memory implementation is
//! [`FrameBuffer`], one of 16-bit pixels written a word (two pixels) at a
//! time is [`PackedFrameBuffer`], and the simulator's
//! dual-port RAM is another.

pub mod band;
pub mod band_draw_target;
pub mod checksum;
pub mod draw_target;
pub mod framebuffer;
pub mod packed;
pub mod packed_band;
pub mod panel;
pub mod runs;
pub mod scanvideo;
#[cfg(scanvert_stm)]
mod store_multiple;

pub use checksum::Checksum;
pub use framebuffer::FrameBuffer;
pub use packed::PackedFrameBuffer;
pub use packed_band::{PackedBand, PackedBandTarget};
pub use panel::{AsyncPanel, Panel, PanelError};

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

/// One run of a row handed to [`SpanTarget::fill_runs_inside`]: the
/// pixels from the end of the run before it (or the batch's first
/// column) up to `x1`, exclusive, in `color`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RowRun<C> {
    /// One past the run's last pixel.
    pub x1: u16,
    /// Its colour.
    pub color: C,
}

/// What a stage wrote into a [`SpanTarget`]: spans, and the pixels in
/// them. The rasteriser's fills, the run decoder and the labels all count
/// with it.
///
/// # Limits
/// Both counts are `u32`, enough for 256 whole frames of 4096 × 4096;
/// [`Counts::span`], `+` and `+=` saturate rather than wrap or panic.
/// A frame painted far to near
/// ([`Resolve::Paint`](crate::visible::Resolve::Paint)) counts each pixel
/// as often as it writes it, with a plain add on its hot path: past
/// `u32::MAX` (more than 256 layers over a 4096 × 4096 frame) that count
/// wraps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Counts {
    /// Spans handed to the target.
    pub spans: u32,
    /// Pixels in those spans.
    pub pixels: u32,
}

impl Counts {
    /// Counts one span of `pixels` pixels.
    #[inline]
    pub fn span(&mut self, pixels: u32) {
        self.spans = self.spans.saturating_add(1);
        self.pixels = self.pixels.saturating_add(pixels);
    }
}

impl core::ops::Add for Counts {
    type Output = Counts;
    #[inline]
    fn add(self, other: Counts) -> Counts {
        Counts {
            spans: self.spans.saturating_add(other.spans),
            pixels: self.pixels.saturating_add(other.pixels),
        }
    }
}

impl core::ops::AddAssign for Counts {
    #[inline]
    fn add_assign(&mut self, other: Counts) {
        *self = *self + other;
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

    /// Whether writing a pixel again costs no more than a store to
    /// memory: `true` (the default) for a buffer in RAM (a frame buffer, a
    /// band), `false` for a display's window or a port that takes its time
    /// for every pixel written. [`Resolve::Auto`] paints far to near, which
    /// writes a pixel as often as faces cover it, only into a target that
    /// says `true`.
    ///
    /// [`Resolve::Auto`]: crate::visible::Resolve::Auto
    const OVERDRAW_IS_CHEAP: bool = true;

    /// Whether the 3D sweep hands every row's runs over in batches
    /// ([`fill_runs_inside`](Self::fill_runs_inside)) rather than one by
    /// one ([`fill_span_inside`](Self::fill_span_inside)): `true` for a
    /// target to which a batch costs less than its runs one at a time (a
    /// row of runs, [`RowRuns`](runs::RowRuns), appends a batch in one
    /// pass), `false` (the default) for one to which each run costs the
    /// same either way, where gathering the batch would only add work. A
    /// row whose faces lie side by side is handed over in batches to
    /// every target. The pixels are the same either way.
    const RUNS_IN_BATCHES: bool = false;

    /// Width and height in pixels. Both are at most 4096.
    fn size(&self) -> (u16, u16);

    /// Writes `color` to every pixel of `span`.
    fn fill_span(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error>;

    /// Writes `color` to every pixel of `span`, which the caller has
    /// already clipped to the target: `span.y < height` and
    /// `span.x0 < span.x1 <= width`. The default is
    /// [`fill_span`](Self::fill_span); a frame buffer overrides it to skip
    /// the checks that `fill_span` would repeat (the 3D sweep's run writer
    /// clips each run itself). A span that breaks the condition must still
    /// not panic nor write outside the target's memory, but may write
    /// pixels other than its own.
    #[inline(always)]
    fn fill_span_inside(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error> {
        self.fill_span(span, color)
    }

    /// Where row `y` (`y <= height`: the row past the last is where a
    /// run of rows ends) starts, for
    /// [`fill_row_inside`](Self::fill_row_inside): a frame buffer's index
    /// of the row's first pixel, so that a caller writing row after row
    /// adds [`row_stride`](Self::row_stride) instead of multiplying. The
    /// default is `y` itself. A target overrides the three together or
    /// none of them.
    #[inline(always)]
    fn row_start(&self, y: u16) -> usize {
        y as usize
    }

    /// How far [`row_start`](Self::row_start) moves from one row to the
    /// next: the width of a frame buffer; 1 (the default) where the start
    /// is the row.
    #[inline(always)]
    fn row_stride(&self) -> usize {
        1
    }

    /// [`fill_span_inside`](Self::fill_span_inside) of the columns
    /// `x0..x1` of the row that starts at `row` (a
    /// [`row_start`](Self::row_start) plus whole
    /// [`row_stride`](Self::row_stride)s, inside the target), with the same
    /// conditions. The default writes the span of row `row`.
    #[inline(always)]
    fn fill_row_inside(
        &mut self,
        row: usize,
        x0: u16,
        x1: u16,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        let span = Span {
            y: row as u16,
            x0,
            x1,
        };
        self.fill_span_inside(span, color)
    }

    /// Writes the runs `runs` of row `y` one after the other from column
    /// `x0`: run `i` covers `runs[i - 1].x1..runs[i].x1` (`x0..runs[0].x1`
    /// for the first), as [`fill_span_inside`](Self::fill_span_inside)
    /// of each, with the same conditions: `y < height`, every run
    /// non-empty, the last ending by the width. The 3D sweep hands the
    /// runs of a row of faces side by side over in batches of this form.
    /// The default writes each
    /// run by `fill_span_inside`, stopping at the first error; a packed
    /// target overrides it to work out the row's address once and store
    /// the half-word between two runs' words once.
    #[inline]
    fn fill_runs_inside(
        &mut self,
        y: u16,
        x0: u16,
        runs: &[RowRun<Self::Color>],
    ) -> Result<(), Self::Error> {
        let mut x = x0;
        for r in runs {
            self.fill_span_inside(Span { y, x0: x, x1: r.x1 }, r.color)?;
            x = r.x1;
        }
        Ok(())
    }

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

    /// Writes `color` to the span `span.x0..span.x1` of the `height` rows
    /// from `span.y` down: a rectangle, as the scan converter finds between
    /// two vertical edges. The default writes it a span a row; frame
    /// buffers override it to work out the addresses once.
    fn fill_rect(
        &mut self,
        span: Span,
        height: u16,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        for y in span.y..span.y.saturating_add(height) {
            self.fill_span(Span { y, ..span }, color)?;
        }
        Ok(())
    }

    /// A polygon begins: [`Rasterizer::fill`](crate::raster::scan::Rasterizer::fill)
    /// calls it once per polygon, before its spans. Memory ignores it (the
    /// default); a port with a set-up cost per polygon, such as the
    /// simulator's write port, counts it here.
    #[inline(always)]
    fn begin_polygon(&mut self) {}
}

impl<T: SpanTarget + ?Sized> SpanTarget for &mut T {
    type Color = T::Color;
    type Error = T::Error;
    const OVERDRAW_IS_CHEAP: bool = T::OVERDRAW_IS_CHEAP;
    const RUNS_IN_BATCHES: bool = T::RUNS_IN_BATCHES;
    #[inline]
    fn size(&self) -> (u16, u16) {
        (**self).size()
    }
    #[inline]
    fn fill_span(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error> {
        (**self).fill_span(span, color)
    }
    #[inline(always)]
    fn fill_span_inside(&mut self, span: Span, color: Self::Color) -> Result<(), Self::Error> {
        (**self).fill_span_inside(span, color)
    }
    #[inline(always)]
    fn row_start(&self, y: u16) -> usize {
        (**self).row_start(y)
    }
    #[inline(always)]
    fn row_stride(&self) -> usize {
        (**self).row_stride()
    }
    #[inline(always)]
    fn fill_row_inside(
        &mut self,
        row: usize,
        x0: u16,
        x1: u16,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        (**self).fill_row_inside(row, x0, x1, color)
    }
    #[inline]
    fn fill_runs_inside(
        &mut self,
        y: u16,
        x0: u16,
        runs: &[RowRun<Self::Color>],
    ) -> Result<(), Self::Error> {
        (**self).fill_runs_inside(y, x0, runs)
    }
    #[inline]
    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        (**self).clear(color)
    }
    #[inline]
    fn fill_rect(
        &mut self,
        span: Span,
        height: u16,
        color: Self::Color,
    ) -> Result<(), Self::Error> {
        (**self).fill_rect(span, height, color)
    }
    #[inline(always)]
    fn begin_polygon(&mut self) {
        (**self).begin_polygon()
    }
}

#[cfg(test)]
mod tests {
    use super::Counts;

    #[test]
    fn counts_add_up_and_saturate() {
        let mut c = Counts::default();
        c.span(5);
        c.span(0);
        assert_eq!(
            c,
            Counts {
                spans: 2,
                pixels: 5
            }
        );
        c += Counts {
            spans: 1,
            pixels: 3,
        };
        assert_eq!(
            c,
            Counts {
                spans: 3,
                pixels: 8
            }
        );
        let top = Counts {
            spans: u32::MAX,
            pixels: u32::MAX - 1,
        };
        assert_eq!(
            c + top,
            Counts {
                spans: u32::MAX,
                pixels: u32::MAX
            }
        );
    }
}
