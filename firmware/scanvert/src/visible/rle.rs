//! Run-length scan lines: what the visible-surface stage produces, one row
//! at a time, and the decoder that writes a row into a frame-buffer port.
//!
//! # Format
//!
//! A row is a sequence of [`Run`]s that cover its columns `0..W` from left
//! to right, with no gap and no overlap. A run is 4 bytes:
//!
//! ```text
//! bits  0..16  length in pixels, 1..=4096
//! bits 16..32  ink: a face of the store (0..=65534), or 0xFFFF for the background
//! ```
//!
//! ([`Run::to_bits`] gives that `u32`; little-endian in memory or on a
//! wire.) The ink's colour is the face's ([`Face::color`]); the background
//! is wherever no face is. Two runs next to each other always differ in
//! colour: runs of the same colour, even of different faces, are merged.
//! A row therefore has at most `W` runs, so a buffer of `W` runs is always
//! enough ([`RunWriter`] checks the capacity anyway).
//!
//! # Decoding
//!
//! [`decode_row`] turns the runs into [`SpanTarget::fill_span`] calls. The
//! background is either filled with a colour or skipped, so that the 3D
//! layer can lie over 2D content already in the frame buffer.
//!
//! [`Face::color`]: crate::visible::store::Face::color

use crate::port::{Counts, Span, SpanTarget};
use core::fmt;

/// One run of a run-length scan line. See the [module](self) docs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Run {
    len: u16,
    ink: u16,
}

impl Run {
    /// The ink of the background.
    pub const BACKGROUND: u16 = 0xffff;

    /// An unused slot.
    pub const EMPTY: Run = Run {
        len: 0,
        ink: Run::BACKGROUND,
    };

    /// `len` pixels of `ink`.
    pub const fn new(len: u16, ink: u16) -> Self {
        Run { len, ink }
    }

    /// Length in pixels.
    pub const fn len(&self) -> u16 {
        self.len
    }

    /// `true` for a run of no pixel (never in a row).
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The face, or [`Run::BACKGROUND`].
    pub const fn ink(&self) -> u16 {
        self.ink
    }

    /// `true` for the background.
    pub const fn is_background(&self) -> bool {
        self.ink == Run::BACKGROUND
    }

    /// The run as one word: length in the low half, ink in the high half.
    pub const fn to_bits(self) -> u32 {
        self.len as u32 | (self.ink as u32) << 16
    }

    /// The run from [`Run::to_bits`].
    pub const fn from_bits(bits: u32) -> Self {
        Run {
            len: bits as u16,
            ink: (bits >> 16) as u16,
        }
    }
}

/// The row buffer is full.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RunsFull {
    /// Runs the buffer holds.
    pub capacity: usize,
}

impl fmt::Display for RunsFull {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "a row needs more than the {} runs available",
            self.capacity
        )
    }
}

impl core::error::Error for RunsFull {}

/// Writes one row of runs into a caller-owned buffer, merging a run into
/// the one before when the ink is the same.
#[derive(Debug)]
#[doc(hidden)]
pub struct RunWriter<'r> {
    runs: &'r mut [Run],
    n: usize,
}

impl<'r> RunWriter<'r> {
    /// An empty row in `runs`.
    pub fn new(runs: &'r mut [Run]) -> Self {
        RunWriter { runs, n: 0 }
    }

    /// Empties the row.
    #[inline]
    pub fn clear(&mut self) {
        self.n = 0;
    }

    /// Appends `len` pixels of `ink`, merged with the last run when it has
    /// the same ink. A zero length is ignored.
    #[inline]
    pub fn push(&mut self, len: u16, ink: u16) -> Result<(), RunsFull> {
        if len == 0 {
            return Ok(());
        }
        if let Some(last) = self.n.checked_sub(1).and_then(|i| self.runs.get_mut(i)) {
            if last.ink == ink {
                last.len = last.len.saturating_add(len);
                return Ok(());
            }
        }
        let capacity = self.runs.len();
        let slot = self.runs.get_mut(self.n).ok_or(RunsFull { capacity })?;
        *slot = Run { len, ink };
        self.n += 1;
        Ok(())
    }

    /// Appends a run as it is, without merging; does nothing when the
    /// buffer is full (callers that size it check first).
    #[inline]
    pub fn append(&mut self, len: u16, ink: u16) {
        if let Some(slot) = self.runs.get_mut(self.n) {
            *slot = Run { len, ink };
            self.n += 1;
        }
    }

    /// The ink of the last run, if any.
    #[inline]
    pub fn last_ink(&self) -> Option<u16> {
        self.n
            .checked_sub(1)
            .and_then(|i| self.runs.get(i))
            .map(|r| r.ink)
    }

    /// The runs so far.
    pub fn runs(&self) -> &[Run] {
        self.runs.get(..self.n).unwrap_or(&[])
    }
}

/// Writes the runs of row `y` into `target` as spans, from column 0:
/// `ink(face)` gives each face's colour, and the background is filled with
/// `background` or skipped when it is `None`. Pixels beyond the target's
/// width or height are discarded.
#[doc(hidden)]
pub fn decode_row<T, F>(
    target: &mut T,
    y: u16,
    runs: &[Run],
    mut ink: F,
    background: Option<T::Color>,
) -> Result<Counts, T::Error>
where
    T: SpanTarget + ?Sized,
    F: FnMut(u16) -> T::Color,
{
    let mut counts = Counts::default();
    let (w, h) = target.size();
    if y >= h {
        return Ok(counts);
    }
    let mut x = 0u32;
    for run in runs {
        let x0 = x;
        x += run.len as u32;
        if x0 >= w as u32 {
            break;
        }
        let x1 = x.min(w as u32);
        if x1 <= x0 {
            continue;
        }
        let color = if run.is_background() {
            match background {
                Some(c) => c,
                None => continue,
            }
        } else {
            ink(run.ink)
        };
        let span = Span {
            y,
            x0: x0 as u16,
            x1: x1 as u16,
        };
        target.fill_span(span, color)?;
        counts.span(x1 - x0);
    }
    Ok(counts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::port::framebuffer::FrameBuffer;
    use embedded_graphics_core::pixelcolor::{Gray8, GrayColor};

    #[test]
    fn writer_merges_and_checks_capacity() {
        let mut buf = [Run::EMPTY; 3];
        let mut w = RunWriter::new(&mut buf);
        w.push(3, 7).unwrap();
        w.push(2, 7).unwrap();
        w.push(0, 9).unwrap();
        w.push(4, Run::BACKGROUND).unwrap();
        w.push(1, 2).unwrap();
        assert_eq!(w.push(1, 3), Err(RunsFull { capacity: 3 }));
        assert_eq!(
            w.runs(),
            &[Run::new(5, 7), Run::new(4, Run::BACKGROUND), Run::new(1, 2)]
        );
        assert_eq!(
            Run::from_bits(Run::new(4096, 12).to_bits()),
            Run::new(4096, 12)
        );
    }

    #[test]
    fn decoder_fills_or_skips_the_background() {
        let runs = [
            Run::new(2, Run::BACKGROUND),
            Run::new(3, 1),
            Run::new(1, Run::BACKGROUND),
            Run::new(9, 2),
        ];
        let mut px = [Gray8::new(5); 8 * 2];
        let mut fb = FrameBuffer::new(&mut px, 8, 2).unwrap();
        let ink = |f: u16| Gray8::new(100 + f as u8);
        let c = decode_row(&mut fb, 1, &runs, ink, None).unwrap();
        assert_eq!(
            c,
            Counts {
                spans: 2,
                pixels: 5
            }
        );
        let row: [u8; 8] = core::array::from_fn(|x| fb.pixel(x as u16, 1).unwrap().luma());
        assert_eq!(row, [5, 5, 101, 101, 101, 5, 102, 102]);
        let c = decode_row(&mut fb, 0, &runs, ink, Some(Gray8::new(0))).unwrap();
        assert_eq!(c.pixels, 8);
        let row: [u8; 8] = core::array::from_fn(|x| fb.pixel(x as u16, 0).unwrap().luma());
        assert_eq!(row, [0, 0, 101, 101, 101, 0, 102, 102]);
        // Rows outside the target are discarded.
        assert_eq!(decode_row(&mut fb, 2, &runs, ink, None).unwrap().spans, 0);
    }
}
