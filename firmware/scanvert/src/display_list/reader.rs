//! The checked, zero-copy reader.

use super::{Error, ErrorKind, Opcode, HEADER_LEN, MAGIC, VERSION};
use crate::clip::ClipWindow;
use crate::fixed::{Coord, Vertex, Vertex3};
use embedded_graphics_core::pixelcolor::Rgb888;

/// A display list that has passed [`DisplayList::new_checked`].
///
/// # Guarantees
/// The header is valid, the frame is 1..=4096 on each side, and the body is
/// a sequence of complete, known commands that ends exactly at the end of
/// the buffer, each polygon with at least 3 vertices. Nothing reachable from
/// a `DisplayList` can fail or panic.
#[derive(Clone, Copy, Debug)]
pub struct DisplayList<'a> {
    bytes: &'a [u8],
    width: u16,
    height: u16,
}

#[inline(always)]
fn u16_at(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

#[inline(always)]
fn i16_at(b: &[u8], at: usize) -> i16 {
    i16::from_le_bytes([b[at], b[at + 1]])
}

/// Size of the command starting at `at`, or an error. Reads only inside
/// `body`.
fn command_len(body: &[u8], at: usize) -> Result<(Opcode, usize), ErrorKind> {
    let op = Opcode::from_byte(body[at]).ok_or(ErrorKind::UnknownOpcode(body[at]))?;
    let rest = body.len() - at;
    let fixed = match op {
        Opcode::Clear | Opcode::Color => 4,
        Opcode::Clip => 9,
        Opcode::Poly | Opcode::Poly3 => 3,
    };
    if rest < fixed {
        return Err(ErrorKind::Truncated);
    }
    let len = match op {
        Opcode::Poly | Opcode::Poly3 => {
            let n = u16_at(body, at + 1);
            if n < 3 {
                return Err(ErrorKind::TooFewVertices(n));
            }
            let per = if op == Opcode::Poly { 4 } else { 6 };
            3 + per * n as usize
        }
        _ => fixed,
    };
    if rest < len {
        return Err(ErrorKind::Truncated);
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
        if version != VERSION {
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
            match command_len(body, at) {
                Ok((_, len)) => at += len,
                Err(kind) => return Err(err(HEADER_LEN + at, kind)),
            }
        }
        Ok(DisplayList {
            bytes,
            width,
            height,
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

    /// The whole list, header included.
    pub fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The commands in order.
    pub fn commands(&self) -> Commands<'a> {
        Commands {
            body: &self.bytes[HEADER_LEN..],
            at: 0,
        }
    }
}

/// One command of a checked display list.
#[derive(Clone, Copy, Debug)]
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
}

/// Iterator over the commands of a [`DisplayList`], with each command's
/// byte offset in the list.
#[derive(Clone, Debug)]
pub struct Commands<'a> {
    body: &'a [u8],
    at: usize,
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
        let (op, len) = command_len(self.body, self.at).ok()?;
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
