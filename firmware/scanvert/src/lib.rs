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
//! | stage | module | what happens |
//! |---|---|---|
//! | reader | [`display_list`] | validate the bytes once, then read commands infallibly |
//! | 3D geometry | [`geometry`] | transform stack, cull, light, near clip, projection, points and lines, window clip, into screen-space polygons |
//! | geometry | [`fixed`] | Q12.4 vertices and the widths of every intermediate |
//! | edges | [`edge`] | per-edge set-up, then an exact Bresenham step per row |
//! | edges, approximate | [`edge_dda`] | faster DDA steppers and vertex snapping, with their error documented |
//! | spans | [`scan`] | active-edge list, even-odd pairing of crossings |
//! | clip registers | [`clip`] | the window every span is cut to |
//! | port | [`port`], [`framebuffer`] | spans into memory (or hardware) |
//! | trapezoids (3D) | [`trapezoid`] | a screen-space polygon cut into trapezoids with horizontal parallel sides; its plane, exact and in fixed point |
//! | store (3D) | [`segment`] | trapezoids and faces by segment, in caller-owned pools; the scan-line index by top row |
//! | visible surfaces (3D) | [`visible`] | active trapezoids per row, spans classified and resolved by depth, no z-buffer |
//! | run-length rows (3D) | [`rle`] | one run-length scan line per row, and its decoder into the port |
//! | labels (3D) | [`label`] | text anchored at projected points, drawn last in `embedded-graphics` mono fonts |
//! | scene (3D) | [`scene`] | segments built by the application's procedures, rebuilt only when stale; draws store and labels |
//! | controller | [`controller`] | runs a display list through all of the above (`poly3` as a 3D layer over the 2D commands) |
//! | colour | [`color`] | list colours to the frame buffer's pixel format |
//! | embedded-graphics | `draw_target` (feature `embedded-graphics`) | spans into any `DrawTarget`; the frame buffer as a `DrawTarget` |
//!
//! # Example
//!
//! ```
//! use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
//! use scanvert::{
//!     controller::Controller, display_list::{DisplayList, Writer}, edge::Edge,
//!     fixed::Vertex, framebuffer::FrameBuffer, scan::Rasterizer,
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

pub mod checksum;
pub mod clip;
pub mod color;
pub mod controller;
pub mod display_list;
#[cfg(feature = "embedded-graphics")]
pub mod draw_target;
pub mod edge;
pub mod edge_dda;
pub mod fixed;
pub mod framebuffer;
pub mod geometry;
pub mod label;
pub mod port;
pub mod rle;
pub mod scan;
pub mod scene;
pub mod segment;
pub mod trapezoid;
pub mod visible;

pub use embedded_graphics_core::pixelcolor;
