//! The 3D layer past 65,535: scenes that need more trapezoids or faces
//! than a store can address end at once with a capacity error, and pools
//! longer than the store can address are used up to what it can.
//!
//! The lists are generated here, rendered through the command line
//! (`scanvert_sim::cli::run`) or the library; the tests run in the test
//! profile, with overflow checks on.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use scanvert::fixed::{Coord, Vertex3};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::clip::ClipRect;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment, StoreError, StoreMemory, TrapezoidStore, MAX_POOL};
use scanvert::visible::sweep::{draw, Active, Resolve, Workspace};
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};
use std::fmt::Write as _;
use std::path::PathBuf;

fn run(args: &[&str]) -> Result<String, scanvert_sim::cli::CliError> {
    let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    scanvert_sim::cli::run(&args)
}

/// Renders `text` through the command line; the image's path and the
/// result.
fn render(name: &str, text: &str) -> (PathBuf, Result<String, String>) {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("capacity_limits");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let scene = dir.join(format!("{name}.dl"));
    let png = dir.join(format!("{name}.png"));
    let _ = std::fs::remove_file(&png);
    std::fs::write(&scene, text).expect("write scene");
    let r = run(&[
        "render",
        scene.to_str().expect("utf-8 path"),
        "--out",
        png.to_str().expect("utf-8 path"),
        "--stats",
    ]);
    (png, r.map_err(|e| e.to_string()))
}

/// A `poly3` of `n` vertices zigzagging between the left and the right
/// side of a `size × size` frame at random heights (in 1/16 px): every
/// edge crosses most others, so it is cut into many trapezoids. Wound
/// counter-clockwise as displayed, so it is drawn.
fn zigzag(n: usize, size: i32, seed: u64) -> String {
    let mut rng = testkit::rng::Rng(seed);
    let mut v: Vec<(i32, i32)> = (0..n)
        .map(|k| {
            let x = if k % 2 == 0 {
                rng.below(40)
            } else {
                size - 1 - rng.below(40)
            };
            (16 * x, rng.below(16 * size as u32))
        })
        .collect();
    let area: i64 = (0..n)
        .map(|k| {
            let (p, q) = (v[k], v[(k + 1) % n]);
            p.0 as i64 * q.1 as i64 - q.0 as i64 * p.1 as i64
        })
        .sum();
    if area > 0 {
        v.reverse();
    }
    let mut s = format!("frame {size} {size}\nclear #000000\ncolor #ff0000\npoly3");
    for (x, y) in v {
        write!(s, " {} {} 5", x as f64 / 16.0, y as f64 / 16.0).unwrap();
    }
    s.push('\n');
    s
}

/// `n` one-vertex faces (points) in a small frame.
fn points(n: usize) -> String {
    let mut s = String::from(
        "frame 64 64\nclear #000000\nperspective 60 1 100\nview 0 0 10 0 0\ncolor #ffffff\n",
    );
    for _ in 0..n {
        s.push_str("face 0 0 0\n");
    }
    s
}

#[test]
fn a_poly3_cut_into_more_than_65535_trapezoids_is_a_capacity_error() {
    let text = zigzag(700, 1000, 0x2545_f491);
    let (png, r) = render("zigzag", &text);
    let e = r.expect_err("more trapezoids than a store addresses");
    assert!(
        e.contains("line 4") && e.contains("65535 trapezoids"),
        "{e}"
    );
    assert!(!png.exists(), "no image on an error");
}

#[test]
fn a_poly3_of_500_vertices_within_the_limit_renders() {
    let text = zigzag(500, 1000, 0x2545_f491);
    let (png, r) = render("zigzag500", &text);
    let out = r.expect("renders");
    assert!(out.contains("1 poly3"), "{out}");
    assert!(png.exists());
}

#[test]
fn the_65536th_face_is_a_capacity_error_and_65535_render() {
    let (png, r) = render("points65535", &points(65_535));
    let out = r.expect("65535 faces render");
    assert!(out.contains("65535 faces"), "{out}");
    assert!(png.exists());

    let (png, r) = render("points65536", &points(65_536));
    let e = r.expect_err("one face too many");
    // The 65536th face is on line 5 + 65536; it needs a 65536th
    // trapezoid as well as a 65536th face, and the trapezoids are counted
    // first.
    assert!(
        e.contains("line 65541") && (e.contains("65535 faces") || e.contains("65535 trapezoids")),
        "{e}"
    );
    assert!(!png.exists(), "no image on an error");
}

fn v(x: i32, y: i32, z: i32) -> Vertex3 {
    Vertex3 {
        x: Coord::from_bits((x * 16) as i16),
        y: Coord::from_bits((y * 16) as i16),
        z: Coord::from_bits((z * 16) as i16),
    }
}

const W: u16 = 32;
const H: u16 = 24;

/// Pools of `n` slots each (trapezoids, faces, segments, active
/// slots).
struct Pools {
    traps: Vec<Trapezoid>,
    faces: Vec<Face>,
    segs: Vec<Segment>,
    rows: Vec<u16>,
    edges: Vec<EdgeSlot>,
    active: Vec<Active>,
    runs: Vec<Run>,
}

impl Pools {
    fn new(n: usize) -> Pools {
        Pools {
            traps: vec![Trapezoid::EMPTY; n],
            faces: vec![Face::EMPTY; n],
            segs: vec![Segment::EMPTY; n],
            rows: vec![0; H as usize],
            edges: vec![EdgeSlot::EMPTY; 8],
            active: vec![Active::EMPTY; n],
            runs: vec![Run::EMPTY; W as usize],
        }
    }
}

/// Two overlapping triangles (four trapezoids) in segments 0 and `last`,
/// drawn into a frame.
fn two_triangles(n: usize) -> Vec<Rgb888> {
    let mut p = Pools::new(n);
    let mut store = TrapezoidStore::new(
        StoreMemory {
            trapezoids: &mut p.traps,
            faces: &mut p.faces,
            segments: &mut p.segs,
            rows: &mut p.rows,
            edges: &mut p.edges,
        },
        W,
        H,
    )
    .expect("store");
    assert_eq!(store.capacity(), n.min(MAX_POOL));
    assert_eq!(store.face_capacity(), n.min(MAX_POOL));
    assert_eq!(store.segments().len(), n.min(MAX_POOL));
    let clip = ClipRect::full(W, H);
    let last = store.segments().len() - 1;
    store
        .add_polygon(
            0,
            [v(1, 1, 5), v(3, 22, 5), v(30, 12, 5)],
            Rgb888::RED,
            &clip,
        )
        .expect("fits");
    store
        .add_polygon(
            last,
            [v(4, 2, 2), v(12, 20, 9), v(28, 3, 9)],
            Rgb888::BLUE,
            &clip,
        )
        .expect("fits");
    assert_eq!(store.len(), 4);
    let mut ws = Workspace::new(&mut p.active, &mut p.runs);
    let mut pixels = vec![Rgb888::WHITE; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut pixels, W, H).expect("frame");
    draw(
        &store,
        &mut ws,
        Resolve::Crossing,
        &mut fb,
        Some(Rgb888::BLACK),
    )
    .expect("drawn");
    pixels
}

#[test]
fn pools_longer_than_65535_are_used_up_to_65535() {
    let want = two_triangles(4);
    for n in [MAX_POOL, MAX_POOL + 1, 70_000] {
        assert_eq!(two_triangles(n), want, "pools of {n}");
    }
}

#[test]
fn filling_a_pool_of_65536_ends_with_a_capacity_error_and_clears() {
    let mut p = Pools::new(MAX_POOL + 1);
    let mut store = TrapezoidStore::new(
        StoreMemory {
            trapezoids: &mut p.traps,
            faces: &mut p.faces,
            segments: &mut p.segs,
            rows: &mut p.rows,
            edges: &mut p.edges,
        },
        W,
        H,
    )
    .expect("store");
    let clip = ClipRect::full(W, H);
    // A rectangle is one trapezoid and one face.
    let rect = [v(1, 1, 5), v(1, 3, 5), v(6, 3, 5), v(6, 1, 5)];
    for k in 0..MAX_POOL {
        assert_eq!(
            store.add_polygon(k % 3, rect, Rgb888::RED, &clip),
            Ok(1),
            "polygon {k}"
        );
    }
    assert_eq!(store.len(), MAX_POOL);
    assert_eq!(
        store.add_polygon(1, rect, Rgb888::RED, &clip),
        Err(StoreError::Faces { capacity: MAX_POOL })
    );
    // Segment 1 was emptied; the others keep theirs.
    assert_eq!(store.segment(1).map(|s| s.trapezoids()), Some(0));
    assert_eq!(store.len(), 2 * MAX_POOL / 3);
    for s in 0..3 {
        store.clear_segment(s).expect("segment");
    }
    assert!(store.is_empty());
    assert_eq!(store.face_count(), 0);
    // Every slot comes back.
    for k in 0..MAX_POOL {
        assert_eq!(store.add_polygon(2, rect, Rgb888::RED, &clip), Ok(1), "{k}");
    }
    assert_eq!(
        store.add_polygon(2, rect, Rgb888::RED, &clip),
        Err(StoreError::Faces { capacity: MAX_POOL })
    );
    assert!(store.is_empty());
}

/// A planar concave `face`: a comb of `teeth` teeth in the plane y = −1,
/// its base far ahead of the eye and its tips `tip` (view z), wound
/// counter-clockwise seen from above.
fn comb(teeth: usize, tip: f64) -> String {
    let mut pts = Vec::new();
    for k in 0..teeth {
        let x = -12.5 + k as f64;
        pts.push((x, -5.0));
        pts.push((x + 0.5, tip));
    }
    pts.extend([(12.5, -5.0), (12.5, -20.0), (-12.5, -20.0)]);
    let face: Vec<String> = pts.iter().map(|(x, z)| format!("{x} -1 {z}")).collect();
    format!(
        "frame 200 150\nclear #000000\nperspective 60 1 100\nlookat 0 3 0 0 -1 -10\nsegment 1\ncolor #ff0000\nface {}\n",
        face.join(" ")
    )
}

/// A face within 58 vertices is drawn whole when clipping leaves it
/// within 64; a concave one whose 25 teeth the near plane cuts off one by
/// one needs 78 and is refused at its line, with that reason, and nothing
/// is written.
#[test]
fn a_concave_face_that_clipping_takes_past_64_is_refused_at_its_line() {
    // 53 vertices, all in front of the eye: drawn.
    let (png, r) = render("comb_in_front", &comb(25, -2.0));
    let out = r.expect("drawn");
    assert!(png.exists() && out.contains("1 faces (0 culled"), "{out}");
    // The same with its tips behind the eye: 25 teeth cut off.
    let (png, r) = render("comb_cut", &comb(25, 2.0));
    let e = r.expect_err("refused");
    assert!(e.contains("line 7"), "{e}");
    assert!(e.contains("64 vertices of a face after clipping"), "{e}");
    assert!(!png.exists());
    // Five teeth cut: 13 + 5 = 18 vertices, drawn.
    let (png, r) = render("comb_few", &comb(5, 2.0));
    let out = r.expect("drawn");
    assert!(png.exists() && out.contains("1 faces (0 culled"), "{out}");
}

/// A convex face of 58 vertices crossing the near plane and all four
/// window sides gains one vertex a plane: drawn.
#[test]
fn a_convex_face_of_58_vertices_is_drawn_whatever_clips_it() {
    let ring: Vec<String> = (0..58)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 58.0;
            // A disc around the eye's axis, wider than the window, from
            // behind the eye to far ahead.
            format!(
                "{:.4} {:.4} {:.4}",
                40.0 * a.cos(),
                30.0 * a.sin(),
                -30.0 + 35.0 * a.sin()
            )
        })
        .collect();
    let text = format!(
        "frame 160 120\nclear #000000\nperspective 60 1 100\nsegment 1\ncolor #00ff00\nface {}\n",
        ring.join(" ")
    );
    let (png, r) = render("convex_58", &text);
    let out = r.expect("drawn");
    assert!(png.exists() && out.contains("1 faces (0 culled"), "{out}");
}
