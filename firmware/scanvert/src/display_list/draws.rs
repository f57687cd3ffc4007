//! The one interpreter of a display list's 2D commands.
//!
//! `clear`, `clip`, `color`, `fill`, `poly` and `line` are read here, and
//! only here: [`DisplayList::draws`] follows the clip registers, the current
//! colour and the fill rule and yields a [`Draw`] for each `clear`, `poly` and `line`, with
//! the state in force at its place. The controller's immediate render and
//! the band edge table both draw from it; [`DisplayList::table_needs`]
//! counts the table's memory from it. The 3D commands have their own one
//! interpreter, in [`scene::list`](crate::scene::list).

use super::reader::{Command, Commands, DisplayList};
use crate::color::DEFAULT_COLOR;
use crate::port::band::{DirtyRows, Mix};
use crate::raster::clip::ClipRect;
use crate::raster::draw::Draw;
use crate::raster::table::TableNeeds;
use crate::raster::winding::FillRule;
use core::fmt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

use super::Vertices;

/// The state the 2D commands carry: the clip registers, cut to the frame,
/// the current colour and the fill rule of `poly`s.
#[derive(Clone, Copy, Debug)]
struct State {
    clip: ClipRect,
    color: Rgb888,
    rule: FillRule,
    frame: (u16, u16),
}

impl State {
    fn new((width, height): (u16, u16)) -> Self {
        State {
            clip: ClipRect::full(width, height),
            color: DEFAULT_COLOR,
            rule: FillRule::EvenOdd,
            frame: (width, height),
        }
    }

    /// Executes `cmd`: what it draws, or `None` for a command that only
    /// changes the state or belongs to the 3D layer.
    #[inline(always)]
    fn step<'a>(&mut self, cmd: Command<'a>) -> Option<Draw<Vertices<'a>>> {
        let (clip, color) = (self.clip, self.color);
        Some(match cmd {
            Command::Clear(c) => Draw::Clear(c),
            Command::Clip(win) => {
                self.clip = ClipRect::from_window(win, self.frame.0, self.frame.1);
                return None;
            }
            Command::Color(c) => {
                self.color = c;
                return None;
            }
            Command::Fill(rule) => {
                self.rule = rule;
                return None;
            }
            Command::Poly(vertices) => Draw::Poly {
                vertices,
                rule: self.rule,
                clip,
                color,
            },
            Command::Line(from, to) => Draw::Line {
                from,
                to,
                clip,
                color,
            },
            // The 3D layer's commands.
            _ => return None,
        })
    }
}

/// The 2D drawing operations of a list, each with the byte offset of its
/// command: from [`DisplayList::draws`].
#[derive(Clone, Debug)]
pub struct Draws<'a> {
    commands: core::iter::Take<Commands<'a>>,
    state: State,
}

impl<'a> Iterator for Draws<'a> {
    /// `(byte offset of the command, what it draws)`.
    type Item = (usize, Draw<Vertices<'a>>);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        for (offset, cmd) in self.commands.by_ref() {
            if let Some(draw) = self.state.step(cmd) {
                return Some((offset, draw));
            }
        }
        None
    }
}

impl<'a> DisplayList<'a> {
    /// The list's 2D drawing operations in order, on a frame of
    /// `width × height` (the list's frame cut to the target's): clip
    /// windows are cut to it. They start with the clip registers on the
    /// whole frame, the colour [`DEFAULT_COLOR`] and the fill rule
    /// even-odd. A list with no
    /// `clear`, `poly` or `line` ([`Summary::draws_2d`](super::Summary))
    /// yields nothing without being read.
    ///
    /// A `clear` fills the whole frame, so what is drawn before the last
    /// one cannot show: those draws are not yielded (their `clip`,
    /// `color` and `fill` still take effect). The work of a list is then bounded by
    /// one frame's clear and the commands after it, however many `clear`s
    /// it holds.
    pub fn draws(&self, frame: (u16, u16)) -> Draws<'a> {
        let (state, start) = self.state_at_last_clear(frame);
        Draws {
            commands: self.commands_from(start).take(self.drawn_2d()),
            state,
        }
    }

    /// The state in force at the last `clear` (the clip registers and
    /// colour the commands before it leave), and its byte offset: where
    /// the draws start. With no `clear`, the first state and offset 0.
    fn state_at_last_clear(&self, frame: (u16, u16)) -> (State, usize) {
        let mut state = State::new(frame);
        let Some(start) = self.summary().last_clear else {
            return (state, 0);
        };
        for (offset, cmd) in self.commands() {
            if offset >= start {
                break;
            }
            match cmd {
                Command::Clip(_) | Command::Color(_) | Command::Fill(_) => {
                    state.step(cmd);
                }
                _ => {}
            }
        }
        (state, start)
    }

    /// [`draws`](Self::draws), each handed to `f` in order, until `f`
    /// fails: the same operations, with the state in the loop's own
    /// variables (the controller's render takes them so).
    #[inline]
    pub fn for_each_draw<E, F>(&self, frame: (u16, u16), mut f: F) -> Result<(), E>
    where
        F: FnMut(usize, Draw<Vertices<'a>>) -> Result<(), E>,
    {
        let (mut state, start) = self.state_at_last_clear(frame);
        for (offset, cmd) in self.commands_from(start).take(self.drawn_2d()) {
            if let Some(draw) = state.step(cmd) {
                f(offset, draw)?;
            }
        }
        Ok(())
    }

    /// How many commands to read for the 2D draws: none for a list with
    /// no `clear`, `poly` or `line`.
    fn drawn_2d(&self) -> usize {
        match self.summary().draws_2d {
            true => usize::MAX,
            false => 0,
        }
    }

    /// The memory of the band edge table of this list
    /// ([`TableMemory`](crate::raster::table::TableMemory)): its `poly`s
    /// and `line`s after its last `clear`, and the polygons' vertices (an
    /// upper bound of their edges).
    pub fn table_needs(&self) -> TableNeeds {
        TableNeeds::count(self.draws((self.width(), self.height())))
    }
}

/// The scratch memory given to [`DisplayList::mark_changes`] holds fewer
/// than two hashes a row of the frame; nothing was marked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScratchTooSmall {
    /// `u64`s given.
    pub len: usize,
    /// `u64`s needed: twice the frame's height.
    pub needed: usize,
}

impl fmt::Display for ScratchTooSmall {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the scratch holds {} row hashes; marking changes needs {}",
            self.len, self.needed
        )
    }
}

impl core::error::Error for ScratchTooSmall {}

/// Rows `(y0, y1)` (end exclusive) that points from `lo` to `hi` (in
/// sixteenths of a pixel, y) may draw on, one row of margin each side,
/// cut to the clip rows.
fn rows_between(lo: i32, hi: i32, clip: &ClipRect) -> (usize, usize) {
    let y0 = (lo.div_euclid(16) - 1).max(clip.y0() as i32);
    let y1 = (hi.div_euclid(16) + 2).min(clip.y1() as i32);
    (y0 as usize, y1.max(y0) as usize)
}

impl<'a> DisplayList<'a> {
    /// Writes into `sig[y]`, for each row `y < sig.len()` of the frame,
    /// a hash of what the list's 2D commands draw on the row, in their
    /// order: each `poly` and `line` (its vertices, colour and clip)
    /// chained onto the rows it may touch, each `clear` starting every
    /// row anew. Two lists whose 2D commands draw a row differently hash
    /// it differently but with a chance of about 2⁻⁶⁴; lists that draw it
    /// the same by the same commands hash it the same.
    pub fn row_signatures(&self, sig: &mut [u64]) {
        sig.fill(0);
        let h = sig.len();
        for (_, draw) in self.draws((self.width(), self.height())) {
            let mut k = Mix::new();
            let (rows, k) = match draw {
                Draw::Clear(c) => {
                    k.add(rgb_word(c));
                    let k = k.finish();
                    sig.fill(k);
                    continue;
                }
                Draw::Poly {
                    vertices,
                    rule,
                    clip,
                    color,
                } => {
                    k.add(1 + rule.to_byte() as u64);
                    let (mut lo, mut hi) = (i32::MAX, i32::MIN);
                    for v in vertices {
                        k.add((v.x.to_bits() as u16 as u64) << 16 | v.y.to_bits() as u16 as u64);
                        (lo, hi) = (lo.min(v.y.units()), hi.max(v.y.units()));
                    }
                    k.add(rgb_word(color));
                    k.add(clip_word(&clip));
                    (rows_between(lo, hi, &clip), k.finish())
                }
                Draw::Line {
                    from,
                    to,
                    clip,
                    color,
                } => {
                    k.add(2);
                    for v in [from, to] {
                        k.add((v.x.to_bits() as u16 as u64) << 16 | v.y.to_bits() as u16 as u64);
                    }
                    k.add(rgb_word(color));
                    k.add(clip_word(&clip));
                    let (lo, hi) = (
                        from.y.units().min(to.y.units()),
                        from.y.units().max(to.y.units()),
                    );
                    (rows_between(lo, hi, &clip), k.finish())
                }
            };
            for s in &mut sig[rows.0.min(h)..rows.1.min(h)] {
                *s = Mix::chain(*s, k);
            }
        }
    }

    /// Marks in `dirty` the rows that this list draws differently from
    /// `before`, the list shown last, by comparing their
    /// [`row_signatures`](Self::row_signatures) in `scratch` (two `u64`s a
    /// row of the frame). Every row is marked when the frames differ in
    /// size or when either list has a 3D layer and the two differ at all
    /// (a 3D layer's rows are known only once it is built: keep changing
    /// 3D content in a [`Scene`](crate::scene::Scene), whose
    /// [`update_marking`](crate::scene::Scene::update_marking) marks it
    /// row by row). Too little scratch is an error, and nothing is marked.
    pub fn mark_changes(
        &self,
        before: &DisplayList<'_>,
        dirty: &mut DirtyRows<'_>,
        scratch: &mut [u64],
    ) -> Result<(), ScratchTooSmall> {
        let h = self.height() as usize;
        let len = scratch.len();
        let Some(sigs) = scratch.get_mut(..2 * h) else {
            return Err(ScratchTooSmall { len, needed: 2 * h });
        };
        let same_frame = (self.width(), self.height()) == (before.width(), before.height());
        let has_3d = self.summary().first_3d.is_some() || before.summary().first_3d.is_some();
        if !same_frame || (has_3d && self.as_bytes() != before.as_bytes()) {
            dirty.mark_all();
            return Ok(());
        }
        let (old, new) = sigs.split_at_mut(h);
        before.row_signatures(old);
        self.row_signatures(new);
        for (y, (a, b)) in old.iter().zip(new.iter()).enumerate() {
            if a != b {
                dirty.mark(y as i32, y as i32 + 1);
            }
        }
        Ok(())
    }
}

/// The clip rectangle in one word.
fn clip_word(c: &ClipRect) -> u64 {
    (c.x0() as u64) << 48 | (c.x1() as u64) << 32 | (c.y0() as u64) << 16 | c.y1() as u64
}

/// A colour in one word.
fn rgb_word(c: Rgb888) -> u64 {
    (c.r() as u64) << 16 | (c.g() as u64) << 8 | c.b() as u64
}
