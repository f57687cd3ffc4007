//! All the memory of a 3D layer or scene in one owned value, its
//! capacities const generics.
//!
//! [`SceneStorage`] holds the store's pools, the visible-surface stage's
//! workspace and the labels, as arrays. It is made by a `const fn`, so it
//! can be a `static` or a local, and lends itself as a
//! [`SceneMemory`] — slices, the capacities erased — which is what
//! [`Scene`](super::Scene) and
//! [`Controller::with_3d`](crate::controller::Controller::with_3d) take.
//! [`controller::needs`](crate::controller::needs) says what a display
//! list needs.
//!
//! ```
//! use scanvert::scene::{SceneMemory, SceneStorage};
//!
//! // 64 trapezoids, 16 faces, 2 segments, 48 rows, 8 edge slots,
//! // 16 active entries, 64 runs, 4 labels, 32 bytes of text.
//! type Storage = SceneStorage<64, 16, 2, 48, 8, 16, 64, 4, 32>;
//! static SHARED: Storage = Storage::new(); // constant: in `.data` (below)
//! const EMPTY: Storage = Storage::new();
//!
//! let mut storage = EMPTY;
//! let mem: SceneMemory<'_> = storage.as_memory();
//! assert_eq!(mem.store.trapezoids.len(), 64);
//! assert_eq!(mem.runs.len(), 64);
//! assert_eq!(SHARED.capacities().labels, 4);
//! ```
//!
//! # `.data` or `.bss`
//!
//! An unused slot is not all zero bytes (its links hold `0xffff`, "none"),
//! so a `static` initialised with `SceneStorage::new()` has a non-zero
//! constant initialiser and lands in `.data`: its whole size is taken in
//! flash as well as in RAM, and copied at start-up. To keep it in `.bss`
//! (RAM only, zeroed at start-up), let the `static` start uninitialised
//! and fill it once at run time, for example with the `static_cell` crate
//! or, on a Cortex-M, `cortex_m::singleton!` (the firmware image's
//! `budget` variant does so):
//!
//! ```ignore
//! // static_cell, any target:
//! use static_cell::StaticCell;
//! static STORAGE: StaticCell<Storage> = StaticCell::new();
//! let storage: &'static mut Storage = STORAGE.init(Storage::new());
//!
//! // cortex-m:
//! let storage: &'static mut Storage = cortex_m::singleton!(: Storage = Storage::new()).unwrap();
//! ```
//!
//! Either may build the value on the stack before moving it into place,
//! so leave room for one `Storage` on the stack where it is made.

use super::label::Label;
use super::SceneMemory;
use crate::visible::rle::Run;
use crate::visible::store::{Face, Segment, StoreMemory};
use crate::visible::sweep::Active;
use crate::visible::trapezoid::{EdgeSlot, Trapezoid};

/// The memory of a 3D layer or [`Scene`](super::Scene), owned, every
/// slot unused until lent.
///
/// | const | pool | slot (32-bit targets) | limit, and what needs it |
/// |---|---|---|---|
/// | `TRAPEZOIDS` | trapezoids | 34 bytes | at most 65535 are used (a `u16` index, one value reserved); as many as the polygons are cut into |
/// | `FACES` | faces | 56 bytes | at most 65535 used; one per polygon with a trapezoid |
/// | `SEGMENTS` | segments | 32 bytes | at most 65535 used; a display list uses one |
/// | `ROWS` | the scan-line index | 2 bytes | at least the frame's height (at most 4096) |
/// | `EDGES` | edge slots | 32 bytes | scratch for one polygon: as many as its vertices (at most 65535) |
/// | `ACTIVE` | active list | 120 bytes | at most 65535 used; the most trapezoids overlapping one row |
/// | `RUNS` | runs of one row | 4 bytes | at least the frame's width (at most 4096) |
/// | `LABELS` | label slots | 20 bytes | one per label placed |
/// | `TEXT` | label text | 1 byte | the bytes of every label's text |
///
/// A pool too small is an error when it runs out, naming the pool; slots
/// beyond a limit are never used.
#[derive(Clone, Debug)]
pub struct SceneStorage<
    const TRAPEZOIDS: usize,
    const FACES: usize,
    const SEGMENTS: usize,
    const ROWS: usize,
    const EDGES: usize,
    const ACTIVE: usize,
    const RUNS: usize,
    const LABELS: usize,
    const TEXT: usize,
> {
    trapezoids: [Trapezoid; TRAPEZOIDS],
    faces: [Face; FACES],
    segments: [Segment; SEGMENTS],
    rows: [u16; ROWS],
    edges: [EdgeSlot; EDGES],
    active: [Active; ACTIVE],
    runs: [Run; RUNS],
    labels: [Label; LABELS],
    text: [u8; TEXT],
}

/// The capacities of a [`SceneStorage`] (or what a list or a scene needs
/// of one: [`Scene::needed`](super::Scene::needed)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Capacities {
    /// Trapezoid slots.
    pub trapezoids: usize,
    /// Face slots.
    pub faces: usize,
    /// Segments.
    pub segments: usize,
    /// Rows of the scan-line index.
    pub rows: usize,
    /// Edge slots.
    pub edges: usize,
    /// Active-list slots.
    pub active: usize,
    /// Runs of one row.
    pub runs: usize,
    /// Label slots.
    pub labels: usize,
    /// Bytes of label text.
    pub text: usize,
}

impl Capacities {
    /// `true` when each capacity is at least `needed`'s: storage of these
    /// capacities holds what `needed` describes. A `const` check of
    /// declared storage against measured needs:
    ///
    /// ```
    /// use scanvert::scene::Capacities;
    /// const CAPS: Capacities = Capacities {
    ///     trapezoids: 64, faces: 16, segments: 2, rows: 240, edges: 16,
    ///     active: 32, runs: 240, labels: 2, text: 32,
    /// };
    /// // What `Scene::needed` reported over the frames the program shows.
    /// const NEEDED: Capacities = Capacities {
    ///     trapezoids: 41, faces: 9, segments: 1, rows: 240, edges: 8,
    ///     active: 12, runs: 240, labels: 1, text: 9,
    /// };
    /// const _: () = assert!(CAPS.covers(&NEEDED));
    /// type Storage = scanvert::scene_storage!(CAPS);
    /// static STORAGE_CAPS: Capacities = Storage::CAPACITIES;
    /// assert_eq!(STORAGE_CAPS, CAPS);
    /// ```
    pub const fn covers(&self, needed: &Capacities) -> bool {
        self.trapezoids >= needed.trapezoids
            && self.faces >= needed.faces
            && self.segments >= needed.segments
            && self.rows >= needed.rows
            && self.edges >= needed.edges
            && self.active >= needed.active
            && self.runs >= needed.runs
            && self.labels >= needed.labels
            && self.text >= needed.text
    }

    /// The larger of each capacity: storage for both.
    pub const fn max(self, o: Capacities) -> Capacities {
        const fn m(a: usize, b: usize) -> usize {
            if a > b {
                a
            } else {
                b
            }
        }
        Capacities {
            trapezoids: m(self.trapezoids, o.trapezoids),
            faces: m(self.faces, o.faces),
            segments: m(self.segments, o.segments),
            rows: m(self.rows, o.rows),
            edges: m(self.edges, o.edges),
            active: m(self.active, o.active),
            runs: m(self.runs, o.runs),
            labels: m(self.labels, o.labels),
            text: m(self.text, o.text),
        }
    }
}

impl<
        const TRAPEZOIDS: usize,
        const FACES: usize,
        const SEGMENTS: usize,
        const ROWS: usize,
        const EDGES: usize,
        const ACTIVE: usize,
        const RUNS: usize,
        const LABELS: usize,
        const TEXT: usize,
    > SceneStorage<TRAPEZOIDS, FACES, SEGMENTS, ROWS, EDGES, ACTIVE, RUNS, LABELS, TEXT>
{
    /// Storage with every slot unused.
    pub const fn new() -> Self {
        SceneStorage {
            trapezoids: [Trapezoid::EMPTY; TRAPEZOIDS],
            faces: [Face::EMPTY; FACES],
            segments: [Segment::EMPTY; SEGMENTS],
            rows: [0; ROWS],
            edges: [EdgeSlot::EMPTY; EDGES],
            active: [Active::EMPTY; ACTIVE],
            runs: [Run::EMPTY; RUNS],
            labels: [Label::EMPTY; LABELS],
            text: [0; TEXT],
        }
    }

    /// The capacities, as the const generics give them.
    pub const CAPACITIES: Capacities = Capacities {
        trapezoids: TRAPEZOIDS,
        faces: FACES,
        segments: SEGMENTS,
        rows: ROWS,
        edges: EDGES,
        active: ACTIVE,
        runs: RUNS,
        labels: LABELS,
        text: TEXT,
    };

    /// The capacities, as the const generics give them.
    pub const fn capacities(&self) -> Capacities {
        Self::CAPACITIES
    }

    /// The memory as slices, the capacities erased: what
    /// [`Scene`](super::Scene) and the controller take.
    pub fn as_memory(&mut self) -> SceneMemory<'_> {
        SceneMemory {
            store: StoreMemory {
                trapezoids: &mut self.trapezoids,
                faces: &mut self.faces,
                segments: &mut self.segments,
                rows: &mut self.rows,
                edges: &mut self.edges,
            },
            active: &mut self.active,
            runs: &mut self.runs,
            labels: &mut self.labels,
            text: &mut self.text,
        }
    }
}

impl<
        const TRAPEZOIDS: usize,
        const FACES: usize,
        const SEGMENTS: usize,
        const ROWS: usize,
        const EDGES: usize,
        const ACTIVE: usize,
        const RUNS: usize,
        const LABELS: usize,
        const TEXT: usize,
    > Default
    for SceneStorage<TRAPEZOIDS, FACES, SEGMENTS, ROWS, EDGES, ACTIVE, RUNS, LABELS, TEXT>
{
    fn default() -> Self {
        Self::new()
    }
}

/// The [`SceneStorage`] type of the capacities named in a `const`
/// [`Capacities`], instead of nine numbers in their order:
///
/// ```
/// use scanvert::scene::Capacities;
/// const CAPS: Capacities = Capacities {
///     trapezoids: 64, faces: 16, segments: 2, rows: 240, edges: 16,
///     active: 32, runs: 240, labels: 2, text: 32,
/// };
/// type Storage = scanvert::scene_storage!(CAPS);
/// let storage = Storage::new();
/// assert_eq!(storage.capacities(), CAPS);
/// ```
#[macro_export]
macro_rules! scene_storage {
    ($caps:path) => {
        $crate::scene::SceneStorage<
            { $caps.trapezoids },
            { $caps.faces },
            { $caps.segments },
            { $caps.rows },
            { $caps.edges },
            { $caps.active },
            { $caps.runs },
            { $caps.labels },
            { $caps.text },
        >
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    type Small = SceneStorage<4, 2, 1, 8, 3, 5, 6, 1, 7>;

    /// Made at compile time, usable as a `static`.
    static STATIC: Small = Small::new();

    #[test]
    fn capacities_are_the_const_generics() {
        let mut s = STATIC.clone();
        let m = s.as_memory();
        assert_eq!(
            (
                m.store.trapezoids.len(),
                m.store.faces.len(),
                m.store.segments.len()
            ),
            (4, 2, 1)
        );
        assert_eq!((m.store.rows.len(), m.store.edges.len()), (8, 3));
        assert_eq!((m.active.len(), m.runs.len()), (5, 6));
        assert_eq!((m.labels.len(), m.text.len()), (1, 7));
        assert_eq!(
            STATIC.capacities(),
            Capacities {
                trapezoids: 4,
                faces: 2,
                segments: 1,
                rows: 8,
                edges: 3,
                active: 5,
                runs: 6,
                labels: 1,
                text: 7
            }
        );
    }
}

// The slot sizes the table above and the module docs of the pools give,
// checked where they are stated: on 32-bit targets (the cross builds).
#[cfg(target_pointer_width = "32")]
const _: () = {
    use core::mem::size_of;
    assert!(size_of::<Trapezoid>() == 34);
    assert!(size_of::<Face>() == 56);
    assert!(size_of::<Segment>() == 32);
    assert!(size_of::<EdgeSlot>() == 32);
    assert!(size_of::<Active>() == 120);
    assert!(size_of::<Run>() == 4);
    assert!(size_of::<Label>() == 20);
};
