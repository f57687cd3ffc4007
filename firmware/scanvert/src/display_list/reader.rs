//! The checked, zero-copy reader.

use super::{Error, ErrorKind, Opcode, HEADER_LEN, MAGIC, VERSION, VERSION_2D};
use crate::fixed::{Coord, Vertex, Vertex3};
use crate::geometry::{Angle, Point3, Q16};
use crate::raster::clip::ClipWindow;
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
fn u16_at(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

#[inline(always)]
fn i16_at(b: &[u8], at: usize) -> i16 {
    i16::from_le_bytes([b[at], b[at + 1]])
}

#[inline(always)]
fn i32_at(b: &[u8], at: usize) -> i32 {
    i32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

#[inline(always)]
fn point_at(b: &[u8], at: usize) -> Point3 {
    Point3::from_bits(i32_at(b, at), i32_at(b, at + 4), i32_at(b, at + 8))
}

/// Size of the command starting at `at` in a list of `version`, or an
/// error. Reads only inside `body`.
fn command_len(body: &[u8], at: usize, version: u16) -> Result<(Opcode, usize), ErrorKind> {
    let byte = body[at];
    let op = Opcode::from_byte(byte)
        .filter(|op| op.version() <= version)
        .ok_or(ErrorKind::UnknownOpcode(byte))?;
    let rest = body.len() - at;
    let fixed = match op {
        Opcode::Push | Opcode::Pop => 1,
        Opcode::Poly | Opcode::Poly3 | Opcode::Face | Opcode::Segment | Opcode::Thickness => 3,
        Opcode::Clear | Opcode::Color | Opcode::Rotate => 4,
        Opcode::Clip => 9,
        Opcode::Perspective => 11,
        Opcode::Ortho | Opcode::Translate | Opcode::Scale => 13,
        Opcode::Light | Opcode::Label => 14,
        Opcode::View => 17,
    };
    if rest < fixed {
        return Err(ErrorKind::Truncated);
    }
    let len = match op {
        Opcode::Poly | Opcode::Poly3 | Opcode::Face => {
            let n = u16_at(body, at + 1);
            let (least, per) = match op {
                Opcode::Poly => (3, 4),
                Opcode::Poly3 => (3, 6),
                _ => (1, 12),
            };
            if n < least {
                return Err(ErrorKind::TooFewVertices(n));
            }
            3 + per * n as usize
        }
        Opcode::Label => fixed + body[at + 13] as usize,
        _ => fixed,
    };
    if rest < len {
        return Err(ErrorKind::Truncated);
    }
    let bad = match op {
        Opcode::Rotate => body[at + 1] > 2,
        Opcode::Light => body[at + 13] > 100,
        Opcode::Thickness => i16_at(body, at + 1) < 0,
        Opcode::Label => {
            let text = &body[at + fixed..at + len];
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
        if bytes.len() < 4 {
            return Err(err(bytes.len(), ErrorKind::Truncated));
        }
        if bytes[..4] != MAGIC {
            return Err(err(0, ErrorKind::BadMagic));
        }
        if bytes.len() < HEADER_LEN {
            return Err(err(bytes.len(), ErrorKind::Truncated));
        }
        let version = u16_at(bytes, 4);
        if version != VERSION && version != VERSION_2D {
            return Err(err(4, ErrorKind::UnsupportedVersion(version)));
        }
        let (width, height) = (u16_at(bytes, 6), u16_at(bytes, 8));
        if !(1..=4096).contains(&width) || !(1..=4096).contains(&height) {
            return Err(err(6, ErrorKind::BadFrameSize { width, height }));
        }
        if u16_at(bytes, 10) != 0 {
            return Err(err(10, ErrorKind::ReservedNotZero));
        }
        let declared = u32::from_le_bytes([bytes[12], bytes[13], bytes[14], bytes[15]]);
        let actual = bytes.len() - HEADER_LEN;
        if declared as usize != actual {
            return Err(err(12, ErrorKind::LengthMismatch { declared, actual }));
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
        let rgb = || Rgb888::new(b[1], b[2], b[3]);
        let cmd = match op {
            Opcode::Clear => Command::Clear(rgb()),
            Opcode::Color => Command::Color(rgb()),
            Opcode::Clip => Command::Clip(ClipWindow {
                x0: i16_at(b, 1),
                y0: i16_at(b, 3),
                x1: i16_at(b, 5),
                y1: i16_at(b, 7),
            }),
            Opcode::Poly => Command::Poly(Vertices { bytes: &b[3..] }),
            Opcode::Poly3 => Command::Poly3(Vertices3 { bytes: &b[3..] }),
            Opcode::Segment => Command::Segment(u16_at(b, 1)),
            Opcode::Perspective => Command::Perspective {
                fov: Angle::from_bits(u16_at(b, 1)),
                near: Q16::from_bits(i32_at(b, 3)),
                far: Q16::from_bits(i32_at(b, 7)),
            },
            Opcode::Ortho => Command::Ortho {
                scale: Q16::from_bits(i32_at(b, 1)),
                near: Q16::from_bits(i32_at(b, 5)),
                far: Q16::from_bits(i32_at(b, 9)),
            },
            Opcode::View => Command::View {
                eye: point_at(b, 1),
                yaw: Angle::from_bits(u16_at(b, 13)),
                pitch: Angle::from_bits(u16_at(b, 15)),
            },
            Opcode::Light => Command::Light {
                toward: point_at(b, 1),
                percent: b[13],
            },
            Opcode::Thickness => Command::Thickness(Coord::from_bits(i16_at(b, 1))),
            Opcode::Push => Command::Push,
            Opcode::Pop => Command::Pop,
            Opcode::Translate => Command::Translate(point_at(b, 1)),
            Opcode::Rotate => {
                Command::Rotate(Axis::from_byte(b[1])?, Angle::from_bits(u16_at(b, 2)))
            }
            Opcode::Scale => Command::Scale(point_at(b, 1)),
            Opcode::Face => Command::Face(Points { bytes: &b[3..] }),
            Opcode::Label => Command::Label {
                at: point_at(b, 1),
                // Printable ASCII, checked by `new_checked`.
                text: core::str::from_utf8(&b[14..]).unwrap_or(""),
            },
        };
        Some((offset, cmd))
    }
}

/// The vertices of a `poly`: at least 3, each `(x, y)` in Q12.4.
#[derive(Clone, Copy, Debug)]
pub struct Vertices<'a> {
    bytes: &'a [u8],
}

impl<'a> Vertices<'a> {
    /// Number of vertices (3..=65535 for a checked list).
    pub fn len(&self) -> usize {
        self.bytes.len() / 4
    }

    /// `true` when there is no vertex (never for a checked list).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Iterates the vertices.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Vertex> + Clone + 'a {
        self.bytes.chunks_exact(4).map(|c| Vertex {
            x: Coord::from_bits(i16::from_le_bytes([c[0], c[1]])),
            y: Coord::from_bits(i16::from_le_bytes([c[2], c[3]])),
        })
    }
}

/// The vertices of a `poly3`: at least 3, each `(x, y, z)` in Q12.4.
#[derive(Clone, Copy, Debug)]
pub struct Vertices3<'a> {
    bytes: &'a [u8],
}

impl<'a> Vertices3<'a> {
    /// Number of vertices (3..=65535 for a checked list).
    pub fn len(&self) -> usize {
        self.bytes.len() / 6
    }

    /// `true` when there is no vertex (never for a checked list).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Iterates the vertices.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Vertex3> + Clone + 'a {
        self.bytes.chunks_exact(6).map(|c| Vertex3 {
            x: Coord::from_bits(i16::from_le_bytes([c[0], c[1]])),
            y: Coord::from_bits(i16::from_le_bytes([c[2], c[3]])),
            z: Coord::from_bits(i16::from_le_bytes([c[4], c[5]])),
        })
    }
}

/// The vertices of a `face`: at least 1, each `(x, y, z)` in Q16.16.
#[derive(Clone, Copy, Debug)]
pub struct Points<'a> {
    bytes: &'a [u8],
}

impl<'a> Points<'a> {
    /// Number of vertices (1..=65535 for a checked list).
    pub fn len(&self) -> usize {
        self.bytes.len() / 12
    }

    /// `true` when there is no vertex (never for a checked list).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Iterates the vertices.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Point3> + Clone + 'a {
        self.bytes.chunks_exact(12).map(|c| point_at(c, 0))
    }
}
