//! The dual-port frame-buffer RAM: the graphic controller writes spans into
//! one port, the refresh controller reads pixels out of the other, each
//! port on its own clock.
//!
//! The RAM holds `width × height` RGB565 pixels, row-major, black (zero)
//! at power-on. The ports are borrowed from the RAM one at a time:
//! [`DualPortRam::write_port`] gives a [`WritePort`], which is a
//! [`SpanTarget`] for [`scanvert::controller::Controller::render`];
//! [`DualPortRam::read_port`] gives a [`ReadPort`] for the refresh
//! controller. Each port counts its own accesses and clock cycles
//! ([`WriteCounters`], [`ReadCounters`]), which persist in the RAM until
//! [`DualPortRam::reset_counters`].
//!
//! # Cycle model
//! The write port stores one pixel per cycle of its clock: a span of `n`
//! pixels (after clipping) takes `n` cycles, a clear takes `width × height`.
//! Each polygon costs [`POLYGON_SETUP_CYCLES`] (10) more, charged when the
//! rasteriser begins it ([`SpanTarget::begin_polygon`]), whether or not any
//! of it is drawn. The reference design's write port runs at 50 MHz
//! (50 Mpixel/s, [`WRITE_PORT_CLOCK`]). The read port delivers one pixel per
//! cycle of its clock, which the refresh controller drives at the pixel
//! clock and also ticks, without an access, through the blanking intervals.
//!
//! The model is the reference unit's own figures, and reproduces them
//! (`hal_sim/tests/fpga_figures.rs`):
//!
//! | reference figure | cycles | model |
//! |---|--:|---|
//! | 20 ns a pixel | 1 | one cycle a pixel at 50 MHz |
//! | 54,945 polygons/s of 30 × 30 px | 910 = 50 MHz ÷ 54,945 | 900 pixel writes + 10 of set-up |
//! | 763 clears/s of 256 × 256 | 65,536 = 50 MHz ÷ 763 | one cycle a pixel |
//!
//! The set-up of 10 cycles is what the second figure leaves over the pixel
//! writes: 50,000,000 ÷ 54,945 = 910.0 cycles a polygon. The rates
//! ([`WriteCounters::polygons_per_second`] and the others) divide each
//! count by the simulated time of the cycles it took: polygons by all busy
//! cycles but the clears', clears by the clears' own.
//!
//! # Double buffering
//! A RAM made with [`DualPortRam::double_buffered`] has two banks. The
//! read port shows the *front* bank; the write port fills the *back* bank.
//! The graphic controller asks for the banks to be exchanged with
//! [`DualPortRam::request_swap`]; the exchange waits for the refresh
//! controller's vertical-blanking strobe ([`ReadPort::vertical_blank`]), so
//! it only happens while no pixel is read out, and a frame on the monitor
//! never mixes two renders. Until the swap has happened
//! ([`DualPortRam::swap_pending`]) the back bank still holds the finished
//! render; a controller waits before drawing the next one.
//!
//! A single-buffered RAM ([`DualPortRam::new`]) has one bank, read and
//! written at once; a swap request does nothing there.

use crate::timing::Clock;
use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::Rgb565;
use scanvert::port::framebuffer::MAX_SIDE;
use scanvert::port::{Span, SpanTarget};

/// The write port's clock in the reference design: 50 MHz, one pixel per
/// cycle.
pub const WRITE_PORT_CLOCK: Clock = match Clock::from_hz(50_000_000) {
    Some(c) => c,
    None => panic!(),
};

/// Write-port cycles of a polygon's set-up, beyond its pixel writes: the
/// reference unit's 54,945 polygons/s of 900 pixels at 50 MHz are 910
/// cycles a polygon (see the module docs).
pub const POLYGON_SETUP_CYCLES: u64 = 10;

/// The read port's clock until the refresh controller sets it: the
/// reference design's 25 MHz pixel clock.
pub const READ_PORT_CLOCK: Clock = match Clock::from_hz(25_000_000) {
    Some(c) => c,
    None => panic!(),
};

/// What the write port has done.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WriteCounters {
    /// The port's clock.
    pub clock: Clock,
    /// Spans received (whether or not any pixel of them was stored).
    pub spans: u64,
    /// Spans cut because they reached past the RAM.
    pub clipped_spans: u64,
    /// Spans discarded whole: empty, or entirely outside the RAM.
    pub discarded_spans: u64,
    /// Whole-RAM clears.
    pub clears: u64,
    /// Polygons begun, each charged [`POLYGON_SETUP_CYCLES`].
    pub polygons: u64,
    /// Pixels stored.
    pub pixels_written: u64,
    /// Clock cycles the port was busy: pixel writes, clears and polygon
    /// set-ups.
    pub cycles: u64,
    /// The part of `cycles` spent on clears.
    pub clear_cycles: u64,
}

impl WriteCounters {
    /// Counters at zero on `clock`.
    pub const fn new(clock: Clock) -> Self {
        WriteCounters {
            clock,
            spans: 0,
            clipped_spans: 0,
            discarded_spans: 0,
            clears: 0,
            polygons: 0,
            pixels_written: 0,
            cycles: 0,
            clear_cycles: 0,
        }
    }

    /// Simulated time of the busy cycles, in picoseconds.
    pub const fn time_ps(&self) -> u64 {
        self.clock.time_ps(self.cycles)
    }

    /// `count` events in `cycles` of the port's clock, per second; `None`
    /// when no cycle passed.
    fn rate(&self, count: u64, cycles: u64) -> Option<f64> {
        (cycles > 0).then(|| count as f64 * f64::from(self.clock.hz()) / cycles as f64)
    }

    /// Pixels stored per second of busy time (clears included).
    pub fn pixels_per_second(&self) -> Option<f64> {
        self.rate(self.pixels_written, self.cycles)
    }

    /// Polygons per second of the busy time outside clears (set-ups and
    /// every span written); `None` when there was none.
    pub fn polygons_per_second(&self) -> Option<f64> {
        self.rate(self.polygons, self.cycles - self.clear_cycles)
            .filter(|_| self.polygons > 0)
    }

    /// Clears per second of the time spent clearing; `None` without a
    /// clear.
    pub fn clears_per_second(&self) -> Option<f64> {
        self.rate(self.clears, self.clear_cycles)
    }
}

/// What the read port has done.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadCounters {
    /// The port's clock.
    pub clock: Clock,
    /// Pixels read from the RAM.
    pub pixels_read: u64,
    /// Reads at an address outside the RAM (answered with nothing).
    pub missed_reads: u64,
    /// Clock cycles, with or without an access.
    pub cycles: u64,
}

impl ReadCounters {
    /// Counters at zero on `clock`.
    pub const fn new(clock: Clock) -> Self {
        ReadCounters {
            clock,
            pixels_read: 0,
            missed_reads: 0,
            cycles: 0,
        }
    }

    /// Simulated time of all cycles, in picoseconds.
    pub const fn time_ps(&self) -> u64 {
        self.clock.time_ps(self.cycles)
    }
}

/// A dual-port RAM of `width × height` RGB565 pixels.
///
/// # Guarantees
/// `1 <= width, height <= 4096` and the memory holds exactly
/// `width × height` pixels.
#[derive(Clone, Debug)]
pub struct DualPortRam {
    width: u16,
    height: u16,
    /// `banks × width × height` pixels, bank after bank.
    cells: Vec<Rgb565>,
    banks: u8,
    front: u8,
    swap_pending: bool,
    swaps: u64,
    write: WriteCounters,
    read: ReadCounters,
}

impl DualPortRam {
    /// A black RAM of `width × height` pixels with the reference design's
    /// port clocks ([`WRITE_PORT_CLOCK`], [`READ_PORT_CLOCK`]). Sides
    /// outside `1..=4096` are clamped into it.
    pub fn new(width: u16, height: u16) -> Self {
        Self::with_clocks(width, height, WRITE_PORT_CLOCK, READ_PORT_CLOCK)
    }

    /// A black RAM with the given port clocks; sides as for [`new`](Self::new).
    pub fn with_clocks(width: u16, height: u16, write: Clock, read: Clock) -> Self {
        Self::with_banks(1, width, height, write, read)
    }

    /// A black RAM of two banks, for double buffering (see the module
    /// docs), with the reference design's port clocks; sides as for
    /// [`new`](Self::new).
    pub fn double_buffered(width: u16, height: u16) -> Self {
        Self::with_banks(2, width, height, WRITE_PORT_CLOCK, READ_PORT_CLOCK)
    }

    fn with_banks(banks: u8, width: u16, height: u16, write: Clock, read: Clock) -> Self {
        let width = width.clamp(1, MAX_SIDE);
        let height = height.clamp(1, MAX_SIDE);
        let area = width as usize * height as usize;
        DualPortRam {
            width,
            height,
            cells: vec![Rgb565::new(0, 0, 0); banks as usize * area],
            banks,
            front: 0,
            swap_pending: false,
            swaps: 0,
            write: WriteCounters::new(write),
            read: ReadCounters::new(read),
        }
    }

    fn area(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// The pixels of `bank`; an empty slice for a bank the RAM lacks.
    fn bank(&self, bank: u8) -> &[Rgb565] {
        let area = self.area();
        let start = bank as usize * area;
        self.cells.get(start..start + area).unwrap_or(&[])
    }

    /// The bank the write port fills: the other one when double-buffered.
    fn back(&self) -> u8 {
        if self.banks == 2 {
            1 - self.front
        } else {
            self.front
        }
    }

    /// `true` for a RAM of two banks.
    pub fn is_double_buffered(&self) -> bool {
        self.banks == 2
    }

    /// Asks for the banks to be exchanged at the next vertical blanking
    /// (double-buffered RAM only; otherwise nothing happens).
    pub fn request_swap(&mut self) {
        self.swap_pending = self.banks == 2;
    }

    /// `true` while a requested swap has not yet happened.
    pub fn swap_pending(&self) -> bool {
        self.swap_pending
    }

    /// Bank swaps done.
    pub fn swaps(&self) -> u64 {
        self.swaps
    }

    /// Width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The bank the read port shows, row-major, without a port access (a
    /// debug view, not counted).
    pub fn contents(&self) -> &[Rgb565] {
        self.bank(self.front)
    }

    /// The bank the write port fills (the same as [`contents`](Self::contents)
    /// when single-buffered), without a port access.
    pub fn back_contents(&self) -> &[Rgb565] {
        self.bank(self.back())
    }

    /// The port the graphic controller writes through.
    pub fn write_port(&mut self) -> WritePort<'_> {
        WritePort { ram: self }
    }

    /// The port the refresh controller reads through.
    pub fn read_port(&mut self) -> ReadPort<'_> {
        ReadPort { ram: self }
    }

    /// The write port's counters.
    pub fn write_counters(&self) -> WriteCounters {
        self.write
    }

    /// The read port's counters.
    pub fn read_counters(&self) -> ReadCounters {
        self.read
    }

    /// Sets every counter of both ports to zero (the clocks stay).
    pub fn reset_counters(&mut self) {
        self.write = WriteCounters::new(self.write.clock);
        self.read = ReadCounters::new(self.read.clock);
    }

    /// Drives the write port from `clock`.
    pub fn set_write_clock(&mut self, clock: Clock) {
        self.write.clock = clock;
    }

    /// Drives the read port from `clock`.
    pub fn set_read_clock(&mut self, clock: Clock) {
        self.read.clock = clock;
    }
}

/// The write port: a [`SpanTarget`] of RGB565 pixels that never fails.
///
/// Spans reaching past the RAM are clipped; spans wholly outside, or empty,
/// are discarded. Neither is an error, and no span can make it panic.
#[derive(Debug)]
pub struct WritePort<'a> {
    ram: &'a mut DualPortRam,
}

impl WritePort<'_> {
    /// The port's counters so far.
    pub fn counters(&self) -> WriteCounters {
        self.ram.write
    }
}

impl SpanTarget for WritePort<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn size(&self) -> (u16, u16) {
        (self.ram.width, self.ram.height)
    }

    fn fill_span(&mut self, span: Span, color: Rgb565) -> Result<(), Infallible> {
        let ram = &mut *self.ram;
        ram.write.spans += 1;
        let x1 = span.x1.min(ram.width);
        if span.y >= ram.height || span.x0 >= x1 {
            ram.write.discarded_spans += 1;
            return Ok(());
        }
        if x1 < span.x1 {
            ram.write.clipped_spans += 1;
        }
        let base = ram.back() as usize * ram.area() + span.y as usize * ram.width as usize;
        if let Some(run) = ram
            .cells
            .get_mut(base + span.x0 as usize..base + x1 as usize)
        {
            run.fill(color);
            ram.write.pixels_written += run.len() as u64;
            ram.write.cycles += run.len() as u64;
        }
        Ok(())
    }

    fn clear(&mut self, color: Rgb565) -> Result<(), Infallible> {
        let ram = &mut *self.ram;
        let area = ram.area();
        let start = ram.back() as usize * area;
        if let Some(bank) = ram.cells.get_mut(start..start + area) {
            bank.fill(color);
        }
        ram.write.clears += 1;
        ram.write.pixels_written += area as u64;
        ram.write.cycles += area as u64;
        ram.write.clear_cycles += area as u64;
        Ok(())
    }

    fn begin_polygon(&mut self) {
        let w = &mut self.ram.write;
        w.polygons += 1;
        w.cycles += POLYGON_SETUP_CYCLES;
    }
}

/// The read port: one pixel per clock cycle.
#[derive(Debug)]
pub struct ReadPort<'a> {
    ram: &'a mut DualPortRam,
}

impl ReadPort<'_> {
    /// Width and height of the RAM behind the port.
    pub fn size(&self) -> (u16, u16) {
        (self.ram.width, self.ram.height)
    }

    /// Reads the pixel at `(x, y)` in one cycle; `None` (a missed read, no
    /// pixel counted) outside the RAM.
    pub fn read(&mut self, x: u16, y: u16) -> Option<Rgb565> {
        let ram = &mut *self.ram;
        ram.read.cycles += 1;
        if x < ram.width && y < ram.height {
            ram.read.pixels_read += 1;
            ram.bank(ram.front)
                .get(y as usize * ram.width as usize + x as usize)
                .copied()
        } else {
            ram.read.missed_reads += 1;
            None
        }
    }

    /// Reads row `y` from column 0 into `out`, one pixel per cycle, as
    /// many as fit in both; returns how many were read (0 outside the RAM).
    pub fn read_row(&mut self, y: u16, out: &mut [Rgb565]) -> usize {
        let ram = &mut *self.ram;
        if y >= ram.height {
            return 0;
        }
        let n = out.len().min(ram.width as usize);
        let base = y as usize * ram.width as usize;
        let src = ram.bank(ram.front).get(base..base + n);
        if let (Some(dst), Some(src)) = (out.get_mut(..n), src) {
            dst.copy_from_slice(src);
            ram.read.pixels_read += n as u64;
            ram.read.cycles += n as u64;
            n
        } else {
            0
        }
    }

    /// Lets `cycles` clock cycles pass without an access (blanking).
    pub fn idle(&mut self, cycles: u64) {
        self.ram.read.cycles += cycles;
    }

    /// The refresh controller's vertical-blanking strobe: a pending bank
    /// swap takes effect. Returns `true` when the banks were exchanged.
    pub fn vertical_blank(&mut self) -> bool {
        let ram = &mut *self.ram;
        if !ram.swap_pending {
            return false;
        }
        ram.swap_pending = false;
        ram.front = ram.back();
        ram.swaps += 1;
        true
    }

    /// The port's counters so far.
    pub fn counters(&self) -> ReadCounters {
        self.ram.read
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_on_is_black_and_counters_are_zero() {
        let ram = DualPortRam::new(4, 3);
        assert!(ram.contents().iter().all(|&p| p == Rgb565::new(0, 0, 0)));
        assert_eq!(ram.contents().len(), 12);
        assert_eq!(ram.write_counters(), WriteCounters::new(WRITE_PORT_CLOCK));
        assert_eq!(ram.read_counters(), ReadCounters::new(READ_PORT_CLOCK));
    }

    #[test]
    fn spans_are_written_clipped_or_discarded_never_panicking() {
        let mut ram = DualPortRam::new(4, 3);
        let c = Rgb565::new(31, 0, 0);
        let mut port = ram.write_port();
        let spans = [
            (1, 1, 3),
            (0, 2, 9),
            (3, 0, 4),
            (2, 5, 9),
            (0, 3, 1),
            (u16::MAX, 0, u16::MAX),
            (0, u16::MAX, u16::MAX),
        ];
        for (y, x0, x1) in spans {
            port.fill_span(Span { y, x0, x1 }, c).unwrap();
        }
        let w = port.counters();
        assert_eq!(
            (w.spans, w.clipped_spans, w.discarded_spans),
            (7, 1, 5),
            "{w:?}"
        );
        assert_eq!((w.pixels_written, w.cycles), (4, 4));
        // 50 MHz: 20 ns per pixel.
        assert_eq!(w.time_ps(), 80_000);
        let lit: Vec<usize> = (0..12).filter(|&i| ram.contents()[i] == c).collect();
        assert_eq!(lit, [2, 3, 5, 6]);
    }

    #[test]
    fn clear_fills_everything_in_one_cycle_per_pixel() {
        let mut ram = DualPortRam::new(5, 2);
        let c = Rgb565::new(1, 2, 3);
        ram.write_port().clear(c).unwrap();
        assert!(ram.contents().iter().all(|&p| p == c));
        let w = ram.write_counters();
        assert_eq!((w.clears, w.pixels_written, w.cycles), (1, 10, 10));
        assert_eq!(w.clear_cycles, 10);
        // 10 cycles at 50 MHz: 5 million clears a second.
        assert_eq!(w.clears_per_second(), Some(5e6));
        assert_eq!(w.polygons_per_second(), None);
    }

    #[test]
    fn a_polygon_costs_its_set_up_and_its_pixels() {
        let mut ram = DualPortRam::new(8, 4);
        let c = Rgb565::new(0, 0, 31);
        let mut port = ram.write_port();
        port.clear(c).unwrap();
        port.begin_polygon();
        for y in 0..3 {
            port.fill_span(Span { y, x0: 1, x1: 6 }, c).unwrap();
        }
        let w = port.counters();
        assert_eq!((w.polygons, w.pixels_written), (1, 32 + 15));
        assert_eq!((w.cycles, w.clear_cycles), (32 + 15 + 10, 32));
        // One polygon in 25 cycles of 20 ns: 2 million a second.
        assert_eq!(w.polygons_per_second(), Some(2e6));
        assert_eq!(w.pixels_per_second(), Some(47.0 * 50e6 / 57.0));
        assert_eq!(
            WriteCounters::new(WRITE_PORT_CLOCK).pixels_per_second(),
            None
        );
    }

    #[test]
    fn read_port_counts_reads_misses_and_idle_cycles() {
        let mut ram = DualPortRam::new(3, 2);
        let c = Rgb565::new(0, 63, 0);
        ram.write_port()
            .fill_span(Span { y: 1, x0: 2, x1: 3 }, c)
            .unwrap();
        let mut port = ram.read_port();
        assert_eq!(port.read(2, 1), Some(c));
        assert_eq!(port.read(3, 1), None);
        let mut row = [Rgb565::new(0, 0, 1); 5];
        assert_eq!(port.read_row(1, &mut row), 3);
        assert_eq!(row[2], c);
        assert_eq!(row[3], Rgb565::new(0, 0, 1));
        assert_eq!(port.read_row(2, &mut row), 0);
        port.idle(10);
        let r = port.counters();
        assert_eq!((r.pixels_read, r.missed_reads, r.cycles), (4, 1, 15));
        // 25 MHz: 40 ns per cycle.
        assert_eq!(r.time_ps(), 600_000);
        ram.reset_counters();
        assert_eq!(ram.read_counters().cycles, 0);
    }

    #[test]
    fn double_buffer_swaps_only_on_vertical_blank() {
        let (a, b) = (Rgb565::new(31, 0, 0), Rgb565::new(0, 0, 31));
        let mut ram = DualPortRam::double_buffered(2, 2);
        assert!(ram.is_double_buffered());
        ram.write_port().clear(a).unwrap();
        assert_eq!(ram.read_port().read(0, 0), Some(Rgb565::new(0, 0, 0)));
        assert_eq!(ram.back_contents(), [a; 4]);
        ram.request_swap();
        assert!(ram.swap_pending());
        assert_eq!(ram.read_port().read(1, 1), Some(Rgb565::new(0, 0, 0)));
        assert!(ram.read_port().vertical_blank());
        assert!(!ram.read_port().vertical_blank());
        assert_eq!((ram.swap_pending(), ram.swaps()), (false, 1));
        assert_eq!(ram.read_port().read(1, 1), Some(a));
        ram.write_port()
            .fill_span(Span { y: 0, x0: 0, x1: 2 }, b)
            .unwrap();
        assert_eq!(ram.contents(), [a; 4]);
        assert_eq!(ram.back_contents()[..2], [b, b]);
        // Single-buffered: a request does nothing.
        let mut one = DualPortRam::new(2, 2);
        one.request_swap();
        assert!(!one.swap_pending() && !one.read_port().vertical_blank());
    }

    #[test]
    fn sides_are_clamped() {
        let ram = DualPortRam::new(0, 5000);
        assert_eq!((ram.width(), ram.height()), (1, 4096));
    }
}
