//! 2D lines one pixel wide, by the line rule, as a per-row span generator.
//!
//! # The rule
//!
//! The major axis is x when `|x₁ − x₀| ≥ |y₁ − y₀|`, else y. For an x-major
//! line, every pixel column `i` with `min(x₀, x₁) ≤ i + ½ < max(x₀, x₁)`
//! gets exactly one pixel, `(i, ⌊y⌋)`, where `y` is the line's exact y at
//! `x = i + ½` (a y on a pixel boundary belongs to the pixel below it, the
//! larger row). A y-major line is the same with x and y swapped. The lower
//! end on the major axis counts and the upper end does not, whichever way
//! the line is written, so lines joined end to end never hit a pixel
//! twice. A line of zero length draws nothing. Pixels outside the clip
//! window are never written.
//!
//! # In integers
//!
//! Coordinates are Q12.4 *units* (1/16 px). An x-major line is walked with
//! `x₀ < x₁`: column `i` is covered when `x₀ ≤ 16i + 8 < x₁`, i.e.
//! `⌈(x₀ − 8)/16⌉ ≤ i < ⌈(x₁ − 8)/16⌉`, and its row is
//!
//! ```text
//! r(i) = ⌊N(i) / D⌋,   N(i) = y₀·dx + dy·(16i + 8 − x₀),   D = 16·dx > 0
//! ```
//!
//! `r` is monotone in `i`, and changes by at most one from a column to the
//! next (`|dy| ≤ dx`), so a row holds one run of columns and every row
//! between the first and the last holds at least one. The columns are
//! walked in the direction in which the row grows (right when `dy ≥ 0`,
//! left otherwise), so that `N` grows by `S = 16·|dy|` a column, and rows
//! come out from top to bottom. With an error counter `e = N − r·D`, a row
//! entered with `e` holds `⌈(D − e)/S⌉` columns; after the first row
//! `e ∈ [0, S)`, and with `D = q·S + ρ` the next row holds `q + 1` columns
//! when `e < ρ` and `q` otherwise, `e` becoming `e + S − ρ` or `e − ρ`:
//! no division per row or pixel. A y-major line is walked down the rows
//! (`y₀ < y₁`), one pixel a row, its column `⌊M(j)/E⌋` kept the same way
//! (`E = 16·dy`, one add and a compare a row).
//!
//! The set-up divides (in `i64`) to find the first and last pixel inside
//! the clip window directly, so a line 4000 px long of which three pixels
//! are visible costs three rows. Intermediates: `N` and `M` need 37 bits
//! (`i64`, set-up only); `D`, `E`, `S`, `e`, `q`, `ρ` are below 2²¹ and
//! stepped in `i32`.
//!
//! # Per row
//!
//! [`Line::new`] gives the line clipped, or `None` when no pixel of it is
//! inside the window. Rows run from [`Line::top`] to [`Line::end`]; the
//! current row is [`Line::row`], its one span [`Line::span`], and
//! [`Line::step`] moves to the next row. A renderer working in bands steps
//! the same generator row by row; [`draw_line`] writes all of it into a
//! [`SpanTarget`]. `Line` is also an iterator over its spans.

use crate::fixed::{ceil_div_i64, Vertex, HALF, ONE};
use crate::port::Counts;
use crate::port::{Span, SpanTarget};
use crate::raster::clip::ClipRect;

/// `floor(n / d)` for `d > 0`.
#[inline]
const fn floor_div(n: i64, d: i64) -> i64 {
    n.div_euclid(d)
}

/// The first pixel index whose centre is at or after `units`:
/// `⌈(units − 8)/16⌉`.
#[inline]
const fn first_centre(units: i64) -> i64 {
    (units - HALF as i64 + ONE as i64 - 1).div_euclid(ONE as i64)
}

/// How a line steps from one row to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Walk {
    /// x-major: a run of columns a row.
    X {
        /// The next column to be drawn, in walking order.
        col: i32,
        /// +1 walking right, −1 walking left.
        dir: i32,
        /// Columns left to draw, the current row's included.
        left: i32,
        /// Columns of the current row (before `left` cuts it).
        run: i32,
        /// The error counter on entering the next row, in `[0, s)`.
        e: i32,
        /// `N`'s growth a column, `16·|dy|`; 0 for a horizontal line.
        s: i32,
        /// `D = q·s + rho`.
        q: i32,
        /// See `q`.
        rho: i32,
    },
    /// y-major: one pixel a row.
    Y {
        /// The current row's column.
        col: i32,
        /// The error counter, in `[0, e_mod)`.
        e: i32,
        /// `M`'s growth a row, `16·dx`, `|step| < e_mod`.
        step: i32,
        /// `E = 16·dy`.
        e_mod: i32,
    },
}

/// A line clipped to a window, stepped row by row: one span a row.
///
/// # Guarantees
/// `top() < end()` on construction; every span lies inside the clip
/// window it was made with, is non-empty, and rows are visited from top
/// to bottom, each once. Stepping past [`end`](Line::end) does nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Line {
    row: i32,
    top: i32,
    end: i32,
    walk: Walk,
}

impl Line {
    /// The line from `p0` to `p1` by the line rule, cut to `clip`, or
    /// `None` when it has no pixel inside `clip` (zero length, too short
    /// to reach a pixel centre, or wholly outside).
    pub fn new(p0: Vertex, p1: Vertex, clip: &ClipRect) -> Option<Line> {
        if clip.is_empty() {
            return None;
        }
        let (x0, y0) = (p0.x.units() as i64, p0.y.units() as i64);
        let (x1, y1) = (p1.x.units() as i64, p1.y.units() as i64);
        let (cx0, cx1) = (clip.x0() as i64, clip.x1() as i64);
        let (cy0, cy1) = (clip.y0() as i64, clip.y1() as i64);
        if (x1 - x0).abs() >= (y1 - y0).abs() {
            if x0 == x1 {
                return None;
            }
            Self::x_major((x0, y0), (x1, y1), (cx0, cx1), (cy0, cy1))
        } else {
            Self::y_major((x0, y0), (x1, y1), (cx0, cx1), (cy0, cy1))
        }
    }

    fn x_major(
        a: (i64, i64),
        b: (i64, i64),
        (cx0, cx1): (i64, i64),
        (cy0, cy1): (i64, i64),
    ) -> Option<Line> {
        let ((x0, y0), (x1, y1)) = if a.0 < b.0 { (a, b) } else { (b, a) };
        let (dx, dy) = (x1 - x0, y1 - y0);
        let (ia, ib) = (first_centre(x0), first_centre(x1));
        let d = ONE as i64 * dx;
        let s = ONE as i64 * dy.abs();
        let dir: i64 = if dy < 0 { -1 } else { 1 };
        let start = if dir > 0 { ia } else { ib - 1 };
        // N at the walk's first column; walk position k is column
        // start + dir·k, with N = n0 + s·k.
        let n0 = y0 * dx + dy * (ONE as i64 * start + HALF as i64 - x0);
        let (mut lo, mut hi) = (0, ib - ia);
        if dir > 0 {
            lo = lo.max(cx0 - start);
            hi = hi.min(cx1 - start);
        } else {
            lo = lo.max(start - cx1 + 1);
            hi = hi.min(start - cx0 + 1);
        }
        if s > 0 {
            lo = lo.max(ceil_div_i64(cy0 * d - n0, s));
            hi = hi.min(ceil_div_i64(cy1 * d - n0, s));
        } else if !(cy0..cy1).contains(&floor_div(n0, d)) {
            return None;
        }
        if lo >= hi {
            return None;
        }
        let n = n0 + s * lo;
        let row = floor_div(n, d);
        let e = n - row * d;
        let last = floor_div(n0 + s * (hi - 1), d);
        let left = hi - lo;
        let (run, e, q, rho) = if s > 0 {
            let run = ceil_div_i64(d - e, s);
            (run, e + run * s - d, d / s, d % s)
        } else {
            (left, 0, 0, 0)
        };
        Some(Line {
            row: row as i32,
            top: row as i32,
            end: last as i32 + 1,
            walk: Walk::X {
                col: (start + dir * lo) as i32,
                dir: dir as i32,
                left: left as i32,
                run: run.min(left) as i32,
                e: e as i32,
                s: s as i32,
                q: q as i32,
                rho: rho as i32,
            },
        })
    }

    fn y_major(
        a: (i64, i64),
        b: (i64, i64),
        (cx0, cx1): (i64, i64),
        (cy0, cy1): (i64, i64),
    ) -> Option<Line> {
        let ((x0, y0), (x1, y1)) = if a.1 < b.1 { (a, b) } else { (b, a) };
        let (dx, dy) = (x1 - x0, y1 - y0);
        let e_mod = ONE as i64 * dy;
        let step = ONE as i64 * dx;
        // M(j) = m0 + step·j; the column of row j is ⌊M(j)/E⌋.
        let m0 = x0 * dy + dx * (HALF as i64 - y0);
        let lo = first_centre(y0).max(cy0);
        let hi = first_centre(y1).min(cy1);
        let (lo, hi) = match step {
            0 if !(cx0..cx1).contains(&floor_div(m0, e_mod)) => return None,
            0 => (lo, hi),
            st if st > 0 => (
                lo.max(ceil_div_i64(cx0 * e_mod - m0, st)),
                hi.min(ceil_div_i64(cx1 * e_mod - m0, st)),
            ),
            st => (
                lo.max(floor_div(m0 - cx1 * e_mod, -st) + 1),
                hi.min(floor_div(m0 - cx0 * e_mod, -st) + 1),
            ),
        };
        if lo >= hi {
            return None;
        }
        let m = m0 + step * lo;
        let col = floor_div(m, e_mod);
        Some(Line {
            row: lo as i32,
            top: lo as i32,
            end: hi as i32,
            walk: Walk::Y {
                col: col as i32,
                e: (m - col * e_mod) as i32,
                step: step as i32,
                e_mod: e_mod as i32,
            },
        })
    }

    /// The first row.
    pub fn top(&self) -> i32 {
        self.top
    }

    /// One past the last row.
    pub fn end(&self) -> i32 {
        self.end
    }

    /// The current row (`end()` once every row is done).
    pub fn row(&self) -> i32 {
        self.row
    }

    /// The current row's pixels, `x0..x1` (non-empty), or `None` once
    /// every row is done.
    pub fn span(&self) -> Option<(i32, i32)> {
        if self.row >= self.end {
            return None;
        }
        match self.walk {
            Walk::X { col, dir, run, .. } if run > 0 => Some(if dir > 0 {
                (col, col + run)
            } else {
                (col - run + 1, col + 1)
            }),
            Walk::X { .. } => None,
            Walk::Y { col, .. } => Some((col, col + 1)),
        }
    }

    /// Moves to the next row: no division, a few `i32` additions.
    pub fn step(&mut self) {
        if self.row >= self.end {
            return;
        }
        self.row += 1;
        match &mut self.walk {
            Walk::X {
                col,
                dir,
                left,
                run,
                e,
                s,
                q,
                rho,
            } => {
                *col += *dir * *run;
                *left -= *run;
                let next = if *e < *rho {
                    *e += *s - *rho;
                    *q + 1
                } else {
                    *e -= *rho;
                    *q
                };
                *run = next.min(*left);
            }
            Walk::Y {
                col,
                e,
                step,
                e_mod,
            } => {
                *e += *step;
                if *e >= *e_mod {
                    *e -= *e_mod;
                    *col += 1;
                } else if *e < 0 {
                    *e += *e_mod;
                    *col -= 1;
                }
            }
        }
    }
}

impl Iterator for Line {
    type Item = Span;

    /// The current row's span, then a step.
    fn next(&mut self) -> Option<Span> {
        let (x0, x1) = self.span()?;
        let span = Span {
            y: self.row as u16,
            x0: x0 as u16,
            x1: x1 as u16,
        };
        self.step();
        Some(span)
    }
}

/// Draws the line from `p0` to `p1` into `target` in `color`, cut to
/// `clip` (which the caller has cut to the target's frame), one span a
/// row.
pub fn draw_line<T>(
    p0: Vertex,
    p1: Vertex,
    clip: &ClipRect,
    color: T::Color,
    target: &mut T,
) -> Result<Counts, T::Error>
where
    T: SpanTarget + ?Sized,
{
    let mut counts = Counts::default();
    if let Some(line) = Line::new(p0, p1, clip) {
        for span in line {
            target.fill_span(span, color)?;
            counts.spans += 1;
            counts.pixels += span.len() as u32;
        }
    }
    Ok(counts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::Coord;

    fn v(x: i16, y: i16) -> Vertex {
        Vertex {
            x: Coord::from_bits(x),
            y: Coord::from_bits(y),
        }
    }

    fn px(x: i16, y: i16) -> Vertex {
        v(x * 16, y * 16)
    }

    fn spans(a: Vertex, b: Vertex, clip: &ClipRect) -> [(i32, i32, i32); 16] {
        let mut out = [(0, 0, 0); 16];
        if let Some(l) = Line::new(a, b, clip) {
            let mut l = l;
            let mut k = 0;
            while let Some((x0, x1)) = l.span() {
                out[k] = (l.row(), x0, x1);
                k += 1;
                l.step();
            }
        }
        out
    }

    #[test]
    fn horizontal_from_centre_to_centre() {
        let clip = ClipRect::full(16, 16);
        // From the centre of pixel 1 to the centre of pixel 5, on row 2:
        // columns 1..5 (the far end does not count).
        let s = spans(v(24, 40), v(88, 40), &clip);
        assert_eq!(s[0], (2, 1, 5));
        assert_eq!(s[1], (0, 0, 0));
        // The same written backwards.
        assert_eq!(spans(v(88, 40), v(24, 40), &clip), s);
    }

    #[test]
    fn zero_and_tiny_lines_draw_nothing() {
        let clip = ClipRect::full(16, 16);
        assert!(Line::new(px(3, 3), px(3, 3), &clip).is_none());
        // 1/16 px long, not reaching a centre.
        assert!(Line::new(v(41, 40), v(42, 40), &clip).is_none());
        // 1/16 px long, ending on a centre: the upper end does not count.
        assert!(Line::new(v(39, 40), v(40, 40), &clip).is_none());
        // 1/16 px long, starting on a centre: one pixel.
        let l = Line::new(v(24, 24), v(25, 24), &clip).map(|l| l.collect::<heapless::Vec<_, 4>>());
        assert_eq!(l.as_deref(), Some(&[Span { y: 1, x0: 1, x1: 2 }][..]));
    }

    #[test]
    fn diagonal_45_degrees() {
        let clip = ClipRect::full(16, 16);
        // From (0, 0) to (4, 4): at x = i + ½, y = i + ½, row i.
        let s = spans(px(0, 0), px(4, 4), &clip);
        for i in 0..4 {
            assert_eq!(s[i as usize], (i, i, i + 1));
        }
        // Up and to the right: y = 4 − (i + ½) = 3.5 − i, row 3 − i.
        let s = spans(px(0, 4), px(4, 0), &clip);
        for k in 0..4 {
            assert_eq!(s[k as usize], (k, 3 - k, 4 - k));
        }
    }

    #[test]
    fn vertical_on_a_boundary_goes_right() {
        let clip = ClipRect::full(16, 16);
        // x = 2 exactly: on the boundary between columns 1 and 2.
        let s = spans(px(2, 1), px(2, 4), &clip);
        assert_eq!(&s[..4], &[(1, 2, 3), (2, 2, 3), (3, 2, 3), (0, 0, 0)]);
    }

    #[test]
    fn clipped_to_the_window() {
        let clip = ClipRect::from_window(
            crate::raster::clip::ClipWindow {
                x0: 2,
                y0: 0,
                x1: 5,
                y1: 1,
            },
            16,
            16,
        );
        // Row 0 from x 0 to 8, then down: only columns 2..=5 of row 0.
        let s = spans(px(0, 0), px(8, 1), &clip);
        assert_eq!(s[0], (0, 2, 6));
        assert_eq!(s[1], (0, 0, 0));
    }
}
