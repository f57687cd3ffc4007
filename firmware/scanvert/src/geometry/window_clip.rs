//! The window clip: re-entrant polygon clipping (Sutherland–Hodgman)
//! against the window's four sides, after projection.
//!
//! A polygon is clipped against one plane at a time: x ≥ 0, x ≤ width,
//! y ≥ 0, y ≤ height (in 1/256 px, sides included). Each pass walks the
//! edges once and keeps the inside vertices and the crossing points, so
//! concave polygons come out as one polygon too (possibly with edges
//! running along the window's side, which cover nothing). Passes whose
//! plane no vertex lies beyond are skipped: the projection gathers each
//! vertex's outcode (the sides it lies beyond), so a polygon wholly inside
//! costs no clipping at all, and one wholly beyond a side is dropped at
//! once.
//!
//! # Crossings
//!
//! A crossing point is `a + (b − a) · num / den`, rounded to nearest, for
//! each coordinate other than the plane's, where `num / den ∈ [0, 1]` is
//! the fraction along the edge. Depth is interpolated the same way: it is
//! affine in screen space, so this is exact up to the rounding. Each edge
//! is taken in a fixed order of its end points (the smaller first), so
//! two polygons sharing an edge get the very same crossing point, whichever
//! way round they walk it.
//!
//! The product `(b − a) · num` is `i64` when both factors are at most 2³⁰
//! in magnitude (always so inside the window, and in view space for the
//! near clip); otherwise it is `i128` (pre-clip screen values reach 2⁴⁶,
//! so the product stays below 2⁹⁴). The result always lies between `a`
//! and `b`, so clipped coordinates stay inside the window and depths
//! between the planes.
//!
//! # Capacity
//!
//! Every pass can add vertices (one per pass for a convex polygon, more
//! for a concave one). The buffers hold `N` vertices; a pass that would
//! need more fails, and the pipeline reports it as
//! [`PipelineError::Capacity`](super::PipelineError::Capacity).

use super::project::Viewport;

/// A polygon under clipping: up to `N` vertices of three `i64`.
pub(super) type Poly<const N: usize> = heapless::Vec<[i64; 3], N>;

/// A clip pass ran out of vertex capacity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Full;

const SMALL: i64 = 1 << 30;

/// `a + round((b − a) · num / den)` for `0 ≤ num ≤ den`, `den > 0`; the
/// result lies between `a` and `b`.
#[inline]
pub(super) fn lerp(a: i64, b: i64, num: i64, den: i64) -> i64 {
    let d = b - a;
    if d.abs() <= SMALL && num <= SMALL {
        // |d · num| ≤ 2⁶⁰.
        a + (d * num + den / 2).div_euclid(den)
    } else {
        let q = (d as i128 * num as i128 + (den / 2) as i128).div_euclid(den as i128);
        a + q as i64
    }
}

/// The point where edge `a`–`b` meets the plane `v[axis] = bound`; the two
/// ends lie on different sides of it.
#[inline]
fn crossing(a: [i64; 3], b: [i64; 3], axis: usize, bound: i64) -> [i64; 3] {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    let (mut num, mut den) = (bound - lo[axis], hi[axis] - lo[axis]);
    if den < 0 {
        num = -num;
        den = -den;
    }
    let mut out = [0i64; 3];
    for (k, o) in out.iter_mut().enumerate() {
        *o = if k == axis {
            bound
        } else {
            lerp(lo[k], hi[k], num, den)
        };
    }
    out
}

#[inline]
fn push_new<const N: usize>(dst: &mut Poly<N>, v: [i64; 3]) -> Result<(), Full> {
    if dst.last() != Some(&v) {
        dst.push(v).map_err(|_| Full)?;
    }
    Ok(())
}

/// One pass: the part of `src` where `v[axis] ≥ bound` (`keep_above`) or
/// `v[axis] ≤ bound`, into `dst`. Repeated points are dropped.
pub(super) fn clip_plane<const N: usize>(
    src: &Poly<N>,
    dst: &mut Poly<N>,
    axis: usize,
    bound: i64,
    keep_above: bool,
) -> Result<(), Full> {
    dst.clear();
    let inside = |v: &[i64; 3]| {
        if keep_above {
            v[axis] >= bound
        } else {
            v[axis] <= bound
        }
    };
    let Some(&last) = src.last() else {
        return Ok(());
    };
    let (mut s, mut s_in) = (last, inside(&last));
    for &e in src {
        let e_in = inside(&e);
        if e_in != s_in {
            push_new(dst, crossing(s, e, axis, bound))?;
        }
        if e_in {
            push_new(dst, e)?;
        }
        (s, s_in) = (e, e_in);
    }
    while dst.len() > 1 && dst.last() == dst.first() {
        dst.pop();
    }
    Ok(())
}

/// Two polygon buffers that clip passes alternate between: one holds the
/// current polygon, the other receives the next pass.
#[derive(Debug)]
pub(super) struct Work<const N: usize> {
    buf: [Poly<N>; 2],
    cur: usize,
}

impl<const N: usize> Work<N> {
    pub(super) const fn new() -> Self {
        Work {
            buf: [Poly::new(), Poly::new()],
            cur: 0,
        }
    }

    /// The current polygon.
    pub(super) fn current(&self) -> &Poly<N> {
        &self.buf[self.cur & 1]
    }

    /// The current polygon, to fill or change in place.
    pub(super) fn current_mut(&mut self) -> &mut Poly<N> {
        &mut self.buf[self.cur & 1]
    }

    /// Clips the current polygon against one plane (see [`clip_plane`]).
    pub(super) fn pass(&mut self, axis: usize, bound: i64, keep_above: bool) -> Result<(), Full> {
        let [first, second] = &mut self.buf;
        let (src, dst) = if self.cur & 1 == 0 {
            (&*first, second)
        } else {
            (&*second, first)
        };
        clip_plane(src, dst, axis, bound, keep_above)?;
        self.cur ^= 1;
        Ok(())
    }
}

/// Which sides of the window a polygon's vertices lie beyond (Cohen and
/// Sutherland's outcodes): bit 0 left, 1 right, 2 above, 3 below.
#[derive(Clone, Copy, Debug)]
pub(super) struct Outcodes {
    /// Sides some vertex is beyond: the planes to clip against.
    any: u8,
    /// Sides every vertex is beyond: non-zero means nothing is inside.
    all: u8,
}

impl Outcodes {
    /// The codes of no vertices.
    pub(super) const EMPTY: Outcodes = Outcodes { any: 0, all: 0xF };

    /// Takes in the vertex `v` for the window `window`.
    #[inline]
    pub(super) fn add(&mut self, v: &[i64; 3], window: &Viewport) {
        let code = (v[0] < 0) as u8
            | ((v[0] > window.right_fine()) as u8) << 1
            | ((v[1] < 0) as u8) << 2
            | ((v[1] > window.bottom_fine()) as u8) << 3;
        self.any |= code;
        self.all &= code;
    }

    /// `true` when no vertex lies beyond a side: the clip changes nothing.
    #[inline]
    pub(super) fn is_inside(&self) -> bool {
        self.any == 0
    }
}

/// Clips the current polygon of `work`, whose vertices have the codes
/// `codes`, to the window; empty when nothing is left.
pub(super) fn clip_window<const N: usize>(
    work: &mut Work<N>,
    window: &Viewport,
    codes: Outcodes,
) -> Result<(), Full> {
    if codes.all != 0 {
        work.current_mut().clear();
        return Ok(());
    }
    let passes = [
        (0, 0, true),
        (0, window.right_fine(), false),
        (1, 0, true),
        (1, window.bottom_fine(), false),
    ];
    for (side, (axis, bound, keep_above)) in passes.into_iter().enumerate() {
        if codes.any & (1 << side) != 0 {
            work.pass(axis, bound, keep_above)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run<const N: usize>(pts: &[[i64; 3]], w: &Viewport) -> Result<Poly<N>, Full> {
        let mut work = Work::<N>::new();
        work.current_mut().extend(pts.iter().copied());
        let mut codes = Outcodes::EMPTY;
        pts.iter().for_each(|v| codes.add(v, w));
        clip_window(&mut work, w, codes)?;
        Ok(work.current().clone())
    }

    #[test]
    fn lerp_stays_between_and_is_symmetric() {
        for (a, b) in [
            (0, 10),
            (10, 0),
            (-7, 7),
            (i64::MAX / 4, -(1 << 46)),
            (1 << 45, -(1 << 45)),
        ] {
            for (num, den) in [
                (0, 3),
                (1, 3),
                (2, 3),
                (3, 3),
                (1 << 40, 1 << 46),
                (7, 1 << 47),
            ] {
                let v = lerp(a, b, num, den);
                assert!(v >= a.min(b) && v <= a.max(b));
            }
        }
        assert_eq!(lerp(0, 10, 1, 2), 5);
        assert_eq!(lerp(0, 1, 1, 2), 1);
        assert_eq!(lerp(10, 0, 1, 4), 8); // 7.5 rounds up
    }

    #[test]
    fn a_triangle_sticking_out_to_the_left() {
        let w = Viewport::centred(100, 100).unwrap();
        let out = run::<8>(&[[-2560, 0, 0], [2560, 0, 0], [2560, 2560, 4096]], &w).unwrap();
        assert_eq!(
            out.as_slice(),
            &[[0, 1280, 2048], [0, 0, 0], [2560, 0, 0], [2560, 2560, 4096]]
        );
    }

    #[test]
    fn wholly_outside_and_capacity() {
        let w = Viewport::centred(10, 10).unwrap();
        assert!(run::<4>(&[[-10, 0, 0], [-5, 0, 0], [-5, 5, 0]], &w)
            .unwrap()
            .is_empty());
        // A triangle with all three corners cut off: a hexagon.
        let tri = [[1280, -1000, 0], [3800, 3500, 0], [-1240, 3500, 0]];
        assert_eq!(run::<8>(&tri, &w).map(|p| p.len()), Ok(6));
        assert_eq!(run::<5>(&tri, &w), Err(Full));
    }

    #[test]
    fn shared_edges_cross_at_the_same_point() {
        let w = Viewport::centred(10, 10).unwrap();
        let p = [-1000, 333, 77];
        let q = [2000, 1900, -5000];
        let one = run::<8>(&[p, q, [2000, -3000, 0]], &w).unwrap();
        let two = run::<8>(&[q, p, [-1000, 3000, 0]], &w).unwrap();
        let on_left = |v: &&[i64; 3]| v[0] == 0;
        let x: heapless::Vec<_, 8> = one.iter().filter(on_left).collect();
        let y: heapless::Vec<_, 8> = two.iter().filter(on_left).collect();
        assert!(x.iter().any(|v| y.contains(v)), "{one:?} {two:?}");
    }
}
