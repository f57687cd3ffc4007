//! Emitting a display list into a caller-owned buffer.

use super::layout::{self, header, Field, Tail};
use super::{Axis, Opcode, HEADER_LEN, MAGIC, MAX_LABEL_LEN, MAX_VERTICES, VERSION_2D};
use crate::fixed::{Coord, Vertex, Vertex3};
use crate::geometry::{Angle, Point3, Q16};
use crate::raster::clip::ClipWindow;
use crate::raster::winding::FillRule;
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
    /// A version this crate does not read (it reads 1 and 2).
    Version(u16),
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
            WriteError::Version(v) => write!(f, "display-list version {v} is not 1 or 2"),
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
        h[header::MAGIC].copy_from_slice(&MAGIC);
        h[header::WIDTH].copy_from_slice(&width.to_le_bytes());
        h[header::HEIGHT].copy_from_slice(&height.to_le_bytes());
        w.put(&h)?;
        Ok(w)
    }

    /// Commands with no header, into `buf` (a segment's record: see
    /// [`scene::record`](crate::scene::record)).
    pub(crate) fn body(buf: &'b mut [u8]) -> Self {
        Writer {
            buf,
            len: 0,
            version: VERSION_2D,
        }
    }

    /// Bytes written so far.
    pub(crate) fn written(&self) -> usize {
        self.len
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
        let mut b = [0u8; layout::rgb::LEN];
        b[layout::OPCODE] = op as u8;
        b[layout::rgb::R] = c.r();
        b[layout::rgb::G] = c.g();
        b[layout::rgb::B] = c.b();
        self.whole(b)
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
        use layout::clip::{LEN, X0, X1, Y0, Y1};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Clip as u8;
        for (f, v) in [(X0, w.x0), (Y0, w.y0), (X1, w.x1), (Y1, w.y1)] {
            b[f].copy_from_slice(&v.to_le_bytes());
        }
        self.whole(b)
    }

    /// `line`: a 2D line one pixel wide from `from` to `to` (version 2;
    /// see [`raster::line`](crate::raster::line)).
    pub fn line(&mut self, from: Vertex, to: Vertex) -> Result<(), WriteError> {
        use layout::line::{LEN, X0, X1, Y0, Y1};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Line as u8;
        for (f, v) in [(X0, from.x), (Y0, from.y), (X1, to.x), (Y1, to.y)] {
            b[f].copy_from_slice(&v.to_bits().to_le_bytes());
        }
        self.whole(b)
    }

    /// The stride and fewest items of a packed command.
    fn packed(op: Opcode) -> (usize, usize) {
        match op.layout().tail {
            Tail::Packed { stride, least } => (stride, least as usize),
            _ => (0, usize::MAX),
        }
    }

    fn poly_head(&mut self, op: Opcode, n: usize) -> Result<(), WriteError> {
        let (_, least) = Self::packed(op);
        if !(least..=MAX_VERTICES).contains(&n) {
            return Err(WriteError::VertexCount(n));
        }
        self.reserve(op.layout().size(n))?;
        let mut b = [0u8; layout::poly::VERTICES];
        b[layout::OPCODE] = op as u8;
        b[layout::Layout::COUNT].copy_from_slice(&(n as u16).to_le_bytes());
        self.version = self.version.max(op.version());
        self.put(&b)
    }

    /// Writes a whole fixed-size command (opcode byte included), or
    /// nothing.
    fn whole<const N: usize>(&mut self, bytes: [u8; N]) -> Result<(), WriteError> {
        let op = Opcode::from_byte(bytes[layout::OPCODE]).ok_or(WriteError::BadOperand)?;
        debug_assert_eq!(op.layout().fixed, N);
        self.reserve(N)?;
        self.version = self.version.max(op.version());
        self.put(&bytes)
    }

    /// Writes a whole fixed-size command from its operands (the bytes
    /// after the opcode), or nothing.
    fn command<const N: usize>(&mut self, op: Opcode, operands: [u8; N]) -> Result<(), WriteError> {
        debug_assert_eq!(op.layout().fixed, 1 + N);
        self.reserve(1 + N)?;
        self.version = self.version.max(op.version());
        self.put(&[op as u8])?;
        self.put(&operands)
    }

    /// Undoes a polygon whose iterator yielded fewer items than its `len`.
    fn check_count(&mut self, start: usize, op: Opcode, n: usize) -> Result<(), WriteError> {
        let layout = op.layout();
        if self.len - start == layout.size(n) {
            Ok(())
        } else {
            let (per, _) = Self::packed(op);
            let n = (self.len - start).saturating_sub(layout.fixed) / per.max(1);
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
        self.poly_head(Opcode::Poly, n)?;
        for v in it.take(n) {
            use layout::poly::{STRIDE, X, Y};
            self.put(&packed::<STRIDE, 2>([(X, v.x), (Y, v.y)]))?;
        }
        self.check_count(start, Opcode::Poly, n)
    }

    /// `poly3`: a screen-space polygon with depth, 3..=65535 vertices.
    pub fn poly3<I>(&mut self, vertices: I) -> Result<(), WriteError>
    where
        I: IntoIterator<Item = Vertex3>,
        I::IntoIter: ExactSizeIterator,
    {
        let it = vertices.into_iter();
        let (n, start) = (it.len(), self.len);
        self.poly_head(Opcode::Poly3, n)?;
        for v in it.take(n) {
            use layout::poly3::{STRIDE, X, Y, Z};
            self.put(&packed::<STRIDE, 3>([(X, v.x), (Y, v.y), (Z, v.z)]))?;
        }
        self.check_count(start, Opcode::Poly3, n)
    }

    /// `segment`: the 3D commands that follow build segment `id`.
    pub fn segment(&mut self, id: u16) -> Result<(), WriteError> {
        self.command(Opcode::Segment, id.to_le_bytes())
    }

    /// `perspective`: horizontal field of view, near and far planes.
    pub fn perspective(&mut self, fov: Angle, near: Q16, far: Q16) -> Result<(), WriteError> {
        use layout::perspective::{FAR, FOV, LEN, NEAR};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Perspective as u8;
        b[FOV].copy_from_slice(&fov.to_bits().to_le_bytes());
        b[NEAR].copy_from_slice(&near.to_bits().to_le_bytes());
        b[FAR].copy_from_slice(&far.to_bits().to_le_bytes());
        self.whole(b)
    }

    /// `ortho`: pixels per world unit, near and far planes.
    pub fn ortho(&mut self, scale: Q16, near: Q16, far: Q16) -> Result<(), WriteError> {
        use layout::ortho::{FAR, LEN, NEAR, SCALE};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Ortho as u8;
        b[SCALE].copy_from_slice(&scale.to_bits().to_le_bytes());
        b[NEAR].copy_from_slice(&near.to_bits().to_le_bytes());
        b[FAR].copy_from_slice(&far.to_bits().to_le_bytes());
        self.whole(b)
    }

    /// `view`: the camera's eye, yaw and pitch.
    pub fn view(&mut self, eye: Point3, yaw: Angle, pitch: Angle) -> Result<(), WriteError> {
        use layout::view::{EYE, LEN, PITCH, YAW};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::View as u8;
        b[EYE].copy_from_slice(&point(eye));
        b[YAW].copy_from_slice(&yaw.to_bits().to_le_bytes());
        b[PITCH].copy_from_slice(&pitch.to_bits().to_le_bytes());
        self.whole(b)
    }

    /// `light`: the direction toward the light, and its share (0..=100 %).
    pub fn light(&mut self, toward: Point3, percent: u8) -> Result<(), WriteError> {
        use layout::light::{LEN, PERCENT, TOWARD};
        if percent > 100 {
            return Err(WriteError::BadOperand);
        }
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Light as u8;
        b[TOWARD].copy_from_slice(&point(toward));
        b[PERCENT] = percent;
        self.whole(b)
    }

    /// `thickness`: of points and lines, in pixels (≥ 0).
    pub fn thickness(&mut self, t: Coord) -> Result<(), WriteError> {
        if t.to_bits() < 0 {
            return Err(WriteError::BadOperand);
        }
        self.command(Opcode::Thickness, t.to_bits().to_le_bytes())
    }

    /// `fill`: the fill rule of the `poly`s that follow.
    pub fn fill(&mut self, rule: FillRule) -> Result<(), WriteError> {
        self.command(Opcode::Fill, [rule.to_byte()])
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
        use layout::rotate::{ANGLE, AXIS, LEN};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Rotate as u8;
        b[AXIS] = axis as u8;
        b[ANGLE].copy_from_slice(&angle.to_bits().to_le_bytes());
        self.whole(b)
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
        self.poly_head(Opcode::Face, n)?;
        for p in it.take(n) {
            self.put(&point(p))?;
        }
        self.check_count(start, Opcode::Face, n)
    }

    /// `v`: a vertex appended to the segment's mesh table.
    pub fn mesh_vertex(&mut self, p: Point3) -> Result<(), WriteError> {
        self.command(Opcode::MeshVertex, point(p))
    }

    /// `f`: a face through 1..=65535 vertices of the segment's mesh table,
    /// by 0-based index (1: a point, 2: a line). The indices are not
    /// checked here: [`DisplayList::new_checked`](super::DisplayList::new_checked)
    /// refuses one that names no `v` of its segment before the `f`.
    pub fn mesh_face<I>(&mut self, indices: I) -> Result<(), WriteError>
    where
        I: IntoIterator<Item = u16>,
        I::IntoIter: ExactSizeIterator,
    {
        let it = indices.into_iter();
        let (n, start) = (it.len(), self.len);
        self.poly_head(Opcode::MeshFace, n)?;
        for i in it.take(n) {
            self.put(&i.to_le_bytes())?;
        }
        self.check_count(start, Opcode::MeshFace, n)
    }

    /// `hide`: segment `id` is not drawn.
    pub fn hide(&mut self, id: u16) -> Result<(), WriteError> {
        self.command(Opcode::Hide, id.to_le_bytes())
    }

    /// `show`: segment `id` is drawn.
    pub fn show(&mut self, id: u16) -> Result<(), WriteError> {
        self.command(Opcode::Show, id.to_le_bytes())
    }

    /// `highlight`: segment `id` drawn in `color`, unlit, or in its own
    /// colours (`None`).
    pub fn highlight(&mut self, id: u16, color: Option<Rgb888>) -> Result<(), WriteError> {
        use layout::highlight::{B, G, ID, LEN, ON, R};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Highlight as u8;
        b[ID].copy_from_slice(&id.to_le_bytes());
        if let Some(c) = color {
            (b[ON], b[R], b[G], b[B]) = (1, c.r(), c.g(), c.b());
        }
        self.whole(b)
    }

    /// `place`: segment `id` built after `placement`'s transforms.
    pub fn place(&mut self, id: u16, placement: &super::Placement) -> Result<(), WriteError> {
        use layout::place::{ID, LEN, ROTATE, SCALE, TRANSLATE};
        let mut b = [0u8; LEN];
        b[layout::OPCODE] = Opcode::Place as u8;
        b[ID].copy_from_slice(&id.to_le_bytes());
        b[TRANSLATE].copy_from_slice(&point(placement.translate));
        for (k, a) in placement.rotate.iter().enumerate() {
            let at = ROTATE.start + 2 * k;
            b[at..at + 2].copy_from_slice(&a.to_bits().to_le_bytes());
        }
        b[SCALE].copy_from_slice(&point(placement.scale));
        self.whole(b)
    }

    /// `label`: `text` (1..=255 bytes of printable ASCII) at a 3D point.
    pub fn label(&mut self, at: Point3, text: &str) -> Result<(), WriteError> {
        let t = text.as_bytes();
        if t.is_empty() || t.len() > MAX_LABEL_LEN || !t.iter().all(|c| (0x20..0x7f).contains(c)) {
            return Err(WriteError::BadOperand);
        }
        use layout::label::{AT, TEXT, TEXT_LEN};
        self.reserve(Opcode::Label.layout().size(t.len()))?;
        let mut head = [0u8; TEXT];
        head[layout::OPCODE] = Opcode::Label as u8;
        head[AT].copy_from_slice(&point(at));
        head[TEXT_LEN] = t.len() as u8;
        self.whole(head)?;
        self.put(t)
    }

    /// Stamps at least `version` in the header, whatever the commands
    /// written need (a list may say it is version 2 with only version-1
    /// commands in it). Versions other than the ones this crate reads are
    /// refused, and so nothing written can fail to read.
    pub fn require_version(&mut self, version: u16) -> Result<(), WriteError> {
        if version != VERSION_2D && version != super::VERSION {
            return Err(WriteError::Version(version));
        }
        self.version = self.version.max(version);
        Ok(())
    }

    /// Stamps the version and the body length and returns the finished
    /// list's bytes.
    pub fn finish(self) -> &'b [u8] {
        self.buf[header::VERSION].copy_from_slice(&self.version.to_le_bytes());
        let body = (self.len - HEADER_LEN) as u32;
        self.buf[header::BODY_LEN].copy_from_slice(&body.to_le_bytes());
        &self.buf[..self.len]
    }
}

/// A packed item of `N` bytes: `K` coordinates at their fields.
fn packed<const N: usize, const K: usize>(fields: [(Field, Coord); K]) -> [u8; N] {
    let mut b = [0u8; N];
    for (f, c) in fields {
        b[f].copy_from_slice(&c.to_bits().to_le_bytes());
    }
    b
}

/// A packed world point.
fn point(p: Point3) -> [u8; layout::point3::LEN] {
    use layout::point3::{LEN, X, Y, Z};
    let mut b = [0u8; LEN];
    for (f, q) in [(X, p.x), (Y, p.y), (Z, p.z)] {
        b[f].copy_from_slice(&q.to_bits().to_le_bytes());
    }
    b
}
