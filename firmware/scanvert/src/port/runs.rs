//! Rows made of runs: one row of the frame composed as colour runs, with
//! no pixel buffer, for racing the beam.
//!
//! A display that has no frame memory (a VGA signal driven by a
//! microcontroller, a soft core with no external RAM, the Pico's
//! `pico_scanvideo`) is fed a row at a time, just before the beam reaches
//! it. Drawing that row into a band of pixels and encoding it again costs
//! its width twice; [`RowRuns`] is a [`SpanTarget`] for one row that keeps
//! the row as a short list of runs instead, so a row costs what is drawn
//! on it:
//!
//! - the background is one run ([`SpanTarget::clear`]);
//! - every span (2D polygons and lines in painter's order, the 3D
//!   layer's resolved runs, the labels' glyph rows merged into spans) is
//!   inserted over what is there: the runs it covers are removed, the
//!   ones it cuts are trimmed, and it merges with a neighbour of its
//!   colour. A span costs a binary search and a move of the runs to its
//!   right. The 3D layer's runs, which come left to right, are appended
//!   instead, a batch of them in one pass
//!   ([`SpanTarget::RUNS_IN_BATCHES`], [`SpanTarget::fill_runs_inside`]).
//!
//! [`ListBands::draw_runs`](crate::controller::ListBands::draw_runs) and
//! [`SceneBands::draw_runs`](crate::scene::SceneBands::draw_runs) compose
//! a row so, through the same stages as a band; the row decodes
//! ([`RowRuns::decode`]) to exactly the pixels of the band path's row.
//!
//! # The row format
//!
//! A row is a slice of [`ColorRun`]s, left to right: run `i` covers the
//! pixels `x_i..x_{i+1}` (the last one up to the row's width) in its
//! colour. Always, for a row of width `w ≥ 1`:
//! - the first run starts at 0, starts increase strictly, all are below
//!   `w` (so every run holds at least one pixel);
//! - two runs next to each other differ in colour (a row of one colour is
//!   one run).
//!
//! A `ColorRun<Rgb565>` is 4 bytes (a `u16` start and the colour); a run's
//! length is the next start minus its own (or the width minus it, for
//! the last). [`RowRuns::runs`] gives `(x0, x1, colour)` triples, and
//! [`scanvideo`](crate::port::scanvideo) encodes a row into the tokens of
//! the Pico's composable scan-line program.
//!
//! # Capacity
//!
//! The caller lends the runs (`[ColorRun<C>]`, any length). A row of width
//! `w` never holds more than `w` runs, before or after an insertion (the
//! runs an insertion puts in are worked out before the row is changed),
//! so a capacity of `w` is never exceeded. A smaller one is enough for
//! most rows (a clear row is one run; [`RowRuns::peak`] says what a row
//! took); a span that does not fit leaves the row
//! [`overflowed`](RowRuns::overflowed) (the span is dropped, later ones
//! still inserted), and the compose calls report it as
//! [`RowsError::Full`] with the row, never a panic.

use super::{RowRun, Span, SpanTarget};
use core::convert::Infallible;
use core::fmt;
use embedded_graphics_core::pixelcolor::PixelColor;

/// One run of a row: from pixel `x` to the next run's start (or the row's
/// end) in `color`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ColorRun<C> {
    /// First pixel.
    pub x: u16,
    /// Its colour.
    pub color: C,
}

impl<C> ColorRun<C> {
    /// A run from `x` in `color` (for filling the caller's array).
    pub const fn new(x: u16, color: C) -> Self {
        ColorRun { x, color }
    }
}

/// Why a row could not be composed from runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RowsError<R> {
    /// The row is refused (outside the frame, above the last one drawn):
    /// nothing was composed.
    Band(super::band::BandError),
    /// The frame's work could not be resolved, as the band path reports
    /// it.
    Render(R),
    /// The runs lent for row `y` are too few for what is drawn on it; a
    /// row of width `w` needs at most `w`.
    Full {
        /// The row.
        y: u16,
        /// Runs lent.
        capacity: usize,
    },
}

impl<R: fmt::Display> fmt::Display for RowsError<R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RowsError::Band(e) => write!(f, "{e}"),
            RowsError::Render(e) => write!(f, "{e}"),
            RowsError::Full { y, capacity } => {
                write!(f, "row {y} needs more than the {capacity} runs lent for it")
            }
        }
    }
}

impl<R: fmt::Display + fmt::Debug> core::error::Error for RowsError<R> {}

impl<R> From<super::band::BandError> for RowsError<R> {
    fn from(e: super::band::BandError) -> Self {
        RowsError::Band(e)
    }
}

/// One row `y` of a `width × height` frame as colour runs in the caller's
/// slice (see the [module](self) docs for the format and the capacity).
/// As a [`SpanTarget`] it has the frame's size and keeps the spans on its
/// row; the others are dropped.
#[derive(Debug)]
pub struct RowRuns<'r, C> {
    runs: &'r mut [ColorRun<C>],
    len: usize,
    width: u16,
    height: u16,
    y: u16,
    overflowed: bool,
    peak: usize,
    moved: u32,
}

impl<'r, C: PixelColor> RowRuns<'r, C> {
    /// An empty row over `runs`, to be started by
    /// [`start`](Self::start) (the compose calls start it).
    pub fn new(runs: &'r mut [ColorRun<C>]) -> Self {
        RowRuns {
            runs,
            len: 0,
            width: 0,
            height: 0,
            y: 0,
            overflowed: false,
            peak: 0,
            moved: 0,
        }
    }

    /// Starts row `y` of a frame of `size`, all of it `background`: one
    /// run (none for a frame of width 0; the row overflows at once when
    /// no run is lent).
    pub fn start(&mut self, y: u16, (width, height): (u16, u16), background: C) {
        self.width = width;
        self.height = height;
        self.y = y;
        self.overflowed = false;
        self.len = 0;
        self.peak = 0;
        self.moved = 0;
        if width > 0 {
            match self.runs.first_mut() {
                Some(r) => {
                    *r = ColorRun::new(0, background);
                    self.len = 1;
                    self.peak = 1;
                }
                None => self.overflowed = true,
            }
        }
    }

    /// The row.
    pub fn y(&self) -> u16 {
        self.y
    }

    /// The row's width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Runs lent.
    pub fn capacity(&self) -> usize {
        self.runs.len()
    }

    /// `true` when a span did not fit since the row was started: the row
    /// is not the frame's.
    pub fn overflowed(&self) -> bool {
        self.overflowed
    }

    /// The most runs the row held at once since it was started (counting
    /// a span that did not fit as if it had): the capacity that composes
    /// it.
    pub fn peak(&self) -> usize {
        self.peak
    }

    /// Runs moved to make room or close gaps since the row was started
    /// (an insertion moves the runs to its right): the part of a row's
    /// cost that grows with its runs.
    pub fn moved(&self) -> u32 {
        self.moved
    }

    /// The row's runs, left to right (see the [module](self) docs).
    pub fn as_slice(&self) -> &[ColorRun<C>] {
        &self.runs[..self.len]
    }

    /// Runs in the row.
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` when the row holds no run (a frame of width 0).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The runs as `(x0, x1, colour)`, pixels `x0..x1`, left to right.
    pub fn runs(&self) -> impl Iterator<Item = (u16, u16, C)> + '_ {
        let s = self.as_slice();
        s.iter().enumerate().map(move |(i, r)| {
            let end = s.get(i + 1).map_or(self.width, |n| n.x);
            (r.x, end, r.color)
        })
    }

    /// Writes the row's pixels into `out`, as far as both reach; returns
    /// the pixels written (the width, when `out` is long enough).
    pub fn decode(&self, out: &mut [C]) -> usize {
        let mut n = 0;
        for (x0, x1, c) in self.runs() {
            let end = usize::from(x1).min(out.len());
            if let Some(px) = out.get_mut(usize::from(x0)..end) {
                px.fill(c);
                n = end;
            }
        }
        n
    }

    /// Puts `color` over the pixels `x0..x1` (`x0 < x1 ≤ width`, and the
    /// row holds a run), when they start in the row's last run: the span
    /// replaces its end, no run moves and none is looked for. The 3D
    /// layer's runs, which come left to right, all do.
    #[inline(always)]
    fn append(&mut self, x0: u16, x1: u16, color: C) {
        let last = self.len - 1;
        let after = self.runs[last];
        // Run `last` stays when it starts left of the span (it is cut at
        // x0); the span's runs go from `n` on: the span's own unless it
        // merges with the run before, then the rest of `after`'s.
        let n = if after.x < x0 { last + 1 } else { last };
        let own = n == 0 || self.runs[n - 1].color != color;
        let rest = x1 < self.width && after.color != color;
        let total = n + own as usize + rest as usize;
        self.peak = self.peak.max(total);
        if total > self.runs.len() {
            self.overflowed = true;
            return;
        }
        let mut at = n;
        if own {
            self.runs[at] = ColorRun::new(x0, color);
            at += 1;
        }
        if rest {
            self.runs[at] = ColorRun::new(x1, after.color);
        }
        self.len = total;
    }

    /// [`append`](Self::append) of the runs `runs` one after the other
    /// from `x0` (as [`SpanTarget::fill_runs_inside`] hands them over),
    /// in one pass: the pixels right of each are the last run's colour
    /// (`after`), which a run puts back at its end only to have the next
    /// one take it away, so it is put back once, after the last. The
    /// row, its peak (each append's count of runs, the put-back one
    /// included) and its length are those of the appends in turn.
    /// `false`, with nothing changed, where the appends would not all
    /// take this path or might not fit: the caller appends them one by
    /// one.
    #[inline(always)]
    fn append_all(&mut self, x0: u16, runs: &[RowRun<C>]) -> bool {
        let width = self.width;
        let Some(last) = self.len.checked_sub(1) else {
            return false;
        };
        let after = self.runs[last];
        // Each run adds one at most, and the put-back run one.
        if after.x > x0 || last + runs.len() + 2 > self.runs.len() {
            return false;
        }
        // Runs go in from `n` on (run `last` stays when it starts left
        // of `x0`, cut there), after the colour `prev`.
        let mut n = if after.x < x0 { last + 1 } else { last };
        // `x`: where the next run starts, as the caller's order has it.
        // `fresh`: the last run put in started a colour. An append
        // counts the runs it leaves, the put-back one included: the most
        // are those of the last colour's first run, which puts one back
        // unless it ends the row.
        let (mut x, mut fresh, mut any) = (x0, false, false);
        let mut it = runs.iter();
        let mut prev = match n {
            0 => {
                // The row is one run, from `x0` = 0: the first run with
                // pixels goes in whatever its colour (none before it).
                let first = loop {
                    match it.next() {
                        None => return true,
                        Some(r) if r.x1 == x0 => continue,
                        Some(r) if r.x1 < x0 => return false,
                        Some(r) => break r,
                    }
                };
                self.runs[0] = ColorRun::new(x0, first.color);
                (n, x, fresh, any) = (1, first.x1, true, true);
                first.color
            }
            _ => self.runs[n - 1].color,
        };
        for r in it {
            if r.x1 <= x {
                if r.x1 < x {
                    // A run that goes back is an insertion: nothing
                    // changed but run `last`, which is put back.
                    self.runs[last] = after;
                    return false;
                }
                continue;
            }
            if x < width {
                fresh = prev != r.color;
                if fresh {
                    self.runs[n] = ColorRun::new(x, r.color);
                    n += 1;
                    prev = r.color;
                }
                any = true;
            }
            x = r.x1;
        }
        if !any {
            // Nothing put in: the row as it was.
            self.runs[last] = after;
            return true;
        }
        let end = x.min(width);
        let back = prev != after.color;
        let first_back = back && (end < width || !fresh);
        self.peak = self.peak.max(n + first_back as usize);
        if back && end < width {
            self.runs[n] = ColorRun::new(end, after.color);
            n += 1;
        }
        self.len = n;
        true
    }

    /// Puts `color` over the pixels `x0..x1` (`x0 < x1 ≤ width`, and the
    /// row holds a run).
    fn insert(&mut self, x0: u16, x1: u16, color: C) {
        let len = self.len;
        let runs = &mut self.runs[..len];
        // The run holding x0 (the first starts at 0 ≤ x0).
        let i = runs.partition_point(|r| r.x <= x0).saturating_sub(1);
        // The first run after the one holding x1 (or len): a walk over
        // the runs the span covers, each of which it removes (a run is
        // put in once and removed once, so the walk is paid for by the
        // insertions).
        let mut k = i + 1;
        while k < len && runs[k].x <= x1 {
            k += 1;
        }
        // The run holding pixel x1, whose colour goes on after the span.
        let after = runs[k - 1];
        // Runs i.. are replaced from s on: run i stays when it starts
        // left of the span (it is cut at x0).
        let s = if runs[i].x < x0 { i + 1 } else { i };
        let before = match s {
            0 => None,
            _ => Some(runs[s - 1].color),
        };
        let mut new = [ColorRun::new(x0, color); 2];
        let mut m = 0;
        if before != Some(color) {
            new[0] = ColorRun::new(x0, color);
            m = 1;
        }
        if x1 < self.width && after.color != color {
            new[m] = ColorRun::new(x1, after.color);
            m += 1;
        }
        let total = len - (k - s) + m;
        self.peak = self.peak.max(total);
        self.moved = self.moved.saturating_add((len - k) as u32);
        if total > self.runs.len() {
            self.overflowed = true;
            return;
        }
        // Run k (when there is one) differs from what now precedes it:
        // from `after`'s colour, which it followed, and when no run was
        // put at x1, that colour is the span's.
        // The runs right of the span move only when the count changes; a
        // move of a few runs is a loop (a call to `memmove` costs more
        // than it moves).
        if s + m != k {
            move_runs(self.runs, k..len, s + m);
        }
        for (slot, run) in self.runs[s..s + m].iter_mut().zip(new) {
            *slot = run;
        }
        self.len = total;
    }
}

/// Moves `runs[from]` to start at `to` (`to + from.len()` within
/// `runs`), as `copy_within` does: element by element for a few, one
/// `memmove` for more.
#[inline(always)]
fn move_runs<T: Copy>(runs: &mut [T], from: core::ops::Range<usize>, to: usize) {
    const FEW: usize = 8;
    let n = from.end - from.start;
    if n > FEW {
        runs.copy_within(from, to);
    } else if to < from.start {
        for i in 0..n {
            runs[to + i] = runs[from.start + i];
        }
    } else {
        for i in (0..n).rev() {
            runs[to + i] = runs[from.start + i];
        }
    }
}

impl<C: PixelColor> SpanTarget for RowRuns<'_, C> {
    type Color = C;
    type Error = Infallible;
    /// A batch of runs is appended in one pass.
    const RUNS_IN_BATCHES: bool = true;

    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }

    #[inline]
    fn fill_span(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let x1 = span.x1.min(self.width);
        if span.y == self.y && span.x0 < x1 && self.len > 0 {
            self.insert(span.x0, x1, color);
        }
        Ok(())
    }

    /// As [`fill_span`](SpanTarget::fill_span), with the same checks (a
    /// span outside the row is dropped); a span that starts in the row's
    /// last run, as the 3D layer's runs do, is put at the row's end
    /// without a search.
    #[inline]
    fn fill_span_inside(&mut self, span: Span, color: C) -> Result<(), Infallible> {
        let x1 = span.x1.min(self.width);
        if span.y == self.y && span.x0 < x1 {
            match self.runs[..self.len].last() {
                Some(r) if r.x <= span.x0 => self.append(span.x0, x1, color),
                Some(_) => self.insert(span.x0, x1, color),
                None => {}
            }
        }
        Ok(())
    }

    /// As [`fill_span_inside`](SpanTarget::fill_span_inside) of each run
    /// in turn, the same row, runs, [`peak`](RowRuns::peak) and
    /// overflow: where the runs start in the row's last run (the 3D
    /// layer's, left to right) they are appended in one pass, with no
    /// run cut and put back between two of them.
    fn fill_runs_inside(&mut self, y: u16, x0: u16, runs: &[RowRun<C>]) -> Result<(), Infallible> {
        if y == self.y && !self.append_all(x0, runs) {
            let mut x = x0;
            for r in runs {
                self.fill_span_inside(Span { y, x0: x, x1: r.x1 }, r.color)?;
                x = r.x1;
            }
        }
        Ok(())
    }

    /// As [`fill_span`](SpanTarget::fill_span) (the 2D spans, in
    /// painter's order, in any place).
    #[inline]
    fn fill_row_inside(
        &mut self,
        row: usize,
        x0: u16,
        x1: u16,
        color: C,
    ) -> Result<(), Infallible> {
        let y = u16::try_from(row).unwrap_or(u16::MAX);
        self.fill_span(Span { y, x0, x1 }, color)
    }

    /// The row is `color`: one run.
    fn clear(&mut self, color: C) -> Result<(), Infallible> {
        if self.len > 0 {
            self.runs[0] = ColorRun::new(0, color);
            self.len = 1;
        }
        Ok(())
    }

    fn fill_rect(&mut self, span: Span, height: u16, color: C) -> Result<(), Infallible> {
        if (span.y..span.y.saturating_add(height)).contains(&self.y) {
            self.fill_span(Span { y: self.y, ..span }, color)?;
        }
        Ok(())
    }
}

/// What the band path's stages need of what they draw into: a
/// [`SpanTarget`] of the frame's size that holds some rows, and can be
/// filled with a background. A [`Band`](super::band::Band) of pixels and
/// a [`RowRuns`] are both.
pub(crate) trait Rows: SpanTarget<Error = Infallible> {
    /// The first row held.
    fn first(&self) -> u16;
    /// Rows held.
    fn count(&self) -> u16;
    /// One past the last row held.
    fn end(&self) -> u16 {
        self.first() + self.count()
    }
    /// Every pixel held is `color`, when there is one.
    fn background(&mut self, color: Option<Self::Color>) {
        if let Some(c) = color {
            match self.clear(c) {
                Ok(()) => {}
                Err(e) => match e {},
            }
        }
    }
}

impl<C: PixelColor> Rows for super::band::Band<'_, C> {
    fn first(&self) -> u16 {
        self.y()
    }
    fn count(&self) -> u16 {
        self.rows()
    }
}

impl<C: PixelColor> Rows for RowRuns<'_, C> {
    fn first(&self) -> u16 {
        self.y
    }
    fn count(&self) -> u16 {
        1
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use embedded_graphics_core::pixelcolor::Gray8;
    use std::vec::Vec;

    fn g(v: u8) -> Gray8 {
        Gray8::new(v)
    }

    /// The row's invariants hold and it decodes to `want`.
    fn check(row: &RowRuns<'_, Gray8>, want: &[Gray8]) {
        let s = row.as_slice();
        assert_eq!(s[0].x, 0);
        for w in s.windows(2) {
            assert!(w[0].x < w[1].x, "{s:?}");
            assert_ne!(w[0].color, w[1].color, "{s:?}");
        }
        assert!(s.last().unwrap().x < row.width());
        let mut px = [g(0); 64];
        assert_eq!(row.decode(&mut px), want.len());
        assert_eq!(&px[..want.len()], want);
    }

    #[test]
    fn spans_overwrite_split_and_merge() {
        let mut buf = [ColorRun::new(0, g(0)); 8];
        let mut row = RowRuns::new(&mut buf);
        row.start(3, (10, 5), g(1));
        let mut px = [g(1); 10];
        check(&row, &px);
        for (x0, x1, c) in [
            (2, 5, 7),
            (4, 8, 9),
            (0, 1, 7),
            (1, 2, 7),
            (5, 6, 7),
            (2, 6, 9),
            (0, 10, 3),
            (9, 10, 4),
        ] {
            row.fill_span(Span { y: 3, x0, x1 }, g(c)).unwrap();
            px[usize::from(x0)..usize::from(x1)].fill(g(c));
            check(&row, &px);
        }
        // Other rows are dropped.
        row.fill_span(Span { y: 2, x0: 0, x1: 4 }, g(5)).unwrap();
        check(&row, &px);
        row.clear(g(6)).unwrap();
        assert_eq!(row.as_slice(), [ColorRun::new(0, g(6))]);
    }

    #[test]
    fn every_span_on_every_row_of_three_colours() {
        // Every sequence of two spans over every starting row of width 5
        // made of runs of colours 0..3.
        let w = 5u16;
        let spans: Vec<(u16, u16)> = (0..w)
            .flat_map(|a| (a + 1..=w).map(move |b| (a, b)))
            .collect();
        for base in 0..3u32.pow(5) {
            let start: Vec<Gray8> = (0..5).map(|i| g((base / 3u32.pow(i) % 3) as u8)).collect();
            for &(a, b) in &spans {
                for (c, how) in (0..3u8).flat_map(|c| (0..3).map(move |h| (c, h))) {
                    // A capacity of the width is enough.
                    let mut buf = [ColorRun::new(0, g(0)); 5];
                    let mut row = RowRuns::new(&mut buf);
                    row.start(0, (w, 1), start[0]);
                    let mut px = start.clone();
                    for x in 1..w {
                        row.fill_span(
                            Span {
                                y: 0,
                                x0: x,
                                x1: x + 1,
                            },
                            start[usize::from(x)],
                        )
                        .unwrap();
                    }
                    check(&row, &px);
                    // The three ways in: a span anywhere, a span inside
                    // (put at the end without a search when it starts in
                    // the last run), a 2D row.
                    let span = Span { y: 0, x0: a, x1: b };
                    match how {
                        0 => row.fill_span(span, g(c)),
                        1 => row.fill_span_inside(span, g(c)),
                        _ => row.fill_row_inside(0, a, b, g(c)),
                    }
                    .unwrap();
                    px[usize::from(a)..usize::from(b)].fill(g(c));
                    check(&row, &px);
                    assert!(!row.overflowed());
                    assert!(row.peak() <= 5);
                }
            }
        }
    }

    #[test]
    fn a_span_at_the_end_is_put_as_one_anywhere() {
        // Rows of 0 to 3 runs of width 8, each span starting in the last
        // run, at every capacity: inside (no search) and anywhere (the
        // search) leave the same runs, peak and overflow, and a span that
        // does not fit leaves the row as it was.
        let w = 8u16;
        for cuts in 0..3u16 {
            for x0 in 0..w {
                for x1 in x0 + 1..=w {
                    for c in 0..3u8 {
                        for cap in 1..=5usize {
                            let mut rows = [[ColorRun::new(0, g(0)); 5]; 2];
                            let [a, b] = &mut rows;
                            let mut out: [(Vec<ColorRun<Gray8>>, usize, bool); 2] =
                                Default::default();
                            for (k, buf) in [a, b].into_iter().enumerate() {
                                let mut row = RowRuns::new(&mut buf[..cap]);
                                row.start(0, (w, 1), g(0));
                                for i in 1..=cuts.min(x0) {
                                    let s = Span { y: 0, x0: i, x1: w };
                                    row.fill_span(s, g((i % 3) as u8)).unwrap();
                                }
                                let before = row.as_slice().to_vec();
                                let full = row.overflowed();
                                let span = Span { y: 0, x0, x1 };
                                match k {
                                    0 => row.fill_span(span, g(c)),
                                    _ => row.fill_span_inside(span, g(c)),
                                }
                                .unwrap();
                                if row.overflowed() && !full {
                                    assert_eq!(row.as_slice(), before);
                                }
                                out[k] = (row.as_slice().to_vec(), row.peak(), row.overflowed());
                            }
                            assert_eq!(out[0], out[1], "{cuts} {x0}..{x1} {c} {cap}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_batch_is_its_runs_one_by_one() {
        // Batches of 0 to 5 runs over rows of 1 to 3 runs of width 12, at
        // every capacity: in order, empty, going back, past the width, on
        // another row. The batch leaves the runs, peak, overflow and
        // moves that its runs' spans leave one by one.
        let w = 12u16;
        let mut next = crate::rng::xorshift32(0x1234_5679);
        let mut bulk = 0;
        for _ in 0..200_000 {
            let r = next();
            let cuts = (r % 3) as u16;
            let n = (r >> 2) as usize % 6;
            let cap = 1 + (r >> 5) as usize % 9;
            let y = u16::from((r >> 9).is_multiple_of(8));
            let mut x0 = (r >> 12) as u16 % w;
            let mut batch = [RowRun { x1: 0, color: g(0) }; 5];
            let mut x = x0;
            for b in batch.iter_mut().take(n) {
                let r = next();
                let x1 = match r % 8 {
                    0 => x,
                    1 => x.saturating_sub(1 + (r >> 3) as u16 % 3),
                    2 => w + (r >> 3) as u16 % 3,
                    _ => (x + 1 + (r >> 3) as u16 % 4).min(w),
                };
                *b = RowRun {
                    x1,
                    color: g((r >> 8) as u8 % 3),
                };
                x = x1;
            }
            if r >> 31 == 0 {
                x0 = x0.min(cuts * 2);
            }
            let mut out: [(Vec<ColorRun<Gray8>>, usize, bool, u32); 2] = Default::default();
            let mut bufs = [[ColorRun::new(0, g(0)); 10]; 2];
            for (k, buf) in bufs.iter_mut().enumerate() {
                let mut row = RowRuns::new(&mut buf[..cap]);
                row.start(0, (w, 1), g(0));
                for i in 1..=cuts {
                    let s = Span {
                        y: 0,
                        x0: i * 2,
                        x1: w,
                    };
                    row.fill_span(s, g((i % 3) as u8)).unwrap();
                }
                // The one-pass append, where it takes the batch, or the
                // trait's call; the spans one by one.
                match k {
                    0 if y == 0 && row.append_all(x0, &batch[..n]) => bulk += 1,
                    0 => row.fill_runs_inside(y, x0, &batch[..n]).unwrap(),
                    _ => {
                        let mut x = x0;
                        for b in &batch[..n] {
                            let s = Span { y, x0: x, x1: b.x1 };
                            row.fill_span_inside(s, b.color).unwrap();
                            x = b.x1;
                        }
                    }
                }
                out[k] = (
                    row.as_slice().to_vec(),
                    row.peak(),
                    row.overflowed(),
                    row.moved(),
                );
            }
            assert_eq!(out[0], out[1], "{cuts} {x0} {:?} {cap} {y}", &batch[..n]);
        }
        // The one-pass append took a good share of them.
        assert!(bulk > 40_000, "{bulk}");
    }

    #[test]
    fn too_few_runs_is_reported_not_a_panic() {
        let mut buf = [ColorRun::new(0, g(0)); 2];
        let mut row = RowRuns::new(&mut buf);
        row.start(0, (10, 1), g(0));
        row.fill_span(Span { y: 0, x0: 2, x1: 4 }, g(1)).unwrap();
        assert!(row.overflowed());
        assert_eq!(row.as_slice(), [ColorRun::new(0, g(0))]);
        // A span at the end fits.
        row.start(0, (10, 1), g(0));
        row.fill_span(
            Span {
                y: 0,
                x0: 4,
                x1: 10,
            },
            g(1),
        )
        .unwrap();
        assert!(!row.overflowed());
        let mut none: [ColorRun<Gray8>; 0] = [];
        let mut row = RowRuns::new(&mut none);
        row.start(0, (10, 1), g(0));
        assert!(row.overflowed());
        row.fill_span(
            Span {
                y: 0,
                x0: 4,
                x1: 10,
            },
            g(1),
        )
        .unwrap();
        assert_eq!(row.decode(&mut [g(0); 10]), 0);
    }
}
