//! The display lists embedded in the firmware image, and the frame
//! checksums the image compares its own renders with.
//!
//! The image (`firmware/image`) embeds binary display lists with
//! `include_bytes!` from `firmware/image/scenes/`, and a table of the
//! checksum each frame must have, `firmware/image/src/scenes.rs`. This
//! test regenerates both, renders every list through the simulated
//! hardware (graphic controller into the dual-port RAM, as `scanvert
//! checksum` does) and fails if a committed file differs, so they never
//! go stale. To write them after an intended change, run
//!
//! ```sh
//! UPDATE_SCENES=1 cargo test -p host-tests --test on_target_scenes
//! ```
//!
//! The lists: `demo` is `scenes/demo.dl` assembled to binary; `w1` to `w5`
//! are the 2D benchmark workloads of `testkit/src/workloads.rs`, each pass
//! of a workload as one frame: `color #ff0000` and its polygons, or one
//! `clear #ff0000` (W2), on a frame that starts black. `poly3-layered` and
//! `poly3-tilted` are the 3D layer alone: the `flat` and `tilted` scenes of
//! `testkit::poly3_scenes` (170 `poly3`s on 512 × 256, parallel to the
//! screen in layers, or tilted and through each other), each `poly3`
//! after a `color` of its own that no other has in RGB565.
//!
//! The image's `budget` variants (`firmware/image/src/budget.rs`) render
//! lists band by band with no frame buffer, in statics sized exactly for
//! them: the constants of `scenes.rs`'s modules `budget_demo` and
//! `budget_poly3`, from `controller::needs`, `DisplayList::table_needs`
//! and the most trapezoids on a row of the host's render. `budget_demo`
//! is the README's 3D demo at 320 × 240, its 8 frames (`scanvert demo`'s
//! default) written as display lists by `scanvert_sim::demo::frame_list`
//! into `firmware/image/scenes/budget/`; each list's checksum is also
//! checked against the `Scene`'s own picture of that frame, so the lists
//! are the demo. `budget_poly3` is the two 170-face lists above.
//!
//! The mesh lists (`firmware/image/scenes/meshes/`, the module `meshes` of
//! `scenes.rs`) are meshes of `testkit::meshes` at 240 × 240, written as
//! `scanvert import` writes a model (`v`/`f` lines, a fitted view, a
//! light): an icosphere of 1,280 triangles, a torus of 720 and the Utah
//! teapot of 992. The image renders them in 16-row bands, in statics
//! sized for them as the `budget` ones are (and a vertex table of the most
//! `v`s of any).

use embedded_graphics_core::pixelcolor::Rgb888;
use host_tests::harness3d::vertex3;
use scanvert::controller::{Needs, RenderStats};
use scanvert::display_list::{DisplayList, Writer};
use scanvert::port::checksum::frame_checksum;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::demo::{self, Size};
use scanvert_sim::dual_port::DualPortRam;
use scanvert_sim::memory::ListMemory;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use testkit::meshes;
use testkit::poly3_scenes as scenes3d;
use testkit::reference3d::Poly3;
use testkit::workloads::{self, Kind, Workload};

/// Largest frame the image holds: 512 × 256 RGB565.
const IMAGE_FRAME_PIXELS: usize = 512 * 256;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// One workload as a display list.
fn workload_list(wl: &Workload) -> Vec<u8> {
    let need = 64 + wl.polys.iter().map(|p| 3 + 4 * p.len()).sum::<usize>();
    let mut buf = vec![0u8; need];
    let mut w = Writer::new(&mut buf, wl.width, wl.height).expect("frame size");
    let ink = Rgb888::new(0xff, 0, 0);
    match wl.kind {
        Kind::Clear => w.clear(ink).expect("fits"),
        Kind::Polygons => {
            w.color(ink).expect("fits");
            for p in &wl.polys {
                w.poly(p.iter().copied()).expect("fits");
            }
        }
    }
    w.finish().to_vec()
}

/// The demo scene, assembled from its text form.
fn demo_list() -> Vec<u8> {
    let text = std::fs::read(root().join("scenes/demo.dl")).expect("read scenes/demo.dl");
    scanvert_sim::text::assemble_bytes(&text)
        .expect("scenes/demo.dl assembles")
        .bytes
}

/// The colour of the `k`-th `poly3`: different from every other `k <
/// 2048` in RGB565, so that no two faces merge into one run.
fn color3(k: usize) -> Rgb888 {
    let (r, g) = ((k & 31) as u8, (16 + (k >> 5)) as u8);
    Rgb888::new(r << 3, (g & 63) << 2, (31 - r) << 3)
}

/// A `poly3` scene as a display list: each `poly3` after its `color`, no
/// clear (the frame starts black) and no clip.
fn scene3_list(polys: &[Poly3]) -> Vec<u8> {
    let need = 64
        + polys
            .iter()
            .map(|p| 4 + 3 + 6 * p.poly.len())
            .sum::<usize>();
    let mut buf = vec![0u8; need];
    let mut w = Writer::new(&mut buf, scenes3d::W, scenes3d::H).expect("frame size");
    for (k, p) in polys.iter().enumerate() {
        w.color(color3(k)).expect("fits");
        w.poly3(p.poly.iter().copied().map(vertex3)).expect("fits");
    }
    w.finish().to_vec()
}

/// Every list the image embeds, by name, in the order it renders them.
fn lists() -> Vec<(String, Vec<u8>)> {
    let mut out = vec![("demo".to_string(), demo_list())];
    for wl in workloads::all() {
        out.push((wl.id.to_lowercase(), workload_list(&wl)));
    }
    let [(_, flat), (_, tilted), ..] = scenes3d::all();
    out.push(("poly3-layered".to_string(), scene3_list(&flat)));
    out.push(("poly3-tilted".to_string(), scene3_list(&tilted)));
    out
}

/// The 3D memory the image must hold (the most over its lists).
#[derive(Default)]
struct Memory3d {
    trapezoids: usize,
    faces: usize,
    active: usize,
    rows: usize,
    runs: usize,
}

/// The size of the demo in the `budget` variant.
const BUDGET_SIZE: (u16, u16) = (320, 240);
/// Its frames: `scanvert demo`'s default.
const BUDGET_FRAMES: usize = 8;
/// Rows of a band in the `budget` variants.
const BUDGET_BAND_ROWS: usize = 16;

/// A set of lists for a `budget` variant: the module of `scenes.rs` it
/// goes in, its doc, and its lists by name with their path under
/// `firmware/image/scenes`.
struct BudgetSet {
    module: &'static str,
    doc: &'static str,
    lists: Vec<(String, String, Vec<u8>)>,
}

/// The `Scene`'s own pictures of the demo's frames at `size`, as
/// checksums, after each frame's update.
fn demo_scene_sums(size: Size, frames: usize) -> Vec<(demo::Step, u32)> {
    let mut out = Vec::new();
    demo::drive_at(
        size,
        frames,
        |scene, procs| scene.update(procs),
        |scene, step, _, bg| {
            let (w, h) = (size.width, size.height);
            let mut pixels = vec![bg; w as usize * h as usize];
            let mut fb =
                scanvert::port::framebuffer::FrameBuffer::new(&mut pixels, w, h).expect("frame");
            scene
                .draw(
                    Resolve::Crossing,
                    Some(bg),
                    scanvert::scene::label::DEFAULT_FONT,
                    &mut fb,
                )
                .expect("draws");
            out.push((step, frame_checksum(&pixels)));
        },
    )
    .expect("the demo runs");
    out
}

/// The `budget` variants' lists.
fn budget_sets(lists: &[(String, Vec<u8>)]) -> Vec<BudgetSet> {
    let size = Size::new(BUDGET_SIZE.0, BUDGET_SIZE.1).expect("size");
    let demo_lists = demo_scene_sums(size, BUDGET_FRAMES)
        .into_iter()
        .enumerate()
        .map(|(i, (step, sum))| {
            let name = format!("demo-{size}-{i:02}");
            let bytes = demo::frame_list(size, step).expect("the frame's list");
            assert_eq!(
                host_render(&bytes).0,
                sum,
                "{name}: the list's render is not the Scene's picture"
            );
            (name.clone(), format!("budget/{name}.scvl"), bytes)
        })
        .collect();
    let poly3 = lists
        .iter()
        .filter(|(name, _)| name.starts_with("poly3-"))
        .map(|(name, bytes)| (name.clone(), format!("{name}.scvl"), bytes.clone()))
        .collect();
    vec![
        BudgetSet {
            module: "budget_demo",
            doc: "the README's 3D demo at 320 × 240, its 8 frames as display lists.",
            lists: demo_lists,
        },
        BudgetSet {
            module: "budget_poly3",
            doc: "the two 170-face lists at 512 × 256.",
            lists: poly3,
        },
    ]
}

/// The module of `scenes.rs` for one `budget` variant: each pool sized
/// to the most any of its lists needs, and the lists.
fn budget_module(set: &BudgetSet) -> String {
    let mut m = Memory3d::default();
    let (mut labels, mut text, mut slots, mut edges, mut width) = (0, 0, 0, 0, 0);
    let mut table = scanvert::raster::table::TableNeeds::default();
    let mut rows = String::new();
    for (name, path, bytes) in &set.lists {
        let list = DisplayList::new_checked(bytes).expect("valid list");
        let (sum, need, stats) = host_render(bytes);
        m.trapezoids = m.trapezoids.max(need.trapezoids);
        m.faces = m.faces.max(need.faces);
        m.active = m.active.max(stats.visible.max_active as usize);
        m.rows = m.rows.max(need.rows);
        m.runs = m.runs.max(need.runs);
        labels = labels.max(need.labels);
        text = text.max(need.text);
        slots = slots.max(need.edge_slots);
        edges = edges.max(need.edges);
        width = width.max(list.width() as usize);
        let t = list.table_needs();
        table.polygons = table.polygons.max(t.polygons);
        table.edges = table.edges.max(t.edges);
        table.lines = table.lines.max(t.lines);
        writeln!(
            rows,
            "        Scene {{\n            name: \"{name}\",\n            list: include_bytes!(\"../scenes/{path}\"),\n            checksum: 0x{sum:08x},\n        }},",
        )
        .unwrap();
    }
    let mut s = String::new();
    writeln!(
        s,
        "/// The `budget` variant's lists and memory: {doc}\n\
         ///\n\
         /// Each capacity is the most any of the lists needs (`controller::needs`,\n\
         /// `DisplayList::table_needs`, the most trapezoids on a row of the\n\
         /// host's render), and no more. (A build uses one such module.)\n\
         #[allow(dead_code)]\n\
         pub mod {module} {{\n    \
         use crate::Scene;\n\n    \
         /// Rows of a band.\n    pub const BAND_ROWS: usize = {BUDGET_BAND_ROWS};\n    \
         /// Pixels of the band buffer: [`BAND_ROWS`] rows of the widest list.\n    pub const BAND_PIXELS: usize = {band};\n    \
         /// The rasteriser's edge storage: the most vertices of a `poly`.\n    pub const RASTER_EDGES: usize = {edges};\n    \
         /// Edge-table entries: `poly`s and `line`s after the last `clear`.\n    pub const TABLE_POLYGONS: usize = {tp};\n    \
         /// Edge-table edges: their vertices.\n    pub const TABLE_EDGES: usize = {te};\n    \
         /// Edge-table lines.\n    pub const TABLE_LINES: usize = {tl};\n    \
         /// Trapezoid slots.\n    pub const TRAPEZOID_SLOTS: usize = {tr};\n    \
         /// Face slots.\n    pub const FACE_SLOTS: usize = {fa};\n    \
         /// Rows of the scan-line index.\n    pub const INDEX_ROWS: usize = {ro};\n    \
         /// Edge slots of the store.\n    pub const EDGE_SLOTS: usize = {sl};\n    \
         /// Active-list entries: the most trapezoids on one row.\n    pub const ACTIVE_SLOTS: usize = {ac};\n    \
         /// Runs of one row.\n    pub const RUN_SLOTS: usize = {ru};\n    \
         /// Label slots.\n    pub const LABEL_SLOTS: usize = {labels};\n    \
         /// Bytes of label text.\n    pub const TEXT_BYTES: usize = {text};\n\n    \
         /// The lists, in the order the variant renders them.\n    pub const SCENES: &[Scene] = &[",
        doc = set.doc,
        module = set.module,
        band = BUDGET_BAND_ROWS * width,
        tp = table.polygons,
        te = table.edges,
        tl = table.lines,
        tr = m.trapezoids.max(1),
        fa = m.faces.max(1),
        ro = m.rows.max(1),
        sl = slots.max(1),
        ac = m.active.max(1),
        ru = m.runs.max(1),
    )
    .unwrap();
    s += &rows;
    s += "    ];\n}\n";
    s
}

/// Rows of a band of the mesh frames.
const MESH_BAND_ROWS: usize = 16;

/// The mesh lists the image renders in bands, by name, 240 × 240.
fn mesh_lists() -> Vec<(String, Vec<u8>)> {
    [
        ("icosphere", meshes::icosphere(3)),
        ("torus", meshes::torus(24, 15)),
        ("teapot", meshes::teapot(4)),
    ]
    .into_iter()
    .map(|(name, m)| {
        let model = scanvert_sim::import::Model {
            vertices: m.vertices_f32(),
            faces: m.faces(),
        };
        let text = scanvert_sim::import::list(&model, 240, 240, Rgb888::new(0xd0, 0xa0, 0x70));
        let bytes = scanvert_sim::text::assemble_bytes(text.as_bytes())
            .expect("the mesh list assembles")
            .bytes;
        (format!("mesh-{name}"), bytes)
    })
    .collect()
}

/// The module `meshes` of `scenes.rs`: the mesh lists and the memory of
/// rendering them in bands, each pool the most any of them needs.
fn mesh_module(lists: &[(String, Vec<u8>)]) -> String {
    let mut m = Memory3d::default();
    let (mut slots, mut edges, mut width, mut vertices) = (0, 0, 0, 0);
    let mut rows = String::new();
    for (name, bytes) in lists {
        let list = DisplayList::new_checked(bytes).expect("valid list");
        let (sum, need, stats) = host_render(bytes);
        m.trapezoids = m.trapezoids.max(need.trapezoids);
        m.faces = m.faces.max(need.faces);
        m.active = m.active.max(stats.visible.max_active as usize);
        m.rows = m.rows.max(need.rows);
        m.runs = m.runs.max(need.runs);
        slots = slots.max(need.edge_slots);
        edges = edges.max(need.edges);
        vertices = vertices.max(need.vertices);
        width = width.max(list.width() as usize);
        writeln!(
            rows,
            "        Scene {{\n            name: \"{name}\",\n            list: include_bytes!(\"../scenes/meshes/{name}.scvl\"),\n            checksum: 0x{sum:08x},\n        }},",
        )
        .unwrap();
    }
    let mut s = format!(
        "/// The mesh lists at 240 × 240 and the memory of rendering them in\n\
         /// bands of [`BAND_ROWS`](meshes::BAND_ROWS) rows, each pool the most any of them needs.\n\
         /// (Not rendered with the `discard` feature.)\n\
         #[allow(dead_code)]\n\
         pub mod meshes {{\n    \
         use crate::Scene;\n\n    \
         /// Rows of a band.\n    pub const BAND_ROWS: usize = {MESH_BAND_ROWS};\n    \
         /// Pixels of the band buffer: [`BAND_ROWS`] rows of the widest list.\n    pub const BAND_PIXELS: usize = {band};\n    \
         /// The rasteriser's edge storage.\n    pub const RASTER_EDGES: usize = {edges};\n    \
         /// Mesh vertex slots: the most `v`s of a list.\n    pub const VERTEX_SLOTS: usize = {vertices};\n    \
         /// Trapezoid slots.\n    pub const TRAPEZOID_SLOTS: usize = {tr};\n    \
         /// Face slots.\n    pub const FACE_SLOTS: usize = {fa};\n    \
         /// Rows of the scan-line index.\n    pub const INDEX_ROWS: usize = {ro};\n    \
         /// Edge slots of the store.\n    pub const EDGE_SLOTS: usize = {sl};\n    \
         /// Active-list entries: the most trapezoids on one row.\n    pub const ACTIVE_SLOTS: usize = {ac};\n    \
         /// Runs of one row.\n    pub const RUN_SLOTS: usize = {ru};\n\n    \
         /// The lists, in the order the image renders them.\n    pub const SCENES: &[Scene] = &[\n",
        band = MESH_BAND_ROWS * width,
        edges = edges.max(3),
        vertices = vertices.max(1),
        tr = m.trapezoids.max(1),
        fa = m.faces.max(1),
        ro = m.rows.max(1),
        sl = slots.max(1),
        ac = m.active.max(1),
        ru = m.runs.max(1),
    );
    s += &rows;
    s += "    ];\n}\n";
    s
}

/// The checksum of `bytes` rendered on the host, into a fresh (black)
/// dual-port RAM, with memory sized by `needs` (as `scanvert checksum`
/// does); what the list needs, and the render's statistics.
fn host_render(bytes: &[u8]) -> (u32, Needs, RenderStats) {
    let list = DisplayList::new_checked(bytes).expect("valid list");
    let mut memory = ListMemory::for_list(&list).expect("within the pools' limits");
    let mut ram = DualPortRam::new(list.width(), list.height());
    let stats = memory
        .controller()
        .with_resolve(Resolve::Crossing)
        .render(&list, &mut ram.write_port())
        .expect("renders");
    (frame_checksum(ram.contents()), *memory.needs(), stats)
}

/// The table the image compiles in.
fn table(lists: &[(String, Vec<u8>)]) -> String {
    let mut slots = 3;
    let mut s = String::from(
        "//! The display lists the image renders, and the checksum of each frame as\n\
         //! the host renders it (`scanvert checksum firmware/image/scenes/*.scvl`).\n\
         //!\n\
         //! Generated, with the `.scvl` files, by\n\
         //! `UPDATE_SCENES=1 cargo test -p host-tests --test on_target_scenes`;\n\
         //! that test fails when this file or a list is stale. Do not edit.\n\n\
         use crate::Scene;\n\n",
    );
    let mut rows = String::new();
    let mut m = Memory3d::default();
    for (name, bytes) in lists {
        let list = DisplayList::new_checked(bytes).expect("valid list");
        let (sum, need, stats) = host_render(bytes);
        slots = slots.max(need.edges).max(need.edge_slots);
        assert!(
            list.width() as usize * list.height() as usize <= IMAGE_FRAME_PIXELS,
            "{name}: frame larger than the image's frame buffer"
        );
        if need.any() {
            m.trapezoids = m.trapezoids.max(need.trapezoids);
            m.faces = m.faces.max(need.faces);
            // The exact number, where `needs` gives a bound.
            m.active = m.active.max(stats.visible.max_active as usize);
            m.rows = m.rows.max(need.rows);
            m.runs = m.runs.max(need.runs);
        }
        writeln!(
            rows,
            "    Scene {{\n        name: \"{name}\",\n        list: include_bytes!(\"../scenes/{name}.scvl\"),\n        checksum: 0x{sum:08x},\n    }},",
        )
        .unwrap();
    }
    writeln!(
        s,
        "/// Edge slots for the largest polygon of any scene.\npub const EDGE_SLOTS: usize = {slots};\n"
    )
    .unwrap();
    writeln!(
        s,
        "/// Trapezoid slots of the 3D layer: the most of any scene.\npub const TRAPEZOID_SLOTS: usize = {};\n\n\
         /// Face slots: the most of any scene (a drawn `poly3` with a trapezoid needs one).\npub const FACE_SLOTS: usize = {};\n\n\
         /// Active-list entries: the most trapezoids on one row of any scene.\npub const ACTIVE_SLOTS: usize = {};\n\n\
         /// Rows of the scan-line index: the tallest 3D scene.\npub const INDEX_ROWS: usize = {};\n\n\
         /// Runs of one row: the widest 3D scene.\npub const RUN_SLOTS: usize = {};\n",
        m.trapezoids.max(1),
        m.faces.max(1),
        m.active.max(1),
        m.rows.max(1),
        m.runs.max(1),
    )
    .unwrap();
    s += "/// The scenes, in the order the image renders them.\npub const SCENES: &[Scene] = &[\n";
    s += &rows;
    s += "];\n";
    for set in budget_sets(lists) {
        s += "\n";
        s += &budget_module(&set);
    }
    s += "\n";
    s += &mesh_module(&mesh_lists());
    s
}

#[test]
fn embedded_scenes_and_checksums_are_current() {
    let update = std::env::var_os("UPDATE_SCENES").is_some();
    let dir = root().join("firmware/image/scenes");
    let lists = lists();
    let mut files: Vec<(PathBuf, Vec<u8>)> = lists
        .iter()
        .map(|(name, bytes)| (dir.join(format!("{name}.scvl")), bytes.clone()))
        .collect();
    for set in budget_sets(&lists) {
        for (_, path, bytes) in set.lists {
            files.push((dir.join(path), bytes));
        }
    }
    for (name, bytes) in mesh_lists() {
        files.push((dir.join(format!("meshes/{name}.scvl")), bytes));
    }
    files.push((
        root().join("firmware/image/src/scenes.rs"),
        table(&lists).into_bytes(),
    ));
    let mut stale = Vec::new();
    for (path, want) in &files {
        if std::fs::read(path).ok().as_deref() != Some(want.as_slice()) {
            if update {
                std::fs::create_dir_all(path.parent().unwrap()).unwrap();
                std::fs::write(path, want).unwrap();
            } else {
                stale.push(path.display().to_string());
            }
        }
    }
    assert!(
        stale.is_empty(),
        "stale on-target files (run `UPDATE_SCENES=1 cargo test -p host-tests --test on_target_scenes`): {stale:?}"
    );
}
