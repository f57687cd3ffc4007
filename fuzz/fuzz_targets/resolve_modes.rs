//! Differential: the three visible-surface resolutions
//! (`Resolve::Bisect`, `Resolve::Crossing` and `Resolve::Paint`) give the
//! same pixels on
//! planar input: triangles (always planar) from a small structured input,
//! each with its own colour and clip window, on a frame of at most 64×64;
//! and painting band by band, in bands of 1 to 16 rows, gives them too.
#![no_main]

use arbitrary::Arbitrary;
use host_tests::harness3d::{render3, render3_bands};
use libfuzzer_sys::fuzz_target;
use scanvert::visible::sweep::Resolve;
use testkit::reference::Window;
use testkit::reference3d::Poly3;

#[derive(Arbitrary, Debug)]
struct Triangle {
    /// Vertices in 1/16 px: x and y within the frame and a little outside,
    /// z anywhere in Q12.4.
    v: [(i16, i16, i16); 3],
    clip: Option<(u8, u8, u8, u8)>,
}

#[derive(Arbitrary, Debug)]
struct Input {
    width: u8,
    height: u8,
    band_rows: u8,
    triangles: Vec<Triangle>,
}

fuzz_target!(|input: Input| {
    let (w, h) = (1 + input.width as u16 % 64, 1 + input.height as u16 % 64);
    // Coordinates in −8 … W+8 px (and the same for y), in sixteenths.
    let fold = |c: i16, side: u16| {
        let span = (side as i32 + 16) * 16;
        (c as i32).rem_euclid(span) - 8 * 16
    };
    let polys: Vec<Poly3> = input
        .triangles
        .iter()
        .take(24)
        .map(|t| Poly3 {
            poly: t
                .v
                .iter()
                .map(|&(x, y, z)| (fold(x, w), fold(y, h), z as i32))
                .collect(),
            clip: t.clip.map(|(x0, y0, x1, y1)| Window {
                x0: (x0 % 72) as i16 - 4,
                y0: (y0 % 72) as i16 - 4,
                x1: (x1 % 72) as i16 - 4,
                y1: (y1 % 72) as i16 - 4,
            }),
        })
        .collect();
    let (bisect, _) = render3(&polys, w, h, Resolve::Bisect);
    let (crossing, _) = render3(&polys, w, h, Resolve::Crossing);
    let (painted, _) = render3(&polys, w, h, Resolve::Paint);
    if let Some(n) = (0..painted.len()).find(|&n| painted[n] != crossing[n]) {
        panic!(
            "pixel ({}, {}): Paint shows {:?}, Crossing {:?}; {w}x{h} {polys:?}",
            n % w as usize,
            n / w as usize,
            painted[n],
            crossing[n]
        );
    }
    let rows = 1 + input.band_rows as u16 % 16;
    let banded = render3_bands(&polys, w, h, Resolve::Paint, rows);
    if let Some(n) = (0..banded.len()).find(|&n| banded[n] != crossing[n]) {
        panic!(
            "pixel ({}, {}): Paint in bands of {rows} shows {:?}, Crossing {:?}; {w}x{h} {polys:?}",
            n % w as usize,
            n / w as usize,
            banded[n],
            crossing[n]
        );
    }
    if let Some(n) = (0..bisect.len()).find(|&n| bisect[n] != crossing[n]) {
        panic!(
            "pixel ({}, {}): Bisect shows {:?}, Crossing {:?}; {w}x{h} {polys:?}",
            n % w as usize,
            n / w as usize,
            bisect[n],
            crossing[n]
        );
    }
});
