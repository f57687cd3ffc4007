//! Instructions per row of the racing path, for the simulator's cost
//! model of racing the beam (`hal_sim/src/race.rs`).
//!
//! Every embedded list is prepared once (`Controller::bands`, counted on
//! a line `prepare NAME instructions=N`) and then composed one row at a
//! time as colour runs (`ListBands::draw_runs`, into a run list of the
//! frame's width, no pixel buffer), each row counted on its own
//! and printed as `row NAME Y instructions=N`: what the producer of the
//! simulator's ring does for a row. Then, for the row-format encoder,
//! each row's runs are encoded as `pico_scanvideo` tokens
//! (`port::scanvideo::encode`), counted on its own as
//! `tokens NAME Y instructions=N`. Last, an empty 512 × 256 list, its 256
//! rows counted together, on a line `empty 512 rows=256
//! instructions=N` (the mean of an empty row to within 40 / 256).
//!
//! The counter is SysTick, one tick per 40 instructions under
//! `-icount shift=0`, so each count is a multiple of 40, within 40 of the
//! row's instructions. With the feature `rows` (which implies `bands`):
//! `cargo run --release --features rows`. `measure.sh` builds and runs
//! it and keeps the counts in `rows-m4.txt` (its `--check`, in CI, fails
//! when they differ from the run's), to which `cargo run --release -p
//! scanvert-bench -- --only race` fits the cost model.

use crate::bands::{Table, TABLE_EDGES, TABLE_LINES, TABLE_POLYGONS};
use crate::{platform, Memory3d, Scene};
use scanvert::controller::Controller;
use scanvert::display_list::{Command, DisplayList, Writer};
use scanvert::port::runs::{ColorRun, RowRuns};
use scanvert::port::scanvideo::{self, Opcodes};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::TableMemory;
use scanvert::visible::Resolve;

#[cfg(not(feature = "defmt"))]
use semihosting::println;

/// Runs a row holds at most: one a pixel of the widest frame.
const ROW_RUNS: usize = 512;

/// Words of tokens a row takes at most: three tokens a run and one a
/// pixel of the short runs, the black pixel and the end.
const ROW_WORDS: usize = (3 * ROW_RUNS + 512 + 4).div_ceil(2);

/// Prepares `scene` once and composes it row by row, printing each row's
/// instructions. `false` if a row could not be composed.
pub fn measure(
    scene: &Scene,
    edges: &mut [Edge],
    mem: &mut Memory3d,
    table: &mut Table,
    counter: &platform::Counter,
) -> bool {
    let Ok(list) = DisplayList::new_checked(scene.list) else {
        return false;
    };
    rows(scene.name, &list, edges, mem, table, counter, true)
}

/// An empty 512 × 256 list, composed row by row, its rows counted
/// together.
pub fn measure_empty(
    edges: &mut [Edge],
    mem: &mut Memory3d,
    table: &mut Table,
    counter: &platform::Counter,
) -> bool {
    let mut buf = [0u8; 64];
    let Ok(writer) = Writer::new(&mut buf, 512, 256) else {
        return false;
    };
    let Ok(list) = DisplayList::new_checked(writer.finish()) else {
        return false;
    };
    rows("empty", &list, edges, mem, table, counter, false)
}

fn rows(
    name: &str,
    list: &DisplayList<'_>,
    edges: &mut [Edge],
    mem: &mut Memory3d,
    table: &mut Table,
    counter: &platform::Counter,
    each: bool,
) -> bool {
    let need = list.table_needs();
    if need.polygons > TABLE_POLYGONS || need.edges > TABLE_EDGES || need.lines > TABLE_LINES {
        return true;
    }
    let three = list.commands().any(|(_, c)| matches!(c, Command::Poly3(_)));
    let Table {
        polygons,
        index,
        edges: table_edges,
        lines,
        ..
    } = table;
    let t = TableMemory {
        polygons: &mut polygons[..],
        index: &mut index[..],
        edges: &mut table_edges[..],
        lines: &mut lines[..],
    };
    let mut c = Controller::new(Rasterizer::new(edges));
    if three {
        c = c.with_3d(mem.as_memory()).with_resolve(Resolve::Crossing);
    }
    let t0 = counter.ticks();
    let Ok(mut bands) = c.bands(list, t) else {
        return false;
    };
    if each {
        report_prepare(
            name,
            (counter.ticks() - t0) * platform::INSTRUCTIONS_PER_TICK,
        );
    }
    let h = bands.size().1;
    let mut runs = [ColorRun::new(0, crate::BLACK); ROW_RUNS];
    let mut row = RowRuns::new(&mut runs);
    let mut words = [0u32; ROW_WORDS];
    let all = counter.ticks();
    for y in 0..h {
        let t0 = counter.ticks();
        let drawn = bands.draw_runs(y, &mut row);
        core::hint::black_box(row.as_slice());
        let ticks = counter.ticks() - t0;
        if drawn.is_err() {
            return false;
        }
        if !each {
            continue;
        }
        report_row("row", name, y, ticks * platform::INSTRUCTIONS_PER_TICK);
        let t0 = counter.ticks();
        let encoded = tokens(&row, &mut words);
        core::hint::black_box(&words);
        let ticks = counter.ticks() - t0;
        if encoded.is_none() {
            return false;
        }
        report_row("tokens", name, y, ticks * platform::INSTRUCTIONS_PER_TICK);
    }
    if !each {
        report_empty(
            name,
            bands.size().0,
            h,
            (counter.ticks() - all) * platform::INSTRUCTIONS_PER_TICK,
        );
    }
    true
}

/// Spans inserted into a row of runs alone: 256 rows of 320 pixels, each
/// with `spans` spans of pseudo-random place, length and colour (of four)
/// inserted in turn, counted together; printed as `insert SPANS
/// rows=256 instructions=N`.
pub fn measure_inserts(counter: &platform::Counter) {
    use scanvert::port::{Span, SpanTarget};
    for spans in [1u32, 4, 16, 64] {
        let mut runs = [ColorRun::new(0, crate::BLACK); 320];
        let mut seed = 0x1234_5678u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            seed >> 8
        };
        let t0 = counter.ticks();
        for _ in 0..256 {
            let mut row = RowRuns::new(&mut runs);
            row.start(0, (320, 1), crate::BLACK);
            for _ in 0..spans {
                let x0 = (next() % 320) as u16;
                let len = (next() % 40) as u16 + 1;
                let color = crate::Pixel::new((next() % 4) as u8, 0, 0);
                let span = Span {
                    y: 0,
                    x0,
                    x1: (x0 + len).min(320),
                };
                let Ok(()) = core::hint::black_box(&mut row).fill_span(span, color);
            }
            core::hint::black_box(row.as_slice());
        }
        let n = (counter.ticks() - t0) * platform::INSTRUCTIONS_PER_TICK;
        report_empty("insert", spans as u16, 256, n);
    }
}

/// The row's runs as `pico_scanvideo` tokens; the words written.
#[inline(never)]
fn tokens(row: &RowRuns<'_, crate::Pixel>, words: &mut [u32]) -> Option<usize> {
    let runs = row
        .runs()
        .map(|(x0, x1, c)| (x1 - x0, scanvideo::rgb565(c)));
    scanvideo::encode(runs, &Opcodes::DEFAULT, words).ok()
}

fn report_prepare(name: &str, instructions: u64) {
    #[cfg(not(feature = "defmt"))]
    println!("prepare {name} instructions={instructions}");
    #[cfg(feature = "defmt")]
    defmt::info!("prepare {=str} instructions={=u64}", name, instructions);
}

fn report_row(what: &str, name: &str, y: u16, instructions: u64) {
    #[cfg(not(feature = "defmt"))]
    println!("{what} {name} {y} instructions={instructions}");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "{=str} {=str} {=u16} instructions={=u64}",
        what,
        name,
        y,
        instructions
    );
}

fn report_empty(name: &str, width: u16, rows: u16, instructions: u64) {
    #[cfg(not(feature = "defmt"))]
    println!("{name} {width} rows={rows} instructions={instructions}");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "{=str} {=u16} rows={=u16} instructions={=u64}",
        name,
        width,
        rows,
        instructions
    );
}
