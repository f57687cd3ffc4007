//! The text form of the display list (host only).
//!
//! The text form is a contract that outside scenes and tools are written
//! against; `docs/display-list.md` states it in full, with the decisions
//! it leaves open. [`assemble`] turns text into the binary form the firmware reads,
//! keeping a line table so that a fault found later in the binary (by the
//! controller, at a byte offset) can still be reported by its line;
//! [`disassemble`] turns a checked binary list back into text.
//!
//! Text → binary → text → binary is stable: the disassembler writes each
//! value as the shortest decimal that the assembler reads back as the same
//! bits, as Rust prints a float (`perspective 50` stores 49.998779296875°
//! and is written `50`), so the second assembly gives the same bytes.
//!
//! ```
//! use scanvert_sim::text;
//! let asm = text::assemble("frame 8 4\ncolor #ff0000\npoly 0 0 8 0 4 3.5\n").unwrap();
//! let list = scanvert::display_list::DisplayList::new_checked(&asm.bytes).unwrap();
//! assert_eq!(text::disassemble(&list), "frame 8 4\ncolor #ff0000\npoly 0 0 8 0 4 3.5\n");
//! assert_eq!(asm.line_of(list.commands().nth(1).unwrap().0), Some(3));
//! ```

mod asm;
mod disasm;
mod number;

pub use asm::{assemble, assemble_bytes, Assembled};
pub use disasm::{
    disassemble, format_angle, format_coord, format_fixed, format_q16, format_shortest,
};
pub use number::{parse_angle, parse_coord, parse_fixed, parse_int, parse_q16, NumberError};

use std::fmt;

/// `s` as it may be shown on a terminal: every character that is not
/// printable (C0 and C1 controls, DEL, format characters such as the bidi
/// overrides, line separators, unassigned code points) is written as its
/// Rust escape (`\u{1b}`, `\t`), and a backslash as `\\`, so that input
/// quoted in a message can neither drive the terminal (title, colours,
/// cursor) nor pass for other text. Every message that quotes input (a
/// word, a file name, an option) goes through this.
///
/// ```
/// use scanvert_sim::text::escape_for_terminal;
/// assert_eq!(escape_for_terminal("\u{1b}]0;pwned\u{7}"), "\\u{1b}]0;pwned\\u{7}");
/// assert_eq!(escape_for_terminal("café \"x\""), "café \"x\"");
/// ```
pub fn escape_for_terminal(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            ' ' | '"' | '\'' => out.push(c),
            c => out.extend(c.escape_debug()),
        }
    }
    out
}

/// What is wrong with a line of the text form.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TextErrorKind {
    /// The file holds no command at all.
    Empty,
    /// The first command is not `frame`.
    FrameFirst(String),
    /// A second `frame` command.
    FrameAgain,
    /// A command word that is not a command.
    UnknownCommand(String),
    /// The line is not valid UTF-8.
    NotUtf8,
    /// A command has the wrong number of operands.
    Operands {
        /// The command.
        command: &'static str,
        /// What it takes.
        expected: &'static str,
        /// How many it got.
        got: usize,
    },
    /// An operand that is not a number, or out of range.
    Number {
        /// The operand as written (cut to a readable length).
        word: String,
        /// Why it was refused.
        error: NumberError,
    },
    /// An operand that is not a `#rrggbb` colour.
    Colour(String),
    /// A polygon with too many vertices for the binary form.
    TooManyVertices(usize),
    /// A label that is too long or holds a character other than printable
    /// ASCII.
    Label,
    /// `lookat` with the eye on the target.
    LookAt,
    /// A rotation axis other than `x`, `y` or `z`.
    Axis(String),
    /// A fill rule other than `evenodd` or `nonzero`.
    FillRule(String),
    /// An `f` index that names no vertex of the segment's table: 0, past
    /// its end, or before its start.
    Index {
        /// The index as written.
        index: i64,
        /// Vertices in the table at the `f` (since the start or the last
        /// `segment`).
        vertices: usize,
    },
    /// An `f` index past the binary form's reach: the 65,536th `v` of a
    /// segment or later.
    IndexLimit(usize),
}

/// A fault in the text form, with its 1-based line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub kind: TextErrorKind,
}

impl fmt::Display for TextErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TextErrorKind::Empty => f.write_str("no command: a scene starts with `frame W H`"),
            TextErrorKind::FrameFirst(c) => {
                let c = escape_for_terminal(c);
                write!(f, "`{c}` before `frame`: a scene starts with `frame W H`")
            }
            TextErrorKind::FrameAgain => f.write_str("a second `frame` command"),
            TextErrorKind::UnknownCommand(c) => {
                write!(f, "unknown command `{}`", escape_for_terminal(c))
            }
            TextErrorKind::NotUtf8 => f.write_str("the line is not valid UTF-8"),
            TextErrorKind::Operands {
                command,
                expected,
                got,
            } => write!(f, "`{command}` takes {expected}, not {got} operands"),
            TextErrorKind::Number { word, error } => {
                write!(f, "`{}`: {error}", escape_for_terminal(word))
            }
            TextErrorKind::Colour(w) => {
                write!(f, "`{}` is not a colour `#rrggbb`", escape_for_terminal(w))
            }
            TextErrorKind::Label => write!(
                f,
                "a label is 1 to {} characters of printable ASCII",
                scanvert::display_list::MAX_LABEL_LEN
            ),
            TextErrorKind::LookAt => f.write_str("`lookat`: the eye is on the target"),
            TextErrorKind::Index { index, vertices: 0 } => write!(
                f,
                "`f`: index {index} names no vertex: the segment has no `v` before this line"
            ),
            TextErrorKind::Index { index, vertices } => write!(
                f,
                "`f`: index {index} names no vertex of the segment's table, which holds {vertices} (indices 1 … {vertices}, or −1 … −{vertices} from the last)"
            ),
            TextErrorKind::IndexLimit(i) => write!(
                f,
                "`f`: vertex {i} of a segment is past the binary form's 65,536 a segment"
            ),
            TextErrorKind::Axis(a) => {
                write!(f, "`{}` is not an axis (x, y or z)", escape_for_terminal(a))
            }
            TextErrorKind::FillRule(r) => write!(
                f,
                "`{}` is not a fill rule (evenodd or nonzero)",
                escape_for_terminal(r)
            ),
            TextErrorKind::TooManyVertices(n) => write!(
                f,
                "polygon has {n} vertices; a display list holds at most {}",
                scanvert::display_list::MAX_VERTICES
            ),
        }
    }
}

impl fmt::Display for TextError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.kind)
    }
}

impl std::error::Error for TextError {}
