//! The refresh controller: generates hsync and vsync from a
//! [`VideoTiming`], clock by clock, and reads the frame-buffer RAM's read
//! port during active display, producing the [`Frame`] a monitor shows.
//!
//! The beam position `(x, y)` counts pixel clocks within the line and
//! lines within the frame, starting at the first active pixel. On each
//! clock the controller
//! - asserts hsync while `x` is in the horizontal sync pulse, and vsync
//!   while `y` is in the vertical sync pulse (a whole number of lines);
//!   a pulse is counted when the signal is asserted (its leading edge);
//! - during active display reads pixel `(x, y)` through the read port,
//!   which it clocks at the pixel clock; during blanking the port idles;
//! - during the vertical retrace strobes the RAM's vertical blanking, where
//!   a double-buffered RAM exchanges its banks if asked to.
//!
//! [`CoSimulation`] runs the graphic controller and the refresh controller
//! together, each on its own clock.
//!
//! # RAM and mode of different sizes
//! The monitor shows the active area of the timing. Where that area reaches
//! beyond the RAM, the read misses (the address decoder selects no cell)
//! and the monitor shows black there. Where the RAM is larger, only its
//! top-left `width × height` corner is read.

use crate::dual_port::{DualPortRam, ReadPort, WritePort};
use crate::timing::VideoTiming;
use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::Rgb565;
use scanvert::port::{Span, SpanTarget};

const BLACK: Rgb565 = Rgb565::new(0, 0, 0);

/// What the refresh controller reads pixels from: the frame-buffer RAM's
/// read port, or (with no frame RAM) the ring of run-length rows of
/// [`race`](crate::race).
pub trait PixelSource {
    /// The pixel at `(x, y)`, read on this clock, or `None` where there is
    /// none (the monitor shows black).
    fn read(&mut self, x: u16, y: u16) -> Option<Rgb565>;
    /// The source idles for `cycles` clocks (blanking).
    fn idle(&mut self, cycles: u64);
    /// Strobed on each clock of the vertical retrace; `true` when the
    /// source exchanged its banks.
    fn vertical_blank(&mut self) -> bool;
}

impl PixelSource for ReadPort<'_> {
    fn read(&mut self, x: u16, y: u16) -> Option<Rgb565> {
        ReadPort::read(self, x, y)
    }
    fn idle(&mut self, cycles: u64) {
        ReadPort::idle(self, cycles)
    }
    fn vertical_blank(&mut self) -> bool {
        ReadPort::vertical_blank(self)
    }
}

/// What the refresh controller did during one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RefreshCounters {
    /// Pixel clocks.
    pub clocks: u64,
    /// Lines completed.
    pub lines: u64,
    /// Leading edges of hsync.
    pub hsync_pulses: u64,
    /// Leading edges of vsync.
    pub vsync_pulses: u64,
    /// Pixels read from the RAM (active pixels inside the RAM).
    pub pixels_read: u64,
    /// Bank swaps of a double-buffered RAM during this frame's retrace.
    pub bank_swaps: u64,
}

/// One frame as the monitor sees it: the active area's pixels, row-major,
/// and the refresh controller's counters for the frame.
///
/// # Guarantees
/// `pixels().len() == width × height`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    width: u16,
    height: u16,
    pixels: Vec<Rgb565>,
    counters: RefreshCounters,
}

impl Frame {
    /// A frame of the given pixels with zero counters, or `None` when
    /// `pixels.len() != width × height`.
    pub fn from_pixels(width: u16, height: u16, pixels: Vec<Rgb565>) -> Option<Frame> {
        (pixels.len() == width as usize * height as usize).then_some(Frame {
            width,
            height,
            pixels,
            counters: RefreshCounters::default(),
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The pixels, row-major.
    pub fn pixels(&self) -> &[Rgb565] {
        &self.pixels
    }

    /// The pixel at `(x, y)`, or `None` outside the frame.
    pub fn pixel(&self, x: u16, y: u16) -> Option<Rgb565> {
        if x < self.width && y < self.height {
            self.pixels
                .get(y as usize * self.width as usize + x as usize)
                .copied()
        } else {
            None
        }
    }

    /// Row `y`, or `None` outside the frame.
    pub fn row(&self, y: u16) -> Option<&[Rgb565]> {
        let w = self.width as usize;
        let start = y as usize * w;
        (y < self.height)
            .then(|| self.pixels.get(start..start + w))
            .flatten()
    }

    /// The refresh controller's counters for this frame.
    pub fn counters(&self) -> RefreshCounters {
        self.counters
    }

    /// The frame checksum shared with the target
    /// ([`scanvert::port::checksum::frame_checksum`]).
    pub fn checksum(&self) -> u32 {
        scanvert::port::checksum::frame_checksum(&self.pixels)
    }
}

/// The refresh controller: a beam counter, the sync generator and the
/// monitor's picture of the frame in progress.
#[derive(Clone, Debug)]
pub struct RefreshController {
    timing: VideoTiming,
    x: u32,
    y: u32,
    hsync: bool,
    vsync: bool,
    screen: Vec<Rgb565>,
    counters: RefreshCounters,
}

impl RefreshController {
    /// A controller for `timing`, with the beam at the first active pixel
    /// of a frame.
    pub fn new(timing: VideoTiming) -> Self {
        RefreshController {
            timing,
            x: 0,
            y: 0,
            hsync: false,
            vsync: false,
            screen: vec![BLACK; Self::area(&timing)],
            counters: RefreshCounters::default(),
        }
    }

    fn area(t: &VideoTiming) -> usize {
        t.width() as usize * t.height() as usize
    }

    /// The video mode.
    pub fn timing(&self) -> &VideoTiming {
        &self.timing
    }

    /// The beam position: `(pixel clock in the line, line in the frame)`.
    pub fn beam(&self) -> (u32, u32) {
        (self.x, self.y)
    }

    /// The hsync level driven on the last clock.
    pub fn hsync(&self) -> bool {
        self.hsync
    }

    /// The vsync level driven on the last clock.
    pub fn vsync(&self) -> bool {
        self.vsync
    }

    /// `true` while the beam is in the vertical retrace (below the active
    /// lines).
    pub fn in_vertical_retrace(&self) -> bool {
        self.y >= self.timing.height() as u32
    }

    /// Counters of the frame in progress.
    pub fn counters(&self) -> RefreshCounters {
        self.counters
    }

    /// Runs one pixel clock: drives the syncs, reads or idles the port,
    /// advances the beam. Returns the frame when this was its last clock.
    ///
    /// The port is the frame-buffer RAM's read port, or any other
    /// [`PixelSource`]: the ring of run-length rows of
    /// [`race`](crate::race), which has no frame RAM.
    pub fn tick<S: PixelSource + ?Sized>(&mut self, port: &mut S) -> Option<Frame> {
        let (h, v) = (self.timing.horizontal(), self.timing.vertical());
        let (x, y) = (self.x, self.y);
        let hsync = (h.sync_start()..h.sync_end()).contains(&x);
        let vsync = (v.sync_start()..v.sync_end()).contains(&y);
        self.counters.hsync_pulses += u64::from(hsync && !self.hsync);
        self.counters.vsync_pulses += u64::from(vsync && !self.vsync);
        self.hsync = hsync;
        self.vsync = vsync;

        if x < h.active as u32 && y < v.active as u32 {
            // Both below 4096 here, so they fit u16 and the index is in
            // the screen.
            let pixel = match port.read(x as u16, y as u16) {
                Some(p) => {
                    self.counters.pixels_read += 1;
                    p
                }
                None => BLACK,
            };
            if let Some(cell) = self
                .screen
                .get_mut(y as usize * h.active as usize + x as usize)
            {
                *cell = pixel;
            }
        } else {
            port.idle(1);
            if y >= v.active as u32 {
                self.counters.bank_swaps += u64::from(port.vertical_blank());
            }
        }
        self.counters.clocks += 1;

        self.x += 1;
        if self.x < h.total() {
            return None;
        }
        self.x = 0;
        self.y += 1;
        self.counters.lines += 1;
        if self.y < v.total() {
            return None;
        }
        self.y = 0;
        let pixels = std::mem::replace(&mut self.screen, vec![BLACK; Self::area(&self.timing)]);
        Some(Frame {
            width: h.active,
            height: v.active,
            pixels,
            counters: std::mem::take(&mut self.counters),
        })
    }

    /// Clocks the controller until the frame in progress is complete and
    /// returns it: from a new controller, exactly one whole frame. The RAM's
    /// read port is driven at the pixel clock.
    pub fn read_frame(&mut self, ram: &mut DualPortRam) -> Frame {
        ram.set_read_clock(self.timing.pixel_clock());
        let mut port = ram.read_port();
        loop {
            if let Some(frame) = self.tick(&mut port) {
                return frame;
            }
        }
    }
}

/// The graphic controller and the refresh controller running at once, each
/// on its own clock: a [`SpanTarget`] that stores each span through the
/// RAM's write port, then runs the refresh controller for as long as the
/// write took on the write port's clock. Every frame completed on the way
/// is kept.
///
/// Time is kept exactly, in cycles of both clocks: after `w` write cycles
/// at `f_w` the refresh controller has run the `r` pixel clocks (at `f_p`)
/// with `r / f_p ≥ w / f_w` and `(r − 1) / f_p < w / f_w`.
///
/// By default every frame completed is kept ([`frames`](Self::frames));
/// [`keeping_last`](Self::keeping_last) keeps only the newest, so that a
/// long run holds one frame, not all of them.
#[derive(Debug)]
pub struct CoSimulation<'a> {
    ram: &'a mut DualPortRam,
    refresh: &'a mut RefreshController,
    write_cycles: u64,
    read_cycles: u64,
    frames: Vec<Frame>,
    /// Frames completed so far, kept or not.
    completed: u64,
    /// Keep only the newest frame.
    last_only: bool,
}

impl<'a> CoSimulation<'a> {
    /// Starts both clocks at zero; the read port is driven at the pixel
    /// clock.
    pub fn new(ram: &'a mut DualPortRam, refresh: &'a mut RefreshController) -> Self {
        ram.set_read_clock(refresh.timing().pixel_clock());
        CoSimulation {
            ram,
            refresh,
            write_cycles: 0,
            read_cycles: 0,
            frames: Vec::new(),
            completed: 0,
            last_only: false,
        }
    }

    /// Keeps only the newest frame completed: [`frames`](Self::frames)
    /// holds at most one.
    pub fn keeping_last(mut self) -> Self {
        self.last_only = true;
        self
    }

    /// Runs the refresh controller up to the writer's time.
    fn catch_up(&mut self) {
        let fw = u128::from(self.ram.write_counters().clock.hz());
        let fp = u128::from(self.refresh.timing().pixel_clock().hz());
        let mut port = self.ram.read_port();
        while u128::from(self.read_cycles) * fw < u128::from(self.write_cycles) * fp {
            self.read_cycles += 1;
            if let Some(frame) = self.refresh.tick(&mut port) {
                self.completed += 1;
                if self.last_only {
                    self.frames.clear();
                }
                self.frames.push(frame);
            }
        }
    }

    /// The writer idles for `cycles` write-port cycles.
    pub fn wait(&mut self, cycles: u64) {
        self.write_cycles += cycles;
        self.catch_up();
    }

    /// Asks the RAM for a bank swap (see
    /// [`DualPortRam::request_swap`]).
    pub fn request_swap(&mut self) {
        self.ram.request_swap();
    }

    /// The writer idles until no swap is pending.
    pub fn wait_for_swap(&mut self) {
        while self.ram.swap_pending() {
            self.wait(1);
        }
    }

    /// The writer idles until the refresh controller has completed
    /// another frame.
    pub fn wait_for_frame(&mut self) {
        let n = self.completed;
        while self.completed == n {
            self.wait(1);
        }
    }

    /// How many frames the refresh controller has completed so far, kept
    /// or not.
    pub fn completed(&self) -> u64 {
        self.completed
    }

    /// Cycles run so far: `(write port, pixel clock)`.
    pub fn cycles(&self) -> (u64, u64) {
        (self.write_cycles, self.read_cycles)
    }

    /// The RAM.
    pub fn ram(&self) -> &DualPortRam {
        self.ram
    }

    /// Frames completed so far (with [`keeping_last`](Self::keeping_last),
    /// the newest only).
    pub fn frames(&self) -> &[Frame] {
        &self.frames
    }

    /// Ends the co-simulation with the frames completed.
    pub fn into_frames(self) -> Vec<Frame> {
        self.frames
    }

    /// Runs one write-port access, then lets the refresh controller catch up.
    fn write<R>(&mut self, access: impl FnOnce(&mut WritePort<'_>) -> R) -> R {
        let before = self.ram.write_counters().cycles;
        let r = access(&mut self.ram.write_port());
        self.write_cycles += self.ram.write_counters().cycles - before;
        self.catch_up();
        r
    }
}

impl SpanTarget for CoSimulation<'_> {
    type Color = Rgb565;
    type Error = Infallible;
    /// The write port takes a cycle for every pixel written (the
    /// reference unit's 50 Mpixel/s): a pixel written again costs its time.
    const OVERDRAW_IS_CHEAP: bool = false;

    fn size(&self) -> (u16, u16) {
        (self.ram.width(), self.ram.height())
    }

    fn fill_span(&mut self, span: Span, color: Rgb565) -> Result<(), Infallible> {
        self.write(|port| port.fill_span(span, color))
    }

    fn clear(&mut self, color: Rgb565) -> Result<(), Infallible> {
        self.write(|port| port.clear(color))
    }

    fn begin_polygon(&mut self) {
        self.write(|port| port.begin_polygon())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timing::{AxisTiming, Clock};

    fn tiny() -> VideoTiming {
        let axis = |active, sync| AxisTiming {
            active,
            front_porch: 1,
            sync,
            back_porch: 1,
        };
        VideoTiming::new("tiny", Clock::from_mhz(1).unwrap(), axis(4, 2), axis(3, 1)).unwrap()
    }

    #[test]
    fn counts_one_tiny_frame() {
        let mut ram = DualPortRam::new(4, 3);
        let c = Rgb565::new(3, 4, 5);
        ram.write_port()
            .fill_span(Span { y: 2, x0: 1, x1: 3 }, c)
            .unwrap();
        let mut rc = RefreshController::new(tiny());
        let f = rc.read_frame(&mut ram);
        let n = f.counters();
        // 8 clocks × 6 lines.
        assert_eq!((n.clocks, n.lines), (48, 6));
        assert_eq!((n.hsync_pulses, n.vsync_pulses, n.pixels_read), (6, 1, 12));
        assert_eq!(f.pixel(1, 2), Some(c));
        assert_eq!(f.pixel(0, 2), Some(BLACK));
        assert_eq!(f.row(2).map(|r| r.len()), Some(4));
        let r = ram.read_counters();
        assert_eq!((r.cycles, r.pixels_read, r.clock.hz()), (48, 12, 1_000_000));
        assert_eq!(rc.beam(), (0, 0));
        // The next frame counts afresh.
        assert_eq!(rc.read_frame(&mut ram).counters(), n);
    }

    #[test]
    fn monitor_shows_black_beyond_a_smaller_ram() {
        let mut ram = DualPortRam::new(2, 5);
        let c = Rgb565::new(31, 63, 31);
        ram.write_port().clear(c).unwrap();
        let f = RefreshController::new(tiny()).read_frame(&mut ram);
        assert_eq!(f.counters().pixels_read, 6);
        for y in 0..3 {
            assert_eq!(f.row(y).unwrap(), [c, c, BLACK, BLACK]);
        }
        assert_eq!(ram.read_counters().missed_reads, 6);
    }

    #[test]
    fn co_simulation_keeps_both_clocks_in_step() {
        let mut ram = DualPortRam::new(4, 3);
        let mut rc = RefreshController::new(tiny());
        let mut co = CoSimulation::new(&mut ram, &mut rc);
        // 100 cycles at 50 MHz = 2 µs = 2 clocks at 1 MHz.
        co.wait(100);
        assert_eq!(co.cycles(), (100, 2));
        co.wait(1);
        assert_eq!(co.cycles(), (101, 3));
        co.clear(Rgb565::new(1, 1, 1)).unwrap();
        assert_eq!(co.cycles(), (113, 3));
        co.wait_for_frame();
        assert_eq!(co.cycles(), (2351, 48));
        assert_eq!(co.frames().len(), 1);
        // The clear landed at clock 3: the frame shows it from there on.
        let f = &co.frames()[0];
        assert_eq!(f.pixel(2, 0), Some(BLACK));
        assert_eq!(f.pixel(3, 0), Some(Rgb565::new(1, 1, 1)));
    }

    #[test]
    fn keeping_last_holds_the_newest_frame_only() {
        let (mut ram_a, mut ram_b) = (DualPortRam::new(4, 3), DualPortRam::new(4, 3));
        let (mut rc_a, mut rc_b) = (
            RefreshController::new(tiny()),
            RefreshController::new(tiny()),
        );
        let mut all = CoSimulation::new(&mut ram_a, &mut rc_a);
        let mut last = CoSimulation::new(&mut ram_b, &mut rc_b).keeping_last();
        for k in 0..3u8 {
            for co in [&mut all, &mut last] {
                co.clear(Rgb565::new(k, k, k)).unwrap();
                co.wait_for_frame();
                co.wait_for_frame();
            }
        }
        assert_eq!((all.completed(), last.completed()), (6, 6));
        assert_eq!(all.frames().len(), 6);
        assert_eq!(last.frames().len(), 1);
        assert!(last.frames()[0].pixels() == all.frames()[5].pixels());
        assert_eq!(last.cycles(), all.cycles());
    }

    #[test]
    fn from_pixels_checks_the_length() {
        assert!(Frame::from_pixels(2, 2, vec![BLACK; 3]).is_none());
        let f = Frame::from_pixels(2, 2, vec![BLACK; 4]).unwrap();
        assert_eq!(f.pixel(2, 0), None);
        assert_eq!(f.row(2), None);
    }
}
