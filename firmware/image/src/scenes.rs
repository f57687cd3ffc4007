//! The display lists the image renders, and the checksum of each frame as
//! the host renders it (`scanvert checksum firmware/image/scenes/*.scvl`).
//!
//! Generated, with the `.scvl` files, by
//! `UPDATE_SCENES=1 cargo test -p host-tests --test on_target_scenes`;
//! that test fails when this file or a list is stale. Do not edit.

use crate::Scene;

/// Edge slots for the largest polygon of any scene.
pub const EDGE_SLOTS: usize = 48;

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
];
