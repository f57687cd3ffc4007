//! Everything that is timed: scanvert's paths, its faster options, the
//! peers, and the memory-bandwidth limit, each behind one small trait.

use crate::heap;
use core::convert::Infallible;
use core::mem::size_of;
use embedded_graphics::{
    prelude::*,
    primitives::{PrimitiveStyle, Rectangle, Styled, Triangle},
};
use scanvert::{
    controller::Controller,
    display_list::{DisplayList, Writer},
    fixed::Vertex,
    pixelcolor::{Rgb565, Rgb888, RgbColor},
    port::framebuffer::FrameBuffer,
    port::{Counts, Span, SpanTarget},
    raster::clip::ClipRect,
    raster::dda::{self, Dda16, Dda7},
    raster::edge::{Edge, Stepper},
    raster::scan::Rasterizer,
};
use testkit::workloads::{Kind, Workload};

/// The colour everything draws in (on black or transparent).
const INK: Rgb565 = Rgb565::RED;

/// One contender on one workload.
pub trait Contender {
    /// Name in the report.
    fn name(&self) -> &'static str;
    /// One pass of the workload: every polygon once, or one clear.
    fn pass(&mut self);
    /// Draws polygon `i` alone (into a frame that is blank around it).
    fn draw_one(&mut self, i: usize);
    /// Whether [`Contender::draw_one`] covered pixel `(x, y)`.
    fn covered(&self, x: i32, y: i32) -> bool;
    /// Blanks the box `(x0, y0, x1, y1)` again.
    fn reset(&mut self, b: (i32, i32, i32, i32));
    /// `false` for the bandwidth limit, which draws no polygon.
    fn has_coverage(&self) -> bool {
        true
    }
    /// Working state needed, in bytes, and how it was counted.
    fn memory(&self) -> (usize, String);
}

/// Row-major pixel index.
fn at(w: u16, x: i32, y: i32) -> usize {
    y as usize * w as usize + x as usize
}

/// scanvert's `Rasterizer::fill` into `FrameBuffer<Rgb565>`, with stepper
/// `S`, vertices snapped to
/// `2^-SNAP` px first (4: not snapped).
pub struct ScanvertFill<S: Stepper, const SNAP: u32> {
    name: &'static str,
    kind: Kind,
    polys: Vec<Vec<Vertex>>,
    pixels: Vec<Rgb565>,
    w: u16,
    h: u16,
    edges: Vec<S>,
}

impl<S: Stepper, const SNAP: u32> ScanvertFill<S, SNAP> {
    /// The contender for `wl`, with `empty` filling the edge slots.
    pub fn new(name: &'static str, wl: &Workload, empty: S) -> Self {
        ScanvertFill {
            name,
            kind: wl.kind,
            polys: wl.polys.clone(),
            pixels: vec![Rgb565::BLACK; wl.width as usize * wl.height as usize],
            w: wl.width,
            h: wl.height,
            edges: vec![empty; wl.max_vertices().max(1)],
        }
    }

    #[inline]
    fn fill<T: SpanTarget<Color = Rgb565> + ?Sized>(
        r: &mut Rasterizer<'_, S>,
        p: &[Vertex],
        clip: &ClipRect,
        fb: &mut T,
    ) {
        let res = if SNAP >= 4 {
            r.fill(p.iter().copied(), clip, INK, fb)
        } else {
            r.fill(p.iter().map(|&v| dda::snap(v, SNAP)), clip, INK, fb)
        };
        debug_assert!(res.is_ok());
        let _ = res;
    }
}

impl<S: Stepper, const SNAP: u32> Contender for ScanvertFill<S, SNAP> {
    fn name(&self) -> &'static str {
        self.name
    }
    fn pass(&mut self) {
        let clip = ClipRect::full(self.w, self.h);
        let mut r = Rasterizer::new(&mut self.edges);
        let Some(mut fb) = FrameBuffer::new(&mut self.pixels, self.w, self.h) else {
            return;
        };
        if self.kind == Kind::Clear {
            let Ok(()) = SpanTarget::clear(&mut fb, INK);
            return;
        }
        for p in &self.polys {
            Self::fill(&mut r, p, &clip, &mut fb);
        }
    }
    fn draw_one(&mut self, i: usize) {
        let clip = ClipRect::full(self.w, self.h);
        let mut r = Rasterizer::new(&mut self.edges);
        let Some(mut fb) = FrameBuffer::new(&mut self.pixels, self.w, self.h) else {
            return;
        };
        Self::fill(&mut r, &self.polys[i], &clip, &mut fb);
    }
    fn covered(&self, x: i32, y: i32) -> bool {
        self.pixels[at(self.w, x, y)] != Rgb565::BLACK
    }
    fn reset(&mut self, b: (i32, i32, i32, i32)) {
        for y in b.1..b.3 {
            self.pixels[at(self.w, b.0, y)..at(self.w, b.2, y)].fill(Rgb565::BLACK);
        }
    }
    fn memory(&self) -> (usize, String) {
        if self.kind == Kind::Clear {
            return (
                size_of::<FrameBuffer<'_>>(),
                "the FrameBuffer struct".into(),
            );
        }
        let slots = self.polys.iter().map(Vec::len).max().unwrap_or(0);
        let structs = size_of::<Rasterizer<'_, S>>() + size_of::<ClipRect>() + size_of::<Counts>();
        (
            slots * size_of::<S>() + structs,
            format!(
                "{slots} edge slots × {} B + {structs} B structs",
                size_of::<S>()
            ),
        )
    }
}

/// scanvert's `Controller::render` of a display list holding the whole
/// pass (validated with `DisplayList::new_checked` every pass, as a list
/// freshly written by a host would be).
pub struct ScanvertList {
    kind: Kind,
    list: Vec<u8>,
    polys: Vec<Vec<Vertex>>,
    pixels: Vec<Rgb565>,
    w: u16,
    h: u16,
    edges: Vec<Edge>,
}

/// A display list: `color`, then the polygons (or a `clear`).
fn list_bytes(w: u16, h: u16, kind: Kind, polys: &[Vec<Vertex>]) -> Vec<u8> {
    let need = 64 + polys.iter().map(|p| 3 + 4 * p.len()).sum::<usize>();
    let mut buf = vec![0u8; need];
    let Ok(mut wr) = Writer::new(&mut buf, w, h) else {
        return Vec::new();
    };
    let ink = Rgb888::new(0xff, 0, 0);
    let ok = match kind {
        Kind::Clear => wr.clear(ink).is_ok(),
        Kind::Polygons => {
            wr.color(ink).is_ok() && polys.iter().all(|p| wr.poly(p.iter().copied()).is_ok())
        }
    };
    assert!(ok, "display list does not fit");
    wr.finish().to_vec()
}

impl ScanvertList {
    /// The contender for `wl`.
    pub fn new(wl: &Workload) -> Self {
        ScanvertList {
            kind: wl.kind,
            list: list_bytes(wl.width, wl.height, wl.kind, &wl.polys),
            polys: wl.polys.clone(),
            pixels: vec![Rgb565::BLACK; wl.width as usize * wl.height as usize],
            w: wl.width,
            h: wl.height,
            edges: vec![Edge::EMPTY; wl.max_vertices().max(3)],
        }
    }

    fn render(bytes: &[u8], edges: &mut [Edge], fb: &mut FrameBuffer<'_>) {
        if let Ok(list) = DisplayList::new_checked(bytes) {
            let res = Controller::new(Rasterizer::new(edges)).render(&list, fb);
            debug_assert!(res.is_ok());
        }
    }
}

impl Contender for ScanvertList {
    fn name(&self) -> &'static str {
        match self.kind {
            Kind::Clear => "scanvert, `clear` in a display list",
            Kind::Polygons => "scanvert exact, display list (`Controller::render`)",
        }
    }
    fn pass(&mut self) {
        if let Some(mut fb) = FrameBuffer::new(&mut self.pixels, self.w, self.h) {
            Self::render(&self.list, &mut self.edges, &mut fb);
        }
    }
    fn draw_one(&mut self, i: usize) {
        let one = list_bytes(self.w, self.h, self.kind, &self.polys[i..=i]);
        if let Some(mut fb) = FrameBuffer::new(&mut self.pixels, self.w, self.h) {
            Self::render(&one, &mut self.edges, &mut fb);
        }
    }
    fn covered(&self, x: i32, y: i32) -> bool {
        self.pixels[at(self.w, x, y)] != Rgb565::BLACK
    }
    fn reset(&mut self, b: (i32, i32, i32, i32)) {
        for y in b.1..b.3 {
            self.pixels[at(self.w, b.0, y)..at(self.w, b.2, y)].fill(Rgb565::BLACK);
        }
    }
    fn memory(&self) -> (usize, String) {
        let slots = self.polys.iter().map(Vec::len).max().unwrap_or(0);
        let structs = size_of::<Controller<'_>>() + size_of::<DisplayList<'_>>();
        (
            slots * size_of::<Edge>() + structs,
            format!(
                "{slots} edge slots × {} B + {structs} B structs; the list ({} B) is read in place",
                size_of::<Edge>(),
                self.list.len()
            ),
        )
    }
}

/// One edge of [`PlainFill`]: x at the current row's centre and its step
/// a row, both 16.16 px, and the rows it spans.
#[derive(Clone, Copy, Debug)]
struct PlainEdge {
    x: i32,
    dx: i32,
    first: i32,
    end: i32,
}

/// A plain 16.16 scan-line filler, written the textbook way as a peer
/// for scanvert's exact path: an edge table with x and dx in 16.16 (one
/// division an edge), an active edge list stepped by one addition a
/// row, sorted by x where an edge joins or leaves, filled in pairs
/// (even-odd),
/// spans by the pixel-centre rule as far as 16.16 resolves it, one
/// `slice::fill` a span into RGB565. No exactness work.
pub struct PlainFill {
    polys: Vec<Vec<Vertex>>,
    pixels: Vec<Rgb565>,
    w: u16,
    h: u16,
    edges: Vec<PlainEdge>,
    active: Vec<PlainEdge>,
}

impl PlainFill {
    /// The contender for `wl`.
    pub fn new(wl: &Workload) -> Self {
        let n = wl.max_vertices().max(1);
        PlainFill {
            polys: wl.polys.clone(),
            pixels: vec![Rgb565::BLACK; wl.width as usize * wl.height as usize],
            w: wl.width,
            h: wl.height,
            edges: Vec::with_capacity(n),
            active: Vec::with_capacity(n),
        }
    }

    /// Fills `p` (vertices in 1/16 px): row `j` samples `y = j + ½`,
    /// pixel `i` of a span is in when `i + ½` lies at or right of the left
    /// crossing and left of the right one.
    fn fill(&mut self, p: &[Vertex]) {
        let (w, h) = (self.w as i32, self.h as i32);
        self.edges.clear();
        for k in 0..p.len() {
            let (a, b) = (p[k], p[(k + 1) % p.len()]);
            let (a, b) = if a.y.units() <= b.y.units() {
                (a, b)
            } else {
                (b, a)
            };
            let (x0, y0, x1, y1) = (a.x.units(), a.y.units(), b.x.units(), b.y.units());
            // First row whose centre is at or below y0, first at or below y1.
            let first = (y0 + 7).div_euclid(16);
            let end = (y1 + 7).div_euclid(16);
            if first >= end {
                continue;
            }
            let dx = (((x1 - x0) as i64) << 16) / (y1 - y0) as i64;
            let yc = 16 * first + 8;
            let x = ((x0 as i64) << 12) + (((yc - y0) as i64 * dx) >> 4);
            self.edges.push(PlainEdge {
                x: x as i32,
                dx: dx as i32,
                first,
                end,
            });
        }
        self.edges.sort_unstable_by_key(|e| e.first);
        self.active.clear();
        let mut next = 0;
        let Some(mut y) = self.edges.first().map(|e| e.first) else {
            return;
        };
        while next < self.edges.len() || !self.active.is_empty() {
            if self.active.is_empty() {
                y = y.max(self.edges[next].first);
            }
            // The active list changes only where an edge starts or ends:
            // joined, retired and sorted by x there, then stepped row by
            // row to the next such event (the polygons are simple, so the
            // order holds between events).
            while next < self.edges.len() && self.edges[next].first <= y {
                self.active.push(self.edges[next]);
                next += 1;
            }
            self.active.retain(|e| e.end > y);
            if self.active.is_empty() {
                continue;
            }
            // Two edges from one vertex cross a row at one x: the one
            // that goes left is left below it.
            self.active.sort_unstable_by_key(|e| (e.x, e.dx));
            let mut stop = self.edges.get(next).map_or(i32::MAX, |e| e.first);
            for e in &self.active {
                stop = stop.min(e.end);
            }
            while y < stop {
                let row = (0..h).contains(&y).then_some(y as usize * w as usize);
                if let Some(row) = row.and_then(|r| self.pixels.get_mut(r..)) {
                    for pair in self.active.chunks_exact(2) {
                        let x0 = ((pair[0].x - 0x8000 + 0xffff) >> 16).clamp(0, w);
                        let x1 = ((pair[1].x - 0x8000 + 0xffff) >> 16).clamp(0, w);
                        if let Some(span) = row.get_mut(x0 as usize..x1 as usize) {
                            span.fill(INK);
                        }
                    }
                }
                for e in &mut self.active {
                    e.x = e.x.wrapping_add(e.dx);
                }
                y += 1;
            }
        }
    }
}

impl Contender for PlainFill {
    fn name(&self) -> &'static str {
        "plain 16.16 scan-line filler (bench)"
    }
    fn pass(&mut self) {
        let polys = core::mem::take(&mut self.polys);
        for p in &polys {
            self.fill(p);
        }
        self.polys = polys;
    }
    fn draw_one(&mut self, i: usize) {
        let p = core::mem::take(&mut self.polys[i]);
        self.fill(&p);
        self.polys[i] = p;
    }
    fn covered(&self, x: i32, y: i32) -> bool {
        self.pixels[at(self.w, x, y)] != Rgb565::BLACK
    }
    fn reset(&mut self, b: (i32, i32, i32, i32)) {
        for y in b.1..b.3 {
            self.pixels[at(self.w, b.0, y)..at(self.w, b.2, y)].fill(Rgb565::BLACK);
        }
    }
    fn memory(&self) -> (usize, String) {
        let slots = self.polys.iter().map(Vec::len).max().unwrap_or(0);
        let one = size_of::<PlainEdge>();
        (
            2 * slots * one,
            format!("{slots} edge slots × {one} B, and as many active"),
        )
    }
}

/// tiny-skia's `fill_path`, anti-aliasing off, even-odd, into its own
/// RGBA8888 `Pixmap` (4 bytes a pixel, twice RGB565's). Paths are built
/// before timing, one per polygon.
pub struct TinySkia {
    kind: Kind,
    pixmap: tiny_skia::Pixmap,
    paths: Vec<Option<tiny_skia::Path>>,
    paint: tiny_skia::Paint<'static>,
    heap_peak: usize,
}

impl TinySkia {
    /// The contender for `wl`.
    pub fn new(wl: &Workload) -> Self {
        let paths = wl
            .polys
            .iter()
            .map(|p| {
                let mut b = tiny_skia::PathBuilder::new();
                let f = |u: i32| u as f32 / 16.0;
                b.move_to(f(p[0].x.units()), f(p[0].y.units()));
                for v in &p[1..] {
                    b.line_to(f(v.x.units()), f(v.y.units()));
                }
                b.close();
                b.finish()
            })
            .collect();
        let mut paint = tiny_skia::Paint::default();
        paint.set_color_rgba8(0xff, 0, 0, 0xff);
        paint.anti_alias = false;
        TinySkia {
            kind: wl.kind,
            pixmap: tiny_skia::Pixmap::new(wl.width as u32, wl.height as u32)
                .expect("frame size is valid"),
            paths,
            paint,
            heap_peak: 0,
        }
    }

    fn fill(&mut self, i: usize) {
        if let Some(p) = &self.paths[i] {
            self.pixmap.fill_path(
                p,
                &self.paint,
                tiny_skia::FillRule::EvenOdd,
                tiny_skia::Transform::identity(),
                None,
            );
        }
    }
}

impl Contender for TinySkia {
    fn name(&self) -> &'static str {
        match self.kind {
            Kind::Clear => "tiny-skia `Pixmap::fill` (RGBA8888)",
            Kind::Polygons => "tiny-skia `fill_path`, no AA (RGBA8888)",
        }
    }
    fn pass(&mut self) {
        if self.kind == Kind::Clear {
            self.pixmap
                .fill(tiny_skia::Color::from_rgba8(0xff, 0, 0, 0xff));
            return;
        }
        for i in 0..self.paths.len() {
            self.fill(i);
        }
    }
    fn draw_one(&mut self, i: usize) {
        let ((), peak) = heap::peak_during(|| self.fill(i));
        self.heap_peak = self.heap_peak.max(peak);
    }
    fn covered(&self, x: i32, y: i32) -> bool {
        self.pixmap.pixels()[at(self.pixmap.width() as u16, x, y)].alpha() != 0
    }
    fn reset(&mut self, b: (i32, i32, i32, i32)) {
        let w = self.pixmap.width() as u16;
        let px = self.pixmap.pixels_mut();
        for y in b.1..b.3 {
            px[at(w, b.0, y)..at(w, b.2, y)].fill(tiny_skia::PremultipliedColorU8::TRANSPARENT);
        }
    }
    fn memory(&self) -> (usize, String) {
        if self.kind == Kind::Clear {
            return (0, "none measured".into());
        }
        let path = self
            .paths
            .iter()
            .flatten()
            .map(|p| size_of::<tiny_skia::Path>() + p.points().len() * 8 + p.verbs().len())
            .max()
            .unwrap_or(0);
        (
            self.heap_peak + path,
            format!(
                "{} B heap peak inside `fill_path` (counting allocator, worst polygon) + {path} B path",
                self.heap_peak
            ),
        )
    }
}

/// A frame buffer as an embedded-graphics `DrawTarget`, with `fill_solid`
/// as one `slice::fill` per row (what a driver for a memory frame buffer
/// would write).
#[derive(Debug)]
pub struct EgFrame<C> {
    /// Row-major pixels.
    pub pixels: Vec<C>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl<C: PixelColor> EgFrame<C> {
    /// A `width × height` frame of `bg`.
    pub fn new(width: u32, height: u32, bg: C) -> Self {
        EgFrame {
            pixels: vec![bg; width as usize * height as usize],
            width,
            height,
        }
    }
}

impl<C: PixelColor> OriginDimensions for EgFrame<C> {
    fn size(&self) -> Size {
        Size::new(self.width, self.height)
    }
}

impl<C: PixelColor> DrawTarget for EgFrame<C> {
    type Color = C;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Infallible>
    where
        I: IntoIterator<Item = Pixel<C>>,
    {
        for Pixel(p, c) in pixels {
            if (0..self.width as i32).contains(&p.x) && (0..self.height as i32).contains(&p.y) {
                self.pixels[p.y as usize * self.width as usize + p.x as usize] = c;
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: C) -> Result<(), Infallible> {
        let a = area.intersection(&self.bounding_box());
        if let Some(br) = a.bottom_right() {
            let w = self.width as usize;
            let (x0, x1) = (a.top_left.x as usize, br.x as usize + 1);
            for y in a.top_left.y as usize..=br.y as usize {
                self.pixels[y * w + x0..y * w + x1].fill(color);
            }
        }
        Ok(())
    }
}

/// embedded-graphics `Triangle`s with a fill style, polygons as fans,
/// vertices at the pixel that holds them (embedded-graphics points are
/// whole pixels).
pub struct EgTriangles {
    kind: Kind,
    frame: EgFrame<Rgb565>,
    tris: Vec<Vec<Styled<Triangle, PrimitiveStyle<Rgb565>>>>,
}

impl EgTriangles {
    /// The contender for `wl`.
    pub fn new(wl: &Workload) -> Self {
        let style = PrimitiveStyle::with_fill(INK);
        let pt = |v: Vertex| Point::new(v.x.units() >> 4, v.y.units() >> 4);
        let tris = wl
            .polys
            .iter()
            .map(|p| {
                (1..p.len() - 1)
                    .map(|k| Triangle::new(pt(p[0]), pt(p[k]), pt(p[k + 1])).into_styled(style))
                    .collect()
            })
            .collect();
        EgTriangles {
            kind: wl.kind,
            frame: EgFrame::new(wl.width as u32, wl.height as u32, Rgb565::BLACK),
            tris,
        }
    }
}

impl Contender for EgTriangles {
    fn name(&self) -> &'static str {
        match self.kind {
            Kind::Clear => "embedded-graphics `clear` (default: `fill_solid`)",
            Kind::Polygons => "embedded-graphics `Triangle` fill (fans)",
        }
    }
    fn pass(&mut self) {
        if self.kind == Kind::Clear {
            let Ok(()) = self.frame.clear(INK);
            return;
        }
        for p in &self.tris {
            for t in p {
                let Ok(()) = t.draw(&mut self.frame);
            }
        }
    }
    fn draw_one(&mut self, i: usize) {
        for t in &self.tris[i] {
            let Ok(()) = t.draw(&mut self.frame);
        }
    }
    fn covered(&self, x: i32, y: i32) -> bool {
        self.frame.pixels[at(self.frame.width as u16, x, y)] != Rgb565::BLACK
    }
    fn reset(&mut self, b: (i32, i32, i32, i32)) {
        let w = self.frame.width as u16;
        for y in b.1..b.3 {
            self.frame.pixels[at(w, b.0, y)..at(w, b.2, y)].fill(Rgb565::BLACK);
        }
    }
    fn memory(&self) -> (usize, String) {
        if self.kind == Kind::Clear {
            return (0, "none".into());
        }
        let n = self.tris.iter().map(Vec::len).max().unwrap_or(0);
        let one = size_of::<Styled<Triangle, PrimitiveStyle<Rgb565>>>();
        let iter = self
            .tris
            .first()
            .and_then(|p| p.first())
            .map(|t| size_of_val(&t.pixels()))
            .unwrap_or(0);
        (
            n * one + iter,
            format!("{n} styled triangles × {one} B + {iter} B scan-line state (size of its pixel iterator)"),
        )
    }
}

/// `slice::fill` of as many pixels as the exact rule covers, contiguous,
/// per polygon (or the whole frame for a clear): the memory-bandwidth
/// limit of any span rasteriser.
pub struct SliceFill {
    kind: Kind,
    pixels: Vec<Rgb565>,
    counts: Vec<usize>,
    cursor: usize,
}

impl SliceFill {
    /// The limit for `wl`, polygon `i` covering `counts[i]` pixels.
    pub fn new(wl: &Workload, counts: Vec<usize>) -> Self {
        SliceFill {
            kind: wl.kind,
            pixels: vec![Rgb565::BLACK; wl.width as usize * wl.height as usize],
            counts,
            cursor: 0,
        }
    }
}

impl Contender for SliceFill {
    fn name(&self) -> &'static str {
        "`slice::fill`, same pixel count (bandwidth limit)"
    }
    fn pass(&mut self) {
        if self.kind == Kind::Clear {
            self.pixels.fill(INK);
            return;
        }
        let len = self.pixels.len();
        for &n in &self.counts {
            if self.cursor + n > len {
                self.cursor = 0;
            }
            self.pixels[self.cursor..self.cursor + n].fill(INK);
            self.cursor += n;
        }
    }
    fn draw_one(&mut self, _: usize) {}
    fn covered(&self, _: i32, _: i32) -> bool {
        false
    }
    fn reset(&mut self, _: (i32, i32, i32, i32)) {}
    fn has_coverage(&self) -> bool {
        false
    }
    fn memory(&self) -> (usize, String) {
        (0, "none".into())
    }
}

/// Every contender for `wl`, scanvert's exact path first and the
/// bandwidth limit last. `counts[i]`: pixels polygon `i` covers.
pub fn for_workload(wl: &Workload, counts: Vec<usize>) -> Vec<Box<dyn Contender>> {
    let mut v: Vec<Box<dyn Contender>> = Vec::new();
    if wl.kind == Kind::Clear {
        v.push(Box::new(ScanvertFill::<Edge, 4>::new(
            "scanvert `FrameBuffer::clear`",
            wl,
            Edge::EMPTY,
        )));
        v.push(Box::new(ScanvertList::new(wl)));
    } else {
        v.push(Box::new(ScanvertFill::<Edge, 4>::new(
            "scanvert exact (`Rasterizer::fill`)",
            wl,
            Edge::EMPTY,
        )));
        if wl.id == "W3" {
            v.push(Box::new(ScanvertList::new(wl)));
        }
        v.push(Box::new(ScanvertFill::<Dda7, 4>::new(
            "scanvert DDA 1/128 px (`Dda7`)",
            wl,
            Dda7::EMPTY,
        )));
        v.push(Box::new(ScanvertFill::<Dda16, 4>::new(
            "scanvert DDA 16.16 (`Dda16`)",
            wl,
            Dda16::EMPTY,
        )));
        v.push(Box::new(PlainFill::new(wl)));
        v.push(Box::new(ScanvertFill::<Edge, 2>::new(
            "scanvert exact, vertices snapped to 1/4 px",
            wl,
            Edge::EMPTY,
        )));
        v.push(Box::new(ScanvertFill::<Edge, 0>::new(
            "scanvert exact, vertices snapped to 1 px",
            wl,
            Edge::EMPTY,
        )));
    }
    v.push(Box::new(TinySkia::new(wl)));
    v.push(Box::new(EgTriangles::new(wl)));
    v.push(Box::new(SliceFill::new(wl, counts)));
    v
}

/// A span target that only consumes its spans: the cost of scan
/// conversion without the pixel writes (for profiling).
#[derive(Debug)]
pub struct NullTarget(pub u16, pub u16);

impl SpanTarget for NullTarget {
    type Color = Rgb565;
    type Error = Infallible;
    fn size(&self) -> (u16, u16) {
        (self.0, self.1)
    }
    #[inline]
    fn fill_span(&mut self, span: Span, color: Rgb565) -> Result<(), Infallible> {
        core::hint::black_box((span, color));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use testkit::{reference, workloads};

    /// Pixels where [`PlainFill`] and the rule differ, over the first
    /// `n` polygons of `wl`, each drawn alone.
    fn plain_mismatches(wl: &Workload, n: usize) -> (u64, u64) {
        let mut c = PlainFill::new(wl);
        let (mut off, mut covered) = (0, 0);
        for (i, p) in wl.polys.iter().enumerate().take(n) {
            let p = reference::units(p);
            let b = reference::pixel_box(&p, 3, wl.width, wl.height);
            c.draw_one(i);
            for y in b.1..b.3 {
                for x in b.0..b.2 {
                    let want = reference::covers(&p, x, y);
                    covered += u64::from(want);
                    off += u64::from(c.covered(x, y) != want);
                }
            }
            c.reset(b);
        }
        (off, covered)
    }

    #[test]
    fn the_plain_filler_follows_the_rule_where_16_16_resolves_it() {
        // Whole-pixel squares and the rotated square: exact.
        assert_eq!(plain_mismatches(&workloads::w1(), 226).0, 0);
        assert_eq!(plain_mismatches(&workloads::w4(), 218).0, 0);
        // Random triangles and slivers: off by a rounding here and there.
        for wl in [workloads::w3(), workloads::w6()] {
            let (off, covered) = plain_mismatches(&wl, 500);
            assert!(
                covered > 0 && off * 100 < covered,
                "{}: {off} of {covered}",
                wl.id
            );
        }
    }
}
