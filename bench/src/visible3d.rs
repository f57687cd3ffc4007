//! The 3D scenes timed: scanvert's scan-line visible surfaces in both
//! resolve modes, two plain z-buffers at the same precision, and the
//! bandwidth limit, each drawing every view of a scene per pass.
//!
//! Every contender clears its RGB565 frame buffer at the start of each
//! frame (one `slice::fill`); scanvert then draws with no background fill
//! (`visible::draw(…, None)`), so that every contender does the same clear.

use crate::numbers::thousands;
use crate::time_fns;
use core::mem::size_of;
use scanvert::{
    controller::{edges_3d, needs, Needs},
    display_list::{DisplayList, Writer},
    fixed::{Vertex, Vertex3},
    pixelcolor::{PixelColor, Rgb565, Rgb888, RgbColor},
    port::framebuffer::FrameBuffer,
    port::{Span, SpanTarget},
    raster::clip::ClipRect,
    raster::edge::Edge,
    raster::scan::Rasterizer,
    visible::rle::Run,
    visible::store::{Face, Segment, StoreMemory, TrapezoidStore},
    visible::trapezoid::{EdgeSlot, Trapezoid},
    visible::{self, Active, Resolve, VisibleStats, Workspace},
};
use std::convert::Infallible;
use std::hint::black_box;
use std::time::Duration;
use testkit::reference::{covers, pixel_box};
use testkit::reference3d;
use testkit::scenes3d::{Scene, Version, H, VIEWS, W};

/// Each timed run repeats a pass (all views) for at least this long.
const MIN_RUN: Duration = Duration::from_millis(30);
/// Timed runs per contender, round-robin; best kept.
pub const ROUNDS: usize = 7;
/// The same for the depth sweep and the P3/P4 split, whose ratios are
/// read across scenes: more runs, for a best run less often disturbed.
pub const ROUNDS_DEPTH: usize = 15;

/// The colour of face `k`: its index, so that a picture tells which face
/// won each pixel (never black, the background).
fn color_of(k: usize) -> Rgb888 {
    Rgb888::new(k as u8, (k >> 8) as u8, 0xff)
}

/// The face a colour belongs to.
fn index_of(c: Rgb888) -> Option<u32> {
    (c.b() == 0xff).then_some(c.r() as u32 | (c.g() as u32) << 8)
}

/// Error of one contender on one scene, against [`reference3d`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Err3 {
    /// Mismatched pixels per 1000 covered pixels, over all views.
    pub per_1000: f64,
    /// Most mismatched pixels in one view (frame).
    pub worst: u64,
    /// All mismatched pixels.
    pub total: u64,
}

/// One line of a 3D table.
#[derive(Debug)]
pub struct Row3 {
    /// Which version.
    pub version: Version,
    /// Faces per frame.
    pub faces: usize,
    /// Contender name.
    pub contender: &'static str,
    /// Trapezoids per frame (scanvert's cut, mean over the views).
    pub trapezoids: f64,
    /// Milliseconds per frame, everything included.
    pub ms: f64,
    /// Milliseconds per frame of resolve + decode alone (scanvert only).
    pub resolve_ms: Option<f64>,
    /// The 16-bit z-buffer's time over this one's: above 1 is faster.
    pub vs_z: f64,
    /// `None` for the bandwidth limit.
    pub err: Option<Err3>,
    /// Bytes of working state (frame buffer not counted) and how.
    pub mem: (usize, String),
}

/// What a scene is like, from scanvert's cut and resolution.
#[derive(Debug)]
pub struct SceneStats {
    /// Which version.
    pub version: Version,
    /// Faces per frame.
    pub faces: usize,
    /// The contender the default resolve (`Resolve::Auto`) is: painting
    /// or crossing points, as it settles for the scene's first view.
    pub default: &'static str,
    /// Trapezoids per frame, mean over the views.
    pub trapezoids: f64,
    /// Covered pixels per frame (the reference's), mean.
    pub covered: f64,
    /// Summed pixels of the faces over covered pixels (depth complexity).
    pub complexity: f64,
    /// Most trapezoids on one row (the active list needed).
    pub max_active: u32,
    /// Intersecting spans per frame, mean.
    pub intersecting: f64,
    /// Subdivisions per frame, mean: (`Crossing`, `Bisect`).
    pub splits: (f64, f64),
}

/// Contender names.
pub const CROSSING: &str = "scanvert `Resolve::Crossing`";
/// Contender name.
pub const BISECT: &str = "scanvert `Resolve::Bisect`";
/// Contender name.
pub const PAINT: &str = "scanvert `Resolve::Paint` (far to near, exact)";
/// Contender name.
pub const Z16: &str = "z-buffer, `i16` depth (Q12.4)";
/// Contender name.
pub const Z32: &str = "z-buffer, `i32` depth (Q12.4 + 14 bits)";
/// Contender name.
pub const LIMIT: &str = "`slice::fill`, same pixel count (bandwidth limit)";

/// The caller's memory of one [`TrapezoidStore`].
struct StoreMem {
    traps: Vec<Trapezoid>,
    faces: Vec<Face>,
    segs: Vec<Segment>,
    rows: Vec<u16>,
    edges: Vec<EdgeSlot>,
}

/// What a store needs for the most demanding view of `scene`: each view
/// as a display list of `poly3`s (every face is front-facing) through
/// `controller::needs`.
fn needs_of(scene: &Scene) -> Needs {
    let mut most = Needs::default();
    for view in &scene.views {
        let size = 64 + view.iter().map(|f| 8 + 6 * f.len()).sum::<usize>();
        let mut buf = vec![0u8; size];
        let mut w = Writer::new(&mut buf, W, H).expect("frame size");
        for f in view {
            w.poly3(f.iter().copied()).expect("sized");
        }
        let list = DisplayList::new_checked(w.finish()).expect("Writer output is valid");
        let mut scratch = vec![EdgeSlot::EMPTY; edges_3d(&list)];
        let n = needs(&list, &mut scratch).expect("within the pools' limits");
        most.trapezoids = most.trapezoids.max(n.trapezoids);
        most.faces = most.faces.max(n.faces);
        most.edge_slots = most.edge_slots.max(n.edge_slots);
        most.rows = most.rows.max(n.rows);
    }
    most
}

impl StoreMem {
    fn for_scene(scene: &Scene) -> StoreMem {
        let need = needs_of(scene);
        StoreMem {
            traps: vec![Trapezoid::EMPTY; need.trapezoids],
            faces: vec![Face::EMPTY; need.faces],
            segs: vec![Segment::EMPTY; 1],
            rows: vec![0; need.rows],
            edges: vec![EdgeSlot::EMPTY; need.edge_slots],
        }
    }

    fn store(&mut self) -> TrapezoidStore<'_> {
        TrapezoidStore::new(
            StoreMemory {
                trapezoids: &mut self.traps,
                faces: &mut self.faces,
                segments: &mut self.segs,
                rows: &mut self.rows,
                edges: &mut self.edges,
            },
            W,
            H,
        )
        .expect("the index has the frame's rows")
    }
}

/// Cuts every face of one view into segment 0 of `store`, emptied first.
#[inline]
fn cut(store: &mut TrapezoidStore<'_>, faces: &[Vec<Vertex3>], clip: &ClipRect) {
    let _ = store.clear_segment(0);
    for (k, f) in faces.iter().enumerate() {
        let r = store.add_polygon(0, f.iter().copied(), color_of(k), clip);
        debug_assert!(r.is_ok());
        let _ = r;
    }
}

/// The caller's memory of one [`Workspace`], sized for `n` trapezoids.
struct WorkMem {
    active: Vec<Active>,
    runs: Vec<Run>,
}

impl WorkMem {
    fn new(n: usize) -> WorkMem {
        WorkMem {
            active: vec![Active::EMPTY; n],
            runs: vec![Run::EMPTY; W as usize],
        }
    }
    fn workspace(&mut self) -> Workspace<'_> {
        Workspace::new(&mut self.active, &mut self.runs)
    }
}

/// Clears `fb` and draws `store` into it with no background fill.
#[inline]
fn draw<C>(
    store: &TrapezoidStore<'_>,
    ws: &mut Workspace<'_>,
    mode: Resolve,
    fb: &mut FrameBuffer<'_, C>,
) -> VisibleStats
where
    C: PixelColor + scanvert::color::ListColor + RgbColor,
{
    let Ok(()) = fb.clear(C::BLACK);
    match visible::draw(store, ws, mode, fb, None) {
        Ok((stats, _)) => stats,
        Err(e) => panic!("the workspace is sized: {e:?}"),
    }
}

/// A cell of a depth buffer.
pub trait DepthCell: Copy + Ord {
    /// The far value a frame starts with.
    const FAR: Self;
    /// The cell's value of a depth in units of 2⁻¹⁴ of a Q12.4 unit.
    fn from_fixed(z: i32) -> Self;
}

impl DepthCell for i16 {
    const FAR: i16 = i16::MAX;
    /// Rounded to Q12.4 (the depths of the scenes are within `i16`).
    #[inline(always)]
    fn from_fixed(z: i32) -> i16 {
        (((z >> 13) + 1) >> 1) as i16
    }
}

impl DepthCell for i32 {
    const FAR: i32 = i32::MAX;
    #[inline(always)]
    fn from_fixed(z: i32) -> i32 {
        z
    }
}

/// A face's depth for the z-buffer: `Z(i, j) = z + i·zx + j·zy` at the
/// centre of pixel `(i, j)`, in units of 2⁻¹⁴ of a Q12.4 unit, wrapping
/// in `i32` (the same fixed point as scanvert's resolution; set up here
/// with code of its own).
#[derive(Clone, Copy, Debug, Default)]
pub struct ZPlane {
    pub(crate) z: i32,
    pub(crate) zx: i32,
    pub(crate) zy: i32,
}

/// `n / c` rounded to nearest, `c > 0`, in `i64` when the numbers fit.
#[inline]
fn round_div(n: i128, c: i128) -> i128 {
    let (n2, c2) = (2 * n + c, 2 * c);
    match (i64::try_from(n2), i64::try_from(c2)) {
        (Ok(n2), Ok(c2)) => n2.div_euclid(c2) as i128,
        _ => n2.div_euclid(c2),
    }
}

impl ZPlane {
    /// The plane of a face by Newell's normal `(a, b, c)` through its
    /// first vertex; `None` when it is edge-on (`c = 0`).
    pub fn of(face: &[Vertex3]) -> Option<ZPlane> {
        let (mut a, mut b, mut c) = (0i64, 0i64, 0i64);
        for k in 0..face.len() {
            let (p, q) = (face[k], face[(k + 1) % face.len()]);
            let (x0, y0, z0) = (p.x.units() as i64, p.y.units() as i64, p.z.units() as i64);
            let (x1, y1, z1) = (q.x.units() as i64, q.y.units() as i64, q.z.units() as i64);
            a += (y0 - y1) * (z0 + z1);
            b += (z0 - z1) * (x0 + x1);
            c += (x0 - x1) * (y0 + y1);
        }
        if c == 0 {
            return None;
        }
        if c < 0 {
            (a, b, c) = (-a, -b, -c);
        }
        let p = face[0];
        let (a, b, c) = (a as i128, b as i128, c as i128);
        let d = a * p.x.units() as i128 + b * p.y.units() as i128 + c * p.z.units() as i128;
        // z = (d − a·x − b·y) / c at x = 16i + 8, y = 16j + 8, times 2¹⁴.
        Some(ZPlane {
            z: round_div((d - 8 * a - 8 * b) << 14, c) as i32,
            zx: round_div(-a << 18, c) as i32,
            zy: round_div(-b << 18, c) as i32,
        })
    }
}

/// A z-buffer as a span target: the exact rasteriser's spans, each pixel
/// tested against the depth buffer.
pub struct ZTarget<D, C> {
    depth: Vec<D>,
    pixels: Vec<C>,
    plane: ZPlane,
}

impl<D: DepthCell, C: PixelColor + RgbColor> ZTarget<D, C> {
    fn new() -> Self {
        ZTarget {
            depth: vec![D::FAR; W as usize * H as usize],
            pixels: vec![C::BLACK; W as usize * H as usize],
            plane: ZPlane::default(),
        }
    }

    /// One frame: clears both buffers, then every face.
    #[inline]
    fn frame(&mut self, faces: &[Vec<Vertex3>], inks: &[C], edges: &mut [Edge], clip: &ClipRect) {
        self.depth.fill(D::FAR);
        self.pixels.fill(C::BLACK);
        let mut raster = Rasterizer::new(edges);
        for (f, &ink) in faces.iter().zip(inks) {
            let Some(plane) = ZPlane::of(f) else { continue };
            self.plane = plane;
            let flat = f.iter().map(|v| Vertex { x: v.x, y: v.y });
            let r = raster.fill(flat, clip, ink, self);
            debug_assert!(r.is_ok());
            let _ = r;
        }
    }
}

impl<D: DepthCell, C: PixelColor> SpanTarget for ZTarget<D, C> {
    type Color = C;
    type Error = Infallible;
    fn size(&self) -> (u16, u16) {
        (W, H)
    }
    #[inline]
    fn fill_span(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let base = span.y as usize * W as usize;
        let (a, b) = (base + span.x0 as usize, base + span.x1.min(W) as usize);
        let p = self.plane;
        let mut z =
            p.z.wrapping_add(p.zx.wrapping_mul(span.x0 as i32))
                .wrapping_add(p.zy.wrapping_mul(span.y as i32));
        if let (Some(ds), Some(ps)) = (self.depth.get_mut(a..b), self.pixels.get_mut(a..b)) {
            for (d, px) in ds.iter_mut().zip(ps) {
                let v = D::from_fixed(z);
                if v < *d {
                    *d = v;
                    *px = color;
                }
                z = z.wrapping_add(p.zx);
            }
        }
        Ok(())
    }
}

/// A full frame of every view, as a pass: the segment emptied, every face
/// cut again, the frame cleared, resolved and decoded.
fn full<'a, 'm: 'a>(
    mode: Resolve,
    store: &'a mut TrapezoidStore<'m>,
    scene: &'a Scene,
    capacity: usize,
) -> Box<dyn FnMut() + 'a> {
    let mut work = WorkMem::new(capacity);
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let clip = ClipRect::full(W, H);
    Box::new(move || {
        let mut ws = work.workspace();
        let mut fb = FrameBuffer::new(&mut px, W, H).expect("size");
        for v in &scene.views {
            cut(store, black_box(v), &clip);
            black_box(draw(store, &mut ws, mode, &mut fb));
        }
    })
}

/// Resolve and decode alone, as a pass: the frames of every view where no
/// segment changed since the last.
fn alone<'a, 'm: 'a>(
    mode: Resolve,
    stores: &'a [TrapezoidStore<'m>],
    capacity: usize,
) -> Box<dyn FnMut() + 'a> {
    let mut work = WorkMem::new(capacity);
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    Box::new(move || {
        let mut ws = work.workspace();
        let mut fb = FrameBuffer::new(&mut px, W, H).expect("size");
        for s in stores {
            black_box(draw(s, &mut ws, mode, &mut fb));
        }
    })
}

/// A z-buffer frame of every view, as a pass.
fn zbuffer<'a, D: DepthCell + 'a>(scene: &'a Scene, inks: &'a [Rgb565]) -> Box<dyn FnMut() + 'a> {
    let mut z = ZTarget::<D, Rgb565>::new();
    let mut edges = vec![Edge::EMPTY; scene.max_vertices().max(3)];
    let clip = ClipRect::full(W, H);
    Box::new(move || {
        for v in &scene.views {
            z.frame(black_box(v), inks, &mut edges, &clip);
        }
        black_box(&z.pixels);
    })
}

/// The faces' colours in RGB565.
fn inks_565(scene: &Scene) -> Vec<Rgb565> {
    (0..scene.faces)
        .map(|k| <Rgb565 as scanvert::color::ListColor>::from_rgb888(color_of(k)))
        .collect()
}

/// `--profile-3d MODE PASSES`: the 170-face 3D scene alone, `PASSES`
/// times every view, for counting instructions under callgrind. MODE is
/// `crossing`, `bisect` or `paint` (full frames), `crossing-alone`,
/// `bisect-alone` or `paint-alone` (resolve + decode), `cut` (the cut alone), `z16` or
/// `z32`. `PROFILE_FACES=N` takes the scene of `N` faces instead of 170,
/// and `PROFILE_VERSION=layered` the 2D version instead of the tilted one.
pub fn profile(mode: &str, passes: u32) {
    let faces = std::env::var("PROFILE_FACES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(170);
    let version = match std::env::var("PROFILE_VERSION").as_deref() {
        Ok("layered") | Ok("2D") | Ok("2d") => Version::Layered,
        _ => Version::Tilted,
    };
    let scene = testkit::scenes3d::scene(version, faces);
    let clip = ClipRect::full(W, H);
    let inks = inks_565(&scene);
    let cap = 8 * scene.faces + 64;
    let mut mems: Vec<StoreMem> = (0..VIEWS).map(|_| StoreMem::for_scene(&scene)).collect();
    let mut stores: Vec<TrapezoidStore<'_>> = mems.iter_mut().map(StoreMem::store).collect();
    if mode.ends_with("-alone") {
        for (s, v) in stores.iter_mut().zip(&scene.views) {
            cut(s, v, &clip);
        }
    }
    let mut own = StoreMem::for_scene(&scene);
    let mut store = own.store();
    let mut f: Box<dyn FnMut() + '_> = match mode {
        "crossing" => full(Resolve::Crossing, &mut store, &scene, cap),
        "bisect" => full(Resolve::Bisect, &mut store, &scene, cap),
        "paint" => full(Resolve::Paint, &mut store, &scene, cap),
        "crossing-alone" => alone(Resolve::Crossing, &stores, cap),
        "paint-alone" => alone(Resolve::Paint, &stores, cap),
        "bisect-alone" => alone(Resolve::Bisect, &stores, cap),
        "cut" => Box::new(|| {
            for v in &scene.views {
                cut(&mut store, black_box(v), &clip);
            }
        }),
        "z16" => zbuffer::<i16>(&scene, &inks),
        "z32" => zbuffer::<i32>(&scene, &inks),
        _ => {
            eprintln!("unknown mode {mode}");
            return;
        }
    };
    for _ in 0..passes {
        f();
    }
}

/// Pixels where `shown` (the face per pixel) differs from `want`.
fn mismatches(shown: impl Iterator<Item = Option<u32>>, want: &[Option<u32>]) -> u64 {
    shown.zip(want).filter(|(g, w)| g != *w).count() as u64
}

/// Collects per-view mismatch counts into [`Err3`].
fn err_of(per_view: &[u64], covered: u64) -> Err3 {
    let total: u64 = per_view.iter().sum();
    Err3 {
        per_1000: total as f64 * 1000.0 / covered.max(1) as f64,
        worst: per_view.iter().copied().max().unwrap_or(0),
        total,
    }
}

/// Measures one scene: error of every contender on every view, then the
/// times, round-robin.
pub fn measure(scene: &Scene) -> (Vec<Row3>, SceneStats) {
    let clip = ClipRect::full(W, H);
    let n_px = W as usize * H as usize;

    // The reference, and the pixel counts.
    let want: Vec<Vec<Option<u32>>> = scene
        .views
        .iter()
        .map(|v| reference3d::winners(v, W, H))
        .collect();
    let covered: Vec<usize> = want
        .iter()
        .map(|w| w.iter().filter(|c| c.is_some()).count())
        .collect();
    let covered_all: u64 = covered.iter().map(|&c| c as u64).sum();
    let summed: u64 = scene
        .views
        .iter()
        .flatten()
        .map(|f| {
            let flat: Vec<(i32, i32)> = f.iter().map(|v| (v.x.units(), v.y.units())).collect();
            let (x0, y0, x1, y1) = pixel_box(&flat, 1, W, H);
            let mut k = 0u64;
            for j in y0..y1 {
                for i in x0..x1 {
                    k += covers(&flat, i, j) as u64;
                }
            }
            k
        })
        .sum();

    // scanvert: one store per view, cut once (resolve-alone runs and the
    // error), and what it needs.
    let mut mems: Vec<StoreMem> = (0..VIEWS).map(|_| StoreMem::for_scene(scene)).collect();
    let mut stores: Vec<TrapezoidStore<'_>> = mems.iter_mut().map(StoreMem::store).collect();
    for (s, v) in stores.iter_mut().zip(&scene.views) {
        cut(s, v, &clip);
    }
    let most_traps = stores.iter().map(|s| s.len()).max().unwrap_or(0);
    let trapezoids = stores.iter().map(|s| s.len()).sum::<usize>() as f64 / VIEWS as f64;
    let mut probe = WorkMem::new(most_traps);
    let max_active = stores
        .iter()
        .map(|s| probe.workspace().check(s).expect("sized"))
        .max()
        .unwrap_or(0);
    let most_faces = stores.iter().map(|s| s.face_count()).max().unwrap_or(0);
    // The mode the default resolve (`Resolve::Auto`) takes for the first
    // view, by its trapezoids' mean height.
    let default = stores.first().map_or(CROSSING, |s| {
        let (mut t, mut rows) = (0u32, 0u32);
        for y in 0..s.height() {
            for (_, tr) in s.starting_at(y) {
                t += 1;
                rows += (tr.end() - tr.top()) as u32;
            }
        }
        match Resolve::Auto.settle(t, rows) {
            Resolve::Paint => PAINT,
            _ => CROSSING,
        }
    });

    // Error and statistics of both modes.
    let mut scan_err = Vec::new();
    let mut stats = Vec::new();
    for mode in [Resolve::Crossing, Resolve::Bisect, Resolve::Paint] {
        let mut px = vec![Rgb888::BLACK; n_px];
        let mut per_view = Vec::new();
        let (mut inter, mut splits) = (0u64, 0u64);
        for (s, w) in stores.iter().zip(&want) {
            let mut fb = FrameBuffer::new(&mut px, W, H).expect("size");
            let st = draw(s, &mut probe.workspace(), mode, &mut fb);
            inter += st.intersecting as u64;
            splits += st.splits as u64;
            per_view.push(mismatches(px.iter().map(|&c| index_of(c)), w));
        }
        scan_err.push(err_of(&per_view, covered_all));
        stats.push((inter, splits));
    }
    let scan_mem = {
        let traps = most_traps * size_of::<Trapezoid>();
        let faces = most_faces * size_of::<Face>();
        let act = max_active as usize * (size_of::<Active>());
        let rows_runs = H as usize * size_of::<u16>() + W as usize * size_of::<Run>();
        let other = size_of::<Segment>()
            + scene.max_vertices() * size_of::<EdgeSlot>()
            + size_of::<TrapezoidStore<'_>>()
            + size_of::<Workspace<'_>>();
        (
            traps + faces + act + rows_runs + other,
            format!(
                "trapezoids {} ({most_traps} × {}), faces {} ({most_faces} × {}), active {} ({max_active} × {}), index + runs {}, other {} (segment, edge slots, structs)",
                thousands(traps as f64),
                size_of::<Trapezoid>(),
                thousands(faces as f64),
                size_of::<Face>(),
                thousands(act as f64),
                size_of::<Active>(),
                thousands(rows_runs as f64),
                other
            ),
        )
    };

    // z-buffers: error with index colours.
    let most_v = scene.max_vertices().max(3);
    let mut edges = vec![Edge::EMPTY; most_v];
    let inks888: Vec<Rgb888> = (0..scene.faces).map(color_of).collect();
    let z_err = |edges: &mut [Edge], sixteen: bool| {
        let per_view: Vec<u64> = scene
            .views
            .iter()
            .zip(&want)
            .map(|(v, w)| {
                if sixteen {
                    let mut z = ZTarget::<i16, Rgb888>::new();
                    z.frame(v, &inks888, edges, &clip);
                    mismatches(z.pixels.iter().map(|&c| index_of(c)), w)
                } else {
                    let mut z = ZTarget::<i32, Rgb888>::new();
                    z.frame(v, &inks888, edges, &clip);
                    mismatches(z.pixels.iter().map(|&c| index_of(c)), w)
                }
            })
            .collect();
        err_of(&per_view, covered_all)
    };
    let z16_err = z_err(&mut edges, true);
    let z32_err = z_err(&mut edges, false);
    let z_mem = |cell: usize| {
        let buf = n_px * cell;
        let other = most_v * size_of::<Edge>()
            + size_of::<Rasterizer<'_, Edge>>()
            + size_of::<ClipRect>()
            + size_of::<ZPlane>();
        (
            buf + other,
            format!(
                "depth buffer {} ({W}×{H} × {cell}), other {other} (edge slots, structs)",
                thousands(buf as f64)
            ),
        )
    };

    // The timed passes: every view once.
    let inks565 = inks_565(scene);
    // The stores of the full frames persist from pass to pass, as on a
    // device: each frame empties the segment and cuts every face again.
    let mut full_mems = [
        StoreMem::for_scene(scene),
        StoreMem::for_scene(scene),
        StoreMem::for_scene(scene),
    ];
    let [m0, m1, m2] = &mut full_mems;
    let (mut full_c, mut full_b, mut full_p) = (m0.store(), m1.store(), m2.store());
    let mut limit_px = vec![Rgb565::BLACK; n_px];
    let mut fns: Vec<Box<dyn FnMut() + '_>> = vec![
        full(Resolve::Crossing, &mut full_c, scene, most_traps),
        full(Resolve::Bisect, &mut full_b, scene, most_traps),
        alone(Resolve::Crossing, &stores, most_traps),
        alone(Resolve::Bisect, &stores, most_traps),
        zbuffer::<i16>(scene, &inks565),
        zbuffer::<i32>(scene, &inks565),
        Box::new(|| {
            for &n in &covered {
                limit_px.fill(Rgb565::BLACK);
                black_box(&mut limit_px[..n]).fill(Rgb565::RED);
            }
        }),
        full(Resolve::Paint, &mut full_p, scene, most_traps),
        alone(Resolve::Paint, &stores, most_traps),
    ];
    let secs = time_fns(&mut fns, MIN_RUN, ROUNDS);
    drop(fns);
    let ms: Vec<f64> = secs.iter().map(|s| s * 1e3 / VIEWS as f64).collect();
    let z16_ms = ms[4];

    let row = |contender, ms: f64, resolve_ms, err, mem| Row3 {
        version: scene.version,
        faces: scene.faces,
        contender,
        trapezoids,
        ms,
        resolve_ms,
        vs_z: z16_ms / ms,
        err,
        mem,
    };
    let rows = vec![
        row(
            CROSSING,
            ms[0],
            Some(ms[2]),
            Some(scan_err[0]),
            scan_mem.clone(),
        ),
        row(
            BISECT,
            ms[1],
            Some(ms[3]),
            Some(scan_err[1]),
            scan_mem.clone(),
        ),
        row(PAINT, ms[7], Some(ms[8]), Some(scan_err[2]), scan_mem),
        row(Z16, ms[4], None, Some(z16_err), z_mem(2)),
        row(Z32, ms[5], None, Some(z32_err), z_mem(4)),
        row(LIMIT, ms[6], None, None, (0, "none".into())),
    ];
    let v = VIEWS as f64;
    let st = SceneStats {
        version: scene.version,
        faces: scene.faces,
        default,
        trapezoids,
        covered: covered_all as f64 / v,
        complexity: summed as f64 / covered_all.max(1) as f64,
        max_active,
        intersecting: stats[0].0 as f64 / v,
        splits: (stats[0].1 as f64 / v, stats[1].1 as f64 / v),
    };
    (rows, st)
}

/// The reference of every view, the covered pixels of each, and the
/// faces' pixels summed over all views (each face alone, by the pixel
/// rule).
fn reference_of(scene: &Scene) -> (Vec<Vec<Option<u32>>>, Vec<usize>, u64) {
    let want: Vec<Vec<Option<u32>>> = scene
        .views
        .iter()
        .map(|v| reference3d::winners(v, W, H))
        .collect();
    let covered = want
        .iter()
        .map(|w| w.iter().filter(|c| c.is_some()).count())
        .collect();
    let summed = scene
        .views
        .iter()
        .flatten()
        .map(|f| {
            let flat: Vec<(i32, i32)> = f.iter().map(|v| (v.x.units(), v.y.units())).collect();
            let (x0, y0, x1, y1) = pixel_box(&flat, 1, W, H);
            let mut k = 0u64;
            for j in y0..y1 {
                for i in x0..x1 {
                    k += covers(&flat, i, j) as u64;
                }
            }
            k
        })
        .sum();
    (want, covered, summed)
}

/// Adds up the counters of two resolutions.
fn add_stats(a: &mut VisibleStats, b: &VisibleStats) {
    a.hidden += b.hidden;
    a.empty += b.empty;
    a.single += b.single;
    a.multiple += b.multiple;
    a.intersecting += b.intersecting;
    a.splits += b.splits;
    a.runs += b.runs;
    a.trapezoids += b.trapezoids;
    a.max_active = a.max_active.max(b.max_active);
}

/// One scene of the depth-complexity sweep: scanvert (default mode, full
/// frames) and both z-buffers.
#[derive(Debug)]
pub struct DepthRow {
    /// Which version.
    pub version: Version,
    /// Faces per frame.
    pub faces: usize,
    /// The depth complexity the scene was generated for.
    pub aimed: usize,
    /// Measured: the faces' pixels over the covered pixels, all views.
    pub complexity: f64,
    /// Covered pixels per frame, mean.
    pub covered: f64,
    /// Trapezoids per frame, mean.
    pub trapezoids: f64,
    /// Rows of the trapezoids, summed, per frame (mean): the entries the
    /// sweep steps, sorts and looks through, row by row.
    pub trapezoid_rows: f64,
    /// What the sweep did, summed over the views.
    pub stats: VisibleStats,
    /// Milliseconds per frame: scanvert `Crossing` (cut + resolve +
    /// decode), `i16` z-buffer, `i32` z-buffer.
    pub ms: [f64; 3],
    /// Errors against the reference, in the same order.
    pub err: [Err3; 3],
}

impl DepthRow {
    /// Spans the sweep classified per frame (empty, single, multiple,
    /// intersecting), mean.
    pub fn spans(&self) -> f64 {
        let s = &self.stats;
        (s.empty + s.single + s.multiple + s.intersecting) as f64 / VIEWS as f64
    }
}

/// Measures one scene of the depth sweep.
pub fn measure_depth(scene: &Scene, aimed: usize) -> DepthRow {
    let clip = ClipRect::full(W, H);
    let (want, covered, summed) = reference_of(scene);
    let covered_all: u64 = covered.iter().map(|&c| c as u64).sum();
    let mut mems: Vec<StoreMem> = (0..VIEWS).map(|_| StoreMem::for_scene(scene)).collect();
    let mut stores: Vec<TrapezoidStore<'_>> = mems.iter_mut().map(StoreMem::store).collect();
    for (s, v) in stores.iter_mut().zip(&scene.views) {
        cut(s, v, &clip);
    }
    let most_traps = stores.iter().map(|s| s.len()).max().unwrap_or(0);
    let trapezoids = stores.iter().map(|s| s.len()).sum::<usize>() as f64 / VIEWS as f64;
    let trapezoid_rows = stores
        .iter()
        .map(|s| {
            (0..H)
                .flat_map(|y| s.starting_at(y))
                .map(|(_, t)| (t.end().min(H as i32) - t.top().max(0)).max(0) as u64)
                .sum::<u64>()
        })
        .sum::<u64>() as f64
        / VIEWS as f64;

    // scanvert's error and counters.
    let mut work = WorkMem::new(most_traps);
    let mut px = vec![Rgb888::BLACK; W as usize * H as usize];
    let mut stats = VisibleStats::default();
    let mut per_view = Vec::new();
    for (s, w) in stores.iter().zip(&want) {
        let mut fb = FrameBuffer::new(&mut px, W, H).expect("size");
        let st = draw(s, &mut work.workspace(), Resolve::Crossing, &mut fb);
        add_stats(&mut stats, &st);
        per_view.push(mismatches(px.iter().map(|&c| index_of(c)), w));
    }
    let scan_err = err_of(&per_view, covered_all);
    drop(stores);

    // The z-buffers' errors.
    let mut edges = vec![Edge::EMPTY; scene.max_vertices().max(3)];
    let inks888: Vec<Rgb888> = (0..scene.faces).map(color_of).collect();
    let mut z_err = |sixteen: bool| {
        let per_view: Vec<u64> = scene
            .views
            .iter()
            .zip(&want)
            .map(|(v, w)| {
                if sixteen {
                    let mut z = ZTarget::<i16, Rgb888>::new();
                    z.frame(v, &inks888, &mut edges, &clip);
                    mismatches(z.pixels.iter().map(|&c| index_of(c)), w)
                } else {
                    let mut z = ZTarget::<i32, Rgb888>::new();
                    z.frame(v, &inks888, &mut edges, &clip);
                    mismatches(z.pixels.iter().map(|&c| index_of(c)), w)
                }
            })
            .collect();
        err_of(&per_view, covered_all)
    };
    let (z16_err, z32_err) = (z_err(true), z_err(false));

    let inks565 = inks_565(scene);
    let mut own = StoreMem::for_scene(scene);
    let mut store = own.store();
    let mut fns: Vec<Box<dyn FnMut() + '_>> = vec![
        full(Resolve::Crossing, &mut store, scene, most_traps),
        zbuffer::<i16>(scene, &inks565),
        zbuffer::<i32>(scene, &inks565),
    ];
    let secs = time_fns(&mut fns, MIN_RUN, ROUNDS_DEPTH);
    drop(fns);
    let ms = |k: usize| secs[k] * 1e3 / VIEWS as f64;
    DepthRow {
        version: scene.version,
        faces: scene.faces,
        aimed,
        complexity: summed as f64 / covered_all.max(1) as f64,
        covered: covered_all as f64 / VIEWS as f64,
        trapezoids,
        trapezoid_rows,
        stats,
        ms: [ms(0), ms(1), ms(2)],
        err: [scan_err, z16_err, z32_err],
    }
}

/// One scene's visible-surface time split as J. H. Jackson split his:
/// P3, the sweep producing run-length rows with no pixel written, and P4,
/// the rows decoded into pixels.
#[derive(Debug)]
pub struct SplitRow {
    /// Which version.
    pub version: Version,
    /// Faces per frame.
    pub faces: usize,
    /// Trapezoids per frame, mean.
    pub trapezoids: f64,
    /// Runs per frame, mean.
    pub runs: f64,
    /// P3: `Workspace::resolve` (`Crossing`) into a sink that discards
    /// the rows, ms per frame.
    pub p3_ms: f64,
    /// P4: the frame cleared and the stored rows decoded into it
    /// (`rle::decode_row`), ms per frame.
    pub p4_ms: f64,
    /// Both at once, as the library draws (`visible::draw`, the frame
    /// cleared first), ms per frame.
    pub both_ms: f64,
}

/// The rows of one view's resolution: `(y, first, end)` into the runs.
struct StoredRows {
    rows: Vec<(u16, usize, usize)>,
    runs: Vec<Run>,
    inks: Vec<Rgb565>,
}

impl StoredRows {
    fn of(store: &TrapezoidStore<'_>, ws: &mut Workspace<'_>) -> StoredRows {
        let mut out = StoredRows {
            rows: Vec::new(),
            runs: Vec::new(),
            inks: (0..store.face_count())
                .map(|f| {
                    let c = store.face(f as u16).map_or(Rgb888::BLACK, |f| f.color());
                    <Rgb565 as scanvert::color::ListColor>::from_rgb888(c)
                })
                .collect(),
        };
        let r = ws.resolve(store, Resolve::Crossing, |y, runs| {
            let a = out.runs.len();
            out.runs.extend_from_slice(runs);
            out.rows.push((y, a, out.runs.len()));
            Ok::<(), Infallible>(())
        });
        if let Err(e) = r {
            panic!("the workspace is sized: {e:?}");
        }
        out
    }

    /// Clears `fb` and decodes every row into it, the background left.
    #[inline]
    fn decode(&self, fb: &mut FrameBuffer<'_, Rgb565>) {
        let Ok(()) = fb.clear(Rgb565::BLACK);
        for &(y, a, b) in &self.rows {
            let inks = &self.inks;
            let r = visible::rle::decode_row(
                fb,
                y,
                &self.runs[a..b],
                |k| inks.get(k as usize).copied().unwrap_or(Rgb565::BLACK),
                None,
            );
            let Ok(_) = r;
        }
    }
}

/// Times P3, P4 and both on each of `scenes` (every view, stores cut
/// beforehand), all round-robin together so that the scenes' ratios hold
/// under a changing load, after checking that the stored rows decode to
/// the picture `visible::draw` makes.
pub fn measure_split(scenes: &[&Scene]) -> Vec<SplitRow> {
    let clip = ClipRect::full(W, H);
    let n_px = W as usize * H as usize;
    let mut mems: Vec<Vec<StoreMem>> = scenes
        .iter()
        .map(|sc| (0..VIEWS).map(|_| StoreMem::for_scene(sc)).collect())
        .collect();
    let mut stores: Vec<Vec<TrapezoidStore<'_>>> = mems
        .iter_mut()
        .map(|m| m.iter_mut().map(StoreMem::store).collect())
        .collect();
    for (ss, sc) in stores.iter_mut().zip(scenes) {
        for (s, v) in ss.iter_mut().zip(&sc.views) {
            cut(s, v, &clip);
        }
    }
    let most: Vec<usize> = stores
        .iter()
        .map(|ss| ss.iter().map(|s| s.len()).max().unwrap_or(0))
        .collect();
    let stored: Vec<Vec<StoredRows>> = stores
        .iter()
        .zip(&most)
        .map(|(ss, &m)| {
            let mut work = WorkMem::new(m);
            ss.iter()
                .map(|s| {
                    let rows = StoredRows::of(s, &mut work.workspace());
                    let mut a = vec![Rgb565::BLACK; n_px];
                    let mut b = vec![Rgb565::BLACK; n_px];
                    draw(
                        s,
                        &mut work.workspace(),
                        Resolve::Crossing,
                        &mut FrameBuffer::new(&mut a, W, H).expect("size"),
                    );
                    rows.decode(&mut FrameBuffer::new(&mut b, W, H).expect("size"));
                    assert!(a == b, "stored rows decode to the drawn picture");
                    rows
                })
                .collect()
        })
        .collect();
    let mut fns: Vec<Box<dyn FnMut() + '_>> = Vec::new();
    for ((ss, rows), &m) in stores.iter().zip(&stored).zip(&most) {
        let mut p3_work = WorkMem::new(m);
        let mut p4_px = vec![Rgb565::BLACK; n_px];
        fns.push(Box::new(move || {
            let mut ws = p3_work.workspace();
            for s in ss {
                let r = ws.resolve(black_box(s), Resolve::Crossing, |y, runs| {
                    black_box((y, runs));
                    Ok::<(), Infallible>(())
                });
                black_box(r.is_ok());
            }
        }));
        fns.push(Box::new(move || {
            let mut fb = FrameBuffer::new(&mut p4_px, W, H).expect("size");
            for r in rows {
                black_box(r).decode(&mut fb);
            }
        }));
        fns.push(alone(Resolve::Crossing, ss, m));
    }
    let secs = time_fns(&mut fns, MIN_RUN, ROUNDS_DEPTH);
    drop(fns);
    let ms = |k: usize| secs[k] * 1e3 / VIEWS as f64;
    scenes
        .iter()
        .enumerate()
        .map(|(k, sc)| SplitRow {
            version: sc.version,
            faces: sc.faces,
            trapezoids: stores[k].iter().map(|s| s.len()).sum::<usize>() as f64 / VIEWS as f64,
            runs: stored[k].iter().map(|r| r.runs.len()).sum::<usize>() as f64 / VIEWS as f64,
            p3_ms: ms(3 * k),
            p4_ms: ms(3 * k + 1),
            both_ms: ms(3 * k + 2),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use testkit::scenes3d::scene;

    #[test]
    fn scanvert_and_the_z_buffers_match_the_reference_on_a_small_scene() {
        let s = scene(Version::Tilted, 10);
        let v = &s.views[0];
        let want = reference3d::winners(v, W, H);
        let clip = ClipRect::full(W, H);
        let mut mem = StoreMem::for_scene(&s);
        let mut store = mem.store();
        cut(&mut store, v, &clip);
        let mut work = WorkMem::new(store.len());
        let mut px = vec![Rgb888::BLACK; W as usize * H as usize];
        let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
        draw(&store, &mut work.workspace(), Resolve::Crossing, &mut fb);
        assert_eq!(mismatches(px.iter().map(|&c| index_of(c)), &want), 0);
        let inks: Vec<Rgb888> = (0..s.faces).map(color_of).collect();
        let mut z = ZTarget::<i32, Rgb888>::new();
        z.frame(v, &inks, &mut [Edge::EMPTY; 4], &clip);
        let bad = mismatches(z.pixels.iter().map(|&c| index_of(c)), &want);
        let covered = want.iter().filter(|w| w.is_some()).count() as u64;
        assert!(bad * 1000 < covered, "{bad} of {covered}");
    }

    #[test]
    fn scanvert_matches_the_reference_on_a_deep_interpenetrating_scene() {
        let s = testkit::scenes3d::depth_scene(Version::Tilted, 24, 8);
        let clip = ClipRect::full(W, H);
        for v in [&s.views[0], &s.views[VIEWS - 1]] {
            let want = reference3d::winners(v, W, H);
            assert!(want.iter().all(Option::is_some), "every pixel covered");
            let mut mem = StoreMem::for_scene(&s);
            let mut store = mem.store();
            cut(&mut store, v, &clip);
            let mut work = WorkMem::new(store.len());
            let mut px = vec![Rgb888::BLACK; W as usize * H as usize];
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let st = draw(&store, &mut work.workspace(), Resolve::Crossing, &mut fb);
            assert!(st.intersecting > 0, "the faces pass through each other");
            assert_eq!(mismatches(px.iter().map(|&c| index_of(c)), &want), 0);
        }
    }

    #[test]
    fn stored_rows_decode_to_the_drawn_picture() {
        let s = scene(Version::Tilted, 30);
        let clip = ClipRect::full(W, H);
        let mut mem = StoreMem::for_scene(&s);
        let mut store = mem.store();
        cut(&mut store, &s.views[2], &clip);
        let mut work = WorkMem::new(store.len());
        let rows = StoredRows::of(&store, &mut work.workspace());
        assert_eq!(rows.rows.len(), H as usize, "a row of runs for every row");
        let n = W as usize * H as usize;
        let (mut a, mut b) = (vec![Rgb565::BLACK; n], vec![Rgb565::RED; n]);
        let mut fa = FrameBuffer::new(&mut a, W, H).unwrap();
        draw(&store, &mut work.workspace(), Resolve::Crossing, &mut fa);
        rows.decode(&mut FrameBuffer::new(&mut b, W, H).unwrap());
        assert!(a == b);
        assert!(a.iter().any(|&c| c != Rgb565::BLACK));
    }
}
