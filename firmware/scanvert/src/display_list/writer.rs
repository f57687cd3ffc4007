//! Emitting a display list into a caller-owned buffer.

use super::{Opcode, HEADER_LEN, MAGIC, MAX_VERTICES, VERSION};
use crate::clip::ClipWindow;
use crate::fixed::{Vertex, Vertex3};
use core::fmt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// Why a [`Writer`] refused a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum WriteError {
    /// The buffer is full; nothing of the command was written.
    BufferFull,
    /// A frame side outside 1..=4096.
    BadFrameSize,
    /// A polygon with fewer than 3 or more than 65535 vertices.
    VertexCount(usize),
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::BufferFull => f.write_str("display-list buffer is full"),
            WriteError::BadFrameSize => f.write_str("frame size is outside 1..=4096"),
            WriteError::VertexCount(n) => {
                write!(f, "polygon has {n} vertices; 3..=65535 are allowed")
            }
        }
    }
}

impl core::error::Error for WriteError {}

/// Writes a display list into `buf`. Every method either writes a whole
/// command or nothing, so the list is valid after any sequence of calls,
/// once [`Writer::finish`] has stamped the length.
#[derive(Debug)]
pub struct Writer<'b> {
    buf: &'b mut [u8],
    len: usize,
}

impl<'b> Writer<'b> {
    /// Starts a list for a `width × height` frame.
    pub fn new(buf: &'b mut [u8], width: u16, height: u16) -> Result<Self, WriteError> {
        if !(1..=4096).contains(&width) || !(1..=4096).contains(&height) {
            return Err(WriteError::BadFrameSize);
        }
        let mut w = Writer { buf, len: 0 };
        let mut h = [0u8; HEADER_LEN];
        h[..4].copy_from_slice(&MAGIC);
        h[4..6].copy_from_slice(&VERSION.to_le_bytes());
        h[6..8].copy_from_slice(&width.to_le_bytes());
        h[8..10].copy_from_slice(&height.to_le_bytes());
        w.put(&h)?;
        Ok(w)
    }

    fn put(&mut self, bytes: &[u8]) -> Result<(), WriteError> {
        let end = self.len + bytes.len();
        let dst = self
            .buf
            .get_mut(self.len..end)
            .ok_or(WriteError::BufferFull)?;
        dst.copy_from_slice(bytes);
        self.len = end;
        Ok(())
    }

    fn reserve(&self, n: usize) -> Result<(), WriteError> {
        if self.buf.len() - self.len >= n {
            Ok(())
        } else {
            Err(WriteError::BufferFull)
        }
    }

    fn rgb(&mut self, op: Opcode, c: Rgb888) -> Result<(), WriteError> {
        self.put(&[op as u8, c.r(), c.g(), c.b()])
    }

    /// `clear`: fill the frame.
    pub fn clear(&mut self, c: Rgb888) -> Result<(), WriteError> {
        self.rgb(Opcode::Clear, c)
    }

    /// `color`: set the current colour.
    pub fn color(&mut self, c: Rgb888) -> Result<(), WriteError> {
        self.rgb(Opcode::Color, c)
    }

    /// `clip`: load the clip registers.
    pub fn clip(&mut self, w: ClipWindow) -> Result<(), WriteError> {
        let mut b = [0u8; 9];
        b[0] = Opcode::Clip as u8;
        for (i, v) in [w.x0, w.y0, w.x1, w.y1].into_iter().enumerate() {
            b[1 + 2 * i..3 + 2 * i].copy_from_slice(&v.to_le_bytes());
        }
        self.put(&b)
    }

    fn poly_head(&mut self, op: Opcode, n: usize, per: usize) -> Result<(), WriteError> {
        if !(3..=MAX_VERTICES).contains(&n) {
            return Err(WriteError::VertexCount(n));
        }
        self.reserve(3 + per * n)?;
        let c = (n as u16).to_le_bytes();
        self.put(&[op as u8, c[0], c[1]])
    }

    /// Undoes a polygon whose iterator yielded fewer items than its `len`.
    fn check_count(&mut self, start: usize, size: usize) -> Result<(), WriteError> {
        if self.len - start == size {
            Ok(())
        } else {
            let n = (self.len - start).saturating_sub(3) / 4;
            self.len = start;
            Err(WriteError::VertexCount(n))
        }
    }

    /// `poly`: a 2D polygon of 3..=65535 vertices.
    pub fn poly<I>(&mut self, vertices: I) -> Result<(), WriteError>
    where
        I: IntoIterator<Item = Vertex>,
        I::IntoIter: ExactSizeIterator,
    {
        let it = vertices.into_iter();
        let (n, start) = (it.len(), self.len);
        self.poly_head(Opcode::Poly, n, 4)?;
        for v in it.take(n) {
            let (x, y) = (v.x.to_bits().to_le_bytes(), v.y.to_bits().to_le_bytes());
            self.put(&[x[0], x[1], y[0], y[1]])?;
        }
        self.check_count(start, 3 + 4 * n)
    }

    /// `poly3`: a screen-space polygon with depth, 3..=65535 vertices.
    pub fn poly3<I>(&mut self, vertices: I) -> Result<(), WriteError>
    where
        I: IntoIterator<Item = Vertex3>,
        I::IntoIter: ExactSizeIterator,
    {
        let it = vertices.into_iter();
        let (n, start) = (it.len(), self.len);
        self.poly_head(Opcode::Poly3, n, 6)?;
        for v in it.take(n) {
            let (x, y, z) = (
                v.x.to_bits().to_le_bytes(),
                v.y.to_bits().to_le_bytes(),
                v.z.to_bits().to_le_bytes(),
            );
            self.put(&[x[0], x[1], y[0], y[1], z[0], z[1]])?;
        }
        self.check_count(start, 3 + 6 * n)
    }

    /// Stamps the body length and returns the finished list's bytes.
    pub fn finish(self) -> &'b [u8] {
        let body = (self.len - HEADER_LEN) as u32;
        self.buf[12..16].copy_from_slice(&body.to_le_bytes());
        &self.buf[..self.len]
    }
}
