//! The band path into a real panel driver: a 240 × 240 ST7789 driven by
//! the `mipidsi` crate over SPI, with no frame buffer, sending only the
//! rows that changed.
//!
//! The SPI device, the data/command pin and the delay are stand-ins that
//! count what the driver sends: every `SpiDevice` transaction (one chip
//! select) and every byte. The bytes also go into a model of the panel's
//! memory (column and page address set, memory write), which the program
//! checks against the frame rendered whole: what the panel would show.
//!
//! A retained scene (a ground, a lit cube with a label, a clock label and
//! a level bar, in four segments) is drawn with `Scene::draw_marked`: the
//! rows marked in a `DirtyRows` are drawn in bands of at most 16 rows
//! through one band buffer of 16 × 240 pixels, each band ONE
//! `fill_contiguous` on the driver (an address window and a burst of
//! pixels), and the rows between are neither rendered nor sent. The rows
//! come from `Scene::update_marking`, which rebuilds the stale segments
//! and marks the rows whose content changed (by row hashes of the
//! segments' trapezoids and labels). Frames:
//!
//! - full: every row marked (the panel starts unknown);
//! - the clock ticks; the clock ticks and the bar grows; the bar shrinks:
//!   partial frames;
//! - the camera moves (every segment stale): the rows that changed;
//! - nothing changes: nothing is sent.
//!
//! Cross-checks, by the host only: after every frame the panel equals the
//! frame rendered whole, and every row whose pixels changed since the last
//! frame was marked; the bands whose hash changed (what a panel path that
//! renders every band and compares hashes would send) are printed beside.
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
use scanvert::geometry::{Angle, Light, Perspective, Pipeline, Point3, View, Viewport, Q16};
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::{
    Builder, DirtyRows, Procedure, Scene, SceneError, SceneStorage, DEFAULT_FONT,
};
use scanvert::visible::sweep::Resolve;
use std::cell::RefCell;
use std::rc::Rc;

const W: u16 = 240;
const H: u16 = 240;
/// Rows per band.
const ROWS: u16 = 16;
const BANDS: usize = H.div_ceil(ROWS) as usize;
/// The driver's SPI buffer, bytes: pixels go out in writes of this size.
const SPI_BUFFER: usize = 1024;

/// Transform depth and polygon vertices of the pipeline.
const DEPTH: usize = 4;
const N: usize = 16;
type Segment<'s, 'a> = Builder<'s, 'a, DEPTH, N>;

/// The scene's memory: 128 trapezoids, 32 faces, 4 segments, H rows, 16
/// edge slots, 32 active entries, W runs, 4 labels, 64 bytes of text.
type Storage = SceneStorage<128, 32, 4, { H as usize }, 16, 32, { W as usize }, 4, 64>;

const BACKGROUND: Rgb888 = Rgb888::new(0x10, 0x18, 0x28);

/// What a frame shows: the clock's text, the bar's length (in 1/40 of a
/// world unit) and the camera's eye.
#[derive(Clone, Copy, PartialEq)]
struct Step {
    what: &'static str,
    clock: &'static str,
    level: i32,
    eye: (i16, i16, i16),
}

/// The frames, each named by what changed.
const STEPS: [Step; 6] = [
    step("full", "12:00", 120, (3, 3, 5)),
    step("clock", "12:01", 120, (3, 3, 5)),
    step("clock, bar", "12:02", 160, (3, 3, 5)),
    step("bar", "12:02", 100, (3, 3, 5)),
    step("camera", "12:02", 100, (4, 3, 4)),
    step("nothing", "12:02", 100, (4, 3, 4)),
];

const fn step(what: &'static str, clock: &'static str, level: i32, eye: (i16, i16, i16)) -> Step {
    Step {
        what,
        clock,
        level,
        eye,
    }
}

fn p(x: i16, y: i16, z: i16) -> Point3 {
    Point3::from_int(x, y, z)
}

/// `v` fortieths of a unit.
fn q40(v: i32) -> Q16 {
    Q16::from_bits(v * 65536 / 40)
}

/// Segment 0: the ground, a square under the cube.
fn ground(b: &mut Segment<'_, '_>) -> Result<(), SceneError> {
    let g = [p(-6, -1, 6), p(6, -1, 6), p(6, -1, -6), p(-6, -1, -6)];
    b.face(&g, Rgb888::new(0x30, 0x50, 0x30)).map(|_| ())
}

/// Segment 1: the lit cube and its name.
fn cube(b: &mut Segment<'_, '_>) -> Result<(), SceneError> {
    for face in [
        [p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1)],
        [p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1)],
        [p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1)],
        [p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1)],
        [p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1)],
        [p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1)],
    ] {
        b.face(&face, Rgb888::new(0xe0, 0x40, 0x40))?;
    }
    b.label(p(-1, -1, 1), "scanvert", Rgb888::WHITE).map(|_| ())
}

/// Segment 2: the clock, a label over the cube's corner.
fn clock(b: &mut Segment<'_, '_>, text: &str) -> Result<(), SceneError> {
    b.label(p(1, 1, 1), text, Rgb888::WHITE).map(|_| ())
}

/// Segment 3: a flat bar on the ground in front of the cube, `level`
/// fortieths of a unit long.
fn bar(b: &mut Segment<'_, '_>, level: i32) -> Result<(), SceneError> {
    let (x0, x1, y) = (q40(-120), q40(-120 + level), q40(-38));
    let (z0, z1) = (q40(80), q40(100));
    let top = [
        Point3::new(x0, y, z1),
        Point3::new(x1, y, z1),
        Point3::new(x1, y, z0),
        Point3::new(x0, y, z0),
    ];
    b.face(&top, Rgb888::new(0x40, 0xc0, 0xff)).map(|_| ())
}

/// The scene's camera at `eye`, looking at the cube.
fn view(eye: (i16, i16, i16)) -> View {
    View::look_at(p(eye.0, eye.1, eye.2), p(0, 0, 0)).expect("the eye is not the target")
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

/// FNV-1a over pixels.
fn hash(pixels: &[Rgb565]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for &p in pixels {
        for b in RawU16::from(p).into_inner().to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// Ships bands to the driver, one `fill_contiguous` each.
struct Panel<D> {
    display: D,
    fills: u32,
    rows: u32,
}

impl<D: DrawTarget<Color = Rgb565>> BandTarget for Panel<D> {
    type Color = Rgb565;
    type Error = D::Error;

    fn ship(&mut self, y: u16, rows: u16, pixels: &[Rgb565]) -> Result<(), D::Error> {
        self.fills += 1;
        self.rows += rows as u32;
        let area = Rectangle::new(Point::new(0, y as i32), Size::new(W as u32, rows as u32));
        self.display.fill_contiguous(&area, pixels.iter().copied())
    }
}

fn main() {
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
        "ST7789 240x240 by mipidsi over SPI (driver buffer {SPI_BUFFER} bytes), bands of at most {ROWS} rows, band buffer {} pixels ({} bytes): init {init_t} transactions, {init_b} bytes",
        ROWS as usize * W as usize,
        ROWS as usize * W as usize * 2
    );
    let mut panel = Panel {
        display,
        fills: 0,
        rows: 0,
    };

    // The scene, its memory and the rows to send: no frame buffer.
    let mut storage = Box::new(Storage::new());
    let persp = Perspective::from_fov(
        Angle::from_degrees(60),
        W,
        Q16::from_int(1),
        Q16::from_int(100),
    )
    .expect("projection");
    let mut pipeline = Pipeline::<DEPTH, N>::new(persp, Viewport::centred(W, H).expect("window"));
    pipeline.set_light(Light::new([1, 2, 3], 70).expect("light"));
    let mut scene = Scene::new(storage.as_memory(), pipeline).expect("scene");
    let mut bits = [0u32; DirtyRows::words(H)];
    let mut dirty = DirtyRows::new(&mut bits, H).expect("bits for the frame");
    // Two row hashes a row for `update_marking`: rows whose content did
    // not change are not marked.
    let mut scratch = [0u64; 2 * H as usize];
    let mut band = vec![Rgb565::BLACK; ROWS as usize * W as usize];
    let bg = Rgb565::from(BACKGROUND);

    // The host's checks: the frame rendered whole, the last one, and the
    // band hashes of the last one.
    let mut whole = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut last: Option<Vec<Rgb565>> = None;
    let mut band_hashes = [0u64; BANDS];

    let frame_bytes = W as u64 * H as u64 * 2;
    let mut before: Option<Step> = None;
    dirty.mark_all(); // the panel starts unknown
    for step in STEPS {
        match before {
            None => scene.set_view(&view(step.eye)).expect("view"),
            Some(b) => {
                if b.eye != step.eye {
                    scene.set_view(&view(step.eye)).expect("view");
                }
                if b.clock != step.clock {
                    scene.invalidate(2).expect("segment");
                }
                if b.level != step.level {
                    scene.invalidate(3).expect("segment");
                }
            }
        }
        let mut c = |b: &mut Segment<'_, '_>| clock(b, step.clock);
        let mut l = |b: &mut Segment<'_, '_>| bar(b, step.level);
        let procs: &mut [&mut dyn Procedure<DEPTH, N>] =
            &mut [&mut ground, &mut cube, &mut c, &mut l];
        let u = scene
            .update_marking(procs, DEFAULT_FONT, &mut dirty, &mut scratch)
            .expect("the scene fits its memory");

        let (t0, b0) = link.borrow().counts();
        panel.fills = 0;
        panel.rows = 0;
        let (_, shipped) = scene
            .draw_marked(
                Resolve::default(),
                bg,
                DEFAULT_FONT,
                &dirty,
                ROWS,
                &mut band,
                &mut panel,
            )
            .expect("draws the marked rows");
        let (t1, b1) = link.borrow().counts();
        assert_eq!(shipped, panel.rows);

        // What the panel shows is the frame rendered whole, and every row
        // that changed was marked.
        let mut fb = FrameBuffer::new(&mut whole, W, H).expect("frame size");
        scene
            .draw(Resolve::default(), Some(bg), DEFAULT_FONT, &mut fb)
            .expect("renders");
        assert!(
            link.borrow().memory == whole,
            "{}: the panel shows the frame",
            step.what
        );
        let w = W as usize;
        let rows = |f: &[Rgb565], y: usize| f[y * w..(y + 1) * w].to_vec();
        let changed = (0..H as usize)
            .filter(|&y| last.as_ref().is_none_or(|l| rows(l, y) != rows(&whole, y)))
            .inspect(|&y| {
                assert!(
                    dirty.is_marked(y as u16),
                    "{}: row {y} changed, not marked",
                    step.what
                )
            })
            .count();
        let mut hashed = 0;
        for (k, h) in band_hashes.iter_mut().enumerate() {
            let y0 = k * ROWS as usize;
            let y1 = (y0 + ROWS as usize).min(H as usize);
            let n = hash(&whole[y0 * w..y1 * w]);
            if last.is_none() || *h != n {
                hashed += 1;
            }
            *h = n;
        }
        let bytes = b1 - b0;
        println!(
            "{:<10} rebuilt {} segment(s); {:>3} rows marked ({:>3} changed), {:>2} fill_contiguous, {:>3} SPI transactions, {:>7} bytes ({} of them pixels), {:>5.1}% of a full frame's pixels; band hashes: {:>2} of {BANDS} bands changed",
            step.what,
            u.regenerated,
            dirty.count(),
            changed,
            panel.fills,
            t1 - t0,
            bytes,
            panel.rows as u64 * W as u64 * 2,
            100.0 * (panel.rows as u64 * W as u64 * 2) as f64 / frame_bytes as f64,
            hashed,
        );
        dirty.clear();
        last = Some(whole.clone());
        before = Some(step);
    }
    println!("the panel's memory equals the frame rendered whole after each, and every changed row was marked: yes");

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
