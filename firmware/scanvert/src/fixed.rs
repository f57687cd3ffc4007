//! Fixed-point formats of the geometry.
//!
//! # Vertex coordinates: Q12.4
//!
//! A [`Coord`] is a signed 16-bit integer counting sixteenths of a pixel:
//! 12 integer bits (sign included) and 4 fraction bits. It holds every
//! multiple of 1/16 from −2048 to +2047.9375, and nothing else, so a value
//! that has been stored is always in range: there is no range check left to
//! forget.
//!
//! # Widths of the intermediates
//!
//! All scan conversion works in *units* of 1/16 px held in `i32`:
//!
//! | quantity | bound | bits |
//! |---|---|---|
//! | a coordinate | \[−2¹⁵, 2¹⁵) | 16 |
//! | `dx`, `dy` of an edge | \|·\| < 2¹⁶ | 17 |
//! | `16·dx` (the step numerator) | \|·\| < 2²⁰ | 21 |
//! | the set-up numerator `x·dy + t·dx` | \|·\| < 2³³ | `i64` |
//! | the edge's first-row error `e₀` | \[0, dy) | 16 |
//! | the edge's accumulator (px, 32 fraction bits) | \|·\| < 2⁴⁴ on the edge's rows | `i64` |
//! | the edge's slope (px a row, 32 fraction bits) | \|·\| < 2⁴⁸ | `i64` |
//!
//! The set-up of an edge needs `i64` for its numerator and builds the
//! accumulator and slope from 32-bit divisions; the per-row step is one
//! `i64` addition (see [`raster::edge`](crate::raster::edge)). The corners
//! of the range are exercised by tests built with overflow checks on.

/// Number of fraction bits of a [`Coord`].
pub const FRAC_BITS: u32 = 4;
/// Units per pixel (16).
pub const ONE: i32 = 1 << FRAC_BITS;
/// Half a pixel in units (8): the offset of a pixel centre.
pub const HALF: i32 = ONE / 2;

/// A subpixel coordinate in Q12.4 (sixteenths of a pixel).
///
/// # Guarantees
/// The value lies in \[−2048, 2047.9375\] and is a multiple of 1/16.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Coord(i16);

impl Coord {
    /// The smallest coordinate, −2048.
    pub const MIN: Coord = Coord(i16::MIN);
    /// The largest coordinate, 2047.9375.
    pub const MAX: Coord = Coord(i16::MAX);
    /// Zero.
    pub const ZERO: Coord = Coord(0);

    /// A coordinate from its raw value in sixteenths of a pixel.
    pub const fn from_bits(units: i16) -> Self {
        Coord(units)
    }

    /// A coordinate at a whole pixel, or `None` outside \[−2048, 2047\].
    pub const fn from_int(px: i32) -> Option<Self> {
        if px < -2048 || px > 2047 {
            None
        } else {
            Some(Coord((px * ONE) as i16))
        }
    }

    /// The raw value in sixteenths of a pixel.
    pub const fn to_bits(self) -> i16 {
        self.0
    }

    /// The value in sixteenths of a pixel, widened.
    pub const fn units(self) -> i32 {
        self.0 as i32
    }
}

/// A 2D vertex in subpixel coordinates: x to the right, y downward.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Vertex {
    /// Horizontal position.
    pub x: Coord,
    /// Vertical position (downward).
    pub y: Coord,
}

impl Vertex {
    /// A vertex from its two coordinates.
    pub const fn new(x: Coord, y: Coord) -> Self {
        Vertex { x, y }
    }

    /// A vertex from raw sixteenths of a pixel: every pair of `i16` is a
    /// vertex (from −2048 to 2047.9375 px on each axis).
    pub const fn from_bits(x: i16, y: i16) -> Self {
        Vertex {
            x: Coord(x),
            y: Coord(y),
        }
    }

    /// A vertex at whole pixels, or `None` when either coordinate lies
    /// outside −2048..=2047, the whole pixels of Q12.4.
    ///
    /// Out-of-range values are refused rather than clamped: a clamped
    /// vertex would draw a different polygon from the one asked for.
    ///
    /// ```
    /// use scanvert::fixed::Vertex;
    /// assert_eq!(Vertex::from_px(3, -2), Some(Vertex::from_bits(48, -32)));
    /// assert_eq!(Vertex::from_px(2047, -2048), Some(Vertex::from_bits(2047 * 16, i16::MIN)));
    /// assert_eq!(Vertex::from_px(2048, 0), None);
    /// assert_eq!(Vertex::from_px(0, -2049), None);
    /// ```
    pub const fn from_px(x: i16, y: i16) -> Option<Self> {
        match (Coord::from_int(x as i32), Coord::from_int(y as i32)) {
            (Some(x), Some(y)) => Some(Vertex { x, y }),
            _ => None,
        }
    }
}

/// A vertex in screen space with depth: x, y as [`Vertex`], larger `z` is
/// farther. `z` is in the same Q12.4 format.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Vertex3 {
    /// Horizontal position.
    pub x: Coord,
    /// Vertical position (downward).
    pub y: Coord,
    /// Depth; larger is farther.
    pub z: Coord,
}

impl Vertex3 {
    /// A vertex from its three coordinates.
    pub const fn new(x: Coord, y: Coord, z: Coord) -> Self {
        Vertex3 { x, y, z }
    }

    /// A vertex from raw sixteenths of a pixel (of depth, for `z`).
    pub const fn from_bits(x: i16, y: i16, z: i16) -> Self {
        Vertex3 {
            x: Coord(x),
            y: Coord(y),
            z: Coord(z),
        }
    }

    /// A vertex at whole pixels (whole depth units for `z`), or `None` when
    /// any coordinate lies outside −2048..=2047, as [`Vertex::from_px`].
    ///
    /// ```
    /// use scanvert::fixed::Vertex3;
    /// assert_eq!(Vertex3::from_px(1, 2, 3), Some(Vertex3::from_bits(16, 32, 48)));
    /// assert_eq!(Vertex3::from_px(1, 2, 2048), None);
    /// ```
    pub const fn from_px(x: i16, y: i16, z: i16) -> Option<Self> {
        match (
            Coord::from_int(x as i32),
            Coord::from_int(y as i32),
            Coord::from_int(z as i32),
        ) {
            (Some(x), Some(y), Some(z)) => Some(Vertex3 { x, y, z }),
            _ => None,
        }
    }

    /// The vertex without its depth.
    pub const fn xy(self) -> Vertex {
        Vertex {
            x: self.x,
            y: self.y,
        }
    }
}

/// `ceil(n / d)` for `d > 0`, exact for every `n`.
#[inline]
pub(crate) const fn ceil_div_i64(n: i64, d: i64) -> i64 {
    let q = n.div_euclid(d);
    if q * d == n {
        q
    } else {
        q + 1
    }
}

/// `(⌈n / d⌉, ⌈n / d⌉·d − n + 1)` for `d > 0` and `n > i32::MIN + d`:
/// the ceiling, and one more than how far its multiple lies past `n`, in
/// `1..=d`.
#[inline(always)]
pub(crate) const fn ceil_div_rem1_i32(n: i32, d: i32) -> (i32, i32) {
    // ⌈n/d⌉ = f + 1 for the floor f = ⌊(n − 1)/d⌋, and the distance plus
    // one is (f + 1)·d − (n − 1). Truncating, n − 1 = q·d + r with r of
    // n − 1's sign, so f = q − 1 when r < 0, else q: `r >> 31` is that −1
    // or 0, with no branch or select. `f·d − (n − 1)` is in −d..=0, and
    // f·d ≥ n − d > i32::MIN, so nothing overflows.
    let n1 = n - 1;
    let (q, r) = (n1 / d, n1 % d);
    let f = q + (r >> 31);
    (f + 1, f * d - n1 + d)
}

/// `ceil(units / 16)`: the whole pixel index at or above a unit position.
#[inline(always)]
pub(crate) const fn ceil_px(units: i32) -> i32 {
    (units + (ONE - 1)) >> FRAC_BITS
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ceil_px_matches_definition() {
        for u in -40_000..40_000 {
            let expect = ceil_div_i64(u as i64, ONE as i64) as i32;
            assert_eq!(ceil_px(u), expect, "u = {u}");
        }
    }

    #[test]
    fn ceil_div_rem1_i32_matches_i64() {
        let ns = [
            i32::MIN + 1,
            i32::MIN + 2,
            i32::MIN + 65_537,
            i32::MIN + 100_000,
            -65536,
            -17,
            -16,
            -1,
            0,
            1,
            15,
            16,
            17,
            65535,
            i32::MAX,
        ];
        let ds = [1, 2, 3, 7, 16, 65535, 65536, i32::MAX];
        for &n in &ns {
            for &d in &ds {
                if n as i64 <= i32::MIN as i64 + d as i64 {
                    continue;
                }
                let want = ceil_div_i64(n as i64, d as i64);
                let (q, e) = ceil_div_rem1_i32(n, d);
                assert_eq!(q as i64, want, "{n} / {d}");
                assert_eq!(e as i64, want * d as i64 - n as i64 + 1, "{n} / {d}");
            }
        }
    }

    #[test]
    fn coord_range_corners() {
        assert_eq!(Coord::MIN.units(), -2048 * 16);
        assert_eq!(Coord::MAX.units(), 2048 * 16 - 1);
        assert_eq!(Coord::from_int(2047).map(Coord::units), Some(2047 * 16));
        assert_eq!(Coord::from_int(2048), None);
        assert_eq!(Coord::from_int(-2048), Some(Coord::MIN));
        assert_eq!(Coord::from_int(-2049), None);
    }

    #[test]
    fn from_px_is_from_int_on_every_i16() {
        for p in i16::MIN..=i16::MAX {
            let c = Coord::from_int(p as i32);
            assert_eq!(c.is_some(), (-2048..=2047).contains(&p), "p = {p}");
            if let Some(c) = c {
                assert_eq!(c.units(), p as i32 * 16);
            }
            let v = Vertex::from_px(p, 0);
            assert_eq!(v.map(|v| v.x), c);
            assert_eq!(Vertex::from_px(0, p).map(|v| v.y), c);
            assert_eq!(Vertex3::from_px(0, 0, p).map(|v| v.z), c);
            assert_eq!(
                Vertex3::from_px(p, 1, 2).map(Vertex3::xy),
                v.map(|v| Vertex { y: Coord(16), ..v })
            );
        }
    }
}
