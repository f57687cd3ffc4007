//! The scene: segments that the application's procedures build, kept
//! between frames and rebuilt only when they change.
//!
//! This is the retained mode of the 3D layer, after the classic dynamic 3D
//! display. A [`Scene`] holds
//!
//! * the [`Pipeline`] (camera, projection, light, window, the thickness of
//!   points and lines, and the modelling transform stack),
//! * the [`TrapezoidStore`]: every segment's trapezoids and faces, in
//!   screen space, with the scan-line index, and
//! * the [`LabelStore`]: every segment's labels, placed on the screen, and
//! * the visible-surface stage's [`Workspace`] (active list, runs).
//!
//! The application supplies one [`Procedure`] per segment (a closure, or
//! any type implementing the trait) that describes the segment through a
//! [`Builder`]: modelling transforms, faces, points, lines, labels. A
//! segment is *stale* when the application says it changed
//! ([`Scene::invalidate`]) and when anything it was projected with
//! changed: the camera, the projection, the light, the thickness or the
//! clip mark every segment stale. [`Scene::update`] rebuilds the stale
//! segments alone; the others keep their trapezoids and labels, so a frame
//! where one segment changed cuts only that segment's polygons again. The
//! store's per-segment [`Counters`](crate::visible::store::Counters) and
//! [`Update`] count the work.
//!
//! [`Scene::draw`] then resolves the visible surfaces row by row into
//! run-length-encoded scan lines, decodes them into the frame buffer as
//! spans, and draws the labels last, over everything.
//!
//! # Capacities
//!
//! The transform stack's depth and the vertices of one polygon (at every
//! clipping stage) are the const generics `DEPTH` and `N` of the
//! [`Pipeline`]. Everything else is the caller's memory, given in
//! [`SceneMemory`]: the store's pools (see [`store`](crate::visible::store)),
//! the visible-surface stage's workspace, the label slots and the label
//! text. [`SceneStorage`] owns all of it, its capacities const generics,
//! and lends it as a [`SceneMemory`]. Running out of any of them is an
//! error that names the pool, and leaves the segment being built empty
//! (and still stale), never half built.
//!
//! # Display lists
//!
//! A procedure may also describe its segment with display-list commands:
//! [`Builder::command`] is the one interpreter of the 3D commands (see
//! [`list`]), the one the [`Controller`](crate::controller::Controller)
//! renders a list's 3D layer with.
//!
//! # Example
//!
//! ```
//! use scanvert::port::framebuffer::FrameBuffer;
//! use scanvert::geometry::{Angle, Perspective, Pipeline, Point3, Q16, View, Viewport};
//! use scanvert::scene::label::DEFAULT_FONT;
//! use scanvert::pixelcolor::{Rgb565, Rgb888, RgbColor};
//! use scanvert::scene::{Builder, Procedure, Scene, SceneError, SceneStorage};
//! use scanvert::visible::sweep::Resolve;
//!
//! const W: u16 = 64;
//! const H: u16 = 48;
//! // 64 trapezoids, 16 faces, 2 segments, H rows, 16 edge slots,
//! // 16 active entries, W runs, 2 labels, 16 bytes of text.
//! let mut storage = SceneStorage::<64, 16, 2, { H as usize }, 16, 16, { W as usize }, 2, 16>::new();
//! let mem = storage.as_memory();
//! let q = Q16::from_int;
//! let persp = Perspective::from_fov(Angle::from_degrees(60), W, q(1), q(100)).unwrap();
//! let mut scene = Scene::new(mem, Pipeline::<4, 16>::new(persp, Viewport::centred(W, H).unwrap()))?;
//! scene.set_view(&View { eye: Point3::from_int(0, 0, 10), yaw: Angle::ZERO, pitch: Angle::ZERO })?;
//!
//! // Segment 0: a red square; segment 1: a blue one further back that
//! // moves, with a label.
//! let mut x = 0i16;
//! let square = |b: &mut Builder<'_, '_, 4, 16>, c: Rgb888| {
//!     let sq = [(-2, -2), (2, -2), (2, 2), (-2, 2)].map(|(x, y)| Point3::from_int(x, y, 0));
//!     b.face(&sq, c).map(|_| ())
//! };
//! let mut red = |b: &mut Builder<'_, '_, 4, 16>| square(b, Rgb888::RED);
//! let mut blue = |b: &mut Builder<'_, '_, 4, 16>| {
//!     b.translate(q(x), q(1), q(-5))?;
//!     square(b, Rgb888::BLUE)?;
//!     b.label(Point3::from_int(2, 2, 0), "B", Rgb888::WHITE).map(|_| ())
//! };
//! let u = scene.update(&mut [&mut red, &mut blue]).unwrap();
//! assert_eq!(u.regenerated, 2);
//!
//! let mut px = [Rgb565::BLACK; W as usize * H as usize];
//! let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
//! let f = scene.draw(Resolve::Crossing, Some(Rgb565::BLACK), DEFAULT_FONT, &mut fb).unwrap();
//! assert_eq!(f.labels.drawn, 1);
//! assert_eq!(fb.pixel(W / 2, H / 2), Some(Rgb565::RED));
//!
//! // Only the blue square moves: only its segment is rebuilt.
//! scene.invalidate(1)?;
//! let u = scene.update(&mut [&mut red, &mut blue]).unwrap();
//! assert_eq!(u.regenerated, 1);
//! assert_eq!(scene.store().segment(0).unwrap().counters().clears, 1);
//! assert_eq!(scene.store().segment(1).unwrap().counters().clears, 2);
//! # Ok::<(), SceneError>(())
//! ```

pub mod bands;
pub mod label;
#[doc(hidden)]
pub mod list;
pub mod mesh;
pub mod record;
pub mod storage;

pub use bands::{DirtyRows, SceneBands, SceneBandsError};

pub use crate::display_list::Placement;
pub use label::{Label, LabelStore, DEFAULT_FONT};
#[doc(hidden)]
pub use list::{list_pipeline, Attributes, Executed, ListState};
#[doc(hidden)]
pub use mesh::VertexTable;
pub use storage::{Capacities, SceneStorage};

use crate::color::ListColor;
use crate::display_list::{Axis, Command};
use crate::fixed::{Coord, Vertex3};
use crate::geometry::{
    Angle, Light, Outcome, Pipeline, PipelineError, Point3, Projection, ProjectionError,
    TransformError, TransformStack, View, ViewPoint, Q16,
};
use crate::port::{Counts, SpanTarget};
use crate::raster::clip::ClipRect;
use crate::visible::rle::Run;
use crate::visible::store::{StoreError, StoreMemory, TrapezoidStore, TriangleRun, LINE_BIAS};
use crate::visible::sweep::Checked;
use crate::visible::{self, Active, Resolve, VisibleError, VisibleStats, Workspace};
use core::fmt;
use embedded_graphics::mono_font::MonoFont;
use embedded_graphics_core::pixelcolor::Rgb888;
use label::{LabelCounts, LabelError};
use record::Records;

/// The caller's memory of a [`Scene`], of any capacities: slices over
/// the pools. [`SceneStorage`] owns one with its capacities as const
/// generics and lends it with [`SceneStorage::as_memory`].
///
/// | part | what it holds | limit |
/// |---|---|---|
/// | `store` | trapezoids, faces, segments, the scan-line index, edge slots (see [`store`](crate::visible::store)) | pools: 65535 each; index: the frame's height |
/// | `active` | trapezoids overlapping one row | 65535 |
/// | `runs` | runs of one row | at least the frame's width |
/// | `labels`, `text` | label slots and their text, shared by all segments | none |
#[derive(Debug)]
pub struct SceneMemory<'a> {
    /// The trapezoid store's pools; its `segments` slice sets how many
    /// segments the scene has, and its `rows` must cover the frame's
    /// height.
    pub store: StoreMemory<'a>,
    /// The active list of the visible-surface stage.
    pub active: &'a mut [Active],
    /// One row of runs: the frame's width is always enough.
    pub runs: &'a mut [Run],
    /// Label slots, shared by all segments.
    pub labels: &'a mut [Label],
    /// Label text, shared by all segments.
    pub text: &'a mut [u8],
}

impl SceneMemory<'_> {
    /// The same memory, lent for a shorter time.
    pub fn reborrow(&mut self) -> SceneMemory<'_> {
        SceneMemory {
            store: StoreMemory {
                trapezoids: &mut *self.store.trapezoids,
                faces: &mut *self.store.faces,
                segments: &mut *self.store.segments,
                rows: &mut *self.store.rows,
                edges: &mut *self.store.edges,
            },
            active: &mut *self.active,
            runs: &mut *self.runs,
            labels: &mut *self.labels,
            text: &mut *self.text,
        }
    }
}

/// A boundary between the stages of a render, reported to a [`Hook`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[doc(hidden)]
pub enum Stage {
    /// The 3D layer's build begins (the controller, after its checks).
    Start,
    /// The 3D commands have been executed and their polygons cut into
    /// trapezoids in the store.
    Cut,
    /// The active list has been checked against the store.
    Checked,
    /// The 2D commands have been drawn (the controller).
    Painted,
    /// The visible surfaces have been resolved and decoded into the
    /// target.
    Resolved,
    /// The labels have been drawn.
    Labelled,
}

/// Called at each [`Stage`] boundary of a render, to time the stages. Any
/// `FnMut(Stage)` is one; a closure that does nothing costs nothing.
#[doc(hidden)]
pub trait Hook {
    /// `stage` has just been reached.
    fn stage(&mut self, stage: Stage);
}

impl<F: FnMut(Stage)> Hook for F {
    #[inline(always)]
    fn stage(&mut self, stage: Stage) {
        self(stage)
    }
}

/// What [`Builder::mesh`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MeshStats {
    /// Vertices transformed (each once).
    pub vertices: u32,
    /// Faces cut into the segment (points and lines too).
    pub faces: u32,
    /// Faces culled (back-facing or edge-on).
    pub culled: u32,
    /// Faces wholly outside the depth range or the window.
    pub clipped_away: u32,
}

/// Why a segment could not be built, or a scene made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum SceneError {
    /// A pool of the trapezoid store ran out, or there is no such segment.
    Store(StoreError),
    /// The label slots or text ran out, or a text was refused.
    Labels(LabelError),
    /// A modelling transform failed: the stack is full or empty, or an
    /// entry left its range.
    Transform(TransformError),
    /// A vertex left view space's range under the current transform.
    Range,
    /// A polygon needs more vertices than the pipeline's `N`.
    Vertices {
        /// Vertices the pipeline holds.
        capacity: usize,
    },
    /// A projection or window was refused.
    Projection(ProjectionError),
    /// A light's direction is zero, or a view's eye is its target.
    Light,
    /// A `v` beyond the vertex table's slots.
    VertexTable {
        /// Slots of the table.
        capacity: usize,
    },
    /// An `f` index that names no vertex of the segment's table.
    Index {
        /// The 0-based index.
        index: usize,
        /// Vertices in the table.
        vertices: usize,
    },
    /// A segment's placement does not fit in the record buffer
    /// ([`Scene::keep_records`]; none given: 0 bytes).
    Records {
        /// Bytes of the buffer.
        capacity: usize,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Store(e) => write!(f, "{e}"),
            SceneError::Labels(e) => write!(f, "{e}"),
            SceneError::Transform(e) => write!(f, "{e}"),
            SceneError::Range => write!(f, "vertex outside the view-space range"),
            SceneError::Vertices { capacity } => {
                write!(f, "polygon needs more than {capacity} vertices")
            }
            SceneError::Projection(e) => write!(f, "{e}"),
            SceneError::Light => write!(f, "{}", crate::geometry::light::ZeroDirection),
            SceneError::VertexTable { capacity } => {
                write!(f, "the vertex table of {capacity} slots is full")
            }
            SceneError::Index { index, vertices } => {
                write!(f, "f names vertex {} of a table of {vertices}", index + 1)
            }
            SceneError::Records { capacity } => {
                write!(f, "the segment records' {capacity} bytes are full")
            }
        }
    }
}

impl core::error::Error for SceneError {}

impl From<crate::geometry::light::ZeroDirection> for SceneError {
    fn from(_: crate::geometry::light::ZeroDirection) -> Self {
        SceneError::Light
    }
}

impl From<StoreError> for SceneError {
    fn from(e: StoreError) -> Self {
        SceneError::Store(e)
    }
}

impl From<LabelError> for SceneError {
    fn from(e: LabelError) -> Self {
        SceneError::Labels(e)
    }
}

impl From<ProjectionError> for SceneError {
    fn from(e: ProjectionError) -> Self {
        SceneError::Projection(e)
    }
}

impl From<TransformError> for SceneError {
    fn from(e: TransformError) -> Self {
        SceneError::Transform(e)
    }
}

impl From<PipelineError<StoreError>> for SceneError {
    fn from(e: PipelineError<StoreError>) -> Self {
        match e {
            PipelineError::Range => SceneError::Range,
            PipelineError::Capacity { capacity } => SceneError::Vertices { capacity },
            PipelineError::Sink(e) => SceneError::Store(e),
        }
    }
}

/// An [`Scene::update`] that failed: the segment, left empty and stale,
/// and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct UpdateError {
    /// The segment whose procedure failed.
    pub segment: usize,
    /// Why.
    pub error: SceneError,
}

impl fmt::Display for UpdateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "segment {}: {}", self.segment, self.error)
    }
}

impl core::error::Error for UpdateError {}

/// The application's description of one segment, run whenever the segment
/// is rebuilt. Any `FnMut(&mut Builder) -> Result<(), SceneError>` is one.
pub trait Procedure<const DEPTH: usize, const N: usize> {
    /// Describes the segment into `segment`, which starts empty with the
    /// camera's transform.
    fn build(&mut self, segment: &mut Builder<'_, '_, DEPTH, N>) -> Result<(), SceneError>;
}

impl<F, const DEPTH: usize, const N: usize> Procedure<DEPTH, N> for F
where
    F: FnMut(&mut Builder<'_, '_, DEPTH, N>) -> Result<(), SceneError>,
{
    fn build(&mut self, segment: &mut Builder<'_, '_, DEPTH, N>) -> Result<(), SceneError> {
        self(segment)
    }
}

/// What one [`Scene::update`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Update {
    /// Segments rebuilt.
    pub regenerated: u32,
    /// Polygons, lines and points their procedures gave.
    pub given: u32,
    /// Of those, the ones that reached the store (not culled, not clipped
    /// away).
    pub polygons: u32,
    /// Trapezoids cut for them.
    pub trapezoids: u32,
    /// Labels placed.
    pub labels: u32,
    /// From [`update_marking`](Scene::update_marking): `true` when its
    /// scratch held fewer than two hashes a row, so every row a rebuilt
    /// segment covered before or covers after was marked, changed or
    /// not.
    pub coarse_marks: bool,
    /// Segments re-cut from their records without running their
    /// procedures ([`Scene::place`]).
    pub recut: u32,
    /// Stale segments left as they are because they are hidden
    /// ([`Scene::set_visible`]): they are rebuilt when shown.
    pub hidden: u32,
}

/// What one [`Scene::draw`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Frame {
    /// The visible-surface pass.
    pub visible: VisibleStats,
    /// The decoder's spans and pixels.
    pub decoded: Counts,
    /// The labels.
    pub labels: LabelCounts,
}

/// Segments of polygons and labels, kept in screen space between frames
/// (see the [module](self) docs).
#[derive(Debug)]
pub struct Scene<'a, const DEPTH: usize, const N: usize> {
    store: TrapezoidStore<'a>,
    labels: LabelStore<'a>,
    workspace: Workspace<'a>,
    pipeline: Pipeline<DEPTH, N>,
    clip: ClipRect,
    /// The most trapezoids on one row, as [`Scene::check`] last found it
    /// (`None` once a segment is emptied or rebuilt since): a pass in
    /// another workspace ([`Scene::bands_in`]) then only compares its
    /// capacity, instead of finding the number again.
    checked: Option<Checked>,
    /// The segments' records ([`Scene::keep_records`]).
    records: Records<'a>,
}

impl<'a, const DEPTH: usize, const N: usize> Scene<'a, DEPTH, N> {
    /// An empty scene on the pipeline's window, every segment stale.
    /// Fails when the store's index has fewer rows than the window.
    pub fn new(mem: SceneMemory<'a>, pipeline: Pipeline<DEPTH, N>) -> Result<Self, SceneError> {
        let (w, h) = (pipeline.viewport().width(), pipeline.viewport().height());
        Self::with_frame(mem, pipeline, w, h)
    }

    /// An empty scene drawn into a frame of `width × height` pixels,
    /// whatever the pipeline's window: polygons are projected onto the
    /// window and cut to the frame (a target smaller than the window shows
    /// its top-left part, unscaled). Every segment is stale. Fails when
    /// the store's index has fewer rows than the frame.
    pub fn with_frame(
        mem: SceneMemory<'a>,
        pipeline: Pipeline<DEPTH, N>,
        width: u16,
        height: u16,
    ) -> Result<Self, SceneError> {
        let store = TrapezoidStore::new(mem.store, width, height)?;
        let mut scene = Scene {
            store,
            labels: LabelStore::new(mem.labels, mem.text),
            workspace: Workspace::new(mem.active, mem.runs),
            pipeline,
            clip: ClipRect::full(width, height),
            checked: None,
            records: Records::default(),
        };
        scene.invalidate_all();
        Ok(scene)
    }

    /// Segments the scene holds.
    pub fn segments(&self) -> usize {
        self.store.segments().len()
    }

    /// The trapezoid store, with its per-segment counters.
    pub fn store(&self) -> &TrapezoidStore<'a> {
        &self.store
    }

    /// The labels placed.
    pub fn labels(&self) -> &LabelStore<'a> {
        &self.labels
    }

    /// The geometry stage, with its counters.
    pub fn pipeline(&self) -> &Pipeline<DEPTH, N> {
        &self.pipeline
    }

    /// Moves the camera; every segment becomes stale.
    pub fn set_view(&mut self, view: &View) -> Result<(), SceneError> {
        self.pipeline.set_view(view)?;
        self.invalidate_all();
        Ok(())
    }

    /// Replaces the projection; every segment becomes stale.
    pub fn set_projection(&mut self, projection: impl Into<Projection>) {
        self.pipeline.set_projection(projection);
        self.invalidate_all();
    }

    /// Replaces the light; every segment becomes stale.
    pub fn set_light(&mut self, light: Light) {
        self.pipeline.set_light(light);
        self.invalidate_all();
    }

    /// Sets the thickness of points and lines; every segment becomes
    /// stale.
    pub fn set_thickness(&mut self, thickness: Coord) {
        self.pipeline.set_thickness(thickness);
        self.invalidate_all();
    }

    /// Draws polygons only inside `clip` (cut to the window); every
    /// segment becomes stale. Labels are not clipped.
    pub fn set_clip(&mut self, clip: ClipRect) {
        self.clip = clip;
        self.invalidate_all();
    }

    /// Marks segment `s` as changed: the next [`update`](Self::update)
    /// rebuilds it.
    pub fn invalidate(&mut self, s: usize) -> Result<(), SceneError> {
        Ok(self.store.set_stale(s, true)?)
    }

    /// Marks every segment as changed.
    pub fn invalidate_all(&mut self) {
        for s in 0..self.segments() {
            let _ = self.store.set_stale(s, true);
        }
    }

    /// `true` when segment `s` will be rebuilt by the next update.
    pub fn is_stale(&self, s: usize) -> bool {
        self.store.segment(s).is_some_and(|g| g.is_stale())
    }

    /// Rebuilds every stale segment `s` that has a procedure
    /// (`procedures[s]`), and nothing else. Stops at the first failure,
    /// which leaves that segment empty and stale.
    pub fn update(
        &mut self,
        procedures: &mut [&mut dyn Procedure<DEPTH, N>],
    ) -> Result<Update, UpdateError> {
        let mut u = Update::default();
        for (s, p) in procedures.iter_mut().enumerate() {
            if !self.is_stale(s) {
                continue;
            }
            if self.is_hidden(s) {
                u.hidden += 1;
                continue;
            }
            let before = self.store.segment(s).map(|g| g.counters());
            let given = self.pipeline.stats().faces_in;
            let labels = self.labels.len();
            self.rebuild(s, &mut **p)
                .map_err(|error| UpdateError { segment: s, error })?;
            if let (Some(b), Some(g)) = (before, self.store.segment(s)) {
                let a = g.counters();
                u.polygons += a.polygons.wrapping_sub(b.polygons);
                u.trapezoids += a.trapezoids.wrapping_sub(b.trapezoids);
            }
            u.given += self.pipeline.stats().faces_in.wrapping_sub(given);
            // The segment's labels were removed, then its new ones added.
            u.labels += self.labels.len().saturating_sub(labels) as u32;
            u.regenerated += 1;
        }
        Ok(u)
    }

    /// Rebuilds segment `s` with `procedure` now, stale or not. On a
    /// failure the segment is left empty and stale.
    pub fn rebuild(
        &mut self,
        s: usize,
        procedure: &mut dyn Procedure<DEPTH, N>,
    ) -> Result<(), SceneError> {
        let mut b = self.open(s)?;
        let r = procedure.build(&mut b);
        if r.is_err() {
            self.empty(s);
        }
        r
    }

    /// `true` when segment `s` is hidden ([`set_visible`](Self::set_visible)).
    pub fn is_hidden(&self, s: usize) -> bool {
        self.store.segment(s).is_some_and(|g| g.is_hidden())
    }

    /// Shows (`true`) or hides (`false`) segment `s`. A hidden segment
    /// keeps its trapezoids and labels but no pass sees them, and an
    /// update leaves it stale rather than rebuilding it
    /// ([`Update::hidden`]); showing it puts them back, with nothing cut
    /// (a segment that went stale while hidden is rebuilt by the next
    /// update). No procedure runs: the [`Update`] says so. Its rows
    /// change: [`mark_segment_rows`](Self::mark_segment_rows) marks them
    /// for [`draw_marked`](Self::draw_marked).
    pub fn set_visible(&mut self, s: usize, visible: bool) -> Result<Update, SceneError> {
        self.store.set_hidden(s, !visible)?;
        self.labels.set_hidden(s as u16, !visible);
        self.checked = None;
        Ok(Update::default())
    }

    /// Draws segment `s`'s faces, points and lines in `color`, unlit,
    /// instead of their own colours, or in their own again (`None`). Its
    /// labels keep their colours. The store's faces are recoloured where
    /// they are: nothing is cut, no procedure runs (the [`Update`] says
    /// so), and a rebuild keeps the highlight. Its rows change:
    /// [`mark_segment_rows`](Self::mark_segment_rows) marks them.
    pub fn set_highlight(&mut self, s: usize, color: Option<Rgb888>) -> Result<Update, SceneError> {
        self.store.set_highlight(s, color)?;
        Ok(Update::default())
    }

    /// The highlight of segment `s`, if any.
    pub fn highlight(&self, s: usize) -> Option<Rgb888> {
        self.store.segment(s).and_then(|g| g.highlight())
    }

    /// Keeps the segments' records in `bytes` from now on, so that
    /// [`place`](Self::place) moves a segment without running its
    /// procedure (see [`record`]; [`records_needed`](Self::records_needed)
    /// sizes it). Every segment becomes stale, to be recorded by the next
    /// update; placements set before are dropped.
    pub fn keep_records(&mut self, bytes: &'a mut [u8]) {
        self.records = Records::new(bytes);
        self.invalidate_all();
    }

    /// The most bytes of the record buffer the scene has held at once:
    /// run the program's frames, as for [`needed`](Self::needed), and take
    /// the largest.
    pub fn records_needed(&self) -> usize {
        self.records.peak()
    }

    /// Segment `s`'s placement ([`Placement::IDENTITY`] until placed).
    pub fn placement(&self, s: usize) -> Placement {
        self.records.placement(s as u16)
    }

    /// Places segment `s`: it is built as if its procedure began with
    /// `placement`'s transforms (see [`Placement`]), now and at every
    /// rebuild. A segment with a complete record (see [`record`]) is
    /// re-transformed and re-cut from it at once, its procedure not run
    /// ([`Update::recut`]); one without is marked stale, and the next
    /// update runs its procedure. The rows it covered before and covers
    /// after change: [`mark_segment_rows`](Self::mark_segment_rows), called
    /// before and after, marks them.
    ///
    /// Fails for an unknown segment, and with [`SceneError::Records`]
    /// when the record buffer has no room for the placement. A failure
    /// of the re-cut (a pool ran out, a vertex left the range) leaves the
    /// segment empty and stale, as a failed update does.
    pub fn place(&mut self, s: usize, placement: Placement) -> Result<Update, SceneError> {
        if self.store.segment(s).is_none() {
            self.store.set_stale(s, true)?;
        }
        if !self.records.set_placement(s as u16, placement) {
            return Err(SceneError::Records {
                capacity: self.records.capacity(),
            });
        }
        if self.is_stale(s) || self.records.commands(s as u16).is_none() {
            self.store.set_stale(s, true)?;
            return Ok(Update::default());
        }
        let before = self.store.segment(s).map(|g| g.counters());
        let given = self.pipeline.stats().faces_in;
        let r = self.replay(s);
        if r.is_err() {
            self.empty(s);
        }
        r?;
        let mut u = Update {
            recut: 1,
            ..Update::default()
        };
        if let (Some(b), Some(g)) = (before, self.store.segment(s)) {
            let a = g.counters();
            u.polygons = a.polygons.wrapping_sub(b.polygons);
            u.trapezoids = a.trapezoids.wrapping_sub(b.trapezoids);
        }
        u.given = self.pipeline.stats().faces_in.wrapping_sub(given);
        u.labels = self
            .labels
            .iter()
            .filter(|(l, _)| usize::from(l.segment()) == s)
            .count() as u32;
        Ok(u)
    }

    /// Builds segment `s` again from its record, under its placement.
    fn replay(&mut self, s: usize) -> Result<(), SceneError> {
        self.checked = None;
        self.store.clear_segment(s)?;
        self.labels.clear_segment(s as u16);
        self.store.set_stale(s, false)?;
        self.pipeline.reset_stack();
        let hidden = self.is_hidden(s);
        let Scene {
            store,
            labels,
            pipeline,
            records,
            clip,
            ..
        } = self;
        records.placement(s as u16).apply(pipeline.stack_mut())?;
        let mut st = ListState::with_clip(store.width(), store.height(), *clip);
        let mut out = SegmentOut {
            to: To::Store(store),
            labels,
            segment: s,
        };
        let mut none = VertexTable::none();
        for cmd in record::commands(records.commands(s as u16).unwrap_or(&[])) {
            list::execute(pipeline, &mut out, &mut st, &mut none, cmd)?;
        }
        if hidden {
            self.labels.set_hidden(s as u16, true);
        }
        Ok(())
    }

    /// Empties segment `s` and returns a [`Builder`] to describe it anew
    /// (what [`rebuild`](Self::rebuild) does around a procedure). The
    /// segment counts as built from here on.
    pub fn open(&mut self, s: usize) -> Result<Builder<'_, 'a, DEPTH, N>, SceneError> {
        self.checked = None;
        self.store.clear_segment(s)?;
        self.labels.clear_segment(s as u16);
        self.store.set_stale(s, false)?;
        self.pipeline.reset_stack();
        self.records.begin(s as u16);
        let placement = self.records.placement(s as u16);
        if let Err(e) = placement.apply(self.pipeline.stack_mut()) {
            self.empty(s);
            return Err(e.into());
        }
        Ok(Builder {
            scene: self,
            segment: s,
        })
    }

    fn empty(&mut self, s: usize) {
        self.checked = None;
        let _ = self.store.clear_segment(s);
        self.labels.clear_segment(s as u16);
        let _ = self.store.set_stale(s, true);
    }

    /// Finds the most trapezoids that overlap one row and checks them
    /// against the active list, and the frame's width against the runs,
    /// without drawing (see [`Workspace::check`]). The scene remembers
    /// the number until a segment changes, so that passes in other
    /// workspaces ([`Scene::bands_in`], one per core) need not find it
    /// again.
    pub fn check(&mut self) -> Result<u32, VisibleError<core::convert::Infallible>> {
        let c = self.workspace.check_rows(&self.store)?;
        self.checked = Some(c);
        Ok(c.most)
    }

    /// What [`check`](Self::check) last found, found again if a segment
    /// changed since.
    pub(crate) fn checked(&mut self) -> Result<Checked, VisibleError<core::convert::Infallible>> {
        match self.checked {
            Some(c) => Ok(c),
            None => self.check().map(|_| self.checked.unwrap_or_default()),
        }
    }

    /// The mode `resolve` settles to for the scene as it stands
    /// ([`Resolve::settle`]), its depths worked out if it paints.
    pub(crate) fn settle(
        &mut self,
        resolve: Resolve,
    ) -> Result<Resolve, VisibleError<core::convert::Infallible>> {
        let resolve = match resolve {
            Resolve::Auto => self.checked()?.settle(resolve),
            m => m,
        };
        if resolve == Resolve::Paint {
            self.store.work_out_depths();
        }
        Ok(resolve)
    }

    /// What the scene uses now, as [`SceneStorage`] capacities: the
    /// trapezoids, faces and labels in use and their text, the most
    /// trapezoids on one row ([`Scene::check`]), the frame's rows and
    /// width, its segments, and the pipeline's `N` edge slots (scratch
    /// for one polygon, whose need is its vertices after clipping: at most
    /// `N`). A frame can need more while it is built than it holds once
    /// built: to size storage, take [`needed`](Self::needed) instead.
    ///
    /// Fails as [`Scene::check`] does when the active list is too short.
    pub fn usage(&mut self) -> Result<Capacities, VisibleError<core::convert::Infallible>> {
        let active = self.check()? as usize;
        Ok(Capacities {
            trapezoids: self.store.len(),
            faces: self.store.face_count(),
            segments: self.store.segments().len(),
            rows: self.store.height() as usize,
            edges: N,
            active,
            runs: self.store.width() as usize,
            labels: self.labels.len(),
            text: self.labels.text_len(),
        })
    }

    /// The storage the scene has needed so far, as [`SceneStorage`]
    /// capacities: the most trapezoids and faces its store held at once
    /// since the scene was made, the most labels and bytes of label text,
    /// and, as [`usage`](Self::usage) gives them, the most trapezoids on
    /// one row of the frame as it is now, the frame's rows and width, the
    /// segments and the pipeline's `N` edge slots.
    ///
    /// This is capacity planning in the library: run the program's frames
    /// (its procedures, its views) in storage large enough, call this after
    /// each frame, and the [`Capacities::max`] of the results is storage
    /// that runs the same frames without running out. Pools hand out any
    /// free slot, so a pool that holds the most ever held at once is never
    /// short; the peaks count the moments inside an update, when a segment
    /// being rebuilt is stored while another still holds its last frame.
    ///
    /// ```
    /// # use scanvert::prelude::*;
    /// # use scanvert::{Angle, Perspective, Pipeline, Point3, Procedure, Scene, SceneError, View, Viewport, Q16};
    /// # use scanvert::scene::{Capacities, SceneStorage};
    /// // Generous storage, on the host or in a spare region of RAM.
    /// let mut big = Box::new(SceneStorage::<512, 64, 2, 64, 16, 64, 64, 4, 64>::new());
    /// let persp = Perspective::from_fov(Angle::from_degrees(50), 64, Q16::from_int(1), Q16::from_int(100)).unwrap();
    /// let mut scene = Scene::new(big.as_memory(), Pipeline::<4, 16>::new(persp, Viewport::centred(64, 64).unwrap()))?;
    /// scene.set_view(&View { eye: Point3::from_int(0, 0, 10), yaw: Angle::ZERO, pitch: Angle::ZERO })?;
    /// let mut needed: Option<Capacities> = None;
    /// for frame in 0..8 {
    ///     // The program's frame: here a quad that grows.
    ///     let mut quad = |b: &mut scanvert::Builder<'_, '_, 4, 16>| {
    ///         let s = 1 + frame;
    ///         let p = |x, y| Point3::from_int(x, y, 0);
    ///         b.face(&[p(-s, -s), p(s, -s), p(s, s), p(-s, s)], Rgb888::RED).map(|_| ())
    ///     };
    ///     scene.invalidate(0)?;
    ///     let procs: &mut [&mut dyn Procedure<4, 16>] = &mut [&mut quad];
    ///     scene.update(procs).unwrap();
    ///     let now = scene.needed().unwrap();
    ///     needed = Some(needed.map_or(now, |n| n.max(now)));
    /// }
    /// let needed = needed.unwrap();
    /// // Declare exactly that, by name, and check it at compile time
    /// // with `Capacities::covers` (see `scene_storage!`).
    /// assert!(needed.trapezoids >= 1 && needed.faces == 1, "{needed:?}");
    /// # Ok::<(), SceneError>(())
    /// ```
    ///
    /// Fails as [`Scene::check`] does when the active list is too short.
    pub fn needed(&mut self) -> Result<Capacities, VisibleError<core::convert::Infallible>> {
        let now = self.usage()?;
        let (trapezoids, faces) = self.store.peak();
        let (labels, text) = self.labels.peak();
        Ok(Capacities {
            trapezoids,
            faces,
            labels,
            text,
            ..now
        })
    }

    /// Draws the scene into `target`: the visible surfaces resolved with
    /// `resolve` through the scene's workspace and decoded as spans
    /// (background runs filled with `background`, or left as they are
    /// with `None`), then every label in `font`, over everything.
    pub fn draw<T>(
        &mut self,
        resolve: Resolve,
        background: Option<T::Color>,
        font: &MonoFont<'_>,
        target: &mut T,
    ) -> Result<Frame, VisibleError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        self.draw_with(resolve, background, font, target, &mut |_| {})
    }

    /// [`draw`](Self::draw), telling `hook` when the visible surfaces are
    /// drawn ([`Stage::Resolved`]) and when the labels are
    /// ([`Stage::Labelled`]).
    #[doc(hidden)]
    pub fn draw_with<T, H>(
        &mut self,
        resolve: Resolve,
        background: Option<T::Color>,
        font: &MonoFont<'_>,
        target: &mut T,
        hook: &mut H,
    ) -> Result<Frame, VisibleError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
        H: Hook + ?Sized,
    {
        // Where overdraw costs, `visible::draw` settles `Auto` itself (it
        // never paints there), and no depth is worked out for painting.
        let resolve = if T::OVERDRAW_IS_CHEAP {
            self.settle(resolve).map_err(VisibleError::widen)?
        } else {
            resolve
        };
        let (visible, decoded) = visible::draw(
            &self.store,
            &mut self.workspace,
            resolve,
            target,
            background,
        )?;
        hook.stage(Stage::Resolved);
        let labels = self.labels.draw(font, target).map_err(VisibleError::Sink)?;
        hook.stage(Stage::Labelled);
        Ok(Frame {
            visible,
            decoded,
            labels,
        })
    }
}

/// A segment of a scene as the interpreter's [`Out`](list::Out): one
/// type for a single command's polygons and a run's, so that the
/// interpreter's mesh path is compiled once.
struct SegmentOut<'s, 'r, 'a> {
    to: To<'s, 'r, 'a>,
    labels: &'s mut LabelStore<'a>,
    segment: usize,
}

/// Where a [`SegmentOut`]'s polygons go.
enum To<'s, 'r, 'a> {
    /// Into the store, one adder set up for each.
    Store(&'s mut TrapezoidStore<'a>),
    /// Through the adder of a run of `v`s and `f`s
    /// ([`TrapezoidStore::triangle_run`]), under the run's clip: a run
    /// does not change the list's clip.
    Run(&'s mut TriangleRun<'r>),
}

impl SegmentOut<'_, '_, '_> {
    /// A single command's polygon, through the store's one-polygon
    /// adder. Out of line, as [`triangle_alone`](Self::triangle_alone).
    #[inline(never)]
    fn polygon_alone<I: IntoIterator<Item = Vertex3>>(
        store: &mut TrapezoidStore<'_>,
        segment: usize,
        vertices: I,
        color: Rgb888,
        clip: &ClipRect,
        lift: u16,
    ) -> Result<u32, StoreError> {
        store.add_lifted(segment, vertices, color, clip, lift)
    }

    /// A single command's triangle, through a run of one
    /// ([`TrapezoidStore::add_triangle`]). Out of line, so that a run's
    /// triangle goes to its adder with the single command's set-up out
    /// of the way (inlined, it cost a mesh frame's run about 19
    /// instructions a drawn face on the Cortex-M4).
    #[inline(never)]
    fn triangle_alone(
        store: &mut TrapezoidStore<'_>,
        segment: usize,
        v: [Vertex3; 3],
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<u32, StoreError> {
        store.add_triangle(segment, v, color, clip)
    }
}

impl list::Out for SegmentOut<'_, '_, '_> {
    #[inline(always)]
    fn polygon<I: IntoIterator<Item = Vertex3>>(
        &mut self,
        vertices: I,
        color: Rgb888,
        clip: &ClipRect,
        point_or_line: bool,
    ) -> Result<(), SceneError> {
        let lift = if point_or_line { LINE_BIAS } else { 0 };
        match &mut self.to {
            To::Store(store) => {
                Self::polygon_alone(store, self.segment, vertices, color, clip, lift)
            }
            To::Run(run) => run.polygon(vertices, color, lift),
        }
        .map(|_| ())
        .map_err(SceneError::Store)
    }

    #[inline(always)]
    fn triangle(
        &mut self,
        v: [Vertex3; 3],
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<(), SceneError> {
        match &mut self.to {
            To::Store(store) => Self::triangle_alone(store, self.segment, v, color, clip),
            To::Run(run) => run.triangle(v, color),
        }
        .map(|_| ())
        .map_err(SceneError::Store)
    }

    fn poly3(
        &mut self,
        vertices: &crate::display_list::Vertices3<'_>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<bool, SceneError> {
        match &mut self.to {
            To::Store(store) => store
                .add_poly3(self.segment, vertices, color, clip)
                .map_err(SceneError::Store),
            // Never met: a run holds nothing but `v`s and `f`s
            // (`list::mesh_run`). Nothing drawn.
            To::Run(_) => Ok(false),
        }
    }

    fn label(&mut self, at: (i32, i32), color: Rgb888, text: &str) -> Result<bool, SceneError> {
        self.labels
            .add(self.segment as u16, at, color, text)
            .map_err(SceneError::Labels)
    }

    fn changed(&mut self) {
        // The other segments were projected with what changed.
        match &mut self.to {
            To::Store(store) => {
                for s in (0..store.segments().len()).filter(|&s| s != self.segment) {
                    let _ = store.set_stale(s, true);
                }
            }
            To::Run(run) => run.others_stale(),
        }
    }
}

/// One segment being described: modelling transforms, polygons and
/// labels, each through the scene's pipeline into the segment.
#[derive(Debug)]
pub struct Builder<'s, 'a, const DEPTH: usize, const N: usize> {
    scene: &'s mut Scene<'a, DEPTH, N>,
    segment: usize,
}

impl<'a, const DEPTH: usize, const N: usize> Builder<'_, 'a, DEPTH, N> {
    /// The segment being built.
    pub fn segment(&self) -> usize {
        self.segment
    }

    /// The modelling transform stack (the camera's matrix at the bottom).
    /// What is done to it here is not recorded: the segment's record is
    /// given up (see [`record`]), and placing it runs its procedure.
    #[doc(hidden)]
    pub fn stack_mut(&mut self) -> &mut TransformStack<DEPTH> {
        self.scene.records.give_up();
        self.scene.pipeline.stack_mut()
    }

    /// Records what `write` writes in the segment's record.
    fn record(
        &mut self,
        color: Option<Rgb888>,
        write: impl FnOnce(
            &mut crate::display_list::Writer<'_>,
        ) -> Result<(), crate::display_list::WriteError>,
    ) {
        self.scene.records.append(self.segment, color, write);
    }

    /// Saves the modelling transform.
    pub fn push(&mut self) -> Result<(), SceneError> {
        self.scene.pipeline.stack_mut().push()?;
        self.record(None, |w| w.push());
        Ok(())
    }

    /// Restores the modelling transform saved last.
    pub fn pop(&mut self) -> Result<(), SceneError> {
        self.scene.pipeline.stack_mut().pop()?;
        self.record(None, |w| w.pop());
        Ok(())
    }

    /// Translates what follows by `(x, y, z)`.
    pub fn translate(&mut self, x: Q16, y: Q16, z: Q16) -> Result<(), SceneError> {
        self.scene.pipeline.stack_mut().translate(x, y, z)?;
        self.record(None, |w| w.translate(Point3::new(x, y, z)));
        Ok(())
    }

    /// Rotates what follows about `axis`.
    pub fn rotate(&mut self, axis: Axis, angle: Angle) -> Result<(), SceneError> {
        let s = self.scene.pipeline.stack_mut();
        match axis {
            Axis::X => s.rotate_x(angle),
            Axis::Y => s.rotate_y(angle),
            Axis::Z => s.rotate_z(angle),
        }?;
        self.scene.records.rotate(self.segment, axis, angle);
        Ok(())
    }

    /// Scales what follows, per axis.
    pub fn scale(&mut self, x: Q16, y: Q16, z: Q16) -> Result<(), SceneError> {
        self.scene.pipeline.stack_mut().scale(x, y, z)?;
        self.record(None, |w| w.scale(Point3::new(x, y, z)));
        Ok(())
    }

    /// A polygon in model coordinates: one point, a point; two, a line;
    /// three or more, a face, front where they run counter-clockwise.
    pub fn face(&mut self, points: &[Point3], color: Rgb888) -> Result<Outcome, SceneError> {
        let clip = self.scene.clip;
        let (pipeline, mut out) = self.split();
        let r = list::face(
            pipeline,
            &mut out,
            points.iter().copied(),
            color,
            clip,
            None,
        )?;
        self.record(Some(color), |w| w.face(points.iter().copied()));
        Ok(r)
    }

    /// A mesh in model coordinates: each of `vertices` transformed once
    /// into `slots` (at least `vertices.len()` of them, else
    /// [`SceneError::VertexTable`]), then one face for each `sides`
    /// consecutive 0-based `indices` (1: points, 2: lines, 3: triangles…;
    /// a last, shorter group is a face too), each drawing exactly what
    /// [`face`](Self::face) draws through the same points. An index
    /// past `vertices` is [`SceneError::Index`], with nothing of that face
    /// drawn (the faces before it are).
    pub fn mesh(
        &mut self,
        vertices: &[Point3],
        indices: &[u16],
        sides: usize,
        color: Rgb888,
        slots: &mut [ViewPoint],
    ) -> Result<MeshStats, SceneError> {
        let clip = self.scene.clip;
        let (pipeline, mut out) = self.split();
        let mut table = VertexTable::new(slots);
        let mut stats = MeshStats::default();
        for &p in vertices {
            table.push(pipeline.view_point(p))?;
            stats.vertices += 1;
        }
        for face in indices.chunks(sides.max(1)) {
            let ix = face.iter().map(|&i| usize::from(i));
            match list::mesh_face(pipeline, &mut out, &mut table, ix, color, clip, None)? {
                Outcome::Emitted => stats.faces += 1,
                Outcome::Culled => stats.culled += 1,
                _ => stats.clipped_away += 1,
            }
        }
        // Recorded as faces through the same points: the same pixels.
        for face in indices.chunks(sides.max(1)) {
            // Every index was checked by the face drawn above.
            let points = face.iter().map(|&i| {
                vertices
                    .get(usize::from(i))
                    .copied()
                    .unwrap_or(Point3::ORIGIN)
            });
            self.scene
                .records
                .append(self.segment, Some(color), |w| w.face(points));
        }
        Ok(stats)
    }

    /// A label whose first character's lower-left corner is at the model
    /// point `at` (see [`label`]). `Ok(false)` when the point
    /// lies before the near plane or too far off the window to show.
    pub fn label(&mut self, at: Point3, text: &str, color: Rgb888) -> Result<bool, SceneError> {
        let (pipeline, mut out) = self.split();
        let placed = list::place_label(pipeline, &mut out, at, text, color)?;
        self.record(Some(color), |w| w.label(at, text));
        if self.scene.is_hidden(self.segment) {
            self.scene.labels.set_hidden(self.segment as u16, true);
        }
        Ok(placed)
    }

    /// Executes one command of a display list into the segment, with the
    /// list's colour and clip registers in `state` (see [`list`]): the
    /// one interpreter of the 3D commands, which
    /// [`Controller`](crate::controller::Controller) renders lists with.
    /// 2D commands are left alone. A command that changes the camera, the
    /// projection, the light or the thickness makes every other segment
    /// stale.
    pub fn command(
        &mut self,
        cmd: Command<'_>,
        state: &mut ListState,
    ) -> Result<Executed, SceneError> {
        self.command_in(cmd, state, &mut VertexTable::none())
    }

    /// [`command`](Self::command) with a mesh vertex table: a `v` goes
    /// into `table`, an `f` draws through it, a `segment` empties it.
    #[doc(hidden)]
    pub fn command_in(
        &mut self,
        cmd: Command<'_>,
        state: &mut ListState,
        table: &mut VertexTable<'_>,
    ) -> Result<Executed, SceneError> {
        let (pipeline, mut out) = self.split();
        let r = list::execute(pipeline, &mut out, state, table, cmd)?;
        if self.scene.records.recording() {
            if matches!(cmd, Command::Face(_)) && *state.clip() != self.scene.clip {
                // The record is replayed under the scene's clip.
                self.scene.records.give_up();
            }
            self.scene
                .records
                .command(self.segment, &cmd, state.color());
        }
        if matches!(cmd, Command::Label { .. }) && self.scene.is_hidden(self.segment) {
            self.scene.labels.set_hidden(self.segment as u16, true);
        }
        Ok(r)
    }

    /// The `v`s and `f`s that come next in `cmds`, executed as
    /// [`command_in`](Self::command_in) executes them, in one loop
    /// ([`list::mesh_run`]); stops before any other command. Nothing is
    /// taken when the segment is hidden or being recorded: its commands
    /// then go one by one through `command_in`. The error names the
    /// offset of the command that failed.
    #[doc(hidden)]
    pub fn mesh_run(
        &mut self,
        cmds: &mut crate::display_list::Commands<'_>,
        state: &ListState,
        table: &mut VertexTable<'_>,
        counts: &mut list::MeshCounts,
    ) -> Result<(), (usize, SceneError)> {
        if state.hidden() || self.scene.records.recording() {
            return Ok(());
        }
        let Scene {
            store,
            labels,
            pipeline,
            ..
        } = &mut *self.scene;
        let segment = self.segment;
        // The run's triangles go to the segment through one adder, set up
        // once (`TriangleRun`), not one for each.
        store.triangle_run(segment, state.clip(), true, |run| {
            let mut out = SegmentOut {
                to: To::Run(run),
                labels,
                segment,
            };
            list::mesh_run(pipeline, &mut out, state, table, cmds, counts)
        })
    }

    /// The pipeline, and the segment as the interpreter's output.
    fn split(&mut self) -> (&mut Pipeline<DEPTH, N>, SegmentOut<'_, '_, 'a>) {
        let Scene {
            store,
            labels,
            pipeline,
            ..
        } = &mut *self.scene;
        (
            pipeline,
            SegmentOut {
                to: To::Store(store),
                labels,
                segment: self.segment,
            },
        )
    }
}
