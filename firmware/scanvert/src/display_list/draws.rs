//! The one interpreter of a display list's 2D commands.
//!
//! `clear`, `clip`, `color`, `poly` and `line` are read here, and only
//! here: [`DisplayList::draws`] follows the clip registers and the current
//! colour and yields a [`Draw`] for each `clear`, `poly` and `line`, with
//! the state in force at its place. The controller's immediate render and
//! the band edge table both draw from it; [`DisplayList::table_needs`]
//! counts the table's memory from it. The 3D commands have their own one
//! interpreter, in [`scene::list`](crate::scene::list).

use super::reader::{Command, Commands, DisplayList};
use crate::color::DEFAULT_COLOR;
use crate::raster::clip::ClipRect;
use crate::raster::draw::Draw;
use crate::raster::table::TableNeeds;
use embedded_graphics_core::pixelcolor::Rgb888;

use super::Vertices;

/// The 2D drawing operations of a list, each with the byte offset of its
/// command: from [`DisplayList::draws`].
#[derive(Clone, Debug)]
pub struct Draws<'a> {
    commands: core::iter::Take<Commands<'a>>,
    clip: ClipRect,
    color: Rgb888,
    frame: (u16, u16),
}

impl<'a> Iterator for Draws<'a> {
    /// `(byte offset of the command, what it draws)`.
    type Item = (usize, Draw<Vertices<'a>>);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        for (offset, cmd) in self.commands.by_ref() {
            let (clip, color) = (self.clip, self.color);
            let draw = match cmd {
                Command::Clear(c) => Draw::Clear(c),
                Command::Clip(win) => {
                    self.clip = ClipRect::from_window(win, self.frame.0, self.frame.1);
                    continue;
                }
                Command::Color(c) => {
                    self.color = c;
                    continue;
                }
                Command::Poly(vertices) => Draw::Poly {
                    vertices,
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
                _ => continue,
            };
            return Some((offset, draw));
        }
        None
    }
}

impl<'a> DisplayList<'a> {
    /// The list's 2D drawing operations in order, on a frame of
    /// `width × height` (the list's frame cut to the target's): clip
    /// windows are cut to it. They start with the clip registers on the
    /// whole frame and the colour [`DEFAULT_COLOR`]. A list with no
    /// `clear`, `poly` or `line` ([`Summary::draws_2d`](super::Summary))
    /// yields nothing without being read.
    pub fn draws(&self, (width, height): (u16, u16)) -> Draws<'a> {
        let n = match self.summary().draws_2d {
            true => usize::MAX,
            false => 0,
        };
        Draws {
            commands: self.commands().take(n),
            clip: ClipRect::full(width, height),
            color: DEFAULT_COLOR,
            frame: (width, height),
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
