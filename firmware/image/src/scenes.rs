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

/// The `budget` variant's lists and memory: the README's 3D demo at 320 × 240, its 8 frames as display lists.
///
/// Each capacity is the most any of the lists needs (`controller::needs`,
/// `DisplayList::table_needs`, the most trapezoids on a row of the
/// host's render), and no more. (A build uses one such module.)
#[allow(dead_code)]
pub mod budget_demo {
    use crate::Scene;

    /// Rows of a band.
    pub const BAND_ROWS: usize = 16;
    /// Pixels of the band buffer: [`BAND_ROWS`] rows of the widest list.
    pub const BAND_PIXELS: usize = 5120;
    /// The rasteriser's edge storage: the most vertices of a `poly`.
    pub const RASTER_EDGES: usize = 0;
    /// Edge-table entries: `poly`s and `line`s after the last `clear`.
    pub const TABLE_POLYGONS: usize = 0;
    /// Edge-table edges: their vertices.
    pub const TABLE_EDGES: usize = 0;
    /// Edge-table lines.
    pub const TABLE_LINES: usize = 0;
    /// Trapezoid slots.
    pub const TRAPEZOID_SLOTS: usize = 597;
    /// Face slots.
    pub const FACE_SLOTS: usize = 200;
    /// Rows of the scan-line index.
    pub const INDEX_ROWS: usize = 240;
    /// Edge slots of the store.
    pub const EDGE_SLOTS: usize = 10;
    /// Active-list entries: the most trapezoids on one row.
    pub const ACTIVE_SLOTS: usize = 57;
    /// Runs of one row.
    pub const RUN_SLOTS: usize = 320;
    /// Label slots.
    pub const LABEL_SLOTS: usize = 38;
    /// Bytes of label text.
    pub const TEXT_BYTES: usize = 107;

    /// The lists, in the order the variant renders them.
    pub const SCENES: &[Scene] = &[
        Scene {
            name: "demo-320x240-00",
            list: include_bytes!("../scenes/budget/demo-320x240-00.scvl"),
            checksum: 0x9b3004a2,
        },
        Scene {
            name: "demo-320x240-01",
            list: include_bytes!("../scenes/budget/demo-320x240-01.scvl"),
            checksum: 0x8af19491,
        },
        Scene {
            name: "demo-320x240-02",
            list: include_bytes!("../scenes/budget/demo-320x240-02.scvl"),
            checksum: 0x25c9fcbb,
        },
        Scene {
            name: "demo-320x240-03",
            list: include_bytes!("../scenes/budget/demo-320x240-03.scvl"),
            checksum: 0x8af19491,
        },
        Scene {
            name: "demo-320x240-04",
            list: include_bytes!("../scenes/budget/demo-320x240-04.scvl"),
            checksum: 0x0ca093fc,
        },
        Scene {
            name: "demo-320x240-05",
            list: include_bytes!("../scenes/budget/demo-320x240-05.scvl"),
            checksum: 0x675d01cc,
        },
        Scene {
            name: "demo-320x240-06",
            list: include_bytes!("../scenes/budget/demo-320x240-06.scvl"),
            checksum: 0x45d00016,
        },
        Scene {
            name: "demo-320x240-07",
            list: include_bytes!("../scenes/budget/demo-320x240-07.scvl"),
            checksum: 0x577a1e59,
        },
    ];
}

/// The `budget` variant's lists and memory: the two 170-face lists at 512 × 256.
///
/// Each capacity is the most any of the lists needs (`controller::needs`,
/// `DisplayList::table_needs`, the most trapezoids on a row of the
/// host's render), and no more. (A build uses one such module.)
#[allow(dead_code)]
pub mod budget_poly3 {
    use crate::Scene;

    /// Rows of a band.
    pub const BAND_ROWS: usize = 16;
    /// Pixels of the band buffer: [`BAND_ROWS`] rows of the widest list.
    pub const BAND_PIXELS: usize = 8192;
    /// The rasteriser's edge storage: the most vertices of a `poly`.
    pub const RASTER_EDGES: usize = 0;
    /// Edge-table entries: `poly`s and `line`s after the last `clear`.
    pub const TABLE_POLYGONS: usize = 0;
    /// Edge-table edges: their vertices.
    pub const TABLE_EDGES: usize = 0;
    /// Edge-table lines.
    pub const TABLE_LINES: usize = 0;
    /// Trapezoid slots.
    pub const TRAPEZOID_SLOTS: usize = 375;
    /// Face slots.
    pub const FACE_SLOTS: usize = 169;
    /// Rows of the scan-line index.
    pub const INDEX_ROWS: usize = 256;
    /// Edge slots of the store.
    pub const EDGE_SLOTS: usize = 4;
    /// Active-list entries: the most trapezoids on one row.
    pub const ACTIVE_SLOTS: usize = 40;
    /// Runs of one row.
    pub const RUN_SLOTS: usize = 512;
    /// Label slots.
    pub const LABEL_SLOTS: usize = 0;
    /// Bytes of label text.
    pub const TEXT_BYTES: usize = 0;

    /// The lists, in the order the variant renders them.
    pub const SCENES: &[Scene] = &[
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
}

/// The mesh lists at 240 × 240 and the memory of rendering them in
/// bands of [`BAND_ROWS`](meshes::BAND_ROWS) rows, each pool the most any of them needs.
/// (Not rendered with the `discard` feature.)
#[allow(dead_code)]
pub mod meshes {
    use crate::Scene;

    /// Rows of a band.
    pub const BAND_ROWS: usize = 16;
    /// Pixels of the band buffer: [`BAND_ROWS`] rows of the widest list.
    pub const BAND_PIXELS: usize = 3840;
    /// The rasteriser's edge storage.
    pub const RASTER_EDGES: usize = 3;
    /// Mesh vertex slots: the most `v`s of a list.
    pub const VERTEX_SLOTS: usize = 642;
    /// Trapezoid slots.
    pub const TRAPEZOID_SLOTS: usize = 943;
    /// Face slots.
    pub const FACE_SLOTS: usize = 502;
    /// Rows of the scan-line index.
    pub const INDEX_ROWS: usize = 240;
    /// Edge slots of the store.
    pub const EDGE_SLOTS: usize = 9;
    /// Active-list entries: the most trapezoids on one row.
    pub const ACTIVE_SLOTS: usize = 62;
    /// Runs of one row.
    pub const RUN_SLOTS: usize = 240;

    /// The lists, in the order the image renders them.
    pub const SCENES: &[Scene] = &[
        Scene {
            name: "mesh-icosphere",
            list: include_bytes!("../scenes/meshes/mesh-icosphere.scvl"),
            checksum: 0xdc45bd7c,
        },
        Scene {
            name: "mesh-torus",
            list: include_bytes!("../scenes/meshes/mesh-torus.scvl"),
            checksum: 0xd75fa693,
        },
        Scene {
            name: "mesh-teapot",
            list: include_bytes!("../scenes/meshes/mesh-teapot.scvl"),
            checksum: 0x03db11dd,
        },
    ];
}
