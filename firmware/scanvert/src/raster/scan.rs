//! Scan conversion of one polygon: the active-edge list, the pairing of
//! crossings (even-odd here, non-zero in [`winding`](super::winding)), and
//! the clip registers applied to every span.
//!
//! The edges of a polygon are set up once ([`Edge::new`], clipped to the
//! window's rows) and sorted by first row. Row by row, edges whose first
//! row has come join the active list, every active edge yields the pixel
//! `⌈x − ½⌉` of its crossing, an insertion sort (nearly free, since the
//! order rarely changes from one row to the next; with a budget, past
//! which an `O(n log n)` sort takes over) orders them, and
//! crossings are paired 1st–2nd, 3rd–4th, …: each pair is the span
//! `c₁..c₂`, cut to the clip window's columns. Rows where nothing is active
//! are jumped over.
//!
//! The active set changes only on rows where an edge starts or ends, so the
//! rows in between form a run that needs no membership test. In a run of
//! two active edges (every row of a convex polygon, most rows of others)
//! both edges are stepped in locals, and the pair needs one compare and no
//! sort. A triangle is that from the start: its long edge beside one short
//! edge, then beside the other, with no edge slots, sort or walk. So is a
//! display list's quadrilateral that is monotone in `y` (the controller
//! calls `Rasterizer::fill_quad` for a 4-vertex `poly`): the edges of
//! its two sides, from its top vertex down to its bottom one, are taken
//! in pairs as each one's rows end.
//!
//! Sorting the integer pixels instead of the exact crossings gives the same
//! pixels: a pixel is covered when an odd number of crossings lie at or
//! left of its centre, and that count only depends on the integers.

use crate::fixed::{ceil_px, Vertex, HALF};
use crate::port::{Counts, Span, SpanTarget};
use crate::raster::clip::ClipRect;
use crate::raster::edge::{Edge, Stepper};
use crate::raster::winding::{emit_nonzero, FillRule};
use core::fmt;

/// Why a polygon could not be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum FillError<E> {
    /// The polygon has more edges inside the clip rows than the edge
    /// storage holds. Nothing of it was drawn.
    Capacity {
        /// Slots the edge storage holds.
        capacity: usize,
    },
    /// The target failed; part of the polygon may have been drawn.
    Target(E),
}

impl<E: fmt::Debug> fmt::Display for FillError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FillError::Capacity { capacity } => {
                write!(
                    f,
                    "polygon needs more than the {capacity} edge slots available"
                )
            }
            FillError::Target(e) => write!(f, "frame-buffer port failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for FillError<E> {}

/// The polygon scan converter over caller-owned edge storage.
///
/// # Capacity
/// A polygon of `n` vertices needs at most `n` edge slots; only edges that
/// cross a row centre inside the clip window take one. With too few slots,
/// [`Rasterizer::fill`] returns [`FillError::Capacity`] and draws nothing.
/// The storage is the active-edge list too, so no other memory is used.
///
/// ```
/// use scanvert::{raster::edge::Edge, raster::scan::Rasterizer};
/// let mut slots = [Edge::EMPTY; 64]; // const-generic capacity on the stack
/// let raster = Rasterizer::new(&mut slots);
/// assert_eq!(raster.capacity(), 64);
/// ```
///
/// # Steppers
/// The edge stepper is the type parameter `S`: the exact [`Edge`] by
/// default, or one of the approximate, faster steppers of
/// [`dda`](crate::raster::dda), chosen by the type of the storage:
///
/// ```
/// use scanvert::{raster::dda::Dda16, raster::scan::Rasterizer};
/// let mut slots = [Dda16::EMPTY; 16];
/// let raster: Rasterizer<'_, Dda16> = Rasterizer::new(&mut slots);
/// assert_eq!(raster.capacity(), 16);
/// ```
#[derive(Debug)]
pub struct Rasterizer<'e, S: Stepper = Edge> {
    edges: &'e mut [S],
}

impl<'e, S: Stepper> Rasterizer<'e, S> {
    /// A rasteriser using `edges` as its edge table.
    pub fn new(edges: &'e mut [S]) -> Self {
        Rasterizer { edges }
    }

    /// Edge slots available.
    pub fn capacity(&self) -> usize {
        self.edges.len()
    }

    /// Fills the polygon through `vertices` (closed implicitly) with the
    /// even-odd rule, writing only pixels inside `clip`. The target is told
    /// of the polygon first ([`SpanTarget::begin_polygon`]), whether or not
    /// any of it is drawn.
    ///
    /// A triangle whose iterator says so (a `size_hint` of exactly three,
    /// as slices' and display lists' iterators give) is drawn without the
    /// edge slots, as two runs of two edges: the same pixels, counts and
    /// calls of the target. Only its first three vertices are read, so an
    /// iterator that yields more than its `size_hint` allows is drawn as
    /// the triangle of its first three.
    pub fn fill<I, T>(
        &mut self,
        vertices: I,
        clip: &ClipRect,
        color: T::Color,
        target: &mut T,
    ) -> Result<Counts, FillError<T::Error>>
    where
        I: IntoIterator<Item = Vertex>,
        T: SpanTarget + ?Sized,
    {
        self.fill_by::<false, I, T>(vertices, clip, color, target)
    }

    /// [`fill`](Self::fill) by the fill rule `rule`: even-odd, or non-zero
    /// winding (see [`FillRule`]).
    ///
    /// ```
    /// use scanvert::prelude::*;
    /// use scanvert::raster::FillRule;
    /// use scanvert::pixelcolor::BinaryColor;
    /// // A five-pointed star in one stroke: its middle winds twice.
    /// let star = [(16, 2), (24, 28), (3, 12), (29, 12), (8, 28)]
    ///     .map(|(x, y)| Vertex::from_bits(16 * x, 16 * y));
    /// let mut px = [BinaryColor::Off; 32 * 32];
    /// let mut fb = FrameBuffer::new(&mut px, 32, 32).unwrap();
    /// let mut slots = [Edge::EMPTY; 5];
    /// let clip = ClipRect::full(32, 32);
    /// let mut raster = Rasterizer::new(&mut slots);
    /// raster.fill_with(FillRule::EvenOdd, star, &clip, BinaryColor::On, &mut fb).unwrap();
    /// assert_eq!(fb.pixel(16, 16), Some(BinaryColor::Off));
    /// raster.fill_with(FillRule::NonZero, star, &clip, BinaryColor::On, &mut fb).unwrap();
    /// assert_eq!(fb.pixel(16, 16), Some(BinaryColor::On));
    /// ```
    pub fn fill_with<I, T>(
        &mut self,
        rule: FillRule,
        vertices: I,
        clip: &ClipRect,
        color: T::Color,
        target: &mut T,
    ) -> Result<Counts, FillError<T::Error>>
    where
        I: IntoIterator<Item = Vertex>,
        T: SpanTarget + ?Sized,
    {
        if rule == FillRule::NonZero {
            return self.fill_nonzero(vertices, clip, color, target);
        }
        self.fill(vertices, clip, color, target)
    }

    /// [`fill_by`](Self::fill_by) the non-zero rule, out of line: the
    /// even-odd fill, inlined into its callers, is compiled as it would
    /// be without it.
    #[inline(never)]
    fn fill_nonzero<I, T>(
        &mut self,
        vertices: I,
        clip: &ClipRect,
        color: T::Color,
        target: &mut T,
    ) -> Result<Counts, FillError<T::Error>>
    where
        I: IntoIterator<Item = Vertex>,
        T: SpanTarget + ?Sized,
    {
        self.fill_by::<true, I, T>(vertices, clip, color, target)
    }

    /// The fill, by the non-zero rule when `NONZERO`, else even-odd.
    #[inline(always)]
    fn fill_by<const NONZERO: bool, I, T>(
        &mut self,
        vertices: I,
        clip: &ClipRect,
        color: T::Color,
        target: &mut T,
    ) -> Result<Counts, FillError<T::Error>>
    where
        I: IntoIterator<Item = Vertex>,
        T: SpanTarget + ?Sized,
    {
        let mut counts = Counts::default();
        target.begin_polygon();
        // The clip cut to the target once, so that every span it passes is
        // inside the target and is written without the target's own checks.
        let (w, h) = target.size();
        let clip = &clip.within(w, h);
        if clip.is_empty() {
            return Ok(counts);
        }
        let mut vertices = vertices.into_iter();
        // A triangle (as its iterator says: exactly three vertices) goes
        // straight to its two runs, with no edge slots, sort or walk. With
        // fewer than three slots the walk's capacity error stands.
        if !NONZERO && vertices.size_hint() == (3, Some(3)) && self.edges.len() >= 3 {
            if let (Some(a), Some(b), Some(c)) = (vertices.next(), vertices.next(), vertices.next())
            {
                fill_triangle::<S, T>([a, b, c], clip, color, target, &mut counts)
                    .map_err(FillError::Target)?;
            }
            return Ok(counts);
        }
        let n = match build_edges::<NONZERO, S>(self.edges, vertices, clip) {
            Some(n) => n,
            None => {
                return Err(FillError::Capacity {
                    capacity: self.edges.len(),
                })
            }
        };
        let edges = &mut self.edges[..n];
        if n < 2 {
            return Ok(counts);
        }
        sort_by_top(edges);
        let (cx0, cx1) = (clip.x0() as i32, clip.x1() as i32);

        let mut walk = Walk::start(edges);
        walk.run::<false, NONZERO, _, _>(
            edges,
            i32::MAX,
            (cx0, cx1),
            Some((target, color)),
            &mut counts,
        )
        .map_err(FillError::Target)?;
        Ok(counts)
    }

    /// [`fill_with`](Self::fill_with) for a polygon of `len` vertices
    /// that is a quadrilateral drawn without the walk of its edges: the
    /// same pixels, counts and outcome, by either fill rule (both are one
    /// here). An axis-aligned rectangle (sides alternately horizontal and
    /// vertical) is filled from its corners, with no edge set up (with an
    /// exact stepper only); a quadrilateral that is monotone in `y`
    /// ([`monotone`]) as two chains of edges from its top vertex down to
    /// its bottom one, stepped in pairs as a triangle's are
    /// ([`fill_chains`]), with no edge slots, sort or walk (with at least
    /// 4 edge slots, so that the walk could not have failed for want of
    /// them). `None`, with nothing done, for any other polygon; the caller
    /// then calls `fill_with`. Not inlined: its own registers, and a call
    /// a 4-vertex polygon, keep the caller's loop as it is for the others.
    #[inline(never)]
    pub(crate) fn fill_quad<I, T>(
        &mut self,
        vertices: I,
        len: usize,
        clip: &ClipRect,
        color: T::Color,
        target: &mut T,
    ) -> Option<Result<Counts, FillError<T::Error>>>
    where
        I: IntoIterator<Item = Vertex>,
        T: SpanTarget + ?Sized,
    {
        if len != 4 || self.edges.len() < 2 {
            return None;
        }
        let mut corners = [Vertex::default(); 4];
        let mut it = vertices.into_iter();
        for c in corners.iter_mut() {
            *c = it.next()?;
        }
        let rect = if S::EXACT { rectangle(&corners) } else { None };
        let chains = match rect {
            Some(_) => None,
            None if self.edges.len() >= 4 => Some(monotone(&corners)?),
            None => return None,
        };
        let mut counts = Counts::default();
        target.begin_polygon();
        let (w, h) = target.size();
        let clip = clip.within(w, h);
        if clip.is_empty() {
            return Some(Ok(counts));
        }
        let cx = (clip.x0() as i32, clip.x1() as i32);
        let done = match (rect, chains) {
            (Some(r), _) => {
                let top = ceil_px(r.1 - HALF).max(clip.y0() as i32);
                let stop = ceil_px(r.3 - HALF).min(clip.y1() as i32);
                let (l, right) = (ceil_px(r.0 - HALF), ceil_px(r.2 - HALF));
                emit_rows(top, stop, l, right, cx, color, target, &mut counts)
            }
            (None, Some(chains)) => {
                fill_chains::<S, T>(&corners, chains, &clip, color, target, &mut counts)
            }
            (None, None) => Ok(()),
        };
        Some(done.map(|()| counts).map_err(FillError::Target))
    }
}

/// The top vertex `t` of the polygon `v` (`3 ≤ v.len()`; least `y`, the
/// first of equals) and the number `k` of its edges from `t` forward (in
/// vertex order) down to its bottom vertex, when the polygon is monotone
/// in `y`: `y` never decreases over those `k` edges and never increases
/// over the other `n − k`, from the bottom vertex forward back to `t`.
/// Then the two chains' edges, as half-open `y` ranges, each tile
/// `[y_t, y_b)`, so every row centre crosses exactly one edge of each:
/// the walk of the edges would pair those two on every row. `None` for
/// any other polygon, and for a flat one (every `y` equal).
#[inline(always)]
fn monotone(v: &[Vertex]) -> Option<(usize, usize)> {
    let n = v.len();
    let y = |i: usize| v.get(i).map_or(0, |p| p.y.units());
    let next = |i: usize| if i + 1 >= n { 0 } else { i + 1 };
    let mut t = 0;
    for i in 1..n {
        if y(i) < y(t) {
            t = i;
        }
    }
    let (mut i, mut k) = (t, 0);
    while k < n && y(next(i)) >= y(i) {
        i = next(i);
        k += 1;
    }
    if k == n {
        return None;
    }
    for _ in k..n {
        if y(next(i)) > y(i) {
            return None;
        }
        i = next(i);
    }
    Some((t, k))
}

/// The polygon `v`, monotone in `y` with top vertex `t` and `k` edges in
/// its forward chain ([`monotone`]), under the clip `clip` (cut to the
/// target): the same pixels and counts as the walk of its edges. Its
/// forward chain's edges and its backward chain's are taken in order as
/// each one's rows end, and stepped in pairs as a triangle's are: the
/// rows of each pair are one run of two edges.
#[inline(always)]
fn fill_chains<S: Stepper, T: SpanTarget + ?Sized>(
    v: &[Vertex],
    (t, k): (usize, usize),
    clip: &ClipRect,
    color: T::Color,
    target: &mut T,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    let n = v.len();
    let rows = (clip.y0() as i32, clip.y1() as i32);
    let at = |i: usize| v.get(i).copied().unwrap_or_default();
    // The next edge down a chain that crosses a row centre in the clip
    // rows: `(vertex, edges left)`, forward or backward in vertex order.
    let down = |(i, left): &mut (usize, usize), forward: bool| -> Option<S> {
        while *left > 0 {
            let j = match (forward, *i) {
                (true, i) if i + 1 >= n => 0,
                (true, i) => i + 1,
                (false, 0) => n - 1,
                (false, i) => i - 1,
            };
            let e = S::new(at(*i), at(j), rows);
            *i = j;
            *left -= 1;
            if e.is_some() {
                return e;
            }
        }
        None
    };
    let (mut fw, mut bw) = ((t, k), (t, n - k));
    let (Some(mut ef), Some(mut eb)) = (down(&mut fw, true), down(&mut bw, false)) else {
        return Ok(());
    };
    let cx = (clip.x0() as i32, clip.x1() as i32);
    // Every exact crossing lies between the leftmost and rightmost
    // vertices: inside the clip columns there, no run needs the clip.
    // `⌈(x − ½)/16⌉` lies in `cx.0..=cx.1` exactly when `x` lies in
    // `16·cx.0 − 7 ..= 16·cx.1 + 8`: one unsigned compare a vertex.
    let (base, span) = (cx.0 * 16 - 7, ((cx.1 - cx.0) * 16 + 15) as u32);
    let inside = S::EXACT && v.iter().all(|p| ((p.x.units() - base) as u32) <= span);
    let top = ef.top();
    let mut y = top;
    let (mut empty, mut pixels) = (0u32, 0u32);
    loop {
        let (end_f, end_b) = (ef.end(), eb.end());
        let stop = end_f.min(end_b);
        let c = (&mut empty, &mut pixels);
        // The backward chain first: it is the left one when the polygon
        // turns clockwise on the screen (`y` down), and a pair that comes
        // in left edge first is not swapped at the run's first row (one
        // of the other turn is, and swapped back below).
        let (ea, eb2) = (&mut eb, &mut ef);
        if inside {
            two_edge_rows::<false, false, S, T>((ea, eb2), (y, stop), cx, color, target, c)?;
        } else {
            two_edge_rows::<false, true, S, T>((ea, eb2), (y, stop), cx, color, target, c)?;
        }
        y = stop;
        // The pair may come back swapped: each chain's edge is the one
        // with its end (when both end here, both are replaced).
        if ef.end() != end_f || eb.end() != end_b {
            core::mem::swap(&mut ef, &mut eb);
        }
        if end_f == y {
            match down(&mut fw, true) {
                Some(e) => ef = e,
                None => break,
            }
        } else {
            ef.step();
        }
        if end_b == y {
            match down(&mut bw, false) {
                Some(e) => eb = e,
                None => break,
            }
        } else {
            eb.step();
        }
    }
    let spans = (y - top) as u32 - empty;
    counts.spans = counts.spans.saturating_add(spans);
    counts.pixels = counts.pixels.saturating_add(pixels);
    Ok(())
}

/// The corners `(x_min, y_min, x_max, y_max)`, in units, of the
/// polygon `v` when it is an axis-aligned rectangle (its sides alternate
/// horizontal and vertical, in either order), else `None`.
#[inline(always)]
fn rectangle(v: &[Vertex; 4]) -> Option<(i32, i32, i32, i32)> {
    let [a, b, c, d] = *v;
    let sides = (a.y == b.y && b.x == c.x && c.y == d.y && d.x == a.x)
        || (a.x == b.x && b.y == c.y && c.x == d.x && d.y == a.y);
    sides.then(|| {
        let (x0, x1) = (a.x.units(), c.x.units());
        let (y0, y1) = (a.y.units(), c.y.units());
        (x0.min(x1), y0.min(y1), x0.max(x1), y0.max(y1))
    })
}

/// Sets up the edges of the polygon through `vertices` that cross a row
/// centre inside `clip` into `edges`; returns their number (0 when the
/// polygon's box misses the clip columns), or `None` when they do not
/// fit. The rasteriser and the band path's edge table
/// ([`table`](super::table)) both set up polygons so. `WOUND` sets them
/// up for a walk by the non-zero rule ([`Stepper::new_wound`]).
#[inline(always)]
pub(super) fn build_edges<const WOUND: bool, S: Stepper>(
    edges: &mut [S],
    vertices: impl IntoIterator<Item = Vertex>,
    clip: &ClipRect,
) -> Option<usize> {
    let rows = (clip.y0() as i32, clip.y1() as i32);
    let mut it = vertices.into_iter();
    let Some(first) = it.next() else {
        return Some(0);
    };
    let (mut lo, mut hi) = (first.x.units(), first.x.units());
    let mut n = 0;
    let mut prev = first;
    let mut push = |a: Vertex, b: Vertex, n: &mut usize| -> Option<()> {
        let e = if WOUND {
            S::new_wound(a, b, rows)
        } else {
            S::new(a, b, rows)
        };
        if let Some(e) = e {
            *edges.get_mut(*n)? = e;
            *n += 1;
        }
        Some(())
    };
    for v in it {
        push(prev, v, &mut n)?;
        lo = lo.min(v.x.units());
        hi = hi.max(v.x.units());
        prev = v;
    }
    push(prev, first, &mut n)?;
    // Columns covered lie in ⌈lo − ½⌉..⌈hi − ½⌉.
    if ceil_px(hi - HALF) <= clip.x0() as i32 || ceil_px(lo - HALF) >= clip.x1() as i32 {
        return Some(0);
    }
    Some(n)
}

/// Moves `edges[from]` into the slot `to < from`, whose contents are
/// never read again. Written as a swap of two disjoint halves of the
/// slice, which is a few loads and stores: `edges[to] = edges[from]`
/// compiles to a call to `memmove` (the slots might overlap, as far as the
/// compiler knows), and so does a plain copy between the halves where the
/// walk is inlined into the band path's table, a call that costs many
/// times the swap on a Cortex-M4.
#[inline(always)]
fn copy_down<S: Stepper>(edges: &mut [S], from: usize, to: usize) {
    let (low, high) = edges.split_at_mut(from);
    if let (Some(dst), Some(src)) = (low.get_mut(to), high.first()) {
        dst.copy_from(src);
    }
}

/// Where one polygon's walk down its rows stands: `edges[..active]` are
/// active, `edges[active..next]` finished (never read again),
/// `edges[next..]` wait for their first row (sorted by it), and `y` is
/// the next row. An edge joins on its first row, so every active edge has
/// `end > y`. The rasteriser walks a polygon in one call; the band path's
/// table ([`table`](super::table)) keeps a walk per polygon and continues
/// it band by band.
#[derive(Clone, Copy, Debug)]
pub(super) struct Walk {
    pub(super) active: usize,
    pub(super) next: usize,
    pub(super) y: i32,
    /// The target holds every row the walk draws, so a run of two
    /// edges inside the clip columns is written a row's start at a time
    /// ([`SpanTarget::row_start`]) with no check a span. Always so
    /// outside a band walk (the rasteriser cuts the clip to the target);
    /// in one, the caller says.
    pub(super) inside: bool,
}

impl Walk {
    /// The walk of `edges` (sorted by first row, at least one) from their
    /// first row.
    #[inline(always)]
    pub(super) fn start<S: Stepper>(edges: &[S]) -> Walk {
        Walk {
            active: 0,
            next: 0,
            y: edges.first().map_or(0, |e| e.top()),
            inside: true,
        }
    }

    /// Walks rows `self.y..y1` of the polygon whose edges are `edges`,
    /// writing its spans cut to the columns `cx` into the target of
    /// `paint` (or, without one, only stepping), and leaves the walk at
    /// row `y1` or past its last row. `BAND` is for a walk that stops at
    /// band ends (the band path's table): two edges that both go on past
    /// `y1` are stepped to it and the walk left at once, without the
    /// general retire loop (fewer branches a predictor misses, at every
    /// band a polygon crosses); where [`inside`](Self::inside), a run of
    /// two edges inside the clip columns is written as outside a band
    /// walk, from each row's start. `NONZERO` walks by the non-zero rule
    /// ([`winding`](super::winding)): every row through the general loop,
    /// its edges loaded with their direction
    /// ([`Stepper::load_wound`]).
    #[inline(always)]
    pub(super) fn run<const BAND: bool, const NONZERO: bool, S: Stepper, T: SpanTarget + ?Sized>(
        &mut self,
        edges: &mut [S],
        y1: i32,
        cx: (i32, i32),
        mut paint: Option<(&mut T, T::Color)>,
        counts: &mut Counts,
    ) -> Result<(), T::Error> {
        let n = edges.len();
        let (mut active, mut next, mut y) = (self.active, self.next, self.y);
        loop {
            if active == 0 {
                match edges.get(next) {
                    Some(e) => y = y.max(e.top()),
                    None => break,
                }
            }
            if y >= y1 {
                break;
            }
            while next < n && edges[next].top() <= y {
                // The slot at `active` is free (a finished edge, or the
                // edge itself): a copy, not a swap.
                if active != next {
                    copy_down(edges, next, active);
                }
                active += 1;
                next += 1;
            }
            // The active set holds for rows y..stop: until an edge ends or
            // another starts, or the walk's last row. Within such a run no
            // membership test is made.
            let mut stop = edges.get(next).map_or(i32::MAX, |e| e.top()).min(y1);
            for e in &edges[..active] {
                stop = stop.min(e.end());
            }
            let (live, waiting) = edges.split_at_mut(active);
            match (paint.as_mut(), live) {
                (Some((target, color)), [a, b])
                    if !NONZERO && a.is_vertical() && b.is_vertical() =>
                {
                    // Two vertical edges (a rectangle's sides): one span,
                    // the same on every row of the run; nothing to step.
                    a.load_pixel();
                    b.load_pixel();
                    let (l, r) = (a.pixel().min(b.pixel()), a.pixel().max(b.pixel()));
                    emit_rows(y, stop, l, r, cx, *color, &mut **target, counts)?;
                    y = stop;
                }
                (Some((target, color)), [a, b]) if !NONZERO => {
                    // Two edges (every convex polygon, most rows of any
                    // other): stepped in locals, one span a row, no sort.
                    let (mut ea, mut eb) = (*a, *b);
                    // Counted in locals and added once a run: the run's
                    // rows and pixels fit in `u32` (a side is at most 4096).
                    // Its spans are its rows but the empty ones, counted
                    // where they are (rarely).
                    let (first, mut empty, mut pixels) = (y, 0u32, 0u32);
                    loop {
                        // Rows y..stop, without the clip where both edges
                        // stay inside its columns over them.
                        let rows = stop - y;
                        let inside = |e: &S| within_columns(e, rows, cx);
                        let (e, c) = ((&mut ea, &mut eb), (&mut empty, &mut pixels));
                        if (!BAND || self.inside) && inside(e.0) && inside(e.1) {
                            two_edge_rows::<false, false, _, T>(
                                e,
                                (y, stop),
                                cx,
                                *color,
                                target,
                                c,
                            )?;
                        } else {
                            two_edge_rows::<BAND, true, _, T>(e, (y, stop), cx, *color, target, c)?;
                        }
                        y = stop;
                        // Where one edge ends and the next waiting edge
                        // begins on this row, alone (a convex polygon's
                        // chains, at every vertex but the last): the pair
                        // stays in locals, as the retire and join below
                        // would leave it. Not in a band walk, whose
                        // polygons cross few vertices a band and whose
                        // code, inlined into the table, grew slower with
                        // it.
                        let joins = waiting.get(next - active).filter(|e| e.top() == y);
                        let alone = waiting.get(next - active + 1).is_none_or(|e| e.top() > y);
                        match joins {
                            Some(e) if !BAND && alone && y < y1 => {
                                if ea.end() == y && eb.end() > y {
                                    ea = *e;
                                    eb.step();
                                } else if eb.end() == y && ea.end() > y {
                                    eb = *e;
                                    ea.step();
                                } else {
                                    break;
                                }
                                next += 1;
                                stop = waiting
                                    .get(next - active)
                                    .map_or(i32::MAX, |e| e.top())
                                    .min(y1)
                                    .min(ea.end())
                                    .min(eb.end());
                            }
                            _ => break,
                        }
                    }
                    let spans = (y - first) as u32 - empty;
                    counts.spans = counts.spans.saturating_add(spans);
                    counts.pixels = counts.pixels.saturating_add(pixels);
                    if BAND && y >= y1 && ea.end() > y && eb.end() > y {
                        // The band's end, not an edge's: on to the next
                        // band's first row.
                        ea.step();
                        eb.step();
                        *a = ea;
                        *b = eb;
                        break;
                    }
                    *a = ea;
                    *b = eb;
                }
                (Some((target, color)), live) => loop {
                    for e in live.iter_mut() {
                        if NONZERO {
                            e.load_wound();
                        } else {
                            e.load_pixel();
                        }
                    }
                    insertion_sort(live);
                    if NONZERO {
                        emit_nonzero::<BAND, S, T>(y, live, cx, *color, &mut **target, counts)?;
                    } else {
                        for pair in live.chunks_exact(2) {
                            emit_span::<BAND, T>(
                                y,
                                pair[0].pixel(),
                                pair[1].pixel(),
                                cx,
                                *color,
                                &mut **target,
                                counts,
                            )?;
                        }
                    }
                    y += 1;
                    if y >= stop {
                        break;
                    }
                    for e in live.iter_mut() {
                        e.step();
                    }
                },
                (None, live) => {
                    // Stepped only: to row stop − 1, as drawing would
                    // leave them.
                    for _ in y + 1..stop {
                        for e in live.iter_mut() {
                            e.step();
                        }
                    }
                    y = stop;
                }
            }
            // Now y == stop: retire the edges that end here (the last
            // active edge takes the slot; what is left behind is never
            // read), step the rest.
            let mut i = 0;
            while i < active {
                if edges[i].end() <= y {
                    active -= 1;
                    if i != active {
                        copy_down(edges, active, i);
                    }
                } else {
                    edges[i].step();
                    i += 1;
                }
            }
        }
        (self.active, self.next, self.y) = (active, next, y);
        Ok(())
    }
}

/// The triangle `v` (even-odd), under the clip `clip` (cut to the
/// target): the same pixels, counts and calls of the target as the walk
/// of its three edges. Its edges by rows are the long one from the top
/// vertex to the bottom one and the two short ones, whose rows are the
/// long one's, split at the middle vertex: two runs of two edges.
#[inline(always)]
fn fill_triangle<S: Stepper, T: SpanTarget + ?Sized>(
    v: [Vertex; 3],
    clip: &ClipRect,
    color: T::Color,
    target: &mut T,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    let [mut a, mut b, mut c] = v;
    if a.y.units() > b.y.units() {
        core::mem::swap(&mut a, &mut b);
    }
    if b.y.units() > c.y.units() {
        core::mem::swap(&mut b, &mut c);
    }
    if a.y.units() > b.y.units() {
        core::mem::swap(&mut a, &mut b);
    }
    let rows = (clip.y0() as i32, clip.y1() as i32);
    let Some(long) = S::new(a, c, rows) else {
        return Ok(());
    };
    // The long edge's rows are the upper edge's, then the lower edge's
    // (either may have none): the first run starts on the long edge's
    // first row, the second on the row the first ends.
    let (first, then) = match (S::new(a, b, rows), S::new(b, c, rows)) {
        (Some(u), l) => (u, l),
        (None, Some(l)) => (l, None),
        (None, None) => return Ok(()),
    };
    let cx = (clip.x0() as i32, clip.x1() as i32);
    // Every exact crossing lies between the leftmost and rightmost
    // vertices: inside the clip columns there, no run needs the clip.
    let (lo, hi) = (
        a.x.units().min(b.x.units()).min(c.x.units()),
        a.x.units().max(b.x.units()).max(c.x.units()),
    );
    let runs = (long, first, then);
    if S::EXACT && ceil_px(lo - HALF) >= cx.0 && ceil_px(hi - HALF) <= cx.1 {
        triangle_runs::<false, S, T>(runs, cx, color, target, counts)
    } else {
        triangle_runs::<true, S, T>(runs, cx, color, target, counts)
    }
}

/// The two runs of a triangle ([`fill_triangle`]): the long edge beside
/// the first short one, then beside the second, cut to the clip columns
/// `cx` when `CLIP`.
#[inline(always)]
fn triangle_runs<const CLIP: bool, S: Stepper, T: SpanTarget + ?Sized>(
    (long, first, mut then): (S, S, Option<S>),
    cx: (i32, i32),
    color: T::Color,
    target: &mut T,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    let top = long.top();
    let (mut ea, mut eb, mut y) = (long, first, top);
    let (mut empty, mut pixels) = (0u32, 0u32);
    loop {
        let stop = ea.end().min(eb.end());
        let c = (&mut empty, &mut pixels);
        two_edge_rows::<false, CLIP, S, T>((&mut ea, &mut eb), (y, stop), cx, color, target, c)?;
        y = stop;
        let Some(next) = then.take() else {
            break;
        };
        // The short edge ends here, the long one goes on a row.
        if ea.end() == y {
            ea = next;
            eb.step();
        } else {
            eb = next;
            ea.step();
        }
    }
    let spans = (y - top) as u32 - empty;
    counts.spans = counts.spans.saturating_add(spans);
    counts.pixels = counts.pixels.saturating_add(pixels);
    Ok(())
}

/// `true` when the pixels of `e` on its `rows` rows from the current one
/// all lie in the clip columns `cx` ([`Stepper::columns`]): a run of
/// them then needs no clip.
#[inline(always)]
fn within_columns<S: Stepper>(e: &S, rows: i32, cx: (i32, i32)) -> bool {
    e.columns(rows)
        .is_some_and(|(lo, hi)| lo >= cx.0 && hi <= cx.1)
}

/// [`two_edge_rows`] of a band walk: from each row's start without the
/// clip where `inside` (the target holds the rows, as
/// [`Walk::inside`]) and both edges stay inside the clip columns `cx`
/// over them, else each span cut to `cx` and checked by the target.
#[inline(always)]
pub(super) fn two_edge_rows_in<S: Stepper, T: SpanTarget + ?Sized>(
    inside: bool,
    e: (&mut S, &mut S),
    rows: (i32, i32),
    cx: (i32, i32),
    color: T::Color,
    target: &mut T,
    counts: (&mut u32, &mut u32),
) -> Result<(), T::Error> {
    let n = rows.1 - rows.0;
    let within = |e: &S| within_columns(e, n, cx);
    if inside && within(e.0) && within(e.1) {
        two_edge_rows::<false, false, S, T>(e, rows, cx, color, target, counts)
    } else {
        two_edge_rows::<true, true, S, T>(e, rows, cx, color, target, counts)
    }
}

/// Writes the rows `y..stop` (`y < stop`) between the edges `e` (loaded
/// at row `y`, both live to `stop`), cut to the clip columns `cx` when
/// `CLIP` (else they are inside them), counting the empty rows and the
/// pixels into `counts`; leaves both edges at row `stop − 1`. Outside a
/// band walk the two may come back swapped (the pair's order does not
/// matter to the caller).
#[inline(always)]
fn two_edge_rows<const BAND: bool, const CLIP: bool, S: Stepper, T: SpanTarget + ?Sized>(
    e: (&mut S, &mut S),
    rows: (i32, i32),
    cx: (i32, i32),
    color: T::Color,
    target: &mut T,
    counts: (&mut u32, &mut u32),
) -> Result<(), T::Error> {
    let ((ea, eb), (mut y, stop)) = (e, rows);
    if !BAND {
        // Rows inside the target: each row's start follows from the last
        // row's, with no `y · width` a row.
        let stride = target.row_stride();
        let mut row = target.row_start(y as u16);
        let end = target.row_start(stop as u16);
        loop {
            // Rows where `ea` is left of `eb`, with no order test a row
            // but this one.
            loop {
                ea.load_pixel();
                eb.load_pixel();
                let (l, r) = (ea.pixel(), eb.pixel());
                if l >= r {
                    break;
                }
                let (x0, x1) = if CLIP {
                    (l.max(cx.0), r.min(cx.1))
                } else {
                    (l, r)
                };
                if x0 < x1 {
                    // In 0..=4096 by the clip guarantee.
                    target.fill_row_inside(row, x0 as u16, x1 as u16, color)?;
                    *counts.1 += (x1 - x0) as u32;
                } else {
                    *counts.0 += 1;
                }
                row += stride;
                if row >= end {
                    return Ok(());
                }
                ea.step();
                eb.step();
            }
            if ea.pixel() > eb.pixel() {
                // The other order (at a run's first row, or where a
                // self-intersecting polygon's edges cross): the row again,
                // the edges swapped.
                core::mem::swap(ea, eb);
                continue;
            }
            // Both edges on one pixel: an empty row.
            *counts.0 += 1;
            row += stride;
            if row >= end {
                return Ok(());
            }
            ea.step();
            eb.step();
        }
    }
    loop {
        ea.load_pixel();
        eb.load_pixel();
        let (l, r) = if ea.pixel() <= eb.pixel() {
            (ea.pixel(), eb.pixel())
        } else {
            (eb.pixel(), ea.pixel())
        };
        let (x0, x1) = if CLIP {
            (l.max(cx.0), r.min(cx.1))
        } else {
            (l, r)
        };
        if x0 < x1 {
            write_span::<BAND, T>(y, x0, x1, color, target)?;
            *counts.1 += (x1 - x0) as u32;
        } else {
            *counts.0 += 1;
        }
        y += 1;
        if y >= stop {
            return Ok(());
        }
        ea.step();
        eb.step();
    }
}

/// Writes the span `l..r` of row `y`, cut to the clip columns `cx`, and
/// counts it: the rasteriser's and the band path's
/// ([`table`](super::table)) one way to hand a span to the port.
#[inline(always)]
pub(super) fn emit_span<const BAND: bool, T: SpanTarget + ?Sized>(
    y: i32,
    l: i32,
    r: i32,
    cx: (i32, i32),
    color: T::Color,
    target: &mut T,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    let (x0, x1) = (l.max(cx.0), r.min(cx.1));
    if x0 < x1 {
        write_span::<BAND, T>(y, x0, x1, color, target)?;
        counts.span((x1 - x0) as u32);
    }
    Ok(())
}

/// Writes the span `x0..x1` (`x0 < x1`, inside the clip) of row `y`
/// (inside the clip rows). Outside a band walk the rasteriser has cut the
/// clip to the target, so the span is inside it and skips the target's
/// checks; a band walk's spans are checked by the target (but a run of
/// two edges inside the clip columns where the band holds its rows:
/// [`Walk::inside`]).
#[inline(always)]
fn write_span<const BAND: bool, T: SpanTarget + ?Sized>(
    y: i32,
    x0: i32,
    x1: i32,
    color: T::Color,
    target: &mut T,
) -> Result<(), T::Error> {
    // In 0..=4096 by the clip guarantee.
    let span = Span {
        y: y as u16,
        x0: x0 as u16,
        x1: x1 as u16,
    };
    if BAND {
        target.fill_span(span, color)
    } else {
        target.fill_span_inside(span, color)
    }
}

/// Writes the span `l..r`, cut to the clip columns `cx`, on every row of
/// `y..stop`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn emit_rows<T: SpanTarget + ?Sized>(
    y: i32,
    stop: i32,
    l: i32,
    r: i32,
    cx: (i32, i32),
    color: T::Color,
    target: &mut T,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    let (x0, x1) = (l.max(cx.0), r.min(cx.1));
    if x0 < x1 && y < stop {
        // In 0..=4096 by the clip guarantee.
        let span = Span {
            y: y as u16,
            x0: x0 as u16,
            x1: x1 as u16,
        };
        let rows = (stop - y) as u32;
        target.fill_rect(span, rows as u16, color)?;
        counts.spans += rows;
        counts.pixels += rows * (x1 - x0) as u32;
    }
    Ok(())
}

/// Sorts a polygon's edges by first row. Up to four (a triangle's, a
/// quadrilateral's) by insertion with swaps in place: a few compares,
/// where the core library's sort is a call into generic code that costs
/// a small polygon more than its compares. More by the core library's
/// sort, out of line. Equal first rows may come in any order: the walk
/// joins every edge of a row before it draws the row.
#[inline(always)]
fn sort_by_top<S: Stepper>(e: &mut [S]) {
    if e.len() > 4 {
        sort_by_top_long(e);
        return;
    }
    for i in 1..e.len() {
        let mut j = i;
        while j > 0 && e[j - 1].top() > e[j].top() {
            e.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// [`sort_by_top`] of more than four edges.
#[inline(never)]
fn sort_by_top_long<S: Stepper>(e: &mut [S]) {
    e.sort_unstable_by_key(|e| e.top());
}

/// Sorts by crossing pixel; linear when the order is the last row's.
///
/// An insertion sort costs one step per inversion: nothing on a row whose
/// order is the last row's, but `n²/2` when many edges join in another
/// order (a zigzag of `n` edges that all start on one row, listed right
/// to left) or cross on one row. So it has a budget of `4n` swaps, and
/// past it a heap sort ([`heap_sort`], `O(n log n)`, in place) finishes
/// the job. Equal pixels may come in any order: the spans are the same.
#[inline]
pub(super) fn insertion_sort<S: Stepper>(e: &mut [S]) {
    let mut budget = 4 * e.len();
    for i in 1..e.len() {
        let mut j = i;
        while j > 0 && e[j - 1].pixel() > e[j].pixel() {
            if budget == 0 {
                heap_sort(e, |a, b| a.pixel() < b.pixel());
                return;
            }
            budget -= 1;
            e.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Sorts `v` by `less` (a strict weak order) with a heap sort: in place,
/// `O(n log n)` compares whatever the order, and a few hundred bytes of
/// code (the core library's sort is tens of kilobytes per element type,
/// too much on a microcontroller for a fallback).
#[inline(never)]
pub(crate) fn heap_sort<T>(v: &mut [T], less: impl Fn(&T, &T) -> bool) {
    // Moves v[root] down the heap of v[..end].
    let sift = |v: &mut [T], mut root: usize, end: usize| loop {
        let mut child = 2 * root + 1;
        if child >= end {
            return;
        }
        if child + 1 < end && less(&v[child], &v[child + 1]) {
            child += 1;
        }
        if !less(&v[root], &v[child]) {
            return;
        }
        v.swap(root, child);
        root = child;
    };
    let n = v.len();
    for root in (0..n / 2).rev() {
        sift(v, root, n);
    }
    for end in (1..n).rev() {
        v.swap(0, end);
        sift(v, 0, end);
    }
}

/// The pixel rule for one pixel, straight from its definition: the number
/// of crossings at or left of the centre of pixel `(i, j)` is odd. `xy`
/// gives a vertex's position in units of 1/16 px. The oracle of the unit
/// tests of every stage that covers pixels.
#[cfg(test)]
pub(crate) fn rule_covers<V: Copy>(
    poly: &[V],
    xy: impl Fn(V) -> (i32, i32),
    i: i32,
    j: i32,
) -> bool {
    let (xc, yc) = (16 * i as i64 + 8, 16 * j as i64 + 8);
    let mut odd = false;
    for k in 0..poly.len() {
        let (a, b) = (xy(poly[k]), xy(poly[(k + 1) % poly.len()]));
        let (mut x0, mut y0) = (a.0 as i64, a.1 as i64);
        let (mut x1, mut y1) = (b.0 as i64, b.1 as i64);
        if y0 > y1 {
            (x0, y0, x1, y1) = (x1, y1, x0, y0);
        }
        if y0 <= yc && yc < y1 && x0 * (y1 - y0) + (yc - y0) * (x1 - x0) <= xc * (y1 - y0) {
            odd = !odd;
        }
    }
    odd
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::port::framebuffer::FrameBuffer;
    use embedded_graphics_core::pixelcolor::BinaryColor;

    const W: u16 = 48;
    const H: u16 = 40;

    /// The pixel rule for one pixel, from its definition.
    fn covers(poly: &[Vertex], i: i32, j: i32) -> bool {
        crate::raster::scan::rule_covers(poly, |v| (v.x.units(), v.y.units()), i, j)
    }

    /// Random polygons of 3 to 12 vertices (concave and self-intersecting
    /// ones included, some reaching outside the frame), each under a
    /// random clip window: every pixel is the rule's.
    #[test]
    fn fill_matches_the_pixel_rule_for_any_polygon() {
        let mut next = crate::rng::xorshift32(0x2545_f491);
        let mut rnd = |m: u32| next() % m;
        let mut px = [BinaryColor::Off; W as usize * H as usize];
        let mut slots = [Edge::EMPTY; 12];
        for _ in 0..1500 {
            let n = 3 + rnd(10) as usize;
            let mut poly = [Vertex::default(); 12];
            for v in poly.iter_mut().take(n) {
                let x = rnd((W as u32 + 8) * 16) as i16 - 64;
                let y = rnd((H as u32 + 8) * 16) as i16 - 64;
                *v = Vertex::from_bits(x, y);
            }
            let poly = &poly[..n];
            let (x0, y0) = (rnd(W as u32) as i32, rnd(H as u32) as i32);
            let (x1, y1) = (x0 + rnd(W as u32) as i32, y0 + rnd(H as u32) as i32);
            let clip = ClipRect::from_window(
                crate::raster::clip::ClipWindow {
                    x0: x0 as i16,
                    y0: y0 as i16,
                    x1: x1 as i16,
                    y1: y1 as i16,
                },
                W,
                H,
            );
            px.fill(BinaryColor::Off);
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let counts = Rasterizer::new(&mut slots)
                .fill(poly.iter().copied(), &clip, BinaryColor::On, &mut fb)
                .unwrap();
            let mut covered = 0;
            for j in 0..H as i32 {
                for i in 0..W as i32 {
                    let want = clip.contains(i, j) && covers(poly, i, j);
                    let got = fb.pixel(i as u16, j as u16) == Some(BinaryColor::On);
                    assert_eq!(got, want, "{poly:?} clip {clip:?} pixel ({i}, {j})");
                    covered += want as u32;
                }
            }
            assert_eq!(counts.pixels, covered);
        }
    }

    /// Zigzags of many edges that all start on one row, listed right to
    /// left (the insertion sort's worst order, past its budget), and
    /// random many-edged polygons whose edges cross on many rows: every
    /// pixel is the rule's.
    #[test]
    fn many_edges_out_of_order_match_the_pixel_rule() {
        let mut next = crate::rng::xorshift32(0x1357_9bdf);
        let mut rnd = |m: u32| next() % m;
        let mut px = [BinaryColor::Off; W as usize * H as usize];
        let mut slots = [Edge::EMPTY; 200];
        let clip = ClipRect::full(W, H);
        for case in 0..60 {
            let n = 40 + rnd(160) as usize;
            let mut poly = [Vertex::default(); 200];
            for (k, v) in poly.iter_mut().take(n).enumerate() {
                *v = if case % 2 == 0 {
                    // Right to left, top and bottom in turn.
                    let x = (W as i32 * 16 - 1) * (n - 1 - k) as i32 / (n - 1) as i32;
                    let y = if k % 2 == 0 { 3 } else { H as i32 * 16 - 5 };
                    Vertex::from_bits(x as i16, y as i16)
                } else {
                    let x = rnd(W as u32 * 16) as i16;
                    let y = rnd(H as u32 * 16) as i16;
                    Vertex::from_bits(x, y)
                };
            }
            let poly = &poly[..n];
            px.fill(BinaryColor::Off);
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            Rasterizer::new(&mut slots)
                .fill(poly.iter().copied(), &clip, BinaryColor::On, &mut fb)
                .unwrap();
            for j in 0..H as i32 {
                for i in 0..W as i32 {
                    let got = fb.pixel(i as u16, j as u16) == Some(BinaryColor::On);
                    assert_eq!(got, covers(poly, i, j), "case {case} pixel ({i}, {j})");
                }
            }
        }
    }

    /// A clip window made for a larger frame than the target: spans are
    /// cut to the target once a polygon, and every pixel of the target is
    /// the rule's (none written past it).
    #[test]
    fn a_target_smaller_than_the_clip_gets_the_rule_inside_it() {
        let mut px = [BinaryColor::Off; W as usize * H as usize];
        let mut slots = [Edge::EMPTY; 8];
        let big = ClipRect::full(W + 20, H + 13);
        let polys: [&[Vertex]; 3] = [
            // Reaches past the right and bottom sides, slanted.
            &[
                Vertex::from_bits(100, 40),
                Vertex::from_bits(W as i16 * 16 + 200, 90),
                Vertex::from_bits(500, H as i16 * 16 + 150),
            ],
            // A rectangle past both sides (the two-vertical-edge path).
            &[
                Vertex::from_bits(40, 40),
                Vertex::from_bits(W as i16 * 16 + 100, 40),
                Vertex::from_bits(W as i16 * 16 + 100, H as i16 * 16 + 100),
                Vertex::from_bits(40, H as i16 * 16 + 100),
            ],
            // Concave, four edges on some rows.
            &[
                Vertex::from_bits(0, 0),
                Vertex::from_bits(W as i16 * 16 + 300, 60),
                Vertex::from_bits(200, 300),
                Vertex::from_bits(W as i16 * 16 + 300, H as i16 * 16 + 250),
                Vertex::from_bits(20, H as i16 * 16 + 200),
            ],
        ];
        for poly in polys {
            px.fill(BinaryColor::Off);
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let counts = Rasterizer::new(&mut slots)
                .fill(poly.iter().copied(), &big, BinaryColor::On, &mut fb)
                .unwrap();
            let mut covered = 0;
            for j in 0..H as i32 {
                for i in 0..W as i32 {
                    let want = covers(poly, i, j);
                    let got = fb.pixel(i as u16, j as u16) == Some(BinaryColor::On);
                    assert_eq!(got, want, "{poly:?} pixel ({i}, {j})");
                    covered += want as u32;
                }
            }
            assert_eq!(counts.pixels, covered);
        }
    }

    /// Bow-ties: two edges that cross inside one run of two (the row loop
    /// takes one as the left edge and swaps them where they cross), at
    /// many slopes and crossing rows, under the whole frame and a narrow
    /// clip: every pixel is the rule's, and the counts are its pixels.
    #[test]
    fn edges_crossing_inside_a_run_match_the_pixel_rule() {
        let mut px = [BinaryColor::Off; W as usize * H as usize];
        let mut slots = [Edge::EMPTY; 4];
        let clips = [
            ClipRect::full(W, H),
            ClipRect::from_window(
                crate::raster::clip::ClipWindow {
                    x0: 9,
                    y0: 3,
                    x1: 30,
                    y1: 35,
                },
                W,
                H,
            ),
        ];
        for clip in clips {
            for k in 0..200i16 {
                let (x0, x1) = (k % 23 * 13 - 40, W as i16 * 16 + 40 - k % 17 * 11);
                let (y0, y1) = (k % 7 * 9 - 20, H as i16 * 16 - k % 11 * 19);
                // Top and bottom sides horizontal: on every row the two
                // slanted edges alone, crossing once.
                let poly = [
                    Vertex::from_bits(x0, y0),
                    Vertex::from_bits(x1, y1),
                    Vertex::from_bits(x0 + k % 9 * 20, y1),
                    Vertex::from_bits(x1 - k % 5 * 30, y0),
                ];
                px.fill(BinaryColor::Off);
                let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
                let counts = Rasterizer::new(&mut slots)
                    .fill(poly.iter().copied(), &clip, BinaryColor::On, &mut fb)
                    .unwrap();
                let mut covered = 0;
                for j in 0..H as i32 {
                    for i in 0..W as i32 {
                        let want = clip.contains(i, j) && covers(&poly, i, j);
                        let got = fb.pixel(i as u16, j as u16) == Some(BinaryColor::On);
                        assert_eq!(got, want, "{poly:?} clip {clip:?} pixel ({i}, {j})");
                        covered += want as u32;
                    }
                }
                assert_eq!(counts.pixels, covered, "{poly:?}");
            }
        }
    }

    #[test]
    fn heap_sort_sorts() {
        let mut next = crate::rng::xorshift32(0x9e37_79b9);
        for n in 0..70 {
            let mut v = [0u32; 70];
            for x in v.iter_mut().take(n) {
                *x = next() % (1 + n as u32 / 2);
            }
            let mut want = v;
            want[..n].sort_unstable();
            heap_sort(&mut v[..n], |a, b| a < b);
            assert_eq!(v[..n], want[..n]);
        }
    }
}
