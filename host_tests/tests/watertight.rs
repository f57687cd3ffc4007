//! Shared edges: polygons that tile a region cover every pixel of it
//! exactly once, with no gap and no double hit (the top-left property of
//! the pixel rule).
//!
//! Every case renders the pieces as separate `poly` commands of one list
//! into a target that counts writes per pixel, and compares with the exact
//! reference rasteriser applied to the outline of the whole region: each
//! pixel the outline covers (inside the clip) is written once, every other
//! pixel never.

use host_tests::harness::{render_counting, Draw, DEFAULT_CAPACITY};
use proptest::prelude::*;
use testkit::reference::{rasterize, Window};

const W: u16 = 64;
const H: u16 = 48;

type Poly = Vec<(i32, i32)>;

fn cross(o: (i32, i32), a: (i32, i32), b: (i32, i32)) -> i64 {
    (a.0 as i64 - o.0 as i64) * (b.1 as i64 - o.1 as i64)
        - (a.1 as i64 - o.1 as i64) * (b.0 as i64 - o.0 as i64)
}

/// Renders `pieces` one command each under `win` and checks that every
/// pixel is written exactly as often as the outline covers it (0 or 1).
fn assert_tiles(pieces: &[Poly], outline: &[(i32, i32)], win: Window, w: u16, h: u16) {
    let draws: Vec<Draw> = pieces
        .iter()
        .enumerate()
        .map(|(k, p)| Draw {
            clip: (k == 0).then_some(win),
            poly: p.clone(),
        })
        .collect();
    let (target, result) = render_counting(&draws, w, h, DEFAULT_CAPACITY);
    result.expect("render");
    let want = rasterize(outline, win, w.into(), h.into());
    let mut gaps = Vec::new();
    let mut bad = Vec::new();
    for j in 0..h as u32 {
        for i in 0..w as u32 {
            let n = target.writes(i, j);
            match (want.get(i, j), n) {
                (true, 1) | (false, 0) => {}
                (true, 0) => gaps.push((i, j)),
                _ => bad.push((i, j, n)),
            }
        }
    }
    assert!(
        gaps.is_empty() && bad.is_empty(),
        "gaps (inside, never written): {gaps:?}\noverdraw or outside writes (i, j, times): {bad:?}\npieces: {pieces:?}\nclip: {win:?}"
    );
}

/// A jittered grid of `nx × ny` cells of `cell` units from `origin`: each
/// vertex moved by less than a quarter cell on each axis (so every cell
/// stays a strictly convex quadrilateral), each cell split along the
/// diagonal `diag[k]`, each triangle wound as `flip[k]` says. Returns the
/// triangles and the grid's outline.
fn grid(
    (nx, ny): (usize, usize),
    cell: i32,
    origin: (i32, i32),
    jitter: &[(i32, i32)],
    diag: &[bool],
    flip: &[bool],
) -> (Vec<Poly>, Poly) {
    let v = |i: usize, j: usize| {
        let (jx, jy) = jitter[j * (nx + 1) + i];
        (
            origin.0 + i as i32 * cell + jx,
            origin.1 + j as i32 * cell + jy,
        )
    };
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            let pair = if diag[k] {
                [vec![a, b, c], vec![a, c, d]]
            } else {
                [vec![a, b, d], vec![b, c, d]]
            };
            for (t, mut tri) in pair.into_iter().enumerate() {
                if flip[2 * k + t] {
                    tri.reverse();
                }
                tris.push(tri);
            }
        }
    }
    let mut outline = Vec::new();
    outline.extend((0..nx).map(|i| v(i, 0)));
    outline.extend((0..ny).map(|j| v(nx, j)));
    outline.extend((1..=nx).rev().map(|i| v(i, ny)));
    outline.extend((1..=ny).rev().map(|j| v(0, j)));
    (tris, outline)
}

/// Grid parameters: size, cell, origin, jitter, diagonals and windings.
type GridCase = (
    (usize, usize),
    i32,
    (i32, i32),
    Vec<(i32, i32)>,
    Vec<bool>,
    Vec<bool>,
);

fn grid_case(
    cells: std::ops::RangeInclusive<i32>,
    origin: BoxedStrategy<(i32, i32)>,
) -> impl Strategy<Value = GridCase> {
    ((1usize..=8, 1usize..=8), cells, origin).prop_flat_map(|((nx, ny), cell, origin)| {
        let j = cell / 4 - 1;
        (
            Just((nx, ny)),
            Just(cell),
            Just(origin),
            prop::collection::vec((-j..=j, -j..=j), (nx + 1) * (ny + 1)),
            prop::collection::vec(any::<bool>(), nx * ny),
            prop::collection::vec(any::<bool>(), 2 * nx * ny),
        )
    })
}

fn window() -> impl Strategy<Value = Window> {
    prop_oneof![
        Just(Window::full(W, H)),
        (0..W as i16, 0..H as i16, 0..W as i16, 0..H as i16).prop_map(|(a, b, c, d)| Window {
            x0: a.min(c),
            y0: b.min(d),
            x1: a.max(c),
            y1: b.max(d),
        }),
    ]
}

/// A ring of `n` points around `centre` at increasing angles (each within
/// a fifth of the even spacing of its slot) and radii in `radii`, keeping
/// every fan triangle strictly turning the same way after rounding.
fn fan(centre: (i32, i32), spokes: &[(f64, i32)]) -> Option<Poly> {
    let n = spokes.len();
    let ring: Poly = spokes
        .iter()
        .enumerate()
        .map(|(k, &(jit, r))| {
            let t = (k as f64 + 0.2 * jit) * std::f64::consts::TAU / n as f64;
            let x = (centre.0 as f64 + r as f64 * t.cos()).round() as i32;
            let y = (centre.1 as f64 + r as f64 * t.sin()).round() as i32;
            (x.clamp(-32768, 32767), y.clamp(-32768, 32767))
        })
        .collect();
    let turning = (0..n).all(|k| cross(centre, ring[k], ring[(k + 1) % n]) > 0);
    turning.then_some(ring)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    /// Jittered grids of up to 8 × 8 cells of 0.5 to 25 px, split into
    /// triangles along random diagonals with random windings, over and
    /// across a 64 × 48 frame.
    #[test]
    fn triangulated_grids_cover_every_pixel_once(
        (size, cell, origin, jitter, diag, flip) in grid_case(8..=400, (-20 * 16..60 * 16, -20 * 16..40 * 16).boxed()),
        win in window(),
    ) {
        let (tris, outline) = grid(size, cell, origin, &jitter, &diag, &flip);
        assert_tiles(&tris, &outline, win, W, H);
    }

    /// Grids with cells of 25 to 437 px anywhere in the coordinate range
    /// that still reach the frame: the frame sees a few long shared edges
    /// at arbitrary slopes, with vertices far outside it.
    #[test]
    fn large_triangulated_grids_cover_every_pixel_once(
        (size, cell, _, jitter, diag, flip) in grid_case(400..=7000, Just((0, 0)).boxed()),
        win in window(),
        place in (0.0f64..=1.0, 0.0f64..=1.0),
    ) {
        // The origin, between "the grid's far corner just reaches past the
        // frame" and "the grid starts at the frame's corner", kept so that
        // every vertex is inside Q12.4.
        let origin = |n: usize, side: u16, f: f64| {
            let span = n as i32 * cell + cell / 4;
            let lo = (-32768 + cell / 4).max(side as i32 * 16 - span);
            let hi = (32767 - span).min(0);
            lo + (f * (hi - lo) as f64) as i32
        };
        let o = (origin(size.0, W, place.0), origin(size.1, H, place.1));
        let (tris, outline) = grid(size, cell, o, &jitter, &diag, &flip);
        assert_tiles(&tris, &outline, win, W, H);
    }

    /// Fans of 4 to 16 triangles around a shared vertex, sometimes exactly
    /// on a pixel centre.
    #[test]
    fn fans_around_a_shared_vertex_cover_every_pixel_once(
        centre in prop_oneof![
            (0..W as i32 * 16, 0..H as i32 * 16),
            (0..W as i32, 0..H as i32).prop_map(|(i, j)| (16 * i + 8, 16 * j + 8)),
        ],
        spokes in prop::collection::vec((-1.0f64..1.0, 4 * 16..60 * 16), 4..=16),
        flip in prop::collection::vec(any::<bool>(), 16),
        win in window(),
    ) {
        let ring = fan(centre, &spokes);
        prop_assume!(ring.is_some());
        let ring = ring.unwrap();
        let n = ring.len();
        let tris: Vec<Poly> = (0..n)
            .map(|k| {
                let mut t = vec![centre, ring[k], ring[(k + 1) % n]];
                if flip[k] {
                    t.reverse();
                }
                t
            })
            .collect();
        assert_tiles(&tris, &ring, win, W, H);
    }

    /// A rectangle split in two along a y-monotone chain of up to 10
    /// segments: the two halves share every segment of the chain.
    #[test]
    fn a_polygon_split_along_a_shared_chain_covers_every_pixel_once(
        (l, t, r, b) in (-8 * 16..30 * 16, -8 * 16..20 * 16, 34 * 16..72 * 16, 28 * 16..56 * 16),
        chain in prop::collection::vec((0.0f64..1.0, 0.0f64..1.0), 0..10),
        ends in (0.0f64..1.0, 0.0f64..1.0),
        flip in (any::<bool>(), any::<bool>()),
        win in window(),
    ) {
        let x = |f: f64| l + 1 + (f * (r - l - 2) as f64) as i32;
        let mut ys: Vec<i32> = chain.iter().map(|c| t + 1 + (c.1 * (b - t - 2) as f64) as i32).collect();
        ys.sort_unstable();
        ys.dedup();
        let mut path = vec![(x(ends.0), t)];
        path.extend(ys.iter().zip(&chain).map(|(&y, c)| (x(c.0), y)));
        path.push((x(ends.1), b));
        let mut left = vec![(l, t)];
        left.extend(path.iter().copied());
        left.push((l, b));
        let mut right = vec![(r, t), (r, b)];
        right.extend(path.iter().rev().copied());
        if flip.0 { left.reverse(); }
        if flip.1 { right.reverse(); }
        let rect = vec![(l, t), (r, t), (r, b), (l, b)];
        assert_tiles(&[left, right], &rect, win, W, H);
    }

    /// A convex polygon cut in two along a diagonal between two of its
    /// vertices.
    #[test]
    fn a_convex_polygon_cut_along_a_diagonal_covers_every_pixel_once(
        pts in prop::collection::vec((-8 * 16..72 * 16, -8 * 16..56 * 16), 4..=12),
        cut in (any::<prop::sample::Index>(), any::<prop::sample::Index>()),
        flip in (any::<bool>(), any::<bool>()),
        win in window(),
    ) {
        let hull = convex_hull(pts);
        let n = hull.len();
        prop_assume!(n >= 4);
        let a = cut.0.index(n);
        let b = (a + 2 + cut.1.index(n - 3)) % n;
        let (a, b) = (a.min(b), a.max(b));
        let mut one: Poly = hull[a..=b].to_vec();
        let mut two: Poly = hull[b..].iter().chain(&hull[..=a]).copied().collect();
        if flip.0 { one.reverse(); }
        if flip.1 { two.reverse(); }
        assert_tiles(&[one, two], &hull, win, W, H);
    }
}

/// The strictly convex hull of `pts` (Andrew's monotone chain).
fn convex_hull(mut pts: Poly) -> Poly {
    pts.sort_unstable();
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut h: Poly = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let order: Vec<(i32, i32)> = if pass == 0 {
            pts.clone()
        } else {
            pts.iter().rev().copied().collect()
        };
        for p in order {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// A fixed case that shows the property in a picture: two triangles
/// sharing the diagonal of a 4 × 4 square, whose every pixel centre off the
/// diagonal is in exactly one of them, and on it in exactly one too.
#[test]
fn two_triangles_sharing_a_diagonal_through_pixel_centres() {
    let px = |x: i32, y: i32| (16 * x, 16 * y);
    let sq = [px(0, 0), px(4, 0), px(4, 4), px(0, 4)];
    // The diagonal from (0,0) to (4,4) passes through the centres (i+½, i+½).
    let upper = vec![sq[0], sq[1], sq[2]];
    let lower = vec![sq[0], sq[2], sq[3]];
    assert_tiles(&[upper, lower], &sq, Window::full(4, 4), 4, 4);
}
