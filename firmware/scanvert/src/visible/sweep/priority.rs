//! A resolve by priority, measured and not kept: a prototype that the
//! tests keep exact and counting (`cargo test -p scanvert --release
//! priority -- --include-ignored --nocapture`), for the next attempt at a
//! resolve cheaper than the sweep's. It draws the rows front to back in
//! one order for the whole frame, and settles the depth relation of two
//! trapezoids once for all the rows they share, instead of comparing
//! depths on every row. Its pixels equal the sweep's on every scene the
//! tests draw; on the Cortex-M4 it cost more than the sweep (figures in
//! `docs/performance.md`, "Where the sweep's instructions go on the
//! Cortex-M4").
//!
//! # The order and the pairs
//!
//! A trapezoid that enters the active list gets a *key*, its fixed-point
//! depth at the middle of its columns on its first row, and takes its
//! place in the live list (the sweep's sorted array, kept by key instead
//! of by `l`: nearest first; at equal keys, in the order they entered). As it enters it is tested against every
//! live trapezoid whose columns overlap its own: over the rectangle of
//! their common rows and columns, the difference of their fixed-point
//! depths is affine, so its least value is at a corner. When the one
//! later in the order is farther by at least [`DEPTH_TOLERANCE`] at that
//! corner, the earlier is strictly in front on every pixel they share.
//! Otherwise the pair is a *conflict*: the later trapezoid is put on the
//! earlier one's conflict list.
//!
//! # A row
//!
//! The live trapezoids are stepped by the sweep's own `step_live`, then
//! visited in order. Each claims the pixels of its `l..r` that no
//! trapezoid before it claimed (the row's *coverage*, a bit a column)
//! and that no trapezoid on
//! its conflict list is in front of: for each one whose `l..r` overlaps
//! its own, the depths at both ends of the overlap are compared exactly
//! (as the sweep compares them), and where the planes cross on it, the
//! crossing pixel is found by one division and checked on both sides.
//! What it claims is written at once as spans, in its colour.
//!
//! # Why it is exact
//!
//! Let `N` be the nearest trapezoid at a pixel. A trapezoid `X` before `N`
//! that covers the pixel is farther there, so `X` is not strictly in front
//! of `N` everywhere they meet: their pair is a conflict, `N` is on `X`'s
//! list, and `X` leaves the pixel to it. So nothing before `N` claims the
//! pixel, and `N` claims it, since nothing on its list is in front of it
//! there. A trapezoid left to one that is not live any more (its slot
//! taken by another) only ever leaves a pixel to a nearer one: that costs
//! a compare, never a pixel. The depth bound holds everywhere: the
//! fixed-point depths used for the pairs are the affine functions the
//! sweep evaluates, unwrapped (the wrapped `i32` depth is taken back to
//! `i64` through the face's first vertex), and within `2¹²` of the exact
//! depth at every pixel centre of the frame.
//!
//! # Memory
//!
//! The workspace's active slots (as for the sweep: the most trapezoids
//! on one row; each slot's `cover` element holds what the order needs),
//! its run buffer for the conflict records (one run each: the partner's
//! slot and the next record; a slot's list is freed when the slot is
//! taken again), and 512 bytes of stack for the coverage. When a frame
//! needs more records than the buffer holds, or a trapezoid leaves more
//! than [`PARTS`] parts of a row to partners, the rows from there on are
//! drawn by the sweep instead, to the same pixels.
//!
//! # Cost
//!
//! Per row, `O(a)` for stepping, `O(a + w/32)` for the coverage of a row
//! `w` columns wide, and the writes, plus two depth compares for each
//! conflict whose trapezoids overlap on the row; per frame, one test per
//! pair of trapezoids that are live together.

use super::{
    capacity, exact_nearer, jump, step_live, Active, Counts, Cover, Covered, Entry, Resolve, Sweep,
    ToTarget, VisibleError, VisibleStats, Workspace, BACKGROUND,
};
use crate::color::ListColor;
use crate::port::SpanTarget;
use crate::visible::rle::Run;
use crate::visible::store::TrapezoidStore;
use crate::visible::trapezoid::{DEPTH_TOLERANCE, NONE};

/// "No record".
const NIL: u16 = NONE;

/// What a live trapezoid keeps besides the sweep's stepping state, in
/// its slot's `cover` element: `r` its key, `zx` its columns' bounds
/// `lo | hi << 16`, `z` the high word of its depth at pixel `(0, 0)`
/// unwrapped (the low word is the wrapped depth's), `p` the head of its
/// conflict list. The live list is the sweep's sorted array
/// (`act[..k].hot`), kept by key instead of by `l`.
#[inline(always)]
fn z00(act: &[Active], slot: usize, y: i32) -> i64 {
    let (e, c) = (&act[slot].entry, &act[slot].cover);
    // The entry's `z` is the depth at column 0 of row `y`.
    let low = e.z.wrapping_sub(e.zy.wrapping_mul(y));
    (c.z as i64) << 32 | low as u32 as i64
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

/// The pixels of the row claimed so far, a bit a column.
struct Coverage {
    bits: [u32; COVERAGE_WORDS],
}

/// Words of [`Coverage`]: 4096 columns, the widest frame.
const COVERAGE_WORDS: usize = 128;

/// Most parts of one trapezoid's pixels on a row that it leaves to
/// conflict partners; a row that needs more is drawn by the sweep.
const PARTS: usize = 8;

/// Resolves `store` by priority and writes it into `target`, as
/// [`draw`](super::draw) does.
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
    let mut out = ToTarget::new(target, background);
    let mut stats = VisibleStats::default();
    let Some(y) = draw_priority(
        workspace.active,
        workspace.runs,
        store,
        &mut out,
        &mut stats,
    )?
    else {
        return Ok((stats, out.counts));
    };
    // Out of records or parts: the rest by the sweep, from row `y` (a
    // row begun is drawn again, to the same pixels).
    let mut s = Sweep::start(workspace.active, Resolve::Crossing);
    let (k, nf) = jump(workspace.active, store, (0, s.nf), (0, y))
        .ok_or(VisibleError::Active { capacity: s.cap })?;
    (s.y, s.k, s.nf) = (y, k, nf);
    s.stats = stats;
    let out = s.rows(workspace.active, store, store.height() - y, out)?;
    Ok((s.stats, out.counts))
}

/// Resolves `store` by priority into `out`. `Ok(None)` when every row is
/// drawn; `Ok(Some(y))` when the conflict records or a trapezoid's
/// [`PARTS`] ran out at row `y`, whose pixels and those below are still
/// to be drawn (by the sweep).
pub(super) fn draw_priority<T>(
    active: &mut [Active],
    runs: &mut [Run],
    store: &TrapezoidStore<'_>,
    out: &mut ToTarget<'_, T>,
    stats: &mut VisibleStats,
) -> Result<Option<u16>, VisibleError<T::Error>>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    let width = store.width() as i32;
    let words = (width as usize).div_ceil(32);
    if words > COVERAGE_WORDS {
        return Ok(Some(0));
    }
    let cap = capacity(active);
    let act = &mut active[..cap];
    for (i, a) in act.iter_mut().enumerate() {
        a.free = i as u16;
        a.cover.p = NIL;
    }
    let (mut k, mut nf) = (0usize, cap);
    let records = runs.len().min(NIL as usize);
    let mut pool = Pool {
        runs: &mut runs[..records],
        used: 0,
        free: NIL,
    };
    let mut cov = Coverage {
        bits: [0; COVERAGE_WORDS],
    };
    for y in 0..store.height() {
        let yi = y as i32;
        // Step the live trapezoids to this row, dropping those that ended
        // (their conflict lists are freed when their slot is taken again).
        (k, nf) = step_live(act, k, nf, yi);
        // Enter the trapezoids whose top is this row, each tested against
        // the live ones and put in its place by key.
        let mut t = store.row_head(y as usize);
        while let Some(tr) = store.trapezoid(t) {
            t = tr.next_row;
            if nf == 0 {
                return Err(VisibleError::Active { capacity: cap });
            }
            nf -= 1;
            let slot = act[nf].free as usize;
            pool.release(act[slot].cover.p);
            let e = Entry::from(tr, store);
            let (lo, hi) = tr.column_bounds();
            let (zu, key) = match store.face(tr.face) {
                Some(f) => {
                    let d = f.depth();
                    let zu = unwrap(d.z, d.zx, d.zy, f.plane().origin_units());
                    let mid = (lo + hi) / 2;
                    let key = zu + d.zx as i64 * mid as i64 + d.zy as i64 * yi as i64;
                    (zu, key.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
                }
                None => (0, 0),
            };
            act[slot].entry = e;
            act[slot].cover = Covered {
                r: key,
                z: (zu >> 32) as i32,
                zx: lo | hi << 16,
                p: NIL,
            };
            stats.trapezoids += 1;
            let last = tr.end() - 1;
            // Its place: after every live one of a key at most its own.
            let mut at = k;
            while at > 0 && act[act[at - 1].hot.slot as usize].cover.r > key {
                at -= 1;
            }
            for p in 0..k {
                let u = act[p].hot.slot as usize;
                let c = act[u].cover;
                let (ulo, uhi) = (c.zx & 0xffff, (c.zx >> 16) & 0xffff);
                let (i0, i1) = (lo.max(ulo), hi.min(uhi) - 1);
                if i0 > i1 {
                    continue;
                }
                padd(0, 1);
                let j1 = last.min(act[u].entry.left.end() - 1);
                let (near, far) = if p < at { (u, slot) } else { (slot, u) };
                if !in_front(act, near, far, (i0, i1), (yi, j1)) {
                    padd(1, 1);
                    pmax(2, pool.used as u64);
                    let Some(q) = pool.push(far as u16, act[near].cover.p) else {
                        padd(9, y as u64);
                        return Ok(Some(y));
                    };
                    act[near].cover.p = q;
                    ppair(false, act[near].entry.face, act[far].entry.face);
                }
            }
            let h = e.hot(slot as u16);
            let mut p = k;
            while p > at {
                act[p].hot = act[p - 1].hot;
                p -= 1;
            }
            act[at].hot = h;
            k += 1;
        }
        stats.max_active = stats.max_active.max(k as u32);
        // Claim, front to back.
        cov.bits[..words].fill(0);
        out.y = y;
        for p in 0..k {
            let h = &act[p].hot;
            if h.l >= h.r {
                continue;
            }
            let h = *h;
            let head = act[h.slot as usize].cover.p;
            if head == NIL {
                stats.hidden += cov.claim(h.l, h.r, h.color, out);
                continue;
            }
            // The parts of l..r left to conflict partners in front.
            let mut parts = [(0i32, 0i32); PARTS];
            let mut n = 0;
            let mut q = head;
            while q != NIL {
                let (u, next) = pool.get(q);
                padd(3, 1);
                let d = left_to(act, store, h.slot as usize, u, (h.l, h.r), yi, stats);
                if d.0 < d.1 {
                    padd(5, 1);
                    ppair(true, act[h.slot as usize].entry.face, act[u].entry.face);
                    let Some(part) = parts.get_mut(n) else {
                        return Ok(Some(y));
                    };
                    *part = d;
                    n += 1;
                }
                q = next;
            }
            // What is not left, left to right.
            let parts = &mut parts[..n];
            parts.sort_unstable_by_key(|d| d.0);
            let mut s = h.l;
            for &(a, b) in parts.iter() {
                if s < a {
                    stats.hidden += cov.claim(s, a, h.color, out);
                }
                s = s.max(b);
            }
            if s < h.r {
                stats.hidden += cov.claim(s, h.r, h.color, out);
            }
        }
        // The background in the gaps.
        if out.background.is_some() {
            cov.claim(0, width, BACKGROUND, out);
        }
        stats.rows += 1;
        if let Some(e) = out.error.take() {
            return Err(VisibleError::Sink(e));
        }
    }
    Ok(None)
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
/// centre of columns `i0..=i1` and rows `j0..=j1` (both live on row `j0`;
/// the depths of `y` greater by at least [`DEPTH_TOLERANCE`] in fixed
/// point at the least corner).
#[inline]
fn in_front(
    act: &[Active],
    x: usize,
    y: usize,
    (i0, i1): (i32, i32),
    (j0, j1): (i32, i32),
) -> bool {
    let (ex, ey) = (&act[x].entry, &act[y].entry);
    let gx = ey.zx as i64 - ex.zx as i64;
    let gy = ey.zy as i64 - ex.zy as i64;
    let g = z00(act, y, j0) - z00(act, x, j0)
        + gx * if gx >= 0 { i0 } else { i1 } as i64
        + gy * if gy >= 0 { j0 } else { j1 } as i64;
    g >= DEPTH_TOLERANCE
}

/// The part `a..b` of `l..r` (slot `x`'s pixels on row `y`) where slot
/// `u` covers the pixels and is in front of `x`; `(0, 0)` when none.
#[inline]
fn left_to(
    act: &[Active],
    store: &TrapezoidStore<'_>,
    x: usize,
    u: usize,
    (l, r): (i32, i32),
    y: i32,
    stats: &mut VisibleStats,
) -> (i32, i32) {
    let (ex, eu) = (&act[x].entry, &act[u].entry);
    // A partner that ended is not stepped any more: it has no pixels
    // (its slot may hold another trapezoid since, which is harmless).
    if eu.left.end() <= y {
        return (0, 0);
    }
    let (ul, ur, _) = eu.pixels();
    let (a, b) = (l.max(ul), r.min(ur));
    if a >= b {
        return (0, 0);
    }
    padd(4, 1);
    let mut nearer = |i: i32| {
        let d =
            ex.z.wrapping_add(ex.zx.wrapping_mul(i))
                .wrapping_sub(eu.z.wrapping_add(eu.zx.wrapping_mul(i)));
        if d < -(DEPTH_TOLERANCE as i32) {
            return true;
        }
        if d > DEPTH_TOLERANCE as i32 {
            return false;
        }
        stats.exact += 1;
        exact_nearer(store, ex.face, eu.face, (i, y), d)
    };
    let (xa, xb) = (nearer(a), nearer(b - 1));
    match (xa, xb) {
        (true, true) => (0, 0),
        (false, false) => (a, b),
        _ => {
            // The planes cross on a..b: the first pixel where the one
            // nearer at `b − 1` is in front, estimated, then checked.
            let cx = Cover {
                z: ex.z,
                zx: ex.zx,
                ..Cover::EMPTY
            };
            let cu = Cover {
                z: eu.z,
                zx: eu.zx,
                ..Cover::EMPTY
            };
            let mut c = if xa {
                super::crossing_point(&cx, &cu, a, b)
            } else {
                super::crossing_point(&cu, &cx, a, b)
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

impl Coverage {
    /// Claims the pixels of `s..e` (`s < e`, within the row) not yet
    /// covered: writes them in `color` and covers `s..e`. 1 when they
    /// were all covered already, else 0.
    #[inline(always)]
    fn claim<T>(&mut self, s: i32, e: i32, color: u32, out: &mut ToTarget<'_, T>) -> u32
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        padd(6, 1);
        let w0 = (s >> 5) as usize;
        if w0 == ((e - 1) >> 5) as usize {
            if let Some(c) = self.bits.get_mut(w0) {
                let m = (!0u32 << (s & 31)) & (!0u32 >> (31 - ((e - 1) & 31)));
                let old = *c;
                *c = old | m;
                if old & m == 0 {
                    out.fill(s, e, color);
                    return 0;
                }
                if old & m == m {
                    return 1;
                }
                *c = old;
            }
        }
        self.claim_words(s, e, color, out)
    }

    /// [`claim`](Self::claim) of a span over several words, or of one
    /// partly covered.
    #[inline(never)]
    fn claim_words<T>(&mut self, s: i32, e: i32, color: u32, out: &mut ToTarget<'_, T>) -> u32
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        let (w0, w1) = ((s >> 5) as usize, ((e - 1) >> 5) as usize);
        let first = !0u32 << (s & 31);
        let last = !0u32 >> (31 - ((e - 1) & 31));
        let Some(words) = self.bits.get_mut(w0..=w1) else {
            return 0;
        };
        let n = words.len();
        padd(7, n as u64);
        let mask = |i: usize| {
            let mut m = !0u32;
            if i == 0 {
                m &= first;
            }
            if i + 1 == n {
                m &= last;
            }
            m
        };
        // Most spans are all new or all covered: told by a pass that
        // only reads, the ends apart from the words between.
        if let [c0, mid @ .., c1] = &mut *words {
            let (o0, o1) = (*c0 & first, *c1 & last);
            if o0 == 0 && o1 == 0 && mid.iter().all(|&c| c == 0) {
                *c0 |= first;
                *c1 |= last;
                mid.fill(!0);
                out.fill(s, e, color);
                return 0;
            }
            if o0 == first && o1 == last && mid.iter().all(|&c| c == !0) {
                return 1;
            }
        } else {
            let m = first & last;
            match words[0] & m {
                0 => {
                    words[0] |= m;
                    out.fill(s, e, color);
                    return 0;
                }
                o if o == m => return 1,
                _ => {}
            }
        }
        // The runs of uncovered columns, joined across words.
        let mut run: Option<(i32, i32)> = None;
        for (i, c) in words.iter_mut().enumerate() {
            let m = mask(i);
            let u = m & !*c;
            *c |= m;
            emit(u, w0 + i, &mut run, color, out);
        }
        if let Some((a, b)) = run {
            out.fill(a, b, color);
        }
        0
    }
}

/// Adds the runs of set bits of `u` (word `w` of a row) to the pending
/// run `run`, writing each run that ends before the next starts.
#[inline(always)]
fn emit<T>(
    mut u: u32,
    w: usize,
    run: &mut Option<(i32, i32)>,
    color: u32,
    out: &mut ToTarget<'_, T>,
) where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    let base = (w as i32) << 5;
    while u != 0 {
        let a = u.trailing_zeros();
        let len = (!(u >> a)).trailing_zeros();
        let (x0, x1) = (base + a as i32, base + (a + len) as i32);
        match run {
            Some((_, b)) if *b == x0 => *b = x1,
            _ => {
                if let Some((p, q)) = run.take() {
                    out.fill(p, q, color);
                }
                *run = Some((x0, x1));
            }
        }
        u &= if a + len >= 32 { 0 } else { !0u32 << (a + len) };
    }
}

/// Counts of the work done, for the counting test.
mod probe {
    use core::sync::atomic::{AtomicU64, Ordering};
    pub static C: [AtomicU64; 12] = [const { AtomicU64::new(0) }; 12];
    pub fn add(i: usize, n: u64) {
        C[i].fetch_add(n, Ordering::Relaxed);
    }
    pub fn max(i: usize, n: u64) {
        C[i].fetch_max(n, Ordering::Relaxed);
    }
    extern crate std;
    /// Pairs of faces.
    type Faces = std::collections::BTreeSet<(u16, u16)>;
    /// Conflicts (faces) recorded, and those that left a pixel.
    pub static PAIRS: std::sync::Mutex<(Faces, Faces)> =
        std::sync::Mutex::new((Faces::new(), Faces::new()));
    pub fn pair(left: bool, a: u16, b: u16) {
        let mut p = PAIRS.lock().unwrap();
        if left {
            p.1.insert((a, b));
        } else {
            p.0.insert((a, b));
        }
    }
    pub fn take() -> [u64; 12] {
        let mut p = PAIRS.lock().unwrap();
        C[10].store(p.0.len() as u64, Ordering::Relaxed);
        C[11].store(p.1.len() as u64, Ordering::Relaxed);
        p.0.clear();
        p.1.clear();
        core::array::from_fn(|i| C[i].swap(0, Ordering::Relaxed))
    }
}
use probe::{add as padd, max as pmax, pair as ppair};

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

    /// The counts are shared: one test at a time.
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

    fn lock() -> std::sync::MutexGuard<'static, ()> {
        ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The pixels written, and how often.
    struct Pixels {
        size: (u16, u16),
        px: Vec<(Rgb888, u32)>,
    }

    impl SpanTarget for Pixels {
        type Color = Rgb888;
        type Error = core::convert::Infallible;
        fn size(&self) -> (u16, u16) {
            self.size
        }
        fn fill_span(&mut self, s: Span, c: Rgb888) -> Result<(), Self::Error> {
            for x in s.x0..s.x1 {
                let p = &mut self.px[s.y as usize * self.size.0 as usize + x as usize];
                *p = (c, p.1 + 1);
            }
            Ok(())
        }
    }

    /// Renders `polys` into a `w × h` frame with `runs` runs, by the sweep
    /// and by priority: the same pixels, and each written once by
    /// priority unless it fell back. The priority resolve's stats.
    fn compare(polys: &[Vec<Vertex3>], (w, h): (u16, u16), runs: usize) -> VisibleStats {
        let mut pools = Pools::new(polys.len(), h);
        let store = pools.store(polys, w, h);
        let mut active = vec![Active::EMPTY; store.len() + 1];
        let mut run_buf = vec![Run::EMPTY; runs];
        let mut ws = Workspace::new(&mut active, &mut run_buf);
        let frame = || Pixels {
            size: (w, h),
            px: vec![(Rgb888::BLACK, 0); w as usize * h as usize],
        };
        let (mut a, mut b) = (frame(), frame());
        let bg = Some(Rgb888::WHITE);
        super::super::draw(&store, &mut ws, Resolve::Crossing, &mut a, bg).unwrap();
        let (stats, counts) = super::draw(&store, &mut ws, &mut b, bg).unwrap();
        let fell_back = stats.single + stats.multiple + stats.empty > 0;
        for (i, (p, q)) in a.px.iter().zip(&b.px).enumerate() {
            let at = (i % w as usize, i / w as usize);
            assert_eq!(p.0, q.0, "pixel {at:?}");
            assert!(fell_back || q.1 == 1, "pixel {at:?} written {} times", q.1);
        }
        if !fell_back {
            assert_eq!(counts.pixels, w as u32 * h as u32);
        }
        stats
    }

    fn v3((x, y, z): (i32, i32, i32)) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits(x as i16),
            y: Coord::from_bits(y as i16),
            z: Coord::from_bits(z as i16),
        }
    }

    #[test]
    fn draws_the_sweeps_pixels() {
        let _one = lock();
        for (name, faces, w, h) in scenes() {
            let size = (w, h);
            // Records enough, and so few that it falls back.
            for runs in [4 * size.0 as usize, size.0 as usize] {
                let st = compare(&faces, size, runs);
                assert!(st.rows == size.1 as u32, "{name}");
            }
        }
    }

    #[test]
    fn random_interpenetrating_triangles_draw_the_sweeps_pixels() {
        let _one = lock();
        let mut rng = Rng(11);
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
            compare(&tris, (40, 32), 40);
            compare(&tris, (40, 32), 200);
        }
    }

    #[test]
    #[ignore]
    fn priority_counts() {
        let _one = lock();
        std::println!("scene | pair tests | conflicts | most live records | partner checks | overlapping | parts left | claims | coverage words | face pairs in conflict | that left a pixel");
        for (name, faces, w, h) in scenes() {
            let size = (w, h);
            super::probe::take();
            compare(&faces, size, 4 * size.0 as usize);
            let c = super::probe::take();
            std::println!(
                "{name} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {}",
                c[0],
                c[1],
                c[2],
                c[3],
                c[4],
                c[5],
                c[6],
                c[7],
                c[10],
                c[11]
            );
        }
    }
}
