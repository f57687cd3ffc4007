//! Instructions per row of the band path with 1-row bands, for the
//! simulator's cost model of racing the beam (`hal_sim/src/race.rs`).
//!
//! Every embedded list is prepared once (`Controller::bands`, counted on
//! a line `prepare NAME instructions=N`) and then drawn one row at a time
//! (`ListBands::draw(y, 1, …)`), each row counted on its own and printed
//! as `row NAME Y instructions=N`. The counter is SysTick, one tick per
//! 40 instructions under `-icount shift=0`, so each count is a multiple of
//! 40, within 40 of the row's instructions. The counted span is what the
//! producer of the simulator's ring does for a row: the draw call, then
//! the row encoded into colour runs (`encode`); nothing is shipped. With the feature `rows` (which implies
//! `bands`): `cargo run --release --features rows`; the counts are kept in
//! `rows-m4.txt`, to which `cargo run --release -p scanvert-bench --
//! --only race` fits the cost model.

use crate::bands::{Table, TABLE_EDGES, TABLE_LINES, TABLE_POLYGONS};
use crate::{platform, Memory3d, Scene};
use scanvert::controller::Controller;
use scanvert::display_list::{Command, DisplayList};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::TableMemory;
use scanvert::visible::Resolve;

#[cfg(not(feature = "defmt"))]
use semihosting::println;

/// Prepares `scene` once and draws it row by row, printing each row's
/// instructions. `false` if a row could not be drawn.
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
        band,
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
    let Ok(mut bands) = c.bands(&list, t) else {
        return false;
    };
    report_prepare(
        scene.name,
        (counter.ticks() - t0) * platform::INSTRUCTIONS_PER_TICK,
    );
    let (w, h) = bands.size();
    let mut runs = [(0u16, crate::BLACK); ROW_RUNS];
    for y in 0..h {
        let t0 = counter.ticks();
        let drawn = bands.draw(y, 1, &mut band[..]);
        let n = encode(&band[..usize::from(w)], &mut runs);
        core::hint::black_box((&runs, n));
        let ticks = counter.ticks() - t0;
        if drawn.is_err() {
            return false;
        }
        report_row(scene.name, y, ticks * platform::INSTRUCTIONS_PER_TICK);
    }
    true
}

/// Runs a row holds at most: one a pixel of the widest frame.
const ROW_RUNS: usize = 512;

/// Encodes `row` as runs of (length, colour) into `runs`, as the
/// simulator's producer does; returns the runs written.
#[inline(never)]
fn encode(row: &[crate::Pixel], runs: &mut [(u16, crate::Pixel); ROW_RUNS]) -> usize {
    let mut n = 0;
    for &p in row {
        match runs[..n].last_mut() {
            Some((len, c)) if *c == p => *len += 1,
            _ => {
                if let Some(r) = runs.get_mut(n) {
                    *r = (1, p);
                    n += 1;
                }
            }
        }
    }
    n
}

fn report_prepare(name: &str, instructions: u64) {
    #[cfg(not(feature = "defmt"))]
    println!("prepare {name} instructions={instructions}");
    #[cfg(feature = "defmt")]
    defmt::info!("prepare {=str} instructions={=u64}", name, instructions);
}

fn report_row(name: &str, y: u16, instructions: u64) {
    #[cfg(not(feature = "defmt"))]
    println!("row {name} {y} instructions={instructions}");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "row {=str} {=u16} instructions={=u64}",
        name,
        y,
        instructions
    );
}
