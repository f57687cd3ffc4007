//! Scan-line visible surfaces: the trapezoids of a [`TrapezoidStore`]
//! resolved row by row into run-length scan lines, with no z-buffer.
//!
//! # Per row
//!
//! 1. The trapezoids whose top is this row (the scan-line index) enter the
//!    active list, a caller-owned array of [`Active`] slots. One that
//!    continues a trapezoid that ended on the row above (a triangle's
//!    lower half), or that starts at the corner where one ended with no
//!    continuation (a mesh's next triangle), takes that one's slot and
//!    its place in the order; the others go to the end.
//! 2. Every active trapezoid knows its pixels `l..r` on the row: its edges'
//!    pixels, stepped down a row with no division, cut to its columns
//!    (`step_live`: up to the first that ends, only `l`, `r` and the
//!    depth of each element of the sorted array are rewritten, in place).
//! 3. A row whose live trapezoids with pixels are side by side, each
//!    starting at or right of the end of the one before it in the order
//!    (a closed mesh's faces, away from the slivers of its silhouette), is
//!    found by one pass over the list (again after the sort below when
//!    one is out of order) and written straight: the
//!    background and each one's span, with no sort and no sweep (the
//!    same runs and counts as the sweep's). Other rows go on:
//!
//!    The active list is sorted by `l` with an insertion sort over an
//!    index array, which costs one compare per entry when the order is the
//!    last row's (the usual case); an entry that would move more than 64
//!    places hands the row over to a heap sort. On a row of more than 64
//!    (`sort_many`), the trapezoids that entered are sorted apart and
//!    merged in, and the moves have a budget of 64 an entry in all, so
//!    that one far out of place (new, or with pixels again after a row
//!    with none) costs its moves and not a heap sort.
//! 4. A sweep from left to right keeps a *front*: a covering trapezoid
//!    known to be nearest from the sweep's position to its own `r`,
//!    because it is in front of every other covering trapezoid at both ends
//!    of their common pixels. A trapezoid that starts behind the front
//!    costs two depth compares (and is *hidden*, left out, when the front
//!    outlasts it); one that ends behind it costs nothing. A new front is
//!    sought where the front ends or a trapezoid starts in front of it, and
//!    what is found there is counted by kind:
//!    * **empty**: no trapezoid, the background up to the next `l`;
//!    * **single**: one trapezoid;
//!    * **multiple**: several, and the nearest one is the front;
//!    * **intersecting**: several, another crosses the nearest before its
//!      end, so no front holds: the span up to the next `l` or `r` is
//!      resolved from its two ends and, if they differ, subdivided
//!      ([`Resolve`]) until every part has the same nearest trapezoid at
//!      both ends (or, if they agree, counted as *multiple*).
//!
//!    Where nothing covers the sweep's position, a trapezoid that ends by
//!    the next one's `l` is alone on all its pixels: its span is written
//!    with no cover and no depth compare (the counts are those of a front
//!    found alone). A closed mesh's row after culling, faces side by side,
//!    goes all this way.
//! 5. The row's runs go to the caller ([`rle`](crate::visible::rle) format), or
//!    with [`draw`] straight to the frame-buffer port as spans.
//! 6. Trapezoids that end drop out; the rest step down a row.
//!
//! Per row the work is proportional to the edges crossed (plus the
//! trapezoids overlapping in depth); nothing is done per pixel, and
//! nothing is divided except to find a crossing point in
//! [`Resolve::Crossing`].
//!
//! # Complexity
//!
//! On a row with `a` active trapezoids, `s` spans resolved (fronts found,
//! empty and intersecting spans) and at most `c` covers at once:
//!
//! * stepping and entering: `O(a)`;
//! * the sort: `O(a)` when the order is the last row's, at most
//!   `O(64·a + a log a)` in any order; on a row of more than 64, `O(a)`
//!   for the merge of those that entered, whatever their order;
//! * the sweep, on a row of at most 64 live trapezoids (`sweep`):
//!   `O((a + s) · c)`: a trapezoid that starts costs two depth compares
//!   behind a front, or its insertion into the cover array (`O(c)`); a
//!   front found or a span resolved compares the covers once (`O(c)`, and
//!   a subdivision `O(c)` per part);
//! * the sweep, on a longer row (`sweep_many`): a trapezoid that starts
//!   costs `O(log c)` compares to find its place in the cover array (kept
//!   by increasing `r`, so one that ends last is appended, and one that
//!   ends with others goes after them, or takes the place of the first of
//!   them when it hides them) and moves the covers that end after it; a
//!   front costs no compare while the covers form a *chain* (each in
//!   front of the next on their common pixels), kept by at most eight
//!   depth compares a trapezoid that starts, and `O(c)` otherwise.
//!
//! A cover is a trapezoid that has started on the row and has neither
//! ended nor been hidden: when a trapezoid that starts breaks the front,
//! the covers that end by the front's end are behind it on all their
//! pixels left and leave the array (once each), so a front is never
//! compared again with what the last one hid. Staggered faces each nearer
//! than the last so keep `c` at 2 however many overlap (in a chain, each
//! takes the place of the last when they end on one column). Trapezoids
//! that start where nothing covers the sweep's position are compared with
//! the first of them as they enter, and those it hides are left out:
//! faces of one extent stacked keep `c` at 1. What stays is
//! `c` trapezoids that overlap in depth and outlast the front: faces each
//! farther than the last, visible one sliver each, make `s` and `c` both
//! of the order of `a`, which would make a row `O(a²)`; but they form a
//! chain, each entering behind the one before it and ending after it, so
//! `sweep_many` appends each with two depth compares and finds each
//! front with none: `O(a log a)` a row. A row whose covers overlap in depth
//! without forming a chain (planes crossing each other everywhere) stays
//! `O((a + s) · c)`. Per frame, the sum over rows; the figures are in
//! `docs/performance.md`, "Worst cases".
//!
//! # Nearest, and why the classification is exact
//!
//! The nearest trapezoid at pixel `(i, j)` is the one whose face's plane
//! has the smallest depth `z` at the pixel centre; at equal depth, the
//! face with the lower key ([`Face::key`]: lower segment, then earlier
//! polygon). Depths are first compared in fixed point ([`Depth`]);
//! when two are closer than [`DEPTH_TOLERANCE`], where rounding could
//! decide, they are compared exactly ([`Plane::cmp_at`](crate::visible::trapezoid::Plane::cmp_at)). So every
//! comparison is exact.
//!
//! Each trapezoid covering a span covers all of it, and along a row the
//! depth difference of two planes is affine. If one trapezoid is nearer
//! than another at both end pixels of a span, it is nearer at every pixel
//! between (an affine function non-negative at both ends is non-negative
//! between, and zero inside only if zero everywhere, where the key
//! decides). So a span whose nearest trapezoid is the same at both ends is
//! that trapezoid's, and subdividing an intersecting span down to such
//! parts gives exactly the nearest plane at every pixel centre. Both
//! [`Resolve`] modes are therefore exact for planar faces; they differ in
//! speed.
//!
//! The front rests on the same argument, pair by pair: two trapezoids both
//! cover the pixels from the later `l` to the earlier `r`, so a front that
//! is nearer than a trapezoid at the sweep's position and at the last of
//! their common pixels is nearer on all of them. It is checked so against
//! every trapezoid covering the position when it is found, and against
//! every trapezoid that starts while it holds, so it is the nearest on
//! every pixel it is given. A trapezoid it hides entirely never shows.
//!
//! # Memory
//!
//! An [`Active`] slot is 120 bytes: one trapezoid's stepping state (two
//! edges, depth) and one element each of the sorted, cover and free
//! arrays (a cover is 16 bytes: its `r` and depth, and the position of
//! its trapezoid in the sorted array, where its face and colour are
//! read). The list needs as many slots as trapezoids overlap one row
//! ([`Workspace::check`] finds the number before anything is drawn). A
//! row of runs needs at most the frame's width of [`Run`]s.
//!
//! # Measured
//!
//! Both modes give **0 mismatched pixels** against the exact reference
//! (`testkit::reference3d`) on every scene the tests and the benchmark
//! draw. The cost, on the host and on the Cortex-M4, is in
//! `docs/performance.md` (the 3D scenes, the depth-complexity sweep, P3
//! against P4, the on-target section), measured by one command each, and
//! its history in `docs/performance-log.md`; `cargo run --release -p host-tests --example
//! visible_modes` measures the four 512 × 256 scenes on the host and
//! writes them as display lists with `-- --write-lists DIR`. A
//! test-only module, `coherence`, counts what coherence between rows
//! could reuse ("Where the sweep's instructions go on the Cortex-M4").
//!
//! [`Resolve::Paint`] resolves a frame another way, into a target that
//! keeps its pixels: far to near, each trapezoid's pixels written in
//! full, depths compared only between trapezoids whose ranges of depth
//! overlap (the `paint` module).
//!
//! [`Face::key`]: crate::visible::store::Face::key

use crate::color::ListColor;
use crate::port::Counts;
use crate::port::SpanTarget;
use crate::port::{RowRun, Span};
use crate::raster::edge::Edge;
use crate::visible::rle::{Run, RunWriter, RunsFull};
use crate::visible::store::TrapezoidStore;
use crate::visible::trapezoid::{Depth, Trapezoid, DEPTH_TOLERANCE, NONE};
use core::fmt;

/// How an intersecting span is subdivided.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Resolve {
    /// Half-interval bisection: split in the middle, classify both
    /// halves, until every part has the same nearest trapezoid at both
    /// ends (at worst, single pixels). `log₂(length)` levels.
    Bisect,
    /// The exact crossing point: split where the planes of the two
    /// trapezoids nearest at the ends meet along the row (one division),
    /// then classify both parts. A part that is still intersecting (a
    /// third plane in between) is split the same way if it is at most half
    /// the span, else bisected once first, so the depth of the subdivision
    /// stays below `2·log₂(length)`.
    Crossing,
    /// Painting far to near, into a target that keeps its pixels (a
    /// frame buffer): every trapezoid's pixels written in full,
    /// nearer ones over farther ones, with depths compared only between
    /// trapezoids whose ranges of depth overlap (where planes cross, at
    /// the exact crossing pixel, as `Crossing`). The same pixels as the
    /// sweep, exactly; each pixel is written as often as trapezoids cover
    /// it, so it is meant for memory, not for a display's window: a
    /// frame buffer ([`draw`]) or a band buffer ([`Sweep::draw`], and so
    /// the band renderers). Where runs are asked for
    /// ([`Workspace::resolve`]) it resolves as `Crossing`. See
    /// `docs/performance.md`, "Painting far to near".
    Paint,
    /// `Paint` or `Crossing`, chosen once a frame from its trapezoids:
    /// `Paint` where they are tall, at least [`PAINT_FROM`] rows each on
    /// average, and the target's overdraw is cheap
    /// ([`SpanTarget::OVERDRAW_IS_CHEAP`]: a frame buffer, a band);
    /// `Crossing` elsewhere, and where a frame's runs are asked for
    /// ([`Workspace::resolve`]). Both draw the same pixels, exactly, so
    /// the choice changes only the work: painting costs more than the
    /// sweep for each trapezoid that enters (its tests against the live
    /// ones) and less for each row of one. What each costs on the
    /// Cortex-M4 is in `docs/performance.md`, "Which resolve a frame
    /// takes"; [`VisibleStats::mode`] says which a frame took. The
    /// default.
    #[default]
    Auto,
}

/// The least mean height of a frame's trapezoids, in rows, at which
/// [`Resolve::Auto`] paints.
pub const PAINT_FROM: u32 = 14;

impl Resolve {
    /// The mode a frame of `trapezoids` trapezoids, `rows` trapezoid-rows
    /// in all, is drawn with: [`Resolve::Auto`] settled by the frame's
    /// mean height, every other mode itself.
    pub fn settle(self, trapezoids: u32, rows: u32) -> Resolve {
        match self {
            Resolve::Auto if trapezoids > 0 && rows / trapezoids >= PAINT_FROM => Resolve::Paint,
            Resolve::Auto => Resolve::Crossing,
            m => m,
        }
    }
}

/// One slot of the workspace's active list (120 bytes on 32-bit
/// targets): the caller provides as many as trapezoids may overlap one
/// row, filled with [`Active::EMPTY`], and nothing else but the runs.
///
/// Each slot holds one active trapezoid's stepping state (at a slot that
/// does not move while it is active) and one element of each of the three
/// arrays the resolution works on: the live trapezoids sorted by `l` with
/// what the sweep reads, the covers of the sweep's position (by
/// decreasing `r`), and the stack of free slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Active {
    entry: Entry,
    hot: Hot,
    cover: Covered,
    free: u16,
}

/// An active trapezoid's stepping state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Entry {
    left: Edge,
    right: Edge,
    /// `Z̃` at column 0 of the current row; `zy` next to it, as
    /// [`step_live`] reads both (one double-word load on the Cortex-M4).
    z: i32,
    zy: i32,
    zx: i32,
    /// The face's colour as a [`list_word`](crate::color::list_word),
    /// converted to the target's pixel once per run without shifts.
    color: u32,
    face: u16,
    x0: u16,
    x1: u16,
    /// Its index in the store, for [`continuation`] (`NONE` from
    /// [`Entry::from`] until the sweep sets it).
    trap: u16,
}

/// A live trapezoid on the current row, in the array sorted by `l`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Hot {
    /// Pixels `l..r` on the row, cut to the columns; `r ≤ l` when there
    /// is none (then it keeps its place in the order and never enters).
    l: i32,
    r: i32,
    z: i32,
    zx: i32,
    color: u32,
    face: u16,
    slot: u16,
}

/// One element of the cover array (16 bytes, in each [`Active`] slot): a
/// trapezoid that has started on the row and may still show, as its `r`
/// and depth (read by the leave checks and the depth compares without
/// going to the trapezoid) and its position `p` in the array sorted by
/// `l`, `act[..k].hot`, which does not change while the row is swept: its
/// colour and face are read there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Covered {
    r: i32,
    z: i32,
    zx: i32,
    p: u16,
}

impl Covered {
    /// An unused element.
    const EMPTY: Covered = Covered {
        r: 0,
        z: 0,
        zx: 0,
        p: 0,
    };

    /// The element of the live trapezoid `h`, at `p` in the sorted array.
    #[inline(always)]
    fn of(h: &Hot, p: usize) -> Covered {
        Covered {
            r: h.r,
            z: h.z,
            zx: h.zx,
            p: p as u16,
        }
    }

    #[inline(always)]
    fn z_at(&self, i: i32) -> i32 {
        self.z.wrapping_add(self.zx.wrapping_mul(i))
    }
}

/// A cover by value, for the computations on it (the front, a span's
/// nearest): its element of the cover array and what it reads of its
/// trapezoid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Cover {
    r: i32,
    z: i32,
    zx: i32,
    color: u32,
    face: u16,
    p: u16,
}

impl Cover {
    /// An unused cover.
    const EMPTY: Cover = Cover {
        r: 0,
        z: 0,
        zx: 0,
        color: 0,
        face: NONE,
        p: 0,
    };

    /// Its element of the cover array.
    #[inline(always)]
    fn element(&self) -> Covered {
        Covered {
            r: self.r,
            z: self.z,
            zx: self.zx,
            p: self.p,
        }
    }

    #[inline(always)]
    fn z_at(&self, i: i32) -> i32 {
        self.z.wrapping_add(self.zx.wrapping_mul(i))
    }
}

impl Entry {
    const EMPTY: Entry = Entry {
        left: Edge::EMPTY,
        right: Edge::EMPTY,
        z: 0,
        zx: 0,
        zy: 0,
        color: 0,
        face: NONE,
        x0: 0,
        x1: 0,
        trap: NONE,
    };

    /// Trapezoid `t` of `store` on its top row: its edges' steppers
    /// rebuilt from their ends, its face's depth and colour. A depth left
    /// for later stays so ([`Depth::LATER`]: `zx` is `i32::MIN`, `zy` 0),
    /// stepped row by row as it is, until [`work_out_depths`]. Inlined
    /// into its callers: out of line, the sweep costs more instructions
    /// on the Cortex-M4.
    #[inline(always)]
    fn from(t: &Trapezoid, store: &TrapezoidStore<'_>) -> Entry {
        let (d, color) = Entry::face_of(t, store);
        Entry::with(t, d, color)
    }

    /// The depth (as stored: [`Depth::LATER`] when left for later) and
    /// colour of `t`'s face, as an entry takes them.
    #[inline(always)]
    fn face_of(t: &Trapezoid, store: &TrapezoidStore<'_>) -> (Depth, u32) {
        store.face(t.face).map_or((Default::default(), 0), |f| {
            (f.depth_or_later(), crate::color::list_word(f.color_bits()))
        })
    }

    /// Sets `self` to [`Entry::from`] of `t`, field by field: each edge's
    /// stepper is made where it is kept, not on the stack and copied.
    #[inline(always)]
    fn set_from(&mut self, t: &Trapezoid, store: &TrapezoidStore<'_>) {
        let (d, color) = Entry::face_of(t, store);
        self.left = t.left();
        self.right = t.right();
        self.z = d.at(0, t.top());
        self.zx = d.zx;
        self.zy = d.zy;
        self.color = color;
        self.face = t.face;
        self.x0 = t.x0;
        self.x1 = t.x1;
        self.trap = NONE;
    }

    /// [`Entry::from`] with the face's depth `d` and colour `color` (a
    /// [`list_word`](crate::color::list_word)) given.
    #[inline(always)]
    fn with(t: &Trapezoid, d: Depth, color: u32) -> Entry {
        Entry {
            left: t.left(),
            right: t.right(),
            z: d.at(0, t.top()),
            zx: d.zx,
            zy: d.zy,
            color,
            face: t.face,
            x0: t.x0,
            x1: t.x1,
            trap: NONE,
        }
    }

    /// The row's pixels `l..r`, cut to the columns, and depth. With no
    /// pixel, `r ≤ l`: such a trapezoid keeps its place in the order by
    /// `l` (a mesh's thin faces lose and regain their pixels from row to
    /// row, and would otherwise move to the end and back) and is never
    /// entered (the sweeps pass it by).
    #[inline(always)]
    fn pixels(&self) -> (i32, i32, i32) {
        let l = self.left.pixel_now().max(self.x0 as i32);
        let r = self.right.pixel_now().min(self.x1 as i32);
        (l, r, self.z)
    }

    /// The row's element of the sorted array.
    #[inline(always)]
    fn hot(&self, slot: u16) -> Hot {
        let (l, r, z) = self.pixels();
        Hot {
            l,
            r,
            z,
            zx: self.zx,
            color: self.color,
            face: self.face,
            slot,
        }
    }
}

impl Active {
    /// An unused entry.
    pub const EMPTY: Active = Active {
        entry: Entry::EMPTY,
        hot: Hot {
            l: 0,
            r: 0,
            z: 0,
            zx: 0,
            color: 0,
            face: NONE,
            slot: 0,
        },
        cover: Covered::EMPTY,
        free: 0,
    };
}

/// Why a frame could not be resolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum VisibleError<E> {
    /// More trapezoids overlap a row than the active list holds.
    Active {
        /// Entries it holds.
        capacity: usize,
    },
    /// A row needs more runs than the buffer holds (never when it holds
    /// the frame's width).
    Runs {
        /// Runs it holds.
        capacity: usize,
    },
    /// The caller's row sink failed.
    Sink(E),
}

impl<E: fmt::Debug> fmt::Display for VisibleError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VisibleError::Active { capacity } => write!(
                f,
                "more trapezoids overlap a row than the {capacity} active entries"
            ),
            VisibleError::Runs { capacity } => {
                write!(f, "a row needs more than the {capacity} runs available")
            }
            VisibleError::Sink(e) => write!(f, "row sink failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for VisibleError<E> {}

impl VisibleError<core::convert::Infallible> {
    /// The same error where another sink's errors are expected (this one
    /// has none).
    pub(crate) fn widen<E>(self) -> VisibleError<E> {
        match self {
            VisibleError::Active { capacity } => VisibleError::Active { capacity },
            VisibleError::Runs { capacity } => VisibleError::Runs { capacity },
            VisibleError::Sink(e) => match e {},
        }
    }
}

impl<E> From<RunsFull> for VisibleError<E> {
    fn from(e: RunsFull) -> Self {
        VisibleError::Runs {
            capacity: e.capacity,
        }
    }
}

/// What resolving a frame did. A frame painted ([`Resolve::Paint`])
/// resolves no spans: it counts its rows, trapezoids, most active, the
/// crossings it split a trapezoid's pixels at (`splits`) and its exact
/// comparisons, and leaves the span counts and `runs` at 0 (but for rows
/// it left to the sweep).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct VisibleStats {
    /// How the frame was resolved: the mode asked for, [`Resolve::Auto`]
    /// settled to `Paint` or `Crossing`. A frame painted band by band
    /// that ran out of conflict records, and went on as the sweep, stays
    /// `Paint`; where nothing was resolved (no 3D layer), the default,
    /// `Auto`.
    pub mode: Resolve,
    /// Rows produced.
    pub rows: u32,
    /// Trapezoids that entered the active list.
    pub trapezoids: u32,
    /// Most entries active on one row.
    pub max_active: u32,
    /// Trapezoids left out of a row where they start, because the
    /// trapezoid in front where they start is in front of all of them.
    pub hidden: u32,
    /// Spans with no trapezoid.
    pub empty: u32,
    /// Spans with one trapezoid.
    pub single: u32,
    /// Spans with several, the same nearest at both ends.
    pub multiple: u32,
    /// Spans with several, different nearest at the ends.
    pub intersecting: u32,
    /// Subdivisions of intersecting spans (and of their parts).
    pub splits: u32,
    /// Depth comparisons too close for fixed point, made exactly.
    pub exact: u32,
    /// Runs written (after merging).
    pub runs: u32,
}

/// The caller's memory for the visible-surface stage: the active list
/// and one row of runs.
#[derive(Debug)]
pub struct Workspace<'a> {
    active: &'a mut [Active],
    runs: &'a mut [Run],
}

impl<'a> Workspace<'a> {
    /// A workspace over `active` (its length is the capacity, at most
    /// 65535 used) and `runs` (at least the frame's width).
    pub fn new(active: &'a mut [Active], runs: &'a mut [Run]) -> Self {
        Workspace { active, runs }
    }

    /// Trapezoids that may overlap one row.
    pub fn capacity(&self) -> usize {
        capacity(self.active)
    }

    /// Runs available for one row.
    pub fn run_capacity(&self) -> usize {
        self.runs.len()
    }

    /// Finds the most trapezoids of `store` that overlap one row, without
    /// resolving anything, and checks it against the active list; checks
    /// that a row of the store's width fits the run buffer. O(rows +
    /// trapezoids) when the run buffer has at least as many runs as the
    /// store has rows (a square frame's or a wide one's), else O(rows +
    /// trapezoids × log overlap).
    pub fn check(
        &mut self,
        store: &TrapezoidStore<'_>,
    ) -> Result<u32, VisibleError<core::convert::Infallible>> {
        self.check_rows(store).map(|c| c.most)
    }

    /// [`check`](Self::check), with the frame's trapezoids and
    /// trapezoid-rows counted on the way (for [`Resolve::settle`]).
    pub(crate) fn check_rows(
        &mut self,
        store: &TrapezoidStore<'_>,
    ) -> Result<Checked, VisibleError<core::convert::Infallible>> {
        if self.runs.len() < store.width() as usize {
            return Err(VisibleError::Runs {
                capacity: self.runs.len(),
            });
        }
        let cap = self.capacity();
        if let Some(ends) = self.runs.get_mut(..store.height() as usize) {
            // The trapezoids that end on each row, counted in the runs'
            // lengths as each starts (at most 65535: the store's), and the
            // overlap kept row by row. Those that end at the store's
            // height are never taken off: no row follows.
            ends.fill(Run::EMPTY);
            let (mut k, mut most, mut entered, mut rows) = (0usize, 0usize, 0u32, 0u32);
            for y in 0..store.height() {
                k -= ends[y as usize].len() as usize;
                let mut t = store.row_head(y as usize);
                while let Some(tr) = store.trapezoid(t) {
                    if k >= cap {
                        return Err(VisibleError::Active { capacity: cap });
                    }
                    k += 1;
                    entered += 1;
                    if let Some(e) = ends.get_mut(tr.end() as usize) {
                        *e = Run::new(e.len() + 1, 0);
                    }
                    t = tr.next_row;
                }
                most = most.max(k);
                // At most 65535 live on each of at most 65535 rows.
                rows = rows.wrapping_add(k as u32);
            }
            return Ok(Checked {
                most: most as u32,
                trapezoids: entered,
                rows,
            });
        }
        // The last rows of the trapezoids overlapping the row, as a binary
        // min-heap in `active[..k].cover.r`: O(log k) per trapezoid,
        // nothing per row where none starts or ends.
        let heap = &mut self.active[..cap];
        let (mut k, mut most, mut entered, mut rows) = (0usize, 0usize, 0u32, 0u32);
        for y in 0..store.height() {
            // A trapezoid starting on the row takes the place of one that
            // ended (as often when a face's second trapezoid follows its
            // first): one sift instead of two.
            let mut t = store.row_head(y as usize);
            while k > 0 && heap[0].cover.r <= y as i32 {
                if let Some(tr) = store.trapezoid(t) {
                    heap[0].cover.r = tr.end();
                    t = tr.next_row;
                    entered += 1;
                } else {
                    k -= 1;
                    heap[0].cover.r = heap[k].cover.r;
                }
                sift_down(&mut heap[..k]);
            }
            while let Some(tr) = store.trapezoid(t) {
                if k >= cap {
                    return Err(VisibleError::Active { capacity: cap });
                }
                heap[k].cover.r = tr.end();
                k += 1;
                entered += 1;
                sift_up(&mut heap[..k]);
                t = tr.next_row;
            }
            most = most.max(k);
            rows = rows.wrapping_add(k as u32);
        }
        Ok(Checked {
            most: most as u32,
            trapezoids: entered,
            rows,
        })
    }

    /// Resolves every row of `store`, top to bottom, handing each row's
    /// runs to `sink(y, runs)`. The runs cover the store's width.
    pub fn resolve<E>(
        &mut self,
        store: &TrapezoidStore<'_>,
        mode: Resolve,
        sink: impl FnMut(u16, &[Run]) -> Result<(), E>,
    ) -> Result<VisibleStats, VisibleError<E>> {
        self.check_runs(store)?;
        let out = ToSink {
            out: RunWriter::new(self.runs),
            sink,
            y: 0,
        };
        resolve_into(self.active, store, mode, out).map(|(stats, _)| stats)
    }

    /// `Err` when a row of the store's width does not fit the run buffer.
    fn check_runs<E>(&self, store: &TrapezoidStore<'_>) -> Result<(), VisibleError<E>> {
        if self.runs.len() < store.width() as usize {
            return Err(VisibleError::Runs {
                capacity: self.runs.len(),
            });
        }
        Ok(())
    }
}

/// What [`Workspace::check_rows`] counts of a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Checked {
    /// The most trapezoids overlapping one row.
    pub(crate) most: u32,
    /// Trapezoids linked into the rows (those of hidden segments are not).
    pub(crate) trapezoids: u32,
    /// Their rows, added up.
    pub(crate) rows: u32,
}

impl Checked {
    /// The mode `resolve` settles to for this frame ([`Resolve::settle`]).
    pub(crate) fn settle(&self, resolve: Resolve) -> Resolve {
        resolve.settle(self.trapezoids, self.rows)
    }
}

/// The capacity of an active list: its length, at most 65535.
fn capacity(active: &[Active]) -> usize {
    active.len().min(NONE as usize)
}

/// Moves the last element of the min-heap `h` (by `cover.r`) up to its
/// place.
fn sift_up(h: &mut [Active]) {
    let Some(mut i) = h.len().checked_sub(1) else {
        return;
    };
    let r = h[i].cover.r;
    while i > 0 {
        let parent = (i - 1) / 2;
        if h[parent].cover.r <= r {
            break;
        }
        h[i].cover.r = h[parent].cover.r;
        i = parent;
    }
    h[i].cover.r = r;
}

/// Moves the first element of the min-heap `h` (by `cover.r`) down to its
/// place.
fn sift_down(h: &mut [Active]) {
    let Some(r) = h.first().map(|c| c.cover.r) else {
        return;
    };
    let mut i = 0;
    loop {
        let mut child = 2 * i + 1;
        let Some(left) = h.get(child) else { break };
        if h.get(child + 1).is_some_and(|c| c.cover.r < left.cover.r) {
            child += 1;
        }
        if r <= h[child].cover.r {
            break;
        }
        h[i].cover.r = h[child].cover.r;
        i = child;
    }
    h[i].cover.r = r;
}

/// Resolves every row of `store` into `out`, with the active list of a
/// workspace. Returns `out` when done.
fn resolve_into<O: RowOut>(
    active: &mut [Active],
    store: &TrapezoidStore<'_>,
    mode: Resolve,
    out: O,
) -> Result<(VisibleStats, O), VisibleError<O::Error>> {
    resolve_many_from(active, store, mode, (MANY, CHAIN_FROM), out)
}

/// [`resolve_into`], rows with more than `many.0` live trapezoids taking
/// [`sweep_many`], which looks for chains past `many.1` covers.
fn resolve_many_from<O: RowOut>(
    active: &mut [Active],
    store: &TrapezoidStore<'_>,
    mode: Resolve,
    many: (usize, usize),
    out: O,
) -> Result<(VisibleStats, O), VisibleError<O::Error>> {
    // Runs are asked for: painting resolves as crossing points here.
    let mode = match mode {
        Resolve::Paint | Resolve::Auto => Resolve::Crossing,
        m => m,
    };
    let mut s = Sweep::start(active, mode);
    s.many = many;
    let out = s.rows(active, store, store.height(), out)?;
    Ok((s.stats, out))
}

/// A frame's resolution under way, top to bottom: the rows done so far
/// and where the active list stands. It holds no memory of its own; the
/// workspace it started with and the store are passed to each call, so
/// that the store can be shared (read only) by several sweeps, each with
/// its own workspace, each drawing some bands and skipping the others.
///
/// [`Sweep::draw`] resolves the next rows into a port; [`Sweep::skip`]
/// moves the active list over rows without resolving them (one jump per
/// trapezoid live after them, whatever their number; no sort, no sweep).
///
/// Started with [`Resolve::Paint`], it paints the rows far to near
/// instead (the target must keep its pixels for the rows of a call: a
/// band buffer does), its conflict records in the workspace's runs; its
/// skips jump the same way, and each trapezoid that starts in the rows
/// skipped and lasts past them is tested against the live ones once,
/// after them. Out of records, it goes on as a sweep with crossing
/// points from the row where they ran out (see the `paint` module).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub struct Sweep {
    /// The next row.
    y: u16,
    /// `act[..k].hot.slot`: the live trapezoids.
    k: usize,
    /// `act[..nf].free`: the free slots.
    nf: usize,
    /// The workspace's capacity when the sweep started.
    cap: usize,
    mode: Resolve,
    /// Live trapezoids past which a row takes [`sweep_many`], and covers
    /// past which it looks for a chain.
    many: (usize, usize),
    stats: VisibleStats,
    /// With [`Resolve::Paint`], the frame painted so far (`None` once it
    /// has fallen back to the sweep, or in the other modes).
    painter: Option<paint::Painter>,
    /// The last row was written side by side: the next is handed to the
    /// output's writer at once, which finds out as it writes whether it
    /// is (a mesh's rows mostly are), and not tested first.
    side: bool,
}

impl Sweep {
    /// A sweep at row 0 with `workspace`, resolving intersecting spans by
    /// `mode`. The same workspace and the same store, unchanged, must be
    /// passed to every call after (a workspace of another capacity is
    /// refused; another store gives another picture, never a panic).
    pub fn new(workspace: &mut Workspace<'_>, mode: Resolve) -> Sweep {
        Sweep::start(workspace.active, mode)
    }

    fn start(active: &mut [Active], mode: Resolve) -> Sweep {
        // Not settled by the frame (`Sweep::new` has no store): the sweep.
        let mode = match mode {
            Resolve::Auto => Resolve::Crossing,
            m => m,
        };
        let cap = capacity(active);
        for (i, a) in active[..cap].iter_mut().enumerate() {
            a.free = i as u16;
        }
        let painter = (mode == Resolve::Paint).then(|| paint::Painter::start(active));
        Sweep {
            y: 0,
            k: 0,
            nf: cap,
            cap,
            mode,
            many: (MANY, CHAIN_FROM),
            stats: VisibleStats {
                mode,
                ..VisibleStats::default()
            },
            painter,
            side: false,
        }
    }

    /// The next row to draw or skip.
    pub fn next_row(&self) -> u16 {
        self.painter.map_or(self.y, |p| p.y)
    }

    /// Goes on from row `y` as a sweep with crossing points: a painter
    /// out of conflict records or of parts. The active list is rebuilt
    /// for row `y` at once ([`jump`] from the top); rows before `y` stay
    /// as painted, and row `y`'s pixels that painting wrote are all
    /// covered by trapezoids, so the sweep writes them again.
    fn fall_back(
        &mut self,
        active: &mut [Active],
        store: &TrapezoidStore<'_>,
        y: u16,
    ) -> Result<(), VisibleError<core::convert::Infallible>> {
        let (stats, many) = (self.stats, self.many);
        *self = Sweep::start(active, Resolve::Crossing);
        (self.stats, self.many) = (stats, many);
        let act = &mut active[..self.cap];
        if y > 0 {
            let (k, nf) = jump(act, store, (0, self.nf), (0, y))
                .ok_or(VisibleError::Active { capacity: self.cap })?;
            (self.y, self.k, self.nf) = (y, k, nf);
        }
        Ok(())
    }

    /// What the rows resolved so far did.
    pub fn stats(&self) -> VisibleStats {
        self.stats
    }

    /// Resolves the next `rows` rows of `store` (cut at its height) and
    /// writes them into `target` as [`draw`] does: faces in their
    /// colours, the background filled with `background` or left as it is.
    ///
    /// Not inlined, so that a band renderer runs the sweep as compiled
    /// for [`draw`]: inlined into `ListBands::draw`, it compiles to more
    /// instructions a row on a Cortex-M4.
    #[inline(never)]
    pub fn draw<T>(
        &mut self,
        store: &TrapezoidStore<'_>,
        workspace: &mut Workspace<'_>,
        rows: u16,
        target: &mut T,
        background: Option<T::Color>,
    ) -> Result<Counts, VisibleError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        self.check(workspace)?;
        let mut runs = pending_runs();
        let mut out = ToTarget::new(target, background, batch_of::<T>(&mut runs));
        let mut rows = rows;
        if let Some(mut p) = self.painter {
            let end = p.y.saturating_add(rows).min(store.height());
            let painted = p.rows(
                workspace.active,
                workspace.runs,
                store,
                rows,
                &mut out,
                &mut self.stats,
            );
            self.painter = Some(p);
            let Some(y) = painted? else {
                return Ok(out.counts);
            };
            // The rest of the rows by the sweep.
            self.fall_back(workspace.active, store, y)
                .map_err(|e| e.widen())?;
            rows = end - y;
        }
        let out = self.rows(workspace.active, store, rows, out)?;
        Ok(out.counts)
    }

    /// Steps over the next `rows` rows of `store` (cut at its height)
    /// without resolving them, at once: the active list left as stepping
    /// it row by row leaves it (the same trapezoids, in an order the next
    /// row's sort takes as it takes the stepped one's, edges moved by
    /// [`Edge::advance`]), at the cost of one jump per
    /// trapezoid live after the rows, not of a step per row.
    ///
    /// Not inlined, as [`draw`](Self::draw) is not: inlined into
    /// `ListBands::draw`, it makes the Cortex-M4 build of the 2D band path
    /// cost more instructions.
    #[inline(never)]
    pub fn skip(
        &mut self,
        store: &TrapezoidStore<'_>,
        workspace: &mut Workspace<'_>,
        rows: u16,
    ) -> Result<(), VisibleError<core::convert::Infallible>> {
        self.check(workspace)?;
        if let Some(mut p) = self.painter {
            let jumped = p.skip(
                workspace.active,
                workspace.runs,
                store,
                rows,
                &mut self.stats,
            );
            self.painter = Some(p);
            if let Some(y) = jumped? {
                self.fall_back(workspace.active, store, y)?;
            }
            return Ok(());
        }
        let act = &mut workspace.active[..self.cap];
        let end = self.y.saturating_add(rows).min(store.height());
        if end <= self.y {
            return Ok(());
        }
        let (k, nf) = jump(act, store, (self.k, self.nf), (self.y, end))
            .ok_or(VisibleError::Active { capacity: self.cap })?;
        (self.y, self.k, self.nf) = (end, k, nf);
        Ok(())
    }

    /// `Err` when `workspace` is not of the capacity the sweep started
    /// with.
    fn check<E>(&self, workspace: &Workspace<'_>) -> Result<(), VisibleError<E>> {
        if workspace.capacity() != self.cap {
            return Err(VisibleError::Active {
                capacity: workspace.capacity(),
            });
        }
        Ok(())
    }

    /// Resolves the next `rows` rows into `out`.
    fn rows<O: RowOut>(
        &mut self,
        active: &mut [Active],
        store: &TrapezoidStore<'_>,
        rows: u16,
        out: O,
    ) -> Result<O, VisibleError<O::Error>> {
        let width = store.width() as i32;
        let cap = self.cap;
        let act = &mut active[..cap];
        let mut cx = Ctx {
            store,
            out,
            ink: Run::BACKGROUND,
            len: 0,
            color: BACKGROUND,
            mode: self.mode,
            y: 0,
            stats: self.stats,
        };
        // act[..k].hot: the live trapezoids, sorted by l as of the last
        // row; act[..nf].free: the free slots.
        let (mut k, mut nf, mut side) = (self.k, self.nf, self.side);
        let mut fresh = Fresh::EMPTY;
        let end = self.y.saturating_add(rows).min(store.height());
        for y in self.y..end {
            let yi = y as i32;
            cx.y = yi;
            // Step the live trapezoids to this row, dropping those that
            // ended, and reload their pixels (in place, keeping the order).
            // A trapezoid that continues one that ended on the row above
            // ([`continues`]) has taken its place there, and so has one
            // of the others where one without a continuation ended at
            // its upper corner ([`Fresh`]).
            fresh.reset();
            (k, nf) = step_live(act, k, nf, yi, store, &mut fresh);
            let mut placed = fresh.placed;
            // Enter the rest of the trapezoids whose top is this row.
            let stepped = k;
            let mut t = store.row_head(y as usize);
            while let Some(tr) = store.trapezoid(t) {
                if continues(store, t, tr) {
                    cx.stats.trapezoids += 1;
                    t = tr.next_row;
                    continue;
                }
                let here = placed & 1 != 0;
                placed >>= 1;
                if here {
                    cx.stats.trapezoids += 1;
                    t = tr.next_row;
                    continue;
                }
                if nf == 0 {
                    return Err(VisibleError::Active { capacity: cap });
                }
                nf -= 1;
                let slot = act[nf].free;
                let e = &mut act[slot as usize].entry;
                e.set_from(tr, store);
                e.trap = t;
                let h = e.hot(slot);
                act[k].hot = h;
                k += 1;
                cx.stats.trapezoids += 1;
                t = tr.next_row;
            }
            cx.stats.max_active = cx.stats.max_active.max(k as u32);
            cx.out.start(y);
            (cx.ink, cx.len, cx.color) = (Run::BACKGROUND, 0, BACKGROUND);
            if k == 0 {
                cx.len = width;
                cx.stats.empty += 1;
            } else {
                // Trapezoids that entered at the end, or edges that
                // crossed, leave the row out of order: sorted, it may
                // still be side by side. After a row written so, the
                // output's writer takes the row at once and finds out
                // as it writes it (a mesh's rows mostly are); after
                // another, or for an output with no writer of its own,
                // a pass that stops at the first overlap finds it first
                // (the rows of faces that overlap mostly do).
                if k > self.many.0 {
                    sort_many(act, stepped, k);
                } else {
                    sort(&mut act[..k]);
                }
                let live = &act[..k];
                let out = match side {
                    true => cx.out.side_by_side(live, width, &mut cx.stats),
                    false => None,
                };
                let written = match out {
                    Some(w) => w,
                    None if side_by_side(live, width) == Row::SideBySide => {
                        if cx.out.side_by_side(live, width, &mut cx.stats).is_none() {
                            write_side_by_side(live, width, &mut cx);
                        }
                        true
                    }
                    None => false,
                };
                side = written;
                if !written {
                    // Trapezoids may share the row's pixels: their
                    // depths are read.
                    work_out_depths(act, k, store, yi);
                    if k > self.many.0 {
                        sweep_many(act, k, width, self.many.1, &mut cx);
                    } else {
                        sweep(act, k, width, &mut cx);
                    }
                }
            }
            cx.flush();
            cx.stats.rows += 1;
            cx.stats.runs += cx.out.finish().map_err(VisibleError::Sink)?;
            // Saved row by row: an error leaves the sweep where it stopped.
            (self.y, self.k, self.nf, self.side) = (y + 1, k, nf, side);
        }
        self.stats = cx.stats;
        Ok(cx.out)
    }
}

/// Moves the active list over rows `y0..y1` (`y0 < y1`) at once, from
/// the live trapezoids `act[..k]` of row `y0 − 1` and the free slots
/// `act[..nf]` to those of row `y1 − 1`, as [`step_live`] and entering
/// row by row would leave them, the elements in this order: the live
/// trapezoids that last past the rows, then those that start in the rows
/// and last past them, in the order they would have entered (row by row,
/// one that continues another would have taken its place). Each
/// is moved down by [`Edge::advance`] (a division per edge, exact), its
/// depth by a product; a trapezoid that starts and ends within the rows
/// is never entered. The new `k` and `nf`; `None` when the free slots run
/// out (a workspace smaller than the rows need).
fn jump(
    act: &mut [Active],
    store: &TrapezoidStore<'_>,
    (k, mut nf): (usize, usize),
    (y0, y1): (u16, u16),
) -> Option<(usize, usize)> {
    let last = y1 as i32 - 1;
    let mut w = 0;
    for p in 0..k {
        let slot = act[p].hot.slot;
        let e = &mut act[slot as usize].entry;
        if e.left.end() <= last {
            act[nf].free = slot;
            nf += 1;
            continue;
        }
        let n = (y1 - y0) as u32;
        e.left.advance(n);
        e.right.advance(n);
        e.z = e.z.wrapping_add(e.zy.wrapping_mul(n as i32));
        act[w].hot = e.hot(slot);
        w += 1;
    }
    for y in y0..y1 {
        let mut t = store.row_head(y as usize);
        while let Some(tr) = store.trapezoid(t) {
            let index = t;
            t = tr.next_row;
            if tr.end() <= last {
                continue;
            }
            nf = nf.checked_sub(1)?;
            let slot = act[nf].free;
            let e = &mut act[slot as usize].entry;
            *e = Entry::from(tr, store);
            e.trap = index;
            if e.left.end() <= last {
                // Not so in a store as built (its edges span its rows).
                nf += 1;
                continue;
            }
            let n = (last - y as i32) as u32;
            e.left.advance(n);
            e.right.advance(n);
            e.z = e.z.wrapping_add(e.zy.wrapping_mul(n as i32));
            act[w].hot = e.hot(slot);
            w += 1;
        }
    }
    Some((w, nf))
}

/// Steps the live trapezoids `act[..k]` to row `y`, dropping those that
/// ended onto the free stack `act[..nf]`, and reloads their pixels (in
/// place, keeping the order); the new `k` and `nf`. Where a trapezoid
/// ended, the one of `store` that [`continues`] it (the other half of a
/// triangle, below its middle corner) takes its slot and its place in
/// the order ([`continuation`]), where its left pixel usually is,
/// instead of entering at the end and being moved there by the sort.
/// Not inlined: kept out of the row loop's registers, it costs fewer
/// instructions on the Cortex-M4 (figures in `docs/performance-log.md`).
#[inline(never)]
fn step_live(
    act: &mut [Active],
    k: usize,
    mut nf: usize,
    y: i32,
    store: &TrapezoidStore<'_>,
    fresh: &mut Fresh,
) -> (usize, usize) {
    let k = k.min(act.len());
    // In place up to the first that ends with nothing to take its place.
    let mut first = step_in_place(act, 0, k, y);
    while first < k {
        let slot = act[first].hot.slot;
        let e = &mut act[slot as usize].entry;
        if !(continuation(e, store, y) || fresh.join(e, store, y)) {
            act[nf].free = slot;
            nf += 1;
            break;
        }
        act[first].hot = e.hot(slot);
        first = step_in_place(act, first + 1, k, y);
    }
    let mut w = first;
    for p in (first + 1).min(k)..k {
        let slot = act[p].hot.slot;
        let e = &mut act[slot as usize].entry;
        if e.left.end() <= y {
            if continuation(e, store, y) || fresh.join(e, store, y) {
                act[w].hot = e.hot(slot);
                w += 1;
                continue;
            }
            act[nf].free = slot;
            nf += 1;
            continue;
        }
        step_edge(&mut e.left);
        step_edge(&mut e.right);
        e.z = e.z.wrapping_add(e.zy);
        let h = e.hot(slot);
        act[w].hot = h;
        w += 1;
    }
    (w, nf)
}

/// `true` when trapezoid `t` of `store`, `tr`, continues the one before
/// it in the store's pool: of the same face, that one ends on the row
/// where `tr` starts. The cut stores a triangle's two trapezoids (above
/// and below its middle corner) so. A face belongs to one segment, so
/// that one is stored and in the row index as `tr` is: it was live on
/// the row above, and [`step_live`] has entered `tr` in its place.
#[inline(always)]
fn continues(store: &TrapezoidStore<'_>, t: u16, tr: &Trapezoid) -> bool {
    let Some(before) = t.checked_sub(1).and_then(|u| store.trapezoid(u)) else {
        return false;
    };
    before.face == tr.face && before.end == tr.top && before.top < before.end
}

/// Where the trapezoid `e` ended above row `y`: if the next trapezoid
/// of `store`'s pool [`continues`] it (so starts on row `y`), that one
/// is entered into `e` (its edges and columns; the rest is its face's,
/// as `e` has it) and `true` returned. Out of line: it runs once a
/// trapezoid that ends, and inlined it would take registers from the
/// stepping loop.
#[inline(never)]
fn continuation(e: &mut Entry, store: &TrapezoidStore<'_>, y: i32) -> bool {
    // Below the pool's never-used mark, a slot holds a stored trapezoid
    // or an empty one (no rows): never one left from before the store.
    let t = e.trap as usize + 1;
    if t >= store.peak().0 {
        return false;
    }
    let t = t as u16;
    let Some(tr) = store.trapezoid(t) else {
        return false;
    };
    if tr.top as i32 != y || !continues(store, t, tr) {
        return false;
    }
    // Of the same face: its depth, colour and face are `e`'s, and its
    // depth at column 0 on row `y` is `e`'s stepped a row (as `Depth::at`
    // computes it, wrapping). The side it shares with `e` (a triangle's
    // long edge, stored with the same ends) is `e`'s stepper moved on a
    // row; the other is set up from its ends.
    let rows = (tr.top as i32, tr.end as i32);
    let ended = store.trapezoid(t - 1).map(|b| (b.left, b.right));
    match ended {
        Some((l, _)) if l == tr.left => {
            e.left.resume(rows);
            e.right = tr.right();
        }
        Some((_, r)) if r == tr.right => {
            e.left = tr.left();
            e.right.resume(rows);
        }
        _ => {
            e.left = tr.left();
            e.right = tr.right();
        }
    }
    e.z = e.z.wrapping_add(e.zy);
    (e.x0, e.x1, e.trap) = (tr.x0, tr.x1, t);
    #[cfg(debug_assertions)]
    {
        // A side moved on keeps the rounding of its first row, not that
        // of `y`: the same pixels, row by row.
        let mut want = Entry {
            trap: t,
            ..Entry::from(tr, store)
        };
        // A depth left for later that a row above worked out.
        if want.zx == Depth::LATER.zx && e.zx != Depth::LATER.zx {
            if let Some(f) = store.face(tr.face) {
                let d = f.depth();
                (want.z, want.zx, want.zy) = (d.at(0, y), d.zx, d.zy);
            }
        }
        let mut got = *e;
        for (g, w) in [(&mut got.left, &want.left), (&mut got.right, &want.right)] {
            let (mut a, mut b) = (*g, *w);
            for _ in rows.0..rows.1 {
                debug_assert_eq!(a.pixel_now(), b.pixel_now());
                debug_assert_eq!(a.units(), b.units());
                a.step();
                b.step();
            }
            debug_assert_eq!((g.top(), g.end()), (w.top(), w.end()));
            *g = *w;
        }
        debug_assert_eq!(got, want);
    }
    true
}

/// The trapezoids of a row's index that continue none ([`continues`]),
/// for those of the row above that end with no continuation: a mesh's
/// triangles that end at a corner are followed by those that start at
/// it, and one that starts where one ended takes its slot and its place
/// in the order ([`Fresh::join`]). The first [`FRESH`] of them are
/// listed, by the upper end of their left edge, when a trapezoid first
/// asks on the row.
struct Fresh {
    /// The row's list has been made.
    made: bool,
    /// Listed.
    n: usize,
    /// The upper end of each one's left edge ([`corner`]), and its index
    /// in the store.
    corners: [u32; FRESH],
    traps: [u16; FRESH],
    /// Bit `i`: the `i`th trapezoid of the row's index that continues
    /// none has been entered.
    placed: u32,
}

/// The most trapezoids [`Fresh`] lists on a row (at most 32, the bits
/// of `placed`): a mesh's corner starts a few.
const FRESH: usize = 8;

/// A corner of a stored edge as one word, for equality.
#[inline(always)]
fn corner(v: crate::fixed::Vertex) -> u32 {
    (v.x.units() as u16 as u32) << 16 | v.y.units() as u16 as u32
}

impl Fresh {
    const EMPTY: Fresh = Fresh {
        made: false,
        n: 0,
        corners: [0; FRESH],
        traps: [0; FRESH],
        placed: 0,
    };

    /// For a new row.
    #[inline(always)]
    fn reset(&mut self) {
        (self.made, self.n, self.placed) = (false, 0, 0);
    }

    /// Lists the trapezoids of `store`'s row `y` that continue none.
    fn make(&mut self, store: &TrapezoidStore<'_>, y: i32) {
        self.made = true;
        let mut n = 0;
        let mut t = store.row_head(y as usize);
        while let Some(tr) = store.trapezoid(t) {
            if n == FRESH {
                break;
            }
            if !continues(store, t, tr) {
                self.corners[n] = corner(tr.left_side().ends().0);
                self.traps[n] = t;
                n += 1;
            }
            t = tr.next_row;
        }
        self.n = n;
    }

    /// Where the trapezoid `e` ended above row `y` with no continuation:
    /// the first listed trapezoid not yet entered whose left edge starts
    /// at the lower end of `e`'s left edge is entered into `e`, and
    /// `true` returned. Out of line, as [`continuation`] is.
    #[inline(never)]
    fn join(&mut self, e: &mut Entry, store: &TrapezoidStore<'_>, y: i32) -> bool {
        let Some(ended) = store.trapezoid(e.trap) else {
            return false;
        };
        if !self.made {
            self.make(store, y);
        }
        let at = corner(ended.left_side().ends().1);
        for i in 0..self.n.min(FRESH) {
            if self.corners[i] != at || self.placed & 1 << i != 0 {
                continue;
            }
            let t = self.traps[i];
            let Some(tr) = store.trapezoid(t) else {
                return false;
            };
            *e = Entry::from(tr, store);
            e.trap = t;
            self.placed |= 1 << i;
            return true;
        }
        false
    }
}

/// The in-place part of [`step_live`]: steps the live trapezoids
/// `act[from..k]` (`k ≤ act.len()`) to row `y` up to the first that
/// ended, each element staying where it is with only its `l`, `r` and
/// `z` changed; the position of that first (`k` if none). Not inlined:
/// with registers of its own, its loop needs no moves between them on
/// the Cortex-M4 (figures in `docs/performance-log.md`).
#[inline(never)]
fn step_in_place(act: &mut [Active], from: usize, k: usize, y: i32) -> usize {
    // `k` bounded by the slice: no bound check on `act[w]` in the loop.
    let k = k.min(act.len());
    let mut w = from;
    while w < k {
        let slot = act[w].hot.slot;
        let Some(a) = act.get_mut(slot as usize) else {
            break;
        };
        let e = &mut a.entry;
        if e.left.end() <= y {
            break;
        }
        // The row's pixels as `Entry::pixels` takes them, one side at a
        // time: the fence keeps the right side's loads after the left
        // side's store, so that the two sides' accumulators and steps
        // (eight words) are not live at once; on the Cortex-M4 the loop
        // then reloads three spilled values an element, not seven
        // (figures in `docs/performance-log.md`). It orders this
        // thread's memory accesses for the compiler alone and emits no
        // instruction.
        step_edge(&mut e.left);
        let l = e.left.pixel_now().max(e.x0 as i32);
        core::sync::atomic::compiler_fence(core::sync::atomic::Ordering::SeqCst);
        step_edge(&mut e.right);
        let r = e.right.pixel_now().min(e.x1 as i32);
        e.z = e.z.wrapping_add(e.zy);
        let z = e.z;
        let h = &mut act[w].hot;
        (h.l, h.r, h.z) = (l, r, z);
        w += 1;
    }
    w
}

/// Works out, at row `y`, the depth of the live trapezoids `act[..k]`
/// (sorted by `l`) that share pixels with another on the row and whose
/// face left it for later ([`Depth::LATER`]), before the row is swept:
/// the sweep reads a trapezoid's depth only where another covers the
/// same pixels. Each one that starts left of the farthest `r` of those
/// before it shares pixels with the one of that `r`; so every one that
/// shares pixels is found (the first that shares pixels with a given
/// one, after it in the order, finds it as the one of the farthest `r`).
/// Nothing to do for a store none of whose faces left its depth for
/// later ([`TrapezoidStore::has_later_depths`]). Out of line: few rows
/// need it.
#[inline(never)]
fn work_out_depths(act: &mut [Active], k: usize, store: &TrapezoidStore<'_>, y: i32) {
    if !store.has_later_depths() {
        return;
    }
    let k = k.min(act.len());
    // The one of the farthest `r`, and whether its depth is still left
    // for later (its `Hot` holds `zx` as its entry does).
    let (mut far, mut of, mut of_later) = (i32::MIN, 0, false);
    let mut p = 0;
    while p < k {
        let h = &act[p].hot;
        let (l, r, mut later) = (h.l, h.r, h.zx == Depth::LATER.zx);
        if l < r {
            if l < far && (later || of_later) {
                work_out_pair(act, (p, of), store, y);
                (later, of_later) = (false, false);
            }
            if r > far {
                (far, of, of_later) = (r, p, later);
            }
        }
        p += 1;
    }
}

/// [`work_out_depth`] of the live trapezoids at `p` and `q`. Out of line
/// and cold, so that [`work_out_depths`]' loop keeps its registers.
#[cold]
#[inline(never)]
fn work_out_pair(act: &mut [Active], (p, q): (usize, usize), store: &TrapezoidStore<'_>, y: i32) {
    work_out_depth(act, p, store, y);
    work_out_depth(act, q, store, y);
}

/// The depth of the live trapezoid at `p` in `act`'s order, at row `y`,
/// if its face left it for later: the face's [`Depth`] at column 0 of the
/// row, as [`Entry::from`] and a step a row would have left it.
#[inline(always)]
fn work_out_depth(act: &mut [Active], p: usize, store: &TrapezoidStore<'_>, y: i32) {
    let slot = act[p].hot.slot as usize;
    let Some(a) = act.get_mut(slot) else {
        return;
    };
    let e = &mut a.entry;
    if e.zx != Depth::LATER.zx {
        return;
    }
    let Some(f) = store.face(e.face) else {
        return;
    };
    let d = f.depth();
    (e.z, e.zx, e.zy) = (d.at(0, y), d.zx, d.zy);
    let (z, zx) = (e.z, e.zx);
    let h = &mut act[p].hot;
    (h.z, h.zx) = (z, zx);
}

/// Steps an active trapezoid's edge down a row. On the hosts' out-of-order
/// cores by a mask ([`Edge::step_masked`]): the carries of many unrelated
/// edges follow no pattern, so a branch there is mispredicted about
/// every other step (figures in `docs/performance-log.md`). Elsewhere by
/// the branch, which costs fewer instructions (on the Cortex-M4 it is
/// conditional execution, no jump).
#[inline(always)]
fn step_edge(e: &mut Edge) {
    #[cfg(any(target_arch = "x86_64", target_arch = "x86", target_arch = "aarch64"))]
    e.step_masked();
    #[cfg(not(any(target_arch = "x86_64", target_arch = "x86", target_arch = "aarch64")))]
    e.step();
}

/// Where the resolved runs go, one row at a time.
trait RowOut {
    /// What the caller's end can fail with.
    type Error;
    /// Starts row `y`.
    fn start(&mut self, y: u16);
    /// Appends `len > 0` pixels of `ink` in `color` (`BACKGROUND` for
    /// the background). Runs next to each other differ in colour.
    fn run(&mut self, len: i32, ink: u16, color: u32);
    /// Ends the row; the runs it had.
    fn finish(&mut self) -> Result<u32, Self::Error>;
    /// Writes the whole row started, with nothing pending, when its live
    /// trapezoids `live` (sorted by `l`) are side by side
    /// ([`side_by_side`]), as [`write_side_by_side`] writes it through
    /// [`run`](Self::run): the same runs, and its `empty` and `single`
    /// added to `stats`; `Some(true)`. `Some(false)` where they are not,
    /// found as the row is written: nothing is counted, and what was
    /// written of the row is the sweep's to write over (every pixel of
    /// it). `None`, with nothing done, where the output does not write
    /// rows so; the default never does.
    #[inline(always)]
    fn side_by_side(
        &mut self,
        _live: &[Active],
        _width: i32,
        _stats: &mut VisibleStats,
    ) -> Option<bool> {
        None
    }
}

/// Rows of runs in the workspace's buffer, each handed to the caller.
struct ToSink<'r, F> {
    out: RunWriter<'r>,
    sink: F,
    y: u16,
}

impl<E, F: FnMut(u16, &[Run]) -> Result<(), E>> RowOut for ToSink<'_, F> {
    type Error = E;

    #[inline]
    fn start(&mut self, y: u16) {
        self.y = y;
        self.out.clear();
    }

    /// The buffer holds at least the width's runs (checked before the
    /// first row), so it never overflows.
    #[inline]
    fn run(&mut self, len: i32, ink: u16, _color: u32) {
        self.out.append(len as u16, ink);
    }

    #[inline]
    fn finish(&mut self) -> Result<u32, E> {
        (self.sink)(self.y, self.out.runs())?;
        Ok(self.out.runs().len() as u32)
    }
}

/// Runs written straight into a frame-buffer port as spans, as
/// [`decode_row`](crate::visible::rle::decode_row) writes a row of runs: the same
/// spans, without the row buffer or the face lookup per run.
struct ToTarget<'t, T: SpanTarget + ?Sized> {
    target: &'t mut T,
    background: Option<T::Color>,
    size: (u32, u32),
    y: u16,
    x: u32,
    runs: u32,
    /// The row's runs not handed to the target (the background left as
    /// it is, past the target's width) and the pixels of those inside
    /// it: the row's spans and pixels are counted from them in
    /// [`RowOut::finish`], not run by run.
    skipped: u32,
    skipped_px: u32,
    counts: Counts,
    error: Option<T::Error>,
    /// For painting: the columns of the current row that may be written,
    /// the target's width, or 0 when the row is below the target or the
    /// target has failed (see [`ToTarget::paint_row`]).
    limit: u32,
    /// For painting: where the current row starts in the target
    /// ([`SpanTarget::row_start`]), worked out once a row.
    row: usize,
    /// For a target that takes runs in batches
    /// ([`SpanTarget::RUNS_IN_BATCHES`]): the row's runs not yet handed
    /// to it, one after the other ([`RowOut::run`]), `pending[..held]`
    /// from column `from`, handed over in one call when `pending` is
    /// full, where a run is skipped, and at the row's end. Lent by the
    /// caller ([`ToTarget::new`]), so that the writer stays small to
    /// move. (A row written side by side, [`RowOut::side_by_side`], is
    /// handed over in batches of its own, to every target.)
    pending: &'t mut [RowRun<T::Color>],
    held: usize,
    from: u16,
}

/// A side-by-side row's runs in [`ToTarget::side_by_side`]: `runs[..n]`,
/// one after the other from column `from`, handed to the target in one
/// call ([`SpanTarget::fill_runs_inside`]) when full and at the row's end;
/// `handed` runs before them, counted when the row is found side by side.
struct Batch<C> {
    runs: [RowRun<C>; BATCH],
    n: usize,
    from: u16,
    handed: u32,
}

/// The runs a [`Batch`] holds (4 bytes each for a 16-bit pixel, on the
/// stack): a row of a mesh's faces at 240 columns is one or two batches.
const BATCH: usize = 16;

impl<'t, T> ToTarget<'t, T>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    /// Rows into `target` from its first, the background filled with
    /// `background` or left as it is; `pending` holds the runs of a
    /// batch ([`ToTarget::pending`]; [`BATCH`] of them, none for a
    /// target that takes runs one by one).
    fn new(
        target: &'t mut T,
        background: Option<T::Color>,
        pending: &'t mut [RowRun<T::Color>],
    ) -> Self {
        let (tw, th) = target.size();
        ToTarget {
            target,
            background,
            size: (tw as u32, th as u32),
            y: 0,
            x: 0,
            runs: 0,
            skipped: 0,
            skipped_px: 0,
            counts: Counts::default(),
            error: None,
            limit: 0,
            row: 0,
            pending,
            held: 0,
            from: 0,
        }
    }
}

/// The runs of a batch for [`ToTarget::new`], in the caller's frame:
/// [`BATCH`] runs for a target that takes runs in batches
/// ([`SpanTarget::RUNS_IN_BATCHES`]), none touched for another (its
/// writer never reads them, so they are not even filled).
#[inline(always)]
fn pending_runs<C: ListColor>() -> [RowRun<C>; BATCH] {
    [RowRun {
        x1: 0,
        color: C::from_list_word(0),
    }; BATCH]
}

/// `runs` ([`pending_runs`]) for a writer into a `T`: all of them if it
/// takes runs in batches, none if not.
#[inline(always)]
fn batch_of<T: SpanTarget + ?Sized>(runs: &mut [RowRun<T::Color>]) -> &mut [RowRun<T::Color>] {
    match T::RUNS_IN_BATCHES {
        true => runs,
        false => &mut [],
    }
}

impl<T> ToTarget<'_, T>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    /// Stores the run that ends at `x1` in `color` in the batch, handed
    /// to the target first when it is full.
    #[inline(always)]
    fn put(&mut self, at: &mut Batch<T::Color>, x1: i32, color: T::Color) {
        if at.n >= BATCH {
            self.hand_over(at);
            at.from = at.runs[BATCH - 1].x1;
            at.n = 0;
            at.handed += BATCH as u32;
        }
        // `n < BATCH` here: the remainder only spares the bound test.
        at.runs[at.n % BATCH] = RowRun {
            x1: x1 as u16,
            color,
        };
        at.n += 1;
    }

    /// Ends a row written by [`RowOut::side_by_side`] at `width`: the
    /// batch handed to the target, the runs and the background's runs
    /// counted.
    #[inline(always)]
    fn close(&mut self, at: &Batch<T::Color>, width: i32, empty: u32, stats: &mut VisibleStats) {
        if at.n > 0 {
            self.hand_over(at);
        }
        self.runs += at.handed + at.n as u32;
        self.x = width as u32;
        stats.empty += empty;
    }

    /// Hands the batch's runs to the target, unless a write has failed
    /// on the row.
    #[inline(always)]
    fn hand_over(&mut self, at: &Batch<T::Color>) {
        if self.error.is_some() {
            return;
        }
        let runs = &at.runs[..at.n.min(BATCH)];
        if let Err(e) = self.target.fill_runs_inside(self.y, at.from, runs) {
            self.fail(e);
        }
    }

    /// Writes pixels `x0..x1` of the current row, clipped to the target
    /// already (so the frame need not check them again), in `c`.
    #[inline(always)]
    fn write(&mut self, x0: u32, x1: u32, c: T::Color) {
        let span = Span {
            y: self.y,
            x0: x0 as u16,
            x1: x1 as u16,
        };
        if let Err(e) = self.target.fill_span_inside(span, c) {
            self.fail(e);
        }
    }

    /// A write failed with `e`: kept for the row's end, and nothing more
    /// is written on the row.
    #[inline(always)]
    fn fail(&mut self, e: T::Error) {
        self.error = Some(e);
        self.limit = 0;
    }

    /// Hands the runs of [`RowOut::run`] held in the batch to the
    /// target, unless a write has failed on the row, and empties it.
    #[inline(always)]
    fn hand_over_runs(&mut self) {
        if !T::RUNS_IN_BATCHES {
            return;
        }
        let n = core::mem::take(&mut self.held);
        if n == 0 || self.error.is_some() {
            return;
        }
        let runs = self.pending.get(..n).unwrap_or_default();
        if let Err(e) = self.target.fill_runs_inside(self.y, self.from, runs) {
            self.fail(e);
        }
    }

    /// Starts row `y`, painted ([`Resolve::Paint`]) or as runs: the row
    /// and the target's state are checked here once, not span by span.
    #[inline(always)]
    fn paint_row(&mut self, y: u16) {
        self.y = y;
        let (w, h) = self.size;
        (self.limit, self.row) = if (y as u32) < h && self.error.is_none() {
            (w, self.target.row_start(y))
        } else {
            (0, 0)
        };
    }

    /// Writes pixels `x0..x1` (`x0 < x1`) of the row started by
    /// [`ToTarget::paint_row`] in `color`, a face's (never `BACKGROUND`),
    /// out of the order of a row's runs, and counts them.
    #[inline(always)]
    fn fill(&mut self, x0: i32, x1: i32, color: u32) {
        if x0 as u32 >= self.limit {
            return;
        }
        let x1 = (x1 as u32).min(self.limit);
        // Spans fit (at most 65535 trapezoids × 4096 rows × 9 parts); a
        // frame's pixels, each counted as often as it is painted, may
        // not: they wrap (see `Counts`), an add that never panics.
        self.counts.spans += 1;
        self.counts.pixels = self.counts.pixels.wrapping_add(x1 - x0 as u32);
        self.write_row(x0 as u32, x1, T::Color::from_list_word(color));
    }

    /// [`write`](Self::write) on the row started by
    /// [`ToTarget::paint_row`], from where it starts in the target.
    #[inline(always)]
    fn write_row(&mut self, x0: u32, x1: u32, c: T::Color) {
        let r = self
            .target
            .fill_row_inside(self.row, x0 as u16, x1 as u16, c);
        if let Err(e) = r {
            self.fail(e);
        }
    }

    /// Fills pixels `0..width` of the row started by
    /// [`ToTarget::paint_row`] with the background, when there is one,
    /// and counts them.
    #[inline]
    fn fill_background(&mut self, width: u32) {
        let x1 = width.min(self.limit);
        if let (Some(c), true) = (self.background, x1 > 0) {
            self.counts.spans += 1;
            self.counts.pixels = self.counts.pixels.wrapping_add(x1);
            self.write_row(0, x1, c);
        }
    }
}

impl<T> RowOut for ToTarget<'_, T>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    type Error = T::Error;

    /// The row and the target's state are checked here once, as for
    /// painting ([`ToTarget::paint_row`]): a run then tests its start
    /// against `limit` alone (a failed write sets it to 0).
    #[inline]
    fn start(&mut self, y: u16) {
        self.paint_row(y);
        self.x = 0;
        self.runs = 0;
        self.skipped = 0;
        self.skipped_px = 0;
    }

    #[inline(always)]
    fn run(&mut self, len: i32, _ink: u16, color: u32) {
        self.runs += 1;
        let x0 = self.x;
        // A row is the store's width at most, within 4096.
        self.x += len as u32;
        if x0 >= self.limit {
            self.skipped += 1;
            return;
        }
        // Inside the target: `limit` is its width.
        let x1 = self.x.min(self.limit);
        let c = if color == BACKGROUND {
            match self.background {
                Some(c) => c,
                None => {
                    self.skipped += 1;
                    self.skipped_px += x1 - x0;
                    self.hand_over_runs();
                    return;
                }
            }
        } else {
            T::Color::from_list_word(color)
        };
        if !T::RUNS_IN_BATCHES {
            self.write(x0, x1, c);
            return;
        }
        // The runs of a row come one after the other: the batch's next
        // starts where its last ends, unless one was skipped between
        // (which handed it over).
        if self.held >= self.pending.len() {
            self.hand_over_runs();
        }
        if self.held == 0 {
            self.from = x0 as u16;
        }
        if let Some(r) = self.pending.get_mut(self.held) {
            *r = RowRun {
                x1: x1 as u16,
                color: c,
            };
            self.held += 1;
        }
    }

    /// Where the background is filled and the target holds the row's
    /// columns: the runs merged by colour as [`Ctx::emit`] merges them,
    /// stored in the batch and handed to the target a batch at a time,
    /// not run by run. Out of line: once a row, with registers of its
    /// own.
    #[inline(never)]
    fn side_by_side(
        &mut self,
        live: &[Active],
        width: i32,
        stats: &mut VisibleStats,
    ) -> Option<bool> {
        let bg = self.background?;
        if self.limit < width as u32 {
            return None;
        }
        // Every run of the row is written (the sweep writes every pixel,
        // the background too, and the row is inside the target). A face's
        // run is stored where the next run starts (it merges with a next
        // face of its colour): the pending run ends at `x` in `pend`. The
        // background's runs, between two faces, are stored as soon as
        // they are found. A face that starts left of the last one's end
        // (an overlap: `live` is sorted) ends the attempt.
        let mut at = Batch {
            runs: [RowRun { x1: 0, color: bg }; BATCH],
            n: 0,
            from: 0,
            handed: 0,
        };
        let mut live = live.iter().map(|a| &a.hot).filter(|h| h.l < h.r);
        let Some(first) = live.next() else {
            // The background alone (as the sweep, none for no columns).
            let any = width > 0;
            if any {
                self.put(&mut at, width, bg);
            }
            self.close(&at, width, any as u32, stats);
            return Some(true);
        };
        let mut empty = 0;
        if first.l > 0 {
            empty += 1;
            self.put(&mut at, first.l, bg);
        }
        let (mut x, mut pend, mut single) = (first.r, first.color, 1);
        for h in live {
            if h.l < x {
                return Some(false);
            }
            single += 1;
            if h.l > x {
                empty += 1;
                self.put(&mut at, x, T::Color::from_list_word(pend));
                self.put(&mut at, h.l, bg);
                pend = h.color;
            } else if h.color != pend {
                self.put(&mut at, x, T::Color::from_list_word(pend));
                pend = h.color;
            }
            x = h.r;
        }
        if x > width {
            return Some(false);
        }
        self.put(&mut at, x, T::Color::from_list_word(pend));
        if x < width {
            empty += 1;
            self.put(&mut at, width, bg);
        }
        self.close(&at, width, empty, stats);
        stats.single += single;
        Some(true)
    }

    /// Counts the row's spans and pixels: every run that was not skipped
    /// went to the target, and together they cover the row's pixels
    /// inside the target but the skipped ones.
    #[inline]
    fn finish(&mut self) -> Result<u32, T::Error> {
        self.hand_over_runs();
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let (w, h) = self.size;
        if (self.y as u32) < h {
            self.counts.spans += self.runs - self.skipped;
            self.counts.pixels += self.x.min(w) - self.skipped_px;
        }
        Ok(self.runs)
    }
}

/// Insertion sort of the live trapezoids by `l`: one compare each when
/// the order is the last row's. Many trapezoids that join a row in
/// another order (listed right to left) would cost `n²/2` moves, so an
/// element moves at most [`SORT_REACH`] places; one that would move
/// farther hands the sort over to a heap sort ([`heap_sort_hot`],
/// `O(n log n)`). So a row costs at most `SORT_REACH · n` moves and a
/// heap sort. Equal `l` may come in any order: the sweep enters them at
/// the same pixel.
#[inline]
fn sort(live: &mut [Active]) {
    let Some(from) = first_out_of_order(live) else {
        return;
    };
    for p in from..live.len() {
        if live[p - 1].hot.l <= live[p].hot.l {
            continue;
        }
        let h = live[p].hot;
        if p > SORT_REACH && live[p - SORT_REACH - 1].hot.l > h.l {
            heap_sort_hot(live);
            return;
        }
        let mut q = p;
        while q > 0 && live[q - 1].hot.l > h.l {
            live[q].hot = live[q - 1].hot;
            q -= 1;
        }
        live[q].hot = h;
    }
}

/// The position of the first live trapezoid whose `l` is less than the
/// one before it, or `None` when `live` is in order. A walk over the
/// elements that keeps the last `l` in a register: on a row in the last
/// row's order (most rows of a mesh), this is all the sort does, and
/// it costs fewer instructions on the Cortex-M4 than the insertion
/// loop's indexed compare of each pair.
#[inline(always)]
fn first_out_of_order(live: &[Active]) -> Option<usize> {
    let (first, rest) = live.split_first()?;
    let mut last = first.hot.l;
    for (i, a) in rest.iter().enumerate() {
        if a.hot.l < last {
            return Some(i + 1);
        }
        last = a.hot.l;
    }
    None
}

/// [`sort`] for a row of many live trapezoids, `act[..k]`, of which
/// `act[stepped..k]` entered on this row: the stepped ones (in the last
/// row's order but for the edges that crossed, and those that gained or
/// lost their pixels) and the new ones are sorted apart, each with a
/// budget of [`SORT_REACH`] moves an element before a heap sort, and
/// merged ([`merge_entered`]).
#[inline(never)]
#[cold]
fn sort_many(act: &mut [Active], stepped: usize, k: usize) {
    let k = k.min(act.len());
    let stepped = stepped.min(k);
    sort_budget(&mut act[..stepped]);
    if k > stepped {
        sort_entered(&mut act[stepped..k]);
        merge_entered(act, stepped, k);
    }
}

/// [`sort_budget`] for the trapezoids that entered on a row, in the
/// store's order: when the first starts right of the last (a mesh's faces
/// listed against the screen's order, right to left), their `hot`
/// elements are reversed first, which puts them in order, not in the
/// insertion sort's worst case (and a heap sort).
fn sort_entered(new: &mut [Active]) {
    if let (Some(a), Some(b)) = (new.first(), new.last()) {
        if a.hot.l > b.hot.l {
            let n = new.len();
            for i in 0..n / 2 {
                let h = new[i].hot;
                move_hot(new, n - 1 - i, i);
                new[n - 1 - i].hot = h;
            }
        }
    }
    sort_budget(new);
}

/// Insertion sort of the live trapezoids by `l`, as [`sort`], but with
/// a budget for the whole array instead of a reach for each element:
/// an element may move far (many entering a row together, listed right
/// to left) as long as the moves stay within `SORT_REACH · n`; past
/// that, a heap sort.
fn sort_budget(live: &mut [Active]) {
    let mut budget = SORT_REACH * live.len();
    for p in 1..live.len() {
        if live[p - 1].hot.l <= live[p].hot.l {
            continue;
        }
        let h = live[p].hot;
        let mut q = p;
        while q > 0 && live[q - 1].hot.l > h.l {
            move_hot(live, q - 1, q);
            q -= 1;
        }
        live[q].hot = h;
        let Some(b) = budget.checked_sub(p - q) else {
            heap_sort_hot(live);
            return;
        };
        budget = b;
    }
}

/// Merges the trapezoids that entered on a row, `act[old..k].hot`
/// (sorted by `l`), into the live ones before them (`act[..old].hot`,
/// sorted), from the end: each element moves once, `O(k)` a row however
/// far left the new ones start (inserted one by one, each would move past
/// all the live ones right of it). The new ones wait in the free array's
/// unused end: `act[n - (k - old)..].free` and `.cover.r` with `n` the
/// list's length, unused while `k` trapezoids are live (each holds a slot
/// off the free stack).
#[inline(never)]
fn merge_entered(act: &mut [Active], old: usize, k: usize) {
    let n = act.len();
    let m = k - old;
    if k > n || m == 0 {
        return;
    }
    let stash = n - m;
    for j in 0..m {
        let h = act[old + j].hot;
        let a = &mut act[stash + j];
        (a.free, a.cover.r) = (h.slot, h.l);
    }
    let (mut i, mut w) = (old, k);
    for j in (0..m).rev() {
        let (slot, l) = (act[stash + j].free, act[stash + j].cover.r);
        while i > 0 && act[i - 1].hot.l > l {
            w -= 1;
            i -= 1;
            move_hot(act, i, w);
        }
        w -= 1;
        act[w].hot = act[slot as usize].entry.hot(slot);
    }
}

/// Copies the live trapezoid `act[from].hot` to `act[to].hot`, field by
/// field. Written as one assignment between two elements of one slice,
/// the copy of this 24-byte element becomes a call to `memmove` on the
/// Cortex-M4 (the compiler cannot tell that the two differ); field by
/// field it is a few loads and stores. The sorts of rows of more than
/// [`MANY`] live trapezoids and the heap sort move their elements with
/// it: with `MANY` set to 16 for a measurement, the image's mesh frames
/// took 28 k to 56 k fewer instructions so (`docs/performance-log.md`).
#[inline(always)]
fn move_hot(act: &mut [Active], from: usize, to: usize) {
    let Hot {
        l,
        r,
        z,
        zx,
        color,
        face,
        slot,
    } = act[from].hot;
    act[to].hot = Hot {
        l,
        r,
        z,
        zx,
        color,
        face,
        slot,
    };
}

/// The farthest an element of the entry sort moves before it falls back
/// to a heap sort: with 24-byte elements, insertion is the cheaper of the
/// two up to a few dozen places.
const SORT_REACH: usize = 64;

/// Sorts the `hot` elements of `live` by `l` with a heap sort, moving
/// nothing else (each entry's stepping state stays at its slot): in
/// place, `O(n log n)` whatever the order. It is
/// [`heap_sort`](crate::raster::scan::heap_sort) on one field of the
/// entries instead of the whole entries.
#[inline(never)]
fn heap_sort_hot(live: &mut [Active]) {
    // Moves live[root].hot down the heap of live[..end] (a max-heap by l).
    let sift = |v: &mut [Active], mut root: usize, end: usize| {
        let h = v[root].hot;
        loop {
            let mut child = 2 * root + 1;
            if child >= end {
                break;
            }
            if child + 1 < end && v[child].hot.l < v[child + 1].hot.l {
                child += 1;
            }
            if h.l >= v[child].hot.l {
                break;
            }
            move_hot(v, child, root);
            root = child;
        }
        v[root].hot = h;
    };
    let n = live.len();
    for root in (0..n / 2).rev() {
        sift(live, root, n);
    }
    for end in (1..n).rev() {
        let top = live[0].hot;
        move_hot(live, end, 0);
        live[end].hot = top;
        sift(live, 0, end);
    }
}

/// What the resolution of a row needs besides the active list.
struct Ctx<'s, O> {
    store: &'s TrapezoidStore<'s>,
    out: O,
    /// The pending run: its ink, length and colour (`BACKGROUND` for the
    /// background).
    ink: u16,
    len: i32,
    color: u32,
    mode: Resolve,
    y: i32,
    stats: VisibleStats,
}

/// Resolves the row by a sweep over the `l` and `r` of the live
/// trapezoids. The cover array holds the trapezoids that have started by
/// decreasing `r`; those that have ended leave from its end whenever a
/// new front is sought, and those a front hid up to their end leave when
/// a trapezoid breaks it (past [`PRUNE_FROM`] covers).
///
/// The sweep keeps a *front*: a covering trapezoid that is nearest on
/// every pixel from the sweep's position to its own `r`, against every
/// trapezoid in the cover array. It is established by comparing it with
/// each of the others at the two ends of their common pixels (see the
/// [module](self) docs), and kept until it ends or a trapezoid enters
/// that it does not dominate in the same way. A trapezoid that leaves
/// while the front holds costs nothing, and one that enters behind it
/// two comparisons. Where no front can be established (a plane crosses
/// it before its end), the span up to the next `l` or `r` is resolved and
/// subdivided as in [`span`].
#[inline(always)]
fn sweep<O: RowOut>(act: &mut [Active], k: usize, width: i32, cx: &mut Ctx<'_, O>) {
    // act[..k].hot: the live trapezoids, by l; act[..nc].cover: the
    // covers, by decreasing r (nc ≤ k).
    let k = k.min(act.len());
    let (mut x, mut nc, mut p) = (0i32, 0usize, 0usize);
    let next_l = |act: &[Active], p: usize| {
        if p < k {
            act[p].hot.l.min(width)
        } else {
            width
        }
    };
    while x < width {
        // Leave the trapezoids ending here or before: the last ones.
        while let Some(c) = nc.checked_sub(1).and_then(|q| act.get(q)) {
            if c.cover.r > x {
                break;
            }
            nc -= 1;
        }
        if nc == 0 {
            // Nothing covers x: a trapezoid that ends by the next one's
            // `l` is alone on all its pixels, and is written with no depth
            // compare and no cover (the spans and counts are the front's
            // that the loop below would find: a mesh's row, its faces side
            // by side, goes all this way).
            while p < k {
                let h = &act[p].hot;
                if h.r <= h.l {
                    // No pixel: passed by.
                    p += 1;
                    continue;
                }
                if h.l > x {
                    // Up to the next `l`.
                    if x >= width {
                        return;
                    }
                    let next = h.l.min(width);
                    cx.stats.empty += 1;
                    cx.emit(next - x, Run::BACKGROUND, BACKGROUND);
                    x = next;
                    if x >= width {
                        return;
                    }
                }
                let h = &act[p].hot;
                if next_l(act, p + 1) < h.r {
                    break;
                }
                let (r, face, color) = (h.r, h.face, h.color);
                cx.stats.single += 1;
                cx.emit(r - x, face, color);
                x = r;
                p += 1;
            }
            if p >= k {
                if x < width {
                    cx.stats.empty += 1;
                    cx.emit(width - x, Run::BACKGROUND, BACKGROUND);
                }
                return;
            }
        }
        // Enter the trapezoids starting here: pending ones have l ≥ x, so
        // these have l = x (and some pixels, see `Hot::l`).
        while p < k && act[p].hot.l <= x {
            let c = Covered::of(&act[p].hot, p);
            p += 1;
            // One with no pixel (`r ≤ l = x`) never covers.
            if c.r > x {
                insert(act, &mut nc, c);
            }
        }
        let mut next = next_l(act, p);
        let cov = &act[..nc.min(k)];
        let Some(last) = cov.last() else {
            let next = next_with_pixels(act, p, k, width);
            cx.stats.empty += 1;
            cx.emit(next - x, Run::BACKGROUND, BACKGROUND);
            x = next;
            continue;
        };
        let Some(f) = cx.establish(act, cov, x) else {
            let t = next_with_pixels(act, p, k, width).min(last.cover.r);
            span(act, cov, x, t, cx);
            x = t;
            continue;
        };
        let f = cover_of(act, f as usize);
        // The front holds from x until it ends or a trapezoid starts that
        // it does not dominate. Those that end behind it wait in the
        // cover array until the next front is sought.
        let start = x;
        loop {
            x = next.min(f.r);
            if x >= f.r {
                break;
            }
            let mut broken = false;
            while p < k && act[p].hot.l <= x {
                let c = Covered::of(&act[p].hot, p);
                p += 1;
                if c.r <= x {
                    continue;
                }
                // The front is in front of the new one on all their
                // common pixels: when those are all of its pixels, it is
                // hidden (the front is in the cover array, so this holds
                // even after the front has lost its place).
                if cx.dominates_el(act, &f, &c, x, f.r.min(c.r) - 1) {
                    if c.r <= f.r {
                        cx.stats.hidden += 1;
                        continue;
                    }
                } else {
                    // The covers that end by the front's end (the last
                    // ones, the front among them) are behind it on all
                    // their pixels left: they leave before the next front
                    // is sought, so that it is not compared with those the
                    // last one hid. Each leaves once.
                    if !broken && nc > PRUNE_FROM {
                        nc = prune(act, nc, &f);
                    }
                    broken = true;
                }
                insert(act, &mut nc, c);
            }
            next = next_l(act, p);
            if broken {
                break;
            }
        }
        cx.emit(x - start, f.face, f.color);
    }
}

/// What [`side_by_side`] finds on a row.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Row {
    /// Each live trapezoid with pixels starts at or right of the end of
    /// the one with pixels before it, and the last ends by the width: a
    /// row of a mesh's faces side by side, none overlapping another.
    SideBySide,
    /// One with pixels starts left of the start of the one before it
    /// (found before any overlap).
    Unsorted,
    /// One with pixels starts inside the pixels of the one before it, or
    /// the last ends past the width.
    Overlapping,
}

/// Whether the live trapezoids `live` are side by side ([`Row`]). Such
/// a row needs no sort, and [`sweep`] would write the same runs with the
/// same counts: those with no pixel on the row never cover, and the
/// sweeps' runs and counts are those of the row without them. One pass,
/// with the last `l` and `r` in registers, finds it.
#[inline(always)]
fn side_by_side(live: &[Active], width: i32) -> Row {
    let (mut last_l, mut last_r) = (i32::MIN, i32::MIN);
    for a in live {
        let (l, r) = (a.hot.l, a.hot.r);
        if r <= l {
            continue;
        }
        if l < last_r {
            return if l < last_l {
                Row::Unsorted
            } else {
                Row::Overlapping
            };
        }
        (last_l, last_r) = (l, r);
    }
    if last_r <= width {
        Row::SideBySide
    } else {
        Row::Overlapping
    }
}

/// Writes a row that [`side_by_side`] accepts, as [`sweep`] writes it:
/// the background up to each trapezoid with pixels, its span, and the
/// background to `width`; the same runs and counts (`empty`, `single`).
/// Those with no pixel are passed by wherever they are in the order. An
/// output that takes such a row whole ([`RowOut::side_by_side`]) writes
/// it itself.
#[inline(always)]
fn write_side_by_side<O: RowOut>(live: &[Active], width: i32, cx: &mut Ctx<'_, O>) {
    let mut x = 0;
    for a in live {
        let h = &a.hot;
        if h.r <= h.l {
            continue;
        }
        if h.l > x {
            cx.stats.empty += 1;
            cx.emit(h.l - x, Run::BACKGROUND, BACKGROUND);
        }
        cx.stats.single += 1;
        cx.emit(h.r - h.l, h.face, h.color);
        x = h.r;
    }
    if x < width {
        cx.stats.empty += 1;
        cx.emit(width - x, Run::BACKGROUND, BACKGROUND);
    }
}

/// The `l` of the first of the live trapezoids `act[p..k]` that has
/// pixels on the row, the width at most. Where a run of the background
/// or of several covers is resolved, it ends there and not at a
/// trapezoid with no pixel (which the sweeps pass by): the runs and their
/// counts are those of the row without it.
#[inline(never)]
fn next_with_pixels(act: &[Active], mut p: usize, k: usize, width: i32) -> i32 {
    while let Some(a) = act[..k.min(act.len())].get(p) {
        if a.hot.l < a.hot.r {
            return a.hot.l.min(width);
        }
        p += 1;
    }
    width
}

/// Covers past which those a broken front hid leave the array (see
/// [`sweep`]); below, a comparison with each costs less than their leaving.
const PRUNE_FROM: usize = 8;

/// Drops from `act[..nc].cover` the covers that end by `f.r`, `f` among
/// them, and puts `f` back last; the new length.
#[inline(never)]
fn prune(act: &mut [Active], mut nc: usize, f: &Cover) -> usize {
    while nc > 0 && act[nc - 1].cover.r <= f.r {
        nc -= 1;
    }
    if let Some(a) = act.get_mut(nc) {
        a.cover = f.element();
        nc += 1;
    }
    nc
}

/// The cover of the live trapezoid `act[p].hot`, by value.
#[inline(always)]
fn cover_of(act: &[Active], p: usize) -> Cover {
    let h = &act[p].hot;
    Cover {
        r: h.r,
        z: h.z,
        zx: h.zx,
        color: h.color,
        face: h.face,
        p: p as u16,
    }
}

/// Inserts `c` into `act[..nc].cover`, kept by decreasing `r`. The array
/// has a place for every live trapezoid, so it never overflows.
#[inline(always)]
fn insert(act: &mut [Active], nc: &mut usize, c: Covered) {
    if *nc >= act.len() {
        return;
    }
    let mut q = *nc;
    while q > 0 && act[q - 1].cover.r < c.r {
        act[q].cover = act[q - 1].cover;
        q -= 1;
    }
    act[q].cover = c;
    *nc += 1;
}

/// Live trapezoids on a row past which it takes [`sweep_many`] instead of
/// [`sweep`]: below, the simpler sweep costs less (on the Cortex-M4 as on
/// the host), and the scenes with many overlapping faces need the other.
const MANY: usize = 64;

/// [`sweep`] for rows with many live trapezoids: the same fronts, spans
/// and runs, with a cover array that keeps the quadratic terms out of
/// long rows.
///
/// * The covers are kept by *increasing* `r`, in `act[lo..nc].cover`: those
///   that end leave from the start, and one that enters ending last (as
///   staggered faces do, each further right) is appended; one that goes
///   elsewhere is placed by a binary search past [`FAR`] moves.
/// * When a front is found, the covers before it (they end by its end,
///   behind it on all their pixels left) leave.
/// * A *chain*: covers each in front of the next on their common pixels
///   from the sweep's position on (the first, which ends first, in front
///   of the second, and so on). At each pixel *nearer* is a strict order,
///   so by transitivity the first is then in front of every other on
///   their common pixels: it is the front, found with no compare. A cover
///   that enters keeps the chain when the one before its place is in front
///   of it and it is in front of the one after: four depth compares (six
///   when the chain ends there, to decide the front as [`sweep`] does).
///   Faces each farther than the last make such a chain. When a front is
///   found among more than [`CHAIN_FROM`] covers, those after it are
///   checked for a chain once (again only when they have doubled in
///   number); a cover that enters out of place ends it.
#[inline(never)]
#[cold]
fn sweep_many<O: RowOut>(
    act: &mut [Active],
    k: usize,
    width: i32,
    chain_from: usize,
    cx: &mut Ctx<'_, O>,
) {
    let k = k.min(act.len());
    let (mut x, mut lo, mut nc, mut p) = (0i32, 0usize, 0usize, 0usize);
    let (mut chain, mut try_from) = (false, chain_from);
    let next_l = |act: &[Active], p: usize| {
        if p < k {
            act[p].hot.l.min(width)
        } else {
            width
        }
    };
    while x < width {
        // Leave the trapezoids ending here or before: the first ones.
        while lo < nc && act[lo].cover.r <= x {
            lo += 1;
        }
        if lo >= nc {
            (lo, nc, chain, try_from) = (0, 0, false, chain_from);
        }
        // Enter the trapezoids starting here (l = x). Where nothing else
        // covers x, the first of them is compared with each of the others
        // first: when one is in front of the other on all its pixels
        // (faces of one extent stacked), that one is hidden, and the
        // cover array stays at one.
        let fresh = lo >= nc;
        let mut first: Option<Cover> = None;
        while p < k && act[p].hot.l <= x {
            let c = cover_of(act, p);
            p += 1;
            // One with no pixel (`r ≤ l = x`) never covers.
            if c.r <= x {
                continue;
            }
            if chain {
                chain = cx.enter_chain(act, lo, &mut nc, c, x, None).chain;
                continue;
            }
            if let Some(h) = first {
                // Faces of one plane: the key decides on every pixel, so
                // one comparison does for both ends.
                let one = cx.one_plane(&h, &c);
                if c.r <= h.r && one.unwrap_or_else(|| cx.dominates(&h, &c, x, c.r - 1)) {
                    cx.stats.hidden += 1;
                    continue;
                }
                if nc - lo == 1
                    && c.r == h.r
                    && one.map_or_else(|| cx.dominates(&c, &h, x, c.r - 1), |h_first| !h_first)
                {
                    // The first, alone in the array, hidden: its place.
                    act[lo].cover = c.element();
                    first = Some(c);
                    cx.stats.hidden += 1;
                    continue;
                }
            } else if fresh {
                first = Some(c);
            }
            insert_many(act, &mut lo, &mut nc, c.element());
        }
        let mut next = next_l(act, p);
        if lo >= nc {
            let next = next_with_pixels(act, p, k, width);
            cx.stats.empty += 1;
            cx.emit(next - x, Run::BACKGROUND, BACKGROUND);
            x = next;
            continue;
        }
        let f = if chain {
            if nc - lo == 1 {
                cx.stats.single += 1;
            } else {
                cx.stats.multiple += 1;
            }
            cover_of(act, act[lo].cover.p as usize)
        } else {
            let cov = &act[lo..nc.min(k)];
            let Some(f) = cx.establish(act, cov, x) else {
                let t = next_with_pixels(act, p, k, width)
                    .min(cov.first().map_or(width, |a| a.cover.r));
                span(act, cov, x, t, cx);
                x = t;
                continue;
            };
            let f = cover_of(act, f as usize);
            // The covers before the front end by its end, behind it.
            while lo < nc && act[lo].cover.r <= f.r && act[lo].cover.p != f.p {
                lo += 1;
            }
            if nc - lo > try_from {
                chain = cx.is_chain(act, &act[lo..nc], x);
                if !chain {
                    try_from = 2 * (nc - lo);
                }
            }
            f
        };
        // The front holds from x until it ends or a trapezoid starts that
        // it does not dominate.
        let start = x;
        loop {
            x = next.min(f.r);
            if x >= f.r {
                break;
            }
            // The first trapezoid that broke the front here, if any: one
            // that starts with it, behind it on all its pixels, is hidden
            // as well (staggered faces that start on one pixel, each in
            // front of those before it).
            let mut breaker: Option<Cover> = None;
            while p < k && act[p].hot.l <= x {
                let c = cover_of(act, p);
                p += 1;
                if c.r <= x {
                    continue;
                }
                if chain {
                    let e = cx.enter_chain(act, lo, &mut nc, c, x, Some(&f));
                    chain = e.chain;
                    if e.breaks && breaker.is_none() {
                        breaker = Some(c);
                    }
                    continue;
                }
                if cx.dominates(&f, &c, x, f.r.min(c.r) - 1) {
                    if c.r <= f.r {
                        cx.stats.hidden += 1;
                        continue;
                    }
                } else if let Some(b) = breaker {
                    if c.r <= b.r && cx.dominates(&b, &c, x, c.r - 1) {
                        cx.stats.hidden += 1;
                        continue;
                    }
                } else {
                    if nc - lo > PRUNE_FROM {
                        lo = prune_many(act, lo, nc, &f);
                    }
                    breaker = Some(c);
                }
                insert_many(act, &mut lo, &mut nc, c.element());
            }
            let broken = breaker.is_some();
            next = next_l(act, p);
            if broken {
                break;
            }
        }
        cx.emit(x - start, f.face, f.color);
    }
}

/// Covers past which [`sweep_many`] checks a front found for a chain.
const CHAIN_FROM: usize = 8;

/// [`prune`] for [`sweep_many`]: drops from `act[lo..nc].cover` (by
/// increasing `r`) the covers that end by `f.r`, `f` among them, and puts
/// `f` back first; the new `lo`.
fn prune_many(act: &mut [Active], lo: usize, nc: usize, f: &Cover) -> usize {
    let mut i = lo;
    while i < nc && act[i].cover.r <= f.r {
        i += 1;
    }
    if i == lo {
        return lo;
    }
    act[i - 1].cover = f.element();
    i - 1
}

/// Inserts `c` into `act[lo..nc].cover`, kept by increasing `r`: first
/// when it ends first and there is room before, else from the end, after
/// those that end with it and before those that end later (found by a
/// binary search past [`FAR`] of them), moving those up. After, not
/// before, those that end with it: faces of one extent enter in the order
/// of their keys, so each is appended (and they form a chain), where
/// going before them would move them all, `O(a)` a face and `O(a²)` a
/// row. The array has a place for every trapezoid that enters the row
/// (`nc` grows by one at most for each), so it never overflows.
fn insert_many(act: &mut [Active], lo: &mut usize, nc: &mut usize, c: Covered) {
    if *nc >= act.len() {
        return;
    }
    if *lo > 0 && (*lo >= *nc || c.r <= act[*lo].cover.r) {
        *lo -= 1;
        act[*lo].cover = c;
        return;
    }
    if *nc - *lo > FAR && act[*nc - FAR].cover.r > c.r {
        let q = place(act, *lo, *nc - FAR, c.r + 1);
        insert_at(act, q, nc, c);
        return;
    }
    // Near the end: found and made room for in one pass.
    let mut q = *nc;
    while q > *lo && act[q - 1].cover.r > c.r {
        act[q].cover = act[q - 1].cover;
        moved(1);
        q -= 1;
    }
    act[q].cover = c;
    *nc += 1;
}

/// Moves past which [`insert_many`] looks for the place by a binary
/// search.
const FAR: usize = 8;

/// The first cover of `act[lo..nc].cover` (by increasing `r`) that ends
/// at `r` or after, by a binary search.
fn place(act: &[Active], lo: usize, nc: usize, r: i32) -> usize {
    let (mut a, mut b) = (lo, nc.min(act.len()));
    while a < b {
        let m = a + (b - a) / 2;
        if act[m].cover.r < r {
            a = m + 1;
        } else {
            b = m;
        }
    }
    a
}

/// Inserts `c` at `q` of `act[..nc].cover`, moving those after it up.
fn insert_at(act: &mut [Active], q: usize, nc: &mut usize, c: Covered) {
    if *nc >= act.len() || q > *nc {
        return;
    }
    moved(*nc - q);
    let mut i = *nc;
    while i > q {
        act[i].cover = act[i - 1].cover;
        i -= 1;
    }
    act[q].cover = c;
    *nc += 1;
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
std::thread_local! {
    /// Covers moved to make room in the cover array, on this thread
    /// (counted for the tests that bound the work of degenerate rows).
    static MOVED: core::cell::Cell<u64> = const { core::cell::Cell::new(0) };
}

/// Counts `n` covers moved (in tests; nothing otherwise).
#[inline(always)]
fn moved(_n: usize) {
    #[cfg(test)]
    MOVED.with(|m| m.set(m.get() + _n as u64));
}

/// What a trapezoid entering a chain did (see [`Ctx::enter_chain`]).
struct Entered {
    /// The front no longer holds.
    breaks: bool,
    /// The covers are still a chain.
    chain: bool,
}

/// Resolves the span `s..t` covered by `cov` (covers of the live
/// trapezoids `act[..k].hot`); returns the nearest at its last pixel.
#[inline(always)]
fn span<O: RowOut>(act: &[Active], cov: &[Active], s: i32, t: i32, cx: &mut Ctx<'_, O>) -> Cover {
    let Some((first, rest)) = cov.split_first() else {
        return Cover::EMPTY;
    };
    let first = &first.cover;
    if rest.is_empty() {
        let f = cover_of(act, first.p as usize);
        cx.stats.single += 1;
        cx.emit(t - s, f.face, f.color);
        return f;
    }
    // The nearest at both ends in one pass.
    let e = t - 1;
    let (mut a, mut za) = (first, first.z_at(s));
    let (mut b, mut zb) = (first, first.z_at(e));
    for c in rest.iter().map(|a| &a.cover) {
        let (zs, ze) = (c.z_at(s), c.z_at(e));
        if cx.nearer_in(act, c, zs, a, za, s) {
            (a, za) = (c, zs);
        }
        if cx.nearer_in(act, c, ze, b, zb, e) {
            (b, zb) = (c, ze);
        }
    }
    if a.p == b.p {
        let f = cover_of(act, a.p as usize);
        cx.stats.multiple += 1;
        cx.emit(t - s, f.face, f.color);
        return f;
    }
    cx.stats.intersecting += 1;
    let (a, b) = (cover_of(act, a.p as usize), cover_of(act, b.p as usize));
    split(act, cov, s, t, &a, &b, true, cx);
    b
}

/// Subdivides `s..t` (at least 2 pixels), whose nearest covering
/// trapezoids at the ends are `a` and `b ≠ a`.
#[allow(clippy::too_many_arguments)]
fn split<O: RowOut>(
    act: &[Active],
    cov: &[Active],
    s: i32,
    t: i32,
    a: &Cover,
    b: &Cover,
    cross: bool,
    cx: &mut Ctx<'_, O>,
) {
    cx.stats.splits += 1;
    let crossing = cx.mode != Resolve::Bisect && cross;
    let m = if crossing {
        crossing_point(a, b, s, t)
    } else {
        s + (t - s) / 2
    };
    // Parts longer than half the span are bisected next, so the depth of
    // the recursion stays within 2·log₂(t − s).
    let half = (t - s) / 2;
    let ma = cx.front(act, cov, m - 1).p;
    if ma == a.p {
        cx.emit(m - s, a.face, a.color);
    } else {
        let ma = cover_of(act, ma as usize);
        split(act, cov, s, m, a, &ma, !crossing || m - s <= half, cx);
    }
    let mb = cx.front(act, cov, m).p;
    if mb == b.p {
        cx.emit(t - m, b.face, b.color);
    } else {
        let mb = cover_of(act, mb as usize);
        split(act, cov, m, t, &mb, b, !crossing || t - m <= half, cx);
    }
}

/// The first pixel of `s + 1..t` where the plane of `b` is estimated to
/// be in front of that of `a`, from their fixed-point depths at the ends
/// of `s..t` (one division).
#[inline(always)]
fn crossing_point(a: &Cover, b: &Cover, s: i32, t: i32) -> i32 {
    // D(i) = Za(i) − Zb(i): ≤ 0 at s, ≥ 0 at t − 1, affine between.
    let d0 = a.z_at(s) as i64 - b.z_at(s) as i64;
    let d1 = a.z_at(t - 1) as i64 - b.z_at(t - 1) as i64;
    let (run, rise) = ((t - 1 - s) as i64, d1 - d0);
    let k = if rise > 0 && d0 <= 0 {
        // |d0| < 2³³, run < 2¹²: the product is below 2⁴⁵. Both are
        // non-negative, so the quotient is the floor; near a crossing
        // they usually fit 32 bits, where a Cortex-M4 divides in one
        // instruction instead of a call to `__aeabi_ldivmod`.
        let n = (-d0 * run) as u64;
        let q = match (u32::try_from(n), u32::try_from(rise)) {
            (Ok(n), Ok(r)) => (n / r) as i64,
            _ => (n / rise as u64) as i64,
        };
        s as i64 + q + 1
    } else {
        (s + (t - s) / 2) as i64
    };
    k.clamp(s as i64 + 1, t as i64 - 1) as i32
}

impl<O: RowOut> Ctx<'_, O> {
    /// The covering trapezoid nearest at pixel `x` when it is also in
    /// front of every other on all their common pixels (`x` to the end of
    /// the shorter), so on `x..r` of its own; `None` when another crosses
    /// it there. Its position in the live trapezoids `act[..k].hot`.
    #[inline(always)]
    fn establish(&mut self, act: &[Active], cov: &[Active], x: i32) -> Option<u16> {
        let f = self.front(act, cov, x);
        if cov.len() == 1 {
            self.stats.single += 1;
            return Some(f.p);
        }
        // The front is told from the others by its place in `cov` (each
        // trapezoid is there once), which costs no load, not by `p`.
        for c in cov.iter().map(|a| &a.cover) {
            if core::ptr::eq(c, f) {
                continue;
            }
            let e = f.r.min(c.r) - 1;
            if !self.nearer_in(act, f, f.z_at(e), c, c.z_at(e), e) {
                return None;
            }
        }
        self.stats.multiple += 1;
        Some(f.p)
    }

    /// Enters `c` into the chain `act[lo..nc].cover` (by increasing `r`,
    /// see [`sweep_many`]) at `x`. With the front `f` (the first cover,
    /// unless a trapezoid that broke it entered since), `c` is left out
    /// when a cover is in front of it on all its pixels left (*hidden*).
    ///
    /// Among the covers that end with it, `c` goes first when it is in
    /// front of the first of them, and then takes that one's place (which
    /// it hides on all its pixels left, as it hides the rest of them by
    /// transitivity), else after them. So staggered faces that end on one
    /// pixel, each in front of the last, keep one cover there, and faces
    /// of one extent entering behind those before them are appended: no
    /// cover moves in either, where going before them all would move them
    /// all, `O(a)` a face.
    fn enter_chain(
        &mut self,
        act: &mut [Active],
        lo: usize,
        nc: &mut usize,
        c: Cover,
        x: i32,
        f: Option<&Cover>,
    ) -> Entered {
        let n = (*nc).min(act.len());
        let mut q = place(act, lo, n, c.r);
        let mut e = Entered {
            breaks: false,
            chain: true,
        };
        // The first of those that end with it, when it is in front of
        // that one: its place, taken.
        let mut take = false;
        if let Some(d) = act[..n].get(q).map(|a| cover_of(act, a.cover.p as usize)) {
            if d.r == c.r {
                take = self.dominates(&c, &d, x, c.r - 1);
                if !take {
                    q = place(act, q, n, c.r + 1);
                }
            }
        }
        if q > lo {
            // It ends after the first, or with it and behind it.
            let u = cover_of(act, act[q - 1].cover.p as usize);
            if self.dominates(&u, &c, x, u.r.min(c.r) - 1) {
                // So is the first (the front), by transitivity.
                if f.is_some() && c.r <= u.r {
                    self.stats.hidden += 1;
                    return e;
                }
            } else {
                e.chain = false;
                if let Some(f) = f {
                    if self.dominates(f, &c, x, f.r.min(c.r) - 1) {
                        if c.r <= f.r {
                            self.stats.hidden += 1;
                            return e;
                        }
                    } else {
                        e.breaks = true;
                    }
                }
            }
            if take {
                // In front of the one after it, whose place it takes.
            } else if let Some(d) = act[..n].get(q).map(|a| cover_of(act, a.cover.p as usize)) {
                e.chain = e.chain && self.dominates(&c, &d, x, c.r.min(d.r) - 1);
            }
        } else if let Some(t) = act[..n].get(lo).map(|a| cover_of(act, a.cover.p as usize)) {
            // It ends first (or with the first, in front of it).
            if let Some(f) = f {
                if self.dominates(f, &c, x, f.r.min(c.r) - 1) {
                    if c.r <= f.r {
                        self.stats.hidden += 1;
                        return e;
                    }
                } else {
                    e.breaks = true;
                }
            }
            e.chain = take || self.dominates(&c, &t, x, c.r.min(t.r) - 1);
        }
        if take {
            // The one it hides leaves; those after it are behind it too.
            act[q].cover = c.element();
        } else {
            insert_at(act, q, nc, c.element());
        }
        e
    }

    /// `true` when each cover of `cov` (by increasing `r`) after the first
    /// is in front of the next on their common pixels from `x`.
    fn is_chain(&mut self, act: &[Active], cov: &[Active], x: i32) -> bool {
        for w in cov.windows(2).skip(1) {
            let a = cover_of(act, w[0].cover.p as usize);
            let b = cover_of(act, w[1].cover.p as usize);
            if !self.dominates(&a, &b, x, a.r.min(b.r) - 1) {
                return false;
            }
        }
        true
    }

    /// The covering trapezoid nearest at pixel `i` (`cov` covers of the
    /// live trapezoids `act[..k].hot`).
    fn front<'v>(&mut self, act: &[Active], cov: &'v [Active], i: i32) -> &'v Covered {
        let (first, rest) = match cov.split_first() {
            Some((f, r)) => (&f.cover, r),
            None => return &NO_COVER,
        };
        let (mut best, mut bz) = (first, first.z_at(i));
        for c in rest.iter().map(|a| &a.cover) {
            let cz = c.z_at(i);
            let d = cz.wrapping_sub(bz);
            // As `nearer`, the sign selecting without a branch where the
            // fixed point decides.
            let take = if d.unsigned_abs() <= DEPTH_TOLERANCE as u32 {
                self.exact_in(act, c, best, i, d)
            } else {
                d < 0
            };
            best = if take { c } else { best };
            bz = if take { cz } else { bz };
        }
        best
    }

    /// [`dominates`](Self::dominates) for an element of the cover array
    /// `g`, whose face is read from `act[..k].hot` only when the fixed
    /// point does not decide.
    #[inline(always)]
    fn dominates_el(&mut self, act: &[Active], f: &Cover, g: &Covered, s: i32, e: i32) -> bool {
        let mut nearer = |i: i32| {
            let d = f.z_at(i).wrapping_sub(g.z_at(i));
            if d < -(DEPTH_TOLERANCE as i32) {
                return true;
            }
            if d > DEPTH_TOLERANCE as i32 {
                return false;
            }
            let gf = act.get(g.p as usize).map_or(NONE, |a| a.hot.face);
            self.exact(f.face, gf, i, d)
        };
        nearer(s) && nearer(e)
    }

    /// `true` when `f` is in front of `g` at pixels `s` and `e`, so on
    /// every pixel between (both cover them all).
    #[inline]
    fn dominates(&mut self, f: &Cover, g: &Cover, s: i32, e: i32) -> bool {
        self.nearer(f.face, f.z_at(s), g.face, g.z_at(s), s)
            && self.nearer(f.face, f.z_at(e), g.face, g.z_at(e), e)
    }

    /// When `a` and `b` are faces of one plane (their fixed-point depths
    /// the same on the row, then their planes), whether `a` is in front
    /// of `b` on every pixel: the lower key.
    #[inline(always)]
    fn one_plane(&mut self, a: &Cover, b: &Cover) -> Option<bool> {
        if a.z != b.z || a.zx != b.zx {
            return None;
        }
        self.stats.exact += 1;
        match (self.store.face(a.face), self.store.face(b.face)) {
            (Some(fa), Some(fb)) if fa.plane() == fb.plane() => Some(fa.key() < fb.key()),
            _ => None,
        }
    }

    /// `true` when face `c` (depth `cz` at pixel `i`) is in front of face
    /// `b` (depth `bz`).
    #[inline(always)]
    fn nearer(&mut self, c: u16, cz: i32, b: u16, bz: i32, i: i32) -> bool {
        // Both depths are below 2³⁰ in magnitude where they are meaningful
        // (see `trapezoid`), so the difference does not wrap.
        let d = cz.wrapping_sub(bz);
        if d < -(DEPTH_TOLERANCE as i32) {
            return true;
        }
        if d > DEPTH_TOLERANCE as i32 {
            return false;
        }
        self.exact(c, b, i, d)
    }

    /// [`nearer`](Self::nearer) for two elements of the cover array, whose
    /// faces are read from the live trapezoids `act[..k].hot` only when
    /// the fixed point does not decide.
    ///
    /// Its fixed-point test repeats `nearer`'s (and `dominates_el`'s) on
    /// purpose: one helper returning `Option<bool>` for the three compiles
    /// to more instructions on the Cortex-M4 (`docs/performance-log.md`).
    #[inline(always)]
    fn nearer_in(
        &mut self,
        act: &[Active],
        c: &Covered,
        cz: i32,
        b: &Covered,
        bz: i32,
        i: i32,
    ) -> bool {
        let d = cz.wrapping_sub(bz);
        if d < -(DEPTH_TOLERANCE as i32) {
            return true;
        }
        if d > DEPTH_TOLERANCE as i32 {
            return false;
        }
        self.exact_in(act, c, b, i, d)
    }

    /// [`exact`](Self::exact) for two elements of the cover array.
    #[inline(never)]
    fn exact_in(&mut self, act: &[Active], c: &Covered, b: &Covered, i: i32, d: i32) -> bool {
        let cf = act.get(c.p as usize).map_or(NONE, |a| a.hot.face);
        let bf = act.get(b.p as usize).map_or(NONE, |a| a.hot.face);
        self.exact(cf, bf, i, d)
    }

    /// The exact comparison, for depths too close for fixed point.
    #[inline(never)]
    fn exact(&mut self, c: u16, b: u16, i: i32, d: i32) -> bool {
        self.stats.exact += 1;
        exact_nearer(self.store, c, b, (i, self.y), d)
    }

    /// Appends `len` pixels of `ink` (a face, or the background) in
    /// `color` to the pending run when the colour is the same, else writes
    /// the pending run out and starts another.
    #[inline(always)]
    fn emit(&mut self, len: i32, ink: u16, color: u32) {
        if color == self.color {
            self.len += len;
            return;
        }
        self.flush();
        self.ink = ink;
        self.len = len;
        self.color = color;
    }

    /// Writes the pending run out.
    #[inline]
    fn flush(&mut self) {
        if self.len > 0 {
            self.out.run(self.len, self.ink, self.color);
        }
        self.len = 0;
    }
}

/// `true` when face `c` is in front of face `b` at the centre of pixel
/// `(i, j)`, exactly: the nearer plane, at equal depth the lower key.
/// `d`, the difference of their fixed-point depths, decides only for a
/// face missing from the store (never in a store as built). Not inlined:
/// rare, and large (the exact comparison in `i128`).
#[inline(never)]
fn exact_nearer(store: &TrapezoidStore<'_>, c: u16, b: u16, (i, j): (i32, i32), d: i32) -> bool {
    match (store.face(c), store.face(b)) {
        // One plane (faces of one extent stacked, points at one place):
        // equal depth everywhere, the key decides, without the products.
        (Some(fc), Some(fb)) if fc.plane() == fb.plane() => fc.key() < fb.key(),
        (Some(fc), Some(fb)) => fc
            .plane()
            .cmp_at(fb.plane(), i, j)
            .then(fc.key().cmp(&fb.key()))
            .is_lt(),
        _ => d < 0,
    }
}

/// The colour of the background in [`Ctx`]: not a 24-bit colour.
const BACKGROUND: u32 = u32::MAX;

/// What [`Ctx::front`] returns for an empty cover (never asked).
static NO_COVER: Covered = Covered::EMPTY;

/// Resolves `store` and writes it into `target`: each face in its colour,
/// the background filled with `background` or left as it is (`None`), so
/// that the 3D layer can lie over 2D content.
#[doc(hidden)]
pub fn draw<T>(
    store: &TrapezoidStore<'_>,
    workspace: &mut Workspace<'_>,
    mode: Resolve,
    target: &mut T,
    background: Option<T::Color>,
) -> Result<(VisibleStats, Counts), VisibleError<T::Error>>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    let mode = match mode {
        Resolve::Auto if !T::OVERDRAW_IS_CHEAP => Resolve::Crossing,
        Resolve::Auto => workspace
            .check_rows(store)
            .map_err(VisibleError::widen)?
            .settle(mode),
        m => m,
    };
    if mode == Resolve::Paint {
        return paint::draw(store, workspace, target, background);
    }
    workspace.check_runs(store)?;
    let mut runs = pending_runs();
    let out = ToTarget::new(target, background, batch_of::<T>(&mut runs));
    let (stats, out) = resolve_into(workspace.active, store, mode, out)?;
    Ok((stats, out.counts))
}

#[cfg(test)]
mod coherence;
mod paint;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::{Coord, Vertex3};
    use crate::raster::clip::ClipRect;
    use crate::visible::store::{Face, Segment, StoreMemory};
    use crate::visible::trapezoid::EdgeSlot;
    use embedded_graphics_core::pixelcolor::Rgb888;

    /// `Auto` paints from a mean height of `PAINT_FROM` rows on, at the
    /// edge and at the counters' extremes; the other modes stay.
    #[test]
    fn auto_settles_by_the_mean_height() {
        let auto = Resolve::Auto;
        assert_eq!(auto.settle(0, 0), Resolve::Crossing);
        assert_eq!(auto.settle(0, u32::MAX), Resolve::Crossing);
        assert_eq!(auto.settle(10, 10 * PAINT_FROM), Resolve::Paint);
        assert_eq!(auto.settle(10, 10 * PAINT_FROM - 1), Resolve::Crossing);
        assert_eq!(auto.settle(1, u32::MAX), Resolve::Paint);
        assert_eq!(auto.settle(u32::MAX, u32::MAX), Resolve::Crossing);
        for m in [Resolve::Bisect, Resolve::Crossing, Resolve::Paint] {
            assert_eq!(m.settle(1, 1000), m);
            assert_eq!(m.settle(1000, 1), m);
        }
        assert_eq!(Resolve::default(), Resolve::Auto);
    }

    const W: u16 = 48;
    const H: u16 = 40;

    fn v(x: i32, y: i32, z: i32) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits(x as i16),
            y: Coord::from_bits(y as i16),
            z: Coord::from_bits(z as i16),
        }
    }

    use super::coherence::Pools;
    use testkit::rng::Rng;

    /// The pixel rule for one pixel, from its definition.
    fn covers(poly: &[Vertex3], i: i32, j: i32) -> bool {
        crate::raster::scan::rule_covers(poly, |v| (v.x.units(), v.y.units()), i, j)
    }

    /// The winner at each pixel by brute force over the store's faces:
    /// the polygon with the smallest exact depth, ties to the lower key.
    /// Asserts that row `y`'s `runs` show the polygons of `want` (the
    /// faces' polygons by `poly_of`); returns the columns they cover.
    fn assert_row(
        y: u16,
        runs: &[Run],
        want: &[u16],
        poly_of: impl Fn(u16) -> u16,
        what: &dyn core::fmt::Debug,
    ) -> i32 {
        let mut x = 0;
        for r in runs {
            let got = if r.is_background() {
                Run::BACKGROUND
            } else {
                poly_of(r.ink())
            };
            for i in x..x + r.len() as i32 {
                assert_eq!(
                    got,
                    want[(y as i32 * W as i32 + i) as usize],
                    "pixel ({i}, {y}) of {what:?}"
                );
            }
            x += r.len() as i32;
        }
        x
    }

    fn brute<P: AsRef<[Vertex3]>>(
        polys: &[P],
        store: &TrapezoidStore<'_>,
    ) -> [u16; (W * H) as usize] {
        let mut out = [Run::BACKGROUND; (W * H) as usize];
        for j in 0..H as i32 {
            for i in 0..W as i32 {
                let mut best: Option<(usize, &Face)> = None;
                for (k, p) in polys.iter().enumerate() {
                    if !covers(p.as_ref(), i, j) {
                        continue;
                    }
                    // Face k is the k-th added to segment 0.
                    let f = (0..64)
                        .map(|f| store.face(f).unwrap())
                        .find(|f| f.segment() == 0 && f.key() == k as u32)
                        .unwrap();
                    let better = match best {
                        None => true,
                        Some((_, b)) => f
                            .plane()
                            .cmp_at(b.plane(), i, j)
                            .then(f.key().cmp(&b.key()))
                            .is_lt(),
                    };
                    if better {
                        best = Some((k, f));
                    }
                }
                out[(j * W as i32 + i) as usize] = best.map_or(Run::BACKGROUND, |(k, _)| k as u16);
            }
        }
        out
    }

    fn run_scene(polys: &[[Vertex3; 3]], mode: Resolve) -> VisibleStats {
        // Every row through `sweep_many` as well, to the same pixels.
        run_scene_many_from(polys, mode, (0, 0));
        run_scene_many_from(polys, mode, (0, CHAIN_FROM));
        run_scene_many_from(polys, mode, (MANY, CHAIN_FROM))
    }

    fn run_scene_many_from<P: AsRef<[Vertex3]> + core::fmt::Debug>(
        polys: &[P],
        mode: Resolve,
        many: (usize, usize),
    ) -> VisibleStats {
        let mut mem = Pools::new(64, H);
        let store = mem.store(polys, W, H);
        let want = brute(polys, &store);
        // Face slot → polygon number.
        let poly_of = |f: u16| store.face(f).unwrap().key() as u16;
        let mut active = [Active::EMPTY; 64];
        let mut runs = [Run::EMPTY; W as usize];
        let most = Workspace::new(&mut active, &mut runs)
            .check(&store)
            .unwrap();
        let check = |y: u16, runs: &[Run]| {
            let x = assert_row(y, runs, &want, poly_of, &(mode, polys));
            assert_eq!(x, W as i32);
            Ok::<(), ()>(())
        };
        let sink = ToSink {
            out: RunWriter::new(&mut runs),
            y: 0,
            sink: &check,
        };
        let (stats, _) = resolve_many_from(&mut active, &store, mode, many, sink).unwrap();
        assert_eq!(stats.max_active, most);
        // In bands of 3 rows, every other one skipped: the rows drawn are
        // the same (a skipped row leaves the active list as a drawn one).
        let mut active = [Active::EMPTY; 64];
        let (mut runs, mut band_runs) = ([Run::EMPTY; W as usize], [Run::EMPTY; W as usize]);
        let mut ws = Workspace::new(&mut active, &mut runs);
        let mut sweep = Sweep::new(&mut ws, mode);
        sweep.many = many;
        let mut sink = ToSink {
            out: RunWriter::new(&mut band_runs),
            y: 0,
            sink: &check,
        };
        for band in 0.. {
            if sweep.next_row() >= H {
                break;
            }
            if band % 2 == 0 {
                sweep.skip(&store, &mut ws, 3).unwrap();
            } else {
                sink = sweep.rows(ws.active, &store, 3, sink).unwrap();
            }
        }
        stats
    }

    /// A target that checks the guarantees of every span it is handed,
    /// counts them, and fails at its `fail_at`-th span.
    struct Recorder {
        size: (u16, u16),
        counts: Counts,
        fail_at: u32,
    }

    impl SpanTarget for Recorder {
        type Color = Rgb888;
        type Error = u32;

        fn size(&self) -> (u16, u16) {
            self.size
        }

        fn fill_span(&mut self, span: Span, _color: Rgb888) -> Result<(), u32> {
            assert!(span.x0 < span.x1 && span.x1 <= self.size.0, "{span:?}");
            assert!(span.y < self.size.1, "{span:?}");
            if self.counts.spans + 1 == self.fail_at {
                return Err(span.y as u32);
            }
            self.counts.span((span.x1 - span.x0) as u32);
            Ok(())
        }
    }

    #[test]
    fn draw_counts_the_spans_and_pixels_it_hands_the_target() {
        let mut rng = Rng(0x5eed_0011);
        let mut mem = Pools::new(64, H);
        let polys: [[Vertex3; 3]; 8] =
            core::array::from_fn(|_| random_tri(&mut rng, (-2000, 2000)));
        let store = mem.store(&polys, W, H);
        let sizes = [(W, H), (W - 7, H - 5), (1, 1), (W + 9, H + 2)];
        for (size, background) in sizes
            .into_iter()
            .flat_map(|s| [(s, None), (s, Some(Rgb888::new(1, 2, 3)))])
        {
            let mut active = [Active::EMPTY; 64];
            let mut runs = [Run::EMPTY; W as usize];
            let mut ws = Workspace::new(&mut active, &mut runs);
            let mut target = Recorder {
                size,
                counts: Counts::default(),
                fail_at: 0,
            };
            let (_, counts) =
                draw(&store, &mut ws, Resolve::Crossing, &mut target, background).unwrap();
            assert_eq!(counts, target.counts, "{size:?} {background:?}");
            assert!(counts.spans > 0 || size == (1, 1), "{size:?}");
            if background.is_some() {
                let (w, h) = (size.0.min(W) as u32, size.1.min(H) as u32);
                assert_eq!(counts.pixels, w * h, "{size:?}");
            }
            if counts.spans == 0 {
                continue;
            }
            // A target that fails part-way: the error, with the row.
            let fail_at = counts.spans / 2 + 1;
            let mut failing = Recorder {
                size,
                counts: Counts::default(),
                fail_at,
            };
            let got = draw(&store, &mut ws, Resolve::Crossing, &mut failing, background);
            assert!(matches!(got, Err(VisibleError::Sink(_))), "{got:?}");
            assert_eq!(failing.counts.spans, fail_at - 1);
        }
    }

    #[test]
    fn check_counts_the_most_trapezoids_on_a_row_as_brute_force_does() {
        // Random stores of large triangles, and of small ones on whole rows
        // so that many trapezoids start and end on the same rows; the count
        // by rows one by one, and the capacity just below and at it.
        let mut rng = Rng(0x5eed_c4ec);
        for round in 0..300 {
            let n = 1 + rng.below(50) as usize;
            let polys: [[Vertex3; 3]; 50] = core::array::from_fn(|_| {
                if round % 2 == 0 {
                    random_tri(&mut rng, (-2000, 2000))
                } else {
                    let (x, y) = (rng.below(W as u32) - 4, rng.below(H as u32) - 4);
                    let mut c = || (x + rng.below(9), y + rng.below(9));
                    let (a, b, d) = (c(), c(), c());
                    [
                        v(a.0 * 16, a.1 * 16, 100),
                        v(b.0 * 16, b.1 * 16, 200),
                        v(d.0 * 16, d.1 * 16, 300),
                    ]
                }
            });
            // The full width: more runs than rows, the ends counted row by
            // row; and a width below the rows, as many runs: the heap.
            for width in [W, H - 8] {
                let mut mem = Pools::new(64, H);
                let store = mem.store(&polys[..n], width, H);
                let mut want = 0;
                for y in 0..H as i32 {
                    let on_row = (0..H)
                        .flat_map(|top| store.starting_at(top))
                        .filter(|(_, t)| (t.top as i32) <= y && y < t.end as i32)
                        .count();
                    want = want.max(on_row);
                }
                let mut active = [Active::EMPTY; 64];
                let mut runs = [Run::EMPTY; W as usize];
                let runs = &mut runs[..width as usize];
                let got = Workspace::new(&mut active[..want.max(1)], runs).check(&store);
                assert_eq!(got, Ok(want as u32), "round {round}, width {width}");
                if want > 0 {
                    let got = Workspace::new(&mut active[..want - 1], runs).check(&store);
                    assert_eq!(got, Err(VisibleError::Active { capacity: want - 1 }));
                }
            }
        }
    }

    fn random_tri(rng: &mut Rng, zs: (i32, i32)) -> [Vertex3; 3] {
        let mut t = [Vertex3::default(); 3];
        for p in t.iter_mut() {
            *p = v(
                rng.below((W as u32 + 8) * 16) - 64,
                rng.below((H as u32 + 8) * 16) - 64,
                zs.0 + rng.below((zs.1 - zs.0) as u32),
            );
        }
        t
    }

    #[test]
    fn interpenetrating_triangles_are_exact_in_both_modes() {
        let mut rng = Rng(0xdead_beef);
        let mut intersecting = 0;
        for _ in 0..150 {
            let n = 2 + rng.below(6) as usize;
            let polys: [[Vertex3; 3]; 8] =
                core::array::from_fn(|_| random_tri(&mut rng, (-2000, 2000)));
            for mode in [Resolve::Bisect, Resolve::Crossing] {
                intersecting += run_scene(&polys[..n], mode).intersecting;
            }
        }
        assert!(intersecting > 100, "the scenes must exercise subdivision");
    }

    #[test]
    fn staggered_faces_in_every_order_are_exact() {
        // Right triangles, each a little right of and below the last:
        // nearer, farther and in an order of their own, parallel to the
        // screen or tilted, so that dozens overlap a row and cover a pixel.
        let mut rng = Rng(0x57a6_6e7d);
        for order in 0..4 {
            for tilt in [0, 3, -5] {
                let polys: [[Vertex3; 3]; 60] = core::array::from_fn(|k| {
                    let o = k as i32 * 7 - 40;
                    let z = match order {
                        0 => 1000 - 10 * k as i32,
                        1 => -1000 + 10 * k as i32,
                        2 => rng.below(4000) - 2000,
                        _ => (k as i32 % 7) * 50,
                    };
                    [
                        v(o, o, z),
                        v(o, o + 500, z + tilt * 500),
                        v(o + 500, o, z - tilt * 300),
                    ]
                });
                for mode in [Resolve::Bisect, Resolve::Crossing] {
                    run_scene(&polys, mode);
                }
            }
        }
    }

    /// Resolves `polys` with every row through `sweep_many` (the chain
    /// looked for from the first front, and from [`CHAIN_FROM`] covers),
    /// against brute force; the covers moved to make room, in all.
    fn moves_many<P: AsRef<[Vertex3]> + core::fmt::Debug>(polys: &[P], mode: Resolve) -> u64 {
        let before = MOVED.with(|m| m.get());
        for many in [(0, 0), (0, CHAIN_FROM)] {
            run_scene_many_from(polys, mode, many);
        }
        MOVED.with(|m| m.get()) - before
    }

    #[test]
    fn faces_ending_on_one_column_move_no_cover() {
        // Quads of one extent stacked at one depth (each behind those
        // before it, by its key) and staggered ½ px, each nearer or each
        // farther, all ending past the last column: each enters after
        // those that end with it, or takes the place of the one it
        // hides, and none moves (going before them all moved them all,
        // O(n²) a row).
        let quad = |x0: i32, z: i32| {
            [
                v(x0, 0, z),
                v(x0, 16 * H as i32, z),
                v(16 * W as i32 + 40, 16 * H as i32, z),
                v(16 * W as i32 + 40, 0, z),
            ]
        };
        let stacked: [[Vertex3; 4]; 60] = core::array::from_fn(|_| quad(0, 700));
        let nearer: [[Vertex3; 4]; 60] =
            core::array::from_fn(|k| quad(8 * k as i32, 900 - 9 * k as i32));
        let farther: [[Vertex3; 4]; 60] =
            core::array::from_fn(|k| quad(8 * k as i32, -900 + 9 * k as i32));
        for mode in [Resolve::Bisect, Resolve::Crossing] {
            for polys in [&stacked, &nearer, &farther] {
                assert_eq!(moves_many(polys, mode), 0, "{mode:?} {polys:?}");
                run_scene_many_from(polys, mode, (MANY, CHAIN_FROM));
            }
        }
        // Stacked in front of one another: most hidden where they start.
        let stats = run_scene_many_from(&stacked, Resolve::Crossing, (0, 0));
        assert!(stats.hidden >= 59 * H as u32, "{stats:?}");
    }

    #[test]
    fn faces_with_no_pixel_on_some_rows_are_passed_by() {
        // A strip of thin triangles sharing edges, as a mesh's faces near
        // its silhouette: each has no pixel on some rows (`r ≤ l`) and
        // keeps its place among the others by `l`. Alone on their rows,
        // and under or over wide faces, so that the sweep meets them where
        // nothing covers and where covers are, and enters none of them.
        let mut rng = Rng(0x7819_5e11);
        for _ in 0..80 {
            let (y0, y1) = (rng.below(16 * 8) - 32, 16 * 24 + rng.below(16 * 24));
            let shift = rng.below(16 * 16) - 16 * 8;
            let mut top = 16 * 8 + rng.below(64);
            let mut bottom = top + shift;
            let mut polys = [[Vertex3::default(); 3]; 24];
            let mut n = 0;
            while n + 2 <= 20 {
                let (t, b) = (top + 1 + rng.below(20), bottom + 1 + rng.below(20));
                let z = |rng: &mut Rng| 600 + rng.below(200);
                let (zt, zb, zt1, zb1) = (z(&mut rng), z(&mut rng), z(&mut rng), z(&mut rng));
                polys[n] = [v(top, y0, zt), v(bottom, y1, zb), v(b, y1, zb1)];
                polys[n + 1] = [v(top, y0, zt), v(b, y1, zb1), v(t, y0, zt1)];
                (top, bottom, n) = (t, b, n + 2);
            }
            let wide = rng.below(4) as usize;
            for p in polys[n..n + wide].iter_mut() {
                let z = if rng.below(2) == 0 {
                    (0, 500)
                } else {
                    (900, 1800)
                };
                *p = random_tri(&mut rng, z);
            }
            for mode in [Resolve::Bisect, Resolve::Crossing] {
                run_scene(&polys[..n + wide], mode);
            }
        }
    }

    /// One row of `live` (sorted by `l` for the sweep) resolved into
    /// `out`, started at `row`, by `side` (the side-by-side writer) or
    /// the sweep; the context is returned with its pending run flushed.
    fn resolve_row<'s, O: RowOut>(
        store: &'s TrapezoidStore<'s>,
        live: &[Hot],
        side: bool,
        out: O,
        row: u16,
    ) -> Ctx<'s, O> {
        let mut act = [Active::EMPTY; 64];
        for (a, h) in act.iter_mut().zip(live) {
            a.hot = *h;
        }
        let k = live.len();
        let mut cx = Ctx {
            store,
            out,
            ink: Run::BACKGROUND,
            len: 0,
            color: BACKGROUND,
            mode: Resolve::Crossing,
            y: 0,
            stats: VisibleStats::default(),
        };
        cx.out.start(row);
        if side {
            // The output's own writer where it has one, as the sweep's
            // rows take it.
            match cx.out.side_by_side(&act[..k], W as i32, &mut cx.stats) {
                Some(true) => {}
                Some(false) => panic!("a side-by-side row refused"),
                None => write_side_by_side(&act[..k], W as i32, &mut cx),
            }
        } else {
            sort(&mut act[..k]);
            sweep(&mut act, k, W as i32, &mut cx);
        }
        cx.flush();
        cx
    }

    /// The runs and counts of one row of `live`, written by `side` (the
    /// side-by-side writer) or the sweep.
    fn row_of(live: &[Hot], side: bool) -> (std::vec::Vec<(u16, u16)>, VisibleStats) {
        let mut mem = Pools::new(1, H);
        let no_faces: [[Vertex3; 3]; 0] = [];
        let store = mem.store(&no_faces, W, H);
        let got = core::cell::RefCell::new(std::vec::Vec::new());
        let keep = |_: u16, runs: &[Run]| {
            got.borrow_mut()
                .extend(runs.iter().map(|r| (r.len(), r.ink())));
            Ok::<(), ()>(())
        };
        let mut runs = [Run::EMPTY; W as usize];
        let out = ToSink {
            out: RunWriter::new(&mut runs),
            sink: &keep,
            y: 0,
        };
        let mut cx = resolve_row(&store, live, side, out, 0);
        cx.out.finish().unwrap();
        let stats = cx.stats;
        (got.into_inner(), stats)
    }

    /// A target that keeps every span it is handed, with its colour.
    struct Spans {
        size: (u16, u16),
        got: std::vec::Vec<(u16, u16, u16, Rgb888)>,
    }

    impl SpanTarget for Spans {
        type Color = Rgb888;
        type Error = core::convert::Infallible;

        fn size(&self) -> (u16, u16) {
            self.size
        }

        fn fill_span(&mut self, span: Span, color: Rgb888) -> Result<(), Self::Error> {
            self.got.push((span.y, span.x0, span.x1, color));
            Ok(())
        }
    }

    /// The spans, counts and runs of one row of `live` (sorted by `l` for
    /// the sweep) written into a target of `width` columns with
    /// `background`, by the side-by-side writer or the sweep.
    #[allow(clippy::type_complexity)]
    fn row_into(
        live: &[Hot],
        side: bool,
        width: u16,
        background: Option<Rgb888>,
    ) -> (
        std::vec::Vec<(u16, u16, u16, Rgb888)>,
        Counts,
        u32,
        VisibleStats,
    ) {
        let mut mem = Pools::new(1, H);
        let no_faces: [[Vertex3; 3]; 0] = [];
        let store = mem.store(&no_faces, W, H);
        let mut target = Spans {
            size: (width, H),
            got: std::vec::Vec::new(),
        };
        let mut runs = pending_runs();
        let mut cx = resolve_row(
            &store,
            live,
            side,
            ToTarget::new(&mut target, background, &mut runs),
            1,
        );
        let runs = cx.out.finish().unwrap();
        let (counts, stats) = (cx.out.counts, cx.stats);
        (target.got, counts, runs, stats)
    }

    #[test]
    fn side_by_side_rows_are_written_as_the_sweep_writes_them() {
        // Rows of trapezoids side by side with gaps, some with no pixel
        // (`r ≤ l`, anywhere, also inside another's pixels or past the
        // width), some of one colour with the one before (their runs
        // merge), in the last row's order or not; and rows where two
        // overlap. Every row the check accepts is written with the
        // sweep's runs and counts, and every row it refuses has an
        // overlap or ends past the width.
        let mut rng = Rng(0x51de_b51d);
        let (mut accepted, mut refused) = (0, 0);
        for _ in 0..4000 {
            let n = 1 + rng.below(12) as usize;
            let mut live = std::vec::Vec::new();
            let mut x = rng.below(4);
            for i in 0..n {
                let color = if i > 0 && rng.below(5) == 0 {
                    i as u32 - 1
                } else {
                    i as u32
                };
                let (l, r) = if rng.below(4) == 0 {
                    let l = rng.below(W as u32 + 8);
                    (l, l - rng.below(3))
                } else {
                    let l = x + rng.below(3) - (rng.below(12) == 0) as i32;
                    let r = l + 1 + rng.below(6);
                    x = r;
                    (l, r)
                };
                live.push(Hot {
                    l: l.max(0),
                    r,
                    z: 0,
                    zx: 0,
                    color,
                    face: color as u16,
                    slot: i as u16,
                });
            }
            if rng.below(3) == 0 {
                let (a, b) = (rng.below(n as u32) as usize, rng.below(n as u32) as usize);
                live.swap(a, b);
            }
            let mut act = [Active::EMPTY; 64];
            for (a, h) in act.iter_mut().zip(&live) {
                a.hot = *h;
            }
            let row = side_by_side(&act[..n], W as i32);
            let mut spans: std::vec::Vec<(i32, i32)> = live
                .iter()
                .filter(|h| h.l < h.r)
                .map(|h| (h.l, h.r))
                .collect();
            spans.sort();
            let apart = spans.windows(2).all(|w| w[0].1 <= w[1].0)
                && spans.last().is_none_or(|s| s.1 <= W as i32);
            let sorted = spans.len() < 2
                || live
                    .iter()
                    .filter(|h| h.l < h.r)
                    .zip(live.iter().filter(|h| h.l < h.r).skip(1))
                    .all(|(a, b)| a.l <= b.l);
            match row {
                Row::SideBySide => {
                    assert!(apart && sorted, "{live:?}");
                    accepted += 1;
                    let (runs, stats) = row_of(&live, true);
                    let (want, want_stats) = row_of(&live, false);
                    assert_eq!(runs, want, "{live:?}");
                    assert_eq!(
                        (stats.empty, stats.single, stats.multiple),
                        (want_stats.empty, want_stats.single, want_stats.multiple),
                        "{live:?}"
                    );
                    // Into a target as wide as the row or narrower, the
                    // background filled or left: the same spans, colours
                    // and counts.
                    for width in [W, W - 5] {
                        for background in [None, Some(Rgb888::new(1, 2, 3))] {
                            let side = row_into(&live, true, width, background);
                            let want = row_into(&live, false, width, background);
                            assert_eq!(side.0, want.0, "{live:?} {width} {background:?}");
                            assert_eq!(
                                (side.1.spans, side.1.pixels, side.2),
                                (want.1.spans, want.1.pixels, want.2),
                                "{live:?} {width} {background:?}"
                            );
                            assert_eq!(
                                (side.3.empty, side.3.single),
                                (want.3.empty, want.3.single),
                                "{live:?}"
                            );
                        }
                    }
                }
                Row::Unsorted => assert!(!sorted, "{live:?}"),
                Row::Overlapping => {
                    assert!(!apart || !sorted, "{live:?}");
                    refused += 1;
                }
            }
            // Sorted, the row is side by side exactly when the writer of
            // a target (the background filled, the row inside it) takes
            // it; one it refuses leaves the counts as they were.
            let mut sorted_act = act;
            sort(&mut sorted_act[..n]);
            let row = side_by_side(&sorted_act[..n], W as i32);
            let mut target = Spans {
                size: (W, H),
                got: std::vec::Vec::new(),
            };
            let mut runs = pending_runs();
            let mut out = ToTarget::new(&mut target, Some(Rgb888::new(1, 2, 3)), &mut runs);
            out.start(0);
            let mut stats = VisibleStats::default();
            let took = out.side_by_side(&sorted_act[..n], W as i32, &mut stats);
            assert_eq!(took, Some(row == Row::SideBySide), "{live:?}");
            if took == Some(false) {
                assert_eq!((out.runs, stats), (0, VisibleStats::default()), "{live:?}");
            }
        }
        assert!(accepted > 1000 && refused > 200, "{accepted} {refused}");
    }

    #[test]
    fn entries_set_up_their_edges_as_edge_new_does() {
        // The record's sides over every run of rows they cross: the set-up
        // without tests gives `Edge::new`'s stepper, at the extremes of
        // the clip's range too.
        use crate::fixed::Vertex;
        let mut rng = Rng(0x0e0e_5e75);
        for k in 0..200_000 {
            let c = |rng: &mut Rng| {
                if k % 4 == 0 {
                    rng.below(65_536) - 32_768
                } else {
                    rng.below(16 * 600) - 16 * 40
                }
            };
            let (x0, mut y0, x1, mut y1) = (c(&mut rng), c(&mut rng), c(&mut rng), c(&mut rng));
            if y0 > y1 {
                core::mem::swap(&mut y0, &mut y1);
            }
            let (a, b) = (
                Vertex::from_bits(x0 as i16, y0 as i16),
                Vertex::from_bits(x1 as i16, y1 as i16),
            );
            if y0 == y1 {
                assert_eq!(Edge::on_rows(x0, y0, x1, y1, (0, 1)), Edge::EMPTY);
                continue;
            }
            let Some(all) = Edge::new(a, b, (i32::MIN / 32, i32::MAX / 32)) else {
                continue;
            };
            let (t, e) = (all.top(), all.end());
            let top = t + rng.below((e - t) as u32);
            let end = top + 1 + rng.below((e - top) as u32);
            assert_eq!(
                Some(Edge::on_rows(x0, y0, x1, y1, (top, end))),
                Edge::new(a, b, (top, end)),
                "{x0} {y0} {x1} {y1} {top}..{end}"
            );
        }
    }

    #[test]
    fn equal_depths_go_to_the_earlier_polygon() {
        // Two coplanar triangles overlapping, and a third at the same
        // constant depth: the earliest wins everywhere they overlap.
        let a = [v(0, 0, 800), v(640, 0, 800), v(0, 600, 800)];
        let b = [v(100, 40, 800), v(700, 300, 800), v(60, 620, 800)];
        let c = [v(-50, -50, 800), v(760, 10, 800), v(300, 640, 800)];
        for mode in [Resolve::Bisect, Resolve::Crossing] {
            run_scene(&[a, b, c], mode);
            run_scene(&[c, b, a], mode);
        }
    }

    #[test]
    fn steep_and_extreme_depths() {
        let mut rng = Rng(0x0bad_f00d);
        for _ in 0..60 {
            // Depths at the ends of the format, and nearly edge-on faces.
            let mut polys: [[Vertex3; 3]; 4] =
                core::array::from_fn(|_| random_tri(&mut rng, (-32768, 32767)));
            polys[0][1] = v(
                polys[0][0].x.units() + 3,
                polys[0][0].y.units() + 700,
                32767,
            );
            polys[1] = [v(16, 16, -32768), v(700, 40, -32768), v(30, 600, -32767)];
            for mode in [Resolve::Bisect, Resolve::Crossing] {
                run_scene(&polys, mode);
            }
        }
    }

    /// The size the sorts' moves are written for (`move_hot`, `SORT_REACH`).
    #[test]
    fn a_sorted_element_is_24_bytes() {
        assert_eq!(core::mem::size_of::<Hot>(), 24);
    }

    #[test]
    fn sort_falls_back_to_a_heap_and_moves_only_the_sorted_array() {
        let mut rng = Rng(0x5eed_1234);
        let sorts: [fn(&mut [Active]); 3] = [sort, sort_budget, sort_entered];
        for n in [0usize, 1, 2, 3, 7, 40, 300] {
            for (kind, sort) in (0..15).map(|p| (p / 3, sorts[p % 3])) {
                let mut live = [Active::EMPTY; 300];
                let live = &mut live[..n];
                for (p, a) in live.iter_mut().enumerate() {
                    a.hot.l = match kind {
                        0 => p as i32,
                        1 => (n - p) as i32,
                        2 => rng.below(8),
                        // Sorted but for a few from the end (those that
                        // gained their pixels).
                        3 if p % 37 == 5 => rng.below(1000),
                        3 => p as i32 * 3,
                        _ => rng.below(1000),
                    };
                    // Every field told apart, so that a move that
                    // dropped one (`move_hot`) is found.
                    let q = p as i32;
                    (a.hot.r, a.hot.z, a.hot.zx) = (q + 1, -q, 3 * q);
                    (a.hot.color, a.hot.face) = (q as u32 ^ 0xa5a5, p as u16 + 7);
                    a.hot.slot = p as u16;
                    a.entry.x0 = p as u16;
                }
                let mut before = [Active::EMPTY.hot; 300];
                for (b, a) in before.iter_mut().zip(live.iter()) {
                    *b = a.hot;
                }
                sort(live);
                assert!(live.windows(2).all(|w| w[0].hot.l <= w[1].hot.l));
                // Each element once, unchanged.
                let mut seen = [false; 300];
                for a in live.iter() {
                    assert!(!seen[a.hot.slot as usize]);
                    seen[a.hot.slot as usize] = true;
                    assert_eq!(before[a.hot.slot as usize], a.hot);
                }
                // The stepping states stay at their slots.
                assert!(live
                    .iter()
                    .enumerate()
                    .all(|(p, a)| a.entry.x0 as usize == p));
            }
        }
    }

    #[test]
    fn too_small_an_active_list_is_found_before_resolving() {
        let polys = [
            [v(0, 0, 1), v(700, 0, 1), v(0, 600, 1)],
            [v(10, 10, 2), v(700, 10, 2), v(10, 600, 2)],
        ];
        let (mut traps, mut faces, mut segs, mut rows, mut edges) = (
            [Trapezoid::EMPTY; 8],
            [Face::EMPTY; 4],
            [Segment::EMPTY; 1],
            [0u16; H as usize],
            [EdgeSlot::EMPTY; 3],
        );
        let mut store = TrapezoidStore::new(
            StoreMemory {
                trapezoids: &mut traps,
                faces: &mut faces,
                segments: &mut segs,
                rows: &mut rows,
                edges: &mut edges,
            },
            W,
            H,
        )
        .unwrap();
        for p in polys {
            store
                .add_polygon(0, p, Rgb888::new(1, 2, 3), &ClipRect::full(W, H))
                .unwrap();
        }
        let mut active = [Active::EMPTY; 1];
        let mut runs = [Run::EMPTY; W as usize];
        let mut ws = Workspace::new(&mut active, &mut runs);
        assert_eq!(ws.check(&store), Err(VisibleError::Active { capacity: 1 }));
        let r = ws.resolve(&store, Resolve::Bisect, |_, _| Ok::<(), ()>(()));
        assert_eq!(r, Err(VisibleError::Active { capacity: 1 }));
        let mut runs = [Run::EMPTY; 4];
        let mut active = [Active::EMPTY; 2];
        assert_eq!(
            Workspace::new(&mut active, &mut runs).check(&store),
            Err(VisibleError::Runs { capacity: 4 })
        );
    }

    /// `Workspace::check` finds the most trapezoids live on one row, by
    /// counting ends row by row when the runs hold the store's rows (a
    /// frame as wide as it is high, or wider) and by its heap when they
    /// do not (a narrower one): the most found by brute force either way.
    #[test]
    fn check_counts_the_most_on_a_row_both_ways() {
        let mut rng = Rng(0x0c0f_fee5);
        for _ in 0..200 {
            let n = 1 + rng.below(8) as usize;
            let polys: [[Vertex3; 3]; 8] =
                core::array::from_fn(|_| random_tri(&mut rng, (-2000, 2000)));
            let polys = &polys[..n];
            for w in [H - 1, H, H + 1] {
                let mut mem = Pools::new(64, H);
                let store = mem.store(polys, w, H);
                let most = (0..H as i32)
                    .map(|y| {
                        (0..store.len() as u16)
                            .filter_map(|t| store.trapezoid(t))
                            .filter(|t| t.top() <= y && y < t.end())
                            .count() as u32
                    })
                    .max()
                    .unwrap_or(0);
                let mut active = [Active::EMPTY; 64];
                let mut runs = [Run::EMPTY; H as usize + 1];
                let mut ws = Workspace::new(&mut active, &mut runs[..w as usize]);
                assert_eq!(ws.check(&store), Ok(most), "{w} × {H}: {polys:?}");
            }
        }
    }

    /// The active list of `sweep` stepped over rows `y..y + n` one by one
    /// (as drawn rows step it, nothing resolved): the reference for
    /// [`jump`].
    fn step_rows(sweep: &mut Sweep, act: &mut [Active], store: &TrapezoidStore<'_>, n: u16) {
        let (mut k, mut nf) = (sweep.k, sweep.nf);
        let end = sweep.y.saturating_add(n).min(store.height());
        for y in sweep.y..end {
            let mut fresh = Fresh::EMPTY;
            (k, nf) = step_live(act, k, nf, y as i32, store, &mut fresh);
            let mut placed = fresh.placed;
            let mut t = store.row_head(y as usize);
            while let Some(tr) = store.trapezoid(t) {
                let mut here = continues(store, t, tr);
                if !here {
                    here = placed & 1 != 0;
                    placed >>= 1;
                }
                if !here {
                    nf -= 1;
                    let slot = act[nf].free;
                    act[slot as usize].entry = Entry::from(tr, store);
                    act[slot as usize].entry.trap = t;
                    act[k].hot = act[slot as usize].entry.hot(slot);
                    k += 1;
                }
                t = tr.next_row;
            }
        }
        (sweep.y, sweep.k, sweep.nf) = (end.max(sweep.y), k, nf);
    }

    /// A triangle's lower trapezoid takes its upper one's slot and place
    /// ([`continuation`]), and a triangle that starts at the corner where
    /// another ended takes that one's ([`Fresh::join`]): of two triangles
    /// meeting at a corner, four trapezoids, only the first enters at the
    /// end of the live array; the list holds one trapezoid on every row,
    /// in the same slot, and the rows drawn are the exact picture's.
    #[test]
    fn continuing_trapezoids_take_the_ended_ones_places() {
        let polys = [
            [v(160, 32, 40), v(32, 160, 40), v(320, 320, 40)],
            [v(320, 320, 60), v(560, 500, 60), v(160, 560, 60)],
        ];
        let mut mem = Pools::new(64, H);
        let store = mem.store(&polys, W, H);
        assert_eq!(store.len(), 4);
        let mut active = [Active::EMPTY; 8];
        let mut runs = [Run::EMPTY; W as usize];
        let mut ws = Workspace::new(&mut active, &mut runs);
        let mut sweep = Sweep::new(&mut ws, Resolve::Crossing);
        let act = &mut ws.active[..sweep.cap];
        let (mut k, mut nf) = (sweep.k, sweep.nf);
        let (mut entered, mut placed_in) = (0, 0);
        let mut slots = std::vec::Vec::new();
        for y in 0..H {
            let mut fresh = Fresh::EMPTY;
            (k, nf) = step_live(act, k, nf, y as i32, &store, &mut fresh);
            let mut placed = fresh.placed;
            let mut t = store.row_head(y as usize);
            while let Some(tr) = store.trapezoid(t) {
                let mut here = continues(&store, t, tr);
                if !here {
                    here = placed & 1 != 0;
                    placed >>= 1;
                }
                if here {
                    placed_in += 1;
                } else {
                    entered += 1;
                    nf -= 1;
                    let slot = act[nf].free;
                    act[slot as usize].entry = Entry::from(tr, &store);
                    act[slot as usize].entry.trap = t;
                    act[k].hot = act[slot as usize].entry.hot(slot);
                    k += 1;
                }
                t = tr.next_row;
            }
            if (2..35).contains(&y) {
                assert_eq!(k, 1, "row {y}");
                slots.push(act[0].hot.slot);
            }
        }
        assert_eq!((entered, placed_in), (1, 3));
        assert!(slots.iter().all(|&s| s == slots[0]));
        sweep = Sweep::new(&mut ws, Resolve::Crossing);
        let want = brute(&polys, &store);
        let poly_of = |f: u16| store.face(f).unwrap().key() as u16;
        let check = |y: u16, runs: &[Run]| {
            assert_row(y, runs, &want, poly_of, &"two triangles at a corner");
            Ok::<(), ()>(())
        };
        let mut row_runs = [Run::EMPTY; W as usize];
        let sink = ToSink {
            out: RunWriter::new(&mut row_runs),
            y: 0,
            sink: &check,
        };
        sweep.rows(ws.active, &store, H, sink).unwrap();
        assert_eq!(sweep.stats().trapezoids, 4);
    }

    /// Jumping over rows leaves the same live trapezoids, with the same
    /// edges, depth and pixels, as stepping over them row by row (the
    /// order may differ where a trapezoid took the place of the one it
    /// continues: the next row's sort orders both): skips of every length
    /// from every row, over scenes whose triangles reach past the frame
    /// on every side; then the rows drawn after a long skip are the exact
    /// picture's.
    #[test]
    fn jump_equals_stepping() {
        let mut rng = Rng(0x5eed_0bad);
        for round in 0..60 {
            let n = 1 + rng.below(8) as usize;
            let polys: [[Vertex3; 3]; 8] =
                core::array::from_fn(|_| random_tri(&mut rng, (-2000, 2000)));
            let polys = &polys[..n];
            let mut mem = Pools::new(64, H);
            let store = mem.store(polys, W, H);
            let (mut a1, mut a2) = ([Active::EMPTY; 64], [Active::EMPTY; 64]);
            let (mut r1, mut r2) = ([Run::EMPTY; W as usize], [Run::EMPTY; W as usize]);
            let mut ws = Workspace::new(&mut a1, &mut r1);
            let mut ws_ref = Workspace::new(&mut a2, &mut r2);
            // From row `from`, skip `len` rows both ways, compare.
            let from = rng.below(H as u32) as u16;
            for len in 1..=H + 1 - from {
                let mut jumped = Sweep::new(&mut ws, Resolve::Crossing);
                let mut stepped = Sweep::new(&mut ws_ref, Resolve::Crossing);
                step_rows(&mut jumped, ws.active, &store, from);
                step_rows(&mut stepped, ws_ref.active, &store, from);
                jumped.skip(&store, &mut ws, len).unwrap();
                step_rows(&mut stepped, ws_ref.active, &store, len);
                assert_eq!(
                    (jumped.y, jumped.k, jumped.nf),
                    (stepped.y, stepped.k, stepped.nf),
                    "round {round}, rows {from}..+{len}"
                );
                // Each list by its trapezoids' indices in the store.
                let by_trap = |act: &[Active], k: usize| {
                    let mut v: std::vec::Vec<(Entry, Hot)> = (0..k)
                        .map(|p| {
                            let h = act[p].hot;
                            (act[h.slot as usize].entry, Hot { slot: 0, ..h })
                        })
                        .collect();
                    v.sort_by_key(|(e, _)| e.trap);
                    v
                };
                let (got, want) = (
                    by_trap(ws.active, jumped.k),
                    by_trap(ws_ref.active, stepped.k),
                );
                // A side moved on from the trapezoid it continues keeps the
                // rounding of its first row: its pixels are compared, row
                // by row to its end, not its bits.
                let canon = |(e, h): &(Entry, Hot)| {
                    let side = |s: &Edge| {
                        let mut s = *s;
                        let pixels: std::vec::Vec<_> = (s.top()..s.end())
                            .map(|_| {
                                let p = (s.pixel_now(), s.units());
                                s.step();
                                p
                            })
                            .collect();
                        (s.top(), s.end(), s.step_units(), pixels)
                    };
                    let bare = Entry {
                        left: Edge::EMPTY,
                        right: Edge::EMPTY,
                        ..*e
                    };
                    (bare, *h, side(&e.left), side(&e.right))
                };
                for (p, (g, w)) in got.iter().zip(&want).enumerate() {
                    assert_eq!(
                        canon(g),
                        canon(w),
                        "round {round}, rows {from}..+{len}, element {p}"
                    );
                }
            }
            // Rows drawn after skipping from row 0 to any row are the
            // exact picture's.
            let want = brute(polys, &store);
            let poly_of = |f: u16| store.face(f).unwrap().key() as u16;
            for from in [1, 7, H / 2, H - 1] {
                let mut sweep = Sweep::new(&mut ws, Resolve::Crossing);
                sweep.skip(&store, &mut ws, from).unwrap();
                let check = |y: u16, runs: &[Run]| {
                    assert_row(y, runs, &want, poly_of, &(round, from));
                    Ok::<(), ()>(())
                };
                let mut band_runs = [Run::EMPTY; W as usize];
                let sink = ToSink {
                    out: RunWriter::new(&mut band_runs),
                    y: 0,
                    sink: &check,
                };
                sweep.rows(ws.active, &store, H, sink).unwrap();
                assert_eq!(sweep.next_row(), H);
            }
        }
    }

    /// The crossing point's quotient in 32 bits where it fits equals the
    /// 64-bit floor division, on both sides of 2³².
    #[test]
    fn crossing_point_divides_as_in_64_bits() {
        let want = |a: &Cover, b: &Cover, s: i32, t: i32| {
            let d0 = a.z_at(s) as i64 - b.z_at(s) as i64;
            let d1 = a.z_at(t - 1) as i64 - b.z_at(t - 1) as i64;
            let (run, rise) = ((t - 1 - s) as i64, d1 - d0);
            let k = if rise > 0 && d0 <= 0 {
                s as i64 + (-d0 * run).div_euclid(rise) + 1
            } else {
                (s + (t - s) / 2) as i64
            };
            k.clamp(s as i64 + 1, t as i64 - 1) as i32
        };
        let mut rng = Rng(0xc0ff_ee11);
        let cover = |z: i32, zx: i32| Cover {
            z,
            zx,
            ..Cover::EMPTY
        };
        for round in 0..20_000 {
            let (s, len) = (rng.below(4000), 2 + rng.below(4094));
            let t = s + len;
            // Depths near ±2²⁹ and slopes from tiny to steep, so that
            // −d0·run and the rise fall on both sides of 2³².
            let zb = rng.below(1 << 30) - (1 << 29);
            let za = zb - rng.below(1 << 30).min((1 << 29) + zb);
            let slope = 1 << rng.below(20);
            let a = cover(za, slope + rng.below(slope as u32));
            let b = cover(zb, -rng.below(slope as u32));
            assert_eq!(
                crossing_point(&a, &b, s, t),
                want(&a, &b, s, t),
                "round {round}: {a:?} {b:?} {s}..{t}"
            );
        }
    }
}
