//! Approximate alternatives to the exact edge stepper: the classic DDA,
//! and vertices snapped to a coarser grid.
//!
//! They buy little speed now, and only on some polygons: on the host
//! benchmark's workloads the exact stepper is as fast as they are or
//! faster, except on many thin slivers (W6), where they are a few per
//! cent faster. `docs/performance.md` (the speed-against-error table)
//! gives each one's rate and error beside the exact path's, measured in
//! one run; measure your own polygons before you trade exactness.
//!
//! The exact [`Edge`](crate::raster::edge::Edge) is a DDA too, with 32
//! fraction bits and both roundings upwards, which is enough for every
//! crossing to be rounded exactly as the pixel rule asks. The steppers
//! here hold `x` in fewer fraction bits and add a slope `dx/dy` rounded to
//! the nearest once per row, in 32-bit words: each row adds the slope's
//! rounding error to `x`, which costs accuracy.
//!
//! Both steppers here select rows exactly as the pixel rule does (a row's
//! centre in `[y₀, y₁)`, with the same clipping to the window's rows), so
//! only the column of a crossing can differ from the exact one.
//!
//! | stepper | `x` held in | error after `k` rows, in px | per row |
//! |---|---|---|---|
//! | [`Edge`](crate::raster::edge::Edge) | 2⁻³² px, `i64`, rounded up | 0 | 1 `i64` add |
//! | [`Dda7`] | 1/128 px (7 fraction bits) | `≤ (k + 1)/256` | 1 add |
//! | [`Dda16`] | 1/65536 px (16.16) | `≤ (k + 1)/131072` | 1 add |
//!
//! The start value and the slope are each rounded to the nearest step, so
//! each is off by at most half a step; the first row's crossing is computed
//! directly (one division), so rows above the clip window add no error.
//! A pixel comes out wrong only where the exact crossing lies within that
//! bound of a pixel centre. Crossings exactly on a pixel centre are
//! common (vertices sit on a 1/16 grid), so even the 16.16 stepper misses
//! some of them: an error of either sign moves such a crossing across the
//! centre. [`Dda7`] on a 256-row edge may be off by a whole pixel.
//!
//! [`snap`] is the other option: fewer subpixel bits in the vertices
//! (1/4 px or whole pixels) before the exact stepper. The pixels are then
//! exact for the snapped polygon, and the error is the snapping's.

use crate::fixed::{ceil_px, Vertex, FRAC_BITS, HALF, ONE};
use crate::raster::edge::Stepper;

/// `round(n / d)` for `d > 0`, halves rounded up.
#[inline]
const fn round_div_i64(n: i64, d: i64) -> i64 {
    (2 * n + d).div_euclid(2 * d)
}

/// An edge stepped by the classic DDA with `x` in fixed point with `F`
/// fraction bits, `x += dx/dy` once per row, no error counter.
///
/// Use it through the aliases [`Dda7`] and [`Dda16`]; `F` must be at least
/// [`FRAC_BITS`] (4) and at most 16.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dda<const F: u32> {
    /// `x` at the current row's centre, in units of `2^-F` px.
    x: i32,
    /// `dx/dy` per row, in units of `2^-F` px, rounded to nearest.
    slope: i32,
    /// First row sampled.
    top: i32,
    /// One past the last row sampled.
    end: i32,
    /// Pixel of the crossing on the current row; in a walk by the non-zero
    /// rule, times two plus the edge's direction
    /// ([`Stepper::load_wound`]), and the direction alone from
    /// [`Stepper::new_wound`] until the first load.
    px: i32,
}

/// The DDA at 1/128 px: `x` with 7 fraction bits. 20 bytes a slot.
pub type Dda7 = Dda<7>;

/// The DDA in 16.16 fixed point. 20 bytes a slot.
pub type Dda16 = Dda<16>;

impl<const F: u32> Dda<F> {
    /// An unused slot.
    pub const EMPTY: Self = Dda {
        x: 0,
        slope: 0,
        top: 0,
        end: 0,
        px: 0,
    };

    /// Checked at compile time for each `F` used.
    const F_IN_RANGE: () = assert!(F >= FRAC_BITS && F <= 16);

    /// The edge from `a` to `b` restricted to rows `rows.0..rows.1`, or
    /// `None` when it crosses no row centre there.
    #[inline]
    pub fn new(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        #[allow(clippy::let_unit_value)]
        let () = Self::F_IN_RANGE;
        let (mut p, mut q) = (a, b);
        if p.y.units() > q.y.units() {
            core::mem::swap(&mut p, &mut q);
        }
        let (x0, y0, x1, y1) = (p.x.units(), p.y.units(), q.x.units(), q.y.units());
        let top = ceil_px(y0 - HALF).max(rows.0);
        let end = ceil_px(y1 - HALF).min(rows.1);
        if top >= end {
            return None;
        }
        let (dx, dy) = (x1 as i64 - x0 as i64, y1 as i64 - y0 as i64);
        // Units (1/16 px) to the stepper's 2^-F px.
        let up = F - FRAC_BITS;
        let yc = (top * ONE + HALF) as i64;
        // |(yc − y0)·dx| < 2^32, shifted by at most 12: fits i64.
        let x = ((x0 as i64) << up) + round_div_i64(((yc - y0 as i64) * dx) << up, dy);
        // One row is ONE units of y. The slope only matters when the edge
        // spans two rows, so dy > ONE and |slope| < 2^(F + 16) / 16 ≤ 2^28.
        let slope = round_div_i64((dx * ONE as i64) << up, dy);
        Some(Dda {
            x: x as i32,
            slope: i32::try_from(slope).unwrap_or(0),
            top,
            end,
            px: 0,
        })
    }
}

impl<const F: u32> Stepper for Dda<F> {
    #[inline]
    fn new(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        Dda::new(a, b, rows)
    }
    #[inline(always)]
    fn top(&self) -> i32 {
        self.top
    }
    #[inline(always)]
    fn end(&self) -> i32 {
        self.end
    }
    /// `⌈x − ½⌉` in pixels: `(x + 2^(F−1) − 1) >> F`.
    #[inline(always)]
    fn load_pixel(&mut self) {
        self.px = (self.x + ((1 << (F - 1)) - 1)) >> F;
    }
    #[inline(always)]
    fn pixel(&self) -> i32 {
        self.px
    }
    #[inline(always)]
    fn step(&mut self) {
        self.x += self.slope;
    }
    #[inline]
    fn new_wound(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        let mut e = Dda::new(a, b, rows)?;
        e.px = (a.y.units() > b.y.units()) as i32;
        Some(e)
    }
    #[inline(always)]
    fn load_wound(&mut self) {
        self.px = ((self.x + ((1 << (F - 1)) - 1)) >> F) << 1 | (self.px & 1);
    }
}

/// `v` with each coordinate rounded to the nearest multiple of
/// `2^-frac_bits` px (halves up; the top of the range rounds down so the
/// result stays representable). `frac_bits` of 4 or more leaves `v` as it
/// is; 2 gives quarter pixels, 0 whole pixels.
#[inline]
pub fn snap(v: Vertex, frac_bits: u32) -> Vertex {
    if frac_bits >= FRAC_BITS {
        return v;
    }
    let s = FRAC_BITS - frac_bits;
    let max = (i16::MAX as i32 >> s) << s;
    let one = |u: i32| (((u + (1 << (s - 1))) >> s) << s).min(max) as i16;
    Vertex::from_bits(one(v.x.units()), one(v.y.units()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::edge::Edge;
    use testkit::rng::Rng;

    /// Walks a DDA edge beside the exact one: same rows, and the pixel is
    /// within the documented bound of the exact crossing.
    fn within_bound<const F: u32>(a: Vertex, b: Vertex) {
        let rows = (-2048, 2048);
        let (Some(mut e), d) = (Edge::new(a, b, rows), Dda::<F>::new(a, b, rows)) else {
            assert!(Dda::<F>::new(a, b, rows).is_none());
            return;
        };
        let mut d = d.unwrap();
        assert_eq!((Stepper::top(&d), Stepper::end(&d)), (e.top(), e.end()));
        for k in 0..(e.end() - e.top()) {
            Stepper::load_pixel(&mut e);
            Stepper::load_pixel(&mut d);
            // Exact crossing X − err/dy in units; DDA x in 2^-F px. Compare
            // in 2^-F px scaled by dy: |x_dda − x_exact| ≤ (k + 1)/2 steps.
            let up = F - FRAC_BITS;
            let exact_minus_half = (e.units() as i64) << up; // ⌈x − ½⌉ (upper bound)
            let x = d.x as i64 - (1 << (F - 1));
            let slack = (k as i64 + 1) / 2 + 1 + (1 << up);
            assert!(
                (x - exact_minus_half).abs() <= slack,
                "{a:?} {b:?} row {k}: {x} vs {exact_minus_half}"
            );
            let diff = (Stepper::pixel(&d) - Stepper::pixel(&e)).abs();
            assert!(diff <= 1 + (k + 1) / (1 << F), "{a:?} {b:?} row {k}");
            if k + 1 < e.end() - e.top() {
                Stepper::step(&mut e);
                Stepper::step(&mut d);
            }
        }
    }

    #[test]
    fn dda_stays_within_its_error_bound() {
        let mut rng = Rng(0x9e37_79b9);
        let mut v =
            || Vertex::from_bits(rng.range(-8000, 8000) as i16, rng.range(-8000, 8000) as i16);
        for _ in 0..3000 {
            let (a, b) = (v(), v());
            within_bound::<7>(a, b);
            within_bound::<16>(a, b);
        }
    }

    #[test]
    fn dda_range_corners_do_not_overflow() {
        let m = [i16::MIN, i16::MIN + 1, -1, 0, 1, i16::MAX - 1, i16::MAX];
        for &ax in &m {
            for &ay in &m {
                for &bx in &m {
                    for &by in &m {
                        let (a, b) = (Vertex::from_bits(ax, ay), Vertex::from_bits(bx, by));
                        within_bound::<7>(a, b);
                        within_bound::<16>(a, b);
                    }
                }
            }
        }
    }

    #[test]
    fn snap_rounds_to_the_grid_and_stays_in_range() {
        let v = |x: i16, y: i16| Vertex::from_bits(x, y);
        assert_eq!(snap(v(5, 6), 2), v(4, 8));
        assert_eq!(snap(v(7, -9), 0), v(0, -16));
        assert_eq!(snap(v(8, -8), 0), v(16, 0));
        assert_eq!(snap(v(i16::MAX, i16::MIN), 0), v(i16::MAX - 15, i16::MIN));
        assert_eq!(snap(v(i16::MAX, 3), 2), v(i16::MAX - 3, 4));
        assert_eq!(snap(v(123, -77), 4), v(123, -77));
    }
}
