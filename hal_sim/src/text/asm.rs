//! Text form → binary form.
//!
//! The file is read a line at a time, as bytes: words are separated by
//! spaces, tabs (and the `\r` of a CRLF line end), and a `#` starts a
//! comment, except as the first character of the colour operand of `clear`
//! and `color`. Bytes inside a comment are never looked at, so a comment may
//! hold any bytes; a word that is used must be UTF-8.
//!
//! Each line becomes at most one command, checked completely before anything
//! is encoded; the binary list is then written with the firmware's own
//! [`Writer`], so the two forms cannot drift apart.

use super::number::{parse_coord, parse_int};
use super::{TextError, TextErrorKind};
use scanvert::clip::ClipWindow;
use scanvert::display_list::{Writer, HEADER_LEN, MAX_VERTICES};
use scanvert::fixed::{Vertex, Vertex3};
use scanvert::pixelcolor::Rgb888;

/// A text scene assembled into the binary form.
#[derive(Clone, Debug)]
pub struct Assembled {
    /// The binary display list (it passes `DisplayList::new_checked`).
    pub bytes: Vec<u8>,
    /// `(byte offset of a command, its line)`, by offset; the first entry is
    /// the header and the `frame` line.
    lines: Vec<(usize, usize)>,
}

impl Assembled {
    /// The line of the command at or around byte `offset` of
    /// [`bytes`](Self::bytes); `None` past the end.
    pub fn line_of(&self, offset: usize) -> Option<usize> {
        if offset >= self.bytes.len() {
            return None;
        }
        let i = self.lines.partition_point(|&(at, _)| at <= offset);
        self.lines.get(i.checked_sub(1)?).map(|&(_, line)| line)
    }
}

/// One command, checked, before encoding.
enum Cmd {
    Clear(Rgb888),
    Clip(ClipWindow),
    Color(Rgb888),
    Poly(Vec<Vertex>),
    Poly3(Vec<Vertex3>),
}

impl Cmd {
    /// Its size in the binary form.
    fn size(&self) -> usize {
        match self {
            Cmd::Clear(_) | Cmd::Color(_) => 4,
            Cmd::Clip(_) => 9,
            Cmd::Poly(v) => 3 + 4 * v.len(),
            Cmd::Poly3(v) => 3 + 6 * v.len(),
        }
    }
}

/// Assembles a scene given as a string.
pub fn assemble(text: &str) -> Result<Assembled, TextError> {
    assemble_bytes(text.as_bytes())
}

/// Assembles a scene given as raw bytes (a file's contents, which need not
/// be UTF-8 outside the words that are read).
pub fn assemble_bytes(raw: &[u8]) -> Result<Assembled, TextError> {
    let mut frame: Option<(u16, u16, usize)> = None;
    let mut cmds: Vec<(usize, Cmd)> = Vec::new();
    let mut last_line = 1;
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
            (_, None) if is_command(name) => {
                return Err(err(TextErrorKind::FrameFirst(name.to_string())))
            }
            _ => cmds.push((number, parse_command(name, operands).map_err(err)?)),
        }
    }
    let Some((width, height, frame_line)) = frame else {
        let line = if raw.is_empty() { 1 } else { last_line };
        return Err(TextError {
            line,
            kind: TextErrorKind::Empty,
        });
    };
    let size = HEADER_LEN + cmds.iter().map(|(_, c)| c.size()).sum::<usize>();
    let mut bytes = vec![0u8; size];
    let mut lines = Vec::with_capacity(cmds.len() + 1);
    lines.push((0, frame_line));
    let mut w = Writer::new(&mut bytes, width, height).map_err(|e| internal(frame_line, e))?;
    let mut at = HEADER_LEN;
    for (line, cmd) in &cmds {
        lines.push((at, *line));
        at += cmd.size();
        match cmd {
            Cmd::Clear(c) => w.clear(*c),
            Cmd::Clip(c) => w.clip(*c),
            Cmd::Color(c) => w.color(*c),
            Cmd::Poly(v) => w.poly(v.iter().copied()),
            Cmd::Poly3(v) => w.poly3(v.iter().copied()),
        }
        .map_err(|e| internal(*line, e))?;
    }
    let len = w.finish().len();
    debug_assert_eq!(len, size);
    Ok(Assembled { bytes, lines })
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
    matches!(name, "clear" | "clip" | "color" | "poly" | "poly3")
}

/// The words of a line, comments removed.
fn words(line: &[u8]) -> Vec<&[u8]> {
    let mut out: Vec<&[u8]> = Vec::new();
    let separators = |c: &u8| matches!(c, b' ' | b'\t' | b'\r');
    for word in line.split(separators).filter(|w| !w.is_empty()) {
        let colour_slot =
            out.len() == 1 && (out[0] == b"clear".as_slice() || out[0] == b"color".as_slice());
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

fn parse_command(name: &str, operands: &[&[u8]]) -> Result<Cmd, TextErrorKind> {
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
                n >= 6 && n % 2 == 0,
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
                n >= 9 && n % 3 == 0,
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
        other => Err(TextErrorKind::UnknownCommand(quoted(other))),
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
