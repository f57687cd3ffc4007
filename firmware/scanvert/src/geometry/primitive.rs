//! Points and lines: polygons of one and two vertices, drawn as small
//! polygons of a fixed thickness in the image.
//!
//! They are visible from every side (never culled), are not lit, and reach
//! the sink with `two_sided` set. After the near clip and projection they
//! are widened in pre-clip screen space (1/256 px), then clipped by the
//! window like any polygon:
//!
//! * a **point** becomes a square of side `t` centred on it, at its depth;
//! * a **line** becomes a quad: both ends moved by `±t/2` perpendicular to
//!   its projected direction, with no caps. Its depth is that of each end at
//!   the two corners there, so the quad is planar: `z` is affine along the
//!   line and constant across it. A line whose ends project to the same
//!   point becomes a square at the nearer depth.
//!
//! The perpendicular is normalised in integers: the direction is scaled by
//! a power of two to 15 bits, its length taken by `isqrt`, and the offset
//! is `(−dy, dx) · (t/2) / len` (`|·| < 2¹⁵ · 2¹⁹`, `i64`), within 1/256 px
//! of the exact one. The ends and the offset are rounded to the output's
//! grid (1/16 px, a Q12.4 step of depth) and both ends share the one
//! offset, so the quad is a parallelogram exactly, in 3D too: its corners
//! are not rounded again, and its plane is the one the visible-surface
//! stage compares (a point's square is at one depth: planar anyway). The
//! vertices run counter-clockwise as displayed.

use super::light::{length15, scale15};

/// The square of half-side `half` (1/256 px) around `p`.
#[inline]
pub(super) fn point_quad(p: [i64; 3], half: i64) -> [[i64; 3]; 4] {
    let [x, y, z] = p;
    [
        [x - half, y - half, z],
        [x - half, y + half, z],
        [x + half, y + half, z],
        [x + half, y - half, z],
    ]
}

/// The quad of half-width `half` (1/256 px) along `a`–`b`.
///
/// Its ends and offset are rounded to the output's grid first (x, y to
/// 1/16 px, depth to a Q12.4 step, as `project::to_vertex3` rounds), so
/// its corners are on the grid and it is a parallelogram in 3D after the
/// rounding too: planar, unless the window clip cuts it.
#[inline]
pub(super) fn line_quad(a: [i64; 3], b: [i64; 3], half: i64) -> [[i64; 3]; 4] {
    let Some(s) = scale15([b[0] - a[0], b[1] - a[1], 0]) else {
        let nearer = if a[2] <= b[2] { a } else { b };
        return point_quad(nearer, half);
    };
    let len = length15(s) as i64;
    let grid = |v: i64, shift: u32| ((v + (1 << (shift - 1))) >> shift) << shift;
    let snap = |p: [i64; 3]| [grid(p[0], 4), grid(p[1], 4), grid(p[2], 8)];
    let off = |c: i32| grid((c as i64 * half + len / 2).div_euclid(len), 4);
    let (ox, oy) = (off(-s[1]), off(s[0]));
    let (a, b) = (snap(a), snap(b));
    [
        [a[0] + ox, a[1] + oy, a[2]],
        [b[0] + ox, b[1] + oy, b[2]],
        [b[0] - ox, b[1] - oy, b[2]],
        [a[0] - ox, a[1] - oy, a[2]],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shoelace(q: &[[i64; 3]; 4]) -> i64 {
        (0..4)
            .map(|i| {
                let (p, n) = (q[i], q[(i + 1) % 4]);
                p[0] * n[1] - n[0] * p[1]
            })
            .sum()
    }

    #[test]
    fn squares_and_quads_run_counter_clockwise_as_displayed() {
        let sq = point_quad([100, 100, 7], 10);
        assert_eq!(shoelace(&sq), -2 * 20 * 20);
        let q = line_quad([0, 0, 1], [1000, 0, 300], 16);
        assert_eq!(
            q,
            [[0, 16, 0], [1008, 16, 256], [1008, -16, 256], [0, -16, 0]]
        );
        assert!(shoelace(&q) < 0);
        let q = line_quad([1000, 0, 1], [0, 0, 9], 16);
        assert!(shoelace(&q) < 0);
        let q = line_quad([0, 0, 1], [300, 400, 9], 500);
        assert_eq!(q[0], [-400, 304, 0]);
    }

    #[test]
    fn end_on_lines_are_squares_at_the_nearer_end() {
        assert_eq!(line_quad([5, 5, 9], [5, 5, 3], 2), point_quad([5, 5, 3], 2));
    }

    #[test]
    fn long_lines_keep_their_width() {
        let big = 1i64 << 46;
        let q = line_quad([-big, -big, 0], [big, big / 3, 0], 1 << 18);
        let (ox, oy) = (q[0][0] + big, q[0][1] + big);
        let w2 = ox * ox + oy * oy;
        let t2 = 1i64 << 36;
        assert!((w2 - t2).abs() < t2 / 1000, "{ox} {oy}");
    }
}
