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
//! The reference design's write port runs at 50 MHz (50 Mpixel/s,
//! [`WRITE_PORT_CLOCK`]). The read port delivers one pixel per cycle of its
//! clock, which the refresh controller drives at the pixel clock and also
//! ticks, without an access, through the blanking intervals.

use crate::timing::Clock;
use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::Rgb565;
use scanvert::framebuffer::MAX_SIDE;
use scanvert::port::{Span, SpanTarget};

/// The write port's clock in the reference design: 50 MHz, one pixel per
/// cycle.
pub const WRITE_PORT_CLOCK: Clock = match Clock::from_hz(50_000_000) {
    Some(c) => c,
    None => panic!(),
};

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
    /// Pixels stored.
    pub pixels_written: u64,
    /// Clock cycles the port was busy.
    pub cycles: u64,
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
            pixels_written: 0,
            cycles: 0,
        }
    }

    /// Simulated time of the busy cycles, in picoseconds.
    pub const fn time_ps(&self) -> u64 {
        self.clock.time_ps(self.cycles)
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
    cells: Vec<Rgb565>,
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
        let width = width.clamp(1, MAX_SIDE);
        let height = height.clamp(1, MAX_SIDE);
        DualPortRam {
            width,
            height,
            cells: vec![Rgb565::new(0, 0, 0); width as usize * height as usize],
            write: WriteCounters::new(write),
            read: ReadCounters::new(read),
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The memory as it is, row-major, without a port access (a debug
    /// view, not counted).
    pub fn contents(&self) -> &[Rgb565] {
        &self.cells
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
        let base = span.y as usize * ram.width as usize;
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
        ram.cells.fill(color);
        ram.write.clears += 1;
        ram.write.pixels_written += ram.cells.len() as u64;
        ram.write.cycles += ram.cells.len() as u64;
        Ok(())
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
            ram.cells
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
        if let (Some(dst), Some(src)) = (out.get_mut(..n), ram.cells.get(base..base + n)) {
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
    fn sides_are_clamped() {
        let ram = DualPortRam::new(0, 5000);
        assert_eq!((ram.width(), ram.height()), (1, 4096));
    }
}
