//! The `budget` variants: lists rendered band by band
//! (`Controller::render_bands_packed`) with no frame buffer, in statics sized
//! exactly for them and nothing else, so that the image's `.data` + `.bss`
//! is the RAM they need (measure.sh reads it from the ELF's sections, by
//! part from the statics' symbols).
//!
//! | feature | lists | `scenes.rs` module |
//! |---|---|---|
//! | `budget` | the README's 3D demo at 320 × 240, its 8 frames as display lists | `budget_demo` |
//! | `budget-poly3` | the two 170-face lists at 512 × 256 | `budget_poly3` |
//!
//! The statics (`platform::budget_memory`, each named `BUDGET_*`):
//! the 3D layer's [`SceneStorage`] (store, workspace, labels), the band
//! buffer of [`BAND_ROWS`](set::BAND_ROWS) rows of RGB565 (in words of two
//! pixels, `PackedBand`), the
//! rasteriser's edges and the 2D edge table, every capacity the most any
//! of the lists needs (the constants of the `scenes.rs` module, which the
//! host test `on_target_scenes` derives from `controller::needs`,
//! `DisplayList::table_needs` and the host's render). Each band is
//! shipped, in order, into a running checksum, which must equal the
//! host's checksum of the whole frame.
//!
//! Printed, besides the usual `checksum` lines: a line `budget` with
//! the bytes of the scene storage's parts, and a line `bands` a list with
//! the instructions of its render (the checksum of its bands included).

use crate::{platform, Pixel, Scene};
use core::convert::Infallible;
use scanvert::controller::Controller;
use scanvert::display_list::DisplayList;
use scanvert::port::checksum::Checksum;
use scanvert::port::packed_band::PackedBandTarget;
use scanvert::raster::edge::Edge;
use scanvert::raster::line::Line;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::scene::label::Label;
use scanvert::scene::SceneStorage;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment};
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};
use scanvert::visible::Resolve;

use semihosting::println;

/// The lists and capacities of this variant.
#[cfg(not(feature = "budget-poly3"))]
pub use crate::scenes::budget_demo as set;
/// The lists and capacities of this variant.
#[cfg(feature = "budget-poly3")]
pub use crate::scenes::budget_poly3 as set;

/// The 3D layer's memory, each pool as large as the lists need: one
/// segment (a list's 3D layer is one).
pub type Storage = SceneStorage<
    { set::TRAPEZOID_SLOTS },
    { set::FACE_SLOTS },
    1,
    { set::INDEX_ROWS },
    { set::EDGE_SLOTS },
    { set::ACTIVE_SLOTS },
    { set::RUN_SLOTS },
    { set::LABEL_SLOTS },
    { set::TEXT_BYTES },
>;

/// Every slot of the storage unused.
pub const EMPTY: Storage = Storage::new();

/// All the memory the variant renders with, in `.bss`.
pub struct Memory {
    /// The 3D layer's store, workspace and labels.
    pub storage: &'static mut Storage,
    /// The rasteriser's edge storage.
    pub edges: &'static mut [Edge; set::RASTER_EDGES],
    /// The edge table's entries.
    pub polygons: &'static mut [TablePolygon; set::TABLE_POLYGONS],
    /// Its live list and order by first row.
    pub index: &'static mut [u32; 2 * set::TABLE_POLYGONS],
    /// Its edges.
    pub table_edges: &'static mut [Edge; set::TABLE_EDGES],
    /// Its lines.
    pub lines: &'static mut [Option<Line>; set::TABLE_LINES],
    /// The band buffer.
    pub band: &'static mut [u32; set::BAND_PIXELS / 2],
}

/// Ships bands into a running checksum, checking that they come in
/// order, each right after the last.
struct Sum {
    /// `None` for the timed render: the bands go nowhere, as a DMA
    /// transfer costs the CPU nothing a pixel (the full frames' checksum
    /// is not timed either); then the render again into the checksum.
    sum: Option<Checksum>,
    next: u16,
    in_order: bool,
}

impl Sum {
    fn new(check: bool) -> Sum {
        Sum {
            sum: check.then(Checksum::default),
            next: 0,
            in_order: true,
        }
    }
}

impl PackedBandTarget for Sum {
    type Color = Pixel;
    type Error = Infallible;
    fn ship_words(
        &mut self,
        y: u16,
        rows: u16,
        width: u16,
        words: &[u32],
    ) -> Result<(), Infallible> {
        self.in_order &= y == self.next;
        self.next = y.saturating_add(rows);
        if let Some(sum) = self.sum.as_mut() {
            crate::write_wire(sum, words, rows as usize * width as usize);
        }
        Ok(())
    }
}

/// Renders every list of the variant in bands and compares each frame's
/// checksum with the host's. `true` when all match and `ok`.
pub fn run(counter: &platform::Counter, ok: bool) -> bool {
    let Some(m) = platform::budget_memory() else {
        crate::log::fault("the budget memory is taken");
        return false;
    };
    report_parts();
    let mut m = m;
    let mut ok = ok;
    let mut matched = 0;
    for scene in set::SCENES {
        if frame(scene, &mut m, counter) {
            matched += 1;
        } else {
            ok = false;
        }
    }
    crate::log::summary(matched, set::SCENES.len(), ok);
    ok
}

/// One list in bands of [`set::BAND_ROWS`]; `true` when its checksum is
/// the host's.
fn frame(scene: &Scene, m: &mut Memory, counter: &platform::Counter) -> bool {
    let list = match DisplayList::new_checked(scene.list) {
        Ok(list) => list,
        Err(e) => {
            crate::log::bad_list(scene.name, e);
            return false;
        }
    };
    let Memory {
        storage,
        edges,
        polygons,
        index,
        table_edges,
        lines,
        band,
    } = m;
    let mut timed = Sum::new(false);
    let t0 = counter.ticks();
    let rendered = render(
        &list,
        storage,
        &mut edges[..],
        TableMemory {
            polygons: &mut polygons[..],
            index: &mut index[..],
            edges: &mut table_edges[..],
            lines: &mut lines[..],
        },
        &mut band[..],
        &mut timed,
    );
    let ticks = counter.ticks() - t0;
    let mut sum = Sum::new(true);
    let again = render(
        &list,
        storage,
        &mut edges[..],
        TableMemory {
            polygons: &mut polygons[..],
            index: &mut index[..],
            edges: &mut table_edges[..],
            lines: &mut lines[..],
        },
        &mut band[..],
        &mut sum,
    );
    let got = sum.sum.map_or(0, |c| c.value());
    let whole = [&timed, &sum]
        .iter()
        .all(|s| s.in_order && s.next >= list.height());
    let matched = rendered.is_some() && again == rendered && whole && got == scene.checksum;
    let (trapezoids, max_active) = rendered.unwrap_or((0, 0));
    report(
        scene.name,
        list.width(),
        list.height(),
        trapezoids,
        max_active,
        ticks * platform::INSTRUCTIONS_PER_TICK,
        got,
        matched,
    );
    crate::log::checksum(scene.name, got);
    if !matched {
        crate::log::mismatch(scene.name, scene.checksum);
    }
    matched
}

/// The render, bands of [`set::BAND_ROWS`] rows: the trapezoids and the
/// most on one row, or `None` (reported) if it failed.
#[inline(never)]
fn render(
    list: &DisplayList<'_>,
    storage: &mut Storage,
    edges: &mut [Edge],
    table: TableMemory<'_>,
    band: &mut [u32],
    sum: &mut Sum,
) -> Option<(u32, u32)> {
    let mut c = Controller::new(Rasterizer::new(edges))
        .with_3d(storage.as_memory())
        .with_resolve(Resolve::default());
    match c.render_bands_packed(list, table, set::BAND_ROWS as u16, band, sum) {
        Ok(stats) => Some((stats.trapezoids, stats.visible.max_active)),
        Err(e) => {
            report_error(e);
            None
        }
    }
}

/// The bytes of the scene storage's parts: each pool its slots times the
/// slot's size, and the workspace the rest (the active list and its
/// entries, and padding).
fn report_parts() {
    use core::mem::size_of;
    let total = size_of::<Storage>();
    let parts = [
        set::TRAPEZOID_SLOTS * size_of::<Trapezoid>(),
        set::FACE_SLOTS * size_of::<Face>(),
        size_of::<Segment>(),
        set::INDEX_ROWS * size_of::<u16>(),
        set::EDGE_SLOTS * size_of::<EdgeSlot>(),
        set::RUN_SLOTS * size_of::<Run>(),
        set::LABEL_SLOTS * size_of::<Label>(),
        set::TEXT_BYTES,
    ];
    let workspace = total.saturating_sub(parts.iter().sum());
    let [traps, faces, segments, index, slots, runs, labels, text] = parts;
    println!(
        "budget storage={total} trapezoids={traps} trapezoid_slots={} trapezoid_size={} faces={faces} segments={segments} index={index} edge_slots={slots} runs={runs} labels={labels} text={text} workspace={workspace} active_slots={} band_rows={}",
        set::TRAPEZOID_SLOTS,
        size_of::<Trapezoid>(),
        set::ACTIVE_SLOTS,
        set::BAND_ROWS
    );
}

#[allow(clippy::too_many_arguments)]
fn report(
    name: &str,
    w: u16,
    h: u16,
    trapezoids: u32,
    max_active: u32,
    instructions: u64,
    sum: u32,
    ok: bool,
) {
    let verdict = if ok { "ok" } else { "MISMATCH" };
    println!(
        "bands {name} {w}x{h} rows={} trapezoids={trapezoids} max_active={max_active} instructions={instructions} checksum={sum:08x} {verdict}",
        set::BAND_ROWS
    );
}

fn report_error(e: scanvert::controller::ListBandsError<Infallible>) {
    println!("budget: the render failed: {e}");
}
