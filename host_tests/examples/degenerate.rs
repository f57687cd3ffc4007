//! Degenerate inputs of the visible-surface sweep, timed against their
//! size: each family's display list is generated at four sizes and
//! rendered through the simulator in every resolve (and in bands of 16
//! rows), and the exponent of time against size is fitted (least squares
//! on the logarithms; 1 is linear, 2 quadratic).
//!
//! ```text
//! cargo run --release -p host-tests --example degenerate
//! cargo run --release -p host-tests --example degenerate -- --small
//! cargo run --release -p host-tests --example degenerate -- --write DIR
//! ```
//!
//! The families (`docs/robustness.md`, "Degenerate inputs"):
//!
//! * `stacked-64`: N identical `poly3` quads covering a 64 × 64 frame;
//! * `stacked-16x2047`: the same on a 16 × 2047 frame (one extent, one
//!   right end, on every row);
//! * `points`: N identical points `face 0 0 -5` in a 3D scene;
//! * `staggered`: K full-height rectangles on a 2047 × 256 frame, each
//!   starting ½ px right of the last and nearer, all ending on the last
//!   column;
//! * `labels`: N one-letter labels of one segment, at scattered points;
//! * `clears-4096`: N `clear`s of a 4096 × 4096 frame, each followed by a
//!   small `poly` (only the last clear and what follows it can show).
//!
//! `--small` uses sizes an eighth as large (for code that is still
//! quadratic); `--write DIR` writes the largest list of each family as
//! text. Times are of this host, in release mode, each the best of two.

use scanvert::visible::Resolve;
use scanvert_sim::cli::{render_scene_bands_with, render_scene_with, Scene};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// A family: its name, its sizes and its list at a size.
struct Family {
    name: &'static str,
    sizes: [usize; 4],
    list: fn(usize) -> String,
}

fn stacked(w: u32, h: u32, n: usize) -> String {
    let mut s = format!("frame {w} {h}\n");
    let (x, y) = (w.min(2047), h.min(2047));
    for _ in 0..n {
        let _ = writeln!(s, "poly3 0 0 5  0 {y} 5  {x} {y} 5  {x} 0 5");
    }
    s
}

fn points(n: usize) -> String {
    let mut s = String::from("frame 64 64\nperspective 50 1 100\nlookat 0 0 10  0 0 0\n");
    for _ in 0..n {
        s.push_str("face 0 0 -5\n");
    }
    s
}

fn staggered(k: usize) -> String {
    let (w, h) = (2047, 256);
    let mut s = format!("frame {w} {h}\n");
    for i in 0..k {
        // ½ px right of the last and ¼ unit nearer.
        let x = i as f64 * 0.5;
        let z = 1500.0 - i as f64 * 0.25;
        let _ = writeln!(s, "poly3 {x} 0 {z}  {x} {h} {z}  {w} {h} {z}  {w} 0 {z}");
    }
    s
}

fn labels(n: usize) -> String {
    let mut s =
        String::from("frame 320 240\nperspective 50 1 100\nlookat 0 0 10  0 0 0\nsegment 1\n");
    for i in 0..n {
        // Scattered over the view, a fixed pattern.
        let (x, y) = (
            (i * 37 % 600) as f64 / 100.0 - 3.0,
            (i * 91 % 600) as f64 / 100.0 - 3.0,
        );
        let _ = writeln!(s, "label {x:.2} {y:.2} 0 a");
    }
    s
}

fn clears(n: usize) -> String {
    let mut s = String::from("frame 4096 4096\n");
    for i in 0..n {
        let _ = writeln!(s, "clear #{:06x}\npoly 0 0 40 0 20 30", i % 0xff_ffff);
    }
    s
}

const FAMILIES: [Family; 6] = [
    Family {
        name: "stacked-64",
        sizes: [4000, 8000, 16000, 32000],
        list: |n| stacked(64, 64, n),
    },
    Family {
        name: "stacked-16x2047",
        sizes: [8192, 16384, 32768, 65535],
        list: |n| stacked(16, 2047, n),
    },
    Family {
        name: "points",
        sizes: [8192, 16384, 32768, 65535],
        list: points,
    },
    Family {
        name: "staggered",
        sizes: [500, 1000, 2000, 4000],
        list: staggered,
    },
    Family {
        name: "labels",
        sizes: [25_000, 50_000, 100_000, 200_000],
        list: labels,
    },
    Family {
        name: "clears-4096",
        sizes: [1000, 2000, 4000, 8000],
        list: clears,
    },
];

/// How a list is rendered.
#[derive(Clone, Copy)]
enum How {
    Whole(Resolve),
    Bands(Resolve, u16),
}

const HOWS: [(&str, How); 5] = [
    ("crossing", How::Whole(Resolve::Crossing)),
    ("bisect", How::Whole(Resolve::Bisect)),
    ("paint", How::Whole(Resolve::Paint)),
    ("bands 16", How::Bands(Resolve::Crossing, 16)),
    ("bands 16 paint", How::Bands(Resolve::Paint, 16)),
];

/// Seconds to render `scene`, the best of two.
fn time(scene: &Scene, how: How) -> f64 {
    (0..2)
        .map(|_| {
            let t = Instant::now();
            let r = match how {
                How::Whole(m) => render_scene_with(scene, m),
                How::Bands(m, rows) => render_scene_bands_with(scene, rows, m),
            };
            let s = t.elapsed().as_secs_f64();
            r.expect("the family renders");
            s
        })
        .fold(f64::INFINITY, f64::min)
}

/// The least-squares slope of `ln t` against `ln n`.
fn exponent(n: &[usize], t: &[f64]) -> f64 {
    let xs: Vec<f64> = n.iter().map(|&n| (n as f64).ln()).collect();
    let ys: Vec<f64> = t.iter().map(|&t| t.max(1e-6).ln()).collect();
    let (mx, my) = (
        xs.iter().sum::<f64>() / xs.len() as f64,
        ys.iter().sum::<f64>() / ys.len() as f64,
    );
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let small = args.iter().any(|a| a == "--small");
    let write = args
        .iter()
        .position(|a| a == "--write")
        .and_then(|i| args.get(i + 1));
    if let Some(dir) = write {
        std::fs::create_dir_all(dir).expect("the directory can be made");
        for f in &FAMILIES {
            let path = Path::new(dir).join(format!("{}.dl", f.name));
            std::fs::write(&path, (f.list)(f.sizes[3])).expect("the list is written");
            println!("{}", path.display());
        }
        return;
    }
    println!("| family | resolve | sizes | seconds | exponent |");
    println!("|---|---|---|---|---|");
    for f in &FAMILIES {
        let sizes: Vec<usize> = f
            .sizes
            .iter()
            .map(|&n| if small { n / 8 } else { n })
            .collect();
        let scenes: Vec<Scene> = sizes
            .iter()
            .map(|&n| {
                let text = (f.list)(n);
                Scene::from_bytes(Path::new(f.name), text.into_bytes()).expect("the list is valid")
            })
            .collect();
        for (name, how) in HOWS {
            let t: Vec<f64> = scenes.iter().map(|s| time(s, how)).collect();
            let sizes_s: Vec<String> = sizes.iter().map(|n| n.to_string()).collect();
            let t_s: Vec<String> = t.iter().map(|t| format!("{t:.3}")).collect();
            println!(
                "| {} | {name} | {} | {} | {:.2} |",
                f.name,
                sizes_s.join(" / "),
                t_s.join(" / "),
                exponent(&sizes, &t)
            );
        }
    }
}
