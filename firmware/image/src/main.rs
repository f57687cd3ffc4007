//! The scanvert firmware image.
//!
//! Renders every display list of [`scenes::SCENES`] (embedded with
//! `include_bytes!`) into a 512 × 256 RGB565 frame buffer, and for each
//! frame prints its statistics, the instructions the render took, and
//! the frame's checksum, through semihosting. For a list with `poly3`s
//! the stages of the 3D layer (cut into trapezoids, checked, resolved and
//! decoded) are counted on their own too, through the controller's stage
//! hook (`Controller::render_with`). Each checksum is compared
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
//! everything but the pixel writes; `halfword` renders into
//! `FrameBuffer<Rgb565>`, one half-word store a pixel, instead of the
//! default `PackedFrameBuffer` (two pixels to a word, written a word at a
//! time), to compare the two; `rows` (with `bands`) composes every list again
//! one row at a time as colour runs and prints each row's instructions (`src/rows.rs`), the
//! measurements of the simulator's cost model of racing the beam;
//! `budget` (and `budget-poly3`) renders instead only the lists of a RAM
//! budget, band by band with no frame buffer, in statics sized exactly
//! for them (`src/budget.rs`).
//!
//! After the lists of [`scenes::SCENES`], the mesh lists of
//! `scenes::meshes` are rendered in 16-row bands with no frame buffer
//! (`src/meshes.rs`; not with `discard`).
#![no_std]
#![no_main]
#![deny(missing_docs)]
#![deny(unsafe_code)]

#[cfg(all(feature = "defmt", not(target_arch = "arm")))]
compile_error!("the `defmt` feature of the image is for Cortex-M only");
#[cfg(all(feature = "bands", feature = "discard"))]
compile_error!("the `bands` feature of the image checks the bands' pixels: not with `discard`");
#[cfg(all(
    feature = "budget",
    any(
        feature = "defmt",
        feature = "discard",
        feature = "halfword",
        feature = "bands"
    )
))]
compile_error!("the `budget` variant of the image is built alone: its statics are all it measures");

#[cfg(all(
    feature = "pico",
    any(
        feature = "defmt",
        feature = "discard",
        feature = "halfword",
        feature = "bands",
        feature = "budget"
    )
))]
compile_error!("the `pico` variant of the image is built alone");

#[cfg_attr(target_arch = "arm", path = "arm.rs")]
#[cfg_attr(target_arch = "riscv32", path = "riscv.rs")]
mod platform;

#[cfg(feature = "bands")]
mod bands;
mod budget;
mod log;
#[cfg(not(feature = "discard"))]
mod meshes;
#[cfg(feature = "pico")]
mod pico;
#[cfg(feature = "rows")]
mod rows;
mod scenes;

use core::convert::Infallible;
use scanvert::controller::{Controller, RenderStats};
use scanvert::display_list::{Command, DisplayList};
use scanvert::pixelcolor::{Rgb565, RgbColor};
#[cfg(all(feature = "halfword", not(feature = "discard")))]
use scanvert::port::checksum::frame_checksum;
#[cfg(all(feature = "halfword", not(feature = "discard")))]
use scanvert::port::framebuffer::FrameBuffer;
#[cfg(not(any(feature = "discard", feature = "halfword")))]
use scanvert::port::PackedFrameBuffer;
use scanvert::port::SpanTarget;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::scene::{SceneStorage, Stage};
use scanvert::visible::{Resolve, VisibleStats};

#[cfg(feature = "discard")]
mod discard;

#[cfg(feature = "defmt")]
use defmt_semihosting as _;

/// The pixel format of the frame buffer.
pub type Pixel = Rgb565;
/// The colour every frame starts from, as on the host.
pub const BLACK: Pixel = Rgb565::BLACK;
/// Chains the pixels of band words in a panel's wire order
/// (`scanvert::port::packed_band`: each pixel high byte first) into
/// `sum`, as `Checksum::write_pixels` chains the same `pixels` pixels
/// (the high half of the last word is no pixel when they are odd).
pub fn write_wire(sum: &mut scanvert::port::checksum::Checksum, words: &[u32], pixels: usize) {
    let (whole, last) = words.split_at((pixels / 2).min(words.len()));
    for w in whole {
        let [a, b, c, d] = w.to_le_bytes();
        sum.write(&[b, a, d, c]);
    }
    if pixels % 2 == 1 {
        if let Some(w) = last.first() {
            let [a, b, _, _] = w.to_le_bytes();
            sum.write(&[b, a]);
        }
    }
}
/// Largest frame: 512 × 256 pixels (256 KiB of RGB565).
pub const FRAME_PIXELS: usize = 512 * 256;

/// What the frame memory is made of: words of two pixels, or (feature
/// `halfword`) pixels.
#[cfg(not(feature = "halfword"))]
pub type Cell = u32;
/// What the frame memory is made of.
#[cfg(feature = "halfword")]
pub type Cell = Pixel;
/// Cells in the frame memory.
pub const CELLS: usize =
    FRAME_PIXELS * core::mem::size_of::<Pixel>() / core::mem::size_of::<Cell>();
/// A black cell.
#[cfg(feature = "halfword")]
pub const BLACK_CELL: Cell = BLACK;
/// A black cell.
#[cfg(not(feature = "halfword"))]
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

/// The memory of the 3D layer, sized for the scenes by `scenes.rs` (from
/// what each list needs): about 60 KiB, in `.bss`. One segment, no
/// labels.
pub type Memory3d = SceneStorage<
    { scenes::TRAPEZOID_SLOTS },
    { scenes::FACE_SLOTS },
    1,
    { scenes::INDEX_ROWS },
    { scenes::EDGE_SLOTS },
    { scenes::ACTIVE_SLOTS },
    { scenes::RUN_SLOTS },
    0,
    0,
>;

/// Every slot of the 3D memory unused.
pub const EMPTY_3D: Memory3d = Memory3d::new();

/// Instructions of the stages of a 3D layer.
#[derive(Clone, Copy, Debug)]
pub struct Stages {
    /// `poly3`s drawn (front-facing).
    pub faces: u32,
    /// Trapezoids they were cut into.
    pub trapezoids: u32,
    /// Executing the 3D commands: every `poly3` culled, and every drawn
    /// one cut into trapezoids in the store (plane, edges, trapezoids, the
    /// scan-line index): from [`Stage::Start`] to [`Stage::Cut`].
    pub cut: u64,
    /// `Workspace::check`, the most trapezoids on a row: to
    /// [`Stage::Checked`].
    pub check: u64,
    /// Resolving the rows and decoding the runs into the frame: from
    /// [`Stage::Painted`] to [`Stage::Resolved`].
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
/// the rest of the image does around it: inlined into `run`, the frame
/// buffer's fill loop depends on the registers left to it there (the
/// colour kept in a register, or reloaded from the stack every pixel),
/// which moves W5's count by as much as 30 %.
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
    logged(name, list, rendered, ticks)
}

/// [`render`] for a list with a 3D layer, counting its stages too, where
/// the controller's hook reports their ends, and logging them first.
#[inline(never)]
fn render_stages<T>(
    name: &str,
    list: &DisplayList<'_>,
    mut controller: Controller<'_>,
    target: &mut T,
    counter: &platform::Counter,
) -> Option<()>
where
    T: SpanTarget<Color = Pixel, Error = Infallible>,
{
    // The counter's ticks at each stage, by `Stage as usize`.
    let mut at = [0u64; 6];
    let t0 = counter.ticks();
    let rendered = controller.render_with(list, target, &mut |s: Stage| {
        at[s as usize] = counter.ticks()
    });
    let ticks = counter.ticks() - t0;
    if let Ok(stats) = &rendered {
        log_stages(name, stats, &at);
    }
    logged(name, list, rendered, ticks)
}

/// Logs a render's statistics and cost, or its error (then `None`).
fn logged(
    name: &str,
    list: &DisplayList<'_>,
    rendered: Result<RenderStats, scanvert::controller::RenderError<Infallible>>,
    ticks: u64,
) -> Option<()> {
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

/// Logs the stages of a 3D layer from the ticks at each [`Stage`].
fn log_stages(name: &str, stats: &RenderStats, at: &[u64; 6]) {
    let per = platform::INSTRUCTIONS_PER_TICK;
    let span = |from: Stage, to: Stage| at[to as usize].saturating_sub(at[from as usize]) * per;
    log::stages(
        name,
        &Stages {
            faces: stats.poly3,
            trapezoids: stats.trapezoids,
            cut: span(Stage::Start, Stage::Cut),
            check: span(Stage::Cut, Stage::Checked),
            resolve: span(Stage::Painted, Stage::Resolved),
            visible: stats.visible,
        },
    );
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

#[cfg(not(any(feature = "discard", feature = "halfword")))]
impl Checked for PackedFrameBuffer<'_, Pixel> {
    fn checksum(&self) -> Option<u32> {
        Some(PackedFrameBuffer::checksum(self))
    }
}

#[cfg(all(feature = "halfword", not(feature = "discard")))]
impl Checked for FrameBuffer<'_, Pixel> {
    fn checksum(&self) -> Option<u32> {
        Some(frame_checksum(self.pixels()))
    }
}

/// Renders `list` into `target` (which starts black) with the
/// controller, for a list with `poly3`s stage by stage, and logs and
/// compares the checksum. `true` when it matches.
fn render_and_check<T: Checked>(
    (scene, resolve): (&Scene, Resolved),
    list: &DisplayList<'_>,
    edges: &mut [Edge],
    mem: &mut Memory3d,
    target: &mut T,
    counter: &platform::Counter,
) -> bool {
    let three = list.commands().any(|(_, c)| matches!(c, Command::Poly3(_)));
    let rendered = if three {
        let controller = Controller::new(Rasterizer::new(edges))
            .with_3d(mem.as_memory())
            .with_resolve(resolve.mode);
        render_stages(resolve.name, list, controller, target, counter)
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
    log::checksum(resolve.name, sum);
    if sum != scene.checksum {
        log::mismatch(resolve.name, scene.checksum);
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
    (scene, resolve): (&Scene, Resolved),
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
        render_and_check((scene, resolve), &list, edges, mem, &mut target, counter)
    }

    #[cfg(not(any(feature = "discard", feature = "halfword")))]
    {
        let n = PackedFrameBuffer::<Pixel>::words_len(w, h);
        let Some(words) = pixels.get_mut(..n) else {
            log::too_big(scene.name, w, h);
            return false;
        };
        words.fill(BLACK_CELL);
        let Some(mut frame) = PackedFrameBuffer::new(words, w, h) else {
            log::too_big(scene.name, w, h);
            return false;
        };
        render_and_check((scene, resolve), &list, edges, mem, &mut frame, counter)
    }

    #[cfg(all(feature = "halfword", not(feature = "discard")))]
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
        render_and_check((scene, resolve), &list, edges, mem, &mut fb, counter)
    }
}

/// W5's pixels in words, two pixels a word: 95,268 pixels.
#[cfg(not(feature = "halfword"))]
const W5_WORDS: usize = 47_634;

/// Counts `[u32]::fill` of W5's words, what W5's frame is compared with,
/// in two forms, each a call that is not inlined, counted as a frame is:
/// on a slice, whose length is known only at run time, as a span's is;
/// and on an array of that length, which LLVM compiles to a loop of
/// double-word stores. The words are the frame memory's, cleared again
/// before each frame.
#[cfg(not(feature = "halfword"))]
fn fill_baselines(cells: &mut [Cell; CELLS], counter: &platform::Counter) {
    #[inline(never)]
    fn slice(words: &mut [u32], v: u32) {
        words.fill(v);
    }
    #[inline(never)]
    fn array(words: &mut [u32; W5_WORDS], v: u32) {
        words.fill(v);
    }
    let Some(words) = cells.first_chunk_mut::<W5_WORDS>() else {
        return;
    };
    // Opaque to the compiler, so that neither call is folded into a
    // constant store pattern or dropped.
    let v = core::hint::black_box(0x1234_5678);
    let t0 = counter.ticks();
    slice(core::hint::black_box(&mut words[..]), v);
    log::fill("u32-slice", W5_WORDS, counter.ticks() - t0);
    let t0 = counter.ticks();
    array(core::hint::black_box(words), v);
    log::fill("u32-array", W5_WORDS, counter.ticks() - t0);
}

/// Checks the packed port's long runs on this core, where they take the
/// library's store-multiple path (Thumb-2 targets): a one-row frame of
/// every even width from 2 to 640 pixels (1 to 320 words), at each of
/// four word offsets, is cleared over a guard pattern, and every word
/// of the slice is compared with what it must hold. Not counted.
#[cfg(not(any(feature = "discard", feature = "halfword")))]
fn check_fills() -> bool {
    use scanvert::pixelcolor::raw::{RawData, RawU16};
    const WORDS: usize = 328;
    const GUARD: u32 = 0xa5a5_5a5a;
    let color = Rgb565::new(3, 40, 17);
    let c = u32::from(RawU16::from(color).into_inner());
    let pair = c | c << 16;
    let mut words = [0u32; WORDS];
    for at in 0..4 {
        for n in 1..=320 {
            for w in words.iter_mut() {
                *w = core::hint::black_box(GUARD);
            }
            let Some(mut fb) =
                PackedFrameBuffer::<Pixel>::new(&mut words[at..at + n], 2 * n as u16, 1)
            else {
                return false;
            };
            let _ = fb.clear(color);
            for (i, &w) in words.iter().enumerate() {
                let want = if (at..at + n).contains(&i) {
                    pair
                } else {
                    GUARD
                };
                if w != want {
                    log::fault("a run of the packed port's words was stored wrongly");
                    return false;
                }
            }
        }
    }
    true
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
    // The budget variant renders its own lists, and nothing here: the
    // frame memory and the rest are then never made.
    if cfg!(feature = "budget") {
        return budget::run(&counter, ok);
    }
    #[cfg(feature = "pico")]
    if cfg!(feature = "pico") {
        return pico::run(&counter, ok);
    }
    let Some(pixels) = platform::frame_memory() else {
        log::fault("the frame memory is taken");
        return false;
    };
    let Some(mem) = platform::memory_3d() else {
        log::fault("the 3D memory is taken");
        return false;
    };
    #[cfg(not(feature = "halfword"))]
    fill_baselines(pixels, &counter);
    #[cfg(not(any(feature = "discard", feature = "halfword")))]
    {
        ok &= check_fills();
    }
    let mut edges = [Edge::EMPTY; scenes::EDGE_SLOTS];
    let mut matched = 0;
    let mut frames = 0;
    for scene in scenes::SCENES {
        for resolve in Resolved::of(scene) {
            frames += 1;
            if frame((scene, resolve), pixels, &mut edges, mem, &counter) {
                matched += 1;
            } else {
                ok = false;
            }
        }
    }
    // The mesh lists, band by band with no frame buffer.
    #[cfg(not(feature = "discard"))]
    {
        ok &= meshes::run(&counter, &mut matched, &mut frames);
    }
    // The same lists again, band by band, checked against the same sums.
    #[cfg(feature = "bands")]
    {
        let Some(mut table) = platform::table_memory() else {
            log::fault("the edge table is taken");
            return false;
        };
        for scene in scenes::SCENES {
            ok &= bands::measure(scene, &mut edges, mem, &mut table, &counter);
        }
        // Each list again, one row at a time, each row counted.
        #[cfg(feature = "rows")]
        {
            for scene in scenes::SCENES {
                ok &= rows::measure(scene, &mut edges, mem, &mut table, &counter);
            }
            ok &= rows::measure_empty(&mut edges, mem, &mut table, &counter);
            rows::measure_inserts(&counter);
        }
    }
    log::summary(matched, frames, ok);
    ok
}

/// How a list's 3D layer is resolved, and the name its frame is logged
/// under.
#[derive(Clone, Copy)]
struct Resolved {
    mode: Resolve,
    name: &'static str,
}

impl Resolved {
    /// Every list with the default resolve ([`Resolve::Auto`], which
    /// paints the two 170-face lists), under its own name; those two
    /// again with the sweep's crossing points ([`Resolve::Crossing`]),
    /// under their names with `-crossing`.
    fn of(scene: &Scene) -> impl Iterator<Item = Resolved> {
        let swept = match scene.name {
            "poly3-layered" => Some("poly3-layered-crossing"),
            "poly3-tilted" => Some("poly3-tilted-crossing"),
            _ => None,
        };
        let first = Resolved {
            mode: Resolve::default(),
            name: scene.name,
        };
        core::iter::once(first).chain(swept.map(|name| Resolved {
            mode: Resolve::Crossing,
            name,
        }))
    }
}

/// Ends the program: QEMU exits with status 0 if `ok`, else 1.
pub fn exit(ok: bool) -> ! {
    semihosting::process::exit(if ok { 0 } else { 1 })
}
