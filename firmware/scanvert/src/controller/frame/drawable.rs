//! embedded-graphics drawables as a layer of the frame.

use super::{fill_background, Layer};
use crate::geometry::{Pipeline, Point3};
use crate::port::band::{Band, DirtyRows};
use crate::port::Counts;
use crate::visible::VisibleError;
use core::convert::Infallible;
use embedded_graphics::prelude::{Dimensions, Drawable, Point, Transform};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics_core::pixelcolor::PixelColor;

/// A layer of one embedded-graphics [`Drawable`]: text in any font, a
/// styled primitive (circle, rounded rectangle, …), an image. It draws
/// into each band as into a frame (a [`Band`] is a `DrawTarget`), and a
/// band that its bounding box misses costs one rectangle test. For
/// several drawables, stack several layers.
///
/// It keeps track of its own changes: [`set`](Self::set) with a different
/// drawable, [`hide`](Self::hide), [`show`](Self::show),
/// [`anchor`](Self::anchor) to another point, or
/// [`invalidate`](Self::invalidate), mark the rows of its bounding box
/// before and after for [`FramePass::draw_marked`](super::FramePass::draw_marked).
/// A new layer is marked whole.
#[derive(Clone, Debug)]
pub struct DrawableLayer<D> {
    item: D,
    shown: bool,
    /// Rows changed since the last pass that asked, `(y0, y1)`, ends
    /// exclusive; empty when `y0 >= y1`.
    changed: (i32, i32),
}

/// The rows `(y0, y1)` (end exclusive) of `r`, in `i64` so that no
/// rectangle overflows.
fn rows_of(r: &Rectangle) -> (i64, i64) {
    let y = r.top_left.y as i64;
    (y, y + r.size.height as i64)
}

impl<D: Dimensions> DrawableLayer<D> {
    /// A shown layer of `item`, its rows marked as changed.
    pub fn new(item: D) -> Self {
        let mut layer = DrawableLayer {
            item,
            shown: true,
            changed: (0, 0),
        };
        layer.invalidate();
        layer
    }

    /// The drawable.
    pub fn get(&self) -> &D {
        &self.item
    }

    /// `true` when the layer is drawn.
    pub fn is_shown(&self) -> bool {
        self.shown
    }

    /// Marks the rows of the drawable's bounding box as changed (when
    /// shown): what the application changed behind the layer's back.
    pub fn invalidate(&mut self) {
        if self.shown {
            let (y0, y1) = rows_of(&self.item.bounding_box());
            let clamp = |v: i64| v.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
            let (y0, y1) = (clamp(y0), clamp(y1));
            self.changed = match self.changed {
                (a, b) if a >= b => (y0, y1),
                (a, b) => (a.min(y0), b.max(y1)),
            };
        }
    }

    /// Replaces the drawable; when it differs from the one there, the
    /// rows of both are marked.
    pub fn set(&mut self, item: D)
    where
        D: PartialEq,
    {
        if item != self.item {
            self.invalidate();
            self.item = item;
            self.invalidate();
        }
    }

    /// Stops drawing it; its rows are marked.
    pub fn hide(&mut self) {
        self.invalidate();
        self.shown = false;
    }

    /// Draws it again; its rows are marked.
    pub fn show(&mut self) {
        if !self.shown {
            self.shown = true;
            self.invalidate();
        }
    }

    /// Moves the drawable so that the point it had at `(0, 0)` is where
    /// `at` lands on the screen under `pipeline`'s current transform and
    /// projection (the whole pixel of a label's anchor), or hides it when
    /// `at` is behind the eye. `origin` is where that point is now (the
    /// last anchor, or `Point::zero()` for a drawable made at the
    /// origin); the new one is returned, to be passed next time.
    pub fn anchor<const DEPTH: usize, const N: usize>(
        &mut self,
        pipeline: &Pipeline<DEPTH, N>,
        at: Point3,
        origin: Point,
    ) -> Point
    where
        D: Transform + PartialEq,
    {
        match pipeline.project_point(at) {
            Ok(a) if a.in_front => {
                // Rounded as a label's anchor is.
                let (x, y) = crate::scene::label::to_pixels(a);
                let to = Point::new(x, y);
                let moved = self.item.translate(to - origin);
                self.set(moved);
                self.show();
                to
            }
            _ => {
                if self.shown {
                    self.hide();
                }
                origin
            }
        }
    }
}

impl<D: Dimensions> DrawableLayer<D> {
    /// `true` when the drawable is shown and its bounding box meets rows
    /// `y0..y1`.
    pub(super) fn meets(&self, y0: u16, y1: u16) -> bool {
        let (top, bottom) = rows_of(&self.item.bounding_box());
        self.shown && bottom > y0 as i64 && top < y1 as i64
    }

    /// The drawable.
    pub(super) fn item(&self) -> &D {
        &self.item
    }
}

impl<C, D> Layer<C> for DrawableLayer<D>
where
    C: PixelColor,
    D: Drawable<Color = C> + Dimensions,
{
    fn draw(
        &mut self,
        band: &mut Band<'_, C>,
        background: Option<C>,
    ) -> Result<Counts, VisibleError<Infallible>> {
        fill_background(band, background);
        if !self.meets(band.y(), band.end()) {
            return Ok(Counts::default());
        }
        match self.item.draw(band) {
            Ok(_) => Ok(Counts::default()),
            Err(e) => match e {},
        }
    }

    fn take_changes(&mut self, dirty: Option<&mut DirtyRows<'_>>) {
        let (y0, y1) = self.changed;
        if let (Some(dirty), true) = (dirty, y0 < y1) {
            dirty.mark(y0, y1);
        }
        self.changed = (0, 0);
    }
}
