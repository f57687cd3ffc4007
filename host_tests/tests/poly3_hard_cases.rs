//! Hard cases of `poly3` against the exact reference, in both ways of
//! resolving intersecting spans: a closed cube (shared edges), depths at
//! the ends of Q12.4, trapezoids one pixel tall, edge-on and nearly
//! edge-on faces, concave and self-intersecting polygons, many faces
//! ending on one column (stacked, staggered).

use host_tests::harness3d::{compare, render3, render3_bands};
use proptest::prelude::*;
use scanvert::visible::sweep::Resolve;
use testkit::reference::{rasterize, Window};
use testkit::reference3d::{resolve, Poly3};

const MODES: [Resolve; 4] = [
    Resolve::Bisect,
    Resolve::Crossing,
    Resolve::Paint,
    Resolve::Auto,
];

/// Zero mismatches in every mode.
#[track_caller]
fn assert_exact(scene: &[Poly3], w: u16, h: u16) {
    for mode in MODES {
        let (m, first) = compare(scene, w, h, mode);
        assert_eq!(
            m.mismatched, 0,
            "{mode:?}: {m:?}, first differences {first:?} in {scene:?}"
        );
    }
}

fn poly(v: &[(i32, i32, i32)]) -> Poly3 {
    Poly3 {
        poly: v.to_vec(),
        clip: None,
    }
}

type V3 = (i32, i32, i32);

fn add(a: V3, b: V3) -> V3 {
    (a.0 + b.0, a.1 + b.1, a.2 + b.2)
}

/// The six faces of the parallelepiped at `o` with edges `u, v, w`, each
/// wound so that its normal points outward (the culling rule then keeps
/// the faces turned towards the viewer, smaller z).
fn cube(o: V3, u: V3, v: V3, w: V3) -> Vec<Poly3> {
    let det = |u: V3, v: V3, w: V3| {
        let (u, v, w) = (
            (u.0 as i64, u.1 as i64, u.2 as i64),
            (v.0 as i64, v.1 as i64, v.2 as i64),
            (w.0 as i64, w.1 as i64, w.2 as i64),
        );
        u.0 * (v.1 * w.2 - v.2 * w.1) - u.1 * (v.0 * w.2 - v.2 * w.0)
            + u.2 * (v.0 * w.1 - v.1 * w.0)
    };
    let (u, v) = if det(u, v, w) < 0 { (v, u) } else { (u, v) };
    // The face at corner `c` spanned by `e1`, `e2`: normal e1 × e2.
    let face = |c: V3, e1: V3, e2: V3| poly(&[c, add(c, e1), add(add(c, e1), e2), add(c, e2)]);
    vec![
        face(o, v, u),
        face(add(o, w), u, v),
        face(o, w, v),
        face(add(o, u), v, w),
        face(o, u, w),
        face(add(o, v), w, u),
    ]
}

/// The convex hull of points (monotone chain), for the silhouette.
fn hull(mut pts: Vec<(i32, i32)>) -> Vec<(i32, i32)> {
    pts.sort_unstable();
    pts.dedup();
    let cross = |o: (i32, i32), a: (i32, i32), b: (i32, i32)| {
        (a.0 as i64 - o.0 as i64) * (b.1 as i64 - o.1 as i64)
            - (a.1 as i64 - o.1 as i64) * (b.0 as i64 - o.0 as i64)
    };
    let mut h: Vec<(i32, i32)> = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let it: Vec<(i32, i32)> = if pass == 0 {
            pts.clone()
        } else {
            pts.iter().rev().copied().collect()
        };
        for p in it {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

fn vec3(r: i32, rz: i32) -> impl Strategy<Value = V3> {
    (-r..=r, -r..=r, -rz..=rz)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 150, failure_persistence: None, ..ProptestConfig::default() })]

    /// A closed cube: the front faces share edges, so together they cover
    /// the silhouette's pixels (the pixel rule of its outline) with no gap,
    /// each once, and every pixel is the reference's.
    #[test]
    fn closed_cube_has_no_gap_and_no_double_hit(
        o in (200..800i32, 200..600i32, -8000..8000i32),
        u in vec3(320, 8000),
        v in vec3(320, 8000),
        w in vec3(320, 8000),
    ) {
        let faces = cube(o, u, v, w);
        let (wd, ht) = (64u16, 48u16);
        assert_exact(&faces, wd, ht);
        let (got, stats) = render3(&faces, wd, ht, Resolve::Crossing);
        let corners: Vec<(i32, i32)> = faces.iter().flat_map(|f| f.poly.iter().map(|p| (p.0, p.1))).collect();
        let outline = hull(corners);
        if outline.len() >= 3 {
            let want = rasterize(&outline, Window::full(wd, ht), wd.into(), ht.into());
            for j in 0..ht as u32 {
                for i in 0..wd as u32 {
                    let n = (j * wd as u32 + i) as usize;
                    prop_assert_eq!(got[n].is_some(), want.get(i, j), "pixel ({}, {}) of {:?}", i, j, faces);
                }
            }
            // The 3D layer wrote each covered pixel once.
            prop_assert_eq!(stats.pixels as usize, want.count());
        }
        prop_assert!(stats.culled >= 3);
    }
}

#[test]
fn depths_at_the_ends_of_the_format() {
    let (lo, hi) = (i16::MIN as i32, i16::MAX as i32);
    let sq = |x0: i32, y0: i32, x1: i32, y1: i32, z: [i32; 3]| {
        // A planar quad: z at three corners, the fourth completes it.
        let (a, b, c) = (z[0], z[1], z[2]);
        poly(&[(x0, y0, a), (x0, y1, b), (x1, y1, b + c - a), (x1, y0, c)])
    };
    // Layers 1/16 apart at both ends of the range, in either list order.
    let far = sq(0, 0, 640, 480, [hi, hi, hi]);
    let far2 = sq(100, 50, 500, 400, [hi - 1, hi - 1, hi - 1]);
    let near = sq(50, 80, 600, 300, [lo + 1, lo + 1, lo + 1]);
    let nearest = sq(200, 0, 300, 480, [lo, lo, lo]);
    assert_exact(
        &[far.clone(), far2.clone(), near.clone(), nearest.clone()],
        40,
        30,
    );
    assert_exact(
        &[nearest.clone(), near.clone(), far2.clone(), far.clone()],
        40,
        30,
    );
    // Faces spanning the whole range across a few pixels (huge slopes),
    // crossing flat faces at both ends.
    let steep = sq(0, 0, 64, 480, [lo, lo, hi]);
    let steep_y = sq(0, 0, 640, 48, [lo, hi, lo]);
    assert_exact(&[steep, steep_y, far, near, far2, nearest], 40, 30);
    // Tiny slopes: a sixteenth over the whole frame, against a flat face
    // it crosses.
    let tilted = sq(0, 0, 640, 480, [0, 0, 1]);
    let flat = poly(&[(0, 0, 0), (0, 480, 0), (640, 480, 0)]);
    assert_exact(&[tilted.clone(), flat.clone()], 40, 30);
    assert_exact(&[flat, tilted], 40, 30);
}

#[test]
fn trapezoids_one_pixel_tall() {
    // Bands that each cross exactly one row centre, stacked and
    // interleaved in depth, and slivers whose top and bottom are on row
    // centres (a row centre on the top edge counts, on the bottom not).
    let mut scene = Vec::new();
    for j in 0..20 {
        let y0 = j * 16 + 3 + (j % 5);
        let y1 = y0 + 9;
        let z = if j % 2 == 0 { 100 } else { -100 };
        // Planar: z = zb + s·x, s in {−1, 0, 1}.
        let s = j % 3 - 1;
        let p = |x: i32, y: i32| (x, y, z + s * x);
        scene.push(poly(&[
            p(-16 + j, y0),
            p(j * 7, y1),
            p(600 - j * 9, y1),
            p(640, y0),
        ]));
        scene.push(poly(&[
            (300 + j * 3, j * 16 + 8, -z),
            (320, j * 16 + 24, 0),
            (340 - j, j * 16 + 8, z),
        ]));
    }
    assert_exact(&scene, 40, 24);
    let (_, stats) = render3(&scene, 40, 24, Resolve::Crossing);
    assert!(stats.trapezoids >= 20);
}

#[test]
fn edge_on_faces() {
    let front = poly(&[(0, 0, 500), (0, 480, 500), (640, 480, 500), (640, 0, 500)]);
    // Zero area in screen space, any depth: no pixel, no error.
    let line = poly(&[(16, 16, -3000), (300, 300, 9000), (600, 600, -32768)]);
    let spike = poly(&[(100, 100, 0), (400, 100, 0), (100, 100, 0), (400, 100, -9)]);
    // One sixteenth wide: nearly edge-on, slopes of thousands per pixel,
    // in front of and behind the flat face.
    let sliver = poly(&[
        (200, 0, -32768),
        (200, 480, -32768),
        (201, 480, 32767),
        (201, 0, 32767),
    ]);
    let sliver2 = poly(&[
        (0, 200, 32767),
        (0, 201, -32768),
        (640, 201, -32768),
        (640, 200, 32767),
    ]);
    let scene = [front, line, spike, sliver, sliver2];
    assert_exact(&scene, 40, 30);
    let mut flipped = scene.to_vec();
    for p in flipped.iter_mut() {
        p.poly.reverse();
    }
    assert_exact(&flipped, 40, 30);
}

#[test]
fn concave_and_self_intersecting_polygons() {
    // Planar: z = 2x − y + c in units.
    let z = |x: i32, y: i32, c: i32| (x, y, 2 * x - y + c);
    // A pentagram (self-intersecting, the centre left empty by even-odd),
    // wound so that its shoelace sum is negative.
    let star = [(256, 16), (115, 450), (484, 182), (28, 182), (397, 450)];
    let mut pentagram: Vec<V3> = star.iter().map(|&(x, y)| z(x, y, 0)).collect();
    if !testkit::reference3d::drawn(&pentagram) {
        pentagram.reverse();
    }
    // An L shape and a comb, in a plane crossing the pentagram's.
    let l_shape: Vec<V3> = [
        (16, 16),
        (16, 400),
        (480, 400),
        (480, 300),
        (120, 300),
        (120, 16),
    ]
    .iter()
    .map(|&(x, y)| (x, y, 200 - 2 * x + 3 * y))
    .collect();
    let mut comb: Vec<V3> = vec![(0, 460, 50)];
    for k in 0..8 {
        let x = 40 + k * 70;
        comb.extend([(x, 100, 60 + k), (x + 30, 460, 60 + k)]);
    }
    comb.push((640, 480, 50));
    // The comb is not planar as written; flatten it to z = 50.
    let comb: Vec<V3> = comb.iter().map(|p| (p.0, p.1, 50)).collect();
    let scenes = [
        vec![poly(&pentagram)],
        vec![poly(&l_shape)],
        vec![poly(&comb)],
        vec![poly(&pentagram), poly(&l_shape), poly(&comb)],
        vec![poly(&comb), poly(&l_shape), poly(&pentagram)],
    ];
    for s in scenes {
        let mut s = s;
        for p in s.iter_mut() {
            if !testkit::reference3d::drawn(&p.poly) {
                p.poly.reverse();
            }
        }
        assert_exact(&s, 40, 32);
    }
}

#[test]
fn clip_registers_apply_to_each_poly3() {
    let a = Poly3 {
        poly: vec![(0, 0, 100), (0, 480, 100), (640, 480, 100), (640, 0, 100)],
        clip: Some(Window {
            x0: 5,
            y0: 3,
            x1: 30,
            y1: 20,
        }),
    };
    let b = Poly3 {
        poly: vec![(0, 0, -100), (0, 480, 900), (640, 480, 900), (640, 0, -100)],
        clip: Some(Window {
            x0: 20,
            y0: -5,
            x1: 60,
            y1: 12,
        }),
    };
    let c = Poly3 {
        poly: vec![(100, 0, 0), (100, 480, 0), (300, 480, 0)],
        clip: Some(Window {
            x0: 10,
            y0: 10,
            x1: 5,
            y1: 20,
        }),
    };
    assert_exact(&[a.clone(), b.clone(), c.clone()], 40, 30);
    assert_exact(&[c, b, a], 40, 30);
}

/// Faces that end on one column on every row, many more than a short row
/// of the sweep holds (so through its long rows' cover array): quads of
/// one extent stacked at one depth (the earliest shows), each nearer and
/// each farther than the last, and full-height rectangles staggered ½ px,
/// each nearer or each farther, all ending on the last column; in every
/// mode, and in bands of 1, 7 and 16 rows.
#[test]
fn faces_sharing_their_right_end() {
    let rect = |(w, h): (i32, i32), x0: i32, z: i32| {
        poly(&[
            (x0, 0, z),
            (x0, 16 * h, z),
            (16 * w, 16 * h, z),
            (16 * w, 0, z),
        ])
    };
    let stacked = (40, 24);
    let staggered = (96, 20);
    let scenes: [(Vec<Poly3>, (i32, i32)); 6] = [
        ((0..200).map(|_| rect(stacked, 0, 500)).collect(), stacked),
        (
            (0..200).map(|k| rect(stacked, 0, 1000 - 4 * k)).collect(),
            stacked,
        ),
        (
            (0..200).map(|k| rect(stacked, 0, -1000 + 4 * k)).collect(),
            stacked,
        ),
        (
            (0..150)
                .map(|k| rect(staggered, 8 * k, 1000 - 8 * k))
                .collect(),
            staggered,
        ),
        (
            (0..150)
                .map(|k| rect(staggered, 8 * k, -1000 + 8 * k))
                .collect(),
            staggered,
        ),
        // Pairs at one place and depth, each pair nearer.
        (
            (0..150)
                .map(|k| rect(staggered, 8 * (k / 2), 1000 - 8 * (k / 2)))
                .collect(),
            staggered,
        ),
    ];
    for (scene, (w, h)) in &scenes {
        let (w, h) = (*w as u16, *h as u16);
        assert_exact(scene, w, h);
        let want = resolve(scene, w.into(), h.into());
        for mode in [Resolve::Crossing, Resolve::Paint] {
            for rows in [1, 7, 16] {
                let got = render3_bands(scene, w, h, mode, rows);
                assert!(got == want, "{mode:?} in bands of {rows}");
            }
        }
    }
}
