//! Emitting a display list into a caller-owned buffer.

use super::{Axis, Opcode, HEADER_LEN, MAGIC, MAX_LABEL_LEN, MAX_VERTICES, VERSION_2D};
use crate::fixed::{Coord, Vertex, Vertex3};
use crate::geometry::{Angle, Point3, Q16};
use crate::raster::clip::ClipWindow;
use core::fmt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// Why a [`Writer`] refused a command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum WriteError {
    /// The buffer is full; nothing of the command was written.
    BufferFull,
    /// A frame side outside 1..=4096.
    BadFrameSize,
    /// A polygon with fewer than 3 or more than 65535 vertices (a face:
    /// fewer than 1).
    VertexCount(usize),
    /// An operand outside its range (light over 100 %, negative thickness,
    /// a label that is empty, longer than 255 bytes or not printable ASCII).
    BadOperand,
}

impl fmt::Display for WriteError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::BufferFull => f.write_str("display-list buffer is full"),
            WriteError::BadFrameSize => f.write_str("frame size is outside 1..=4096"),
            WriteError::VertexCount(n) => {
                write!(
                    f,
                    "polygon has {n} vertices; 3..=65535 are allowed (a face: 1..)"
                )
            }
            WriteError::BadOperand => f.write_str("operand out of range"),
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
    /// The lowest version that holds every command written.
    version: u16,
}

impl<'b> Writer<'b> {
    /// Starts a list for a `width × height` frame.
    pub fn new(buf: &'b mut [u8], width: u16, height: u16) -> Result<Self, WriteError> {
        if !(1..=4096).contains(&width) || !(1..=4096).contains(&height) {
            return Err(WriteError::BadFrameSize);
        }
        let mut w = Writer {
            buf,
            len: 0,
            version: VERSION_2D,
        };
        let mut h = [0u8; HEADER_LEN];
        h[..4].copy_from_slice(&MAGIC);
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
        let least = if op == Opcode::Face { 1 } else { 3 };
        if !(least..=MAX_VERTICES).contains(&n) {
            return Err(WriteError::VertexCount(n));
        }
        self.reserve(3 + per * n)?;
        let c = (n as u16).to_le_bytes();
        self.version = self.version.max(op.version());
        self.put(&[op as u8, c[0], c[1]])
    }

    /// Writes a whole fixed-size command, or nothing.
    fn command<const N: usize>(&mut self, op: Opcode, operands: [u8; N]) -> Result<(), WriteError> {
        self.reserve(1 + N)?;
        self.version = self.version.max(op.version());
        self.put(&[op as u8])?;
        self.put(&operands)
    }

    /// Undoes a polygon whose iterator yielded fewer items than its `len`.
    fn check_count(&mut self, start: usize, per: usize, n: usize) -> Result<(), WriteError> {
        if self.len - start == 3 + per * n {
            Ok(())
        } else {
            let n = (self.len - start).saturating_sub(3) / per;
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
        self.check_count(start, 4, n)
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
        self.check_count(start, 6, n)
    }

    /// `segment`: the 3D commands that follow build segment `id`.
    pub fn segment(&mut self, id: u16) -> Result<(), WriteError> {
        self.command(Opcode::Segment, id.to_le_bytes())
    }

    /// `perspective`: horizontal field of view, near and far planes.
    pub fn perspective(&mut self, fov: Angle, near: Q16, far: Q16) -> Result<(), WriteError> {
        let mut b = [0u8; 10];
        b[..2].copy_from_slice(&fov.to_bits().to_le_bytes());
        b[2..6].copy_from_slice(&near.to_bits().to_le_bytes());
        b[6..].copy_from_slice(&far.to_bits().to_le_bytes());
        self.command(Opcode::Perspective, b)
    }

    /// `ortho`: pixels per world unit, near and far planes.
    pub fn ortho(&mut self, scale: Q16, near: Q16, far: Q16) -> Result<(), WriteError> {
        self.command(Opcode::Ortho, q16s([scale, near, far]))
    }

    /// `view`: the camera's eye, yaw and pitch.
    pub fn view(&mut self, eye: Point3, yaw: Angle, pitch: Angle) -> Result<(), WriteError> {
        let mut b = [0u8; 16];
        b[..12].copy_from_slice(&point(eye));
        b[12..14].copy_from_slice(&yaw.to_bits().to_le_bytes());
        b[14..].copy_from_slice(&pitch.to_bits().to_le_bytes());
        self.command(Opcode::View, b)
    }

    /// `light`: the direction toward the light, and its share (0..=100 %).
    pub fn light(&mut self, toward: Point3, percent: u8) -> Result<(), WriteError> {
        if percent > 100 {
            return Err(WriteError::BadOperand);
        }
        let mut b = [0u8; 13];
        b[..12].copy_from_slice(&point(toward));
        b[12] = percent;
        self.command(Opcode::Light, b)
    }

    /// `thickness`: of points and lines, in pixels (≥ 0).
    pub fn thickness(&mut self, t: Coord) -> Result<(), WriteError> {
        if t.to_bits() < 0 {
            return Err(WriteError::BadOperand);
        }
        self.command(Opcode::Thickness, t.to_bits().to_le_bytes())
    }

    /// `push`: save the modelling transform.
    pub fn push(&mut self) -> Result<(), WriteError> {
        self.command(Opcode::Push, [])
    }

    /// `pop`: restore the modelling transform.
    pub fn pop(&mut self) -> Result<(), WriteError> {
        self.command(Opcode::Pop, [])
    }

    /// `translate`.
    pub fn translate(&mut self, by: Point3) -> Result<(), WriteError> {
        self.command(Opcode::Translate, point(by))
    }

    /// `rotate` about `axis`.
    pub fn rotate(&mut self, axis: Axis, angle: Angle) -> Result<(), WriteError> {
        let a = angle.to_bits().to_le_bytes();
        self.command(Opcode::Rotate, [axis as u8, a[0], a[1]])
    }

    /// `scale`, per axis.
    pub fn scale(&mut self, by: Point3) -> Result<(), WriteError> {
        self.command(Opcode::Scale, point(by))
    }

    /// `face`: a 3D polygon of 1..=65535 vertices (1: a point, 2: a line).
    pub fn face<I>(&mut self, vertices: I) -> Result<(), WriteError>
    where
        I: IntoIterator<Item = Point3>,
        I::IntoIter: ExactSizeIterator,
    {
        let it = vertices.into_iter();
        let (n, start) = (it.len(), self.len);
        self.poly_head(Opcode::Face, n, 12)?;
        for p in it.take(n) {
            self.put(&point(p))?;
        }
        self.check_count(start, 12, n)
    }

    /// `label`: `text` (1..=255 bytes of printable ASCII) at a 3D point.
    pub fn label(&mut self, at: Point3, text: &str) -> Result<(), WriteError> {
        let t = text.as_bytes();
        if t.is_empty() || t.len() > MAX_LABEL_LEN || !t.iter().all(|c| (0x20..0x7f).contains(c)) {
            return Err(WriteError::BadOperand);
        }
        self.reserve(14 + t.len())?;
        let mut head = [0u8; 13];
        head[..12].copy_from_slice(&point(at));
        head[12] = t.len() as u8;
        self.command(Opcode::Label, head)?;
        self.put(t)
    }

    /// Stamps the version and the body length and returns the finished
    /// list's bytes.
    pub fn finish(self) -> &'b [u8] {
        self.buf[4..6].copy_from_slice(&self.version.to_le_bytes());
        let body = (self.len - HEADER_LEN) as u32;
        self.buf[12..16].copy_from_slice(&body.to_le_bytes());
        &self.buf[..self.len]
    }
}

fn q16s(v: [Q16; 3]) -> [u8; 12] {
    let mut b = [0u8; 12];
    for (chunk, q) in b.chunks_exact_mut(4).zip(v) {
        chunk.copy_from_slice(&q.to_bits().to_le_bytes());
    }
    b
}

fn point(p: Point3) -> [u8; 12] {
    q16s([p.x, p.y, p.z])
}
