//! An independent per-pixel reference of the pixel rule, in `i128`.
//!
//! It shares nothing with scanvert's stepper: for one pixel centre it
//! counts, edge by edge, the crossings at or left of the centre, with the
//! rule's half-open row test, and the pixel is covered when the count is
//! odd (which is the rule's "x_first ≤ centre < x_second for one pair").
//! Every product is formed in `i128`, so no input can overflow it.

use scanvert::fixed::Vertex;

/// `true` when pixel `(i, j)` is covered by the polygon `poly` under the
/// even-odd pixel rule of `text-form.md`.
pub fn covers(poly: &[Vertex], i: i32, j: i32) -> bool {
    // Pixel centre in units of 1/16 px.
    let xc = 16 * i as i128 + 8;
    let yc = 16 * j as i128 + 8;
    let mut odd = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        let (mut x0, mut y0) = (a.x.units() as i128, a.y.units() as i128);
        let (mut x1, mut y1) = (b.x.units() as i128, b.y.units() as i128);
        if y0 == y1 {
            continue;
        }
        if y0 > y1 {
            (x0, y0, x1, y1) = (x1, y1, x0, y0);
        }
        if !(y0 <= yc && yc < y1) {
            continue;
        }
        // Crossing x = x0 + (yc − y0)(x1 − x0)/(y1 − y0) is at or left of
        // the centre; multiplied through by y1 − y0 > 0.
        if x0 * (y1 - y0) + (yc - y0) * (x1 - x0) <= xc * (y1 - y0) {
            odd = !odd;
        }
    }
    odd
}

/// Pixels that may be covered (by any contender): the polygon's box,
/// widened by `margin` pixels and cut to the `w × h` frame, as
/// `(x0, y0, x1, y1)` with exclusive ends.
pub fn pixel_box(poly: &[Vertex], margin: i32, w: u16, h: u16) -> (i32, i32, i32, i32) {
    let xs = poly.iter().map(|v| v.x.units());
    let ys = poly.iter().map(|v| v.y.units());
    let (lx, hx) = (xs.clone().min().unwrap_or(0), xs.max().unwrap_or(0));
    let (ly, hy) = (ys.clone().min().unwrap_or(0), ys.max().unwrap_or(0));
    (
        ((lx >> 4) - margin).clamp(0, w as i32),
        ((ly >> 4) - margin).clamp(0, h as i32),
        ((hx >> 4) + 1 + margin).clamp(0, w as i32),
        ((hy >> 4) + 1 + margin).clamp(0, h as i32),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_covers_its_pixels_only() {
        let p = |x: i16, y: i16| Vertex::from_bits(x * 16, y * 16);
        let sq = [p(0, 0), p(3, 0), p(3, 2), p(0, 2)];
        let mut n = 0;
        for j in -1..4 {
            for i in -1..5 {
                if covers(&sq, i, j) {
                    assert!((0..3).contains(&i) && (0..2).contains(&j));
                    n += 1;
                }
            }
        }
        assert_eq!(n, 6);
    }

    #[test]
    fn tie_on_a_centre_goes_to_the_left_crossing() {
        // Left edge at x = 0.5 covers pixel 0, right edge at 2.5 excludes 2.
        let v = |x: i16, y: i16| Vertex::from_bits(x, y);
        let sq = [v(8, 0), v(40, 0), v(40, 16), v(8, 16)];
        assert!(covers(&sq, 0, 0));
        assert!(covers(&sq, 1, 0));
        assert!(!covers(&sq, 2, 0));
    }
}
