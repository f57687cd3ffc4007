//! The graphic controller: executes a display list into a frame-buffer
//! port, holding the clip registers and the current colour.

use crate::clip::ClipRect;
use crate::color::ListColor;
use crate::display_list::{Command, DisplayList};
use crate::port::SpanTarget;
use crate::scan::{FillError, Rasterizer};
use core::fmt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// The colour of `poly` before the first `color` command.
pub const DEFAULT_COLOR: Rgb888 = Rgb888::WHITE;

/// Why a display list could not be rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RenderError<E> {
    /// A polygon has more vertices than the edge storage has slots.
    /// Found before anything is drawn.
    Capacity {
        /// Byte offset of the command in the list.
        offset: usize,
        /// Its vertices.
        vertices: usize,
        /// Edge slots available.
        capacity: usize,
    },
    /// A command this controller does not execute. Found before anything
    /// is drawn.
    Unsupported {
        /// Byte offset of the command in the list.
        offset: usize,
        /// The command's name in the text form.
        command: &'static str,
    },
    /// The frame-buffer port failed at the command at `offset`.
    Target {
        /// Byte offset of the command in the list.
        offset: usize,
        /// The port's error.
        error: E,
    },
}

impl<E> RenderError<E> {
    /// Byte offset of the command at fault.
    pub fn offset(&self) -> usize {
        match *self {
            RenderError::Capacity { offset, .. }
            | RenderError::Unsupported { offset, .. }
            | RenderError::Target { offset, .. } => offset,
        }
    }
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Capacity {
                vertices, capacity, ..
            } => write!(
                f,
                "polygon has {vertices} vertices; this renderer holds {capacity} edges"
            ),
            RenderError::Unsupported { command, .. } => {
                write!(f, "`{command}` is not supported by this renderer yet")
            }
            RenderError::Target { error, .. } => write!(f, "frame-buffer port failed: {error:?}"),
        }
    }
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stats {
    /// Commands executed.
    pub commands: u32,
    /// Polygons scan-converted.
    pub polygons: u32,
    /// Clears executed.
    pub clears: u32,
    /// Spans written by polygons.
    pub spans: u32,
    /// Pixels written by polygons.
    pub pixels: u64,
}

/// The graphic controller.
#[derive(Debug)]
pub struct Controller<'e> {
    raster: Rasterizer<'e>,
}

impl<'e> Controller<'e> {
    /// A controller scan-converting with `raster`.
    pub fn new(raster: Rasterizer<'e>) -> Self {
        Controller { raster }
    }

    /// Checks that every command of `list` can be executed, without
    /// drawing: polygon sizes against the edge storage, and known commands.
    pub fn check(
        &self,
        list: &DisplayList<'_>,
    ) -> Result<(), RenderError<core::convert::Infallible>> {
        let capacity = self.raster.capacity();
        for (offset, cmd) in list.commands() {
            match cmd {
                Command::Poly(v) if v.len() > capacity => {
                    return Err(RenderError::Capacity {
                        offset,
                        vertices: v.len(),
                        capacity,
                    })
                }
                Command::Poly3(_) => {
                    return Err(RenderError::Unsupported {
                        offset,
                        command: "poly3",
                    })
                }
                Command::Clear(_) | Command::Clip(_) | Command::Color(_) | Command::Poly(_) => {}
                _ => {
                    return Err(RenderError::Unsupported {
                        offset,
                        command: "3D scene",
                    })
                }
            }
        }
        Ok(())
    }

    /// Executes `list` into `target`, starting with the clip registers on
    /// the whole frame and the colour [`DEFAULT_COLOR`].
    ///
    /// The frame is the list's, cut to the target's size. The list is
    /// [`check`](Self::check)ed first: on a capacity or unsupported-command
    /// error nothing is drawn.
    pub fn render<T>(
        &mut self,
        list: &DisplayList<'_>,
        target: &mut T,
    ) -> Result<Stats, RenderError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        self.check(list).map_err(|e| match e {
            RenderError::Capacity {
                offset,
                vertices,
                capacity,
            } => RenderError::Capacity {
                offset,
                vertices,
                capacity,
            },
            RenderError::Unsupported { offset, command } => {
                RenderError::Unsupported { offset, command }
            }
            RenderError::Target { error, .. } => match error {},
        })?;
        let (tw, th) = target.size();
        let (w, h) = (list.width().min(tw), list.height().min(th));
        let mut clip = ClipRect::full(w, h);
        let mut color = T::Color::from_rgb888(DEFAULT_COLOR);
        let mut stats = Stats::default();
        for (offset, cmd) in list.commands() {
            stats.commands += 1;
            match cmd {
                Command::Clear(c) => {
                    target
                        .clear(T::Color::from_rgb888(c))
                        .map_err(|error| RenderError::Target { offset, error })?;
                    stats.clears += 1;
                }
                Command::Clip(win) => clip = ClipRect::from_window(win, w, h),
                Command::Color(c) => color = T::Color::from_rgb888(c),
                Command::Poly(v) => {
                    let counts = self
                        .raster
                        .fill(v.iter(), &clip, color, target)
                        .map_err(|e| match e {
                            FillError::Target(error) => RenderError::Target { offset, error },
                            FillError::Capacity { capacity } => RenderError::Capacity {
                                offset,
                                vertices: v.len(),
                                capacity,
                            },
                        })?;
                    stats.polygons += 1;
                    stats.spans += counts.spans;
                    stats.pixels += counts.pixels as u64;
                }
                // Rejected by `check`.
                _ => {}
            }
        }
        Ok(stats)
    }
}
