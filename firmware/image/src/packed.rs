//! A frame of RGB565 pixels packed two to a `u32` (feature `packed`): a
//! measured proposal for Cortex-M, where a `slice::fill` of 16-bit pixels
//! is one `strh` a pixel. Spans are written a word (two pixels) at a time,
//! with a half-word at an odd start or end. Pixel `2k` is the low half of
//! word `k`, so the words' little-endian bytes are the pixels' bytes, and
//! the frame checksum is the same as `FrameBuffer`'s.
//!
//! The words are stored four at a time (`q.copy_from_slice(&[v; 4])`,
//! which becomes one `stm`/`strd` pair or four `str` with the value held in
//! registers); a plain `slice::fill` of `u32` inside the render loop was
//! one `str` a word with the value reloaded from the stack each time.

use crate::Pixel;
use core::convert::Infallible;
use scanvert::pixelcolor::IntoStorage;
use scanvert::port::checksum::Checksum;
use scanvert::port::{Span, SpanTarget};

/// A `width × height` frame over caller-owned words, `width` even.
#[derive(Debug)]
pub struct PackedFrame<'a> {
    words: &'a mut [u32],
    width: u16,
    height: u16,
}

impl<'a> PackedFrame<'a> {
    /// The frame, or `None` for an odd or zero width, a zero height or too
    /// few words.
    pub fn new(words: &'a mut [u32], width: u16, height: u16) -> Option<Self> {
        let n = width as usize / 2 * height as usize;
        let ok = width.is_multiple_of(2) && width > 0 && height > 0 && words.len() >= n;
        ok.then_some(PackedFrame {
            words,
            width,
            height,
        })
    }

    /// The checksum of the pixels, as `frame_checksum` computes it.
    pub fn checksum(&self) -> u32 {
        let n = self.width as usize / 2 * self.height as usize;
        let mut c = Checksum::default();
        for w in &self.words[..n] {
            c.write(&w.to_le_bytes());
        }
        c.value()
    }
}

/// Fills `run` four words (eight pixels) a store group at a time.
#[inline(always)]
fn fill_words(run: &mut [u32], v: u32) {
    let mut quads = run.chunks_exact_mut(4);
    for q in &mut quads {
        q.copy_from_slice(&[v; 4]);
    }
    for w in quads.into_remainder() {
        *w = v;
    }
}

impl SpanTarget for PackedFrame<'_> {
    type Color = Pixel;
    type Error = Infallible;

    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }

    #[inline]
    fn fill_span(&mut self, span: Span, color: Pixel) -> Result<(), Infallible> {
        if span.y >= self.height {
            return Ok(());
        }
        let (mut a, mut b) = (span.x0 as usize, span.x1.min(self.width) as usize);
        if a >= b {
            return Ok(());
        }
        let v = color.into_storage() as u32;
        let row = span.y as usize * (self.width as usize / 2);
        if a % 2 == 1 {
            if let Some(w) = self.words.get_mut(row + a / 2) {
                *w = (*w & 0xffff) | v << 16;
            }
            a += 1;
        }
        if b % 2 == 1 && a < b {
            if let Some(w) = self.words.get_mut(row + b / 2) {
                *w = (*w & 0xffff_0000) | v;
            }
            b -= 1;
        }
        if a < b {
            if let Some(run) = self.words.get_mut(row + a / 2..row + b / 2) {
                fill_words(run, v | v << 16);
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: Pixel) -> Result<(), Infallible> {
        let v = color.into_storage() as u32;
        let n = self.width as usize / 2 * self.height as usize;
        if let Some(all) = self.words.get_mut(..n) {
            fill_words(all, v | v << 16);
        }
        Ok(())
    }
}
