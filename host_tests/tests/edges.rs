//! The exact edge stepper (`raster::edge::Edge`, a 64-bit DDA) against two
//! references on every row: the error-counter stepper it replaced (kept
//! here, in `i64`), and the rational crossing of `testkit`. Random edges
//! over the whole coordinate range under random row windows, the range's
//! corners, and `advance` against steps.

use proptest::prelude::*;
use scanvert::fixed::Vertex;
use scanvert::raster::edge::Edge;
use testkit::reference::crossing;

/// The error-counter stepper: `X = ⌈x − ½⌉` in units with `e ∈ [0, dy)`
/// and the exact position `X − e/dy`; a row `X += q; e −= r; if e < 0
/// { X += 1; e += dy }` where `16·dx = q·dy + r`; the pixel `⌈X/16⌉`.
struct Counter {
    x: i64,
    e: i64,
    q: i64,
    r: i64,
    dy: i64,
}

impl Counter {
    fn new(a: (i32, i32), b: (i32, i32), top: i32) -> Counter {
        let ((x0, y0), (x1, y1)) = if a.1 <= b.1 { (a, b) } else { (b, a) };
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (dx, dy) = (x1 as i64 - x0, y1 as i64 - y0);
        let num = (x0 - 8) * dy + (top as i64 * 16 + 8 - y0) * dx;
        let x = -(-num).div_euclid(dy);
        Counter {
            x,
            e: x * dy - num,
            q: (16 * dx).div_euclid(dy),
            r: (16 * dx).rem_euclid(dy),
            dy,
        }
    }
    fn pixel(&self) -> i32 {
        -(-self.x).div_euclid(16) as i32
    }
    fn step(&mut self) {
        self.x += self.q;
        self.e -= self.r;
        if self.e < 0 {
            self.x += 1;
            self.e += self.dy;
        }
    }
}

/// Every row of the edge `a`–`b` inside `rows`: the stepper exists
/// exactly when the edge crosses a row there, and each row's pixel is the
/// counter's and the rational crossing's, its units the counter's.
fn check(a: (i32, i32), b: (i32, i32), rows: (i32, i32)) {
    let v = |p: (i32, i32)| Vertex::from_bits(p.0 as i16, p.1 as i16);
    let Some(mut e) = Edge::new(v(a), v(b), rows) else {
        // Every row an `i16` edge can cross lies in −2048..2048.
        let (r0, r1) = (rows.0.max(-2049), rows.1.min(2049));
        let crossed = (r0..r1).filter(|&j| crossing(a, b, j).is_some());
        assert_eq!(crossed.count(), 0, "{a:?} {b:?} {rows:?}");
        return;
    };
    // The rows are those the edge crosses inside the window (they are
    // consecutive): none just above or below them.
    for j in [e.top() - 1, e.end()] {
        if rows.0 <= j && j < rows.1 {
            assert_eq!(crossing(a, b, j), None, "{a:?} {b:?} {rows:?} row {j}");
        }
    }
    let mut counter = Counter::new(a, b, e.top());
    for j in e.top()..e.end() {
        e.load_pixel();
        assert_eq!(Some(e.pixel()), crossing(a, b, j), "{a:?} {b:?} row {j}");
        assert_eq!(e.pixel(), counter.pixel(), "{a:?} {b:?} row {j}");
        assert_eq!(e.units() as i64, counter.x, "{a:?} {b:?} row {j}");
        if j + 1 < e.end() {
            e.step();
            counter.step();
        }
    }
}

fn point() -> impl Strategy<Value = (i32, i32)> {
    (any::<i16>(), any::<i16>()).prop_map(|(x, y)| (x as i32, y as i32))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(600))]

    /// Any edge of the coordinate range, on every row it crosses.
    #[test]
    fn any_edge_is_exact_on_every_row(a in point(), b in point()) {
        check(a, b, (i32::MIN, i32::MAX));
    }

    /// Any edge under a window of rows: the first row is set up directly.
    #[test]
    fn any_edge_under_a_row_window(a in point(), b in point(), r0 in -2100..2100i32, h in 0..600i32) {
        check(a, b, (r0, r0 + h));
    }

    /// Short edges, where each remainder and rounding is likelier.
    #[test]
    fn short_edges(x in -300..300i32, y in -300..300i32, dx in -200..200i32, dy in -200..200i32) {
        check((x, y), (x + dx, y + dy), (i32::MIN, i32::MAX));
    }

    /// `advance(n)` is `n` steps, for every `n` inside the edge.
    #[test]
    fn advance_is_steps(a in point(), b in point(), from in 0..4096u32) {
        let v = |p: (i32, i32)| Vertex::from_bits(p.0 as i16, p.1 as i16);
        if let Some(e) = Edge::new(v(a), v(b), (i32::MIN, i32::MAX)) {
            let h = (e.end() - e.top()) as u32;
            let from = from % h;
            let mut stepped = e;
            for _ in 0..from {
                stepped.step();
            }
            let mut jumped = e;
            jumped.advance(from);
            prop_assert_eq!(jumped, stepped);
        }
    }
}

/// Every pair of the range's corners and points next to them (the
/// tallest edges, 65,535 units and 4,096 rows; the steepest and flattest
/// slopes of both signs; vertical edges at the extreme columns), on every
/// row, and under windows at the top, the middle and the bottom rows.
#[test]
fn range_corners_are_exact_on_every_row() {
    let m = [
        i16::MIN as i32,
        i16::MIN as i32 + 1,
        i16::MIN as i32 + 8,
        -9,
        -1,
        0,
        7,
        8,
        i16::MAX as i32 - 8,
        i16::MAX as i32 - 1,
        i16::MAX as i32,
    ];
    for &ax in &m {
        for &ay in &m {
            for &bx in &m {
                for &by in &m {
                    let (a, b) = ((ax, ay), (bx, by));
                    check(a, b, (i32::MIN, i32::MAX));
                    for rows in [(-2048, -2040), (-3, 5), (2040, 2048)] {
                        check(a, b, rows);
                    }
                }
            }
        }
    }
}

/// [`check`] for an edge given as two `Vertex`es, on every row it crosses:
/// under a window of the rows its height spans and one more each side
/// (every row it can cross), so that an edge between two row centres is
/// checked on those rows, not on all 4,098.
fn vcheck(a: Vertex, b: Vertex) {
    let (y0, y1) = (a.y.units().min(b.y.units()), a.y.units().max(b.y.units()));
    vcheck_rows(a, b, (y0.div_euclid(16) - 1, y1.div_euclid(16) + 2));
}

/// [`check`] for an edge given as two `Vertex`es, under `rows`.
fn vcheck_rows(a: Vertex, b: Vertex, rows: (i32, i32)) {
    let p = |v: Vertex| (v.x.units(), v.y.units());
    check(p(a), p(b), rows);
}

/// Every edge between two points of a small grid of units (both
/// slopes, vertical, horizontal, every remainder of small heights),
/// on all its rows.
#[test]
fn every_small_edge_matches_the_counter() {
    for ax in -24..24i16 {
        for ay in -20..20i16 {
            for bx in -24..24i16 {
                for by in ay + 1..ay + 41 {
                    vcheck(Vertex::from_bits(ax, ay), Vertex::from_bits(bx, by));
                }
            }
        }
    }
}

/// Heights on both sides of 1,016 units, where the set-up changes
/// from one digit to two: every subpixel start, slopes of both signs
/// with many remainders, on every row and under a window that starts
/// at the edge's last rows.
#[test]
fn heights_around_the_one_digit_bound_are_exact() {
    for dy in 1000..=1032i16 {
        for y0 in -16..16i16 {
            for dx in (-2100..2100i16).step_by(37) {
                let (a, b) = (Vertex::from_bits(5, y0), Vertex::from_bits(5 + dx, y0 + dy));
                vcheck(a, b);
                vcheck_rows(a, b, (60, 70));
            }
        }
    }
}

/// The bound of the proof at its limit: the tallest edges (`dy` =
/// 65,535 units, 4,096 rows), at the steepest and the flattest
/// slopes, both signs, vertical at the extreme columns, and the
/// heights just around 65,528 where `dy·(dy + 15)` crosses 2³²; on
/// every row, and clipped to rows near the bottom (the largest `k`
/// from the first row is then small, so the top rows are covered too).
#[test]
fn tallest_edges_are_exact_on_every_row() {
    let (lo, hi) = (i16::MIN, i16::MAX);
    let xs = [lo, lo + 1, lo + 7, -9, -1, 0, 1, 8, 9, hi - 7, hi - 1, hi];
    for &ax in &xs {
        for &bx in &xs {
            let (a, b) = (Vertex::from_bits(ax, lo), Vertex::from_bits(bx, hi));
            let e = Edge::new(a, b, (i32::MIN, i32::MAX)).unwrap();
            assert_eq!(e.end() - e.top(), 4096);
            vcheck(a, b);
            vcheck(b, a);
            vcheck_rows(a, b, (2000, 2048));
            for dy in [65_520, 65_527, 65_528, 65_529, 65_534] {
                let b = Vertex::from_bits(bx, (lo as i32 + dy) as i16);
                vcheck(a, b);
                let a = Vertex::from_bits(ax, (hi as i32 - dy) as i16);
                vcheck(a, Vertex::from_bits(bx, hi));
            }
        }
    }
    // Slopes whose remainder is the largest (16·dx ≡ −1 mod dy) and
    // the smallest non-zero (≡ 1), where the step's rounding is the
    // most and the least.
    for (ax, bx) in [(lo, 28671), (hi, -28672), (0, 4095), (0, -4095)] {
        vcheck(Vertex::from_bits(ax, lo), Vertex::from_bits(bx, hi));
    }
}
