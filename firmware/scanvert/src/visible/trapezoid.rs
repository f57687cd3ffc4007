//! Trapezoids: a screen-space polygon cut into pieces whose parallel sides
//! are horizontal, each with the depth of the polygon's plane.
//!
//! # Coverage
//!
//! A trapezoid is a pair of polygon edges, a left one and a right one,
//! over a run of rows `top..end`. On row `j` it covers the pixels
//! `c_left..c_right`, where `c = ⌈x − ½⌉` is the crossing's pixel as the
//! exact [`Edge`] stepper computes it (the rule of [`scan`](crate::raster::scan)).
//! The union of a polygon's trapezoids is exactly the set of pixels that
//! `poly` covers, each pixel once, for every polygon: convex, concave or
//! self-intersecting. The cut works like this:
//!
//! 1. Every edge that crosses a row centre inside the clip rows is set up
//!    ([`Polygon::load`]) and sorted by first row.
//! 2. The rows are cut into *bands* between the rows where an edge starts or
//!    ends. In a band the active edges are sorted by their exact crossing
//!    on the band's first row (ties broken by the band's last row), with
//!    integer cross-multiplication, no division.
//! 3. The order is checked on the band's last row. Each difference of two
//!    crossings is affine in the row, so an order that holds on the first
//!    and the last row holds on every row between. If two edges swap
//!    inside the band (a self-intersection), a binary search finds the last
//!    row where the order holds, and the band ends after it.
//! 4. The sorted edges are paired 1st–2nd, 3rd–4th, … (even-odd). A pair
//!    that is the same as in the band before continues its trapezoid;
//!    other pairs close it and open new ones.
//!
//! A polygon whose edges set up are two chains, one down and one up, in
//! the order loaded (every convex polygon) has exactly two active edges
//! on every row. [`Polygon::cut`] walks its chains instead: the same
//! bands, the same two crossings compared a band, the same trapezoids in
//! the same order, with no sort and no slot moved. It runs only when the
//! edges' rows add up to twice the polygon's (so exactly two edges are
//! active on every row), and hands over to the steps above where a band
//! needs them (the two edges cross, or coincide) or a chain breaks,
//! which then skip the trapezoids it has made (their first ones). A
//! triangle from the `poly3` and mesh adders is cut before that without
//! the walk (`cut_triangle`: the long edge, one cross product, the
//! split at the middle vertex's row), the walk's trapezoids again.
//!
//! The even-odd pairs of the exact crossings on a row are the pixel rule's
//! spans, and sorting by the exact crossings keeps `c_left ≤ c_right` on
//! every row of a trapezoid, so the trapezoids cover the rule's pixels and
//! never overlap. Two faces that share an edge therefore leave no gap and
//! no double hit, as polygons do. A triangle is one or two trapezoids, a
//! convex `n`-gon at most `n − 1` (each vertex between the top and the
//! bottom one starts a new trapezoid on its side).
//!
//! # The plane
//!
//! Depth comes from the polygon's plane, never from interpolation along
//! edges, so every trapezoid of a face has the same depth function.
//! [`Plane::of`] takes the normal `(a, b, c)` by Newell's method over the
//! Q12.4 vertices (units of 1/16), through the first vertex
//! `(x₀, y₀, z₀)`:
//!
//! ```text
//! a = Σ (yₖ − yₖ₊₁)(zₖ + zₖ₊₁)    b = Σ (zₖ − zₖ₊₁)(xₖ + xₖ₊₁)
//! c = Σ (xₖ − xₖ₊₁)(yₖ + yₖ₊₁)    d = a·x₀ + b·y₀ + c·z₀
//! a·x + b·y + c·z = d,  signs flipped so that c > 0
//! ```
//!
//! `c` is the shoelace sum, twice the signed area. For planar vertices
//! (the contract of `poly3`) this is the polygon's plane exactly; for a
//! triangle it always is. For vertices that are not planar, see below. A
//! polygon with `c = 0` is
//! edge-on: it has no plane in screen space and gets no trapezoid (a planar
//! one covers no pixel anyway).
//!
//! # Non-planar polygons
//!
//! Newell's normal is the usual best fit of a non-planar polygon's
//! orientation, and the plane with it through the first vertex is a fair
//! depth for one that is nearly planar. But when the polygon has little
//! area for its depths (nearly edge-on, or a bow tie whose halves nearly
//! cancel), `c` is small and that plane can be thousands of pixels deep at
//! pixels the polygon covers, while its vertices are inside the format:
//! outside the range the fixed-point depth and the visible-surface stage
//! are exact in, so it would be drawn in front of faces it is behind, and
//! differently by the two ways of resolving a span. A face of the
//! geometry stage is such a polygon when it is seen nearly edge-on: the
//! near clip and the projection round its vertices. So [`Polygon::load`]
//! keeps every polygon's depth inside its vertices' depth range
//! `[z_min, z_max]`:
//!
//! * the plane is Newell's when its depth lies in `[z_min, z_max]` at both
//!   ends of every edge set up (the edges that cross a row centre inside
//!   the clip rows). Every covered pixel centre lies on a row between two
//!   of those edges' crossings, so in their ends' convex hull, where the
//!   plane's depth is between its values at the ends: inside
//!   `[z_min, z_max]` too. Every planar polygon passes (its plane is its
//!   vertices' depth there), unchanged. (A quadrilateral is checked first
//!   at its vertices, in the pass that finds its plane: when it passes
//!   there it passes at those ends, which are vertices.);
//! * otherwise its slopes are scaled by `k / 2¹⁶` (`a` and `b` times
//!   `k / 2¹⁶`, rounded toward zero; `c` and the first vertex kept) with
//!   `k` found by bisection so that the depth is in `[z_min, z_max]` at
//!   those ends and would not be at `k + 1` (at `k = 0` the plane is the
//!   constant depth `z₀`, which is). It costs 17 more passes over the
//!   edges, multiplies only, and is kept when it moves no depth of the
//!   range by more than 2 units, `(1 − k/2¹⁶)·(z_max − z_min) ≤ 2`: a
//!   face that rounding tilted past its range by a unit or two;
//! * otherwise the plane is *fitted*: the slopes are scaled by the
//!   `k` whose depths at those ends span no more than `[z_min, z_max]`
//!   does (found from the span of the full slopes' depths: where it
//!   would be `z_max − z_min`, else 2 units less), and the plane is then moved by the fewest
//!   whole units of depth that bring those depths into `[z_min, z_max]`.
//!   Scaling alone fails this way when the first vertex is at the end of
//!   the range that the tilt passes elsewhere: only small `k` hold, and a
//!   ground plate cut by the window would be drawn at about its nearest
//!   depth, over what stands on it. Fitted, a polygon that rounding
//!   moved a little off its plane (a large face the clips cut, a nearly
//!   edge-on one) keeps its slope and lies within a few units of where it
//!   was. It costs two to four more passes, and a bisection only where
//!   the rounding of the slopes weighs, only for such polygons.
//!
//! So a non-planar `poly3` (or face) is drawn with the pixel rule's
//! coverage, as every polygon is, and the depth of one plane through its
//! first vertex, between its vertices' depths: Newell's, or Newell's
//! fitted when that leaves them. That plane is compared exactly, in
//! both ways of resolving, so both draw the same pixels.
//!
//! A point's or a line's polygon ([`Polygon::load_lifted`], `lift` units
//! toward the eye, at most 2¹³) is bounded the same way by
//! `[z_min − lift, z_max + lift]`, then moved ([`Plane::toward_eye`]):
//! its depth lies in `[z_min − 2·lift, z_max]`. A line's quad is planar
//! as the geometry stage delivers it unless the window clip cut it;
//! then rounding tilts it by a few units, and as its two ends' corners
//! are at the extremes of its depths, bounded by `[z_min, z_max]` it
//! would be fitted, its slope scaled down and its depth moved by those
//! few units; the widened range keeps Newell's plane itself.
//!
//! # Depth ranges
//!
//! Every plane a polygon is loaded with has, at every pixel centre the
//! polygon covers, an exact depth between its vertices' depths, inside
//! the Q12.4 range \[−2¹⁵, 2¹⁵) units; a point's or a line's, moved
//! toward the eye, between its vertices' least depth less 2¹⁴ and their
//! greatest: inside \[−2¹⁵ − 2¹⁴, 2¹⁵). Scaled by 2¹⁴ (below) that is
//! \[−2²⁹ − 2²⁸, 2²⁹), and the fixed-point value `Z̃` is within 2¹² of it,
//! so `|Z̃| < 2²⁹ + 2²⁸ + 2¹²` at every covered pixel, and the difference
//! of two faces' `Z̃` at a pixel both cover is below
//! `2³⁰ + 2²⁸ + 2¹³ < 2³¹`: the
//! visible-surface stage's `i32` depth differences never wrap, and its
//! `i64` crossing-point products (a difference times a run of at most
//! 2¹² pixels) stay below 2⁴³. Both ways of resolving a span therefore
//! compare the same planes exactly and draw the same pixels, planar or
//! not. `host_tests/tests/depth_range.rs` tests the corners of the range
//! and random non-planar polygons with overflow checks on.
//!
//! # Depth in fixed point
//!
//! The per-row work uses [`Depth`]: the plane's depth at the centre of
//! pixel `(i, j)`,
//!
//! ```text
//! Z(i, j) = 2¹⁴ · (d − a·(16i + 8) − b·(16j + 8)) / c
//! ```
//!
//! in units of 2⁻¹⁴ of a Q12.4 unit (2⁻¹⁸ px), as
//! `Z̃(i, j) = z + i·zx + j·zy`, all arithmetic wrapping in `i32`: `zx`
//! and `zy` are the slopes rounded to the nearest integer, and `z` makes
//! `Z̃` the rounded depth at an anchor pixel `(i₀, j₀)`, the first
//! vertex's pixel clamped to `0..4096` (there the numerator is small, so
//! the division is in `i64`). The error is at most
//! `½·(1 + |i − i₀| + |j − j₀|) < 2¹²` for `0 ≤ i, j < 4096`, so two depths that
//! differ by [`DEPTH_TOLERANCE`] (2¹³) or more compare the same way exactly;
//! closer ones are compared exactly with [`Plane::cmp_at`]. The value is
//! exact modulo 2³², so huge slopes (faces nearly edge-on) wrap but still
//! give the right depth wherever the true depth is in range: inside a
//! polygon it lies between its vertices' depths (see *Depth ranges*
//! above), in \[−2²⁹, 2²⁹) after scaling, and the wrapped sum equals it.
//! Tiny slopes round to zero within the same error bound.
//!
//! Each set-up costs three divisions per polygon and two per trapezoid
//! each time it enters the active list (its edges, rebuilt from their
//! ends: see [`Trapezoid`]); nothing is divided per row. The polygon's
//! three are in `i64` arithmetic whenever `|a|`, `|b|`, `c < 2³¹` (for a
//! simple polygon they are at most twice the areas of its projections,
//! so any up to 512 px across, whatever its depths: 2·2¹³·2¹⁶): the
//! divisor `2c` is normalised once and its reciprocal found by one long
//! division of two 16-bit digits (two 32-bit divisions), after which each
//! of the three, while its quotient fits in 32 bits, is one 32 × 32 →
//! 64-bit multiply-add and at most two corrections; the library's 64-bit
//! division (a loop of about 150 instructions on a 32-bit core) only past
//! that; `i128` only for larger normals. The plane keeps its first vertex, not `d`: every exact use
//! works relative to it, so making a plane multiplies nothing in `i128`.

use crate::fixed::{ceil_px, Vertex, Vertex3, HALF, ONE};
use crate::raster::clip::ClipRect;
use crate::raster::edge::Edge;
use crate::raster::scan::heap_sort;
use core::cmp::Ordering;
use core::fmt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// Fraction bits of [`Depth`] below a Q12.4 unit of depth.
pub const Z_FRAC_BITS: u32 = 14;

/// Two fixed-point depths that differ by at least this much compare the
/// same way as the exact depths (the error of each is below 2¹²).
pub const DEPTH_TOLERANCE: i64 = 1 << 13;

/// Most vertices a polygon may have (the display list's limit).
pub const MAX_VERTICES: usize = u16::MAX as usize;

/// The plane of a polygon in screen space, exactly: `a·x + b·y + c·z = d`
/// with `x, y, z` in units of 1/16, `c > 0`. See the [module](self) docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[doc(hidden)]
pub struct Plane {
    a: i64,
    b: i64,
    c: i64,
    /// The point it was made through (the first vertex, its depth less
    /// [`LINE_BIAS`](crate::visible::store::LINE_BIAS) for a point or a
    /// line: [`Plane::toward_eye`]), in
    /// units. The right-hand side `d = a·x₀ + b·y₀ + c·z₀` is not kept:
    /// every use works relative to this point ([`Plane::offset`]
    /// computes `d`).
    origin: (i16, i16, i32),
}

/// The running sums of [`Plane::of`], fed one edge at a time.
#[derive(Clone, Copy, Debug, Default)]
struct PlaneSums {
    a: i64,
    b: i64,
    c: i64,
    first: Vertex3,
    n: i64,
    /// The vertices' least and greatest depth, in units.
    z: (i32, i32),
    /// Found that the plane's depth stays within `z` at every vertex, as
    /// [`Polygon::bounded`]'s usual case checks at the edges' ends (which
    /// are vertices): the plane needs no check then. `false` when not
    /// looked at.
    within: bool,
}

impl PlaneSums {
    /// Adds the edge `p → q` (the first call names the first vertex). Each
    /// difference and sum of coordinates is below 2¹⁶ in magnitude, so
    /// each term is one 32 × 32 → 64-bit multiply, below 2³², and there
    /// are at most 65535 of them.
    #[inline]
    fn edge(&mut self, p: Vertex3, q: Vertex3) {
        let (px, py, pz) = (p.x.units(), p.y.units(), p.z.units());
        let (qx, qy, qz) = (q.x.units(), q.y.units(), q.z.units());
        self.a += (py - qy) as i64 * (pz + qz) as i64;
        self.b += (pz - qz) as i64 * (px + qx) as i64;
        self.c += (px - qx) as i64 * (py + qy) as i64;
        if self.n == 0 {
            self.first = p;
            self.z = (pz, pz);
        }
        self.z = (self.z.0.min(qz), self.z.1.max(qz));
        self.n += 1;
    }

    fn finish(&self) -> Option<Plane> {
        if self.c == 0 || self.n == 0 {
            return None;
        }
        let f = self.first;
        let sign = if self.c < 0 { -1 } else { 1 };
        let (a, b, c) = (sign * self.a, sign * self.b, sign * self.c);
        Some(Plane {
            a,
            b,
            c,
            origin: (f.x.to_bits(), f.y.to_bits(), f.z.units()),
        })
    }
}

/// The first pass of [`Polygon::load`] over a polygon's vertices:
/// Newell's sums, the depth range and the columns' range, in units. Its
/// `c` is twice the signed area, the shoelace sum of
/// [`front_facing`](crate::visible::store::front_facing) exactly (the terms
/// `xₖyₖ` it adds cancel round the polygon).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Outline {
    /// `None`: no vertex.
    sums: Option<PlaneSums>,
    x: (i32, i32),
}

impl Outline {
    /// The outline of the polygon through `it` (closed implicitly).
    /// Fails when it has more than [`MAX_VERTICES`] vertices.
    ///
    /// A triangle's or a quadrilateral's (as its iterator's size hint
    /// says) is worked out from its vertices at once: Newell's sums are
    /// twice its vector area, `Σ vₖ × vₖ₊₁`, which is `(v₁ − v₀) × (v₂ − v₀)`
    /// for three vertices and `(v₂ − v₀) × (v₃ − v₁)` for four, exactly
    /// (the same integers; each difference below 2¹⁶, each product one
    /// 32 × 32 → 64-bit multiply). Six multiplies instead of nine or
    /// twelve, and no loop.
    #[inline(always)]
    pub(crate) fn of<I: Iterator<Item = Vertex3> + Clone>(it: I) -> Result<Outline, LoadError> {
        let mut q = it.clone();
        match q.size_hint() {
            (3, Some(3)) => {
                if let (Some(p0), Some(p1), Some(p2)) = (q.next(), q.next(), q.next()) {
                    let u = Outline::units(p0);
                    let (v1, v2) = (Outline::units(p1), Outline::units(p2));
                    let d1 = (v1.0 - u.0, v1.1 - u.1, v1.2 - u.2);
                    let d2 = (v2.0 - u.0, v2.1 - u.1, v2.2 - u.2);
                    return Ok(Outline::of_cross(p0, 3, d1, d2, [u, v1, v2, v2]));
                }
            }
            (4, Some(4)) => {
                if let (Some(p0), Some(p1), Some(p2), Some(p3)) =
                    (q.next(), q.next(), q.next(), q.next())
                {
                    let u = Outline::units(p0);
                    let (v1, v2, v3) = (Outline::units(p1), Outline::units(p2), Outline::units(p3));
                    let d1 = (v2.0 - u.0, v2.1 - u.1, v2.2 - u.2);
                    let d2 = (v3.0 - v1.0, v3.1 - v1.1, v3.2 - v1.2);
                    return Ok(Outline::of_cross(p0, 4, d1, d2, [u, v1, v2, v3]));
                }
            }
            _ => {}
        }
        Outline::walk(it, |_, _| Ok(()))
    }

    /// A vertex in units.
    #[inline(always)]
    fn units(v: Vertex3) -> (i32, i32, i32) {
        (v.x.units(), v.y.units(), v.z.units())
    }

    /// The outline of `n` (3 or 4) vertices `v` (a triangle's third
    /// repeated), the first `first`, whose Newell sums are `p × q`.
    #[inline(always)]
    fn of_cross(
        first: Vertex3,
        n: i64,
        p: (i32, i32, i32),
        q: (i32, i32, i32),
        v: [(i32, i32, i32); 4],
    ) -> Outline {
        let m = |a: i32, b: i32| a as i64 * b as i64;
        let (mut zlo, mut zhi, mut lo, mut hi) = (v[0].2, v[0].2, v[0].0, v[0].0);
        for w in &v[1..] {
            zlo = zlo.min(w.2);
            zhi = zhi.max(w.2);
            lo = lo.min(w.0);
            hi = hi.max(w.0);
        }
        let (a, b, c) = (
            m(p.1, q.2) - m(p.2, q.1),
            m(p.2, q.0) - m(p.0, q.2),
            m(p.0, q.1) - m(p.1, q.0),
        );
        // A quadrilateral's depth check at its vertices, as
        // `Polygon::bounded`'s usual case makes it at the edges' ends
        // (same bounds), on the plane as `PlaneSums::finish` turns it.
        // Parallel to the screen: the depth is z₀ everywhere.
        let within = n == 4
            && (a | b == 0 && c != 0
                || match (i32::try_from(a), i32::try_from(b), i32::try_from(c)) {
                    (Ok(a), Ok(b), Ok(c)) if c != 0 => {
                        let (a, b, c) = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
                        let (x0, y0, z0) = v[0];
                        let (zl, zh) = ((zlo - z0) as i64 * c as i64, (zhi - z0) as i64 * c as i64);
                        v[1..].iter().all(|w| {
                            let e = m(a, x0 - w.0) + m(b, y0 - w.1);
                            zl <= e && e <= zh
                        })
                    }
                    _ => false,
                });
        Outline {
            sums: Some(PlaneSums {
                a,
                b,
                c,
                first,
                n,
                z: (zlo, zhi),
                within,
            }),
            x: (lo, hi),
        }
    }

    /// [`Outline::of`], handing each edge (its ends' `x` and `y` in units,
    /// the closing edge last) to `edge` in the same loop.
    #[inline(always)]
    pub(crate) fn walk<I, F>(mut it: I, mut edge: F) -> Result<Outline, LoadError>
    where
        I: Iterator<Item = Vertex3>,
        F: FnMut((i32, i32), (i32, i32)) -> Result<(), LoadError>,
    {
        let Some(first) = it.next() else {
            return Ok(Outline {
                sums: None,
                x: (0, 0),
            });
        };
        // Kept in locals with the first vertex peeled (see
        // `PlaneSums::edge` for the bounds).
        let (fx, fy, fz) = (first.x.units(), first.y.units(), first.z.units());
        let (mut px, mut py, mut pz) = (fx, fy, fz);
        let (mut sa, mut sb, mut sc) = (0i64, 0i64, 0i64);
        let (mut zlo, mut zhi) = (fz, fz);
        let (mut lo, mut hi) = (fx, fx);
        let mut count = 1usize;
        for v in it {
            count += 1;
            if count > MAX_VERTICES {
                return Err(LoadError::Vertices);
            }
            let (x, y, z) = (v.x.units(), v.y.units(), v.z.units());
            sa += (py - y) as i64 * (pz + z) as i64;
            sb += (pz - z) as i64 * (px + x) as i64;
            sc += (px - x) as i64 * (py + y) as i64;
            zlo = zlo.min(z);
            zhi = zhi.max(z);
            lo = lo.min(x);
            hi = hi.max(x);
            edge((px, py), (x, y))?;
            (px, py, pz) = (x, y, z);
        }
        sa += (py - fy) as i64 * (pz + fz) as i64;
        sb += (pz - fz) as i64 * (px + fx) as i64;
        sc += (px - fx) as i64 * (py + fy) as i64;
        edge((px, py), (fx, fy))?;
        Ok(Outline {
            sums: Some(PlaneSums {
                a: sa,
                b: sb,
                c: sc,
                first,
                n: count as i64,
                z: (zlo, zhi),
                within: false,
            }),
            x: (lo, hi),
        })
    }

    /// `true` when the polygon is counter-clockwise as displayed (y
    /// down): [`front_facing`](crate::visible::store::front_facing).
    #[inline(always)]
    pub(crate) fn front(&self) -> bool {
        self.sums.is_some_and(|s| s.c < 0)
    }
}

impl Plane {
    /// The plane `z = 0` (placeholder of unused slots).
    pub const FLAT: Plane = Plane {
        a: 0,
        b: 0,
        c: 1,
        origin: (0, 0, 0),
    };

    /// The plane of the polygon through `vertices` (closed implicitly), or
    /// `None` when it is edge-on (zero signed area in screen space), has
    /// no vertex, or has more than [`MAX_VERTICES`].
    pub fn of<I: IntoIterator<Item = Vertex3>>(vertices: I) -> Option<Plane> {
        let mut sums = PlaneSums::default();
        let mut it = vertices.into_iter();
        let first = it.next()?;
        let mut prev = first;
        for v in it {
            if sums.n as usize >= MAX_VERTICES - 1 {
                return None;
            }
            sums.edge(prev, v);
            prev = v;
        }
        sums.edge(prev, first);
        sums.finish()
    }

    /// `true` when `v` lies on the plane exactly: always for the vertices
    /// of a triangle, for all vertices of a planar polygon.
    pub fn contains(&self, v: Vertex3) -> bool {
        let (x0, y0, z0) = self.origin_units();
        let (x, y, z) = (
            (v.x.units() - x0) as i128,
            (v.y.units() - y0) as i128,
            (v.z.units() - z0) as i128,
        );
        // Each product below 2⁶⁵, the sum below 2⁶⁷.
        self.a as i128 * x + self.b as i128 * y + self.c as i128 * z == 0
    }

    /// The first vertex, in units.
    #[inline]
    pub(crate) fn origin_units(&self) -> (i32, i32, i32) {
        (self.origin.0 as i32, self.origin.1 as i32, self.origin.2)
    }

    /// The same plane moved `steps` units of depth toward the eye: its
    /// depth less `steps` everywhere (`0 ≤ steps ≤ 2¹⁴`). For a polygon's
    /// plane (depth within the Q12.4 range at every pixel it covers), the
    /// depth stays within \[−2¹⁵ − 2¹⁴, 2¹⁵) units: see *Depth ranges* in
    /// the [module](self) docs.
    pub fn toward_eye(&self, steps: u16) -> Plane {
        let steps = steps.min(1 << 14) as i32;
        Plane {
            origin: (self.origin.0, self.origin.1, self.origin.2 - steps),
            ..*self
        }
    }

    /// `d − a·x − b·y = a·(x₀ − x) + b·(y₀ − y) + c·z₀` for `x`, `y` in
    /// units: `c` times the depth at `(x, y)`. Below 2⁶⁷ for `|x|, |y| <
    /// 2¹⁷` (each of `a`, `b`, `c` is below 2⁴⁸: see [`PlaneSums::edge`]).
    #[inline]
    fn rhs_at(&self, x: i128, y: i128) -> i128 {
        let (x0, y0, z0) = self.origin_units();
        self.a as i128 * (x0 as i128 - x)
            + self.b as i128 * (y0 as i128 - y)
            + self.c as i128 * z0 as i128
    }

    /// `true` when the plane's depth at the point `(x, y)` (units, each
    /// within `i16`) lies in `lo..=hi` (units, each within `±2¹⁶`).
    pub fn depth_within(&self, x: i32, y: i32, (lo, hi): (i32, i32)) -> bool {
        // e < 2⁶⁷ (see `rhs_at`), lo·c and hi·c below 2⁶³.
        let e = self.rhs_at(x as i128, y as i128);
        let c = self.c as i128;
        e >= lo as i128 * c && e <= hi as i128 * c
    }

    /// The plane through the same first vertex with the slopes scaled by
    /// `k / 2¹⁶` (`0 ≤ k ≤ 2¹⁶`), rounded toward zero: `(a·k / 2¹⁶,
    /// b·k / 2¹⁶, c)`. With `k = 0`, the plane of constant depth `z₀`.
    fn flattened(&self, k: i64) -> Plane {
        // |a|·k < 2⁶⁴ in `i128`; the quotient is below |a|.
        let scale = |v: i64| (v as i128 * k as i128 / (1 << 16)) as i64;
        Plane {
            a: scale(self.a),
            b: scale(self.b),
            c: self.c,
            origin: self.origin,
        }
    }

    /// The normal `(a, b, c)`, `c > 0`.
    pub fn normal(&self) -> (i64, i64, i64) {
        (self.a, self.b, self.c)
    }

    /// The right-hand side `d` (computed: the plane keeps its first
    /// vertex instead).
    pub fn offset(&self) -> i128 {
        self.rhs_at(0, 0)
    }

    /// The depth at the centre of pixel `(i, j)` as the fraction
    /// `num / den` of Q12.4 units, `den = c > 0`.
    pub fn depth_at(&self, i: i32, j: i32) -> (i128, i64) {
        let (px, py) = (16 * i as i128 + 8, 16 * j as i128 + 8);
        (self.rhs_at(px, py), self.c)
    }

    /// Compares the exact depths of two planes at the centre of pixel
    /// `(i, j)`, for `|i|, |j| ≤ 4096`: `Less` when `self` is nearer.
    pub fn cmp_at(&self, other: &Plane, i: i32, j: i32) -> Ordering {
        let (e1, c1) = self.depth_at(i, j);
        let (e2, c2) = other.depth_at(i, j);
        // |e| < 2⁶⁷ and c < 2⁴⁸: the products are below 2¹¹⁵.
        (e1 * c2 as i128).cmp(&(e2 * c1 as i128))
    }

    /// `true` when both slopes of [`Plane::depth`] are below 2³⁰ in
    /// magnitude, so not wrapped: `Z̃` is then, unwrapped, an affine
    /// function in `i64` within the error bound of the plane everywhere
    /// in the frame. False for planes nearly edge-on, whose slopes wrap.
    #[inline]
    pub(crate) fn slopes_fit(&self) -> bool {
        // |zx| ≈ 2¹⁸·|a|/c: below 2³⁰ when |a| < 2¹²·c. Each of a, b, c
        // is below 2⁴⁸ (see `PlaneSums::edge`): this fits `i64` (saturated
        // all the same).
        let lim = self.c.saturating_mul(1 << 12);
        let lim = lim.unsigned_abs();
        self.a.unsigned_abs() < lim && self.b.unsigned_abs() < lim
    }

    /// The fixed-point depth coefficients (see the [module](self) docs).
    pub fn depth(&self) -> Depth {
        let (x0, y0, z0) = self.origin_units();
        // The anchor: the pixel of the first vertex, clamped to the pixel
        // range. A vertex is within `i16`, so `i₀ ≤ 2047` and the clamp
        // only raises a negative pixel to 0: |dx|, |dy| ≤ 2¹⁵ + 8.
        let (i0, j0) = ((x0 >> 4).clamp(0, 4095), (y0 >> 4).clamp(0, 4095));
        let (dx, dy) = (x0 - 16 * i0 - 8, y0 - 16 * j0 - 8);
        let (zx, zy, at) = match (
            i32::try_from(self.a),
            i32::try_from(self.b),
            u32::try_from(self.c),
        ) {
            // The usual case, in `i64`: |a|, |b| < 2³¹ and 0 < c < 2³²,
            // so the slopes' numerators 2¹⁸·|a| are below 2⁴⁹, and the
            // anchor's 2¹⁴·|a·dx + b·dy| at most 2¹⁴·2·2³¹·(2¹⁵ + 8) =
            // 2⁶¹ + 2⁵⁰: within what `round_div64` takes.
            (Ok(a), Ok(b), Ok(c)) if c < 1 << 31 => {
                // Parallel to the screen: both slopes zero, the depth z₀
                // everywhere (each division below would be of zero).
                if a | b == 0 {
                    return Depth {
                        z: z0 << Z_FRAC_BITS,
                        zx: 0,
                        zy: 0,
                    };
                }
                depth_narrow((a, b, c), (dx, dy), z0)
            }
            _ => self.depth_wide(dx, dy),
        };
        // Wrapping to `i32` keeps every value modulo 2³².
        let z = at
            .wrapping_sub(zx.wrapping_mul(i0))
            .wrapping_sub(zy.wrapping_mul(j0));
        Depth { z, zx, zy }
    }

    /// [`Plane::depth`]'s slopes and anchor depth (wrapped) in `i128`, for
    /// any plane: numerators below 2⁸², so the doubling in `round_div`
    /// cannot overflow. Out of line: inlined, its `i128` work gave
    /// [`Plane::depth`] a frame of nearly 400 bytes and more to save.
    #[inline(never)]
    fn depth_wide(&self, dx: i32, dy: i32) -> (i32, i32, i32) {
        let (a, b, c) = (self.a as i128, self.b as i128, self.c);
        let s = 1i128 << Z_FRAC_BITS;
        let zx = round_div(-16 * s * a, c) as i32;
        let zy = round_div(-16 * s * b, c) as i32;
        // Z(i₀, j₀) = 2¹⁴·z₀ + 2¹⁴·(a·(x₀ − px) + b·(y₀ − py)) / c.
        let z0 = self.origin.2 as i128;
        let at = z0 * s + round_div(s * (a * dx as i128 + b * dy as i128), c);
        (zx, zy, at as i32)
    }
}

/// `n / c` rounded to the nearest integer (halves up), `c > 0`, in `i32`
/// or `i64` when the numbers fit.
#[inline]
fn round_div(n: i128, c: i64) -> i128 {
    let (n2, c2) = (2 * n + c as i128, 2 * c as i128);
    // The narrowest division that holds the numbers: on 32-bit targets a
    // 32-bit division is one instruction, a 64-bit one a loop.
    if let (Ok(n2), Ok(c2)) = (i32::try_from(n2), i32::try_from(c2)) {
        return n2.div_euclid(c2) as i128;
    }
    match (i64::try_from(n2), i64::try_from(c2)) {
        (Ok(n2), Ok(c2)) => n2.div_euclid(c2) as i128,
        _ => n2.div_euclid(c2),
    }
}

/// [`Plane::depth`]'s slopes and anchor depth (wrapped) in its usual
/// case, `|a|, |b| < 2³¹` and `0 < c < 2³¹`: three divisions by `c` in
/// `i64`, the divisor normalised once. Out of line, so that the planes
/// parallel to the screen do not pay for its registers.
#[inline(never)]
fn depth_narrow((a, b, c): (i32, i32, u32), (dx, dy): (i32, i32), z0: i32) -> (i32, i32, i32) {
    let (a, b) = (a as i64, b as i64);
    let d = Divisor::new(2 * c);
    let zx = round_div64(-(a << (Z_FRAC_BITS + 4)), c, &d);
    let zy = round_div64(-(b << (Z_FRAC_BITS + 4)), c, &d);
    let n = (a * dx as i64 + b * dy as i64) << Z_FRAC_BITS;
    let at = ((z0 as i64) << Z_FRAC_BITS) + round_div64(n, c, &d);
    (zx as i32, zy as i32, at as i32)
}

/// `n / c` rounded to the nearest integer (halves up), for
/// `|n| ≤ 2⁶² − 2³¹` and `0 < c < 2³¹`: [`round_div`] in `i64`,
/// `⌊(2n + c) / 2c⌋`, where `|2n + c| < 2⁶³` and `2c < 2³²`. `d` is
/// [`Divisor::new`]`(2c)`, made once for the several divisions by one `c`.
#[inline(always)]
fn round_div64(n: i64, c: u32, d: &Divisor) -> i64 {
    d.floor_div(2 * n + c as i64)
}

/// `⌊n / d⌋` for `d > 0` and `|n| < 2⁶³` ([`Divisor::floor_div`]).
#[cfg(test)]
fn floor_div(n: i64, d: u32) -> i64 {
    Divisor::new(d).floor_div(n)
}

/// `u / v` for `v > 0` and `u < v·2³²` ([`Divisor::div_64_32`]).
#[cfg(test)]
fn div_64_32(u: u64, v: u32) -> u32 {
    Divisor::new(v).div_64_32(u)
}

/// A divisor `d > 0` made ready once for several long divisions by it:
/// normalised (shifted left by `s` until its top bit is set, `v`), with
/// its reciprocal `inv = ⌊(2⁶⁴ − 1) / v⌋ − 2³²`, so that each division
/// is a multiply and at most two corrections ([`Divisor::div_64_32`]).
/// A divisor below [`SMALL_DIVISOR`] needs no reciprocal: its divisions
/// are three 32-bit ones ([`small_div_64_32`]).
#[derive(Clone, Copy, Debug)]
struct Divisor {
    d: u32,
    s: u32,
    v: u32,
    inv: u32,
}

impl Divisor {
    #[inline(always)]
    fn new(d: u32) -> Divisor {
        debug_assert!(d > 0);
        if d < SMALL_DIVISOR {
            return Divisor {
                d,
                s: 0,
                v: 0,
                inv: 0,
            };
        }
        let s = d.leading_zeros() & 31;
        let v = d << s;
        // 2⁶⁴ − 1 − 2³²·v = (2³² − 1 − v)·2³² + 2³² − 1, whose top word
        // !v is below v (v ≥ 2³¹): the quotient by v fits in `u32`.
        let inv = knuth_64_32(u64::from(!v) << 32 | 0xffff_ffff, v);
        Divisor { d, s, v, inv }
    }

    /// `⌊n / d⌋` for `|n| < 2⁶³`: when the quotient's magnitude fits in
    /// `u32`, one step of [`Divisor::div_64_32`]; else the library's
    /// 64-bit division (a loop of about 150 instructions on a 32-bit
    /// core), for quotients past 2³² (planes nearly edge-on).
    #[inline(always)]
    fn floor_div(&self, n: i64) -> i64 {
        let d = self.d;
        // ⌊n / d⌋ = −⌈−n / d⌉ = −⌊(−n + d − 1) / d⌋ for n < 0; |n| + d − 1
        // is below 2⁶³ + 2³², within `u64`.
        let m = if n < 0 {
            n.unsigned_abs() + (d as u64 - 1)
        } else {
            n as u64
        };
        // A numerator within 32 bits (a small face's slopes, an anchor
        // near the first vertex) is one 32-bit division.
        let q = if m >> 32 == 0 {
            (m as u32 / d) as u64
        } else if m >> 43 == 0 && d.wrapping_sub(1 << 11) < SMALL_DIVISOR - (1 << 11) {
            // Within 43 bits (a small face's slopes, mostly) and a
            // divisor of 2¹¹ or more, so that the quotient fits `u32`:
            // two digits of the long division.
            small_div_43_32(m, d) as u64
        } else if ((m >> 32) as u32) < d {
            self.div_64_32(m) as u64
        } else {
            m / d as u64
        };
        if n < 0 {
            -(q as i64)
        } else {
            q as i64
        }
    }

    /// `u / d` for `u < d·2³²` (so the quotient fits in `u32`), exactly:
    /// `u` shifted by `s` (nothing lost, and its top word `u₁` below `v`),
    /// the quotient estimated as the top word of `inv·u₁ + u`, plus one,
    /// then corrected by the remainder: down once when it wrapped above
    /// the estimate's low word, up once when it is still `v` or more. The
    /// estimate is never more than one away after the first step, so the
    /// two steps make it exact (division by an invariant integer with a
    /// precomputed reciprocal).
    #[inline(always)]
    fn div_64_32(&self, u: u64) -> u32 {
        debug_assert!(((u >> 32) as u32) < self.d);
        if self.d < SMALL_DIVISOR {
            return small_div_64_32(u, self.d);
        }
        let (s, v) = (self.s, self.v);
        let (hi, lo) = ((u >> 32) as u32, u as u32);
        // `u << s` word by word: `lo >> 1 >> (31 − s)` is `lo >> (32 − s)`
        // for 0 < s < 32 and 0 for s = 0.
        let u1 = hi << s | (lo >> 1) >> (31 - s);
        let u0 = lo << s;
        // inv·u₁ + u₁·2³² + u₀ = u₁·⌊(2⁶⁴ − 1) / v⌋ + u₀ < 2⁶⁴ for u₁ < v.
        let q = (self.inv as u64 * u1 as u64).wrapping_add((u1 as u64) << 32 | u0 as u64);
        let (mut q1, q0) = (((q >> 32) as u32).wrapping_add(1), q as u32);
        let mut r = u0.wrapping_sub(q1.wrapping_mul(v));
        if r > q0 {
            q1 = q1.wrapping_sub(1);
            r = r.wrapping_add(v);
        }
        if r >= v {
            q1 = q1.wrapping_add(1);
        }
        q1
    }
}

/// The divisors below which [`Divisor`] divides by [`small_div_64_32`].
/// [`Plane::depth`] divides by `2c`, where `c` is twice the face's screen
/// area in units of 1/256 px²: below this for faces of less than 2¹¹
/// px².
const SMALL_DIVISOR: u32 = 1 << 21;

/// `u / d` for `0 < d < 2²¹` and `u < d·2³²` (so the quotient fits in
/// `u32`), exactly, by long division in digits of 11, 11 and 10 bits:
/// each partial remainder is below `d`, so with the next digit appended
/// it is below `d·2¹¹ < 2³²`, one 32-bit division, and each quotient
/// digit below `2¹¹`.
#[inline(always)]
fn small_div_64_32(u: u64, d: u32) -> u32 {
    let (hi, lo) = ((u >> 32) as u32, u as u32);
    let t = hi << 11 | lo >> 21;
    let q2 = t / d;
    let t = (t - q2 * d) << 11 | (lo >> 10) & 0x7ff;
    let q1 = t / d;
    let t = (t - q1 * d) << 10 | lo & 0x3ff;
    let q0 = t / d;
    q2 << 21 | q1 << 10 | q0
}

/// `u / d` for `0 < d < 2²¹`, `u < 2⁴³` and `u < d·2³²` (so the quotient
/// fits in `u32`), exactly, by long division in two digits of 32 and 11
/// bits: the first is `u`'s top 32 bits, whose quotient is below 2²¹
/// (that of `u` is below 2³²); the remainder, below `d`, with the last 11
/// bits appended is below `d·2¹¹ < 2³²`, and its quotient below 2¹¹. One
/// 32-bit division each.
#[inline(always)]
fn small_div_43_32(u: u64, d: u32) -> u32 {
    let t = (u >> 11) as u32;
    let q1 = t / d;
    let t = (t - q1 * d) << 11 | u as u32 & 0x7ff;
    let q0 = t / d;
    q1 << 11 | q0
}

/// `u / v` for `v ≥ 2³¹` (normalised) and `u < v·2³²` (so the quotient
/// fits in `u32`), exactly, by long division in two 16-bit digits, each
/// estimated with one 32-bit division and corrected at most twice (Knuth's
/// algorithm D for a two-digit divisor): [`Divisor::new`]'s reciprocal.
/// Out of line: inlined, its correction loop is unrolled into more work
/// than it saves.
#[inline(never)]
fn knuth_64_32(u: u64, v: u32) -> u32 {
    debug_assert!(v >= 1 << 31 && ((u >> 32) as u32) < v);
    const B: u32 = 1 << 16;
    // v's top digit, nonzero: v ≥ 2³¹.
    let vn1 = core::num::NonZeroU32::new(v >> 16).unwrap_or(core::num::NonZeroU32::MIN);
    let vn0 = v & 0xffff;
    let (un32, un10) = ((u >> 32) as u32, u as u32);
    let (un1, un0) = (un10 >> 16, un10 & 0xffff);
    // A digit q̂ = ⌊top / vn1⌋ with remainder r̂, lowered while it is too
    // big, which with v normalised is at most twice; r̂ < B keeps r̂·B +
    // digit within `u32`, and q̂ < B (checked first) keeps q̂·vn0 within
    // it. (Written as a loop, the compiler unrolled it into products
    // for four steps made before the first.)
    let digit = |top: u32, next: u32| -> u32 {
        let too_big = |q: u32, r: u32| q >= B || q * vn0 > (r << 16 | next);
        let q = top / vn1;
        let r = top - q * vn1.get();
        if !too_big(q, r) {
            return q;
        }
        let (q, r) = (q - 1, r + vn1.get());
        if r < B && too_big(q, r) {
            q - 1
        } else {
            q
        }
    };
    let q1 = digit(un32, un1);
    // The remainder after the first digit is below v: exact modulo 2³².
    let un21 = (un32 << 16 | un1).wrapping_sub(q1.wrapping_mul(v));
    let q0 = digit(un21, un0);
    q1 << 16 | q0
}

/// The fixed-point depth of a plane: `Z̃(i, j) = z + i·zx + j·zy`
/// (wrapping) in units of 2⁻¹⁴ of a Q12.4 unit at the centre of pixel
/// `(i, j)`. See the [module](self) docs for the error bound.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[doc(hidden)]
pub struct Depth {
    /// `Z̃` at pixel `(0, 0)` (of the plane, wherever the polygon is;
    /// wrapped).
    pub z: i32,
    /// `∂Z/∂i`: change per pixel to the right.
    pub zx: i32,
    /// `∂Z/∂j`: change per row down.
    pub zy: i32,
}

impl Depth {
    /// A depth not worked out yet: its face's plane gives it when a
    /// trapezoid of the face first shares a row's pixels with another
    /// ([`Face::depth`](crate::visible::store::Face::depth) and the sweep).
    /// Marked by `zx`: a worked-out depth whose `zx` is `i32::MIN` (a
    /// plane nearly edge-on) reads as not worked out, and is worked out
    /// again, to the same values.
    pub const LATER: Depth = Depth {
        z: 0,
        zx: i32::MIN,
        zy: 0,
    };

    /// `true` for [`Depth::LATER`] (any depth whose `zx` is `i32::MIN`).
    #[inline(always)]
    pub fn is_later(&self) -> bool {
        self.zx == i32::MIN
    }

    /// `Z̃(i, j)`.
    #[inline(always)]
    pub fn at(&self, i: i32, j: i32) -> i32 {
        self.z
            .wrapping_add(self.zx.wrapping_mul(i))
            .wrapping_add(self.zy.wrapping_mul(j))
    }
}

/// One trapezoid: a left and a right edge over the rows `top..end`, the
/// columns it may write (its clip window) and its face.
///
/// On row `j` it covers `max(c_left, x0)..min(c_right, x1)` where `c` is
/// each edge's pixel (see the [module](self) docs), possibly nothing.
///
/// # Edges
/// Each edge is kept by its ends in Q12.4 (upper end first), the rows
/// once for both. The exact [`Edge`] stepper is rebuilt from them with
/// [`Edge::new`] over `top..end` when the trapezoid enters the active
/// list ([`Trapezoid::left`], [`Trapezoid::right`]): one division per
/// edge each time, none per row. It is the stepper of the side
/// [`Polygon::cut`] handed over ([`Side::edge`]: the same call on the same
/// ends and rows), field for field, so the pixels are those of the cut.
///
/// # Depth and colour
/// Not here: they are the face's ([`Face`](crate::visible::store::Face)),
/// the same for every trapezoid of it. The depth is the plane's [`Depth`],
/// `Z̃(i, j) = z + i·zx + j·zy`; the active list starts a trapezoid at
/// `Z̃(0, top)` and adds `zy` a row, so the depth of pixel `i` on the
/// current row is one multiply-add, `z + i·zx`, the same function on every
/// trapezoid of a face whatever edge a pixel is reached from.
///
/// # Size
/// 34 bytes (alignment 2): two edges' ends of 8 (four `i16`), and nine
/// `u16`: rows `top` and `end`, face, segment, columns `x0` and `x1`, and
/// the store's three links.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Trapezoid {
    pub(crate) left: Ends,
    pub(crate) right: Ends,
    pub(crate) top: u16,
    pub(crate) end: u16,
    pub(crate) face: u16,
    pub(crate) segment: u16,
    pub(crate) x0: u16,
    pub(crate) x1: u16,
    pub(crate) next_row: u16,
    pub(crate) prev_row: u16,
    pub(crate) next_seg: u16,
}

/// "No link" in the store's `u16` links.
pub(crate) const NONE: u16 = u16::MAX;

/// A colour as `0x00rrggbb`.
#[inline]
pub(crate) fn rgb_bits(c: Rgb888) -> u32 {
    (c.r() as u32) << 16 | (c.g() as u32) << 8 | c.b() as u32
}

/// One side of a trapezoid as [`Polygon::cut`] hands it over: the edge's
/// ends (Q12.4, upper end first) and the trapezoid's rows `top..end`, a
/// run of rows the edge crosses, inside the clip (so within `0..=4096`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[doc(hidden)]
pub struct Side {
    ends: Ends,
    top: u16,
    end: u16,
}

impl Side {
    /// The edge's ends, upper first.
    pub fn ends(&self) -> (Vertex, Vertex) {
        (self.ends.a(), self.ends.b())
    }

    /// The rows `top..end`.
    pub fn rows(&self) -> (i32, i32) {
        (self.top as i32, self.end as i32)
    }

    /// The exact stepper over the rows, as of the first.
    pub fn edge(&self) -> Edge {
        self.ends.stepper(self.rows())
    }

    /// The ends and the rows as the store keeps them.
    #[inline(always)]
    pub(crate) fn parts(&self) -> (Ends, u16, u16) {
        (self.ends, self.top, self.end)
    }
}

#[doc(hidden)]
impl Trapezoid {
    /// An unused slot.
    pub const EMPTY: Trapezoid = Trapezoid {
        left: Ends {
            x0: 0,
            y0: 0,
            x1: 0,
            y1: 0,
        },
        right: Ends {
            x0: 0,
            y0: 0,
            x1: 0,
            y1: 0,
        },
        top: 0,
        end: 0,
        face: NONE,
        segment: NONE,
        x0: 0,
        x1: 0,
        next_row: NONE,
        prev_row: NONE,
        next_seg: NONE,
    };

    /// The trapezoid between `left` and `right` (from one call of
    /// [`Polygon::cut`]'s `emit`: the same rows) of face `face`, writing
    /// only the columns of `clip`.
    pub fn new(left: Side, right: Side, face: u16, clip: &ClipRect) -> Self {
        debug_assert_eq!(left.rows(), right.rows());
        Trapezoid {
            left: left.ends,
            right: right.ends,
            top: left.top,
            end: left.end,
            face,
            segment: NONE,
            x0: clip.x0(),
            x1: clip.x1(),
            next_row: NONE,
            prev_row: NONE,
            next_seg: NONE,
        }
    }

    /// First row.
    #[inline(always)]
    pub fn top(&self) -> i32 {
        self.top as i32
    }

    /// One past the last row.
    #[inline(always)]
    pub fn end(&self) -> i32 {
        self.end as i32
    }

    /// The left edge's stepper, as of the top row (rebuilt from its ends).
    #[inline]
    pub fn left(&self) -> Edge {
        self.left.stepper((self.top(), self.end()))
    }

    /// The right edge's stepper, as of the top row (rebuilt from its ends).
    #[inline]
    pub fn right(&self) -> Edge {
        self.right.stepper((self.top(), self.end()))
    }

    /// The left edge as stored.
    pub fn left_side(&self) -> Side {
        Side {
            ends: self.left,
            top: self.top,
            end: self.end,
        }
    }

    /// The right edge as stored.
    pub fn right_side(&self) -> Side {
        Side {
            ends: self.right,
            top: self.top,
            end: self.end,
        }
    }

    /// The face (polygon) it belongs to: its depth and colour.
    pub fn face(&self) -> u16 {
        self.face
    }

    /// The segment that owns it (`0xffff` before it is stored).
    pub fn segment(&self) -> u16 {
        self.segment
    }

    /// The columns `x0..x1` it may write.
    pub fn columns(&self) -> (u16, u16) {
        (self.x0, self.x1)
    }

    /// Columns `lo..hi` that hold every pixel it covers on any of its
    /// rows (possibly more): its edges' extreme ends, cut to its columns.
    /// For painting (`visible::sweep`'s `paint`).
    pub(crate) fn column_bounds(&self) -> (i32, i32) {
        let (l, r) = (self.left, self.right);
        // A pixel i on a row is covered only if its centre 16·i + 8 is at
        // or right of the left crossing, so i ≥ ⌊(x − 8)/16⌋ for the
        // least x of the left edge, and left of the right crossing.
        let lo = ((l.x0.min(l.x1) as i32 - HALF) >> 4).max(self.x0 as i32);
        let hi = (((r.x0.max(r.x1) as i32 - HALF) >> 4) + 1).min(self.x1 as i32);
        (lo, hi)
    }

    /// Every field but the store's links, as `i32`s: two trapezoids with
    /// the same fields and faces of the same depth and colour draw the
    /// same pixels.
    pub(crate) fn fields(&self) -> [i32; 12] {
        let (l, r) = (self.left, self.right);
        [
            l.x0 as i32,
            l.y0 as i32,
            l.x1 as i32,
            l.y1 as i32,
            r.x0 as i32,
            r.y0 as i32,
            r.x1 as i32,
            r.y1 as i32,
            self.top as i32,
            self.end as i32,
            self.x0 as i32,
            self.x1 as i32,
        ]
    }

    /// The pixels `l..r` it covers on row `j` (clipped to its columns;
    /// `l ≥ r` when none), computed directly; `None` outside its rows.
    /// For tests and tools: the renderer steps instead.
    pub fn span_at(&self, j: i32) -> Option<(i32, i32)> {
        if j < self.top() || j >= self.end() {
            return None;
        }
        let (mut l, mut r) = (self.left(), self.right());
        for _ in self.top()..j {
            l.step();
            r.step();
        }
        l.load_pixel();
        r.load_pixel();
        Some((l.pixel().max(self.x0 as i32), r.pixel().min(self.x1 as i32)))
    }
}

/// The ends of an edge in units, upper end first (`y0 < y1`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Ends {
    x0: i16,
    y0: i16,
    x1: i16,
    y1: i16,
}

impl Ends {
    fn a(&self) -> Vertex {
        Vertex::from_bits(self.x0, self.y0)
    }
    fn b(&self) -> Vertex {
        Vertex::from_bits(self.x1, self.y1)
    }
    /// The exact stepper over `rows`, a run of rows the edge crosses (as
    /// the cut stores them): [`Edge::new`]'s, set up without its tests
    /// (a debug build checks the two are equal).
    #[inline]
    fn stepper(&self, rows: (i32, i32)) -> Edge {
        let e = Edge::on_rows(
            self.x0 as i32,
            self.y0 as i32,
            self.x1 as i32,
            self.y1 as i32,
            rows,
        );
        debug_assert_eq!(Edge::new(self.a(), self.b(), rows), Some(e));
        e
    }
    /// The crossing with the centre line of row `j` as `num / den`,
    /// `den = dy > 0`: `num = x0·dy + (yc − y0)·dx`, below 2³³ for a row
    /// the edge crosses.
    #[inline]
    fn crossing(&self, j: i32) -> (i64, i64) {
        let (x0, y0, x1, y1) = (
            self.x0 as i64,
            self.y0 as i64,
            self.x1 as i64,
            self.y1 as i64,
        );
        let yc = j as i64 * ONE as i64 + HALF as i64;
        let dy = y1 - y0;
        (x0 * dy + (yc - y0) * (x1 - x0), dy)
    }
}

/// A trapezoid being built: its left edge holds it, with its right edge
/// and its first row (a row of the clip, so within `0..4096`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Open {
    right: Ends,
    right_id: u16,
    start: i16,
}

/// Scratch storage for one edge while a polygon is cut (32 bytes, so
/// that moving one is a few word loads and stores). The
/// caller owns it, as the edge storage of a
/// [`Rasterizer`](crate::raster::scan::Rasterizer): a polygon of `n` vertices needs
/// at most `n` slots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeSlot {
    ends: Ends,
    top: i32,
    end: i32,
    id: u16,
    open: Option<Open>,
}

#[doc(hidden)]
impl EdgeSlot {
    /// An unused slot.
    pub const EMPTY: EdgeSlot = EdgeSlot {
        ends: Ends {
            x0: 0,
            y0: 0,
            x1: 0,
            y1: 0,
        },
        top: 0,
        end: 0,
        id: 0,
        open: None,
    };
}

/// Why a polygon could not be loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
#[doc(hidden)]
pub enum LoadError {
    /// More edges cross the clip rows than there are [`EdgeSlot`]s.
    Edges {
        /// Slots available.
        capacity: usize,
    },
    /// More than [`MAX_VERTICES`] vertices.
    Vertices,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::Edges { capacity } => {
                write!(
                    f,
                    "polygon needs more than the {capacity} edge slots available"
                )
            }
            LoadError::Vertices => write!(f, "polygon has more than {MAX_VERTICES} vertices"),
        }
    }
}

impl core::error::Error for LoadError {}

/// A polygon loaded into edge slots, ready to be cut into trapezoids.
#[derive(Debug)]
#[doc(hidden)]
pub struct Polygon<'s> {
    slots: &'s mut [EdgeSlot],
    edges: usize,
    plane: Option<Plane>,
    cols: (i32, i32),
    /// Three vertices: [`Polygon::cut_triangles`] tries [`cut_triangle`] first.
    triangle: bool,
}

/// What [`cut_chains`] needs of the rows of the edges set up: the first
/// row and the first edge that starts on it, how many do, the last row
/// (one past), and the rows of all edges added up (each below 4097, at
/// most 65535 edges: below 2²⁸). Found in one pass over the slots
/// ([`Rows::of`]), kept out of [`Polygon::load`]'s loop.
#[derive(Clone, Copy, Debug)]
struct Rows {
    first: i32,
    first_edge: usize,
    starting: u32,
    end: i32,
    sum: u32,
}

impl<'s> Polygon<'s> {
    /// Sets up the edges of the polygon through `vertices` (closed
    /// implicitly) that cross a row centre inside `clip`, and its plane,
    /// in one pass over the vertices, then one over the edges (a few for a
    /// plane that leaves its vertices' depth range: see *Non-planar polygons* in the
    /// [module](self) docs).
    ///
    /// Only edges inside the clip rows take a slot. A polygon whose box
    /// misses the clip columns loads no edge.
    ///
    /// Always inlined: returned by value from a call, the polygon (about
    /// 80 bytes on 32-bit targets) is copied with `memcpy`, a call per
    /// face that inlining avoids.
    #[inline(always)]
    pub fn load<I>(
        slots: &'s mut [EdgeSlot],
        vertices: I,
        clip: &ClipRect,
    ) -> Result<Self, LoadError>
    where
        I: IntoIterator<Item = Vertex3>,
    {
        Polygon::load_lifted(slots, vertices, clip, 0)
    }

    /// [`Polygon::load`] with the plane moved `lift` units of depth
    /// toward the eye ([`Plane::toward_eye`]; `lift ≤ 2¹³`, more is
    /// taken as 2¹³), as the store does for points and lines: the plane
    /// is kept within `[z_min − lift, z_max + lift]`, then moved, so its
    /// depth lies within `[z_min − 2·lift, z_max]` (see *Non-planar
    /// polygons* in the [module](self) docs).
    #[inline(always)]
    pub fn load_lifted<I>(
        slots: &'s mut [EdgeSlot],
        vertices: I,
        clip: &ClipRect,
        lift: u16,
    ) -> Result<Self, LoadError>
    where
        I: IntoIterator<Item = Vertex3>,
    {
        let rows = (clip.y0() as i32, clip.y1() as i32);
        let mut poly = Polygon::empty(slots, clip);
        // `Outline::of` and the edges in one loop.
        let outline = Outline::walk(vertices.into_iter(), |p, q| poly.push(p, q, rows))?;
        if let Some(sums) = outline.sums {
            poly.finish(&sums, outline.x, clip, lift.min(1 << 13));
        }
        Ok(poly)
    }

    /// [`Polygon::load`] in two passes over the vertices: the second, over
    /// the edges, of the vertices `it` whose first (their [`Outline`],
    /// which is also a `poly3`'s cull) is `outline`. With fewer values to
    /// keep in registers, each loop spills less on a 32-bit core.
    #[inline(always)]
    pub(crate) fn load_edges<I>(
        slots: &'s mut [EdgeSlot],
        mut it: I,
        outline: Outline,
        clip: &ClipRect,
    ) -> Result<Self, LoadError>
    where
        I: Iterator<Item = Vertex3>,
    {
        let rows = (clip.y0() as i32, clip.y1() as i32);
        let mut poly = Polygon::empty(slots, clip);
        let (Some(sums), Some(first)) = (outline.sums, it.next()) else {
            return Ok(poly);
        };
        let (fx, fy) = (first.x.units(), first.y.units());
        let (mut px, mut py) = (fx, fy);
        for v in it {
            let (x, y) = (v.x.units(), v.y.units());
            poly.push((px, py), (x, y), rows)?;
            (px, py) = (x, y);
        }
        poly.push((px, py), (fx, fy), rows)?;
        poly.finish(&sums, outline.x, clip, 0);
        Ok(poly)
    }

    /// No edge yet, no plane.
    #[inline(always)]
    fn empty(slots: &'s mut [EdgeSlot], clip: &ClipRect) -> Self {
        Polygon {
            slots,
            edges: 0,
            plane: None,
            cols: (clip.x0() as i32, clip.x1() as i32),
            triangle: false,
        }
    }

    /// After the edges: none when the polygon's columns (`x`, the least
    /// and greatest vertex x in units) miss the clip's, and the plane,
    /// moved `lift` toward the eye.
    #[inline(always)]
    fn finish(&mut self, sums: &PlaneSums, (lo, hi): (i32, i32), clip: &ClipRect, lift: u16) {
        // Columns covered lie in ⌈lo − ½⌉..⌈hi − ½⌉.
        let cols = self.cols;
        if clip.is_empty() || ceil_px(hi - HALF) <= cols.0 || ceil_px(lo - HALF) >= cols.1 {
            self.edges = 0;
        }
        // A triangle's plane passes through its three vertices: nothing to
        // check.
        // A line's quad is planar but for the rounding of its corners,
        // and the corners at each end are at an extreme of its depths:
        // bounded by `[z_min, z_max]`, a plane that rounding tilts past
        // one of them would be fitted, scaled and moved by a few units.
        // Bounded by `[z_min − lift, z_max + lift]`, it is kept whole
        // unless the tilt exceeds `lift`; moved, it lies in
        // `[z_min − 2·lift, z_max]`.
        let (zlo, zhi) = (sums.z.0 - lift as i32, sums.z.1 + lift as i32);
        self.triangle = sums.n == 3;
        self.plane = match sums.n {
            ..=3 => sums.finish(),
            _ if sums.within => sums.finish(),
            _ => sums.finish().map(|p| self.bounded(p, (zlo, zhi))),
        };
        if let (Some(p), 1..) = (&mut self.plane, lift) {
            *p = p.toward_eye(lift);
        }
    }

    /// `plane`, or if its depth leaves `z` (the vertices' depth range) at
    /// an end of an edge set up, a fitted plane whose depth does not
    /// (see *Non-planar polygons* in the [module](self) docs).
    fn bounded(&self, plane: Plane, z: (i32, i32)) -> Plane {
        let slots = &self.slots[..self.edges];
        let holds = |p: &Plane| {
            slots.iter().all(|e| {
                let e = &e.ends;
                p.depth_within(e.x0 as i32, e.y0 as i32, z)
                    && p.depth_within(e.x1 as i32, e.y1 as i32, z)
            })
        };
        // The usual case, in `i64`, relative to the first vertex
        // (x₀, y₀, z₀): with |a|, |b|, |c| < 2³¹ and every coordinate
        // difference below 2¹⁶, e = a·(x₀ − x) + b·(y₀ − y) is below 2⁴⁸,
        // (z − z₀)·c below 2⁴⁷, and each product is one 32 × 32 → 64-bit
        // multiply.
        let (a, b, c) = plane.normal();
        // Parallel to the screen: the depth is z₀ everywhere, a vertex's.
        if a == 0 && b == 0 {
            return plane;
        }
        // The plane scaled by k/2¹⁶ about the first vertex holds at k = 0
        // (the depth z₀ of a vertex); when it does not hold at k = 2¹⁶,
        // bisect for a k that holds with k + 1 failing, 16 more checks,
        // multiplies only.
        let lo =
            if let (Ok(a), Ok(b), Ok(_)) = (i32::try_from(a), i32::try_from(b), i32::try_from(c)) {
                // The usual case: `holds(&plane.flattened(k))` in `i64`, the
                // same test. The scaled slopes `a·k / 2¹⁶` (|a·k| < 2⁴⁷,
                // rounded toward zero as `flattened` rounds) are `i32`s again.
                let (x0, y0, z0) = plane.origin_units();
                let (lo, hi) = ((z.0 - z0) as i64 * c, (z.1 - z0) as i64 * c);
                if ends_within(slots, (a, b), (x0, y0), (lo, hi)) {
                    return plane;
                }
                bisect_ends(slots, (a, b), (x0, y0), (lo, hi))
            } else {
                if holds(&plane) {
                    return plane;
                }
                bisect(|k| holds(&plane.flattened(k)))
            };
        // Scaled by k, no depth in the range moves by more than
        // (1 − k/2¹⁶)·(z₁ − z₀): kept when that is at most 2 units, as
        // for a face that rounding tilted past its range by a unit or
        // two. Otherwise (the first vertex at the end of the range the
        // tilt passes, where only small k hold) the plane is fitted.
        if ((1i64 << 16) - lo) * (z.1 - z.0) as i64 <= 2 << 16 {
            return plane.flattened(lo);
        }
        fitted(&plane, slots, z)
    }

    /// Sets up the edge `p → q` (units, each within `i16`) when it
    /// crosses a row centre inside `rows`.
    #[inline(always)]
    fn push(&mut self, p: (i32, i32), q: (i32, i32), rows: (i32, i32)) -> Result<(), LoadError> {
        let ((ax, y0), (bx, y1)) = if p.1 > q.1 { (q, p) } else { (p, q) };
        // The rows of `Edge::new`: centres j·16 + 8 in [y0, y1).
        let top = ceil_px(y0 - HALF).max(rows.0);
        let end = ceil_px(y1 - HALF).min(rows.1);
        if top >= end {
            return Ok(());
        }
        let capacity = self.slots.len();
        let slot = self
            .slots
            .get_mut(self.edges)
            .ok_or(LoadError::Edges { capacity })?;
        *slot = EdgeSlot {
            ends: Ends {
                x0: ax as i16,
                y0: y0 as i16,
                x1: bx as i16,
                y1: y1 as i16,
            },
            top,
            end,
            id: self.edges as u16,
            open: None,
        };
        self.edges += 1;
        Ok(())
    }

    /// The polygon's plane, `None` when it is edge-on: Newell's, or
    /// fitted into its vertices' depth range when that leaves it.
    pub fn plane(&self) -> Option<&Plane> {
        self.plane.as_ref()
    }

    /// Edges set up (those crossing a row centre inside the clip).
    pub fn edges(&self) -> usize {
        self.edges
    }

    /// Cuts the polygon into trapezoids, handing each one's left and right
    /// edges (their ends and its rows: [`Side::edge`] sets up the stepper)
    /// to `emit`, top to bottom in the order they close. Returns how many were emitted. Pairs that can never
    /// write a pixel in the clip columns (both edges the same, or wholly
    /// left or right of the columns) are not emitted.
    pub fn cut<E>(self, emit: impl FnMut(Side, Side) -> Result<(), E>) -> Result<u32, E> {
        self.cut_with::<false, E>(true, emit)
    }

    /// [`Polygon::cut`], a triangle's trapezoids found by [`cut_triangle`]
    /// (the same ones), other polygons' as `cut` finds them.
    pub(crate) fn cut_triangles<E>(
        self,
        emit: impl FnMut(Side, Side) -> Result<(), E>,
    ) -> Result<u32, E> {
        self.cut_with::<true, E>(true, emit)
    }

    /// [`Polygon::cut`], trying the two chains' walk first when `chains`
    /// (the tests compare both ways), and before it a triangle's cut when
    /// `TRI`. Inlined into each adder, as are [`cut_triangle`],
    /// `cut_chains` and `sorted_at`: left to the compiler, which
    /// depends on how many adders there are, the `poly3` adder called
    /// them out of line, about 40 instructions a `poly3` more on the
    /// Cortex-M4.
    #[inline(always)]
    fn cut_with<const TRI: bool, E>(
        self,
        chains: bool,
        emit: impl FnMut(Side, Side) -> Result<(), E>,
    ) -> Result<u32, E> {
        let n = self.edges;
        let slots = &mut self.slots[..n];
        if n < 2 {
            return Ok(0);
        }
        let mut c = Closer {
            emit,
            cols: self.cols,
            count: 0,
            skip: 0,
        };
        if chains {
            // Nothing emitted when the triangle's cut declines.
            if TRI && self.triangle && cut_triangle(slots, &mut c)? {
                return Ok(c.count);
            }
            if cut_chains(slots, Rows::of(slots), &mut c)? {
                return Ok(c.count);
            }
            // The walk stopped where the sweep below is needed: what it
            // emitted is what the sweep emits first, in the same order.
            c.skip = c.count;
        }
        slots.sort_unstable_by_key(|e| e.top);
        // As in `scan`: slots[..active] are active, slots[active..next]
        // finished, slots[next..] wait for their first row.
        let (mut active, mut next) = (0usize, 0usize);
        let mut y = slots[0].top;
        loop {
            if active == 0 {
                match slots.get(next) {
                    Some(e) => y = y.max(e.top),
                    None => break,
                }
            }
            while next < n && slots[next].top <= y {
                swap(slots, active, next);
                slots[active].open = None;
                active += 1;
                next += 1;
            }
            let mut stop = slots.get(next).map_or(i32::MAX, |e| e.top);
            for e in &slots[..active] {
                stop = stop.min(e.end);
            }
            let live = &mut slots[..active];
            let last = stop - 1;
            sort_at(live, y, last);
            let band_end = if sorted_at(live, last) {
                stop
            } else {
                // Sorted on row y, not on `last`: each adjacent pair keeps
                // its order on an interval of rows from y, so the rows where
                // all do are an interval too.
                let (mut lo, mut hi) = (y, last);
                while hi - lo > 1 {
                    let mid = lo + (hi - lo) / 2;
                    if sorted_at(live, mid) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo + 1
            };
            // Close the trapezoids whose pair does not continue from row y.
            for i in 0..live.len() {
                if let Some(op) = live[i].open {
                    let keep = i % 2 == 0 && live.get(i + 1).is_some_and(|r| r.id == op.right_id);
                    if !keep {
                        c.close(&live[i].ends, &op.right, op.start as i32, y)?;
                        live[i].open = None;
                    }
                }
            }
            for pair in live.chunks_exact_mut(2) {
                if pair[0].open.is_none() {
                    pair[0].open = Some(Open {
                        right: pair[1].ends,
                        right_id: pair[1].id,
                        // y is a row of the clip: 0 ≤ y < 4096.
                        start: y as i16,
                    });
                }
            }
            y = band_end;
            let mut i = 0;
            while i < active {
                if slots[i].end <= y {
                    if let Some(op) = slots[i].open.take() {
                        c.close(&slots[i].ends, &op.right, op.start as i32, y)?;
                    }
                    active -= 1;
                    swap(slots, i, active);
                } else {
                    i += 1;
                }
            }
        }
        Ok(c.count)
    }
}

/// The depths of `plane` at the ends of `slots`, in whole units: the
/// least rounded down and the greatest rounded up. Every end shares the
/// plane's `c > 0`, so the least and greatest `c`·depth give them: two
/// divisions.
#[cold]
fn depth_span(plane: &Plane, slots: &[EdgeSlot]) -> (i128, i128) {
    let (lo, hi) = rhs_span(plane, slots);
    // `c` is below 2⁴⁸; `lo` and `hi` fit `i64` but for planes far out
    // of the range, and a 64-bit division is many times cheaper than a
    // 128-bit one on a 32-bit core.
    match (i64::try_from(lo), i64::try_from(hi)) {
        (Ok(lo), Ok(hi)) if hi < i64::MAX => {
            let c = plane.c;
            (lo.div_euclid(c) as i128, -((-hi).div_euclid(c)) as i128)
        }
        _ => {
            let c = plane.c as i128;
            (lo.div_euclid(c), -(-hi).div_euclid(c))
        }
    }
}

/// The least and greatest `c`·depth of `plane` at the ends of `slots`.
fn rhs_span(plane: &Plane, slots: &[EdgeSlot]) -> (i128, i128) {
    // The usual case in `i64`, as in `Polygon::bounded`: with |a|, |b|,
    // |c| < 2³¹, every term is one 32 × 32 → 64-bit multiply and the sum
    // is below 2⁵⁰.
    if let (Ok(a), Ok(b), Ok(c)) = (
        i32::try_from(plane.a),
        i32::try_from(plane.b),
        i32::try_from(plane.c),
    ) {
        let (x0, y0, z0) = plane.origin_units();
        let base = c as i64 * z0 as i64;
        let (mut lo, mut hi) = (i64::MAX, i64::MIN);
        for e in slots.iter().map(|s| &s.ends) {
            for (x, y) in [(e.x0, e.y0), (e.x1, e.y1)] {
                let v =
                    a as i64 * (x0 - x as i32) as i64 + b as i64 * (y0 - y as i32) as i64 + base;
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        return (lo as i128, hi as i128);
    }
    let (mut lo, mut hi) = (i128::MAX, i128::MIN);
    for e in slots.iter().map(|s| &s.ends) {
        for (x, y) in [(e.x0, e.y0), (e.x1, e.y1)] {
            // Below 2⁶⁷: see `Plane::rhs_at`.
            let v = plane.rhs_at(x as i128, y as i128);
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    (lo, hi)
}

/// A plane whose depth lies in `z` at every end of `slots`, as near
/// `plane` as a scale of its slopes and a shift of its depth make it: its
/// slopes scaled by `k / 2¹⁶` ([`Plane::flattened`]) with a `k` whose
/// depths there span no more than `z` does (the full slopes when they
/// do; else the `k` at which the span would be `z`'s, or `z`'s less 2
/// units, or below that by bisection when rounding needs more), then
/// moved by the fewest whole units of depth that bring them into
/// `z`. At `k = 0` the depths span nothing, so one always fits. For the
/// planes that scaling alone, about the first vertex, leaves with little
/// slope (see the [module](self) docs).
#[cold]
#[inline(never)]
fn fitted(plane: &Plane, slots: &[EdgeSlot], z: (i32, i32)) -> Plane {
    let room = (z.1 - z.0) as i128;
    let fits = |k: i64| {
        let (lo, hi) = depth_span(&plane.flattened(k), slots);
        hi - lo <= room
    };
    let k = if fits(1 << 16) {
        1 << 16
    } else {
        // The depths' span scales with k: the k at which it would be the
        // room, then the room less 2 units (for the rounding of the ends'
        // depths and of the slopes), tried first; bisected below that when
        // the rounding is more.
        let (lo, hi) = rhs_span(plane, slots);
        let at = |room: i128| {
            (room.max(0) * plane.c as i128 * (1 << 16) / (hi - lo).max(1)).min((1 << 16) - 1) as i64
        };
        let (mut lo, mut hi) = (0i64, at(room - 2));
        if fits(at(room)) {
            lo = at(room);
            hi = lo;
        } else if fits(hi) {
            lo = hi;
        }
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if fits(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    };
    let scaled = plane.flattened(k);
    let (lo, hi) = depth_span(&scaled, slots);
    // The shifts that fit form `[z₀ − lo, z₁ − hi]`, not empty: take the
    // one nearest zero. It is small unless the first vertex (the origin,
    // whose depth is in `z`) lies far from the ends along a steep slope;
    // past 2¹⁶ units the plane of constant depth is taken instead, so the
    // origin's depth stays within 2¹⁷ units and `Plane::rhs_at` within
    // its bound.
    let shift = (z.0 as i128 - lo).max(0).min(z.1 as i128 - hi);
    if shift.abs() > 1 << 16 {
        return plane.flattened(0);
    }
    let (x0, y0, z0) = scaled.origin;
    Plane {
        origin: (x0, y0, z0 + shift as i32),
        ..scaled
    }
}

/// The `k` in `0..2¹⁶` that [`Polygon::bounded`]'s bisection finds:
/// `holds(k)` true with `holds(k + 1)` false, on the path of midpoints
/// from `(0, 2¹⁶)` (`holds(0)` is true, `holds(2¹⁶)` false).
#[inline(always)]
fn bisect(holds: impl Fn(i64) -> bool) -> i64 {
    let (mut lo, mut hi) = (0i64, 1i64 << 16);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if holds(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// [`bisect`] over `k` with the test of [`ends_within`] for the slopes
/// `a·k / 2¹⁶` and `b·k / 2¹⁶` (rounded toward zero, as
/// [`Plane::flattened`] rounds them): the same steps and the same `k`.
/// For a polygon of at most four edges set up, each distinct end other
/// than the first vertex is tested once a step (a quad's corner ends two
/// edges), its offsets `(x₀ − x, y₀ − y)` taken once.
#[inline(never)]
fn bisect_ends(
    slots: &[EdgeSlot],
    (a, b): (i32, i32),
    (x0, y0): (i32, i32),
    (lo, hi): (i64, i64),
) -> i64 {
    let scale = |v: i32, k: i64| (v as i64 * k / (1 << 16)) as i32;
    if slots.len() > 4 {
        return bisect(|k| ends_within(slots, (scale(a, k), scale(b, k)), (x0, y0), (lo, hi)));
    }
    let mut offsets = [(0i32, 0i32); 8];
    let mut n = 0;
    for s in slots {
        for (x, y) in [(s.ends.x0, s.ends.y0), (s.ends.x1, s.ends.y1)] {
            let d = (x0 - x as i32, y0 - y as i32);
            // The first vertex's depth is z₀, inside the range at any k.
            if d != (0, 0) && !offsets[..n].contains(&d) {
                offsets[n] = d;
                n += 1;
            }
        }
    }
    let offsets = &offsets[..n];
    bisect(|k| {
        let (a, b) = (scale(a, k) as i64, scale(b, k) as i64);
        offsets.iter().all(|&(dx, dy)| {
            let e = a * dx as i64 + b * dy as i64;
            lo <= e && e <= hi
        })
    })
}

/// `true` when `lo ≤ a·(x₀ − x) + b·(y₀ − y) ≤ hi` at both ends `(x, y)`
/// of every slot ([`Polygon::bounded`]'s usual case). Out of line, so
/// that `a` and `b` are `i32`s here and each product one 32 × 32 → 64-bit
/// multiply (inlined, the compiler multiplied the `i64`s they came from).
#[inline(never)]
fn ends_within(
    slots: &[EdgeSlot],
    (a, b): (i32, i32),
    (x0, y0): (i32, i32),
    (lo, hi): (i64, i64),
) -> bool {
    let within = |x: i16, y: i16| {
        let e = a as i64 * (x0 - x as i32) as i64 + b as i64 * (y0 - y as i32) as i64;
        lo <= e && e <= hi
    };
    slots
        .iter()
        .all(|s| within(s.ends.x0, s.ends.y0) && within(s.ends.x1, s.ends.y1))
}

/// Where [`Polygon::cut`] hands its trapezoids: `emit`, less those that
/// can write no pixel in the columns `cols`, and less the first `skip`
/// (made already by [`cut_chains`] before it gave up).
struct Closer<F> {
    emit: F,
    cols: (i32, i32),
    count: u32,
    skip: u32,
}

impl<F> Closer<F> {
    /// The trapezoid between `l` and `r` over the rows `start..end`.
    #[inline]
    fn close<E>(&mut self, l: &Ends, r: &Ends, start: i32, end: i32) -> Result<(), E>
    where
        F: FnMut(Side, Side) -> Result<(), E>,
    {
        if *l == *r || start >= end {
            return Ok(());
        }
        let rmax = r.x0.max(r.x1) as i32;
        let lmin = l.x0.min(l.x1) as i32;
        if ceil_px(rmax - HALF) <= self.cols.0 || ceil_px(lmin - HALF) >= self.cols.1 {
            return Ok(());
        }
        if self.skip > 0 {
            self.skip -= 1;
            return Ok(());
        }
        // Both edges cross every row of `start..end` (they were active
        // in its bands), inside the clip rows (so within 0..=4096): the
        // steppers `Edge::new` makes over them are never `None`.
        let (top, end) = (start as u16, end as u16);
        let side = |ends: Ends| Side { ends, top, end };
        (self.emit)(side(*l), side(*r))?;
        self.count += 1;
        Ok(())
    }
}

impl Rows {
    /// The rows of `slots`, the edges set up in the order loaded.
    #[inline(always)]
    fn of(slots: &[EdgeSlot]) -> Rows {
        let mut r = Rows {
            first: i32::MAX,
            first_edge: 0,
            starting: 0,
            end: i32::MIN,
            sum: 0,
        };
        for (k, e) in slots.iter().enumerate() {
            if e.top < r.first {
                (r.first, r.first_edge, r.starting) = (e.top, k, 1);
            } else if e.top == r.first {
                r.starting += 1;
            }
            r.end = r.end.max(e.end);
            r.sum += (e.end - e.top) as u32;
        }
        r
    }
}

/// The cut of a polygon whose edges set up (in polygon order, as loaded)
/// are two chains, one down and one up, from the two edges that start on
/// the first row to the two that end on the last: every convex polygon,
/// and every other whose rows cross its boundary twice. Then exactly two
/// edges are active on every row, one of each chain, and the sweep's bands
/// are the runs of rows between the chains' vertices: this walk makes the
/// sweep's trapezoids, in the sweep's order, without sorting or moving a
/// slot (two crossings compared a band, the order on the band's first row,
/// ties broken on its last, as [`sort_at`] does).
///
/// `Ok(false)` as soon as the polygon is not such (more than two edges
/// start on the first row, or a chain breaks), or a band is not one the
/// walk can decide as the sweep does (the two edges swap inside it, or
/// coincide on its first and last rows): the trapezoids emitted until
/// then are the sweep's first ones, which [`Closer::skip`] then passes
/// over.
#[inline(always)]
fn cut_chains<F, E>(slots: &[EdgeSlot], rows: Rows, c: &mut Closer<F>) -> Result<bool, E>
where
    F: FnMut(Side, Side) -> Result<(), E>,
{
    let n = slots.len();
    let next = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let prev = |i: usize| if i == 0 { n - 1 } else { i - 1 };
    // Every row from the first to the last is crossed by an even number
    // of edges, at least two (the boundary is closed and connected, and
    // the clip rows are an interval). So when the edges' rows add up to
    // twice the rows, exactly two edges are active on every row: the
    // sweep's bands are those of the walk below, which therefore emits
    // the sweep's first trapezoids even where it stops.
    let mut y = rows.first;
    if rows.starting != 2 || rows.sum as i64 != 2 * (rows.end as i64 - y as i64) {
        return Ok(false);
    }
    // The two edges that start on the first row, next to each other: `u`
    // heads the chain up (walked backwards), `d` the chain down.
    let k = rows.first_edge;
    let (mut u, mut d) = if slots[next(k)].top == y {
        (k, next(k))
    } else if slots[prev(k)].top == y {
        (prev(k), k)
    } else {
        return Ok(false);
    };
    // The trapezoid being built: left slot, right slot, first row.
    let mut open: Option<(usize, usize, i32)> = None;
    loop {
        let (ed, eu) = (&slots[d], &slots[u]);
        let stop = ed.end.min(eu.end);
        let last = stop - 1;
        let Some(d_left) = band_order(ed, eu, y, last) else {
            return Ok(false);
        };
        let (l, r) = if d_left { (d, u) } else { (u, d) };
        match open {
            Some((ol, or, _)) if ol == l && or == r => {}
            _ => {
                if let Some((ol, or, start)) = open {
                    c.close(&slots[ol].ends, &slots[or].ends, start, y)?;
                }
                open = Some((l, r, y));
            }
        }
        y = stop;
        // The chains' next edges: each edge after the first of its chain
        // starts on the row where the one before it ends; at the last
        // row the chains meet.
        let (d_ends, u_ends) = (slots[d].end == y, slots[u].end == y);
        if d_ends && u_ends && next(d) == u {
            break;
        }
        if d_ends {
            d = next(d);
        }
        if u_ends {
            u = prev(u);
        }
        if d == u || (d_ends && slots[d].top != y) || (u_ends && slots[u].top != y) {
            return Ok(false);
        }
    }
    if let Some((ol, or, start)) = open {
        c.close(&slots[ol].ends, &slots[or].ends, start, y)?;
    }
    Ok(true)
}

/// [`cut_chains`]'s cut of a triangle, from the edges set up (`slots`,
/// in polygon order) without the walk: `Ok(false)`, with nothing
/// emitted, where the walk would not finish alone (two edges that
/// coincide or are collinear, a band of one row through the top vertex)
/// or the slots are not what a triangle sets up; the caller then cuts
/// as before.
///
/// Every row of a triangle is crossed by two of its edges. Two set up
/// share the rows and a vertex: one band, ordered by [`band_order`].
/// Three are the long edge from the top vertex T to the bottom one B,
/// which crosses the first and the last row, the edge T → M, which
/// crosses the first, and M → B, which crosses the last: two bands,
/// split at the row where T → M ends and M → B starts. On the first,
/// T → M is left of T → B when `S = (M − T) × (B − T)` is negative
/// (edges from one top vertex: [`band_order`]); on the second, M → B
/// and T → B share B and their cross product is `−S`, so M → B is left
/// of T → B when T → M was. One product for both bands.
#[inline(always)]
fn cut_triangle<F, E>(slots: &[EdgeSlot], c: &mut Closer<F>) -> Result<bool, E>
where
    F: FnMut(Side, Side) -> Result<(), E>,
{
    let (tm, mb, tb) = match slots {
        [p, q] => {
            if p.top != q.top || p.end != q.end {
                return Ok(false);
            }
            let Some(p_left) = band_order(p, q, p.top, p.end - 1) else {
                return Ok(false);
            };
            let (l, r) = if p_left { (p, q) } else { (q, p) };
            c.close(&l.ends, &r.ends, p.top, p.end)?;
            return Ok(true);
        }
        // The long edge is the one of the three whose rows hold the
        // others'; the edge after it in polygon order starts where it
        // starts when the polygon is walked one way, ends where it ends
        // the other way.
        [e0, e1, e2] => {
            let long = |t: &EdgeSlot, o: &EdgeSlot, p: &EdgeSlot| {
                t.top <= o.top.min(p.top) && t.end >= o.end.max(p.end)
            };
            let (tb, x, y) = if long(e0, e1, e2) {
                (e0, e1, e2)
            } else if long(e1, e2, e0) {
                (e1, e2, e0)
            } else {
                (e2, e0, e1)
            };
            if x.top == tb.top {
                (x, y, tb)
            } else {
                (y, x, tb)
            }
        }
        _ => return Ok(false),
    };
    let (t, m, b) = (&tb.ends, &tm.ends, &mb.ends);
    // What a triangle's edges are, checked (a few compares) rather than
    // assumed.
    if tm.top != tb.top
        || tm.end != mb.top
        || mb.end != tb.end
        || (m.x0, m.y0) != (t.x0, t.y0)
        || (b.x1, b.y1) != (t.x1, t.y1)
        || (m.x1, m.y1) != (b.x0, b.y0)
    {
        return Ok(false);
    }
    // Each difference below 2¹⁶, each product below 2³².
    let d = |x0: i16, y0: i16, x1: i16, y1: i16| (x1 as i64 - x0 as i64, y1 as i64 - y0 as i64);
    let (dxm, dym) = d(t.x0, t.y0, m.x1, m.y1);
    let (dxb, dyb) = d(t.x0, t.y0, t.x1, t.y1);
    let s = dxm * dyb - dxb * dym;
    // The first band's last row through T: both crossings are T on it.
    let split = tm.end;
    if s == 0 || (split - 1) * ONE + HALF == t.y0 as i32 {
        return Ok(false);
    }
    if s < 0 {
        c.close(m, t, tb.top, split)?;
        c.close(b, t, split, tb.end)?;
    } else {
        c.close(t, m, tb.top, split)?;
        c.close(t, b, split, tb.end)?;
    }
    Ok(true)
}

/// A triangle's plane and trapezoids worked out from its three vertices
/// at once ([`TriangleCut::of`]): the vertices sorted by `y`, the long
/// edge from the top one to the bottom one and the two short ones, with
/// no edge slots, no outline and no walk. What [`Polygon::load`] and
/// [`Polygon::cut_triangles`] make of the same vertices and clip: the
/// same plane, the same trapezoids in the same order, but for a first
/// band of one row whose centre passes through the top vertex, which
/// has no pixel and is left out (the unit test
/// `direct_triangle_cut_is_the_polygons` compares them).
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleCut {
    plane: Option<Plane>,
    /// The long edge T → B and the short ones T → M and M → B.
    long: Ends,
    upper: Ends,
    lower: Ends,
    /// The bands' rows: `top..split` and `split..end`, either possibly
    /// empty (all zero when the triangle writes nothing).
    top: u16,
    split: u16,
    end: u16,
    /// The short edges are left of the long one.
    short_left: bool,
    /// The clip's columns.
    cols: (i32, i32),
    /// The columns the triangle may cover lie strictly inside `cols`, so
    /// that no band of it can miss them ([`TriangleCut::band`]).
    inside: bool,
}

impl TriangleCut {
    /// The cut of the triangle `v` (in polygon order) under `clip`, or
    /// `None` where `S` below is zero, which it is not for a triangle
    /// with a plane (`|S| = c`): the polygon's cut is then taken. A
    /// triangle whose first band is one row through its top vertex,
    /// which [`cut_triangle`] leaves to the walk, is cut here without
    /// that band (it has no pixel).
    ///
    /// The plane is [`Outline::of`]'s: `(v₁ − v₀) × (v₂ − v₀)`, turned
    /// so that `c > 0`, through `v₀`. Of the edges set up by
    /// [`Polygon::load`], the long one T → B holds the rows of the two
    /// others (T → M above the row where M is passed, M → B below), an
    /// edge set up runs upper end first and one with no row centre takes
    /// no part: so the first band is T → M beside T → B over the long
    /// edge's rows before M's, the second M → B beside T → B over the
    /// rest, either possibly empty, and `S = (M − T) × (B − T)` orders
    /// both ([`cut_triangle`]). When two vertices share a row the order
    /// chosen between them swaps both the sign of `S` and which edge is
    /// called what, so the trapezoids are the same.
    #[inline(always)]
    pub(crate) fn of(v: &[Vertex3; 3], clip: &ClipRect) -> Option<TriangleCut> {
        let u = v.map(|p| (p.x.units(), p.y.units(), p.z.units()));
        let d = |p: (i32, i32, i32)| (p.0 - u[0].0, p.1 - u[0].1, p.2 - u[0].2);
        let (p, q) = (d(u[1]), d(u[2]));
        // Each difference below 2¹⁶, each product below 2³².
        let m = |a: i32, b: i32| a as i64 * b as i64;
        let c = m(p.0, q.1) - m(p.1, q.0);
        let cols = (clip.x0() as i32, clip.x1() as i32);
        let mut cut = TriangleCut {
            plane: None,
            long: Ends::default(),
            upper: Ends::default(),
            lower: Ends::default(),
            top: 0,
            split: 0,
            end: 0,
            short_left: false,
            cols,
            inside: false,
        };
        if c == 0 {
            return Some(cut);
        }
        let (a, b) = (m(p.1, q.2) - m(p.2, q.1), m(p.2, q.0) - m(p.0, q.2));
        // Turned so that c > 0: negated, not multiplied by a sign, which
        // in `i64` is a wide product on a 32-bit core.
        let (a, b, c) = if c < 0 { (-a, -b, -c) } else { (a, b, c) };
        cut.plane = Some(Plane {
            a,
            b,
            c,
            origin: (v[0].x.to_bits(), v[0].y.to_bits(), u[0].2),
        });
        // Columns covered lie in ⌈lo − ½⌉..⌈hi − ½⌉ (`Polygon::finish`).
        let lo = u[0].0.min(u[1].0).min(u[2].0);
        let hi = u[0].0.max(u[1].0).max(u[2].0);
        let (first, last) = (ceil_px(lo - HALF), ceil_px(hi - HALF));
        if clip.is_empty() || last <= cols.0 || first >= cols.1 {
            return Some(cut);
        }
        cut.inside = first > cols.0 && last < cols.1;
        // T, M, B: the vertices' (x, y) sorted by y, moved as values.
        let (mut t, mut mv, mut b) = ((u[0].0, u[0].1), (u[1].0, u[1].1), (u[2].0, u[2].1));
        if mv.1 < t.1 {
            (t, mv) = (mv, t);
        }
        if b.1 < mv.1 {
            (mv, b) = (b, mv);
            if mv.1 < t.1 {
                (t, mv) = (mv, t);
            }
        }
        // The rows of `Edge::new` through each vertex, cut to the clip's.
        let row = |y: i32| ceil_px(y - HALF);
        let top = row(t.1).max(clip.y0() as i32);
        let end = row(b.1).min(clip.y1() as i32);
        if top >= end {
            return Some(cut);
        }
        let split = row(mv.1).max(top).min(end);
        let s = m(mv.0 - t.0, b.1 - t.1) - m(b.0 - t.0, mv.1 - t.1);
        if s == 0 {
            return None;
        }
        // A first band of one row whose centre passes through T: both of
        // its edges cross that row at T, so it has no pixel, and it is
        // left out (the walk emits it, in an order of its own).
        let top = match split > top && (split - 1) * ONE + HALF == t.1 {
            true => split,
            false => top,
        };
        let ends = |p: (i32, i32), q: (i32, i32)| Ends {
            x0: p.0 as i16,
            y0: p.1 as i16,
            x1: q.0 as i16,
            y1: q.1 as i16,
        };
        // Rows of the clip: within 0..=4096.
        (cut.long, cut.upper, cut.lower) = (ends(t, b), ends(t, mv), ends(mv, b));
        (cut.top, cut.split, cut.end) = (top as u16, split as u16, end as u16);
        cut.short_left = s < 0;
        Some(cut)
    }

    /// The triangle's plane, `None` when it is edge-on.
    #[inline(always)]
    pub(crate) fn plane(&self) -> Option<&Plane> {
        self.plane.as_ref()
    }

    /// Hands each trapezoid to `emit` (its left and right edges' ends,
    /// its rows `top..end`: the [`Side`]s [`Polygon::cut_triangles`]
    /// hands over), top to bottom, as `cut_triangles` does; how many.
    #[inline(always)]
    pub(crate) fn cut<E>(
        &self,
        mut emit: impl FnMut(Ends, Ends, u16, u16) -> Result<(), E>,
    ) -> Result<u32, E> {
        let first = self.band(self.upper, self.top, self.split, &mut emit)?;
        let second = self.band(self.lower, self.split, self.end, &mut emit)?;
        Ok(first as u32 + second as u32)
    }

    /// The trapezoid between the short edge `short` and the long one over
    /// `top..end`, handed to `emit` unless it is empty or can write no
    /// pixel in the clip columns (`Closer::close`'s test); `true` when
    /// handed.
    #[inline(always)]
    fn band<E>(
        &self,
        short: Ends,
        top: u16,
        end: u16,
        emit: &mut impl FnMut(Ends, Ends, u16, u16) -> Result<(), E>,
    ) -> Result<bool, E> {
        let (l, r) = match self.short_left {
            true => (short, self.long),
            false => (self.long, short),
        };
        if top >= end {
            return Ok(false);
        }
        // The test of the columns, where the triangle's own do not settle
        // it: each edge's ends are vertices, so a band's columns lie
        // within the triangle's.
        if !self.inside {
            let rmax = r.x0.max(r.x1) as i32;
            let lmin = l.x0.min(l.x1) as i32;
            if ceil_px(rmax - HALF) <= self.cols.0 || ceil_px(lmin - HALF) >= self.cols.1 {
                return Ok(false);
            }
        }
        emit(l, r, top, end)?;
        Ok(true)
    }
}

/// `Some(true)` when `a` is left of `b` on the band of rows `y..=last`
/// (both cross every row of it) as the sweep orders them: by the exact
/// crossings on row `y`, ties broken on row `last`; `Some(false)` when
/// `b` is; `None` when they swap inside the band (the sweep splits it) or
/// coincide on both rows.
///
/// Edges from one upper end `(x₀, y₀)` (a top vertex) differ on the row
/// centre `yc` by `(yc − y₀)·S / (dy_a·dy_b)`, `S = dx_a·dy_b − dx_b·dy_a`,
/// and `yc ≥ y₀` on every row they cross: the order is the sign of `S`,
/// one product each, no crossing worked out. Edges to one lower end
/// (a bottom vertex) likewise, with `yc < y₁`: the opposite sign. Edges
/// whose ends' x ranges are apart are ordered by them alone.
#[inline]
fn band_order(a: &EdgeSlot, b: &EdgeSlot, y: i32, last: i32) -> Option<bool> {
    let (ea, eb) = (&a.ends, &b.ends);
    let top = ea.x0 == eb.x0 && ea.y0 == eb.y0;
    if top || (ea.x1 == eb.x1 && ea.y1 == eb.y1) {
        let d = |e: &Ends| (e.x1 as i64 - e.x0 as i64, e.y1 as i64 - e.y0 as i64);
        let ((dxa, dya), (dxb, dyb)) = (d(ea), d(eb));
        // Each product below 2³², S below 2³³.
        let s = dxa * dyb - dxb * dya;
        // On the last row yc > y₀ unless the band is one row through the
        // shared top: then both crossings are the vertex on both rows.
        let flat = top && last * ONE + HALF == ea.y0 as i32;
        return match s.cmp(&0) {
            Ordering::Equal => None,
            _ if flat => None,
            o => Some(o.is_lt() == top),
        };
    }
    // An edge's crossings lie between its ends' x: edges whose x ranges
    // do not meet are in that order on every row.
    let range = |e: &Ends| (e.x0.min(e.x1), e.x0.max(e.x1));
    let ((a0, a1), (b0, b1)) = (range(ea), range(eb));
    if a1 < b0 {
        return Some(true);
    }
    if b1 < a0 {
        return Some(false);
    }
    match cmp_x(a, b, y) {
        Ordering::Less if !cmp_x(a, b, last).is_gt() => Some(true),
        Ordering::Greater if !cmp_x(a, b, last).is_lt() => Some(false),
        Ordering::Equal => match cmp_x(a, b, last) {
            Ordering::Less => Some(true),
            Ordering::Greater => Some(false),
            Ordering::Equal => None,
        },
        _ => None,
    }
}

/// Swaps slots `a` and `b` as two distinct places (`slice::swap` allows
/// for them being one, and calls a library `memmove` on 32-bit targets).
#[inline(always)]
fn swap(slots: &mut [EdgeSlot], a: usize, b: usize) {
    let (lo, hi) = (a.min(b), a.max(b));
    if lo == hi {
        return;
    }
    let (head, tail) = slots.split_at_mut(hi);
    if let (Some(x), Some(y)) = (head.get_mut(lo), tail.first_mut()) {
        core::mem::swap(x, y);
    }
}

/// Compares the exact crossings of two edges on row `j` (both cross it).
#[inline]
fn cmp_x(a: &EdgeSlot, b: &EdgeSlot, j: i32) -> Ordering {
    let (na, da) = a.ends.crossing(j);
    let (nb, db) = b.ends.crossing(j);
    // |num| < 2³³, den < 2¹⁶: products below 2⁴⁹.
    (na * db).cmp(&(nb * da))
}

/// Insertion sort by the crossing on row `y`, ties by row `last`: one
/// step per inversion, so linear when the order is the last band's. With
/// a budget of `4n` swaps, past which a heap sort
/// ([`heap_sort`], `O(n log n)`, in place) finishes, so that many edges joining in
/// another order, or crossing in one band, cost `O(n log n)`, not `n²/2`.
/// The order is total (exact crossings compared lexicographically).
fn sort_at(e: &mut [EdgeSlot], y: i32, last: i32) {
    let cmp = |a: &EdgeSlot, b: &EdgeSlot| cmp_x(a, b, y).then_with(|| cmp_x(a, b, last));
    let mut budget = 4 * e.len();
    for i in 1..e.len() {
        let mut j = i;
        while j > 0 && cmp(&e[j - 1], &e[j]).is_gt() {
            if budget == 0 {
                heap_sort(e, |a, b| cmp(a, b).is_lt());
                return;
            }
            budget -= 1;
            swap(e, j - 1, j);
            j -= 1;
        }
    }
}

/// `true` when the crossings on row `j` are in order.
#[inline(always)]
fn sorted_at(e: &[EdgeSlot], j: i32) -> bool {
    e.windows(2).all(|w| !cmp_x(&w[0], &w[1], j).is_gt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::Coord;
    use crate::raster::clip::ClipWindow;

    pub(crate) fn v3(x: i32, y: i32, z: i32) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits(x as i16),
            y: Coord::from_bits(y as i16),
            z: Coord::from_bits(z as i16),
        }
    }

    /// The pixel rule for one pixel, from its definition.
    fn covers(poly: &[Vertex3], i: i32, j: i32) -> bool {
        crate::raster::scan::rule_covers(poly, |v| (v.x.units(), v.y.units()), i, j)
    }

    use testkit::rng::Rng;

    const W: i32 = 40;
    const H: i32 = 32;

    /// Every pixel of the frame, counted over the trapezoids' spans.
    fn hits(
        poly: &[Vertex3],
        clip: &ClipRect,
        slots: &mut [EdgeSlot],
    ) -> ([u8; (W * H) as usize], u32) {
        let mut hit = [0u8; (W * H) as usize];
        let p = Polygon::load(slots, poly.iter().copied(), clip).unwrap();
        let n = p
            .cut(|l, r| {
                let t = Trapezoid::new(l, r, 0, clip);
                for j in t.top()..t.end() {
                    let (a, b) = t.span_at(j).unwrap();
                    for i in a..b {
                        hit[(j * W + i) as usize] += 1;
                    }
                }
                Ok::<(), ()>(())
            })
            .unwrap();
        (hit, n)
    }

    /// A triangle's and a quadrilateral's outline, worked out at once,
    /// equals the general walk's: Newell's sums, depth and column ranges,
    /// first vertex and count, over coordinates to both ends of `i16`.
    #[test]
    fn outline_of_three_or_four_vertices_is_the_walks() {
        let mut rng = Rng(0x0a11_7e55);
        let mut within = 0;
        for case in 0..20000 {
            let n = 3 + case % 2;
            let span = [16, 4096, 65536][case % 3];
            let mut poly = [Vertex3::default(); 4];
            for v in poly.iter_mut() {
                let mut c = || (rng.below(span as u32) - span / 2).clamp(-32768, 32767);
                *v = v3(c(), c(), c());
            }
            if case % 7 == 0 {
                poly[1] = poly[0];
            }
            let fast = Outline::of(poly[..n].iter().copied()).unwrap();
            let walk = Outline::walk(poly[..n].iter().copied(), |_, _| Ok(())).unwrap();
            let (f, w) = (fast.sums.unwrap(), walk.sums.unwrap());
            assert_eq!(
                (f.a, f.b, f.c, f.first, f.n, f.z, fast.x),
                (w.a, w.b, w.c, w.first, w.n, w.z, walk.x),
                "{:?}",
                &poly[..n]
            );
            assert_eq!(fast.front(), walk.front());
            // Found within at the vertices: the general load's plane (which
            // checks the edges' ends) is not flattened.
            if f.within {
                let mut slots = [EdgeSlot::EMPTY; 4];
                let clip = ClipRect::from_window(
                    ClipWindow {
                        x0: 0,
                        y0: 0,
                        x1: 4095,
                        y1: 4095,
                    },
                    4096,
                    4096,
                );
                let p = Polygon::load(&mut slots, poly[..n].iter().copied(), &clip).unwrap();
                assert_eq!(p.plane().copied(), f.finish(), "{:?}", &poly[..n]);
                within += 1;
            }
        }
        assert!(within > 1000, "{within}");
    }

    #[test]
    fn trapezoids_cover_the_pixel_rule_once() {
        let mut rng = Rng(0x9e37_79b9);
        let mut slots = [EdgeSlot::EMPTY; 12];
        for case in 0..3000 {
            let n = 3 + rng.below(10) as usize;
            let mut poly = [Vertex3::default(); 12];
            // Coarse grids make coincident vertices, shared rows and
            // crossings on row centres likely.
            let grid = [1, 4, 8, 16][case % 4];
            for v in poly.iter_mut().take(n) {
                let x = rng.below(((W + 8) * 16 / grid) as u32) * grid - 64;
                let y = rng.below(((H + 8) * 16 / grid) as u32) * grid - 64;
                *v = v3(x, y, 0);
            }
            let poly = &poly[..n];
            let clip = if case % 3 == 0 {
                let (x0, y0) = (rng.below(W as u32) as i16, rng.below(H as u32) as i16);
                ClipRect::from_window(
                    ClipWindow {
                        x0,
                        y0,
                        x1: x0 + rng.below(W as u32) as i16,
                        y1: y0 + rng.below(H as u32) as i16,
                    },
                    W as u16,
                    H as u16,
                )
            } else {
                ClipRect::full(W as u16, H as u16)
            };
            let (hit, _) = hits(poly, &clip, &mut slots);
            for j in 0..H {
                for i in 0..W {
                    let want = clip.contains(i, j) && covers(poly, i, j);
                    let got = hit[(j * W + i) as usize];
                    assert_eq!(got, want as u8, "{poly:?} {clip:?} pixel ({i}, {j})");
                }
            }
        }
    }

    #[test]
    fn convex_polygons_make_few_trapezoids() {
        let px = |x: i32, y: i32| v3(x * 16 + 3, y * 16 + 5, 0);
        let clip = ClipRect::full(W as u16, H as u16);
        let mut slots = [EdgeSlot::EMPTY; 8];
        // A triangle: two trapezoids (the middle vertex splits one side).
        let tri = [px(2, 2), px(30, 9), px(6, 28)];
        assert_eq!(hits(&tri, &clip, &mut slots).1, 2);
        // A convex hexagon with horizontal top and bottom: 2.
        let hex = [
            px(10, 2),
            px(20, 2),
            px(28, 12),
            px(20, 24),
            px(10, 24),
            px(3, 12),
        ];
        assert_eq!(hits(&hex, &clip, &mut slots).1, 2);
        // A convex hexagon with its vertices on six different rows: each
        // of the four between the top and the bottom one starts a
        // trapezoid, n − 1 = 5 in all.
        let hex = [
            px(15, 2),
            px(26, 6),
            px(28, 16),
            px(20, 27),
            px(6, 22),
            px(3, 9),
        ];
        assert_eq!(hits(&hex, &clip, &mut slots).1, 5);
        // An axis-aligned rectangle: one.
        let rect = [px(3, 3), px(20, 3), px(20, 10), px(3, 10)];
        assert_eq!(hits(&rect, &clip, &mut slots).1, 1);
    }

    #[test]
    fn self_intersection_inside_a_band_splits_it() {
        // A bow tie: the two long edges cross at row 16.
        let bow = [v3(0, 0, 0), v3(640, 0, 0), v3(0, 512, 0), v3(640, 512, 0)];
        let clip = ClipRect::full(W as u16, H as u16);
        let mut slots = [EdgeSlot::EMPTY; 4];
        let (hit, n) = hits(&bow, &clip, &mut slots);
        assert_eq!(n, 2);
        for j in 0..H {
            for i in 0..W {
                assert_eq!(hit[(j * W + i) as usize], covers(&bow, i, j) as u8);
            }
        }
    }

    /// Zigzags of many edges that all start on one row, listed right to
    /// left (past the insertion sort's budget), and random many-edged
    /// polygons: the trapezoids still cover the pixel rule once.
    #[test]
    fn many_edges_out_of_order_cover_the_pixel_rule_once() {
        let mut rng = Rng(0x2468_ace1);
        let clip = ClipRect::full(W as u16, H as u16);
        let mut slots = [EdgeSlot::EMPTY; 160];
        for case in 0..40 {
            let n = 40 + rng.below(120) as usize;
            let mut poly = [Vertex3::default(); 160];
            for (k, v) in poly.iter_mut().take(n).enumerate() {
                *v = if case % 2 == 0 {
                    let x = (W * 16 - 1) * (n - 1 - k) as i32 / (n - 1) as i32;
                    let y = if k % 2 == 0 { 3 } else { H * 16 - 5 };
                    v3(x, y, 0)
                } else {
                    v3(rng.below(W as u32 * 16), rng.below(H as u32 * 16), 0)
                };
            }
            let poly = &poly[..n];
            let (hit, _) = hits(poly, &clip, &mut slots);
            for j in 0..H {
                for i in 0..W {
                    let want = covers(poly, i, j) as u8;
                    assert_eq!(hit[(j * W + i) as usize], want, "case {case} ({i}, {j})");
                }
            }
        }
    }

    /// The two chains' walk hands over exactly the sweep's trapezoids, in
    /// the sweep's order, for every polygon: convex ones (the walk's
    /// case), concave and self-intersecting ones (where it gives up part
    /// way, and the sweep skips what it made), clipped or not, with
    /// coincident vertices and shared rows (coarse grids).
    #[test]
    fn the_chains_walk_makes_the_sweeps_trapezoids() {
        let mut rng = Rng(0x3c3c_5a5a);
        let mut slots = [EdgeSlot::EMPTY; 16];
        let (mut walked, mut total, mut gave_up_late) = (0, 0, 0);
        for case in 0..20_000 {
            let n = 3 + rng.below(9) as usize;
            let mut poly = [Vertex3::default(); 16];
            let grid = [1, 4, 8, 16, 64][case % 5];
            if case % 3 == 0 {
                // Convex: points on an ellipse, in angle order.
                let (cx, cy) = (
                    rng.below(W as u32 * 16) as i64,
                    rng.below(H as u32 * 16) as i64,
                );
                let (rx, ry) = (1 + rng.below(800) as i64, 1 + rng.below(800) as i64);
                let mut t = [0i64; 16];
                for a in t.iter_mut().take(n) {
                    *a = rng.below(3600) as i64;
                }
                t[..n].sort_unstable();
                for (v, &a) in poly.iter_mut().zip(&t[..n]) {
                    // cos and sin of a tenth of a degree, roughly, in integers.
                    let (c, s) = approx_cos_sin(a);
                    let x = (cx + rx * c / 1024) as i32 / grid * grid;
                    let y = (cy + ry * s / 1024) as i32 / grid * grid;
                    *v = v3(x, y, 0);
                }
            } else {
                for v in poly.iter_mut().take(n) {
                    let x = rng.below(((W + 8) * 16 / grid) as u32) * grid - 64;
                    let y = rng.below(((H + 8) * 16 / grid) as u32) * grid - 64;
                    *v = v3(x, y, 0);
                }
            }
            let poly = &poly[..n];
            let clip = if case % 4 == 0 {
                let (x0, y0) = (rng.below(W as u32) as i16, rng.below(H as u32) as i16);
                ClipRect::from_window(
                    ClipWindow {
                        x0,
                        y0,
                        x1: x0 + rng.below(W as u32) as i16,
                        y1: y0 + rng.below(H as u32) as i16,
                    },
                    W as u16,
                    H as u16,
                )
            } else {
                ClipRect::full(W as u16, H as u16)
            };
            let run = |chains: bool, slots: &mut [EdgeSlot]| {
                let mut out = [(
                    Side {
                        ends: Ends::default(),
                        top: 0,
                        end: 0,
                    },
                    Side {
                        ends: Ends::default(),
                        top: 0,
                        end: 0,
                    },
                ); 128];
                let mut k = 0;
                let p = Polygon::load(slots, poly.iter().copied(), &clip).unwrap();
                let got = p
                    .cut_with::<false, ()>(chains, |l, r| {
                        out[k] = (l, r);
                        k += 1;
                        Ok::<(), ()>(())
                    })
                    .unwrap();
                assert_eq!(got as usize, k);
                (out, k)
            };
            let (want, nw) = run(false, &mut slots);
            let (got, ng) = run(true, &mut slots);
            assert_eq!(&got[..ng], &want[..nw], "case {case}: {poly:?} {clip:?}");
            // How often the walk finishes alone.
            let p = Polygon::load(&mut slots, poly.iter().copied(), &clip).unwrap();
            if p.edges >= 2 {
                total += 1;
                let mut c = Closer {
                    emit: |_: Side, _: Side| Ok::<(), ()>(()),
                    cols: p.cols,
                    count: 0,
                    skip: 0,
                };
                if cut_chains(&p.slots[..p.edges], Rows::of(&p.slots[..p.edges]), &mut c).unwrap() {
                    walked += 1;
                } else if c.count > 0 {
                    gave_up_late += 1;
                }
            }
        }
        // The convex third at least, and some of the others.
        assert!(walked * 3 > total, "{walked} of {total}");
        // And the walk gave up after emitting, so the sweep skipped some.
        assert!(gave_up_late > 50, "{gave_up_late}");
    }

    /// A triangle's cut ([`cut_triangle`]) emits the walk's trapezoids
    /// ([`cut_chains`], then the sweep where it stops), the same records
    /// in the same order, or declines with nothing emitted: over the
    /// whole `i16` range and near the frame, with vertices on row
    /// centres, two or three on one row, repeated or collinear ones,
    /// both windings, and clips that cut the rows and the columns.
    /// A triangle and a clip for case `case` of the triangle cut tests:
    /// the whole `i16` range, frames of 40 × 32 and 4096 × 4096, vertices
    /// on row centres, two or three on one row, repeated and collinear
    /// vertices, clips cutting rows and columns.
    fn random_triangle(rng: &mut Rng, case: u32) -> ([Vertex3; 3], ClipRect) {
        let big = case % 5 == 1;
        let (fw, fh) = if big {
            (4096u16, 4096u16)
        } else {
            (W as u16, H as u16)
        };
        let mut r = |axis: i32| -> i32 {
            match case % 5 {
                // The whole range.
                0 | 1 => rng.range(-32768, 32768),
                // Near the frame, any unit.
                2 => rng.range(-64, axis * 16 + 64),
                // Near the frame, on a coarse grid: shared rows and
                // columns, row centres.
                3 => rng.range(-2, axis + 2) * 16 + [0, 8][rng.below(2) as usize],
                // Small, around one row centre.
                _ => 16 * (axis / 2) + 8 + rng.range(-20, 21),
            }
        };
        let mut p = [(0i32, 0i32); 3];
        for v in p.iter_mut() {
            *v = (r(W), r(H));
        }
        match case % 7 {
            // Two on one row.
            0 => p[1].1 = p[0].1,
            // A vertex repeated.
            1 => p[2] = p[rng.below(2) as usize],
            // Collinear: the third on the line through the others.
            2 => {
                let (dx, dy) = (p[1].0 - p[0].0, p[1].1 - p[0].1);
                let k = rng.range(-2, 3);
                let q = (p[0].0 + k * dx, p[0].1 + k * dy);
                if (-32768..32768).contains(&q.0) && (-32768..32768).contains(&q.1) {
                    p[2] = q;
                }
            }
            // The top on a row centre.
            3 => p[0].1 = p[0].1 - p[0].1.rem_euclid(16) + 8,
            // All on one row.
            4 => (p[1].1, p[2].1) = (p[0].1, p[0].1),
            _ => {}
        }
        let poly = p.map(|(x, y)| v3(x, y, rng.range(-32768, 32768)));
        let clip = if case.is_multiple_of(3) {
            let (x0, y0) = (rng.below(fw as u32) as i16, rng.below(fh as u32) as i16);
            ClipRect::from_window(
                ClipWindow {
                    x0,
                    y0,
                    x1: x0.saturating_add(rng.below(fw as u32) as i16),
                    y1: y0.saturating_add(rng.below(fh as u32) as i16),
                },
                fw,
                fh,
            )
        } else {
            ClipRect::full(fw, fh)
        };
        (poly, clip)
    }

    #[test]
    fn triangle_cut_is_the_walks() {
        let mut rng = Rng(0x7c07_3a11);
        let mut slots = [EdgeSlot::EMPTY; 4];
        let (mut direct, mut declined, mut none) = (0u32, 0u32, 0u32);
        for case in 0..300_000u32 {
            let (poly, clip) = random_triangle(&mut rng, case);
            let run = |triangle: bool, slots: &mut [EdgeSlot]| {
                let side = Side {
                    ends: Ends::default(),
                    top: 0,
                    end: 0,
                };
                let mut out = [(side, side); 8];
                let mut k = 0;
                let mut p = Polygon::load(slots, poly.iter().copied(), &clip).unwrap();
                assert!(p.triangle || p.edges < 2);
                p.triangle = triangle;
                let got = p
                    .cut_triangles(|l, r| {
                        out[k] = (l, r);
                        k += 1;
                        Ok::<(), ()>(())
                    })
                    .unwrap();
                assert_eq!(got as usize, k);
                (out, k)
            };
            let (want, nw) = run(false, &mut slots);
            let (got, ng) = run(true, &mut slots);
            assert_eq!(&got[..ng], &want[..nw], "case {case}: {poly:?} {clip:?}");
            // How often the triangle's cut decides alone.
            let p = Polygon::load(&mut slots, poly.iter().copied(), &clip).unwrap();
            if p.edges < 2 {
                none += 1;
                continue;
            }
            let mut c = Closer {
                emit: |_: Side, _: Side| Ok::<(), ()>(()),
                cols: p.cols,
                count: 0,
                skip: 0,
            };
            if cut_triangle(&p.slots[..p.edges], &mut c).unwrap() {
                direct += 1;
            } else {
                assert_eq!(c.count, 0);
                declined += 1;
            }
        }
        assert!(direct > 100_000, "{direct} {declined} {none}");
        assert!(declined > 5_000, "{direct} {declined} {none}");
    }

    #[test]
    fn direct_triangle_cut_is_the_polygons() {
        let mut rng = Rng(0x51de_7a0e);
        let mut slots = [EdgeSlot::EMPTY; 4];
        let (mut direct, mut declined, mut left_out) = (0u32, 0u32, 0u32);
        let side = Side {
            ends: Ends::default(),
            top: 0,
            end: 0,
        };
        // A band of one row whose edges both start at the centre of that
        // row (so cross it at one point): it has no pixel.
        let no_pixel = |(l, r): &(Side, Side)| {
            let (a, b) = (&l.ends, &r.ends);
            l.top + 1 == l.end
                && (a.x0, a.y0) == (b.x0, b.y0)
                && a.y0 as i32 == l.top as i32 * ONE + HALF
        };
        for case in 0..300_000u32 {
            let (poly, clip) = random_triangle(&mut rng, case);
            let mut want = [(side, side); 8];
            let p = Polygon::load(&mut slots, poly.iter().copied(), &clip).unwrap();
            let plane = p.plane().copied();
            let mut nw = 0;
            if plane.is_some() && p.edges() >= 2 {
                p.cut_triangles(|l, r| {
                    want[nw] = (l, r);
                    nw += 1;
                    Ok::<(), ()>(())
                })
                .unwrap();
            }
            let Some(cut) = TriangleCut::of(&poly, &clip) else {
                declined += 1;
                // Declined only where the triangle's cut declines too.
                let p = Polygon::load(&mut slots, poly.iter().copied(), &clip).unwrap();
                let mut c = Closer {
                    emit: |_: Side, _: Side| Ok::<(), ()>(()),
                    cols: p.cols,
                    count: 0,
                    skip: 0,
                };
                let done = cut_triangle(&p.slots[..p.edges], &mut c).unwrap();
                assert!(!done || p.plane.is_none(), "case {case}: {poly:?} {clip:?}");
                continue;
            };
            direct += 1;
            assert_eq!(
                cut.plane().copied(),
                plane,
                "case {case}: {poly:?} {clip:?}"
            );
            let mut got = [(side, side); 8];
            let mut ng = 0;
            if plane.is_some() {
                let n = cut
                    .cut(|l, r, top, end| {
                        got[ng] = (Side { ends: l, top, end }, Side { ends: r, top, end });
                        ng += 1;
                        Ok::<(), ()>(())
                    })
                    .unwrap();
                assert_eq!(n as usize, ng);
            }
            // The walk's first band of one row through the top vertex,
            // which the direct cut leaves out.
            let skip = (nw > ng && no_pixel(&want[0])) as usize;
            left_out += skip as u32;
            assert_eq!(
                &got[..ng],
                &want[skip..nw],
                "case {case}: {poly:?} {clip:?}"
            );
        }
        assert!(direct > 200_000, "{direct} {declined}");
        assert_eq!(declined, 0, "{direct} {declined}");
        assert!(left_out > 2_000, "{direct} {left_out}");
    }

    /// `(1024·cos, 1024·sin)` of `a` tenths of a degree, near enough for
    /// points in convex position (a table of 10° and a linear blend).
    fn approx_cos_sin(a: i64) -> (i64, i64) {
        const C: [i64; 37] = [
            1024, 1008, 962, 887, 784, 658, 512, 350, 178, 0, -178, -350, -512, -658, -784, -887,
            -962, -1008, -1024, -1008, -962, -887, -784, -658, -512, -350, -178, 0, 178, 350, 512,
            658, 784, 887, 962, 1008, 1024,
        ];
        let (i, f) = ((a / 100) as usize, a % 100);
        let c = (C[i] * (100 - f) + C[i + 1] * f) / 100;
        let j = (i + 27) % 36;
        let s = -(C[j] * (100 - f) + C[j + 1] * f) / 100;
        (c, s)
    }

    /// The shortcuts (edges from one vertex, edges apart in x) order
    /// every band as the crossings do, over the whole coordinate range,
    /// bands of one row through a shared vertex included.
    #[test]
    fn edges_from_one_vertex_are_ordered_as_their_crossings() {
        let mut rng = Rng(0x7e57_0bad);
        let slot = |x0: i32, y0: i32, x1: i32, y1: i32| EdgeSlot {
            ends: Ends {
                x0: x0 as i16,
                y0: y0 as i16,
                x1: x1 as i16,
                y1: y1 as i16,
            },
            ..EdgeSlot::EMPTY
        };
        let reference = |a: &EdgeSlot, b: &EdgeSlot, y: i32, last: i32| match cmp_x(a, b, y) {
            Ordering::Less if !cmp_x(a, b, last).is_gt() => Some(true),
            Ordering::Greater if !cmp_x(a, b, last).is_lt() => Some(false),
            Ordering::Equal => match cmp_x(a, b, last) {
                Ordering::Less => Some(true),
                Ordering::Greater => Some(false),
                Ordering::Equal => None,
            },
            _ => None,
        };
        let mut shared = 0;
        for case in 0..200_000 {
            let span = [32768, 4096, 64][case % 3];
            let mut r = |lo: i32| lo + rng.below((32767 - lo).min(span) as u32 + 1);
            let (x, y) = (r(-32768), r(-32768));
            let (xa, ya, xb, yb) = (r(-32768), r(y + 1), r(-32768), r(y + 1));
            if ya > 32767 || yb > 32767 || ya <= y || yb <= y {
                continue;
            }
            let (a, b) = if case % 2 == 0 {
                (slot(x, y, xa, ya), slot(x, y, xb, yb))
            } else {
                // The lower end shared: (x, y) as the bottom vertex.
                let (y, ya, yb) = (ya.max(yb), y, y - (yb - ya).abs().min(y + 32768));
                if ya >= y || yb >= y {
                    continue;
                }
                (slot(xa, ya, x, y), slot(xb, yb, x, y))
            };
            // Rows both cross (centres in [y0, y1)), a random band of them.
            let rows = |e: &EdgeSlot| {
                (
                    ceil_px(e.ends.y0 as i32 - HALF),
                    ceil_px(e.ends.y1 as i32 - HALF),
                )
            };
            let ((ta, ea), (tb, eb)) = (rows(&a), rows(&b));
            let (top, end) = (ta.max(tb), ea.min(eb));
            if top >= end {
                continue;
            }
            let first = top + rng.below((end - top) as u32);
            let last = first + rng.below((end - first) as u32);
            shared += 1;
            assert_eq!(
                band_order(&a, &b, first, last),
                reference(&a, &b, first, last),
                "{a:?} {b:?} {first}..={last}"
            );
        }
        assert!(shared > 50_000, "{shared}");
        // And edges with no end in common: apart in x, or not.
        let mut apart = 0;
        for case in 0..200_000 {
            let span = [32768, 512, 64][case % 3];
            let mut r = |lo: i32| lo + rng.below((32767 - lo).min(span) as u32 + 1);
            let (x0, y0) = (r(-32768), r(-32768));
            let (a, b) = (
                slot(x0, y0, r(x0 - span), r(y0 + 1)),
                slot(r(x0 - span), r(y0 - span), r(x0 - span), r(y0 + 1)),
            );
            if a.ends.y1 <= a.ends.y0 || b.ends.y1 <= b.ends.y0 || a.ends == b.ends {
                continue;
            }
            let rows = |e: &EdgeSlot| {
                (
                    ceil_px(e.ends.y0 as i32 - HALF),
                    ceil_px(e.ends.y1 as i32 - HALF),
                )
            };
            let ((ta, ea), (tb, eb)) = (rows(&a), rows(&b));
            let (top, end) = (ta.max(tb), ea.min(eb));
            if top >= end {
                continue;
            }
            let first = top + rng.below((end - top) as u32);
            let last = first + rng.below((end - first) as u32);
            let (ra, rb) = (
                (a.ends.x0.min(a.ends.x1), a.ends.x0.max(a.ends.x1)),
                (b.ends.x0.min(b.ends.x1), b.ends.x0.max(b.ends.x1)),
            );
            apart += (ra.1 < rb.0 || rb.1 < ra.0) as u32;
            assert_eq!(
                band_order(&a, &b, first, last),
                reference(&a, &b, first, last),
                "{a:?} {b:?} {first}..={last}"
            );
        }
        assert!(apart > 10_000, "{apart}");
    }

    /// The 16-bit-digit division equals the library's, at the edges of
    /// its range (quotients just below 2³², divisors of every length,
    /// the corrections of each digit) and at random.
    #[test]
    fn long_division_is_exact() {
        let mut rng = Rng(0x5151_7a7a);
        let check = |u: u64, v: u32| {
            if v > 0 && ((u >> 32) as u32) < v {
                assert_eq!(div_64_32(u, v) as u64, u / v as u64, "{u} / {v}");
            }
        };
        for sh in 0..32 {
            for v in [
                1u32 << sh,
                (1 << sh) + 1,
                (1u32 << sh).wrapping_sub(1),
                u32::MAX >> sh,
            ] {
                for u in [
                    0,
                    1,
                    v as u64,
                    ((v as u64) << 32).wrapping_sub(1),
                    (v as u64) << 31,
                    u64::MAX,
                ] {
                    check(u, v);
                    check(u.wrapping_sub((v as u64).wrapping_sub(1)), v);
                }
            }
        }
        for _ in 0..200_000 {
            let v = (rng.next_u64() >> 32) as u32 >> rng.below(32);
            let u = rng.next_u64() >> rng.below(64);
            check(u, v);
            // Quotients near 2³² and divisors with a second digit that
            // needs correcting.
            check(
                ((v as u64) << 32).wrapping_sub(1 + rng.below(1 << 20) as u64),
                v,
            );
            check(
                ((v as u64) << 32).wrapping_sub((v as u64) * (1 + rng.below(70_000) as u64)),
                v,
            );
            check(u, v | 0xffff);
            check(u, v & 0xffff_0000);
        }
    }

    /// `floor_div` is `div_euclid` by a positive divisor; `round_div64`
    /// is `round_div` wherever it is used (|n| < 2⁶², 0 < c < 2³¹).
    #[test]
    fn narrow_divisions_equal_the_wide_ones() {
        let mut rng = Rng(0x0ddb_a11e);
        for _ in 0..100_000 {
            let c = ((rng.next_u64() >> 32) as u32 >> (1 + rng.below(31))).max(1);
            let big = rng.next_u64() >> (3 + rng.below(61));
            for n in [big as i64, -(big as i64), 0, 1, -1, c as i64, -(c as i64)] {
                assert_eq!(
                    round_div64(n, c, &Divisor::new(2 * c)) as i128,
                    round_div(n as i128, c as i64),
                    "{n} / {c}"
                );
                let d = 2 * c;
                let m = 2 * n + c as i64;
                assert_eq!(floor_div(m, d), m.div_euclid(d as i64), "{m} / {d}");
            }
        }
        // The edges: |n| at 2⁶² − 2³¹, c at both ends.
        for c in [1u32, 2, 3, (1 << 31) - 1, 1 << 30, 12345] {
            for n in [
                (1i64 << 62) - (1 << 31),
                -(1i64 << 62) + (1 << 31),
                (1 << 32) - 1,
                -(1 << 32),
            ] {
                assert_eq!(
                    round_div64(n, c, &Divisor::new(2 * c)) as i128,
                    round_div(n as i128, c as i64)
                );
            }
        }
        // Numerators about 2³², where the one 32-bit division ends, and
        // about −2³², where `|n| + d − 1` crosses it, for divisors of both
        // kinds (below and above `SMALL_DIVISOR`).
        for d in [
            1u32,
            2,
            3,
            0x7ff,
            SMALL_DIVISOR - 1,
            SMALL_DIVISOR,
            u32::MAX,
        ] {
            for base in [1i64 << 32, -(1i64 << 32) + d as i64 - 1] {
                for k in -3..=3 {
                    let m = base + k;
                    assert_eq!(floor_div(m, d), m.div_euclid(d as i64), "{m} / {d}");
                }
            }
        }
    }

    /// The two-digit long division (`small_div_43_32`) where `floor_div`
    /// takes it, and about its edges: magnitudes about 2³² and 2⁴³ (both
    /// signs), divisors about 2¹¹ and `SMALL_DIVISOR`, where it starts and
    /// ends, and at random between.
    #[test]
    fn two_digit_divisions_are_exact() {
        let mut rng = Rng(0x2d16_4375);
        let divisors = [
            1u32,
            0x7fe,
            0x7ff,
            0x800,
            0x801,
            0xfff,
            0x1000,
            SMALL_DIVISOR - 2,
            SMALL_DIVISOR - 1,
            SMALL_DIVISOR,
        ];
        for d in divisors {
            for base in [1i64 << 32, 1 << 43, (1 << 43) - (1 << 11), 1 << 42] {
                for k in -3..=3 {
                    for m in [base + k, -(base + k), -(base + k) + d as i64 - 1] {
                        assert_eq!(floor_div(m, d), m.div_euclid(d as i64), "{m} / {d}");
                    }
                }
            }
            assert_eq!(
                small_div_43_32((1 << 43) - 1, d.max(0x800)) as u64,
                ((1u64 << 43) - 1) / d.max(0x800) as u64
            );
        }
        for _ in 0..500_000 {
            let d = 0x800 + rng.below(SMALL_DIVISOR - 0x800) as u32;
            let d = if rng.below(4) == 0 {
                d >> rng.below(12)
            } else {
                d
            }
            .max(1);
            let m = (rng.next_u64() >> (20 + rng.below(13))) as i64;
            for m in [m, -m] {
                assert_eq!(floor_div(m, d), m.div_euclid(d as i64), "{m} / {d}");
            }
            let u = rng.next_u64() >> 21;
            if d >= 0x800 {
                assert_eq!(small_div_43_32(u, d) as u64, u / d as u64, "{u} / {d}");
            }
        }
    }

    /// The `i64` path of [`Plane::depth`] gives the `i128` path's values
    /// (modulo 2³²), over the whole Q12.4 range and for normals at the
    /// edges of the `i64` path (|a|, |b|, c just below 2³¹).
    #[test]
    fn narrow_depth_equals_the_wide_one() {
        let mut rng = Rng(0x600d_f00d);
        let wide = |p: &Plane| {
            let (x0, y0, _) = p.origin_units();
            let (i0, j0) = ((x0 >> 4).clamp(0, 4095), (y0 >> 4).clamp(0, 4095));
            let (zx, zy, at) = p.depth_wide(x0 - 16 * i0 - 8, y0 - 16 * j0 - 8);
            let z = at
                .wrapping_sub(zx.wrapping_mul(i0))
                .wrapping_sub(zy.wrapping_mul(j0));
            Depth { z, zx, zy }
        };
        let m = (1i64 << 31) - 1;
        let ends = [-m, -m + 1, -1, 0, 1, m - 1, m, 1 << 20, -(1 << 20), 3];
        let origins = [i16::MIN, -8, -1, 0, 7, 8, 4095, i16::MAX];
        // Depths down to those of a plane moved 2¹⁴ toward the eye.
        let depths = [-(1 << 15) - (1 << 14), -8, -1, 0, 7, 8, 4095, 32767];
        for &a in &ends {
            for &b in &ends {
                for c in [1, 2, 3, m - 1, m, 1 << 16, m + 1, 1 << 40] {
                    let origin = (
                        origins[rng.below(8) as usize],
                        origins[rng.below(8) as usize],
                        depths[rng.below(8) as usize],
                    );
                    let p = Plane { a, b, c, origin };
                    assert_eq!(p.depth(), wide(&p), "{p:?}");
                }
            }
        }
        for _ in 0..20_000 {
            let mut r = |m: u32| rng.below(2 * m) - m as i32;
            let tri = [
                v3(r(32767), r(32767), r(32767)),
                v3(r(32767), r(32767), r(32767)),
                v3(r(32767), r(32767), r(32767)),
            ];
            if let Some(p) = Plane::of(tri) {
                assert_eq!(p.depth(), wide(&p), "{tri:?}");
            }
        }
    }

    #[test]
    fn an_edge_slot_is_32_bytes() {
        assert_eq!(core::mem::size_of::<EdgeSlot>(), 32);
    }

    /// `u16`s and `i16`s only: the same size on every target.
    #[test]
    fn a_trapezoid_is_34_bytes() {
        assert_eq!(core::mem::size_of::<Trapezoid>(), 34);
        assert_eq!(core::mem::align_of::<Trapezoid>(), 2);
    }

    #[test]
    fn too_few_slots_is_an_error() {
        let quad = [v3(0, 0, 0), v3(160, 0, 0), v3(160, 160, 0), v3(0, 160, 0)];
        let clip = ClipRect::full(W as u16, H as u16);
        let mut slots = [EdgeSlot::EMPTY; 1];
        assert_eq!(
            Polygon::load(&mut slots, quad, &clip).err(),
            Some(LoadError::Edges { capacity: 1 })
        );
        // Horizontal edges take no slot.
        let mut slots = [EdgeSlot::EMPTY; 2];
        assert!(Polygon::load(&mut slots, quad, &clip).is_ok());
    }

    #[test]
    fn plane_of_a_triangle_passes_through_its_vertices() {
        let tri = [v3(16, 16, 100), v3(500, 40, -300), v3(200, 480, 2000)];
        let p = Plane::of(tri).unwrap();
        let (a, b, c) = p.normal();
        assert!(c > 0);
        for v in tri {
            let lhs = a as i128 * v.x.units() as i128
                + b as i128 * v.y.units() as i128
                + c as i128 * v.z.units() as i128;
            assert_eq!(lhs, p.offset());
        }
        // Winding does not matter.
        let rev = Plane::of([tri[2], tri[1], tri[0]]).unwrap();
        assert_eq!((rev.normal(), rev.offset()), (p.normal(), p.offset()));
    }

    #[test]
    fn edge_on_polygons_have_no_plane() {
        let line = [v3(0, 0, 0), v3(160, 160, 50), v3(320, 320, 9)];
        assert_eq!(Plane::of(line), None);
    }

    /// The fixed-point depth is within its bound of the exact one, at the
    /// corners of the pixel range, for planes from flat to nearly edge-on.
    #[test]
    fn fixed_point_depth_error_is_bounded() {
        let mut rng = Rng(0x1234_5677);
        for _ in 0..2000 {
            let mut r = |m: u32| rng.below(2 * m) - m as i32;
            let tri = [
                v3(r(32767), r(32767), r(32767)),
                v3(r(32767), r(32767), r(32767)),
                v3(r(32767), r(32767), r(32767)),
            ];
            let Some(p) = Plane::of(tri) else { continue };
            let d = p.depth();
            for (i, j) in [(0, 0), (4095, 0), (0, 4095), (4095, 4095), (17, 3000)] {
                let (num, den) = p.depth_at(i, j);
                let exact = num * (1 << Z_FRAC_BITS);
                // Only where the true depth is in range is it meaningful.
                let z = exact.div_euclid(den as i128);
                if z.abs() >= 1 << 29 {
                    continue;
                }
                let got = d.at(i, j) as i128;
                // |got − exact/den| ≤ ½(1 + |i − i₀| + |j − j₀|) < 4096.
                let err2 = (2 * (got * den as i128 - exact)).abs();
                assert!(err2 < 8192 * den as i128, "{tri:?} at ({i}, {j})");
            }
        }
    }

    /// The plane a polygon is loaded with: Newell's for planar polygons;
    /// for others, between the vertices' depths at every covered pixel,
    /// and Newell's itself whenever that is.
    #[test]
    fn loaded_planes_stay_between_the_vertices_depths() {
        let mut rng = Rng(0x0bad_5eed);
        let clip = ClipRect::full(W as u16, H as u16);
        let mut slots = [EdgeSlot::EMPTY; 8];
        let mut flattened = 0;
        for case in 0..3000 {
            let n = 3 + rng.below(5) as usize;
            let mut poly = [Vertex3::default(); 8];
            let wide = case % 2 == 0;
            for v in poly.iter_mut().take(n) {
                let x = rng.below(16 * W as u32);
                let y = rng.below(16 * H as u32);
                let z = if wide {
                    rng.below(65536) - 32768
                } else {
                    rng.below(64)
                };
                *v = v3(x, y, z);
            }
            let poly = &poly[..n];
            let (zmin, zmax) = poly.iter().fold((i32::MAX, i32::MIN), |(a, b), v| {
                (a.min(v.z.units()), b.max(v.z.units()))
            });
            let newell = Plane::of(poly.iter().copied());
            let p = Polygon::load(&mut slots, poly.iter().copied(), &clip).unwrap();
            let got = p.plane().copied();
            assert_eq!(got.is_some(), newell.is_some());
            let (Some(got), Some(newell)) = (got, newell) else {
                continue;
            };
            let inside = |pl: &Plane| {
                (0..H).all(|j| {
                    (0..W).all(|i| {
                        !covers(poly, i, j) || {
                            let (e, c) = pl.depth_at(i, j);
                            zmin as i128 * c as i128 <= e && e <= zmax as i128 * c as i128
                        }
                    })
                })
            };
            assert!(inside(&got), "{poly:?}");
            if got != newell {
                flattened += 1;
                assert!(!inside(&newell) || !poly.iter().all(|&v| newell.contains(v)));
            }
            if poly.iter().all(|&v| newell.contains(v)) {
                assert_eq!(got, newell);
            }
        }
        assert!(flattened > 100, "{flattened}");
    }

    /// `Polygon::bounded` gives the plane of its definition: the test of
    /// each scaled plane in `i128` (`depth_within`), the bisection over
    /// `0..2¹⁶`, then the tail; its usual case tests in `i64`. On quads
    /// whose rounded depths tilt the plane past their range, of every
    /// size.
    #[test]
    fn bounded_is_the_bisection_of_its_definition() {
        let mut rng = Rng(0x0b15_ec75);
        let clip = ClipRect::full(4096, 4096);
        let mut slots = [EdgeSlot::EMPTY; 5];
        let (mut bisected, mut pentagons) = (0, 0);
        for case in 0..30_000 {
            let (p, q) = (rng.below(401) - 200, rng.below(401) - 200);
            let z0 = rng.below(8001) - 4000;
            let (x0, y0) = (rng.below(16 * 200), rng.below(16 * 200));
            let size = [16 * 4, 16 * 40, 16 * 180][case % 3];
            let (w, h) = (16 + rng.below(size), 16 + rng.below(size));
            let (x1, y1) = (x0 + w, y0 + h);
            let wide = case % 4 == 3;
            let jitter = |r: &mut Rng| {
                if wide {
                    r.below(33) - 16
                } else {
                    r.below(9) - 4
                }
            };
            // Every fourth a pentagon: more than four edges set up.
            let corners = [
                (x0, y0, jitter(&mut rng)),
                (x0 + 5, y1, jitter(&mut rng)),
                (x1, y1 - 7, jitter(&mut rng)),
                (x1 + w / 3, (y0 + y1) / 2, jitter(&mut rng)),
                (x1 - 3, y0 + 2, jitter(&mut rng)),
            ]
            .map(|(x, y, j)| {
                let z = z0 + (p as i64 * x as i64 + q as i64 * y as i64).div_euclid(64) as i32;
                v3(x, y, (z + j).clamp(-32768, 32767))
            });
            let quad: &[Vertex3] = if wide {
                &corners
            } else {
                &[corners[0], corners[1], corners[2], corners[4]]
            };
            let Some(plane) = Plane::of(quad.iter().copied()) else {
                continue;
            };
            let zs = quad.iter().map(|v| v.z.units());
            let z = (zs.clone().min().unwrap(), zs.max().unwrap());
            let Ok(poly) = Polygon::load(&mut slots, quad.iter().copied(), &clip) else {
                continue;
            };
            let ends = &poly.slots[..poly.edges];
            let holds = |p: &Plane| {
                ends.iter().all(|e| {
                    let e = &e.ends;
                    p.depth_within(e.x0 as i32, e.y0 as i32, z)
                        && p.depth_within(e.x1 as i32, e.y1 as i32, z)
                })
            };
            let want = if holds(&plane) {
                plane
            } else {
                bisected += 1;
                pentagons += (quad.len() == 5) as u32;
                let k = bisect(|k| holds(&plane.flattened(k)));
                if ((1i64 << 16) - k) * (z.1 - z.0) as i64 <= 2 << 16 {
                    plane.flattened(k)
                } else {
                    fitted(&plane, ends, z)
                }
            };
            assert_eq!(poly.bounded(plane, z), want, "{quad:?}");
        }
        assert!(bisected > 2000, "{bisected}");
        assert!(pentagons > 200, "{pentagons}");
    }

    /// Large quads on random planes, their vertices' depths rounded to
    /// whole units (as the geometry stage leaves a face the clips cut):
    /// whatever plane is loaded stays within a unit or two of each vertex,
    /// never flattened to the first vertex's depth.
    #[test]
    fn a_rounded_plane_is_fitted_near_its_vertices() {
        let mut rng = Rng(0x5eed_f17e);
        let clip = ClipRect::full(4096, 4096);
        let mut slots = [EdgeSlot::EMPTY; 4];
        let (mut fitted, mut worst) = (0, 0i128);
        for _ in 0..3000 {
            // z = z₀ + (p·x + q·y) / 64, in units.
            // |z| < 4000 + 2 · 100 · 6400 / 64 < 2¹⁵: none clamped.
            let (p, q) = (rng.below(201) - 100, rng.below(201) - 100);
            let z0 = rng.below(8001) - 4000;
            // A convex quad at least 20 px on a side.
            let (x0, y0) = (rng.below(16 * 200), rng.below(16 * 200));
            let (w, h) = (320 + rng.below(16 * 180), 320 + rng.below(16 * 180));
            let (x1, y1) = (x0 + w, y0 + h);
            let quad = [(x0, y0), (x0 + 5, y1), (x1, y1 - 7), (x1 - 3, y0 + 2)].map(|(x, y)| {
                let z = z0 + (p as i64 * x as i64 + q as i64 * y as i64).div_euclid(64) as i32;
                v3(x, y, z.clamp(-32768, 32767))
            });
            let Some(newell) = Plane::of(quad) else {
                continue;
            };
            let loaded = Polygon::load(&mut slots, quad, &clip).unwrap();
            let got = *loaded.plane().unwrap();
            fitted += (got != newell) as u32;
            for v in quad {
                let (e, c) = (got.rhs_at(v.x.units() as i128, v.y.units() as i128), got.c);
                let d = (e - v.z.units() as i128 * c as i128).abs();
                worst = worst.max(d / c as i128);
            }
        }
        assert!(fitted > 100, "{fitted}");
        assert!(worst <= 2, "{worst}");
    }

    #[test]
    fn triangles_are_never_flattened() {
        let mut rng = Rng(0x7777_1234);
        let clip = ClipRect::full(4096, 4096);
        let mut slots = [EdgeSlot::EMPTY; 3];
        for _ in 0..3000 {
            let mut r = || rng.below(65536) - 32768;
            let tri = [v3(r(), r(), r()), v3(r(), r(), r()), v3(r(), r(), r())];
            let p = Polygon::load(&mut slots, tri, &clip).unwrap();
            assert_eq!(p.plane().copied(), Plane::of(tri));
        }
    }

    #[test]
    fn extreme_coordinates_do_not_overflow() {
        let m = [i16::MIN as i32, -1, 0, 1, i16::MAX as i32];
        let clip = ClipRect::full(4096, 4096);
        let mut slots = [EdgeSlot::EMPTY; 3];
        let mut wide = [EdgeSlot::EMPTY; 4];
        for &x in &m {
            for &y in &m {
                for &z in &m {
                    let neg = |v: i32| (-v).min(i16::MAX as i32);
                    let tri = [
                        v3(x, y, z),
                        v3(neg(x), y, neg(z)),
                        v3(y, neg(x), i16::MIN as i32),
                    ];
                    if let Some(p) = Plane::of(tri) {
                        let d = p.depth();
                        let _ = d.at(4095, 4095);
                        let _ = p.cmp_at(&p, 4096, 4096);
                    }
                    let poly = Polygon::load(&mut slots, tri, &clip).unwrap();
                    let _ = poly.cut(|_, _| Ok::<(), ()>(()));
                    // A bow tie through the same corners, far from planar.
                    let bow = [tri[0], tri[1], v3(neg(y), x, z), tri[2]];
                    let poly = Polygon::load(&mut wide, bow, &clip).unwrap();
                    if let Some(p) = poly.plane() {
                        let d = p.depth();
                        let _ = d.at(4095, 4095);
                        let _ = p.cmp_at(p, 4096, 4096);
                    }
                    // Moved as far toward the eye as a plane may be.
                    let poly = Polygon::load_lifted(&mut wide, bow, &clip, 1 << 13).unwrap();
                    if let Some(p) = poly.plane() {
                        let d = p.depth();
                        let _ = d.at(4095, 4095);
                        let _ = p.cmp_at(p, 4096, 4096);
                    }
                }
            }
        }
    }

    /// A moved plane is the same plane, its depth less the move at every
    /// pixel, exactly and in fixed point.
    #[test]
    fn a_plane_moved_toward_the_eye_is_nearer_by_the_move_everywhere() {
        let mut rng = Rng(0x11f7_e71e);
        for _ in 0..2000 {
            let mut r = |m: u32| rng.below(2 * m) - m as i32;
            let tri = [
                v3(r(32767), r(32767), r(32767)),
                v3(r(32767), r(32767), r(32767)),
                v3(r(32767), r(32767), r(32767)),
            ];
            let Some(p) = Plane::of(tri) else { continue };
            for lift in [1u16, 256, 1 << 14] {
                let q = p.toward_eye(lift);
                assert_eq!(q.normal(), p.normal());
                for (i, j) in [(0, 0), (4095, 0), (0, 4095), (4095, 4095), (17, 3000)] {
                    let (e, c) = p.depth_at(i, j);
                    let (f, d) = q.depth_at(i, j);
                    assert_eq!((f, d), (e - lift as i128 * c as i128, c));
                    let z = p.depth().at(i, j);
                    let want = z.wrapping_sub((lift as i32) << Z_FRAC_BITS);
                    assert_eq!(q.depth().at(i, j), want, "{tri:?} {lift}");
                }
            }
        }
        // Beyond 2¹⁴, the move is 2¹⁴.
        let p = Plane::of([v3(0, 0, 0), v3(0, 16, 0), v3(16, 0, 0)]).unwrap();
        assert_eq!(p.toward_eye(u16::MAX), p.toward_eye(1 << 14));
    }

    /// The quad of a line, made as the geometry stage makes it (ends in
    /// 1/256 px, the offset across shared, then each corner rounded to
    /// Q12.4): depth `za` at both corners of one end and `zb` at the
    /// other's.
    fn line_quad(rng: &mut Rng) -> [Vertex3; 4] {
        let a = [
            rng.below(256 * 200) + 256 * 20,
            rng.below(256 * 140) + 256 * 20,
        ];
        let (dx, dy) = loop {
            let d = (rng.below(2001) - 1000, rng.below(2001) - 1000);
            if d.0 * d.0 + d.1 * d.1 > 10_000 {
                break d;
            }
        };
        let len = ((dx * dx + dy * dy) as u32).isqrt() as i32;
        // 4 to 64 px long, 1 to 3 px thick.
        let (along, half) = (256 * (4 + rng.below(60)), 128 + rng.below(256));
        let b = [a[0] + dx * along / len, a[1] + dy * along / len];
        let (ox, oy) = (-dy * half / len, dx * half / len);
        let za = rng.below(60000) - 30000;
        let zb = (za + rng.below(4000) - 2000).clamp(-32768, 32767);
        let c = |p: [i32; 2], s: i32, z: i32| {
            let r = |v: i32| (v + 8).div_euclid(16);
            v3(r(p[0] + s * ox), r(p[1] + s * oy), z)
        };
        [c(a, 1, za), c(b, 1, zb), c(b, -1, zb), c(a, -1, za)]
    }

    /// Rounding tilts a line's quad off its plane; bounded by its depth
    /// range, Newell's plane is then fitted (scaled and moved: the
    /// corners of one end are at an extreme of the range); bounded by the
    /// range widened by the move, it is kept.
    #[test]
    fn a_line_quad_moved_toward_the_eye_keeps_its_slope() {
        let mut rng = Rng(0x0715_e0ff);
        let clip = ClipRect::full(320, 240);
        let mut slots = [EdgeSlot::EMPTY; 4];
        let (mut flat, mut kept) = (0, 0);
        for _ in 0..3000 {
            let quad = line_quad(&mut rng);
            let Some(newell) = Plane::of(quad) else {
                continue;
            };
            let plain = Polygon::load(&mut slots, quad, &clip).unwrap();
            flat += (plain.plane() != Some(&newell)) as u32;
            let lifted = Polygon::load_lifted(&mut slots, quad, &clip, 256).unwrap();
            let lifted = lifted.plane().copied();
            if lifted == Some(newell.toward_eye(256)) {
                kept += 1;
            }
        }
        assert!(flat > 300, "{flat}");
        assert!(kept >= 2990, "{kept}");
    }

    /// A moved plane stays within `[z_min − 2·lift, z_max]` (the
    /// vertices' depth range) at every pixel the polygon covers, planar
    /// or not; and is Newell's plane moved whenever Newell's stays within
    /// `[z_min − lift, z_max + lift]` at the vertices.
    #[test]
    fn lifted_planes_stay_within_the_widened_range() {
        let mut rng = Rng(0x1f7e_d5ee);
        let clip = ClipRect::full(W as u16, H as u16);
        let mut slots = [EdgeSlot::EMPTY; 8];
        for case in 0..2000 {
            let n = 3 + rng.below(5) as usize;
            let mut poly = [Vertex3::default(); 8];
            for v in poly.iter_mut().take(n) {
                let z = match case % 2 {
                    0 => rng.below(65536) - 32768,
                    _ => rng.below(64) - 32768,
                };
                *v = v3(rng.below(16 * W as u32), rng.below(16 * H as u32), z);
            }
            let poly = &poly[..n];
            let lift = [1, 256, 1 << 13][case % 3];
            let (zmin, zmax) = poly.iter().fold((i32::MAX, i32::MIN), |(a, b), v| {
                (a.min(v.z.units()), b.max(v.z.units()))
            });
            let zmin = zmin - 2 * lift as i32;
            let loaded = Polygon::load_lifted(&mut slots, poly.iter().copied(), &clip, lift);
            let Some(got) = loaded.unwrap().plane().copied() else {
                continue;
            };
            let inside = |pl: &Plane| {
                (0..H).all(|j| {
                    (0..W).all(|i| {
                        !covers(poly, i, j) || {
                            let (e, c) = pl.depth_at(i, j);
                            zmin as i128 * c as i128 <= e && e <= zmax as i128 * c as i128
                        }
                    })
                })
            };
            assert!(inside(&got), "{poly:?}");
            let newell = Plane::of(poly.iter().copied()).unwrap();
            let wide = (zmin + lift as i32, zmax + lift as i32);
            if poly.iter().all(|&v| {
                let (x, y) = (v.x.units(), v.y.units());
                newell.depth_within(x, y, wide)
            }) {
                assert_eq!(got, newell.toward_eye(lift), "{poly:?}");
            }
        }
    }
}
