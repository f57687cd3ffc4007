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
//! are the 2D benchmark workloads of `bench/src/workloads.rs`, each pass
//! of a workload as one frame: `color #ff0000` and its polygons, or one
//! `clear #ff0000` (W2), on a frame that starts black.

#[allow(dead_code)]
#[path = "../../bench/src/workloads.rs"]
mod workloads;

use embedded_graphics_core::pixelcolor::Rgb888;
use scanvert::checksum::frame_checksum;
use scanvert::controller::Controller;
use scanvert::display_list::{Command, DisplayList, Writer};
use scanvert::edge::Edge;
use scanvert::scan::Rasterizer;
use scanvert_sim::dual_port::DualPortRam;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use workloads::{Kind, Workload};

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

/// Every list the image embeds, by name, in the order it renders them.
fn lists() -> Vec<(String, Vec<u8>)> {
    let mut out = vec![("demo".to_string(), demo_list())];
    for wl in workloads::all() {
        out.push((wl.id.to_lowercase(), workload_list(&wl)));
    }
    out
}

/// Vertices of the largest polygon in `list`.
fn max_vertices(list: &DisplayList<'_>) -> usize {
    list.commands()
        .map(|(_, c)| match c {
            Command::Poly(v) => v.len(),
            Command::Poly3(v) => v.len(),
            _ => 0,
        })
        .max()
        .unwrap_or(0)
}

/// The checksum of `bytes` rendered on the host, into a fresh (black)
/// dual-port RAM.
fn host_checksum(bytes: &[u8]) -> u32 {
    let list = DisplayList::new_checked(bytes).expect("valid list");
    let mut edges = vec![Edge::EMPTY; max_vertices(&list).max(3)];
    let mut ram = DualPortRam::new(list.width(), list.height());
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut ram.write_port())
        .expect("renders");
    frame_checksum(ram.contents())
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
    for (name, bytes) in lists {
        let list = DisplayList::new_checked(bytes).expect("valid list");
        slots = slots.max(max_vertices(&list));
        assert!(
            list.width() as usize * list.height() as usize <= IMAGE_FRAME_PIXELS,
            "{name}: frame larger than the image's frame buffer"
        );
        writeln!(
            rows,
            "    Scene {{\n        name: \"{name}\",\n        list: include_bytes!(\"../scenes/{name}.scvl\"),\n        checksum: 0x{:08x},\n    }},",
            host_checksum(bytes)
        )
        .unwrap();
    }
    writeln!(
        s,
        "/// Edge slots for the largest polygon of any scene.\npub const EDGE_SLOTS: usize = {slots};\n"
    )
    .unwrap();
    s += "/// The scenes, in the order the image renders them.\npub const SCENES: &[Scene] = &[\n";
    s += &rows;
    s += "];\n";
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
