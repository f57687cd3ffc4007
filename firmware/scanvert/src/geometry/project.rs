//! View space to the screen: perspective and orthographic projection into
//! the window, with a depth that is affine in screen space.
//!
//! # Output formats
//!
//! The window is `width × height` pixels (each 1 to 2047), x right and y
//! down, with the view axis through `centre` (Q12.4). Final vertices are
//! [`Vertex3`]: x and y in Q12.4 pixels, z in Q12.4 depth, larger farther.
//! Depth spans the whole Q12.4 range: the near plane maps to
//! [`Z_NEAR`] (−2048) and the far plane to [`Z_FAR`] (2047.9375), which
//! gives 65536 depth steps.
//!
//! Between projection and the window clip, a vertex is a `[i64; 3]`:
//! x and y in **1/256 px** and z in **1/4096** (Q12.4 with eight more
//! fraction bits). That is 16 times finer than the output, so the clip's
//! intersections round only once, at the end. After the near clip,
//! `|x|, |y| < 2⁴⁶` in these units (see the bounds below).
//!
//! # Perspective
//!
//! `sx = cx + f·x/d`, `sy = cy + f·y/d`, with `d` the view depth and `f` the
//! focal length in pixels. Depth is `z = A − B/d`, with `A` and `B` chosen so
//! that `z(near) = Z_NEAR` and `z(far) = Z_FAR`: `1/d` is affine in screen
//! space over a plane, so `z` is too, which is what the visible-surface
//! stage needs (plain `d` would not be).
//!
//! One division per vertex gives a 32-bit reciprocal (64 by 32 bits, done
//! as two 32-bit hardware divisions, see `div_2_63`):
//!
//! | step | value | bound |
//! |---|---|---|
//! | `s`, `dₙ = d << s` | normalised depth | `(2³⁰, 2³¹]` |
//! | `r = ⌊2⁶² / dₙ⌋` | reciprocal, `1/d = r·2ˢ/2⁶²` | `[2³¹, 2³²)`, `u32` |
//! | `P = x · r = x · 2³¹ + x · (r − 2³¹)` | one 32 × 32-bit product | `< 2³⁰ · 2³² = 2⁶²` |
//! | `P = P₁ · 2³¹ + P₀`, `0 ≤ P₀ < 2³¹` | two halves | `|P₁| < 2³¹` |
//! | `P₁ · f` and `P₀ · f` (`f` Q16.16 px, `< 2³¹`) | 32 × 32-bit products | `< 2⁶²` each |
//! | `sx − cx = f·P / 2⁷⁰⁻ˢ` in 1/256 px: `(P₁·f + (P₀·f >> 31) + ½) >> (39 − s)` | exactly rounded | `< 2⁴⁵` |
//! | `w = ⌊2ᴷ/d⌋ = r >> (clz(near) − s)`, `K = 62 − clz(near)` | exact floor | `(0, 2³¹]` |
//! | `z = Z_NEAR + (w(near) − w) · M >> 38`, `M = ⌊S·2³⁸ / (w(near) − w(far))⌋` | | product `< 2⁶²` |
//!
//! (`S` is the depth span, 65535 · 256 in 1/4096 units.) The product
//! `f · P` is formed in two `i64` halves, so the only errors of `sx` and
//! `sy` before the output's rounding are the reciprocal's (relative, below
//! 2⁻³¹) and the rounding to 1/256 px: together below 1/256 px anywhere in
//! the window. The output vertices are then within 1/32 + 1/256 px of the
//! exact projection of the view-space point. `z` is within 1/16 of a Q12.4
//! step of `A − B/d` before its final rounding, because
//! `w(near) − w(far) ≥ 2²⁰` is required.
//!
//! View space itself has a step of 2⁻¹⁶ units, which at depth `d` is
//! `f · 2⁻¹⁶ / d` px on the screen. Transformed vertices, and the near
//! clip's new vertices, are rounded to that step. A near plane at
//! `near ≥ f / 2048` keeps it within 1/32 px everywhere (half of that for
//! the rounding).
//!
//! Limits, checked by [`Perspective::new`]: `1/256 ≤ near < far < 16384`
//! units, `far − near` large enough for 2²⁰ steps of `w` (about
//! `far ≥ 1.001 · near`), and a focal length of 1 to 32767 px.
//!
//! # Orthographic
//!
//! `sx = cx + k·x`, `sy = cy + k·y` with `k` in pixels per unit (Q16.16;
//! `|x · k| < 2⁶¹`), and `z = Z_NEAR + (d − near)·M >> 32` with
//! `M = ⌊S·2³² / (far − near)⌋` (product `< 2⁵⁶`), linear in `d` and so
//! affine in screen space too. The near plane may be behind the eye.

use super::transform::{Point3, Q16, VIEW_LIMIT};
use super::trig::{cos, sin, Angle};
use crate::fixed::{Coord, Vertex, Vertex3};
use core::fmt;

/// Depth of the near plane on screen: −2048.
pub const Z_NEAR: Coord = Coord::MIN;
/// Depth of the far plane on screen: 2047.9375.
pub const Z_FAR: Coord = Coord::MAX;

/// Screen depth of the near plane in 1/4096 units.
pub(super) const Z_NEAR_FINE: i64 = (Z_NEAR.units() as i64) << 8;
/// The depth span in 1/4096 units: 65535 · 256 < 2²⁴.
const Z_SPAN_FINE: i64 = ((Z_FAR.units() - Z_NEAR.units()) as i64) << 8;
/// Smallest perspective near plane, raw Q16.16: 1/256 unit.
pub const NEAR_MIN: Q16 = Q16::from_bits(256);
/// Largest window side in pixels.
pub const WINDOW_MAX: u16 = 2047;

/// Why projection parameters were refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum ProjectionError {
    /// The near plane is outside its range.
    Near,
    /// The far plane is not beyond the near plane, or is outside view space.
    Far,
    /// Near and far are so close that depth would have too few steps.
    DepthResolution,
    /// The focal length is outside 1 to 32767 px, or the field of view is
    /// not between zero and half a turn.
    Focal,
    /// The orthographic scale is not positive.
    Scale,
    /// A window side is 0 or larger than [`WINDOW_MAX`].
    Window,
}

impl fmt::Display for ProjectionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ProjectionError::Near => "near plane out of range",
            ProjectionError::Far => "far plane not beyond the near plane, or out of range",
            ProjectionError::DepthResolution => "near and far planes too close together",
            ProjectionError::Focal => "focal length or field of view out of range",
            ProjectionError::Scale => "orthographic scale must be positive",
            ProjectionError::Window => "window side must be 1 to 2047 pixels",
        })
    }
}

impl core::error::Error for ProjectionError {}

/// The screen window: `width × height` pixels, and the point the view
/// axis goes through.
///
/// # Guarantees
/// `1 ≤ width, height ≤ 2047`, so every point of the window
/// `[0, width] × [0, height]` is a [`Coord`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Viewport {
    width: u16,
    height: u16,
    centre: Vertex,
}

impl Viewport {
    /// A window with the view axis through `centre` (which may lie
    /// anywhere, even off the window).
    pub fn new(width: u16, height: u16, centre: Vertex) -> Result<Self, ProjectionError> {
        if width == 0 || height == 0 || width > WINDOW_MAX || height > WINDOW_MAX {
            return Err(ProjectionError::Window);
        }
        Ok(Viewport {
            width,
            height,
            centre,
        })
    }

    /// A window with the view axis through its middle.
    pub fn centred(width: u16, height: u16) -> Result<Self, ProjectionError> {
        // width · 8 ≤ 16376: a valid Q12.4 value.
        let c = Vertex::from_bits(
            (width.min(WINDOW_MAX) * 8) as i16,
            (height.min(WINDOW_MAX) * 8) as i16,
        );
        Viewport::new(width, height, c)
    }

    /// Width in pixels.
    pub const fn width(&self) -> u16 {
        self.width
    }

    /// Height in pixels.
    pub const fn height(&self) -> u16 {
        self.height
    }

    /// Where the view axis meets the screen.
    pub const fn centre(&self) -> Vertex {
        self.centre
    }

    /// The window's right edge, in 1/256 px.
    pub(super) const fn right_fine(&self) -> i64 {
        (self.width as i64) << 8
    }

    /// The window's bottom edge, in 1/256 px.
    pub(super) const fn bottom_fine(&self) -> i64 {
        (self.height as i64) << 8
    }
}

/// Perspective projection: a focal length, and near and far planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Perspective {
    /// Focal length in Q16.16 px, `[2¹⁶, 2³¹)`.
    focal: i64,
    near: i32,
    far: i32,
    /// `clz(near)`.
    near_lz: u32,
    /// `w(near)`.
    w_near: i64,
    /// `M`: depth per step of `w`, scaled by 2³⁸.
    depth_mul: i64,
}

/// `(r, s)` with `1/d = r · 2ˢ / 2⁶²`, for `1 ≤ d < 2³⁰`: `r` is
/// `⌊2⁶² / dₙ⌋` exactly, `dₙ = d << s ∈ (2³⁰, 2³¹]`, so `r ∈ [2³¹, 2³²)`
/// and `s ≤ clz(d)`.
#[inline]
fn reciprocal(d: i32) -> (u32, u32) {
    let s = (d as u32).leading_zeros() - 1;
    let dn = (d as u32) << s;
    if dn == 1 << 30 {
        // A power of two: one more shift gives dₙ = 2³¹ and r = 2³¹.
        (1 << 31, s + 1)
    } else {
        // 2⁶² / dₙ = 2⁶³ / (2 dₙ).
        (div_2_63(dn << 1), s)
    }
}

/// `⌊2⁶³ / v⌋` for `2³¹ < v < 2³²`.
///
/// A 64-by-32-bit division in two 16-bit digits, each found with one
/// 32-bit division and corrected at most twice (Knuth's algorithm D, as in
/// Hacker's Delight's `divlu`). A Cortex-M has a 32-bit divide
/// instruction, but a `u64` division is a library call several times
/// slower; this is the one division per vertex of the projection. All
/// arithmetic is `u32`: each product is checked against the digit base
/// before it is formed, so none overflows.
#[inline]
fn div_2_63(v: u32) -> u32 {
    const B: u32 = 1 << 16;
    let (vn1, vn0) = (v >> 16, v & 0xFFFF);
    // The dividend's digits: 2³¹ above, then 0 and 0.
    let top = 1u32 << 31;
    let mut q1 = top / vn1;
    let mut rhat = top - q1 * vn1;
    while q1 >= B || q1 * vn0 > B * rhat {
        q1 -= 1;
        rhat += vn1;
        if rhat >= B {
            break;
        }
    }
    // The partial remainder, below v: exact modulo 2³².
    let mid = top.wrapping_mul(B).wrapping_sub(q1.wrapping_mul(v));
    let mut q0 = mid / vn1;
    let mut rhat = mid - q0 * vn1;
    while q0 >= B || q0 * vn0 > B * rhat {
        q0 -= 1;
        rhat += vn1;
        if rhat >= B {
            break;
        }
    }
    q1 * B + q0
}

/// `round(v / 2ᵏ)` for `1 ≤ k ≤ 62`.
#[inline]
fn round_shift(v: i64, k: u32) -> i64 {
    (v + (1i64 << (k - 1))) >> k
}

impl Perspective {
    /// A perspective with focal length `focal` pixels, between the planes
    /// at view depths `near` and `far`.
    pub fn new(focal: Q16, near: Q16, far: Q16) -> Result<Self, ProjectionError> {
        let f = focal.to_bits();
        if f < 1 << 16 {
            return Err(ProjectionError::Focal);
        }
        let (near, far) = (near.to_bits(), far.to_bits());
        if near < NEAR_MIN.to_bits() || near >= VIEW_LIMIT {
            return Err(ProjectionError::Near);
        }
        if far <= near || far >= VIEW_LIMIT {
            return Err(ProjectionError::Far);
        }
        let mut p = Perspective {
            focal: f as i64,
            near,
            far,
            near_lz: (near as u32).leading_zeros(),
            w_near: 0,
            depth_mul: 0,
        };
        p.w_near = p.w(reciprocal(near));
        let steps = p.w_near - p.w(reciprocal(far));
        if steps < 1 << 20 {
            return Err(ProjectionError::DepthResolution);
        }
        // S · 2³⁸ < 2⁶²; M < 2⁴².
        p.depth_mul = (Z_SPAN_FINE << 38) / steps;
        Ok(p)
    }

    /// A perspective whose horizontal field of view across `width` pixels
    /// is `fov` (strictly between zero and half a turn):
    /// `f = (width/2) · cos(fov/2) / sin(fov/2)`.
    pub fn from_fov(fov: Angle, width: u16, near: Q16, far: Q16) -> Result<Self, ProjectionError> {
        let half = Angle::from_bits(fov.to_bits() / 2);
        if fov.to_bits() == 0 || fov.to_bits() >= Angle::HALF.to_bits() {
            return Err(ProjectionError::Focal);
        }
        let (s, c) = (sin(half) as i64, cos(half) as i64);
        if s <= 0 {
            return Err(ProjectionError::Focal);
        }
        // width · 2¹⁵ · c < 2⁴³; the quotient is the focal length in Q16.16.
        let f = ((width as i64) << 15) * c / s;
        let f = i32::try_from(f).map_err(|_| ProjectionError::Focal)?;
        Perspective::new(Q16::from_bits(f), near, far)
    }

    /// The near plane.
    pub const fn near(&self) -> Q16 {
        Q16::from_bits(self.near)
    }

    /// The far plane.
    pub const fn far(&self) -> Q16 {
        Q16::from_bits(self.far)
    }

    /// The focal length in pixels.
    pub const fn focal(&self) -> Q16 {
        Q16::from_bits(self.focal as i32)
    }

    /// `⌊2ᴷ / d⌋` for `near ≤ d < 2³⁰`, from `reciprocal(d)`:
    /// `r · 2ˢ · 2ᴷ / 2⁶²` with `K = 62 − clz(near)`, a right shift by
    /// `clz(near) − s ≥ 0`.
    #[inline]
    fn w(&self, (r, s): (u32, u32)) -> i64 {
        (r >> (self.near_lz - s)) as i64
    }

    /// `f · x · r / 2⁷⁰⁻ˢ`, rounded, for `|x| < 2³⁰`, `r ∈ [2³¹, 2³²)` and
    /// `1 ≤ s ≤ 23`. `P = x · r = x · 2³¹ + x · (r − 2³¹)` (`|P| < 2⁶²`) is
    /// split as `P₁ · 2³¹ + P₀`; `P₁ · f` and `P₀ · f` are 32 × 32-bit
    /// products below 2⁶².
    #[inline]
    fn scale(&self, x: i32, r: u32, s: u32) -> i64 {
        let p = ((x as i64) << 31) + x as i64 * (r - (1 << 31)) as i32 as i64;
        let (hi, lo) = ((p >> 31) as i32, (p as u32) & 0x7FFF_FFFF);
        let f = self.focal as i32;
        let lo_f = (lo as u64 * f as u64) >> 31;
        (hi as i64 * f as i64 + lo_f as i64 + (1 << (38 - s))) >> (39 - s)
    }

    /// x and y offsets from the centre in 1/256 px, and depth in 1/4096,
    /// for `near ≤ d ≤ far`... or beyond `far`, where the depth is clamped.
    #[inline]
    fn project(&self, v: [i64; 3]) -> [i64; 3] {
        let d = v[2] as i32;
        let (r, s) = reciprocal(d);
        let sx = self.scale(v[0] as i32, r, s);
        let sy = self.scale(v[1] as i32, r, s);
        let z = if d > self.far {
            Z_NEAR_FINE + Z_SPAN_FINE
        } else {
            // w(near) − w ∈ [0, 2³¹), M < 2⁴²: the product is below 2⁶².
            let steps = (self.w_near - self.w((r, s))) as u64;
            Z_NEAR_FINE + round_shift((steps * self.depth_mul as u64) as i64, 38)
        };
        [sx, sy, z]
    }
}

/// Orthographic projection: a scale, and near and far planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Orthographic {
    scale: i64,
    near: i32,
    far: i32,
    depth_mul: i64,
}

impl Orthographic {
    /// An orthographic projection of `scale` pixels per unit between the
    /// planes at view depths `near` and `far` (both inside view space).
    pub fn new(scale: Q16, near: Q16, far: Q16) -> Result<Self, ProjectionError> {
        if scale.to_bits() <= 0 {
            return Err(ProjectionError::Scale);
        }
        let (near, far) = (near.to_bits(), far.to_bits());
        if near <= -VIEW_LIMIT || near >= VIEW_LIMIT {
            return Err(ProjectionError::Near);
        }
        if far <= near || far >= VIEW_LIMIT {
            return Err(ProjectionError::Far);
        }
        Ok(Orthographic {
            scale: scale.to_bits() as i64,
            near,
            far,
            // S · 2³² < 2⁵⁶; far − near ∈ [1, 2³¹).
            depth_mul: (Z_SPAN_FINE << 32) / (far as i64 - near as i64),
        })
    }

    /// The near plane.
    pub const fn near(&self) -> Q16 {
        Q16::from_bits(self.near)
    }

    /// The far plane.
    pub const fn far(&self) -> Q16 {
        Q16::from_bits(self.far)
    }

    #[inline]
    fn project(&self, v: [i64; 3]) -> [i64; 3] {
        // |x · k| < 2³⁰ · 2³¹; Q16.16 · Q16.16 px to 1/256 px is >> 24.
        let sx = round_shift(v[0] * self.scale, 24);
        let sy = round_shift(v[1] * self.scale, 24);
        let d = v[2].min(self.far as i64);
        let z = Z_NEAR_FINE + round_shift((d - self.near as i64) * self.depth_mul, 32);
        [sx, sy, z]
    }
}

/// A projection of either kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Projection {
    /// Perspective: farther is smaller.
    Perspective(Perspective),
    /// Orthographic: parallel rays along the view axis.
    Orthographic(Orthographic),
}

impl From<Perspective> for Projection {
    fn from(p: Perspective) -> Self {
        Projection::Perspective(p)
    }
}

impl From<Orthographic> for Projection {
    fn from(p: Orthographic) -> Self {
        Projection::Orthographic(p)
    }
}

impl Projection {
    /// The near plane (raw Q16.16).
    pub(super) fn near_raw(&self) -> i32 {
        match self {
            Projection::Perspective(p) => p.near,
            Projection::Orthographic(p) => p.near,
        }
    }

    /// The far plane (raw Q16.16).
    pub(super) fn far_raw(&self) -> i32 {
        match self {
            Projection::Perspective(p) => p.far,
            Projection::Orthographic(p) => p.far,
        }
    }

    /// A view-space vertex with `near ≤ d < 2³⁰` to the screen, before the
    /// window clip: x, y in 1/256 px, z in 1/4096 (clamped to the far
    /// plane's beyond it).
    #[inline]
    pub(super) fn project(&self, v: [i64; 3], window: &Viewport) -> [i64; 3] {
        let [x, y, z] = match self {
            Projection::Perspective(p) => p.project(v),
            Projection::Orthographic(p) => p.project(v),
        };
        let c = window.centre;
        [
            x + ((c.x.units() as i64) << 4),
            y + ((c.y.units() as i64) << 4),
            z,
        ]
    }
}

/// A pre-clip screen vertex to the output format, rounding half up.
///
/// # Guarantees
/// Exact for every input whose x and y lie inside the window and whose z
/// lies between the planes' depths (as the window clip leaves them): all
/// three are then below 2²⁴ in magnitude and the arithmetic is `i32`.
/// Anything else still gives a valid [`Coord`] (clamped), never a panic.
#[inline]
pub(super) fn to_vertex3(v: [i64; 3]) -> Vertex3 {
    let c = |u: i64, shift: u32| {
        let r = (u as i32).wrapping_add(1 << (shift - 1)) >> shift;
        Coord::from_bits(r.clamp(i16::MIN as i32, i16::MAX as i32) as i16)
    };
    Vertex3 {
        x: c(v[0], 4),
        y: c(v[1], 4),
        z: c(v[2], 8),
    }
}

/// Where a 3D point lands on the screen, for a label anchored there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Anchor {
    /// Screen x in 1/16 px (Q12.4 scale, wider range), saturated to
    /// `i32`. Meaningful only when `in_front`.
    pub x: i32,
    /// Screen y in 1/16 px, downward, saturated to `i32`. Meaningful only
    /// when `in_front`.
    pub y: i32,
    /// Screen depth, clamped to [`Z_FAR`] beyond the far plane.
    /// Meaningful only when `in_front`.
    pub z: Coord,
    /// The point is at or beyond the near plane. When `false`, `x`, `y`
    /// and `z` are zero.
    pub in_front: bool,
    /// The point is between the planes and on the window: `0 ≤ x < width`
    /// and `0 ≤ y < height` pixels.
    pub inside: bool,
}

/// The anchor of a view-space point (|coordinates| < 2³⁰).
pub(super) fn anchor(projection: &Projection, window: &Viewport, v: [i64; 3]) -> Anchor {
    let near = projection.near_raw() as i64;
    if v[2] < near {
        return Anchor::default();
    }
    let p = projection.project(v, window);
    // 1/256 px to 1/16 px, saturated: |p| < 2⁴⁶.
    let sat = |u: i64| ((u + 8) >> 4).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
    let (x, y) = (sat(p[0]), sat(p[1]));
    let z = to_vertex3(p).z;
    let on_window = (0..(window.width as i32) << 4).contains(&x)
        && (0..(window.height as i32) << 4).contains(&y);
    Anchor {
        x,
        y,
        z,
        in_front: true,
        inside: on_window && v[2] <= projection.far_raw() as i64,
    }
}

/// The anchor of a model point under `m` — what [`Pipeline::project_point`]
/// returns.
///
/// [`Pipeline::project_point`]: super::Pipeline::project_point
pub(super) fn anchor_of(
    m: &super::transform::Matrix,
    projection: &Projection,
    window: &Viewport,
    p: Point3,
) -> Result<Anchor, super::transform::TransformError> {
    let v = m.apply(p)?;
    Ok(anchor(
        projection,
        window,
        [v[0] as i64, v[1] as i64, v[2] as i64],
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn persp(f: i16, near: i16, far: i16) -> Projection {
        Perspective::new(Q16::from_int(f), Q16::from_int(near), Q16::from_int(far))
            .unwrap()
            .into()
    }

    fn win() -> Viewport {
        Viewport::centred(512, 256).unwrap()
    }

    const U: i64 = 1 << 16;

    #[test]
    fn near_and_far_map_to_the_depth_range() {
        let p = persp(256, 1, 100);
        let at = |d: i64| to_vertex3(p.project([0, 0, d * U], &win()));
        assert_eq!(at(1).z, Z_NEAR);
        assert_eq!(at(100).z, Z_FAR);
        assert_eq!(at(1).x.units(), 256 * 16);
        assert_eq!(at(1).y.units(), 128 * 16);
        // Beyond far, clamped.
        assert_eq!(at(1000).z, Z_FAR);
        // z = A − B/d: at d = 2, (1 − 1/2) / (1 − 1/100) = 50/99 of the span.
        let expect = -32768 + (65535 * 50 + 49) / 99;
        assert!((at(2).z.units() - expect).abs() <= 1, "{:?}", at(2));
    }

    #[test]
    fn perspective_divides_by_depth() {
        let p = persp(100, 1, 1000);
        // x = 5, d = 10: 50 px right of centre.
        let v = to_vertex3(p.project([5 * U, -3 * U, 10 * U], &win()));
        assert_eq!(v.x.units(), (256 + 50) * 16);
        assert_eq!(v.y.units(), (128 - 30) * 16);
    }

    #[test]
    fn orthographic_is_linear() {
        let o: Projection =
            Orthographic::new(Q16::from_int(2), Q16::from_int(-10), Q16::from_int(10))
                .unwrap()
                .into();
        let v = to_vertex3(o.project([5 * U, -3 * U, 0], &win()));
        assert_eq!(
            (v.x.units(), v.y.units()),
            ((256 + 10) * 16, (128 - 6) * 16)
        );
        assert_eq!(v.z.units(), 0);
        assert_eq!(to_vertex3(o.project([0, 0, -10 * U], &win())).z, Z_NEAR);
        assert_eq!(to_vertex3(o.project([0, 0, 10 * U], &win())).z, Z_FAR);
    }

    #[test]
    fn reciprocals_are_exact() {
        let check = |d: i32| {
            let (r, s) = reciprocal(d);
            let dn = (d as u64) << s;
            assert!((1u64 << 30) < dn && dn <= 1u64 << 31, "{d}");
            assert!(s <= (d as u32).leading_zeros());
            assert_eq!(r as u64, (1u64 << 62) / dn, "d = {d}");
        };
        for d in 1..70_000 {
            check(d);
        }
        let mut d: i32 = 1 << 29;
        while d < (1 << 30) - 7_919 {
            check(d);
            d += 7_919;
        }
        for d in [
            (1 << 30) - 1,
            (1 << 29) + 1,
            1 << 29,
            (1 << 30) - (1 << 14),
            3 << 28,
        ] {
            check(d);
        }
        for v in [
            (1u32 << 31) + 1,
            u32::MAX,
            u32::MAX - 1,
            0xC000_0000,
            0x8000_FFFF,
            0xFFFF_0000,
        ] {
            assert_eq!(div_2_63(v) as u64, (1u64 << 63) / v as u64, "{v}");
        }
    }

    #[test]
    fn parameters_are_checked() {
        let q = Q16::from_int;
        assert_eq!(
            Perspective::new(q(0), q(1), q(2)),
            Err(ProjectionError::Focal)
        );
        assert_eq!(Perspective::new(q(32767), q(1), q(2)).map(|_| ()), Ok(()));
        assert_eq!(
            Perspective::new(q(1), Q16::from_bits(255), q(2)),
            Err(ProjectionError::Near)
        );
        assert_eq!(
            Perspective::new(q(1), q(2), q(2)),
            Err(ProjectionError::Far)
        );
        assert_eq!(
            Perspective::new(q(1), q(2), q(16384)),
            Err(ProjectionError::Far)
        );
        assert_eq!(
            Perspective::new(q(1), q(1000), q(1000)),
            Err(ProjectionError::Far)
        );
        assert_eq!(
            Perspective::new(q(1), q(1000), Q16::from_bits((1000 << 16) + (1 << 15))),
            Err(ProjectionError::DepthResolution)
        );
        assert!(Perspective::new(q(1), q(1000), q(1001)).is_ok());
        assert!(Perspective::new(q(1), q(1000), q(1002)).is_ok());
        assert!(Perspective::new(q(1), NEAR_MIN, Q16::from_bits(VIEW_LIMIT - 1)).is_ok());
        assert_eq!(
            Orthographic::new(q(0), q(0), q(1)),
            Err(ProjectionError::Scale)
        );
        assert!(Orthographic::new(
            Q16::MAX,
            Q16::from_bits(1 - VIEW_LIMIT),
            Q16::from_bits(VIEW_LIMIT - 1)
        )
        .is_ok());
        assert_eq!(Viewport::centred(0, 5), Err(ProjectionError::Window));
        assert_eq!(Viewport::centred(2048, 5), Err(ProjectionError::Window));
        assert!(Viewport::centred(2047, 2047).is_ok());
        assert_eq!(
            Perspective::from_fov(Angle::HALF, 512, q(1), q(10)),
            Err(ProjectionError::Focal)
        );
        assert_eq!(
            Perspective::from_fov(Angle::ZERO, 512, q(1), q(10)),
            Err(ProjectionError::Focal)
        );
        // 90° across 512 px: f = 256.
        let p = Perspective::from_fov(Angle::QUARTER, 512, q(1), q(10)).unwrap();
        assert_eq!(p.focal(), q(256));
    }

    #[test]
    fn range_corners_do_not_overflow() {
        // Largest focal, smallest near, view-space extremes.
        let p: Projection = Perspective::new(Q16::MAX, NEAR_MIN, Q16::from_bits(VIEW_LIMIT - 1))
            .unwrap()
            .into();
        let e = VIEW_LIMIT as i64 - 1;
        for v in [
            [e, -e, NEAR_MIN.to_bits() as i64],
            [-e, e, e],
            [e, e, e],
            [0, 0, e],
        ] {
            let s = p.project(v, &win());
            assert!(s[0].abs() < 1 << 46 && s[1].abs() < 1 << 46);
            assert!((Z_NEAR_FINE..=Z_NEAR_FINE + Z_SPAN_FINE).contains(&s[2]));
        }
        let o: Projection = Orthographic::new(
            Q16::MAX,
            Q16::from_bits(-e as i32),
            Q16::from_bits(e as i32),
        )
        .unwrap()
        .into();
        for v in [[e, -e, -e], [-e, e, e]] {
            let s = o.project(v, &win());
            assert!(s[0].abs() < 1 << 46);
            assert!((Z_NEAR_FINE..=Z_NEAR_FINE + Z_SPAN_FINE).contains(&s[2]));
        }
    }

    #[test]
    fn anchors() {
        let p = persp(100, 1, 100);
        let w = win();
        let a = anchor(&p, &w, [0, 0, 10 * U]);
        assert!(a.in_front && a.inside);
        assert_eq!((a.x, a.y), (256 * 16, 128 * 16));
        let behind = anchor(&p, &w, [0, 0, -10 * U]);
        assert_eq!(behind, Anchor::default());
        let beyond = anchor(&p, &w, [0, 0, 1000 * U]);
        assert!(beyond.in_front && !beyond.inside);
        assert_eq!(beyond.z, Z_FAR);
        let off = anchor(&p, &w, [100 * U, 0, U]);
        assert!(off.in_front && !off.inside);
        assert_eq!(off.x, (256 + 10000) * 16);
        let e = VIEW_LIMIT as i64 - 1;
        let far_off = anchor(&p, &w, [e, -e, U]);
        assert!(far_off.x > 0 && far_off.y < 0);
    }
}
