//! The scanvert firmware image.
//!
//! Renders every display list of [`scenes::SCENES`] (embedded with
//! `include_bytes!`) into a 512 × 256 RGB565 frame buffer, and for each
//! frame prints its statistics, the instructions the render took, and
//! the frame's checksum, through semihosting. Each checksum is compared
//! with the host's render of the same list (the table in `scenes.rs`,
//! which a host test keeps current). The image exits QEMU with status 0
//! when every frame matches, 1 on a mismatch or a fault, and 101 on a
//! panic.
//!
//! | target | machine | counter |
//! |---|---|---|
//! | `thumbv7em-none-eabihf` | QEMU `mps2-an386`, Cortex-M4F | SysTick, 40 instructions a tick under `-icount shift=0` |
//! | `riscv32imc-unknown-none-elf` | QEMU `virt`, RV32IMC | `minstret`, exact under `-icount shift=0` |
//!
//! Features: `defmt` (Cortex-M only) logs everything through defmt over
//! semihosting instead of plain text (decode it with `defmt-print -e
//! IMAGE`); `discard` renders into a port that writes nothing, to count
//! everything but the pixel writes; `packed` renders into a frame of two
//! pixels per word (`src/packed.rs`), a measured proposal.
#![no_std]
#![no_main]
#![deny(missing_docs)]
#![deny(unsafe_code)]

#[cfg(all(feature = "defmt", not(target_arch = "arm")))]
compile_error!("the `defmt` feature of the image is for Cortex-M only");

#[cfg_attr(target_arch = "arm", path = "arm.rs")]
#[cfg_attr(target_arch = "riscv32", path = "riscv.rs")]
mod platform;

mod log;
mod scenes;

use core::convert::Infallible;
#[cfg(not(any(feature = "discard", feature = "packed")))]
use scanvert::checksum::frame_checksum;
use scanvert::controller::Controller;
use scanvert::display_list::DisplayList;
use scanvert::edge::Edge;
#[cfg(not(any(feature = "discard", feature = "packed")))]
use scanvert::framebuffer::FrameBuffer;
use scanvert::pixelcolor::{Rgb565, RgbColor};
use scanvert::port::SpanTarget;
use scanvert::scan::Rasterizer;

#[cfg(feature = "discard")]
mod discard;
#[cfg(feature = "packed")]
mod packed;

#[cfg(feature = "defmt")]
use defmt_semihosting as _;

/// The pixel format of the frame buffer.
pub type Pixel = Rgb565;
/// The colour every frame starts from, as on the host.
pub const BLACK: Pixel = Rgb565::BLACK;
/// Largest frame: 512 × 256 pixels (256 KiB of RGB565).
pub const FRAME_PIXELS: usize = 512 * 256;

/// What the frame memory is made of: pixels, or (feature `packed`) words
/// of two pixels.
#[cfg(not(feature = "packed"))]
pub type Cell = Pixel;
/// What the frame memory is made of.
#[cfg(feature = "packed")]
pub type Cell = u32;
/// Cells in the frame memory.
pub const CELLS: usize =
    FRAME_PIXELS * core::mem::size_of::<Pixel>() / core::mem::size_of::<Cell>();
/// A black cell.
#[cfg(not(feature = "packed"))]
pub const BLACK_CELL: Cell = BLACK;
/// A black cell.
#[cfg(feature = "packed")]
pub const BLACK_CELL: Cell = 0;

/// One embedded display list and the checksum of the host's render of it.
#[derive(Debug)]
pub struct Scene {
    /// Name, the list's file stem.
    pub name: &'static str,
    /// The binary display list.
    pub list: &'static [u8],
    /// `frame_checksum` of the host's frame.
    pub checksum: u32,
}

/// Instructions counted around one render.
#[derive(Clone, Copy, Debug)]
pub struct Cost {
    /// Ticks of the platform's counter.
    pub ticks: u64,
    /// `ticks` × instructions per tick.
    pub instructions: u64,
}

/// Loop length for the check of the counter's factor: about 4 million
/// instructions.
const CALIBRATION_LOOP: u32 = 1_999_999;

/// Checks the counter against a loop of known length: the instructions
/// it reports must be those of the loop, within two ticks plus the
/// instructions of the call and the reads (under 100).
fn calibrate(counter: &platform::Counter) -> bool {
    let t0 = counter.ticks();
    let expected = platform::known_loop(CALIBRATION_LOOP);
    let ticks = counter.ticks() - t0;
    let measured = ticks * platform::INSTRUCTIONS_PER_TICK;
    let slack = 2 * platform::INSTRUCTIONS_PER_TICK + 100;
    let ok = measured.abs_diff(expected) <= slack;
    log::calibration(expected, ticks, measured, ok);
    ok
}

/// Renders `list` into `target`, counting the instructions, and logs the
/// frame's statistics and cost. `None` (logged) if the render failed.
///
/// Never inlined, so that the code measured is compiled the same whatever
/// the rest of the image does around it: inlined into `run`, small edits
/// elsewhere changed the frame buffer's fill loop (the colour kept in a
/// register, or reloaded from the stack every pixel) and W5's count by
/// 30 %.
#[inline(never)]
fn render<T>(
    name: &str,
    list: &DisplayList<'_>,
    edges: &mut [Edge],
    target: &mut T,
    counter: &platform::Counter,
) -> Option<()>
where
    T: SpanTarget<Color = Pixel, Error = Infallible>,
{
    let mut controller = Controller::new(Rasterizer::new(edges));
    let t0 = counter.ticks();
    let rendered = controller.render(list, target);
    let ticks = counter.ticks() - t0;
    match rendered {
        Ok(stats) => {
            let cost = Cost {
                ticks,
                instructions: ticks * platform::INSTRUCTIONS_PER_TICK,
            };
            log::frame(name, list.width(), list.height(), &stats, cost);
            Some(())
        }
        Err(e) => {
            log::render_error(name, e);
            None
        }
    }
}

/// Renders one scene, times it, and compares its checksum. `true` when it
/// matches the host's.
///
/// With the `discard` feature the spans go to a port that writes nothing:
/// the count is then that of everything but the pixel writes, and there
/// is no frame to check.
fn frame(
    scene: &Scene,
    pixels: &mut [Cell],
    edges: &mut [Edge],
    counter: &platform::Counter,
) -> bool {
    let list = match DisplayList::new_checked(scene.list) {
        Ok(list) => list,
        Err(e) => {
            log::bad_list(scene.name, e);
            return false;
        }
    };
    let (w, h) = (list.width(), list.height());

    #[cfg(feature = "discard")]
    {
        let _ = pixels;
        let mut target = discard::Discard::new(w, h);
        render(scene.name, &list, edges, &mut target, counter).is_some()
    }

    #[cfg(all(feature = "packed", not(feature = "discard")))]
    {
        let words = pixels;
        let n = w as usize / 2 * h as usize;
        let Some(px) = words.get_mut(..n) else {
            log::too_big(scene.name, w, h);
            return false;
        };
        px.fill(0);
        let Some(mut frame) = packed::PackedFrame::new(px, w, h) else {
            log::too_big(scene.name, w, h);
            return false;
        };
        if render(scene.name, &list, edges, &mut frame, counter).is_none() {
            return false;
        }
        let checksum = frame.checksum();
        log::checksum(scene.name, checksum);
        if checksum != scene.checksum {
            log::mismatch(scene.name, scene.checksum);
            return false;
        }
        true
    }

    #[cfg(not(any(feature = "discard", feature = "packed")))]
    {
        let Some(px) = pixels.get_mut(..FrameBuffer::<Pixel>::buffer_len(w, h)) else {
            log::too_big(scene.name, w, h);
            return false;
        };
        px.fill(BLACK);
        let Some(mut fb) = FrameBuffer::new(px, w, h) else {
            log::too_big(scene.name, w, h);
            return false;
        };
        if render(scene.name, &list, edges, &mut fb, counter).is_none() {
            return false;
        }
        let checksum = frame_checksum(fb.pixels());
        log::checksum(scene.name, checksum);
        if checksum != scene.checksum {
            log::mismatch(scene.name, scene.checksum);
            return false;
        }
        true
    }
}

/// Everything the image does; `true` when every frame matched.
pub fn run() -> bool {
    log::start(
        platform::MACHINE,
        platform::COUNTER,
        platform::INSTRUCTIONS_PER_TICK,
    );
    let Some(counter) = platform::Counter::start() else {
        log::fault("the instruction counter is taken");
        return false;
    };
    let mut ok = calibrate(&counter);
    let Some(pixels) = platform::frame_memory() else {
        log::fault("the frame memory is taken");
        return false;
    };
    let mut edges = [Edge::EMPTY; scenes::EDGE_SLOTS];
    let mut matched = 0;
    for scene in scenes::SCENES {
        if frame(scene, pixels, &mut edges, &counter) {
            matched += 1;
        } else {
            ok = false;
        }
    }
    log::summary(matched, scenes::SCENES.len(), ok);
    ok
}

/// Ends the program: QEMU exits with status 0 if `ok`, else 1.
pub fn exit(ok: bool) -> ! {
    semihosting::process::exit(if ok { 0 } else { 1 })
}
