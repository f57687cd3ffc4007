//! The near clip, in view space before projection: the part of a polygon
//! at depths `near ≤ z ≤ far`.
//!
//! Projection divides by the view depth, so nothing may reach it at or
//! behind the eye. Sutherland–Hodgman against the plane `z = near` cuts
//! each polygon to the part in front of it: a polygon crossing the plane
//! gets new vertices on it, and one wholly behind the eye (or behind the
//! near plane) vanishes. The far plane is clipped in the same pass, so
//! every depth that reaches the screen lies in the Q12.4 range, and
//! the mapping of depth stays planar (clamping it would bend the planes).
//!
//! The crossing of edge `a`–`b` with `z = c` is
//! `a + (b − a)·(c − a_z)/(b_z − a_z)` in x and y, and exactly `c` in z. In
//! view space `|b − a| < 2³¹` and `|c − a_z| < 2³¹`, so the product fits
//! `i64`. The shared rules of [`window_clip`](super::window_clip) apply:
//! edges are taken in a fixed order of their ends (shared edges give the
//! same point), repeated points are dropped, and the vertex capacity is
//! the pipeline's `N`.
//!
//! A line (two vertices) is clipped as a segment, a point is kept or not.

use super::window_clip::{Full, Work};

/// Clips the current view-space polygon of `work`, whose depths span
/// `lo..=hi`, to `near ≤ z ≤ far`; empty when nothing is left.
pub(super) fn clip_depth<const N: usize>(
    work: &mut Work<N>,
    near: i32,
    far: i32,
    (lo, hi): (i32, i32),
) -> Result<(), Full> {
    if hi < near || lo > far {
        work.current_mut().clear();
        return Ok(());
    }
    if lo < near {
        work.pass(2, near as i64, true)?;
    }
    if hi > far {
        work.pass(2, far as i64, false)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::window_clip::Poly;

    fn run<const N: usize>(pts: &[[i64; 3]], near: i32, far: i32) -> Result<Poly<N>, Full> {
        let mut work = Work::<N>::new();
        work.current_mut().extend(pts.iter().copied());
        let lo = pts.iter().map(|v| v[2] as i32).min().unwrap_or(0);
        let hi = pts.iter().map(|v| v[2] as i32).max().unwrap_or(0);
        clip_depth(&mut work, near, far, (lo, hi))?;
        Ok(work.current().clone())
    }

    #[test]
    fn crossing_the_near_plane() {
        // A triangle with one corner behind the eye.
        let out = run::<8>(&[[0, 0, -10], [10, 0, 10], [-10, 0, 10]], 2, 100).unwrap();
        assert_eq!(
            out.as_slice(),
            &[[-6, 0, 2], [6, 0, 2], [10, 0, 10], [-10, 0, 10]]
        );
        assert!(out.iter().all(|v| v[2] >= 2));
    }

    #[test]
    fn wholly_behind_the_eye_vanishes() {
        assert!(run::<8>(&[[0, 0, -10], [10, 0, -1], [-10, 5, 0]], 1, 100)
            .unwrap()
            .is_empty());
        // Touching the near plane from behind leaves only points on it.
        let out = run::<8>(&[[0, 0, 1], [10, 0, -1], [-10, 5, 0]], 1, 100).unwrap();
        assert_eq!(out.as_slice(), &[[0, 0, 1]]);
    }

    #[test]
    fn near_and_far_together() {
        let out = run::<8>(&[[0, 0, -100], [0, 0, 300], [10, 0, 300]], 1, 100).unwrap();
        assert!(out.iter().all(|v| (1..=100).contains(&v[2])), "{out:?}");
        assert_eq!(out.len(), 4);
    }

    #[test]
    fn segments_and_points() {
        let seg = run::<4>(&[[0, 0, -10], [0, 20, 10]], 2, 100).unwrap();
        assert_eq!(seg.as_slice(), &[[0, 12, 2], [0, 20, 10]]);
        let seg = run::<4>(&[[0, 20, 10], [0, 0, -10]], 2, 100).unwrap();
        assert_eq!(seg.as_slice(), &[[0, 12, 2], [0, 20, 10]]);
        assert_eq!(run::<4>(&[[1, 2, 3]], 2, 100).unwrap().len(), 1);
        assert!(run::<4>(&[[1, 2, 1]], 2, 100).unwrap().is_empty());
        assert!(run::<4>(&[[1, 2, 101]], 2, 100).unwrap().is_empty());
    }

    #[test]
    fn view_space_extremes() {
        let e = (1i64 << 30) - 1;
        let out = run::<8>(&[[-e, -e, -e], [e, e, e], [e, -e, e]], 256, e as i32 - 1).unwrap();
        assert!(out.iter().all(|v| (256..=e - 1).contains(&v[2])));
        assert!(out.iter().all(|v| v[0].abs() <= e && v[1].abs() <= e));
    }
}
