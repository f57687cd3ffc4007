//! The binary format's layout, in one place: every byte range of the
//! header and of each command, after smoltcp's `mod field`.
//!
//! The reader, the [`Writer`](super::Writer), and the host's assembler and
//! disassembler all take sizes and offsets from here, and
//! [`Opcode::layout`] gives each command's size rule; nothing else spells
//! out a number of bytes. Offsets inside a command count from its opcode
//! byte (offset 0). All multi-byte values are little-endian; `i16` Q12.4
//! coordinates, `i32` Q16.16 world values, `u16` binary angles.
//!
//! | module | command | fixed part | then |
//! |---|---|---|---|
//! | [`rgb`] | `clear`, `color` | 4 | |
//! | [`clip`] | `clip` | 9 | |
//! | [`line`](mod@line) | `line` | 9 | |
//! | [`poly`] | `poly` | 3 | `n × 4` (`n` ≥ 3 at [`poly::COUNT`]) |
//! | [`poly3`] | `poly3` | 3 | `n × 6` (`n` ≥ 3) |
//! | [`segment`] | `segment` | 3 | |
//! | [`perspective`] | `perspective` | 11 | |
//! | [`ortho`] | `ortho` | 13 | |
//! | [`view`] | `view` | 17 | |
//! | [`light`] | `light` | 14 | |
//! | [`thickness`] | `thickness` | 3 | |
//! | [`bare`] | `push`, `pop` | 1 | |
//! | [`point`] | `translate`, `scale` | 13 | |
//! | [`rotate`] | `rotate` | 4 | |
//! | [`face`] | `face` | 3 | `n × 12` (`n` ≥ 1) |
//! | [`label`] | `label` | 14 | `len` text bytes (`len` at [`label::TEXT_LEN`]) |
//! | [`point`] | `v` | 13 | |
//! | [`mesh_face`] | `f` | 3 | `n × 2` (`n` ≥ 1): `u16` 0-based indices into the segment's table |
//! | [`fill`] | `fill` | 2 | |
//! | [`segment`] | `hide`, `show` | 3 | |
//! | [`highlight`] | `highlight` | 7 | |
//! | [`place`] | `place` | 33 | |
//!
//! The tests at the end check that the table and the field modules agree.

use super::Opcode;
use core::ops::Range;

/// A byte range inside the header or a command.
pub type Field = Range<usize>;

/// The opcode byte of every command.
pub const OPCODE: usize = 0;

/// The 16-byte header.
pub mod header {
    use super::Field;
    /// `"SCVL"`.
    pub const MAGIC: Field = 0..4;
    /// `u16`: 1 (2D only) or 2.
    pub const VERSION: Field = 4..6;
    /// `u16` frame width, 1..=4096.
    pub const WIDTH: Field = 6..8;
    /// `u16` frame height, 1..=4096.
    pub const HEIGHT: Field = 8..10;
    /// `u16`, 0.
    pub const RESERVED: Field = 10..12;
    /// `u32`: bytes after the header.
    pub const BODY_LEN: Field = 12..16;
    /// Size of the header.
    pub const LEN: usize = 16;
}

/// `clear` and `color`: one colour.
pub mod rgb {
    /// Red.
    pub const R: usize = 1;
    /// Green.
    pub const G: usize = 2;
    /// Blue.
    pub const B: usize = 3;
    /// Size.
    pub const LEN: usize = 4;
}

/// `clip`: four `i16` whole pixels, inclusive.
pub mod clip {
    use super::Field;
    /// Leftmost column.
    pub const X0: Field = 1..3;
    /// Top row.
    pub const Y0: Field = 3..5;
    /// Rightmost column.
    pub const X1: Field = 5..7;
    /// Bottom row.
    pub const Y1: Field = 7..9;
    /// Size.
    pub const LEN: usize = 9;
}

/// `line`: two end points, `i16` Q12.4.
pub mod line {
    use super::Field;
    /// First end, x.
    pub const X0: Field = 1..3;
    /// First end, y.
    pub const Y0: Field = 3..5;
    /// Second end, x.
    pub const X1: Field = 5..7;
    /// Second end, y.
    pub const Y1: Field = 7..9;
    /// Size.
    pub const LEN: usize = 9;
}

/// `poly`: a count, then packed `(x, y)` vertices, `i16` Q12.4.
pub mod poly {
    use super::Field;
    /// `u16` vertex count.
    pub const COUNT: Field = 1..3;
    /// The first vertex.
    pub const VERTICES: usize = 3;
    /// Bytes per vertex.
    pub const STRIDE: usize = 4;
    /// Inside a vertex: x.
    pub const X: Field = 0..2;
    /// Inside a vertex: y.
    pub const Y: Field = 2..4;
    /// Fewest vertices.
    pub const LEAST: u16 = 3;
}

/// `poly3`: a count, then packed `(x, y, z)` vertices, `i16` Q12.4.
pub mod poly3 {
    use super::Field;
    /// `u16` vertex count.
    pub const COUNT: Field = 1..3;
    /// The first vertex.
    pub const VERTICES: usize = 3;
    /// Bytes per vertex.
    pub const STRIDE: usize = 6;
    /// Inside a vertex: x.
    pub const X: Field = 0..2;
    /// Inside a vertex: y.
    pub const Y: Field = 2..4;
    /// Inside a vertex: depth.
    pub const Z: Field = 4..6;
    /// Fewest vertices.
    pub const LEAST: u16 = 3;
}

/// `face`: a count, then packed `(x, y, z)` points, `i32` Q16.16.
pub mod face {
    use super::Field;
    /// `u16` vertex count.
    pub const COUNT: Field = 1..3;
    /// The first vertex.
    pub const VERTICES: usize = 3;
    /// Bytes per vertex.
    pub const STRIDE: usize = 12;
    /// Fewest vertices (one is a point, two a line).
    pub const LEAST: u16 = 1;
}

/// `f`: a count, then packed `u16` indices, 0-based, into the vertex
/// table of the segment (every index below the `v`s of the segment so
/// far, checked by the reader).
pub mod mesh_face {
    use super::Field;
    /// `u16` index count.
    pub const COUNT: Field = 1..3;
    /// The first index.
    pub const INDICES: usize = 3;
    /// Bytes per index.
    pub const STRIDE: usize = 2;
    /// Fewest indices (one is a point, two a line).
    pub const LEAST: u16 = 1;
}

/// A packed world point, `i32` Q16.16 each (inside `view`, `light`,
/// `translate`, `scale`, `face` and `label`).
pub mod point3 {
    use super::Field;
    /// x.
    pub const X: Field = 0..4;
    /// y.
    pub const Y: Field = 4..8;
    /// z.
    pub const Z: Field = 8..12;
    /// Size.
    pub const LEN: usize = 12;
}

/// `segment`: a `u16` id.
pub mod segment {
    use super::Field;
    /// The segment.
    pub const ID: Field = 1..3;
    /// Size.
    pub const LEN: usize = 3;
}

/// `highlight`: a segment, on or off, a colour (0 when off).
pub mod highlight {
    use super::Field;
    /// `u16` segment.
    pub const ID: Field = 1..3;
    /// `u8`: 1 on, 0 off.
    pub const ON: usize = 3;
    /// Red.
    pub const R: usize = 4;
    /// Green.
    pub const G: usize = 5;
    /// Blue.
    pub const B: usize = 6;
    /// Size.
    pub const LEN: usize = 7;
}

/// `place`: a segment, a translation, three angles (about x, y, z), a
/// scale.
pub mod place {
    use super::Field;
    /// `u16` segment.
    pub const ID: Field = 1..3;
    /// The translation, a point.
    pub const TRANSLATE: Field = 3..15;
    /// The angles about x, y and z, `u16` each.
    pub const ROTATE: Field = 15..21;
    /// The scale, a point.
    pub const SCALE: Field = 21..33;
    /// Size.
    pub const LEN: usize = 33;
}

/// `perspective`: an angle and two Q16.16 depths.
pub mod perspective {
    use super::Field;
    /// Horizontal field of view, `u16` angle.
    pub const FOV: Field = 1..3;
    /// Near plane.
    pub const NEAR: Field = 3..7;
    /// Far plane.
    pub const FAR: Field = 7..11;
    /// Size.
    pub const LEN: usize = 11;
}

/// `ortho`: three Q16.16 values.
pub mod ortho {
    use super::Field;
    /// Pixels per world unit.
    pub const SCALE: Field = 1..5;
    /// Near plane.
    pub const NEAR: Field = 5..9;
    /// Far plane.
    pub const FAR: Field = 9..13;
    /// Size.
    pub const LEN: usize = 13;
}

/// `view`: a point and two angles.
pub mod view {
    use super::Field;
    /// The eye, a packed point.
    pub const EYE: Field = 1..13;
    /// Yaw, `u16` angle.
    pub const YAW: Field = 13..15;
    /// Pitch, `u16` angle.
    pub const PITCH: Field = 15..17;
    /// Size.
    pub const LEN: usize = 17;
}

/// `light`: a direction and a share.
pub mod light {
    use super::Field;
    /// Toward the light, a packed point.
    pub const TOWARD: Field = 1..13;
    /// `u8` percent, ≤ 100.
    pub const PERCENT: usize = 13;
    /// Size.
    pub const LEN: usize = 14;
}

/// `thickness`: one `i16` Q12.4, ≥ 0.
pub mod thickness {
    use super::Field;
    /// The thickness.
    pub const T: Field = 1..3;
    /// Size.
    pub const LEN: usize = 3;
}

/// `fill`: one byte, the fill rule (0 even-odd, 1 non-zero).
pub mod fill {
    /// The rule.
    pub const RULE: usize = 1;
    /// Size.
    pub const LEN: usize = 2;
}

/// `push` and `pop`: the opcode alone.
pub mod bare {
    /// Size.
    pub const LEN: usize = 1;
}

/// `translate`, `scale` and `v`: one packed point.
pub mod point {
    use super::Field;
    /// The offset or the factors.
    pub const P: Field = 1..13;
    /// Size.
    pub const LEN: usize = 13;
}

/// `rotate`: an axis and an angle.
pub mod rotate {
    use super::Field;
    /// `u8` axis: 0 x, 1 y, 2 z.
    pub const AXIS: usize = 1;
    /// `u16` angle.
    pub const ANGLE: Field = 2..4;
    /// Size.
    pub const LEN: usize = 4;
}

/// `label`: a point, a length, then the text.
pub mod label {
    use super::Field;
    /// The anchor, a packed point.
    pub const AT: Field = 1..13;
    /// `u8` text length, ≥ 1.
    pub const TEXT_LEN: usize = 13;
    /// The first byte of the text.
    pub const TEXT: usize = 14;
}

/// What follows a command's fixed part.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Tail {
    /// Nothing: the command is `fixed` bytes.
    None,
    /// `count` (a `u16` at [`Layout::COUNT`]) items of `stride` bytes,
    /// `count ≥ least`.
    Packed {
        /// Bytes per item.
        stride: usize,
        /// Fewest items.
        least: u16,
    },
    /// As many bytes as the `u8` at `len_at`.
    Text {
        /// Where the length byte is.
        len_at: usize,
    },
}

/// A command's size rule: its fixed part and what follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Layout {
    /// Bytes of the fixed part, opcode included: what must be present
    /// before the tail's length can be read.
    pub fixed: usize,
    /// What follows.
    pub tail: Tail,
}

impl Layout {
    /// Where a packed command's `u16` count is (the same for every one).
    pub const COUNT: Field = 1..3;

    const fn fixed(fixed: usize) -> Self {
        Layout {
            fixed,
            tail: Tail::None,
        }
    }

    const fn packed(stride: usize, least: u16) -> Self {
        Layout {
            fixed: 3,
            tail: Tail::Packed { stride, least },
        }
    }

    /// The size of the command with `items` tail items (vertices, or
    /// bytes of text); `items` is ignored for a fixed-size command.
    pub const fn size(&self, items: usize) -> usize {
        match self.tail {
            Tail::None => self.fixed,
            Tail::Packed { stride, .. } => self.fixed + stride * items,
            Tail::Text { .. } => self.fixed + items,
        }
    }
}

impl Opcode {
    /// The command's layout: the table above.
    pub const fn layout(self) -> Layout {
        match self {
            Opcode::Clear | Opcode::Color => Layout::fixed(rgb::LEN),
            Opcode::Clip => Layout::fixed(clip::LEN),
            Opcode::Line => Layout::fixed(line::LEN),
            Opcode::Poly => Layout::packed(poly::STRIDE, poly::LEAST),
            Opcode::Poly3 => Layout::packed(poly3::STRIDE, poly3::LEAST),
            Opcode::Segment | Opcode::Hide | Opcode::Show => Layout::fixed(segment::LEN),
            Opcode::Highlight => Layout::fixed(highlight::LEN),
            Opcode::Place => Layout::fixed(place::LEN),
            Opcode::Perspective => Layout::fixed(perspective::LEN),
            Opcode::Ortho => Layout::fixed(ortho::LEN),
            Opcode::View => Layout::fixed(view::LEN),
            Opcode::Light => Layout::fixed(light::LEN),
            Opcode::Thickness => Layout::fixed(thickness::LEN),
            Opcode::Fill => Layout::fixed(fill::LEN),
            Opcode::Push | Opcode::Pop => Layout::fixed(bare::LEN),
            Opcode::Translate | Opcode::Scale | Opcode::MeshVertex => Layout::fixed(point::LEN),
            Opcode::Rotate => Layout::fixed(rotate::LEN),
            Opcode::Face => Layout::packed(face::STRIDE, face::LEAST),
            Opcode::MeshFace => Layout::packed(mesh_face::STRIDE, mesh_face::LEAST),
            Opcode::Label => Layout {
                fixed: label::TEXT,
                tail: Tail::Text {
                    len_at: label::TEXT_LEN,
                },
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every opcode, in code order.
    const ALL: [Opcode; 26] = [
        Opcode::Clear,
        Opcode::Clip,
        Opcode::Color,
        Opcode::Poly,
        Opcode::Poly3,
        Opcode::Line,
        Opcode::Segment,
        Opcode::Perspective,
        Opcode::Ortho,
        Opcode::View,
        Opcode::Light,
        Opcode::Thickness,
        Opcode::Push,
        Opcode::Pop,
        Opcode::Translate,
        Opcode::Rotate,
        Opcode::Scale,
        Opcode::Face,
        Opcode::Label,
        Opcode::MeshVertex,
        Opcode::MeshFace,
        Opcode::Fill,
        Opcode::Hide,
        Opcode::Show,
        Opcode::Highlight,
        Opcode::Place,
    ];

    #[test]
    fn every_byte_is_an_opcode_once() {
        let n = (0..=255u8).filter_map(Opcode::from_byte).count();
        assert_eq!(n, ALL.len());
        for op in ALL {
            assert_eq!(Opcode::from_byte(op as u8), Some(op));
            assert_eq!(Opcode::from_name(op.name()), Some(op));
        }
    }

    #[test]
    fn fields_tile_their_commands() {
        // Each command's fields are contiguous from byte 1 to its fixed size.
        let tiles: [(&[Field], usize); 10] = [
            (
                &[
                    highlight::ID,
                    highlight::ON..highlight::R,
                    highlight::R..highlight::G,
                    highlight::G..highlight::B,
                    highlight::B..highlight::LEN,
                ],
                highlight::LEN,
            ),
            (
                &[place::ID, place::TRANSLATE, place::ROTATE, place::SCALE],
                place::LEN,
            ),
            (&[clip::X0, clip::Y0, clip::X1, clip::Y1], clip::LEN),
            (&[line::X0, line::Y0, line::X1, line::Y1], line::LEN),
            (
                &[perspective::FOV, perspective::NEAR, perspective::FAR],
                perspective::LEN,
            ),
            (&[ortho::SCALE, ortho::NEAR, ortho::FAR], ortho::LEN),
            (&[view::EYE, view::YAW, view::PITCH], view::LEN),
            (&[light::TOWARD, light::PERCENT..light::LEN], light::LEN),
            (
                &[rotate::AXIS..rotate::ANGLE.start, rotate::ANGLE],
                rotate::LEN,
            ),
            (&[label::AT, label::TEXT_LEN..label::TEXT], label::TEXT),
        ];
        for (fields, len) in tiles.iter() {
            let mut at = 1;
            for f in fields.iter() {
                assert_eq!(f.start, at);
                at = f.end;
            }
            assert_eq!(at, *len);
        }
        let head = [
            header::MAGIC,
            header::VERSION,
            header::WIDTH,
            header::HEIGHT,
            header::RESERVED,
            header::BODY_LEN,
        ];
        assert_eq!(head[0].start, 0);
        for pair in head.windows(2) {
            assert_eq!(pair[0].end, pair[1].start);
        }
        assert_eq!(header::BODY_LEN.end, header::LEN);
        assert_eq!(point3::Z.end, point3::LEN);
        assert_eq!(view::EYE.len(), point3::LEN);
        assert_eq!(point::P.len(), point3::LEN);
        assert_eq!(face::STRIDE, point3::LEN);
        assert_eq!(poly::Y.end, poly::STRIDE);
        assert_eq!(poly3::Z.end, poly3::STRIDE);
        for c in [poly::COUNT, poly3::COUNT, face::COUNT, mesh_face::COUNT] {
            assert_eq!(c, Layout::COUNT);
        }
        for v in [
            poly::VERTICES,
            poly3::VERTICES,
            face::VERTICES,
            mesh_face::INDICES,
        ] {
            assert_eq!(v, Layout::COUNT.end);
        }
    }

    #[test]
    fn sizes_match_the_documented_table() {
        let size = |op: Opcode, n| op.layout().size(n);
        assert_eq!(size(Opcode::Clear, 0), 4);
        assert_eq!(size(Opcode::Clip, 0), 9);
        assert_eq!(size(Opcode::Line, 0), 9);
        assert_eq!(size(Opcode::Poly, 5), 3 + 4 * 5);
        assert_eq!(size(Opcode::Poly3, 5), 3 + 6 * 5);
        assert_eq!(size(Opcode::Segment, 0), 3);
        assert_eq!(size(Opcode::Perspective, 0), 11);
        assert_eq!(size(Opcode::Ortho, 0), 13);
        assert_eq!(size(Opcode::View, 0), 17);
        assert_eq!(size(Opcode::Light, 0), 14);
        assert_eq!(size(Opcode::Thickness, 0), 3);
        assert_eq!(size(Opcode::Push, 0), 1);
        assert_eq!(size(Opcode::Translate, 0), 13);
        assert_eq!(size(Opcode::Rotate, 0), 4);
        assert_eq!(size(Opcode::Face, 2), 3 + 12 * 2);
        assert_eq!(size(Opcode::Label, 7), 14 + 7);
        assert_eq!(size(Opcode::MeshVertex, 0), 13);
        assert_eq!(size(Opcode::MeshFace, 3), 3 + 2 * 3);
        assert_eq!(size(Opcode::Fill, 0), 2);
        assert_eq!(size(Opcode::Hide, 0), 3);
        assert_eq!(size(Opcode::Show, 0), 3);
        assert_eq!(size(Opcode::Highlight, 0), 7);
        assert_eq!(size(Opcode::Place, 0), 33);
    }
}
