//! Host-side simulator of the scanvert display hardware.
//!
//! # The simulated hardware
//!
//! A graphic controller ([`scanvert::controller::Controller`]) writes
//! pixels into one port of a dual-port frame-buffer RAM; a refresh
//! controller reads the other port, each port on its own clock, in step
//! with the hsync/vsync timing it generates.
//!
//! | module | hardware |
//! |---|---|
//! | [`timing`] | pixel clock, porches and sync pulses; the presets of the reference design |
//! | [`dual_port`] | the dual-port RAM: a span write port, a pixel read port, counters per port; optionally two banks swapped in vertical retrace |
//! | [`refresh`] | the refresh controller: sync generator and read-out of one frame; [`refresh::CoSimulation`] runs it alongside the graphic controller |
//! | [`image`] | the frame as a PNG (RGB565 expanded by bit replication) |
//! | [`text`] | the text form of the display list: assembler and disassembler |
//! | [`cli`] | the `scanvert` program: `render`, `asm`, `disasm`, `checksum` |
//! | [`race`] | the display device with no frame RAM: a ring of run-length rows drawn just in time, with deadlines |
//! | [`memory`] | the graphic controller's memory for a list, sized by what it needs |
//!
//! ```
//! use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
//! use scanvert::{
//!     controller::Controller, display_list::{DisplayList, Writer}, raster::edge::Edge,
//!     fixed::Vertex, raster::scan::Rasterizer,
//! };
//! use scanvert_sim::{dual_port::DualPortRam, image, refresh::RefreshController, timing::VideoTiming};
//!
//! let mut bytes = [0u8; 64];
//! let mut w = Writer::new(&mut bytes, 32, 16)?;
//! w.color(Rgb888::RED)?;
//! let px = |x: i16, y: i16| Vertex::from_bits(x * 16, y * 16);
//! w.poly([px(2, 2), px(30, 8), px(4, 14)])?;
//! let list = DisplayList::new_checked(w.finish()).unwrap();
//! let mut edges = [Edge::EMPTY; 16];
//! let mut controller = Controller::new(Rasterizer::new(&mut edges));
//!
//! let mut ram = DualPortRam::new(list.width(), list.height());
//! controller.render(&list, &mut ram.write_port()).unwrap();
//! let timing = VideoTiming::for_frame(list.width(), list.height());
//! let frame = RefreshController::new(timing).read_frame(&mut ram);
//! assert_eq!(frame.pixel(10, 8), Some(Rgb565::RED));
//! assert_eq!(frame.counters().vsync_pulses, 1);
//! let png = image::encode_png(&frame)?; // or image::write_png(path, &frame)
//! assert_eq!(image::decode_png(&png)?.0, 32);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]
#![deny(missing_debug_implementations)]
#![deny(unsafe_code)]
#![deny(rustdoc::broken_intra_doc_links)]

pub mod cli;
pub mod demo;
pub mod dual_port;
pub mod error;
pub mod image;
pub mod import;
pub mod memory;
mod output;
pub mod race;
pub mod refresh;
pub mod text;
pub mod timing;
