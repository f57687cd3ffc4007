//! The edge stepper: where an edge crosses each pixel row, in integers.
//!
//! Row `j` is sampled on the line `y = j + ½`. An edge from `(x₀, y₀)` to
//! `(x₁, y₁)`, `y₀ < y₁`, crosses it when `y₀ ≤ j + ½ < y₁`. By the pixel
//! rule, a crossing at `x` separates pixel `i` with `i + ½ < x` from pixel
//! `i` with `i + ½ ≥ x`, so all a row needs of a crossing is the integer
//!
//! ```text
//! c = ⌈x − ½⌉      (the first pixel whose centre is at or right of x)
//! ```
//!
//! and a span of the even-odd rule is `c_left..c_right`. The stepper keeps,
//! in units of 1/16 px, `X = ⌈x − ½⌉₁₆` (the position rounded up to a
//! unit) and an error counter `e = X·dy − (x − ½)·dy ∈ [0, dy)`, so that the
//! exact position is `X − e/dy`. One row down, the exact position moves by
//! `16·dx/dy = q + r/dy`; the step is `X += q; e −= r; if e < 0 { X += 1;
//! e += dy }`, with no division. Since `⌈⌈v⌉/16⌉ = ⌈v/16⌉`, the pixel is
//! `c = ⌈X/16⌉`, a shift. The first row inside the clip window is computed
//! directly (one `i64` division), so rows above the window cost nothing.
//!
//! The widths of every quantity are in [`crate::fixed`].

use crate::fixed::{ceil_div_i64, ceil_div_rem_i32, ceil_px, Vertex, HALF, ONE};

/// How the scan converter steps one edge down the rows.
///
/// [`Rasterizer`](crate::raster::scan::Rasterizer) is generic over it, with the
/// exact [`Edge`] the default; the faster, approximate steppers of
/// [`dda`](crate::raster::dda) implement it too. Row `j` is sampled on
/// `y = j + ½`; a stepper reports, for each row from [`top`](Stepper::top)
/// to [`end`](Stepper::end), the first pixel whose centre is at or right of
/// its crossing (exactly or approximately).
///
/// # Contract
/// A stepper made by [`new`](Stepper::new) has `top < end`, both inside the
/// rows it was given. [`pixel`](Stepper::pixel) is meaningful after
/// [`load_pixel`](Stepper::load_pixel) on the current row; `step` moves to
/// the next row and is called only while the next row is before `end`.
pub trait Stepper: Copy {
    /// The edge from `a` to `b` restricted to rows `rows.0..rows.1`, or
    /// `None` when it crosses no row centre there.
    fn new(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self>;
    /// First row sampled.
    fn top(&self) -> i32;
    /// One past the last row sampled.
    fn end(&self) -> i32;
    /// Computes [`pixel`](Stepper::pixel) for the current row.
    fn load_pixel(&mut self);
    /// The crossing's pixel on the current row, as of the last
    /// [`load_pixel`](Stepper::load_pixel).
    fn pixel(&self) -> i32;
    /// Moves to the next row.
    fn step(&mut self);
    /// `true` when [`step`](Stepper::step) never moves the crossing (a
    /// vertical edge): the scan converter then repeats one span down a run
    /// of rows without stepping. `false` (the default) is always correct.
    #[inline(always)]
    fn is_vertical(&self) -> bool {
        false
    }
    /// Bounds `(lo, hi)` on the pixels [`pixel`](Stepper::pixel) gives
    /// on the `rows` rows from the current one (`rows ≥ 1`), or `None`
    /// (the default) when the stepper does not tell: the scan converter
    /// skips the clip on a run of rows whose crossings all lie inside it.
    #[inline(always)]
    #[doc(hidden)]
    fn columns(&self, rows: i32) -> Option<(i32, i32)> {
        let _ = rows;
        None
    }
    /// `true` when the stepper's pixels are the pixel rule's on every
    /// edge, as [`Edge`]'s are: the scan converter then fills an
    /// axis-aligned rectangle straight from its corners, with no edge set
    /// up. `false` (the default) sends every polygon through the steppers.
    #[doc(hidden)]
    const EXACT: bool = false;
    /// [`new`](Stepper::new) for a walk by the non-zero rule
    /// ([`FillRule::NonZero`](crate::raster::FillRule)): the stepper keeps
    /// the edge's direction, `u`, 1 for an edge running up the rows (`b`
    /// above `a`), 0 for one running down, for
    /// [`load_wound`](Stepper::load_wound).
    #[doc(hidden)]
    fn new_wound(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self>;
    /// Computes the pixel for the current row, as
    /// [`load_pixel`](Stepper::load_pixel) does, with the direction of a
    /// stepper made by [`new_wound`](Stepper::new_wound) beside it:
    /// [`pixel`](Stepper::pixel) is then `2·c + u`, `c` the pixel. A walk
    /// by the non-zero rule loads its edges only so, and never by
    /// `load_pixel`, which drops the direction.
    #[doc(hidden)]
    fn load_wound(&mut self);
    /// Makes `self` a copy of `other`, as `*self = *other`. A stepper may
    /// copy field by field: a copy of a whole record between two slots
    /// of one slice can become a call to `memmove`.
    #[inline(always)]
    fn copy_from(&mut self, other: &Self) {
        *self = *other;
    }
}

/// One polygon edge being stepped down the rows, in the form of the
/// classic Bresenham error counter.
///
/// Storage for edges is owned by the caller (see
/// [`Rasterizer`](crate::raster::scan::Rasterizer)); [`Edge::EMPTY`] fills it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Edge {
    /// `⌈x − ½⌉` at the current row, in units of 1/16 px.
    x: i32,
    /// Error counter, `0 ≤ err < dy`.
    err: i32,
    /// Whole units per row, `⌊16·dx / dy⌋`.
    step: i32,
    /// Remainder per row, `16·dx mod dy`.
    rem: i32,
    /// Height in units, `> 0`.
    dy: i32,
    /// First row sampled (inside the clip rows).
    pub(super) top: i32,
    /// One past the last row sampled.
    pub(super) end: i32,
    /// Pixel of the crossing on the current row, `⌈x/16⌉`; set by
    /// [`Edge::load_pixel`]. Or, in a walk by the non-zero rule, that
    /// pixel times two plus the edge's direction ([`Stepper::load_wound`]),
    /// and from [`Stepper::new_wound`] until the first load the direction
    /// alone: the slot stays 32 bytes, and the even-odd walk reads and
    /// writes nothing more.
    pub(super) px: i32,
}

impl Edge {
    /// An unused slot.
    pub const EMPTY: Edge = Edge {
        x: 0,
        err: 0,
        step: 0,
        rem: 0,
        dy: 1,
        top: 0,
        end: 0,
        px: 0,
    };

    /// The edge from `a` to `b` restricted to rows `rows.0..rows.1`, or
    /// `None` when it crosses no row centre there (horizontal edges, edges
    /// between two row centres, edges outside the rows).
    #[inline(always)]
    #[doc(hidden)]
    pub fn new(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Edge> {
        let (mut p, mut q) = (a, b);
        if p.y.units() > q.y.units() {
            core::mem::swap(&mut p, &mut q);
        }
        let (x0, y0, x1, y1) = (p.x.units(), p.y.units(), q.x.units(), q.y.units());
        // Rows whose centre j·16 + 8 lies in [y0, y1).
        let top = ceil_px(y0 - HALF).max(rows.0);
        let end = ceil_px(y1 - HALF).min(rows.1);
        let (dx, dy) = (x1 - x0, y1 - y0);
        // A row centre in [y0, y1) makes dy ≥ 1. Tested all the same, so
        // that the divisions by dy below need no check for a zero divisor
        // or an overflow.
        if top >= end || dy <= 0 {
            return None;
        }
        // (x − ½)·dy at the first row's centre, exactly.
        let yc = top * ONE + HALF;
        // |num| < 2³³ (see `fixed`); on a frame of ordinary size it fits
        // in `i32`, and a 32-bit division is one instruction on a 32-bit
        // core where a 64-bit one is a library call.
        let num = (x0 - HALF) as i64 * dy as i64 + (yc - y0) as i64 * dx as i64;
        let (x, err) = match i32::try_from(num) {
            Ok(n) => ceil_div_rem_i32(n, dy),
            Err(_) => {
                let x = ceil_div_i64(num, dy as i64);
                (x as i32, (x * dy as i64 - num) as i32)
            }
        };
        Some(Edge::stepping(x, err, dx, dy, (top, end)))
    }

    /// The stepper over rows `rows.0..rows.1` of an edge of slope
    /// `dx / dy` (`dy ≥ 1`) crossing the first row at `x` with error
    /// `err`: its step is ⌊16·dx / dy⌋ and its remainder, from one
    /// truncating division.
    #[inline(always)]
    fn stepping(x: i32, err: i32, dx: i32, dy: i32, (top, end): (i32, i32)) -> Edge {
        let (mut step, mut rem) = ((ONE * dx) / dy, (ONE * dx) % dy);
        if rem < 0 {
            step -= 1;
            rem += dy;
        }
        Edge {
            x,
            err,
            step,
            rem,
            dy,
            top,
            end,
            px: 0,
        }
    }

    /// Computes [`Edge::pixel`] for the current row.
    #[inline(always)]
    #[doc(hidden)]
    pub fn load_pixel(&mut self) {
        self.px = ceil_px(self.x);
    }

    /// The first pixel whose centre is at or right of the crossing on the
    /// current row, as of the last [`Edge::load_pixel`].
    #[inline(always)]
    #[doc(hidden)]
    pub fn pixel(&self) -> i32 {
        self.px
    }

    /// The crossing on the current row: `⌈x − ½⌉` in units of 1/16 px.
    #[inline(always)]
    #[doc(hidden)]
    pub fn units(&self) -> i32 {
        self.x
    }

    /// Whole units the crossing moves down a row: each [`Edge::step`]
    /// moves it by this or one more.
    #[inline(always)]
    #[doc(hidden)]
    pub fn step_units(&self) -> i32 {
        self.step
    }

    /// Moves to the next row.
    #[inline(always)]
    #[doc(hidden)]
    pub fn step(&mut self) {
        self.x += self.step;
        self.err -= self.rem;
        if self.err < 0 {
            self.x += 1;
            self.err += self.dy;
        }
    }

    /// [`Edge::step`] with the carry taken by a mask instead of a branch:
    /// the same state after, for loops over many edges whose carries
    /// follow no pattern a branch predictor could learn.
    #[inline(always)]
    #[doc(hidden)]
    pub fn step_masked(&mut self) {
        // −dy < err − rem < dy: no overflow; `m` is −1 on a carry, else 0.
        self.err -= self.rem;
        let m = self.err >> 31;
        self.x += self.step - m;
        self.err += self.dy & m;
    }

    /// Moves `n` rows down at once: the same state as `n` calls of
    /// [`Edge::step`] (or [`Edge::step_masked`]), with one division
    /// instead of `n` steps. The carries over the `n` rows are
    /// `⌈(n·rem − err) / dy⌉` when positive, else none. Meant for rows
    /// inside the edge (`n` below its height); beyond them the position
    /// wraps as the steps would.
    #[inline]
    #[doc(hidden)]
    pub fn advance(&mut self, n: u32) {
        // n < 2³² and 0 ≤ err, rem < dy < 2³¹: |drop| < 2⁶³, and
        // carries·dy ≤ drop + dy. On a frame of ordinary size it fits in
        // `i32`, and a 32-bit division is one instruction on a 32-bit
        // core where a 64-bit one is a library call.
        let drop = n as i64 * self.rem as i64 - self.err as i64;
        // ⌈drop/dy⌉ = (drop − 1)/dy + 1 for drop > 0, written out here:
        // the `fixed` helpers have callers enough that the Cortex-M4
        // build does not inline them into `Edge::new`.
        let carries = if drop <= 0 {
            0
        } else if let Ok(d) = i32::try_from(drop) {
            ((d - 1) / self.dy + 1) as i64
        } else {
            (drop - 1) / self.dy as i64 + 1
        };
        self.err = (carries * self.dy as i64 - drop) as i32;
        self.x = self
            .x
            .wrapping_add((n as i32).wrapping_mul(self.step))
            .wrapping_add(carries as i32);
    }

    /// [`Edge::new`] for an edge from `(x0, y0)` to `(x1, y1)` (units,
    /// `y0 < y1`) over `rows`, rows whose centres it crosses, as a cut
    /// trapezoid's sides are stored: the same stepper, without the ends'
    /// order, the rows' bounds or their test, which the record already
    /// holds. Rows it does not cross give a stepper whose positions are
    /// the line's, not the edge's; ends with `y0 ≥ y1` give
    /// [`Edge::EMPTY`]. The ends are `i16` widened (so nothing here
    /// overflows). Not inlined: inlined into the entries (the sweep's and
    /// painting's), it cost the 3D demo more than the call (figures in
    /// `docs/performance-log.md`).
    #[inline(never)]
    pub(crate) fn on_rows(x0: i32, y0: i32, x1: i32, y1: i32, (top, end): (i32, i32)) -> Edge {
        let (dx, dy) = (x1 - x0, y1 - y0);
        if dy <= 0 {
            return Edge::EMPTY;
        }
        let yc = top * ONE + HALF;
        let num = (x0 - HALF) as i64 * dy as i64 + (yc - y0) as i64 * dx as i64;
        // ⌈num/dy⌉ from a truncating division (dy > 0), written out as in
        // `advance`: the `fixed` helper is not inlined here.
        let (x, err) = match i32::try_from(num) {
            Ok(n) => {
                let q = n / dy;
                let x = if n > 0 && q * dy != n { q + 1 } else { q };
                (x, x.wrapping_mul(dy).wrapping_sub(n))
            }
            Err(_) => {
                let x = ceil_div_i64(num, dy as i64);
                (x as i32, (x * dy as i64 - num) as i32)
            }
        };
        Edge::stepping(x, err, dx, dy, (top, end))
    }

    /// First row sampled.
    #[doc(hidden)]
    pub fn top(&self) -> i32 {
        self.top
    }

    /// One past the last row sampled.
    #[doc(hidden)]
    pub fn end(&self) -> i32 {
        self.end
    }
}

impl Stepper for Edge {
    const EXACT: bool = true;
    // Out of line: a call an edge, where inlined into the fill and the
    // band table it would grow the functions whose row loops it shares.
    #[inline(never)]
    fn new(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        Edge::new(a, b, rows)
    }
    #[inline(always)]
    fn top(&self) -> i32 {
        self.top
    }
    #[inline(always)]
    fn end(&self) -> i32 {
        self.end
    }
    #[inline(always)]
    fn load_pixel(&mut self) {
        Edge::load_pixel(self)
    }
    #[inline(always)]
    fn pixel(&self) -> i32 {
        self.px
    }
    #[inline(always)]
    fn step(&mut self) {
        Edge::step(self)
    }
    #[inline]
    fn new_wound(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        let mut e = Edge::new(a, b, rows)?;
        e.px = (a.y.units() > b.y.units()) as i32;
        Some(e)
    }
    #[inline(always)]
    fn load_wound(&mut self) {
        self.px = ceil_px(self.x) << 1 | (self.px & 1);
    }
    #[inline(always)]
    fn columns(&self, rows: i32) -> Option<(i32, i32)> {
        // k rows down, x moves by k·step plus 0..=k carries: over the
        // rows it stays between x, x + (rows − 1)·step and x + (rows −
        // 1)·(step + 1) (saturated, still bounds), and ⌈·/16⌉ keeps the
        // order.
        let k = rows - 1;
        let a = self.x.saturating_add(k.saturating_mul(self.step));
        let b = a.saturating_add(k);
        Some((ceil_px(a.min(self.x)), ceil_px(b.max(self.x))))
    }
    #[inline(always)]
    fn is_vertical(&self) -> bool {
        // x += 0 and err −= 0 every row.
        self.step == 0 && self.rem == 0
    }
    #[inline(always)]
    fn copy_from(&mut self, other: &Self) {
        // Field by field: loads and stores, never `memmove` or `memcpy`.
        let Edge {
            x,
            err,
            step,
            rem,
            dy,
            top,
            end,
            px,
        } = *other;
        (self.x, self.err, self.step, self.rem) = (x, err, step, rem);
        (self.dy, self.top, self.end, self.px) = (dy, top, end, px);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A xorshift generator from `seed`: each call a value in `-m..m`.
    fn xorshift(mut s: u32) -> impl FnMut(i32) -> i32 {
        move |m| {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            (s % (2 * m as u32)) as i32 - m
        }
    }

    /// `⌈x − ½⌉` in pixels at row `j`, straight from the definition with
    /// rationals over a common denominator.
    fn direct(a: Vertex, b: Vertex, j: i32) -> i32 {
        let (mut p, mut q) = (a, b);
        if p.y > q.y {
            core::mem::swap(&mut p, &mut q);
        }
        let (x0, y0, x1, y1) = (
            p.x.units() as i64,
            p.y.units() as i64,
            q.x.units() as i64,
            q.y.units() as i64,
        );
        let yc = j as i64 * 16 + 8;
        // x·dy in units: x0·dy + (yc − y0)·dx; pixel = ⌈(x − 8)/16⌉.
        let n = x0 * (y1 - y0) + (yc - y0) * (x1 - x0) - 8 * (y1 - y0);
        ceil_div_i64(n, 16 * (y1 - y0)) as i32
    }

    fn check(a: Vertex, b: Vertex) {
        let Some(mut e) = Edge::new(a, b, (i32::MIN, i32::MAX)) else {
            return;
        };
        let mut masked = e;
        for j in e.top()..e.end() {
            e.load_pixel();
            assert_eq!(e.pixel(), direct(a, b, j), "{a:?} {b:?} row {j}");
            e.step();
            masked.load_pixel();
            masked.step_masked();
            assert_eq!(masked, e, "step_masked, {a:?} {b:?} row {j}");
        }
    }

    /// [`Edge::advance`] by every `n` up to the edge's last row, from its
    /// first row and from a third of the way down, against `n` steps.
    fn check_advance(a: Vertex, b: Vertex) {
        let Some(first) = Edge::new(a, b, (i32::MIN, i32::MAX)) else {
            return;
        };
        let h = (first.end() - first.top()) as u32;
        let mut mid = first;
        mid.advance(h / 3);
        for start in [first, mid] {
            let mut stepped = start;
            for n in 0..h - h / 3 {
                let mut jumped = start;
                jumped.advance(n);
                assert_eq!(jumped, stepped, "{a:?} {b:?} n {n}");
                stepped.step();
            }
        }
    }

    #[test]
    fn advance_equals_steps() {
        let mut rnd = xorshift(0x9e37_79b9u32);
        for _ in 0..400 {
            let a = Vertex::from_bits(rnd(32767) as i16, rnd(32767) as i16);
            let b = Vertex::from_bits(rnd(32767) as i16, rnd(32767) as i16);
            check_advance(a, b);
        }
        for _ in 0..3000 {
            let a = Vertex::from_bits(rnd(300) as i16, rnd(3000) as i16);
            let b = Vertex::from_bits(rnd(300) as i16, rnd(3000) as i16);
            check_advance(a, b);
        }
        // The range's corners: the longest edges, the steepest slopes.
        let m = [i16::MIN, i16::MIN + 1, -1, 0, 1, i16::MAX - 1, i16::MAX];
        for &ax in &m {
            for &ay in &m {
                for &bx in &m {
                    for &by in &m {
                        check_advance(Vertex::from_bits(ax, ay), Vertex::from_bits(bx, by));
                    }
                }
            }
        }
        // Inside the range n·rem stays below 2²⁸; past the edge's rows it
        // can leave the 32-bit path: 16·dx ≡ −1 (mod dy), the largest
        // remainder.
        let (a, b) = (
            Vertex::from_bits(i16::MIN, i16::MIN),
            Vertex::from_bits(28671, i16::MAX),
        );
        let e = Edge::new(a, b, (i32::MIN, i32::MAX)).unwrap();
        assert_eq!(e.rem, e.dy - 1);
        let n = 600_000;
        assert!(e.rem as i64 * n as i64 > i32::MAX as i64);
        let (mut stepped, mut jumped) = (e, e);
        for _ in 0..n {
            stepped.step();
        }
        jumped.advance(n);
        assert_eq!(jumped, stepped);
    }

    /// [`Stepper::columns`] from every row of an edge, over every count
    /// of rows to its end: each pixel on those rows lies within.
    fn check_columns(a: Vertex, b: Vertex) {
        let Some(mut e) = Edge::new(a, b, (i32::MIN, i32::MAX)) else {
            return;
        };
        let mut px = [0i32; 64];
        let h = ((e.end() - e.top()) as usize).min(px.len());
        let mut at = e;
        for p in px.iter_mut().take(h) {
            at.load_pixel();
            *p = at.pixel();
            at.step();
        }
        for start in 0..h {
            for rows in 1..=h - start {
                let (lo, hi) = Stepper::columns(&e, rows as i32).unwrap();
                for &p in &px[start..start + rows] {
                    assert!(lo <= p && p <= hi, "{a:?} {b:?} row {start} rows {rows}");
                }
            }
            e.step();
        }
    }

    #[test]
    fn columns_bound_the_pixels() {
        let mut rnd = xorshift(0x2468_ace1u32);
        for _ in 0..2000 {
            let a = Vertex::from_bits(rnd(3000) as i16, rnd(600) as i16);
            let b = Vertex::from_bits(rnd(3000) as i16, rnd(600) as i16);
            check_columns(a, b);
        }
        // Steep, flat and the range's corners (saturated bounds).
        let m = [
            i16::MIN,
            i16::MIN + 1,
            -1,
            0,
            1,
            17,
            500,
            i16::MAX - 1,
            i16::MAX,
        ];
        for &ax in &m {
            for &ay in &m {
                for &bx in &m {
                    for &by in &m {
                        check_columns(Vertex::from_bits(ax, ay), Vertex::from_bits(bx, by));
                    }
                }
            }
        }
    }

    #[test]
    fn stepper_matches_direct_formula() {
        let mut rnd = xorshift(0x1234_5678u32);
        for _ in 0..3000 {
            let a = Vertex::from_bits(rnd(3000) as i16, rnd(3000) as i16);
            let b = Vertex::from_bits(rnd(3000) as i16, rnd(3000) as i16);
            check(a, b);
        }
    }

    #[test]
    fn range_corners_do_not_overflow() {
        let m = [i16::MIN, i16::MIN + 1, -1, 0, 1, i16::MAX - 1, i16::MAX];
        for &ax in &m {
            for &ay in &m {
                for &bx in &m {
                    for &by in &m {
                        check(Vertex::from_bits(ax, ay), Vertex::from_bits(bx, by));
                    }
                }
            }
        }
    }

    #[test]
    fn first_row_is_clipped_directly() {
        let a = Vertex::from_bits(0, -2048 * 16);
        let b = Vertex::from_bits(100 * 16, 2047 * 16);
        let e = Edge::new(a, b, (10, 13)).unwrap();
        assert_eq!((e.top(), e.end()), (10, 13));
    }
}
