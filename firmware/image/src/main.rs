//! The scanvert firmware image.
//!
//! Renders every display list of [`scenes::SCENES`] (embedded with
//! `include_bytes!`) into a 512 × 256 RGB565 frame buffer, and for each
//! frame prints its statistics, the instructions the render took, and
//! the frame's checksum, through semihosting. A list with `poly3`s is
//! also rendered stage by stage (cut into trapezoids, then resolved and
//! decoded), each stage counted on its own. Each checksum is compared
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
#[cfg(all(feature = "bands", any(feature = "discard", feature = "packed")))]
compile_error!("the `bands` feature of the image renders plain RGB565 bands only");

#[cfg_attr(target_arch = "arm", path = "arm.rs")]
#[cfg_attr(target_arch = "riscv32", path = "riscv.rs")]
mod platform;

#[cfg(feature = "bands")]
mod bands;
mod log;
mod scenes;

use core::convert::Infallible;
use scanvert::controller::{front_facing, Controller, Storage3d, DEFAULT_COLOR};
use scanvert::display_list::{Command, DisplayList};
use scanvert::pixelcolor::{Rgb565, RgbColor};
#[cfg(not(any(feature = "discard", feature = "packed")))]
use scanvert::port::checksum::frame_checksum;
#[cfg(not(any(feature = "discard", feature = "packed")))]
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::port::SpanTarget;
use scanvert::raster::clip::ClipRect;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment, StoreMemory, TrapezoidStore};
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};
use scanvert::visible::{self, Active, Cover, Resolve, VisibleStats, Workspace};

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

/// The memory of the 3D layer, sized for the scenes by `scenes.rs`:
/// about 60 KiB, in `.bss`.
pub struct Memory3d {
    trapezoids: [Trapezoid; scenes::TRAPEZOID_SLOTS],
    faces: [Face; scenes::FACE_SLOTS],
    segments: [Segment; 1],
    rows: [u16; scenes::INDEX_ROWS],
    edges: [EdgeSlot; scenes::EDGE_SLOTS],
    active: [Active; scenes::ACTIVE_SLOTS],
    cover: [Cover; scenes::ACTIVE_SLOTS],
    runs: [Run; scenes::RUN_SLOTS],
}

impl Memory3d {
    /// Every slot unused.
    pub const EMPTY: Memory3d = Memory3d {
        trapezoids: [Trapezoid::EMPTY; scenes::TRAPEZOID_SLOTS],
        faces: [Face::EMPTY; scenes::FACE_SLOTS],
        segments: [Segment::EMPTY; 1],
        rows: [0; scenes::INDEX_ROWS],
        edges: [EdgeSlot::EMPTY; scenes::EDGE_SLOTS],
        active: [Active::EMPTY; scenes::ACTIVE_SLOTS],
        cover: [Cover::EMPTY; scenes::ACTIVE_SLOTS],
        runs: [Run::EMPTY; scenes::RUN_SLOTS],
    };

    /// The store's memory, the active list, the cover array and the runs.
    fn parts(&mut self) -> (StoreMemory<'_>, &mut [Active], &mut [Cover], &mut [Run]) {
        let store = StoreMemory {
            trapezoids: &mut self.trapezoids,
            faces: &mut self.faces,
            segments: &mut self.segments,
            rows: &mut self.rows,
            edges: &mut self.edges,
        };
        (store, &mut self.active, &mut self.cover, &mut self.runs)
    }
}

/// Instructions of the stages of a 3D layer.
#[derive(Clone, Copy, Debug)]
pub struct Stages {
    /// `poly3`s drawn (front-facing).
    pub faces: u32,
    /// Trapezoids they were cut into.
    pub trapezoids: u32,
    /// Cutting every drawn `poly3` into trapezoids in the store (plane,
    /// edges, trapezoids, the scan-line index).
    pub cut: u64,
    /// `Workspace::check`: the most trapezoids on a row.
    pub check: u64,
    /// Resolving the rows and decoding the runs into the frame.
    pub resolve: u64,
    /// What the visible-surface stage did.
    pub visible: VisibleStats,
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
    mut controller: Controller<'_>,
    target: &mut T,
    counter: &platform::Counter,
) -> Option<()>
where
    T: SpanTarget<Color = Pixel, Error = Infallible>,
{
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

/// Renders the 3D layer of `list` into `target` stage by stage, as the
/// controller does (`poly3`s with the colour and clip in force, culled by
/// `front_facing`, cut into one segment of the store, then resolved by
/// crossing points and decoded with the background left as it is),
/// counting each stage, and logs the counts. `None` (logged) if a stage
/// failed.
///
/// Never inlined, for the reason given at [`render`].
#[inline(never)]
fn stages<T>(
    name: &str,
    list: &DisplayList<'_>,
    mem: &mut Memory3d,
    target: &mut T,
    counter: &platform::Counter,
) -> Option<()>
where
    T: SpanTarget<Color = Pixel, Error = Infallible>,
{
    let (tw, th) = target.size();
    let (w, h) = (list.width().min(tw), list.height().min(th));
    let (store_memory, active, cover, runs) = mem.parts();
    let t0 = counter.ticks();
    let Ok(mut store) = TrapezoidStore::new(store_memory, w, h) else {
        log::stage_error(name, "the 3D store does not fit the frame");
        return None;
    };
    let mut clip = ClipRect::full(w, h);
    let mut color = DEFAULT_COLOR;
    let (mut faces, mut trapezoids) = (0u32, 0u32);
    for (_, cmd) in list.commands() {
        match cmd {
            Command::Clip(win) => clip = ClipRect::from_window(win, w, h),
            Command::Color(c) => color = c,
            Command::Poly3(v) if front_facing(&v) => {
                let Ok(n) = store.add_polygon(0, v.iter(), color, &clip) else {
                    log::stage_error(name, "the 3D store is too small");
                    return None;
                };
                faces += 1;
                trapezoids += n;
            }
            _ => {}
        }
    }
    let t1 = counter.ticks();
    let mut ws = Workspace::new(active, cover, runs);
    if ws.check(&store).is_err() {
        log::stage_error(name, "the active list is too small");
        return None;
    }
    let t2 = counter.ticks();
    let drawn = visible::draw(&store, &mut ws, Resolve::Crossing, target, None);
    let t3 = counter.ticks();
    let Ok((visible, _)) = drawn else {
        log::stage_error(name, "resolving failed");
        return None;
    };
    let per = platform::INSTRUCTIONS_PER_TICK;
    log::stages(
        name,
        &Stages {
            faces,
            trapezoids,
            cut: (t1 - t0) * per,
            check: (t2 - t1) * per,
            resolve: (t3 - t2) * per,
            visible,
        },
    );
    Some(())
}

/// A frame the image renders into: its checksum, when it keeps pixels.
trait Checked: SpanTarget<Color = Pixel, Error = Infallible> {
    fn checksum(&self) -> Option<u32>;
}

#[cfg(feature = "discard")]
impl Checked for discard::Discard {
    fn checksum(&self) -> Option<u32> {
        None
    }
}

#[cfg(all(feature = "packed", not(feature = "discard")))]
impl Checked for packed::PackedFrame<'_> {
    fn checksum(&self) -> Option<u32> {
        Some(packed::PackedFrame::checksum(self))
    }
}

#[cfg(not(any(feature = "discard", feature = "packed")))]
impl Checked for FrameBuffer<'_, Pixel> {
    fn checksum(&self) -> Option<u32> {
        Some(frame_checksum(self.pixels()))
    }
}

/// Renders `list` into `target` (which starts black) with the
/// controller, and logs and compares the checksum; for a list with
/// `poly3`s, first renders it stage by stage into the same target and
/// compares that frame's checksum too. `true` when all match.
fn render_and_check<T: Checked>(
    scene: &Scene,
    list: &DisplayList<'_>,
    edges: &mut [Edge],
    mem: &mut Memory3d,
    target: &mut T,
    counter: &platform::Counter,
) -> bool {
    let three = list.commands().any(|(_, c)| matches!(c, Command::Poly3(_)));
    if three {
        if stages(scene.name, list, mem, target, counter).is_none() {
            return false;
        }
        if let Some(sum) = target.checksum() {
            if sum != scene.checksum {
                log::stage_mismatch(scene.name, sum, scene.checksum);
                return false;
            }
        }
        let _ = target.clear(BLACK);
    }
    let rendered = if three {
        let (store, active, cover, runs) = mem.parts();
        let storage = Storage3d {
            store,
            active,
            cover,
            runs,
            resolve: Resolve::Crossing,
        };
        let controller = Controller::new(Rasterizer::new(edges)).with_3d(storage);
        render(scene.name, list, controller, target, counter)
    } else {
        let controller = Controller::new(Rasterizer::new(edges));
        render(scene.name, list, controller, target, counter)
    };
    if rendered.is_none() {
        return false;
    }
    let Some(sum) = target.checksum() else {
        return true;
    };
    log::checksum(scene.name, sum);
    if sum != scene.checksum {
        log::mismatch(scene.name, scene.checksum);
        return false;
    }
    true
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
    mem: &mut Memory3d,
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
        render_and_check(scene, &list, edges, mem, &mut target, counter)
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
        render_and_check(scene, &list, edges, mem, &mut frame, counter)
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
        render_and_check(scene, &list, edges, mem, &mut fb, counter)
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
    let Some(mem) = platform::memory_3d() else {
        log::fault("the 3D memory is taken");
        return false;
    };
    let mut edges = [Edge::EMPTY; scenes::EDGE_SLOTS];
    let mut matched = 0;
    for scene in scenes::SCENES {
        if frame(scene, pixels, &mut edges, mem, &counter) {
            matched += 1;
        } else {
            ok = false;
        }
    }
    // The same lists again, band by band, checked against the same sums.
    #[cfg(feature = "bands")]
    {
        let Some(mut table) = platform::table_memory() else {
            log::fault("the edge table is taken");
            return false;
        };
        for scene in scenes::SCENES {
            ok &= bands::measure(scene, pixels, &mut edges, mem, &mut table, &counter);
        }
    }
    log::summary(matched, scenes::SCENES.len(), ok);
    ok
}

/// Ends the program: QEMU exits with status 0 if `ok`, else 1.
pub fn exit(ok: bool) -> ! {
    semihosting::process::exit(if ok { 0 } else { 1 })
}
