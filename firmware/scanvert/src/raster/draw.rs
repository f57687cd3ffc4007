//! What the 2D path draws: a `clear`, a polygon or a line, each with the
//! colour and the clip registers (and a polygon with the fill rule) in
//! force where it stands in its list.
//!
//! The display list's 2D commands are interpreted in one place,
//! [`DisplayList::draws`](crate::display_list::DisplayList::draws), which
//! follows `clip` and `color` and yields a [`Draw`] for each `clear`,
//! `poly` and `line`. Both ways of drawing them take these: the
//! controller's immediate render (a [`Rasterizer`](super::Rasterizer) and
//! [`draw_line`](super::line::draw_line) into a frame) and the band edge
//! table ([`EdgeTable::build`](super::table::EdgeTable::build)), so that
//! the two cannot disagree on what a list means.

use crate::fixed::Vertex;
use crate::raster::clip::ClipRect;
use crate::raster::winding::FillRule;
use embedded_graphics_core::pixelcolor::Rgb888;

/// One 2D drawing operation. `V` is the polygon's vertices: any
/// `IntoIterator<Item = Vertex>` that can be walked more than once
/// (`Clone`); from a display list, its
/// [`Vertices`](crate::display_list::Vertices).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Draw<V> {
    /// Every pixel of the frame gets this colour; the clip registers do
    /// not apply.
    Clear(Rgb888),
    /// A polygon by the pixel rule of its fill rule, cut to `clip`.
    Poly {
        /// At least three vertices, in order.
        vertices: V,
        /// The fill rule in force: even-odd or non-zero winding.
        rule: FillRule,
        /// The clip registers, cut to the frame.
        clip: ClipRect,
        /// The current colour.
        color: Rgb888,
    },
    /// A line one pixel wide by the line rule, cut to `clip`.
    Line {
        /// Its first end.
        from: Vertex,
        /// Its second end.
        to: Vertex,
        /// The clip registers, cut to the frame.
        clip: ClipRect,
        /// The current colour.
        color: Rgb888,
    },
}
