//! Racing the beam: the display device with no frame RAM.
//!
//! The refresh controller reads each scan line from a small ring of `K`
//! rows and expands them to pixels as the beam scans them. A producer
//! (the graphic controller, composing the frame one row at a time as
//! colour runs through the library's racing path,
//! [`ListBands::draw_runs`](scanvert::controller::ListBands::draw_runs):
//! no pixel buffer, the background one run, every span inserted over it)
//! fills the ring just in time. Each row costs the producer some
//! instructions, from a [`CostModel`] of the row's work, and so some time
//! at the producer's CPU clock. A row that is not in the ring when the
//! beam reaches its line is a **deadline miss**: every pixel of that line
//! is pure red ([`MISS`], `#ff0000` in the image).
//!
//! # The row formats
//!
//! A row in the ring is in one of two formats ([`RowFormat`]), and the
//! refresh controller decodes either:
//! - **colour runs** ([`RowFormat::Runs`]): the library's row
//!   ([`scanvert::port::runs`]), a list of runs of one RGB565 colour each,
//!   left to right, covering the frame's width, no two neighbours of one
//!   colour; here each as a [`Run`], a 16-bit length and the colour, 4
//!   bytes. A clear row is one run; a row has at most `width` runs.
//! - **`pico_scanvideo` tokens** ([`RowFormat::Scanvideo`]): the same row
//!   encoded by [`scanvert::port::scanvideo::encode`] for the Pico's
//!   composable scan-line program (colour runs, raw runs, a black pixel
//!   at the end, an end-of-line token that makes the stream whole 32-bit
//!   words), decoded by [`scanvert::port::scanvideo::decode`].
//!
//! The 3D layer's own runs ([`scanvert::visible::rle::Run`], `x0..x1`
//! of one trapezoid) cover only its part of the row; they are inserted
//! into the row's colour runs as they are, over the 2D spans below them
//! and under the labels.
//!
//! # Time
//!
//! Time starts, for each frame, at the start of the vertical retrace that
//! precedes it: the producer prepares the frame ([`Producer::prepare`])
//! and starts on row 0 there. Line `y`'s active display starts
//! `(retrace lines + y) × line period` later, and its active part ends
//! `active width` pixel clocks after that. The producer
//! - draws rows in order, one at a time, each taking
//!   [`CostModel::row`] instructions at one instruction a cycle of the
//!   CPU clock;
//! - runs ahead of the beam by at most `K` rows: it may start row `y` only
//!   once the beam has scanned out the active part of line `y − K` (that
//!   row's slot is then free);
//! - never skips a row: a row finished after its line started is dropped
//!   (the line was shown red) and the producer goes on with the next.
//!
//! Row `y` is on time when it is finished no later than the start of line
//! `y`'s active display. All of this is computed exactly, in integers:
//! time is counted in units of `1 / (CPU clock × pixel clock)` seconds.
//! [`schedule`] computes the misses from the rows' costs alone;
//! [`race`] runs the refresh controller clock by clock on the ring, and
//! the two agree (a test checks it).
//!
//! # Preparing a frame in the spare time of the one before
//!
//! Preparing a frame before its row 0 ([`schedule`]) must fit in the
//! retrace with the rows the ring lets the producer bank there. A
//! producer with two sets of the frame's memory (two edge tables, two 3D
//! layers) can instead prepare frame `n + 1` while frame `n` is raced:
//! in the time it waits for a slot of the ring, and after its last row
//! until the next retrace (the rows come first: a row starts as soon as
//! its slot is free, as an interrupt would start it). Frame `n + 1` then
//! starts at its retrace already prepared. [`schedule_spread`] computes
//! this: the rows' misses as if the frame were prepared, and whether the
//! preparation fits in the spare time of one frame period (the frame
//! shown once a period, its preparation one frame ahead).
//!
//! Lines of the frame below the timing's active area are not produced;
//! lines of the active area below the frame, and pixels beyond a row's
//! runs, are black and never missed. `N` in `M of N lines` is the lines
//! the frame shows: the smaller of the frame's and the timing's heights.

use crate::refresh::{Frame, PixelSource, RefreshController};
use crate::timing::VideoTiming;
use embedded_graphics_core::pixelcolor::Rgb565;
use scanvert::controller::{ListBands, RenderStats};
use scanvert::display_list::{Command, DisplayList};
use scanvert::port::runs::{ColorRun, RowRuns};
use scanvert::port::scanvideo::{self, Opcodes};
use scanvert::scene::{Frame as SceneFrame, SceneBands};
use std::num::NonZeroU64;

/// The producer's CPU clock, 1 Hz to [`CpuClock::MAX_MHZ`] MHz.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct CpuClock(NonZeroU64);

impl CpuClock {
    /// The fastest clock taken: 100 GHz.
    pub const MAX_MHZ: u64 = 100_000;

    /// `hz` hertz, or `None` outside 1 Hz to 100 GHz.
    pub const fn from_hz(hz: u64) -> Option<CpuClock> {
        if hz > Self::MAX_MHZ * 1_000_000 {
            return None;
        }
        match NonZeroU64::new(hz) {
            Some(hz) => Some(CpuClock(hz)),
            None => None,
        }
    }

    /// `mhz` megahertz, or `None` outside 1 to 100,000 MHz.
    pub const fn from_mhz(mhz: u64) -> Option<CpuClock> {
        match mhz.checked_mul(1_000_000) {
            Some(hz) => CpuClock::from_hz(hz),
            None => None,
        }
    }

    /// The clock in hertz.
    pub const fn hz(self) -> u64 {
        self.0.get()
    }
}

impl std::fmt::Display for CpuClock {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let hz = self.hz();
        match hz % 1_000_000 {
            0 => write!(f, "{} MHz", hz / 1_000_000),
            r => write!(f, "{}.{:06} MHz", hz / 1_000_000, r),
        }
    }
}

/// How a row sits in the ring (see the [module](self) docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RowFormat {
    /// Colour runs, 4 bytes each.
    #[default]
    Runs,
    /// `pico_scanvideo` composable scan-line tokens, in 32-bit words.
    Scanvideo,
}

/// The colour of a missed line: pure red (`#ff0000` in the image).
pub const MISS: Rgb565 = Rgb565::new(31, 0, 0);

/// The ring's rows when `--fifo` is not given: two, the least that lets
/// the producer draw one row while the beam shows the other.
pub const DEFAULT_FIFO: u16 = 2;

/// One run of a row in the ring: `len` pixels of `color`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    /// Pixels, at least 1.
    pub len: u16,
    /// Their colour.
    pub color: Rgb565,
}

/// Encodes `row` of pixels as colour runs into `out` (cleared first):
/// each run as long as the pixels of one colour next to each other, so no
/// two runs next to each other have the same colour. Returns the runs.
/// For pictures drawn into pixels ([`FrameRows`]); the racing path
/// composes its rows as runs and never has the pixels.
pub fn encode_row(row: &[Rgb565], out: &mut Vec<Run>) -> usize {
    out.clear();
    for &p in row {
        match out.last_mut() {
            Some(r) if r.color == p && r.len < u16::MAX => r.len += 1,
            _ => out.push(Run { len: 1, color: p }),
        }
    }
    out.len()
}

/// The work of one row, as the producer counts it: what [`CostModel`]
/// prices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RowWork {
    /// Pixels of the row (composed as runs, it touches none of them: the
    /// fitted model gives this no weight).
    pub width: u32,
    /// Spans written into the row (2D polygons, the 3D layer, labels).
    pub spans: u32,
    /// Pixels written by those spans.
    pub pixels: u32,
    /// Colour runs of the finished row.
    pub runs: u32,
    /// Trapezoids that entered the 3D layer's active list at this row.
    pub entered: u32,
    /// Spans the visible-surface stage resolved on this row (between
    /// consecutive edges of the active list).
    pub resolved: u32,
    /// Labels drawn on this row.
    pub labels: u32,
    /// Runs the row needed at once while it was composed (its share of
    /// the ring's memory; not priced).
    pub peak: u32,
    /// 2D polygons and lines of the edge table live on this row: those
    /// whose vertical extent reaches the row's centre (see
    /// [`live_polygons`]).
    pub live: u32,
    /// Words of the edge table's live set scanned for the row: one per 32
    /// of the table's polygons and lines, whether live or not.
    pub words: u32,
    /// Runs moved by the row's insertions
    /// ([`RowRuns::moved`](scanvert::port::runs::RowRuns::moved)).
    pub moved: u32,
}

/// The work of preparing a frame before its first row.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PrepareWork {
    /// Commands of the list.
    pub commands: u32,
    /// 2D polygons entered into the edge table.
    pub polygons: u32,
    /// Trapezoids the 3D layer was cut into.
    pub trapezoids: u32,
}

/// Instructions of a row (and of preparing a frame) as a linear function
/// of its work. Coefficients are in 1/16 instruction.
///
/// [`CostModel::M4`] is fitted to the instructions measured row by row on
/// the Cortex-M4 image (see its docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CostModel {
    /// A row, whatever it holds.
    pub row: i64,
    /// A pixel of the row's width.
    pub width: i64,
    /// A span.
    pub span: i64,
    /// A pixel written.
    pub pixel: i64,
    /// A colour run.
    pub run: i64,
    /// A trapezoid entering.
    pub entered: i64,
    /// A span resolved by the visible-surface stage.
    pub resolved: i64,
    /// A label drawn.
    pub label: i64,
    /// A 2D polygon live on the row.
    pub live: i64,
    /// A word of the edge table's live set scanned.
    pub word: i64,
    /// A run moved by an insertion.
    pub moved: i64,
    /// Preparing a frame, whatever it holds.
    pub frame: i64,
    /// A command, when preparing.
    pub command: i64,
    /// A trapezoid, when preparing.
    pub trapezoid: i64,
}

impl CostModel {
    /// Fitted by least squares to the instructions the Cortex-M4 image
    /// (`firmware/image`, feature `rows`, under QEMU with
    /// `-icount shift=0`) counted for each row of the eight lists it
    /// embeds (1,992 rows: `firmware/image/rows-m4.txt`), each composed
    /// as colour runs with no pixel buffer (`ListBands::draw_runs`), and
    /// for preparing each list. The fit is
    /// `cargo run --release -p scanvert-bench -- --only race`, and the
    /// benchmark's tests check that it gives these coefficients and the
    /// error below.
    ///
    /// Against the 1,992 measured rows the model's error is 8.2 % on
    /// average and 48.8 % at worst (the 2D lists' rows: 1.7 % to 10.3 %
    /// on average, the 3D lists' 16.6 % and 14.4 %; the worst are rows of
    /// a few hundred instructions, where the counter's step of 40 is a
    /// large part). A row's cost hardly grows with its width (a sixteenth
    /// of an instruction a pixel); a 2D polygon live on the row costs 88
    /// instructions besides its span, the edge table's live set 18 a
    /// word of 32 polygons on every row (W3's 313 words), and a run
    /// moved by an insertion 5. Preparing a list is fitted to
    /// the eight lists' counts. Labels are in none of the measured lists,
    /// so `label` is 0 and a label costs its spans and pixels. One
    /// instruction is taken as one CPU cycle.
    pub const M4: CostModel = CostModel {
        row: 1239,
        width: 1,
        span: 3246,
        pixel: -3,
        run: 547,
        entered: 7211,
        resolved: 1037,
        label: 0,
        live: 1414,
        word: 295,
        moved: 78,
        frame: 118018,
        command: 11079,
        trapezoid: 671,
    };

    /// Instructions of a row of `work`, at least 1.
    pub fn row(&self, w: &RowWork) -> u64 {
        let sixteenths = self.row
            + self.width * i64::from(w.width)
            + self.span * i64::from(w.spans)
            + self.pixel * i64::from(w.pixels)
            + self.run * i64::from(w.runs)
            + self.entered * i64::from(w.entered)
            + self.resolved * i64::from(w.resolved)
            + self.label * i64::from(w.labels)
            + self.live * i64::from(w.live)
            + self.word * i64::from(w.words)
            + self.moved * i64::from(w.moved);
        (sixteenths.max(16) as u64).div_ceil(16)
    }

    /// Instructions of preparing a frame of `work`, at least 0.
    pub fn prepare(&self, w: &PrepareWork) -> u64 {
        let sixteenths = self.frame
            + self.command * i64::from(w.commands)
            + self.trapezoid * i64::from(w.trapezoids);
        (sixteenths.max(0) as u64).div_ceil(16)
    }
}

/// What draws the rows of a frame, one at a time, top to bottom.
pub trait Producer {
    /// Width and height of the frame.
    fn size(&self) -> (u16, u16);
    /// The work done to prepare the frame (before row 0).
    fn prepare(&self) -> PrepareWork;
    /// Draws row `y` (rows come in order, from 0) as runs into `runs`
    /// and says what it took.
    fn row(&mut self, y: u16, runs: &mut Vec<Run>) -> RowWork;
}

/// A producer of a frame already drawn: its rows are encoded as they are
/// asked for, and each counts as runs only (the other work is zero). For
/// tests, and for pictures the band path does not draw.
#[derive(Debug)]
pub struct FrameRows<'a> {
    width: u16,
    height: u16,
    pixels: &'a [Rgb565],
}

impl<'a> FrameRows<'a> {
    /// The rows of `pixels`, `width × height` of them row-major, or
    /// `None` when the length differs.
    pub fn new(width: u16, height: u16, pixels: &'a [Rgb565]) -> Option<Self> {
        (pixels.len() == usize::from(width) * usize::from(height)).then_some(FrameRows {
            width,
            height,
            pixels,
        })
    }
}

impl Producer for FrameRows<'_> {
    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }
    fn prepare(&self) -> PrepareWork {
        PrepareWork::default()
    }
    fn row(&mut self, y: u16, runs: &mut Vec<Run>) -> RowWork {
        let w = usize::from(self.width);
        let start = usize::from(y) * w;
        let row = self.pixels.get(start..start + w).unwrap_or(&[]);
        let n = encode_row(row, runs);
        RowWork {
            width: u32::from(self.width),
            runs: n as u32,
            ..RowWork::default()
        }
    }
}

/// The figures of time a race needs, in units of
/// `1 / (CPU clock × pixel clock)` seconds.
#[derive(Clone, Copy, Debug)]
struct Clocks {
    /// A CPU cycle.
    cycle: u128,
    /// A pixel clock.
    pixel: u128,
    /// Pixel clocks from the start of the retrace to line 0's first
    /// active pixel.
    lead: u128,
    /// Pixel clocks of a line.
    line: u128,
    /// Active pixel clocks of a line.
    active: u128,
    /// Ring rows.
    k: u32,
    /// Pixel clocks of a frame: every line, the retrace's too.
    period: u128,
}

impl Clocks {
    fn new(timing: &VideoTiming, cpu: CpuClock, k: u16) -> Self {
        let v = timing.vertical();
        let line = u128::from(timing.clocks_per_line());
        Clocks {
            cycle: u128::from(timing.pixel_clock().hz()),
            pixel: u128::from(cpu.hz()),
            lead: u128::from(v.total() - u32::from(v.active)) * line,
            line,
            active: u128::from(timing.horizontal().active),
            k: u32::from(k.max(1)),
            period: u128::from(v.total()) * line,
        }
    }

    /// When line `y`'s active display starts.
    fn line_start(&self, y: u32) -> u128 {
        (self.lead + u128::from(y) * self.line) * self.pixel
    }

    /// When row `y` may start: the end of line `y − K`'s active part.
    fn free(&self, y: u32) -> u128 {
        match y.checked_sub(self.k) {
            Some(z) => self.line_start(z) + self.active * self.pixel,
            None => 0,
        }
    }

    /// The time of `instructions` at one a CPU cycle.
    fn cost(&self, instructions: u64) -> u128 {
        u128::from(instructions) * self.cycle
    }
}

/// Which of `rows.len()` rows miss their deadline, from the instructions
/// of preparing the frame and of each row (see the [module](self) docs):
/// `true` for a missed row.
pub fn schedule(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    cpu: CpuClock,
    k: u16,
) -> Vec<bool> {
    let c = Clocks::new(timing, cpu, k);
    let mut finish = c.cost(prepare);
    let mut missed = Vec::with_capacity(rows.len());
    for (y, &cost) in rows.iter().enumerate() {
        let y = y as u32;
        finish = finish.max(c.free(y)) + c.cost(cost);
        missed.push(finish > c.line_start(y));
    }
    missed
}

/// [`schedule`] with `cores` producers (at least 1) taking the rows in
/// turn: core `c` draws rows `c`, `c + cores`, … in order, each core at
/// `cpu`, one instruction a cycle. The first core prepares the frame and
/// the others wait for it; a row still starts only once line `y − K` has
/// been scanned (its slot is free), and a core never skips a row. With
/// one core this is [`schedule`].
pub fn schedule_cores(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    cpu: CpuClock,
    k: u16,
    cores: usize,
) -> Vec<bool> {
    let c = Clocks::new(timing, cpu, k);
    let mut finish = vec![c.cost(prepare); cores.max(1)];
    let mut missed = Vec::with_capacity(rows.len());
    for (y, &cost) in rows.iter().enumerate() {
        let core = &mut finish[y % cores.max(1)];
        let y = y as u32;
        *core = (*core).max(c.free(y)) + c.cost(cost);
        missed.push(*core > c.line_start(y));
    }
    missed
}

/// [`schedule`] with the frame's preparation spread over the spare time
/// of the frame before it (see the [module](self) docs): which of the
/// rows miss their deadline, the frame prepared before its retrace, and
/// `true` when the `prepare` instructions fit in the time the producer
/// does not spend on rows in one frame period (waiting for a slot, and
/// from its last row to the next retrace).
pub fn schedule_spread(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    cpu: CpuClock,
    k: u16,
) -> (Vec<bool>, bool) {
    schedule_spread_cores(prepare, rows, timing, cpu, k, 1)
}

/// [`schedule_spread`] with `cores` producers (at least 1) taking the
/// rows in turn, as in [`schedule_cores`]: the rows' misses, every core
/// starting the frame at its retrace with the frame prepared, and `true`
/// when the `prepare` instructions fit in the spare time of one of the
/// cores (the preparation is one core's work, done in the gaps its own
/// rows leave). With one core this is [`schedule_spread`].
pub fn schedule_spread_cores(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    cpu: CpuClock,
    k: u16,
    cores: usize,
) -> (Vec<bool>, bool) {
    let c = Clocks::new(timing, cpu, k);
    let n = cores.max(1);
    let (mut finish, mut spare) = (vec![0u128; n], vec![0u128; n]);
    let mut missed = Vec::with_capacity(rows.len());
    for (y, &cost) in rows.iter().enumerate() {
        let (f, s) = (&mut finish[y % n], &mut spare[y % n]);
        let y = y as u32;
        let free = c.free(y);
        if free > *f {
            *s += free - *f;
            *f = free;
        }
        *f += c.cost(cost);
        missed.push(*f > c.line_start(y));
    }
    let most = finish
        .iter()
        .zip(&spare)
        .map(|(&f, &s)| s + (c.period * c.pixel).saturating_sub(f))
        .max()
        .unwrap_or(0);
    (missed, c.cost(prepare) <= most)
}

/// The lowest CPU clock, in whole kilohertz, at which no row misses its
/// deadline and the preparation fits, by [`schedule_spread`], or `None`
/// when even [`CpuClock::MAX_MHZ`] does not do.
pub fn lowest_clock_spread(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    k: u16,
) -> Option<CpuClock> {
    lowest_by(|c| {
        let (missed, fits) = schedule_spread(prepare, rows, timing, c, k);
        fits && !missed.contains(&true)
    })
}

/// [`lowest_clock_spread`] with `cores` producers taking the rows in turn
/// ([`schedule_spread_cores`]).
pub fn lowest_clock_spread_cores(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    k: u16,
    cores: usize,
) -> Option<CpuClock> {
    lowest_by(|c| {
        let (missed, fits) = schedule_spread_cores(prepare, rows, timing, c, k, cores);
        fits && !missed.contains(&true)
    })
}

/// The lowest CPU clock, in whole kilohertz, at which no row misses its
/// deadline, or `None` when even [`CpuClock::MAX_MHZ`] misses (a frame
/// whose preparation or rows take longer than the beam gives them).
pub fn lowest_clock(prepare: u64, rows: &[u64], timing: &VideoTiming, k: u16) -> Option<CpuClock> {
    lowest_clock_cores(prepare, rows, timing, k, 1)
}

/// [`lowest_clock`] with `cores` producers taking the rows in turn
/// ([`schedule_cores`]).
pub fn lowest_clock_cores(
    prepare: u64,
    rows: &[u64],
    timing: &VideoTiming,
    k: u16,
    cores: usize,
) -> Option<CpuClock> {
    lowest_by(|c| !schedule_cores(prepare, rows, timing, c, k, cores).contains(&true))
}

/// The lowest clock, in whole kilohertz, that `ok` takes, for an `ok`
/// that takes every clock above one it takes; `None` when it does not
/// take [`CpuClock::MAX_MHZ`].
fn lowest_by(ok: impl Fn(CpuClock) -> bool) -> Option<CpuClock> {
    let ok = |khz: u64| CpuClock::from_hz(khz * 1000).is_some_and(&ok);
    let (mut lo, mut hi) = (0u64, CpuClock::MAX_MHZ * 1000);
    if !ok(hi) {
        return None;
    }
    // ok(hi) holds, ok(lo) does not (0 Hz is no clock).
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    CpuClock::from_hz(hi * 1000)
}

/// One frame shown by racing the beam.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RaceFrame {
    /// What the monitor showed (missed lines red).
    pub frame: Frame,
    /// Instructions of preparing the frame, from the model.
    pub prepare: u64,
    /// Instructions of each row produced, from the model.
    pub rows: Vec<u64>,
    /// Which lines missed their deadline, one a line shown.
    pub missed: Vec<bool>,
    /// The ring's rows.
    pub k: u16,
    /// The format of the ring's rows.
    pub format: RowFormat,
    /// The most runs a row needed while it was composed.
    pub most_runs: usize,
    /// The most 32-bit words of `pico_scanvideo` tokens a row took (0 for
    /// rows kept as runs).
    pub most_words: usize,
}

impl RaceFrame {
    /// Bytes of the ring: `K` slots, each as large as the largest row of
    /// the frame in the ring's format (4 bytes a run, or a word of
    /// tokens).
    pub fn ring_bytes(&self) -> usize {
        let per_row = match self.format {
            RowFormat::Runs => self.most_runs,
            RowFormat::Scanvideo => self.most_words,
        };
        usize::from(self.k) * per_row * 4
    }

    /// Lines that missed their deadline.
    pub fn misses(&self) -> usize {
        self.missed.iter().filter(|&&m| m).count()
    }

    /// Lines shown: the `N` of `M of N lines`.
    pub fn lines(&self) -> usize {
        self.missed.len()
    }
}

/// A row being drawn: done at `finish`.
#[derive(Debug)]
struct InProgress {
    y: u16,
    finish: u128,
    row: Slot,
}

/// A row in the ring, in its format.
#[derive(Debug)]
enum Slot {
    Runs(Vec<Run>),
    Tokens(Vec<u32>),
}

/// The ring of `K` rows and its producer, as the refresh controller's
/// pixel source.
#[derive(Debug)]
struct Ring<'m, P> {
    producer: P,
    model: &'m CostModel,
    clocks: Clocks,
    /// Rows the frame shows.
    lines: u16,
    /// Rows waiting for the beam, oldest first, at most K.
    slots: std::collections::VecDeque<(u16, Slot)>,
    /// Emptied run buffers, reused.
    spare: Vec<Vec<Run>>,
    /// The rows' format in the ring.
    format: RowFormat,
    /// The most runs and words of tokens a row took.
    most: (usize, usize),
    next: u16,
    finished: u128,
    drawing: Option<InProgress>,
    /// The line being scanned: its runs, the run and the pixels left of it.
    line: Vec<Run>,
    cursor: (usize, u16),
    /// The line being scanned missed its deadline.
    red: bool,
    costs: Vec<u64>,
    missed: Vec<bool>,
}

impl<P: Producer> Ring<'_, P> {
    /// Runs the producer up to time `now`.
    fn advance(&mut self, now: u128) {
        loop {
            if let Some(d) = self.drawing.take() {
                if d.finish > now {
                    self.drawing = Some(d);
                    return;
                }
                self.finished = d.finish;
                if d.finish <= self.clocks.line_start(u32::from(d.y)) {
                    // Its slot is free: the row K rows up was scanned
                    // before this one started.
                    debug_assert!(self.slots.len() < self.clocks.k as usize);
                    self.slots.push_back((d.y, d.row));
                } else if let Slot::Runs(runs) = d.row {
                    self.spare.push(runs);
                }
            }
            if self.next >= self.lines {
                return;
            }
            let y = self.next;
            let start = self.finished.max(self.clocks.free(u32::from(y)));
            if start > now {
                return;
            }
            let mut runs = self.spare.pop().unwrap_or_default();
            let work = self.producer.row(y, &mut runs);
            let cost = self.model.row(&work);
            self.costs.push(cost);
            self.most.0 = self.most.0.max(work.peak as usize).max(runs.len());
            let row = match self.format {
                RowFormat::Runs => Slot::Runs(runs),
                RowFormat::Scanvideo => {
                    let words = tokens(&runs);
                    self.most.1 = self.most.1.max(words.len());
                    self.spare.push(runs);
                    Slot::Tokens(words)
                }
            };
            self.drawing = Some(InProgress {
                y,
                finish: start + self.clocks.cost(cost),
                row,
            });
            self.next += 1;
        }
    }

    /// The beam reaches line `y`'s first active pixel.
    fn begin_line(&mut self, y: u16) {
        let old = std::mem::take(&mut self.line);
        if old.capacity() > 0 {
            self.spare.push(old);
        }
        self.cursor = (0, 0);
        self.red = false;
        if y >= self.lines {
            return;
        }
        self.advance(self.clocks.line_start(u32::from(y)));
        while self.slots.front().is_some_and(|(r, _)| *r < y) {
            if let Some((_, Slot::Runs(runs))) = self.slots.pop_front() {
                self.spare.push(runs);
            }
        }
        match self.slots.front() {
            Some((r, _)) if *r == y => {
                match self.slots.pop_front() {
                    Some((_, Slot::Runs(runs))) => self.line = runs,
                    Some((_, Slot::Tokens(words))) => {
                        let mut line = self.spare.pop().unwrap_or_default();
                        if decode_tokens(&words, self.producer.size().0, &mut line) {
                            self.line = line;
                        } else {
                            // Never, for the encoder's own tokens.
                            self.red = true;
                        }
                    }
                    None => {}
                }
                self.missed.push(false);
            }
            _ => {
                self.red = true;
                self.missed.push(true);
            }
        }
    }
}

impl<P: Producer> PixelSource for Ring<'_, P> {
    fn read(&mut self, x: u16, y: u16) -> Option<Rgb565> {
        if x == 0 {
            self.begin_line(y);
        }
        if y >= self.lines {
            return None;
        }
        if self.red {
            return Some(MISS);
        }
        let (i, used) = self.cursor;
        let run = self.line.get(i)?;
        if used + 1 >= run.len {
            self.cursor = (i + 1, 0);
        } else {
            self.cursor = (i, used + 1);
        }
        Some(run.color)
    }

    fn idle(&mut self, _: u64) {}

    fn vertical_blank(&mut self) -> bool {
        false
    }
}

/// Shows one frame of `producer` by racing the beam of `timing`, the
/// producer's CPU at `cpu`, through a ring of `k` rows (at least 1),
/// each row priced by `model`: the refresh controller runs clock by
/// clock, from line 0's first active pixel to the end of the frame's
/// retrace, reading the ring (see the [module](self) docs).
pub fn race<P: Producer>(
    producer: P,
    timing: &VideoTiming,
    cpu: CpuClock,
    k: u16,
    model: &CostModel,
) -> RaceFrame {
    race_in(producer, timing, cpu, k, model, RowFormat::Runs)
}

/// [`race`] with the ring's rows in `format`: the refresh controller
/// decodes each row from it as the beam reaches its line.
pub fn race_in<P: Producer>(
    producer: P,
    timing: &VideoTiming,
    cpu: CpuClock,
    k: u16,
    model: &CostModel,
    format: RowFormat,
) -> RaceFrame {
    let clocks = Clocks::new(timing, cpu, k);
    let prepare = model.prepare(&producer.prepare());
    let lines = producer.size().1.min(timing.height());
    let mut ring = Ring {
        producer,
        model,
        clocks,
        lines,
        slots: Default::default(),
        spare: Vec::new(),
        format,
        most: (0, 0),
        next: 0,
        finished: clocks.cost(prepare),
        drawing: None,
        line: Vec::new(),
        cursor: (0, 0),
        red: false,
        costs: Vec::with_capacity(usize::from(lines)),
        missed: Vec::with_capacity(usize::from(lines)),
    };
    let mut refresh = RefreshController::new(*timing);
    let frame = loop {
        if let Some(f) = refresh.tick(&mut ring) {
            break f;
        }
    };
    // Rows started after the beam passed the last line still count.
    ring.advance(u128::MAX);
    RaceFrame {
        frame,
        prepare,
        rows: ring.costs,
        missed: ring.missed,
        k: clocks.k as u16,
        format,
        most_runs: ring.most.0,
        most_words: ring.most.1,
    }
}

/// A row of runs as `pico_scanvideo` tokens ([`Opcodes::DEFAULT`],
/// RGB565 colours), in words sized for it.
pub fn tokens(runs: &[Run]) -> Vec<u32> {
    let pixels: usize = runs.iter().map(|r| usize::from(r.len)).sum();
    let mut words = vec![0u32; (3 * runs.len() + pixels + 4).div_ceil(2)];
    let it = runs.iter().map(|r| (r.len, scanvideo::rgb565(r.color)));
    match scanvideo::encode(it, &Opcodes::DEFAULT, &mut words) {
        Ok(n) => words.truncate(n),
        // The words are sized for any row; the runs are never empty.
        Err(_) => words.clear(),
    }
    words
}

/// Decodes a line of `pico_scanvideo` tokens into the runs of its first
/// `width` pixels (the black pixel after them is the blanking's); `false`
/// when the tokens are not a line.
pub fn decode_tokens(words: &[u32], width: u16, line: &mut Vec<Run>) -> bool {
    let mut px = vec![0u16; usize::from(width) + 1];
    match scanvideo::decode(words, &Opcodes::DEFAULT, &mut px) {
        Ok(n) => {
            let row: Vec<Rgb565> = px[..n.min(usize::from(width))]
                .iter()
                .map(|&v| Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(v)))
                .collect();
            encode_row(&row, line);
            true
        }
        Err(_) => false,
    }
}

/// A clock given in megahertz on the command line: digits with an
/// optional fraction of at most six digits (`168`, `12.5`), from
/// 0.000001 (1 Hz) to [`CpuClock::MAX_MHZ`] (100 GHz). `None` for
/// anything else (a sign, an exponent, 0, an empty string, a clock out
/// of range).
pub fn parse_mhz(s: &str) -> Option<CpuClock> {
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    let digits = |t: &str| t.bytes().all(|b| b.is_ascii_digit());
    if int.is_empty() || !digits(int) || !digits(frac) || frac.len() > 6 {
        return None;
    }
    if s.ends_with('.') {
        return None;
    }
    let int: u64 = int.parse().ok()?;
    let frac_hz: u64 = format!("{frac:0<6}").parse().ok()?;
    let hz = int.checked_mul(1_000_000)?.checked_add(frac_hz)?;
    CpuClock::from_hz(hz)
}

/// What the program says of a clock [`parse_mhz`] refuses: the range.
pub fn mhz_range_message(option: &str) -> String {
    format!(
        "{option} needs the CPU clock in MHz: a number from 0.000001 to {} (1 Hz to 100 GHz), such as 168 or 12.5",
        CpuClock::MAX_MHZ
    )
}

/// The line the program prints after a race: `deadline misses: M of N
/// lines`.
pub fn misses_line(misses: usize, lines: usize) -> String {
    format!("deadline misses: {misses} of {lines} lines\n")
}

/// The line the program prints after the misses: the ring's memory,
/// `ring: K rows of at most R runs (4 bytes a run): B bytes` (or of
/// words of `pico_scanvideo` tokens).
pub fn ring_line(r: &RaceFrame) -> String {
    let rows = if r.k == 1 { "row" } else { "rows" };
    match r.format {
        RowFormat::Runs => format!(
            "ring: {} {rows} of at most {} runs (4 bytes a run): {} bytes\n",
            r.k,
            r.most_runs,
            r.ring_bytes()
        ),
        RowFormat::Scanvideo => format!(
            "ring: {} {rows} of at most {} words of pico_scanvideo tokens: {} bytes\n",
            r.k,
            r.most_words,
            r.ring_bytes()
        ),
    }
}

/// `scanvert render SCENE --out IMAGE --race MHZ [--fifo K]`: shows the
/// scene by racing the beam of `timing` and writes what the monitor
/// showed; returns the line of misses.
#[allow(clippy::too_many_arguments)]
pub(crate) fn render(
    scene: &crate::cli::Scene,
    timing: &VideoTiming,
    cut: Option<(u16, u16)>,
    cpu: CpuClock,
    fifo: Option<u16>,
    format: RowFormat,
    out: &std::path::Path,
    warn: &mut dyn FnMut(&str),
) -> Result<String, crate::error::CliError> {
    let list = scene.list();
    let (tw, th) = (timing.width(), timing.height());
    if tw < list.width() || th < list.height() {
        warn(&format!(
            "warning: timing {} shows {tw}×{th} of the {}×{} frame; the image is cropped",
            timing.name(),
            list.width(),
            list.height()
        ));
    }
    let mut memory = crate::memory::ListMemory::for_bands(&list).map_err(|e| {
        crate::cli::prepare_error(scene, scanvert::controller::PrepareError::Render(e))
    })?;
    // The cost model is fitted to rows the sweep resolves (crossing points).
    let (controller, table) = memory.band_parts();
    let mut controller = controller.with_resolve(scanvert::visible::Resolve::Crossing);
    let bands = controller
        .bands(&list, table)
        .map_err(|e| crate::cli::prepare_error(scene, e))?;
    let rows = ListRows::new(bands, &list);
    let shown = race_in(
        rows,
        timing,
        cpu,
        fifo.unwrap_or(DEFAULT_FIFO),
        &CostModel::M4,
        format,
    );
    let png = crate::image::encode_png(&cut_to(&shown.frame, cut))
        .map_err(|e| crate::error::io(out, e))?;
    crate::output::write_output(out, &png)?;
    Ok(misses_line(shown.misses(), shown.lines()) + &ring_line(&shown))
}

/// The monitor's image cut to its top-left `w × h` (a frame raced on a
/// larger raster), or whole.
fn cut_to(frame: &Frame, cut: Option<(u16, u16)>) -> Frame {
    let Some((w, h)) = cut else {
        return frame.clone();
    };
    let (w, h) = (w.min(frame.width()), h.min(frame.height()));
    let pixels = frame
        .pixels()
        .chunks(usize::from(frame.width()))
        .take(usize::from(h))
        .flat_map(|row| &row[..usize::from(w)])
        .copied()
        .collect();
    Frame::from_pixels(w, h, pixels).unwrap_or_else(|| frame.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timing::{AxisTiming, Clock};
    use proptest::prelude::*;

    fn timing(w: u16, h: u16) -> VideoTiming {
        let axis = |active, porch| AxisTiming {
            active,
            front_porch: porch,
            sync: 2,
            back_porch: porch,
        };
        VideoTiming::new("test", Clock::from_mhz(1).unwrap(), axis(w, 3), axis(h, 1)).unwrap()
    }

    /// A producer of rows of given costs (a model of one instruction a
    /// span and no more), each row a stripe of its own colour.
    struct Costed {
        w: u16,
        costs: Vec<u32>,
        prepare: u32,
    }

    impl Producer for Costed {
        fn size(&self) -> (u16, u16) {
            (self.w, self.costs.len() as u16)
        }
        fn prepare(&self) -> PrepareWork {
            PrepareWork {
                commands: self.prepare,
                ..PrepareWork::default()
            }
        }
        fn row(&mut self, y: u16, runs: &mut Vec<Run>) -> RowWork {
            runs.clear();
            runs.push(Run {
                len: self.w,
                color: Rgb565::new((y % 32) as u8, 63, 1),
            });
            RowWork {
                spans: self.costs[usize::from(y)],
                ..RowWork::default()
            }
        }
    }

    const SPANS: CostModel = CostModel {
        row: 0,
        width: 0,
        span: 16,
        pixel: 0,
        run: 0,
        entered: 0,
        resolved: 0,
        label: 0,
        live: 0,
        word: 0,
        moved: 0,
        frame: 0,
        command: 16,
        trapezoid: 0,
    };

    #[test]
    fn encode_row_merges_equal_neighbours() {
        let (a, b) = (Rgb565::new(1, 2, 3), Rgb565::new(4, 5, 6));
        let mut runs = Vec::new();
        assert_eq!(encode_row(&[a, a, b, a, a, a], &mut runs), 3);
        assert_eq!(
            runs,
            [
                Run { len: 2, color: a },
                Run { len: 1, color: b },
                Run { len: 3, color: a }
            ]
        );
        assert_eq!(encode_row(&[], &mut runs), 0);
    }

    #[test]
    fn parse_mhz_takes_decimals_and_refuses_the_rest() {
        assert_eq!(parse_mhz("168").map(CpuClock::hz), Some(168_000_000));
        assert_eq!(parse_mhz("12.5").map(CpuClock::hz), Some(12_500_000));
        assert_eq!(parse_mhz("0.000001").map(CpuClock::hz), Some(1));
        assert_eq!(parse_mhz("4294.967296").map(CpuClock::hz), Some(1 << 32));
        assert_eq!(parse_mhz("10000").map(CpuClock::hz), Some(10_000_000_000));
        assert_eq!(parse_mhz("100000").map(CpuClock::hz), Some(100_000_000_000));
        for bad in [
            "",
            "0",
            "0.0",
            "-5",
            "+5",
            "1e3",
            "abc",
            "1.",
            ".5",
            "100000.000001",
            "184467440737095.51616",
            "1.0000001",
            " 5",
        ] {
            assert_eq!(parse_mhz(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn a_fast_producer_shows_the_frame_and_a_slow_one_red_lines() {
        let t = timing(8, 6);
        let p = |costs: Vec<u32>| Costed {
            w: 8,
            costs,
            prepare: 0,
        };
        // A line is 8 + 3 + 2 + 3 = 16 pixel clocks of 1 µs.
        let fast = race(
            p(vec![5; 6]),
            &t,
            CpuClock::from_mhz(1000).unwrap(),
            2,
            &SPANS,
        );
        assert_eq!(fast.misses(), 0);
        for y in 0..6u16 {
            let row = fast.frame.row(y).unwrap();
            assert!(row.iter().all(|&c| c == Rgb565::new(y as u8, 63, 1)));
        }
        // 100 instructions a row at 1 MHz: 100 µs a row against 16 µs a line.
        let slow = race(
            p(vec![100; 6]),
            &t,
            CpuClock::from_mhz(1).unwrap(),
            2,
            &SPANS,
        );
        assert!(slow.misses() > 0);
        for y in 0..6u16 {
            let red = slow.frame.row(y).unwrap().iter().all(|&c| c == MISS);
            assert_eq!(red, slow.missed[usize::from(y)]);
        }
    }

    #[test]
    fn the_ring_bounds_how_far_ahead_the_producer_runs() {
        // Retrace: 1 + 2 + 1 = 4 lines of 16 µs = 64 µs before line 0.
        // Row 0 costs 200 µs; then rows of 1 µs. With K = 1 the producer
        // cannot bank rows in the retrace, so it falls behind by the first
        // row and stays there for as long as the ring lets it catch up.
        let t = timing(8, 6);
        let costs = vec![1, 1, 1, 1, 1, 1];
        let c = Costed {
            w: 8,
            costs: costs.clone(),
            prepare: 60,
        };
        // Prepared at 60 µs, row 0 at 61 µs against line 0 at 64 µs.
        let r = race(c, &t, CpuClock::from_mhz(1).unwrap(), 1, &SPANS);
        assert_eq!(r.misses(), 0);
        let c = Costed {
            w: 8,
            costs,
            prepare: 64,
        };
        let r = race(c, &t, CpuClock::from_mhz(1).unwrap(), 1, &SPANS);
        assert_eq!(r.missed, [true, false, false, false, false, false]);
    }

    proptest! {
        #[test]
        fn the_beam_and_the_schedule_agree(
            costs in proptest::collection::vec(0u32..80, 1..12),
            prepare in 0u32..200,
            k in 1u16..5,
            mhz in 1u32..4,
        ) {
            let t = timing(5, costs.len() as u16);
            let cpu = CpuClock::from_mhz(u64::from(mhz)).unwrap();
            let r = race(Costed { w: 5, costs: costs.clone(), prepare }, &t, cpu, k, &SPANS);
            let rows: Vec<u64> = costs.iter().map(|&c| u64::from(c.max(1))).collect();
            prop_assert_eq!(&r.rows, &rows);
            prop_assert_eq!(&r.missed, &schedule(u64::from(prepare), &rows, &t, cpu, k));
            for (y, &m) in r.missed.iter().enumerate() {
                let red = r.frame.row(y as u16).unwrap().iter().all(|&c| c == MISS);
                prop_assert_eq!(red, m);
            }
        }
    }

    #[test]
    fn live_polygons_counts_the_rows_each_polygon_reaches() {
        let asm = crate::text::assemble_bytes(
            b"frame 8 12\ncolor #ffffff\npoly 0 2 8 2 4 10\nclear #000000\npoly 0 2.5 8 2.5 4 4.5\npoly 0 -3 8 0 4 1.5\n",
        )
        .unwrap();
        let list = DisplayList::new_checked(&asm.bytes).unwrap();
        // After the clear: rows 2 and 3 (centres 2.5, 3.5 in [2.5, 4.5))
        // and rows 0 (centre 0.5 in [-3, 1.5)); the first poly is cleared.
        assert_eq!(live_polygons(&list), [1, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0]);
    }

    proptest! {
        #[test]
        fn one_core_is_the_schedule_and_two_are_never_later(
            costs in proptest::collection::vec(1u64..80, 1..12),
            prepare in 0u64..200,
            k in 1u16..5,
            mhz in 1u64..4,
        ) {
            let t = timing(5, costs.len() as u16);
            let cpu = CpuClock::from_mhz(mhz).unwrap();
            let one = schedule(prepare, &costs, &t, cpu, k);
            prop_assert_eq!(&schedule_cores(prepare, &costs, &t, cpu, k, 1), &one);
            let two = schedule_cores(prepare, &costs, &t, cpu, k, 2);
            for (a, b) in one.iter().zip(&two) {
                prop_assert!(!b || *a, "a row missed with two cores and not with one");
            }
        }
    }

    #[test]
    fn a_preparation_spread_over_the_frame_before_fits_in_its_spare_time() {
        // Lines of 16 µs, 10 of them a frame (4 of retrace): 160 µs a
        // period. Six rows of 1 µs with K = 1 leave 154 µs spare (waiting
        // for slots, and after the last row); prepared before row 0, at
        // most 63 µs fit (`the_ring_bounds_how_far_ahead_the_producer_runs`).
        let t = timing(8, 6);
        let cpu = CpuClock::from_mhz(1).unwrap();
        let rows = [1u64; 6];
        let (missed, fits) = schedule_spread(154, &rows, &t, cpu, 1);
        assert_eq!((missed, fits), (vec![false; 6], true));
        assert!(!schedule_spread(155, &rows, &t, cpu, 1).1);
        assert!(schedule(154, &rows, &t, cpu, 1).contains(&true));
        // The lowest clock: the rows' or the preparation's, whichever
        // needs more.
        let c = lowest_clock_spread(154, &rows, &t, 1).unwrap();
        assert!(c.hz() <= 1_000_000, "{c}");
        assert!(!schedule_spread(154, &rows, &t, c, 1).0.contains(&true));
        let below = CpuClock::from_hz(c.hz() - 1000).unwrap();
        let (m, fits) = schedule_spread(154, &rows, &t, below, 1);
        assert!(!fits || m.contains(&true));
    }

    proptest! {
        #[test]
        fn a_spread_preparation_misses_no_row_the_retrace_does_not(
            costs in proptest::collection::vec(1u64..80, 1..12),
            prepare in 0u64..400,
            k in 1u16..5,
            mhz in 1u64..4,
        ) {
            let t = timing(5, costs.len() as u16);
            let cpu = CpuClock::from_mhz(mhz).unwrap();
            let (spread, fits) = schedule_spread(prepare, &costs, &t, cpu, k);
            // The rows as if the frame were prepared already.
            prop_assert_eq!(&spread, &schedule(0, &costs, &t, cpu, k));
            let before = schedule(prepare, &costs, &t, cpu, k);
            for (a, b) in spread.iter().zip(&before) {
                prop_assert!(!a || *b);
            }
            // A preparation that fits before row 0 with no row missed
            // fits in the spare time too.
            if !before.contains(&true) {
                prop_assert!(fits);
            }
        }

        #[test]
        fn two_producers_spread_their_rows_as_two_cores_with_the_frame_prepared(
            costs in proptest::collection::vec(1u64..80, 1..12),
            prepare in 0u64..400,
            k in 1u16..5,
            mhz in 1u64..4,
        ) {
            let t = timing(5, costs.len() as u16);
            let cpu = CpuClock::from_mhz(mhz).unwrap();
            prop_assert_eq!(
                schedule_spread_cores(prepare, &costs, &t, cpu, k, 1),
                schedule_spread(prepare, &costs, &t, cpu, k)
            );
            let (two, fits) = schedule_spread_cores(prepare, &costs, &t, cpu, k, 2);
            prop_assert_eq!(&two, &schedule_cores(0, &costs, &t, cpu, k, 2));
            // The core with more spare time than one producer has (its
            // rows are half the rows) takes a preparation one producer
            // fits.
            if schedule_spread(prepare, &costs, &t, cpu, k).1 {
                prop_assert!(fits);
            }
        }
    }

    #[test]
    fn lowest_clock_is_the_edge_of_no_misses() {
        let t = VideoTiming::REFERENCE_640X480;
        let rows = vec![5376u64; 480];
        let c = lowest_clock(0, &rows, &t, 2).unwrap();
        assert!(!schedule(0, &rows, &t, c, 2).contains(&true));
        let below = CpuClock::from_hz(c.hz() - 1000).unwrap();
        assert!(schedule(0, &rows, &t, below, 2).contains(&true));
        // 5,376 instructions in a 32 µs line: 168 MHz, a little less for
        // the rows banked in the retrace (K = 2 of 480 rows).
        assert!((167_000_000..=168_000_000).contains(&c.hz()), "{c}");
    }
}

/// The producer of a display list's rows: the library's racing path
/// ([`ListBands::draw_runs`]), each row composed as colour runs with no
/// pixel buffer. Its work per row is what the path counted for the row
/// (spans, pixels, labels, the 3D layer's trapezoids entered and spans
/// resolved, runs moved by insertions), the row's runs, and the edge
/// table's polygons live on it and words of its live set scanned.
#[derive(Debug)]
pub struct ListRows<'t> {
    bands: ListBands<'t>,
    live: Vec<u32>,
    words: u32,
    row: Vec<ColorRun<Rgb565>>,
    last: RenderStats,
    prepare: PrepareWork,
}

impl<'t> ListRows<'t> {
    /// The rows of `list` prepared for bands
    /// ([`Controller::bands`](scanvert::controller::Controller::bands)),
    /// none drawn yet.
    pub fn new(bands: ListBands<'t>, list: &DisplayList<'_>) -> Self {
        let s = bands.stats();
        let entries = list.table_needs();
        ListRows {
            live: live_polygons(list),
            words: entries.polygons.div_ceil(32) as u32,
            row: vec![ColorRun::new(0, Rgb565::new(0, 0, 0)); usize::from(bands.size().0)],
            last: s,
            prepare: PrepareWork {
                commands: s.commands,
                polygons: s.polygons,
                trapezoids: s.trapezoids,
            },
            bands,
        }
    }
}

/// The runs of a composed row as the ring's runs (lengths).
fn ring_runs(row: &RowRuns<'_, Rgb565>, out: &mut Vec<Run>) -> usize {
    out.clear();
    out.extend(row.runs().map(|(x0, x1, color)| Run {
        len: x1 - x0,
        color,
    }));
    out.len()
}

/// The work of a row from the band path's counters before and after it,
/// and the row's runs.
fn row_work(before: &RenderStats, after: &RenderStats, width: u16, runs: usize) -> RowWork {
    let resolved = |s: &RenderStats| {
        let v = &s.visible;
        v.empty + v.single + v.multiple + v.intersecting
    };
    RowWork {
        width: u32::from(width),
        spans: after.spans - before.spans,
        pixels: (after.pixels - before.pixels) as u32,
        runs: runs as u32,
        entered: after.visible.trapezoids - before.visible.trapezoids,
        resolved: resolved(after) - resolved(before),
        labels: after.labels - before.labels,
        ..RowWork::default()
    }
}

/// For each row of `list`'s frame, the `poly`s and `line`s after its last
/// `clear` (the edge table's polygons) whose vertical extent reaches the
/// row's centre: `min y ≤ row + ½ < max y`, before clipping.
pub fn live_polygons(list: &DisplayList<'_>) -> Vec<u32> {
    let h = usize::from(list.height());
    let mut delta = vec![0i64; h + 1];
    let mut add = |ys: &mut dyn Iterator<Item = i16>| {
        let (lo, hi) = ys.fold((i16::MAX, i16::MIN), |(lo, hi), y| (lo.min(y), hi.max(y)));
        // Rows whose centre 16·row + 8 (in 1/16 pixel) is in [lo, hi).
        let first =
            (i64::from(lo) - 8).div_euclid(16) + i64::from((i64::from(lo) - 8).rem_euclid(16) != 0);
        let end =
            (i64::from(hi) - 8).div_euclid(16) + i64::from((i64::from(hi) - 8).rem_euclid(16) != 0);
        let (first, end) = (first.clamp(0, h as i64), end.clamp(0, h as i64));
        if first < end {
            delta[first as usize] += 1;
            delta[end as usize] -= 1;
        }
    };
    let mut cleared = 0;
    let cmds: Vec<Command<'_>> = list.commands().map(|(_, c)| c).collect();
    for (i, c) in cmds.iter().enumerate() {
        if matches!(c, Command::Clear(_)) {
            cleared = i;
        }
    }
    for c in &cmds[cleared..] {
        match c {
            Command::Poly(v) => add(&mut v.iter().map(|v| v.y.to_bits())),
            Command::Line(a, b) => add(&mut [a.y.to_bits(), b.y.to_bits()].into_iter()),
            _ => {}
        }
    }
    let mut live = 0i64;
    delta[..h]
        .iter()
        .map(|d| {
            live += d;
            live.max(0) as u32
        })
        .collect()
}

impl Producer for ListRows<'_> {
    fn size(&self) -> (u16, u16) {
        self.bands.size()
    }
    fn prepare(&self) -> PrepareWork {
        self.prepare
    }
    fn row(&mut self, y: u16, runs: &mut Vec<Run>) -> RowWork {
        // Rows come in order and inside the frame, and the runs are as
        // many as the row's pixels: the path refuses none of them.
        let mut row = RowRuns::new(&mut self.row);
        let drawn = self.bands.draw_runs(y, &mut row);
        debug_assert!(drawn.is_ok());
        let n = ring_runs(&row, runs);
        let now = self.bands.stats();
        let mut work = row_work(&self.last, &now, self.bands.size().0, n);
        work.live = self.live.get(usize::from(y)).copied().unwrap_or(0);
        work.words = self.words;
        work.moved = row.moved();
        work.peak = row.peak() as u32;
        self.last = now;
        work
    }
}

/// The work of preparing `list`'s frame and of each of its rows, as
/// [`ListRows`] counts them on the band path, or `None` when the list
/// cannot be rendered (a capacity it needs is refused).
pub fn list_work(list: &DisplayList<'_>) -> Option<(PrepareWork, Vec<RowWork>)> {
    let mut memory = crate::memory::ListMemory::for_bands(list).ok()?;
    let (controller, table) = memory.band_parts();
    let mut controller = controller.with_resolve(scanvert::visible::Resolve::Crossing);
    let mut rows = ListRows::new(controller.bands(list, table).ok()?, list);
    let mut runs = Vec::new();
    let work = (0..rows.size().1).map(|y| rows.row(y, &mut runs)).collect();
    Some((rows.prepare(), work))
}

/// The producer of a 3D scene's rows: the scene's band pass
/// ([`Scene::bands`](scanvert::scene::Scene::bands)), each row composed
/// as colour runs ([`SceneBands::draw_runs`]). The scene's polygons are already
/// cut into trapezoids (by `Scene::update`, before the pass, which is not
/// counted), so preparing the pass is priced as the frame term of the
/// model alone.
#[derive(Debug)]
pub struct SceneRows<'s, 'a, 'w> {
    bands: SceneBands<'s, 'a, 'w, Rgb565>,
    size: (u16, u16),
    row: Vec<ColorRun<Rgb565>>,
    last: SceneFrame,
}

impl<'s, 'a, 'w> SceneRows<'s, 'a, 'w> {
    /// The rows of a pass over a scene of `size` (width, height), none
    /// drawn yet.
    pub fn new(bands: SceneBands<'s, 'a, 'w, Rgb565>, size: (u16, u16)) -> Self {
        SceneRows {
            last: bands.frame(),
            bands,
            size,
            row: vec![ColorRun::new(0, Rgb565::new(0, 0, 0)); usize::from(size.0)],
        }
    }
}

impl Producer for SceneRows<'_, '_, '_> {
    fn size(&self) -> (u16, u16) {
        self.size
    }
    fn prepare(&self) -> PrepareWork {
        PrepareWork::default()
    }
    fn row(&mut self, y: u16, runs: &mut Vec<Run>) -> RowWork {
        let mut row = RowRuns::new(&mut self.row);
        let drawn = self.bands.draw_runs(y, &mut row);
        debug_assert!(drawn.is_ok());
        let n = ring_runs(&row, runs);
        let (moved, peak) = (row.moved(), row.peak() as u32);
        let (a, b) = (self.last, self.bands.frame());
        self.last = b;
        let resolved = |f: &SceneFrame| {
            let v = &f.visible;
            v.empty + v.single + v.multiple + v.intersecting
        };
        RowWork {
            width: u32::from(self.size.0),
            spans: (b.decoded.spans + b.labels.written.spans)
                - (a.decoded.spans + a.labels.written.spans),
            pixels: (b.decoded.pixels + b.labels.written.pixels)
                - (a.decoded.pixels + a.labels.written.pixels),
            runs: n as u32,
            entered: b.visible.trapezoids - a.visible.trapezoids,
            resolved: resolved(&b) - resolved(&a),
            labels: b.labels.drawn - a.labels.drawn,
            moved,
            peak,
            ..RowWork::default()
        }
    }
}

/// `scanvert demo --race MHZ [--fifo K]`: every frame of the demo shown
/// by racing the beam of `timing`, written as `DIR/frame-NN.png`; returns
/// a line `frame NN: deadline misses: M of N lines` a frame.
pub(crate) fn demo(
    dir: &std::path::Path,
    frames: usize,
    timing: &VideoTiming,
    cut: Option<(u16, u16)>,
    cpu: CpuClock,
    fifo: Option<u16>,
    format: RowFormat,
) -> Result<String, crate::error::CliError> {
    use crate::demo::{HEIGHT, WIDTH};
    use scanvert::scene::DEFAULT_FONT;
    use scanvert::visible::sweep::Resolve;
    std::fs::create_dir_all(dir).map_err(|e| crate::error::io(dir, e))?;
    let mut report = String::new();
    let mut failure = None;
    // The ring sized for every frame.
    let mut ring: Option<RaceFrame> = None;
    let mut i = 0;
    crate::demo::drive(
        frames,
        |scene, procs| scene.update(procs),
        |scene, _, _, background| {
            if failure.is_some() {
                return;
            }
            let shown = match scene.bands(Resolve::Crossing, background, DEFAULT_FONT) {
                Ok(bands) => race_in(
                    SceneRows::new(bands, (WIDTH, HEIGHT)),
                    timing,
                    cpu,
                    fifo.unwrap_or(DEFAULT_FIFO),
                    &CostModel::M4,
                    format,
                ),
                Err(e) => {
                    failure = Some(crate::error::input(std::path::Path::new("demo"), e));
                    return;
                }
            };
            let path = dir.join(format!("frame-{i:02}.png"));
            let written = crate::image::encode_png(&cut_to(&shown.frame, cut))
                .map_err(|e| crate::error::io(&path, e))
                .and_then(|png| crate::output::write_output(&path, &png));
            match written {
                Ok(()) => {
                    report += &format!("frame {i:02}: ");
                    report += &misses_line(shown.misses(), shown.lines());
                    let most = ring.get_or_insert_with(|| shown.clone());
                    most.most_runs = most.most_runs.max(shown.most_runs);
                    most.most_words = most.most_words.max(shown.most_words);
                }
                Err(e) => failure = Some(e),
            }
            i += 1;
        },
    )?;
    if let Some(r) = &ring {
        report += &ring_line(r);
    }
    match failure {
        Some(e) => Err(e),
        None => Ok(report),
    }
}

/// The instructions, from `model`, of preparing and of each row of every
/// frame of the demo's first `frames` steps (`scanvert demo`), with the
/// most runs a row of the frame needed.
pub fn demo_costs(
    frames: usize,
    model: &CostModel,
) -> Result<Vec<(u64, Vec<u64>, usize)>, crate::error::CliError> {
    use crate::demo::{HEIGHT, WIDTH};
    use scanvert::scene::DEFAULT_FONT;
    use scanvert::visible::sweep::Resolve;
    let timing = VideoTiming::for_frame(WIDTH, HEIGHT);
    let cpu = CpuClock::from_mhz(1000).expect("1 GHz");
    let mut costs = Vec::new();
    crate::demo::drive(
        frames,
        |scene, procs| scene.update(procs),
        |scene, _, _, background| {
            if let Ok(bands) = scene.bands(Resolve::Crossing, background, DEFAULT_FONT) {
                let r = race(
                    SceneRows::new(bands, (WIDTH, HEIGHT)),
                    &timing,
                    cpu,
                    1,
                    model,
                );
                costs.push((r.prepare, r.rows, r.most_runs));
            }
        },
    )?;
    Ok(costs)
}
