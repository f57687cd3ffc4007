//! RV32IMC on QEMU's `virt` board (a stand-in for an FPGA soft-core):
//! start-up, the instruction counter and the frame memory.
//!
//! The counter is `minstret`, the machine's retired-instruction counter.
//! Under `-icount shift=0` QEMU derives it from its instruction count, so
//! it is exact and repeats from run to run.

use riscv_rt::entry;

/// Instructions per tick of [`Counter`].
pub const INSTRUCTIONS_PER_TICK: u64 = 1;
/// What the counter counts, for the log.
pub const COUNTER: &str = "minstret";
/// The machine, for the log.
pub const MACHINE: &str = "RV32IMC, QEMU virt";

#[entry]
fn main() -> ! {
    crate::exit(crate::run())
}

/// `minstret`, 64 bits.
#[derive(Debug)]
pub struct Counter(());

impl Counter {
    /// The counter runs from reset; nothing to start.
    pub fn start() -> Option<Counter> {
        Some(Counter(()))
    }

    /// Instructions retired since reset.
    pub fn ticks(&self) -> u64 {
        riscv::register::minstret::read64()
    }
}

/// A loop of a known number of instructions: `riscv::asm::delay(n)` runs
/// `addi; bne` `1 + n / 2` times. Returns the instructions it executes in
/// the loop for `n`.
pub fn known_loop(n: u32) -> u64 {
    riscv::asm::delay(n);
    2 * (1 + n as u64 / 2)
}

/// The frame memory: 512 × 256 RGB565 in `.bss`, handed out once.
pub fn frame_memory() -> Option<&'static mut [crate::Cell; crate::CELLS]> {
    riscv::singleton!(: [crate::Cell; crate::CELLS] = [crate::BLACK_CELL; crate::CELLS])
}

/// The memory of the 3D layer, in `.bss`, handed out once.
pub fn memory_3d() -> Option<&'static mut crate::Memory3d> {
    riscv::singleton!(: crate::Memory3d = crate::EMPTY_3D)
}

/// The band path's edge table and band buffer, in `.bss`, handed out
/// once; in parts, so that no more than one is made on the stack at a
/// time.
#[cfg(feature = "bands")]
pub fn table_memory() -> Option<crate::bands::Table> {
    use crate::bands::{BAND_PIXELS, TABLE_EDGES, TABLE_LINES, TABLE_POLYGONS};
    use scanvert::raster::{edge::Edge, line::Line, table::TablePolygon};
    Some(crate::bands::Table {
        polygons: riscv::singleton!(: [TablePolygon; TABLE_POLYGONS] = [TablePolygon::EMPTY; TABLE_POLYGONS])?,
        index: riscv::singleton!(: [u32; 2 * TABLE_POLYGONS] = [0; 2 * TABLE_POLYGONS])?,
        edges: riscv::singleton!(: [Edge; TABLE_EDGES] = [Edge::EMPTY; TABLE_EDGES])?,
        lines: riscv::singleton!(: [Option<Line>; TABLE_LINES] = [None; TABLE_LINES])?,
        band: riscv::singleton!(: [u32; BAND_PIXELS / 2] = [0; BAND_PIXELS / 2])?,
    })
}

/// The `budget` variant's memory (`src/budget.rs`), in `.bss`, handed
/// out once; each part a static of its own, so that no more than one is
/// made on the stack at a time (measured on the Cortex-M4 image).
pub fn budget_memory() -> Option<crate::budget::Memory> {
    use crate::budget::{set, Storage, EMPTY};
    use scanvert::raster::{edge::Edge, line::Line, table::TablePolygon};
    Some(crate::budget::Memory {
        storage: riscv::singleton!(: Storage = EMPTY)?,
        edges: riscv::singleton!(: [Edge; set::RASTER_EDGES] = [Edge::EMPTY; set::RASTER_EDGES])?,
        polygons: riscv::singleton!(: [TablePolygon; set::TABLE_POLYGONS] = [TablePolygon::EMPTY; set::TABLE_POLYGONS])?,
        index: riscv::singleton!(: [u32; 2 * set::TABLE_POLYGONS] = [0; 2 * set::TABLE_POLYGONS])?,
        table_edges: riscv::singleton!(: [Edge; set::TABLE_EDGES] = [Edge::EMPTY; set::TABLE_EDGES])?,
        lines: riscv::singleton!(: [Option<Line>; set::TABLE_LINES] = [None; set::TABLE_LINES])?,
        band: riscv::singleton!(: [u32; set::BAND_PIXELS / 2] = [0; set::BAND_PIXELS / 2])?,
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
        storage: riscv::singleton!(: Storage = EMPTY)?,
        vertices: riscv::singleton!(: [ViewPoint; set::VERTEX_SLOTS] = [ViewPoint::EMPTY; set::VERTEX_SLOTS])?,
        edges: riscv::singleton!(: [Edge; set::RASTER_EDGES] = [Edge::EMPTY; set::RASTER_EDGES])?,
        band: riscv::singleton!(: [u32; set::BAND_PIXELS / 2] = [0; set::BAND_PIXELS / 2])?,
    })
}
