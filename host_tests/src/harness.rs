//! Running polygons through the library's real path: a display list built
//! with [`Writer`], checked, and executed by [`Controller::render`] into a
//! target that counts every pixel write.

use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::BinaryColor;
use scanvert::controller::{Controller, RenderError, RenderStats};
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::port::{Span, SpanTarget};
use scanvert::raster::edge::{Edge, Stepper};
use scanvert::raster::scan::Rasterizer;
use std::cell::Cell;
use testkit::reference::{Coverage, Window};

/// Edge slots the harness gives the rasteriser unless told otherwise.
pub const DEFAULT_CAPACITY: usize = 64;

/// A [`SpanTarget`] that counts how often each pixel is written and keeps
/// every span. It checks the port's guarantee on each span (non-empty,
/// inside the target) and panics when it is broken.
#[derive(Debug, Clone)]
pub struct CountingTarget {
    width: u16,
    height: u16,
    writes: Vec<u32>,
    /// Every span received, in order.
    pub spans: Vec<Span>,
}

impl CountingTarget {
    /// A `width × height` target with no write yet.
    pub fn new(width: u16, height: u16) -> Self {
        CountingTarget {
            width,
            height,
            writes: vec![0; width as usize * height as usize],
            spans: Vec::new(),
        }
    }

    /// Times pixel `(i, j)` was written.
    pub fn writes(&self, i: u32, j: u32) -> u32 {
        self.writes[j as usize * self.width as usize + i as usize]
    }

    /// The pixels written at least once.
    pub fn coverage(&self) -> Coverage {
        Coverage::from_fn(self.width.into(), self.height.into(), |i, j| {
            self.writes(i, j) > 0
        })
    }

    /// Pixels written more than once, as `(i, j, times)`.
    pub fn overdrawn(&self) -> Vec<(u32, u32, u32)> {
        let mut v = Vec::new();
        for j in 0..self.height as u32 {
            for i in 0..self.width as u32 {
                if self.writes(i, j) > 1 {
                    v.push((i, j, self.writes(i, j)));
                }
            }
        }
        v
    }

    /// Distinct rows that received a span.
    pub fn rows_touched(&self) -> usize {
        let mut rows: Vec<u16> = self.spans.iter().map(|s| s.y).collect();
        rows.sort_unstable();
        rows.dedup();
        rows.len()
    }
}

impl SpanTarget for CountingTarget {
    type Color = BinaryColor;
    type Error = Infallible;

    fn size(&self) -> (u16, u16) {
        (self.width, self.height)
    }

    fn fill_span(&mut self, span: Span, _color: BinaryColor) -> Result<(), Infallible> {
        assert!(
            span.x0 < span.x1 && span.x1 <= self.width && span.y < self.height,
            "span {span:?} breaks the port guarantee for a {}x{} target",
            self.width,
            self.height
        );
        let base = span.y as usize * self.width as usize;
        for w in &mut self.writes[base + span.x0 as usize..base + span.x1 as usize] {
            *w += 1;
        }
        self.spans.push(span);
        Ok(())
    }
}

/// One `poly` of a scene, with the clip registers loaded before it
/// (`None`: leave them as they are).
#[derive(Debug, Clone)]
pub struct Draw {
    /// A `clip` command to emit first.
    pub clip: Option<Window>,
    /// The vertices in units of 1/16 px; each must fit in `i16`.
    pub poly: Vec<(i32, i32)>,
}

/// A vertex from units of 1/16 px; panics when it is outside Q12.4.
pub fn vertex((x, y): (i32, i32)) -> Vertex {
    let fit = |v: i32| i16::try_from(v).unwrap_or_else(|_| panic!("{v} is outside Q12.4"));
    Vertex::from_bits(fit(x), fit(y))
}

/// The display list for `draws` on a `width × height` frame, as the
/// library's [`Writer`] encodes it.
pub fn build_list(draws: &[Draw], width: u16, height: u16) -> Vec<u8> {
    let size = 16
        + draws
            .iter()
            .map(|d| 9 + 3 + 4 * d.poly.len())
            .sum::<usize>();
    let mut buf = vec![0u8; size];
    let mut w = Writer::new(&mut buf, width, height).expect("frame size");
    for d in draws {
        if let Some(c) = d.clip {
            w.clip(c.to_clip_window())
                .expect("buffer sized for the list");
        }
        w.poly(d.poly.iter().copied().map(vertex))
            .expect("3..=65535 vertices");
    }
    w.finish().to_vec()
}

/// Renders `draws` through [`Controller::render`] with `capacity` edge
/// slots into a fresh [`CountingTarget`].
pub fn render_counting(
    draws: &[Draw],
    width: u16,
    height: u16,
    capacity: usize,
) -> (CountingTarget, Result<RenderStats, RenderError<Infallible>>) {
    let bytes = build_list(draws, width, height);
    let list = DisplayList::new_checked(&bytes).expect("Writer output is a valid list");
    let mut edges = vec![Edge::EMPTY; capacity];
    let mut target = CountingTarget::new(width, height);
    let result = Controller::new(Rasterizer::new(&mut edges)).render(&list, &mut target);
    (target, result)
}

/// One polygon under one clip window, rendered by the library into a
/// counting target. Panics if the render fails or a pixel is written twice
/// (one polygon's spans never overlap).
pub fn render_poly(poly: &[(i32, i32)], window: Window, width: u16, height: u16) -> CountingTarget {
    let draw = Draw {
        clip: Some(window),
        poly: poly.to_vec(),
    };
    let (target, result) = render_counting(&[draw], width, height, DEFAULT_CAPACITY);
    let stats = result.expect("render");
    let over = target.overdrawn();
    assert!(over.is_empty(), "one polygon wrote pixels twice: {over:?}");
    let written: u64 = target.spans.iter().map(|s| s.len() as u64).sum();
    assert_eq!(
        stats.pixels, written,
        "RenderStats::pixels disagrees with the spans"
    );
    assert_eq!(
        stats.spans as usize,
        target.spans.len(),
        "RenderStats::spans"
    );
    target
}

/// One polygon under one clip window, rendered by the library into a
/// `FrameBuffer<BinaryColor>` (the real memory port).
pub fn render_framebuffer(
    poly: &[(i32, i32)],
    window: Window,
    width: u16,
    height: u16,
) -> Coverage {
    let draw = Draw {
        clip: Some(window),
        poly: poly.to_vec(),
    };
    let bytes = build_list(&[draw], width, height);
    let list = DisplayList::new_checked(&bytes).expect("valid list");
    let mut edges = [Edge::EMPTY; DEFAULT_CAPACITY];
    let mut pixels = vec![BinaryColor::Off; width as usize * height as usize];
    let mut fb = FrameBuffer::new(&mut pixels, width, height).expect("frame size");
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut fb)
        .expect("render");
    Coverage::from_fn(width.into(), height.into(), |i, j| {
        fb.pixel(i as u16, j as u16) == Some(BinaryColor::On)
    })
}

/// Panics with the differing pixels unless `got` equals `want`.
#[track_caller]
pub fn assert_same(got: &Coverage, want: &Coverage, what: &dyn core::fmt::Debug) {
    if got != want {
        let d = got.diff(want);
        panic!(
            "{} pixels differ from the reference for {what:?}; first (i, j, library's value): {:?}\nlibrary: {got:?}reference: {want:?}",
            d.len(),
            &d[..d.len().min(12)]
        );
    }
}

thread_local! {
    static STEPS: Cell<u64> = const { Cell::new(0) };
    static SETUPS: Cell<u64> = const { Cell::new(0) };
}

/// The exact [`Edge`] stepper, counting its set-ups and row steps (per
/// thread), to show how much work a fill does without timing it.
#[derive(Clone, Copy, Debug)]
pub struct CountingEdge(Edge);

impl CountingEdge {
    /// An unused slot.
    pub const EMPTY: CountingEdge = CountingEdge(Edge::EMPTY);

    /// `(edges set up, row steps)` on this thread since the last reset.
    pub fn counts() -> (u64, u64) {
        (SETUPS.with(Cell::get), STEPS.with(Cell::get))
    }

    /// Zeroes this thread's counters.
    pub fn reset() {
        SETUPS.with(|c| c.set(0));
        STEPS.with(|c| c.set(0));
    }
}

impl Stepper for CountingEdge {
    fn new(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        let e = Edge::new(a, b, rows)?;
        SETUPS.with(|c| c.set(c.get() + 1));
        Some(CountingEdge(e))
    }
    fn top(&self) -> i32 {
        self.0.top()
    }
    fn end(&self) -> i32 {
        self.0.end()
    }
    fn load_pixel(&mut self) {
        self.0.load_pixel()
    }
    fn pixel(&self) -> i32 {
        self.0.pixel()
    }
    fn step(&mut self) {
        STEPS.with(|c| c.set(c.get() + 1));
        self.0.step()
    }
    fn new_wound(a: Vertex, b: Vertex, rows: (i32, i32)) -> Option<Self> {
        let e = Edge::new_wound(a, b, rows)?;
        SETUPS.with(|c| c.set(c.get() + 1));
        Some(CountingEdge(e))
    }
    fn load_wound(&mut self) {
        self.0.load_wound()
    }
}
