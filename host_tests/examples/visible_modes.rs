//! A quick measurement of the visible-surface stages on 512 × 256 scenes
//! of about 170 `poly3`s: the two ways of resolving intersecting spans
//! (error against the exact reference, and time per frame), with a plain
//! z-buffer at the same depth precision for comparison.
//!
//! ```text
//! cargo run --release -p host-tests --example visible_modes
//! ```
//!
//! Times are of this host, in release mode; they are for comparing the
//! contenders with each other, not a target's figures.
//! `-- --profile SCENE MODE FRAMES` only resolves and decodes one scene
//! (`flat`, `tilted` or `bars`; `Bisect`, `Crossing` or `zbuffer`), for
//! counting instructions under callgrind; `-- --write-lists DIR` writes
//! the scenes as binary display lists.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use host_tests::harness3d::{build_list3, color_of, index_of, vertex3};
use host_tests::reference3d::{drawn, resolve, Poly3};
use scanvert::clip::ClipRect;
use scanvert::edge::Edge;
use scanvert::fixed::Vertex;
use scanvert::framebuffer::FrameBuffer;
use scanvert::port::{Span, SpanTarget};
use scanvert::rle::Run;
use scanvert::scan::Rasterizer;
use scanvert::segment::{Face, Segment, StoreMemory, TrapezoidStore};
use scanvert::trapezoid::{Depth, EdgeSlot, Plane, Trapezoid};
use scanvert::visible::{self, Active, Cover, Resolve, Workspace};
use std::convert::Infallible;
use std::hint::black_box;
use std::time::{Duration, Instant};

const W: u16 = 512;
const H: u16 = 256;

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo) as u64) as i32
    }
}

type V3 = (i32, i32, i32);

fn add(a: V3, b: V3) -> V3 {
    (a.0 + b.0, a.1 + b.1, a.2 + b.2)
}

fn scale(a: V3, k: i32) -> V3 {
    (a.0 * k, a.1 * k, a.2 * k)
}

fn front(mut p: Vec<V3>) -> Poly3 {
    if !drawn(&p) {
        p.reverse();
    }
    Poly3 {
        poly: p,
        clip: None,
    }
}

/// 170 faces parallel to the screen, each at a depth of its own.
fn flat(rng: &mut Rng) -> Vec<Poly3> {
    (0..170)
        .map(|k| {
            let (x, y) = (
                rng.range(-400, W as i32 * 16),
                rng.range(-400, H as i32 * 16),
            );
            let (w, h) = (rng.range(160, 1400), rng.range(160, 1000));
            let z = rng.range(-30000, 30000) / 170 * 170 + k;
            if k % 2 == 0 {
                front(vec![
                    (x, y, z),
                    (x, y + h, z),
                    (x + w, y + h, z),
                    (x + w, y, z),
                ])
            } else {
                front(vec![
                    (x, y, z),
                    (x - w / 2, y + h, z),
                    (x + w, y + h / 2, z),
                ])
            }
        })
        .collect()
}

/// 170 tilted triangles and parallelograms whose depths overlap.
fn tilted(rng: &mut Rng) -> Vec<Poly3> {
    (0..170)
        .map(|k| {
            let o = (
                rng.range(-400, W as i32 * 16),
                rng.range(-400, H as i32 * 16),
                rng.range(-8000, 8000),
            );
            let u = (
                rng.range(-1200, 1200),
                rng.range(-800, 800),
                rng.range(-6000, 6000),
            );
            let v = (
                rng.range(-1200, 1200),
                rng.range(-800, 800),
                rng.range(-6000, 6000),
            );
            if k % 2 == 0 {
                front(vec![o, add(o, u), add(o, v)])
            } else {
                front(vec![o, add(o, u), add(add(o, u), v), add(o, v)])
            }
        })
        .collect()
}

/// 170 large triangles through each other: many intersecting spans.
fn dense(rng: &mut Rng) -> Vec<Poly3> {
    (0..170)
        .map(|_| {
            let p = |rng: &mut Rng| {
                (
                    rng.range(-1600, W as i32 * 16 + 1600),
                    rng.range(-800, H as i32 * 16 + 800),
                    rng.range(-30000, 30000),
                )
            };
            front(vec![p(rng), p(rng), p(rng)])
        })
        .collect()
}

/// Bars over a map, in an oblique parallel projection: a 10 × 7 grid of
/// tiles and 20 bars (boxes, three faces culled each), about 190 `poly3`s.
fn bars(rng: &mut Rng) -> Vec<Poly3> {
    // Screen-space images of the world axes (x east, y north, z up), in
    // units; depth grows to the north and to the west and falls upwards.
    let ex = (640, 96, -900);
    let ey = (-288, -224, 1600);
    let ez = (0, -480, -400);
    let origin = (1100, 3000, 2000);
    let at =
        |x: i32, y: i32, z: i32| add(add(add(origin, scale(ex, x)), scale(ey, y)), scale(ez, z));
    let mut out = Vec::new();
    for gy in 0..7 {
        for gx in 0..10 {
            // Corners in eighths of a cell, so that the tiles are planar.
            let c = |x: i32, y: i32| {
                let p = add(add(scale(ex, x), scale(ey, y)), scale(origin, 8));
                (p.0 / 8, p.1 / 8, p.2 / 8)
            };
            let (x, y) = (gx * 8, gy * 8);
            out.push(front(vec![
                c(x, y),
                c(x + 8, y),
                c(x + 8, y + 8),
                c(x, y + 8),
            ]));
        }
    }
    for _ in 0..20 {
        let (gx, gy) = (rng.range(0, 10), rng.range(0, 7));
        let h = rng.range(1, 4);
        let o = at(gx, gy, 0);
        let (u, v, w) = (scale(ex, 1), scale(ey, 1), scale(ez, h));
        // Outward windings; the culling rule drops the back three.
        let face = |c: V3, e1: V3, e2: V3| vec![c, add(c, e1), add(add(c, e1), e2), add(c, e2)];
        for f in [
            face(o, v, u),
            face(add(o, w), u, v),
            face(o, w, v),
            face(add(o, u), v, w),
            face(o, u, w),
            face(add(o, v), w, u),
        ] {
            // Both windings are possible for a left-handed image of the
            // axes; keep the given winding and let culling decide.
            out.push(Poly3 {
                poly: f,
                clip: None,
            });
        }
    }
    out
}

/// A plain z-buffer at the same depth precision: every face's pixels by
/// the exact rasteriser, each tested against a 32-bit depth per pixel
/// computed with the same fixed-point plane ([`Depth`]).
struct ZBuffer {
    z: Vec<i32>,
    color: Vec<Rgb565>,
    depth: Depth,
    ink: Rgb565,
    /// For the error count only: which face each pixel shows.
    ids: Option<(Vec<usize>, usize)>,
}

impl SpanTarget for ZBuffer {
    type Color = Rgb565;
    type Error = Infallible;
    fn size(&self) -> (u16, u16) {
        (W, H)
    }
    fn fill_span(&mut self, span: Span, _: Rgb565) -> Result<(), Infallible> {
        let row = span.y as usize * W as usize;
        let mut z = self.depth.at(span.x0 as i32, span.y as i32);
        for x in span.x0 as usize..span.x1 as usize {
            if z < self.z[row + x] {
                self.z[row + x] = z;
                self.color[row + x] = self.ink;
                if let Some((ids, id)) = &mut self.ids {
                    ids[row + x] = *id;
                }
            }
            z = z.wrapping_add(self.depth.zx);
        }
        Ok(())
    }
}

fn zbuffer_frame(
    zb: &mut ZBuffer,
    faces: &[(Vec<Vertex>, Depth, Rgb565, usize)],
    edges: &mut [Edge],
) {
    zb.z.fill(i32::MAX);
    zb.color.fill(Rgb565::BLACK);
    let clip = ClipRect::full(W, H);
    let mut raster = Rasterizer::new(edges);
    for (poly, depth, ink, k) in faces {
        zb.depth = *depth;
        zb.ink = *ink;
        if let Some((_, id)) = &mut zb.ids {
            *id = *k;
        }
        let _ = raster.fill(poly.iter().copied(), &clip, *ink, zb);
    }
}

/// Best time of a few runs of `f`, each repeated for at least 100 ms.
fn time(mut f: impl FnMut()) -> Duration {
    let mut best = Duration::MAX;
    for _ in 0..5 {
        let start = Instant::now();
        let mut n = 0u32;
        while start.elapsed() < Duration::from_millis(100) {
            f();
            n += 1;
        }
        best = best.min(start.elapsed() / n);
    }
    best
}

fn main() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let scenes = [
        ("flat", flat(&mut rng)),
        ("tilted", tilted(&mut rng)),
        ("bars", bars(&mut rng)),
        ("dense", dense(&mut rng)),
    ];
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--write-lists") {
        for (name, scene) in &scenes {
            let path = std::path::Path::new(&args[1]).join(format!("{name}.scvl"));
            std::fs::write(&path, build_list3(scene, W, H)).expect("write the list");
        }
        return;
    }
    if args.first().map(String::as_str) == Some("--profile") {
        let scene = &scenes.iter().find(|s| s.0 == args[1]).expect("scene").1;
        let frames: u32 = args[3].parse().expect("frames");
        profile(scene, &args[2], frames);
        return;
    }
    println!("scene | poly3 drawn | trapezoids | max active | intersecting spans | mode | splits | mismatched / covered | per 1000 | exact compares | resolve | resolve + decode | cut");
    println!("---|---|---|---|---|---|---|---|---|---|---|---|---");
    for (name, scene) in &scenes {
        let want = resolve(scene, W.into(), H.into());
        let covered = want.iter().filter(|w| w.is_some()).count();
        let shown: Vec<usize> = (0..scene.len())
            .filter(|&k| drawn(&scene[k].poly))
            .collect();

        let n = scene.len();
        let mut traps = vec![Trapezoid::EMPTY; 8 * n];
        let mut faces = vec![Face::EMPTY; n];
        let mut segs = [Segment::EMPTY; 1];
        let mut rows = vec![0u16; H as usize];
        let mut slots = vec![EdgeSlot::EMPTY; 8];
        let mut store = TrapezoidStore::new(
            StoreMemory {
                trapezoids: &mut traps,
                faces: &mut faces,
                segments: &mut segs,
                rows: &mut rows,
                edges: &mut slots,
            },
            W,
            H,
        )
        .unwrap();
        let clip = ClipRect::full(W, H);
        let fill = |store: &mut TrapezoidStore<'_>| {
            store.clear_segment(0).unwrap();
            for &k in &shown {
                store
                    .add_polygon(
                        0,
                        scene[k].poly.iter().copied().map(vertex3),
                        color_of(k),
                        &clip,
                    )
                    .unwrap();
            }
        };
        let cut = time(|| fill(&mut store));
        fill(&mut store);

        let mut active = vec![Active::EMPTY; store.len()];
        let mut cover = vec![Cover::EMPTY; store.len()];
        let mut runs = vec![Run::EMPTY; W as usize];
        let mut ws = Workspace::new(&mut active, &mut cover, &mut runs);
        let most = ws.check(&store).unwrap();
        for mode in [Resolve::Bisect, Resolve::Crossing] {
            // Error: decode into 24-bit colour and compare pixel by pixel.
            let mut px = vec![Rgb888::BLACK; W as usize * H as usize];
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let (stats, _) =
                visible::draw(&store, &mut ws, mode, &mut fb, Some(Rgb888::BLACK)).unwrap();
            let bad = px
                .iter()
                .zip(&want)
                .filter(|(g, w)| index_of(**g) != **w)
                .count();
            let resolve_only = time(|| {
                ws.resolve(&store, mode, |_, r| {
                    black_box(r);
                    Ok::<(), ()>(())
                })
                .unwrap();
            });
            let mut px565 = vec![Rgb565::BLACK; W as usize * H as usize];
            let mut fb565 = FrameBuffer::new(&mut px565, W, H).unwrap();
            let with_decode = time(|| {
                visible::draw(&store, &mut ws, mode, &mut fb565, Some(Rgb565::BLACK)).unwrap();
            });
            println!(
                "{name} | {} | {} | {most} | {} | {mode:?} | {} | {bad} / {covered} | {:.3} | {} | {:.1} µs | {:.1} µs | {:.1} µs",
                shown.len(),
                store.len(),
                stats.intersecting,
                stats.splits,
                1000.0 * bad as f64 / covered.max(1) as f64,
                stats.exact,
                resolve_only.as_secs_f64() * 1e6,
                with_decode.as_secs_f64() * 1e6,
                cut.as_secs_f64() * 1e6,
            );
        }

        // The z-buffer at the same precision.
        let zfaces: Vec<(Vec<Vertex>, Depth, Rgb565, usize)> = shown
            .iter()
            .filter_map(|&k| {
                let v: Vec<_> = scene[k].poly.iter().copied().map(vertex3).collect();
                let plane = Plane::of(v.iter().copied())?;
                let c = color_of(k);
                let ink = Rgb565::new(c.r() >> 3, c.g() >> 2, c.b() >> 3);
                Some((
                    v.iter().map(|p| Vertex { x: p.x, y: p.y }).collect(),
                    plane.depth(),
                    ink,
                    k,
                ))
            })
            .collect();
        let mut zb = ZBuffer {
            z: vec![i32::MAX; W as usize * H as usize],
            color: vec![Rgb565::BLACK; W as usize * H as usize],
            depth: Depth::default(),
            ink: Rgb565::BLACK,
            ids: None,
        };
        let mut edges = vec![Edge::EMPTY; 8];
        let zt = time(|| zbuffer_frame(&mut zb, &zfaces, &mut edges));
        zb.ids = Some((vec![usize::MAX; W as usize * H as usize], 0));
        zbuffer_frame(&mut zb, &zfaces, &mut edges);
        let ids = zb.ids.take().unwrap().0;
        let zbad = ids
            .iter()
            .zip(&want)
            .filter(|(g, w)| (**g != usize::MAX).then_some(**g) != **w)
            .count();
        println!(
            "{name} | {} | – | – | – | z-buffer (32-bit, same planes; {} KiB of depth) | – | {zbad} / {covered} | {:.3} | – | – | {:.1} µs | –",
            shown.len(),
            W as usize * H as usize * 4 / 1024,
            1000.0 * zbad as f64 / covered.max(1) as f64,
            zt.as_secs_f64() * 1e6,
        );
    }
}

/// Resolves and decodes `scene` `frames` times (or runs the z-buffer).
fn profile(scene: &[Poly3], mode: &str, frames: u32) {
    let shown: Vec<usize> = (0..scene.len())
        .filter(|&k| drawn(&scene[k].poly))
        .collect();
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
    if mode == "zbuffer" {
        let zfaces: Vec<(Vec<Vertex>, Depth, Rgb565, usize)> = shown
            .iter()
            .filter_map(|&k| {
                let v: Vec<_> = scene[k].poly.iter().copied().map(vertex3).collect();
                let plane = Plane::of(v.iter().copied())?;
                Some((
                    v.iter().map(|p| Vertex { x: p.x, y: p.y }).collect(),
                    plane.depth(),
                    Rgb565::RED,
                    k,
                ))
            })
            .collect();
        let mut zb = ZBuffer {
            z: vec![i32::MAX; W as usize * H as usize],
            color: vec![Rgb565::BLACK; W as usize * H as usize],
            depth: Depth::default(),
            ink: Rgb565::BLACK,
            ids: None,
        };
        let mut edges = vec![Edge::EMPTY; 8];
        for _ in 0..frames {
            zbuffer_frame(&mut zb, &zfaces, &mut edges);
        }
        black_box(&zb.color);
        return;
    }
    let mode = if mode == "Bisect" {
        Resolve::Bisect
    } else {
        Resolve::Crossing
    };
    let n = scene.len();
    let mut traps = vec![Trapezoid::EMPTY; 8 * n];
    let mut faces = vec![Face::EMPTY; n];
    let mut segs = [Segment::EMPTY; 1];
    let mut rows = vec![0u16; H as usize];
    let mut slots = vec![EdgeSlot::EMPTY; 8];
    let mut store = TrapezoidStore::new(
        StoreMemory {
            trapezoids: &mut traps,
            faces: &mut faces,
            segments: &mut segs,
            rows: &mut rows,
            edges: &mut slots,
        },
        W,
        H,
    )
    .unwrap();
    for &k in &shown {
        store
            .add_polygon(
                0,
                scene[k].poly.iter().copied().map(vertex3),
                color_of(k),
                &ClipRect::full(W, H),
            )
            .unwrap();
    }
    let mut active = vec![Active::EMPTY; store.len()];
    let mut cover = vec![Cover::EMPTY; store.len()];
    let mut runs = vec![Run::EMPTY; W as usize];
    let mut ws = Workspace::new(&mut active, &mut cover, &mut runs);
    for f in 0..frames {
        let (stats, counts) =
            visible::draw(&store, &mut ws, mode, &mut fb, Some(Rgb565::BLACK)).unwrap();
        if f == 0 {
            eprintln!("{stats:?} {counts:?}");
        }
    }
}
