//! A row of colour runs as the token stream of the Raspberry Pi Pico's
//! composable scan-line program (`pico_scanvideo`, in `pico-extras`).
//!
//! `pico_scanvideo` drives a VGA (DPI) signal from a PIO state machine
//! with no frame buffer: before the beam reaches a line, the program hands
//! it a buffer of 32-bit words that the state machine reads by DMA. Its
//! default scan-line program (`video_24mhz_composable_default`) reads the
//! words as 16-bit tokens, the low half-word of each word first. A token
//! is the address of a routine of the program (where it jumps), followed
//! by its operands:
//!
//! | token | operands | pixels |
//! |---|---|---|
//! | `COLOR_RUN` | colour, `n − 3` | `n ≥ 3` of one colour |
//! | `RAW_RUN` | colour 1, `n − 3`, colours 2 to `n` | `n ≥ 3`, each its own colour (the first colour comes before the count) |
//! | `RAW_1P` | colour | 1 |
//! | `RAW_2P` | colour 1, colour 2 | 2 |
//! | `RAW_1P_SKIP_ALIGN` | colour, one ignored token; the token itself in a high half-word | 1 |
//! | `END_OF_SCANLINE_ALIGN` | none; in a high half-word, so after an odd number of tokens | end |
//! | `END_OF_SCANLINE_SKIP_ALIGN` | one ignored token; in a low half-word, so after an even number | end |
//!
//! The state machine consumes whole words, so a line's stream is an even
//! number of tokens: the two end tokens make any line so. The pins keep
//! the last colour output, which would go on into the blanking: a line
//! must end with a black pixel. Colours are 16 bits as they go to the
//! pins (by the program's convention 5:5:5 RGB; the caller maps its
//! colours, [`rgb565`] passes RGB565 through).
//!
//! The token values are the routines' addresses in the program, loaded at
//! offset 0 (`.origin 0`): [`Opcodes::DEFAULT`] are those of
//! `video_24mhz_composable_default` as listed in `scanvideo.pio`. A
//! program of one's own (or the `raw1p_2cycle` variant) gives its own
//! [`Opcodes`].
//!
//! [`encode`] writes a row's runs (lengths and colours) as: a run of 3
//! pixels or more as `COLOR_RUN`; runs of 1 or 2 pixels next to each
//! other as one `RAW_1P`, `RAW_2P` or `RAW_RUN` of their pixels; then, if
//! the row's last pixel is not black, one black `RAW_1P` after it (the
//! first pixel of the blanking); then the end token that makes the count
//! even. A row of `r` runs and `p` pixels in short runs takes at most
//! `3r + p + 4` tokens. [`decode`] reads a stream back into pixels,
//! checking every rule above.

use core::fmt;
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::Rgb565;

/// The token values (routine addresses) of a composable scan-line
/// program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Opcodes {
    /// `COLOR_RUN`.
    pub color_run: u16,
    /// `RAW_RUN`.
    pub raw_run: u16,
    /// `RAW_1P`.
    pub raw_1p: u16,
    /// `RAW_2P`.
    pub raw_2p: u16,
    /// `RAW_1P_SKIP_ALIGN` (decoded, never written by [`encode`]).
    pub raw_1p_skip_align: u16,
    /// `END_OF_SCANLINE_ALIGN`.
    pub end_of_line_align: u16,
    /// `END_OF_SCANLINE_SKIP_ALIGN`.
    pub end_of_line_skip_align: u16,
}

impl Opcodes {
    /// `video_24mhz_composable_default` loaded at offset 0: each token is
    /// the index of its routine's first instruction in the program.
    pub const DEFAULT: Opcodes = Opcodes {
        end_of_line_skip_align: 0,
        end_of_line_align: 1,
        color_run: 3,
        raw_run: 7,
        raw_1p: 11,
        raw_2p: 13,
        raw_1p_skip_align: 14,
    };
}

/// The 16 bits of an RGB565 colour, as pins wired for RGB565 take them.
pub fn rgb565(c: Rgb565) -> u16 {
    RawU16::from(c).into_inner()
}

/// Why a row could not be encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EncodeError {
    /// The words lent hold fewer than the row's tokens.
    Full {
        /// Words the row needs.
        needed: usize,
        /// Words lent.
        capacity: usize,
    },
    /// A run of no pixel, at this index of the runs.
    Empty {
        /// Index of the run.
        run: usize,
    },
}

impl fmt::Display for EncodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EncodeError::Full { needed, capacity } => write!(
                f,
                "the row needs {needed} words of tokens; {capacity} were lent"
            ),
            EncodeError::Empty { run } => write!(f, "run {run} holds no pixel"),
        }
    }
}

impl core::error::Error for EncodeError {}

/// Tokens into words, low half first; writes past the words are counted,
/// not made.
struct Writer<'w> {
    words: &'w mut [u32],
    at: usize,
}

impl Writer<'_> {
    fn set(&mut self, t: usize, v: u16) {
        if let Some(w) = self.words.get_mut(t / 2) {
            let shift = 16 * (t % 2);
            *w = (*w & !(0xffff << shift)) | (u32::from(v) << shift);
        }
    }
    fn put(&mut self, v: u16) {
        self.set(self.at, v);
        self.at += 1;
    }
}

/// Short runs next to each other, gathered into one raw token.
#[derive(Clone, Copy)]
struct Raw {
    start: usize,
    n: usize,
    first: [u16; 2],
}

/// Encodes a row given as runs `(length, colour)` left to right (colours
/// as they go to the pins, black 0) into `out` as tokens of the program
/// of `op` (see the [module](self) docs); returns the words written.
/// Nothing but `out` is written; on an error its content is unspecified.
pub fn encode<I>(runs: I, op: &Opcodes, out: &mut [u32]) -> Result<usize, EncodeError>
where
    I: IntoIterator<Item = (u16, u16)>,
{
    let mut w = Writer { words: out, at: 0 };
    let mut raw: Option<Raw> = None;
    let mut last = 0u16;
    let mut pixels = 0usize;
    for (i, (len, color)) in runs.into_iter().enumerate() {
        if len == 0 {
            return Err(EncodeError::Empty { run: i });
        }
        pixels += usize::from(len);
        last = color;
        if len >= 3 {
            flush(&mut w, raw.take(), op);
            w.put(op.color_run);
            w.put(color);
            w.put(len - 3);
            continue;
        }
        let r = raw.get_or_insert(Raw {
            start: w.at,
            n: 0,
            first: [0; 2],
        });
        for _ in 0..len {
            match r.n {
                0 | 1 => r.first[r.n] = color,
                2 => {
                    // A third pixel: a `RAW_RUN`, its count set at the end.
                    w.at = r.start;
                    w.put(op.raw_run);
                    w.put(r.first[0]);
                    w.put(0);
                    w.put(r.first[1]);
                    w.put(color);
                }
                _ => w.put(color),
            }
            r.n += 1;
        }
    }
    flush(&mut w, raw.take(), op);
    if pixels > 0 && last != 0 {
        w.put(op.raw_1p);
        w.put(0);
    }
    if w.at % 2 == 1 {
        w.put(op.end_of_line_align);
    } else {
        w.put(op.end_of_line_skip_align);
        w.put(0);
    }
    let needed = w.at / 2;
    if needed > w.words.len() {
        return Err(EncodeError::Full {
            needed,
            capacity: w.words.len(),
        });
    }
    Ok(needed)
}

/// Ends a group of short runs: one or two pixels as `RAW_1P` or `RAW_2P`,
/// more as the `RAW_RUN` already written, with its count.
fn flush(w: &mut Writer<'_>, raw: Option<Raw>, op: &Opcodes) {
    let Some(r) = raw else { return };
    match r.n {
        0 => {}
        1 => {
            w.at = r.start;
            w.put(op.raw_1p);
            w.put(r.first[0]);
        }
        2 => {
            w.at = r.start;
            w.put(op.raw_2p);
            w.put(r.first[0]);
            w.put(r.first[1]);
        }
        n => w.set(r.start + 2, (n - 3) as u16),
    }
}

/// Why a token stream is not a line of the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DecodeError {
    /// Token `at` is none of the program's routines.
    Unknown {
        /// Index of the token.
        at: usize,
    },
    /// The stream ends inside the token at `at`, or with no end token.
    Truncated {
        /// Index of the token.
        at: usize,
    },
    /// The token at `at` is in the wrong half of its word.
    Misaligned {
        /// Index of the token.
        at: usize,
    },
    /// The line's pixels go past the `len` pixels lent, at token `at`.
    TooLong {
        /// Index of the token.
        at: usize,
        /// Pixels lent.
        len: usize,
    },
    /// The line's last pixel is not black.
    NotBlack,
    /// Words follow the end of the line.
    Trailing {
        /// Words of the line.
        words: usize,
    },
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DecodeError::Unknown { at } => write!(f, "token {at} is no routine of the program"),
            DecodeError::Truncated { at } => write!(f, "the stream ends inside token {at}"),
            DecodeError::Misaligned { at } => {
                write!(f, "token {at} is in the wrong half of its word")
            }
            DecodeError::TooLong { at, len } => {
                write!(f, "token {at} goes past the {len} pixels of the line")
            }
            DecodeError::NotBlack => f.write_str("the line does not end with a black pixel"),
            DecodeError::Trailing { words } => {
                write!(f, "words follow the end of the line after {words}")
            }
        }
    }
}

impl core::error::Error for DecodeError {}

/// Decodes one line of tokens (`words`, exactly the line's) as the
/// program of `op` would show it into `out`; returns the pixels shown,
/// including the black one a line ends with. Every rule of the
/// [module](self) docs is checked.
pub fn decode(words: &[u32], op: &Opcodes, out: &mut [u16]) -> Result<usize, DecodeError> {
    let token = |t: usize| -> Result<u16, DecodeError> {
        words
            .get(t / 2)
            .map(|w| (w >> (16 * (t % 2))) as u16)
            .ok_or(DecodeError::Truncated { at: t })
    };
    let (mut t, mut x) = (0usize, 0usize);
    let len = out.len();
    let mut pixel = |x: &mut usize, at: usize, c: u16| -> Result<(), DecodeError> {
        let p = out.get_mut(*x).ok_or(DecodeError::TooLong { at, len })?;
        *p = c;
        *x += 1;
        Ok(())
    };
    let mut last = 0u16;
    loop {
        let at = t;
        let code = token(t)?;
        t += 1;
        if code == op.end_of_line_align || code == op.end_of_line_skip_align {
            let skip = code == op.end_of_line_skip_align;
            if (at % 2 == 0) != skip {
                return Err(DecodeError::Misaligned { at });
            }
            if skip {
                token(t)?;
                t += 1;
            }
            break;
        }
        if code == op.color_run {
            let c = token(t)?;
            let n = usize::from(token(t + 1)?) + 3;
            t += 2;
            for _ in 0..n {
                pixel(&mut x, at, c)?;
            }
            last = c;
        } else if code == op.raw_run {
            let c = token(t)?;
            let n = usize::from(token(t + 1)?) + 3;
            pixel(&mut x, at, c)?;
            t += 2;
            last = c;
            for _ in 1..n {
                last = token(t)?;
                pixel(&mut x, at, last)?;
                t += 1;
            }
        } else if code == op.raw_1p || code == op.raw_2p {
            let n = if code == op.raw_1p { 1 } else { 2 };
            for _ in 0..n {
                last = token(t)?;
                pixel(&mut x, at, last)?;
                t += 1;
            }
        } else if code == op.raw_1p_skip_align {
            if at % 2 == 0 {
                return Err(DecodeError::Misaligned { at });
            }
            last = token(t)?;
            token(t + 1)?;
            pixel(&mut x, at, last)?;
            t += 2;
        } else {
            return Err(DecodeError::Unknown { at });
        }
    }
    if x > 0 && last != 0 {
        return Err(DecodeError::NotBlack);
    }
    if t / 2 != words.len() {
        return Err(DecodeError::Trailing { words: t / 2 });
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec::Vec;

    const OP: Opcodes = Opcodes::DEFAULT;

    fn round_trip(runs: &[(u16, u16)]) -> (usize, [u16; 64], usize) {
        let mut words = [0u32; 64];
        let n = encode(runs.iter().copied(), &OP, &mut words).unwrap();
        let mut px = [0xaaaa; 64];
        let got = decode(&words[..n], &OP, &mut px).unwrap();
        (n, px, got)
    }

    #[test]
    fn runs_come_back_as_their_pixels() {
        for runs in [
            &[(10u16, 0u16)][..],
            &[(3, 5), (1, 6), (2, 7), (1, 8), (4, 0)],
            &[(1, 5)],
            &[(2, 5)],
            &[(1, 5), (1, 6), (1, 7)],
            &[(5, 9), (2, 1), (1, 0)],
            &[(1, 1), (3, 2)],
        ] {
            let (_, px, got) = round_trip(runs);
            let want: Vec<u16> = runs
                .iter()
                .flat_map(|&(l, c)| core::iter::repeat_n(c, usize::from(l)))
                .collect();
            let black = usize::from(*want.last().unwrap() != 0);
            assert_eq!(got, want.len() + black, "{runs:?}");
            assert_eq!(&px[..want.len()], &want[..], "{runs:?}");
            if black == 1 {
                assert_eq!(px[want.len()], 0);
            }
        }
    }

    #[test]
    fn a_black_row_is_one_colour_run_and_an_end() {
        let mut words = [0u32; 4];
        assert_eq!(encode([(640u16, 0u16)], &OP, &mut words), Ok(2));
        // | COLOR_RUN | 0 || 637 | EOL_ALIGN ||
        assert_eq!(words[..2], [3, 637 | 1 << 16]);
        assert_eq!(
            encode([(640u16, 0u16)], &OP, &mut words[..1]),
            Err(EncodeError::Full {
                needed: 2,
                capacity: 1
            })
        );
        assert_eq!(
            encode([(0u16, 0u16)], &OP, &mut words),
            Err(EncodeError::Empty { run: 0 })
        );
    }

    #[test]
    fn bad_streams_are_errors() {
        let mut px = [0u16; 8];
        // An end token in the wrong half.
        assert_eq!(
            decode(&[1], &OP, &mut px),
            Err(DecodeError::Misaligned { at: 0 })
        );
        assert_eq!(
            decode(&[0xffff], &OP, &mut px),
            Err(DecodeError::Unknown { at: 0 })
        );
        assert_eq!(
            decode(&[3 | 5 << 16], &OP, &mut px),
            Err(DecodeError::Truncated { at: 2 })
        );
        // Ten pixels of colour 5 into 8.
        assert_eq!(
            decode(&[3 | 5 << 16, 7 | 1 << 16], &OP, &mut px),
            Err(DecodeError::TooLong { at: 0, len: 8 })
        );
        // Three pixels of 5 and no black.
        assert_eq!(
            decode(&[3 | 5 << 16, 1 << 16], &OP, &mut px),
            Err(DecodeError::NotBlack)
        );
        assert_eq!(
            decode(&[3, 1 << 16, 0], &OP, &mut px),
            Err(DecodeError::Trailing { words: 2 })
        );
    }
}
