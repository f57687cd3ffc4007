//! The mesh workloads of `testkit::meshes` (icosphere, torus, terrain,
//! teapot) as display lists, the way `scanvert import` writes them: the
//! `v`/`f` list and its `face` form render to the same pixels at a few
//! sizes, whole frame and in 16-row bands, in every resolve; and the
//! library's `Builder::mesh` draws the picture of the exact reference
//! (`testkit::reference3d`) on small meshes.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use host_tests::harness3d::{color_of, index_of};
use scanvert::fixed::Vertex3;
use scanvert::geometry::{
    Angle, Perspective, Pipeline, Point3, PolygonSink, View, ViewPoint, Viewport, Q16,
};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::label::DEFAULT_FONT;
use scanvert::scene::{Builder, Capacities, Procedure, Scene, SceneError};
use scanvert::visible::sweep::Resolve;
use scanvert_sim::cli::{render_scene_bands_with, render_scene_with, Scene as Listed};
use scanvert_sim::import::{list, Model};
use scanvert_sim::memory::SceneHeap;
use std::path::Path;
use testkit::meshes::{faces_form, Kind, Mesh};
use testkit::reference3d::{drawn, resolve, Poly3};

const W: u16 = 240;
const H: u16 = 240;

/// The list `scanvert import` writes for `m`, 240 × 240.
fn mesh_list(m: &Mesh) -> String {
    let model = Model {
        vertices: m.vertices_f32(),
        faces: m.faces(),
    };
    list(&model, W, H, Rgb888::new(0xd0, 0xa0, 0x70))
}

fn pixels(text: &str, resolve: Resolve, band_rows: Option<u16>) -> Vec<Rgb565> {
    let scene = Listed::from_bytes(Path::new("mesh.dl"), text.as_bytes().to_vec())
        .expect("the list assembles");
    let r = match band_rows {
        None => render_scene_with(&scene, resolve),
        Some(rows) => render_scene_bands_with(&scene, rows, resolve),
    }
    .expect("renders");
    r.ram.contents().to_vec()
}

const RESOLVES: [Resolve; 4] = [
    Resolve::Crossing,
    Resolve::Bisect,
    Resolve::Paint,
    Resolve::Auto,
];

#[test]
fn each_mesh_as_v_and_f_is_the_mesh_as_faces() {
    for kind in Kind::ALL {
        for &p in &kind.sweep()[..3] {
            let m = kind.make(p);
            let v_f = mesh_list(&m);
            let faces = faces_form(&v_f);
            assert!(!faces.contains("\nf ") && faces.contains("\nface "));
            let want = pixels(&faces, Resolve::Crossing, None);
            let lit = want.iter().filter(|&&p| p != Rgb565::BLACK).count();
            assert!(lit > 5_000, "{kind:?} {p}: the mesh shows ({lit} pixels)");
            for resolve in RESOLVES {
                for rows in [None, Some(16)] {
                    let what = format!(
                        "{} {} triangles, {resolve:?}, bands {rows:?}",
                        kind.name(),
                        m.triangles.len()
                    );
                    assert!(
                        pixels(&v_f, resolve, rows) == want,
                        "{what}: v/f differs from face"
                    );
                    assert!(
                        pixels(&faces, resolve, rows) == want,
                        "{what}: face differs from face"
                    );
                }
            }
        }
    }
}

/// The delivered polygons of a pipeline, as delivered.
#[derive(Default)]
struct Record(Vec<(Vec<Vertex3>, Rgb888)>);

impl PolygonSink for Record {
    type Error = core::convert::Infallible;
    fn polygon(&mut self, v: &[Vertex3], c: Rgb888, _two: bool) -> Result<(), Self::Error> {
        self.0.push((v.to_vec(), c));
        Ok(())
    }
}

type P = Pipeline<8, 32>;

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

/// `m` drawn by `Builder::mesh` (one call a triangle, each in a colour of
/// its own, no light) against the exact reference of the polygons the
/// same pipeline delivers for the same triangles; the pixels that differ.
fn check(m: &Mesh, yaw: f64) -> (usize, usize) {
    let (s, c) = (yaw.to_radians().sin(), yaw.to_radians().cos());
    // Scaled into the unit ball, which the view holds whole.
    let r = m
        .vertices
        .iter()
        .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        .fold(0.0, f64::max);
    let points: Vec<Point3> = m
        .vertices
        .iter()
        .map(|v| v.map(|x| x / r))
        .map(|v| Point3::new(q(v[0] * c + v[2] * s), q(v[1]), q(v[2] * c - v[0] * s)))
        .collect();
    let mut pipe = P::new(
        Perspective::from_fov(Angle::from_degrees(45), W, q(0.5), q(20.0)).unwrap(),
        Viewport::centred(W, H).unwrap(),
    );
    pipe.set_view(
        &View::look_at(
            Point3::new(q(1.6), q(1.5), q(2.6)),
            Point3::new(q(0.0), q(0.0), q(0.0)),
        )
        .unwrap(),
    )
    .unwrap();
    let mut rec = Record::default();
    let mut twin = pipe.clone();
    for (k, t) in m.triangles.iter().enumerate() {
        let f: Vec<Point3> = t.iter().map(|&i| points[i as usize]).collect();
        twin.polygon(&f, color_of(k), &mut rec).unwrap();
    }
    let mut slots = vec![ViewPoint::EMPTY; points.len()];
    let mut build = |b: &mut Builder<'_, '_, 8, 32>| -> Result<(), SceneError> {
        for (k, t) in m.triangles.iter().enumerate() {
            let ix: Vec<u16> = t.iter().map(|&i| i as u16).collect();
            b.mesh(&points, &ix, 3, color_of(k), &mut slots)?;
        }
        Ok(())
    };
    let start = Capacities {
        segments: 1,
        rows: H as usize,
        runs: W as usize,
        edges: 32,
        ..Capacities::default()
    };
    let caps = SceneHeap::fit(start, |mem| {
        let mut scene = Scene::new(mem, pipe.clone())?;
        scene.update(&mut [&mut build as &mut dyn Procedure<8, 32>])?;
        Ok(scene.needed()?)
    })
    .unwrap();
    let mut heap = SceneHeap::new(caps);
    let mut scene = Scene::new(heap.memory(), pipe.clone()).unwrap();
    scene
        .update(&mut [&mut build as &mut dyn Procedure<8, 32>])
        .unwrap();
    let mut px = vec![Rgb888::WHITE; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
    scene
        .draw(
            Resolve::default(),
            Some(Rgb888::BLACK),
            DEFAULT_FONT,
            &mut fb,
        )
        .unwrap();
    let got: Vec<Option<usize>> = px.iter().map(|&c| index_of(c)).collect();

    let mut polys = Vec::new();
    let mut owner = Vec::new();
    for (v, c) in &rec.0 {
        let poly: Vec<(i32, i32, i32)> = v
            .iter()
            .map(|v| (v.x.units(), v.y.units(), v.z.units()))
            .collect();
        if drawn(&poly) {
            polys.push(Poly3 { poly, clip: None });
            owner.push(index_of(*c).unwrap());
        }
    }
    let want: Vec<Option<usize>> = resolve(&polys, W.into(), H.into())
        .into_iter()
        .map(|r| r.map(|k| owner[k]))
        .collect();
    let covered = want.iter().filter(|w| w.is_some()).count();
    let differ = got.iter().zip(&want).filter(|(g, w)| g != w).count();
    (differ, covered)
}

#[test]
fn small_meshes_through_builder_mesh_are_the_exact_reference() {
    for (kind, p) in [
        (Kind::Icosphere, 2),
        (Kind::Torus, 12),
        (Kind::Terrain, 6),
        (Kind::Teapot, 2),
    ] {
        let m = kind.make(p);
        for yaw in [0.0, 37.0, 131.0] {
            let (differ, covered) = check(&m, yaw);
            assert_eq!(differ, 0, "{kind:?} {p} at {yaw}°");
            assert!(covered > 3_000, "{kind:?} {p} at {yaw}°: {covered} pixels");
        }
    }
}

/// `models/teapot.obj`, the model the README and the `model_panel`
/// example show: `testkit::meshes::teapot(4)` as OBJ. Written by
/// `UPDATE_MODELS=1 cargo test -p host-tests --test mesh_workloads`; this
/// test fails when it is stale.
#[test]
fn the_example_model_is_current() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../models/teapot.obj");
    let want = testkit::meshes::teapot(4)
        .obj("the Utah teapot (Newell's patches, 4 x 4 a patch), from testkit::meshes::teapot(4)");
    if std::env::var_os("UPDATE_MODELS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &want).unwrap();
    }
    let got = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        got == want,
        "models/teapot.obj is stale (UPDATE_MODELS=1 cargo test -p host-tests --test mesh_workloads)"
    );
}
