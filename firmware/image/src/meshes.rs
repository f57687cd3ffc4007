//! The mesh lists (`scenes.rs`, module `meshes`): meshes of 720 to 1,280
//! triangles at 240 × 240 as `scanvert import` writes them (`v`/`f`
//! lines), each rendered band by band (`Controller::render_bands_packed`,
//! bands of [`BAND_ROWS`](set::BAND_ROWS) rows of words of two pixels)
//! with no frame buffer, in
//! statics sized for them (the store, the workspace, the vertex table and
//! one band buffer). Each band is shipped into a running checksum, which
//! must equal the host's checksum of the whole frame.
//!
//! Each list is rendered with the default resolve (`Resolve::Auto`,
//! which takes the sweep's crossing points for their small trapezoids)
//! under its name, and painted far to near (`Resolve::Paint`) under its
//! name with `-paint`. Printed for each: a line
//! `frame mesh-NAME 240x240 rows=16 vertices=… faces=… drawn=… culled=…
//! trapezoids=… max_active=… mode=… ticks=… instructions=…` (`faces` the list's
//! `f`s, `drawn` those that reached the 3D layer; the instructions those
//! of a render whose bands go nowhere, see [`Sum`]), and its `checksum`
//! line, from a second render into the checksum.

use crate::{platform, Pixel, Scene};
use core::convert::Infallible;
use scanvert::controller::{Controller, RenderStats};
use scanvert::display_list::DisplayList;
use scanvert::geometry::ViewPoint;
use scanvert::port::checksum::Checksum;
use scanvert::port::packed_band::PackedBandTarget;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::TableMemory;
use scanvert::scene::SceneStorage;
use scanvert::visible::Resolve;

#[cfg(not(feature = "defmt"))]
use semihosting::println;

/// The lists and their capacities.
pub use crate::scenes::meshes as set;

/// The 3D layer's memory, each pool as large as the lists need.
pub type Storage = SceneStorage<
    { set::TRAPEZOID_SLOTS },
    { set::FACE_SLOTS },
    1,
    { set::INDEX_ROWS },
    { set::EDGE_SLOTS },
    { set::ACTIVE_SLOTS },
    { set::RUN_SLOTS },
    0,
    0,
>;

/// Every slot of the storage unused.
pub const EMPTY: Storage = Storage::new();

/// The memory the mesh frames render with, in `.bss`.
pub struct Memory {
    /// The store and the workspace.
    pub storage: &'static mut Storage,
    /// The mesh vertex table.
    pub vertices: &'static mut [ViewPoint; set::VERTEX_SLOTS],
    /// The rasteriser's edge storage.
    pub edges: &'static mut [Edge; set::RASTER_EDGES],
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

/// Renders every mesh list in bands, in both resolves, and compares each
/// frame's checksum with the host's. Adds to `matched` and `frames`;
/// `false` on a mismatch or a failure.
pub fn run(counter: &platform::Counter, matched: &mut usize, frames: &mut usize) -> bool {
    let Some(mut m) = platform::mesh_memory() else {
        crate::log::fault("the mesh memory is taken");
        return false;
    };
    report_parts();
    let mut ok = true;
    for scene in set::SCENES {
        for (resolve, suffix) in [(Resolve::default(), ""), (Resolve::Paint, "-paint")] {
            *frames += 1;
            if frame(scene, resolve, suffix, &mut m, counter) {
                *matched += 1;
            } else {
                ok = false;
            }
        }
    }
    ok
}

/// One list in bands; `true` when its checksum is the host's.
fn frame(
    scene: &Scene,
    resolve: Resolve,
    suffix: &str,
    m: &mut Memory,
    counter: &platform::Counter,
) -> bool {
    let list = match DisplayList::new_checked(scene.list) {
        Ok(list) => list,
        Err(e) => {
            crate::log::bad_list(scene.name, e);
            return false;
        }
    };
    let mut timed = Sum::new(false);
    let t0 = counter.ticks();
    let rendered = render(&list, resolve, m, &mut timed);
    let ticks = counter.ticks() - t0;
    let mut sum = Sum::new(true);
    let again = render(&list, resolve, m, &mut sum);
    let got = sum.sum.map_or(0, |c| c.value());
    let whole = [&timed, &sum]
        .iter()
        .all(|s| s.in_order && s.next >= list.height());
    let matched = rendered.is_some() && again.is_some() && whole && got == scene.checksum;
    if let Some(s) = rendered {
        report(scene.name, suffix, &list, &s, ticks);
    }
    print_checksum(scene.name, suffix, got);
    if !matched {
        crate::log::mismatch(scene.name, scene.checksum);
    }
    matched
}

/// The render in bands; its statistics, or `None` (reported) if it
/// failed.
#[inline(never)]
fn render(
    list: &DisplayList<'_>,
    resolve: Resolve,
    m: &mut Memory,
    sum: &mut Sum,
) -> Option<RenderStats> {
    // A mesh list has no 2D command: the edge table is empty.
    let table = TableMemory {
        polygons: &mut [],
        index: &mut [],
        edges: &mut [],
        lines: &mut [],
    };
    let mut c = Controller::new(Rasterizer::new(&mut m.edges[..]))
        .with_3d(m.storage.as_memory())
        .with_vertices(&mut m.vertices[..])
        .with_resolve(resolve);
    match c.render_bands_packed(list, table, set::BAND_ROWS as u16, &mut m.band[..], sum) {
        Ok(stats) => Some(stats),
        Err(e) => {
            #[cfg(not(feature = "defmt"))]
            println!("meshes: the render failed: {}", e);
            #[cfg(feature = "defmt")]
            {
                let _ = e;
                defmt::error!("meshes: the render failed");
            }
            None
        }
    }
}

/// The bytes of the mesh frames' statics.
fn report_parts() {
    use core::mem::size_of;
    let storage = size_of::<Storage>();
    let vertices = set::VERTEX_SLOTS * size_of::<ViewPoint>();
    let edges = set::RASTER_EDGES * size_of::<Edge>();
    let band = set::BAND_PIXELS / 2 * size_of::<u32>();
    let total = storage + vertices + edges + band;
    #[cfg(not(feature = "defmt"))]
    println!(
        "meshes memory={total} storage={storage} vertices={vertices} vertex_slots={} edges={edges} band={band} band_rows={}",
        set::VERTEX_SLOTS,
        set::BAND_ROWS
    );
    #[cfg(feature = "defmt")]
    defmt::info!(
        "meshes memory={=usize} storage={=usize} vertices={=usize} edges={=usize} band={=usize}",
        total,
        storage,
        vertices,
        edges,
        band
    );
}

fn report(name: &str, suffix: &str, list: &DisplayList<'_>, s: &RenderStats, ticks: u64) {
    let instructions = ticks * platform::INSTRUCTIONS_PER_TICK;
    let faces = s.faces + s.culled + s.clipped_away;
    let (w, h) = (list.width(), list.height());
    #[cfg(not(feature = "defmt"))]
    println!(
        "frame {name}{suffix} {w}x{h} rows={} vertices={} faces={faces} drawn={} culled={} trapezoids={} max_active={} mode={} ticks={ticks} instructions={instructions}",
        set::BAND_ROWS, s.vertices, s.faces, s.culled, s.trapezoids, s.visible.max_active, crate::log::resolve_name(s.visible.mode)
    );
    #[cfg(feature = "defmt")]
    defmt::info!(
        "frame {=str}{=str} {=u16}x{=u16} rows={=usize} vertices={=u32} faces={=u32} drawn={=u32} culled={=u32} trapezoids={=u32} mode={=str} ticks={=u64} instructions={=u64}",
        name, suffix, w, h, set::BAND_ROWS, s.vertices, faces, s.faces, s.culled, s.trapezoids, crate::log::resolve_name(s.visible.mode), ticks, instructions
    );
}

fn print_checksum(name: &str, suffix: &str, sum: u32) {
    #[cfg(not(feature = "defmt"))]
    println!("checksum {name}{suffix} {sum:08x}");
    #[cfg(feature = "defmt")]
    defmt::info!("checksum {=str}{=str} {=u32:08x}", name, suffix, sum);
}
