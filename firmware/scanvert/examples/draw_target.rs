//! A display list into an embedded-graphics display, through
//! `DrawTargetPort`, and embedded-graphics text over it.
//!
//! The "display" is what a panel on SPI looks like to embedded-graphics:
//! a `DrawTarget` that pays for every call (an address window) and keeps
//! its pixels. Every span arrives as one `fill_solid` of a one-row
//! rectangle, never as single pixels. The same list rendered into a
//! `FrameBuffer` gives the same pixels.
//!
//! ```sh
//! cargo run -p scanvert --example draw_target
//! ```

use core::convert::Infallible;
use embedded_graphics::mono_font::{ascii::FONT_5X8, MonoTextStyle};
use embedded_graphics::prelude::{DrawTarget, Drawable, OriginDimensions, Pixel, Point};
use embedded_graphics::prelude::{PointsIter, Size};
use embedded_graphics::primitives::Rectangle;
use embedded_graphics::text::Text;
use scanvert::prelude::*;
use scanvert::DrawTargetPort;

const W: usize = 48;
const H: usize = 16;

/// A 48 × 16 RGB565 panel that keeps its pixels and counts the calls.
struct Panel {
    pixels: [Rgb565; W * H],
    fill_solid: u32,
    single_pixels: u32,
}

impl OriginDimensions for Panel {
    fn size(&self) -> Size {
        Size::new(W as u32, H as u32)
    }
}

impl Panel {
    fn put(&mut self, p: Point, c: Rgb565) {
        if (0..W as i32).contains(&p.x) && (0..H as i32).contains(&p.y) {
            self.pixels[p.y as usize * W + p.x as usize] = c;
        }
    }
}

impl DrawTarget for Panel {
    type Color = Rgb565;
    type Error = Infallible;

    /// Pixel by pixel: what a driver must avoid.
    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        for Pixel(p, c) in pixels {
            self.single_pixels += 1;
            self.put(p, c);
        }
        Ok(())
    }

    /// One address window, one burst.
    fn fill_solid(&mut self, area: &Rectangle, color: Rgb565) -> Result<(), Infallible> {
        self.fill_solid += 1;
        area.points().for_each(|p| self.put(p, color));
        Ok(())
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut bytes = [0u8; 128];
    let mut w = Writer::new(&mut bytes, W as u16, H as u16)?;
    w.color(Rgb888::BLUE)?;
    w.poly([(0, 0), (48, 0), (48, 16), (0, 16)].map(|(x, y)| Vertex::from_px(x, y).unwrap()))?;
    w.color(Rgb888::RED)?;
    w.poly([(2, 14), (24, 1), (46, 14)].map(|(x, y)| Vertex::from_px(x, y).unwrap()))?;
    let list = DisplayList::new_checked(w.finish())?;
    let mut edges = [Edge::EMPTY; 8];
    let mut controller = Controller::new(Rasterizer::new(&mut edges));

    let mut panel = Panel {
        pixels: [Rgb565::BLACK; W * H],
        fill_solid: 0,
        single_pixels: 0,
    };
    let stats = controller.render(&list, &mut DrawTargetPort::new(&mut panel))?;
    println!(
        "{} spans: {} fill_solid calls, {} single pixels",
        stats.spans, panel.fill_solid, panel.single_pixels
    );

    let mut pixels = [Rgb565::BLACK; W * H];
    let mut fb = FrameBuffer::new(&mut pixels, W as u16, H as u16).ok_or("frame size")?;
    controller.render(&list, &mut fb)?;
    println!(
        "the same pixels as a FrameBuffer: {}",
        fb.pixels() == &panel.pixels[..]
    );

    // The panel is the caller's again: embedded-graphics text over the scene.
    Text::new(
        "scanvert",
        Point::new(4, 11),
        MonoTextStyle::new(&FONT_5X8, Rgb565::WHITE),
    )
    .draw(&mut panel)?;
    for row in panel.pixels.chunks(W) {
        let glyph = |c: &Rgb565| match *c {
            Rgb565::RED => 'r',
            Rgb565::BLUE => '.',
            Rgb565::WHITE => '#',
            _ => ' ',
        };
        println!("{}", row.iter().map(glyph).collect::<String>());
    }
    Ok(())
}
