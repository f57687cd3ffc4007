//! The display list: what the graphic controller reads.
//!
//! A display list is a byte string, little-endian, version 1:
//!
//! ```text
//! offset size  field
//!  0     4     magic  "SCVL"
//!  4     2     version (1)
//!  6     2     frame width  W, 1..=4096
//!  8     2     frame height H, 1..=4096
//! 10     2     reserved, 0
//! 12     4     body length in bytes (everything after the header)
//! 16     ...   commands, each an opcode byte and its operands
//! ```
//!
//! | opcode | command | operands | size |
//! |---|---|---|---|
//! | `0x01` | `clear` | `r g b` | 4 |
//! | `0x02` | `clip`  | `x0 y0 x1 y1`: `i16` whole pixels, inclusive | 9 |
//! | `0x03` | `color` | `r g b` | 4 |
//! | `0x10` | `poly`  | `n: u16` (≥ 3), then `n × (x, y)`: `i16` Q12.4 | 3 + 4n |
//! | `0x11` | `poly3` | `n: u16` (≥ 3), then `n × (x, y, z)`: `i16` Q12.4 | 3 + 6n |
//!
//! Reading is done in two steps, after smoltcp's `wire` module:
//! [`DisplayList::new_checked`] walks the whole list once and returns a
//! typed [`Error`] with the byte offset of the first fault; after that, the
//! [`Commands`] iterator and every accessor cannot fail and cannot panic.
//! [`Writer`] emits the same format into a caller-owned buffer.

mod reader;
mod writer;

pub use reader::{Command, Commands, DisplayList, Vertices, Vertices3};
pub use writer::{WriteError, Writer};

use core::fmt;

/// The four bytes every display list starts with.
pub const MAGIC: [u8; 4] = *b"SCVL";
/// The format version this crate reads and writes.
pub const VERSION: u16 = 1;
/// Size of the header in bytes.
pub const HEADER_LEN: usize = 16;
/// Most vertices one polygon can have (the count is a `u16`).
pub const MAX_VERTICES: usize = u16::MAX as usize;

/// The command codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum Opcode {
    /// Fill the whole frame.
    Clear = 0x01,
    /// Load the clip registers.
    Clip = 0x02,
    /// Set the current colour.
    Color = 0x03,
    /// A 2D polygon in painter's order.
    Poly = 0x10,
    /// A screen-space polygon with depth.
    Poly3 = 0x11,
}

impl Opcode {
    /// The opcode for a byte, if it is one.
    pub const fn from_byte(b: u8) -> Option<Self> {
        Some(match b {
            0x01 => Opcode::Clear,
            0x02 => Opcode::Clip,
            0x03 => Opcode::Color,
            0x10 => Opcode::Poly,
            0x11 => Opcode::Poly3,
            _ => return None,
        })
    }
}

/// What is wrong with a display list.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ErrorKind {
    /// The list ends inside the header or inside a command.
    Truncated,
    /// The first four bytes are not [`MAGIC`].
    BadMagic,
    /// A version this reader does not know.
    UnsupportedVersion(u16),
    /// Width or height outside 1..=4096.
    BadFrameSize {
        /// Declared width.
        width: u16,
        /// Declared height.
        height: u16,
    },
    /// The reserved header field is not zero.
    ReservedNotZero,
    /// The header's body length does not match the bytes that follow.
    LengthMismatch {
        /// Body length in the header.
        declared: u32,
        /// Bytes actually after the header.
        actual: usize,
    },
    /// A byte that is not an [`Opcode`].
    UnknownOpcode(u8),
    /// A polygon with fewer than 3 vertices.
    TooFewVertices(u16),
}

/// A fault in a display list, with the byte offset where it was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Error {
    /// Byte offset from the start of the list.
    pub offset: usize,
    /// What is wrong.
    pub kind: ErrorKind,
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ErrorKind::Truncated => f.write_str("display list is truncated"),
            ErrorKind::BadMagic => f.write_str("not a display list (bad magic number)"),
            ErrorKind::UnsupportedVersion(v) => {
                write!(
                    f,
                    "unsupported display-list version {v} (this reader knows {VERSION})"
                )
            }
            ErrorKind::BadFrameSize { width, height } => {
                write!(f, "frame size {width}x{height} is outside 1..=4096")
            }
            ErrorKind::ReservedNotZero => f.write_str("reserved header field is not zero"),
            ErrorKind::LengthMismatch { declared, actual } => write!(
                f,
                "header declares a body of {declared} bytes but {actual} follow"
            ),
            ErrorKind::UnknownOpcode(b) => write!(f, "unknown opcode 0x{b:02x}"),
            ErrorKind::TooFewVertices(n) => {
                write!(f, "polygon has {n} vertices; at least 3 are needed")
            }
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "byte offset {}: {}", self.offset, self.kind)
    }
}

impl core::error::Error for Error {}
