//! Your model on a 240 × 240 panel: a Wavefront OBJ or STL file read as
//! `scanvert import` reads it, turned about its vertical axis, and drawn
//! band by band (16 rows, 7.5 KiB) with no frame buffer.
//!
//! The model's vertices are moved and scaled as `scanvert import` fits
//! them (its bounding box centred on the origin, its half-diagonal 10
//! units) and go to the library once a frame through `Builder::mesh`
//! (each vertex transformed once into a vertex table; faces of more than
//! three vertices as fans of triangles), lit, from a fitted three-quarter
//! view. Each frame is drawn with `Scene::draw_bands` into a panel (a
//! host model that keeps the rows it is sent) and compared with the same
//! frame drawn whole into a frame buffer.
//!
//! ```sh
//! cargo run --release -p scanvert-sim --example model_panel [-- MODEL.obj|MODEL.stl]
//! ```
//!
//! Without a file it shows `models/teapot.obj` (the Utah teapot of
//! `testkit::meshes`, 992 triangles).

use scanvert::display_list::Axis;
use scanvert::geometry::{Angle, Light, Perspective, Pipeline, Point3, View, ViewPoint, Viewport};
use scanvert::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::label::DEFAULT_FONT;
use scanvert::scene::{Builder, Capacities, Procedure, Scene, SceneError};
use scanvert::visible::sweep::Resolve;
use scanvert::Q16;
use scanvert_sim::import::{format_of, read, RADIUS};
use scanvert_sim::memory::SceneHeap;

const W: u16 = 240;
const H: u16 = 240;
const ROWS: u16 = 16;
const FRAMES: i32 = 24;
const INK: Rgb888 = Rgb888::new(0xd0, 0xa0, 0x70);

/// The panel: keeps the rows it is sent, and counts them.
struct Panel {
    pixels: Vec<Rgb565>,
    rows: u32,
}

impl BandTarget for Panel {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn ship(&mut self, y: u16, rows: u16, px: &[Rgb565]) -> Result<(), Self::Error> {
        let at = y as usize * W as usize;
        self.pixels[at..at + px.len()].copy_from_slice(px);
        self.rows += rows as u32;
        Ok(())
    }
}

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let default = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/teapot.obj");
    let path = std::env::args().nth(1).unwrap_or_else(|| default.into());
    let bytes = std::fs::read(&path).map_err(|e| format!("{path}: {e}"))?;
    let model = read(format_of(&path, &bytes), &bytes).map_err(|e| format!("{path}: {e}"))?;

    // Fitted as `scanvert import` fits it.
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for v in &model.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k] as f64);
            hi[k] = hi[k].max(v[k] as f64);
        }
    }
    let half = (0..3)
        .map(|k| (hi[k] - lo[k]).powi(2) / 4.0)
        .sum::<f64>()
        .sqrt();
    let scale = if half > 0.0 { RADIUS / half } else { 1.0 };
    let points: Vec<Point3> = model
        .vertices
        .iter()
        .map(|v| {
            let c = |k: usize| q((v[k] as f64 - (lo[k] + hi[k]) / 2.0) * scale);
            Point3::new(c(0), c(1), c(2))
        })
        .collect();
    // Every face as a fan of triangles.
    let mut indices: Vec<u16> = Vec::new();
    for f in &model.faces {
        for k in 1..f.len() - 1 {
            indices.extend([f[0], f[k], f[k + 1]].map(|i| i as u16));
        }
    }
    let mut slots = vec![ViewPoint::EMPTY; points.len()];

    let fov = 45.0f64;
    let distance = RADIUS / (fov.to_radians() / 2.0).tan().atan().sin() * 1.05;
    let eye = [0.55, 0.45, 0.7].map(|d: f64| d / 1.0247 * distance);
    let mut pipeline = Pipeline::new(
        Perspective::from_fov(
            Angle::from_degrees(45),
            W,
            q(distance - RADIUS * 1.1),
            q(distance + RADIUS * 1.1),
        )?,
        Viewport::centred(W, H)?,
    );
    pipeline.set_light(Light::new([1, 2, 3], 70)?);
    pipeline.set_view(&View::look_at(
        Point3::new(q(eye[0]), q(eye[1]), q(eye[2])),
        Point3::new(Q16::ZERO, Q16::ZERO, Q16::ZERO),
    )?)?;

    // The procedure: the model, turned by `turn` degrees.
    let mut turn = 0;
    let mut draw_model = |b: &mut Builder<'_, '_, 4, 16>, turn: i32| -> Result<(), SceneError> {
        b.rotate(Axis::Y, Angle::from_degrees(turn))?;
        b.mesh(&points, &indices, 3, INK, &mut slots).map(|_| ())
    };
    // The scene's memory: the most any frame needs.
    let start = Capacities {
        segments: 1,
        rows: H as usize,
        runs: W as usize,
        edges: 16,
        ..Capacities::default()
    };
    let caps = SceneHeap::fit(start, |mem| {
        let mut scene = Scene::new(mem, pipeline.clone())?;
        let mut most = Capacities::default();
        for frame in 0..FRAMES {
            let mut proc = |b: &mut Builder<'_, '_, 4, 16>| draw_model(b, frame * 360 / FRAMES);
            scene.invalidate_all();
            scene.update(&mut [&mut proc as &mut dyn Procedure<4, 16>])?;
            most = most.max(scene.needed()?);
        }
        Ok(most)
    })?;
    let mut heap = SceneHeap::new(caps);
    let mut scene = Scene::new(heap.memory(), pipeline)?;

    let mut band = vec![Rgb565::BLACK; ROWS as usize * W as usize];
    let mut panel = Panel {
        pixels: vec![Rgb565::RED; W as usize * H as usize],
        rows: 0,
    };
    let mut whole = vec![Rgb565::BLACK; W as usize * H as usize];
    let (mut most_traps, mut least_traps) = (0, u32::MAX);
    for frame in 0..FRAMES {
        let mut proc = |b: &mut Builder<'_, '_, 4, 16>| draw_model(b, turn);
        scene.invalidate(0)?;
        scene.update(&mut [&mut proc as &mut dyn Procedure<4, 16>])?;
        let f = scene.draw_bands(
            Resolve::default(),
            Rgb565::BLACK,
            DEFAULT_FONT,
            ROWS,
            &mut band,
            &mut panel,
        )?;
        let mut fb = FrameBuffer::new(&mut whole, W, H).ok_or("frame")?;
        scene.draw(
            Resolve::default(),
            Some(Rgb565::BLACK),
            DEFAULT_FONT,
            &mut fb,
        )?;
        assert!(
            panel.pixels == whole,
            "frame {frame}: the bands differ from the whole frame"
        );
        let traps = scene.needed()?.trapezoids as u32;
        most_traps = most_traps.max(traps);
        least_traps = least_traps.min(traps);
        let _ = f;
        turn += 360 / FRAMES;
    }
    let name = std::path::Path::new(&path)
        .file_name()
        .map_or(path.clone(), |n| n.to_string_lossy().into_owned());
    println!(
        "{name}: {} vertices, {} triangles, turned in {FRAMES} frames of {W} x {H}",
        points.len(),
        indices.len() / 3
    );
    println!(
        "bands of {ROWS} rows: {} rows sent, every frame equal to the whole frame",
        panel.rows
    );
    println!("trapezoids a frame: {least_traps} to {most_traps}");
    println!(
        "memory: band buffer {} B, scene {} trapezoids and {} faces",
        band.len() * 2,
        caps.trapezoids,
        caps.faces
    );
    Ok(())
}
