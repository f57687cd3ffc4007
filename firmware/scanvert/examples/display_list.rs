//! A display list, assembled in a caller buffer, run by the controller
//! into a frame buffer.
//!
//! The list is validated once (`DisplayList::new_checked`, every fault a
//! typed error with its byte offset); the controller then runs it: clear,
//! clip registers, colours, polygons. Every error converts to
//! `Box<dyn Error>`, so `?` reports a fault with where it is.
//!
//! ```sh
//! cargo run -p scanvert --example display_list
//! ```

use scanvert::port::checksum::frame_checksum;
use scanvert::prelude::*;

const W: u16 = 40;
const H: u16 = 16;

/// Whole pixels, as every vertex of this list is.
fn v(x: i16, y: i16) -> Vertex {
    Vertex::from_px(x, y).expect("in Q12.4 range")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut bytes = [0u8; 256];
    let mut w = Writer::new(&mut bytes, W, H)?;
    w.clear(Rgb888::new(0x10, 0x10, 0x30))?;
    w.color(Rgb888::RED)?;
    w.poly([v(1, 1), v(18, 3), v(4, 15)])?;
    // Only columns 20..=39 from here on.
    w.clip(ClipWindow {
        x0: 20,
        y0: 0,
        x1: 39,
        y1: 15,
    })?;
    w.color(Rgb888::GREEN)?;
    w.poly([v(14, 2), v(38, 2), v(38, 8), v(14, 8)])?;
    w.color(Rgb888::YELLOW)?;
    w.poly([v(22, 6), v(34, 6), v(34, 14), v(22, 14), v(28, 10)])?; // concave
    let list = DisplayList::new_checked(w.finish())?;

    let mut pixels = [Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut pixels, W, H).ok_or("frame size")?;
    let mut edges = [Edge::EMPTY; 16];
    let stats = Controller::new(Rasterizer::new(&mut edges)).render(&list, &mut fb)?;

    for y in 0..H {
        let row = fb.row(y).ok_or("row")?;
        let glyph = |c: &Rgb565| match *c {
            Rgb565::RED => 'r',
            Rgb565::GREEN => 'g',
            Rgb565::YELLOW => 'y',
            _ => '.',
        };
        println!("{}", row.iter().map(glyph).collect::<String>());
    }
    println!(
        "{} bytes, {} commands: {} polygons, {} spans; checksum {:08x}",
        list.as_bytes().len(),
        stats.commands,
        stats.polygons,
        stats.spans,
        frame_checksum(fb.pixels())
    );
    Ok(())
}
