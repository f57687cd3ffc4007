//! The display lists the image renders, and the checksum of each frame as
//! the host renders it (`scanvert checksum firmware/image/scenes/*.scvl`).
//!
//! Generated, with the `.scvl` files, by
//! `UPDATE_SCENES=1 cargo test -p host-tests --test on_target_scenes`;
//! that test fails when this file or a list is stale. Do not edit.

use crate::Scene;

/// Edge slots for the largest polygon of any scene.
pub const EDGE_SLOTS: usize = 48;

/// Trapezoid slots of the 3D layer: the most of any scene.
pub const TRAPEZOID_SLOTS: usize = 375;

/// Face slots: the most of any scene (a drawn `poly3` with a trapezoid needs one).
pub const FACE_SLOTS: usize = 169;

/// Active-list entries: the most trapezoids on one row of any scene.
pub const ACTIVE_SLOTS: usize = 40;

/// Rows of the scan-line index: the tallest 3D scene.
pub const INDEX_ROWS: usize = 256;

/// Runs of one row: the widest 3D scene.
pub const RUN_SLOTS: usize = 512;

/// The scenes, in the order the image renders them.
pub const SCENES: &[Scene] = &[
    Scene {
        name: "demo",
        list: include_bytes!("../scenes/demo.scvl"),
        checksum: 0xb224a28d,
    },
    Scene {
        name: "w1",
        list: include_bytes!("../scenes/w1.scvl"),
        checksum: 0xce9e9d2d,
    },
    Scene {
        name: "w2",
        list: include_bytes!("../scenes/w2.scvl"),
        checksum: 0xe39c9dc5,
    },
    Scene {
        name: "w3",
        list: include_bytes!("../scenes/w3.scvl"),
        checksum: 0x42cc3cad,
    },
    Scene {
        name: "w4",
        list: include_bytes!("../scenes/w4.scvl"),
        checksum: 0x437b23ad,
    },
    Scene {
        name: "w5",
        list: include_bytes!("../scenes/w5.scvl"),
        checksum: 0x2e14dca5,
    },
    Scene {
        name: "poly3-layered",
        list: include_bytes!("../scenes/poly3-layered.scvl"),
        checksum: 0xadaf071c,
    },
    Scene {
        name: "poly3-tilted",
        list: include_bytes!("../scenes/poly3-tilted.scvl"),
        checksum: 0x48a997ee,
    },
];
