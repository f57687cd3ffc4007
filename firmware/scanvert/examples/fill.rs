//! Polygons straight into a frame buffer, without a display list.
//!
//! `Rasterizer::fill` scan-converts one polygon (convex, concave or
//! self-intersecting, even-odd) into any `SpanTarget`, cut to a clip
//! rectangle. Vertices are Q12.4: whole pixels with `Vertex::from_px`,
//! sixteenths with `Vertex::from_bits`.
//!
//! ```sh
//! cargo run -p scanvert --example fill
//! ```

use scanvert::port::checksum::frame_checksum;
use scanvert::prelude::*;

const W: u16 = 48;
const H: u16 = 20;

fn main() {
    let mut pixels = [Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut pixels, W, H).expect("frame size");
    let mut edges = [Edge::EMPTY; 8]; // the largest polygon has 5 edges
    let mut raster = Rasterizer::new(&mut edges);
    let px = |points: &[(i16, i16)]| -> Vec<Vertex> {
        let v = points.iter().map(|&(x, y)| Vertex::from_px(x, y));
        v.collect::<Option<_>>().expect("in Q12.4 range")
    };
    let all = ClipRect::full(W, H);

    // A triangle, a self-intersecting star (its centre is outside: even-odd)
    // and a triangle cut to a clip rectangle, all with exact shared edges.
    let triangle = px(&[(1, 1), (20, 4), (6, 18)]);
    let star = px(&[(34, 1), (39, 18), (25, 7), (43, 7), (29, 18)]);
    let clip = ClipRect::from_window(
        ClipWindow {
            x0: 10,
            y0: 12,
            x1: 30,
            y1: 17,
        },
        W,
        H,
    );
    let cut = [
        Vertex::from_bits(0, 320),
        Vertex::from_bits(760, 200),
        Vertex::from_bits(600, 319),
    ];

    let mut spans = 0;
    for (shape, clip, color) in [
        (&triangle[..], &all, Rgb565::RED),
        (&star[..], &all, Rgb565::YELLOW),
        (&cut[..], &clip, Rgb565::CYAN),
    ] {
        let counts = raster
            .fill(shape.iter().copied(), clip, color, &mut fb)
            .expect("enough edge slots; memory cannot fail");
        spans += counts.spans;
    }

    for y in 0..H {
        let row = fb.row(y).expect("in the frame");
        let text: String = row
            .iter()
            .map(|&c| match c {
                Rgb565::RED => 'r',
                Rgb565::YELLOW => 'y',
                Rgb565::CYAN => 'c',
                _ => '.',
            })
            .collect();
        println!("{text}");
    }
    println!(
        "{spans} spans, checksum {:08x}",
        frame_checksum(fb.pixels())
    );
}
