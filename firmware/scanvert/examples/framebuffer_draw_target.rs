//! embedded-graphics drawing into scanvert's frame buffer.
//!
//! A small scene is rendered by the controller; then embedded-graphics
//! draws a frame, a circle and a line of text into the same
//! `FrameBuffer`, which is a `DrawTarget`. The frame is printed as text,
//! one character per pixel, and with `--out FILE.ppm` also written as a
//! PPM image.
//!
//! ```sh
//! cargo run -p scanvert --example framebuffer_draw_target --features embedded-graphics
//! ```

use embedded_graphics::mono_font::{ascii::FONT_6X10, MonoTextStyle};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle};
use embedded_graphics::text::Text;
use scanvert::color::ToRgb888;
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::pixelcolor::{Rgb565, Rgb888};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;

const W: u16 = 96;
const H: u16 = 40;

/// A vertex at `(x, y)` pixels plus `(fx, fy)` sixteenths.
fn v((x, fx): (i16, i16), (y, fy): (i16, i16)) -> Vertex {
    Vertex::from_bits(x * 16 + fx, y * 16 + fy)
}

/// The scene: a dark background, a red triangle and a blue concave shape.
fn scene(buf: &mut [u8]) -> &[u8] {
    let mut w = Writer::new(buf, W, H).expect("frame size");
    w.clear(Rgb888::new(0x10, 0x14, 0x1c)).unwrap();
    w.color(Rgb888::new(0xef, 0x53, 0x50)).unwrap();
    w.poly([v((4, 0), (36, 0)), v((30, 8), (3, 4)), v((44, 0), (36, 0))])
        .unwrap();
    w.color(Rgb888::new(0x4f, 0xc3, 0xf7)).unwrap();
    let arrow = [(50, 30), (70, 14), (70, 22), (92, 22), (92, 38), (70, 38)];
    w.poly(arrow.map(|(x, y)| v((x, 0), (y, 0)))).unwrap();
    w.finish()
}

/// One character for a pixel.
fn glyph(c: Rgb565) -> char {
    match c {
        Rgb565::WHITE => '#',
        Rgb565::YELLOW => 'o',
        c if c == Rgb565::new(0x10 >> 3, 0x14 >> 2, 0x1c >> 3) => '.',
        c if c.r() > c.b() => 'r',
        _ => 'b',
    }
}

fn main() -> std::io::Result<()> {
    let mut bytes = [0u8; 256];
    let list = DisplayList::new_checked(scene(&mut bytes)).expect("valid list");
    let mut pixels = [Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut pixels, W, H).expect("frame size");
    let mut edges = [Edge::EMPTY; 8];
    let stats = Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut fb)
        .expect("renders");

    // embedded-graphics into the same frame.
    Rectangle::new(Point::zero(), Size::new(W as u32, H as u32))
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::WHITE, 1))
        .draw(&mut fb)
        .expect("infallible");
    Circle::new(Point::new(6, 4), 9)
        .into_styled(PrimitiveStyle::with_fill(Rgb565::YELLOW))
        .draw(&mut fb)
        .expect("infallible");
    Text::new(
        "scanvert",
        Point::new(44, 10),
        MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE),
    )
    .draw(&mut fb)
    .expect("infallible");

    println!(
        "{}x{}: {} polygons by scanvert, then a rectangle, a circle and text by embedded-graphics",
        W, H, stats.polygons
    );
    for y in 0..H {
        let row = fb.row(y).expect("in the frame");
        println!("{}", row.iter().map(|&c| glyph(c)).collect::<String>());
    }

    let args: Vec<String> = std::env::args().collect();
    if let [_, flag, path] = args.as_slice() {
        if flag == "--out" {
            let mut ppm = format!("P6\n{W} {H}\n255\n").into_bytes();
            for &c in fb.pixels() {
                let c = c.to_rgb888();
                ppm.extend([c.r(), c.g(), c.b()]);
            }
            std::fs::write(path, ppm)?;
            println!("wrote {path}");
        }
    }
    Ok(())
}
