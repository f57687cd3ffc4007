//! The trapezoid store: segments, faces, and the scan-line index.
//!
//! A 3D scene is a set of *segments*, each owning the trapezoids and faces
//! of the polygons added to it. [`TrapezoidStore::clear_segment`] empties
//! one segment alone and [`TrapezoidStore::add_polygon`] refills it; the
//! trapezoids of every other segment stay where they are, untouched, so a
//! frame where one segment changed cuts only that segment's polygons again.
//! Per-segment [`Counters`] show it.
//!
//! # Memory
//!
//! All of it is the caller's ([`StoreMemory`]), in pools with free lists,
//! so emptying and refilling a segment never moves anything else:
//!
//! | pool | slot (32-bit targets) | holds | limit |
//! |---|---|---|---|
//! | trapezoids | [`Trapezoid`], 34 bytes | edges' ends, rows, face, segment, columns, links | [`MAX_POOL`] |
//! | faces | [`Face`], 56 bytes | exact plane, fixed-point depth, colour, tie key | [`MAX_POOL`] |
//! | segments | [`Segment`], 32 bytes | chains, counters, hidden, highlight | [`MAX_POOL`] |
//! | scan-line index | `u16` per row | first trapezoid starting on the row | the frame's height |
//! | edge slots | [`EdgeSlot`], 32 bytes | scratch while a polygon is cut | its vertex count |
//!
//! The scan-line index is one `u16` per row: the head of a doubly linked
//! list, threaded through the trapezoids, of the trapezoids whose top row
//! it is. Everything else grows with the scene. Adding a trapezoid and
//! removing one are O(1).
//!
//! Links and the indices of trapezoids, faces and segments are `u16`, and
//! `0xffff` is "none". So a pool addresses at most [`MAX_POOL`] = 65535
//! slots: [`TrapezoidStore::new`] takes any slice and uses its first
//! 65535 slots when it is longer (the rest is left alone), which
//! [`TrapezoidStore::capacity`] and the errors report. A scene that needs
//! more gets [`StoreError::Trapezoids`] or [`StoreError::Faces`], never a
//! wrong link.
//!
//! # Errors
//!
//! When a pool runs out while a polygon is added, the segment being filled
//! is emptied and the error says which pool: a segment is always either
//! complete or empty, and the other segments are untouched.
//!
//! # Ties
//!
//! Each face has a key, `segment << 16 | n` where `n` counts the polygons
//! added to the segment since it was last emptied. Where two faces have
//! the same depth at a pixel, the lower key is in front: the lower
//! segment, then the earlier polygon.
//!
//! # Points and lines
//!
//! A point or a line (a face of one or two vertices, which the geometry
//! stage delivers as a small polygon with `two_sided` set, and
//! [`TrapezoidStore::add_point_or_line`] adds) is compared at its plane
//! moved [`LINE_BIAS`] = 256 units of depth (16 Q12.4 units, 1/256 of the
//! depth range) toward the eye: at every pixel, its depth is its plane's
//! less 256, and the rule above (the nearer, then the lower key) decides.
//! So a point or a line lying on a face is in front of it wherever the
//! face's depth differs from the line's by less than 256 units at the
//! pixel centres the line covers: a face whose depth changes by less than
//! about `256 / (t/2 + ½)` units a pixel across a line of thickness `t`
//! px. A point or line less than 256 units behind a face shows through it
//! too, as with a polygon offset. Points and lines are moved alike, so
//! among themselves nothing changes. The move is made where the face's
//! plane is made ([`Polygon::load_lifted`](crate::visible::trapezoid::Polygon::load_lifted)), so every way of resolving,
//! whole or in bands, compares the same moved plane.

use crate::display_list::Vertices3;
use crate::fixed::Vertex3;
use crate::raster::clip::{ClipRect, ClipWindow};
use crate::visible::trapezoid::{
    rgb_bits, Depth, EdgeSlot, Ends, LoadError, Outline, Plane, Polygon, Side, Trapezoid,
    TriangleCut, NONE,
};
use core::fmt;
use embedded_graphics_core::pixelcolor::Rgb888;

/// How far the plane of a point or a line is moved toward the eye, in
/// units of depth (1/16 of a Q12.4 unit, the step of [`Vertex3`]'s `z`):
/// see *Points and lines* in the [module](self) docs.
pub const LINE_BIAS: u16 = 256;

/// A polygon of the store: its exact plane and fixed-point depth (read by
/// every trapezoid of it), colour and tie key.
///
/// The colour drawn is its own, or its segment's highlight
/// ([`TrapezoidStore::set_highlight`]); its own is kept beside it, in the
/// bits the drawn colour leaves free, so that clearing a highlight needs
/// nothing but the face.
///
/// A mesh's triangle leaves its depth to be worked out when it is needed
/// ([`Depth::LATER`]): most of a closed mesh's faces never share a row's
/// pixels with another, and the sweep reads their depth only where they
/// do. Two faces are equal when their depths, worked out, are.
#[derive(Clone, Copy, Debug)]
pub struct Face {
    plane: Plane,
    depth: Depth,
    /// `0xRRrrggbb`: the colour drawn in the low 24 bits, the red of the
    /// face's own colour in the high 8.
    color: u32,
    key: u32,
    /// The green and blue of the face's own colour.
    own: u16,
    next: u16,
}

impl Face {
    /// An unused slot.
    pub const EMPTY: Face = Face {
        plane: Plane::FLAT,
        depth: Depth { z: 0, zx: 0, zy: 0 },
        color: 0,
        key: 0,
        own: 0,
        next: NONE,
    };

    /// The exact plane.
    #[doc(hidden)]
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The plane's fixed-point depth, [`Plane::depth`]: that of every
    /// trapezoid of the face (worked out here if it was left for later).
    #[doc(hidden)]
    pub fn depth(&self) -> Depth {
        if self.depth.is_later() {
            return self.plane.depth();
        }
        self.depth
    }

    /// The depth as stored: [`Depth::LATER`] when it was left for later.
    #[inline(always)]
    pub(crate) fn depth_or_later(&self) -> Depth {
        self.depth
    }

    /// The colour drawn: its own, or its segment's highlight.
    pub fn color(&self) -> Rgb888 {
        let c = self.color;
        Rgb888::new((c >> 16) as u8, (c >> 8) as u8, c as u8)
    }

    /// Its own colour, as its polygon was added.
    pub fn own_color(&self) -> Rgb888 {
        let o = self.own_bits();
        Rgb888::new((o >> 16) as u8, (o >> 8) as u8, o as u8)
    }

    fn own_bits(&self) -> u32 {
        (self.color >> 24) << 16 | self.own as u32
    }

    /// The colour drawn as `0x00rrggbb`.
    #[inline(always)]
    pub(crate) fn color_bits(&self) -> u32 {
        self.color & 0x00ff_ffff
    }

    /// The tie key: lower is in front at equal depth.
    #[doc(hidden)]
    pub fn key(&self) -> u32 {
        self.key
    }

    /// The segment that owns it (the key's high half: a segment's index
    /// is below [`MAX_POOL`]).
    pub fn segment(&self) -> u16 {
        (self.key >> 16) as u16
    }
}

impl PartialEq for Face {
    fn eq(&self, other: &Face) -> bool {
        self.plane == other.plane
            && self.depth() == other.depth()
            && (self.color, self.key, self.own, self.next)
                == (other.color, other.key, other.own, other.next)
    }
}

impl Eq for Face {}

/// Work done for one segment (or the whole store), counted since the store
/// was made. All counters wrap.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Counters {
    /// Polygons added.
    pub polygons: u32,
    /// Trapezoids built (cut and stored).
    pub trapezoids: u32,
    /// Times the segment was emptied.
    pub clears: u32,
}

impl Counters {
    fn add(&mut self, o: Counters) {
        self.polygons = self.polygons.wrapping_add(o.polygons);
        self.trapezoids = self.trapezoids.wrapping_add(o.trapezoids);
        self.clears = self.clears.wrapping_add(o.clears);
    }
}

/// One segment: the chains of its trapezoids and faces, and its counters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Segment {
    traps: u16,
    faces: u16,
    trapezoids: u32,
    face_count: u32,
    ordinal: u16,
    stale: bool,
    hidden: bool,
    /// `0` none, else `0x0100_0000 | 0x00rrggbb`.
    highlight: u32,
    work: Counters,
}

impl Segment {
    /// An unused slot.
    pub const EMPTY: Segment = Segment {
        traps: NONE,
        faces: NONE,
        trapezoids: 0,
        face_count: 0,
        ordinal: 0,
        stale: false,
        hidden: false,
        highlight: 0,
        work: Counters {
            polygons: 0,
            trapezoids: 0,
            clears: 0,
        },
    };

    /// Trapezoids it owns now.
    pub fn trapezoids(&self) -> u32 {
        self.trapezoids
    }

    /// Faces it owns now.
    pub fn faces(&self) -> u32 {
        self.face_count
    }

    /// Work done for it.
    pub fn counters(&self) -> Counters {
        self.work
    }

    /// Marked as needing to be built again (see
    /// [`TrapezoidStore::set_stale`]).
    pub fn is_stale(&self) -> bool {
        self.stale
    }

    /// Hidden: its trapezoids are kept but out of the scan-line index
    /// ([`TrapezoidStore::set_hidden`]).
    pub fn is_hidden(&self) -> bool {
        self.hidden
    }

    /// The colour its faces are drawn in instead of their own
    /// ([`TrapezoidStore::set_highlight`]).
    pub fn highlight(&self) -> Option<Rgb888> {
        let h = self.highlight;
        (h != 0).then(|| Rgb888::new((h >> 16) as u8, (h >> 8) as u8, h as u8))
    }
}

/// What ran out, or what was asked that does not exist.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum StoreError {
    /// The trapezoid pool is full.
    Trapezoids {
        /// Slots it holds.
        capacity: usize,
    },
    /// The face pool is full.
    Faces {
        /// Slots it holds.
        capacity: usize,
    },
    /// A polygon has more edges inside the clip rows than there are edge
    /// slots.
    Edges {
        /// Slots available.
        capacity: usize,
    },
    /// A polygon has more than 65535 vertices.
    Vertices,
    /// No such segment.
    Segment {
        /// The index asked for.
        segment: usize,
        /// Segments the store holds.
        capacity: usize,
    },
    /// The scan-line index has fewer rows than the frame.
    Rows {
        /// Rows of the frame.
        height: u16,
        /// Rows the index holds.
        capacity: usize,
    },
}

impl fmt::Display for StoreError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            StoreError::Trapezoids { capacity } => {
                write!(f, "more than the {capacity} trapezoids the store holds")
            }
            StoreError::Faces { capacity } => {
                write!(f, "more than the {capacity} faces the store holds")
            }
            StoreError::Edges { capacity } => {
                write!(
                    f,
                    "polygon needs more than the {capacity} edge slots available"
                )
            }
            StoreError::Vertices => f.write_str("polygon has more than 65535 vertices"),
            StoreError::Segment { segment, capacity } => {
                write!(
                    f,
                    "segment {segment} does not exist (the store holds {capacity})"
                )
            }
            StoreError::Rows { height, capacity } => write!(
                f,
                "scan-line index holds {capacity} rows; the frame has {height}"
            ),
        }
    }
}

impl core::error::Error for StoreError {}

impl From<LoadError> for StoreError {
    fn from(e: LoadError) -> Self {
        match e {
            LoadError::Edges { capacity } => StoreError::Edges { capacity },
            LoadError::Vertices => StoreError::Vertices,
        }
    }
}

/// The caller's memory for a [`TrapezoidStore`]. Every slice may have any
/// length; the pools (trapezoids, faces, segments) use at most their first
/// [`MAX_POOL`] slots, the index needs at least the frame's height.
#[derive(Debug)]
pub struct StoreMemory<'a> {
    /// The trapezoid pool.
    pub trapezoids: &'a mut [Trapezoid],
    /// The face pool: one face per polygon that has trapezoids.
    pub faces: &'a mut [Face],
    /// The segments.
    pub segments: &'a mut [Segment],
    /// The scan-line index: one entry per row.
    pub rows: &'a mut [u16],
    /// Scratch for cutting one polygon: as many as its vertices.
    pub edges: &'a mut [EdgeSlot],
}

/// Trapezoids of a frame, by segment, indexed by top row. See the
/// [module](self) docs.
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
/// use scanvert::{raster::clip::ClipRect, fixed::{Coord, Vertex3}, visible::store::*, visible::trapezoid::*};
///
/// let (mut traps, mut faces) = ([Trapezoid::EMPTY; 64], [Face::EMPTY; 16]);
/// let (mut segs, mut rows, mut edges) = ([Segment::EMPTY; 2], [0u16; 48], [EdgeSlot::EMPTY; 8]);
/// let mut store = TrapezoidStore::new(
///     StoreMemory { trapezoids: &mut traps, faces: &mut faces, segments: &mut segs, rows: &mut rows, edges: &mut edges },
///     64, 48,
/// ).unwrap();
/// let v = |x: i16, y: i16, z: i16| Vertex3 { x: Coord::from_bits(x * 16), y: Coord::from_bits(y * 16), z: Coord::from_bits(z * 16) };
/// let clip = ClipRect::full(64, 48);
/// store.add_polygon(0, [v(2, 2, 5), v(60, 10, 5), v(8, 40, 5)], Rgb888::RED, &clip)?;
/// store.add_polygon(1, [v(10, 5, 9), v(50, 5, 9), v(50, 30, 9), v(10, 30, 9)], Rgb888::BLUE, &clip)?;
/// assert_eq!(store.segment(0).unwrap().trapezoids(), 2);
/// store.clear_segment(0)?; // segment 1 is untouched
/// assert_eq!(store.len(), 1);
/// # Ok::<(), StoreError>(())
/// ```
#[derive(Debug)]
pub struct TrapezoidStore<'a> {
    traps: &'a mut [Trapezoid],
    faces: &'a mut [Face],
    segments: &'a mut [Segment],
    rows: &'a mut [u16],
    edges: &'a mut [EdgeSlot],
    width: u16,
    height: u16,
    free_trap: u16,
    unused_trap: u16,
    free_face: u16,
    unused_face: u16,
    live: u32,
    live_faces: u32,
    /// Some face added may have left its depth for later
    /// ([`Depth::LATER`]): a mesh's run of triangles added one.
    later: bool,
}

/// Most slots a pool of the store uses: its indices are `u16`, and
/// `0xffff` is the "none" link, so slot 65535 cannot be addressed.
pub const MAX_POOL: usize = NONE as usize;

/// The part of a pool the store uses: at most [`MAX_POOL`] slots, so that
/// no slot's index is `NONE`.
fn pool<T>(p: &mut [T]) -> &mut [T] {
    let n = p.len().min(MAX_POOL);
    &mut p[..n]
}

impl<'a> TrapezoidStore<'a> {
    /// An empty store for a `width × height` frame (each side at most
    /// 4096). Fails when the index has fewer rows than the frame. Of a pool
    /// longer than [`MAX_POOL`], the first [`MAX_POOL`] slots are used.
    #[doc(hidden)]
    pub fn new(mem: StoreMemory<'a>, width: u16, height: u16) -> Result<Self, StoreError> {
        let height = height.min(4096);
        let capacity = mem.rows.len();
        let rows = mem
            .rows
            .get_mut(..height as usize)
            .ok_or(StoreError::Rows { height, capacity })?;
        rows.fill(NONE);
        let segments = pool(mem.segments);
        for s in segments.iter_mut() {
            *s = Segment::EMPTY;
        }
        Ok(TrapezoidStore {
            traps: pool(mem.trapezoids),
            faces: pool(mem.faces),
            segments,
            rows,
            edges: mem.edges,
            width: width.min(4096),
            height,
            free_trap: NONE,
            unused_trap: 0,
            free_face: NONE,
            unused_face: 0,
            live: 0,
            live_faces: 0,
            later: false,
        })
    }

    /// Frame width.
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Frame height: the rows of the index.
    pub fn height(&self) -> u16 {
        self.height
    }

    /// Trapezoids stored.
    pub fn len(&self) -> usize {
        self.live as usize
    }

    /// `true` when no trapezoid is stored.
    pub fn is_empty(&self) -> bool {
        self.live == 0
    }

    /// Faces stored.
    pub fn face_count(&self) -> usize {
        self.live_faces as usize
    }

    /// Works out every depth its face left for later ([`Depth::LATER`]):
    /// before painting ([`Resolve::Paint`](crate::visible::Resolve::Paint)),
    /// which reads every trapezoid's depth, so that a face's is worked
    /// out once and not once a trapezoid.
    pub(crate) fn work_out_depths(&mut self) {
        if !self.later {
            return;
        }
        let used = (self.unused_face as usize).min(self.faces.len());
        for f in &mut self.faces[..used] {
            if f.depth.is_later() {
                f.depth = f.plane.depth();
            }
        }
        self.later = false;
    }

    /// `true` when a face of the store may have left its depth for later
    /// ([`Depth::LATER`]; [`Face::depth`] works it out): the sweep then
    /// works out the depths of a row's trapezoids before it reads them.
    #[inline(always)]
    pub(crate) fn has_later_depths(&self) -> bool {
        self.later
    }

    /// The most trapezoids and faces the store has held at once since it
    /// was made. A pool hands out any free slot, so pools of these sizes
    /// would have held everything the store was asked to hold.
    pub fn peak(&self) -> (usize, usize) {
        // A never-used slot is taken only when every used one is in use,
        // so the never-used mark is the most in use at once.
        (self.unused_trap as usize, self.unused_face as usize)
    }

    /// Trapezoid slots (at most [`MAX_POOL`]).
    pub fn capacity(&self) -> usize {
        self.traps.len()
    }

    /// Face slots (at most [`MAX_POOL`]).
    pub fn face_capacity(&self) -> usize {
        self.faces.len()
    }

    /// Segment `s`.
    pub fn segment(&self, s: usize) -> Option<&Segment> {
        self.segments.get(s)
    }

    /// The segments.
    pub fn segments(&self) -> &[Segment] {
        self.segments
    }

    /// The work of all segments together.
    pub fn counters(&self) -> Counters {
        let mut c = Counters::default();
        for s in self.segments.iter() {
            c.add(s.work);
        }
        c
    }

    /// Face `f`.
    #[doc(hidden)]
    pub fn face(&self, f: u16) -> Option<&Face> {
        self.faces.get(f as usize)
    }

    /// Trapezoid slot `t`.
    #[doc(hidden)]
    pub fn trapezoid(&self, t: u16) -> Option<&Trapezoid> {
        self.traps.get(t as usize)
    }

    /// The scan-line index: the trapezoids whose top row is `y`.
    #[doc(hidden)]
    pub fn starting_at(&self, y: u16) -> impl Iterator<Item = (u16, &Trapezoid)> + '_ {
        let head = self.rows.get(y as usize).copied().unwrap_or(NONE);
        Chain {
            traps: self.traps,
            at: head,
            next: |t: &Trapezoid| t.next_row,
        }
    }

    /// The trapezoids of segment `s`, newest first.
    #[doc(hidden)]
    pub fn segment_trapezoids(&self, s: usize) -> impl Iterator<Item = (u16, &Trapezoid)> + '_ {
        let head = self.segments.get(s).map_or(NONE, |s| s.traps);
        Chain {
            traps: self.traps,
            at: head,
            next: |t: &Trapezoid| t.next_seg,
        }
    }

    /// The head of row `y`'s list (`NONE` past the end).
    #[inline]
    pub(crate) fn row_head(&self, y: usize) -> u16 {
        self.rows.get(y).copied().unwrap_or(NONE)
    }

    /// Empties segment `s`: its trapezoids and faces go back to the pools.
    /// No other segment is touched.
    #[doc(hidden)]
    pub fn clear_segment(&mut self, s: usize) -> Result<(), StoreError> {
        let seg = segment_at(self.segments, s)?;
        let mut t = seg.traps;
        // A hidden segment's trapezoids are out of the row lists already.
        let linked = !seg.hidden;
        while let Some(tr) = self.traps.get(t as usize).copied() {
            if linked {
                unlink_row(self.traps, self.rows, t);
            }
            self.traps[t as usize] = Trapezoid {
                next_seg: self.free_trap,
                ..Trapezoid::EMPTY
            };
            self.free_trap = t;
            self.live -= 1;
            t = tr.next_seg;
        }
        let mut f = seg.faces;
        while let Some(face) = self.faces.get(f as usize).copied() {
            self.faces[f as usize] = Face {
                next: self.free_face,
                ..Face::EMPTY
            };
            self.free_face = f;
            self.live_faces -= 1;
            f = face.next;
        }
        seg.traps = NONE;
        seg.faces = NONE;
        seg.trapezoids = 0;
        seg.face_count = 0;
        seg.ordinal = 0;
        seg.work.clears = seg.work.clears.wrapping_add(1);
        Ok(())
    }

    /// Hides segment `s` (`true`): its trapezoids leave the scan-line
    /// index, so no pass sees them, and stay in the segment, so showing it
    /// again (`false`) puts them back without cutting anything. Polygons
    /// added to a hidden segment are kept hidden too. O(the segment's
    /// trapezoids) when the mark changes, nothing otherwise.
    pub fn set_hidden(&mut self, s: usize, hidden: bool) -> Result<(), StoreError> {
        let seg = segment_at(self.segments, s)?;
        if seg.hidden == hidden {
            return Ok(());
        }
        seg.hidden = hidden;
        let mut t = seg.traps;
        while let Some(tr) = self.traps.get(t as usize).copied() {
            if hidden {
                unlink_row(self.traps, self.rows, t);
            } else {
                link_row(self.traps, self.rows, t);
            }
            t = tr.next_seg;
        }
        Ok(())
    }

    /// Draws segment `s`'s faces in `color` instead of their own, or in
    /// their own again (`None`); polygons added to it later take the
    /// highlight too. Each face keeps its own colour, so nothing is cut
    /// or rebuilt: O(the segment's faces).
    pub fn set_highlight(&mut self, s: usize, color: Option<Rgb888>) -> Result<(), StoreError> {
        let seg = segment_at(self.segments, s)?;
        seg.highlight = color.map_or(0, |c| 0x0100_0000 | rgb_bits(c));
        let mut f = seg.faces;
        while let Some(face) = self.faces.get_mut(f as usize) {
            let drawn = color.map_or(face.own_bits(), rgb_bits);
            face.color = (face.color & 0xff00_0000) | drawn;
            f = face.next;
        }
        Ok(())
    }

    /// Marks segment `s` as needing to be built again (`true`) or as built
    /// (`false`). The store itself only keeps the mark: it is for the
    /// [`Scene`](crate::scene::Scene) that owns the store.
    #[doc(hidden)]
    pub fn set_stale(&mut self, s: usize, stale: bool) -> Result<(), StoreError> {
        let seg = segment_at(self.segments, s)?;
        seg.stale = stale;
        Ok(())
    }

    /// `r`, after emptying segment `s` when `r` is an error other than
    /// the segment's own (`StoreError::Segment`): a polygon that failed
    /// halfway leaves no trapezoid of the segment behind.
    #[inline(always)]
    fn emptied_on_error(
        &mut self,
        s: usize,
        r: Result<u32, StoreError>,
    ) -> Result<u32, StoreError> {
        if let Err(e) = &r {
            if !matches!(e, StoreError::Segment { .. }) {
                let _ = self.clear_segment(s);
            }
        }
        r
    }

    /// Empties every segment.
    #[doc(hidden)]
    pub fn clear(&mut self) {
        for s in 0..self.segments.len() {
            let _ = self.clear_segment(s);
        }
    }

    /// Cuts the polygon through `vertices` (closed implicitly, any winding:
    /// trapezoids do not cull) into trapezoids of segment `s`, in colour
    /// `color`, writing only the pixels of `clip` (cut to the store's
    /// frame). Returns the trapezoids added: none for an edge-on polygon
    /// or one outside the clip.
    ///
    /// On an error the segment is emptied (see the [module](self) docs).
    #[doc(hidden)]
    pub fn add_polygon<I>(
        &mut self,
        s: usize,
        vertices: I,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<u32, StoreError>
    where
        I: IntoIterator<Item = Vertex3>,
    {
        self.add_lifted(s, vertices, color, clip, 0)
    }

    /// [`add_polygon`](Self::add_polygon) for the polygon a point or a line
    /// became ([`geometry::primitive`](crate::geometry::primitive)): its
    /// face's plane is moved [`LINE_BIAS`] units of depth toward the eye
    /// (see *Points and lines* in the [module](self) docs), so that it
    /// shows on the faces it lies on.
    #[doc(hidden)]
    pub fn add_point_or_line<I>(
        &mut self,
        s: usize,
        vertices: I,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<u32, StoreError>
    where
        I: IntoIterator<Item = Vertex3>,
    {
        self.add_lifted(s, vertices, color, clip, LINE_BIAS)
    }

    /// [`add_polygon`](Self::add_polygon) with the plane moved `lift`
    /// units toward the eye (`lift ≤ 2¹⁴`): one body for both adders.
    pub(crate) fn add_lifted<I>(
        &mut self,
        s: usize,
        vertices: I,
        color: Rgb888,
        clip: &ClipRect,
        lift: u16,
    ) -> Result<u32, StoreError>
    where
        I: IntoIterator<Item = Vertex3>,
    {
        let r = self.add_once(s, vertices.into_iter(), color, clip, lift);
        self.emptied_on_error(s, r)
    }

    /// `add_lifted`'s work: the adder set up for the one polygon, its
    /// trapezoids added through [`Adding::polygon`] (the body a run's
    /// polygon goes through too), the chains and counters written back
    /// (on an error too).
    #[inline(always)]
    fn add_once<I>(
        &mut self,
        s: usize,
        it: I,
        color: Rgb888,
        clip: &ClipRect,
        lift: u16,
    ) -> Result<u32, StoreError>
    where
        I: Iterator<Item = Vertex3>,
    {
        let clip = self.frame_clip(clip);
        let seg = segment_at(self.segments, s)?;
        seg.work.polygons = seg.work.polygons.wrapping_add(1);
        let key = (s.min(0xffff) as u32) << 16 | seg.ordinal as u32;
        seg.ordinal = seg.ordinal.saturating_add(1);
        let mut add = Adding {
            traps: &mut *self.traps,
            rows: &mut *self.rows,
            faces: &mut *self.faces,
            free: self.free_trap,
            unused: self.unused_trap,
            free_face: self.free_face,
            unused_face: self.unused_face,
            seg_traps: seg.traps,
            seg_faces: seg.faces,
            added: 0,
            face: NONE,
            plane: Plane::FLAT,
            color: match seg.highlight {
                0 => rgb_bits(color),
                h => h & 0x00ff_ffff,
            },
            own: rgb_bits(color),
            key,
            segment: s as u16,
            clip,
            later: false,
        };
        let n = add.polygon(self.edges, it, lift);
        [
            self.free_trap,
            self.unused_trap,
            self.free_face,
            self.unused_face,
        ] = add.pools();
        let faces = u32::from(add.face != NONE);
        let added = add.settle(seg, faces);
        self.count(added, faces);
        n
    }

    /// Counts what a single polygon's adder added ([`Adding::settle`]).
    #[inline(always)]
    fn count(&mut self, added: u32, faces: u32) {
        self.live += added;
        self.live_faces += faces;
    }

    /// [`add_polygon`](Self::add_polygon) of a triangle: cut from its
    /// three vertices at once ([`TriangleCut`]) where that cut decides
    /// alone, else loaded as a polygon whose outline (Newell's sums,
    /// depth and column ranges) is worked out at once ([`Outline::of`]).
    /// The same trapezoids as `add_polygon`. A run of one
    /// ([`triangle_run`](Self::triangle_run)): the run's adder is the
    /// only triangle adder.
    pub(crate) fn add_triangle(
        &mut self,
        s: usize,
        v: [Vertex3; 3],
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<u32, StoreError> {
        self.triangle_run(s, clip, false, |r| r.triangle(v, color))
    }

    /// `clip` cut to the store's frame (a clip is within 0..=4096):
    /// itself when it lies inside, as a list's clip does.
    #[inline(always)]
    fn frame_clip(&self, clip: &ClipRect) -> ClipRect {
        if clip.x1() <= self.width && clip.y1() <= self.height {
            *clip
        } else {
            ClipRect::from_window(
                ClipWindow {
                    x0: clip.x0() as i16,
                    y0: clip.y0() as i16,
                    x1: clip.x1() as i16 - 1,
                    y1: clip.y1() as i16 - 1,
                },
                self.width,
                self.height,
            )
        }
    }

    /// A `poly3`'s vertices into segment `s` as
    /// [`add_polygon`](Self::add_polygon) when they are front-facing
    /// ([`front_facing`]), which the first pass over them finds;
    /// `Ok(false)`, and nothing done, when they are not.
    pub(crate) fn add_poly3(
        &mut self,
        s: usize,
        vertices: &Vertices3<'_>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<bool, StoreError> {
        let it = vertices.iter();
        match Outline::of(it.clone()) {
            Ok(o) if !o.front() => Ok(false),
            Ok(o) => self.add_from(s, it, Ok(o), color, clip).map(|_| true),
            // Too many vertices: an error only for a drawn one.
            Err(e) => match front_facing(vertices) {
                true => self
                    .add_from(s, it, Err(e.into()), color, clip)
                    .map(|_| true),
                false => Ok(false),
            },
        }
    }

    /// [`add_polygon`](Self::add_polygon) of the vertices of `it`, read a
    /// second time after a first found their `outline` (or too many); a
    /// triangle cut without the chains' walk ([`Polygon::cut_triangles`]:
    /// the adder of `poly3`s).
    #[inline(always)]
    fn add_from<I>(
        &mut self,
        s: usize,
        it: I,
        outline: Result<Outline, StoreError>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<u32, StoreError>
    where
        I: Iterator<Item = Vertex3>,
    {
        let r = self.add_inner(s, it, outline, color, clip);
        self.emptied_on_error(s, r)
    }

    #[inline(always)]
    fn add_inner<I>(
        &mut self,
        s: usize,
        it: I,
        outline: Result<Outline, StoreError>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<u32, StoreError>
    where
        I: Iterator<Item = Vertex3>,
    {
        let clip = self.frame_clip(clip);
        let seg = segment_at(self.segments, s)?;
        seg.work.polygons = seg.work.polygons.wrapping_add(1);
        let key = (s.min(0xffff) as u32) << 16 | seg.ordinal as u32;
        seg.ordinal = seg.ordinal.saturating_add(1);
        let poly = Polygon::load_edges(self.edges, it, outline?, &clip)?;
        if poly.edges() < 2 {
            return Ok(0);
        }
        let Some(plane) = poly.plane().copied() else {
            return Ok(0);
        };
        // The face is taken with the first trapezoid, so that a polygon
        // with none needs no face slot, and written there in place, its
        // depth worked out then: built on the stack and copied, it would
        // cost a copy of the face on the Cortex-M4. What the
        // cut's closure changes is in one place it reaches by one pointer
        // (each pool and counter captured apart cost a store each to set
        // up and a load more each to reach), and goes back to the store
        // and the segment after, on an error too (the segment is then
        // emptied through its links).
        let mut add = Adding {
            traps: &mut *self.traps,
            rows: &mut *self.rows,
            faces: &mut *self.faces,
            free: self.free_trap,
            unused: self.unused_trap,
            free_face: self.free_face,
            unused_face: self.unused_face,
            seg_traps: seg.traps,
            seg_faces: seg.faces,
            added: 0,
            face: NONE,
            plane: &plane,
            color: match seg.highlight {
                0 => rgb_bits(color),
                h => h & 0x00ff_ffff,
            },
            own: rgb_bits(color),
            key,
            segment: s as u16,
            clip,
            later: false,
        };
        let n = poly.cut_triangles(|l, r| add.trapezoid(l, r));
        [
            self.free_trap,
            self.unused_trap,
            self.free_face,
            self.unused_face,
        ] = add.pools();
        let faces = u32::from(add.face != NONE);
        let added = add.settle(seg, faces);
        self.count(added, faces);
        n
    }
}

impl<'a> TrapezoidStore<'a> {
    /// A run of triangles added to segment `s` under `clip`, as
    /// [`add_triangle`](Self::add_triangle) (a run of one) adds each: `f` adds them
    /// through the [`TriangleRun`] it is given. The segment, the clip cut
    /// to the frame and the pools are taken once for the run, and the
    /// segment's chains and counters go back to the store once, after
    /// `f`; the same trapezoids, faces, keys and counters as one
    /// `add_triangle` a triangle. After a triangle's error (other than
    /// [`StoreError::Segment`]) the segment is emptied, as `add_triangle`
    /// empties it; `f` is expected to add nothing after one.
    ///
    /// `later`: the triangles' faces leave their depth for later
    /// ([`Depth::LATER`]), as a mesh's do: the sweep works a depth out
    /// only where the face shares a row's pixels with another.
    pub(crate) fn triangle_run<R>(
        &mut self,
        s: usize,
        clip: &ClipRect,
        later: bool,
        f: impl FnOnce(&mut TriangleRun<'_>) -> R,
    ) -> R {
        let clip = self.frame_clip(clip);
        let capacity = self.segments.len();
        let seg = self.segments.get(s).copied();
        let valid = seg.is_some();
        let seg = seg.unwrap_or(Segment::EMPTY);
        let mut run = TriangleRun {
            add: Adding {
                traps: &mut *self.traps,
                rows: &mut *self.rows,
                faces: &mut *self.faces,
                free: self.free_trap,
                unused: self.unused_trap,
                free_face: self.free_face,
                unused_face: self.unused_face,
                seg_traps: seg.traps,
                seg_faces: seg.faces,
                added: 0,
                face: NONE,
                plane: Plane::FLAT,
                color: 0,
                own: 0,
                key: 0,
                segment: s as u16,
                clip,
                later,
            },
            edges: &mut *self.edges,
            segments: &mut *self.segments,
            s,
            capacity,
            valid,
            highlight: seg.highlight,
            key: (s.min(0xffff) as u32) << 16,
            ordinal: seg.ordinal,
            polygons: 0,
            faces: 0,
            failed: false,
        };
        let r = f(&mut run);
        let TriangleRun {
            add,
            ordinal,
            polygons,
            faces,
            failed,
            ..
        } = run;
        let (added, chains) = (add.added, (add.seg_traps, add.seg_faces));
        (self.free_trap, self.unused_trap) = (add.free, add.unused);
        (self.free_face, self.unused_face) = (add.free_face, add.unused_face);
        let Some(seg) = self.segments.get_mut(s) else {
            return r;
        };
        (seg.traps, seg.faces) = chains;
        seg.ordinal = ordinal;
        seg.work.polygons = seg.work.polygons.wrapping_add(polygons);
        seg.trapezoids += added;
        seg.work.trapezoids = seg.work.trapezoids.wrapping_add(added);
        self.live += added;
        seg.face_count += faces;
        self.live_faces += faces;
        self.later |= later && faces > 0;
        if seg.hidden {
            // The newest trapezoids head the segment's chain.
            let mut t = seg.traps;
            for _ in 0..added {
                let next = self.traps.get(t as usize).map_or(NONE, |tr| tr.next_seg);
                unlink_row(self.traps, self.rows, t);
                t = next;
            }
        }
        if failed {
            let _ = self.clear_segment(s);
        }
        r
    }
}

/// Takes trapezoid `t` out of its row's list.
fn unlink_row(traps: &mut [Trapezoid], rows: &mut [u16], t: u16) {
    let Some(tr) = traps.get(t as usize).copied() else {
        return;
    };
    match traps.get_mut(tr.prev_row as usize) {
        Some(p) => p.next_row = tr.next_row,
        None => {
            if let Some(h) = rows.get_mut(tr.top() as usize) {
                *h = tr.next_row;
            }
        }
    }
    if let Some(n) = traps.get_mut(tr.next_row as usize) {
        n.prev_row = tr.prev_row;
    }
    if let Some(me) = traps.get_mut(t as usize) {
        me.next_row = NONE;
        me.prev_row = NONE;
    }
}

/// Puts trapezoid `t` at the head of its row's list.
fn link_row(traps: &mut [Trapezoid], rows: &mut [u16], t: u16) {
    let Some(top) = traps.get(t as usize).map(|tr| tr.top() as usize) else {
        return;
    };
    let head = rows.get(top).copied().unwrap_or(NONE);
    if let Some(h) = traps.get_mut(head as usize) {
        h.prev_row = t;
    }
    if let Some(me) = traps.get_mut(t as usize) {
        me.next_row = head;
        me.prev_row = NONE;
    }
    if let Some(h) = rows.get_mut(top) {
        *h = t;
    }
}

/// The pools and a segment's chains while one polygon's trapezoids are
/// added ([`TrapezoidStore::add_polygon`]).
struct Adding<'p, P = &'p Plane> {
    traps: &'p mut [Trapezoid],
    rows: &'p mut [u16],
    faces: &'p mut [Face],
    free: u16,
    unused: u16,
    free_face: u16,
    unused_face: u16,
    seg_traps: u16,
    seg_faces: u16,
    /// Trapezoids added.
    added: u32,
    /// The polygon's face, `NONE` until its first trapezoid.
    face: u16,
    /// The face's plane, colour, key and segment.
    plane: P,
    color: u32,
    /// The polygon's own colour (`color` is its segment's highlight, if
    /// any).
    own: u32,
    key: u32,
    segment: u16,
    clip: ClipRect,
    /// A triangle's cut ([`TriangleRun`] of a mesh) leaves its face's
    /// depth for later ([`Depth::LATER`]).
    later: bool,
}

impl<P: core::borrow::Borrow<Plane>> Adding<'_, P> {
    /// Stores the trapezoid between `l` and `r` (and the face with the
    /// first), and indexes it by its top row.
    #[inline(always)]
    fn trapezoid(&mut self, l: Side, r: Side) -> Result<(), StoreError> {
        let ((l, top, end), (r, _, _)) = (l.parts(), r.parts());
        self.between(l, r, top, end)
    }

    /// [`Adding::trapezoid`] from the edges' ends and the rows `top..end`
    /// (of the clip).
    #[inline(always)]
    fn between(&mut self, l: Ends, r: Ends, top: u16, end: u16) -> Result<(), StoreError> {
        let Adding {
            traps,
            rows,
            faces,
            free,
            unused,
            free_face,
            unused_face,
            ..
        } = self;
        if self.face == NONE {
            let cap = faces.len();
            let f = alloc(free_face, unused_face, cap, |i| faces[i as usize].next)
                .ok_or(StoreError::Faces { capacity: cap })?;
            if let Some(slot) = faces.get_mut(f as usize) {
                *slot = Face {
                    plane: *self.plane.borrow(),
                    depth: if self.later {
                        Depth::LATER
                    } else {
                        self.plane.borrow().depth()
                    },
                    color: self.color | (self.own >> 16) << 24,
                    key: self.key,
                    own: self.own as u16,
                    next: self.seg_faces,
                };
            }
            self.seg_faces = f;
            self.face = f;
        }
        let cap = traps.len();
        let t = alloc(free, unused, cap, |i| traps[i as usize].next_seg)
            .ok_or(StoreError::Trapezoids { capacity: cap })?;
        // Rows are inside the frame: the edges were cut to the clip.
        let head = rows.get(top as usize).copied().unwrap_or(NONE);
        if let Some(h) = traps.get_mut(head as usize) {
            h.prev_row = t;
        }
        if let Some(h) = rows.get_mut(top as usize) {
            *h = t;
        }
        // Written in place, every field at once: built on the stack and
        // copied, it would cost a copy of the trapezoid on the Cortex-M4.
        if let Some(slot) = traps.get_mut(t as usize) {
            *slot = Trapezoid {
                left: l,
                right: r,
                top,
                end,
                face: self.face,
                segment: self.segment,
                x0: self.clip.x0(),
                x1: self.clip.x1(),
                next_row: head,
                prev_row: NONE,
                next_seg: self.seg_traps,
            };
        }
        self.seg_traps = t;
        self.added += 1;
        Ok(())
    }
}

impl<P> Adding<'_, P> {
    /// The store's pools as the adder leaves them: the free and unused
    /// trapezoids, the free and unused faces.
    #[inline(always)]
    fn pools(&self) -> [u16; 4] {
        [self.free, self.unused, self.free_face, self.unused_face]
    }

    /// Ends a single polygon's adder (its [`pools`](Self::pools) taken
    /// back first): the segment's chains and counters written back to
    /// `seg`, with `faces` faces added (its new trapezoids taken out of
    /// their rows when it is hidden; the newest head its chain); returns
    /// the trapezoids added, for [`TrapezoidStore::count`]. A run's end
    /// ([`TrapezoidStore::triangle_run`]) writes its own back: through
    /// this, the run's triangles cost more (the mesh frames +0.6 %).
    #[inline(always)]
    fn settle(self, seg: &mut Segment, faces: u32) -> u32 {
        (seg.traps, seg.faces) = (self.seg_traps, self.seg_faces);
        let added = self.added;
        seg.trapezoids += added;
        seg.work.trapezoids = seg.work.trapezoids.wrapping_add(added);
        seg.face_count += faces;
        if seg.hidden {
            let mut t = seg.traps;
            for _ in 0..added {
                let next = self.traps.get(t as usize).map_or(NONE, |tr| tr.next_seg);
                unlink_row(self.traps, self.rows, t);
                t = next;
            }
        }
        added
    }
}

impl Adding<'_, Plane> {
    /// The trapezoids of the polygon through `it` (loaded into `edges`
    /// in one pass, its plane moved `lift` units toward the eye), the
    /// face's colour and key set: the one body of a single polygon's
    /// adder ([`TrapezoidStore::add_lifted`]) and a run's
    /// ([`TriangleRun::polygon`]).
    #[inline(never)]
    fn polygon<I>(&mut self, edges: &mut [EdgeSlot], it: I, lift: u16) -> Result<u32, StoreError>
    where
        I: Iterator<Item = Vertex3>,
    {
        // No face yet, whatever comes of the polygon: a run's last
        // polygon's is not this one's.
        self.face = NONE;
        let clip = self.clip;
        let poly = Polygon::load_lifted(edges, it, &clip, lift)?;
        if poly.edges() < 2 {
            return Ok(0);
        }
        let Some(plane) = poly.plane().copied() else {
            return Ok(0);
        };
        self.plane = plane;
        poly.cut(|l, r| self.trapezoid(l, r))
    }
}

/// A run of triangles being added to one segment of a store
/// ([`TrapezoidStore::triangle_run`]): the pools, the segment's chains
/// and the clip (cut to the frame) kept across its triangles, and what
/// the segment's counters gain, added to them once at the end.
pub(crate) struct TriangleRun<'r> {
    add: Adding<'r, Plane>,
    edges: &'r mut [EdgeSlot],
    segments: &'r mut [Segment],
    s: usize,
    /// Segments of the store, for the error of a bad `s`.
    capacity: usize,
    /// `s` names a segment.
    valid: bool,
    /// The segment's highlight (`Segment::highlight`).
    highlight: u32,
    /// The segment's part of a face's key.
    key: u32,
    ordinal: u16,
    /// Polygons added, for the segment's work counters.
    polygons: u32,
    /// Faces taken.
    faces: u32,
    /// A triangle failed: the segment is emptied at the end.
    failed: bool,
}

impl TriangleRun<'_> {
    /// [`TrapezoidStore::add_triangle`] into the run's segment, under its
    /// clip; the trapezoids added.
    #[inline(never)]
    pub(crate) fn triangle(&mut self, v: [Vertex3; 3], color: Rgb888) -> Result<u32, StoreError> {
        // With fewer than three edge slots the polygon's load reports
        // what is missing.
        if self.edges.len() >= 3 {
            if let Some(cut) = TriangleCut::of(&v, &self.add.clip) {
                return self.cut(&cut, color);
            }
        }
        self.triangle_polygon(v, color)
    }

    /// [`triangle`](Self::triangle) of a triangle its cut does not take
    /// (a store of fewer than three edge slots, whose error the load
    /// reports): loaded as a polygon whose outline is worked out at once
    /// ([`Outline::of`]). Out of line, so that the cut's code is left
    /// without it.
    #[inline(never)]
    fn triangle_polygon(&mut self, v: [Vertex3; 3], color: Rgb888) -> Result<u32, StoreError> {
        let it = v.into_iter();
        let outline = Outline::of(it.clone()).map_err(StoreError::from);
        self.add(it, outline, color)
    }

    /// [`TrapezoidStore::add_lifted`] into the run's segment, under its
    /// clip.
    #[inline(never)]
    pub(crate) fn polygon<I>(
        &mut self,
        vertices: I,
        color: Rgb888,
        lift: u16,
    ) -> Result<u32, StoreError>
    where
        I: IntoIterator<Item = Vertex3>,
    {
        if !self.valid {
            return Err(StoreError::Segment {
                segment: self.s,
                capacity: self.capacity,
            });
        }
        let key = self.begin();
        let add = &mut self.add;
        add.color = match self.highlight {
            0 => rgb_bits(color),
            h => h & 0x00ff_ffff,
        };
        add.own = rgb_bits(color);
        add.key = key;
        let n = add.polygon(self.edges, vertices.into_iter(), lift);
        self.faces += (add.face != NONE) as u32;
        if n.is_err() {
            self.failed = true;
        }
        n
    }

    /// Marks every segment but the run's as stale
    /// ([`TrapezoidStore::set_stale`]).
    pub(crate) fn others_stale(&mut self) {
        let s = self.s;
        for (i, seg) in self.segments.iter_mut().enumerate() {
            if i != s {
                seg.stale = true;
            }
        }
    }

    /// [`add`](Self::add) of a triangle's cut, read where it lies: its
    /// plane copied once, into the adder.
    #[inline(always)]
    fn cut(&mut self, cut: &TriangleCut, color: Rgb888) -> Result<u32, StoreError> {
        if !self.valid {
            return Err(StoreError::Segment {
                segment: self.s,
                capacity: self.capacity,
            });
        }
        let key = self.begin();
        let Some(plane) = cut.plane() else {
            return Ok(0);
        };
        let add = &mut self.add;
        add.plane = *plane;
        add.face = NONE;
        add.color = match self.highlight {
            0 => rgb_bits(color),
            h => h & 0x00ff_ffff,
        };
        add.own = rgb_bits(color);
        add.key = key;
        // Inlined into both bands of the cut: as a call (LLVM's choice
        // for a closure called twice) it cost the mesh frames 7 k to 11 k
        // instructions more on the Cortex-M4 (`docs/performance-log.md`).
        let n = cut.cut(
            #[inline(always)]
            |l, r, top, end| add.between(l, r, top, end),
        );
        self.faces += (add.face != NONE) as u32;
        if n.is_err() {
            self.failed = true;
        }
        n
    }

    /// A polygon of the run counted; its face's key.
    #[inline(always)]
    fn begin(&mut self) -> u32 {
        self.polygons = self.polygons.wrapping_add(1);
        let key = self.key | self.ordinal as u32;
        self.ordinal = self.ordinal.saturating_add(1);
        key
    }

    /// `add_inner`'s work for one polygon of the run, the segment's
    /// counters kept in the run; an error marks the run failed.
    #[inline(always)]
    fn add<I>(
        &mut self,
        it: I,
        outline: Result<Outline, StoreError>,
        color: Rgb888,
    ) -> Result<u32, StoreError>
    where
        I: Iterator<Item = Vertex3>,
    {
        if !self.valid {
            return Err(StoreError::Segment {
                segment: self.s,
                capacity: self.capacity,
            });
        }
        let r = self.add_valid(it, outline, color);
        if r.is_err() {
            self.failed = true;
        }
        r
    }

    #[inline(always)]
    fn add_valid<I>(
        &mut self,
        it: I,
        outline: Result<Outline, StoreError>,
        color: Rgb888,
    ) -> Result<u32, StoreError>
    where
        I: Iterator<Item = Vertex3>,
    {
        let key = self.begin();
        let clip = self.add.clip;
        let poly = Polygon::load_edges(self.edges, it, outline?, &clip)?;
        if poly.edges() < 2 {
            return Ok(0);
        }
        let Some(plane) = poly.plane().copied() else {
            return Ok(0);
        };
        let add = &mut self.add;
        add.plane = plane;
        add.face = NONE;
        add.color = match self.highlight {
            0 => rgb_bits(color),
            h => h & 0x00ff_ffff,
        };
        add.own = rgb_bits(color);
        add.key = key;
        let n = poly.cut_triangles(|l, r| add.trapezoid(l, r));
        self.faces += (add.face != NONE) as u32;
        n
    }
}

/// One segment of a store as the geometry stage's
/// [`PolygonSink`](crate::geometry::PolygonSink): every polygon delivered
/// is cut into that segment's trapezoids under `clip` (winding is not
/// looked at: the geometry stage has culled), and points and lines (the
/// polygons delivered `two_sided`) as
/// [`add_point_or_line`](TrapezoidStore::add_point_or_line) adds them.
#[derive(Debug)]
#[doc(hidden)]
pub struct SegmentSink<'s, 'a> {
    store: &'s mut TrapezoidStore<'a>,
    segment: usize,
    clip: ClipRect,
}

impl<'s, 'a> SegmentSink<'s, 'a> {
    /// A sink filling segment `segment` of `store`, writing only `clip`.
    #[doc(hidden)]
    pub fn new(store: &'s mut TrapezoidStore<'a>, segment: usize, clip: ClipRect) -> Self {
        SegmentSink {
            store,
            segment,
            clip,
        }
    }
}

impl crate::geometry::PolygonSink for SegmentSink<'_, '_> {
    type Error = StoreError;

    fn polygon(
        &mut self,
        vertices: &[Vertex3],
        color: Rgb888,
        point_or_line: bool,
    ) -> Result<(), StoreError> {
        let lift = if point_or_line { LINE_BIAS } else { 0 };
        let v = vertices.iter().copied();
        self.store
            .add_lifted(self.segment, v, color, &self.clip, lift)
            .map(|_| ())
    }
}

/// Segment `s` of `segments`, or the error that names it.
fn segment_at(segments: &mut [Segment], s: usize) -> Result<&mut Segment, StoreError> {
    let capacity = segments.len();
    segments.get_mut(s).ok_or(StoreError::Segment {
        segment: s,
        capacity,
    })
}

/// Takes a slot from a pool: the free list first, then never-used slots.
/// `len` is at most [`MAX_POOL`], so a slot taken is never `NONE`.
fn alloc(free: &mut u16, unused: &mut u16, len: usize, next: impl Fn(u16) -> u16) -> Option<u16> {
    if *free != NONE {
        let t = *free;
        *free = next(t);
        Some(t)
    } else if (*unused as usize) < len {
        let t = *unused;
        *unused += 1;
        Some(t)
    } else {
        None
    }
}

/// Walks a `u16` chain through the trapezoid pool.
struct Chain<'t, F> {
    traps: &'t [Trapezoid],
    at: u16,
    next: F,
}

impl<'t, F: Fn(&Trapezoid) -> u16> Iterator for Chain<'t, F> {
    type Item = (u16, &'t Trapezoid);
    fn next(&mut self) -> Option<Self::Item> {
        let i = self.at;
        let t = self.traps.get(i as usize)?;
        self.at = (self.next)(t);
        Some((i, t))
    }
}

/// `true` when a `poly3` (screen space, Q12.4) is drawn: the shoelace sum
/// of its vertices `v` is negative (counter-clockwise as displayed, y
/// down). Each term is below 2³¹ in magnitude and there are at most
/// 65535: the sum fits in `i64`. Not generic over the vertices: a
/// generic instance is inlined into `add_poly3`, which costs the
/// Cortex-M4's cut about 340 instructions a `poly3`.
#[doc(hidden)]
pub fn front_facing(v: &Vertices3<'_>) -> bool {
    let mut it = v.iter();
    let Some(first) = it.next() else {
        return false;
    };
    // Each term one pair of 32 × 32 → 64-bit multiplies; the closing
    // edge after the loop (chaining it in cost a check a vertex).
    let term = |p: Vertex3, q: Vertex3| {
        p.x.units() as i64 * q.y.units() as i64 - q.x.units() as i64 * p.y.units() as i64
    };
    let mut s = 0i64;
    let mut prev = first;
    for p in it {
        s += term(prev, p);
        prev = p;
    }
    s + term(prev, first) < 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::Coord;
    use embedded_graphics_core::pixelcolor::RgbColor;

    fn v(x: i32, y: i32, z: i32) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits((x * 16) as i16),
            y: Coord::from_bits((y * 16) as i16),
            z: Coord::from_bits((z * 16) as i16),
        }
    }

    struct Mem<const N: usize, const F: usize> {
        traps: [Trapezoid; N],
        faces: [Face; F],
        segs: [Segment; 4],
        rows: [u16; 64],
        edges: [EdgeSlot; 8],
    }

    impl<const N: usize, const F: usize> Mem<N, F> {
        fn new() -> Self {
            Mem {
                traps: [Trapezoid::EMPTY; N],
                faces: [Face::EMPTY; F],
                segs: [Segment::EMPTY; 4],
                rows: [0; 64],
                edges: [EdgeSlot::EMPTY; 8],
            }
        }
        fn store(&mut self) -> TrapezoidStore<'_> {
            TrapezoidStore::new(
                StoreMemory {
                    trapezoids: &mut self.traps,
                    faces: &mut self.faces,
                    segments: &mut self.segs,
                    rows: &mut self.rows,
                    edges: &mut self.edges,
                },
                64,
                64,
            )
            .unwrap()
        }
    }

    /// `add_poly3` draws a `poly3` exactly when `front_facing` does, as
    /// `add_polygon` would (the same trapezoids and faces), and leaves
    /// the store and the segment's counters alone when it culls.
    #[test]
    fn poly3_is_drawn_when_front_facing() {
        use crate::display_list::{Command, DisplayList, Writer};
        let mut rng = testkit::rng::Rng(0x7019_3fac);
        let clip = ClipRect::full(64, 64);
        let (mut drawn, mut culled) = (0, 0);
        for case in 0..2000 {
            let n = 3 + rng.below(6) as usize;
            let mut poly = [Vertex3::default(); 8];
            for p in poly.iter_mut().take(n) {
                // Coarse grids make edge-on and degenerate ones likely.
                let g = [1, 16, 128][case % 3];
                let c = |r: &mut testkit::rng::Rng, span: u32| {
                    (r.below(span / g) * g as i32 - 64) as i16
                };
                *p = Vertex3 {
                    x: Coord::from_bits(c(&mut rng, 1152)),
                    y: Coord::from_bits(c(&mut rng, 1152)),
                    z: Coord::from_bits(c(&mut rng, 4096)),
                };
            }
            let poly = &poly[..n];
            let mut bytes = [0u8; 128];
            let mut w = Writer::new(&mut bytes, 64, 64).unwrap();
            w.poly3(poly.iter().copied()).unwrap();
            let list = DisplayList::new_checked(w.finish()).unwrap();
            let Some((_, Command::Poly3(v))) = list.commands().next() else {
                panic!("no poly3");
            };
            let (mut a, mut b) = (Mem::<32, 4>::new(), Mem::<32, 4>::new());
            let (mut sa, mut sb) = (a.store(), b.store());
            let front = front_facing(&v);
            let got = sa.add_poly3(1, &v, Rgb888::RED, &clip);
            if front {
                let want = sb.add_polygon(1, poly.iter().copied(), Rgb888::RED, &clip);
                assert_eq!(got.map(|_| ()), want.map(|_| ()), "{poly:?}");
                drawn += 1;
            } else {
                culled += 1;
            }
            assert_eq!(got.map_err(|_| ()), Ok(front), "{poly:?}");
            assert_eq!(sa.len(), sb.len(), "{poly:?}");
            assert_eq!(sa.face_count(), sb.face_count(), "{poly:?}");
            assert_eq!(sa.segments(), sb.segments(), "{poly:?}");
            let (ta, tb) = (sa.segment_trapezoids(1), sb.segment_trapezoids(1));
            assert!(ta.map(|t| t.1.fields()).eq(tb.map(|t| t.1.fields())));
            assert_eq!(sa.face(0), sb.face(0));
        }
        assert!(drawn > 500 && culled > 500, "{drawn} {culled}");
    }

    fn tri(k: i32) -> [Vertex3; 3] {
        [v(2 + k, 1, k), v(40 + k, 9 + k, k), v(5, 30 + k, k)]
    }

    /// Every trapezoid is in its segment's chain and in its row's list,
    /// once, and the counts agree.
    fn check(store: &TrapezoidStore<'_>) {
        let mut by_rows = 0;
        for y in 0..store.height() {
            for (_, t) in store.starting_at(y) {
                assert_eq!(t.top(), y as i32);
                by_rows += 1;
            }
        }
        let mut by_segs = 0;
        for s in 0..store.segments().len() {
            let n = store.segment_trapezoids(s).count();
            assert_eq!(n as u32, store.segment(s).unwrap().trapezoids());
            for (_, t) in store.segment_trapezoids(s) {
                assert_eq!(store.face(t.face()).unwrap().segment(), s as u16);
                assert_eq!(t.segment(), s as u16);
            }
            by_segs += n;
        }
        assert_eq!(by_rows, store.len());
        assert_eq!(by_segs, store.len());
    }

    #[test]
    fn clearing_one_segment_leaves_the_others_untouched() {
        let mut mem = Mem::<64, 16>::new();
        let mut store = mem.store();
        let clip = ClipRect::full(64, 64);
        for s in 0..3 {
            for k in 0..3 {
                store
                    .add_polygon(s, tri(k + 3 * s as i32), Rgb888::RED, &clip)
                    .unwrap();
            }
        }
        check(&store);
        let keep: [([u16; 16], usize); 3] = core::array::from_fn(|s| {
            let mut ids = [0; 16];
            let mut n = 0;
            for (i, _) in store.segment_trapezoids(s) {
                ids[n] = i;
                n += 1;
            }
            (ids, n)
        });
        let before: [Counters; 3] = core::array::from_fn(|s| store.segment(s).unwrap().counters());
        let snapshot: [Trapezoid; 64] =
            core::array::from_fn(|i| *store.trapezoid(i as u16).unwrap());

        store.clear_segment(1).unwrap();
        check(&store);
        store.add_polygon(1, tri(20), Rgb888::BLUE, &clip).unwrap();
        check(&store);

        for s in [0, 2] {
            assert_eq!(store.segment(s).unwrap().counters(), before[s]);
            let (ids, n) = keep[s];
            for &i in &ids[..n] {
                // Not moved, not recomputed.
                let t = store.trapezoid(i).unwrap();
                assert_eq!(t.left(), snapshot[i as usize].left());
                assert_eq!(t.fields(), snapshot[i as usize].fields());
                assert_eq!(t.face(), snapshot[i as usize].face());
            }
        }
        let c1 = store.segment(1).unwrap().counters();
        assert_eq!(c1.polygons, before[1].polygons + 1);
        assert_eq!(c1.clears, before[1].clears + 1);
        assert!(c1.trapezoids > before[1].trapezoids);
    }

    #[test]
    fn running_out_empties_the_segment_being_filled() {
        let mut mem = Mem::<5, 16>::new();
        let mut store = mem.store();
        let clip = ClipRect::full(64, 64);
        store.add_polygon(0, tri(0), Rgb888::RED, &clip).unwrap();
        store.add_polygon(1, tri(1), Rgb888::RED, &clip).unwrap();
        assert_eq!(store.len(), 4);
        let e = store.add_polygon(1, tri(2), Rgb888::RED, &clip);
        assert_eq!(e, Err(StoreError::Trapezoids { capacity: 5 }));
        check(&store);
        assert_eq!(store.segment(1).unwrap().trapezoids(), 0);
        assert_eq!(store.segment(1).unwrap().faces(), 0);
        assert_eq!(store.segment(0).unwrap().trapezoids(), 2);
        // The pool is whole again: segment 1 refills.
        store.add_polygon(1, tri(3), Rgb888::RED, &clip).unwrap();
        check(&store);
        assert_eq!(store.len(), 4);

        let mut mem = Mem::<64, 2>::new();
        let mut store = mem.store();
        store.add_polygon(2, tri(0), Rgb888::RED, &clip).unwrap();
        store.add_polygon(2, tri(1), Rgb888::RED, &clip).unwrap();
        assert_eq!(
            store.add_polygon(2, tri(2), Rgb888::RED, &clip),
            Err(StoreError::Faces { capacity: 2 })
        );
        assert_eq!(store.len(), 0);
        assert_eq!(store.face_count(), 0);
        assert_eq!(
            store.add_polygon(9, tri(2), Rgb888::RED, &clip),
            Err(StoreError::Segment {
                segment: 9,
                capacity: 4
            })
        );
    }

    /// A run of triangles (`triangle_run`) leaves the store exactly as
    /// `add_triangle` (a run of one) one by one does, and a run's polygon
    /// as `add_polygon` does: pools, chains, rows, faces, keys and
    /// counters; a hidden segment, a clip inside the frame, a pool that
    /// runs out part way and a bad segment too.
    #[test]
    fn a_triangle_run_is_its_triangles_one_by_one() {
        let mut rng = testkit::rng::Rng(0x51ce_7a11);
        let mut outcomes = [0; 3];
        for case in 0..600 {
            let (s, hidden) = ([0, 1, 3, 7][case % 4], case % 3 == 0);
            let clip = match case % 5 {
                0 => ClipRect::from_window(
                    ClipWindow {
                        x0: 5,
                        y0: 3,
                        x1: 50,
                        y1: 40,
                    },
                    64,
                    64,
                ),
                _ => ClipRect::full(64, 64),
            };
            let mut tris = [[v(0, 0, 0); 3]; 12];
            for t in tris.iter_mut() {
                for p in t.iter_mut() {
                    *p = v(rng.range(-8, 72), rng.range(-8, 72), rng.range(-50, 50));
                }
                if rng.below(8) == 0 {
                    t[2] = t[0];
                }
            }
            let tris = &tris[..4 + rng.below(9) as usize];
            let color = |k: usize| Rgb888::new(k as u8 * 20, 7, 200);
            let (mut one, mut run) = (Mem::<40, 9>::new(), Mem::<40, 9>::new());
            let mut a = one.store();
            let mut b = run.store();
            for st in [&mut a, &mut b] {
                st.add_polygon(2, tri(0), Rgb888::RED, &clip).unwrap();
                st.set_hidden(1, hidden).unwrap();
                st.set_highlight(3, Some(Rgb888::GREEN)).unwrap();
            }
            let mut want = Ok(());
            // Every third one a polygon of the run.
            let poly = |k: usize| k % 3 == 2;
            for (k, t) in tris.iter().enumerate() {
                let r = match poly(k) {
                    true => a.add_polygon(s, *t, color(k), &clip),
                    false => a.add_triangle(s, *t, color(k), &clip),
                };
                if let Err(e) = r {
                    want = Err(e);
                    break;
                }
            }
            let got = b.triangle_run(s, &clip, false, |r| {
                for (k, t) in tris.iter().enumerate() {
                    match poly(k) {
                        true => r.polygon(*t, color(k), 0)?,
                        false => r.triangle(*t, color(k))?,
                    };
                }
                Ok(())
            });
            assert_eq!(got, want, "case {case}");
            outcomes[match want {
                Ok(()) => 0,
                Err(StoreError::Segment { .. }) => 1,
                Err(_) => 2,
            }] += 1;
            assert_eq!(
                (a.free_trap, a.unused_trap, a.free_face, a.unused_face),
                (b.free_trap, b.unused_trap, b.free_face, b.unused_face),
                "case {case}"
            );
            assert_eq!((a.live, a.live_faces), (b.live, b.live_faces));
            assert_eq!(a.traps, b.traps, "case {case}");
            assert_eq!(a.faces, b.faces, "case {case}");
            assert_eq!(a.segments, b.segments, "case {case}");
            assert_eq!(a.rows, b.rows, "case {case}");
            if !(hidden && s == 1) {
                check(&b);
            }
        }
        assert!(outcomes.iter().all(|&n| n > 40), "{outcomes:?}");
    }

    #[test]
    fn edge_on_and_clipped_away_polygons_take_nothing() {
        let mut mem = Mem::<8, 4>::new();
        let mut store = mem.store();
        let clip = ClipRect::full(64, 64);
        let edge_on = [v(1, 1, 0), v(20, 20, 9), v(40, 40, 3)];
        assert_eq!(store.add_polygon(0, edge_on, Rgb888::RED, &clip), Ok(0));
        let outside = [v(-30, 1, 0), v(-2, 1, 0), v(-10, 20, 0)];
        assert_eq!(store.add_polygon(0, outside, Rgb888::RED, &clip), Ok(0));
        assert_eq!((store.len(), store.face_count()), (0, 0));
        assert_eq!(store.segment(0).unwrap().counters().polygons, 2);
    }

    #[test]
    fn a_segment_is_a_polygon_sink() {
        use crate::geometry::PolygonSink;
        let mut mem = Mem::<16, 4>::new();
        let mut store = mem.store();
        let mut sink = SegmentSink::new(&mut store, 2, ClipRect::full(64, 64));
        sink.polygon(&tri(0), Rgb888::RED, false).unwrap();
        sink.polygon(&tri(1), Rgb888::RED, true).unwrap();
        assert_eq!(store.segment(2).unwrap().counters().polygons, 2);
        assert_eq!(store.segment(2).unwrap().trapezoids(), 4);
    }

    #[test]
    fn index_shorter_than_the_frame_is_an_error() {
        let (mut t, mut f, mut s, mut r, mut e) = (
            [Trapezoid::EMPTY; 1],
            [Face::EMPTY; 1],
            [Segment::EMPTY; 1],
            [0u16; 10],
            [EdgeSlot::EMPTY; 1],
        );
        let mem = StoreMemory {
            trapezoids: &mut t,
            faces: &mut f,
            segments: &mut s,
            rows: &mut r,
            edges: &mut e,
        };
        assert_eq!(
            TrapezoidStore::new(mem, 4, 11).err(),
            Some(StoreError::Rows {
                height: 11,
                capacity: 10
            })
        );
    }
}
