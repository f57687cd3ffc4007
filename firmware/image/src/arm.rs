//! Cortex-M4F on QEMU's `mps2-an386`: start-up, the instruction counter
//! and the frame memory.
//!
//! QEMU models no cycles. With `-icount shift=0` every executed
//! instruction advances virtual time by 1 ns, and SysTick, clocked from
//! the core at 25 MHz on this board, advances one tick per 40
//! instructions. The counts repeat exactly from run to run.

use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::{syst::SystClkSource, SCB, SYST};
use cortex_m_rt::{entry, exception};

/// Instructions per tick of [`Counter`] (under `-icount shift=0`).
pub const INSTRUCTIONS_PER_TICK: u64 = 40;
/// What the counter counts, for the log.
pub const COUNTER: &str = "SysTick from the core clock";
/// The machine, for the log.
pub const MACHINE: &str = "Cortex-M4F, QEMU mps2-an386";

/// SysTick counts down from this value; a wrap is `RELOAD + 1` ticks.
const RELOAD: u32 = 0x00ff_ffff;

/// Wraps of SysTick since [`Counter::start`], counted by its exception.
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    // A load and a store, not `fetch_add`: thumbv6m (the `pico` variant)
    // has no atomic read-modify-write, and nothing else writes it.
    WRAPS.store(WRAPS.load(Ordering::Relaxed) + 1, Ordering::Relaxed);
}

#[entry]
fn main() -> ! {
    crate::exit(crate::run())
}

/// SysTick, free-running from the core clock, extended to 64 bits by
/// counting its wraps.
pub struct Counter {
    _syst: SYST,
}

impl Counter {
    /// Starts SysTick, or `None` if it was already taken.
    pub fn start() -> Option<Counter> {
        let mut syst = cortex_m::Peripherals::take()?.SYST;
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        // The write to the current value clears it; it takes the reload
        // value on the next tick. Until then it reads 0, which would look
        // like a whole wrap.
        while SYST::get_current() == 0 {}
        Some(Counter { _syst: syst })
    }

    /// Ticks since [`start`](Self::start).
    ///
    /// A wrap can happen between reading the wrap count and the counter,
    /// and its exception can still be pending: a pending SysTick means the
    /// counter has wrapped once more than counted, and it is read again
    /// after the wrap. If the exception ran in between, the read repeats.
    pub fn ticks(&self) -> u64 {
        loop {
            let wraps = WRAPS.load(Ordering::Relaxed);
            let mut current = SYST::get_current();
            let mut counted = wraps as u64;
            if SCB::is_pendst_pending() {
                current = SYST::get_current();
                counted += 1;
            }
            if WRAPS.load(Ordering::Relaxed) == wraps {
                return counted * (RELOAD as u64 + 1) + (RELOAD - current) as u64;
            }
        }
    }
}

/// A loop of a known number of instructions: `cortex_m::asm::delay(n)`
/// runs `subs; bne` `n + 1` times. Returns the instructions it executes
/// in the loop for `n`.
pub fn known_loop(n: u32) -> u64 {
    cortex_m::asm::delay(n);
    2 * (n as u64 + 1)
}

/// The frame memory: 512 × 256 RGB565 in `.bss`, handed out once.
pub fn frame_memory() -> Option<&'static mut [crate::Cell; crate::CELLS]> {
    cortex_m::singleton!(: [crate::Cell; crate::CELLS] = [crate::BLACK_CELL; crate::CELLS])
}

/// The memory of the 3D layer, in `.bss`, handed out once.
pub fn memory_3d() -> Option<&'static mut crate::Memory3d> {
    cortex_m::singleton!(: crate::Memory3d = crate::EMPTY_3D)
}

/// The band path's edge table and band buffer, in `.bss`, handed out
/// once; in parts, so that no more than one is made on the stack at a
/// time.
#[cfg(feature = "bands")]
pub fn table_memory() -> Option<crate::bands::Table> {
    use crate::bands::{BAND_PIXELS, TABLE_EDGES, TABLE_LINES, TABLE_POLYGONS};
    use scanvert::raster::{edge::Edge, line::Line, table::TablePolygon};
    Some(crate::bands::Table {
        polygons: cortex_m::singleton!(: [TablePolygon; TABLE_POLYGONS] = [TablePolygon::EMPTY; TABLE_POLYGONS])?,
        index: cortex_m::singleton!(: [u32; 2 * TABLE_POLYGONS] = [0; 2 * TABLE_POLYGONS])?,
        edges: cortex_m::singleton!(: [Edge; TABLE_EDGES] = [Edge::EMPTY; TABLE_EDGES])?,
        lines: cortex_m::singleton!(: [Option<Line>; TABLE_LINES] = [None; TABLE_LINES])?,
        band: cortex_m::singleton!(: [u32; BAND_PIXELS / 2] = [0; BAND_PIXELS / 2])?,
    })
}

/// The `budget` variant's memory (`src/budget.rs`), in `.bss`, handed
/// out once; each part a static of its own, named `BUDGET_*` (measure.sh
/// reads their sizes), so that no more than one is made on the stack at a
/// time.
pub fn budget_memory() -> Option<crate::budget::Memory> {
    use crate::budget::{set, Storage, EMPTY};
    use scanvert::raster::{edge::Edge, line::Line, table::TablePolygon};
    Some(crate::budget::Memory {
        storage: cortex_m::singleton!(BUDGET_SCENE: Storage = EMPTY)?,
        edges: cortex_m::singleton!(BUDGET_EDGES: [Edge; set::RASTER_EDGES] = [Edge::EMPTY; set::RASTER_EDGES])?,
        polygons: cortex_m::singleton!(BUDGET_TABLE_POLYGONS: [TablePolygon; set::TABLE_POLYGONS] = [TablePolygon::EMPTY; set::TABLE_POLYGONS])?,
        index: cortex_m::singleton!(BUDGET_TABLE_INDEX: [u32; 2 * set::TABLE_POLYGONS] = [0; 2 * set::TABLE_POLYGONS])?,
        table_edges: cortex_m::singleton!(BUDGET_TABLE_EDGES: [Edge; set::TABLE_EDGES] = [Edge::EMPTY; set::TABLE_EDGES])?,
        lines: cortex_m::singleton!(BUDGET_TABLE_LINES: [Option<Line>; set::TABLE_LINES] = [None; set::TABLE_LINES])?,
        band: cortex_m::singleton!(BUDGET_BAND: [u32; set::BAND_PIXELS / 2] = [0; set::BAND_PIXELS / 2])?,
    })
}

/// The mesh frames' memory (`src/meshes.rs`), in `.bss`, handed out once;
/// each part a static of its own, so that no more than one is made on the
/// stack at a time.
#[cfg(not(feature = "discard"))]
pub fn mesh_memory() -> Option<crate::meshes::Memory> {
    use crate::meshes::{set, Storage, EMPTY};
    use scanvert::geometry::ViewPoint;
    use scanvert::raster::edge::Edge;
    Some(crate::meshes::Memory {
        storage: cortex_m::singleton!(MESH_SCENE: Storage = EMPTY)?,
        vertices: cortex_m::singleton!(MESH_VERTICES: [ViewPoint; set::VERTEX_SLOTS] = [ViewPoint::EMPTY; set::VERTEX_SLOTS])?,
        edges: cortex_m::singleton!(MESH_EDGES: [Edge; set::RASTER_EDGES] = [Edge::EMPTY; set::RASTER_EDGES])?,
        band: cortex_m::singleton!(MESH_BAND: [u32; set::BAND_PIXELS / 2] = [0; set::BAND_PIXELS / 2])?,
    })
}
