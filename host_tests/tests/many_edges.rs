//! Polygons of many edges in the order that sorting handles worst: a
//! zigzag of 65,535 vertices, listed right to left, every edge from the
//! top row to the bottom one, so all of them join the active list on one
//! row. As `poly` (the rasteriser's active-edge sort) and as `poly3` (the
//! cut's band sort) through `scanvert render`, each pixel is checked
//! against the pixel rule, computed here row by row from the exact
//! crossings. (The sorts fall back to `O(n log n)` past a budget of
//! swaps; before, these took seconds, and the benchmark is where their
//! speed is measured.)

use std::cmp::Ordering;
use std::fmt::Write as _;
use std::path::PathBuf;

const W: u32 = 400;
const H: u32 = 100;

/// The zigzag in units of 1/16 px: `n` vertices from the right edge to
/// the left one, on rows 0 and `H − 1` in turn (a quarter pixel inside).
fn zigzag(n: usize) -> Vec<(i32, i32)> {
    (0..n)
        .map(|k| {
            let x = (16 * W as i64 - 1) * (n - 1 - k) as i64 / (n - 1) as i64;
            let y = if k % 2 == 0 { 4 } else { 16 * H as i32 - 4 };
            (x as i32, y)
        })
        .collect()
}

/// The pixel rule, row by row: the exact crossings of the row's centre
/// line (half-open in y), sorted; pixel `i` is covered when an odd number
/// of them lie at or left of its centre.
fn coverage(poly: &[(i32, i32)]) -> Vec<bool> {
    let mut out = vec![false; (W * H) as usize];
    for j in 0..H as i64 {
        let yc = 16 * j + 8;
        // Crossings as (numerator, denominator > 0) in units.
        let mut xs: Vec<(i128, i128)> = Vec::new();
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            let (mut x0, mut y0, mut x1, mut y1) = (a.0 as i64, a.1 as i64, b.0 as i64, b.1 as i64);
            if y0 > y1 {
                (x0, y0, x1, y1) = (x1, y1, x0, y0);
            }
            if y0 <= yc && yc < y1 {
                let dy = y1 - y0;
                xs.push(((x0 * dy + (yc - y0) * (x1 - x0)) as i128, dy as i128));
            }
        }
        xs.sort_by(|p, q| (p.0 * q.1).cmp(&(q.0 * p.1)));
        for i in 0..W as i64 {
            let xc = (16 * i + 8) as i128;
            // Crossings at or left of the centre: a prefix of the sorted list.
            let left = xs.partition_point(|p| p.0.cmp(&(xc * p.1)) != Ordering::Greater);
            out[(j * W as i64 + i) as usize] = left % 2 == 1;
        }
    }
    out
}

/// Renders `text` through the command line; the picture as "lit or not"
/// per pixel.
fn render(name: &str, text: &str) -> Vec<bool> {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("many_edges");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (scene, png) = (
        dir.join(format!("{name}.dl")),
        dir.join(format!("{name}.png")),
    );
    std::fs::write(&scene, text).expect("write scene");
    let args: Vec<String> = [
        "render",
        scene.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    scanvert_sim::cli::run(&args).expect("renders");
    let bytes = std::fs::read(&png).expect("png written");
    let (w, h, rgb) = scanvert_sim::image::decode_png(&bytes).expect("decode");
    assert_eq!((w, h), (W, H));
    rgb.chunks(3).map(|p| p != [0, 0, 0]).collect()
}

fn text(command: &str, poly: &[(i32, i32)], z: Option<i32>) -> String {
    let mut s = format!("frame {W} {H}\nclear #000000\ncolor #ffffff\n{command}");
    for &(x, y) in poly {
        write!(s, " {} {}", x as f64 / 16.0, y as f64 / 16.0).unwrap();
        if let Some(z) = z {
            write!(s, " {z}").unwrap();
        }
    }
    s.push('\n');
    s
}

fn shoelace(poly: &[(i32, i32)]) -> i64 {
    (0..poly.len())
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            p.0 as i64 * q.1 as i64 - q.0 as i64 * p.1 as i64
        })
        .sum()
}

#[test]
fn a_zigzag_poly_of_65535_vertices_right_to_left() {
    let poly = zigzag(65_535);
    let want = coverage(&poly);
    assert!(want.iter().filter(|&&c| c).count() > 1000);
    let got = render("zigzag_poly", &text("poly", &poly, None));
    let differ = (0..want.len()).filter(|&k| got[k] != want[k]).count();
    assert_eq!(differ, 0);
}

#[test]
fn a_zigzag_poly3_of_65535_vertices_right_to_left() {
    // Counter-clockwise as displayed, so it is drawn; the zigzag stays
    // right to left, starting on the other row.
    let mut poly = zigzag(65_535);
    if shoelace(&poly) >= 0 {
        for p in poly.iter_mut() {
            p.1 = 16 * H as i32 - p.1;
        }
    }
    assert!(shoelace(&poly) < 0);
    let want = coverage(&poly);
    let got = render("zigzag_poly3", &text("poly3", &poly, Some(7)));
    let differ = (0..want.len()).filter(|&k| got[k] != want[k]).count();
    assert_eq!(differ, 0);
}
