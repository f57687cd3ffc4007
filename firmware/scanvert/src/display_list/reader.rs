//! The checked, zero-copy reader.

use super::layout::{self, header, Field, Layout, Tail};
use super::{Error, ErrorKind, Opcode, HEADER_LEN, MAGIC, VERSION, VERSION_2D};
use crate::fixed::{Coord, Vertex, Vertex3};
use crate::geometry::{Angle, Point3, Q16};
use crate::raster::clip::ClipWindow;
use core::marker::PhantomData;
use embedded_graphics_core::pixelcolor::Rgb888;

/// A display list that has passed [`DisplayList::new_checked`].
///
/// # Guarantees
/// The header is valid, the frame is 1..=4096 on each side, and the body is
/// a sequence of complete, known commands of its version that ends exactly
/// at the end of the buffer, each polygon with at least 3 vertices (a face
/// at least 1), every operand in its range. Nothing reachable from a
/// `DisplayList` can fail or panic.
#[derive(Clone, Copy, Debug)]
pub struct DisplayList<'a> {
    bytes: &'a [u8],
    width: u16,
    height: u16,
    version: u16,
}

#[inline(always)]
fn u16_at(b: &[u8], f: Field) -> u16 {
    u16::from_le_bytes([b[f.start], b[f.start + 1]])
}

#[inline(always)]
fn i16_at(b: &[u8], f: Field) -> i16 {
    i16::from_le_bytes([b[f.start], b[f.start + 1]])
}

#[inline(always)]
fn i32_at(b: &[u8], f: Field) -> i32 {
    let at = f.start;
    i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

#[inline(always)]
fn point_at(b: &[u8], f: Field) -> Point3 {
    let p = &b[f];
    Point3::from_bits(
        i32_at(p, layout::point3::X),
        i32_at(p, layout::point3::Y),
        i32_at(p, layout::point3::Z),
    )
}

#[inline(always)]
fn vertex_at(b: &[u8], x: Field, y: Field) -> Vertex {
    Vertex {
        x: Coord::from_bits(i16_at(b, x)),
        y: Coord::from_bits(i16_at(b, y)),
    }
}

/// Size of the command starting at `at` in a list of `version`, or an
/// error, by the command's [`layout`](Opcode::layout). Reads only inside
/// `body`.
fn command_len(body: &[u8], at: usize, version: u16) -> Result<(Opcode, usize), ErrorKind> {
    let byte = body[at];
    let op = Opcode::from_byte(byte)
        .filter(|op| op.version() <= version)
        .ok_or(ErrorKind::UnknownOpcode(byte))?;
    let rest = &body[at..];
    let layout = op.layout();
    if rest.len() < layout.fixed {
        return Err(ErrorKind::Truncated);
    }
    let len = match layout.tail {
        Tail::None => layout.fixed,
        Tail::Packed { least, .. } => {
            let n = u16_at(rest, Layout::COUNT);
            if n < least {
                return Err(ErrorKind::TooFewVertices(n));
            }
            layout.size(n as usize)
        }
        Tail::Text { len_at } => layout.size(rest[len_at] as usize),
    };
    if rest.len() < len {
        return Err(ErrorKind::Truncated);
    }
    let bad = match op {
        Opcode::Rotate => rest[layout::rotate::AXIS] > 2,
        Opcode::Light => rest[layout::light::PERCENT] > 100,
        Opcode::Thickness => i16_at(rest, layout::thickness::T) < 0,
        Opcode::Label => {
            let text = &rest[layout.fixed..len];
            text.is_empty() || !text.iter().all(|c| (0x20..0x7f).contains(c))
        }
        _ => false,
    };
    if bad {
        return Err(ErrorKind::BadOperand(op));
    }
    Ok((op, len))
}

impl<'a> DisplayList<'a> {
    /// Validates `bytes` as a display list.
    ///
    /// This walks every command once. On success every later access is
    /// infallible; on failure the error names the byte offset of the fault.
    pub fn new_checked(bytes: &'a [u8]) -> Result<Self, Error> {
        let err = |offset, kind| Error { offset, kind };
        if bytes.len() < header::MAGIC.end {
            return Err(err(bytes.len(), ErrorKind::Truncated));
        }
        if bytes[header::MAGIC] != MAGIC {
            return Err(err(0, ErrorKind::BadMagic));
        }
        if bytes.len() < HEADER_LEN {
            return Err(err(bytes.len(), ErrorKind::Truncated));
        }
        let version = u16_at(bytes, header::VERSION);
        if version != VERSION && version != VERSION_2D {
            return Err(err(
                header::VERSION.start,
                ErrorKind::UnsupportedVersion(version),
            ));
        }
        let (width, height) = (u16_at(bytes, header::WIDTH), u16_at(bytes, header::HEIGHT));
        if !(1..=4096).contains(&width) || !(1..=4096).contains(&height) {
            return Err(err(
                header::WIDTH.start,
                ErrorKind::BadFrameSize { width, height },
            ));
        }
        if u16_at(bytes, header::RESERVED) != 0 {
            return Err(err(header::RESERVED.start, ErrorKind::ReservedNotZero));
        }
        let declared = i32_at(bytes, header::BODY_LEN) as u32;
        let actual = bytes.len() - HEADER_LEN;
        if declared as usize != actual {
            return Err(err(
                header::BODY_LEN.start,
                ErrorKind::LengthMismatch { declared, actual },
            ));
        }
        let body = &bytes[HEADER_LEN..];
        let mut at = 0;
        while at < body.len() {
            match command_len(body, at, version) {
                Ok((_, len)) => at += len,
                Err(kind) => return Err(err(HEADER_LEN + at, kind)),
            }
        }
        Ok(DisplayList {
            bytes,
            width,
            height,
            version,
        })
    }

    /// Frame width in pixels (1..=4096).
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Frame height in pixels (1..=4096).
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The format version (1: 2D only; 2: with 3D commands).
    pub fn version(&self) -> u16 {
        self.version
    }

    /// The whole list, header included.
    pub fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The commands in order.
    pub fn commands(&self) -> Commands<'a> {
        Commands {
            body: &self.bytes[HEADER_LEN..],
            at: 0,
            version: self.version,
        }
    }
}

/// One command of a checked display list.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub enum Command<'a> {
    /// Fill every pixel of the frame (the clip registers do not apply).
    Clear(Rgb888),
    /// Load the clip registers.
    Clip(ClipWindow),
    /// Set the current colour.
    Color(Rgb888),
    /// A 2D polygon in the current colour, in painter's order.
    Poly(Vertices<'a>),
    /// A screen-space polygon with depth.
    Poly3(Vertices3<'a>),
    /// A 2D line one pixel wide from the first end to the second, in the
    /// current colour, in painter's order (see
    /// [`raster::line`](crate::raster::line)).
    Line(Vertex, Vertex),
    /// The 3D commands that follow build this segment.
    Segment(u16),
    /// Perspective projection: horizontal field of view, near and far
    /// planes.
    Perspective {
        /// Horizontal field of view.
        fov: Angle,
        /// Near plane, view depth.
        near: Q16,
        /// Far plane, view depth.
        far: Q16,
    },
    /// Orthographic projection: pixels per world unit, near and far planes.
    Ortho {
        /// Pixels per world unit.
        scale: Q16,
        /// Near plane, view depth.
        near: Q16,
        /// Far plane, view depth.
        far: Q16,
    },
    /// The camera: eye, then yaw and pitch.
    View {
        /// Eye position, world.
        eye: Point3,
        /// Turn about the vertical axis.
        yaw: Angle,
        /// Tilt up or down.
        pitch: Angle,
    },
    /// The parallel light: the direction toward it and its share in percent
    /// (0..=100); the rest is ambient.
    Light {
        /// Direction toward the light, world.
        toward: Point3,
        /// The light's share, 0..=100.
        percent: u8,
    },
    /// Thickness of points and lines, in Q12.4 pixels (≥ 0).
    Thickness(Coord),
    /// Save the modelling transform.
    Push,
    /// Restore the modelling transform.
    Pop,
    /// Translate the modelling transform.
    Translate(Point3),
    /// Rotate the modelling transform about an axis.
    Rotate(Axis, Angle),
    /// Scale the modelling transform (per axis).
    Scale(Point3),
    /// A 3D polygon in the current colour: one vertex is a point, two a
    /// line, three or more a face, front where its vertices run
    /// counter-clockwise.
    Face(Points<'a>),
    /// A text label, its first character's lower-left corner at a 3D point.
    Label {
        /// The anchor, model coordinates.
        at: Point3,
        /// The text: 1..=255 printable ASCII characters.
        text: &'a str,
    },
}

impl Command<'_> {
    /// The command's opcode.
    pub const fn opcode(&self) -> Opcode {
        match self {
            Command::Clear(_) => Opcode::Clear,
            Command::Clip(_) => Opcode::Clip,
            Command::Color(_) => Opcode::Color,
            Command::Poly(_) => Opcode::Poly,
            Command::Poly3(_) => Opcode::Poly3,
            Command::Line(..) => Opcode::Line,
            Command::Segment(_) => Opcode::Segment,
            Command::Perspective { .. } => Opcode::Perspective,
            Command::Ortho { .. } => Opcode::Ortho,
            Command::View { .. } => Opcode::View,
            Command::Light { .. } => Opcode::Light,
            Command::Thickness(_) => Opcode::Thickness,
            Command::Push => Opcode::Push,
            Command::Pop => Opcode::Pop,
            Command::Translate(_) => Opcode::Translate,
            Command::Rotate(..) => Opcode::Rotate,
            Command::Scale(_) => Opcode::Scale,
            Command::Face(_) => Opcode::Face,
            Command::Label { .. } => Opcode::Label,
        }
    }

    /// `true` for the commands of the 3D layer (see [`Opcode::is_3d`]).
    pub const fn is_3d(&self) -> bool {
        self.opcode().is_3d()
    }

    /// `true` for the 3D scene's commands (see [`Opcode::is_scene`]).
    pub const fn is_scene(&self) -> bool {
        self.opcode().is_scene()
    }
}

/// An axis of rotation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Axis {
    /// x, to the right.
    X,
    /// y, up.
    Y,
    /// z, toward the viewer.
    Z,
}

impl Axis {
    /// The axis of an operand byte (0, 1, 2).
    pub const fn from_byte(b: u8) -> Option<Axis> {
        match b {
            0 => Some(Axis::X),
            1 => Some(Axis::Y),
            2 => Some(Axis::Z),
            _ => None,
        }
    }
}

/// Iterator over the commands of a [`DisplayList`], with each command's
/// byte offset in the list.
#[derive(Clone, Debug)]
pub struct Commands<'a> {
    body: &'a [u8],
    at: usize,
    version: u16,
}

impl<'a> Iterator for Commands<'a> {
    /// `(byte offset of the opcode, command)`.
    type Item = (usize, Command<'a>);

    fn next(&mut self) -> Option<Self::Item> {
        if self.at >= self.body.len() {
            return None;
        }
        // Checked by `new_checked`; an `Err` here cannot happen, and ends
        // the iteration rather than panicking if it ever did.
        let (op, len) = command_len(self.body, self.at, self.version).ok()?;
        let b = self.body.get(self.at..self.at + len)?;
        let offset = HEADER_LEN + self.at;
        self.at += len;
        let rgb = || {
            use layout::rgb::{B, G, R};
            Rgb888::new(b[R], b[G], b[B])
        };
        let cmd = match op {
            Opcode::Clear => Command::Clear(rgb()),
            Opcode::Color => Command::Color(rgb()),
            Opcode::Clip => {
                use layout::clip::{X0, X1, Y0, Y1};
                Command::Clip(ClipWindow {
                    x0: i16_at(b, X0),
                    y0: i16_at(b, Y0),
                    x1: i16_at(b, X1),
                    y1: i16_at(b, Y1),
                })
            }
            Opcode::Line => {
                use layout::line::{X0, X1, Y0, Y1};
                Command::Line(vertex_at(b, X0, Y0), vertex_at(b, X1, Y1))
            }
            Opcode::Poly => Command::Poly(Packed::new(&b[layout::poly::VERTICES..])),
            Opcode::Poly3 => Command::Poly3(Packed::new(&b[layout::poly3::VERTICES..])),
            Opcode::Segment => Command::Segment(u16_at(b, layout::segment::ID)),
            Opcode::Perspective => {
                use layout::perspective::{FAR, FOV, NEAR};
                Command::Perspective {
                    fov: Angle::from_bits(u16_at(b, FOV)),
                    near: Q16::from_bits(i32_at(b, NEAR)),
                    far: Q16::from_bits(i32_at(b, FAR)),
                }
            }
            Opcode::Ortho => {
                use layout::ortho::{FAR, NEAR, SCALE};
                Command::Ortho {
                    scale: Q16::from_bits(i32_at(b, SCALE)),
                    near: Q16::from_bits(i32_at(b, NEAR)),
                    far: Q16::from_bits(i32_at(b, FAR)),
                }
            }
            Opcode::View => {
                use layout::view::{EYE, PITCH, YAW};
                Command::View {
                    eye: point_at(b, EYE),
                    yaw: Angle::from_bits(u16_at(b, YAW)),
                    pitch: Angle::from_bits(u16_at(b, PITCH)),
                }
            }
            Opcode::Light => Command::Light {
                toward: point_at(b, layout::light::TOWARD),
                percent: b[layout::light::PERCENT],
            },
            Opcode::Thickness => {
                Command::Thickness(Coord::from_bits(i16_at(b, layout::thickness::T)))
            }
            Opcode::Push => Command::Push,
            Opcode::Pop => Command::Pop,
            Opcode::Translate => Command::Translate(point_at(b, layout::point::P)),
            Opcode::Rotate => Command::Rotate(
                Axis::from_byte(b[layout::rotate::AXIS])?,
                Angle::from_bits(u16_at(b, layout::rotate::ANGLE)),
            ),
            Opcode::Scale => Command::Scale(point_at(b, layout::point::P)),
            Opcode::Face => Command::Face(Packed::new(&b[layout::face::VERTICES..])),
            Opcode::Label => Command::Label {
                at: point_at(b, layout::label::AT),
                // Printable ASCII, checked by `new_checked`.
                text: core::str::from_utf8(&b[layout::label::TEXT..]).unwrap_or(""),
            },
        };
        Some((offset, cmd))
    }
}

/// An item of a packed list in a command (a vertex of `poly`, `poly3`
/// or `face`), read from [`SIZE`](Self::SIZE) little-endian bytes; the
/// size is the command's stride in [`layout`].
pub trait FromBytes: Sized {
    /// Bytes per item.
    const SIZE: usize;
    /// The item in `bytes`, which holds exactly [`SIZE`](Self::SIZE)
    /// bytes (a [`Packed`] view only ever passes such a slice).
    fn from_bytes(bytes: &[u8]) -> Self;
}

impl FromBytes for Vertex {
    const SIZE: usize = layout::poly::STRIDE;
    fn from_bytes(c: &[u8]) -> Self {
        vertex_at(c, layout::poly::X, layout::poly::Y)
    }
}

impl FromBytes for Vertex3 {
    const SIZE: usize = layout::poly3::STRIDE;
    fn from_bytes(c: &[u8]) -> Self {
        use layout::poly3::{X, Y, Z};
        Vertex3 {
            x: Coord::from_bits(i16_at(c, X)),
            y: Coord::from_bits(i16_at(c, Y)),
            z: Coord::from_bits(i16_at(c, Z)),
        }
    }
}

impl FromBytes for Point3 {
    const SIZE: usize = layout::face::STRIDE;
    fn from_bytes(c: &[u8]) -> Self {
        point_at(c, 0..layout::point3::LEN)
    }
}

/// A packed list of `V`s inside a checked display list, read in place.
#[derive(Clone, Copy, Debug)]
pub struct Packed<'a, V> {
    bytes: &'a [u8],
    item: PhantomData<fn() -> V>,
}

impl<'a, V: FromBytes + 'a> Packed<'a, V> {
    /// The items in `bytes` (a trailing part item is never read).
    fn new(bytes: &'a [u8]) -> Self {
        Packed {
            bytes,
            item: PhantomData,
        }
    }

    /// Number of items (for a checked list: 3..=65535 for `poly` and
    /// `poly3`, 1..=65535 for `face`).
    pub fn len(&self) -> usize {
        self.bytes.len() / V::SIZE
    }

    /// `true` when there is no item (never for a checked list).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Iterates the items.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = V> + Clone + 'a {
        self.bytes.chunks_exact(V::SIZE).map(V::from_bytes)
    }
}

/// The vertices of a `poly`: at least 3, each `(x, y)` in Q12.4.
pub type Vertices<'a> = Packed<'a, Vertex>;

/// The vertices of a `poly3`: at least 3, each `(x, y, z)` in Q12.4.
pub type Vertices3<'a> = Packed<'a, Vertex3>;

/// The vertices of a `face`: at least 1, each `(x, y, z)` in Q16.16.
pub type Points<'a> = Packed<'a, Point3>;
