//! The mesh sweep: the four generators of `testkit::meshes` from about
//! 100 to about 20,000 triangles, each written as `scanvert import`
//! writes a model (`v`/`f` lines, a fitted view and light) at 240 × 240,
//! timed in one process run:
//!
//! * scanvert through the controller (`Controller::render`) into an
//!   RGB565 frame buffer, in each resolve, and in 16-row bands
//!   (`Controller::render_bands`, the default resolve) with no frame
//!   buffer;
//! * scanvert's stages, from the controller's hook: *transform* is the
//!   render of the list with its `f` lines left out (every `v`
//!   transformed, nothing drawn); *cut* is the rest of the time to
//!   [`Stage::Cut`] (the faces culled, lit, clipped, projected and cut
//!   into trapezoids); *resolve + write* is from there to
//!   [`Stage::Resolved`] (the check, the sweep and the decode into the
//!   frame buffer);
//! * two `i32` z-buffers fed by the same geometry code (each vertex
//!   transformed once by `Pipeline::view_point`, each face through
//!   `Pipeline::polygon_view`, lit the same), each delivered face filled
//!   by scanvert's exact rasteriser with a depth test a pixel: one over
//!   the whole frame (240 × 240 depths and pixels), and one of 16-row
//!   bands (the faces delivered once into a list, then each band's depths
//!   and pixels cleared and every face that meets the band filled into
//!   it), the rival of the same memory on a small machine.
//!
//! `--only meshes` prints the table, writes `docs/mesh-sweep.svg` and
//! rewrites the section between [`BEGIN`] and [`END`] of
//! `docs/performance.md`.

use crate::numbers::thousands;
// A face's depth at pixel centres, the 3D section's z-buffer's.
use crate::visible3d::ZPlane;
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::display_list::{Command, DisplayList};
use scanvert::fixed::{Vertex, Vertex3};
use scanvert::geometry::{Light, Orthographic, Perspective, Pipeline, PolygonSink, View, Viewport};
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::port::{Span, SpanTarget};
use scanvert::raster::clip::{ClipRect, ClipWindow};
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::scene::Stage;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::import::{list, Model};
use scanvert_sim::memory::ListMemory;
use std::convert::Infallible;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};
use testkit::meshes::{Kind, Mesh};

/// The frame.
pub const W: u16 = 240;
/// The frame.
pub const H: u16 = 240;
/// Rows of a band.
pub const BAND_ROWS: u16 = 16;

/// Markers of the section `--only meshes` rewrites.
pub const BEGIN: &str = "<!-- mesh-sweep:begin -->";
/// End marker.
pub const END: &str = "<!-- mesh-sweep:end -->";

/// One mesh's times, each the best seconds a frame.
#[derive(Clone, Debug)]
pub struct MeshRow {
    pub kind: Kind,
    pub triangles: usize,
    pub vertices: usize,
    /// Faces that reached the 3D layer, and trapezoids.
    pub drawn: u32,
    pub trapezoids: u32,
    /// scanvert, whole frame: Crossing (the default), Bisect, Paint.
    pub crossing: f64,
    pub bisect: f64,
    pub paint: f64,
    /// scanvert in 16-row bands, Crossing.
    pub bands: f64,
    /// Stages of the Crossing frame.
    pub transform: f64,
    pub cut: f64,
    pub resolve: f64,
    /// The z-buffers' geometry alone (transform, cull, light, clip,
    /// project, into a list).
    pub z_geometry: f64,
    pub z_full: f64,
    pub z_band: f64,
    /// Pixels the full z-buffer covers where scanvert's frame shows the
    /// background, or the other way round.
    pub z_differ: usize,
}

/// The list `scanvert import` writes for `m`.
pub fn mesh_list(m: &Mesh) -> Vec<u8> {
    let model = Model {
        vertices: m.vertices_f32(),
        faces: m.faces(),
    };
    let text = list(&model, W, H, Rgb888::new(0xd0, 0xa0, 0x70));
    scanvert_sim::text::assemble_bytes(text.as_bytes())
        .expect("the mesh list assembles")
        .bytes
}

/// The same list without its `f` lines.
fn vertices_only(m: &Mesh) -> Vec<u8> {
    let model = Model {
        vertices: m.vertices_f32(),
        faces: m.faces(),
    };
    let text: String = list(&model, W, H, Rgb888::BLACK)
        .lines()
        .filter(|l| !l.starts_with("f "))
        .flat_map(|l| [l, "\n"])
        .collect();
    scanvert_sim::text::assemble_bytes(text.as_bytes())
        .expect("assembles")
        .bytes
}

/// A pipeline set up by the list's camera, projection and light, and the
/// list's vertices and faces (0-based), as the controller reads them.
fn geometry(
    list: &DisplayList<'_>,
) -> (
    Pipeline<8, 32>,
    Vec<scanvert::geometry::Point3>,
    Vec<[u16; 3]>,
) {
    let w = list.width();
    // The controller's defaults until the list sets its own.
    let q = |v: i32| scanvert::geometry::Q16::from_bits(v << 16);
    let mut pipe = Pipeline::<8, 32>::new(
        Perspective::from_fov(
            scanvert::geometry::Angle::from_degrees(60),
            w,
            q(1),
            q(1000),
        )
        .expect("fits"),
        Viewport::centred(w, list.height()).expect("viewport"),
    );
    let (mut points, mut faces) = (Vec::new(), Vec::new());
    for (_, c) in list.commands() {
        match c {
            Command::Perspective { fov, near, far } => {
                pipe.set_projection(Perspective::from_fov(fov, w, near, far).expect("fits"))
            }
            Command::Ortho { scale, near, far } => {
                pipe.set_projection(Orthographic::new(scale, near, far).expect("fits"))
            }
            Command::View { eye, yaw, pitch } => {
                pipe.set_view(&View { eye, yaw, pitch }).expect("fits")
            }
            Command::Light { toward, percent } => {
                pipe.set_light(Light::new(toward.to_bits(), percent).expect("fits"))
            }
            Command::MeshVertex(p) => points.push(p),
            Command::MeshFace(ix) => {
                let v: Vec<u16> = ix.into_iter().collect();
                faces.push([v[0], v[1], v[2]]);
            }
            _ => {}
        }
    }
    (pipe, points, faces)
}

/// The faces a pipeline delivers, kept: screen vertices and lit colour.
#[derive(Default)]
struct Delivered {
    vertices: Vec<Vertex3>,
    faces: Vec<(u32, u32, Rgb565)>,
}

impl PolygonSink for Delivered {
    type Error = Infallible;
    fn polygon(&mut self, v: &[Vertex3], c: Rgb888, _two: bool) -> Result<(), Infallible> {
        let at = self.vertices.len() as u32;
        self.vertices.extend_from_slice(v);
        self.faces.push((at, v.len() as u32, Rgb565::from(c)));
        Ok(())
    }
}

/// The z-buffers' geometry: every vertex once, every face delivered.
fn deliver(
    pipe: &mut Pipeline<8, 32>,
    points: &[scanvert::geometry::Point3],
    faces: &[[u16; 3]],
    view: &mut Vec<Option<[i32; 3]>>,
    out: &mut Delivered,
) {
    view.clear();
    view.extend(points.iter().map(|&p| pipe.view_point(p).raw()));
    out.vertices.clear();
    out.faces.clear();
    let ink = Rgb888::new(0xd0, 0xa0, 0x70);
    for f in faces {
        let it = f.iter().map(|&i| view[i as usize]);
        let _ = pipe.polygon_view(it, ink, out);
    }
}

/// An `i32` z-buffer over rows `y0..y0 + rows` of the frame.
struct ZBuffer {
    y0: u16,
    depth: Vec<i32>,
    pixels: Vec<Rgb565>,
    plane: ZPlane,
}

impl ZBuffer {
    fn new(rows: u16) -> ZBuffer {
        let n = W as usize * rows as usize;
        ZBuffer {
            y0: 0,
            depth: vec![i32::MAX; n],
            pixels: vec![Rgb565::BLACK; n],
            plane: ZPlane::default(),
        }
    }

    /// Rows `y0..y1`: cleared, then every face of `d` that meets them.
    fn rows(&mut self, d: &Delivered, y0: u16, y1: u16, raster: &mut Rasterizer<'_>) {
        self.y0 = y0;
        self.depth.fill(i32::MAX);
        self.pixels.fill(Rgb565::BLACK);
        let clip = ClipRect::from_window(
            ClipWindow {
                x0: 0,
                y0: y0 as i16,
                x1: W as i16 - 1,
                y1: y1 as i16 - 1,
            },
            W,
            H,
        );
        let (top, bottom) = (y0 as i32 * 16, y1 as i32 * 16);
        for &(at, n, ink) in &d.faces {
            let f = &d.vertices[at as usize..(at + n) as usize];
            let (lo, hi) = f.iter().fold((i32::MAX, i32::MIN), |(lo, hi), v| {
                let y = v.y.units();
                (lo.min(y), hi.max(y))
            });
            if hi < top || lo > bottom {
                continue;
            }
            let Some(plane) = ZPlane::of(f) else { continue };
            self.plane = plane;
            let flat = f.iter().map(|v| Vertex { x: v.x, y: v.y });
            let _ = raster.fill(flat, &clip, ink, self);
        }
    }
}

impl SpanTarget for ZBuffer {
    type Color = Rgb565;
    type Error = Infallible;
    fn size(&self) -> (u16, u16) {
        (W, H)
    }
    #[inline]
    fn fill_span(&mut self, span: Span, color: Rgb565) -> Result<(), Infallible> {
        let base = (span.y - self.y0) as usize * W as usize;
        let (a, b) = (base + span.x0 as usize, base + span.x1.min(W) as usize);
        let p = self.plane;
        let mut z =
            p.z.wrapping_add(p.zx.wrapping_mul(span.x0 as i32))
                .wrapping_add(p.zy.wrapping_mul(span.y as i32));
        if let (Some(ds), Some(ps)) = (self.depth.get_mut(a..b), self.pixels.get_mut(a..b)) {
            for (d, px) in ds.iter_mut().zip(ps) {
                if z < *d {
                    *d = z;
                    *px = color;
                }
                z = z.wrapping_add(p.zx);
            }
        }
        Ok(())
    }
}

/// A band target that keeps nothing (the bands' cost without shipping).
struct Nowhere;

impl BandTarget for Nowhere {
    type Color = Rgb565;
    type Error = Infallible;
    fn ship(&mut self, _: u16, _: u16, px: &[Rgb565]) -> Result<(), Infallible> {
        black_box(px);
        Ok(())
    }
}

/// Times one mesh.
fn measure_one(kind: Kind, m: &Mesh, min_run: Duration, rounds: usize) -> MeshRow {
    let bytes = mesh_list(m);
    let list = DisplayList::new_checked(&bytes).expect("valid");
    let vbytes = vertices_only(m);
    let vlist = DisplayList::new_checked(&vbytes).expect("valid");
    let mut memory = ListMemory::for_bands(&list).expect("fits");
    let mut vmemory = ListMemory::for_list(&vlist).expect("fits");
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut band = vec![Rgb565::BLACK; W as usize * BAND_ROWS as usize];
    let stats = {
        let mut fb = FrameBuffer::new(&mut px, W, H).expect("size");
        memory.controller().render(&list, &mut fb).expect("renders")
    };
    // The stages, summed over the timed frames of the first function.
    let stage_at = std::cell::RefCell::new([Duration::ZERO; 2]);
    let (pipe, points, faces) = geometry(&list);
    let mut delivered = Delivered::default();
    let mut view = Vec::new();
    let mut edges = vec![Edge::EMPTY; 8];
    let mut full = ZBuffer::new(H);
    let mut bandz = ZBuffer::new(BAND_ROWS);
    let times = {
        let memory = std::cell::RefCell::new(&mut memory);
        let px = std::cell::RefCell::new(&mut px);
        let frame = |mode: Resolve| {
            let mut m = memory.borrow_mut();
            let mut p = px.borrow_mut();
            p.fill(Rgb565::BLACK);
            let mut fb = FrameBuffer::new(&mut p[..], W, H).expect("size");
            black_box(m.controller().with_resolve(mode).render(&list, &mut fb)).ok();
        };
        let mut fs: Vec<Box<dyn FnMut() + '_>> = vec![
            Box::new(|| {
                let mut m = memory.borrow_mut();
                let mut p = px.borrow_mut();
                p.fill(Rgb565::BLACK);
                let mut fb = FrameBuffer::new(&mut p[..], W, H).expect("size");
                let t0 = Instant::now();
                let mut at = [t0; 2];
                let _ = black_box(m.controller().render_with(
                    &list,
                    &mut fb,
                    &mut |s: Stage| match s {
                        Stage::Cut => at[0] = Instant::now(),
                        Stage::Resolved => at[1] = Instant::now(),
                        _ => {}
                    },
                ));
                let mut st = stage_at.borrow_mut();
                st[0] += at[0] - t0;
                st[1] += at[1].saturating_duration_since(at[0]);
            }),
            Box::new(|| frame(Resolve::Bisect)),
            Box::new(|| frame(Resolve::Paint)),
            Box::new(|| {
                let mut m = memory.borrow_mut();
                let (c, table) = m.band_parts();
                let _ = black_box(c.with_resolve(Resolve::Crossing).render_bands(
                    &list,
                    table,
                    BAND_ROWS,
                    &mut band,
                    &mut Nowhere,
                ));
            }),
            Box::new(|| {
                let mut p = px.borrow_mut();
                let mut fb = FrameBuffer::new(&mut p[..], W, H).expect("size");
                let _ = black_box(vmemory.controller().render(&vlist, &mut fb));
            }),
            Box::new({
                let (mut view, mut delivered) = (Vec::new(), Delivered::default());
                let (pipe, points, faces) = (&pipe, &points, &faces);
                move || {
                    let mut p = pipe.clone();
                    deliver(&mut p, points, faces, &mut view, &mut delivered);
                    black_box(&delivered);
                }
            }),
        ];
        crate::time_fns(&mut fs, min_run, rounds)
    };
    // The z-buffers (the geometry included), timed after: they borrow the
    // delivered list.
    let ztimes = {
        let (pipe, points, faces) = (&pipe, &points, &faces);
        let full = &mut full;
        let mut fs: Vec<Box<dyn FnMut() + '_>> = vec![
            Box::new(move || {
                let mut p = pipe.clone();
                deliver(&mut p, points, faces, &mut view, &mut delivered);
                let mut raster = Rasterizer::new(&mut edges);
                full.rows(&delivered, 0, H, &mut raster);
                black_box(&full.pixels);
            }),
            Box::new({
                let (mut view, mut delivered) = (Vec::new(), Delivered::default());
                let mut edges = vec![Edge::EMPTY; 8];
                move || {
                    let mut p = pipe.clone();
                    deliver(&mut p, points, faces, &mut view, &mut delivered);
                    let mut raster = Rasterizer::new(&mut edges);
                    let mut y = 0;
                    while y < H {
                        let y1 = (y + BAND_ROWS).min(H);
                        bandz.rows(&delivered, y, y1, &mut raster);
                        black_box(&bandz.pixels);
                        y = y1;
                    }
                }
            }),
        ];
        crate::time_fns(&mut fs, min_run, rounds)
    };
    let z_differ = {
        px.fill(Rgb565::BLACK);
        let mut fb = FrameBuffer::new(&mut px, W, H).expect("size");
        memory.controller().render(&list, &mut fb).expect("renders");
        let bg = Rgb565::BLACK;
        px.iter()
            .zip(&full.pixels)
            .filter(|(a, b)| (**a == bg) != (**b == bg))
            .count()
    };
    // The stage sums cover the calibration and every timed frame of the
    // first function: their shares split its best time.
    let st = stage_at.into_inner();
    let whole = (st[0] + st[1]).as_secs_f64().max(1e-12);
    let (to_cut, resolve) = (
        times[0] * st[0].as_secs_f64() / whole,
        times[0] * st[1].as_secs_f64() / whole,
    );
    let transform = times[4].min(to_cut);
    MeshRow {
        kind,
        triangles: m.triangles.len(),
        vertices: m.vertices.len(),
        drawn: stats.faces,
        trapezoids: stats.trapezoids,
        crossing: times[0],
        bisect: times[1],
        paint: times[2],
        bands: times[3],
        transform,
        cut: to_cut - transform,
        resolve,
        z_geometry: times[5],
        z_full: ztimes[0],
        z_band: ztimes[1],
        z_differ,
    }
}

/// Every generator at every size of its sweep.
pub fn measure(min_run: Duration, rounds: usize) -> Vec<MeshRow> {
    let mut rows = Vec::new();
    for kind in Kind::ALL {
        for &p in kind.sweep() {
            let m = kind.make(p);
            let r = measure_one(kind, &m, min_run, rounds);
            eprintln!(
                "{} {:>6} triangles: scanvert {:.3} ms (bands {:.3}), z-buffer full {:.3} ms, band {:.3} ms; z-buffer coverage differs at {} px",
                kind.name(),
                r.triangles,
                r.crossing * 1e3,
                r.bands * 1e3,
                r.z_full * 1e3,
                r.z_band * 1e3,
                r.z_differ
            );
            rows.push(r);
        }
    }
    rows
}

/// The section of `docs/performance.md`, between its markers.
pub fn section(rows: &[MeshRow], machine: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{BEGIN}\n## Meshes: scanvert against z-buffers\n\n\
         Written by `cargo run --release -p scanvert-bench -- --only meshes`\n\
         ({machine}). The meshes of `testkit::meshes` as `scanvert import`\n\
         writes them, {W} × {H}; best of {ROUNDS} timed runs, ms a frame.\n\
         *Bands*: scanvert in {BAND_ROWS}-row bands, no frame buffer. The\n\
         z-buffers (`i32` depth) take the same geometry code (each vertex\n\
         once, each face culled, lit, clipped and projected) and scanvert's\n\
         exact rasteriser; *z band* clears and fills {BAND_ROWS}-row bands,\n\
         every face that meets a band filled into it. Stages of the default\n\
         frame: *transform* (the `v`s alone), *cut* (faces to trapezoids),\n\
         *resolve + write*. See `bench/src/meshes.rs`.\n\n\
         ![time against triangles](mesh-sweep.svg)\n\n\
         | mesh | triangles | vertices | drawn | trapezoids | scanvert | bisect | paint | bands | transform | cut | resolve + write | z geometry | z full | z band | z band ÷ scanvert bands | coverage: z full ≠ scanvert, px |\n\
         |---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
    );
    for r in rows {
        let ms = |t: f64| format!("{:.3}", t * 1e3);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} | {} |",
            r.kind.name(),
            thousands(r.triangles as f64),
            thousands(r.vertices as f64),
            thousands(r.drawn as f64),
            thousands(r.trapezoids as f64),
            ms(r.crossing),
            ms(r.bisect),
            ms(r.paint),
            ms(r.bands),
            ms(r.transform),
            ms(r.cut),
            ms(r.resolve),
            ms(r.z_geometry),
            ms(r.z_full),
            ms(r.z_band),
            r.z_band / r.bands,
            r.z_differ
        );
    }
    let _ = writeln!(s, "{END}\n");
    s
}

/// Timed runs of each contender.
pub const ROUNDS: usize = 5;

/// A line of the plot: its name, its colour and its value of a row.
type Series = (&'static str, &'static str, fn(&MeshRow) -> f64);

/// The plot: ms a frame against triangles, both on log scales, a line
/// for scanvert whole frame, scanvert in bands and each z-buffer, one
/// panel a generator; a small SVG of polylines.
pub fn svg(rows: &[MeshRow]) -> String {
    let (pw, ph, pad) = (300.0, 220.0, 46.0);
    let series: [Series; 4] = [
        ("scanvert", "#1f77b4", |r| r.crossing),
        ("scanvert, bands", "#2ca02c", |r| r.bands),
        ("z-buffer, full", "#d62728", |r| r.z_full),
        ("z-buffer, bands", "#ff7f0e", |r| r.z_band),
    ];
    let (tmin, tmax) = rows.iter().fold((f64::MAX, f64::MIN), |(a, b), r| {
        series
            .iter()
            .map(|s| s.2(r) * 1e3)
            .fold((a, b), |(a, b), v| (a.min(v), b.max(v)))
    });
    let (lt0, lt1) = (tmin.log10().floor(), tmax.log10().ceil());
    let (lx0, lx1) = (
        2.0f64.min(
            rows.iter()
                .map(|r| (r.triangles as f64).log10())
                .fold(f64::MAX, f64::min)
                .floor(),
        ),
        4.5f64,
    );
    let width = 2.0 * (pw + pad) + pad;
    let height = 2.0 * (ph + pad) + pad + 24.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    for (k, kind) in Kind::ALL.iter().enumerate() {
        let (ox, oy) = (
            pad + (k % 2) as f64 * (pw + pad),
            pad + (k / 2) as f64 * (ph + pad),
        );
        let x = |n: f64| ox + (n.log10() - lx0) / (lx1 - lx0) * pw;
        let y = |t: f64| oy + ph - (t.log10() - lt0) / (lt1 - lt0) * ph;
        let _ = writeln!(
            s,
            "<rect x=\"{ox}\" y=\"{oy}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#888\"/>\n\
             <text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-weight=\"bold\">{}</text>",
            ox + pw / 2.0,
            oy - 6.0,
            kind.name()
        );
        let mut e = lt0;
        while e <= lt1 {
            let t = 10f64.powf(e);
            let _ = writeln!(
                s,
                "<line x1=\"{ox}\" x2=\"{}\" y1=\"{yy:.1}\" y2=\"{yy:.1}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{} ms</text>",
                ox + pw,
                ox - 4.0,
                y(t) + 4.0,
                if e < 0.0 { format!("{t:.*}", (-e) as usize) } else { format!("{t:.0}") },
                yy = y(t)
            );
            e += 1.0;
        }
        for n in [100.0f64, 1_000.0, 10_000.0] {
            if n.log10() >= lx0 {
                let _ = writeln!(
                    s,
                    "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
                    x(n),
                    oy + ph + 14.0,
                    thousands(n)
                );
            }
        }
        for (name, colour, f) in &series {
            let pts: Vec<String> = rows
                .iter()
                .filter(|r| r.kind == *kind)
                .map(|r| format!("{:.1},{:.1}", x(r.triangles as f64), y(f(r) * 1e3)))
                .collect();
            let _ = writeln!(
                s,
                "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\" points=\"{}\"><title>{name}</title></polyline>",
                pts.join(" ")
            );
        }
    }
    let ly = height - 14.0;
    let _ = writeln!(
        s,
        "<text x=\"{pad}\" y=\"{}\">ms a frame ({W} × {H}) against triangles, log scales</text>",
        ly - 16.0
    );
    for (k, (name, colour, _)) in series.iter().enumerate() {
        let lx = pad + k as f64 * 150.0;
        let _ = writeln!(
            s,
            "<line x1=\"{lx}\" x2=\"{}\" y1=\"{}\" y2=\"{}\" stroke=\"{colour}\" stroke-width=\"2\"/><text x=\"{}\" y=\"{ly}\">{name}</text>",
            lx + 18.0,
            ly - 4.0,
            ly - 4.0,
            lx + 22.0
        );
    }
    s.push_str("</svg>\n");
    s
}
