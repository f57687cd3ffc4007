//! The demo: 3D bars over a map-like grid, with labels, animated, through
//! the simulated display hardware.
//!
//! The scene is built with [`scanvert::scene::Scene`] in three segments,
//! each with its own procedure:
//!
//! | segment | procedure | polygons |
//! |---|---|---|
//! | 0 `ground` | a 10 × 8 grid of map tiles | 80 faces |
//! | 1 `bars` | a bar on every other tile, its height the tile's value; bars over the threshold are highlighted and labelled with their value | 40 bars × 5 faces |
//! | 2 `names` | place names on the tiles without a bar | 8 labels |
//!
//! The animation first raises and lowers the threshold (only `bars` is
//! rebuilt), then moves the camera around the scene (every segment is
//! rebuilt). `scanvert demo` then shows the segment attributes on the
//! last frame ([`attribute_frames`]): the bars highlighted, the names
//! hidden, the bars placed higher, and all undone, with no procedure
//! run. Each frame is drawn into the back bank of a double-buffered
//! [`DualPortRam`] while the refresh controller reads the front bank on
//! its own clock ([`CoSimulation`]); the banks swap in vertical retrace,
//! and the frame the monitor shows next is written as a PNG.
//!
//! The speed figures are measured apart from the simulator (whose cost is
//! the simulation's, not the renderer's): the same frames drawn into a
//! plain [`FrameBuffer`], best of several timed runs.
//!
//! The frame's size is a parameter ([`Size`]; [`DEFAULT_SIZE`], 512 × 256,
//! is `scanvert demo`'s, `--size` another). The segments' procedures write
//! into a [`Sink`]: a segment of the [`Scene`], or a display list
//! ([`frame_list`]) of the same faces and labels in the same order, with
//! the camera, projection and light as `view`, `perspective` and `light`
//! commands of the same bits, which [`Controller`](scanvert::controller::Controller)
//! draws as the `Scene` draws the frame, pixel for pixel (the firmware
//! image's `budget` variant renders these lists in bands).

use crate::dual_port::DualPortRam;
use crate::error::{self, CliError};
use crate::memory::{SceneHeap, Shortfall};
use crate::refresh::{CoSimulation, Frame, RefreshController};
use crate::timing::VideoTiming;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::display_list::{WriteError, Writer};
use scanvert::fixed::Coord;
use scanvert::geometry::{Angle, Light, Perspective, Pipeline, Point3, View, Viewport, Q16};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::port::SpanTarget;
use scanvert::scene::label::DEFAULT_FONT;
use scanvert::scene::{
    Builder, Capacities, DirtyRows, Placement, Procedure, Scene, SceneError, Update,
};
use scanvert::visible::sweep::Resolve;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Frame width of the default size.
pub const WIDTH: u16 = 512;
/// Frame height of the default size.
pub const HEIGHT: u16 = 256;

/// The size of the demo's frame, in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// Width.
    pub width: u16,
    /// Height.
    pub height: u16,
}

/// `scanvert demo`'s size: 512 × 256.
pub const DEFAULT_SIZE: Size = Size {
    width: WIDTH,
    height: HEIGHT,
};

impl Size {
    /// Smallest side: the projection's focal length is then several
    /// pixels, and a label fits.
    pub const MIN: u16 = 16;
    /// Largest side: the geometry stage's window (2047 px).
    pub const MAX: u16 = 2047;

    /// `width × height`, or `None` when a side is outside
    /// [`MIN`](Self::MIN)`..=`[`MAX`](Self::MAX).
    pub fn new(width: u16, height: u16) -> Option<Size> {
        let ok = |v: u16| (Self::MIN..=Self::MAX).contains(&v);
        (ok(width) && ok(height)).then_some(Size { width, height })
    }

    /// `WxH` (as `320x240`), in range.
    pub fn parse(s: &str) -> Option<Size> {
        let (w, h) = s.split_once(['x', 'X', '×'])?;
        Size::new(w.parse().ok()?, h.parse().ok()?)
    }
}

impl std::fmt::Display for Size {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}
/// Depth of the transform stack.
const DEPTH: usize = 8;
/// Vertices of one polygon at every clipping stage.
const N: usize = 16;

type DemoScene<'a> = Scene<'a, DEPTH, N>;
type DemoBuilder<'s, 'a> = Builder<'s, 'a, DEPTH, N>;

/// Tiles across (x) and deep (z).
const TILES: (i32, i32) = (10, 8);
/// Side of a tile, world units.
const TILE: i32 = 4;
/// The segments, by name.
pub const SEGMENTS: [&str; 3] = ["ground", "bars", "names"];

const BACKGROUND: Rgb888 = Rgb888::new(16, 24, 40);

/// What one step of the animation changes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    /// Bars over this value are highlighted and labelled.
    pub threshold: i32,
    /// The camera's angle around the scene, degrees.
    pub orbit: i32,
}

/// The animation: the threshold steps up and down, then the camera
/// moves.
pub fn steps(frames: usize) -> Vec<Step> {
    const THRESHOLDS: [i32; 4] = [30, 50, 70, 50];
    (0..frames)
        .map(|i| {
            if i < THRESHOLDS.len() {
                Step {
                    threshold: THRESHOLDS[i],
                    orbit: 25,
                }
            } else {
                Step {
                    threshold: 50,
                    orbit: 25 + 12 * (i - THRESHOLDS.len() + 1) as i32,
                }
            }
        })
        .collect()
}

/// The value of tile `(i, j)`: 15 … 94, fixed.
fn value(i: i32, j: i32) -> i32 {
    15 + (i * 37 + j * 61 + i * j * 13) % 80
}

fn q(v: f64) -> Q16 {
    Q16::from_bits((v * 65536.0).round() as i32)
}

fn p(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(q(x), q(y), q(z))
}

/// The world x, z of tile `(i, j)`'s corner nearest the origin of the grid.
fn corner(i: i32, j: i32) -> (f64, f64) {
    (
        ((i - TILES.0 / 2) * TILE) as f64,
        ((j - TILES.1 / 2) * TILE) as f64,
    )
}

/// Where the segments' procedures put their faces and labels: a segment
/// of the [`Scene`] ([`Builder`]), or a display list ([`ListSink`]).
pub trait Sink {
    /// Why a face or a label could not be put.
    type Error;
    /// A face of model points, counter-clockwise from its front.
    fn face(&mut self, points: &[Point3], color: Rgb888) -> Result<(), Self::Error>;
    /// A label at the model point `at`.
    fn label(&mut self, at: Point3, text: &str, color: Rgb888) -> Result<(), Self::Error>;
}

impl Sink for DemoBuilder<'_, '_> {
    type Error = SceneError;
    fn face(&mut self, points: &[Point3], color: Rgb888) -> Result<(), SceneError> {
        Builder::face(self, points, color).map(|_| ())
    }
    fn label(&mut self, at: Point3, text: &str, color: Rgb888) -> Result<(), SceneError> {
        Builder::label(self, at, text, color).map(|_| ())
    }
}

/// The segments as display-list commands: `face` and `label`, each after
/// a `color` when its colour is not the one in force.
#[derive(Debug)]
pub struct ListSink<'w, 'b> {
    writer: &'w mut Writer<'b>,
    color: Option<Rgb888>,
}

impl ListSink<'_, '_> {
    fn color(&mut self, c: Rgb888) -> Result<(), WriteError> {
        if self.color != Some(c) {
            self.writer.color(c)?;
            self.color = Some(c);
        }
        Ok(())
    }
}

impl Sink for ListSink<'_, '_> {
    type Error = WriteError;
    fn face(&mut self, points: &[Point3], color: Rgb888) -> Result<(), WriteError> {
        self.color(color)?;
        self.writer.face(points.iter().copied())
    }
    fn label(&mut self, at: Point3, text: &str, color: Rgb888) -> Result<(), WriteError> {
        self.color(color)?;
        self.writer.label(at, text)
    }
}

/// A box on the ground from `(x0, z0)` to `(x1, z1)`, `h` high: its top
/// and four sides, counter-clockwise seen from outside (no bottom: it
/// stands on the ground).
fn bar<S: Sink>(
    b: &mut S,
    (x0, z0, x1, z1): (f64, f64, f64, f64),
    h: f64,
    c: Rgb888,
) -> Result<(), S::Error> {
    let faces = [
        [p(x0, h, z1), p(x1, h, z1), p(x1, h, z0), p(x0, h, z0)],
        [p(x0, 0.0, z1), p(x1, 0.0, z1), p(x1, h, z1), p(x0, h, z1)],
        [p(x1, 0.0, z0), p(x0, 0.0, z0), p(x0, h, z0), p(x1, h, z0)],
        [p(x1, 0.0, z1), p(x1, 0.0, z0), p(x1, h, z0), p(x1, h, z1)],
        [p(x0, 0.0, z0), p(x0, 0.0, z1), p(x0, h, z1), p(x0, h, z0)],
    ];
    for f in &faces {
        b.face(f, c)?;
    }
    Ok(())
}

/// Segment 0: the map tiles.
fn ground<S: Sink>(b: &mut S) -> Result<(), S::Error> {
    for j in 0..TILES.1 {
        for i in 0..TILES.0 {
            let (x0, z0) = corner(i, j);
            let (x1, z1) = (x0 + TILE as f64, z0 + TILE as f64);
            let c = match (i + j) % 3 {
                0 => Rgb888::new(120, 170, 90),
                1 => Rgb888::new(150, 190, 110),
                _ => Rgb888::new(200, 190, 140),
            };
            b.face(
                &[
                    p(x0, 0.0, z1),
                    p(x1, 0.0, z1),
                    p(x1, 0.0, z0),
                    p(x0, 0.0, z0),
                ],
                c,
            )?;
        }
    }
    Ok(())
}

/// Segment 1: the bars, highlighted and labelled over `threshold`.
fn bars<S: Sink>(b: &mut S, threshold: i32) -> Result<(), S::Error> {
    for j in 0..TILES.1 {
        for i in 0..TILES.0 {
            if (i + j) % 2 != 0 {
                continue;
            }
            let v = value(i, j);
            let (x, z) = corner(i, j);
            let h = v as f64 / 10.0;
            let over = v > threshold;
            let c = if over {
                Rgb888::new(230, 90, 50)
            } else {
                Rgb888::new(70, 110, 200)
            };
            bar(b, (x + 1.0, z + 1.0, x + 3.0, z + 3.0), h, c)?;
            if over {
                b.label(p(x + 1.0, h + 0.3, z + 3.0), &v.to_string(), Rgb888::WHITE)?;
            }
        }
    }
    Ok(())
}

/// Segment 2: place names on tiles without a bar.
fn names<S: Sink>(b: &mut S) -> Result<(), S::Error> {
    const NAMES: [(&str, i32, i32); 8] = [
        ("Leiden", 1, 0),
        ("Delft", 5, 0),
        ("Gouda", 2, 3),
        ("Utrecht", 6, 3),
        ("Haarlem", 0, 5),
        ("Zwolle", 4, 5),
        ("Arnhem", 9, 2),
        ("Breda", 7, 6),
    ];
    for (name, i, j) in NAMES {
        let (x, z) = corner(i, j);
        b.label(p(x + 0.5, 0.0, z + 3.0), name, Rgb888::new(255, 255, 160))?;
    }
    Ok(())
}

/// The projection's horizontal field of view, degrees; near and far
/// planes, world units.
const FOV: i32 = 55;
const NEAR: f64 = 1.0;
const FAR: f64 = 200.0;
/// Toward the light, and its share in percent.
const LIGHT: ((f64, f64, f64), u8) = ((1.0, 3.0, 2.0), 70);
/// Points and lines, 1/16 px (the demo draws none).
const THICKNESS: i16 = 24;

fn perspective(size: Size) -> Result<Perspective, CliError> {
    Perspective::from_fov(Angle::from_degrees(FOV), size.width, q(NEAR), q(FAR))
        .map_err(|e| error::input(Path::new("demo"), e))
}

fn light() -> Light {
    let ((x, y, z), percent) = LIGHT;
    Light::new([q(x).to_bits(), q(y).to_bits(), q(z).to_bits()], percent).expect("light")
}

fn view(orbit: i32) -> View {
    let a = (orbit as f64).to_radians();
    let (r, h) = (40.0, 30.0);
    View::look_at(p(r * a.sin(), h, r * a.cos()), p(0.0, 3.0, 0.0)).expect("eye is not the target")
}

/// The caller's memory of the demo scene at one size: as large as the
/// frames it will show need, found by running them
/// ([`SceneHeap::fit`]), and no larger.
struct Memory {
    size: Size,
    heap: SceneHeap,
}

impl Memory {
    /// Memory for the scene at `size` showing `steps` in turn.
    fn new(size: Size, steps: &[Step]) -> Result<Memory, CliError> {
        let fail = |e: &dyn std::fmt::Display| error::input(Path::new("demo"), e);
        let pipe = pipeline(size)?;
        let start = Capacities {
            segments: SEGMENTS.len(),
            rows: size.height as usize,
            runs: size.width as usize,
            edges: N,
            ..Capacities::default()
        };
        let caps = SceneHeap::fit(start, |mem| {
            let mut scene = Scene::new(mem, pipe.clone())?;
            let mut most = Capacities::default();
            let mut last = None;
            for &step in steps {
                apply(&mut scene, last, step)?;
                most = most.max(scene.needed()?);
                last = Some(step);
            }
            Ok(most)
        })
        .map_err(|e| fail(&e))?;
        Ok(Memory {
            size,
            heap: SceneHeap::new(caps),
        })
    }

    fn scene(&mut self) -> Result<DemoScene<'_>, CliError> {
        let pipe = pipeline(self.size)?;
        Scene::new(self.heap.memory(), pipe).map_err(|e| error::input(Path::new("demo"), e))
    }
}

/// The demo's pipeline at `size`: its projection, window, light and line
/// thickness.
fn pipeline(size: Size) -> Result<Pipeline<DEPTH, N>, CliError> {
    let fail = |e: &dyn std::fmt::Display| error::input(Path::new("demo"), e);
    let window = Viewport::centred(size.width, size.height).map_err(|e| fail(&e))?;
    let mut pipe = Pipeline::new(perspective(size)?, window);
    pipe.set_light(light());
    pipe.set_thickness(Coord::from_bits(THICKNESS));
    Ok(pipe)
}

/// Rebuilds what `step` changed since `last` and returns what the update
/// did.
fn advance(scene: &mut DemoScene<'_>, last: Option<Step>, step: Step) -> Result<Update, CliError> {
    apply(scene, last, step).map_err(|e| error::input(Path::new("demo"), e))
}

/// [`advance`], marking in `dirty` the rows whose content the update
/// changed (`Scene::update_marking`, with `scratch` of two words a row).
fn advance_marking(
    scene: &mut DemoScene<'_>,
    last: Option<Step>,
    step: Step,
    dirty: &mut DirtyRows<'_>,
    scratch: &mut [u64],
) -> Result<Update, CliError> {
    apply_marking(scene, last, step, Some((dirty, scratch)))
        .map_err(|e| error::input(Path::new("demo"), e))
}

/// [`advance`], failing with what the scene says.
fn apply(scene: &mut DemoScene<'_>, last: Option<Step>, step: Step) -> Result<Update, Shortfall> {
    apply_marking(scene, last, step, None)
}

/// [`apply`], marking the rows it changed when given a bit set and scratch.
fn apply_marking(
    scene: &mut DemoScene<'_>,
    last: Option<Step>,
    step: Step,
    marks: Option<(&mut DirtyRows<'_>, &mut [u64])>,
) -> Result<Update, Shortfall> {
    if last.map(|l| l.orbit) != Some(step.orbit) {
        scene.set_view(&view(step.orbit))?;
    }
    if last.map(|l| l.threshold) != Some(step.threshold) {
        scene.invalidate(1)?;
    }
    let mut g = |s: &mut DemoBuilder<'_, '_>| ground(s);
    let mut b = |s: &mut DemoBuilder<'_, '_>| bars(s, step.threshold);
    let mut n = |s: &mut DemoBuilder<'_, '_>| names(s);
    let procs: &mut [&mut dyn Procedure<DEPTH, N>] = &mut [&mut g, &mut b, &mut n];
    Ok(match marks {
        Some((dirty, scratch)) => scene.update_marking(procs, DEFAULT_FONT, dirty, scratch)?,
        None => scene.update(procs)?,
    })
}

fn draw<T>(scene: &mut DemoScene<'_>, target: &mut T) -> scanvert::scene::Frame
where
    T: SpanTarget<Color = Rgb565, Error = core::convert::Infallible>,
{
    match scene.draw(
        Resolve::default(),
        Some(Rgb565::from(BACKGROUND)),
        DEFAULT_FONT,
        target,
    ) {
        Ok(f) => f,
        // The workspace holds every trapezoid the store can.
        Err(e) => panic!("demo workspace too small: {e}"),
    }
}

/// Rows of `width` pixels where `after` differs from `before`; all of
/// them when there is no `before`.
fn rows_changed(before: &[Rgb565], after: &[Rgb565], width: u16) -> u32 {
    let w = usize::from(width);
    if before.len() != after.len() {
        return (after.len() / w) as u32;
    }
    before
        .chunks_exact(w)
        .zip(after.chunks_exact(w))
        .filter(|(a, b)| a != b)
        .count() as u32
}

/// Median and most of rows marked per row changed, over `frames` of
/// `(marked, changed)`; a frame where no row changed counts its marks.
fn marking_ratios(frames: &[(u32, u32)]) -> Option<(f64, f64)> {
    let mut r: Vec<f64> = frames
        .iter()
        .map(|&(m, c)| f64::from(m) / f64::from(c.max(1)))
        .collect();
    r.sort_by(f64::total_cmp);
    Some((*r.get(r.len() / 2)?, *r.last()?))
}

/// Frames per second of `f`, best of five runs of about 0.1 s each.
fn rate(mut f: impl FnMut()) -> f64 {
    let mut n = 1u32;
    loop {
        let t = Instant::now();
        for _ in 0..n {
            f();
        }
        if t.elapsed().as_secs_f64() > 0.1 {
            break;
        }
        n *= 2;
    }
    (0..5)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..n {
                f();
            }
            n as f64 / t.elapsed().as_secs_f64()
        })
        .fold(0.0, f64::max)
}

/// One frame of the animation, as shown.
#[derive(Debug)]
pub struct DemoFrame {
    /// What changed.
    pub step: Step,
    /// What the scene update did.
    pub update: Update,
    /// Trapezoids in the store.
    pub trapezoids: usize,
    /// What drawing did.
    pub drawn: scanvert::scene::Frame,
    /// The frame the monitor showed after the swap.
    pub shown: Frame,
    /// Per segment: times it was emptied so far.
    pub rebuilt: [u32; 3],
    /// Rows the update marked as changed (`Scene::update_marking`): what a
    /// panel that keeps its pixels would be sent. Every row on the first
    /// frame, since the panel starts unknown.
    pub marked: u32,
    /// Rows whose pixels differ from the last frame shown (every row on
    /// the first).
    pub changed: u32,
}

/// Runs the animation of `frames` frames through the simulator, at the
/// default size.
pub fn animate(frames: usize) -> Result<Vec<DemoFrame>, CliError> {
    animate_at(DEFAULT_SIZE, frames)
}

/// Runs the animation of `frames` frames through the simulator at `size`.
/// Holds every frame: for a few small ones (tests); [`animate_each`] hands
/// each over as it is made.
pub fn animate_at(size: Size, frames: usize) -> Result<Vec<DemoFrame>, CliError> {
    let mut out = Vec::with_capacity(frames);
    animate_each(size, frames, |f| {
        out.push(f);
        Ok(())
    })?;
    Ok(out)
}

/// Runs the animation of `frames` frames through the simulator at `size`,
/// handing each frame to `each` as soon as the monitor has shown it, in
/// order, and stopping at the first error `each` returns. Only one frame
/// shown is held at a time: the co-simulation keeps the newest frame
/// read out, not all of them.
pub fn animate_each(
    size: Size,
    frames: usize,
    mut each: impl FnMut(DemoFrame) -> Result<(), CliError>,
) -> Result<(), CliError> {
    let steps = steps(frames);
    let mut mem = Memory::new(size, &steps)?;
    let mut scene = mem.scene()?;
    let (w, h) = (size.width, size.height);
    let mut ram = DualPortRam::double_buffered(w, h);
    let mut refresh = RefreshController::new(VideoTiming::for_frame(w, h));
    let mut co = CoSimulation::new(&mut ram, &mut refresh).keeping_last();
    let mut last = None;
    let mut bits = vec![0u32; DirtyRows::words(h)];
    let mut dirty = DirtyRows::new(&mut bits, h).expect("a bit for every row");
    let mut scratch = vec![0u64; 2 * usize::from(h)];
    let mut before: Vec<Rgb565> = Vec::new();
    // The panel starts unknown: every row is sent first.
    dirty.mark_all();
    for step in steps {
        let update = advance_marking(&mut scene, last, step, &mut dirty, &mut scratch)?;
        let marked = dirty.count() as u32;
        dirty.clear();
        last = Some(step);
        let drawn = draw(&mut scene, &mut co);
        co.request_swap();
        co.wait_for_swap();
        // The banks swap in the retrace at the end of the frame being read
        // out, so that frame still shows the last render; the next one is
        // the first to show this one.
        co.wait_for_frame();
        co.wait_for_frame();
        let shown = co.frames().last().cloned().expect("a frame was read out");
        let changed = rows_changed(&before, shown.pixels(), w);
        before = shown.pixels().to_vec();
        let rebuilt =
            std::array::from_fn(|s| scene.store().segment(s).map_or(0, |g| g.counters().clears));
        each(DemoFrame {
            step,
            update,
            trapezoids: scene.store().len(),
            drawn,
            shown,
            rebuilt,
            marked,
            changed,
        })?;
    }
    Ok(())
}

/// The frame of `step` drawn from scratch into a plain frame buffer: what
/// the monitor must show for it.
pub fn reference_frame(step: Step) -> Result<Vec<Rgb565>, CliError> {
    reference_frame_at(DEFAULT_SIZE, step)
}

/// [`reference_frame`] at `size`.
pub fn reference_frame_at(size: Size, step: Step) -> Result<Vec<Rgb565>, CliError> {
    let mut mem = Memory::new(size, &[step])?;
    let mut scene = mem.scene()?;
    advance(&mut scene, None, step)?;
    let (w, h) = (size.width, size.height);
    let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
    draw(&mut scene, &mut fb);
    Ok(pixels)
}

/// Speeds on the host, frames per second: `(camera moves, threshold
/// changes, nothing changes)`.
pub fn speeds() -> Result<(f64, f64, f64), CliError> {
    speeds_at(DEFAULT_SIZE)
}

/// [`speeds`] at `size`.
pub fn speeds_at(size: Size) -> Result<(f64, f64, f64), CliError> {
    // The camera turns a degree at a time and the threshold takes 30, 50
    // and 70 at any angle: the memory is sized for all of them.
    let all: Vec<Step> = (0..360)
        .flat_map(|orbit| [30, 50, 70].map(|threshold| Step { threshold, orbit }))
        .collect();
    let mut mem = Memory::new(size, &all)?;
    let mut scene = mem.scene()?;
    let (w, h) = (size.width, size.height);
    let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
    let mut last = None;
    let mut error = None;
    let mut run = |scene: &mut DemoScene<'_>, step: Step, fb: &mut FrameBuffer<'_, Rgb565>| {
        if let Err(e) = advance(scene, last, step) {
            error = Some(e);
        }
        last = Some(step);
        draw(scene, fb);
    };
    let mut orbit = 0;
    let camera = rate(|| {
        orbit = (orbit + 1) % 360;
        run(
            &mut scene,
            Step {
                threshold: 50,
                orbit,
            },
            &mut fb,
        );
    });
    let mut k = 0;
    let threshold = rate(|| {
        k += 1;
        run(
            &mut scene,
            Step {
                threshold: 30 + 20 * (k % 3),
                orbit,
            },
            &mut fb,
        );
    });
    let still = rate(|| {
        run(
            &mut scene,
            Step {
                threshold: 30 + 20 * (k % 3),
                orbit,
            },
            &mut fb,
        );
    });
    match error {
        Some(e) => Err(e),
        None => Ok((camera, threshold, still)),
    }
}

/// `scanvert demo`: writes `frames` PNGs into `dir` and returns the report.
pub fn run(dir: &Path, frames: usize, measure: bool) -> Result<String, CliError> {
    run_at(DEFAULT_SIZE, dir, frames, measure)
}

/// `scanvert demo --size WxH`: [`run`] at `size`. Each frame's PNG is
/// written as soon as the frame is shown, and its line of the report made
/// then, so that no more than one frame is held at a time.
pub fn run_at(size: Size, dir: &Path, frames: usize, measure: bool) -> Result<String, CliError> {
    std::fs::create_dir_all(dir).map_err(|e| error::io(dir, e))?;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "demo: {} bars over a map of {} tiles, with labels, {}x{}, double-buffered through the simulator",
        TILES.0 * TILES.1 / 2,
        TILES.0 * TILES.1,
        size.width,
        size.height
    );
    let mut prev = [0u32; 3];
    let mut marks = Vec::new();
    let mut trapezoids = 0;
    let mut i = 0;
    animate_each(size, frames, |f| {
        let path: PathBuf = dir.join(format!("frame-{i:02}.png"));
        let png = crate::image::encode_png(&f.shown).map_err(|e| error::io(&path, e))?;
        crate::output::write_output(&path, &png)?;
        let names: Vec<&str> = (0..3)
            .filter(|&s| f.rebuilt[s] != prev[s])
            .map(|s| SEGMENTS[s])
            .collect();
        prev = f.rebuilt;
        trapezoids += f.trapezoids;
        let _ = writeln!(
            s,
            "frame {i}: threshold {:2}, camera at {:3}°: segments regenerated {} ({}): {} polygons, {} visible, cut into {} trapezoids; {} trapezoids drawn, {} runs, {} labels; rows marked {} ({} changed) -> {}",
            f.step.threshold,
            f.step.orbit,
            f.update.regenerated,
            names.join(", "),
            f.update.given,
            f.update.polygons,
            f.update.trapezoids,
            f.trapezoids,
            f.drawn.visible.runs,
            f.drawn.labels.drawn,
            f.marked,
            f.changed,
            crate::error::shown(&path)
        );
        marks.push((f.marked, f.changed));
        i += 1;
        Ok(())
    })?;
    if let Some(average) = trapezoids.checked_div(i) {
        let _ = writeln!(s, "trapezoids per frame: {average} on average");
    }
    if let Some(&last) = steps(frames).last() {
        for (change, update, pixels, marked, changed) in attribute_frames(size, last)? {
            let path: PathBuf = dir.join(format!("frame-{i:02}.png"));
            let png = crate::image::encode_pixels(size.width.into(), size.height.into(), &pixels)
                .map_err(|e| error::io(&path, e))?;
            crate::output::write_output(&path, &png)?;
            let _ = writeln!(
                s,
                "frame {i}: {change}: procedures run {}, segments re-cut {} ({} trapezoids); rows marked {marked} ({changed} changed) -> {}",
                update.regenerated,
                update.recut,
                update.trapezoids,
                crate::error::shown(&path)
            );
            marks.push((marked, changed));
            i += 1;
        }
    }
    if let Some((median, most)) = marking_ratios(&marks) {
        let _ = writeln!(
            s,
            "rows marked per row changed: median {median:.2}, most {most:.2} ({} frames)",
            marks.len()
        );
    }
    if measure {
        let (camera, threshold, still) = speeds_at(size)?;
        let _ = writeln!(
            s,
            "frames/s on this host (plain frame buffer, best of 5): camera moving {camera:.0} (all 3 segments regenerated), threshold changing {threshold:.0} (1 segment), nothing changing {still:.0} (draw only); the classic display ran 3"
        );
    }
    Ok(s)
}

/// The segment attributes on the scene of `step`: the bars highlighted,
/// the names hidden, the bars placed 3 units higher, then each undone.
/// For each change: what it was, what it did (no procedure runs: the
/// placement re-cuts the bars from their record), the frame drawn
/// after it, the rows `Scene::marking` marked for it and the rows whose
/// pixels it changed. The last frame is `step`'s own.
pub fn attribute_frames(size: Size, step: Step) -> Result<Vec<AttributeFrame>, CliError> {
    let fail = |e: &dyn std::fmt::Display| error::input(Path::new("demo"), e);
    // Sized by running the changes: the bars placed higher take other
    // rows and cover other faces.
    let pipe = pipeline(size)?;
    let start = Capacities {
        segments: SEGMENTS.len(),
        rows: size.height as usize,
        runs: size.width as usize,
        edges: N,
        ..Capacities::default()
    };
    let caps = SceneHeap::fit(start, |mut mem| {
        let mut records = vec![0u8; RECORDS];
        let mut scene = Scene::new(mem.reborrow(), pipe.clone())?;
        scene.keep_records(&mut records);
        apply(&mut scene, None, step)?;
        let mut most = scene.needed()?;
        for (_, _, change) in ATTRIBUTE_CHANGES {
            change(&mut scene)?;
            most = most.max(scene.needed()?);
        }
        Ok(most)
    })
    .map_err(|e| fail(&e))?;
    let mut mem = Memory {
        size,
        heap: SceneHeap::new(caps),
    };
    let mut records = vec![0u8; RECORDS];
    let mut scene = mem.scene()?;
    scene.keep_records(&mut records);
    advance(&mut scene, None, step)?;
    let (w, h) = (size.width, size.height);
    let mut out = Vec::new();
    let mut bits = vec![0u32; DirtyRows::words(h)];
    let mut dirty = DirtyRows::new(&mut bits, h).expect("a bit for every row");
    let mut before = vec![Rgb565::BLACK; w as usize * h as usize];
    draw(
        &mut scene,
        &mut FrameBuffer::new(&mut before, w, h).expect("frame"),
    );
    for (what, segment, change) in ATTRIBUTE_CHANGES {
        let update = scene
            .marking(segment, DEFAULT_FONT, &mut dirty, change)
            .map_err(|e| fail(&e))?;
        let marked = dirty.count() as u32;
        dirty.clear();
        let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
        let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
        draw(&mut scene, &mut fb);
        let changed = rows_changed(&before, &pixels, w);
        before.clone_from(&pixels);
        out.push((what, update, pixels, marked, changed));
    }
    Ok(out)
}

/// One frame of [`attribute_frames`]: the change, what it did, the
/// frame drawn after it, the rows marked for it and the rows it changed.
pub type AttributeFrame = (&'static str, Update, Vec<Rgb565>, u32, u32);

/// Bytes of the demo's segment records: room for all of them (a face of
/// four points takes 51 bytes, and the demo has 280). A record that did
/// not fit would make the placement run the bars' procedure, which the
/// tests rule out.
const RECORDS: usize = 1 << 16;

type AttributeChange = fn(&mut DemoScene<'_>) -> Result<Update, SceneError>;

/// Frames [`attribute_frames`] draws, one a change.
pub const ATTRIBUTE_FRAMES: usize = 6;

/// The changes of [`attribute_frames`], in order, with the segment each
/// changes.
const ATTRIBUTE_CHANGES: [(&str, usize, AttributeChange); ATTRIBUTE_FRAMES] = [
    ("highlight bars #ffd700", 1, |s| {
        s.set_highlight(1, Some(Rgb888::new(255, 215, 0)))
    }),
    ("hide names", 2, |s| s.set_visible(2, false)),
    ("place bars 3 units higher", 1, |s| {
        s.place(
            1,
            Placement::translation(Q16::ZERO, Q16::from_int(3), Q16::ZERO),
        )
    }),
    ("place bars back", 1, |s| s.place(1, Placement::IDENTITY)),
    ("show names", 2, |s| s.set_visible(2, true)),
    ("highlight bars off", 1, |s| s.set_highlight(1, None)),
];

/// The demo's scene at `step`, built from scratch, handed to `f` with the
/// demo's background: what the band tests and benchmarks draw, in the
/// scene's workspace or in workspaces of their own.
pub fn with_scene<R>(
    step: Step,
    f: impl FnOnce(&mut Scene<'_, DEPTH, N>, Rgb565) -> R,
) -> Result<R, CliError> {
    with_scene_at(DEFAULT_SIZE, step, f)
}

/// [`with_scene`] at `size`.
pub fn with_scene_at<R>(
    size: Size,
    step: Step,
    f: impl FnOnce(&mut Scene<'_, DEPTH, N>, Rgb565) -> R,
) -> Result<R, CliError> {
    let mut mem = Memory::new(size, &[step])?;
    let mut scene = mem.scene()?;
    advance(&mut scene, None, step)?;
    Ok(f(&mut scene, Rgb565::from(BACKGROUND)))
}

/// The demo's `frames` steps on one scene: each step's changes applied
/// (the camera set, the bars' segment invalidated) and the stale segments
/// rebuilt by `update(scene, procedures)` (`Scene::update` or a variant
/// of it), then `frame(scene, step)`. For the band tests and benchmarks.
pub fn drive(
    frames: usize,
    update: impl FnMut(
        &mut Scene<'_, DEPTH, N>,
        &mut [&mut dyn Procedure<DEPTH, N>],
    ) -> Result<Update, scanvert::scene::UpdateError>,
    frame: impl FnMut(&mut Scene<'_, DEPTH, N>, Step, Update, Rgb565),
) -> Result<(), CliError> {
    drive_at(DEFAULT_SIZE, frames, update, frame)
}

/// [`drive`] at `size`.
pub fn drive_at(
    size: Size,
    frames: usize,
    mut update: impl FnMut(
        &mut Scene<'_, DEPTH, N>,
        &mut [&mut dyn Procedure<DEPTH, N>],
    ) -> Result<Update, scanvert::scene::UpdateError>,
    mut frame: impl FnMut(&mut Scene<'_, DEPTH, N>, Step, Update, Rgb565),
) -> Result<(), CliError> {
    let fail = |e: &dyn std::fmt::Display| crate::error::input(Path::new("demo"), e);
    let steps = steps(frames);
    let mut mem = Memory::new(size, &steps)?;
    let mut scene = mem.scene()?;
    let mut last: Option<Step> = None;
    for step in steps {
        if last.map(|l| l.orbit) != Some(step.orbit) {
            scene.set_view(&view(step.orbit)).map_err(|e| fail(&e))?;
        }
        if last.map(|l| l.threshold) != Some(step.threshold) {
            scene.invalidate(1).map_err(|e| fail(&e))?;
        }
        let mut g = |s: &mut DemoBuilder<'_, '_>| ground(s);
        let mut b = |s: &mut DemoBuilder<'_, '_>| bars(s, step.threshold);
        let mut n = |s: &mut DemoBuilder<'_, '_>| names(s);
        let procs: &mut [&mut dyn Procedure<DEPTH, N>] = &mut [&mut g, &mut b, &mut n];
        let u = update(&mut scene, procs).map_err(|e| fail(&e))?;
        frame(&mut scene, step, u, Rgb565::from(BACKGROUND));
        last = Some(step);
    }
    Ok(())
}

/// The frame of `step` at `size` as a version-2 display list: `clear`
/// with the background, the `perspective`, `light`, `thickness` and
/// `view` the scene is drawn with (their bits, so the geometry is the
/// same), then each segment after a `segment` command, its faces and
/// labels in the order its procedure makes them. Rendered by
/// [`Controller`](scanvert::controller::Controller), in full or in bands,
/// it is the picture [`Scene`] draws of that step, pixel for pixel.
pub fn frame_list(size: Size, step: Step) -> Result<Vec<u8>, CliError> {
    let fail = |e: WriteError| error::input(Path::new("demo"), format_args!("frame list: {e}"));
    // Every command is at most 64 bytes, a label 16 and its text (3
    // digits or a name): far below this.
    let mut buf = vec![0u8; 1 << 17];
    let mut w = Writer::new(&mut buf, size.width, size.height).map_err(fail)?;
    w.clear(BACKGROUND).map_err(fail)?;
    w.perspective(Angle::from_degrees(FOV), q(NEAR), q(FAR))
        .map_err(fail)?;
    let ((x, y, z), percent) = LIGHT;
    w.light(p(x, y, z), percent).map_err(fail)?;
    w.thickness(Coord::from_bits(THICKNESS)).map_err(fail)?;
    let v = view(step.orbit);
    w.view(v.eye, v.yaw, v.pitch).map_err(fail)?;
    let mut sink = ListSink {
        writer: &mut w,
        color: None,
    };
    for segment in 0..SEGMENTS.len() {
        sink.writer.segment(segment as u16).map_err(fail)?;
        match segment {
            0 => ground(&mut sink),
            1 => bars(&mut sink, step.threshold),
            _ => names(&mut sink),
        }
        .map_err(fail)?;
    }
    Ok(w.finish().to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::memory::ListMemory;
    use scanvert::display_list::DisplayList;

    /// `frame_list` rendered by the controller into a black frame.
    fn list_pixels(size: Size, step: Step) -> Vec<Rgb565> {
        let bytes = frame_list(size, step).expect("the list is written");
        let list = DisplayList::new_checked(&bytes).expect("a valid list");
        let mut memory = ListMemory::for_list(&list).expect("within the pools");
        let (w, h) = (size.width, size.height);
        let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
        let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
        memory.controller().render(&list, &mut fb).expect("renders");
        pixels
    }

    /// Every frame of the animation, as the `Scene` draws it after its
    /// updates, equals its display list rendered by the controller.
    #[test]
    fn frame_lists_draw_the_scene_s_pictures() {
        for size in [DEFAULT_SIZE, Size::new(320, 240).unwrap()] {
            let mut frames = Vec::new();
            drive_at(
                size,
                8,
                |scene, procs| scene.update(procs),
                |scene, step, _, bg| {
                    let (w, h) = (size.width, size.height);
                    let mut pixels = vec![Rgb565::BLACK; w as usize * h as usize];
                    let mut fb = FrameBuffer::new(&mut pixels, w, h).expect("frame");
                    scene
                        .draw(Resolve::default(), Some(bg), DEFAULT_FONT, &mut fb)
                        .expect("draws");
                    frames.push((step, pixels));
                },
            )
            .expect("the demo runs");
            for (i, (step, want)) in frames.iter().enumerate() {
                let got = list_pixels(size, *step);
                let differ = got.iter().zip(want).filter(|(a, b)| a != b).count();
                assert_eq!(differ, 0, "{size} frame {i}: {differ} pixels differ");
            }
        }
    }

    /// `scanvert demo --size 320x240` writes frames of that size; a bad
    /// size, or one with `--race`, is a usage error.
    #[test]
    fn the_command_line_takes_a_size() {
        let dir = std::env::temp_dir().join(format!("scanvert-demo-size-{}", std::process::id()));
        let args = |more: &[&str]| -> Vec<String> {
            [
                "demo",
                "--out",
                dir.to_str().unwrap(),
                "--frames",
                "1",
                "--no-speed",
            ]
            .iter()
            .chain(more)
            .map(|s| s.to_string())
            .collect()
        };
        let report = crate::cli::run(&args(&["--size", "320x240"])).expect("runs");
        assert!(report.contains("320x240"), "{report}");
        let png = std::fs::read(dir.join("frame-00.png")).expect("a frame");
        // The IHDR chunk: width and height, big-endian, at bytes 16 and 20.
        let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
        assert_eq!((be(16), be(20)), (320, 240));
        std::fs::remove_dir_all(&dir).unwrap();
        for bad in [
            &["--size", "320"][..],
            &["--size"],
            &["--size", "320x240", "--race", "100"],
        ] {
            let e = crate::cli::run(&args(bad)).expect_err("a usage error");
            assert_eq!(e.status, crate::cli::EXIT_USAGE, "{bad:?}");
        }
    }

    #[test]
    fn sizes_parse_in_range() {
        assert_eq!(Size::parse("320x240"), Size::new(320, 240));
        assert_eq!(Size::parse("512×256"), Some(DEFAULT_SIZE));
        for bad in [
            "320",
            "x240",
            "0x240",
            "15x240",
            "2048x16",
            "320x-1",
            "320 x 240",
        ] {
            assert_eq!(Size::parse(bad), None, "{bad}");
        }
    }
}
