//! Model space to view space: points, matrices, the transform stack and the
//! camera.
//!
//! # Model and world coordinates: Q16.16
//!
//! A [`Q16`] is an `i32` counting 1/65536 of a unit: 16 integer bits (sign
//! included) and 16 fraction bits, from −32768 to 32767.99998. A
//! [`Point3`] holds three of them. Units are the application's (metres,
//! map cells, …); only the projection relates them to pixels.
//!
//! # View space
//!
//! The transform takes a model point to *view space*: x to the right, y
//! **down** and z forward, away from the eye, which sits at the origin.
//! This frame is right-handed, and it is the screen's orientation with
//! depth added, so the projection needs no sign changes. The world of
//! [`View`] is the usual right-handed one with y up; its matrix turns the
//! world half a turn about x to get there.
//!
//! Every view-space coordinate must lie in **(−16384, 16384)** units, that
//! is `|raw| < 2³⁰` ([`VIEW_LIMIT`]). A point that lands outside is not
//! clamped: [`Matrix::transform`] reports [`TransformError::Range`], and the
//! pipeline rejects the whole polygon with that error. Keeping world and
//! eye within ±8192 units of each other is always enough for rigid
//! transforms.
//!
//! # Matrices: Q16.16 entries, `i64` products
//!
//! A [`Matrix`] is the top three rows of a 4 × 4 affine matrix: a 3 × 3
//! linear part and a translation column, all Q16.16 in `i32`. The linear
//! entries are limited to `|m| ≤ 2³⁰` (±16384.0, [`Matrix::LINEAR_LIMIT`]);
//! the translation may be any `i32`.
//!
//! | quantity | bound | width |
//! |---|---|---|
//! | linear entry × coordinate or translation | ≤ 2³⁰ · 2³¹ = 2⁶¹ | `i64` |
//! | sum of three, plus translation · 2¹⁶ | ≤ 3 · 2⁶¹ + 2⁴⁷ < 2⁶³ | `i64` |
//! | linear entry × linear entry, three summed | ≤ 3 · 2⁶⁰ | `i64` |
//! | result, rounded (`+2¹⁵`, `>> 16`) | checked against its limit | `i32` |
//!
//! Composition ([`Matrix::checked_mul`]) and point transforms round to
//! nearest. A product whose entry leaves its limit is reported as
//! [`TransformError::Range`] and leaves the matrix as it was.
//!
//! # The stack
//!
//! [`TransformStack`] works like OpenGL's model-view stack: each call
//! post-multiplies the current matrix, so the transform written *last*
//! acts on the model *first*. `push` saves the current matrix and `pop`
//! restores it; the depth is a const generic, and overflow and underflow
//! are errors, not panics.

use super::light::ZeroDirection;
use super::trig::{atan2, cos, sin, Angle};
use core::fmt;

/// Raw view-space bound: every coordinate satisfies `|raw| < VIEW_LIMIT`.
pub const VIEW_LIMIT: i32 = 1 << 30;

/// A number in Q16.16: an `i32` counting 1/65536 of a unit.
///
/// # Guarantees
/// Every `i32` is a valid value, from −32768 to 32767.99998.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Q16(i32);

impl Q16 {
    /// Zero.
    pub const ZERO: Q16 = Q16(0);
    /// One unit.
    pub const ONE: Q16 = Q16(1 << 16);
    /// The smallest value, −32768.
    pub const MIN: Q16 = Q16(i32::MIN);
    /// The largest value, 32767.99998.
    pub const MAX: Q16 = Q16(i32::MAX);

    /// A value from its raw form, in 1/65536 of a unit.
    pub const fn from_bits(bits: i32) -> Self {
        Q16(bits)
    }

    /// A whole number of units (every `i16` is exact).
    pub const fn from_int(units: i16) -> Self {
        Q16((units as i32) << 16)
    }

    /// The nearest value to `num / den`, or `None` when `den` is zero or
    /// the quotient is outside the range (`i64` intermediates).
    pub const fn from_ratio(num: i32, den: i32) -> Option<Self> {
        if den == 0 {
            return None;
        }
        let (n, d) = if den < 0 {
            (-(num as i64), -(den as i64))
        } else {
            (num as i64, den as i64)
        };
        // |n| · 2¹⁶ < 2⁴⁸.
        let q = ((n << 16) + d / 2).div_euclid(d);
        if q < i32::MIN as i64 || q > i32::MAX as i64 {
            None
        } else {
            Some(Q16(q as i32))
        }
    }

    /// The raw value, in 1/65536 of a unit.
    pub const fn to_bits(self) -> i32 {
        self.0
    }

    /// `-self`, or `None` for [`Q16::MIN`].
    pub const fn checked_neg(self) -> Option<Self> {
        match self.0.checked_neg() {
            Some(v) => Some(Q16(v)),
            None => None,
        }
    }
}

/// A point (or a direction) in model, world or view space, in Q16.16.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Point3 {
    /// x: right in view space.
    pub x: Q16,
    /// y: up in the world of [`View`], down in view space.
    pub y: Q16,
    /// z: toward the viewer in the world of [`View`], depth in view space.
    pub z: Q16,
}

impl Point3 {
    /// The origin.
    pub const ORIGIN: Point3 = Point3::from_bits(0, 0, 0);

    /// A point from three Q16.16 values.
    pub const fn new(x: Q16, y: Q16, z: Q16) -> Self {
        Point3 { x, y, z }
    }

    /// A point at whole units.
    pub const fn from_int(x: i16, y: i16, z: i16) -> Self {
        Point3::new(Q16::from_int(x), Q16::from_int(y), Q16::from_int(z))
    }

    /// A point from raw Q16.16 values.
    pub const fn from_bits(x: i32, y: i32, z: i32) -> Self {
        Point3::new(Q16(x), Q16(y), Q16(z))
    }

    /// The raw coordinates.
    pub const fn to_bits(self) -> [i32; 3] {
        [self.x.0, self.y.0, self.z.0]
    }
}

/// Why a transform could not be applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum TransformError {
    /// `push` on a full stack.
    StackOverflow {
        /// Matrices the stack can save.
        depth: usize,
    },
    /// `pop` on an empty stack.
    StackUnderflow,
    /// A matrix entry or a transformed coordinate fell outside its
    /// documented range. The matrix is unchanged.
    Range,
}

impl fmt::Display for TransformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TransformError::StackOverflow { depth } => {
                write!(f, "transform stack full ({depth} matrices saved)")
            }
            TransformError::StackUnderflow => write!(f, "pop on an empty transform stack"),
            TransformError::Range => write!(f, "transform result outside the fixed-point range"),
        }
    }
}

impl core::error::Error for TransformError {}

/// An affine transform: a 3 × 3 linear part and a translation, Q16.16.
///
/// Row `r` is `[m_r0, m_r1, m_r2, t_r]`, and a point `p` maps to
/// `M · p + t`.
///
/// # Guarantees
/// Every linear entry satisfies `|m| ≤ 2³⁰` ([`Matrix::LINEAR_LIMIT`]);
/// translations are any `i32`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[doc(hidden)]
pub struct Matrix {
    rows: [[i32; 4]; 3],
}

impl Default for Matrix {
    fn default() -> Self {
        Matrix::IDENTITY
    }
}

const ONE: i32 = 1 << 16;
const HALF: i64 = 1 << 15;

/// `(s + ½) >> 16` into `i32` if it fits there.
#[inline]
fn round16(s: i64) -> Option<i32> {
    i32::try_from((s + HALF) >> 16).ok()
}

impl Matrix {
    /// Largest magnitude of a linear entry (raw): 2³⁰, i.e. 16384.0.
    pub const LINEAR_LIMIT: i32 = 1 << 30;

    /// The identity.
    pub const IDENTITY: Matrix = Matrix {
        rows: [[ONE, 0, 0, 0], [0, ONE, 0, 0], [0, 0, ONE, 0]],
    };

    /// A matrix from raw rows, or `None` when a linear entry exceeds
    /// [`Matrix::LINEAR_LIMIT`].
    pub fn from_rows(rows: [[i32; 4]; 3]) -> Option<Self> {
        let ok = rows.iter().all(|r| {
            r[..3]
                .iter()
                .all(|&m| m.unsigned_abs() <= Self::LINEAR_LIMIT as u32)
        });
        ok.then_some(Matrix { rows })
    }

    /// The raw rows.
    pub const fn rows(&self) -> [[i32; 4]; 3] {
        self.rows
    }

    /// A translation by `t`.
    pub const fn translation(t: Point3) -> Self {
        Matrix {
            rows: [[ONE, 0, 0, t.x.0], [0, ONE, 0, t.y.0], [0, 0, ONE, t.z.0]],
        }
    }

    /// A scaling by `(sx, sy, sz)`, or `None` when a factor exceeds
    /// ±16384.
    pub fn scaling(sx: Q16, sy: Q16, sz: Q16) -> Option<Self> {
        Matrix::from_rows([[sx.0, 0, 0, 0], [0, sy.0, 0, 0], [0, 0, sz.0, 0]])
    }

    /// A rotation about the x axis by `a`, counter-clockwise when looking
    /// from +x toward the origin (y toward z).
    pub fn rotation_x(a: Angle) -> Self {
        let (s, c) = (sin(a), cos(a));
        Matrix {
            rows: [[ONE, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0]],
        }
    }

    /// A rotation about the y axis by `a` (z toward x).
    pub fn rotation_y(a: Angle) -> Self {
        let (s, c) = (sin(a), cos(a));
        Matrix {
            rows: [[c, 0, s, 0], [0, ONE, 0, 0], [-s, 0, c, 0]],
        }
    }

    /// A rotation about the z axis by `a` (x toward y).
    pub fn rotation_z(a: Angle) -> Self {
        let (s, c) = (sin(a), cos(a));
        Matrix {
            rows: [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, ONE, 0]],
        }
    }

    /// `self · rhs`: `rhs` acts first. [`TransformError::Range`] when an
    /// entry of the product leaves its range.
    pub fn checked_mul(&self, rhs: &Matrix) -> Result<Matrix, TransformError> {
        let a = &self.rows;
        let b = &rhs.rows;
        let mut out = [[0i32; 4]; 3];
        for (r, row) in out.iter_mut().enumerate() {
            for (c, cell) in row.iter_mut().enumerate() {
                // Linear: three products ≤ 2⁶⁰. Translation: three ≤ 2⁶¹,
                // plus t · 2¹⁶ ≤ 2⁴⁷. Both below 2⁶³.
                let mut s: i64 = (0..3).map(|k| a[r][k] as i64 * b[k][c] as i64).sum();
                if c == 3 {
                    s += (a[r][3] as i64) << 16;
                }
                let v = round16(s).ok_or(TransformError::Range)?;
                if c < 3 && v.unsigned_abs() > Self::LINEAR_LIMIT as u32 {
                    return Err(TransformError::Range);
                }
                *cell = v;
            }
        }
        Ok(Matrix { rows: out })
    }

    /// `M · p + t`, rounded to nearest, or [`TransformError::Range`] when a
    /// coordinate leaves view space's (−16384, 16384).
    pub fn transform(&self, p: Point3) -> Result<Point3, TransformError> {
        let [x, y, z] = self.apply(p)?;
        Ok(Point3::from_bits(x, y, z))
    }

    /// [`Matrix::transform`] in raw form.
    #[inline]
    pub(super) fn apply(&self, p: Point3) -> Result<[i32; 3], TransformError> {
        let p = p.to_bits();
        let mut out = [0i32; 3];
        for (o, row) in out.iter_mut().zip(&self.rows) {
            // Three products ≤ 2⁶¹ plus t · 2¹⁶: below 2⁶³.
            let s = row[0] as i64 * p[0] as i64
                + row[1] as i64 * p[1] as i64
                + row[2] as i64 * p[2] as i64
                + ((row[3] as i64) << 16);
            let v = (s + HALF) >> 16;
            if v <= -(VIEW_LIMIT as i64) || v >= VIEW_LIMIT as i64 {
                return Err(TransformError::Range);
            }
            *o = v as i32;
        }
        Ok(out)
    }

    /// The linear part applied to a direction `v` whose components are at
    /// most 2¹⁷ in magnitude (`i64`; no translation, no range check needed).
    pub(super) fn rotate_vector(&self, v: [i32; 3]) -> [i32; 3] {
        let mut out = [0i32; 3];
        for (o, row) in out.iter_mut().zip(&self.rows) {
            let s = row[0] as i64 * v[0] as i64
                + row[1] as i64 * v[1] as i64
                + row[2] as i64 * v[2] as i64;
            // ≤ 3 · 2³⁰ · 2¹⁷ >> 16 = 3 · 2³¹: clamp into i32.
            *o = ((s + HALF) >> 16).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        }
        out
    }
}

/// The camera: an eye position and the direction it looks in.
///
/// The world is right-handed with y up. At `yaw = pitch = 0` the eye looks
/// along world −z, with +x to its right. Positive `yaw` turns it to the
/// left (counter-clockwise seen from above, about +y), then positive
/// `pitch` tilts it up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct View {
    /// Where the eye is, in world coordinates.
    pub eye: Point3,
    /// Turn about the world's vertical axis.
    pub yaw: Angle,
    /// Tilt up from the horizontal.
    pub pitch: Angle,
}

impl View {
    /// The eye at `eye` looking at `target`, without roll;
    /// [`ZeroDirection`] when the two are the same point. Yaw and pitch come from [`atan2`], within
    /// 0.011° of the exact direction.
    pub fn look_at(eye: Point3, target: Point3) -> Result<View, ZeroDirection> {
        let (e, t) = (eye.to_bits(), target.to_bits());
        // Differences of i32 fit i64 (|·| < 2³²).
        let d = [0, 1, 2].map(|k| t[k] as i64 - e[k] as i64);
        if d == [0, 0, 0] {
            return Err(ZeroDirection);
        }
        // Forward = (−sin yaw · cos pitch, sin pitch, −cos yaw · cos pitch).
        let yaw = atan2(-d[0], -d[2]);
        // The horizontal length, with the vector scaled to 15 bits (the
        // precision atan2 works at; squares summed in u32).
        let s = super::light::scale15(d).unwrap_or([0, 0, 0]);
        let h = super::light::length15([s[0], 0, s[2]]);
        let pitch = atan2(s[1] as i64, h as i64);
        Ok(View { eye, yaw, pitch })
    }

    /// The world-to-view matrix: `F · Rx(−pitch) · Ry(−yaw) · T(−eye)`,
    /// where `F = diag(1, −1, −1)` turns y up / looking along −z into
    /// view space's y down / z forward. [`TransformError::Range`] when the
    /// eye is so far out that its rotated position leaves Q16.16, or when
    /// a coordinate is `Q16::MIN`.
    pub fn matrix(&self) -> Result<Matrix, TransformError> {
        let neg = |q: Q16| q.checked_neg().ok_or(TransformError::Range);
        let back = Point3::new(neg(self.eye.x)?, neg(self.eye.y)?, neg(self.eye.z)?);
        let flip = Matrix {
            rows: [[ONE, 0, 0, 0], [0, -ONE, 0, 0], [0, 0, -ONE, 0]],
        };
        flip.checked_mul(&Matrix::rotation_x(-self.pitch))?
            .checked_mul(&Matrix::rotation_y(-self.yaw))?
            .checked_mul(&Matrix::translation(back))
    }
}

/// The current matrix and up to `DEPTH` saved ones.
///
/// # Capacity
/// `push` saves the current matrix; the `DEPTH + 1`-th push without a
/// `pop` fails with [`TransformError::StackOverflow`] and changes nothing.
/// `pop` with nothing saved fails with [`TransformError::StackUnderflow`].
/// Each level costs 48 bytes.
#[derive(Clone, Debug)]
#[doc(hidden)]
pub struct TransformStack<const DEPTH: usize> {
    current: Matrix,
    saved: heapless::Vec<Matrix, DEPTH>,
}

impl<const DEPTH: usize> Default for TransformStack<DEPTH> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const DEPTH: usize> TransformStack<DEPTH> {
    /// A stack holding the identity, with nothing saved.
    pub const fn new() -> Self {
        TransformStack {
            current: Matrix::IDENTITY,
            saved: heapless::Vec::new(),
        }
    }

    /// The current matrix.
    pub fn current(&self) -> &Matrix {
        &self.current
    }

    /// Matrices saved by `push`.
    pub fn depth(&self) -> usize {
        self.saved.len()
    }

    /// Replaces the current matrix.
    pub fn load(&mut self, m: Matrix) {
        self.current = m;
    }

    /// Replaces the current matrix with the identity.
    pub fn load_identity(&mut self) {
        self.current = Matrix::IDENTITY;
    }

    /// Saves the current matrix.
    pub fn push(&mut self) -> Result<(), TransformError> {
        self.saved
            .push(self.current)
            .map_err(|_| TransformError::StackOverflow { depth: DEPTH })
    }

    /// Restores the matrix saved last.
    pub fn pop(&mut self) -> Result<(), TransformError> {
        self.current = self.saved.pop().ok_or(TransformError::StackUnderflow)?;
        Ok(())
    }

    /// Post-multiplies the current matrix by `m` (`m` acts first).
    pub fn multiply(&mut self, m: &Matrix) -> Result<(), TransformError> {
        self.current = self.current.checked_mul(m)?;
        Ok(())
    }

    /// Translates by `(x, y, z)`.
    pub fn translate(&mut self, x: Q16, y: Q16, z: Q16) -> Result<(), TransformError> {
        self.multiply(&Matrix::translation(Point3::new(x, y, z)))
    }

    /// Rotates about x.
    pub fn rotate_x(&mut self, a: Angle) -> Result<(), TransformError> {
        self.multiply(&Matrix::rotation_x(a))
    }

    /// Rotates about y.
    pub fn rotate_y(&mut self, a: Angle) -> Result<(), TransformError> {
        self.multiply(&Matrix::rotation_y(a))
    }

    /// Rotates about z.
    pub fn rotate_z(&mut self, a: Angle) -> Result<(), TransformError> {
        self.multiply(&Matrix::rotation_z(a))
    }

    /// Scales by `(sx, sy, sz)`; each factor within ±16384.
    pub fn scale(&mut self, sx: Q16, sy: Q16, sz: Q16) -> Result<(), TransformError> {
        let m = Matrix::scaling(sx, sy, sz).ok_or(TransformError::Range)?;
        self.multiply(&m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: i16, y: i16, z: i16) -> Point3 {
        Point3::from_int(x, y, z)
    }

    #[test]
    fn call_order_is_post_multiplication() {
        // translate then rotate: the rotation acts on the model first.
        let mut s = TransformStack::<4>::new();
        s.translate(Q16::from_int(10), Q16::ZERO, Q16::ZERO)
            .unwrap();
        s.rotate_z(Angle::QUARTER).unwrap();
        // (1, 0, 0) rotated a quarter about z is (0, 1, 0), then + (10, 0, 0).
        assert_eq!(s.current().transform(p(1, 0, 0)), Ok(p(10, 1, 0)));

        let mut s = TransformStack::<4>::new();
        s.rotate_z(Angle::QUARTER).unwrap();
        s.translate(Q16::from_int(10), Q16::ZERO, Q16::ZERO)
            .unwrap();
        assert_eq!(s.current().transform(p(1, 0, 0)), Ok(p(0, 11, 0)));
    }

    #[test]
    fn push_pop_and_their_errors() {
        let mut s = TransformStack::<2>::new();
        assert_eq!(s.pop(), Err(TransformError::StackUnderflow));
        s.push().unwrap();
        s.scale(Q16::from_int(2), Q16::from_int(2), Q16::from_int(2))
            .unwrap();
        s.push().unwrap();
        assert_eq!(s.push(), Err(TransformError::StackOverflow { depth: 2 }));
        s.translate(Q16::ONE, Q16::ONE, Q16::ONE).unwrap();
        assert_eq!(s.current().transform(p(1, 1, 1)), Ok(p(4, 4, 4)));
        s.pop().unwrap();
        assert_eq!(s.current().transform(p(1, 1, 1)), Ok(p(2, 2, 2)));
        s.pop().unwrap();
        assert_eq!(s.current(), &Matrix::IDENTITY);
        assert_eq!(s.depth(), 0);
    }

    #[test]
    fn range_errors_leave_the_matrix_alone() {
        let mut s = TransformStack::<1>::new();
        let big = Q16::from_int(16384);
        s.scale(big, big, big).unwrap();
        let before = *s.current();
        assert_eq!(
            s.scale(Q16::from_int(2), Q16::ONE, Q16::ONE),
            Err(TransformError::Range)
        );
        assert_eq!(s.current(), &before);
        assert_eq!(
            s.scale(Q16::from_int(-16385), Q16::ONE, Q16::ONE),
            Err(TransformError::Range)
        );
        // A translation that overflows Q16.16 after scaling.
        assert_eq!(
            s.translate(Q16::from_int(2), Q16::ZERO, Q16::ZERO),
            Err(TransformError::Range)
        );
        // Points beyond view space.
        assert_eq!(
            s.current().transform(p(1, 0, 0)),
            Err(TransformError::Range)
        );
    }

    #[test]
    fn extreme_entries_do_not_overflow() {
        let lim = Matrix::LINEAR_LIMIT;
        let m = Matrix::from_rows([[lim, -lim, lim, i32::MAX]; 3]).unwrap();
        let n = Matrix::from_rows([[-lim, lim, -lim, i32::MIN]; 3]).unwrap();
        assert_eq!(m.checked_mul(&n), Err(TransformError::Range));
        let corner = Point3::new(Q16::MIN, Q16::MAX, Q16::MIN);
        assert_eq!(m.transform(corner), Err(TransformError::Range));
        assert!(Matrix::from_rows([[lim + 1, 0, 0, 0]; 3]).is_none());
        assert!(Matrix::from_rows([[-lim - 1, 0, 0, 0]; 3]).is_none());
        // Largest view-space coordinate accepted, and the first refused.
        let id = Matrix::IDENTITY;
        let edge = VIEW_LIMIT - 1;
        assert!(id.transform(Point3::from_bits(edge, -edge, 0)).is_ok());
        assert_eq!(
            id.transform(Point3::from_bits(VIEW_LIMIT, 0, 0)),
            Err(TransformError::Range)
        );
    }

    #[test]
    fn view_of_the_default_camera() {
        // Eye at (0, 0, 10) looking along −z: the origin is 10 ahead.
        let v = View {
            eye: p(0, 0, 10),
            ..View::default()
        };
        let m = v.matrix().unwrap();
        assert_eq!(m.transform(p(0, 0, 0)), Ok(p(0, 0, 10)));
        // World up is view-space up, i.e. negative y.
        assert_eq!(m.transform(p(0, 1, 0)), Ok(p(0, -1, 10)));
        assert_eq!(m.transform(p(1, 0, 0)), Ok(p(1, 0, 10)));
        // Turned a quarter to the left, the eye looks along world −x.
        let v = View {
            eye: p(0, 0, 0),
            yaw: Angle::QUARTER,
            pitch: Angle::ZERO,
        };
        assert_eq!(v.matrix().unwrap().transform(p(-5, 0, 0)), Ok(p(0, 0, 5)));
        // Tilted a quarter up, it looks along world +y.
        let v = View {
            eye: p(0, 0, 0),
            yaw: Angle::ZERO,
            pitch: Angle::QUARTER,
        };
        assert_eq!(v.matrix().unwrap().transform(p(0, 5, 0)), Ok(p(0, 0, 5)));
        let far = View {
            eye: Point3::new(Q16::MIN, Q16::ZERO, Q16::ZERO),
            ..View::default()
        };
        assert_eq!(far.matrix(), Err(TransformError::Range));
    }

    #[test]
    fn look_at_aims_the_eye() {
        let v = View::look_at(p(0, 0, 10), p(0, 0, 0)).unwrap();
        assert_eq!((v.yaw, v.pitch), (Angle::ZERO, Angle::ZERO));
        let v = View::look_at(p(0, 0, 0), p(-3, 0, 0)).unwrap();
        assert_eq!((v.yaw, v.pitch), (Angle::QUARTER, Angle::ZERO));
        let v = View::look_at(p(0, 0, 0), p(0, 4, 0)).unwrap();
        assert_eq!(v.pitch, Angle::QUARTER);
        assert_eq!(View::look_at(p(1, 2, 3), p(1, 2, 3)), Err(ZeroDirection));
        // The target lands on the view axis.
        let (eye, target) = (p(7, 5, -9), p(-2, 1, 4));
        let m = View::look_at(eye, target).unwrap().matrix().unwrap();
        let t = m.transform(target).unwrap().to_bits();
        assert!(
            t[0].abs() < 1 << 10 && t[1].abs() < 1 << 10 && t[2] > 16 << 16,
            "{t:?}"
        );
        let far = View::look_at(
            Point3::new(Q16::MIN, Q16::MIN, Q16::MIN),
            Point3::new(Q16::MAX, Q16::MAX, Q16::MAX),
        );
        assert!(far.is_ok());
        // Both horizontal components at the scaled range's corner.
        let v = View::look_at(
            Point3::from_bits(65535, 0, 65535),
            Point3::from_bits(0, 0, 0),
        )
        .unwrap();
        assert_eq!(v.yaw, Angle::from_bits(0x2000));
    }

    #[test]
    fn ratios() {
        assert_eq!(Q16::from_ratio(1, 2), Some(Q16::from_bits(32768)));
        assert_eq!(Q16::from_ratio(-3, -4), Some(Q16::from_bits(49152)));
        assert_eq!(Q16::from_ratio(1, 0), None);
        assert_eq!(Q16::from_ratio(32768, 1), None);
        assert_eq!(Q16::from_ratio(-32768, 1), Some(Q16::MIN));
        assert_eq!(Q16::from_ratio(i32::MIN, -1), None);
    }
}
