//! What the fuzz targets share: a renderer sized the way the `scanvert`
//! program sizes it (`scanvert_sim::cli::render_scene`), drawing into a
//! small frame buffer, and the checks every error must pass.
//!
//! The targets are in `fuzz_targets/`; `docs/robustness.md` tells what
//! each one checks and how to run them.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use scanvert::controller::{RenderError, RenderStats, Resource};
use scanvert::display_list::DisplayList;
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::memory::ListMemory;

/// The largest frame the targets draw: a list's frame is cut to this
/// (the controller draws the part of the frame the target holds), so that
/// one execution stays cheap whatever the header says.
pub const MAX_SIDE: u16 = 64;

/// Lists whose 3D layer needs more trapezoid slots than this are not
/// rendered (their memory, not their correctness, is the limit).
pub const MAX_TRAPEZOIDS: usize = 1 << 16;

/// What rendering a checked list gave.
#[derive(Debug)]
pub struct Rendered {
    /// The frame as drawn: `min(W, MAX_SIDE) × min(H, MAX_SIDE)` pixels,
    /// black before the list ran.
    pub pixels: Vec<Rgb565>,
    /// The controller's result.
    pub result: Result<RenderStats, RenderError<core::convert::Infallible>>,
    /// `true` when the whole frame was drawn (not cut to `MAX_SIDE`).
    pub whole: bool,
    /// `true` when the memory was sized by `controller::needs`, as the
    /// program sizes it (always, since `needs` reports a failing command
    /// itself).
    pub sized: bool,
}

/// Renders `list` with memory sized as `render_scene` sizes it, into a
/// frame buffer of at most `MAX_SIDE × MAX_SIDE`, resolving with `resolve`.
/// `None` when the list's 3D layer would need more than `MAX_TRAPEZOIDS`.
pub fn render_small(list: &DisplayList<'_>, resolve: Resolve) -> Option<Rendered> {
    let (w, h) = (list.width().min(MAX_SIDE), list.height().min(MAX_SIDE));
    let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
    let whole = (w, h) == (list.width(), list.height());
    let mut memory = match ListMemory::for_list(list) {
        Ok(m) => m,
        // What the render would report, at the same command.
        Err(e) => {
            return Some(Rendered {
                pixels,
                result: Err(e),
                whole,
                sized: true,
            })
        }
    };
    let need = memory.needs();
    if need.trapezoids > MAX_TRAPEZOIDS || need.faces > MAX_TRAPEZOIDS {
        return None;
    }
    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("1..=64 a side");
    let result = memory
        .controller()
        .with_resolve(resolve)
        .render(list, &mut fb);
    Some(Rendered {
        pixels,
        result,
        whole,
        sized: true,
    })
}

/// Checks what is owed for any checked list: a render error names the
/// byte offset of a command of the list, and with the memory the program
/// sizes for the whole frame no capacity runs out (a face of more than
/// 58 vertices is a limit of the executor, not of the memory).
pub fn check_rendered(list: &DisplayList<'_>, r: &Rendered) {
    let Err(e) = &r.result else { return };
    let at = e.offset();
    assert!(
        list.commands().any(|(offset, _)| offset == at),
        "{e}: offset {at} is not a command of the list"
    );
    if r.whole && r.sized {
        assert!(
            !matches!(
                e,
                RenderError::Capacity { .. }
                    | RenderError::Unsupported { .. }
                    | RenderError::Capacity3d {
                        resource: Resource::Trapezoids
                            | Resource::Faces
                            | Resource::EdgeSlots
                            | Resource::Segments
                            | Resource::Rows
                            | Resource::Active
                            | Resource::Runs
                            | Resource::Labels
                            | Resource::LabelText,
                        ..
                    }
            ),
            "memory sized by needs ran out: {e}"
        );
    }
}

/// The frame assembled from shipped bands.
struct Shipped {
    width: usize,
    pixels: Vec<Rgb565>,
}

impl BandTarget for Shipped {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn ship(&mut self, y: u16, rows: u16, pixels: &[Rgb565]) -> Result<(), Self::Error> {
        let at = y as usize * self.width;
        let n = rows as usize * self.width;
        self.pixels[at..at + n].copy_from_slice(&pixels[..n]);
        Ok(())
    }
}

/// Renders a whole frame `r` gave (at most 64 × 64) again in bands of
/// `rows` rows, with memory sized as the program sizes it for bands, and
/// checks that the bands give the same pixels and the same outcome.
pub fn check_bands(list: &DisplayList<'_>, r: &Rendered, rows: u16) {
    if !r.whole {
        return;
    }
    let Ok(mut memory) = ListMemory::for_bands(list) else {
        assert!(r.result.is_err(), "needs refused a list the render drew");
        return;
    };
    let (w, h) = (list.width() as usize, list.height() as usize);
    let mut band = vec![Rgb565::BLACK; rows as usize * w];
    let mut out = Shipped {
        width: w,
        pixels: vec![Rgb565::new(1, 2, 3); w * h],
    };
    let (mut controller, table) = memory.band_parts();
    let banded = controller.render_bands(list, table, rows, &mut band, &mut out);
    match (&r.result, banded) {
        (Ok(_), Ok(_)) => assert!(
            out.pixels == r.pixels,
            "bands of {rows} rows differ from the full frame"
        ),
        (Err(_), Err(_)) => {}
        (full, bands) => panic!("the full frame gave {full:?}, bands of {rows} rows {bands:?}"),
    }
}
