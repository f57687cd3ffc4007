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
//! (`flat`, `tilted`, `bars` or `dense`; `Bisect`, `Crossing` or
//! `zbuffer`), or only cuts it into trapezoids (`cut`), for
//! counting instructions under callgrind; `-- --write-lists DIR` writes
//! the scenes as binary display lists.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use host_tests::harness3d::{build_list3, color_of, index_of, vertex3};
use scanvert::fixed::Vertex;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::port::{Span, SpanTarget};
use scanvert::raster::clip::ClipRect;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment, StoreMemory, TrapezoidStore};
use scanvert::visible::trapezoid::{Depth, EdgeSlot, Plane, Trapezoid};
use scanvert::visible::{self, Active, Resolve, Workspace};
use std::convert::Infallible;
use std::hint::black_box;
use std::time::{Duration, Instant};
use testkit::poly3_scenes::{self as scenes3d, H, W};
use testkit::reference3d::{drawn, resolve, Poly3};

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
    let scenes = scenes3d::all();
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
        let mut runs = vec![Run::EMPTY; W as usize];
        let mut ws = Workspace::new(&mut active, &mut runs);
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
    let cut_only = mode == "cut";
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
    let fill = |store: &mut TrapezoidStore<'_>| {
        store.clear_segment(0).unwrap();
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
    };
    fill(&mut store);
    if cut_only {
        for _ in 1..frames {
            fill(&mut store);
        }
        return;
    }
    let mut active = vec![Active::EMPTY; store.len()];
    let mut runs = vec![Run::EMPTY; W as usize];
    let mut ws = Workspace::new(&mut active, &mut runs);
    for f in 0..frames {
        let (stats, counts) =
            visible::draw(&store, &mut ws, mode, &mut fb, Some(Rgb565::BLACK)).unwrap();
        if f == 0 {
            eprintln!("{stats:?} {counts:?}");
        }
    }
}
