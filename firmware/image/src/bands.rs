//! Every embedded list rendered again band by band
//! (`Controller::render_bands_packed`), with no frame buffer: bands of 1,
//! 8, 16 and 64 rows through one band buffer of words (`PackedBand`: two
//! RGB565 pixels a word, in a panel's byte order, whatever the frame
//! memory's cells), each band shipped into a running checksum.
//! The checksum must equal the host's frame's; the instructions (of a
//! run shipping nowhere, as the full frame's exclude its checksum) are
//! printed on lines starting `bands`, next to the full frame's `frame`
//! line. With the feature `bands` only (its edge table takes about
//! 1.24 MiB of `.bss` with 256 lines, the band buffer 64 KiB):
//! `cargo run --release --features bands`.

use crate::{platform, Memory3d, Resolved, Scene};
use core::convert::Infallible;
use scanvert::controller::Controller;
use scanvert::display_list::{Command, DisplayList};
use scanvert::port::checksum::Checksum;
use scanvert::port::packed_band::PackedBandTarget;
use scanvert::raster::edge::Edge;
use scanvert::raster::line::Line;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::visible::Resolve;

#[cfg(not(feature = "defmt"))]
use semihosting::println;

/// Polygons the edge table holds: W3's 10 000.
pub const TABLE_POLYGONS: usize = 10_000;
/// Edges it holds: W3's 30 000.
pub const TABLE_EDGES: usize = 30_000;
/// Lines it holds.
pub const TABLE_LINES: usize = 256;
/// Pixels of the band buffer: 64 rows of the widest frame (512).
pub const BAND_PIXELS: usize = 64 * 512;

/// The edge table's memory (about 1.24 MiB, in `.bss`) and the band buffer.
pub struct Table {
    /// Polygon entries.
    pub polygons: &'static mut [TablePolygon; TABLE_POLYGONS],
    /// The live list and the order by first row.
    pub index: &'static mut [u32; 2 * TABLE_POLYGONS],
    /// Edges.
    pub edges: &'static mut [Edge; TABLE_EDGES],
    /// Lines.
    pub lines: &'static mut [Option<Line>; TABLE_LINES],
    /// The band buffer.
    pub band: &'static mut [u32; BAND_PIXELS / 2],
}

/// Band heights measured.
const HEIGHTS: [u16; 4] = [1, 8, 16, 64];

/// Ships bands into a running checksum, in order, or (`None`, for the
/// timed run) nowhere.
struct Sum(Option<Checksum>);

impl PackedBandTarget for Sum {
    type Color = crate::Pixel;
    type Error = Infallible;
    fn ship_words(
        &mut self,
        _: u16,
        rows: u16,
        width: u16,
        words: &[u32],
    ) -> Result<(), Infallible> {
        if let Some(c) = self.0.as_mut() {
            crate::write_wire(c, words, rows as usize * width as usize);
        }
        Ok(())
    }
}

/// Renders `scene` in bands of each height, counting instructions, and
/// checks each frame's checksum. `true` when all match (or the list does
/// not fit the table, which is reported and skipped).
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
        report_skip(scene.name);
        return true;
    }
    let three = list.commands().any(|(_, c)| matches!(c, Command::Poly3(_)));
    let mut ok = true;
    // Each list as the full frames are drawn: the 170-face lists again
    // with the sweep, band by band, under their `-crossing` names.
    for resolved in Resolved::of(scene) {
        let three = three.then_some(resolved.mode);
        for rows in HEIGHTS {
            // Timed without the checksum (the full frame's is not timed
            // either), then again into the checksum.
            let t0 = counter.ticks();
            let timed = render(&list, rows, edges, mem, table, three, &mut Sum(None));
            let ticks = counter.ticks() - t0;
            let mut sum = Sum(Some(Checksum::default()));
            let done = render(&list, rows, edges, mem, table, three, &mut sum);
            let got = sum.0.map_or(0, |c| c.value());
            let matched = timed && done && got == scene.checksum;
            ok &= matched;
            report(
                resolved.name,
                rows,
                ticks * platform::INSTRUCTIONS_PER_TICK,
                got,
                matched,
            );
        }
    }
    ok
}

/// One band render; `false` if it failed.
#[inline(never)]
fn render(
    list: &DisplayList<'_>,
    rows: u16,
    edges: &mut [Edge],
    mem: &mut Memory3d,
    table: &mut Table,
    three: Option<Resolve>,
    sum: &mut Sum,
) -> bool {
    let t = TableMemory {
        polygons: &mut table.polygons[..],
        index: &mut table.index[..],
        edges: &mut table.edges[..],
        lines: &mut table.lines[..],
    };
    let mut c = Controller::new(Rasterizer::new(edges));
    if let Some(mode) = three {
        c = c.with_3d(mem.as_memory()).with_resolve(mode);
    }
    c.render_bands_packed(list, t, rows, &mut table.band[..], sum)
        .is_ok()
}

fn report(name: &str, rows: u16, instructions: u64, sum: u32, ok: bool) {
    let verdict = if ok { "ok" } else { "MISMATCH" };
    #[cfg(not(feature = "defmt"))]
    println!("bands {name} rows={rows} instructions={instructions} checksum={sum:08x} {verdict}");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "bands {=str} rows={=u16} instructions={=u64} checksum={=u32:08x} {=str}",
        name,
        rows,
        instructions,
        sum,
        verdict
    );
}

fn report_skip(name: &str) {
    #[cfg(not(feature = "defmt"))]
    println!("bands {name}: skipped, the edge table is too small");
    #[cfg(feature = "defmt")]
    defmt::info!("bands {=str}: skipped, the edge table is too small", name);
}
