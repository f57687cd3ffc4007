//! The exact winding-number reference: both fill rules decided pixel by
//! pixel from the winding number of the pixel's centre.
//!
//! It shares no code with `scanvert::raster` (no stepper, no active-edge
//! list, no sort, no pairing) nor with [`reference`](crate::reference):
//! where that one counts the crossings *at or left of* a centre, this one
//! sums signed crossings of the ray going *right* from it, as in the
//! classic point-in-polygon winding test, and decides on which side of an
//! edge the centre lies by the sign of a cross product rather than by
//! placing the crossing.
//!
//! # The rule, as evaluated here
//!
//! For the centre `p = (i + ½, j + ½)` and each edge `a → b` in the
//! polygon's order, with `s(a, b, p) = (b.x − a.x)(p.y − a.y) −
//! (p.x − a.x)(b.y − a.y)`:
//! * an edge running down the rows with `a.y ≤ p.y < b.y` crosses the ray
//!   right of `p` when `s > 0`, and adds +1;
//! * an edge running up with `b.y ≤ p.y < a.y` crosses it right of `p`
//!   when `s < 0`, and adds −1.
//!
//! `s` is the crossing's distance right of `p` times `b.y − a.y`, so the
//! two cases are "the crossing's `x` is greater than `p.x`", exactly, with
//! `i128` products of coordinates in units of 1/16 px (exact for any
//! `i32` input). The half-open `y` test is the pixel rule's (an edge's
//! upper end counts, its lower end does not; horizontal edges never
//! count). The sum is the winding number `w` of the centre.
//!
//! # Why this is the pixel rule, for both fill rules
//!
//! The signed crossings of one row add up to zero (walking the closed
//! polygon, it crosses the row down as often as up). So the sum right of
//! the centre is minus the sum at or left of it, and both are zero
//! together: the non-zero rule covers the pixel when `w ≠ 0`. Each
//! crossing adds ±1, so `w` is odd exactly when the number of crossings
//! right of the centre is odd, that is (the row has an even number of
//! them) when the number at or left of it is odd: the even-odd rule
//! covers the pixel when `w` is odd.

use crate::reference::{Coverage, Window};
use scanvert::raster::FillRule;

/// The winding number of the centre of pixel `(i, j)`: the signed
/// crossings of the ray going right from it (+1 for an edge running down
/// the rows). `poly` in units of 1/16 px.
pub fn winding_number(poly: &[(i32, i32)], i: i32, j: i32) -> i64 {
    let p = (16 * i as i128 + 8, 16 * j as i128 + 8);
    let mut w = 0i64;
    for (k, &a) in poly.iter().enumerate() {
        let b = poly[(k + 1) % poly.len()];
        let (a, b) = ((a.0 as i128, a.1 as i128), (b.0 as i128, b.1 as i128));
        let s = (b.0 - a.0) * (p.1 - a.1) - (p.0 - a.0) * (b.1 - a.1);
        if a.1 <= p.1 && p.1 < b.1 {
            if s > 0 {
                w += 1;
            }
        } else if b.1 <= p.1 && p.1 < a.1 && s < 0 {
            w -= 1;
        }
    }
    w
}

/// `true` when `rule` covers pixel `(i, j)` of `poly`.
pub fn covers(poly: &[(i32, i32)], rule: FillRule, i: i32, j: i32) -> bool {
    let w = winding_number(poly, i, j);
    match rule {
        FillRule::EvenOdd => w % 2 != 0,
        FillRule::NonZero => w != 0,
    }
}

/// The pixels of a `width × height` frame that `rule` covers inside the
/// clip `window`.
pub fn rasterize(
    poly: &[(i32, i32)],
    rule: FillRule,
    window: Window,
    width: u32,
    height: u32,
) -> Coverage {
    Coverage::from_fn(width, height, |i, j| {
        let (i, j) = (i as i32, j as i32);
        window.contains(i, j) && !poly.is_empty() && covers(poly, rule, i, j)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Random polygons, self-intersecting ones included: the even-odd rule
    /// decided from the winding number is the crossing count's of
    /// [`reference`](crate::reference), pixel for pixel.
    #[test]
    fn even_odd_from_the_winding_number_is_the_crossing_count() {
        let mut rng = Rng(0x5eed_0a1d);
        for _ in 0..300 {
            let n = rng.range(3, 10) as usize;
            let poly: Vec<(i32, i32)> = (0..n)
                .map(|_| (rng.range(-40, 560), rng.range(-40, 560)))
                .collect();
            for j in -1..34 {
                for i in -1..34 {
                    assert_eq!(
                        covers(&poly, FillRule::EvenOdd, i, j),
                        crate::reference::covers(&poly, i, j),
                        "{poly:?} ({i}, {j})"
                    );
                }
            }
        }
    }

    /// A five-pointed star in one stroke winds twice around its middle;
    /// traversed the other way, −2; a square once, on every inner pixel.
    #[test]
    fn a_star_winds_twice_around_its_middle() {
        let star: Vec<(i32, i32)> = [(16, 2), (24, 28), (3, 12), (29, 12), (8, 28)]
            .iter()
            .map(|&(x, y)| (16 * x, 16 * y))
            .collect();
        assert_eq!(winding_number(&star, 16, 16).abs(), 2);
        let back: Vec<_> = star.iter().rev().copied().collect();
        assert_eq!(
            winding_number(&back, 16, 16),
            -winding_number(&star, 16, 16)
        );
        assert!(covers(&star, FillRule::NonZero, 16, 16));
        assert!(!covers(&star, FillRule::EvenOdd, 16, 16));
        let square = [(0, 0), (160, 0), (160, 160), (0, 160)];
        for j in 0..10 {
            for i in 0..10 {
                assert_eq!(winding_number(&square, i, j).abs(), 1);
            }
        }
        assert_eq!(winding_number(&square, 10, 5), 0);
    }
}
