//! Integer scan conversion of display lists, for microcontrollers and FPGA
//! soft-cores.
//!
//! `scanvert` is the graphic controller of a scan-conversion unit in
//! software: it reads a *display list* of polygons, steps each polygon's
//! edges with integer error counters, clips every horizontal span against
//! four *clip registers*, and writes the spans into a frame-buffer port.
//! There is no floating point, no allocation and no `unsafe`; all memory is
//! the caller's.
//!
//! # The pipeline, display list to pixel
//!
//! The folders are the stages, in the order the data goes through them:
//!
//! | stage | module | what happens |
//! |---|---|---|
//! | 1. read | [`display_list`] | validate the bytes once, then read commands infallibly |
//! | 2D: 2. raster | [`raster`] | edge set-up, an exact error-counter step per row, even-odd spans, the clip registers |
//! | 3D: 2. geometry | [`geometry`] | transform stack, cull, light, near clip, projection, points and lines, window clip, into screen-space polygons |
//! | 3D: 3. visible | [`visible`] | polygons cut into trapezoids, kept by segment, resolved row by row into run-length rows with no z-buffer |
//! | 3D: scene | [`scene`] | segments built by the application's procedures, rebuilt only when stale; labels drawn last |
//! | 4. port | [`port`] | spans into memory or hardware: the frame buffer, the checksum, any embedded-graphics `DrawTarget` |
//! | all | [`controller`] | runs a display list through all of the above (`poly3` and the 3D scene as a layer over the 2D commands) |
//!
//! Beside them: [`fixed`] (Q12.4 vertices and the widths of every
//! intermediate) and [`color`] (list colours to the port's pixel format).
//!
//! # Example
//!
//! ```
//! use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
//! use scanvert::{
//!     controller::Controller, display_list::{DisplayList, Writer}, raster::edge::Edge,
//!     fixed::Vertex, port::framebuffer::FrameBuffer, raster::scan::Rasterizer,
//! };
//!
//! // Assemble a list: a red triangle on a black frame of 32 × 16.
//! let mut bytes = [0u8; 64];
//! let mut w = Writer::new(&mut bytes, 32, 16)?;
//! w.clear(Rgb888::BLACK)?;
//! w.color(Rgb888::RED)?;
//! let px = |x: i16, y: i16| Vertex::from_bits(x * 16, y * 16);
//! w.poly([px(2, 2), px(30, 8), px(4, 14)])?;
//! let list = DisplayList::new_checked(w.finish()).unwrap();
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 16];
//! let mut fb = FrameBuffer::new(&mut pixels, 32, 16).unwrap();
//! let mut edges = [Edge::EMPTY; 16];
//! let stats = Controller::new(Rasterizer::new(&mut edges)).render(&list, &mut fb).unwrap();
//! assert_eq!(fb.pixel(10, 8), Some(Rgb565::RED));
//! assert_eq!(stats.polygons, 1);
//! # Ok::<(), scanvert::display_list::WriteError>(())
//! ```
#![no_std]
#![deny(missing_docs)]
#![deny(missing_debug_implementations)]
#![deny(unsafe_code)]
#![deny(rustdoc::broken_intra_doc_links)]
#![deny(clippy::float_arithmetic)]

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
