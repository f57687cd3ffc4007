//! The RAM of rendering with no frame buffer, by part, at the sizes the
//! scenes actually need: the 3D demo scene (every frame, the worst one)
//! and the 170-face lists the image embeds, against a full RGB565 frame
//! buffer and a z-buffer renderer's frame and depth buffer. Nothing here
//! is timed.
//!
//! The slot sizes are those of 32-bit targets (asserted at the end of
//! `scene/storage.rs` and in `raster/table.rs`), so the figures are the
//! Cortex-M4's whatever the host. `--only ram` rewrites the table of
//! `docs/performance.md` ("RAM without a frame buffer", between [`BEGIN`]
//! and [`END`]); the tests below fail when it is stale.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use scanvert::display_list::DisplayList;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::table::TableNeeds;
use scanvert::visible::Resolve;
use scanvert_sim::memory::ListMemory;
use std::fmt::Write as _;
use std::path::Path;

/// Markers of the table `--only ram` rewrites.
pub const BEGIN: &str = "<!-- ram-table:begin -->";
/// End marker.
pub const END: &str = "<!-- ram-table:end -->";

/// Bytes of one slot on a 32-bit target.
mod slot {
    pub const TRAPEZOID: usize = 34;
    pub const FACE: usize = 56;
    pub const SEGMENT: usize = 32;
    pub const INDEX_ROW: usize = 2;
    pub const EDGE_SLOT: usize = 32;
    /// An active slot.
    pub const ACTIVE: usize = 120;
    pub const RUN: usize = 4;
    pub const LABEL: usize = 20;
    /// A table entry and its two `u32` index entries.
    pub const TABLE_POLYGON: usize = 24 + 2 * 4;
    pub const TABLE_EDGE: usize = 24;
    pub const TABLE_LINE: usize = 48;
    /// An RGB565 pixel.
    pub const PIXEL: usize = 2;
}

/// Rows of a band.
const BAND_ROWS: usize = 16;

/// What a frame needs, counted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Counts {
    width: usize,
    height: usize,
    trapezoids: usize,
    faces: usize,
    segments: usize,
    edge_slots: usize,
    /// The most trapezoids overlapping one row.
    active: usize,
    labels: usize,
    text: usize,
    table: TableNeeds,
}

/// Bytes by part.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Ram {
    trapezoids: usize,
    faces: usize,
    segments: usize,
    index: usize,
    edge_slots: usize,
    active: usize,
    runs: usize,
    labels: usize,
    table: usize,
    band: usize,
}

impl Ram {
    fn of(c: &Counts) -> Ram {
        Ram {
            trapezoids: c.trapezoids * slot::TRAPEZOID,
            faces: c.faces * slot::FACE,
            segments: c.segments * slot::SEGMENT,
            index: c.height * slot::INDEX_ROW,
            edge_slots: c.edge_slots * slot::EDGE_SLOT,
            active: c.active * slot::ACTIVE,
            runs: c.width * slot::RUN,
            labels: c.labels * slot::LABEL + c.text,
            table: c.table.polygons * slot::TABLE_POLYGON
                + c.table.edges * slot::TABLE_EDGE
                + c.table.lines * slot::TABLE_LINE,
            band: BAND_ROWS * c.width * slot::PIXEL,
        }
    }

    /// A projection: the same counts with trapezoid slots of `trapezoid`
    /// bytes, active-plus-cover entries of `active` bytes and bands of
    /// `rows` rows.
    fn projected(c: &Counts, trapezoid: usize, active: usize, rows: usize) -> Ram {
        Ram {
            trapezoids: c.trapezoids * trapezoid,
            active: c.active * active,
            band: rows * c.width * slot::PIXEL,
            ..Ram::of(c)
        }
    }

    fn total(&self) -> usize {
        self.trapezoids
            + self.faces
            + self.segments
            + self.index
            + self.edge_slots
            + self.active
            + self.runs
            + self.labels
            + self.table
            + self.band
    }
}

/// A full RGB565 frame buffer.
fn frame_buffer(w: usize, h: usize) -> usize {
    w * h * slot::PIXEL
}

/// A z-buffer renderer: the frame and an `i16` or `i32` depth a pixel.
fn z_buffer(w: usize, h: usize, depth_bytes: usize) -> usize {
    w * h * (slot::PIXEL + depth_bytes)
}

#[cfg(test)]
#[test]
fn the_arithmetic_of_the_parts() {
    let c = Counts {
        width: 320,
        height: 240,
        trapezoids: 10,
        faces: 3,
        segments: 2,
        edge_slots: 16,
        active: 5,
        labels: 4,
        text: 9,
        table: TableNeeds {
            polygons: 2,
            edges: 7,
            lines: 1,
        },
    };
    let r = Ram::of(&c);
    assert_eq!(r.trapezoids, 340);
    assert_eq!(r.faces, 168);
    assert_eq!(r.segments, 64);
    assert_eq!(r.index, 480);
    assert_eq!(r.edge_slots, 512);
    assert_eq!(r.active, 600);
    assert_eq!(r.runs, 1280);
    assert_eq!(r.labels, 89);
    assert_eq!(r.table, 64 + 168 + 48);
    assert_eq!(r.band, 10_240);
    assert_eq!(
        r.total(),
        340 + 168 + 64 + 480 + 512 + 600 + 1280 + 89 + 280 + 10_240
    );
    assert_eq!(frame_buffer(320, 240), 153_600);
    assert_eq!(z_buffer(320, 240, 2), 307_200);
    assert_eq!(z_buffer(320, 240, 4), 460_800);
    assert_eq!(Ram::of(&Counts::default()).total(), 0);
    let p = Ram::projected(&c, 48, 72, 8);
    assert_eq!((p.trapezoids, p.active, p.band), (480, 360, 5120));
    assert_eq!(p.total(), r.total() - 340 + 480 - 600 + 360 - 10_240 + 5120);
    assert_eq!(Ram::projected(&c, 34, 120, 16), r);
    assert_eq!(
        (sep(0), sep(999), sep(1000), sep(94_911)),
        ("0".into(), "999".into(), "1,000".into(), "94,911".into())
    );
}

/// The slot sizes above are the library's where it can be checked on the
/// host too (the 32-bit ones are asserted in the cross builds).
#[cfg(test)]
#[test]
fn the_slot_sizes_are_the_library_s_on_32_bit_targets() {
    use core::mem::size_of;
    use scanvert::raster::table::TablePolygon;
    use scanvert::visible::rle::Run;
    assert_eq!(size_of::<TablePolygon>() + 8, slot::TABLE_POLYGON);
    assert_eq!(size_of::<Run>(), slot::RUN);
    assert_eq!(size_of::<u16>(), slot::INDEX_ROW);
    if cfg!(target_pointer_width = "32") {
        use scanvert::visible::{Active, Face, Segment, Trapezoid};
        assert_eq!(size_of::<Trapezoid>(), slot::TRAPEZOID);
        assert_eq!(size_of::<Face>(), slot::FACE);
        assert_eq!(size_of::<Segment>(), slot::SEGMENT);
        assert_eq!(size_of::<Active>(), slot::ACTIVE);
    }
}

/// The demo's counts after each frame's update, over `frames` frames.
fn demo_counts(frames: usize) -> Vec<(scanvert_sim::demo::Step, Counts)> {
    use scanvert_sim::demo::{drive, HEIGHT, SEGMENTS, WIDTH};
    let mut out = Vec::new();
    drive(
        frames,
        |scene, procs| scene.update(procs),
        |scene, step, _, _| {
            let most = scene.check().expect("the demo's workspace holds a row");
            out.push((
                step,
                Counts {
                    width: WIDTH as usize,
                    height: HEIGHT as usize,
                    trapezoids: scene.store().len(),
                    faces: scene.store().face_count(),
                    segments: SEGMENTS.len(),
                    // The scene's clipping bound of one polygon (`N`).
                    edge_slots: 16,
                    active: most as usize,
                    labels: scene.labels().len(),
                    text: scene.labels().text_len(),
                    table: TableNeeds::default(),
                },
            ));
        },
    )
    .expect("the demo runs");
    out
}

/// What a list the image embeds needs: `needs`, the table's needs, and
/// the most trapezoids overlapping a row, from rendering it.
fn list_counts(path: &Path) -> Counts {
    let bytes = std::fs::read(path).expect("list reads");
    let list = DisplayList::new_checked(&bytes).expect("valid list");
    let mut memory = ListMemory::for_list(&list).expect("within the pools");
    let (w, h) = (list.width(), list.height());
    let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
    let stats = memory
        .controller()
        .with_resolve(Resolve::Crossing)
        .render(&list, &mut fb)
        .expect("renders");
    let n = *memory.needs();
    Counts {
        width: w as usize,
        height: h as usize,
        trapezoids: n.trapezoids,
        faces: n.faces,
        segments: n.segments,
        edge_slots: n.edge_slots,
        active: stats.visible.max_active as usize,
        labels: n.labels,
        text: n.text,
        table: list.table_needs(),
    }
}

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("root")
}

fn kib(b: usize) -> String {
    format!("{:.1}", b as f64 / 1024.0)
}

/// `n` with thousands separated by commas, as the page writes them.
fn sep(n: usize) -> String {
    let d = n.to_string();
    let mut out = String::new();
    for (i, ch) in d.chars().enumerate() {
        if i > 0 && (d.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

fn row(name: &str, c: &Counts) -> String {
    let r = Ram::of(c);
    let (w, h) = (c.width, c.height);
    let t = r.total();
    format!(
        "| {name} | {} / {} / {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | **{}** ({}) | {} ({:.1}×) | {} / {} ({:.1}× / {:.1}×) |",
        c.trapezoids,
        c.faces,
        c.active,
        sep(r.trapezoids),
        sep(r.faces),
        sep(r.segments),
        sep(r.index),
        sep(r.edge_slots),
        sep(r.active),
        sep(r.runs),
        sep(r.labels),
        sep(r.table),
        sep(r.band),
        sep(t),
        kib(t),
        sep(frame_buffer(w, h)),
        frame_buffer(w, h) as f64 / t as f64,
        sep(z_buffer(w, h, 2)),
        sep(z_buffer(w, h, 4)),
        z_buffer(w, h, 2) as f64 / t as f64,
        z_buffer(w, h, 4) as f64 / t as f64,
    )
}

/// The table of `docs/performance.md`; the demo's frames and the
/// projections of other slot sizes go to stderr.
pub fn table() -> String {
    let mut s = String::new();
    s.push_str(
        "| scene | trapezoids / faces / most on a row | trapezoids | faces | segments | index | edge slots | active | runs | labels + text | 2D table | band (16 rows) | total, bytes (KiB) | RGB565 frame buffer (× total) | frame + i16 / i32 depth |\n",
    );
    s.push_str("|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    // Every frame of the default animation (8) and of a full orbit.
    for frames in [8, 34] {
        let all = demo_counts(frames);
        for (i, (step, c)) in all.iter().enumerate() {
            eprintln!(
                "demo frame {i}: threshold {} orbit {}: {c:?} total {}",
                step.threshold,
                step.orbit,
                Ram::of(c).total()
            );
        }
        let (i, (step, worst)) = all
            .iter()
            .enumerate()
            .max_by_key(|(_, (_, c))| Ram::of(c).total())
            .expect("frames");
        if frames == 8 {
            let _ = writeln!(
            s,
            "{}",
            row(
                &format!(
                    "3D demo, worst of {frames} frames (frame {i}: threshold {}, orbit {}°), 512×256",
                    step.threshold, step.orbit
                ),
                worst
            )
        );
        }
        let most = |f: fn(&Counts) -> usize| all.iter().map(|(_, c)| f(c)).max().unwrap_or(0);
        eprintln!(
            "demo over {frames} frames, most of each: trapezoids {} faces {} active {} labels {} text {}",
            most(|c| c.trapezoids),
            most(|c| c.faces),
            most(|c| c.active),
            most(|c| c.labels),
            most(|c| c.text)
        );
        // A static `SceneStorage` must hold the most of every pool over
        // the frames, not only the worst frame's.
        let pools = Counts {
            trapezoids: most(|c| c.trapezoids),
            faces: most(|c| c.faces),
            active: most(|c| c.active),
            labels: most(|c| c.labels),
            text: most(|c| c.text),
            ..*worst
        };
        if frames == 34 {
            let _ = writeln!(
                s,
                "{}",
                row(
                    &format!("3D demo, pools for all {frames} frames (the most of each), 512×256"),
                    &pools
                )
            );
        }
        if frames == 34 {
            // The pools for every frame at 512×256 and with the rows,
            // runs and band at 320×240: as measured, and projections (not
            // implemented) of a smaller active entry and 8-row bands.
            let small = Counts {
                width: 320,
                height: 240,
                ..pools
            };
            for (size, c) in [("512×256", &pools), ("320×240", &small)] {
                for (what, t, a, rows) in [
                    ("as measured", slot::TRAPEZOID, slot::ACTIVE, 16),
                    (
                        "projection: an active slot of 68 B",
                        slot::TRAPEZOID,
                        68,
                        16,
                    ),
                    (
                        "projection: an active slot of 68 B, 8-row bands",
                        slot::TRAPEZOID,
                        68,
                        8,
                    ),
                ] {
                    let p = Ram::projected(c, t, a, rows);
                    eprintln!(
                        "demo pools for {frames} frames, {size}, {what}: trapezoids {} faces {} active {} band {} total {} ({} KiB), {} under 65536",
                        p.trapezoids,
                        p.faces,
                        p.active,
                        p.band,
                        p.total(),
                        kib(p.total()),
                        65_536 - p.total() as i64
                    );
                }
            }
        }
        if frames == 8 {
            // The same counts at 320×240: an estimate (the demo is built
            // at 512×256 only).
            let est = Counts {
                width: 320,
                height: 240,
                ..*worst
            };
            let _ = writeln!(
                s,
                "{}",
                row(
                    "3D demo at 320×240, **estimate**: the worst frame's counts, the rows, runs and band at 320×240",
                    &est
                )
            );
        }
    }
    for name in ["poly3-layered", "poly3-tilted"] {
        let c = list_counts(&root().join(format!("firmware/image/scenes/{name}.scvl")));
        let _ = writeln!(s, "{}", row(&format!("{name} (170 faces), 512×256"), &c));
    }
    s
}

/// The table between its markers.
pub fn section() -> String {
    format!("{BEGIN}\n{}{END}\n\n", table())
}

/// `--only ram`: the table of `docs/performance.md` rewritten in place.
pub fn write_section(page: &Path) -> std::io::Result<()> {
    let old = std::fs::read_to_string(page).unwrap_or_default();
    let md = crate::report::splice(
        &old,
        BEGIN,
        END,
        &section(),
        "The 320×240 row is an estimate",
    );
    std::fs::write(page, md)?;
    eprintln!("rewrote the RAM table of docs/performance.md");
    Ok(())
}

#[cfg(test)]
#[test]
fn the_performance_page_has_the_current_table() {
    let page = std::fs::read_to_string(root().join("docs/performance.md")).expect("the page");
    let section = section();
    assert!(
        page.contains(&section),
        "docs/performance.md: run `cargo run --release -p scanvert-bench -- --only ram`; it should hold\n{section}"
    );
}
