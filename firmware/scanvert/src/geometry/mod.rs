//! The 3D geometry stage: model points to visible, lit, clipped polygons
//! in screen space, in fixed point.
//!
//! # The stages, in the order a polygon meets them
//!
//! | # | stage | file | what happens |
//! |---|---|---|---|
//! | 1 | transform | [`transform`] | model → view space by the current matrix of a push/pop stack (translate, rotate, scale in call order, the camera's [`View`] at the bottom: eye and yaw/pitch, or [`View::look_at`]) |
//! | 2 | cull | [`cull`] | a face that does not run counter-clockwise as displayed, as a whole polygon (Newell's normal), is dropped (edge-on ones too); points and lines pass |
//! | 3 | light | [`light`] | Lambert: ambient plus a parallel light's share times `max(0, n̂ · l̂)` scales the face's colour |
//! | 4 | near clip | [`near_clip`] | Sutherland–Hodgman in view space to `near ≤ z ≤ far`: nothing at or behind the eye is projected |
//! | 5 | project | [`project`] | perspective (`f·x/d`, depth `A − B/d`) or orthographic onto the window, one division per vertex |
//! | 6 | points and lines | [`primitive`] | one vertex becomes a square, two a quad, of the pipeline's thickness |
//! | 7 | window clip | [`window_clip`] | re-entrant polygon clipping against the window's four sides, depth interpolated |
//! | 8 | sink | [`PolygonSink`] | the polygon, in [`Vertex3`]s inside the window, with its colour |
//!
//! Culling is decided in view space, on the whole polygon as transformed
//! (Newell's normal, exact in `i128`): there its sign is exactly that of
//! the projected shoelace sum (see [`cull`]), it needs no projected vertex, and it is defined even
//! when some of them lie behind the eye. So the cull and the light come
//! before the clips, and a back face costs no clipping and no division.
//! [`trig`] holds the angles, the sine table, the arctangent and the
//! integer square root that the stages share.
//!
//! # Formats
//!
//! | quantity | type | range | unit |
//! |---|---|---|---|
//! | model and world coordinates | [`Point3`] of [`Q16`] (`i32` Q16.16) | ±32768 | the application's |
//! | view-space coordinates | `i32` Q16.16 | **(−16384, 16384)**, checked | same |
//! | angles | [`Angle`] (`u16`) | any, wraps | 1/65536 turn |
//! | sine, cosine | `i32` Q16.16 | \[−1, 1\] | error < 1.3·10⁻⁵ |
//! | matrix entries | [`Matrix`]: `i32` Q16.16, `i64` products | linear part ±16384, translation any `i32` | |
//! | pre-clip screen x, y | `i64` | `< 2⁴⁶` | 1/256 px |
//! | pre-clip depth | `i64` | the Q12.4 range | 1/4096 |
//! | output x, y | [`Coord`] (Q12.4) | the window, `[0, width] × [0, height]` | 1/16 px |
//! | output depth | [`Coord`] (Q12.4) | [`Z_NEAR`] (−2048) at the near plane to [`Z_FAR`] (2047.9375) at the far plane, larger farther, affine in screen space | |
//! | point and line thickness | [`Coord`] | `[0, 2047.9375]` px | 1/16 px |
//!
//! Each stage's file gives the width of every intermediate. Input outside
//! a range is never clamped silently and never panics:
//!
//! * a matrix whose entry would leave its range is refused with
//!   [`TransformError::Range`], and the stack keeps its matrix;
//! * a vertex whose view-space coordinate leaves (−16384, 16384) makes
//!   [`Pipeline::polygon`] return [`PipelineError::Range`] and draw nothing
//!   of that polygon;
//! * a polygon that needs more than `N` vertices at any stage returns
//!   [`PipelineError::Capacity`] and draws nothing;
//! * parameters of projections and windows are checked when they are made
//!   ([`ProjectionError`]).
//!
//! Depth beyond the far plane is clipped, not clamped, so planes stay
//! planes.
//!
//! # Example
//!
//! ```
//! use scanvert::fixed::Vertex3;
//! use scanvert::geometry::{
//!     Angle, Perspective, Pipeline, Point3, PolygonSink, Q16, View, Viewport,
//! };
//! use scanvert::pixelcolor::{Rgb888, RgbColor};
//!
//! // A sink that counts polygons and checks they lie in the window.
//! struct Count(u32);
//! impl PolygonSink for Count {
//!     type Error = core::convert::Infallible;
//!     fn polygon(&mut self, v: &[Vertex3], _: Rgb888, _: bool) -> Result<(), Self::Error> {
//!         assert!(v.len() >= 3);
//!         assert!(v.iter().all(|p| (0..=320 * 16).contains(&p.x.units())));
//!         self.0 += 1;
//!         Ok(())
//!     }
//! }
//!
//! let q = Q16::from_int;
//! let persp = Perspective::from_fov(Angle::from_degrees(60), 320, q(1), q(100)).unwrap();
//! let mut pipe = Pipeline::<4, 16>::new(persp, Viewport::centred(320, 240).unwrap());
//! pipe.set_view(&View { eye: Point3::from_int(0, 2, 10), yaw: Angle::ZERO, pitch: Angle::ZERO })?;
//!
//! // One square, counter-clockwise seen from +z (the eye's side), turned
//! // a little about y.
//! pipe.stack_mut().push()?;
//! pipe.stack_mut().rotate_y(Angle::from_degrees(20))?;
//! let square = [(-1, 0), (1, 0), (1, 2), (-1, 2)].map(|(x, y)| Point3::from_int(x, y, 0));
//! let mut sink = Count(0);
//! pipe.polygon(&square, Rgb888::RED, &mut sink).unwrap();
//! // Its back, wound the other way, is culled.
//! let mut back = square;
//! back.reverse();
//! pipe.polygon(&back, Rgb888::RED, &mut sink).unwrap();
//! pipe.stack_mut().pop()?;
//!
//! assert_eq!(sink.0, 1);
//! let s = pipe.stats();
//! assert_eq!((s.faces_in, s.emitted, s.culled), (2, 1, 1));
//! # Ok::<(), scanvert::geometry::TransformError>(())
//! ```

pub mod cull;
pub mod light;
pub mod near_clip;
pub mod primitive;
pub mod project;
pub mod transform;
pub mod trig;
pub mod window_clip;

pub use light::{Light, ZeroDirection};
pub use project::{
    Anchor, Orthographic, Perspective, Projection, ProjectionError, Viewport, Z_FAR, Z_NEAR,
};
#[doc(hidden)]
pub use transform::{Matrix, TransformStack};
pub use transform::{Point3, TransformError, View, Q16};
pub use trig::Angle;

use crate::fixed::{Coord, Vertex3};
use core::fmt;
use embedded_graphics_core::pixelcolor::Rgb888;
use window_clip::{Outcodes, Work};

/// Where the geometry stage delivers screen-space polygons.
pub trait PolygonSink {
    /// What the sink can fail with (capacity, usually).
    type Error;
    /// One visible, lit polygon in screen space: at least 3 vertices, inside
    /// the window, depth larger = farther. Points and lines arrive here as
    /// small polygons too (their `two_sided` flag is set, so the sink does not cull them).
    fn polygon(
        &mut self,
        vertices: &[Vertex3],
        color: Rgb888,
        two_sided: bool,
    ) -> Result<(), Self::Error>;
}

/// Why a polygon was not delivered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum PipelineError<E> {
    /// A vertex left view space's range (−16384, 16384) under the current
    /// transform. Nothing of the polygon was drawn.
    Range,
    /// The polygon had, or would have had after clipping, more vertices
    /// than the pipeline's `N`. Nothing of it was drawn.
    Capacity {
        /// Vertices the pipeline holds.
        capacity: usize,
    },
    /// The sink failed.
    Sink(E),
}

impl<E: fmt::Debug> fmt::Display for PipelineError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PipelineError::Range => write!(f, "vertex outside the view-space range"),
            PipelineError::Capacity { capacity } => {
                write!(f, "polygon needs more than {capacity} vertices")
            }
            PipelineError::Sink(e) => write!(f, "polygon sink failed: {e:?}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for PipelineError<E> {}

/// What became of one polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Outcome {
    /// Delivered to the sink.
    Emitted,
    /// A back face or an edge-on face.
    Culled,
    /// Nothing, or nothing with an area, is left inside the depth range
    /// and the window.
    ClippedAway,
    /// No vertices were given; nothing is counted.
    Empty,
}

/// A point in view space, as the transform stage of a [`Pipeline`] put
/// it ([`Pipeline::view_point`]), or the mark of one that left the range
/// of view space (a polygon through it is [`PipelineError::Range`]).
/// Meshes keep their transformed vertices in slices of these.
///
/// A mesh's vertex table also keeps, in its slot, where the projection
/// put the point when that lies inside the window and the depth range
/// (the output vertex, so that the faces through it after the first
/// project nothing). That is a cache of the table: equality and hashing
/// look at the view-space point alone.
///
/// # Size
/// 20 bytes: three `i32`s, the projected vertex's three `i16`s and a
/// `u16` of flags.
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ViewPoint {
    xyz: [i32; 3],
    screen: [i16; 3],
    /// [`ViewPoint::IN_RANGE`] and [`ViewPoint::PROJECTED`].
    flags: u16,
}

impl ViewPoint {
    /// A slot not yet filled (out of range).
    pub const EMPTY: ViewPoint = ViewPoint {
        xyz: [0; 3],
        screen: [0; 3],
        flags: 0,
    };

    /// Set when `xyz` is a point of view space's range.
    const IN_RANGE: u16 = 1;
    /// Set when `screen` holds the point's output vertex under the
    /// projection and window its table was last told of
    /// ([`Pipeline::screen_epoch`]), the point being inside both.
    const PROJECTED: u16 = 2;

    fn new(xyz: Option<[i32; 3]>) -> ViewPoint {
        match xyz {
            Some(xyz) => ViewPoint {
                xyz,
                flags: Self::IN_RANGE,
                ..ViewPoint::EMPTY
            },
            None => ViewPoint::EMPTY,
        }
    }

    /// The coordinates in view space (Q16.16 raw), `None` when the point
    /// left its range.
    #[inline]
    pub fn raw(&self) -> Option<[i32; 3]> {
        (self.flags & Self::IN_RANGE != 0).then_some(self.xyz)
    }

    /// The output vertex kept by [`Pipeline::mesh_triangle`], if any.
    #[inline]
    fn screen(&self) -> Option<Vertex3> {
        (self.flags & Self::PROJECTED != 0).then(|| Vertex3 {
            x: Coord::from_bits(self.screen[0]),
            y: Coord::from_bits(self.screen[1]),
            z: Coord::from_bits(self.screen[2]),
        })
    }

    /// Keeps `o` as the point's output vertex.
    #[inline]
    fn keep_screen(&mut self, o: Vertex3) {
        self.screen = [o.x.to_bits(), o.y.to_bits(), o.z.to_bits()];
        self.flags |= Self::PROJECTED;
    }

    /// Forgets the output vertex (the projection or the window changed).
    #[inline]
    pub(crate) fn forget_screen(&mut self) {
        self.flags &= !Self::PROJECTED;
    }
}

impl PartialEq for ViewPoint {
    fn eq(&self, other: &ViewPoint) -> bool {
        self.raw() == other.raw()
    }
}

impl Eq for ViewPoint {}

impl core::hash::Hash for ViewPoint {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        self.raw().hash(state)
    }
}

/// Counters of the polygons through a [`Pipeline`], for statistics.
///
/// Every polygon with at least one vertex counts in `faces_in` and in
/// exactly one of the others, so
/// `faces_in = culled + clipped_away + emitted + rejected`. The counters
/// wrap around at 2³².
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PipelineStats {
    /// Polygons, lines and points given.
    pub faces_in: u32,
    /// Back faces and edge-on faces.
    pub culled: u32,
    /// Wholly outside the depth range or the window (or left without area).
    pub clipped_away: u32,
    /// Delivered to the sink.
    pub emitted: u32,
    /// Refused with an error (range, capacity or the sink's).
    pub rejected: u32,
}

impl PipelineStats {
    /// Counts one face given, and what became of it.
    #[inline(always)]
    fn count<E>(&mut self, r: &Result<Outcome, E>) {
        self.faces_in = self.faces_in.wrapping_add(1);
        let counter = match r {
            Ok(Outcome::Emitted) => &mut self.emitted,
            Ok(Outcome::Culled) => &mut self.culled,
            Ok(Outcome::ClippedAway | Outcome::Empty) => &mut self.clipped_away,
            Err(_) => &mut self.rejected,
        };
        *counter = counter.wrapping_add(1);
    }
}

/// The geometry stage: a transform stack of depth `DEPTH`, a projection,
/// a window, a light and a point/line thickness, delivering polygons of up
/// to `N` vertices.
///
/// # Capacity
/// A polygon may have up to `N` vertices on input and at every stage of
/// clipping; a convex one gains at most one per clip plane (six planes),
/// so `N` = the largest input + 6 is always enough for convex faces.
/// `N ≥ 4` is checked at compile time (a point or line needs four). The
/// working buffers live on the stack during [`Pipeline::polygon`]: about
/// `54 · N` bytes.
#[derive(Clone, Debug)]
pub struct Pipeline<const DEPTH: usize, const N: usize> {
    stack: TransformStack<DEPTH>,
    view: Matrix,
    projection: Projection,
    viewport: Viewport,
    light: Light,
    /// The light's direction in view space, unit Q16.16.
    light_view: [i32; 3],
    thickness: Coord,
    stats: PipelineStats,
    /// Changed with the projection or the window: what a mesh's kept
    /// output vertices were made under ([`Pipeline::screen_epoch`]).
    screen_epoch: u32,
}

impl<const DEPTH: usize, const N: usize> Pipeline<DEPTH, N> {
    /// A pipeline with the identity transform (view space = world), only
    /// ambient light, and points and lines one pixel thick.
    pub fn new(projection: impl Into<Projection>, viewport: Viewport) -> Self {
        const {
            assert!(
                N >= 4,
                "a pipeline needs N >= 4 (points and lines are quads)"
            )
        };
        Pipeline {
            stack: TransformStack::new(),
            view: Matrix::IDENTITY,
            projection: projection.into(),
            viewport,
            light: Light::AMBIENT,
            light_view: Light::AMBIENT.direction(),
            thickness: Coord::from_bits(16),
            stats: PipelineStats::default(),
            screen_epoch: 0,
        }
    }

    /// The transform stack.
    #[doc(hidden)]
    pub fn stack(&self) -> &TransformStack<DEPTH> {
        &self.stack
    }

    /// The transform stack, to push, pop, translate, rotate and scale.
    #[doc(hidden)]
    pub fn stack_mut(&mut self) -> &mut TransformStack<DEPTH> {
        &mut self.stack
    }

    /// Loads the camera's matrix as the current one (like loading the view
    /// at the start of a frame) and turns the light into the new view
    /// space. Saved matrices are not touched.
    pub fn set_view(&mut self, view: &View) -> Result<(), TransformError> {
        let m = view.matrix()?;
        self.stack.load(m);
        self.view = m;
        self.light_view = m.rotate_vector(self.light.direction());
        Ok(())
    }

    /// Empties the transform stack and loads the camera's matrix (of the
    /// last [`Pipeline::set_view`], the identity before any): where the
    /// modelling transforms of a segment start.
    #[doc(hidden)]
    pub fn reset_stack(&mut self) {
        self.stack = TransformStack::new();
        self.stack.load(self.view);
    }

    /// The projection.
    pub fn projection(&self) -> &Projection {
        &self.projection
    }

    /// Replaces the projection.
    pub fn set_projection(&mut self, projection: impl Into<Projection>) {
        self.projection = projection.into();
        self.screen_epoch = self.screen_epoch.wrapping_add(1);
    }

    /// The window.
    pub fn viewport(&self) -> &Viewport {
        &self.viewport
    }

    /// Replaces the window.
    pub fn set_viewport(&mut self, viewport: Viewport) {
        self.viewport = viewport;
        self.screen_epoch = self.screen_epoch.wrapping_add(1);
    }

    /// The light.
    pub fn light(&self) -> &Light {
        &self.light
    }

    /// Replaces the light; its direction is in the world of the last
    /// [`Pipeline::set_view`] (in view space before any).
    pub fn set_light(&mut self, light: Light) {
        self.light = light;
        self.light_view = self.view.rotate_vector(light.direction());
    }

    /// The thickness of points and lines in pixels.
    pub fn thickness(&self) -> Coord {
        self.thickness
    }

    /// Sets the thickness of points and lines in pixels; a negative value
    /// counts as zero, and zero makes them invisible.
    pub fn set_thickness(&mut self, thickness: Coord) {
        self.thickness = thickness.max(Coord::ZERO);
    }

    /// The counters since the last reset.
    pub fn stats(&self) -> PipelineStats {
        self.stats
    }

    /// Zeroes the counters.
    pub fn reset_stats(&mut self) {
        self.stats = PipelineStats::default();
    }

    /// Where `p` lands on the screen under the current transform: the
    /// anchor of a label. [`TransformError::Range`] when it leaves view
    /// space.
    pub fn project_point(&self, p: Point3) -> Result<Anchor, TransformError> {
        project::anchor_of(self.stack.current(), &self.projection, &self.viewport, p)
    }

    /// Runs one polygon (one vertex: a point; two: a line) through the
    /// stages and hands what is visible of it to `sink`.
    ///
    /// Faces (three or more vertices) are culled by the orientation of the
    /// whole polygon as projected (see [`cull`]) and lit with the face's
    /// normal; they should be planar.
    /// Points and lines are neither culled nor lit.
    pub fn polygon<S: PolygonSink>(
        &mut self,
        points: &[Point3],
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>> {
        self.polygon_from(points.iter().copied(), color, sink)
    }

    /// [`polygon`](Self::polygon) of points read as they come: a display
    /// list's `face` is transformed straight from the list, with no copy
    /// of its points on the stack.
    pub(crate) fn polygon_from<I, S>(
        &mut self,
        points: I,
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>>
    where
        I: ExactSizeIterator<Item = Point3>,
        S: PolygonSink,
    {
        let m = *self.stack.current();
        self.polygon_view(points.map(move |p| m.apply(p).ok()), color, sink)
    }

    /// Where `p` lies in view space under the current transform, as the
    /// first stage of [`polygon`](Self::polygon) puts it: a mesh's vertex,
    /// transformed once and used by every face through it.
    pub fn view_point(&self, p: Point3) -> ViewPoint {
        ViewPoint::new(self.stack.current().apply(p).ok())
    }

    /// [`polygon`](Self::polygon) of points already in view space (from
    /// [`view_point`](Self::view_point)): the stages after the transform,
    /// the same code. A point that left view space's range is
    /// [`PipelineError::Range`], as it is for `polygon`.
    pub fn polygon_view<I, S>(
        &mut self,
        points: I,
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>>
    where
        I: ExactSizeIterator<Item = Option<[i32; 3]>>,
        S: PolygonSink,
    {
        if points.len() == 0 {
            return Ok(Outcome::Empty);
        }
        let r = self.run(points, color, sink);
        self.stats.count(&r);
        r
    }

    /// What a mesh's kept output vertices
    /// ([`mesh_triangle`](Self::mesh_triangle)) were made under: it changes
    /// with the projection and the window. A table whose vertices were
    /// projected under another forgets them
    /// ([`VertexTable`](crate::scene::VertexTable)). It wraps after 2³²
    /// changes.
    #[doc(hidden)]
    pub fn screen_epoch(&self) -> u32 {
        self.screen_epoch
    }

    /// [`polygon_view`](Self::polygon_view) of the triangle through the
    /// points `slots[corners[k]]` of a mesh's vertex table, with the same
    /// outcome, counters and polygon. A corner that lies inside the
    /// depth range and the window keeps its output vertex in its slot,
    /// and the next face through it takes it from there instead of
    /// projecting it again: the slots' kept vertices must be of this
    /// pipeline's [`screen_epoch`](Self::screen_epoch). A triangle with a
    /// corner outside either is clipped as `polygon_view` clips it. A
    /// corner past `slots` is [`PipelineError::Range`] (the table checks
    /// its indices before).
    #[doc(hidden)]
    pub fn mesh_triangle<S: PolygonSink>(
        &mut self,
        slots: &mut [ViewPoint],
        corners: [usize; 3],
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>> {
        let r = self.triangle(slots, corners, color, sink);
        self.stats.count(&r);
        r
    }

    /// [`mesh_triangle`](Self::mesh_triangle) with nothing counted, for a
    /// caller that counts what became of a run of triangles and adds it
    /// at once ([`add_counts`](Self::add_counts)).
    #[doc(hidden)]
    #[inline(always)]
    pub fn mesh_triangle_uncounted<S: PolygonSink>(
        &mut self,
        slots: &mut [ViewPoint],
        corners: [usize; 3],
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>> {
        self.triangle(slots, corners, color, sink)
    }

    /// Adds to the counters faces given that were emitted, culled,
    /// clipped away and refused, as [`stats`](Self::stats) counts them
    /// one by one.
    #[doc(hidden)]
    pub fn add_counts(&mut self, emitted: u32, culled: u32, clipped_away: u32, rejected: u32) {
        let s = &mut self.stats;
        s.faces_in = s
            .faces_in
            .wrapping_add(emitted)
            .wrapping_add(culled)
            .wrapping_add(clipped_away)
            .wrapping_add(rejected);
        s.emitted = s.emitted.wrapping_add(emitted);
        s.culled = s.culled.wrapping_add(culled);
        s.clipped_away = s.clipped_away.wrapping_add(clipped_away);
        s.rejected = s.rejected.wrapping_add(rejected);
    }

    /// The body of [`mesh_triangle`](Self::mesh_triangle): `run`'s stages
    /// for three points, with no copy of them where no clip is needed.
    #[inline(always)]
    fn triangle<S: PolygonSink>(
        &self,
        slots: &mut [ViewPoint],
        corners: [usize; 3],
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>> {
        // Kept as read (each below 2³⁰), widened where used: nine words
        // live across the function, not eighteen.
        let mut v = [[0i32; 3]; 3];
        for (w, &i) in v.iter_mut().zip(&corners) {
            let p = slots.get(i).and_then(ViewPoint::raw);
            *w = p.ok_or(PipelineError::Range)?;
        }
        let wide = |k: usize| v[k].map(i64::from);
        // As `run` culls and lights a triangle.
        let n = cull::normal(wide(0), wide(1), wide(2));
        if !cull::is_front_triangle(&self.projection, wide(0), n) {
            return Ok(Outcome::Culled);
        }
        let base = color;
        let color = light::shade(color, n, self.light_view, self.light.percent());
        let (near, far) = (
            self.projection.near_raw() as i64,
            self.projection.far_raw() as i64,
        );
        // Inside the depth range and the window, the clips change nothing
        // and the polygon is the corners' output vertices. A corner that
        // kept its output vertex lies inside both; another is tested.
        let mut out = [Vertex3::default(); 3];
        let mut inside = true;
        for k in 0..3 {
            out[k] = match slots.get(corners[k]).and_then(ViewPoint::screen) {
                Some(o) => o,
                None => {
                    let z = v[k][2] as i64;
                    if !(near <= z && z <= far) {
                        inside = false;
                        break;
                    }
                    let q = self.projection.project(wide(k), &self.viewport);
                    let mut codes = Outcodes::EMPTY;
                    codes.add(&q, &self.viewport);
                    if !codes.is_inside() {
                        inside = false;
                        break;
                    }
                    let o = project::to_vertex3(q);
                    if let Some(slot) = slots.get_mut(corners[k]) {
                        slot.keep_screen(o);
                    }
                    o
                }
            };
        }
        if !inside {
            // A clip is needed: the general stages from the points (the
            // cull and the light again, on this rare path).
            return self.clipped_triangle([wide(0), wide(1), wide(2)], base, sink);
        }
        // Three vertices have an area exactly when they are not on one
        // line (two equal ones are): `has_area` of what `run` would
        // have left after dropping repeated vertices.
        let d = |q: Vertex3| {
            (
                q.x.units() as i64 - out[0].x.units() as i64,
                q.y.units() as i64 - out[0].y.units() as i64,
            )
        };
        let ((ax, ay), (bx, by)) = (d(out[1]), d(out[2]));
        if ax * by - ay * bx == 0 {
            return Ok(Outcome::ClippedAway);
        }
        sink.polygon(&out, color, false)
            .map_err(PipelineError::Sink)?;
        Ok(Outcome::Emitted)
    }

    /// A mesh triangle that needs a clip: `run` of its view-space points
    /// `v`, unlit colour `color`. Out of line and cold, so that the
    /// triangles that need none do not carry its frame.
    #[cold]
    #[inline(never)]
    fn clipped_triangle<S: PolygonSink>(
        &self,
        v: [[i64; 3]; 3],
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>> {
        let points = v.map(|w| Some(w.map(|c| c as i32)));
        self.run(points.into_iter(), color, sink)
    }

    /// A triangle of view-space points culled and lit as `run` does it:
    /// its Newell normal is its one corner, which also lights it (it
    /// points the way of itself). `None` when culled. Out of line, so
    /// that `run`'s polygons of more vertices keep their registers.
    #[inline(never)]
    fn lit_triangle(
        &self,
        v0: [i64; 3],
        v1: [i64; 3],
        v2: [i64; 3],
        color: Rgb888,
    ) -> Option<Rgb888> {
        let n = cull::normal(v0, v1, v2);
        if !cull::is_front_triangle(&self.projection, v0, n) {
            return None;
        }
        Some(light::shade(
            color,
            n,
            self.light_view,
            self.light.percent(),
        ))
    }

    fn run<I: ExactSizeIterator<Item = Option<[i32; 3]>>, S: PolygonSink>(
        &self,
        points: I,
        color: Rgb888,
        sink: &mut S,
    ) -> Result<Outcome, PipelineError<S::Error>> {
        let full = || PipelineError::Capacity { capacity: N };
        if points.len() > N {
            return Err(full());
        }
        let mut work = Work::<N>::new();
        // The depth range is gathered on the way, for the near clip.
        let mut depth = (i32::MAX, i32::MIN);
        let two_sided = points.len() < 3;
        for v in points {
            let v = v.ok_or(PipelineError::Range)?;
            depth = (depth.0.min(v[2]), depth.1.max(v[2]));
            work.current_mut()
                .push(v.map(i64::from))
                .map_err(|_| full())?;
        }

        let mut color = color;
        if let [v0, v1, v2] = *work.current().as_slice() {
            match self.lit_triangle(v0, v1, v2, color) {
                Some(c) => color = c,
                None => return Ok(Outcome::Culled),
            }
        } else if let [v0, v1, v2, ..] = *work.current().as_slice() {
            let n = cull::newell(work.current());
            if !cull::is_front(&self.projection, v0, n) {
                return Ok(Outcome::Culled);
            }
            let n = cull::light_normal(cull::normal(v0, v1, v2), n);
            color = light::shade(color, n, self.light_view, self.light.percent());
        }

        let (near, far) = (self.projection.near_raw(), self.projection.far_raw());
        near_clip::clip_depth(&mut work, near, far, depth).map_err(|_| full())?;
        let poly = work.current_mut();
        if poly.is_empty() || (!two_sided && poly.len() < 3) {
            return Ok(Outcome::ClippedAway);
        }
        // The sides of the window each vertex lies beyond are gathered on
        // the way, for the window clip.
        let mut codes = Outcodes::EMPTY;
        for v in poly.iter_mut() {
            *v = self.projection.project(*v, &self.viewport);
            codes.add(v, &self.viewport);
        }
        if two_sided {
            // Thickness in 1/16 px to half of it in 1/256 px: ≤ 2¹⁸.
            let half = (self.thickness.units() as i64) << 3;
            let quad = match *poly.as_slice() {
                [p] => primitive::point_quad(p, half),
                [a, b] => primitive::line_quad(a, b, half),
                _ => return Ok(Outcome::ClippedAway),
            };
            poly.clear();
            codes = Outcodes::EMPTY;
            for v in quad {
                codes.add(&v, &self.viewport);
                poly.push(v).map_err(|_| full())?;
            }
        }

        window_clip::clip_window(&mut work, &self.viewport, codes).map_err(|_| full())?;
        let mut out = heapless::Vec::<Vertex3, N>::new();
        for &v in work.current() {
            let v = project::to_vertex3(v);
            if out.last() != Some(&v) {
                out.push(v).map_err(|_| full())?;
            }
        }
        while out.len() > 1 && out.last() == out.first() {
            out.pop();
        }
        if !has_area(&out) {
            return Ok(Outcome::ClippedAway);
        }
        sink.polygon(&out, color, two_sided)
            .map_err(PipelineError::Sink)?;
        Ok(Outcome::Emitted)
    }
}

/// `true` when the vertices do not all lie on one line (so at least three
/// distinct ones). Q12.4 differences are below 2¹⁶, products below 2³².
fn has_area(v: &[Vertex3]) -> bool {
    let Some((&o, rest)) = v.split_first() else {
        return false;
    };
    let d = |p: Vertex3| {
        (
            p.x.units() as i64 - o.x.units() as i64,
            p.y.units() as i64 - o.y.units() as i64,
        )
    };
    let Some(&a) = rest.iter().find(|&&p| d(p) != (0, 0)) else {
        return false;
    };
    let (ax, ay) = d(a);
    rest.iter().any(|&p| {
        let (px, py) = d(p);
        ax * py - ay * px != 0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::RgbColor;

    #[derive(Default)]
    struct Collect {
        polys: heapless::Vec<(heapless::Vec<Vertex3, 16>, Rgb888, bool), 16>,
    }

    impl PolygonSink for Collect {
        type Error = ();
        fn polygon(&mut self, v: &[Vertex3], c: Rgb888, two: bool) -> Result<(), ()> {
            let v = heapless::Vec::from_slice(v).map_err(|_| ())?;
            self.polys.push((v, c, two)).map_err(|_| ())
        }
    }

    fn pipe() -> Pipeline<4, 16> {
        let q = Q16::from_int;
        let p = Perspective::new(q(100), q(1), q(100)).unwrap();
        Pipeline::new(p, Viewport::centred(200, 100).unwrap())
    }

    const P: fn(i16, i16, i16) -> Point3 = Point3::from_int;

    #[test]
    fn a_front_face_is_emitted_inside_the_window() {
        let mut p = pipe();
        let mut sink = Collect::default();
        // View space: y down, z forward; counter-clockwise as displayed.
        let tri = [P(0, 0, 10), P(0, 1, 10), P(1, 1, 10)];
        assert_eq!(
            p.polygon(&tri, Rgb888::RED, &mut sink),
            Ok(Outcome::Emitted)
        );
        let (v, c, two) = &sink.polys[0];
        assert_eq!((*c, *two), (Rgb888::RED, false));
        let px = |x: i16, y: i16| (x * 16, y * 16);
        let got: heapless::Vec<_, 3> = v
            .iter()
            .map(|p| (p.x.units() as i16, p.y.units() as i16))
            .collect();
        assert_eq!(got.as_slice(), &[px(100, 50), px(100, 60), px(110, 60)]);
        assert!(v.iter().all(|p| p.z == v[0].z));
        let mut back = tri;
        back.reverse();
        assert_eq!(
            p.polygon(&back, Rgb888::RED, &mut sink),
            Ok(Outcome::Culled)
        );
    }

    #[test]
    fn stats_add_up_and_errors_are_counted() {
        let mut p = pipe();
        let mut sink = Collect::default();
        let tri = [P(0, 0, 10), P(0, 1, 10), P(1, 1, 10)];
        let _ = p.polygon(&tri, Rgb888::RED, &mut sink);
        let behind = [P(1, 1, -10), P(0, 1, -10), P(0, 0, -10)];
        assert_eq!(
            p.polygon(&behind, Rgb888::RED, &mut sink),
            Ok(Outcome::ClippedAway)
        );
        assert_eq!(p.polygon(&[], Rgb888::RED, &mut sink), Ok(Outcome::Empty));
        let far = [P(0, 0, 10), P(0, 1, 10), P(16384, 1, 10)];
        assert_eq!(
            p.polygon(&far, Rgb888::RED, &mut sink),
            Err(PipelineError::Range)
        );
        let many = [P(0, 0, 10); 17];
        assert_eq!(
            p.polygon(&many, Rgb888::RED, &mut sink),
            Err(PipelineError::Capacity { capacity: 16 })
        );
        let s = p.stats();
        assert_eq!(
            s,
            PipelineStats {
                faces_in: 4,
                culled: 0,
                clipped_away: 1,
                emitted: 1,
                rejected: 2
            }
        );
        p.reset_stats();
        assert_eq!(p.stats(), PipelineStats::default());
    }

    #[test]
    fn points_and_lines_are_two_sided_quads() {
        let mut p = pipe();
        p.set_thickness(Coord::from_bits(32));
        let mut sink = Collect::default();
        assert_eq!(
            p.polygon(&[P(0, 0, 10)], Rgb888::GREEN, &mut sink),
            Ok(Outcome::Emitted)
        );
        assert_eq!(
            p.polygon(&[P(0, 0, 10), P(1, 0, 10)], Rgb888::GREEN, &mut sink),
            Ok(Outcome::Emitted)
        );
        let (sq, c, two) = &sink.polys[0];
        assert!(*two && *c == Rgb888::GREEN && sq.len() == 4);
        let xs: heapless::Vec<i16, 4> = sq.iter().map(|v| v.x.units() as i16).collect();
        assert_eq!(xs.as_slice(), &[99 * 16, 99 * 16, 101 * 16, 101 * 16]);
        p.set_thickness(Coord::ZERO);
        assert_eq!(
            p.polygon(&[P(0, 0, 10)], Rgb888::GREEN, &mut sink),
            Ok(Outcome::ClippedAway)
        );
    }

    #[test]
    fn a_mesh_triangle_is_polygon_view_with_or_without_kept_vertices() {
        // Random triangles of few points (so that they share corners),
        // inside the window, across its sides, the near and far planes
        // and behind the eye; each through `polygon_view` and twice
        // through `mesh_triangle` (the second time from the kept output
        // vertices), in both projections.
        let mut next = crate::rng::xorshift64(0x2545_f491_4f6c_dd1d);
        let mut rnd = move |n: i32| (next() % n as u64) as i32;
        let q = Q16::from_int;
        let ortho = Orthographic::new(q(10), q(1), q(100)).unwrap();
        for projection in [*pipe().projection(), ortho.into()] {
            let mut p = pipe();
            p.set_projection(projection);
            let mut q = pipe();
            q.set_projection(projection);
            let mut slots = [ViewPoint::EMPTY; 12];
            for s in slots.iter_mut() {
                let z = rnd(130 << 16) - (10 << 16);
                let xy = |r: &mut dyn FnMut(i32) -> i32| r(120 << 16) - (60 << 16);
                *s = ViewPoint::new(Some([xy(&mut rnd), xy(&mut rnd), z]));
            }
            slots[11] = ViewPoint::EMPTY;
            for _ in 0..4000 {
                let c = [rnd(12), rnd(12), rnd(12)].map(|i| i as usize);
                let points = c.map(|i| slots[i].raw());
                let (mut a, mut b, mut k) =
                    (Collect::default(), Collect::default(), Collect::default());
                let want = p.polygon_view(points.into_iter(), Rgb888::RED, &mut a);
                let got = q.mesh_triangle(&mut slots, c, Rgb888::RED, &mut b);
                let kept = q.mesh_triangle(&mut slots, c, Rgb888::RED, &mut k);
                assert_eq!(got, want, "{points:?}");
                assert_eq!(kept, want, "{points:?}");
                assert_eq!(b.polys, a.polys, "{points:?}");
                assert_eq!(k.polys, a.polys, "{points:?}");
            }
            let s = p.stats();
            let t = q.stats();
            assert_eq!(s.faces_in * 2, t.faces_in);
            assert_eq!(s.emitted * 2, t.emitted);
            assert_eq!(s.culled * 2, t.culled);
            assert_eq!(s.clipped_away * 2, t.clipped_away);
            assert_eq!(s.rejected * 2, t.rejected);
            assert!(
                s.emitted > 100 && s.culled > 100 && s.clipped_away > 100,
                "{s:?}"
            );
        }
    }

    #[test]
    fn area_test() {
        let v = |x: i16, y: i16| Vertex3 {
            x: Coord::from_bits(x),
            y: Coord::from_bits(y),
            z: Coord::ZERO,
        };
        assert!(!has_area(&[]));
        assert!(!has_area(&[v(0, 0), v(0, 0), v(0, 0)]));
        assert!(!has_area(&[v(0, 0), v(1, 1), v(2, 2), v(-5, -5)]));
        assert!(has_area(&[v(0, 0), v(0, 0), v(1, 1), v(2, 3)]));
    }
}
