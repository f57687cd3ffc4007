//! Painting far to near ([`Resolve::Paint`]): the rows written into a
//! target that keeps its pixels (a frame buffer), every trapezoid's
//! pixels in full, farther ones first, so that nearer ones overwrite
//! them. Depths are compared only between trapezoids whose ranges of
//! depth overlap; the rest of the order is settled once, when a
//! trapezoid enters.
//!
//! # The order and the pairs
//!
//! A trapezoid that enters the active list gets the range of its
//! fixed-point depth `Z̃` over the rectangle of its rows and columns
//! (exact in `i64`, then saturated to `i32`, which keeps it a range of
//! every pixel it covers: those are within `±2³⁰`; for a plane nearly
//! edge-on, whose slopes wrap in `i32`, the whole of `±2³⁰`). The live
//! list is kept by the least depth of each range, greatest first
//! (farthest first); at equal keys, in the order they entered. As it
//! enters, it is tested against the live trapezoids whose ranges may
//! overlap its own (the order, and the widest range seen in the frame,
//! bound the scan) and whose columns overlap its own. The one later in
//! the order is strictly in front of the earlier on every pixel they
//! share, exactly (see `trapezoid`'s module docs), when its fixed-point
//! depth is below the earlier's by at least [`DEPTH_TOLERANCE`]: over
//! the whole of both ranges; or at the least corner of the rectangle of
//! their common rows and columns (the difference is affine); or on every
//! common row within both trapezoids' edges, each edge moved as far as
//! it can go ([`in_front_edges`]). Otherwise the pair is a *conflict*,
//! recorded on the later one's list. Faces parallel to the screen at
//! different depths never conflict.
//!
//! # A row
//!
//! The live trapezoids are visited in order, each stepped to the row and
//! its pixels `l..r` written, but for the parts where a live trapezoid
//! on its conflict list is in front: for each whose `l..r` overlaps its
//! own, the depths at both ends of the overlap are compared (in fixed
//! point, exactly where they are too close), and where the planes cross
//! on it, the crossing pixel is found by one division and checked on both
//! sides, as the sweep splits an intersecting span.
//!
//! # Why it is exact
//!
//! Let `N` be the nearest trapezoid at a pixel (the nearer plane, at equal
//! depth the lower key, as everywhere). `N` writes it: nothing on its list
//! is in front of it there. A trapezoid `X` after `N` in the order that
//! covers the pixel is not strictly in front of `N` everywhere they meet
//! (it is farther here), so their pair is a conflict, `N` is on `X`'s list,
//! and `X` leaves the pixel to `N`. Those before `N` are overwritten. A
//! record whose partner has ended, its slot taken by another trapezoid
//! since, leaves a pixel only to a live trapezoid in front there: never
//! to the wrong one, since that pixel is not the trapezoid's to show.
//!
//! # Memory
//!
//! The workspace's active slots, as for the sweep, and its run buffer for
//! the conflict records (one run each: the partner's slot and the next
//! record; a slot's list is freed when the slot is taken again). When a
//! frame needs more records than the buffer holds, or a trapezoid leaves
//! more than [`PARTS`] parts of a row to partners, the frame is drawn
//! again by the sweep, to the same pixels.
//!
//! # Band by band
//!
//! The painter keeps where it stands between calls ([`Painter`]), so a
//! [`Sweep`](super::Sweep) in [`Resolve::Paint`] paints a band at a time
//! into a band buffer (which keeps its pixels for the band's rows), and
//! jumps over rows it is not asked to draw: the live trapezoids' edges
//! move down at once, and those that start in the rows enter on the row
//! after them. Out of records or parts at row `y`, it goes on from row `y`
//! as the sweep with crossing points: the rows before stay as painted,
//! and the pixels painting wrote on row `y` are all covered by
//! trapezoids, so the sweep writes each again.
//!
//! # Cost
//!
//! Per row, one step and one span written a live trapezoid, plus two
//! depth compares for each conflict whose trapezoids overlap on the row;
//! per frame, one test per pair of trapezoids live together. Pixels are
//! written as often as trapezoids cover them (the depth complexity), so
//! it suits targets where a pixel is cheap to write: memory, not a
//! display's window.

use super::{
    batch_of, capacity, crossing_point, exact_nearer, pending_runs, step_edge, Active, Counts,
    Cover, Entry, Resolve, ToTarget, VisibleError, VisibleStats, Workspace,
};
use crate::color::ListColor;
use crate::port::SpanTarget;
use crate::raster::edge::Edge;
use crate::visible::rle::Run;
use crate::visible::store::{Face, TrapezoidStore};
use crate::visible::trapezoid::{Depth, Trapezoid, DEPTH_TOLERANCE, NONE};

/// "No record", "no row".
const NIL: u16 = NONE;

/// Most parts of one trapezoid's pixels on a row that it leaves to
/// conflict partners; a row that needs more is drawn by the sweep.
const PARTS: usize = 8;

// What the slots hold besides their edges' stepping state (`entry`,
// whose `z` is the depth at pixel `(0, 0)`, wrapped: no depth is stepped,
// see [`z_row`]):
// - by slot, `hot.l`, `hot.r`: its pixels on row `hot.slot` (`l ≥ r`:
//   none), `hot.z`: the head of its conflict list (`NIL`: none),
//   `hot.zx`: the high word of its depth at pixel `(0, 0)`, unwrapped
//   (`WRAPS` for a plane whose slopes wrap),
//   `cover.z`: its columns' bounds `lo | hi << 16`, `cover.r` and
//   `cover.zx`: the least and greatest depth of its range (the least is
//   its key in the order);
// - by place, `act[..k].cover.p`: the live list, in order (slots);
// - `act[..nf].free`: the free slots, as for the sweep.

/// Resolves `store` by painting and writes it into `target`, as
/// [`draw`](super::draw) does. Not inlined, so that the sweep's `draw`
/// compiles as it does without it.
#[inline(never)]
pub(super) fn draw<T>(
    store: &TrapezoidStore<'_>,
    workspace: &mut Workspace<'_>,
    target: &mut T,
    background: Option<T::Color>,
) -> Result<(VisibleStats, Counts), VisibleError<T::Error>>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    workspace.check_runs(store)?;
    {
        let mut runs = pending_runs();
        let mut out = ToTarget::new(&mut *target, background, batch_of::<T>(&mut runs));
        let mut stats = VisibleStats {
            mode: Resolve::Paint,
            ..VisibleStats::default()
        };
        let mut painter = Painter::start(workspace.active);
        let painted = painter.rows(
            workspace.active,
            workspace.runs,
            store,
            store.height(),
            &mut out,
            &mut stats,
        )?;
        if painted.is_none() {
            return Ok((stats, out.counts));
        }
    }
    // Out of records or parts: the frame again by the sweep, to the same
    // pixels.
    super::draw(store, workspace, Resolve::Crossing, target, background)
}

/// The conflict records, one run each in the run buffer: the partner's
/// slot and the next record.
struct Pool<'r> {
    runs: &'r mut [Run],
    /// Records never used: `used..runs.len()`.
    used: usize,
    /// The free records, linked by `next`.
    free: u16,
}

impl Pool<'_> {
    #[inline(always)]
    fn get(&self, q: u16) -> (usize, u16) {
        let r = self
            .runs
            .get(q as usize)
            .copied()
            .unwrap_or(Run::new(0, NIL));
        (r.len() as usize, r.ink())
    }

    /// A record of `slot` ahead of `next`; `None` when none is left.
    #[inline]
    fn push(&mut self, slot: u16, next: u16) -> Option<u16> {
        let q = if self.free != NIL {
            let q = self.free;
            self.free = self.get(q).1;
            q
        } else if self.used < self.runs.len() {
            self.used += 1;
            (self.used - 1) as u16
        } else {
            return None;
        };
        self.runs[q as usize] = Run::new(slot, next);
        Some(q)
    }

    /// Takes record `q` (after `prev`, `NIL` for the head; `next` after
    /// it) out of slot `slot`'s list, and frees it.
    #[inline(never)]
    fn unlink(&mut self, act: &mut [Active], slot: usize, prev: u16, q: u16, next: u16) {
        match self.runs.get_mut(prev as usize) {
            Some(p) => *p = Run::new(p.len(), next),
            None => act[slot].hot.z = next as i32,
        }
        if let Some(r) = self.runs.get_mut(q as usize) {
            *r = Run::new(r.len(), self.free);
            self.free = q;
        }
    }

    /// Frees the list from `q`.
    #[inline]
    fn release(&mut self, mut q: u16) {
        while let Some(r) = self.runs.get_mut(q as usize) {
            let next = r.ink();
            *r = Run::new(r.len(), self.free);
            self.free = q;
            q = next;
        }
    }
}

/// A frame being painted, top to bottom: where it stands between calls
/// (the live list and free slots in the workspace's active list, the
/// conflict records in its run buffer), so that it can be painted a band
/// at a time ([`Sweep`](super::Sweep) in [`Resolve::Paint`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Painter {
    /// The next row.
    pub(super) y: u16,
    /// `act[..k].cover.p`: the live trapezoids, in order.
    k: usize,
    /// `act[..nf].free`: the free slots.
    nf: usize,
    /// The records never used, `used..`, and the free ones' list.
    used: usize,
    free: u16,
    /// The widest range of depth of a trapezoid entered so far.
    spread: i64,
}

impl Painter {
    /// A frame at row 0, with the slots of `active` (at most 65535) free.
    pub(super) fn start(active: &mut [Active]) -> Painter {
        let cap = capacity(active);
        for (i, a) in active[..cap].iter_mut().enumerate() {
            a.free = i as u16;
            a.hot.slot = NIL;
            a.hot.z = NIL as i32;
        }
        Painter {
            y: 0,
            k: 0,
            nf: cap,
            used: 0,
            free: NIL,
            spread: 0,
        }
    }

    /// Keeps where the frame stands: row `y` next, `k` live trapezoids,
    /// `nf` free slots, the records as `pool` leaves them, `spread`.
    #[inline(always)]
    fn keep(&mut self, y: u16, (k, nf): (usize, usize), pool: &Pool<'_>, spread: i64) {
        *self = Painter {
            y,
            k,
            nf,
            used: pool.used,
            free: pool.free,
            spread,
        };
    }

    /// Paints the next `rows` rows of `store` (cut at its height) into
    /// `out`, with the slots of `active` it started with and the records
    /// in `runs`. `Ok(None)` when they are drawn; `Ok(Some(y))` when the
    /// conflict records or a trapezoid's [`PARTS`] ran out at row `y`:
    /// rows before `y` are drawn, row `y` in part (pixels its trapezoids
    /// cover, none of the background), and the painter cannot go on.
    /// Out of line, so that the band pass it is called from compiles the
    /// sweep as it does without it.
    #[inline(never)]
    pub(super) fn rows<T>(
        &mut self,
        active: &mut [Active],
        runs: &mut [Run],
        store: &TrapezoidStore<'_>,
        rows: u16,
        out: &mut ToTarget<'_, T>,
        stats: &mut VisibleStats,
    ) -> Result<Option<u16>, VisibleError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        let width = store.width() as u32;
        let cap = capacity(active);
        let act = &mut active[..cap];
        let (mut k, mut nf) = (self.k.min(cap), self.nf.min(cap));
        let records = runs.len().min(NIL as usize);
        let mut pool = Pool {
            runs: &mut runs[..records],
            used: self.used,
            free: self.free,
        };
        // The parts of a row left to partners (see `draw_conflicted`).
        let mut parts = [(0i32, 0i32); PARTS];
        let mut spread = self.spread;
        let end = self.y.saturating_add(rows).min(store.height());
        for y in self.y..end {
            let yi = y as i32;
            // Enter the trapezoids whose top is this row, each in its place
            // by key and tested against the live ones.
            let mut t = store.row_head(y as usize);
            while let Some(tr) = store.trapezoid(t) {
                t = tr.next_row;
                if nf == 0 || k >= act.len() {
                    return Err(VisibleError::Active { capacity: cap });
                }
                nf -= 1;
                let slot = act[nf].free as usize;
                if !enter(act, &mut pool, store, tr, (slot, k, y), &mut spread, false) {
                    return Ok(Some(y));
                }
                stats.trapezoids += 1;
                k += 1;
            }
            stats.max_active = stats.max_active.max(k as u32);
            out.paint_row(y);
            out.fill_background(width);
            // Write, far to near, each stepped to the row as it comes (the
            // ones that entered on it are there already); those that end on
            // the row leave the list for the free stack after it.
            let next = yi + 1;
            let mut w = 0;
            // (`k` is within the slots: said again for the bounds checks.)
            for p in 0..k.min(act.len()) {
                let slot = act[p].cover.p as usize;
                let a = &mut act[slot];
                if a.hot.slot != y {
                    step_one(a, y);
                }
                let (l, r, color, head) = (a.hot.l, a.hot.r, a.entry.color, a.hot.z as u16);
                if a.entry.left.end() <= next {
                    act[nf].free = slot as u16;
                    nf += 1;
                } else {
                    if w != p {
                        act[w].cover.p = slot as u16;
                    }
                    w += 1;
                }
                if l >= r {
                    continue;
                }
                if head == NIL {
                    out.fill(l, r, color);
                    continue;
                }
                if !draw_conflicted(
                    act,
                    store,
                    &mut pool,
                    &mut parts,
                    slot,
                    (l, r),
                    y,
                    out,
                    stats,
                ) {
                    return Ok(Some(y));
                }
            }
            k = w;
            if let Some(e) = out.error.take() {
                // The row is done; the target failed.
                self.keep(y + 1, (k, nf), &pool, spread);
                return Err(VisibleError::Sink(e));
            }
        }
        stats.rows += (end - self.y.min(end)) as u32;
        self.keep(end.max(self.y), (k, nf), &pool, spread);
        Ok(None)
    }

    /// Moves over the next `rows` rows of `store` (cut at its height)
    /// without painting them, at once: the live trapezoids that end in
    /// them leave; the others' edges move down by [`Edge::advance`], one
    /// jump each; those that start in them and last past them enter on
    /// the row after, tested against the live ones for the rows left (a
    /// trapezoid that starts and ends in them is never entered).
    /// `Ok(Some(y))` when the conflict records ran out as they entered:
    /// the painter cannot go on from row `y`, the row after.
    ///
    /// [`Edge::advance`]: crate::raster::edge::Edge::advance
    pub(super) fn skip(
        &mut self,
        active: &mut [Active],
        runs: &mut [Run],
        store: &TrapezoidStore<'_>,
        rows: u16,
        stats: &mut VisibleStats,
    ) -> Result<Option<u16>, VisibleError<core::convert::Infallible>> {
        let cap = capacity(active);
        let act = &mut active[..cap];
        let (y0, y1) = (self.y, self.y.saturating_add(rows).min(store.height()));
        if y1 <= y0 {
            return Ok(None);
        }
        let (mut k, mut nf) = (self.k.min(cap), self.nf.min(cap));
        // The live ones: those that end in the rows leave; the others go
        // down to the row before `y1`, as the pass of that row leaves
        // them (each from the row it is on: a trapezoid that entered by
        // an earlier jump is on that jump's last row).
        let mut w = 0;
        for p in 0..k {
            let slot = act[p].cover.p as usize;
            let a = &mut act[slot];
            if a.entry.left.end() <= y1 as i32 {
                act[nf].free = slot as u16;
                nf += 1;
                continue;
            }
            let n = (y1 as i32 - 1 - a.hot.slot as i32).max(0) as u32;
            a.entry.left.advance(n);
            a.entry.right.advance(n);
            a.hot.slot = y1 - 1;
            act[w].cover.p = slot as u16;
            w += 1;
        }
        k = w;
        let records = runs.len().min(NIL as usize);
        let mut pool = Pool {
            runs: &mut runs[..records],
            used: self.used,
            free: self.free,
        };
        let mut spread = self.spread;
        for y in y0..y1 {
            let mut t = store.row_head(y as usize);
            while let Some(tr) = store.trapezoid(t) {
                t = tr.next_row;
                if tr.end() <= y1 as i32 || y1 >= store.height() {
                    continue;
                }
                if nf == 0 || k >= act.len() {
                    return Err(VisibleError::Active { capacity: cap });
                }
                nf -= 1;
                let slot = act[nf].free as usize;
                if !enter(act, &mut pool, store, tr, (slot, k, y1), &mut spread, true) {
                    return Ok(Some(y1));
                }
                k += 1;
                stats.trapezoids += 1;
            }
        }
        stats.max_active = stats.max_active.max(k as u32);
        self.keep(y1, (k, nf), &pool, spread);
        Ok(None)
    }
}

/// Enters trapezoid `tr` into slot `slot` on row `y`, its top (or, when
/// `jumped`, a later row it reaches: its edges moved down to it at once):
/// its stepping state, its place among the `k` live ones by key, and its
/// pairs with those whose ranges of depth may overlap its own (`spread`:
/// the widest range of depth entered so far). `false` when out of
/// records. Inlined into both its callers: painting rows and jumping.
#[inline(always)]
fn enter(
    act: &mut [Active],
    pool: &mut Pool<'_>,
    store: &TrapezoidStore<'_>,
    tr: &Trapezoid,
    (slot, k, y): (usize, usize, u16),
    spread: &mut i64,
    jumped: bool,
) -> bool {
    let yi = y as i32;
    pool.release(act[slot].hot.z as u16);
    let (lo, hi) = tr.column_bounds();
    // The face's depth, worked out here if it was left for later.
    let face = store.face(tr.face);
    let (d, color) = face.map_or((Depth::default(), 0), |f| {
        (f.depth(), crate::color::list_word(f.color_bits()))
    });
    let (zu, zmin, zmax) = depth_range(face, d, tr, (lo, hi));
    {
        // Made in its slot, not copied there.
        let a = &mut act[slot];
        a.entry = Entry::with(tr, d, color);
        let e = &mut a.entry;
        // Its depth at pixel (0, 0), from that on its top row.
        let top = if jumped { tr.top() } else { yi };
        e.z = e.z.wrapping_sub(e.zy.wrapping_mul(top));
        if jumped {
            // Down from its top to the row, at once.
            let n = (yi - tr.top()).max(0) as u32;
            e.left.advance(n);
            e.right.advance(n);
        }
        let (l, r) = row_pixels(e);
        (a.hot.l, a.hot.r, a.hot.slot) = (l, r, y);
        (a.hot.z, a.hot.zx) = (NIL as i32, zu.map_or(WRAPS, |z| (z >> 32) as i32));
    }
    // Its place: after every live one of a key at least its own.
    let (mut at, mut past) = (0, k);
    while at < past {
        let mid = (at + past) / 2;
        if act[act[mid].cover.p as usize].cover.r >= zmin {
            at = mid + 1;
        } else {
            past = mid;
        }
    }
    let last = tr.end() - 1;
    // The earlier ones, keys at least its own, nearest key first:
    // past one whose least depth is beyond its greatest, so are
    // all before.
    *spread = (*spread).max(zmax as i64 - zmin as i64);
    let me = (slot, (lo, hi), (zmin, zmax), (yi, last));
    let past = zmax.saturating_add(DEPTH_TOLERANCE as i32);
    // Most pairs are apart in columns: tested first.
    let apart = |act: &[Active], u: usize| {
        let cz = act[u].cover.z;
        lo >= cz >> 16 || hi <= cz & 0xffff
    };
    for p in (0..at).rev() {
        let u = act[p].cover.p as usize;
        if act[u].cover.r > past {
            break;
        }
        if apart(act, u) {
            continue;
        }
        if !pair(act, pool, me, u, true) {
            return false;
        }
    }
    // The later ones, keys below its own, each tested as it moves a
    // place up to make room: a greatest depth is at most the key and the
    // widest range seen, so those with keys below `below` need no test.
    // (Saturated: a bound below `i32` stops nothing.)
    let below = (zmin as i64 - DEPTH_TOLERANCE - *spread).max(i32::MIN as i64) as i32;
    let mut p = k;
    while p > at {
        let u = act[p - 1].cover.p as usize;
        act[p].cover.p = u as u16;
        p -= 1;
        if act[u].cover.r < below || apart(act, u) {
            continue;
        }
        if !pair(act, pool, me, u, false) {
            return false;
        }
    }
    let c = &mut act[slot].cover;
    (c.r, c.z, c.zx) = (zmin, lo | hi << 16, zmax);
    act[at].cover.p = slot as u16;
    true
}

/// Tests the entering trapezoid `slot` (columns `lo..hi`, depths
/// `zmin..=zmax`, rows `y..=last`) against the live one `u`, before it
/// in the order (`earlier`) or after, and records their pair on the
/// later one's list when it is a conflict. `false` when out of records.
#[inline(always)]
#[allow(clippy::type_complexity)]
fn pair(
    act: &mut [Active],
    pool: &mut Pool<'_>,
    (slot, (lo, hi), (zmin, zmax), (y, last)): (usize, (i32, i32), (i32, i32), (i32, i32)),
    u: usize,
    earlier: bool,
) -> bool {
    let c = act[u].cover;
    let (i0, i1) = (lo.max(c.z & 0xffff), hi.min(c.z >> 16) - 1);
    if i0 > i1 {
        return true;
    }
    // The later one (nearer in the order) and the earlier.
    let (later, first, later_max, first_min) = if earlier {
        (slot, u, zmax, c.r)
    } else {
        (u, slot, c.zx, zmin)
    };
    if later_max < first_min.saturating_sub(DEPTH_TOLERANCE as i32) {
        return true;
    }
    let j1 = last.min(act[u].entry.left.end() - 1);
    if j1 < y {
        return true;
    }
    // The live one to the row, as it will be when the row is written,
    // so that both are tested from the row they are on.
    if act[u].hot.slot != y as u16 {
        step_one(&mut act[u], y as u16);
    }
    if in_front(act, later, first, (i0, i1), (y, j1))
        || in_front_edges(act, later, first, (y, j1))
        || !may_meet(&act[slot].entry, &act[u].entry, j1 - y)
    {
        return true;
    }
    let head = act[later].hot.z as u16;
    let Some(q) = pool.push(first as u16, head) else {
        return false;
    };
    act[later].hot.z = q as i32;
    true
}

/// Writes slot `slot`'s pixels `l..r` on row `y` but for the parts where
/// a partner on its conflict list is in front, dropping the records of
/// partners that have ended. `false` when they are more than [`PARTS`]
/// (nothing written).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn draw_conflicted<T>(
    act: &mut [Active],
    store: &TrapezoidStore<'_>,
    pool: &mut Pool<'_>,
    parts: &mut [(i32, i32); PARTS],
    slot: usize,
    (l, r): (i32, i32),
    y: u16,
    out: &mut ToTarget<'_, T>,
    stats: &mut VisibleStats,
) -> bool
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    let mut n = 0;
    let (mut prev, mut q) = (NIL, act[slot].hot.z as u16);
    let yi = y as i32;
    let (zq, zxq) = (z_row(&act[slot].entry, yi), act[slot].entry.zx);
    let t = DEPTH_TOLERANCE as i32;
    // (`NIL` is past the records: the walk ends there.)
    while let Some(&rec) = pool.runs.get(q as usize) {
        let (u, next) = (rec.len() as usize, rec.ink());
        // A partner not stepped to the row has ended: a live one is
        // earlier in the order, so stepped already. Its slot may hold
        // another trapezoid since: one stepped to the row is live, and
        // leaving it pixels where it is in front is harmless.
        let au = match act.get(u) {
            Some(au) if au.hot.slot == y && u != slot => au,
            _ => {
                pool.unlink(act, slot, prev, q, next);
                q = next;
                continue;
            }
        };
        (prev, q) = (q, next);
        let (a, b) = (l.max(au.hot.l), r.min(au.hot.r));
        if a >= b {
            continue;
        }
        // The difference of the depths (this one's less the partner's)
        // at both ends of the overlap: it wraps back to the true one on
        // pixels both cover (see `trapezoid`).
        let dz = zq.wrapping_sub(z_row(&au.entry, yi));
        let dzx = zxq.wrapping_sub(au.entry.zx);
        let (da, db) = (
            dz.wrapping_add(dzx.wrapping_mul(a)),
            dz.wrapping_add(dzx.wrapping_mul(b - 1)),
        );
        let d = if da < -t && db < -t {
            continue;
        } else if da > t && db > t {
            (a, b)
        } else {
            left_to(act, store, slot, u, (a, b), y, stats)
        };
        if d.0 < d.1 {
            let Some(part) = parts.get_mut(n) else {
                return false;
            };
            *part = d;
            n += 1;
        }
    }
    // What is not left, left to right.
    let parts = &mut parts[..n];
    for i in 1..parts.len() {
        let mut j = i;
        while j > 0 && parts[j - 1].0 > parts[j].0 {
            parts.swap(j - 1, j);
            j -= 1;
        }
    }
    let color = act[slot].entry.color;
    let mut s = l;
    for &(a, b) in parts.iter() {
        if s < a {
            out.fill(s, a, color);
        }
        s = s.max(b);
    }
    if s < r {
        out.fill(s, r, color);
    }
    true
}

/// Steps the live trapezoid in `a` down to row `y` and keeps its pixels.
#[inline(always)]
fn step_one(a: &mut Active, y: u16) {
    let e = &mut a.entry;
    step_edge(&mut e.left);
    step_edge(&mut e.right);
    let (l, r) = row_pixels(e);
    (a.hot.l, a.hot.r, a.hot.slot) = (l, r, y);
}

/// The pixels `l..r` of the row `e` is stepped to, cut to its columns;
/// none when `l ≥ r` (as [`Entry::pixels`], without moving `l`).
#[inline(always)]
fn row_pixels(e: &Entry) -> (i32, i32) {
    (
        e.left.pixel_now().max(e.x0 as i32),
        e.right.pixel_now().min(e.x1 as i32),
    )
}

/// The wrapped fixed-point depth of `e`'s plane at column 0 of row `y`:
/// painting keeps the depth at pixel `(0, 0)` in `e.z` and steps none.
#[inline(always)]
fn z_row(e: &Entry, y: i32) -> i32 {
    e.z.wrapping_add(e.zy.wrapping_mul(y))
}

/// The least and greatest fixed-point depth of trapezoid `tr` (of face
/// `face`, whose depth is `d`, worked out) over the rectangle of its rows and columns `lo..hi`, saturated to `i32`: a
/// range of its depth at every pixel it covers; and its depth at pixel
/// `(0, 0)` unwrapped, `None` when its plane's slopes wrap (nearly
/// edge-on): its range is then that of every depth a polygon can have.
#[inline]
fn depth_range(
    face: Option<&Face>,
    d: Depth,
    tr: &Trapezoid,
    (lo, hi): (i32, i32),
) -> (Option<i64>, i32, i32) {
    let Some(f) = face.filter(|f| f.plane().slopes_fit()) else {
        return (None, -WIDEST, WIDEST);
    };
    let zu = unwrap(d.z, d.zx, d.zy, f.plane().origin_units());
    let (zx, zy) = (d.zx as i64, d.zy as i64);
    let (i0, i1) = (lo as i64, (hi - 1).max(lo) as i64);
    let (j0, j1) = (tr.top() as i64, (tr.end() - 1) as i64);
    let (xa, xb) = if zx >= 0 {
        (zx * i0, zx * i1)
    } else {
        (zx * i1, zx * i0)
    };
    let (ya, yb) = if zy >= 0 {
        (zy * j0, zy * j1)
    } else {
        (zy * j1, zy * j0)
    };
    let sat = |z: i64| z.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
    (Some(zu), sat(zu + xa + ya), sat(zu + xb + yb))
}

/// Beyond every fixed-point depth at a pixel a polygon covers (see
/// `trapezoid`: below `2²⁹ + 2²⁸ + 2¹²` in magnitude).
const WIDEST: i32 = 1 << 30;

/// The high word of an unwrapped depth for a plane whose slopes wrap: it
/// takes no part in the tests that unwrap ([`in_front`],
/// [`in_front_edges`]).
const WRAPS: i32 = i32::MIN;

/// The depth at pixel `(0, 0)` of slot `slot`'s plane, unwrapped: the
/// wrapped one in `entry.z` and the high word kept in `hot.zx`.
#[inline(always)]
fn z00(act: &[Active], slot: usize) -> i64 {
    let (e, c) = (&act[slot].entry, &act[slot].hot);
    (c.zx as i64) << 32 | e.z as u32 as i64
}

/// `true` when slot `x` is strictly in front of slot `y` on every pixel
/// centre of columns `i0..=i1` and rows `j0..=j1`: the depths of `y` greater by at least [`DEPTH_TOLERANCE`] in
/// fixed point at the corner where the difference is least (it is
/// affine).
#[inline]
fn in_front(
    act: &[Active],
    x: usize,
    y: usize,
    (i0, i1): (i32, i32),
    (j0, j1): (i32, i32),
) -> bool {
    if act[x].hot.zx == WRAPS || act[y].hot.zx == WRAPS {
        return false;
    }
    let (ex, ey) = (&act[x].entry, &act[y].entry);
    let gx = ey.zx as i64 - ex.zx as i64;
    let gy = ey.zy as i64 - ex.zy as i64;
    let g = z00(act, y) - z00(act, x)
        + gx * if gx >= 0 { i0 } else { i1 } as i64
        + gy * if gy >= 0 { j0 } else { j1 } as i64;
    g >= DEPTH_TOLERANCE
}

/// The depth at pixel `(0, 0)` of the plane whose wrapped fixed-point
/// depth is `z + zx·i + zy·j`, unwrapped: the multiple of 2³² that puts
/// the face's first vertex `(x, y, z₀)` (units) at its own depth.
#[inline]
fn unwrap(z: i32, zx: i32, zy: i32, (x, y, z0): (i32, i32, i32)) -> i64 {
    // 16 times the depth at the vertex, as the wrapped function gives
    // it: |zx·(x − 8)| < 2³¹·2¹⁶.
    let at = 16 * z as i64 + zx as i64 * (x - 8) as i64 + zy as i64 * (y - 8) as i64;
    let want = (z0 as i64) << (4 + 14);
    let m = (at - want + (1 << 35)) >> 36;
    z as i64 - (m << 32)
}

/// `true` when slot `x` is strictly in front of slot `y` on every pixel
/// both cover on rows `j0..=j1`, by their edges: on a row, a common pixel
/// is right of both left edges and left of both right edges, and each
/// edge's crossing moves by its whole units a row or one more, so the
/// difference of depths, affine, is bounded below on each row by its
/// value at either trapezoid's left edge (if it grows to the right) or
/// right edge (else), moved as far as it can go; that bound is linear in
/// the row, least at `j0` or `j1`. Both are stepped to `j0`; `16·TOL`
/// because the crossings are in sixteenths.
#[inline]
fn in_front_edges(act: &[Active], x: usize, y: usize, (j0, j1): (i32, i32)) -> bool {
    if act[x].hot.zx == WRAPS || act[y].hot.zx == WRAPS {
        return false;
    }
    let (ex, ey) = (&act[x].entry, &act[y].entry);
    let gx = ey.zx as i64 - ex.zx as i64;
    let gy = ey.zy as i64 - ex.zy as i64;
    let a = 16 * (z00(act, y) - z00(act, x));
    // On row `jj` the bound is `a + gx·(x0 + step·(jj − j)) + 16·gy·jj`,
    // linear in `jj`: its least over `j0..=j1` is at the end its slope
    // points away from.
    let bound = |s: usize| {
        let e = &act[s].entry;
        let j = act[s].hot.slot as i64;
        let (x0, step) = if gx >= 0 {
            (e.left.units() as i64, e.left.step_units() as i64)
        } else {
            (e.right.units() as i64, e.right.step_units() as i64 + 1)
        };
        let at_j = a + gx * x0 + 16 * gy * j;
        let slope = gx * step + 16 * gy;
        let jj = if slope >= 0 { j0 } else { j1 } as i64;
        at_j + slope * (jj - j)
    };
    // Either bound is one: the second is needed only when the first fails.
    bound(x) >= 16 * DEPTH_TOLERANCE || bound(y) >= 16 * DEPTH_TOLERANCE
}

/// `false` when the trapezoids stepped to `e` and `f`, both on the same
/// row `y`, share no pixel on rows `y..=y + rows`: a pixel of both is
/// left of `e`'s right edge and right of `f`'s left edge, and left of
/// `f`'s right edge and right of `e`'s left edge. On row `y + t` the gap
/// from a left edge's crossing to the other's right edge's is at most
/// `d + s·t` (sixteenths; each crossing moves by its whole units a row
/// or one more), and pixels can meet only where both gaps are positive:
/// the least of two affine bounds is positive somewhere on `0..=rows`
/// only at an end or where the two cross. Out of line: it runs only for
/// the pairs no depth bound settles.
#[inline(never)]
fn may_meet(e: &Entry, f: &Entry, rows: i32) -> bool {
    edges_may_meet((&e.left, &e.right), (&f.left, &f.right), rows)
}

/// [`may_meet`] of two pairs of edges (left, right), stepped to one row.
#[inline(always)]
fn edges_may_meet(e: (&Edge, &Edge), f: (&Edge, &Edge), rows: i32) -> bool {
    let gap = |l: &Edge, r: &Edge| {
        (
            r.units() as i64 - l.units() as i64,
            r.step_units() as i64 + 1 - l.step_units() as i64,
        )
    };
    let ((d1, s1), (d2, s2)) = (gap(e.0, f.1), gap(f.0, e.1));
    let t = rows as i64;
    let both = |t: i64| d1 + s1 * t > 0 && d2 + s2 * t > 0;
    if both(0) || both(t) {
        return true;
    }
    // The bounds cross at `(d2 − d1) / (s1 − s2)`, where both are
    // `(s1·d2 − s2·d1) / (s1 − s2)`.
    let den = s1 - s2;
    let (at, value) = (d2 - d1, s1 * d2 - s2 * d1);
    let (at, value, den) = if den < 0 {
        (-at, -value, -den)
    } else {
        (at, value, den)
    };
    den != 0 && value > 0 && at >= 0 && at <= t * den
}

/// The part of `a..b` (common pixels of slots `x` and `u` on row `y`)
/// where `u` is in front of `x`, when the fixed-point depths at its ends
/// do not decide both: compared exactly there, and where the planes
/// cross, split at the crossing pixel, estimated and checked.
#[inline(never)]
fn left_to(
    act: &[Active],
    store: &TrapezoidStore<'_>,
    x: usize,
    u: usize,
    (a, b): (i32, i32),
    y: u16,
    stats: &mut VisibleStats,
) -> (i32, i32) {
    let (Some(ax), Some(au)) = (act.get(x), act.get(u)) else {
        return (0, 0);
    };
    let (ex, eu) = (&ax.entry, &au.entry);
    let yi = y as i32;
    let (zx0, zu0) = (z_row(ex, yi), z_row(eu, yi));
    let mut nearer = |i: i32| {
        let d = zx0
            .wrapping_add(ex.zx.wrapping_mul(i))
            .wrapping_sub(zu0.wrapping_add(eu.zx.wrapping_mul(i)));
        if d < -(DEPTH_TOLERANCE as i32) {
            return true;
        }
        if d > DEPTH_TOLERANCE as i32 {
            return false;
        }
        stats.exact += 1;
        exact_nearer(store, ex.face, eu.face, (i, yi), d)
    };
    let (xa, xb) = (nearer(a), nearer(b - 1));
    match (xa, xb) {
        (true, true) => (0, 0),
        (false, false) => (a, b),
        _ => {
            // The planes cross on a..b: the first pixel where the one
            // nearer at `b − 1` is in front, estimated, then checked.
            stats.splits += 1;
            let cx = Cover {
                z: zx0,
                zx: ex.zx,
                ..Cover::EMPTY
            };
            let cu = Cover {
                z: zu0,
                zx: eu.zx,
                ..Cover::EMPTY
            };
            let mut c = if xa {
                crossing_point(&cx, &cu, a, b)
            } else {
                crossing_point(&cu, &cx, a, b)
            };
            // `nearer` is `xa` on a..c and `xb` on c..b (an affine
            // difference changes sign once).
            while c > a + 1 && nearer(c - 1) != xa {
                c -= 1;
            }
            while c < b - 1 && nearer(c) == xa {
                c += 1;
            }
            if xa {
                (c, b)
            } else {
                (a, c)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::coherence::{scenes, Pools};
    use super::super::*;
    use crate::fixed::{Coord, Vertex3};
    use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
    use std::vec;
    use std::vec::Vec;
    use testkit::rng::Rng;

    /// `edges_may_meet` is `false` only for pairs of edge pairs whose
    /// pixels (from the crossings' ceilings, as a row's are) never meet
    /// on the rows it is given.
    #[test]
    fn may_meet_is_false_only_where_pixels_never_meet() {
        use super::edges_may_meet;
        use crate::fixed::{ceil_px, Coord, Vertex};
        use crate::raster::edge::Edge;
        let mut rng = Rng(25);
        let (r0, r1) = (4, 40);
        let v =
            |x: i32, y: i32| Vertex::new(Coord::from_bits(x as i16), Coord::from_bits(y as i16));
        let edge = |rng: &mut Rng| {
            let (xa, xb) = (rng.range(0, 2048), rng.range(0, 2048));
            Edge::new(v(xa, 16 * r0 - 24), v(xb, 16 * r1 + 24), (r0, r1)).unwrap()
        };
        let (mut apart, mut meeting) = (0, 0);
        for _ in 0..20_000 {
            let mut e = [
                edge(&mut rng),
                edge(&mut rng),
                edge(&mut rng),
                edge(&mut rng),
            ];
            assert_eq!((e[0].top(), e[0].end()), (r0, r1));
            let may = edges_may_meet((&e[0], &e[1]), (&e[2], &e[3]), r1 - 1 - r0);
            let mut met = false;
            for _ in r0..r1 {
                let px: [i32; 4] = core::array::from_fn(|i| ceil_px(e[i].units()));
                met |= px[0].max(px[2]) < px[1].min(px[3]);
                e.iter_mut().for_each(Edge::step);
            }
            assert!(may || !met, "{e:?}");
            apart += !may as u32;
            meeting += met as u32;
        }
        assert!(apart > 1000 && meeting > 1000, "{apart} {meeting}");
    }

    /// The last colour written to each pixel.
    struct Pixels {
        size: (u16, u16),
        px: Vec<Rgb888>,
    }

    impl SpanTarget for Pixels {
        type Color = Rgb888;
        type Error = core::convert::Infallible;
        fn size(&self) -> (u16, u16) {
            self.size
        }
        fn fill_span(&mut self, s: Span, c: Rgb888) -> Result<(), Self::Error> {
            for x in s.x0..s.x1 {
                self.px[s.y as usize * self.size.0 as usize + x as usize] = c;
            }
            Ok(())
        }
    }

    /// Renders `polys` into a `w × h` frame with `runs` runs, by the sweep
    /// and by painting, whole and band by band, over a background and
    /// without: the same pixels. Painting's stats (the whole frame, over
    /// a background), and whether a band by band pass fell back to the
    /// sweep.
    fn compare(polys: &[Vec<Vertex3>], (w, h): (u16, u16), runs: usize) -> (VisibleStats, bool) {
        let mut pools = Pools::new(polys.len(), h);
        let store = pools.store(polys, w, h);
        let mut active = vec![Active::EMPTY; store.len() + 1];
        let mut run_buf = vec![Run::EMPTY; runs];
        let mut ws = Workspace::new(&mut active, &mut run_buf);
        let frame = || Pixels {
            size: (w, h),
            px: vec![Rgb888::BLACK; w as usize * h as usize],
        };
        let mut stats = VisibleStats::default();
        let mut banded_fell_back = false;
        for bg in [Some(Rgb888::WHITE), None] {
            let (mut a, mut b) = (frame(), frame());
            draw(&store, &mut ws, Resolve::Crossing, &mut a, bg).unwrap();
            let (st, _) = draw(&store, &mut ws, Resolve::Paint, &mut b, bg).unwrap();
            for (i, (p, q)) in a.px.iter().zip(&b.px).enumerate() {
                let at = (i % w as usize, i / w as usize);
                assert_eq!(p, q, "pixel {at:?}, background {bg:?}");
            }
            if bg.is_some() {
                stats = st;
            }
            // Band by band through a `Sweep` that paints: bands of 1, 3
            // and 7 rows, and bands of 5 with every other one skipped.
            for (band, skipping) in [(1, false), (3, false), (7, false), (5, true)] {
                let mut c = frame();
                let mut sweep = Sweep::new(&mut ws, Resolve::Paint);
                let mut drawn = vec![false; h as usize];
                let mut i = 0;
                while sweep.next_row() < h {
                    let y = sweep.next_row();
                    if skipping && i % 2 == 0 {
                        sweep.skip(&store, &mut ws, band).unwrap();
                    } else {
                        sweep.draw(&store, &mut ws, band, &mut c, bg).unwrap();
                        let end = (y + band).min(h);
                        drawn[y as usize..end as usize].fill(true);
                    }
                    assert!(sweep.next_row() > y);
                    i += 1;
                }
                for (i, (p, q)) in a.px.iter().zip(&c.px).enumerate() {
                    let at = (i % w as usize, i / w as usize);
                    if drawn[at.1] {
                        assert_eq!(p, q, "pixel {at:?}, bands of {band}, background {bg:?}");
                    }
                }
                let st = sweep.stats();
                banded_fell_back |= st.single + st.multiple + st.empty > 0;
            }
        }
        (stats, banded_fell_back)
    }

    fn v3((x, y, z): (i32, i32, i32)) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits(x as i16),
            y: Coord::from_bits(y as i16),
            z: Coord::from_bits(z as i16),
        }
    }

    #[test]
    fn a_target_smaller_than_the_store_gets_the_sweeps_pixels() {
        let (_, faces, w, h) = scenes().into_iter().nth(1).expect("tilted");
        let mut pools = Pools::new(faces.len(), h);
        let store = pools.store(&faces, w, h);
        let mut active = vec![Active::EMPTY; store.len() + 1];
        let mut run_buf = vec![Run::EMPTY; 4 * w as usize];
        let mut ws = Workspace::new(&mut active, &mut run_buf);
        let (tw, th) = (w - 37, h - 21);
        let frame = || Pixels {
            size: (tw, th),
            px: vec![Rgb888::BLACK; tw as usize * th as usize],
        };
        let (mut a, mut b) = (frame(), frame());
        let bg = Some(Rgb888::WHITE);
        let (_, ca) = draw(&store, &mut ws, Resolve::Crossing, &mut a, bg).unwrap();
        let (st, cb) = draw(&store, &mut ws, Resolve::Paint, &mut b, bg).unwrap();
        assert!(a.px == b.px);
        assert_eq!(st.single + st.multiple + st.empty, 0, "painted");
        // Every pixel inside written, some more than once.
        assert_eq!(ca.pixels, tw as u32 * th as u32);
        assert!(cb.pixels > ca.pixels);
    }

    #[test]
    fn too_small_an_active_list_is_an_error_not_a_panic() {
        let (_, faces, w, h) = scenes().into_iter().nth(1).expect("tilted");
        let mut pools = Pools::new(faces.len(), h);
        let store = pools.store(&faces, w, h);
        let mut active = vec![Active::EMPTY; 5];
        let mut run_buf = vec![Run::EMPTY; w as usize];
        let mut ws = Workspace::new(&mut active, &mut run_buf);
        let mut px = Pixels {
            size: (w, h),
            px: vec![Rgb888::BLACK; w as usize * h as usize],
        };
        let got = draw(&store, &mut ws, Resolve::Paint, &mut px, None);
        assert!(matches!(got, Err(VisibleError::Active { capacity: 5 })));
        let mut short = vec![Run::EMPTY; w as usize - 1];
        let mut ws = Workspace::new(&mut active, &mut short);
        let got = draw(&store, &mut ws, Resolve::Paint, &mut px, None);
        assert!(matches!(got, Err(VisibleError::Runs { .. })));
    }

    #[test]
    fn a_bow_tie_and_a_face_nearly_edge_on() {
        let bow = [(0, 0, 0), (345, 198, 0), (345, 0, 0), (0, 197, 0)];
        let steep = [(675, 232, 0), (300, 139, 22698), (294, 141, -5513)];
        let faces: Vec<Vec<Vertex3>> = vec![
            bow.iter().map(|&v| v3(v)).collect(),
            steep.iter().map(|&v| v3(v)).collect(),
        ];
        compare(&faces, (40, 30), 200);
    }

    #[test]
    fn paints_the_sweeps_pixels() {
        for (name, faces, w, h) in scenes() {
            // Records enough, and so few that it falls back.
            for runs in [4 * w as usize, w as usize] {
                let (st, _) = compare(&faces, (w, h), runs);
                assert!(st.rows == h as u32, "{name}");
                // Painted to the end: the sweep's span counts stay 0.
                assert_eq!(st.single + st.multiple + st.empty, 0, "{name}");
            }
        }
    }

    #[test]
    fn random_interpenetrating_triangles_paint_the_sweeps_pixels() {
        let mut rng = Rng(11);
        // Frames that fell back to the sweep, with few records and many;
        // band by band passes that did.
        let mut fell_back = (0, 0);
        let mut banded = 0;
        for _ in 0..300 {
            let n = 2 + rng.below(12) as usize;
            let near = rng.below(2) == 0;
            let tris: Vec<Vec<Vertex3>> = (0..n)
                .map(|_| {
                    (0..3)
                        .map(|_| {
                            let z = if near {
                                rng.below(64)
                            } else {
                                rng.below(4000) - 2000
                            };
                            v3((rng.below(48 * 16) - 64, rng.below(40 * 16) - 64, z))
                        })
                        .collect()
                })
                .collect();
            let (a, banded_a) = compare(&tris, (40, 32), 40);
            let (b, banded_b) = compare(&tris, (40, 32), 200);
            fell_back.0 += (a.single + a.multiple + a.empty > 0) as u32;
            fell_back.1 += (b.single + b.multiple + b.empty > 0) as u32;
            banded += banded_a as u32 + banded_b as u32;
        }
        // Both ways are taken, whole and band by band.
        assert!(fell_back.0 > 0 && fell_back.1 < 300, "{fell_back:?}");
        assert!(banded > 0 && banded < 600, "{banded}");
    }
}
