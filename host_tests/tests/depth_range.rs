//! Depths stay inside the format: a face seen nearly edge-on across the
//! near plane (planar in model space, not quite planar once rounded), a
//! non-planar `poly3` whose plane leaves the format between its vertices,
//! and random non-planar polygons, on which both ways of resolving
//! intersecting spans must draw the same pixels. The tests run in the
//! test profile, with overflow checks on.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use host_tests::harness3d::{compare, render3, render3_bands};
use proptest::prelude::*;
use scanvert::fixed::Vertex3;
use scanvert::geometry::{Angle, Perspective, Pipeline, Point3, PolygonSink, View, Viewport, Q16};
use scanvert::raster::clip::ClipRect;
use scanvert::visible::sweep::Resolve;
use scanvert::visible::trapezoid::{EdgeSlot, Plane, Polygon};
use std::path::PathBuf;
use testkit::reference::covers;
use testkit::reference3d::Poly3;

const MODES: [Resolve; 4] = [
    Resolve::Bisect,
    Resolve::Crossing,
    Resolve::Paint,
    Resolve::Auto,
];

/// The Q12.4 depth range in units.
const Z_MIN: i128 = -32768;
const Z_MAX: i128 = 32767;

fn poly(v: &[(i32, i32, i32)]) -> Poly3 {
    Poly3 {
        poly: v.to_vec(),
        clip: None,
    }
}

/// A polygon the geometry stage delivered (not culled there) as a `poly3`
/// that is drawn: wound counter-clockwise as displayed. Rounding may have
/// left a sliver wound the other way; the plane is the same either way.
fn drawn(v: &[(i32, i32, i32)]) -> Poly3 {
    let mut v = v.to_vec();
    if !testkit::reference3d::drawn(&v) {
        v.reverse();
    }
    poly(&v)
}

/// `true` when the vertices lie on one plane exactly (or have none).
fn is_planar(v: &[Vertex3]) -> bool {
    Plane::of(v.iter().copied()).is_none_or(|p| v.iter().all(|&q| p.contains(q)))
}

fn units(v: &Vertex3) -> (i32, i32, i32) {
    (v.x.units(), v.y.units(), v.z.units())
}

/// The least and greatest exact depth (in units, rounded down) of the
/// plane of `v` over the pixels the pixel rule gives `v` on a `w × h`
/// frame.
fn depth_range(v: &[(i32, i32, i32)], w: u16, h: u16) -> Option<(i128, i128)> {
    let plane = Plane::of(v.iter().map(|&p| host_tests::harness3d::vertex3(p)))?;
    let xy: Vec<(i32, i32)> = v.iter().map(|p| (p.0, p.1)).collect();
    let mut r: Option<(i128, i128)> = None;
    for j in 0..h as i32 {
        for i in 0..w as i32 {
            if covers(&xy, i, j) {
                let (n, d) = plane.depth_at(i, j);
                let z = n.div_euclid(d as i128);
                r = Some(r.map_or((z, z), |(lo, hi)| (lo.min(z), hi.max(z))));
            }
        }
    }
    r
}

// ---------------------------------------------------------------------
// A floor seen nearly edge-on across the near plane, a wall behind it.

const W: u16 = 160;
const H: u16 = 120;

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

fn p(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(q(x), q(y), q(z))
}

#[derive(Default)]
struct Record(Vec<Vec<Vertex3>>);

impl PolygonSink for Record {
    type Error = core::convert::Infallible;
    fn polygon(&mut self, v: &[Vertex3], _: Rgb888, _: bool) -> Result<(), Self::Error> {
        self.0.push(v.to_vec());
        Ok(())
    }
}

/// The floor: 4 × 43 units, 0.0001 below the eye, from 3 units behind it
/// to 40 in front (across the near plane at 1), turned about the view
/// axis (8214/65536 of a turn) and tilted by 5/65536 of a turn, so that
/// it is a sliver across the window. The wall: 60 × 60 units, square to
/// the view, 9 units behind the floor's far end.
const FLOOR: [(f64, f64, f64); 4] = [
    (-2.0, -0.0001, 3.0),
    (2.0, -0.0001, 3.0),
    (2.0, -0.0001, -40.0),
    (-2.0, -0.0001, -40.0),
];
const WALL: [(f64, f64, f64); 4] = [
    (-30.0, -30.0, -49.0),
    (30.0, -30.0, -49.0),
    (30.0, 30.0, -49.0),
    (-30.0, 30.0, -49.0),
];
const TURN_Z: u16 = 8214;
const TILT_X: u16 = 5;

/// The polygons the geometry stage delivers for the floor and the wall,
/// in units.
/// Polygons in units.
type Polys = Vec<Vec<(i32, i32, i32)>>;

fn floor_and_wall() -> (Polys, Polys) {
    let persp = Perspective::from_fov(Angle::from_degrees(60), W, q(1.0), q(100.0)).unwrap();
    let mut pipe = Pipeline::<4, 16>::new(persp, Viewport::centred(W, H).unwrap());
    pipe.set_view(&View {
        eye: Point3::from_int(0, 0, 0),
        yaw: Angle::ZERO,
        pitch: Angle::ZERO,
    })
    .unwrap();
    let mut wall = Record::default();
    pipe.polygon(&WALL.map(|(x, y, z)| p(x, y, z)), Rgb888::BLUE, &mut wall)
        .unwrap();
    pipe.stack_mut().rotate_z(Angle::from_bits(TURN_Z)).unwrap();
    pipe.stack_mut().rotate_x(Angle::from_bits(TILT_X)).unwrap();
    let mut floor = Record::default();
    pipe.polygon(&FLOOR.map(|(x, y, z)| p(x, y, z)), Rgb888::RED, &mut floor)
        .unwrap();
    let u = |r: Record| -> Polys { r.0.iter().map(|v| v.iter().map(units).collect()).collect() };
    (u(floor), u(wall))
}

/// The depth range of the plane the trapezoid stage gives `v` (Newell's,
/// or fitted: see `visible::trapezoid`) over the pixels it covers.
fn stored_depth_range(v: &[(i32, i32, i32)], w: u16, h: u16) -> Option<(i128, i128)> {
    let mut slots = vec![EdgeSlot::EMPTY; v.len()];
    let poly = Polygon::load(
        &mut slots,
        v.iter().map(|&p| host_tests::harness3d::vertex3(p)),
        &ClipRect::full(w, h),
    )
    .unwrap();
    let plane = *poly.plane()?;
    let xy: Vec<(i32, i32)> = v.iter().map(|p| (p.0, p.1)).collect();
    let mut r: Option<(i128, i128)> = None;
    for j in 0..h as i32 {
        for i in 0..w as i32 {
            if covers(&xy, i, j) {
                let (n, d) = plane.depth_at(i, j);
                let z = n.div_euclid(d as i128);
                r = Some(r.map_or((z, z), |(lo, hi)| (lo.min(z), hi.max(z))));
            }
        }
    }
    r
}

#[test]
fn the_edge_on_floor_across_the_near_plane_stays_in_the_format() {
    let (floor, wall) = floor_and_wall();
    assert_eq!(wall.len(), 1);
    let zs = |v: &[(i32, i32, i32)]| {
        let z = v.iter().map(|p| p.2 as i128);
        (z.clone().min().unwrap(), z.max().unwrap())
    };
    assert_eq!(floor.len(), 1);
    let v = &floor[0];
    let exact: Vec<Vertex3> = v
        .iter()
        .map(|&p| host_tests::harness3d::vertex3(p))
        .collect();
    // Clipped and rounded, the floor is a sliver (that even crosses
    // itself), not planar, and Newell's plane through it is about
    // 900 000 px deep at a pixel it covers.
    assert!(!is_planar(&exact));
    let (lo, _) = depth_range(v, W, H).expect("covers pixels");
    assert!(lo < -16 * 100_000, "{lo}");
    // What the trapezoid stage keeps stays within its vertices' depths at
    // every pixel it covers.
    let (lo, hi) = zs(v);
    let (a, b) = stored_depth_range(v, W, H).expect("covers pixels");
    assert!(lo <= a && b <= hi, "{v:?}: {a}..{b} outside {lo}..{hi}");
}

#[test]
fn the_wall_behind_the_edge_on_floor_shows_only_where_it_is_nearer() {
    let (floor, wall) = floor_and_wall();
    // Every vertex of the floor is nearer than the wall.
    let wall_z = wall[0].iter().map(|p| p.2).min().unwrap();
    assert!(floor.iter().flatten().all(|p| p.2 < wall_z));
    let mut scene: Vec<Poly3> = wall.iter().map(|v| drawn(v)).collect();
    scene.extend(floor.iter().map(|v| drawn(v)));
    let wall_xy: Vec<(i32, i32)> = wall[0].iter().map(|p| (p.0, p.1)).collect();
    let (a, _) = render3(&scene, W, H, Resolve::Bisect);
    let (b, _) = render3(&scene, W, H, Resolve::Crossing);
    assert_eq!(a, b);
    assert_eq!(render3(&scene, W, H, Resolve::Paint).0, b);
    let mut floor_pixels = 0;
    for j in 0..H as i32 {
        for i in 0..W as i32 {
            let on_floor = floor.iter().any(|t| {
                let xy: Vec<(i32, i32)> = t.iter().map(|p| (p.0, p.1)).collect();
                covers(&xy, i, j)
            });
            let want = if on_floor {
                floor_pixels += 1;
                "floor"
            } else if covers(&wall_xy, i, j) {
                "wall"
            } else {
                "background"
            };
            let shown = match a[(j * W as i32 + i) as usize] {
                Some(0) => "wall",
                Some(_) => "floor",
                None => "background",
            };
            assert_eq!(shown, want, "pixel ({i}, {j})");
        }
    }
    assert!(floor_pixels >= 4, "{floor_pixels}");
}

/// The same scene in the text form, through `scanvert render`.
#[test]
fn the_edge_on_floor_through_the_command_line() {
    let deg = |bits: u16| bits as f64 * 360.0 / 65536.0;
    let face = |v: &[(f64, f64, f64)]| {
        let mut s = String::from("face");
        for (x, y, z) in v {
            s += &format!("  {x} {y} {z}");
        }
        s + "\n"
    };
    let text = format!(
        "frame {W} {H}\nclear #000000\nperspective 60 1 100\nview 0 0 0 0 0\n\
         color #0000ff\n{}push\nrotate z {}\nrotate x {}\ncolor #ff0000\n{}pop\n",
        face(&WALL),
        deg(TURN_Z),
        deg(TILT_X),
        face(&FLOOR),
    );
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("depth_range");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (scene, png) = (dir.join("floor.dl"), dir.join("floor.png"));
    std::fs::write(&scene, &text).expect("write scene");
    let args: Vec<String> = [
        "render",
        scene.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    scanvert_sim::cli::run(&args).expect("renders");
    let bytes = std::fs::read(&png).expect("png written");
    let (w, h, rgb) = scanvert_sim::image::decode_png(&bytes).expect("decode");
    assert_eq!((w, h), (W as u32, H as u32));
    let (floor, wall) = floor_and_wall();
    let wall_xy: Vec<(i32, i32)> = wall[0].iter().map(|p| (p.0, p.1)).collect();
    for j in 0..H as i32 {
        for i in 0..W as i32 {
            let on_floor = floor.iter().any(|t| {
                let xy: Vec<(i32, i32)> = t.iter().map(|p| (p.0, p.1)).collect();
                covers(&xy, i, j)
            });
            let k = 3 * (j as usize * W as usize + i as usize);
            let px = (rgb[k], rgb[k + 1], rgb[k + 2]);
            let want = if on_floor {
                (255, 0, 0)
            } else if covers(&wall_xy, i, j) {
                (0, 0, 255)
            } else {
                (0, 0, 0)
            };
            assert_eq!(px, want, "pixel ({i}, {j})");
        }
    }
}

// ---------------------------------------------------------------------
// A non-planar poly3 whose plane leaves the format between its vertices.

/// A bow tie at depths 100 and 300 px, its two halves almost the same
/// size: Newell's plane through its first vertex is 15 301 px deep at
/// pixel (2, 30), which it covers.
fn bow_tie() -> Vec<(i32, i32, i32)> {
    [
        (2.0, 2.0, 100),
        (2.0, 30.75, 300),
        (60.0, 2.0, 300),
        (60.0, 30.0, 100),
    ]
    .iter()
    .map(|&(x, y, z)| ((x * 16.0) as i32, (y * 16.0) as i32, z * 16))
    .collect()
}

#[test]
fn a_non_planar_poly3_15000_px_deep_stays_behind_a_face_at_depth_10() {
    let tie = bow_tie();
    assert!(testkit::reference3d::drawn(&tie));
    let v: Vec<Vertex3> = tie
        .iter()
        .map(|&p| host_tests::harness3d::vertex3(p))
        .collect();
    assert!(!is_planar(&v));
    // Newell's plane is that deep at a pixel the bow tie covers.
    let (_, hi) = depth_range(&tie, 64, 40).unwrap();
    assert!(hi > 16 * 15_000, "{hi}");

    let face = vec![(0, 0, 160), (0, 640, 160), (1024, 640, 160), (1024, 0, 160)];
    for scene in [vec![poly(&face), poly(&tie)], vec![poly(&tie), poly(&face)]] {
        let k = if scene[0].poly == face { 0 } else { 1 };
        for mode in MODES {
            let (got, _) = render3(&scene, 64, 40, mode);
            for (n, g) in got.iter().enumerate() {
                assert_eq!(*g, Some(k), "{mode:?}: pixel {n}");
            }
        }
        // Alone, the bow tie shows its own pixels, the same in both modes.
        let alone = [poly(&tie)];
        let (a, _) = render3(&alone, 64, 40, Resolve::Bisect);
        let (b, _) = render3(&alone, 64, 40, Resolve::Crossing);
        assert_eq!(a, b);
        assert_eq!(render3(&alone, 64, 40, Resolve::Paint).0, b);
        assert!(a.iter().filter(|p| p.is_some()).count() > 100);
    }
}

// ---------------------------------------------------------------------
// The corners of the format.

/// Faces at both ends of the depth range, planar and not, nearly edge-on
/// and not, through each other: both modes draw the same pixels, and the
/// planar ones alone match the exact reference.
#[test]
fn depths_at_the_corners_of_the_format() {
    let (lo, hi) = (Z_MIN as i32, Z_MAX as i32);
    let planar = vec![
        poly(&[(0, 0, lo), (0, 639, lo), (1023, 639, hi), (1023, 0, hi)]),
        poly(&[(0, 0, hi), (0, 639, hi), (1023, 639, lo), (1023, 0, lo)]),
        poly(&[(16, 8, lo), (24, 632, hi), (1016, 320, lo)]),
        // Nearly edge-on: one unit of area across the whole depth range.
        poly(&[(0, 300, lo), (1023, 301, hi), (1023, 302, hi)]),
    ];
    for mode in MODES {
        let (m, first) = compare(&planar, 64, 40, mode);
        assert_eq!(m.mismatched, 0, "{mode:?}: {m:?} {first:?}");
    }
    let mut all = planar.clone();
    all.push(poly(&[
        (0, 0, lo),
        (1023, 639, hi),
        (1023, 0, lo),
        (0, 650, hi),
    ]));
    all.push(poly(&[
        (8, 630, hi),
        (1016, 10, lo),
        (1016, 630, hi),
        (8, 12, lo),
    ]));
    all.push(poly(&[
        (0, 320, lo),
        (512, 0, hi),
        (1023, 321, lo),
        (512, 639, hi),
        (500, 330, lo),
    ]));
    for scene in [all.clone(), all.iter().rev().cloned().collect()] {
        let (a, _) = render3(&scene, 64, 40, Resolve::Bisect);
        let (b, _) = render3(&scene, 64, 40, Resolve::Crossing);
        assert_eq!(a, b);
        assert_eq!(render3(&scene, 64, 40, Resolve::Paint).0, b);
    }
}

// ---------------------------------------------------------------------
// Random input, non-planar too: both modes draw the same pixels.

fn vertex(w: i32, h: i32) -> impl Strategy<Value = (i32, i32, i32)> {
    (
        -64..16 * w + 64,
        -64..16 * h + 64,
        prop_oneof![-32768..=32767i32, -200..200i32],
    )
}

fn polygon(w: i32, h: i32) -> impl Strategy<Value = Vec<(i32, i32, i32)>> {
    prop_oneof![
        prop::collection::vec(vertex(w, h), 3..8),
        // Slivers: nearly edge-on, thin in y.
        (vertex(w, h), vertex(w, h), -24..24i32, -32768..=32767i32).prop_map(|(a, b, dy, z)| vec![
            a,
            b,
            (b.0 + dy, b.1 + dy.abs() % 5 + 1, z)
        ]),
        // Bow ties of almost no area, far from planar: Newell's plane
        // leaves the format between the vertices.
        (
            vertex(w, h),
            vertex(w, h),
            -12..12i32,
            prop::array::uniform4(-32768..=32767i32)
        )
            .prop_map(|(a, b, e, z)| vec![
                (a.0, a.1, z[0]),
                (b.0, b.1, z[1]),
                (b.0, a.1, z[2]),
                (a.0, b.1 + e, z[3]),
            ]),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn both_modes_draw_the_same_pixels(
        scene in prop::collection::vec(polygon(40, 30), 1..7),
    ) {
        let scene: Vec<Poly3> = scene.iter().map(|v| poly(v)).collect();
        let (a, _) = render3(&scene, 40, 30, Resolve::Bisect);
        let (b, _) = render3(&scene, 40, 30, Resolve::Crossing);
        let (c, _) = render3(&scene, 40, 30, Resolve::Paint);
        prop_assert_eq!(&c, &b, "painted");
        for rows in [1, 4, 11] {
            let d = render3_bands(&scene, 40, 30, Resolve::Paint, rows);
            prop_assert_eq!(&d, &b, "painted in bands of {}", rows);
        }
        let differ: Vec<(usize, Option<usize>, Option<usize>)> = a
            .iter()
            .zip(&b)
            .enumerate()
            .filter(|(_, (x, y))| x != y)
            .map(|(n, (x, y))| (n, *x, *y))
            .take(8)
            .collect();
        prop_assert!(differ.is_empty(), "pixel, bisection, crossing: {:?}", differ);
    }
}

// ---------------------------------------------------------------------
// A large face the window cuts, under a box standing on it.

/// A cube standing on a ground plate, seen from 2 units above the plate
/// and beyond the plate's corner: with the plate 200 units square, the
/// clips cut it to a polygon whose rounded vertices are not quite planar
/// and whose plane, scaled about its first vertex alone, was flattened
/// to that vertex's depth and drawn over the whole cube. Each mode, whole
/// and in 7-row bands, must show the cube exactly as over a plate of 8
/// units, which the clips leave whole.
#[test]
fn a_window_cut_plate_stays_under_the_box_standing_on_it() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("depth_range_plate");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let render = |half: u32, extra: &[&str]| -> Vec<u8> {
        let text = format!(
            "frame 320 240\nclear #101820\nperspective 50 1 100\nlookat 8 1 2  0 0.5 0\n\
             light 2 5 3 75\nsegment 1\ncolor #00ff00\n\
             face -{half} -1 {half}  {half} -1 {half}  {half} -1 -{half}  -{half} -1 -{half}\n\
             segment 2\ncolor #ff0000\n\
             face -1 -1 1  1 -1 1  1 1 1  -1 1 1\nface 1 -1 -1  -1 -1 -1  -1 1 -1  1 1 -1\n\
             face 1 -1 1  1 -1 -1  1 1 -1  1 1 1\nface -1 -1 -1  -1 -1 1  -1 1 1  -1 1 -1\n\
             face -1 1 1  1 1 1  1 1 -1  -1 1 -1\nface -1 -1 -1  1 -1 -1  1 -1 1  -1 -1 1\n"
        );
        let scene = dir.join(format!("plate{half}.dl"));
        let png = dir.join(format!("plate{half}{}.png", extra.join("")));
        std::fs::write(&scene, &text).expect("write scene");
        let mut args = vec![
            "render".to_string(),
            scene.to_str().unwrap().to_string(),
            "--out".to_string(),
            png.to_str().unwrap().to_string(),
        ];
        args.extend(extra.iter().map(|s| s.to_string()));
        scanvert_sim::cli::run(&args).expect("renders");
        let bytes = std::fs::read(&png).expect("png written");
        scanvert_sim::image::decode_png(&bytes).expect("decode").2
    };
    // The cube's pixels: red, lit (green and blue zero).
    let cube = |rgb: &[u8]| -> Vec<bool> {
        rgb.chunks(3)
            .map(|p| p[0] > 0 && p[1] == 0 && p[2] == 0)
            .collect()
    };
    for extra in [
        &["--resolve", "crossing"][..],
        &["--resolve", "bisect"],
        &["--resolve", "paint"],
        &["--resolve", "crossing", "--band-rows", "7"],
        &["--resolve", "paint", "--band-rows", "7"],
    ] {
        let small = cube(&render(4, extra));
        let large = cube(&render(100, extra));
        assert!(small.iter().filter(|&&c| c).count() > 5000, "{extra:?}");
        let differ = small.iter().zip(&large).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{extra:?}: {differ} pixels of the cube differ");
    }
}
