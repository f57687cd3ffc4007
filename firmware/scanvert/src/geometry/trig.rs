//! Angles, sines and square roots in integers.
//!
//! # Angles: binary, 65536 to the turn
//!
//! An [`Angle`] is a `u16` counting 1/65536 of a full turn (about 0.0055°).
//! Every `u16` is an angle, and adding or subtracting angles wraps, exactly
//! as turning does: there is no range to leave.
//!
//! # Sine and cosine: a quarter-wave table with linear interpolation
//!
//! [`sin`] and [`cos`] return Q16.16 in `i32` (65536 = 1.0), in
//! \[−65536, 65536\]. The table holds `sin` at the 257 points
//! `k · (π/2)/256`, `k = 0..=256`, in Q2.30, and is computed at compile time
//! from a Taylor series in `i128` integers (no table typed in by hand). An
//! angle picks its quadrant from its top two bits, a table interval from the
//! next eight, and interpolates linearly with the low six bits (`i32`: a
//! table step is below 2²³, times 63 below 2²⁹).
//!
//! The error against the true sine, over all 65536 angles, is at most
//! `h²/8 ≈ 4.71·10⁻⁶` from the interpolation (`h = π/512`), plus half a
//! Q16.16 step (7.63·10⁻⁶) from the final rounding: below **1.3·10⁻⁵**, less
//! than one Q16.16 step. The endpoints are exact: `sin` of 0, ¼, ½ and ¾ of
//! a turn is 0, 1, 0 and −1. The host tests compare every angle with a
//! double-precision reference.
//!
//! # Arctangent
//!
//! [`atan2`] finds the angle of a vector by bisection over the first
//! quadrant of the same table (14 steps, each comparing `sin·|x|` with
//! `cos·|y|` after both are scaled to 15 bits, `i64` products), then
//! places it in its quadrant. It is meant for set-up, such as aiming a
//! camera ([`View::look_at`](super::View::look_at)), not for per-vertex
//! work. Its result is within two binary units (0.011°) of the true angle.
//!
//! # Integer square root
//!
//! [`isqrt`] is `⌊√v⌋` for a `u32`, by Newton's method from a power of two
//! above the root: a handful of steps, each one 32-bit division. Lighting and the line
//! primitive scale their vectors below 2¹⁵ per component first, so their
//! squared lengths fit in `u32`.

use core::ops::{Add, Neg, Sub};

/// An angle in binary units: 65536 to the turn.
///
/// # Guarantees
/// Every `u16` is a valid angle; arithmetic wraps around the turn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Angle(u16);

impl Angle {
    /// No rotation.
    pub const ZERO: Angle = Angle(0);
    /// A quarter turn, 90°.
    pub const QUARTER: Angle = Angle(0x4000);
    /// Half a turn, 180°.
    pub const HALF: Angle = Angle(0x8000);

    /// An angle from its raw value, 65536 to the turn.
    pub const fn from_bits(bits: u16) -> Self {
        Angle(bits)
    }

    /// The raw value, 65536 to the turn.
    pub const fn to_bits(self) -> u16 {
        self.0
    }

    /// The nearest binary angle to `deg` degrees; any `i32`, taken modulo
    /// 360 (`i64` intermediate: `|deg mod 360| · 65536 < 2²⁵`).
    pub const fn from_degrees(deg: i32) -> Self {
        let d = (deg as i64).rem_euclid(360);
        Angle(((d * 65536 + 180) / 360) as u16)
    }

    /// The nearest binary angle to `num / den` of a full turn, or `None`
    /// when `den` is zero. Any `i32` values; `i64` intermediates.
    pub const fn from_turns(num: i32, den: i32) -> Option<Self> {
        if den == 0 {
            return None;
        }
        let (n, d) = if den < 0 {
            (-(num as i64), -(den as i64))
        } else {
            (num as i64, den as i64)
        };
        // n · 65536 + d/2 < 2⁴⁹; floor division, then wrap to 16 bits.
        let q = (n * 65536 + d / 2).div_euclid(d);
        Some(Angle(q as u16))
    }
}

impl Add for Angle {
    type Output = Angle;
    fn add(self, rhs: Angle) -> Angle {
        Angle(self.0.wrapping_add(rhs.0))
    }
}

impl Sub for Angle {
    type Output = Angle;
    fn sub(self, rhs: Angle) -> Angle {
        Angle(self.0.wrapping_sub(rhs.0))
    }
}

impl Neg for Angle {
    type Output = Angle;
    fn neg(self) -> Angle {
        Angle(self.0.wrapping_neg())
    }
}

/// Table points per quarter turn.
const STEPS: usize = 256;
/// Binary-angle units per table step (16384 / 256).
const STEP_BITS: u32 = 6;

/// π · 2⁶², rounded.
const PI_Q62: i128 = 14_488_038_916_154_245_685;

/// `sin(k · (π/2) / 256)` in Q2.30, rounded, by a Taylor series in Q62.
const fn sin_q30(k: usize) -> i32 {
    // x = k·π/512 < 1.571 in Q62, so x² < 2¹²⁶ fits i128.
    let x = PI_Q62 * k as i128 / 512;
    let x2 = (x * x) >> 62;
    let mut term = x;
    let mut sum = x;
    let mut n: i128 = 1;
    while term != 0 {
        // term < 2⁶³ and x2 < 2⁶³: the product fits i128.
        term = -((term * x2) >> 62) / ((n + 1) * (n + 2));
        sum += term;
        n += 2;
    }
    ((sum + (1 << 31)) >> 32) as i32
}

const fn build_table() -> [i32; STEPS + 1] {
    let mut t = [0i32; STEPS + 1];
    let mut k = 0;
    while k <= STEPS {
        t[k] = sin_q30(k);
        k += 1;
    }
    t
}

/// `sin` over a quarter turn, 257 points in Q2.30 (1 028 bytes).
static QUARTER_SINE: [i32; STEPS + 1] = build_table();

/// `sin` of `r` units into the first quadrant, `r` in `0..=16384`, Q2.30.
#[inline]
fn quarter(r: u32) -> i32 {
    let i = (r >> STEP_BITS) as usize;
    let f = (r & ((1 << STEP_BITS) - 1)) as i32;
    match (QUARTER_SINE.get(i), QUARTER_SINE.get(i + 1)) {
        (Some(&a), Some(&b)) => a + (((b - a) * f + (1 << (STEP_BITS - 1))) >> STEP_BITS),
        (Some(&a), None) => a,
        // `r` never exceeds 16384; the table ends at index 256.
        _ => 1 << 30,
    }
}

/// The sine of `a` in Q16.16, in \[−65536, 65536\]; error below 1.3·10⁻⁵.
pub fn sin(a: Angle) -> i32 {
    let bits = a.0 as u32;
    let r = bits & 0x3FFF;
    let v = match bits >> 14 {
        0 | 2 => quarter(r),
        _ => quarter(0x4000 - r),
    };
    // Q30 to Q16, rounding half up on the magnitude (so sin(−a) = −sin a);
    // 0 ≤ v ≤ 2³⁰.
    let v = (v + (1 << 13)) >> 14;
    if bits >> 15 == 0 {
        v
    } else {
        -v
    }
}

/// The cosine of `a` in Q16.16, in \[−65536, 65536\]; error below 1.3·10⁻⁵.
pub fn cos(a: Angle) -> i32 {
    sin(a + Angle::QUARTER)
}

/// The angle of the vector `(x, y)`, counter-clockwise from +x toward +y;
/// zero for the zero vector. Any `i64` values.
pub fn atan2(y: i64, x: i64) -> Angle {
    let m = x.unsigned_abs().max(y.unsigned_abs());
    if m == 0 {
        return Angle::ZERO;
    }
    // Both magnitudes to at most 15 bits, by the same shift.
    let shift = (64 - m.leading_zeros()).saturating_sub(15);
    let (ax, ay) = (
        (x.unsigned_abs() >> shift) as i64,
        (y.unsigned_abs() >> shift) as i64,
    );
    // The largest a in [0, ¼ turn] with sin(a)·ax ≤ cos(a)·ay (tan a ≤ ay/ax).
    let (mut lo, mut hi) = (0u16, 0x4000u16);
    while lo < hi {
        let mid = lo + (hi - lo).div_ceil(2);
        let a = Angle(mid);
        if sin(a) as i64 * ax <= cos(a) as i64 * ay {
            lo = mid;
        } else {
            hi = mid - 1;
        }
    }
    // Round to the nearer of lo and lo + 1.
    let a = if lo < 0x4000 {
        let (e0, e1) = (
            (sin(Angle(lo)) as i64 * ax - cos(Angle(lo)) as i64 * ay).abs(),
            (sin(Angle(lo + 1)) as i64 * ax - cos(Angle(lo + 1)) as i64 * ay).abs(),
        );
        if e1 < e0 {
            lo + 1
        } else {
            lo
        }
    } else {
        lo
    };
    let a = Angle(a);
    match (x >= 0, y >= 0) {
        (true, true) => a,
        (false, true) => Angle::HALF - a,
        (false, false) => Angle::HALF + a,
        (true, false) => -a,
    }
}

/// `⌊√v⌋`, exact for every `u32`.
pub const fn isqrt(v: u32) -> u16 {
    if v == 0 {
        return 0;
    }
    // Newton's method, its first step taken by shifts from the power of
    // two 2ᵏ at or below the root (2²ᵏ ≤ v < 2²ᵏ⁺²): any step lands at
    // or above ⌊√v⌋, here within 5/4 of it. The iterates then fall
    // monotonically to ⌊√v⌋ and stop (x ≤ 2¹⁶ + 2¹⁴ and v / x ≤ 2¹⁶ + 1,
    // so the sums fit).
    let k = (31 - v.leading_zeros()) / 2;
    let mut x = ((v >> k) + (1 << k)) / 2;
    loop {
        let y = (x + v / x) / 2;
        if y >= x {
            return x as u16;
        }
        x = y;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_points() {
        assert_eq!(sin(Angle::ZERO), 0);
        assert_eq!(sin(Angle::QUARTER), 65536);
        assert_eq!(sin(Angle::HALF), 0);
        assert_eq!(sin(Angle::from_bits(0xC000)), -65536);
        assert_eq!(cos(Angle::ZERO), 65536);
        assert_eq!(cos(Angle::HALF), -65536);
        assert_eq!(QUARTER_SINE[0], 0);
        assert_eq!(QUARTER_SINE[STEPS], 1 << 30);
        // sin²(π/4) · 2 = 1, within the table's rounding.
        let s45 = QUARTER_SINE[128] as i64;
        let sq = s45 * s45 * 2;
        assert!((sq - (1i64 << 60)).abs() < 1i64 << 32);
    }

    #[test]
    fn symmetric_and_monotone() {
        let mut prev = -1;
        for b in 0..=0x4000u32 {
            let s = sin(Angle::from_bits(b as u16));
            assert!(s >= prev, "not monotone at {b}");
            prev = s;
        }
        for b in 0..=u16::MAX {
            let a = Angle::from_bits(b);
            assert_eq!(sin(-a), -sin(a), "odd at {b}");
            assert_eq!(cos(-a), cos(a), "even at {b}");
        }
    }

    #[test]
    fn pythagoras_holds_closely() {
        for b in (0..=u16::MAX).step_by(7) {
            let a = Angle::from_bits(b);
            let (s, c) = (sin(a) as i64, cos(a) as i64);
            let one = s * s + c * c;
            // Each of s, c within 0.85 of a Q16.16 step: s² + c² within
            // 2 · 65536 · 0.85 · √2 < 160 000 of 2³².
            assert!((one - (1i64 << 32)).abs() < 160_000, "b = {b}: {one}");
        }
    }

    #[test]
    fn degrees_and_turns() {
        assert_eq!(Angle::from_degrees(90), Angle::QUARTER);
        assert_eq!(Angle::from_degrees(-90), Angle::from_bits(0xC000));
        assert_eq!(Angle::from_degrees(360), Angle::ZERO);
        assert_eq!(Angle::from_degrees(i32::MIN).to_bits(), {
            let d = (i32::MIN as i64).rem_euclid(360);
            ((d * 65536 + 180) / 360) as u16
        });
        assert_eq!(
            Angle::from_degrees(i32::MAX),
            Angle::from_degrees(i32::MAX % 360)
        );
        assert_eq!(Angle::from_turns(1, 4), Some(Angle::QUARTER));
        assert_eq!(Angle::from_turns(-1, -2), Some(Angle::HALF));
        assert_eq!(Angle::from_turns(1, 0), None);
        assert!(Angle::from_turns(i32::MIN, -1).is_some());
        assert!(Angle::from_turns(i32::MAX, 3).is_some());
    }

    #[test]
    fn arctangents() {
        assert_eq!(atan2(0, 0), Angle::ZERO);
        assert_eq!(atan2(0, 5), Angle::ZERO);
        assert_eq!(atan2(5, 0), Angle::QUARTER);
        assert_eq!(atan2(0, -5), Angle::HALF);
        assert_eq!(atan2(-5, 0), Angle::from_bits(0xC000));
        assert_eq!(atan2(7, 7), Angle::from_bits(0x2000));
        assert_eq!(atan2(-7, -7), Angle::from_bits(0xA000));
        for (y, x) in [
            (i64::MAX, i64::MIN),
            (i64::MIN, i64::MAX),
            (1, i64::MAX),
            (i64::MIN, 1),
        ] {
            let a = atan2(y, x);
            // Back through sin and cos: the direction matches.
            let (s, c) = (sin(a) as i128, cos(a) as i128);
            let cross = c * (y >> 40) as i128 - s * (x >> 40) as i128;
            assert!(cross.abs() < (1i128 << 40), "{y} {x} {a:?}");
        }
        // Every angle survives a round trip within two units.
        for b in (0..=u16::MAX).step_by(13) {
            let a = Angle::from_bits(b);
            let back = atan2(sin(a) as i64 * 1000, cos(a) as i64 * 1000);
            let d = back.to_bits().wrapping_sub(b) as i16;
            assert!(d.abs() <= 2, "{b}: {d}");
        }
    }

    #[test]
    fn isqrt_is_floor_sqrt() {
        for v in 0..100_000u32 {
            let r = isqrt(v) as u64;
            assert!(r * r <= v as u64 && (r + 1) * (r + 1) > v as u64, "{v}");
        }
        for v in [
            u32::MAX,
            u32::MAX - 1,
            1 << 31,
            (1 << 30) - 1,
            65535 * 65535,
        ] {
            let r = isqrt(v) as u64;
            assert!(r * r <= v as u64 && (r + 1) * (r + 1) > v as u64, "{v}");
        }
        // Around every power of two and every square, and at random.
        let mut next = crate::rng::xorshift32(0x2545_f491);
        for i in 0..2_000_000u32 {
            let seed = next();
            let r0 = i % 65536;
            for v in [
                seed,
                seed >> (i % 32),
                (1u32 << (i % 32)).wrapping_add(i % 3).wrapping_sub(1),
                (r0 * r0).wrapping_add(i % 3).wrapping_sub(1),
            ] {
                let r = isqrt(v) as u64;
                assert!(r * r <= v as u64 && (r + 1) * (r + 1) > v as u64, "{v}");
            }
        }
    }
}
