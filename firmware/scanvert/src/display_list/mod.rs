//! The display list: what the graphic controller reads.
//!
//! A display list is a byte string, little-endian:
//!
//! ```text
//! offset size  field
//!  0     4     magic  "SCVL"
//!  4     2     version: 1 (2D commands only) or 2 (with 3D commands)
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
//! | `0x12` | `line`  | `x0 y0 x1 y1`: `i16` Q12.4 (version 2) | 9 |
//!
//! Version 2 adds `line` (drawn by [`raster::line`](crate::raster::line),
//! in painter's order with `poly`) and the 3D scene (world values are `i32` Q16.16, angles `u16`
//! binary angles, 65536 to the turn; see [`crate::geometry`]):
//!
//! | opcode | command | operands | size |
//! |---|---|---|---|
//! | `0x20` | `segment` | `id: u16` | 3 |
//! | `0x21` | `perspective` | `fov: u16` angle, `near far`: Q16.16 | 11 |
//! | `0x22` | `ortho` | `scale near far`: Q16.16 | 13 |
//! | `0x23` | `view` | `eye x y z`: Q16.16, `yaw pitch`: angles | 17 |
//! | `0x24` | `light` | `toward x y z`: Q16.16, `percent: u8` (≤ 100) | 14 |
//! | `0x25` | `thickness` | `t: i16` Q12.4 px (≥ 0) | 3 |
//! | `0x26` | `push` | | 1 |
//! | `0x27` | `pop` | | 1 |
//! | `0x28` | `translate` | `x y z`: Q16.16 | 13 |
//! | `0x29` | `rotate` | `axis: u8` (0 x, 1 y, 2 z), angle | 4 |
//! | `0x2a` | `scale` | `x y z`: Q16.16 | 13 |
//! | `0x30` | `face` | `n: u16` (≥ 1), then `n × (x, y, z)`: Q16.16 | 3 + 12n |
//! | `0x31` | `label` | `x y z`: Q16.16, `len: u8` (≥ 1), `len` bytes of printable ASCII | 14 + len |
//! | `0x32` | `v` | `x y z`: Q16.16 | 13 |
//! | `0x33` | `f` | `n: u16` (≥ 1), then `n × i: u16` (0-based) | 3 + 2n |
//! | `0x34` | `fill` | `rule: u8`: 0 even-odd, 1 non-zero ([`FillRule`](crate::raster::FillRule)) | 2 |
//!
//! `fill` is a 2D command (version 2): it sets the fill rule of the `poly`s
//! after it, as `color` sets their colour, until the next `fill`; a list
//! starts with even-odd.
//!
//! A version-1 list may hold only version-1 opcodes. [`Writer`] stamps the
//! lowest version that holds what was written, so a list of only the
//! version-1 commands stays version 1, byte for byte as before `line`
//! existed. A reader older than `line` rejects a list holding one with
//! [`ErrorKind::UnknownOpcode`]`(0x12)` at the command's byte offset; it
//! never misreads it.
//!
//! Every size and offset above is in [`layout`], the one table the
//! reader, the writer and the host's text tools use; which commands belong
//! to the 3D layer is [`Opcode::is_3d`].
//!
//! Reading is done in two steps, after smoltcp's `wire` module:
//! [`DisplayList::new_checked`] walks the whole list once and returns a
//! typed [`Error`] with the byte offset of the first fault; after that, the
//! [`Commands`] iterator and every accessor cannot fail and cannot panic.
//! The iterator trusts the check (it does not check a command again), and
//! what the check learns on its walk (the number of commands, where the 3D
//! layer starts, the widest polygons: [`Summary`]) is kept with the list,
//! so that the controller need not walk it again to learn it.
//! [`Writer`] emits the same format into a caller-owned buffer.

mod draws;
#[doc(hidden)]
pub mod layout;
mod placement;
mod reader;
mod writer;

pub use draws::{Draws, ScratchTooSmall};
pub use placement::Placement;
pub(crate) use reader::decode;
pub use reader::{
    Axis, Command, Commands, DisplayList, FromBytes, Items, Packed, Placed, Points, Summary,
    Vertices, Vertices3,
};
pub use writer::{WriteError, Writer};

use core::fmt;

/// The four bytes every display list starts with.
pub const MAGIC: [u8; 4] = *b"SCVL";
/// The newest format version this crate reads and writes.
pub const VERSION: u16 = 2;
/// The version of lists that hold only 2D commands.
pub const VERSION_2D: u16 = 1;
/// Most bytes of a label's text.
pub const MAX_LABEL_LEN: usize = u8::MAX as usize;
/// Size of the header in bytes.
pub const HEADER_LEN: usize = layout::header::LEN;
/// Most vertices one polygon can have (the count is a `u16`).
pub const MAX_VERTICES: usize = u16::MAX as usize;

/// The command codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
#[non_exhaustive]
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
    /// A 2D line one pixel wide, in painter's order (version 2).
    Line = 0x12,
    /// Start (or return to) a segment of the 3D scene.
    Segment = 0x20,
    /// Perspective projection.
    Perspective = 0x21,
    /// Orthographic projection.
    Ortho = 0x22,
    /// The camera.
    View = 0x23,
    /// The parallel light.
    Light = 0x24,
    /// Thickness of points and lines.
    Thickness = 0x25,
    /// Save the modelling transform.
    Push = 0x26,
    /// Restore the modelling transform.
    Pop = 0x27,
    /// Translate the modelling transform.
    Translate = 0x28,
    /// Rotate the modelling transform about an axis.
    Rotate = 0x29,
    /// Scale the modelling transform.
    Scale = 0x2a,
    /// A 3D polygon (one vertex: a point; two: a line).
    Face = 0x30,
    /// A text label at a 3D point.
    Label = 0x31,
    /// A vertex of the segment's mesh table (`v`).
    MeshVertex = 0x32,
    /// A face through vertices of the segment's mesh table (`f`).
    MeshFace = 0x33,
    /// The fill rule of the `poly`s that follow (version 2).
    Fill = 0x34,
    /// Hide a segment.
    Hide = 0x35,
    /// Show a segment.
    Show = 0x36,
    /// Highlight a segment, or clear its highlight.
    Highlight = 0x37,
    /// Place a segment.
    Place = 0x38,
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
            0x12 => Opcode::Line,
            0x20 => Opcode::Segment,
            0x21 => Opcode::Perspective,
            0x22 => Opcode::Ortho,
            0x23 => Opcode::View,
            0x24 => Opcode::Light,
            0x25 => Opcode::Thickness,
            0x26 => Opcode::Push,
            0x27 => Opcode::Pop,
            0x28 => Opcode::Translate,
            0x29 => Opcode::Rotate,
            0x2a => Opcode::Scale,
            0x30 => Opcode::Face,
            0x31 => Opcode::Label,
            0x32 => Opcode::MeshVertex,
            0x33 => Opcode::MeshFace,
            0x34 => Opcode::Fill,
            0x35 => Opcode::Hide,
            0x36 => Opcode::Show,
            0x37 => Opcode::Highlight,
            0x38 => Opcode::Place,
            _ => return None,
        })
    }

    /// The first format version that has this opcode.
    pub const fn version(self) -> u16 {
        match self {
            Opcode::Clear | Opcode::Clip | Opcode::Color | Opcode::Poly | Opcode::Poly3 => {
                VERSION_2D
            }
            _ => VERSION,
        }
    }

    /// `true` for the commands of the 3D layer: `poly3` and the 3D
    /// scene's. The others (`clear`, `clip`, `color`, `fill`, `poly`,
    /// `line`) are the 2D commands, executed in painter's order; `clip`
    /// and `color` also set the registers the 3D layer takes (`fill` is
    /// the 2D `poly`s' alone).
    pub const fn is_3d(self) -> bool {
        !matches!(
            self,
            Opcode::Clear
                | Opcode::Clip
                | Opcode::Color
                | Opcode::Fill
                | Opcode::Poly
                | Opcode::Line
        )
    }

    /// `true` for the 3D scene's commands: the 3D layer but `poly3`.
    pub const fn is_scene(self) -> bool {
        self.is_3d() && !matches!(self, Opcode::Poly3)
    }

    /// The command's name in the text form.
    pub const fn name(self) -> &'static str {
        match self {
            Opcode::Clear => "clear",
            Opcode::Clip => "clip",
            Opcode::Color => "color",
            Opcode::Poly => "poly",
            Opcode::Poly3 => "poly3",
            Opcode::Line => "line",
            Opcode::Segment => "segment",
            Opcode::Perspective => "perspective",
            Opcode::Ortho => "ortho",
            Opcode::View => "view",
            Opcode::Light => "light",
            Opcode::Thickness => "thickness",
            Opcode::Push => "push",
            Opcode::Pop => "pop",
            Opcode::Translate => "translate",
            Opcode::Rotate => "rotate",
            Opcode::Scale => "scale",
            Opcode::Face => "face",
            Opcode::Label => "label",
            Opcode::MeshVertex => "v",
            Opcode::MeshFace => "f",
            Opcode::Fill => "fill",
            Opcode::Hide => "hide",
            Opcode::Show => "show",
            Opcode::Highlight => "highlight",
            Opcode::Place => "place",
        }
    }

    /// The opcode of a text-form name (`lookat`, which the text form
    /// turns into a `view`, is not one).
    pub fn from_name(name: &str) -> Option<Self> {
        (0..=u8::MAX)
            .filter_map(Opcode::from_byte)
            .find(|op| op.name() == name)
    }
}

/// What is wrong with a display list.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
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
    /// A polygon with fewer than 3 vertices (`face`: fewer than 1).
    TooFewVertices(u16),
    /// An operand outside its range: a rotation axis over 2, a light over
    /// 100 %, a negative thickness, a fill rule other than 0 and 1, an
    /// empty label or one with a byte that is not printable ASCII.
    BadOperand(Opcode),
    /// An `f` index that names no vertex of its segment's table: the
    /// table then held `vertices` (the error's offset is the index's).
    BadIndex {
        /// The 0-based index.
        index: u16,
        /// Vertices in the segment's table at the `f`.
        vertices: usize,
    },
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
                    "unsupported display-list version {v} (this reader knows {VERSION_2D} and {VERSION})"
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
                write!(
                    f,
                    "polygon has {n} vertices; at least 3 are needed (a face: 1)"
                )
            }
            ErrorKind::BadOperand(op) => write!(f, "operand out of range in {op:?}"),
            ErrorKind::BadIndex { index, vertices } => write!(
                f,
                "f names vertex {} of a table of {vertices} (since the segment's start)",
                index as usize + 1
            ),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "byte offset {}: {}", self.offset, self.kind)
    }
}

impl core::error::Error for Error {}
