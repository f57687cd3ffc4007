//! The checked, zero-copy reader.

use super::layout::{self, header, Field, Layout, Tail};
use super::{Error, ErrorKind, Opcode, HEADER_LEN, MAGIC, VERSION, VERSION_2D};
use crate::fixed::{Coord, Vertex, Vertex3};
use crate::geometry::{Angle, Point3, Q16};
use crate::raster::clip::ClipWindow;
use crate::raster::winding::FillRule;
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
///
/// What the check learns on its walk is kept ([`summary`](Self::summary)),
/// so that a reader need not walk the list again to learn it.
#[derive(Clone, Copy, Debug)]
pub struct DisplayList<'a> {
    bytes: &'a [u8],
    width: u16,
    height: u16,
    version: u16,
    summary: Summary,
}

/// What [`DisplayList::new_checked`] learns of a list on its one walk.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub struct Summary {
    /// Commands in the list.
    pub commands: usize,
    /// Byte offset of the first command of the 3D layer (see
    /// [`Opcode::is_3d`]), if there is one.
    pub first_3d: Option<usize>,
    /// `true` when the list has a `clear`, a `poly` or a `line`: a
    /// command that draws in painter's order.
    pub draws_2d: bool,
    /// Byte offset of the last `clear`, if there is one. A `clear` fills
    /// the whole frame, so nothing drawn before it in painter's order
    /// shows: the 2D draws start there.
    pub last_clear: Option<usize>,
    /// Most vertices of one `poly` (0 without one).
    pub poly: u16,
    /// Most vertices of one `poly3` (0 without one).
    pub poly3: u16,
    /// Most vertices of one `face` (0 without one).
    pub face: u16,
    /// Most indices of one `f` (0 without one).
    pub mesh_face: u16,
    /// Most `v`s in one segment (the table's size, counted from the start
    /// of the list and from each `segment`): the slots of the vertex
    /// table a render needs.
    pub vertices: usize,
    /// `true` when the list has a segment attribute (`hide`, `show`,
    /// `highlight`, `place`).
    pub attributes: bool,
}

impl Summary {
    /// Takes in the command `op` at `offset`, whose bytes start `b`.
    fn add(&mut self, op: Opcode, offset: usize, b: &[u8]) {
        self.commands += 1;
        let most = match op {
            Opcode::Clear => {
                self.draws_2d = true;
                self.last_clear = Some(offset);
                return;
            }
            Opcode::Line => {
                self.draws_2d = true;
                return;
            }
            Opcode::Poly => {
                self.draws_2d = true;
                &mut self.poly
            }
            Opcode::Color | Opcode::Clip | Opcode::Fill => return,
            // The rest is the 3D layer's.
            _ => {
                debug_assert!(op.is_3d());
                self.first_3d.get_or_insert(offset);
                if matches!(
                    op,
                    Opcode::Hide | Opcode::Show | Opcode::Highlight | Opcode::Place
                ) {
                    self.attributes = true;
                }
                match op {
                    Opcode::Poly3 => &mut self.poly3,
                    Opcode::Face => &mut self.face,
                    Opcode::MeshFace => &mut self.mesh_face,
                    _ => return,
                }
            }
        };
        // A packed command's fixed part, checked present.
        if let Some(fixed) = b.first_chunk::<{ Layout::COUNT.end }>() {
            *most = (*most).max(u16_at(fixed, Layout::COUNT));
        }
    }
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

/// What the check needs to know of an opcode: its
/// [`version`](Opcode::version), its [`layout`](Opcode::layout), and
/// whether an operand has a range to check; `op` is `None` for a byte
/// that is not an opcode.
#[derive(Clone, Copy)]
struct Rule {
    op: Option<Opcode>,
    version: u16,
    layout: Layout,
    operands: bool,
}

/// The rules of the opcodes, and for each byte the index of its rule
/// (0, no opcode, for the bytes that are not one): made at compile time
/// from [`Opcode::from_byte`], [`Opcode::version`] and [`Opcode::layout`],
/// so that checking a command looks its rule up once rather than matching
/// its opcode for each of them.
static RULES: ([u8; 256], [Rule; 27]) = {
    let none = Rule {
        op: None,
        version: 0,
        layout: Layout {
            fixed: 0,
            tail: Tail::None,
        },
        operands: false,
    };
    let (mut index, mut rules) = ([0u8; 256], [none; 27]);
    let (mut byte, mut n) = (0, 1);
    while byte < 256 {
        if let Some(op) = Opcode::from_byte(byte as u8) {
            rules[n] = Rule {
                op: Some(op),
                version: op.version(),
                layout: op.layout(),
                operands: matches!(
                    op,
                    Opcode::Rotate
                        | Opcode::Light
                        | Opcode::Thickness
                        | Opcode::Fill
                        | Opcode::Label
                        | Opcode::Highlight
                ),
            };
            index[byte] = n as u8;
            n += 1;
        }
        byte += 1;
    }
    (index, rules)
};

/// Size of the command starting at `at` in a list of `version`, or an
/// error, by the command's [`layout`](Opcode::layout). Reads only inside
/// `body`.
fn command_len(body: &[u8], at: usize, version: u16) -> Result<(Opcode, usize), ErrorKind> {
    let rest = &body[at..];
    let byte = rest[0];
    let rule = &RULES.1[RULES.0[byte as usize] as usize];
    let op = match rule.op {
        Some(op) if rule.version <= version => op,
        _ => return Err(ErrorKind::UnknownOpcode(byte)),
    };
    let layout = rule.layout;
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
    if !rule.operands {
        return Ok((op, len));
    }
    let bad = match op {
        Opcode::Rotate => rest[layout::rotate::AXIS] > 2,
        Opcode::Light => rest[layout::light::PERCENT] > 100,
        Opcode::Thickness => i16_at(rest, layout::thickness::T) < 0,
        Opcode::Fill => FillRule::from_byte(rest[layout::fill::RULE]).is_none(),
        Opcode::Highlight => {
            use layout::highlight::{LEN, ON, R};
            // Off carries no colour, so that every list reads back the
            // same from its text.
            rest[ON] > 1 || (rest[ON] == 0 && rest[R..LEN] != [0; LEN - R])
        }
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

/// Checks every command of `body`, a list's body of `version`, and
/// summarises them. Out of line, so that the loop's state stays in
/// registers: inlined into a large caller, it is kept on the stack.
#[inline(never)]
fn walk(body: &[u8], version: u16) -> Result<Summary, Error> {
    let mut at = 0;
    let mut summary = Summary::default();
    // `v`s in the current segment's table.
    let mut table = 0usize;
    while at < body.len() {
        match command_len(body, at, version) {
            Ok((op, len)) => {
                summary.add(op, HEADER_LEN + at, &body[at..]);
                match op {
                    Opcode::Segment => table = 0,
                    Opcode::MeshVertex => {
                        table += 1;
                        summary.vertices = summary.vertices.max(table);
                    }
                    Opcode::MeshFace => {
                        check_indices(&body[at..at + len], table).map_err(|(i, kind)| Error {
                            offset: HEADER_LEN + at + i,
                            kind,
                        })?
                    }
                    _ => {}
                }
                at += len;
            }
            Err(kind) => {
                return Err(Error {
                    offset: HEADER_LEN + at,
                    kind,
                })
            }
        }
    }
    Ok(summary)
}

/// Checks the indices of an `f` (its whole bytes) against a table of
/// `table` vertices: the first bad one's offset in the command and error.
fn check_indices(f: &[u8], table: usize) -> Result<(), (usize, ErrorKind)> {
    use layout::mesh_face::{INDICES, STRIDE};
    for (k, b) in f[INDICES..].chunks_exact(STRIDE).enumerate() {
        let index = u16::from_le_bytes([b[0], b[1]]);
        if index as usize >= table {
            let kind = ErrorKind::BadIndex {
                index,
                vertices: table,
            };
            return Err((INDICES + k * STRIDE, kind));
        }
    }
    Ok(())
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
        let summary = walk(&bytes[HEADER_LEN..], version)?;
        Ok(DisplayList {
            bytes,
            width,
            height,
            version,
            summary,
        })
    }

    /// What the check learnt of the list: its commands, where its 3D
    /// layer starts, whether it draws in 2D, its widest polygons.
    pub fn summary(&self) -> &Summary {
        &self.summary
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
        }
    }

    /// The commands from the one at byte `offset` on (an offset the list
    /// gave, such as [`Summary::last_clear`]); from the first when
    /// `offset` is the header's end or before it.
    pub(crate) fn commands_from(&self, offset: usize) -> Commands<'a> {
        Commands {
            body: &self.bytes[HEADER_LEN..],
            at: offset.saturating_sub(HEADER_LEN),
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
    /// The fill rule of the 2D `poly`s that follow.
    Fill(FillRule),
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
    /// `v`: a vertex appended to the segment's vertex table, transformed
    /// by the transform current here.
    MeshVertex(Point3),
    /// `f`: a polygon (a point, a line) in the current colour through
    /// vertices of the segment's table, by 0-based index (each below the
    /// `v`s of the segment before it, checked), with the rules of
    /// [`Command::Face`].
    MeshFace(Packed<'a, u16>),
    /// Hide the segment: its faces, points, lines, `poly3`s and labels
    /// are not drawn.
    Hide(u16),
    /// Show the segment (undoes `Hide`).
    Show(u16),
    /// Draw the segment's faces, points, lines and `poly3`s in this
    /// colour, unlit, or in their own (`None`).
    Highlight(u16, Option<Rgb888>),
    /// Place the segment: its commands are built after these transforms.
    /// Kept as its bytes, so that a command stays as small as it was.
    Place(Placed<'a>),
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
            Command::Fill(_) => Opcode::Fill,
            Command::Push => Opcode::Push,
            Command::Pop => Opcode::Pop,
            Command::Translate(_) => Opcode::Translate,
            Command::Rotate(..) => Opcode::Rotate,
            Command::Scale(_) => Opcode::Scale,
            Command::Face(_) => Opcode::Face,
            Command::Label { .. } => Opcode::Label,
            Command::MeshVertex(_) => Opcode::MeshVertex,
            Command::MeshFace(_) => Opcode::MeshFace,
            Command::Hide(_) => Opcode::Hide,
            Command::Show(_) => Opcode::Show,
            Command::Highlight(..) => Opcode::Highlight,
            Command::Place(..) => Opcode::Place,
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

    /// A `poly`'s number of vertices; `None` for every other command.
    pub fn poly_vertices(&self) -> Option<usize> {
        match self {
            Command::Poly(v) => Some(v.len()),
            _ => None,
        }
    }
}

/// A `place` command's operands, read when asked.
#[derive(Clone, Copy, Debug)]
pub struct Placed<'a>(&'a [u8; layout::place::LEN]);

impl Placed<'_> {
    /// The segment.
    pub fn id(&self) -> u16 {
        u16_at(self.0, layout::place::ID)
    }

    /// The placement.
    pub fn placement(&self) -> super::Placement {
        use layout::place::{ROTATE, SCALE, TRANSLATE};
        let a = |k: usize| {
            let at = ROTATE.start + 2 * k;
            Angle::from_bits(u16_at(self.0, at..at + 2))
        };
        super::Placement {
            translate: point_at(self.0, TRANSLATE),
            rotate: [a(0), a(1), a(2)],
            scale: point_at(self.0, SCALE),
        }
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
}

impl<'a> Iterator for Commands<'a> {
    /// `(byte offset of the opcode, command)`.
    type Item = (usize, Command<'a>);

    // Inlined into each reading loop, so that the command is decoded into
    // the loop's own registers and match rather than returned through
    // memory, which costs instructions on every command.
    #[inline(always)]
    fn next(&mut self) -> Option<Self::Item> {
        let rest = self.body.get(self.at..)?;
        let (cmd, len) = decode(rest)?;
        let offset = HEADER_LEN + self.at;
        self.at += len;
        Some((offset, cmd))
    }
}

impl<'a> Commands<'a> {
    /// The next command when it is a `v` or an `f`, as
    /// [`next`](Iterator::next) gives it; `None`, with nothing taken,
    /// when it is another command or the list ends. A mesh's run of
    /// `v`s and `f`s is read by this in one loop, without the general
    /// decode's match over every opcode.
    #[doc(hidden)]
    #[inline(always)]
    pub fn next_mesh(&mut self) -> Option<(usize, Command<'a>)> {
        let rest = self.body.get(self.at..)?;
        let (cmd, len) = match *rest.first()? {
            b if b == Opcode::MeshFace as u8 => {
                let count = u16_at(rest.first_chunk::<3>()?, Layout::COUNT);
                let len = Opcode::MeshFace.layout().size(count as usize);
                let fixed = Opcode::MeshFace.layout().fixed;
                (Command::MeshFace(Packed::new(rest.get(fixed..len)?)), len)
            }
            b if b == Opcode::MeshVertex as u8 => {
                use layout::point::{LEN, P};
                let p = point_at(rest.first_chunk::<LEN>()?, P);
                (Command::MeshVertex(p), LEN)
            }
            _ => return None,
        };
        let offset = HEADER_LEN + self.at;
        self.at += len;
        Some((offset, cmd))
    }
}

/// The command at the start of `rest`, a checked list's body from a
/// command on, and its size; `None` at the end of the body.
///
/// The list has passed [`DisplayList::new_checked`], so the opcode is
/// known, the command complete and its operands in range: none of that
/// is checked again. Each command's fixed part is taken as one array (one
/// bounds check, then every field at a constant offset inside it), and a
/// packed or text tail as one slice; a read outside `rest` (which a
/// checked list never makes) ends the iteration rather than panicking.
#[inline(always)]
pub(crate) fn decode(rest: &[u8]) -> Option<(Command<'_>, usize)> {
    /// The fixed part of a command of `N` bytes.
    #[inline(always)]
    fn fixed<const N: usize>(rest: &[u8]) -> Option<&[u8; N]> {
        rest.first_chunk::<N>()
    }
    /// A packed command: its tail of `count` items of `stride` bytes
    /// after its fixed part, and its size.
    #[inline(always)]
    fn packed<'a, V: FromBytes + 'a>(rest: &'a [u8], op: Opcode) -> Option<(Packed<'a, V>, usize)> {
        let layout = op.layout();
        let count = u16_at(fixed::<3>(rest)?, Layout::COUNT);
        let len = layout.size(count as usize);
        Some((Packed::new(rest.get(layout.fixed..len)?), len))
    }
    let rgb = |b: &[u8; layout::rgb::LEN]| {
        use layout::rgb::{B, G, R};
        Rgb888::new(b[R], b[G], b[B])
    };
    let op = Opcode::from_byte(*rest.first()?)?;
    Some(match op {
        Opcode::Clear => (Command::Clear(rgb(fixed(rest)?)), layout::rgb::LEN),
        Opcode::Color => (Command::Color(rgb(fixed(rest)?)), layout::rgb::LEN),
        Opcode::Clip => {
            use layout::clip::{LEN, X0, X1, Y0, Y1};
            let b = fixed::<LEN>(rest)?;
            let win = ClipWindow {
                x0: i16_at(b, X0),
                y0: i16_at(b, Y0),
                x1: i16_at(b, X1),
                y1: i16_at(b, Y1),
            };
            (Command::Clip(win), LEN)
        }
        Opcode::Line => {
            use layout::line::{LEN, X0, X1, Y0, Y1};
            let b = fixed::<LEN>(rest)?;
            (
                Command::Line(vertex_at(b, X0, Y0), vertex_at(b, X1, Y1)),
                LEN,
            )
        }
        Opcode::Poly => {
            let (v, len) = packed(rest, op)?;
            (Command::Poly(v), len)
        }
        Opcode::Poly3 => {
            let (v, len) = packed(rest, op)?;
            (Command::Poly3(v), len)
        }
        Opcode::Face => {
            let (p, len) = packed(rest, op)?;
            (Command::Face(p), len)
        }
        Opcode::Segment => {
            use layout::segment::{ID, LEN};
            (Command::Segment(u16_at(fixed::<LEN>(rest)?, ID)), LEN)
        }
        Opcode::Perspective => {
            use layout::perspective::{FAR, FOV, LEN, NEAR};
            let b = fixed::<LEN>(rest)?;
            let cmd = Command::Perspective {
                fov: Angle::from_bits(u16_at(b, FOV)),
                near: Q16::from_bits(i32_at(b, NEAR)),
                far: Q16::from_bits(i32_at(b, FAR)),
            };
            (cmd, LEN)
        }
        Opcode::Ortho => {
            use layout::ortho::{FAR, LEN, NEAR, SCALE};
            let b = fixed::<LEN>(rest)?;
            let cmd = Command::Ortho {
                scale: Q16::from_bits(i32_at(b, SCALE)),
                near: Q16::from_bits(i32_at(b, NEAR)),
                far: Q16::from_bits(i32_at(b, FAR)),
            };
            (cmd, LEN)
        }
        Opcode::View => {
            use layout::view::{EYE, LEN, PITCH, YAW};
            let b = fixed::<LEN>(rest)?;
            let cmd = Command::View {
                eye: point_at(b, EYE),
                yaw: Angle::from_bits(u16_at(b, YAW)),
                pitch: Angle::from_bits(u16_at(b, PITCH)),
            };
            (cmd, LEN)
        }
        Opcode::Light => {
            use layout::light::{LEN, PERCENT, TOWARD};
            let b = fixed::<LEN>(rest)?;
            let cmd = Command::Light {
                toward: point_at(b, TOWARD),
                percent: b[PERCENT],
            };
            (cmd, LEN)
        }
        Opcode::Thickness => {
            use layout::thickness::{LEN, T};
            let t = Coord::from_bits(i16_at(fixed::<LEN>(rest)?, T));
            (Command::Thickness(t), LEN)
        }
        Opcode::Fill => {
            use layout::fill::{LEN, RULE};
            let rule = FillRule::from_byte(fixed::<LEN>(rest)?[RULE])?;
            (Command::Fill(rule), LEN)
        }
        Opcode::Push => (Command::Push, layout::bare::LEN),
        Opcode::Pop => (Command::Pop, layout::bare::LEN),
        Opcode::Translate => {
            use layout::point::{LEN, P};
            (Command::Translate(point_at(fixed::<LEN>(rest)?, P)), LEN)
        }
        Opcode::Scale => {
            use layout::point::{LEN, P};
            (Command::Scale(point_at(fixed::<LEN>(rest)?, P)), LEN)
        }
        Opcode::MeshVertex => {
            use layout::point::{LEN, P};
            (Command::MeshVertex(point_at(fixed::<LEN>(rest)?, P)), LEN)
        }
        Opcode::MeshFace => {
            let (p, len) = packed(rest, op)?;
            (Command::MeshFace(p), len)
        }
        Opcode::Rotate => {
            use layout::rotate::{ANGLE, AXIS, LEN};
            let b = fixed::<LEN>(rest)?;
            let cmd = Command::Rotate(
                Axis::from_byte(b[AXIS])?,
                Angle::from_bits(u16_at(b, ANGLE)),
            );
            (cmd, LEN)
        }
        Opcode::Hide | Opcode::Show => {
            use layout::segment::{ID, LEN};
            let id = u16_at(fixed::<LEN>(rest)?, ID);
            let cmd = match op {
                Opcode::Hide => Command::Hide(id),
                _ => Command::Show(id),
            };
            (cmd, LEN)
        }
        Opcode::Highlight => {
            use layout::highlight::{B, G, ID, LEN, ON, R};
            let b = fixed::<LEN>(rest)?;
            let color = (b[ON] != 0).then(|| Rgb888::new(b[R], b[G], b[B]));
            (Command::Highlight(u16_at(b, ID), color), LEN)
        }
        Opcode::Place => {
            use layout::place::LEN;
            (Command::Place(Placed(fixed::<LEN>(rest)?)), LEN)
        }
        Opcode::Label => {
            use layout::label::{AT, TEXT, TEXT_LEN};
            let b = fixed::<TEXT>(rest)?;
            let len = op.layout().size(b[TEXT_LEN] as usize);
            // Printable ASCII, checked by `new_checked`.
            let text = core::str::from_utf8(rest.get(TEXT..len)?).ok()?;
            (
                Command::Label {
                    at: point_at(b, AT),
                    text,
                },
                len,
            )
        }
    })
}

/// An item of a packed list in a command (a vertex of `poly`, `poly3`
/// or `face`), read from [`SIZE`](Self::SIZE) little-endian bytes; the
/// size is the command's stride in [`layout`].
#[doc(hidden)]
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

impl FromBytes for u16 {
    const SIZE: usize = layout::mesh_face::STRIDE;
    fn from_bytes(c: &[u8]) -> Self {
        u16_at(c, 0..2)
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

impl Packed<'_, u16> {
    /// An `f`'s three indices when it has exactly three (a triangle),
    /// read from the list's bytes at once.
    #[inline(always)]
    pub fn triangle(&self) -> Option<[u16; 3]> {
        let b: &[u8; 6] = self.bytes.try_into().ok()?;
        Some([
            u16::from_le_bytes([b[0], b[1]]),
            u16::from_le_bytes([b[2], b[3]]),
            u16::from_le_bytes([b[4], b[5]]),
        ])
    }
}

impl<'a, V: FromBytes + 'a> IntoIterator for Packed<'a, V> {
    type Item = V;
    type IntoIter = Items<'a, V>;

    /// The items, in order (as [`Packed::iter`]).
    fn into_iter(self) -> Items<'a, V> {
        Items {
            chunks: self.bytes.chunks_exact(V::SIZE),
            item: PhantomData,
        }
    }
}

/// The items of a [`Packed`], in order.
#[derive(Clone, Debug)]
pub struct Items<'a, V> {
    chunks: core::slice::ChunksExact<'a, u8>,
    item: PhantomData<fn() -> V>,
}

impl<V: FromBytes> Iterator for Items<'_, V> {
    type Item = V;

    #[inline]
    fn next(&mut self) -> Option<V> {
        self.chunks.next().map(V::from_bytes)
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.chunks.size_hint()
    }

    #[inline]
    fn fold<B, F: FnMut(B, V) -> B>(self, init: B, f: F) -> B {
        self.chunks.map(V::from_bytes).fold(init, f)
    }
}

impl<V: FromBytes> ExactSizeIterator for Items<'_, V> {
    #[inline]
    fn len(&self) -> usize {
        self.chunks.len()
    }
}

/// The vertices of a `poly`: at least 3, each `(x, y)` in Q12.4.
pub type Vertices<'a> = Packed<'a, Vertex>;

/// The vertices of a `poly3`: at least 3, each `(x, y, z)` in Q12.4.
pub type Vertices3<'a> = Packed<'a, Vertex3>;

/// The vertices of a `face`: at least 1, each `(x, y, z)` in Q16.16.
pub type Points<'a> = Packed<'a, Point3>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::display_list::Writer;

    /// A list of every command, each once.
    fn every_command(bytes: &mut [u8]) -> &[u8] {
        let p = |x, y, z| Point3::from_bits(x, y, z);
        let v = |x, y| Vertex {
            x: Coord::from_bits(x),
            y: Coord::from_bits(y),
        };
        let v3 = |x, y, z| Vertex3 {
            x: Coord::from_bits(x),
            y: Coord::from_bits(y),
            z: Coord::from_bits(z),
        };
        let q = Q16::from_bits;
        let mut w = Writer::new(bytes, 320, 200).unwrap();
        w.clear(Rgb888::new(1, 2, 3)).unwrap();
        w.clip(ClipWindow {
            x0: -1,
            y0: 2,
            x1: 300,
            y1: -4,
        })
        .unwrap();
        w.color(Rgb888::new(4, 5, 6)).unwrap();
        w.poly([v(1, 2), v(-3, 4), v(5, -6)]).unwrap();
        w.poly3([v3(1, 2, 3), v3(4, 5, 6), v3(7, 8, 9), v3(-1, -2, -3)])
            .unwrap();
        w.line(v(7, 8), v(-9, 10)).unwrap();
        w.segment(513).unwrap();
        w.perspective(Angle::from_bits(1234), q(5), q(-6)).unwrap();
        w.ortho(q(7), q(8), q(-9)).unwrap();
        w.view(p(1, -2, 3), Angle::from_bits(40000), Angle::from_bits(5))
            .unwrap();
        w.light(p(-7, 8, 9), 100).unwrap();
        w.thickness(Coord::from_bits(33)).unwrap();
        w.push().unwrap();
        w.pop().unwrap();
        w.translate(p(i32::MIN, i32::MAX, 0)).unwrap();
        w.rotate(Axis::Z, Angle::from_bits(65535)).unwrap();
        w.scale(p(3, 2, 1)).unwrap();
        w.face([p(1, 2, 3)]).unwrap();
        w.label(p(4, 5, 6), "Hi!").unwrap();
        w.finish()
    }

    #[test]
    fn the_summary_is_what_the_commands_say() {
        let mut bytes = [0u8; 512];
        let list = DisplayList::new_checked(every_command(&mut bytes)).unwrap();
        let s = list.summary();
        let first = list.commands().find(|(_, c)| c.is_3d()).map(|(o, _)| o);
        assert_eq!(first, Some(HEADER_LEN + 4 + 9 + 4 + 15));
        assert_eq!(
            (s.commands, s.first_3d, s.draws_2d),
            (list.commands().count(), first, true)
        );
        assert_eq!((s.poly, s.poly3, s.face), (3, 4, 1));
        // Colour and clip draw nothing; a `poly3` is the 3D layer's.
        let mut w = Writer::new(&mut bytes, 8, 8).unwrap();
        w.color(Rgb888::new(1, 2, 3)).unwrap();
        w.clip(ClipWindow {
            x0: 0,
            y0: 0,
            x1: 3,
            y1: 3,
        })
        .unwrap();
        let v3 = |x| Vertex3 {
            x: Coord::from_bits(x),
            y: Coord::from_bits(x * x),
            z: Coord::from_bits(0),
        };
        for n in [5, 3, 9, 4] {
            w.poly3((0..n).map(v3)).unwrap();
        }
        let list = DisplayList::new_checked(w.finish()).unwrap();
        let s = *list.summary();
        assert_eq!((s.commands, s.first_3d, s.draws_2d), (6, Some(29), false));
        assert_eq!((s.poly, s.poly3, s.face), (0, 9, 0));
        // No command at all.
        let list = DisplayList::new_checked(Writer::new(&mut bytes, 8, 8).unwrap().finish());
        assert_eq!(*list.unwrap().summary(), Summary::default());
    }

    #[test]
    fn commands_read_what_was_written_with_the_checked_sizes() {
        let mut bytes = [0u8; 512];
        let list = DisplayList::new_checked(every_command(&mut bytes)).unwrap();
        let body = &list.as_bytes()[HEADER_LEN..];
        // The offsets are those of the checking walk, command by command.
        let mut at = 0;
        let mut n = 0;
        for (offset, cmd) in list.commands() {
            assert_eq!(offset, HEADER_LEN + at);
            let (op, len) = command_len(body, at, list.version()).unwrap();
            assert_eq!(cmd.opcode(), op);
            at += len;
            n += 1;
        }
        assert_eq!((at, n), (body.len(), 19));
        let mut c = list.commands().map(|(_, c)| c);
        let p = |x, y, z| Point3::from_bits(x, y, z);
        assert!(matches!(c.next(), Some(Command::Clear(k)) if k == Rgb888::new(1, 2, 3)));
        assert!(matches!(
            c.next(),
            Some(Command::Clip(ClipWindow {
                x0: -1,
                y0: 2,
                x1: 300,
                y1: -4
            }))
        ));
        assert!(matches!(c.next(), Some(Command::Color(k)) if k == Rgb888::new(4, 5, 6)));
        let Some(Command::Poly(v)) = c.next() else {
            panic!("poly")
        };
        let xy = |v: Vertex| (v.x.to_bits(), v.y.to_bits());
        let mut it = v.iter().map(xy);
        assert_eq!(v.len(), 3);
        assert_eq!(
            (it.next(), it.next(), it.next(), it.next()),
            (Some((1, 2)), Some((-3, 4)), Some((5, -6)), None)
        );
        let Some(Command::Poly3(v)) = c.next() else {
            panic!("poly3")
        };
        assert_eq!(v.len(), 4);
        let last = v.iter().last().unwrap();
        assert_eq!(
            (last.x.to_bits(), last.y.to_bits(), last.z.to_bits()),
            (-1, -2, -3)
        );
        let Some(Command::Line(a, b)) = c.next() else {
            panic!("line")
        };
        assert_eq!((xy(a), xy(b)), ((7, 8), (-9, 10)));
        assert!(matches!(c.next(), Some(Command::Segment(513))));
        assert!(matches!(
            c.next(),
            Some(Command::Perspective { fov, near, far })
                if (fov.to_bits(), near.to_bits(), far.to_bits()) == (1234, 5, -6)
        ));
        assert!(matches!(
            c.next(),
            Some(Command::Ortho { scale, near, far })
                if (scale.to_bits(), near.to_bits(), far.to_bits()) == (7, 8, -9)
        ));
        assert!(matches!(
            c.next(),
            Some(Command::View { eye, yaw, pitch })
                if (eye, yaw.to_bits(), pitch.to_bits()) == (p(1, -2, 3), 40000, 5)
        ));
        assert!(matches!(
            c.next(),
            Some(Command::Light { toward, percent: 100 }) if toward == p(-7, 8, 9)
        ));
        assert!(matches!(c.next(), Some(Command::Thickness(t)) if t.to_bits() == 33));
        assert!(matches!(c.next(), Some(Command::Push)));
        assert!(matches!(c.next(), Some(Command::Pop)));
        assert!(matches!(
            c.next(),
            Some(Command::Translate(t)) if t == p(i32::MIN, i32::MAX, 0)
        ));
        assert!(matches!(
            c.next(),
            Some(Command::Rotate(Axis::Z, a)) if a.to_bits() == 65535
        ));
        assert!(matches!(c.next(), Some(Command::Scale(s)) if s == p(3, 2, 1)));
        let Some(Command::Face(f)) = c.next() else {
            panic!("face")
        };
        assert_eq!((f.len(), f.iter().next()), (1, Some(p(1, 2, 3))));
        assert!(matches!(
            c.next(),
            Some(Command::Label { at, text: "Hi!" }) if at == p(4, 5, 6)
        ));
        assert!(c.next().is_none());
        assert!(c.next().is_none(), "stays at the end");
    }
}
