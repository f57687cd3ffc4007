//! A scene into a display driver, through `DrawTargetPort`.
//!
//! The "driver" here is what a display on SPI looks like to
//! embedded-graphics: a `DrawTarget` that pays for every call (an address
//! window to set) and for every pixel it is sent. It counts both. The
//! demo scene (the binary list the firmware image embeds) is rendered
//! into it; every span arrives as one `fill_solid` of a one-row
//! rectangle, never as single pixels. A few rows of run-length runs then
//! arrive as one `fill_contiguous` each.
//!
//! ```sh
//! cargo run -p scanvert --example draw_target_port --features embedded-graphics
//! ```

use core::convert::Infallible;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use scanvert::controller::Controller;
use scanvert::display_list::DisplayList;
use scanvert::pixelcolor::Rgb565;
use scanvert::port::draw_target::DrawTargetPort;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;

/// The demo scene in binary form, as the firmware image embeds it.
const DEMO: &[u8] = include_bytes!("../../image/scenes/demo.scvl");

/// What a display driver was asked to do.
#[derive(Debug, Default)]
struct Calls {
    /// `draw_iter` calls, and the pixels they carried.
    draw_iter: u32,
    draw_iter_pixels: u64,
    /// `fill_solid` calls (one address window each).
    fill_solid: u32,
    /// `fill_contiguous` calls (one address window each).
    fill_contiguous: u32,
    /// `clear` calls.
    clear: u32,
    /// Pixels sent by all of the above.
    pixels: u64,
}

/// A 320 × 200 RGB565 panel that only counts.
#[derive(Debug, Default)]
struct Panel {
    calls: Calls,
}

impl OriginDimensions for Panel {
    fn size(&self) -> Size {
        Size::new(320, 200)
    }
}

impl DrawTarget for Panel {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Infallible> {
        self.calls.draw_iter += 1;
        let n = pixels.into_iter().count() as u64;
        self.calls.draw_iter_pixels += n;
        self.calls.pixels += n;
        Ok(())
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        self.calls.fill_contiguous += 1;
        let n = area.size.width as u64 * area.size.height as u64;
        self.calls.pixels += colors.into_iter().take(n as usize).count() as u64;
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, _color: Rgb565) -> Result<(), Infallible> {
        self.calls.fill_solid += 1;
        self.calls.pixels += area.size.width as u64 * area.size.height as u64;
        Ok(())
    }

    fn clear(&mut self, _color: Rgb565) -> Result<(), Infallible> {
        self.calls.clear += 1;
        self.calls.pixels += 320 * 200;
        Ok(())
    }
}

fn main() {
    let list = DisplayList::new_checked(DEMO).expect("the embedded demo list is valid");
    let mut edges = [Edge::EMPTY; 64];
    let mut port = DrawTargetPort::new(Panel::default());
    let stats = Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut port)
        .expect("the demo renders");

    let calls = &port.get_ref().calls;
    println!(
        "demo scene {}x{}: {} polygons, {} spans, {} polygon pixels, {} clear",
        list.width(),
        list.height(),
        stats.polygons,
        stats.spans,
        stats.pixels,
        stats.clears
    );
    println!(
        "the driver received: {} fill_solid, {} clear, {} fill_contiguous, {} draw_iter ({} single pixels)",
        calls.fill_solid, calls.clear, calls.fill_contiguous, calls.draw_iter, calls.draw_iter_pixels
    );
    println!(
        "{} calls for {} spans; {} pixels per call on average, where one call per pixel would be {} calls",
        calls.fill_solid,
        stats.spans,
        stats.pixels / calls.fill_solid.max(1) as u64,
        stats.pixels
    );
    assert_eq!(calls.fill_solid, stats.spans);
    assert_eq!(calls.draw_iter, 0);

    // Rows of run-length runs, such as a shaded renderer emits: a colour
    // ramp of 16 runs of 20 pixels on each of 8 rows.
    let before = port.get_ref().calls.fill_contiguous;
    for y in 190..198u16 {
        let ramp = (0..16u8).map(|i| (20u16, Rgb565::new(i * 2, i * 4, 31 - i * 2)));
        port.fill_run_row(y, 0, ramp).expect("infallible");
    }
    let rows = port.get_ref().calls.fill_contiguous - before;
    println!("8 rows of 16 runs each: {rows} fill_contiguous calls");
    assert_eq!(rows, 8);
}
