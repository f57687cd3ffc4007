//! The exact 2D reference rasteriser, written from the pixel rule of the
//! display list (`docs/display-list.md`) and nothing else.
//!
//! It shares no code with `scanvert::raster::scan` or `scanvert::raster::edge`,
//! nor even their vertex type: no stepper, no active-edge list, no sort, no
//! division. Every pixel is decided on its own, with `i128` products of the
//! vertex coordinates (in units of 1/16 px, as plain `(x, y)` pairs), so it
//! is exact for any `i32` input. [`units`] turns the library's vertices
//! into such pairs.
//!
//! # The rule, as evaluated here
//!
//! For pixel `(i, j)` with centre `(xc, yc) = (i + ½, j + ½)`, count the
//! edges `(x0, y0)–(x1, y1)`, ordered so that `y0 < y1`, with
//! `y0 ≤ yc < y1` (horizontal edges never count) whose crossing with the
//! line `y = yc`, `x = x0 + (yc − y0)·(x1 − x0)/(y1 − y0)`, satisfies
//! `x ≤ xc`. Since `y1 − y0 > 0` the comparison is made multiplied out:
//! `x0·(y1 − y0) + (yc − y0)·(x1 − x0) ≤ xc·(y1 − y0)`. The pixel is
//! covered when the count is odd.
//!
//! # Why this is the spec's sorted-pairs rule
//!
//! Fix a row and let `c = j + ½`. An edge crosses `y = c` exactly when its
//! two end-points lie on different sides of the partition `{y ≤ c}` /
//! `{y > c}` (the half-open rule puts the upper end-point on the first
//! side, the lower one on the second). Walking the closed polygon once
//! changes side an even number of times, so the row has an even number
//! `2m` of crossings. Sort them: `x₁ ≤ x₂ ≤ … ≤ x₂ₘ`, and let
//! `n(xc) = #{l : x_l ≤ xc}`; since the list is sorted, `x_l ≤ xc` exactly
//! for `l ≤ n(xc)`.
//! * If `x_{2k−1} ≤ xc < x_{2k}` for some pair, then `n(xc) = 2k − 1`, odd.
//! * If `n(xc) = p` is odd, then `p < 2m` (2m is even), so
//!   `x_p ≤ xc < x_{p+1}` with `p = 2k − 1`: the pair `(x_{2k−1}, x_{2k})`
//!   covers the pixel.
//!
//! Equal crossings may be sorted either way without changing `n(xc)`, so
//! the two formulations pick the same pixels. The clip window is applied
//! afterwards, pixel by pixel.

use core::fmt;
use scanvert::fixed::Vertex;

/// The vertices as `(x, y)` in units of 1/16 px, the form every function
/// here takes.
pub fn units(poly: &[Vertex]) -> Vec<(i32, i32)> {
    poly.iter().map(|v| (v.x.units(), v.y.units())).collect()
}

/// The clip registers as loaded by a `clip` command: inclusive pixel
/// bounds, any `i16` values (empty when inverted, cut to the frame).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// Leftmost column written.
    pub x0: i16,
    /// Top row written.
    pub y0: i16,
    /// Rightmost column written.
    pub x1: i16,
    /// Bottom row written.
    pub y1: i16,
}

impl Window {
    /// The default registers: the whole frame `w × h`.
    pub fn full(w: u16, h: u16) -> Self {
        Window {
            x0: 0,
            y0: 0,
            x1: (w as i32 - 1) as i16,
            y1: (h as i32 - 1) as i16,
        }
    }

    /// `true` when pixel `(i, j)` is inside the registers (the frame is
    /// checked separately).
    pub fn contains(&self, i: i32, j: i32) -> bool {
        (self.x0 as i32) <= i && i <= self.x1 as i32 && (self.y0 as i32) <= j && j <= self.y1 as i32
    }

    /// The same window as the library's register type.
    pub fn to_clip_window(self) -> scanvert::raster::clip::ClipWindow {
        scanvert::raster::clip::ClipWindow {
            x0: self.x0,
            y0: self.y0,
            x1: self.x1,
            y1: self.y1,
        }
    }
}

/// Which pixels of a `width × height` frame are set.
#[derive(Clone, PartialEq, Eq)]
pub struct Coverage {
    width: u32,
    height: u32,
    bits: Vec<bool>,
}

impl Coverage {
    /// An empty bitmap.
    pub fn new(width: u32, height: u32) -> Self {
        Coverage {
            width,
            height,
            bits: vec![false; width as usize * height as usize],
        }
    }

    /// A bitmap from a per-pixel predicate.
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> bool) -> Self {
        let mut c = Coverage::new(width, height);
        for j in 0..height {
            for i in 0..width {
                c.set(i, j, f(i, j));
            }
        }
        c
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Pixel `(i, j)`; `false` outside.
    pub fn get(&self, i: u32, j: u32) -> bool {
        i < self.width && j < self.height && self.bits[(j * self.width + i) as usize]
    }

    /// Sets pixel `(i, j)`, which must be inside.
    pub fn set(&mut self, i: u32, j: u32, on: bool) {
        assert!(i < self.width && j < self.height, "({i}, {j}) outside");
        self.bits[(j * self.width + i) as usize] = on;
    }

    /// Number of set pixels.
    pub fn count(&self) -> usize {
        self.bits.iter().filter(|&&b| b).count()
    }

    /// Pixels set in one bitmap and not in the other, as `(i, j, self's
    /// value)`. The bitmaps must be of the same size.
    pub fn diff(&self, other: &Coverage) -> Vec<(u32, u32, bool)> {
        assert_eq!(
            (self.width, self.height),
            (other.width, other.height),
            "bitmaps of different sizes"
        );
        let mut d = Vec::new();
        for j in 0..self.height {
            for i in 0..self.width {
                if self.get(i, j) != other.get(i, j) {
                    d.push((i, j, self.get(i, j)));
                }
            }
        }
        d
    }

    /// The bitmap as rows of `#` (set) and `.` (clear).
    pub fn rows(&self) -> Vec<String> {
        (0..self.height)
            .map(|j| {
                (0..self.width)
                    .map(|i| if self.get(i, j) { '#' } else { '.' })
                    .collect()
            })
            .collect()
    }
}

impl fmt::Debug for Coverage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Coverage {}x{}:", self.width, self.height)?;
        if self.width <= 128 && self.height <= 128 {
            for r in self.rows() {
                writeln!(f, "{r}")?;
            }
        } else {
            writeln!(f, "({} pixels set)", self.count())?;
        }
        Ok(())
    }
}

/// Panics, showing both pictures, unless `actual` is the picture drawn by
/// `pattern`: one string per row, `#` for a set pixel and ` ` or `.` for a
/// clear one (as embedded-graphics' `MockDisplay::assert_pattern`). The
/// pattern gives the bitmap's full size.
#[track_caller]
pub fn assert_pattern(actual: &Coverage, pattern: &[&str]) {
    let h = pattern.len() as u32;
    let w = pattern.first().map_or(0, |r| r.chars().count()) as u32;
    for (j, r) in pattern.iter().enumerate() {
        assert_eq!(
            r.chars().count() as u32,
            w,
            "pattern row {j} has another width"
        );
        assert!(
            r.chars().all(|c| matches!(c, '#' | ' ' | '.')),
            "pattern row {j}: use '#', ' ' or '.'"
        );
    }
    let want = Coverage::from_fn(w, h, |i, j| {
        pattern[j as usize].chars().nth(i as usize) == Some('#')
    });
    assert_eq!(
        (actual.width, actual.height),
        (w, h),
        "size differs from the pattern's"
    );
    if *actual != want {
        panic!(
            "picture differs from the pattern\n  got:        want:\n{}",
            actual
                .rows()
                .iter()
                .zip(want.rows())
                .map(|(a, b)| format!("  {a}   {b}\n"))
                .collect::<String>()
        );
    }
}

/// `true` when pixel `(i, j)` is covered by the closed polygon through
/// `poly` (units of 1/16 px), by the pixel rule. The clip is not applied.
pub fn covers(poly: &[(i32, i32)], i: i32, j: i32) -> bool {
    let xc = 16 * i as i128 + 8;
    let yc = 16 * j as i128 + 8;
    let mut crossings_at_or_left = 0u32;
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        let ((x0, y0), (x1, y1)) = if a.1 <= b.1 { (a, b) } else { (b, a) };
        let (x0, y0, x1, y1) = (x0 as i128, y0 as i128, x1 as i128, y1 as i128);
        // Horizontal edges fail `y0 <= yc < y1` by themselves.
        if !(y0 <= yc && yc < y1) {
            continue;
        }
        let dy = y1 - y0;
        if x0 * dy + (yc - y0) * (x1 - x0) <= xc * dy {
            crossings_at_or_left += 1;
        }
    }
    crossings_at_or_left % 2 == 1
}

/// The first pixel whose centre is at or right of the crossing of the
/// edge `a`–`b` (units of 1/16 px, either order) with the centre line of
/// row `j`, `⌈x − ½⌉`, or `None` when the edge does not cross it (by the
/// half-open rule of [`covers`]). The crossing is the rational
/// `x = x0 + (yc − y0)·(x1 − x0)/(y1 − y0)`; the answer is the least `i`
/// with `x ≤ 16·i + 8`, found in `i128` from the floor of a quotient.
pub fn crossing(a: (i32, i32), b: (i32, i32), j: i32) -> Option<i32> {
    let ((x0, y0), (x1, y1)) = if a.1 <= b.1 { (a, b) } else { (b, a) };
    let (x0, y0, x1, y1) = (x0 as i128, y0 as i128, x1 as i128, y1 as i128);
    let yc = 16 * j as i128 + 8;
    if !(y0 <= yc && yc < y1) {
        return None;
    }
    let dy = y1 - y0;
    // x·dy = n; want the least i with n ≤ (16·i + 8)·dy, that is
    // i ≥ (n − 8·dy)/(16·dy): minus the floor of minus that.
    let n = x0 * dy + (yc - y0) * (x1 - x0);
    let i = -((8 * dy - n).div_euclid(16 * dy));
    Some(i as i32)
}

/// Pixels that may be covered (by the rule, or by a contender that is
/// off by up to `margin` pixels): the polygon's box in whole pixels,
/// widened by `margin` and cut to the `w × h` frame, as `(x0, y0, x1, y1)`
/// with exclusive ends. Every pixel the rule covers is inside it for any
/// `margin ≥ 0`.
pub fn pixel_box(poly: &[(i32, i32)], margin: i32, w: u16, h: u16) -> (i32, i32, i32, i32) {
    let xs = poly.iter().map(|p| p.0);
    let ys = poly.iter().map(|p| p.1);
    let (lx, hx) = (xs.clone().min().unwrap_or(0), xs.max().unwrap_or(0));
    let (ly, hy) = (ys.clone().min().unwrap_or(0), ys.max().unwrap_or(0));
    (
        ((lx >> 4) - margin).clamp(0, w as i32),
        ((ly >> 4) - margin).clamp(0, h as i32),
        ((hx >> 4) + 1 + margin).clamp(0, w as i32),
        ((hy >> 4) + 1 + margin).clamp(0, h as i32),
    )
}

/// The pixels of a `width × height` frame that the polygon `poly` (units
/// of 1/16 px) covers by the pixel rule, inside the clip registers
/// `window` (cut to the frame).
pub fn rasterize(poly: &[(i32, i32)], window: Window, width: u32, height: u32) -> Coverage {
    let mut c = Coverage::new(width, height);
    if poly.is_empty() {
        return c;
    }
    // Rows outside the polygon's y range have no crossing at all; skipping
    // them only saves time.
    let ymin = poly.iter().map(|p| p.1 as i64).min().unwrap_or(0);
    let ymax = poly.iter().map(|p| p.1 as i64).max().unwrap_or(0);
    for j in 0..height {
        let yc = 16 * j as i64 + 8;
        if yc < ymin || yc >= ymax {
            continue;
        }
        for i in 0..width {
            if window.contains(i as i32, j as i32) && covers(poly, i as i32, j as i32) {
                c.set(i, j, true);
            }
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    const PX: i32 = 16;

    #[test]
    fn square_on_pixel_edges_covers_its_pixels() {
        let sq = [(PX, PX), (3 * PX, PX), (3 * PX, 3 * PX), (PX, 3 * PX)];
        let c = rasterize(&sq, Window::full(4, 4), 4, 4);
        assert_pattern(&c, &["....", ".##.", ".##.", "...."]);
    }

    #[test]
    fn centre_on_left_edge_is_in_and_on_right_edge_is_out() {
        // x from 0.5 to 2.5: centres 0.5 and 1.5 in, 2.5 out.
        let r = [(8, 0), (40, 0), (40, 16), (8, 16)];
        assert_pattern(&rasterize(&r, Window::full(4, 1), 4, 1), &["##.."]);
        // y from 0.5 to 1.5: row 0 (centre 0.5) in, row 1 (centre 1.5) out.
        let r = [(0, 8), (16, 8), (16, 24), (0, 24)];
        assert_pattern(&rasterize(&r, Window::full(1, 2), 1, 2), &["#", "."]);
    }

    #[test]
    fn self_intersecting_bow_tie_is_even_odd() {
        // Two overlapping squares as one polygon: the overlap is even.
        let p = [
            (0, 0),
            (4 * PX, 0),
            (4 * PX, 4 * PX),
            (2 * PX, 4 * PX),
            (2 * PX, 2 * PX),
            (6 * PX, 2 * PX),
            (6 * PX, 6 * PX),
            (0, 6 * PX),
        ];
        let c = rasterize(&p, Window::full(6, 6), 6, 6);
        assert_pattern(
            &c,
            &["####..", "####..", "##..##", "##..##", "######", "######"],
        );
    }

    #[test]
    fn window_is_inclusive_and_cut_to_the_frame() {
        let big = [
            (-100 * PX, -100 * PX),
            (100 * PX, -100 * PX),
            (100 * PX, 100 * PX),
            (-100 * PX, 100 * PX),
        ];
        let w = Window {
            x0: 1,
            y0: -7,
            x1: 2,
            y1: 0,
        };
        assert_pattern(&rasterize(&big, w, 4, 2), &[".##.", "...."]);
        let inverted = Window {
            x0: 3,
            y0: 0,
            x1: 2,
            y1: 1,
        };
        assert_eq!(rasterize(&big, inverted, 4, 2).count(), 0);
    }

    #[test]
    fn pixel_box_holds_every_covered_pixel() {
        let tri = [(-37, 5), (300, 90), (41, 250)];
        let (x0, y0, x1, y1) = pixel_box(&tri, 0, 32, 32);
        for j in -2..34 {
            for i in -2..34 {
                if covers(&tri, i, j) && (0..32).contains(&i) && (0..32).contains(&j) {
                    assert!(x0 <= i && i < x1 && y0 <= j && j < y1, "({i}, {j})");
                }
            }
        }
        let v = |x: i16, y: i16| Vertex::from_bits(x, y);
        assert_eq!(units(&[v(-3, 7), v(16, 0)]), vec![(-3, 7), (16, 0)]);
    }
}
