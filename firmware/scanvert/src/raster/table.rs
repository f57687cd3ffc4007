//! The 2D edge table: every polygon and line of a display list set up
//! once and stepped down the frame band by band, for rendering without a
//! frame buffer ([`port::band`](crate::port::band)).
//!
//! # One pass
//!
//! [`EdgeTable::build`] reads the list once, through its one 2D
//! interpreter ([`DisplayList::draws`](crate::display_list::DisplayList::draws)).
//! Every `poly` and `line` after
//! the last `clear` (what comes before it is covered by it: a `clear`
//! empties the table) is entered, in list order, with its colour and the
//! clip registers (and, for a polygon, the fill rule) in force at its
//! place. A polygon's edges are set up
//! exactly as [`Rasterizer::fill`](crate::raster::scan::Rasterizer::fill)
//! sets them up (the exact [`Edge`], restricted to the clip rows, sorted by
//! first row; those of its first row are made active, as its walk's first
//! step would), so it covers exactly the same pixels; a line is the
//! [`Line`] generator [`draw_line`](crate::raster::line::draw_line) steps,
//! cut to the same clip, so it writes exactly the same spans. The entries
//! are then ordered by first row (an index array; the entries stay in list
//! order).
//!
//! [`EdgeTable::draw`] draws rows `y0..y1`: the entries whose first row
//! has come join the live set, a bit per entry in list order (so joining
//! is setting a bit: no sort, no merge); each live entry in that order
//! (painter's order: the band holds all its rows, so a later entry covers
//! an earlier one on every row), found word by word, emits its spans on
//! the band's rows and keeps its state (a polygon's active edges, a line's
//! row), stepped to `y1`, for the next band; entries past their last row
//! leave (their bit is cleared). A polygon walks its rows with the full
//! frame's own loop (`raster::scan`'s `Walk`); where a run of two edges
//! meets the band's end and both go on, they are stepped to the next
//! band's first row and the walk is left at once. A polygon's last row
//! of a band (every row of a one-row band, as racing the beam composes
//! them) whose two active edges both go on past it, with no edge joining
//! on it, is drawn without the walk: one span, both edges stepped in
//! place.
//! [`EdgeTable::skip`] steps the same way without emitting anything.
//! Nothing is set up again, and the list is not read again.
//!
//! # Memory
//!
//! All of it is the caller's ([`TableMemory`]): a [`TablePolygon`] (24
//! bytes on 32-bit targets) and two `u32`s per entry (the order by first
//! row, and the live set, which takes one bit an entry of its half;
//! `build` counts the entries by first row there first), an [`Edge`] (24
//! bytes) per edge of the polygons and an `Option<`[`Line`]`>` (48 bytes)
//! per line; [`DisplayList::table_needs`](crate::display_list::DisplayList::table_needs)
//! counts them for a list, as an upper bound
//! (one edge per vertex, every line entered).
//! Running out is a [`TableError`] found by `build`, before anything is
//! drawn.

use crate::color::ListColor;
use crate::fixed::Vertex;
use crate::port::runs::Rows;
use crate::port::Counts;
use crate::port::{Span, SpanTarget};
use crate::raster::draw::Draw;
use crate::raster::edge::{Edge, Stepper};
use crate::raster::line::Line;
use crate::raster::scan::{build_edges, two_edge_rows_in, Walk};
use crate::raster::winding::FillRule;
use core::fmt;
use embedded_graphics_core::pixelcolor::Rgb888;

/// One entry of the table: a polygon or a line. The caller provides the
/// array, filled with [`TablePolygon::EMPTY`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TablePolygon {
    /// A polygon's first edge slot; a line's slot.
    first: u32,
    /// A polygon's edges, from `first` (at least two); 0 for a line.
    n: u16,
    /// `edges[..active]` are active, `edges[active..next]` finished,
    /// `edges[next..]` wait for their first row.
    active: u16,
    next: u16,
    /// The next row it works on (its first row until it starts).
    y: i32,
    /// The clip rectangle's columns.
    x0: u16,
    x1: u16,
    color: Rgb888,
    /// A polygon's fill rule.
    rule: FillRule,
}

impl TablePolygon {
    /// An unused entry.
    pub const EMPTY: TablePolygon = TablePolygon {
        first: 0,
        n: 0,
        active: 0,
        next: 0,
        y: 0,
        x0: 0,
        x1: 0,
        color: Rgb888::new(0, 0, 0),
        rule: FillRule::EvenOdd,
    };

    /// `true` for a line.
    fn is_line(&self) -> bool {
        self.n == 0
    }

    /// `true` when a polygon's every edge has been used up.
    fn done(&self) -> bool {
        self.active == 0 && self.next == self.n
    }
}

/// The caller's memory for an [`EdgeTable`];
/// [`DisplayList::table_needs`](crate::display_list::DisplayList::table_needs)
/// sizes it.
#[derive(Debug)]
pub struct TableMemory<'a> {
    /// One entry per polygon and line after the last `clear`.
    pub polygons: &'a mut [TablePolygon],
    /// The live set (a bit an entry) and the order by first row: twice
    /// as many as `polygons`.
    pub index: &'a mut [u32],
    /// Every edge of those polygons.
    pub edges: &'a mut [Edge],
    /// Those lines, filled with `None`.
    pub lines: &'a mut [Option<Line>],
}

/// What the table of a list needs, from
/// [`DisplayList::table_needs`](crate::display_list::DisplayList::table_needs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TableNeeds {
    /// `poly`s and `line`s after the last `clear`: entries (and twice as
    /// many index entries).
    pub polygons: usize,
    /// The `poly`s' vertices: edge slots.
    pub edges: usize,
    /// The `line`s: line slots.
    pub lines: usize,
}

impl TableNeeds {
    /// Counts the table memory of `draws` (a list's
    /// [`draws`](crate::display_list::DisplayList::draws); see
    /// [`table_needs`](crate::display_list::DisplayList::table_needs)): the
    /// polygons and lines after the last clear, the polygons' vertices (an
    /// upper bound of their edges).
    pub fn count<V, I>(draws: I) -> TableNeeds
    where
        I: IntoIterator<Item = (usize, Draw<V>)>,
        V: IntoIterator<Item = Vertex>,
        V::IntoIter: ExactSizeIterator,
    {
        let mut n = TableNeeds::default();
        // One pass: a clear drops what came before it.
        for (_, draw) in draws {
            match draw {
                Draw::Clear(_) => n = TableNeeds::default(),
                Draw::Poly { vertices, .. } => {
                    n.polygons += 1;
                    n.edges += vertices.into_iter().len();
                }
                Draw::Line { .. } => {
                    n.polygons += 1;
                    n.lines += 1;
                }
            }
        }
        n
    }
}

/// The table ran out of memory at the `poly` or `line` at `offset`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TableError {
    /// Polygon (and index) entries.
    Polygons {
        /// Byte offset of the `poly` in the list.
        offset: usize,
        /// Entries available.
        capacity: usize,
    },
    /// Edge slots.
    Edges {
        /// Byte offset of the `poly` in the list.
        offset: usize,
        /// Slots available.
        capacity: usize,
    },
    /// Line slots.
    Lines {
        /// Byte offset of the `line` in the list.
        offset: usize,
        /// Slots available.
        capacity: usize,
    },
}

impl TableError {
    /// Byte offset of the `poly` or `line` at fault.
    pub fn offset(&self) -> usize {
        match *self {
            TableError::Polygons { offset, .. }
            | TableError::Edges { offset, .. }
            | TableError::Lines { offset, .. } => offset,
        }
    }
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableError::Polygons { capacity, .. } => write!(
                f,
                "the edge table holds {capacity} polygons and lines; the list has more"
            ),
            TableError::Edges { capacity, .. } => write!(
                f,
                "the edge table holds {capacity} edges; the list's polygons have more"
            ),
            TableError::Lines { capacity, .. } => write!(
                f,
                "the edge table holds {capacity} lines; the list has more"
            ),
        }
    }
}

impl core::error::Error for TableError {}

/// The polygons and lines of a display list after its last `clear`, set
/// up once, drawn band by band. See the [module](self) docs.
#[derive(Debug)]
#[doc(hidden)]
pub struct EdgeTable<'a> {
    polygons: &'a mut [TablePolygon],
    /// `index[..count.div_ceil(32)]`: the live set, bit `k % 32` of word
    /// `k / 32` for entry `k` (entries are in list order);
    /// `index[cap..cap + count]`: all of them by first row, of which the
    /// first `entered` have entered.
    index: &'a mut [u32],
    edges: &'a mut [Edge],
    lines: &'a mut [Option<Line>],
    cap: usize,
    count: usize,
    /// Of the `count` entries, lines.
    nlines: usize,
    entered: usize,
    /// The next row to draw or skip.
    y: i32,
    clear: Option<Rgb888>,
    commands: u32,
}

impl<'a> EdgeTable<'a> {
    /// A table of nothing, over no memory: the place a table is built
    /// into.
    pub(crate) fn empty() -> Self {
        EdgeTable {
            polygons: &mut [],
            index: &mut [],
            edges: &mut [],
            lines: &mut [],
            cap: 0,
            count: 0,
            nlines: 0,
            entered: 0,
            y: 0,
            clear: None,
            commands: 0,
        }
    }

    /// Enters every polygon and line of `draws` after the last clear, on
    /// a frame `height` rows high: a list's
    /// [`draws`](crate::display_list::DisplayList::draws) on its frame cut
    /// to the target's. `commands` is the list's count of commands, kept
    /// for the statistics ([`commands`](Self::commands)).
    ///
    /// Kept out of line: it runs once a frame, and inlined into a band
    /// render it changes how the render's pixel loops are compiled.
    #[inline(never)]
    pub fn build<V, I>(
        mem: TableMemory<'a>,
        draws: I,
        h: u16,
        commands: u32,
    ) -> Result<Self, TableError>
    where
        I: IntoIterator<Item = (usize, Draw<V>)>,
        V: IntoIterator<Item = Vertex>,
    {
        let TableMemory {
            polygons,
            index,
            edges,
            lines,
        } = mem;
        let cap = polygons.len().min(index.len() / 2);
        let (mut count, mut used, mut nlines) = (0usize, 0usize, 0usize);
        // One pass: a `clear` empties the table (it covers everything
        // before it), and running out of memory counts only if no `clear`
        // follows.
        let mut clear = None;
        let mut full: Option<TableError> = None;
        for (offset, draw) in draws {
            match draw {
                Draw::Clear(c) => {
                    (count, used, nlines, full, clear) = (0, 0, 0, None, Some(c));
                }
                Draw::Poly {
                    vertices,
                    rule,
                    clip,
                    color,
                } if full.is_none() && !clip.is_empty() => {
                    let room = &mut edges[used..];
                    let built = match rule {
                        FillRule::EvenOdd => build_edges::<false, _>(room, vertices, &clip),
                        FillRule::NonZero => build_nonzero(room, vertices, &clip),
                    };
                    let Some(n) = built else {
                        full = Some(TableError::Edges {
                            offset,
                            capacity: edges.len(),
                        });
                        continue;
                    };
                    if n < 2 {
                        continue;
                    }
                    if count >= cap {
                        full = Some(TableError::Polygons {
                            offset,
                            capacity: cap,
                        });
                        continue;
                    }
                    let e = &mut room[..n];
                    e.sort_unstable_by_key(|e| e.top());
                    // The edges of its first row active already (at least
                    // two), as its walk's first step would make them: its
                    // every visit then starts with active edges.
                    let y = e[0].top();
                    let m = e.iter().take_while(|e| e.top() <= y).count() as u16;
                    polygons[count] = TablePolygon {
                        first: used as u32,
                        n: n as u16,
                        active: m,
                        next: m,
                        y,
                        x0: clip.x0(),
                        x1: clip.x1(),
                        color,
                        rule,
                    };
                    count += 1;
                    used += n;
                }
                Draw::Line {
                    from,
                    to,
                    clip,
                    color,
                } if full.is_none() => {
                    // As `draw_line`: nothing when no pixel is in the clip.
                    let Some(line) = Line::new(from, to, &clip) else {
                        continue;
                    };
                    let Some(slot) = lines.get_mut(nlines) else {
                        full = Some(TableError::Lines {
                            offset,
                            capacity: lines.len(),
                        });
                        continue;
                    };
                    if count >= cap {
                        full = Some(TableError::Polygons {
                            offset,
                            capacity: cap,
                        });
                        continue;
                    }
                    *slot = Some(line);
                    polygons[count] = TablePolygon {
                        first: nlines as u32,
                        y: line.top(),
                        color,
                        ..TablePolygon::EMPTY
                    };
                    count += 1;
                    nlines += 1;
                }
                _ => {}
            }
        }
        if let Some(e) = full {
            return Err(e);
        }
        // The order by first row: a counting sort over the rows when the
        // live set (unused yet) can hold a counter a row, else a sort.
        let (live, order) = index.split_at_mut(cap);
        let order = &mut order[..count];
        let rows = h as usize;
        if let Some(at) = live.get_mut(..rows + 1) {
            // First rows lie in the clip rows, inside 0..h.
            let row = |p: &TablePolygon| (p.y.max(0) as usize).min(rows - 1);
            at.fill(0);
            for p in &polygons[..count] {
                at[row(p) + 1] += 1;
            }
            for r in 1..=rows {
                at[r] += at[r - 1];
            }
            for (k, p) in polygons[..count].iter().enumerate() {
                let slot = &mut at[row(p)];
                order[*slot as usize] = k as u32;
                *slot += 1;
            }
        } else {
            for (k, o) in order.iter_mut().enumerate() {
                *o = k as u32;
            }
            order.sort_unstable_by_key(|&k| polygons[k as usize].y);
        }
        // The live set, empty: a bit an entry (count ≤ cap).
        live[..count.div_ceil(32)].fill(0);
        Ok(EdgeTable {
            polygons,
            index,
            edges,
            lines,
            cap,
            count,
            nlines,
            entered: 0,
            y: 0,
            clear,
            commands,
        })
    }

    /// Entries: polygons and lines entered.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Lines entered.
    pub fn lines(&self) -> usize {
        self.nlines
    }

    /// `true` when no polygon or line draws anything.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Commands in the list.
    pub fn commands(&self) -> u32 {
        self.commands
    }

    /// The colour of the list's last `clear`.
    pub fn clear_color(&self) -> Option<Rgb888> {
        self.clear
    }

    /// The next row [`draw`](Self::draw) or [`skip`](Self::skip) starts at.
    pub fn next_row(&self) -> i32 {
        self.y
    }

    /// Draws rows `self.next_row()..y1` of every polygon and line into
    /// `target`, in painter's order, and keeps their state for the rows
    /// after.
    pub fn draw<T>(&mut self, y1: i32, target: &mut T) -> Result<Counts, T::Error>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        self.advance(y1, Some(target), false)
    }

    /// [`draw`](Self::draw) of the rows up to the end of `band`'s. Where
    /// the band holds every row drawn (it starts at or above
    /// [`next_row`](Self::next_row)) and more than one, a run of two edges inside its
    /// polygon's clip columns is written row by row from the row's start,
    /// with no check a span ([`SpanTarget::row_start`]).
    pub(crate) fn draw_band<T>(&mut self, band: &mut T) -> Result<Counts, T::Error>
    where
        T: Rows + ?Sized,
        T::Color: ListColor,
    {
        // A band of one row gains nothing from a row's start: its runs
        // are one row each.
        let inside = band.count() > 1 && i32::from(band.first()) <= self.y;
        self.advance(i32::from(band.end()), Some(band), inside)
    }

    /// Steps every polygon and line to row `y1` without drawing.
    pub fn skip(&mut self, y1: i32) {
        // `None` of a target that cannot fail.
        let _ = self.advance::<crate::port::band::Band<'_, Rgb888>>(y1, None, false);
    }

    /// Rows `self.y..y1` of every entry, drawn into `target` or only
    /// stepped; `inside` when the target holds all of them
    /// ([`Walk::inside`]).
    fn advance<T>(
        &mut self,
        y1: i32,
        mut target: Option<&mut T>,
        inside: bool,
    ) -> Result<Counts, T::Error>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        let mut counts = Counts::default();
        if y1 <= self.y || self.count == 0 {
            self.y = self.y.max(y1);
            return Ok(counts);
        }
        // Enter the polygons starting above y1: a bit each in the live set.
        let (live, order) = self.index.split_at_mut(self.cap);
        let entering = order.get(self.entered..self.count).unwrap_or(&[]);
        for &k in entering {
            match self.polygons.get(k as usize) {
                Some(p) if p.y < y1 => {}
                _ => break,
            }
            if let Some(word) = live.get_mut(k as usize / 32) {
                *word |= 1 << (k % 32);
            }
            self.entered += 1;
        }
        // The live entries in list order: word by word, bit by bit; an
        // entry past its last row leaves (its bit cleared, with no
        // branch). A machine word at a time: two `u32`s on a 64-bit host,
        // half the loop exits (the one branch a word costs that a
        // predictor misses).
        const K: usize = (usize::BITS / 32) as usize;
        let words = self.count.div_ceil(32);
        for (w, pair) in live[..words].chunks_mut(K).enumerate() {
            let mut bits = 0usize;
            for (j, &x) in pair.iter().enumerate() {
                bits |= (x as usize) << (32 * j);
            }
            let mut keep = bits;
            while bits != 0 {
                let b = bits.trailing_zeros();
                bits &= bits - 1;
                let i = w * usize::BITS as usize + b as usize;
                let Some(p) = self.polygons.get_mut(i) else {
                    break;
                };
                let color = target.as_ref().map(|_| T::Color::from_rgb888(p.color));
                let done = if p.is_line() {
                    match self
                        .lines
                        .get_mut(p.first as usize)
                        .and_then(Option::as_mut)
                    {
                        Some(line) => {
                            run_line(line, y1, color, target.as_deref_mut(), &mut counts)?;
                            p.y = line.row();
                            line.row() >= line.end()
                        }
                        // Entered with its line: never.
                        None => true,
                    }
                } else {
                    let edges = &mut self.edges[p.first as usize..p.first as usize + p.n as usize];
                    let one =
                        last_row_of_two(p, edges, y1, color, target.as_deref_mut(), &mut counts)?;
                    let paint = target.as_deref_mut().zip(color);
                    if !one && !band_of_two(p, edges, y1, paint, inside, &mut counts)? {
                        let paint = target.as_deref_mut().zip(color);
                        run(p, edges, y1, paint, inside, &mut counts)?;
                    }
                    p.done()
                };
                keep &= !((done as usize) << b);
            }
            for (j, x) in pair.iter_mut().enumerate() {
                *x = (keep >> (32 * j)) as u32;
            }
        }
        self.y = y1;
        Ok(counts)
    }
}

/// Rows `p.y..y1` of one polygon, walked as
/// [`Rasterizer::fill`](crate::raster::scan::Rasterizer::fill) walks them
/// (the same [`Walk`]), drawn into the target of `paint` (or only
/// stepped without one; `inside` as [`Walk::inside`]); its state is left
/// for row `y1`.
#[inline]
fn run<T: SpanTarget + ?Sized>(
    p: &mut TablePolygon,
    edges: &mut [Edge],
    y1: i32,
    paint: Option<(&mut T, T::Color)>,
    inside: bool,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    let mut walk = Walk {
        active: p.active as usize,
        next: p.next as usize,
        y: p.y,
        inside,
    };
    let cx = (p.x0 as i32, p.x1 as i32);
    match p.rule {
        FillRule::EvenOdd => walk.run::<true, false, _, _>(edges, y1, cx, paint, counts)?,
        FillRule::NonZero => run_nonzero(&mut walk, edges, y1, cx, paint, counts)?,
    }
    // At most `n` (a `u16`).
    p.active = walk.active as u16;
    p.next = walk.next as u16;
    p.y = walk.y;
    Ok(())
}

/// Rows `p.y..y1` of a polygon of two active edges by the even-odd rule,
/// drawn into the target of `paint` between its edges, cut to the clip
/// columns, where the band holds no more than a triangle's walk: both
/// edges go on past the band (they are stepped to row `y1`); or both end
/// on one row in it, with no edge left to come (the polygon is done);
/// or one ends where the polygon's third and last edge starts, and that
/// one and the other then go on past the band or end together in it (a
/// triangle's middle vertex). This is what [`run`] does for such a band
/// (every band a triangle crosses but where a vertex lies on its first
/// row), without the walk's loop, its copies of the edges and its checks
/// for edges joining or leaving (a band's last row alone is
/// [`last_row_of_two`]'s). `inside` as [`Walk::inside`]. `false`,
/// with nothing done, for any other polygon or band, and without a
/// target where an edge ends in the band.
#[inline(always)]
fn band_of_two<T: SpanTarget + ?Sized>(
    p: &mut TablePolygon,
    edges: &mut [Edge],
    y1: i32,
    paint: Option<(&mut T, T::Color)>,
    inside: bool,
    counts: &mut Counts,
) -> Result<bool, T::Error> {
    if p.active != 2 || p.rule != FillRule::EvenOdd || p.y >= y1 {
        return Ok(false);
    }
    let (y, next) = (p.y, p.next as usize);
    let [a, b, rest @ ..] = edges else {
        return Ok(false);
    };
    let waiting = rest.get(next.wrapping_sub(2));
    let joins = waiting.filter(|e| e.top() < y1);
    // A rectangle's sides (one span down the rows, written at once) are
    // the walk's.
    if a.is_vertical() && b.is_vertical() {
        return Ok(false);
    }
    let Some((t, color)) = paint else {
        // Stepped only, where the edges go on past the band.
        if joins.is_some() || a.end() <= y1 || b.end() <= y1 {
            return Ok(false);
        }
        for _ in y..y1 {
            a.step();
            b.step();
        }
        p.y = y1;
        return Ok(true);
    };
    // The rows drawn between `a` and `b` first (to the band's end, the
    // polygon's, or the middle vertex's row), and the triangle's third
    // edge with the row it starts on, if it joins in the band.
    let (first, then) = match joins {
        None => {
            let stop = a.end().min(b.end());
            if stop > y1 {
                // Both go on past the band.
                (y1, None)
            } else if a.end() == b.end() && waiting.is_none() {
                // The polygon's last rows.
                (stop, None)
            } else {
                return Ok(false);
            }
        }
        Some(c) => {
            // A triangle's middle vertex at row m: one edge ends there,
            // the last edge starts there, and it ends with the other.
            let m = c.top();
            let last = (a.end() == m) != (b.end() == m) && next + 1 == p.n as usize;
            if !last || m <= y || c.end() != a.end().max(b.end()) {
                return Ok(false);
            }
            (m, Some(*c))
        }
    };
    let cx = (p.x0 as i32, p.x1 as i32);
    let (mut empty, mut pixels) = (0u32, 0u32);
    let c = (&mut empty, &mut pixels);
    two_edge_rows_in(inside, (&mut *a, &mut *b), (y, first), cx, color, t, c)?;
    let (a, b, stop) = match then {
        None => (a, b, first),
        Some(c) => {
            // The pair may come back swapped: the one that ends at the
            // middle vertex is found again, and the third edge takes its
            // place.
            let (short, long) = if a.end() == first { (a, b) } else { (b, a) };
            *short = c;
            long.step();
            p.next += 1;
            let stop = c.end().min(y1);
            let n = (&mut empty, &mut pixels);
            two_edge_rows_in(
                inside,
                (&mut *short, &mut *long),
                (first, stop),
                cx,
                color,
                t,
                n,
            )?;
            (short, long, stop)
        }
    };
    if stop < y1 || a.end() == y1 {
        // Both end on the band's rows (together, checked above).
        p.active = 0;
    } else {
        a.step();
        b.step();
    }
    p.y = stop;
    let spans = (stop - y) as u32 - empty;
    counts.spans = counts.spans.saturating_add(spans);
    counts.pixels = counts.pixels.saturating_add(pixels);
    Ok(true)
}

/// Row `y1 − 1` of a polygon on that row (its walk at `y1 − 1`) whose
/// two active edges both go on past it and whose next edge starts at
/// `y1` or below, by the even-odd rule: the span between the two
/// crossings, cut to the clip columns, drawn into `target` (or nothing
/// without one), and both edges stepped to row `y1`. This is what
/// [`run`] does for such a row (the last row of a band, every row of a
/// racing row's one-row band), without the walk's loop, its copies of
/// the edges and its checks for edges joining or leaving; bands of more
/// rows are [`band_of_two`]'s. `false`, with nothing done, for any other
/// polygon or row.
#[inline(always)]
fn last_row_of_two<T: SpanTarget + ?Sized>(
    p: &mut TablePolygon,
    edges: &mut [Edge],
    y1: i32,
    color: Option<T::Color>,
    target: Option<&mut T>,
    counts: &mut Counts,
) -> Result<bool, T::Error> {
    if p.active != 2 || p.rule != FillRule::EvenOdd || p.y.wrapping_add(1) != y1 {
        return Ok(false);
    }
    let joins = edges.get(p.next as usize).is_some_and(|e| e.top() < y1);
    let [a, b, ..] = edges else {
        return Ok(false);
    };
    if joins || a.end() <= y1 || b.end() <= y1 {
        return Ok(false);
    }
    if let (Some(t), Some(color)) = (target, color) {
        a.load_pixel();
        b.load_pixel();
        let (l, r) = if a.pixel() <= b.pixel() {
            (a.pixel(), b.pixel())
        } else {
            (b.pixel(), a.pixel())
        };
        let (x0, x1) = (l.max(p.x0 as i32), r.min(p.x1 as i32));
        if x0 < x1 {
            // In 0..=4096 by the clip guarantee, as the walk's spans.
            let span = Span {
                y: p.y as u16,
                x0: x0 as u16,
                x1: x1 as u16,
            };
            t.fill_span(span, color)?;
            counts.span((x1 - x0) as u32);
        }
    }
    a.step();
    b.step();
    p.y = y1;
    Ok(true)
}

/// [`build_edges`] for a walk by the non-zero rule, out of line: the
/// even-odd set-up, inlined into the table's build, is compiled as it
/// would be without it.
#[inline(never)]
fn build_nonzero<V: IntoIterator<Item = Vertex>>(
    edges: &mut [Edge],
    vertices: V,
    clip: &crate::raster::clip::ClipRect,
) -> Option<usize> {
    build_edges::<true, _>(edges, vertices, clip)
}

/// [`Walk::run`] by the non-zero rule, out of line: the even-odd walk,
/// inlined into the band loop, is compiled as it would be without it.
#[inline(never)]
fn run_nonzero<T: SpanTarget + ?Sized>(
    walk: &mut Walk,
    edges: &mut [Edge],
    y1: i32,
    cx: (i32, i32),
    paint: Option<(&mut T, T::Color)>,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    walk.run::<true, true, _, _>(edges, y1, cx, paint, counts)
}

/// Rows `line.row()..y1` of one line, as
/// [`draw_line`](crate::raster::line::draw_line) writes them, drawn into
/// `target` (or only stepped without one); it is left at row `y1` (or
/// its end).
#[inline]
fn run_line<T: SpanTarget + ?Sized>(
    line: &mut Line,
    y1: i32,
    color: Option<T::Color>,
    mut target: Option<&mut T>,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    while line.row() < y1.min(line.end()) {
        if let (Some(t), Some(color), Some((x0, x1))) = (target.as_deref_mut(), color, line.span())
        {
            t.fill_span(
                Span {
                    y: line.row() as u16,
                    x0: x0 as u16,
                    x1: x1 as u16,
                },
                color,
            )?;
            counts.spans += 1;
            counts.pixels += (x1 - x0) as u32;
        }
        line.step();
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::display_list::{Command, DisplayList, Writer};
    use crate::fixed::Vertex;
    use crate::raster::clip::ClipRect;

    #[test]
    fn needs_count_what_follows_the_last_clear() {
        // Random lists of `clear`, `poly`, `line`, `color` and `poly3`:
        // the one pass counts what a count after the last `clear` counts.
        let mut rng = testkit::rng::Rng(0x7ab1e);
        let mut bytes = [0u8; 2048];
        for _ in 0..500 {
            let mut w = Writer::new(&mut bytes, 32, 32).unwrap();
            for _ in 0..rng.range(0, 12) {
                let k = rng.range(3, 9) as i16;
                let v = (0..k).map(|i| Vertex::from_bits(16 * i, 3 * i * i));
                match rng.below(5) {
                    0 => w.clear(Rgb888::new(1, 2, 3)),
                    1 => w.poly(v),
                    2 => w.line(Vertex::from_bits(0, 0), Vertex::from_bits(k, 99)),
                    3 => w.color(Rgb888::new(4, 5, 6)),
                    _ => w.poly3(v.map(|v| crate::fixed::Vertex3 {
                        x: v.x,
                        y: v.y,
                        z: v.x,
                    })),
                }
                .unwrap();
            }
            let list = DisplayList::new_checked(w.finish()).unwrap();
            let last = list
                .commands()
                .filter(|(_, c)| matches!(c, Command::Clear(_)))
                .map(|(o, _)| o)
                .last();
            let mut want = TableNeeds::default();
            for (offset, cmd) in list.commands() {
                let counted = last.is_none_or(|c| offset > c);
                match cmd {
                    Command::Poly(v) if counted => {
                        want.polygons += 1;
                        want.edges += v.len();
                    }
                    Command::Line(..) if counted => {
                        want.polygons += 1;
                        want.lines += 1;
                    }
                    _ => {}
                }
            }
            assert_eq!(list.table_needs(), want);
        }
    }

    #[test]
    fn bands_and_skips_over_many_entries_give_the_full_frames_rows() {
        // Lists of up to 300 small triangles, rectangles, hexagons and
        // lines (live sets across several words, entries leaving at every
        // bit position), drawn in bands of random heights with rows
        // skipped between some: every drawn row is the one the rasteriser
        // and `draw_line` draw in list order.
        use crate::port::framebuffer::FrameBuffer;
        use crate::raster::line::draw_line;
        use crate::raster::scan::Rasterizer;
        const W: u16 = 64;
        const H: u16 = 48;
        let mut rng = testkit::rng::Rng(0xb175);
        let mut bytes = [0u8; 16384];
        let mut want = [Rgb888::new(0, 0, 0); W as usize * H as usize];
        let mut got = [Rgb888::new(0, 0, 0); W as usize * H as usize];
        for _ in 0..40 {
            let mut w = Writer::new(&mut bytes, W, H).unwrap();
            for k in 0..rng.range(1, 300) {
                w.color(Rgb888::new(k as u8, (k >> 8) as u8, 7)).unwrap();
                let x = rng.range(0, W as i32 * 16) as i16 - 64;
                let y = rng.range(0, H as i32 * 16) as i16 - 64;
                let kind = rng.below(8);
                let (dx, dy) = (rng.range(0, 256) as i16, rng.range(0, 256) as i16);
                let mut v = || {
                    Vertex::from_bits(x + rng.range(0, 256) as i16, y + rng.range(0, 256) as i16)
                };
                match kind {
                    0 => w.line(v(), v()),
                    // A rectangle (two vertical edges) and a hexagon
                    // (concave or crossing itself, more than two edges
                    // active at once).
                    1 => w.poly(
                        [(0, 0), (dx, 0), (dx, dy), (0, dy)]
                            .map(|(a, b)| Vertex::from_bits(x + a, y + b)),
                    ),
                    2 => w.poly([v(), v(), v(), v(), v(), v()]),
                    _ => w.poly([v(), v(), v()]),
                }
                .unwrap();
            }
            let list = DisplayList::new_checked(w.finish()).unwrap();
            let clip = ClipRect::full(W, H);
            want.fill(Rgb888::new(0, 0, 0));
            let mut fb = FrameBuffer::new(&mut want, W, H).unwrap();
            let mut slots = [Edge::EMPTY; 6];
            let mut color = Rgb888::new(0, 0, 0);
            for (_, cmd) in list.commands() {
                match cmd {
                    Command::Color(c) => color = c,
                    Command::Poly(v) => {
                        Rasterizer::new(&mut slots)
                            .fill(v.iter(), &clip, color, &mut fb)
                            .unwrap();
                    }
                    Command::Line(a, b) => {
                        draw_line(a, b, &clip, color, &mut fb).unwrap();
                    }
                    _ => {}
                }
            }
            let need = list.table_needs();
            let mut polygons = [TablePolygon::EMPTY; 300];
            let mut index = [0u32; 600];
            let mut edges = [Edge::EMPTY; 1800];
            let mut lines = [None; 300];
            let mem = TableMemory {
                polygons: &mut polygons[..need.polygons],
                index: &mut index[..2 * need.polygons],
                edges: &mut edges[..need.edges],
                lines: &mut lines[..need.lines],
            };
            let mut table = EdgeTable::build(mem, list.draws((W, H)), H, 0).unwrap();
            got.fill(Rgb888::new(0, 0, 0));
            let mut fb = FrameBuffer::new(&mut got, W, H).unwrap();
            let mut drawn = [false; H as usize];
            let mut y = 0;
            while y < H as i32 {
                let y1 = (y + rng.range(1, 20)).min(H as i32);
                if rng.below(4) == 0 {
                    table.skip(y1);
                } else {
                    table.draw(y1, &mut fb).unwrap();
                    for d in &mut drawn[y as usize..y1 as usize] {
                        *d = true;
                    }
                }
                y = y1;
            }
            for (row, d) in drawn.iter().enumerate() {
                let r = row * W as usize..(row + 1) * W as usize;
                if *d {
                    assert_eq!(got[r.clone()], want[r], "row {row}");
                }
            }
        }
    }

    #[test]
    fn entry_and_line_sizes_are_as_documented() {
        assert_eq!(core::mem::size_of::<TablePolygon>(), 24);
        assert_eq!(core::mem::size_of::<Option<Line>>(), 48);
    }
}
