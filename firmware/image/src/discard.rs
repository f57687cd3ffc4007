//! A port that takes every span and writes nothing (feature `discard`),
//! to count the instructions of everything but the pixel writes: list
//! check, edge set-up, stepping and span clipping.
//!
//! It is a feature, not a second pass in the same image, because a second
//! port type changes how the compiler inlines the render path, and with
//! it the counts being measured.

use crate::Pixel;
use core::convert::Infallible;
use scanvert::port::{Span, SpanTarget};

/// A `width × height` frame that discards every span.
#[derive(Debug)]
pub struct Discard {
    size: (u16, u16),
}

impl Discard {
    /// A frame of `width × height`.
    pub fn new(width: u16, height: u16) -> Self {
        Discard {
            size: (width, height),
        }
    }
}

impl SpanTarget for Discard {
    type Color = Pixel;
    type Error = Infallible;

    fn size(&self) -> (u16, u16) {
        self.size
    }

    fn fill_span(&mut self, _span: Span, _color: Pixel) -> Result<(), Infallible> {
        Ok(())
    }

    fn clear(&mut self, _color: Pixel) -> Result<(), Infallible> {
        Ok(())
    }
}
