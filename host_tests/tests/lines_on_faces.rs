//! Points and lines on faces: a point or a line (a `face` of one or two
//! vertices) is compared at its plane moved `LINE_BIAS` units of depth
//! toward the eye, so that it shows on a face it lies on
//! (`docs/display-list.md`).
//!
//! - `scenes/cube.dl` shows every pixel of its axes, as it does with its
//!   faces taken out (nothing in it is nearer than the axes), in every
//!   resolve mode and band height;
//! - scenes of lines on tilted faces, on the edges that faces share, and
//!   points on faces, drawn by `Scene` in every resolve mode, whole and in
//!   bands, against the exact reference (`testkit::reference3d`, which
//!   implements the same rule apart) with no pixel different.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use host_tests::harness3d::{color_of, index_of};
use scanvert::fixed::{Coord, Vertex3};
use scanvert::geometry::{
    Angle, Orthographic, Perspective, Pipeline, Point3, PolygonSink, Projection, View, Viewport,
    Q16,
};
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::{Builder, Capacities, Scene, DEFAULT_FONT};
use scanvert::visible::store::LINE_BIAS;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::cli::{render_scene_bands_with, render_scene_with, Scene as ListScene};
use scanvert_sim::memory::SceneHeap;
use std::path::Path;
use testkit::reference3d::{drawn, resolve_lifted, Poly3};

const MODES: [Resolve; 4] = [
    Resolve::Crossing,
    Resolve::Bisect,
    Resolve::Paint,
    Resolve::Auto,
];

/// The library and the reference state the same move.
#[test]
fn the_reference_moves_points_and_lines_as_far_as_the_library() {
    assert_eq!(LINE_BIAS as i128, testkit::reference3d::LINE_BIAS);
}

// ---------------------------------------------------------------------
// scenes/cube.dl

fn cube_text() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cube.dl"))
        .expect("scenes/cube.dl")
}

/// `text` without its polygon faces (`face` commands of three or more
/// vertices): the points, lines and labels stay.
fn without_faces(text: &str) -> String {
    text.lines()
        .filter(|l| {
            let words: Vec<&str> = l.split('#').next().unwrap().split_whitespace().collect();
            !(words.first() == Some(&"face") && words.len() > 1 + 6)
        })
        .map(|l| format!("{l}\n"))
        .collect()
}

fn list(text: &str) -> ListScene {
    ListScene::from_bytes(Path::new("cube.dl"), text.as_bytes().to_vec()).expect("scene reads")
}

/// The axes' colours in the frame's format: x, y, z.
fn axes() -> [Rgb565; 3] {
    [(0xff, 0x80, 0x80), (0x80, 0xff, 0x80), (0x80, 0x80, 0xff)]
        .map(|(r, g, b)| Rgb565::from(Rgb888::new(r, g, b)))
}

/// The pixels of each axis's colour.
fn axis_pixels(px: &[Rgb565]) -> [Vec<usize>; 3] {
    axes().map(|c| (0..px.len()).filter(|&k| px[k] == c).collect())
}

#[test]
fn the_cube_scene_shows_every_pixel_of_its_axes() {
    let text = cube_text();
    let (full, bare) = (list(&text), list(&without_faces(&text)));
    assert!(without_faces(&text).lines().count() < text.lines().count() - 10);
    let want = axis_pixels(
        render_scene_with(&bare, Resolve::default())
            .unwrap()
            .ram
            .contents(),
    );
    // The axes' lines as the frame shows them alone: 258, 189 and 131
    // pixels (the labels drawn over them take none).
    assert_eq!(want.each_ref().map(|v| v.len()), [258, 189, 131]);
    let h = full.list().height();
    for mode in MODES {
        let got = render_scene_with(&full, mode).unwrap();
        assert_eq!(axis_pixels(got.ram.contents()), want, "{mode:?}");
        for rows in [1, 7, 16, 64, h] {
            let got = render_scene_bands_with(&full, rows, mode).unwrap();
            assert_eq!(
                axis_pixels(got.ram.contents()),
                want,
                "{mode:?}, bands of {rows}"
            );
        }
    }
}

// ---------------------------------------------------------------------
// Scenes against the reference

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

fn pipeline(projection: impl Into<Projection>, eye: Point3, target: Point3, thick: f64) -> P {
    let mut pipe = P::new(projection, Viewport::centred(W, H).unwrap());
    pipe.set_view(&View::look_at(eye, target).unwrap()).unwrap();
    pipe.set_thickness(Coord::from_bits((thick * 16.0) as i16));
    pipe
}

fn persp(eye: Point3, target: Point3, thick: f64) -> P {
    let f = Perspective::from_fov(Angle::from_degrees(60), W, q(1.0), q(100.0)).unwrap();
    pipeline(f, eye, target, thick)
}

fn ortho(eye: Point3, target: Point3, thick: f64) -> P {
    let o = Orthographic::new(q(8.0), q(1.0), q(100.0)).unwrap();
    pipeline(o, eye, target, thick)
}

/// The polygons the geometry stage delivers: vertices, colour, and
/// whether a point or a line became it.
#[derive(Default)]
struct Record(Vec<(Vec<Vertex3>, Rgb888, bool)>);

impl PolygonSink for Record {
    type Error = core::convert::Infallible;
    fn polygon(&mut self, v: &[Vertex3], c: Rgb888, two: bool) -> Result<(), Self::Error> {
        self.0.push((v.to_vec(), c, two));
        Ok(())
    }
}

/// The reference's picture of `faces` (face `k` in `color_of(k)`) on
/// `pipe`: the delivered polygons as fans of triangles (rounded to 1/16
/// px, a quad is planar only within rounding, and the reference takes
/// planar polygons alone), points and lines marked.
fn reference(pipe: &P, faces: &[Vec<Point3>]) -> (Vec<Option<usize>>, usize) {
    let mut rec = Record::default();
    let mut twin = pipe.clone();
    for (k, f) in faces.iter().enumerate() {
        twin.polygon(f, color_of(k), &mut rec).unwrap();
    }
    let (mut polys, mut owner, mut lifted) = (Vec::new(), Vec::new(), Vec::new());
    for (v, c, two) in &rec.0 {
        let mut poly: Vec<(i32, i32, i32)> = v
            .iter()
            .map(|v| (v.x.units(), v.y.units(), v.z.units()))
            .collect();
        if !drawn(&poly) {
            assert!(*two, "a culled face was delivered");
            poly.reverse();
        }
        for k in 1..poly.len() - 1 {
            let t = vec![poly[0], poly[k], poly[k + 1]];
            if drawn(&t) {
                polys.push(Poly3 {
                    poly: t,
                    clip: None,
                });
                owner.push(index_of(*c).unwrap());
                lifted.push(*two);
            }
        }
    }
    let want = resolve_lifted(&polys, &lifted, W.into(), H.into())
        .into_iter()
        .map(|r| r.map(|k| owner[k]))
        .collect();
    (want, rec.0.len())
}

/// Collects shipped bands into a frame.
struct Frame(Vec<Rgb888>);

impl BandTarget for Frame {
    type Color = Rgb888;
    type Error = ();
    fn ship(&mut self, _: u16, _: u16, px: &[Rgb888]) -> Result<(), ()> {
        self.0.extend_from_slice(px);
        Ok(())
    }
}

/// The pixels that differ from the reference, of `faces` drawn by a
/// `Scene` on `pipe` in every resolve mode, whole and in bands of 1, 7
/// and 16 rows; and how many pixels the lines and points win.
fn mismatches(pipe: &P, faces: &[Vec<Point3>]) -> (usize, usize) {
    let (want, emitted) = reference(pipe, faces);
    assert!(emitted >= faces.len() / 2, "{emitted} of {}", faces.len());
    let mut build = |b: &mut B<'_, '_>| {
        for (k, f) in faces.iter().enumerate() {
            b.face(f, color_of(k))?;
        }
        Ok(())
    };
    let caps = SceneHeap::fit(
        Capacities {
            segments: 1,
            rows: H as usize,
            runs: W as usize,
            edges: 32,
            ..Capacities::default()
        },
        |mem| {
            let mut scene = Scene::new(mem, pipe.clone())?;
            scene.update(&mut [&mut build])?;
            Ok(scene.usage()?)
        },
    )
    .unwrap();
    let mut heap = SceneHeap::new(caps);
    let mut scene = Scene::new(heap.memory(), pipe.clone()).unwrap();
    scene.update(&mut [&mut build]).unwrap();
    let mut bad = 0;
    let mut count = |px: &[Rgb888], what: &dyn core::fmt::Debug| {
        let got: Vec<Option<usize>> = px.iter().map(|&c| index_of(c)).collect();
        let n = got.iter().zip(&want).filter(|(g, w)| g != w).count();
        if n > 0 {
            eprintln!("{what:?}: {n} pixels differ");
        }
        bad += n;
    };
    for mode in MODES {
        let mut px = vec![Rgb888::WHITE; W as usize * H as usize];
        let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
        scene
            .draw(mode, Some(Rgb888::BLACK), DEFAULT_FONT, &mut fb)
            .unwrap();
        count(&px, &mode);
        for rows in [1u16, 7, 16] {
            let mut band = vec![Rgb888::WHITE; rows as usize * W as usize];
            let mut out = Frame(Vec::new());
            scene
                .draw_bands(mode, Rgb888::BLACK, DEFAULT_FONT, rows, &mut band, &mut out)
                .unwrap();
            count(&out.0, &(mode, rows));
        }
    }
    let lines = want
        .iter()
        .filter(|w| w.is_some_and(|k| faces[k].len() < 3))
        .count();
    (bad, lines)
}

/// A square of side `2s` in the plane through `c` spanned by `u` and
/// `v`, counter-clockwise seen from the side `u × v` points to.
fn square(c: [f64; 3], u: [f64; 3], v: [f64; 3], s: f64) -> Vec<Point3> {
    let at = |a: f64, b: f64| {
        p(
            c[0] + a * u[0] + b * v[0],
            c[1] + a * u[1] + b * v[1],
            c[2] + a * u[2] + b * v[2],
        )
    };
    vec![at(-s, -s), at(s, -s), at(s, s), at(-s, s)]
}

/// Lines in several directions and points on `face` (the square of
/// [`square`]), the lines at `(a, b)` offsets along `u` and `v`.
fn marks(c: [f64; 3], u: [f64; 3], v: [f64; 3], s: f64) -> Vec<Vec<Point3>> {
    let at = |a: f64, b: f64| {
        p(
            c[0] + a * u[0] + b * v[0],
            c[1] + a * u[1] + b * v[1],
            c[2] + a * u[2] + b * v[2],
        )
    };
    let t = 0.8 * s;
    vec![
        vec![at(-t, 0.1), at(t, 0.1)],
        vec![at(0.2, -t), at(0.2, t)],
        vec![at(-t, -t), at(t, 0.7 * t)],
        vec![at(-0.5 * t, t), at(0.6 * t, -t)],
        vec![at(0.5 * t, 0.5 * t)],
        vec![at(-0.5 * t, -0.3 * t)],
    ]
}

#[test]
fn lines_and_points_on_tilted_faces_show_as_the_reference_shows_them() {
    let mut total = 0;
    // Faces tilted from facing the eye to seen at a slant, lines of 1 to 3 px.
    for (k, tilt) in [0.0f64, 25.0, 45.0, 60.0].into_iter().enumerate() {
        let t = tilt.to_radians();
        let (u, v) = ([1.0, 0.0, 0.0], [0.0, t.cos(), -t.sin()]);
        let face = square([0.0, 0.0, 0.0], u, v, 3.0);
        let mut faces = vec![face];
        faces.extend(marks([0.0, 0.0, 0.0], u, v, 3.0));
        // A second face beside it, turned about the vertical axis.
        let (u2, v2) = ([t.cos(), 0.0, t.sin()], [0.0, 1.0, 0.0]);
        faces.push(square([4.0, 0.5, -1.0], u2, v2, 1.5));
        // Its marks before it: the order in the list does not matter.
        let mut before = marks([4.0, 0.5, -1.0], u2, v2, 1.5);
        before.append(&mut faces);
        let faces = before;
        let thick = [1.0, 1.5, 2.0, 3.0][k];
        for pipe in [
            persp(p(1.0, 1.5, 9.0), p(1.0, 0.0, 0.0), thick),
            persp(p(-4.0, 3.0, 7.0), p(1.0, 0.0, 0.0), thick),
            ortho(p(2.0, 2.0, 10.0), p(1.0, 0.0, 0.0), thick),
        ] {
            let (bad, shown) = mismatches(&pipe, &faces);
            assert_eq!(bad, 0, "tilt {tilt}");
            total += shown;
        }
    }
    assert!(total > 2000, "{total}");
}

/// The six faces of a box, counter-clockwise seen from outside, and its
/// twelve edges as lines: each edge shared by two faces, seen along one
/// or both of them, or hidden behind the box.
fn wire_box((x0, y0, z0): (f64, f64, f64), (x1, y1, z1): (f64, f64, f64)) -> Vec<Vec<Point3>> {
    let mut faces = vec![
        vec![p(x0, y0, z1), p(x1, y0, z1), p(x1, y1, z1), p(x0, y1, z1)],
        vec![p(x1, y0, z0), p(x0, y0, z0), p(x0, y1, z0), p(x1, y1, z0)],
        vec![p(x1, y0, z1), p(x1, y0, z0), p(x1, y1, z0), p(x1, y1, z1)],
        vec![p(x0, y0, z0), p(x0, y0, z1), p(x0, y1, z1), p(x0, y1, z0)],
        vec![p(x0, y1, z1), p(x1, y1, z1), p(x1, y1, z0), p(x0, y1, z0)],
        vec![p(x0, y0, z0), p(x1, y0, z0), p(x1, y0, z1), p(x0, y0, z1)],
    ];
    let c = |i: usize| p([x0, x1][i & 1], [y0, y1][i >> 1 & 1], [z0, z1][i >> 2 & 1]);
    for a in 0..8 {
        for bit in [1, 2, 4] {
            if a & bit == 0 {
                faces.push(vec![c(a), c(a | bit)]);
            }
        }
    }
    faces
}

#[test]
fn lines_along_edges_that_faces_share_show_as_the_reference_shows_them() {
    let mut total = 0;
    for (k, orbit) in (0..360).step_by(40).enumerate() {
        let a = (orbit as f64 + 10.0).to_radians();
        let eye = p(9.0 * a.sin(), 5.0 + (k % 3) as f64, 9.0 * a.cos());
        let target = p(0.0, 0.5, 0.0);
        let mut faces = wire_box((-1.5, -1.0, -1.0), (1.5, 2.0, 1.0));
        // A ground plate under the box, inside the window, and lines on
        // it from the box.
        faces.push(vec![
            p(-3.0, -1.0, 3.0),
            p(3.0, -1.0, 3.0),
            p(3.0, -1.0, -3.0),
            p(-3.0, -1.0, -3.0),
        ]);
        faces.push(vec![p(-1.5, -1.0, 1.0), p(-1.5, -1.0, 2.5)]);
        faces.push(vec![p(1.5, -1.0, 1.0), p(2.5, -1.0, 1.0)]);
        for pipe in [persp(eye, target, 1.5), ortho(eye, target, 2.0)] {
            let (bad, shown) = mismatches(&pipe, &faces);
            assert_eq!(bad, 0, "orbit {orbit}");
            total += shown;
        }
    }
    assert!(total > 3000, "{total}");
}

// ---------------------------------------------------------------------
// The edges of the depth range

/// Lines and points at the nearest and the farthest depth of the format,
/// on a face running from one to the other and on a face at the near
/// plane: moved past the near plane, they are drawn, compared exactly
/// and nothing wraps (overflow checks are on), in every resolve mode.
#[test]
fn lines_at_the_ends_of_the_depth_range_show_as_the_reference_shows_them() {
    use scanvert::visible::{
        draw, Active, EdgeSlot, Face, Run, Segment, StoreMemory, Trapezoid, TrapezoidStore,
        Workspace,
    };
    let (w, h) = (64u16, 48u16);
    let (near, far) = (i16::MIN as i32, i16::MAX as i32);
    // A rectangle counter-clockwise as displayed, its depth `z(x)`.
    let rect = |x0: i32, y0: i32, x1: i32, y1: i32, z: &dyn Fn(i32) -> i32| {
        vec![
            (x0, y0, z(x0)),
            (x0, y1, z(x0)),
            (x1, y1, z(x1)),
            (x1, y0, z(x1)),
        ]
    };
    let ramp = |x: i32| near + (x * (far - near)) / 1024;
    // Each polygon, and whether a point or a line became it.
    type Marked = (Vec<(i32, i32, i32)>, bool);
    let polys: Vec<Marked> = vec![
        // The ramp from the near plane (x = 0) to the far one (x = 64 px).
        (rect(0, 0, 1024, 400, &ramp), false),
        // A face at the near plane.
        (rect(0, 400, 1024, 768, &|_| near), false),
        // Lines on them: at the near plane at the ramp's near end, at the
        // far plane at its far end, along the ramp, and across the flat
        // face; a point on the flat face.
        (rect(0, 40, 40, 360, &|_| near), true),
        (rect(984, 40, 1024, 360, &|_| far), true),
        (rect(0, 180, 1024, 204, &ramp), true),
        (rect(100, 560, 900, 584, &|_| near), true),
        (rect(500, 640, 540, 680, &|_| near), true),
    ];
    let (want, lifted): (Vec<Poly3>, Vec<bool>) = polys
        .iter()
        .map(|(p, l)| {
            (
                Poly3 {
                    poly: p.clone(),
                    clip: None,
                },
                *l,
            )
        })
        .unzip();
    let want = resolve_lifted(&want, &lifted, w.into(), h.into());
    let shown = want.iter().filter(|k| k.is_some_and(|k| k >= 2)).count();
    assert!(shown > 200, "{shown}");
    let mut traps = vec![Trapezoid::EMPTY; 64];
    let mut faces = [Face::EMPTY; 16];
    let mut segs = [Segment::EMPTY; 1];
    let mut rows = vec![0u16; h as usize];
    let mut slots = [EdgeSlot::EMPTY; 8];
    let mut store = TrapezoidStore::new(
        StoreMemory {
            trapezoids: &mut traps,
            faces: &mut faces,
            segments: &mut segs,
            rows: &mut rows,
            edges: &mut slots,
        },
        w,
        h,
    )
    .unwrap();
    let clip = scanvert::raster::clip::ClipRect::full(w, h);
    for (k, (p, line)) in polys.iter().enumerate() {
        let v = p.iter().map(|&v| host_tests::harness3d::vertex3(v));
        let n = match line {
            true => store.add_point_or_line(0, v, color_of(k), &clip),
            false => store.add_polygon(0, v, color_of(k), &clip),
        };
        assert!(n.unwrap() > 0);
    }
    let (mut active, mut runs) = (vec![Active::EMPTY; 16], vec![Run::EMPTY; w as usize]);
    for mode in MODES {
        let mut px = vec![Rgb888::WHITE; w as usize * h as usize];
        let mut fb = FrameBuffer::new(&mut px, w, h).unwrap();
        let mut ws = Workspace::new(&mut active, &mut runs);
        draw(&store, &mut ws, mode, &mut fb, Some(Rgb888::BLACK)).unwrap();
        let got: Vec<Option<usize>> = px.iter().map(|&c| index_of(c)).collect();
        assert_eq!(got, want, "{mode:?}");
    }
}
