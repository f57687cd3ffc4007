//! The band path into a real panel driver: a 240 × 240 ST7789 driven by
//! the `mipidsi` crate over SPI, with no frame buffer.
//!
//! The SPI device, the data/command pin and the delay are stand-ins that
//! count what the driver sends: every `SpiDevice` transaction (one chip
//! select) and every byte. The bytes also go into a model of the panel's
//! memory (column and page address set, memory write), which the program
//! checks against the frame rendered whole: what the panel would show.
//!
//! A display list (2D polygons, a lit 3D cube, labels) is rendered in
//! 16-row bands through one band buffer of 16 × 240 pixels; each band is
//! ONE `fill_contiguous` on the driver (an address window and a burst of
//! pixels). Two frames:
//!
//! - full: every band shipped;
//! - partial: the next frame, where a label's text and a 2D level bar
//!   changed. Every band is rendered again, but a band is shipped only
//!   when its pixels differ from what was shipped for it last time (a
//!   64-bit hash of each band is kept, 15 words in all, not the frame);
//!   the panel keeps the other rows.
//!
//! With `--out FILE.ppm` the panel's memory after the last frame is also
//! written as a PPM image.
//!
//! ```sh
//! cargo run -p scanvert-sim --example st7789
//! ```

use core::convert::Infallible;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::pixelcolor::raw::{RawData, RawU16};
use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_graphics_core::primitives::Rectangle;
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::{Operation, SpiDevice};
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::geometry::{Angle, Point3, View, Q16};
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert_sim::memory::ListMemory;
use std::cell::RefCell;
use std::rc::Rc;

const W: u16 = 240;
const H: u16 = 240;
/// Rows per band.
const ROWS: u16 = 16;
const BANDS: usize = H.div_ceil(ROWS) as usize;
/// The driver's SPI buffer, bytes: pixels go out in writes of this size.
const SPI_BUFFER: usize = 1024;

/// A vertex at `(x, y)` pixels.
fn v(x: i16, y: i16) -> Vertex {
    Vertex::from_bits(x * 16, y * 16)
}

/// The list: a background, a 2D ground and sun, a lit cube with two
/// labels (one reads `clock`), and a level bar `level` pixels long.
fn list<'b>(buf: &'b mut [u8], clock: &str, level: i16) -> &'b [u8] {
    let mut w = Writer::new(buf, W, H).expect("frame size");
    w.clear(Rgb888::new(0x10, 0x18, 0x28)).unwrap();
    w.color(Rgb888::new(0x30, 0x50, 0x30)).unwrap();
    w.poly([v(0, 150), v(240, 130), v(240, 240), v(0, 240)])
        .unwrap();
    w.color(Rgb888::new(0xff, 0xc0, 0x40)).unwrap();
    w.poly([v(190, 12), v(222, 24), v(214, 52), v(186, 44)])
        .unwrap();
    w.perspective(
        Angle::from_degrees(60),
        Q16::from_int(1),
        Q16::from_int(100),
    )
    .unwrap();
    let eye = View::look_at(Point3::from_int(3, 3, 5), Point3::from_int(0, 0, 0)).unwrap();
    w.view(eye.eye, eye.yaw, eye.pitch).unwrap();
    w.light(Point3::from_int(1, 2, 3), 70).unwrap();
    w.segment(1).unwrap();
    w.color(Rgb888::new(0xe0, 0x40, 0x40)).unwrap();
    let p = Point3::from_int;
    for face in [
        [p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1)],
        [p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1)],
        [p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1)],
        [p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1)],
        [p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1)],
        [p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1)],
    ] {
        w.face(face).unwrap();
    }
    w.color(Rgb888::new(0xff, 0xff, 0xff)).unwrap();
    w.label(p(1, 1, 1), clock).unwrap();
    w.label(p(-1, -1, 1), "scanvert").unwrap();
    w.color(Rgb888::new(0x40, 0xc0, 0xff)).unwrap();
    w.poly([v(8, 220), v(8 + level, 220), v(8 + level, 232), v(8, 232)])
        .unwrap();
    w.finish()
}

/// What went over the link, and the panel's memory it wrote.
struct Link {
    dc: bool,
    transactions: u64,
    bytes: u64,
    /// The last command, its argument bytes so far.
    command: u8,
    args: Vec<u8>,
    /// The address window (inclusive) and the write position in it.
    columns: (u16, u16),
    pages: (u16, u16),
    at: (u16, u16),
    memory: Vec<Rgb565>,
}

impl Link {
    /// A byte with DC high: an argument, or pixel data after RAMWR.
    fn data(&mut self, b: u8) {
        self.args.push(b);
        match self.command {
            // CASET, RASET: start and end, big-endian.
            0x2a | 0x2b if self.args.len() == 4 => {
                let a = &self.args;
                let r = (
                    u16::from_be_bytes([a[0], a[1]]),
                    u16::from_be_bytes([a[2], a[3]]),
                );
                if self.command == 0x2a {
                    self.columns = r;
                } else {
                    self.pages = r;
                }
            }
            // RAMWR: RGB565, big-endian, row by row through the window.
            0x2c if self.args.len() == 2 => {
                let c = Rgb565::from(RawU16::new(u16::from_be_bytes([
                    self.args[0],
                    self.args[1],
                ])));
                self.args.clear();
                let (x, y) = self.at;
                if let Some(p) = self.memory.get_mut(y as usize * W as usize + x as usize) {
                    *p = c;
                }
                self.at = if x < self.columns.1 {
                    (x + 1, y)
                } else {
                    (self.columns.0, y + 1)
                };
            }
            _ => {}
        }
    }

    fn take(&mut self, bytes: &[u8]) {
        self.bytes += bytes.len() as u64;
        for &b in bytes {
            if self.dc {
                self.data(b);
            } else {
                self.command = b;
                self.args.clear();
                if b == 0x2c {
                    self.at = (self.columns.0, self.pages.0);
                }
            }
        }
    }

    /// Transactions and bytes so far.
    fn counts(&self) -> (u64, u64) {
        (self.transactions, self.bytes)
    }
}

/// The SPI device: one transaction per chip select.
struct Spi(Rc<RefCell<Link>>);

impl embedded_hal::spi::ErrorType for Spi {
    type Error = Infallible;
}

impl SpiDevice for Spi {
    fn transaction(&mut self, ops: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        let mut link = self.0.borrow_mut();
        link.transactions += 1;
        for op in ops {
            match op {
                Operation::Write(b) => link.take(b),
                Operation::Transfer(_, w) => link.take(w),
                Operation::TransferInPlace(b) => link.take(b),
                Operation::Read(_) | Operation::DelayNs(_) => {}
            }
        }
        Ok(())
    }
}

/// The data/command pin.
struct Dc(Rc<RefCell<Link>>);

impl embedded_hal::digital::ErrorType for Dc {
    type Error = Infallible;
}

impl OutputPin for Dc {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().dc = false;
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        self.0.borrow_mut().dc = true;
        Ok(())
    }
}

struct NoDelay;

impl DelayNs for NoDelay {
    fn delay_ns(&mut self, _: u32) {}
}

/// FNV-1a over a band's pixels.
fn hash(pixels: &[Rgb565]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for &p in pixels {
        for b in RawU16::from(p).into_inner().to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// Ships bands to the driver, one `fill_contiguous` each; with `changed`,
/// only those whose hash differs from the band shipped there last.
struct Panel<D> {
    display: D,
    shipped: [Option<u64>; BANDS],
    changed: bool,
    bands: u32,
    rows: u32,
}

impl<D: DrawTarget<Color = Rgb565>> BandTarget for Panel<D> {
    type Color = Rgb565;
    type Error = D::Error;

    fn ship(&mut self, y: u16, rows: u16, pixels: &[Rgb565]) -> Result<(), D::Error> {
        let k = (y / ROWS) as usize;
        let h = hash(pixels);
        if self.changed && self.shipped[k] == Some(h) {
            return Ok(());
        }
        self.shipped[k] = Some(h);
        self.bands += 1;
        self.rows += rows as u32;
        let area = Rectangle::new(Point::new(0, y as i32), Size::new(W as u32, rows as u32));
        self.display.fill_contiguous(&area, pixels.iter().copied())
    }
}

fn main() {
    let (mut a, mut b) = ([0u8; 2048], [0u8; 2048]);
    let first = DisplayList::new_checked(list(&mut a, "12:00", 120)).expect("valid list");
    let next = DisplayList::new_checked(list(&mut b, "12:01", 128)).expect("valid list");

    // The panel.
    let link = Rc::new(RefCell::new(Link {
        dc: false,
        transactions: 0,
        bytes: 0,
        command: 0,
        args: Vec::new(),
        columns: (0, 0),
        pages: (0, 0),
        at: (0, 0),
        memory: vec![Rgb565::BLACK; W as usize * H as usize],
    }));
    let mut spi_buffer = [0u8; SPI_BUFFER];
    let interface =
        mipidsi::interface::SpiInterface::new(Spi(link.clone()), Dc(link.clone()), &mut spi_buffer);
    let display = mipidsi::Builder::new(mipidsi::models::ST7789, interface)
        .display_size(W, H)
        .init(&mut NoDelay)
        .expect("the driver starts");
    let (init_t, init_b) = link.borrow().counts();
    println!(
        "ST7789 240x240 by mipidsi over SPI (driver buffer {SPI_BUFFER} bytes), {ROWS}-row bands, band buffer {} pixels ({} bytes): init {init_t} transactions, {init_b} bytes",
        ROWS as usize * W as usize,
        ROWS as usize * W as usize * 2
    );
    let mut panel = Panel {
        display,
        shipped: [None; BANDS],
        changed: false,
        bands: 0,
        rows: 0,
    };
    let mut band = vec![Rgb565::BLACK; ROWS as usize * W as usize];
    let mut whole = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut last: Vec<Rgb565> = Vec::new();

    for (name, list, changed) in [("full", &first, false), ("partial", &next, true)] {
        let (t0, b0) = link.borrow().counts();
        panel.changed = changed;
        panel.bands = 0;
        panel.rows = 0;
        // Memory sized from the list: the edge table, the 3D layer's pools
        // and its workspace, no frame.
        let mut memory = ListMemory::for_bands(list).expect("memory for the list");
        let (mut controller, table) = memory.band_parts();
        controller
            .render_bands(list, table, ROWS, &mut band, &mut panel)
            .expect("renders in bands");
        let (t1, b1) = link.borrow().counts();
        println!(
            "{name} frame: {} of {BANDS} bands shipped ({} rows, one fill_contiguous each), {} SPI transactions, {} bytes ({} of them pixels)",
            panel.bands,
            panel.rows,
            t1 - t0,
            b1 - b0,
            panel.rows as u64 * W as u64 * 2
        );
        // What the panel shows is the frame rendered whole.
        whole.fill(Rgb565::BLACK);
        let mut fb = FrameBuffer::new(&mut whole, W, H).expect("frame size");
        memory.controller().render(list, &mut fb).expect("renders");
        assert!(
            link.borrow().memory == whole,
            "{name}: the panel shows the frame"
        );
        assert!(last != whole, "{name}: the frame differs from the last");
        last.clone_from(&whole);
    }
    println!("the panel's memory equals the frame rendered whole after each: yes");

    let args: Vec<String> = std::env::args().collect();
    if let [_, flag, path] = args.as_slice() {
        if flag == "--out" {
            use scanvert::color::ToRgb888;
            let mut ppm = format!("P6\n{W} {H}\n255\n").into_bytes();
            for &c in &link.borrow().memory {
                let c = c.to_rgb888();
                ppm.extend([c.r(), c.g(), c.b()]);
            }
            std::fs::write(path, ppm).expect("writes the image");
            println!("wrote {path}");
        }
    }
}
