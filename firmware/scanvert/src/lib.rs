#![doc = include_str!("../README.md")]
//!
//! # The pipeline, display list to pixel
//!
//! The folders are the stages, in the order the data goes through them:
//!
//! | stage | module | what happens |
//! |---|---|---|
//! | 1. read | [`display_list`] | validate the bytes once, then read commands infallibly |
//! | 2D: 2. raster | [`raster`] | edge set-up, an exact integer step per row, even-odd spans, the clip registers |
//! | 3D: 2. geometry | [`geometry`] | transform stack, cull, light, near clip, projection, points and lines, window clip, into screen-space polygons |
//! | 3D: 3. visible | [`visible`] | polygons cut into trapezoids, kept by segment, resolved row by row into run-length rows with no z-buffer |
//! | 3D: scene | [`scene`] | segments built by the application's procedures, rebuilt only when stale; labels drawn last |
//! | 4. port | [`port`] | spans into memory or hardware: the frame buffer, the checksum, any embedded-graphics `DrawTarget` |
//! | all | [`controller`] | runs a display list through all of the above (`poly3` and the 3D scene as a layer over the 2D commands) |
//! | 5. frame | [`frame`] (in [`controller`]) | one pass over a stack of layers (display lists, scenes, embedded-graphics drawables), band by band, changed rows only, shipped to the panel |
//!
//! Beside them: [`fixed`] (Q12.4 vertices and the widths of every
//! intermediate) and [`color`] (list colours to the port's pixel format).
//!
//! # Where the names are
//!
//! The types an application names are re-exported at the root
//! (`scanvert::Rasterizer`, `scanvert::Scene`, …), and the [`prelude`]
//! holds those of the 2D path with the traits and colours they need, so
//! that one `use scanvert::prelude::*;` draws a polygon. The modules keep
//! everything else: the parts of each stage, their counters and their
//! less common errors. What only the stages themselves use (the binary
//! layout table, the sweep's run writer, the store's writers, edge
//! stepping, the transform stack) is `#[doc(hidden)]`: reachable for the
//! simulator and the tests, but not part of the API, and it may change in
//! any release.
//!
//! # Features
//!
//! - `defmt`: `defmt::Format` on the public types. Without it there is no
//!   logging code at all.
//!
//! The embedded-graphics port ([`port::draw_target`]) is always there: it
//! needs only `embedded-graphics-core`, a dependency in any case.
//!
#![no_std]
#![deny(missing_docs)]
#![deny(missing_debug_implementations)]
// One `unsafe` block, allowed where it is: `port::store_multiple`
// (Thumb-2 targets only), with its measured reason.
#![deny(unsafe_code)]
#![deny(rustdoc::broken_intra_doc_links)]
#![deny(clippy::float_arithmetic)]
#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod color;
pub mod controller;
pub mod display_list;
pub mod fixed;
pub mod geometry;
pub mod port;
pub mod raster;
pub mod scene;
pub mod visible;

pub use embedded_graphics_core::pixelcolor;

// The 2D path: polygons into a span target.
pub use crate::fixed::{Coord, Vertex, Vertex3};
pub use crate::port::draw_target::DrawTargetPort;
pub use crate::port::{Checksum, Counts, FrameBuffer, Span, SpanTarget};
pub use crate::raster::{ClipRect, ClipWindow, Edge, FillError, Rasterizer};

// Display lists and the controller that runs them.
pub use crate::controller::{Controller, RenderError};
pub use crate::display_list::{Command, DisplayList, WriteError, Writer};

// The retained 3D scene and the memory it is given.
pub use crate::geometry::{
    Angle, Light, Orthographic, Perspective, Pipeline, Point3, Projection, View, ViewPoint,
    Viewport, Q16,
};
pub use crate::scene::{Builder, Label, Procedure, Scene, SceneError, SceneMemory};
pub use crate::visible::{
    Active, EdgeSlot, Face, Resolve, Run, Segment, StoreMemory, Trapezoid, Workspace,
};

// One frame over a stack of layers.
pub use crate::controller::frame::{self, DrawableLayer, FramePass, Layer};

// Colours.
pub use crate::color::{ListColor, ToRgb888};

/// One `use scanvert::prelude::*;` for the 2D path: the types that draw a
/// polygon, directly or through a display list, with the traits whose
/// methods they need and the common colours.
///
/// ```
/// use scanvert::prelude::*;
///
/// let mut pixels = [Rgb565::BLACK; 16 * 8];
/// let mut fb = FrameBuffer::new(&mut pixels, 16, 8).unwrap();
/// let mut edges = [Edge::EMPTY; 4];
/// let triangle = [(1, 1), (15, 4), (2, 7)].map(|(x, y)| Vertex::from_px(x, y).unwrap());
/// Rasterizer::new(&mut edges)
///     .fill(triangle, &ClipRect::full(16, 8), Rgb565::RED, &mut fb)
///     .unwrap();
/// assert_eq!(fb.pixel(5, 4), Some(Rgb565::RED));
/// ```
///
/// [`SpanTarget`] and embedded-graphics' `DrawTarget` both have `clear`
/// and `size`; where both are in scope, name the one meant:
/// `SpanTarget::clear(&mut fb, c)`.
pub mod prelude {
    pub use crate::color::{ListColor, ToRgb888};
    pub use crate::controller::Controller;
    pub use crate::display_list::{DisplayList, Writer};
    pub use crate::fixed::{Coord, Vertex};
    pub use crate::pixelcolor::{Rgb565, Rgb888, RgbColor};
    pub use crate::port::{FrameBuffer, SpanTarget};
    pub use crate::raster::{ClipRect, ClipWindow, Edge, Rasterizer};
}

#[cfg(test)]
mod rng;

#[cfg(test)]
mod tests {
    use core::convert::Infallible;

    /// `E` is an error that `?` turns into `Box<dyn Error>`.
    fn is_error<E: core::error::Error + Send + Sync + 'static>() {}

    #[test]
    fn every_public_error_implements_error() {
        is_error::<crate::RenderError<Infallible>>();
        is_error::<crate::FillError<Infallible>>();
        is_error::<crate::display_list::Error>();
        is_error::<crate::WriteError>();
        is_error::<crate::visible::StoreError>();
        is_error::<crate::visible::VisibleError<Infallible>>();
        is_error::<crate::visible::trapezoid::LoadError>();
        is_error::<crate::visible::RunsFull>();
        is_error::<crate::scene::label::LabelError>();
        is_error::<crate::SceneError>();
        is_error::<crate::scene::UpdateError>();
        is_error::<crate::geometry::TransformError>();
        is_error::<crate::geometry::ProjectionError>();
        is_error::<crate::geometry::PipelineError<Infallible>>();
        is_error::<crate::port::band::BandError>();
        is_error::<crate::port::panel::PanelError<Infallible, Infallible>>();
        is_error::<crate::controller::ListBandsError<Infallible>>();
        is_error::<crate::controller::PrepareError>();
        is_error::<crate::raster::table::TableError>();
    }
}
