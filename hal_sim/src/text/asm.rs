//! Text form → binary form.
//!
//! The file is read a line at a time, as bytes: words are separated by
//! spaces, tabs (and the `\r` of a CRLF line end), and a `#` starts a
//! comment, except as the first character of the colour operand of `clear`
//! and `color`, and inside a `label` text in double quotes. Bytes inside
//! a comment are never looked at, so a comment may hold any bytes; a word
//! that is used must be UTF-8.
//!
//! Each line becomes at most one command, checked completely before anything
//! is encoded; the binary list is then written with the firmware's own
//! [`Writer`], so the two forms cannot drift apart.

use super::number::{parse_angle, parse_coord, parse_int, parse_q16};
use super::{TextError, TextErrorKind};
use scanvert::display_list::{Axis, Opcode, Writer, HEADER_LEN, MAX_LABEL_LEN, MAX_VERTICES};
use scanvert::fixed::{Coord, Vertex, Vertex3};
use scanvert::geometry::{Angle, Point3, View, Q16};
use scanvert::pixelcolor::Rgb888;
use scanvert::raster::clip::ClipWindow;
use scanvert::raster::FillRule;
use scanvert::scene::Placement;

/// A text scene assembled into the binary form.
#[derive(Clone, Debug)]
pub struct Assembled {
    /// The binary display list (it passes `DisplayList::new_checked`).
    pub bytes: Vec<u8>,
    /// `(byte offset of a command, its line)`, by offset; the first entry is
    /// the header and the `frame` line.
    lines: Vec<(u32, u32)>,
}

impl Assembled {
    /// The line of the command at or around byte `offset` of
    /// [`bytes`](Self::bytes); `None` past the end.
    pub fn line_of(&self, offset: usize) -> Option<usize> {
        if offset >= self.bytes.len() {
            return None;
        }
        let i = self.lines.partition_point(|&(at, _)| at as usize <= offset);
        self.lines
            .get(i.checked_sub(1)?)
            .map(|&(_, line)| line as usize)
    }
}

/// One command, checked, before encoding.
enum Cmd {
    Clear(Rgb888),
    Clip(ClipWindow),
    Color(Rgb888),
    Poly(Vec<Vertex>),
    Poly3(Vec<Vertex3>),
    Line(Vertex, Vertex),
    Segment(u16),
    Perspective(Angle, Q16, Q16),
    Ortho(Q16, Q16, Q16),
    View(View),
    Light(Point3, u8),
    Thickness(Coord),
    Fill(FillRule),
    Push,
    Pop,
    Translate(Point3),
    Rotate(Axis, Angle),
    Scale(Point3),
    Face(Vec<Point3>),
    Label(Point3, String),
    MeshVertex(Point3),
    /// The indices as written, then 0-based once [`walk`] resolved them.
    MeshFace(Vec<i64>),
    Hide(u16),
    Show(u16),
    Highlight(u16, Option<Rgb888>),
    Place(u16, Placement),
}

impl Cmd {
    /// Its opcode.
    fn opcode(&self) -> Opcode {
        match self {
            Cmd::Clear(_) => Opcode::Clear,
            Cmd::Clip(_) => Opcode::Clip,
            Cmd::Color(_) => Opcode::Color,
            Cmd::Poly(_) => Opcode::Poly,
            Cmd::Poly3(_) => Opcode::Poly3,
            Cmd::Line(..) => Opcode::Line,
            Cmd::Segment(_) => Opcode::Segment,
            Cmd::Perspective(..) => Opcode::Perspective,
            Cmd::Ortho(..) => Opcode::Ortho,
            Cmd::View(_) => Opcode::View,
            Cmd::Light(..) => Opcode::Light,
            Cmd::Thickness(_) => Opcode::Thickness,
            Cmd::Fill(_) => Opcode::Fill,
            Cmd::Push => Opcode::Push,
            Cmd::Pop => Opcode::Pop,
            Cmd::Translate(_) => Opcode::Translate,
            Cmd::Rotate(..) => Opcode::Rotate,
            Cmd::Scale(_) => Opcode::Scale,
            Cmd::Face(_) => Opcode::Face,
            Cmd::Label(..) => Opcode::Label,
            Cmd::MeshVertex(_) => Opcode::MeshVertex,
            Cmd::MeshFace(_) => Opcode::MeshFace,
            Cmd::Hide(_) => Opcode::Hide,
            Cmd::Show(_) => Opcode::Show,
            Cmd::Highlight(..) => Opcode::Highlight,
            Cmd::Place(..) => Opcode::Place,
        }
    }

    /// Its size in the binary form, by the format's layout table
    /// (`scanvert::display_list::layout`).
    fn size(&self) -> usize {
        let items = match self {
            Cmd::Poly(v) => v.len(),
            Cmd::Poly3(v) => v.len(),
            Cmd::Face(v) => v.len(),
            Cmd::MeshFace(v) => v.len(),
            Cmd::Label(_, t) => t.len(),
            _ => 0,
        };
        self.opcode().layout().size(items)
    }

    fn write(&self, w: &mut Writer<'_>) -> Result<(), scanvert::display_list::WriteError> {
        match self {
            Cmd::Clear(c) => w.clear(*c),
            Cmd::Clip(c) => w.clip(*c),
            Cmd::Color(c) => w.color(*c),
            Cmd::Poly(v) => w.poly(v.iter().copied()),
            Cmd::Poly3(v) => w.poly3(v.iter().copied()),
            Cmd::Line(from, to) => w.line(*from, *to),
            Cmd::Segment(id) => w.segment(*id),
            Cmd::Perspective(fov, near, far) => w.perspective(*fov, *near, *far),
            Cmd::Ortho(scale, near, far) => w.ortho(*scale, *near, *far),
            Cmd::View(v) => w.view(v.eye, v.yaw, v.pitch),
            Cmd::Light(toward, percent) => w.light(*toward, *percent),
            Cmd::Thickness(t) => w.thickness(*t),
            Cmd::Fill(rule) => w.fill(*rule),
            Cmd::Push => w.push(),
            Cmd::Pop => w.pop(),
            Cmd::Translate(p) => w.translate(*p),
            Cmd::Rotate(axis, a) => w.rotate(*axis, *a),
            Cmd::Scale(p) => w.scale(*p),
            Cmd::Face(v) => w.face(v.iter().copied()),
            Cmd::Label(at, text) => w.label(*at, text),
            Cmd::MeshVertex(p) => w.mesh_vertex(*p),
            // Resolved by `walk`: 0 ≤ i < 65536.
            Cmd::MeshFace(v) => w.mesh_face(v.iter().map(|&i| i as u16)),
            Cmd::Hide(id) => w.hide(*id),
            Cmd::Show(id) => w.show(*id),
            Cmd::Highlight(id, c) => w.highlight(*id, *c),
            Cmd::Place(id, p) => w.place(*id, p),
        }
    }
}

/// Assembles a scene given as a string.
pub fn assemble(text: &str) -> Result<Assembled, TextError> {
    assemble_bytes(text.as_bytes())
}

/// The UTF-8 byte-order mark, which some editors put at the start of a
/// text file: skipped there.
const BOM: &[u8] = b"\xef\xbb\xbf";

/// Assembles a scene given as raw bytes (a file's contents, which need not
/// be UTF-8 outside the words that are read). A UTF-8 byte-order mark at
/// the very start is skipped.
///
/// The text is read twice: once to check it and size the list, then again
/// to write each command as it is parsed. No parsed command is kept, so
/// the memory is the text, the list, and 8 bytes of line table a command.
pub fn assemble_bytes(raw: &[u8]) -> Result<Assembled, TextError> {
    let raw = raw.strip_prefix(BOM).unwrap_or(raw);
    // First pass: every error, the frame, the version, and the size.
    let (mut size, mut count) = (HEADER_LEN, 0usize);
    let head = walk(raw, |_, cmd| {
        size += cmd.size();
        count += 1;
        Ok(())
    })?;
    let (width, height, frame_line) = head.frame;
    let mut bytes = vec![0u8; size];
    let mut lines = Vec::with_capacity(count + 1);
    lines.push((0, frame_line as u32));
    let mut w = Writer::new(&mut bytes, width, height).map_err(|e| internal(frame_line, e))?;
    if let Some((v, line)) = head.version {
        w.require_version(v).map_err(|e| internal(line, e))?;
    }
    // Second pass: the same commands, written as they are parsed.
    let mut at = HEADER_LEN;
    walk(raw, |line, cmd| {
        // Text of the program's input limit makes a list of a few hundred
        // MiB at most, and has fewer lines: both fit in `u32`.
        lines.push((at as u32, line as u32));
        at += cmd.size();
        cmd.write(&mut w).map_err(|e| internal(line, e))
    })?;
    let len = w.finish().len();
    debug_assert_eq!(len, size);
    Ok(Assembled { bytes, lines })
}

/// What the text says besides its commands: the `frame` (width, height,
/// line) and the `version` (version, line), if given.
struct Head {
    frame: (u16, u16, usize),
    version: Option<(u16, usize)>,
}

/// Parses every line of `raw` in order, handing each command with its line
/// to `each`; returns the frame and version, or the first error.
fn walk(
    raw: &[u8],
    mut each: impl FnMut(usize, Cmd) -> Result<(), TextError>,
) -> Result<Head, TextError> {
    let mut frame: Option<(u16, u16, usize)> = None;
    // `version N`: the header's version, at least (see the docs).
    let mut version: Option<(u16, usize)> = None;
    let mut last_line = 1;
    // `v`s in the current segment's table.
    let mut table = 0usize;
    for (k, line) in raw.split(|&b| b == b'\n').enumerate() {
        let number = k + 1;
        last_line = number;
        let err = |kind| TextError { line: number, kind };
        let words = words(line);
        let Some((&name, operands)) = words.split_first() else {
            continue;
        };
        let name = utf8(name).map_err(err)?;
        match (name, frame) {
            ("frame", None) => {
                let (w, h) = parse_frame(operands).map_err(err)?;
                frame = Some((w, h, number));
            }
            ("frame", Some(_)) => return Err(err(TextErrorKind::FrameAgain)),
            ("version", Some(_)) => {
                let v = match operands {
                    [b"1"] => 1,
                    [b"2"] => 2,
                    _ => {
                        return Err(err(TextErrorKind::Operands {
                            command: "version",
                            expected: "1 (1 or 2)",
                            got: operands.len(),
                        }))
                    }
                };
                version = Some((v, number));
            }
            (_, None) if is_command(name) => {
                return Err(err(TextErrorKind::FrameFirst(name.to_string())))
            }
            _ => {
                let mut cmd = parse_command(name, operands, line).map_err(err)?;
                match &mut cmd {
                    Cmd::Segment(_) => table = 0,
                    Cmd::MeshVertex(_) => table += 1,
                    Cmd::MeshFace(indices) => resolve(indices, table).map_err(err)?,
                    _ => {}
                }
                each(number, cmd)?
            }
        }
    }
    let Some(frame) = frame else {
        let line = if raw.is_empty() { 1 } else { last_line };
        return Err(TextError {
            line,
            kind: TextErrorKind::Empty,
        });
    };
    Ok(Head { frame, version })
}

/// An `f`'s indices as written (1-based, or negative from the last) to
/// 0-based ones into a table of `table` vertices.
fn resolve(indices: &mut [i64], table: usize) -> Result<(), TextErrorKind> {
    let n = table as i64;
    for i in indices.iter_mut() {
        let at = match *i {
            k if k > 0 && k <= n => k - 1,
            k if k < 0 && -k <= n => n + k,
            index => {
                return Err(TextErrorKind::Index {
                    index,
                    vertices: table,
                })
            }
        };
        if at > u16::MAX as i64 {
            return Err(TextErrorKind::IndexLimit(at as usize + 1));
        }
        *i = at;
    }
    Ok(())
}

/// A command the parser checked but the writer refused: cannot happen (the
/// buffer is sized exactly and every limit is checked first), and is a
/// reported error rather than a panic if it ever did.
fn internal(line: usize, e: scanvert::display_list::WriteError) -> TextError {
    TextError {
        line,
        kind: TextErrorKind::UnknownCommand(format!("(internal: {e})")),
    }
}

fn is_command(name: &str) -> bool {
    Opcode::from_name(name).is_some() || name == "lookat" || name == "version"
}

/// The words of a line, comments removed.
fn words(line: &[u8]) -> Vec<&[u8]> {
    let mut out: Vec<&[u8]> = Vec::new();
    let separators = |c: &u8| matches!(c, b' ' | b'\t' | b'\r');
    for word in line.split(separators).filter(|w| !w.is_empty()) {
        let colour_slot = (out.len() == 1
            && (out[0] == b"clear".as_slice() || out[0] == b"color".as_slice()))
            || (out.len() == 2 && out[0] == b"highlight".as_slice());
        let cut = if colour_slot && word[0] == b'#' {
            word[1..].iter().position(|&c| c == b'#').map(|p| p + 1)
        } else {
            word.iter().position(|&c| c == b'#')
        };
        match cut {
            Some(p) => {
                if p > 0 {
                    out.push(&word[..p]);
                }
                break;
            }
            None => out.push(word),
        }
    }
    out
}

fn utf8(word: &[u8]) -> Result<&str, TextErrorKind> {
    std::str::from_utf8(word).map_err(|_| TextErrorKind::NotUtf8)
}

/// A word as it may be quoted in a message: at most 40 characters.
fn quoted(word: &str) -> String {
    match word.char_indices().nth(40) {
        Some((i, _)) => format!("{}…", &word[..i]),
        None => word.to_string(),
    }
}

fn operand_count(
    command: &'static str,
    expected: &'static str,
    operands: &[&[u8]],
    ok: bool,
) -> Result<(), TextErrorKind> {
    if ok {
        Ok(())
    } else {
        Err(TextErrorKind::Operands {
            command,
            expected,
            got: operands.len(),
        })
    }
}

fn int(word: &[u8], lo: i64, hi: i64, range: &'static str) -> Result<i64, TextErrorKind> {
    let w = utf8(word)?;
    parse_int(w, lo, hi, range).map_err(|error| TextErrorKind::Number {
        word: quoted(w),
        error,
    })
}

fn coord(word: &[u8]) -> Result<scanvert::fixed::Coord, TextErrorKind> {
    let w = utf8(word)?;
    parse_coord(w).map_err(|error| TextErrorKind::Number {
        word: quoted(w),
        error,
    })
}

fn q16(word: &[u8]) -> Result<Q16, TextErrorKind> {
    let w = utf8(word)?;
    parse_q16(w).map_err(|error| TextErrorKind::Number {
        word: quoted(w),
        error,
    })
}

fn angle(word: &[u8]) -> Result<Angle, TextErrorKind> {
    let w = utf8(word)?;
    parse_angle(w).map_err(|error| TextErrorKind::Number {
        word: quoted(w),
        error,
    })
}

/// Three world values from `words[0..3]`.
fn point(words: &[&[u8]]) -> Result<Point3, TextErrorKind> {
    Ok(Point3::new(q16(words[0])?, q16(words[1])?, q16(words[2])?))
}

fn colour(word: &[u8]) -> Result<Rgb888, TextErrorKind> {
    let w = utf8(word)?;
    let bad = || TextErrorKind::Colour(quoted(w));
    let hex = w.strip_prefix('#').ok_or_else(bad)?;
    if hex.len() != 6 || !hex.bytes().all(|c| c.is_ascii_hexdigit()) {
        return Err(bad());
    }
    let v = u32::from_str_radix(hex, 16).map_err(|_| bad())?;
    Ok(Rgb888::new((v >> 16) as u8, (v >> 8) as u8, v as u8))
}

fn parse_frame(operands: &[&[u8]]) -> Result<(u16, u16), TextErrorKind> {
    operand_count("frame", "2 (W H)", operands, operands.len() == 2)?;
    let side = |w| int(w, 1, 4096, "1 … 4096").map(|v| v as u16);
    Ok((side(operands[0])?, side(operands[1])?))
}

/// The command `name` with its `operands`, all words of `line` (a label's
/// text is read from the line itself).
fn parse_command(name: &str, operands: &[&[u8]], line: &[u8]) -> Result<Cmd, TextErrorKind> {
    match name {
        "clear" | "color" => {
            let command = if name == "clear" { "clear" } else { "color" };
            operand_count(command, "1 (#rrggbb)", operands, operands.len() == 1)?;
            let c = colour(operands[0])?;
            Ok(if name == "clear" {
                Cmd::Clear(c)
            } else {
                Cmd::Color(c)
            })
        }
        "clip" => {
            operand_count("clip", "4 (X0 Y0 X1 Y1)", operands, operands.len() == 4)?;
            let mut v = [0i16; 4];
            for (slot, w) in v.iter_mut().zip(operands) {
                *slot = int(w, i16::MIN as i64, i16::MAX as i64, "-32768 … 32767")? as i16;
            }
            Ok(Cmd::Clip(ClipWindow {
                x0: v[0],
                y0: v[1],
                x1: v[2],
                y1: v[3],
            }))
        }
        "poly" => {
            let n = operands.len();
            operand_count(
                "poly",
                "an even number ≥ 6 (X Y …)",
                operands,
                n >= 6 && n.is_multiple_of(2),
            )?;
            vertex_limit(n / 2)?;
            let c = operands
                .iter()
                .map(|w| coord(w))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Cmd::Poly(
                c.chunks_exact(2)
                    .map(|p| Vertex { x: p[0], y: p[1] })
                    .collect(),
            ))
        }
        "poly3" => {
            let n = operands.len();
            operand_count(
                "poly3",
                "a multiple of 3, ≥ 9 (X Y Z …)",
                operands,
                n >= 9 && n.is_multiple_of(3),
            )?;
            vertex_limit(n / 3)?;
            let c = operands
                .iter()
                .map(|w| coord(w))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Cmd::Poly3(
                c.chunks_exact(3)
                    .map(|p| Vertex3 {
                        x: p[0],
                        y: p[1],
                        z: p[2],
                    })
                    .collect(),
            ))
        }
        "line" => {
            operand_count("line", "4 (X0 Y0 X1 Y1)", operands, operands.len() == 4)?;
            let c = operands
                .iter()
                .map(|w| coord(w))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Cmd::Line(
                Vertex { x: c[0], y: c[1] },
                Vertex { x: c[2], y: c[3] },
            ))
        }
        "segment" => {
            operand_count("segment", "1 (ID)", operands, operands.len() == 1)?;
            Ok(Cmd::Segment(int(operands[0], 0, 65535, "0 … 65535")? as u16))
        }
        "perspective" => {
            operand_count(
                "perspective",
                "3 (FOV NEAR FAR)",
                operands,
                operands.len() == 3,
            )?;
            Ok(Cmd::Perspective(
                angle(operands[0])?,
                q16(operands[1])?,
                q16(operands[2])?,
            ))
        }
        "ortho" => {
            operand_count("ortho", "3 (SCALE NEAR FAR)", operands, operands.len() == 3)?;
            Ok(Cmd::Ortho(
                q16(operands[0])?,
                q16(operands[1])?,
                q16(operands[2])?,
            ))
        }
        "view" => {
            operand_count("view", "5 (X Y Z YAW PITCH)", operands, operands.len() == 5)?;
            Ok(Cmd::View(View {
                eye: point(operands)?,
                yaw: angle(operands[3])?,
                pitch: angle(operands[4])?,
            }))
        }
        "lookat" => {
            operand_count(
                "lookat",
                "6 (X Y Z TX TY TZ)",
                operands,
                operands.len() == 6,
            )?;
            let (eye, target) = (point(operands)?, point(&operands[3..])?);
            Ok(Cmd::View(
                View::look_at(eye, target).map_err(|_| TextErrorKind::LookAt)?,
            ))
        }
        "light" => {
            operand_count(
                "light",
                "4 (DX DY DZ PERCENT)",
                operands,
                operands.len() == 4,
            )?;
            let percent = int(operands[3], 0, 100, "0 … 100")? as u8;
            Ok(Cmd::Light(point(operands)?, percent))
        }
        "thickness" => {
            operand_count("thickness", "1 (T)", operands, operands.len() == 1)?;
            let t = coord(operands[0])?;
            if t.to_bits() < 0 {
                let w = utf8(operands[0])?;
                return Err(TextErrorKind::Number {
                    word: quoted(w),
                    error: super::NumberError::Range("0 … 2047.9375"),
                });
            }
            Ok(Cmd::Thickness(t))
        }
        "fill" => {
            operand_count("fill", "1 (evenodd|nonzero)", operands, operands.len() == 1)?;
            let word = String::from_utf8_lossy(operands[0]);
            match FillRule::from_name(&word) {
                Some(rule) => Ok(Cmd::Fill(rule)),
                None => Err(TextErrorKind::FillRule(quoted(&word))),
            }
        }
        "push" | "pop" => {
            let command = if name == "push" { "push" } else { "pop" };
            operand_count(command, "no", operands, operands.is_empty())?;
            Ok(if name == "push" { Cmd::Push } else { Cmd::Pop })
        }
        "translate" | "scale" => {
            let command = if name == "translate" {
                "translate"
            } else {
                "scale"
            };
            operand_count(command, "3 (X Y Z)", operands, operands.len() == 3)?;
            let p = point(operands)?;
            Ok(if name == "translate" {
                Cmd::Translate(p)
            } else {
                Cmd::Scale(p)
            })
        }
        "rotate" => {
            operand_count("rotate", "2 (x|y|z DEGREES)", operands, operands.len() == 2)?;
            let axis = match operands[0] {
                b"x" => Axis::X,
                b"y" => Axis::Y,
                b"z" => Axis::Z,
                other => return Err(TextErrorKind::Axis(quoted(&String::from_utf8_lossy(other)))),
            };
            Ok(Cmd::Rotate(axis, angle(operands[1])?))
        }
        "face" => {
            let n = operands.len();
            operand_count(
                "face",
                "a multiple of 3, ≥ 3 (X Y Z …)",
                operands,
                n >= 3 && n.is_multiple_of(3),
            )?;
            vertex_limit(n / 3)?;
            let points = operands
                .chunks_exact(3)
                .map(point)
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Cmd::Face(points))
        }
        "v" => {
            operand_count("v", "3 (X Y Z)", operands, operands.len() == 3)?;
            Ok(Cmd::MeshVertex(point(operands)?))
        }
        "f" => {
            operand_count("f", "≥ 1 (I J K …)", operands, !operands.is_empty())?;
            vertex_limit(operands.len())?;
            let indices = operands
                .iter()
                .map(|w| int(w, -(u32::MAX as i64), u32::MAX as i64, "an index"))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Cmd::MeshFace(indices))
        }
        "hide" | "show" => {
            let command = if name == "hide" { "hide" } else { "show" };
            operand_count(command, "1 (ID)", operands, operands.len() == 1)?;
            let id = int(operands[0], 0, 65535, "0 … 65535")? as u16;
            Ok(if name == "hide" {
                Cmd::Hide(id)
            } else {
                Cmd::Show(id)
            })
        }
        "highlight" => {
            operand_count(
                "highlight",
                "2 (ID #rrggbb|off)",
                operands,
                operands.len() == 2,
            )?;
            let id = int(operands[0], 0, 65535, "0 … 65535")? as u16;
            let c = match operands[1] {
                b"off" => None,
                w => Some(colour(w)?),
            };
            Ok(Cmd::Highlight(id, c))
        }
        "place" => {
            operand_count(
                "place",
                "4, 7 or 10 (ID X Y Z [AX AY AZ [SX SY SZ]])",
                operands,
                matches!(operands.len(), 4 | 7 | 10),
            )?;
            let id = int(operands[0], 0, 65535, "0 … 65535")? as u16;
            let mut p = Placement {
                translate: point(&operands[1..])?,
                ..Placement::IDENTITY
            };
            if operands.len() >= 7 {
                for (slot, w) in p.rotate.iter_mut().zip(&operands[4..7]) {
                    *slot = angle(w)?;
                }
            }
            if operands.len() == 10 {
                p.scale = point(&operands[7..])?;
            }
            Ok(Cmd::Place(id, p))
        }
        "label" => {
            operand_count("label", "X Y Z and a text", operands, operands.len() >= 4)?;
            let text = label_text(line, operands)?;
            Ok(Cmd::Label(point(operands)?, text))
        }
        other => Err(TextErrorKind::UnknownCommand(quoted(other))),
    }
}

/// Where `word`, a sub-slice of `line`, starts in it.
fn offset_in(line: &[u8], word: &[u8]) -> usize {
    word.as_ptr() as usize - line.as_ptr() as usize
}

/// The text of a `label` whose operands (X Y Z, then the text's words) are
/// `operands`, words of `line`.
///
/// The text is *quoted* when, from its first byte to the end of the line,
/// it is one string in double quotes (see [`parse_quoted`]) followed by
/// nothing but blanks and a comment. Otherwise it is *bare*, read as it
/// always was: its words joined by single spaces, up to a `#`.
fn label_text(line: &[u8], operands: &[&[u8]]) -> Result<String, TextErrorKind> {
    let rest = &line[offset_in(line, operands[3])..];
    let bytes = match parse_quoted(rest) {
        Some(bytes) => bytes,
        None => {
            let words = operands[3..]
                .iter()
                .map(|w| utf8(w))
                .collect::<Result<Vec<_>, _>>()?;
            words.join(" ").into_bytes()
        }
    };
    let ok = (1..=MAX_LABEL_LEN).contains(&bytes.len())
        && bytes.iter().all(|c| (0x20..0x7f).contains(c));
    match String::from_utf8(bytes) {
        Ok(text) if ok => Ok(text),
        _ => Err(TextErrorKind::Label),
    }
}

/// A string in double quotes at the start of `rest`, decoded, when `rest`
/// is exactly that and then blanks or a comment: between the quotes every
/// byte is printable ASCII, `\"` stands for `"`, `\\` for `\` and `\xNN`
/// (two hex digits) for the byte `NN`; a `#` inside is text. `None` for
/// anything else, which is then read as bare words.
fn parse_quoted(rest: &[u8]) -> Option<Vec<u8>> {
    let mut bytes = rest.strip_prefix(b"\"")?.iter();
    let mut out = Vec::new();
    loop {
        match *bytes.next()? {
            b'"' => break,
            b'\\' => match *bytes.next()? {
                c @ (b'"' | b'\\') => out.push(c),
                b'x' => {
                    let hex = [*bytes.next()?, *bytes.next()?];
                    let hex = std::str::from_utf8(&hex).ok()?;
                    if !hex.bytes().all(|c| c.is_ascii_hexdigit()) {
                        return None;
                    }
                    out.push(u8::from_str_radix(hex, 16).ok()?);
                }
                _ => return None,
            },
            c @ 0x20..=0x7e => out.push(c),
            _ => return None,
        }
    }
    let tail = bytes.as_slice();
    let end = tail.iter().position(|&c| c == b'#').unwrap_or(tail.len());
    tail[..end]
        .iter()
        .all(|c| matches!(c, b' ' | b'\t' | b'\r'))
        .then_some(out)
}

/// `text` in double quotes, escaped as [`parse_quoted`] reads it.
fn quote(text: &[u8]) -> String {
    let mut s = String::from("\"");
    for &c in text {
        match c {
            b'"' => s.push_str("\\\""),
            b'\\' => s.push_str("\\\\"),
            0x20..=0x7e => s.push(c as char),
            _ => s.push_str(&format!("\\x{c:02x}")),
        }
    }
    s.push('"');
    s
}

/// A label's text as the text form writes it: bare when the bare form
/// reads back as `text`, quoted otherwise (a `#`, spaces at either end or
/// doubled, a text of blanks, or a text that is itself a quoted string).
pub(super) fn label_text_form(text: &str) -> String {
    let line = format!("label 0 0 0 {text}");
    let words = words(line.as_bytes());
    if words.len() >= 5 && label_text(line.as_bytes(), &words[1..]).as_deref() == Ok(text) {
        text.to_string()
    } else {
        quote(text.as_bytes())
    }
}

fn vertex_limit(n: usize) -> Result<(), TextErrorKind> {
    if n > MAX_VERTICES {
        Err(TextErrorKind::TooManyVertices(n))
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scanvert::display_list::{Command, DisplayList};

    fn err(text: &str) -> TextError {
        assemble(text).unwrap_err()
    }

    #[test]
    fn comments_and_colours() {
        let a = assemble(
            "# head\n\tframe 4 4 # size\r\nclear #102030 # bg\ncolor #ff0000#red\npoly 0 0 4 0 4#x\n 4\n",
        );
        // `poly 0 0 4 0 4#x` has five numbers: the `#` cut the line.
        assert_eq!(a.unwrap_err().line, 5);
        let a = assemble("frame 4 4\ncolor #ff0000#red\nclear #000000 #ffffff\n").unwrap();
        let list = DisplayList::new_checked(&a.bytes).unwrap();
        let cmds: Vec<_> = list.commands().map(|(_, c)| c).collect();
        assert!(matches!(cmds[0], Command::Color(c) if c == Rgb888::new(255, 0, 0)));
        assert!(matches!(cmds[1], Command::Clear(c) if c == Rgb888::new(0, 0, 0)));
    }

    #[test]
    fn faults_name_their_line() {
        assert_eq!(err("").line, 1);
        assert_eq!(err("# x\n\n").kind, TextErrorKind::Empty);
        assert_eq!(err("color #000000\n").line, 1);
        assert_eq!(err("\n\nframe 1 1\nframe 2 2\n").line, 4);
        assert_eq!(err("frame 1 1\nclear #00000\n").line, 2);
        assert_eq!(err("frame 1 1\nclear #000000 7\n").line, 2);
        assert_eq!(err("frame 1 1\nbogus\n").line, 2);
        assert_eq!(err("frame 1 1\n\npoly 0 0 1 1 2\n").line, 3);
        assert_eq!(err("frame 1 1\npoly3 0 0 0 1 1 1\n").line, 2);
        assert_eq!(err("frame 1 1\nclip 0 0 32768 1\n").line, 2);
        assert!(assemble("frame 1 1\nclip -32768 0 32767 1\n").is_ok());
    }

    #[test]
    fn line_table() {
        let a =
            assemble("frame 9 9\n\ncolor #000000\n# c\npoly 0 0 1 0 1 1\nclear #ffffff\n").unwrap();
        assert_eq!(a.line_of(0), Some(1));
        assert_eq!(a.line_of(16), Some(3));
        assert_eq!(a.line_of(20), Some(5));
        assert_eq!(a.line_of(31), Some(5));
        assert_eq!(a.line_of(35), Some(6));
        assert_eq!(a.line_of(39), None);
    }
}
