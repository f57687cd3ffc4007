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
//! The write port charges what the reference design's scan-conversion
//! unit (an FPGA at 50 MHz) would spend, in three terms ([`CycleModel`]):
//!
//! | term | cycles | where the constant comes from |
//! |---|--:|---|
//! | a pixel written (spans and clears) | 1 | the reference unit's 20 ns a pixel (50 Mpixel/s); its 763 clears/s of 256 × 256 are 65,536 cycles each |
//! | a polygon's set-up ([`SpanTarget::begin_polygon`]), whether or not any of it is drawn | 10 ([`POLYGON_SETUP_CYCLES`]) | **calibrated on W1**: its 54,945 polygons/s are 910 cycles a 30 × 30 square, of which 900 are pixel writes and none a wait for the stepper |
//! | a span: the edge stepper's update of the span's two edges | 2 ([`ROW_STEP_CYCLES`]), overlapped with the writes | **assumed**: one cycle an edge (the error-counter step of `raster/edge.rs`: `x += q`, `e += r`, a carry when `e ≥ dy`) |
//!
//! The stepper works out the next span while the port writes the current
//! one, so a span costs `max(pixels, 2)` cycles: the writes wait for the
//! stepper only after a span of fewer than 2 pixels (a span wholly outside
//! the RAM costs the 2). It cannot be otherwise: W1 leaves 10 cycles a
//! square beside its 900 writes for 30 rows, so a stepper that held the
//! writes for even one cycle a row would cost 930 cycles, 53,763
//! polygons/s, against the reference unit's 54,945. On W1 the stepper is
//! never waited for, whatever its time up to 30 cycles a span, so W1 fixes
//! the set-up alone ([`CycleModel::calibrate`]) and the stepper's time is
//! a design assumption; the other lists' rates are **predictions**. The
//! rates ([`WriteCounters::polygons_per_second`] and the others) divide
//! each count by the simulated time of the cycles it took: polygons by all
//! busy cycles but the clears', clears by the clears' own.
//!
//! What the model gives on the firmware image's 2D lists
//! (`firmware/image/scenes`), clears left out: the spans the simulator
//! writes, counted exactly. `cargo run --release -p scanvert-bench --
//! --only model` prints this table and writes it to `docs/performance.md`,
//! and the benchmark's tests fail when either copy is stale; `scanvert
//! render LIST --out x.png --stats` prints a list's counts and rates. The
//! last column is the prediction with a stepper of another time, the
//! set-up calibrated on W1 again:
//!
//! | list | polygons | spans | pixels | waits for the stepper (cycles) | cycles a polygon | polygons/s | Mpixel/s | | polygons/s with a stepper of 1 / 4 / 8 cycles a span |
//! |---|--:|--:|--:|--:|--:|--:|--:|---|--:|
//! | W1, 30 × 30 squares | 226 | 6,780 | 203,400 | 0 | 910.0 | 54,945 | 49.45 | calibrated | 54,945 / 54,945 / 54,945 |
//! | W4, W1 rotated by 17° | 218 | 8,284 | 196,200 | 436 | 912.0 | 54,825 | 49.34 | predicted | 54,945 / 54,585 / 53,648 |
//! | W3, 10,000 small triangles | 10,000 | 178,202 | 1,217,803 | 29,476 | 134.7 | 371,118 | 45.19 | predicted | 379,419 / 340,653 / 267,085 |
//! | W5, one 12-gon | 1 | 250 | 95,268 | 0 | 95,278.0 | 525 | 49.99 | predicted | 525 / 525 / 525 |
//! | the 2D demo (`scenes/demo.dl`) | 19 | 881 | 47,490 | 221 | 2,521.1 | 19,833 | 49.57 | predicted | 19,924 / 19,499 / 18,783 |
//!
//! The reference unit's own measured fill rate, 49.3 Mpixel/s, is 0.3 %
//! below the model's 49.45 Mpixel/s on W1: at 900 pixels a square it is
//! 912.8 cycles, 2.8 more than the model (less than a cycle in ten rows),
//! which the model does not place. The read port delivers one pixel per
//! cycle of its clock, which the refresh controller drives at the pixel
//! clock and also ticks, without an access, through the blanking intervals.
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

/// Write-port cycles of a polygon's set-up, beyond its pixel writes:
/// calibrated on W1, whose 54,945 polygons/s of 900 pixels at 50 MHz are
/// 910 cycles a polygon (see the module docs and [`CycleModel::calibrate`]).
pub const POLYGON_SETUP_CYCLES: u64 = 10;

/// Write-port cycles the edge stepper takes for a span, one an edge of its
/// pair, overlapped with the writing of the span before: assumed, as W1
/// cannot show it (see the module docs).
pub const ROW_STEP_CYCLES: u64 = 2;

/// Spans are counted by their stored length below this
/// ([`WriteCounters::short_spans`]), so that a [`CycleModel`] with a
/// stepper of up to this many cycles a span can re-cost a render.
pub const SHORT_SPANS: usize = 8;

/// The write port's cycle model: a polygon's set-up, the edge stepper's
/// time a span (overlapped with the writes), one cycle a pixel (see the
/// module docs).
///
/// # Guarantees
/// `1 <= row_cycles() <= SHORT_SPANS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CycleModel {
    setup: u64,
    row: u64,
}

impl CycleModel {
    /// The reference unit's: [`POLYGON_SETUP_CYCLES`] and
    /// [`ROW_STEP_CYCLES`].
    pub const REFERENCE: CycleModel = CycleModel {
        setup: POLYGON_SETUP_CYCLES,
        row: ROW_STEP_CYCLES,
    };

    /// A model of `setup` cycles a polygon and a stepper of `row` cycles a
    /// span; `None` unless `1 <= row <= SHORT_SPANS`.
    pub const fn new(setup: u64, row: u64) -> Option<CycleModel> {
        if row >= 1 && row <= SHORT_SPANS as u64 {
            Some(CycleModel { setup, row })
        } else {
            None
        }
    }

    /// Cycles of a polygon's set-up.
    pub const fn setup_cycles(&self) -> u64 {
        self.setup
    }

    /// Cycles the stepper takes for a span.
    pub const fn row_cycles(&self) -> u64 {
        self.row
    }

    /// Cycles the writes wait for the stepper after a span of `stored`
    /// pixels.
    pub const fn wait_after(&self, stored: u64) -> u64 {
        self.row.saturating_sub(stored)
    }

    /// The stepper's waits over the spans counted in `w`.
    pub fn waits(&self, w: &WriteCounters) -> u64 {
        (0..self.row)
            .zip(w.short_spans)
            .map(|(n, spans)| spans * self.wait_after(n))
            .sum()
    }

    /// The busy cycles this model gives the accesses counted in `w`:
    /// set-ups, pixels and the stepper's waits.
    pub fn cycles(&self, w: &WriteCounters) -> u64 {
        self.setup * w.polygons + w.pixels_written + self.waits(w)
    }

    /// The model with a stepper of `row` cycles a span whose set-up makes
    /// the render counted in `w` (polygons only, no clear) run at
    /// `polygons_per_second` on `w`'s clock: the set-up is what a polygon's
    /// share of the time leaves beside its pixels and waits, rounded to
    /// the nearest cycle. `None` for no polygon, a rate of zero, a `row`
    /// out of range, or when the pixels and waits alone take longer (the
    /// model cannot reach the rate).
    pub fn calibrate(row: u64, w: &WriteCounters, polygons_per_second: u64) -> Option<Self> {
        let model = CycleModel::new(0, row)?;
        if w.polygons == 0 || polygons_per_second == 0 {
            return None;
        }
        let hz = u128::from(w.clock.hz());
        let (polygons, rate) = (u128::from(w.polygons), u128::from(polygons_per_second));
        let other = u128::from(w.pixels_written + model.waits(w));
        // setup = hz / rate − other / polygons, over one denominator.
        let num = (hz * polygons).checked_sub(rate * other)?;
        let den = rate * polygons;
        let setup = u64::try_from((num + den / 2) / den).ok()?;
        CycleModel::new(setup, row)
    }
}

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
    /// Polygons begun, each charged its set-up.
    pub polygons: u64,
    /// Pixels stored.
    pub pixels_written: u64,
    /// Spans by the pixels stored of them, `0..SHORT_SPANS`: the spans
    /// after which the writes may wait for the stepper.
    pub short_spans: [u64; SHORT_SPANS],
    /// Clock cycles the port was busy: pixel writes, clears, polygon
    /// set-ups and waits for the stepper.
    pub cycles: u64,
    /// The part of `cycles` spent on clears.
    pub clear_cycles: u64,
    /// The part of `cycles` the writes waited for the stepper.
    pub stepper_wait_cycles: u64,
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
            short_spans: [0; SHORT_SPANS],
            cycles: 0,
            clear_cycles: 0,
            stepper_wait_cycles: 0,
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
    model: CycleModel,
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
            model: CycleModel::REFERENCE,
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

    /// The write port's cycle model ([`CycleModel::REFERENCE`] until set).
    pub fn cycle_model(&self) -> CycleModel {
        self.model
    }

    /// Charges the write port's accesses from now on by `model`.
    pub fn set_cycle_model(&mut self, model: CycleModel) {
        self.model = model;
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
    /// The write port takes a cycle for every pixel written (the
    /// reference unit's 50 Mpixel/s): a pixel written again costs its time.
    const OVERDRAW_IS_CHEAP: bool = false;

    fn size(&self) -> (u16, u16) {
        (self.ram.width, self.ram.height)
    }

    fn fill_span(&mut self, span: Span, color: Rgb565) -> Result<(), Infallible> {
        let ram = &mut *self.ram;
        ram.write.spans += 1;
        let x1 = span.x1.min(ram.width);
        let mut stored = 0;
        if span.y >= ram.height || span.x0 >= x1 {
            ram.write.discarded_spans += 1;
        } else {
            if x1 < span.x1 {
                ram.write.clipped_spans += 1;
            }
            let base = ram.back() as usize * ram.area() + span.y as usize * ram.width as usize;
            if let Some(run) = ram
                .cells
                .get_mut(base + span.x0 as usize..base + x1 as usize)
            {
                run.fill(color);
                stored = run.len() as u64;
            }
        }
        if let Some(n) = ram.write.short_spans.get_mut(stored as usize) {
            *n += 1;
        }
        let wait = ram.model.wait_after(stored);
        ram.write.pixels_written += stored;
        ram.write.stepper_wait_cycles += wait;
        ram.write.cycles += stored + wait;
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
        let setup = self.ram.model.setup;
        let w = &mut self.ram.write;
        w.polygons += 1;
        w.cycles += setup;
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
        // Two spans of 2 pixels; the 5 discarded ones cost the stepper's 2
        // cycles each.
        assert_eq!((w.pixels_written, w.stepper_wait_cycles), (4, 10));
        assert_eq!(w.cycles, 14);
        assert_eq!(w.short_spans[..3], [5, 0, 2]);
        // 50 MHz: 20 ns per cycle.
        assert_eq!(w.time_ps(), 280_000);
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
    fn the_writes_wait_for_the_stepper_after_short_spans_only() {
        let mut ram = DualPortRam::new(16, 4);
        let c = Rgb565::new(0, 0, 31);
        let mut port = ram.write_port();
        port.begin_polygon();
        for (y, x0, x1) in [(0, 5, 6), (1, 4, 6), (2, 3, 9), (3, 7, 7)] {
            port.fill_span(Span { y, x0, x1 }, c).unwrap();
        }
        let w = port.counters();
        // 1 + 2 + 6 pixels; after the 1-pixel span 1 cycle's wait, after
        // the empty one 2.
        assert_eq!((w.pixels_written, w.stepper_wait_cycles), (9, 3));
        assert_eq!(w.cycles, 10 + 9 + 3);
        assert_eq!(CycleModel::REFERENCE.cycles(&w), w.cycles);
        assert_eq!(w.short_spans[..3], [1, 1, 1]);
        // Re-costed with other steppers.
        let m = |setup, row| CycleModel::new(setup, row).expect("in range");
        assert_eq!(m(0, 1).cycles(&w), 9 + 1);
        assert_eq!(m(4, 8).cycles(&w), 4 + 9 + 8 + 7 + 6 + 2);
        assert_eq!(CycleModel::new(10, 0), None);
        assert_eq!(CycleModel::new(10, SHORT_SPANS as u64 + 1), None);
        // A RAM charging another model.
        let mut other = DualPortRam::new(16, 4);
        other.set_cycle_model(m(3, 4));
        assert_eq!(other.cycle_model(), m(3, 4));
        let mut port = other.write_port();
        port.begin_polygon();
        port.fill_span(Span { y: 0, x0: 0, x1: 3 }, c).unwrap();
        assert_eq!(port.counters().cycles, 3 + 3 + 1);
    }

    #[test]
    fn calibration_gives_the_set_up_that_the_rate_leaves() {
        // 4 polygons of one 30-pixel span each, at 50 MHz: 1,000,000
        // polygons/s are 50 cycles a polygon, 30 of them writes.
        let mut ram = DualPortRam::new(40, 4);
        let c = Rgb565::new(1, 1, 1);
        let mut port = ram.write_port();
        for y in 0..4 {
            port.begin_polygon();
            port.fill_span(Span { y, x0: 0, x1: 30 }, c).unwrap();
        }
        let w = port.counters();
        let cal = |row, rate| CycleModel::calibrate(row, &w, rate).map(|m| m.setup_cycles());
        assert_eq!(cal(2, 1_000_000), Some(20));
        assert_eq!(cal(8, 1_000_000), Some(20));
        // To the nearest cycle: 49.4 and 49.6 cycles a polygon.
        assert_eq!(cal(2, 1_012_146), Some(19));
        assert_eq!(cal(2, 1_008_065), Some(20));
        // Faster than the writes alone: no set-up can give it.
        assert_eq!(cal(2, 2_000_000), None);
        assert_eq!(cal(2, 0), None);
        assert_eq!(cal(9, 1_000_000), None);
        let none = WriteCounters::new(WRITE_PORT_CLOCK);
        assert_eq!(CycleModel::calibrate(2, &none, 1), None);
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
