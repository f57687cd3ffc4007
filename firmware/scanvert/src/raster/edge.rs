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
//! and a span of the even-odd rule is `c_left..c_right`.
//!
//! # A wide DDA, exact
//!
//! The stepper is one `i64` accumulator `A` in pixels with 32 fraction
//! bits, stepped by an `i64` slope `S`: a row is `A += S` (two
//! instructions on a 32-bit core, `adds` and `adc`), and the pixel is the
//! high word, `A >> 32`, with no shift or rounding.
//!
//! *Why the high word is `c`.* Coordinates are units of 1/16 px and the
//! edge is `dy ≥ 1` units high, so at a row centre `v = x − ½` is a
//! multiple of `1/(16·dy)`. Then `c = ⌈v⌉ = ⌊w⌋` with
//! `w = v + 1 − 1/(16·dy)`, and `w`, a multiple of `1/(16·dy)` too, lies
//! at least `1/(16·dy)` below `⌊w⌋ + 1`. The first row's `W₀ = ⌈w₀·2³²⌉`
//! and `S = ⌈(dx/dy)·2³²⌉` are both rounded up, each by less than one, so
//! after `k` steps `0 ≤ A_k − w_k·2³² < k + 1`, and `⌊A_k / 2³²⌋ = ⌊w_k⌋`
//! whenever `k + 1 ≤ 2³²/(16·dy) = 2²⁸/dy`. An edge crosses at most
//! `⌈dy/16⌉` rows, so `k + 1 ≤ ⌈dy/16⌉`; the ends are `i16` units, so
//! `dy ≤ 65,535` and `⌈dy/16⌉ ≤ 4,096`, and `⌈dy/16⌉·dy ≤ 4,096·65,535 <
//! 2²⁸`. The condition holds on every row of every edge in range: there
//! is no fallback. The tests check the bound's corners (`dy` = 65,535 over
//! 4,096 rows, both slopes, vertical edges at the extreme columns).
//!
//! *The units.* `⌊16·w⌋ = ⌈16·v⌉ + 15` by the same argument in units (the
//! error condition is again `(k + 1)·dy ≤ 2²⁸`), so `⌈x − ½⌉` in 1/16 px
//! is `(A >> 28) − 15`; the whole units a row, `⌊16·dx/dy⌋`, are
//! `S >> 28`.
//!
//! *The set-up, with 32-bit divisions only.* The first row inside the clip
//! window is found directly, as `X₀ = ⌈16·v₀⌉` units and its error
//! `e₀ = X₀·dy − 16·v₀·dy ∈ [0, dy)` (one division, `i64` only when the
//! numerator leaves `i32`), so rows above the window cost nothing. With
//! `16·dx = q·dy + r`, `0 ≤ r < dy < 2¹⁶`:
//!
//! ```text
//! S  = q·2²⁸ + ⌈r·2²⁸ / dy⌉                 the ceiling < 2²⁸, as r < dy
//! W₀ = (X₀ + 16)·2²⁸ − ⌊(e₀ + 1)·2²⁸ / dy⌋  as 16·w₀ = X₀ + 16 − (e₀ + 1)/dy;
//!                                           the quotient ≤ 2²⁸ (= when e₀ + 1 = dy)
//! ```
//!
//! each quotient by long division in two 16-bit digits (`n·2¹²` and the
//! first remainder times 2¹⁶ fit `u32`). [`Edge::advance`] is `A += n·S`,
//! one multiplication, exact while the rows stay inside the edge; the
//! bounds of the pixels over a run of rows are those at its two ends.
//!
//! The widths of every quantity are in [`crate::fixed`].

use crate::fixed::{ceil_div_i64, ceil_div_rem1_i32, ceil_px, Vertex, HALF, ONE};

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

/// One polygon edge being stepped down the rows, as a wide DDA: one
/// 64-bit accumulator in pixels with 32 fraction bits, whose high word is
/// the pixel (the module docs prove it exact over the whole range).
///
/// # Limits
/// The ends are [`Vertex`]es (`i16` units), so an edge is at most 65,535
/// units high and crosses at most 4,096 rows, all in −2048..2048 (so its
/// rows are kept as `i16`, and the record is 24 bytes): the accumulator is
/// exact on every row of every such edge, with no fallback. Stepped past
/// its last row it follows the line, no longer exactly.
///
/// Storage for edges is owned by the caller (see
/// [`Rasterizer`](crate::raster::scan::Rasterizer)); [`Edge::EMPTY`] fills it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Edge {
    /// `⌈w·2³²⌉ + k·(S − (dx/dy)·2³²)` on the `k`-th row stepped, where
    /// `w = x − ½ + 1 − 1/(16·dy)` px: its high word is `⌈x − ½⌉`.
    acc: i64,
    /// `⌈(dx/dy)·2³²⌉`: the accumulator's step a row.
    slope: i64,
    /// First row sampled (inside the clip rows), in −2048..2048.
    top: i16,
    /// One past the last row sampled, in −2047..=2048.
    end: i16,
    /// Pixel of the crossing on the current row, the accumulator's high
    /// word; set by [`Edge::load_pixel`], and by the set-up to the first
    /// row's (the word is at hand there, where a zero takes an instruction
    /// more). Or, in a walk by the non-zero
    /// rule, that pixel times two plus the edge's direction
    /// ([`Stepper::load_wound`]), and from [`Stepper::new_wound`] until the
    /// first load the direction alone.
    pub(super) px: i32,
}

// The record's size as the docs give it (edge storage, the band table).
const _: () = assert!(core::mem::size_of::<Edge>() == 24);

/// `(⌊n·2²⁸ / d⌋, whether the division is exact)` for `0 ≤ n ≤ d` and
/// `1 ≤ d < 2¹⁶`, by long division in two 16-bit digits, each a 32-bit
/// division: `n·2¹²` ≤ 2²⁸ and the first remainder times 2¹⁶ < 2³² fit
/// `u32`. The quotient is at most 2²⁸ (when `n = d`).
#[inline(always)]
fn frac28(n: u32, d: u32) -> (u32, bool) {
    let hi = n << 12;
    let (h, r) = (hi / d, hi % d);
    let lo = r << 16;
    let (l, r) = (lo / d, lo % d);
    ((h << 16) + l, r == 0)
}

impl Edge {
    /// An unused slot.
    pub const EMPTY: Edge = Edge {
        acc: 0,
        slope: 0,
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
        // The first row's centre, `m ≥ 0` units below the upper end (as
        // `top ≥ ⌈(y0 − ½)/16⌉`; `m < 16` unless the clip cut the edge).
        let yc = top * ONE + HALF;
        let m = yc - y0;
        // (x − ½)·dy there is `num = (x0 − ½)·dy + m·dx`, exactly, and
        // `⌈num/dy⌉ = x0 − ½ + ⌈m·dx/dy⌉` with the same remainder. With
        // `m < 2¹⁵` and `|dx|, dy < 2¹⁶`, `m·dx` and `m·dx − dy` (as
        // `ceil_div_rem1_i32` needs) fit `i32`: one 32-bit
        // division, where a 64-bit one is a library call on a 32-bit
        // core. The bound is taken a little lower, `m − ½ < 0x7F00`: the
        // compiler tests `m − ½`, and 0x7F00 is an immediate of a Thumb-2
        // compare, where 2¹⁵ − ½ takes a register.
        let (x16, e) = if m - HALF < 0x7F00 {
            let (c, e) = ceil_div_rem1_i32(m * dx, dy);
            (x0 + (16 - HALF) + c, e)
        } else {
            Edge::first_row_wide(x0, m, dx, dy)
        };
        Some(Edge::stepping(x16, e, dx, dy, (top, end)))
    }

    /// `(x + 16, err + 1)` of [`Edge::new`]'s first row, `m ≥ 0x7F00 + ½`
    /// units below the upper end, in 64 bits (|num| < 2³³, see `fixed`);
    /// [`Edge::on_rows`]'s for any `m` outside `0..0x7F00` (its rows are
    /// within ±2048, so |num| < 2³³ too). Out of line: only an edge the
    /// clip cut more than 2,032 rows below its top takes it, and its
    /// library division, inlined into [`Edge::new`], takes registers and
    /// a stack slot there from every edge.
    #[cold]
    #[inline(never)]
    fn first_row_wide(x0: i32, m: i32, dx: i32, dy: i32) -> (i32, i32) {
        let num = (x0 - HALF) as i64 * dy as i64 + m as i64 * dx as i64;
        let x = ceil_div_i64(num, dy as i64);
        (x as i32 + 16, (x * dy as i64 - num) as i32 + 1)
    }

    /// The stepper over rows `rows.0..rows.1` of an edge of slope
    /// `dx / dy` (`1 ≤ dy < 2¹⁶`) crossing the first row at `x − err/dy`
    /// units (`x = ⌈·⌉`, `0 ≤ err < dy`), given `x16 = x + 16` and
    /// `e = err + 1`: the accumulator and its step, both rounded up (see
    /// the module docs), from `16·dx = q·dy + r`.
    #[inline(always)]
    fn stepping(x16: i32, e: i32, dx: i32, dy: i32, (top, end): (i32, i32)) -> Edge {
        // Rows of a `Vertex` edge (see the type's limits).
        let (top, end) = (top as i16, end as i16);
        // The floor: the truncated quotient less one when the truncated
        // remainder is negative (`>> 31` is that −1 or 0), and the
        // remainder again from it, a multiply-subtract, with no select.
        let n = ONE * dx;
        let (q, r) = (n / dy, n % dy);
        let q = q + (r >> 31);
        let r = n - q * dy;
        // S = q·2²⁸ + ⌈r·2²⁸/dy⌉ (r < dy keeps the ceiling below 2²⁸)
        // and W₀ = (X₀ + 16)·2²⁸ − ⌊(e₀ + 1)·2²⁸/dy⌋ (e₀ + 1 ≤ dy).
        let (d, e) = (dy as u32, e as u32);
        let (f, g) = if dy <= 1016 {
            // One 16-bit digit each, rounded the same ways: each errs by
            // less than 2¹², and an edge this short crosses at most 64
            // rows, so (k + 1)·2¹² ≤ 2²⁸/dy still holds on every row.
            let (n, m) = ((r as u32) << 16, e << 16);
            // The ceiling as `(n + d − 1)/d` (`n + d − 1 < 2²⁷`), not
            // `div_ceil`: one division, with no remainder or its test.
            #[allow(clippy::manual_div_ceil)]
            let f = (n + d - 1) / d;
            (f << 12, (m / d) << 12)
        } else {
            let (f, exact) = frac28(r as u32, d);
            (f + !exact as u32, frac28(e, d).0)
        };
        // `v·2²⁸` by its 32-bit words: `v >> 4` high and `v << 28` low.
        // The step's low words' carry moves its high word by one; the
        // accumulator is a 64-bit difference, a subtraction with borrow.
        let (lo, carry) = ((q as u32) << 28).overflowing_add(f);
        let slope = (((q >> 4) + carry as i32) as i64) << 32 | lo as i64;
        let acc = (((x16 >> 4) as i64) << 32 | ((x16 as u32) << 28) as i64) - g as i64;
        Edge {
            acc,
            slope,
            top,
            end,
            px: (acc >> 32) as i32,
        }
    }

    /// The pixel of the crossing on the current row: the accumulator's
    /// high word.
    #[inline(always)]
    fn now(&self) -> i32 {
        (self.acc >> 32) as i32
    }

    /// Computes [`Edge::pixel`] for the current row.
    #[inline(always)]
    #[doc(hidden)]
    pub fn load_pixel(&mut self) {
        self.px = self.now();
    }

    /// The first pixel whose centre is at or right of the crossing on the
    /// current row, as of the last [`Edge::load_pixel`].
    #[inline(always)]
    #[doc(hidden)]
    pub fn pixel(&self) -> i32 {
        self.px
    }

    /// The first pixel whose centre is at or right of the crossing on the
    /// current row, `⌈x − ½⌉`, read from the accumulator (no load needed).
    #[inline(always)]
    #[doc(hidden)]
    pub fn pixel_now(&self) -> i32 {
        self.now()
    }

    /// The crossing on the current row: `⌈x − ½⌉` in units of 1/16 px,
    /// `⌊16·w⌋ − 15` (module docs).
    #[inline(always)]
    #[doc(hidden)]
    pub fn units(&self) -> i32 {
        (self.acc >> 28) as i32 - 15
    }

    /// Whole units the crossing moves down a row, `⌊16·dx / dy⌋`: each
    /// [`Edge::step`] moves [`Edge::units`] by this or one more.
    #[inline(always)]
    #[doc(hidden)]
    pub fn step_units(&self) -> i32 {
        (self.slope >> 28) as i32
    }

    /// Moves to the next row: one 64-bit addition.
    #[inline(always)]
    #[doc(hidden)]
    pub fn step(&mut self) {
        self.acc = self.acc.wrapping_add(self.slope);
    }

    /// [`Edge::step`]: it has no carry to branch on, so the loops that
    /// step many unrelated edges take this same addition.
    #[inline(always)]
    #[doc(hidden)]
    pub fn step_masked(&mut self) {
        self.step();
    }

    /// Moves `n` rows down at once: the same state as `n` calls of
    /// [`Edge::step`], one multiplication. Exact for rows inside the edge;
    /// beyond them it follows the steps.
    #[inline]
    #[doc(hidden)]
    pub fn advance(&mut self, n: u32) {
        self.acc = self.acc.wrapping_add((n as i64).wrapping_mul(self.slope));
    }

    /// [`Edge::new`] for an edge from `(x0, y0)` to `(x1, y1)` (units,
    /// `y0 < y1`) over `rows`, rows whose centres it crosses, as a cut
    /// trapezoid's sides are stored: the same stepper, without the ends'
    /// order, the rows' bounds or their test, which the record already
    /// holds. Rows it does not cross give a stepper whose positions are
    /// the line's, not the edge's; ends with `y0 ≥ y1` give
    /// [`Edge::EMPTY`]. The ends are `i16` widened (so nothing here
    /// overflows, and `dy < 2¹⁶`), and `rows` inside the rows of such an
    /// edge, −2048..=2048. Not inlined: inlined into the entries
    /// (the sweep's and painting's), it cost the 3D demo more than the
    /// call (figures in `docs/performance-log.md`).
    #[inline(never)]
    pub(crate) fn on_rows(x0: i32, y0: i32, x1: i32, y1: i32, (top, end): (i32, i32)) -> Edge {
        let (dx, dy) = (x1 - x0, y1 - y0);
        if dy <= 0 {
            return Edge::EMPTY;
        }
        let yc = top * ONE + HALF;
        let m = yc - y0;
        // As in [`Edge::new`]: a first row `0 ≤ m < 0x7F00` units below
        // the upper end (every row of a trapezoid but those the clip
        // moved far down) takes one 32-bit division of `m·dx`, which
        // `|dx| < 2¹⁶` keeps within `i32` (`m·dx − dy` too).
        if (m as u32) < 0x7F00 {
            let (c, e) = ceil_div_rem1_i32(m * dx, dy);
            return Edge::stepping(x0 + (16 - HALF) + c, e, dx, dy, (top, end));
        }
        // A first row far below the upper end (or above it): `Edge::new`'s
        // 64-bit path, out of line.
        let (x16, e) = Edge::first_row_wide(x0, m, dx, dy);
        Edge::stepping(x16, e, dx, dy, (top, end))
    }

    /// Moves the stepper on to the rows `top..end` of the same edge that
    /// follow those it was made for (`top` one past its last row, where
    /// it stands): one step, and the rows. Its pixels are those of
    /// [`Edge::on_rows`] over `top..end` while the rows stay inside the
    /// edge's own: the accumulator errs by less than a step's rounding a
    /// row from the edge's first row sampled, as the bound in the
    /// [module](self) docs allows over all its rows.
    #[inline(always)]
    pub(crate) fn resume(&mut self, (top, end): (i32, i32)) {
        self.step();
        (self.top, self.end) = (top as i16, end as i16);
    }

    /// First row sampled.
    #[doc(hidden)]
    #[inline(always)]
    pub fn top(&self) -> i32 {
        self.top as i32
    }

    /// One past the last row sampled.
    #[doc(hidden)]
    #[inline(always)]
    pub fn end(&self) -> i32 {
        self.end as i32
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
        self.top as i32
    }
    #[inline(always)]
    fn end(&self) -> i32 {
        self.end as i32
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
        self.px = self.now() << 1 | (self.px & 1);
    }
    #[inline(always)]
    fn columns(&self, rows: i32) -> Option<(i32, i32)> {
        // The pixel is monotone down the rows, so the first and last rows'
        // bound it. Past 4,096 rows (more than an edge has) no bound is
        // given, which keeps (rows − 1)·S below 2⁶¹.
        if rows > 4096 {
            return None;
        }
        let last = self
            .acc
            .wrapping_add((rows - 1) as i64 * self.slope)
            .wrapping_shr(32) as i32;
        let first = self.now();
        Some((first.min(last), first.max(last)))
    }
    #[inline(always)]
    fn is_vertical(&self) -> bool {
        // The accumulator does not move.
        self.slope == 0
    }
    #[inline(always)]
    fn copy_from(&mut self, other: &Self) {
        // Field by field: loads and stores, never `memmove` or `memcpy`.
        let Edge {
            acc,
            slope,
            top,
            end,
            px,
        } = *other;
        (self.acc, self.slope) = (acc, slope);
        (self.top, self.end, self.px) = (top, end, px);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A xorshift generator from `seed`: each call a value in `-m..m`.
    fn xorshift(s: u32) -> impl FnMut(i32) -> i32 {
        let mut next = crate::rng::xorshift32(s);
        move |m| (next() % (2 * m as u32)) as i32 - m
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

    /// Every row of the edge `a`–`b` under the rows `rows`: the pixel is
    /// the definition's, [`Edge::pixel_now`] reads it without a load, and
    /// [`Edge::step_masked`] keeps the same state as [`Edge::step`]. The
    /// error-counter stepper this one replaced and `testkit`'s crossing
    /// check it too, in `host_tests/tests/edges.rs`.
    fn check_rows(a: Vertex, b: Vertex, rows: (i32, i32)) {
        let Some(mut e) = Edge::new(a, b, rows) else {
            return;
        };
        let mut masked = e;
        for j in e.top()..e.end() {
            e.load_pixel();
            assert_eq!(e.pixel(), direct(a, b, j), "{a:?} {b:?} row {j}");
            assert_eq!(e.pixel_now(), e.pixel());
            e.step();
            masked.load_pixel();
            masked.step_masked();
            assert_eq!(masked, e, "step_masked, {a:?} {b:?} row {j}");
        }
    }

    fn check(a: Vertex, b: Vertex) {
        check_rows(a, b, (i32::MIN, i32::MAX));
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
        // Far past the edge's rows (600,000 steps of about 2³² each)
        // the jump still equals the steps.
        let (a, b) = (
            Vertex::from_bits(i16::MIN, i16::MIN),
            Vertex::from_bits(28671, i16::MAX),
        );
        let e = Edge::new(a, b, (i32::MIN, i32::MAX)).unwrap();
        let n = 600_000;
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
    fn clipped_first_rows_match_the_definition() {
        // Edges the full height of the range, cut by clip rows on both
        // sides of the 32-bit path's bound, `yc − y0 − ½ < 0x7F00` (row
        // −17: 32,504; row −16: 32,520), and of `yc − y0 = 2¹⁵` (row −1:
        // 32,760; row 0: 32,776): the first row's crossing from the
        // 32-bit division and from the 64-bit one, at the steepest slopes
        // either way.
        for (ax, bx) in [(-32768, 32767), (32767, -32768), (0, 1), (-5, 3000)] {
            let a = Vertex::from_bits(ax, -32768);
            let b = Vertex::from_bits(bx, 32767);
            for top in (-20..-12).chain(-4..4) {
                check_rows(a, b, (top, top + 40));
                check_rows(b, a, (top, top + 40));
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
