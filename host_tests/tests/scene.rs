//! The whole 3D path end to end: model polygons through `Scene` (the
//! geometry stage, the trapezoid store, the visible-surface pass, the
//! decoder, labels) into a frame buffer, checked against the exact
//! nearest-plane reference (`testkit::reference3d`) of the polygons
//! the geometry stage delivered.
//!
//! The geometry stage's own arithmetic is tested in `geometry.rs`; here
//! the question is whether what it delivers is drawn exactly, on the hard
//! cases: near plane, behind the eye, window edges, edge-on faces, a
//! closed cube, depths near the limits of the format, points and lines,
//! labels off screen, and segments rebuilt alone.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use host_tests::harness3d::{color_of, index_of};
use scanvert::fixed::Vertex3;
use scanvert::geometry::{
    Angle, Matrix, Orthographic, Outcome, Perspective, Pipeline, Point3, PolygonSink, Projection,
    View, Viewport, Q16,
};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::label::DEFAULT_FONT;
use scanvert::scene::{Builder, Capacities, Procedure, Scene, SceneError};
use scanvert::visible::store::StoreError;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::memory::SceneHeap;
use testkit::reference3d::{drawn, resolve, Poly3};

const W: u16 = 160;
const H: u16 = 120;
type P = Pipeline<8, 32>;
type B<'s, 'a> = Builder<'s, 'a, 8, 32>;

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

fn p(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(q(x), q(y), q(z))
}

fn persp(fov: i32, near: f64, far: f64) -> Perspective {
    Perspective::from_fov(Angle::from_degrees(fov), W, q(near), q(far)).unwrap()
}

fn pipeline(projection: impl Into<Projection>, eye: Point3, target: Point3) -> P {
    let mut pipe = P::new(projection, Viewport::centred(W, H).unwrap());
    pipe.set_view(&View::look_at(eye, target).unwrap()).unwrap();
    pipe
}

/// The six faces of a box, counter-clockwise seen from outside.
fn cuboid((x0, y0, z0): (f64, f64, f64), (x1, y1, z1): (f64, f64, f64)) -> Vec<Vec<Point3>> {
    vec![
        vec![p(x0, y0, z1), p(x1, y0, z1), p(x1, y1, z1), p(x0, y1, z1)],
        vec![p(x1, y0, z0), p(x0, y0, z0), p(x0, y1, z0), p(x1, y1, z0)],
        vec![p(x1, y0, z1), p(x1, y0, z0), p(x1, y1, z0), p(x1, y1, z1)],
        vec![p(x0, y0, z0), p(x0, y0, z1), p(x0, y1, z1), p(x0, y1, z0)],
        vec![p(x0, y1, z1), p(x1, y1, z1), p(x1, y1, z0), p(x0, y1, z0)],
        vec![p(x0, y0, z0), p(x1, y0, z0), p(x1, y0, z1), p(x0, y0, z1)],
    ]
}

/// The polygons the geometry stage delivers, as they are delivered.
#[derive(Default)]
struct Record(Vec<(Vec<Vertex3>, Rgb888, bool)>);

impl PolygonSink for Record {
    type Error = core::convert::Infallible;
    fn polygon(&mut self, v: &[Vertex3], c: Rgb888, two: bool) -> Result<(), Self::Error> {
        self.0.push((v.to_vec(), c, two));
        Ok(())
    }
}

/// The caller's memory of a test scene, on the heap.
struct Mem(SceneHeap);

/// What running `frames` on `pipe` needs, one after the other in one
/// scene (every segment rebuilt for each): each frame is a procedure per
/// segment.
fn needs(pipe: &P, frames: &mut [&mut [&mut dyn Procedure<8, 32>]]) -> Capacities {
    let segments = frames.first().map_or(1, |f| f.len());
    let start = Capacities {
        segments,
        rows: H as usize,
        runs: W as usize,
        edges: 32,
        ..Capacities::default()
    };
    SceneHeap::fit(start, |mem| {
        let mut scene = Scene::new(mem, pipe.clone())?;
        let mut most = Capacities::default();
        for procs in frames.iter_mut() {
            scene.invalidate_all();
            scene.update(procs)?;
            most = most.max(scene.needed()?);
        }
        Ok(most)
    })
    .unwrap()
}

impl Mem {
    /// Memory as large as running `frames` needs ([`needs`]).
    fn fit(pipe: &P, frames: &mut [&mut [&mut dyn Procedure<8, 32>]]) -> Mem {
        Mem(SceneHeap::new(needs(pipe, frames)))
    }

    /// Memory of `caps`.
    fn of(caps: Capacities) -> Mem {
        Mem(SceneHeap::new(caps))
    }

    /// Memory with `segments` segments and room for `trapezoids` (and as
    /// many faces and active slots): a pool deliberately too small.
    fn with_trapezoids(segments: usize, trapezoids: usize) -> Mem {
        Mem(SceneHeap::new(Capacities {
            trapezoids,
            faces: trapezoids,
            segments,
            rows: H as usize,
            edges: 32,
            active: trapezoids,
            runs: W as usize,
            labels: 0,
            text: 0,
        }))
    }

    fn scene(&mut self, pipe: P) -> Scene<'_, 8, 32> {
        Scene::new(self.0.memory(), pipe).unwrap()
    }
}

/// Draws a scene into an `Rgb888` frame (black background); returns the
/// face index at each pixel (by colour) and the labels drawn.
fn draw(scene: &mut Scene<'_, 8, 32>) -> (Vec<Option<usize>>, Vec<Rgb888>, u32) {
    let mut px = vec![Rgb888::WHITE; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
    let f = scene
        .draw(
            Resolve::default(),
            Some(Rgb888::BLACK),
            DEFAULT_FONT,
            &mut fb,
        )
        .unwrap();
    (
        px.iter().map(|&c| index_of(c)).collect(),
        px,
        f.labels.drawn,
    )
}

/// What one end-to-end check found.
#[derive(Debug, Default)]
struct Check {
    emitted: usize,
    covered: usize,
    mismatched: usize,
    /// Background pixels strictly inside the hull of everything drawn.
    holes: usize,
}

/// Runs `faces` (face `k` in colour `color_of(k)`) through a scene on
/// `pipe` and through the same pipeline into a recorder, and compares the
/// scene's picture with the exact reference of the recorded polygons.
fn check(pipe: &P, faces: &[Vec<Point3>]) -> Check {
    let mut rec = Record::default();
    let mut twin = pipe.clone();
    for (k, f) in faces.iter().enumerate() {
        twin.polygon(f, color_of(k), &mut rec).unwrap();
    }
    let mut build = |b: &mut B<'_, '_>| {
        for (k, f) in faces.iter().enumerate() {
            b.face(f, color_of(k))?;
        }
        Ok(())
    };
    let mut mem = Mem::fit(pipe, &mut [&mut [&mut build]]);
    let mut scene = mem.scene(pipe.clone());
    scene.update(&mut [&mut build]).unwrap();
    let (got, _, _) = draw(&mut scene);

    // The reference culls by the spec's rule for `poly3`: every face the
    // geometry stage lets through must pass it; points and lines (two
    // sided) are turned to pass it.
    let mut polys = Vec::new();
    let mut owner = Vec::new();
    for (v, c, two) in &rec.0 {
        let mut poly: Vec<(i32, i32, i32)> = v
            .iter()
            .map(|v| (v.x.units(), v.y.units(), v.z.units()))
            .collect();
        assert!(
            poly.iter()
                .all(|&(x, y, _)| (0..=W as i32 * 16).contains(&x)
                    && (0..=H as i32 * 16).contains(&y)),
            "delivered outside the window: {poly:?}"
        );
        if !drawn(&poly) {
            if *two {
                poly.reverse();
            } else {
                // A front face whose projection rounds to zero area or
                // less: the reference draws nothing of it, nor does the
                // library (no pixel centre lies inside it), so it can be
                // left out.
                continue;
            }
        }
        // Rounded to 1/16 px, a delivered polygon of four or more
        // vertices is planar only within rounding; the reference takes
        // planar polygons alone, so it gets the fan of triangles (the
        // library keeps one plane per polygon: depths differ by far less
        // than the gaps between the test scenes' surfaces).
        for k in 1..poly.len() - 1 {
            let t = vec![poly[0], poly[k], poly[k + 1]];
            if drawn(&t) {
                polys.push(Poly3 {
                    poly: t,
                    clip: None,
                });
                owner.push(index_of(*c).unwrap());
            }
        }
    }
    let want: Vec<Option<usize>> = resolve(&polys, W.into(), H.into())
        .into_iter()
        .map(|r| r.map(|k| owner[k]))
        .collect();
    let mut c = Check {
        emitted: rec.0.len(),
        ..Check::default()
    };
    for (g, w) in got.iter().zip(&want) {
        c.covered += w.is_some() as usize;
        c.mismatched += (g != w) as usize;
    }
    c.holes = holes(&rec.0, &got);
    c
}

/// Background pixels whose centre lies more than 1 px inside the convex
/// hull of every vertex delivered: for one convex solid seen whole, a
/// crack between faces.
fn holes(polys: &[(Vec<Vertex3>, Rgb888, bool)], got: &[Option<usize>]) -> usize {
    let mut pts: Vec<(f64, f64)> = polys
        .iter()
        .flat_map(|(v, _, _)| {
            v.iter()
                .map(|v| (v.x.units() as f64 / 16.0, v.y.units() as f64 / 16.0))
        })
        .collect();
    if pts.len() < 3 {
        return 0;
    }
    pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    pts.dedup();
    // Andrew's monotone chain.
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let it: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &pt in it {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], pt) <= 0.0
            {
                hull.pop();
            }
            hull.push(pt);
        }
        hull.pop();
    }
    let inside = |x: f64, y: f64| {
        (0..hull.len()).all(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            len == 0.0 || cross(a, b, (x, y)) / len > 1.0
        })
    };
    let mut n = 0;
    for j in 0..H as usize {
        for i in 0..W as usize {
            if got[j * W as usize + i].is_none() && inside(i as f64 + 0.5, j as f64 + 0.5) {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn separate_boxes_match_the_reference_in_both_projections() {
    let mut faces = Vec::new();
    for i in 0..4 {
        for j in 0..3 {
            let (x, z) = (i as f64 * 3.0 - 5.0, j as f64 * 3.0 - 4.0);
            let h = 1.0 + ((i * 7 + j * 3) % 5) as f64;
            faces.extend(cuboid((x, 0.0, z), (x + 2.0, h, z + 2.0)));
        }
    }
    let mut total = Check::default();
    for orbit in (0..360).step_by(45) {
        let a = (orbit as f64).to_radians();
        let eye = p(20.0 * a.sin(), 12.0, 20.0 * a.cos());
        for pipe in [
            pipeline(persp(60, 1.0, 100.0), eye, p(0.0, 1.0, 0.0)),
            pipeline(
                Orthographic::new(q(6.0), q(1.0), q(100.0)).unwrap(),
                eye,
                p(0.0, 1.0, 0.0),
            ),
        ] {
            let c = check(&pipe, &faces);
            assert_eq!(c.mismatched, 0, "orbit {orbit}: {c:?}");
            total.covered += c.covered;
        }
    }
    assert!(total.covered > 30_000, "{total:?}");
}

#[test]
fn closed_cube_has_no_cracks_at_any_angle() {
    let cube = cuboid((-1.0, -1.0, -1.0), (1.0, 1.0, 1.0));
    let mut seen = 0;
    for k in 0..40 {
        let (yaw, pitch) = (k * 37 % 360, k * 53 % 360);
        // Some cubes lie across the window's edges.
        let shift = [(0.0, 0.0), (3.5, 0.0), (0.0, -2.6), (-3.2, 2.4)][k as usize % 4];
        let pipe = pipeline(persp(50, 0.5, 50.0), p(0.0, 0.0, 7.0), p(0.0, 0.0, 0.0));
        let c = check_with_model(&pipe, &cube, (shift, yaw, pitch));
        assert_eq!(c.mismatched, 0, "cube {k}: {c:?}");
        if shift == (0.0, 0.0) {
            assert_eq!(c.holes, 0, "cube {k} (yaw {yaw}, pitch {pitch}): {c:?}");
        }
        seen += c.covered;
    }
    assert!(seen > 20_000);
}

/// [`check`] of `faces` moved by `(shift, yaw, pitch)`: turned about y,
/// then x, then shifted.
fn check_with_model(
    pipe: &P,
    faces: &[Vec<Point3>],
    (shift, yaw, pitch): ((f64, f64), i32, i32),
) -> Check {
    let m = Matrix::translation(p(shift.0, shift.1, 0.0))
        .checked_mul(&Matrix::rotation_y(Angle::from_degrees(yaw)))
        .unwrap()
        .checked_mul(&Matrix::rotation_x(Angle::from_degrees(pitch)))
        .unwrap();
    let moved: Vec<Vec<Point3>> = faces
        .iter()
        .map(|f| f.iter().map(|&pt| m.transform(pt).unwrap()).collect())
        .collect();
    check(pipe, &moved)
}

#[test]
fn polygons_across_the_near_plane_and_behind_the_eye() {
    let mut pipe = pipeline(persp(70, 0.25, 200.0), p(0.0, 2.0, 0.0), p(0.0, 1.5, -10.0));
    let floor = vec![
        p(-50.0, 0.0, 50.0),
        p(50.0, 0.0, 50.0),
        p(50.0, 0.0, -50.0),
        p(-50.0, 0.0, -50.0),
    ];
    let behind = vec![
        p(-1.0, 0.0, 5.0),
        p(1.0, 0.0, 5.0),
        p(1.0, 3.0, 5.0),
        p(-1.0, 3.0, 5.0),
    ];
    let through_eye = vec![
        p(-3.0, 1.0, 3.0),
        p(3.0, 1.0, 3.0),
        p(3.0, 3.0, -3.0),
        p(-3.0, 3.0, -3.0),
    ];
    let wall = vec![
        p(-4.0, 0.0, -8.0),
        p(4.0, 0.0, -8.0),
        p(4.0, 4.0, -8.0),
        p(-4.0, 4.0, -8.0),
    ];
    let faces = [floor, behind.clone(), through_eye, wall];
    let c = check(&pipe, &faces);
    assert_eq!(c.mismatched, 0, "{c:?}");
    assert!(c.covered > (W as usize * H as usize) / 3, "{c:?}");
    // The wall behind the eye is clipped away whichever way it faces.
    let mut sink = Record::default();
    let mut rev = behind.clone();
    rev.reverse();
    for f in [&behind, &rev] {
        let o = pipe.polygon(f, Rgb888::RED, &mut sink).unwrap();
        assert!(matches!(o, Outcome::ClippedAway | Outcome::Culled), "{o:?}");
    }
    assert!(sink.0.is_empty());
}

#[test]
fn edge_on_faces_draw_nothing() {
    // Planes through the eye, seen exactly edge-on.
    let pipe = pipeline(persp(60, 1.0, 100.0), p(0.0, 0.0, 10.0), p(0.0, 0.0, 0.0));
    let faces = [
        vec![
            p(-2.0, 0.0, 2.0),
            p(2.0, 0.0, 2.0),
            p(2.0, 0.0, -2.0),
            p(-2.0, 0.0, -2.0),
        ],
        vec![
            p(0.0, -2.0, -2.0),
            p(0.0, -2.0, 2.0),
            p(0.0, 2.0, 2.0),
            p(0.0, 2.0, -2.0),
        ],
    ];
    let c = check(&pipe, &faces);
    assert_eq!((c.emitted, c.covered, c.mismatched), (0, 0, 0), "{c:?}");
}

#[test]
fn depths_near_the_limits_of_the_format() {
    // Near plane at 1/16, far at 16000: view depths at both ends map to
    // screen depths near −2048 and +2048.
    let pipe = pipeline(
        persp(60, 1.0 / 16.0, 16000.0),
        p(0.0, 0.0, 0.0),
        p(0.0, 0.0, -1.0),
    );
    let mut faces: Vec<Vec<Point3>> = Vec::with_capacity(5);
    let face = |v: Vec<Point3>| v;
    // Two layers just past the near plane, a hair apart.
    faces.push(face(vec![
        p(-0.05, -0.05, -0.07),
        p(0.05, -0.05, -0.07),
        p(0.05, 0.05, -0.07),
        p(-0.05, 0.05, -0.07),
    ]));
    faces.push(vec![
        p(-0.02, -0.08, -0.075),
        p(0.08, -0.08, -0.075),
        p(0.08, 0.02, -0.075),
        p(-0.02, 0.02, -0.075),
    ]);
    // Two layers just before the far plane.
    faces.push(vec![
        p(-9000.0, -9000.0, -15000.0),
        p(0.0, -9000.0, -15000.0),
        p(0.0, 0.0, -15000.0),
        p(-9000.0, 0.0, -15000.0),
    ]);
    faces.push(vec![
        p(-12000.0, -3000.0, -15990.0),
        p(3000.0, -3000.0, -15990.0),
        p(3000.0, 6000.0, -15990.0),
        p(-12000.0, 6000.0, -15990.0),
    ]);
    // A long face from near to far.
    faces.push(vec![
        p(1.0, 1.0, -0.1),
        p(3000.0, 1.0, -15000.0),
        p(3000.0, -1.0, -15000.0),
        p(1.0, -1.0, -0.1),
    ]);
    let mut twin = pipe.clone();
    let outcomes: Vec<Outcome> = faces
        .iter()
        .map(|f| {
            twin.polygon(f, Rgb888::RED, &mut Record::default())
                .unwrap()
        })
        .collect();
    let c = check(&pipe, &faces);
    assert_eq!(c.emitted, 5, "{c:?} {outcomes:?}");
    assert_eq!(c.mismatched, 0, "{c:?}");
}

#[test]
fn points_and_lines_at_the_window_edges() {
    // One world unit is one pixel, the view axis through the window's
    // middle: world (±80, ±60) are the window's corners.
    let mut pipe = pipeline(
        Orthographic::new(q(1.0), q(1.0), q(100.0)).unwrap(),
        p(0.0, 0.0, 10.0),
        p(0.0, 0.0, 0.0),
    );
    pipe.set_thickness(scanvert::fixed::Coord::from_bits(3 * 16));
    let (x, y) = (80.0, 60.0);
    let mut faces = Vec::new();
    for (px, py) in [
        (-x, -y),
        (x, -y),
        (x, y),
        (-x, y),
        (0.0, y),
        (x, 0.0),
        (-x - 1.0, 0.0),
        (0.0, -y - 1.5),
    ] {
        faces.push(vec![p(px, py, 0.0)]);
    }
    for (a, b) in [
        ((-x, -y), (x, -y)),
        ((x, -y), (x, y)),
        ((x, y), (-x, y)),
        ((-x, y), (-x, -y)),
        ((-x - 5.0, 0.0), (x + 5.0, 3.0)),
    ] {
        faces.push(vec![p(a.0, a.1, -1.0), p(b.0, b.1, -1.0)]);
    }
    let c = check(&pipe, &faces);
    assert_eq!(c.mismatched, 0, "{c:?}");
    assert!(c.emitted >= 11 && c.covered > 700, "{c:?}");
}

#[test]
fn labels_behind_the_eye_and_off_screen() {
    let pipe = pipeline(persp(60, 1.0, 100.0), p(0.0, 0.0, 10.0), p(0.0, 0.0, 0.0));
    let mut placed = Vec::new();
    let mut build = |b: &mut B<'_, '_>| {
        placed.clear();
        for (at, text) in [
            (p(0.0, 0.0, 0.0), "centre"),
            (p(0.0, 0.0, 20.0), "behind"),
            (p(0.0, 0.0, 10.0), "at the eye"),
            (p(-500.0, 0.0, 0.0), "far left"),
            (p(0.0, 300.0, 0.0), "far up"),
            (p(16000.0, -16000.0, 5.0), "extreme"),
            (p(-6.5, 0.0, 0.0), "cut at the left edge"),
            (p(5.0, -4.5, 0.0), "cut at the bottom"),
        ] {
            placed.push((text, b.label(at, text, Rgb888::WHITE)?));
        }
        Ok(())
    };
    let mut mem = Mem::fit(&pipe, &mut [&mut [&mut build]]);
    let mut scene = mem.scene(pipe);
    scene.update(&mut [&mut build]).unwrap();
    let behind: Vec<_> = placed.iter().filter(|p| !p.1).map(|p| p.0).collect();
    assert_eq!(behind, ["behind", "at the eye"]);
    let (_, px, drawn) = draw(&mut scene);
    assert_eq!(drawn, 3, "centre and the two cut at edges");
    assert!(px.contains(&Rgb888::WHITE));
    // A bad text fails even when the point is behind the eye.
    let mut bad = |b: &mut B<'_, '_>| {
        b.label(p(0.0, 0.0, 20.0), "tab\there", Rgb888::WHITE)
            .map(|_| ())
    };
    let e = scene.update(&mut [&mut bad]);
    assert!(e.is_ok(), "the segment was not stale");
    scene.invalidate(0).unwrap();
    let e = scene.update(&mut [&mut bad]).unwrap_err();
    assert_eq!(e.segment, 0);
    assert!(matches!(e.error, SceneError::Labels(_)), "{e:?}");
    assert_eq!(scene.labels().len(), 0);
}

/// A box per segment, the middle one moved by `dx`.
fn three_boxes(dx: f64) -> [Vec<Vec<Point3>>; 3] {
    [
        cuboid((-6.0, 0.0, 0.0), (-4.0, 2.0, 2.0)),
        cuboid((-1.0 + dx, 0.0, 0.0), (1.0 + dx, 3.0, 2.0)),
        cuboid((4.0, 0.0, 0.0), (6.0, 2.0, 2.0)),
    ]
}

fn segment_procs(
    boxes: &[Vec<Vec<Point3>>; 3],
) -> [impl FnMut(&mut B<'_, '_>) -> Result<(), SceneError> + '_; 3] {
    std::array::from_fn(move |s| {
        move |b: &mut B<'_, '_>| {
            for (k, f) in boxes[s].iter().enumerate() {
                b.face(f, color_of(s * 8 + k))?;
            }
            Ok(())
        }
    })
}

#[test]
fn only_the_changed_segment_is_rebuilt() {
    let pipe = pipeline(persp(60, 1.0, 100.0), p(2.0, 6.0, 14.0), p(0.0, 1.0, 0.0));
    let first = three_boxes(0.0);
    let [mut a, mut b, mut c] = segment_procs(&first);
    let moved = three_boxes(1.5);
    let [mut a2, mut b2, mut c2] = segment_procs(&moved);
    // Room for both frames, and for the second after a camera move.
    let eye = View::look_at(p(-3.0, 6.0, 14.0), p(0.0, 1.0, 0.0)).unwrap();
    let mut turned = pipe.clone();
    turned.set_view(&eye).unwrap();
    let caps = needs(
        &pipe,
        &mut [
            &mut [&mut a, &mut b, &mut c],
            &mut [&mut a2, &mut b2, &mut c2],
        ],
    )
    .max(needs(&turned, &mut [&mut [&mut a2, &mut b2, &mut c2]]));
    let mut mem = Mem::of(caps);
    let mut scene = mem.scene(pipe.clone());
    let u = scene.update(&mut [&mut a, &mut b, &mut c]).unwrap();
    assert_eq!(u.regenerated, 3);
    let before: Vec<_> = scene
        .store()
        .segments()
        .iter()
        .map(|s| s.counters())
        .collect();

    // Nothing stale: nothing is done.
    let u = scene.update(&mut [&mut a, &mut b, &mut c]).unwrap();
    assert_eq!((u.regenerated, u.polygons, u.trapezoids), (0, 0, 0));

    // The middle box moves: only its segment is emptied and cut again.
    scene.invalidate(1).unwrap();
    let u = scene.update(&mut [&mut a2, &mut b2, &mut c2]).unwrap();
    assert_eq!(u.regenerated, 1);
    let after: Vec<_> = scene
        .store()
        .segments()
        .iter()
        .map(|s| s.counters())
        .collect();
    assert_eq!(after[0], before[0]);
    assert_eq!(after[2], before[2]);
    assert_eq!(after[1].clears, before[1].clears + 1);
    assert!(after[1].polygons > before[1].polygons);
    assert_eq!(u.given, 6);
    assert_eq!(u.trapezoids, after[1].trapezoids - before[1].trapezoids);
    assert!(u.trapezoids > 0);

    // The picture is the one a scene built from scratch draws.
    let (got, _, _) = draw(&mut scene);
    let mut mem2 = Mem::fit(&pipe, &mut [&mut [&mut a2, &mut b2, &mut c2]]);
    let mut fresh = mem2.scene(pipe.clone());
    fresh.update(&mut [&mut a2, &mut b2, &mut c2]).unwrap();
    let (want, _, _) = draw(&mut fresh);
    assert_eq!(got, want);

    // A camera move makes every segment stale.
    scene.set_view(&eye).unwrap();
    let u = scene.update(&mut [&mut a2, &mut b2, &mut c2]).unwrap();
    assert_eq!(u.regenerated, 3);
}

#[test]
fn a_failing_segment_is_left_empty_and_stale_alone() {
    let pipe = pipeline(persp(60, 1.0, 100.0), p(2.0, 6.0, 14.0), p(0.0, 1.0, 0.0));
    // Room for the small boxes, not for the big one.
    let mut mem = Mem::with_trapezoids(3, 40);
    let mut scene = mem.scene(pipe);
    let boxes = three_boxes(0.0);
    let [mut a, _, mut c] = segment_procs(&boxes);
    let mut big = |b: &mut B<'_, '_>| {
        for i in 0..20 {
            for f in cuboid(
                (i as f64 * 0.5 - 5.0, 3.0, -2.0),
                (i as f64 * 0.5 - 4.8, 4.0, -1.0),
            ) {
                b.face(&f, Rgb888::RED)?;
            }
        }
        Ok(())
    };
    let e = scene.update(&mut [&mut a, &mut big, &mut c]).unwrap_err();
    assert_eq!(e.segment, 1);
    assert!(
        matches!(
            e.error,
            SceneError::Store(StoreError::Trapezoids { capacity: 40 })
        ),
        "{e:?}"
    );
    assert_eq!(scene.store().segment(1).unwrap().trapezoids(), 0);
    assert!(scene.is_stale(1) && !scene.is_stale(0) && scene.is_stale(2));
    // Segment 0 was built before the failure and stays; 2 is built next.
    let held = scene.store().segment(0).unwrap().trapezoids();
    assert!(held > 0);
    let mut none = |_: &mut B<'_, '_>| Ok(());
    let procs: &mut [&mut dyn Procedure<8, 32>] = &mut [&mut a, &mut none, &mut c];
    let u = scene.update(procs).unwrap();
    assert_eq!(u.regenerated, 2);
    assert_eq!(scene.store().segment(0).unwrap().trapezoids(), held);
}

/// An arrow head pointing down (y up), counter-clockwise seen from +z,
/// listed so that the corner of its first three vertices is the reflex
/// one: the old rule (the first three vertices) called it a back face.
fn arrow(z: f64) -> Vec<Point3> {
    [(3.0, 3.0), (0.0, 1.0), (-3.0, 3.0), (0.0, -3.0)]
        .iter()
        .map(|&(x, y)| p(x, y, z))
        .collect()
}

/// The list's default camera: the eye at the origin looking along −z, y
/// up. A face in front of it (z = −5) is drawn; one behind it (z = +5)
/// is not, in either winding.
#[test]
fn the_default_camera_of_a_list_looks_along_minus_z() {
    let square = |z: f64| {
        vec![
            p(-1.0, -1.0, z),
            p(1.0, -1.0, z),
            p(1.0, 1.0, z),
            p(-1.0, 1.0, z),
        ]
    };
    for (z, shown) in [(-5.0, true), (5.0, false)] {
        for reverse in [false, true] {
            let mut face = square(z);
            if reverse {
                face.reverse();
            }
            let mut build = |b: &mut B<'_, '_>| b.face(&face, color_of(0)).map(|_| ());
            let pipe = scanvert::scene::list_pipeline(W, H).unwrap();
            let mut mem = Mem::fit(&pipe, &mut [&mut [&mut build]]);
            let mut scene = mem.scene(pipe);
            scene.update(&mut [&mut build]).unwrap();
            let (got, _, _) = draw(&mut scene);
            let n = got.iter().filter(|c| c.is_some()).count();
            assert_eq!(n > 0, shown && !reverse, "z = {z}, reversed: {reverse}");
            if n > 0 {
                // Centred on the view axis.
                assert_eq!(
                    got[(H / 2) as usize * W as usize + (W / 2) as usize],
                    Some(0)
                );
            }
        }
    }
}

/// Facing is decided by the whole polygon: a concave face listed from
/// its reflex corner is drawn, exactly, and its reverse is culled; the
/// same face given as a display-list command through `Builder::command`
/// draws the same pixels.
#[test]
fn a_concave_face_from_its_reflex_corner_is_drawn() {
    let pipe = pipeline(persp(60, 1.0, 100.0), p(0.0, 0.0, 10.0), p(0.0, 0.0, 0.0));
    let face = arrow(0.0);
    // The reference: the delivered polygon whole (parallel to the screen,
    // so planar exactly), by the pixel rule.
    let mut rec = Record::default();
    pipe.clone().polygon(&face, color_of(0), &mut rec).unwrap();
    assert_eq!(rec.0.len(), 1);
    let poly: Vec<(i32, i32, i32)> = rec.0[0]
        .0
        .iter()
        .map(|v| (v.x.units(), v.y.units(), v.z.units()))
        .collect();
    assert!(drawn(&poly));
    let want = resolve(&[Poly3 { poly, clip: None }], W.into(), H.into());
    let mut build = |b: &mut B<'_, '_>| {
        assert_eq!(b.face(&face, color_of(0))?, Outcome::Emitted);
        Ok(())
    };
    let mut mem = Mem::fit(&pipe, &mut [&mut [&mut build]]);
    let mut scene = mem.scene(pipe.clone());
    scene.update(&mut [&mut build]).unwrap();
    let (got, _, _) = draw(&mut scene);
    assert_eq!(got, want);
    assert!(got.iter().filter(|c| c.is_some()).count() > 300);
    let mut back = face.clone();
    back.reverse();
    let mut build = |b: &mut B<'_, '_>| {
        assert_eq!(b.face(&back, color_of(0))?, Outcome::Culled);
        Ok(())
    };
    let mut mem = Mem::fit(&pipe, &mut [&mut [&mut build]]);
    let mut scene = mem.scene(pipe.clone());
    scene.update(&mut [&mut build]).unwrap();
    let (got, _, _) = draw(&mut scene);
    assert!(got.iter().all(|c| c.is_none()));

    // The same through the list interpreter.
    let text = "frame 160 120\ncolor #000000\nface 3 3 0  0 1 0  -3 3 0  0 -3 0\n";
    let bytes = scanvert_sim::text::assemble_bytes(text.as_bytes())
        .unwrap()
        .bytes;
    let list = scanvert::display_list::DisplayList::new_checked(&bytes).unwrap();
    let mut run = |b: &mut B<'_, '_>| {
        let mut st = scanvert::scene::ListState::new(W, H);
        for (_, cmd) in list.commands() {
            b.command(cmd, &mut st)?;
        }
        Ok(())
    };
    let mut direct = |b: &mut B<'_, '_>| b.face(&face, Rgb888::BLACK).map(|_| ());
    let mut frames = Vec::new();
    for proc in [
        &mut run as &mut dyn scanvert::scene::Procedure<8, 32>,
        &mut direct,
    ] {
        let mut mem = Mem::fit(&pipe, &mut [&mut [&mut *proc]]);
        let mut scene = mem.scene(pipe.clone());
        scene.update(&mut [proc]).unwrap();
        frames.push(draw(&mut scene).1);
    }
    assert_eq!(frames[0], frames[1]);
    assert!(frames[0].contains(&Rgb888::BLACK));
}

/// `Scene::needed` counts the moments inside an update: a rebuilt segment
/// that grew is stored while the next still holds its last frame. Here
/// segment 0 goes from 1 quad to 6 while segment 1 goes from 6 to 1, so
/// every frame ends holding 7 quads, but the second held 12 while it was
/// built. Storage of `Capacities::max` of `usage` runs out; of `needed`,
/// it does not.
#[test]
fn needed_counts_what_an_update_holds_while_it_builds() {
    let pipe = pipeline(persp(60, 1.0, 100.0), p(0.0, 0.0, 10.0), p(0.0, 0.0, 0.0));
    let quads = |n: usize, x: f64| {
        (0..n)
            .map(|k| {
                let y = k as f64 * 0.5 - 2.0;
                vec![
                    p(x, y, 0.0),
                    p(x + 1.0, y, 0.0),
                    p(x + 1.0, y + 0.3, 0.0),
                    p(x, y + 0.3, 0.0),
                ]
            })
            .collect::<Vec<_>>()
    };
    let frames = [
        (quads(1, -2.0), quads(6, 1.0)),
        (quads(6, -2.0), quads(1, 1.0)),
    ];
    let run = |scene: &mut Scene<'_, 8, 32>| -> Result<(Capacities, Capacities), SceneError> {
        let (mut used, mut needed) = (Capacities::default(), Capacities::default());
        for (a, b) in &frames {
            let mut seg_a = |bd: &mut B<'_, '_>| {
                a.iter()
                    .try_for_each(|f| bd.face(f, Rgb888::RED).map(|_| ()))
            };
            let mut seg_b = |bd: &mut B<'_, '_>| {
                b.iter()
                    .try_for_each(|f| bd.face(f, Rgb888::BLUE).map(|_| ()))
            };
            scene.invalidate_all();
            scene
                .update(&mut [&mut seg_a, &mut seg_b])
                .map_err(|e| e.error)?;
            used = used.max(scene.usage().unwrap());
            needed = needed.max(scene.needed().unwrap());
        }
        Ok((used, needed))
    };
    let mut big = Mem::with_trapezoids(2, 1000);
    let (used, needed) = run(&mut big.scene(pipe.clone())).unwrap();
    assert!(
        needed.trapezoids > used.trapezoids,
        "{needed:?} against {used:?}"
    );
    assert_eq!(needed.faces, 12);
    assert_eq!(used.faces, 7);
    // In what the frames used once built, the second frame runs out.
    let short = run(&mut Mem::of(used).scene(pipe.clone()));
    assert!(matches!(short, Err(SceneError::Store(_))), "{short:?}");
    // In what they needed, it does not, and needs the same again.
    let (_, again) = run(&mut Mem::of(needed).scene(pipe)).unwrap();
    assert_eq!(again, needed);
}
