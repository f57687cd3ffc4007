//! An exact reference of the line rule (`docs/display-list.md`, *The line rule*),
//! written from the rule alone.
//!
//! It shares nothing with `scanvert::raster::line`: no walk, no error
//! counter, no division. Each pixel is decided on its own by
//! [`on_line`], a comparison of `i128` products of the end points (in units
//! of 1/16 px), so it is exact for any input:
//!
//! * x-major (`|x₁ − x₀| ≥ |y₁ − y₀|`, not both zero): pixel `(i, j)` is on
//!   the line when the centre column `xc = i + ½` has
//!   `min(x₀, x₁) ≤ xc < max(x₀, x₁)`, and the line's exact y there,
//!   `y = y₀ + (y₁ − y₀)(xc − x₀)/(x₁ − x₀)`, has `j ≤ y < j + 1` (a y on a
//!   boundary is in the pixel below). Multiplied out by the denominator
//!   made positive: `16j·den ≤ num < 16(j + 1)·den` with
//!   `num/den = y` in units.
//! * y-major: the same with x and y swapped.
//!
//! [`line_pixels`] lists the pixels by asking [`on_line`] about the few
//! candidates around each major-axis position (found with `f64`, only to
//! keep the search short; the decision is exact), and checks that exactly
//! one is on the line there, as the rule says.

use crate::reference::Window;

/// `true` when pixel `(i, j)` is on the line from `a` to `b` (units of
/// 1/16 px) by the line rule, clipping aside.
pub fn on_line(a: (i32, i32), b: (i32, i32), i: i32, j: i32) -> bool {
    let (dx, dy) = (b.0 as i128 - a.0 as i128, b.1 as i128 - a.1 as i128);
    if dx == 0 && dy == 0 {
        return false;
    }
    if dx.abs() >= dy.abs() {
        decide((a.0, a.1), (b.0, b.1), i, j)
    } else {
        decide((a.1, a.0), (b.1, b.0), j, i)
    }
}

/// The rule for a line major along the first coordinate: `m` is the
/// major-axis pixel, `n` the minor-axis pixel.
fn decide(a: (i32, i32), b: (i32, i32), m: i32, n: i32) -> bool {
    let (a0, a1, b0, b1) = (a.0 as i128, a.1 as i128, b.0 as i128, b.1 as i128);
    let c = 16 * m as i128 + 8; // the centre, in units
    if !(a0.min(b0) <= c && c < a0.max(b0)) {
        return false;
    }
    // The minor coordinate at c is num/den units.
    let mut den = b0 - a0;
    let mut num = a1 * den + (b1 - a1) * (c - a0);
    if den < 0 {
        den = -den;
        num = -num;
    }
    let lo = 16 * n as i128 * den;
    lo <= num && num < lo + 16 * den
}

/// Every pixel of the line from `a` to `b` (units), unclipped, in
/// major-axis order. Panics if a major-axis position in range had no
/// pixel or two, which the rule forbids.
pub fn line_pixels(a: (i32, i32), b: (i32, i32)) -> Vec<(i32, i32)> {
    let (dx, dy) = (b.0 as i64 - a.0 as i64, b.1 as i64 - a.1 as i64);
    if dx == 0 && dy == 0 {
        return Vec::new();
    }
    let x_major = dx.abs() >= dy.abs();
    let (ma, mb, na, nb) = if x_major {
        (a.0, b.0, a.1, b.1)
    } else {
        (a.1, b.1, a.0, b.0)
    };
    let lo = ma.min(mb) as i64 / 16 - 2;
    let hi = ma.max(mb) as i64 / 16 + 2;
    let mut out = Vec::new();
    for m in lo..=hi {
        let c = 16.0 * m as f64 + 8.0;
        let (lo_m, hi_m) = (ma.min(mb) as f64, ma.max(mb) as f64);
        let in_range = lo_m <= c && c < hi_m;
        let t = (c - ma as f64) / (mb as f64 - ma as f64);
        let guess = ((na as f64 + t * (nb as f64 - na as f64)) / 16.0).floor() as i64;
        let hits: Vec<i32> = (guess - 2..=guess + 2)
            .map(|n| n as i32)
            .filter(|&n| {
                let (i, j) = if x_major {
                    (m as i32, n)
                } else {
                    (n, m as i32)
                };
                on_line(a, b, i, j)
            })
            .collect();
        assert_eq!(
            hits.len(),
            in_range as usize,
            "line {a:?}–{b:?} at major pixel {m}: {hits:?}"
        );
        for n in hits {
            out.push(if x_major {
                (m as i32, n)
            } else {
                (n, m as i32)
            });
        }
    }
    out
}

/// The pixels of the line inside the clip registers and a `width ×
/// height` frame, sorted by row, then column.
pub fn line_clipped(
    a: (i32, i32),
    b: (i32, i32),
    window: Window,
    width: u16,
    height: u16,
) -> Vec<(i32, i32)> {
    let mut v: Vec<(i32, i32)> = line_pixels(a, b)
        .into_iter()
        .filter(|&(i, j)| {
            window.contains(i, j)
                && (0..width as i32).contains(&i)
                && (0..height as i32).contains(&j)
        })
        .collect();
    v.sort_unstable_by_key(|&(i, j)| (j, i));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spec_examples() {
        // From the centre of (1, 2) to the centre of (5, 2): 1..5 on row 2.
        let p = line_pixels((24, 40), (88, 40));
        assert_eq!(p, vec![(1, 2), (2, 2), (3, 2), (4, 2)]);
        // Reversed: the same pixels (the lower end counts either way).
        let mut q = line_pixels((88, 40), (24, 40));
        q.sort_unstable();
        assert_eq!(q, p);
        // A y on a boundary goes to the pixel below: y = 2 exactly.
        assert_eq!(line_pixels((0, 32), (32, 32)), vec![(0, 2), (1, 2)]);
        // Zero length.
        assert!(line_pixels((5, 5), (5, 5)).is_empty());
    }
}
