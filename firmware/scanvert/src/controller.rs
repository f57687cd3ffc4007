//! The graphic controller: executes a display list into a frame-buffer
//! port, holding the clip registers and the current colour.
//!
//! # `poly` and `poly3` in one list
//!
//! `clear` and `poly` are executed in list order (painter's order). The
//! `poly3`s are the *3D layer*: all of them are resolved together by the
//! visible-surface stages ([`trapezoid`](crate::visible::trapezoid) →
//! [`segment`](crate::visible::store) → [`visible`](mod@crate::visible::sweep) →
//! [`rle`](crate::visible::rle)), and the layer is drawn **after** every 2D command
//! of the list, writing only the pixels its faces cover: where no `poly3`
//! is, the 2D content shows through. Each `poly3` takes the colour and the
//! clip registers in force at its place in the list, and is culled by the
//! spec's rule: it is drawn only when the shoelace sum of its vertices is
//! negative (counter-clockwise as displayed). At equal depth the earlier
//! `poly3` is in front.
//!
//! # The 3D scene (version 2)
//!
//! The scene commands of version 2 feed the same 3D layer. They are
//! executed in list order through a [`Pipeline`] of [`LIST_STACK`] saved
//! transforms and polygons of up to [`LIST_VERTICES`] vertices (after
//! clipping), starting from these defaults:
//!
//! | state | default | set by |
//! |---|---|---|
//! | projection | perspective, 60° horizontal field of view, near 1, far 1000 | `perspective`, `ortho` |
//! | window | the frame, the view axis through its middle | (fixed) |
//! | camera | eye at the origin, yaw 0, pitch 0: looking along −z, y up | `view` (`lookat`) |
//! | light | ambient only: every face keeps its colour | `light` |
//! | thickness of points and lines | 1 px | `thickness` |
//! | modelling transform | the camera's, nothing saved | `push`, `pop`, `translate`, `rotate`, `scale` |
//! | colour and clip | the list's `color` and `clip` registers, as for `poly3` | `color`, `clip` |
//!
//! Each state command acts on the faces and labels that follow it. A
//! `segment` command empties the transform stack and loads the camera's
//! matrix again, so each segment starts from the camera; a `view` loads
//! the new camera as the current matrix. A one-shot render draws every
//! segment (the retained, per-segment rebuilding is [`Scene`]'s); at equal
//! depth the face earlier in the list is in front, whatever its segment.
//! `face`s are culled by their first three vertices (see
//! [`geometry::cull`](crate::geometry::cull)) and lit; `label`s are drawn
//! after the whole 3D layer, in the colour in force at their place, with
//! the lower-left corner of their first character at the projected point
//! (see [`scene::label`](crate::scene::label)), never hidden.
//!
//! # Memory
//!
//! The 3D layer needs memory of its own ([`Storage3d`], given with
//! [`Controller::with_3d`]), and labels need label slots and text space
//! ([`Controller::with_labels`]). Without 3D storage a list with a `poly3`
//! or any scene command is rejected as [`RenderError::Unsupported`];
//! with too little of either, as [`RenderError::Capacity3d`]. A scene
//! command that fails (a `pop` with nothing saved, a vertex outside view
//! space, a projection out of range) is a [`RenderError::Scene`]. All of
//! these are found before anything is drawn. [`needs_3d`] sizes the memory
//! for a list.
//!
//! [`Pipeline`]: crate::geometry::Pipeline
//! [`Scene`]: crate::scene::Scene

use crate::color::ListColor;
use crate::display_list::{Axis, Command, DisplayList, Vertices3};
use crate::fixed::Vertex3;
use crate::geometry::{
    Angle, Light, Orthographic, Perspective, Pipeline, PipelineError, Point3, PolygonSink, View,
    Viewport, Q16,
};
use crate::port::SpanTarget;
use crate::raster::clip::ClipRect;
use crate::raster::scan::{FillError, Rasterizer};
use crate::scene::label::{self, Label, LabelError, LabelStore};
use crate::scene::SceneError;
use crate::visible::rle::Run;
use crate::visible::store::{StoreError, StoreMemory, TrapezoidStore};
use crate::visible::trapezoid::{EdgeSlot, Polygon};
use crate::visible::{self, Active, Cover, Resolve, VisibleError, VisibleStats, Workspace};
use core::fmt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

mod bands;
pub use bands::{ListBands, ListBandsError, PrepareError};

/// Matrices the transform stack of a list's 3D scene saves (`push`
/// without `pop`).
pub const LIST_STACK: usize = 16;

/// Vertices of one 3D polygon of a list, at every stage of clipping: a
/// `face` may have up to `LIST_VERTICES − 6` (each of the six clip planes
/// adds at most one to a convex face).
pub const LIST_VERTICES: usize = 64;

/// The geometry stage of a list's 3D scene.
type ListPipeline = Pipeline<LIST_STACK, LIST_VERTICES>;

/// The colour of `poly` before the first `color` command.
pub const DEFAULT_COLOR: Rgb888 = Rgb888::WHITE;

/// Why a display list could not be rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RenderError<E> {
    /// A polygon has more vertices than the edge storage has slots.
    /// Found before anything is drawn.
    Capacity {
        /// Byte offset of the command in the list.
        offset: usize,
        /// Its vertices.
        vertices: usize,
        /// Edge slots available.
        capacity: usize,
    },
    /// A command this controller does not execute. Found before anything
    /// is drawn.
    Unsupported {
        /// Byte offset of the command in the list.
        offset: usize,
        /// The command's name in the text form.
        command: &'static str,
    },
    /// The 3D storage is too small for the list's `poly3`s. Found before
    /// anything is drawn.
    Capacity3d {
        /// Byte offset of the `poly3` at fault (the first `poly3` when the
        /// layer as a whole does not fit).
        offset: usize,
        /// What ran out.
        resource: Resource,
        /// How many the storage holds.
        capacity: usize,
    },
    /// A command of the 3D scene failed. Found before anything is drawn.
    Scene {
        /// Byte offset of the command in the list.
        offset: usize,
        /// Why.
        error: SceneError,
    },
    /// The frame-buffer port failed at the command at `offset`.
    Target {
        /// Byte offset of the command in the list.
        offset: usize,
        /// The port's error.
        error: E,
    },
}

impl<E> RenderError<E> {
    /// Byte offset of the command at fault.
    pub fn offset(&self) -> usize {
        match *self {
            RenderError::Capacity { offset, .. }
            | RenderError::Capacity3d { offset, .. }
            | RenderError::Unsupported { offset, .. }
            | RenderError::Scene { offset, .. }
            | RenderError::Target { offset, .. } => offset,
        }
    }
}

impl<E: fmt::Debug> fmt::Display for RenderError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Capacity {
                vertices, capacity, ..
            } => write!(
                f,
                "polygon has {vertices} vertices; this renderer holds {capacity} edges"
            ),
            RenderError::Capacity3d {
                resource, capacity, ..
            } => write!(
                f,
                "the 3D layer needs more than the {capacity} {resource} this renderer holds"
            ),
            RenderError::Unsupported { command, .. } => {
                write!(f, "`{command}` is not supported by this renderer yet")
            }
            RenderError::Scene { error, .. } => write!(f, "{error}"),
            RenderError::Target { error, .. } => write!(f, "frame-buffer port failed: {error:?}"),
        }
    }
}

/// A pool of the 3D storage, in a [`RenderError::Capacity3d`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Resource {
    /// Trapezoid slots.
    Trapezoids,
    /// Face slots (one per drawn `poly3`).
    Faces,
    /// Edge slots (a `poly3` of `n` vertices needs `n`).
    EdgeSlots,
    /// Segments (the controller uses one).
    Segments,
    /// Rows of the scan-line index (the frame's height).
    Rows,
    /// Active-list entries (trapezoids overlapping one row).
    Active,
    /// Runs of one row (the frame's width).
    Runs,
    /// Vertices of one 3D `face` ([`LIST_VERTICES`] less six).
    FaceVertices,
    /// Label slots.
    Labels,
    /// Bytes of label text.
    LabelText,
}

impl fmt::Display for Resource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Resource::Trapezoids => "trapezoids",
            Resource::Faces => "faces",
            Resource::EdgeSlots => "edge slots",
            Resource::Segments => "segments",
            Resource::Rows => "index rows",
            Resource::Active => "active entries",
            Resource::Runs => "runs",
            Resource::FaceVertices => "vertices of a face",
            Resource::Labels => "labels",
            Resource::LabelText => "bytes of label text",
        })
    }
}

impl Resource {
    fn of_store(e: StoreError) -> (Resource, usize) {
        match e {
            StoreError::Trapezoids { capacity } => (Resource::Trapezoids, capacity),
            StoreError::Faces { capacity } => (Resource::Faces, capacity),
            StoreError::Edges { capacity } => (Resource::EdgeSlots, capacity),
            StoreError::Vertices => (Resource::EdgeSlots, crate::visible::trapezoid::MAX_VERTICES),
            StoreError::Segment { capacity, .. } => (Resource::Segments, capacity),
            StoreError::Rows { capacity, .. } => (Resource::Rows, capacity),
        }
    }

    fn of_labels(e: LabelError) -> (Resource, usize) {
        match e {
            LabelError::Labels { capacity } => (Resource::Labels, capacity),
            LabelError::Text { capacity } => (Resource::LabelText, capacity),
            // The reader checked every text.
            LabelError::Invalid => (Resource::LabelText, 0),
        }
    }
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stats {
    /// Commands executed.
    pub commands: u32,
    /// Polygons scan-converted.
    pub polygons: u32,
    /// Clears executed.
    pub clears: u32,
    /// Spans written by polygons, the 3D layer and labels.
    pub spans: u32,
    /// Pixels written by polygons, the 3D layer and labels.
    pub pixels: u64,
    /// `poly3`s drawn (front-facing).
    pub poly3: u32,
    /// `poly3`s and `face`s culled (back-facing or edge-on).
    pub culled: u32,
    /// `face`s (points and lines too) that reached the 3D layer.
    pub faces: u32,
    /// `face`s wholly outside the depth range or the window.
    pub clipped_away: u32,
    /// Trapezoids the 3D layer was cut into.
    pub trapezoids: u32,
    /// Labels drawn (at least partly on the frame).
    pub labels: u32,
    /// What the visible-surface stage did.
    pub visible: VisibleStats,
}

/// The memory of the 3D layer: the trapezoid store (one segment is
/// enough), the active list and one row of runs, and the way intersecting
/// spans are resolved. [`needs_3d`] sizes it for a list.
#[derive(Debug)]
pub struct Storage3d<'a> {
    /// Trapezoids, faces, segments, the scan-line index and edge slots.
    pub store: StoreMemory<'a>,
    /// The active list.
    pub active: &'a mut [Active],
    /// The cover array: as many as the active list.
    pub cover: &'a mut [Cover],
    /// One row of runs: the frame's width is always enough.
    pub runs: &'a mut [Run],
    /// How intersecting spans are resolved.
    pub resolve: Resolve,
}

/// What the 3D layer of a list needs, from [`needs_3d`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Needs3d {
    /// `poly3` commands in the list.
    pub poly3: usize,
    /// Scene commands (version 2) in the list.
    pub scene: usize,
    /// Trapezoid slots.
    pub trapezoids: usize,
    /// Face slots.
    pub faces: usize,
    /// Edge slots: the most vertices of one polygon reaching the layer.
    pub edges: usize,
    /// Rows of the scan-line index: the frame's height.
    pub rows: usize,
    /// Runs of one row: the frame's width.
    pub runs: usize,
    /// Label slots.
    pub labels: usize,
    /// Bytes of label text.
    pub text: usize,
}

impl Needs3d {
    /// `true` when the list has a 3D layer at all.
    pub fn any(&self) -> bool {
        self.poly3 + self.scene > 0
    }
}

/// `true` when the `poly3` is drawn: the shoelace sum of its vertices is
/// negative (counter-clockwise as displayed, y down). Each term is below
/// 2³¹ and there are at most 65535: the sum fits in `i64`.
pub fn front_facing(v: &Vertices3<'_>) -> bool {
    let mut it = v.iter();
    let Some(first) = it.next() else {
        return false;
    };
    let mut s = 0i64;
    let mut prev = first;
    for p in it.chain(core::iter::once(first)) {
        s +=
            prev.x.units() as i64 * p.y.units() as i64 - p.x.units() as i64 * prev.y.units() as i64;
        prev = p;
    }
    s < 0
}

/// Edge slots a polygon of the 3D layer may need, from its command alone:
/// a `poly3`'s vertices; a `face`'s plus the six it may gain by clipping,
/// at most [`LIST_VERTICES`], and at least four (points and lines).
fn edge_bound(cmd: &Command<'_>) -> usize {
    match cmd {
        Command::Poly3(v) => v.len(),
        Command::Face(p) => (p.len() + 6).clamp(4, LIST_VERTICES),
        _ => 0,
    }
}

/// Edge slots the 3D layer of `list` needs: what [`needs_3d`] wants as
/// scratch, and [`Storage3d`]'s store as edge slots.
pub fn edges_3d(list: &DisplayList<'_>) -> usize {
    list.commands()
        .map(|(_, c)| edge_bound(&c))
        .max()
        .unwrap_or(0)
}

/// `true` for the commands of the 3D scene (version 2).
fn is_scene_command(cmd: &Command<'_>) -> bool {
    !matches!(
        cmd,
        Command::Clear(_)
            | Command::Clip(_)
            | Command::Color(_)
            | Command::Poly(_)
            | Command::Poly3(_)
    )
}

/// Where the 3D layer goes: the store and the labels of a render, or
/// counters sizing them.
trait Layer3d {
    /// A polygon of the layer, in screen space.
    fn polygon(
        &mut self,
        vertices: impl IntoIterator<Item = Vertex3>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<(), (Resource, usize)>;
    /// A label, placed.
    fn label(&mut self, at: (i32, i32), color: Rgb888, text: &str)
        -> Result<(), (Resource, usize)>;
}

/// The geometry stage's polygons into a [`Layer3d`], under one clip.
struct Faces<'l, L> {
    layer: &'l mut L,
    clip: ClipRect,
}

impl<L: Layer3d> PolygonSink for Faces<'_, L> {
    type Error = (Resource, usize);
    fn polygon(&mut self, v: &[Vertex3], color: Rgb888, _: bool) -> Result<(), Self::Error> {
        self.layer.polygon(v.iter().copied(), color, &self.clip)
    }
}

/// What [`run_layer`] counted.
#[derive(Clone, Copy, Debug, Default)]
struct LayerCounts {
    poly3: u32,
    culled: u32,
    faces: u32,
    clipped_away: u32,
}

/// Executes the 3D layer of `list` (its `poly3`s and its scene commands,
/// in list order) into `layer`, on a frame of `w × h`.
#[inline(never)]
fn run_layer<L: Layer3d>(
    list: &DisplayList<'_>,
    (w, h): (u16, u16),
    layer: &mut L,
) -> Result<LayerCounts, RenderError<core::convert::Infallible>> {
    let mut n = LayerCounts::default();
    let mut clip = ClipRect::full(w, h);
    let mut color = DEFAULT_COLOR;
    let mut pipe: Option<ListPipeline> = None;
    let full = |offset, (resource, capacity)| RenderError::Capacity3d {
        offset,
        resource,
        capacity,
    };
    let scene = |offset, error: SceneError| RenderError::Scene { offset, error };
    for (offset, cmd) in list.commands() {
        // The pipeline is made at the first scene command.
        if pipe.is_none() && is_scene_command(&cmd) {
            let window = Viewport::centred(w, h).map_err(|e| scene(offset, e.into()))?;
            let q = Q16::from_int;
            let persp = Perspective::from_fov(Angle::from_degrees(60), w, q(1), q(1000))
                .map_err(|e| scene(offset, e.into()))?;
            pipe = Some(ListPipeline::new(persp, window));
        }
        let err = |e: SceneError| scene(offset, e);
        match (cmd, pipe.as_mut()) {
            (Command::Clip(win), _) => clip = ClipRect::from_window(win, w, h),
            (Command::Color(c), _) => color = c,
            (Command::Poly3(v), _) => {
                if front_facing(&v) {
                    layer
                        .polygon(v.iter(), color, &clip)
                        .map_err(|e| full(offset, e))?;
                    n.poly3 += 1;
                } else {
                    n.culled += 1;
                }
            }
            (Command::Clear(_) | Command::Poly(_), _) | (_, None) => {}
            (Command::Segment(_), Some(p)) => p.reset_stack(),
            (Command::Perspective { fov, near, far }, Some(p)) => p.set_projection(
                Perspective::from_fov(fov, w, near, far).map_err(|e| err(e.into()))?,
            ),
            (Command::Ortho { scale, near, far }, Some(p)) => {
                p.set_projection(Orthographic::new(scale, near, far).map_err(|e| err(e.into()))?)
            }
            (Command::View { eye, yaw, pitch }, Some(p)) => p
                .set_view(&View { eye, yaw, pitch })
                .map_err(|e| err(e.into()))?,
            (Command::Light { toward, percent }, Some(p)) => {
                p.set_light(Light::new(toward.to_bits(), percent).ok_or(err(SceneError::Light))?)
            }
            (Command::Thickness(t), Some(p)) => p.set_thickness(t),
            (Command::Push, Some(p)) => p.stack_mut().push().map_err(|e| err(e.into()))?,
            (Command::Pop, Some(p)) => p.stack_mut().pop().map_err(|e| err(e.into()))?,
            (Command::Translate(t), Some(p)) => p
                .stack_mut()
                .translate(t.x, t.y, t.z)
                .map_err(|e| err(e.into()))?,
            (Command::Rotate(axis, a), Some(p)) => {
                let s = p.stack_mut();
                match axis {
                    Axis::X => s.rotate_x(a),
                    Axis::Y => s.rotate_y(a),
                    Axis::Z => s.rotate_z(a),
                }
                .map_err(|e| err(e.into()))?
            }
            (Command::Scale(f), Some(p)) => p
                .stack_mut()
                .scale(f.x, f.y, f.z)
                .map_err(|e| err(e.into()))?,
            (Command::Face(points), Some(p)) => {
                let mut v: heapless::Vec<Point3, LIST_VERTICES> = heapless::Vec::new();
                for q in points.iter() {
                    v.push(q)
                        .map_err(|_| full(offset, (Resource::FaceVertices, LIST_VERTICES - 6)))?;
                }
                let mut sink = Faces {
                    layer: &mut *layer,
                    clip,
                };
                match p.polygon(&v, color, &mut sink) {
                    Ok(crate::geometry::Outcome::Emitted) => n.faces += 1,
                    Ok(crate::geometry::Outcome::Culled) => n.culled += 1,
                    Ok(_) => n.clipped_away += 1,
                    Err(PipelineError::Sink(e)) => return Err(full(offset, e)),
                    Err(PipelineError::Capacity { .. }) => {
                        return Err(full(offset, (Resource::FaceVertices, LIST_VERTICES - 6)))
                    }
                    Err(PipelineError::Range) => return Err(err(SceneError::Range)),
                }
            }
            (Command::Label { at, text }, Some(p)) => {
                let a = p.project_point(at).map_err(|e| err(e.into()))?;
                if a.in_front {
                    layer
                        .label(label::to_pixels(a), color, text)
                        .map_err(|e| full(offset, e))?;
                }
            }
        }
    }
    Ok(n)
}

/// Counts what the 3D layer needs, cutting polygons without keeping them.
struct Count<'e> {
    edges: &'e mut [EdgeSlot],
    need: Needs3d,
}

impl Layer3d for Count<'_> {
    fn polygon(
        &mut self,
        v: impl IntoIterator<Item = Vertex3>,
        _: Rgb888,
        clip: &ClipRect,
    ) -> Result<(), (Resource, usize)> {
        let cap = self.edges.len();
        let poly =
            Polygon::load(&mut *self.edges, v, clip).map_err(|_| (Resource::EdgeSlots, cap))?;
        if poly.plane().is_none() {
            return Ok(());
        }
        let t = poly.cut(|_, _| Ok::<(), ()>(())).unwrap_or(0) as usize;
        self.need.trapezoids += t;
        self.need.faces += (t > 0) as usize;
        Ok(())
    }

    fn label(&mut self, _: (i32, i32), _: Rgb888, text: &str) -> Result<(), (Resource, usize)> {
        self.need.labels += 1;
        self.need.text += text.len();
        Ok(())
    }
}

/// Sizes [`Storage3d`] and the label memory for `list` by running its 3D
/// layer (nothing is drawn), with `edges` as scratch. Returns `None` when
/// `edges` has fewer slots than [`Needs3d::edges`] or a scene command
/// fails (rendering reports it). Active entries are not counted: at most
/// [`Needs3d::trapezoids`] are needed, and [`Workspace::check`] gives the
/// exact number once the store is built. Labels are counted when their
/// point is in front of the eye, on the frame or not.
pub fn needs_3d(list: &DisplayList<'_>, edges: &mut [EdgeSlot]) -> Option<Needs3d> {
    let (w, h) = (list.width(), list.height());
    let mut need = Needs3d {
        rows: h as usize,
        runs: w as usize,
        ..Needs3d::default()
    };
    for (_, cmd) in list.commands() {
        match cmd {
            Command::Poly3(_) => need.poly3 += 1,
            Command::Clear(_) | Command::Clip(_) | Command::Color(_) | Command::Poly(_) => {}
            _ => need.scene += 1,
        }
        need.edges = need.edges.max(edge_bound(&cmd));
    }
    if edges.len() < need.edges {
        return None;
    }
    let mut count = Count { edges, need };
    run_layer(list, (w, h), &mut count).ok()?;
    Some(count.need)
}

/// The graphic controller.
///
/// For 2D lists it needs only a [`Rasterizer`]; `poly3` and the 3D scene
/// also need the memory of the 3D layer, and labels their own:
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
/// use scanvert::{
///     controller::{Controller, Storage3d}, display_list::{DisplayList, Writer}, raster::edge::Edge,
///     fixed::{Coord, Vertex3}, port::framebuffer::FrameBuffer, visible::rle::Run, raster::scan::Rasterizer,
///     segment::{Face, Segment, StoreMemory}, visible::trapezoid::{EdgeSlot, Trapezoid},
///     visible::{Active, Cover, Resolve},
/// };
///
/// let v = |x: i16, y: i16, z: i16| Vertex3 { x: Coord::from_bits(x * 16), y: Coord::from_bits(y * 16), z: Coord::from_bits(z * 16) };
/// let mut bytes = [0u8; 128];
/// let mut w = Writer::new(&mut bytes, 32, 16)?;
/// w.color(Rgb888::RED)?;
/// w.poly3([v(2, 2, 10), v(4, 14, 10), v(30, 8, 10)])?; // counter-clockwise as displayed
/// w.color(Rgb888::BLUE)?;
/// w.poly3([v(12, 0, 5), v(12, 16, 5), v(20, 16, 20)])?; // nearer on its left
/// let list = DisplayList::new_checked(w.finish()).unwrap();
///
/// let mut edges = [Edge::EMPTY; 8];
/// let (mut traps, mut faces, mut segs) = ([Trapezoid::EMPTY; 32], [Face::EMPTY; 8], [Segment::EMPTY; 1]);
/// let (mut rows, mut slots) = ([0u16; 16], [EdgeSlot::EMPTY; 8]);
/// let (mut active, mut cover, mut runs) = ([Active::EMPTY; 16], [Cover::EMPTY; 16], [Run::EMPTY; 32]);
/// let storage = Storage3d {
///     store: StoreMemory { trapezoids: &mut traps, faces: &mut faces, segments: &mut segs, rows: &mut rows, edges: &mut slots },
///     active: &mut active,
///     cover: &mut cover,
///     runs: &mut runs,
///     resolve: Resolve::Crossing,
/// };
/// let mut pixels = [Rgb565::BLACK; 32 * 16];
/// let mut fb = FrameBuffer::new(&mut pixels, 32, 16).unwrap();
/// let stats = Controller::new(Rasterizer::new(&mut edges)).with_3d(storage).render(&list, &mut fb).unwrap();
/// assert_eq!(stats.poly3, 2);
/// assert_eq!(fb.pixel(13, 8), Some(Rgb565::BLUE));
/// assert_eq!(fb.pixel(19, 8), Some(Rgb565::RED));
/// # Ok::<(), scanvert::display_list::WriteError>(())
/// ```
#[derive(Debug)]
pub struct Controller<'e> {
    raster: Rasterizer<'e>,
    three: Option<Storage3d<'e>>,
    labels: Option<(&'e mut [Label], &'e mut [u8])>,
}

impl<'e> Controller<'e> {
    /// A controller scan-converting with `raster`, for 2D lists.
    pub fn new(raster: Rasterizer<'e>) -> Self {
        Controller {
            raster,
            three: None,
            labels: None,
        }
    }

    /// The same controller, rendering `poly3` and the 3D scene with
    /// `storage`.
    pub fn with_3d(mut self, storage: Storage3d<'e>) -> Self {
        self.three = Some(storage);
        self
    }

    /// The same controller, placing labels in `slots` with their text in
    /// `text` (see [`scene::label`](crate::scene::label)).
    pub fn with_labels(mut self, slots: &'e mut [Label], text: &'e mut [u8]) -> Self {
        self.labels = Some((slots, text));
        self
    }

    /// Checks, without drawing, what can be checked before the 3D layer
    /// is built: polygon sizes against the edge storage, `poly3` and
    /// `face` sizes against the edge slots, known commands, the 3D layer
    /// only with 3D storage and labels only with label memory.
    /// [`render`](Self::render) checks the rest (trapezoids, faces,
    /// labels, active entries, the scene's commands) after building the
    /// layer, still before drawing.
    pub fn check(
        &self,
        list: &DisplayList<'_>,
    ) -> Result<(), RenderError<core::convert::Infallible>> {
        let capacity = self.raster.capacity();
        for (offset, cmd) in list.commands() {
            match cmd {
                Command::Poly(v) if v.len() > capacity => {
                    return Err(RenderError::Capacity {
                        offset,
                        vertices: v.len(),
                        capacity,
                    })
                }
                Command::Clear(_) | Command::Clip(_) | Command::Color(_) | Command::Poly(_) => {}
                _ => {
                    let Some(t) = &self.three else {
                        return Err(RenderError::Unsupported {
                            offset,
                            command: if matches!(cmd, Command::Poly3(_)) {
                                "poly3"
                            } else {
                                "3D scene"
                            },
                        });
                    };
                    if let Command::Face(p) = &cmd {
                        if p.len() > LIST_VERTICES - 6 {
                            return Err(RenderError::Capacity3d {
                                offset,
                                resource: Resource::FaceVertices,
                                capacity: LIST_VERTICES - 6,
                            });
                        }
                    }
                    if edge_bound(&cmd) > t.store.edges.len() {
                        return Err(RenderError::Capacity3d {
                            offset,
                            resource: Resource::EdgeSlots,
                            capacity: t.store.edges.len(),
                        });
                    }
                    if matches!(cmd, Command::Label { .. }) && self.labels.is_none() {
                        return Err(RenderError::Capacity3d {
                            offset,
                            resource: Resource::Labels,
                            capacity: 0,
                        });
                    }
                }
            }
        }
        Ok(())
    }

    /// Executes `list` into `target`, starting with the clip registers on
    /// the whole frame and the colour [`DEFAULT_COLOR`].
    ///
    /// The frame is the list's, cut to the target's size. The list is
    /// [`check`](Self::check)ed and its 3D layer built first: on any error
    /// but the port's, nothing is drawn.
    pub fn render<T>(
        &mut self,
        list: &DisplayList<'_>,
        target: &mut T,
    ) -> Result<Stats, RenderError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        self.check(list).map_err(widen)?;
        let (tw, th) = target.size();
        let (w, h) = (list.width().min(tw), list.height().min(th));
        let mut stats = Stats::default();
        let Controller {
            raster,
            three,
            labels,
        } = self;
        // The 3D layer is built first: running out of memory, or a scene
        // command that fails, is found before anything is drawn.
        let layer = match three.as_mut() {
            // Without 3D storage, `check` has refused the 3D layer.
            None => None,
            Some(t) => match list.commands().find(|(_, c)| {
                !matches!(
                    c,
                    Command::Clear(_) | Command::Clip(_) | Command::Color(_) | Command::Poly(_)
                )
            }) {
                Some((first, _)) => Some(
                    build_layer(t, labels.as_mut(), list, (w, h), first, &mut stats)
                        .map_err(widen)?,
                ),
                None => None,
            },
        };
        let mut clip = ClipRect::full(w, h);
        let mut color = T::Color::from_rgb888(DEFAULT_COLOR);
        for (offset, cmd) in list.commands() {
            stats.commands += 1;
            match cmd {
                Command::Clear(c) => {
                    target
                        .clear(T::Color::from_rgb888(c))
                        .map_err(|error| RenderError::Target { offset, error })?;
                    stats.clears += 1;
                }
                Command::Clip(win) => clip = ClipRect::from_window(win, w, h),
                Command::Color(c) => color = T::Color::from_rgb888(c),
                Command::Poly(v) => {
                    let counts =
                        raster
                            .fill(v.iter(), &clip, color, target)
                            .map_err(|e| match e {
                                FillError::Target(error) => RenderError::Target { offset, error },
                                FillError::Capacity { capacity } => RenderError::Capacity {
                                    offset,
                                    vertices: v.len(),
                                    capacity,
                                },
                            })?;
                    stats.polygons += 1;
                    stats.spans += counts.spans;
                    stats.pixels += counts.pixels as u64;
                }
                // The 3D layer, drawn below.
                _ => {}
            }
        }
        if let Some(layer) = layer {
            draw_layer(layer, target, &mut stats)?;
        }
        Ok(stats)
    }
}

/// A render error of no port, as one of a port's.
fn widen<E>(e: RenderError<core::convert::Infallible>) -> RenderError<E> {
    match e {
        RenderError::Capacity {
            offset,
            vertices,
            capacity,
        } => RenderError::Capacity {
            offset,
            vertices,
            capacity,
        },
        RenderError::Capacity3d {
            offset,
            resource,
            capacity,
        } => RenderError::Capacity3d {
            offset,
            resource,
            capacity,
        },
        RenderError::Unsupported { offset, command } => {
            RenderError::Unsupported { offset, command }
        }
        RenderError::Scene { offset, error } => RenderError::Scene { offset, error },
        RenderError::Target { error, .. } => match error {},
    }
}

/// Draws a built 3D layer into `target` over what is there, then its
/// labels. Kept out of line, so that the 2D path of
/// [`Controller::render`] compiles as it does without it.
#[inline(never)]
fn draw_layer<T>(
    (store, mut ws, resolve, first, labels): Layer<'_>,
    target: &mut T,
    stats: &mut Stats,
) -> Result<(), RenderError<T::Error>>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
{
    let (v, counts) =
        visible::draw(&store, &mut ws, resolve, target, None).map_err(|e| match e {
            VisibleError::Sink(error) => RenderError::Target {
                offset: first,
                error,
            },
            // Checked by `build_layer`.
            VisibleError::Active { capacity } => RenderError::Capacity3d {
                offset: first,
                resource: Resource::Active,
                capacity,
            },
            VisibleError::Runs { capacity } => RenderError::Capacity3d {
                offset: first,
                resource: Resource::Runs,
                capacity,
            },
        })?;
    stats.visible = v;
    stats.spans += counts.spans;
    stats.pixels += counts.pixels as u64;
    if let Some(labels) = labels {
        let c = labels
            .draw(label::DEFAULT_FONT, target)
            .map_err(|error| RenderError::Target {
                offset: first,
                error,
            })?;
        stats.labels = c.drawn;
        stats.spans += c.spans;
        stats.pixels += c.pixels as u64;
    }
    Ok(())
}

/// The store, workspace and labels of a built 3D layer, ready to draw.
type Layer<'t> = (
    TrapezoidStore<'t>,
    Workspace<'t>,
    Resolve,
    usize,
    Option<LabelStore<'t>>,
);

/// The store and labels of a render as a [`Layer3d`]; everything goes
/// into segment 0, in list order.
struct Keep<'s, 't> {
    store: &'s mut TrapezoidStore<'t>,
    labels: Option<&'s mut LabelStore<'t>>,
    trapezoids: u32,
}

impl Layer3d for Keep<'_, '_> {
    fn polygon(
        &mut self,
        v: impl IntoIterator<Item = Vertex3>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<(), (Resource, usize)> {
        self.trapezoids += self
            .store
            .add_polygon(0, v, color, clip)
            .map_err(Resource::of_store)?;
        Ok(())
    }

    fn label(
        &mut self,
        at: (i32, i32),
        color: Rgb888,
        text: &str,
    ) -> Result<(), (Resource, usize)> {
        match self.labels.as_mut() {
            Some(l) => l
                .add(0, at, color, text)
                .map(|_| ())
                .map_err(Resource::of_labels),
            // `check` refuses labels without label memory.
            None => Err((Resource::Labels, 0)),
        }
    }
}

/// Builds the 3D layer of `list` in `t` (and `labels`) and checks the
/// active list and the run buffer against it.
#[inline(never)]
fn build_layer<'t>(
    t: &'t mut Storage3d<'_>,
    labels: Option<&'t mut (&mut [Label], &mut [u8])>,
    list: &DisplayList<'_>,
    (w, h): (u16, u16),
    first: usize,
    stats: &mut Stats,
) -> Result<Layer<'t>, RenderError<core::convert::Infallible>> {
    let full = |offset: usize, (resource, capacity): (Resource, usize)| RenderError::Capacity3d {
        offset,
        resource,
        capacity,
    };
    let mem = StoreMemory {
        trapezoids: &mut *t.store.trapezoids,
        faces: &mut *t.store.faces,
        segments: &mut *t.store.segments,
        rows: &mut *t.store.rows,
        edges: &mut *t.store.edges,
    };
    let mut store =
        TrapezoidStore::new(mem, w, h).map_err(|e| full(first, Resource::of_store(e)))?;
    let mut labels = labels.map(|(s, x)| LabelStore::new(s, x));
    let mut keep = Keep {
        store: &mut store,
        labels: labels.as_mut(),
        trapezoids: 0,
    };
    let n = run_layer(list, (w, h), &mut keep)?;
    stats.trapezoids = keep.trapezoids;
    stats.poly3 = n.poly3;
    stats.culled = n.culled;
    stats.faces = n.faces;
    stats.clipped_away = n.clipped_away;
    let mut ws = Workspace::new(&mut *t.active, &mut *t.cover, &mut *t.runs);
    ws.check(&store).map_err(|e| match e {
        VisibleError::Active { capacity } => full(first, (Resource::Active, capacity)),
        VisibleError::Runs { capacity } => full(first, (Resource::Runs, capacity)),
        VisibleError::Sink(e) => match e {},
    })?;
    Ok((store, ws, t.resolve, first, labels))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::display_list::Writer;
    use crate::fixed::{Coord, Vertex, Vertex3};
    use crate::port::framebuffer::FrameBuffer;
    use crate::raster::edge::Edge;
    use crate::visible::store::{Face, Segment};
    use crate::visible::trapezoid::Trapezoid;
    use embedded_graphics_core::pixelcolor::Rgb888;

    const W: u16 = 24;
    const H: u16 = 16;

    fn v(x: i16, y: i16, z: i16) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits(x * 16),
            y: Coord::from_bits(y * 16),
            z: Coord::from_bits(z * 16),
        }
    }

    struct Mem {
        edges: [Edge; 8],
        traps: [Trapezoid; 16],
        faces: [Face; 4],
        segs: [Segment; 1],
        rows: [u16; H as usize],
        slots: [EdgeSlot; 8],
        active: [Active; 8],
        cover: [Cover; 8],
        runs: [Run; W as usize],
    }

    impl Mem {
        fn new() -> Self {
            Mem {
                edges: [Edge::EMPTY; 8],
                traps: [Trapezoid::EMPTY; 16],
                faces: [Face::EMPTY; 4],
                segs: [Segment::EMPTY; 1],
                rows: [0; H as usize],
                slots: [EdgeSlot::EMPTY; 8],
                active: [Active::EMPTY; 8],
                cover: [Cover::EMPTY; 8],
                runs: [Run::EMPTY; W as usize],
            }
        }

        /// Renders `list` with 3D storage (`three`) or without; returns the
        /// frame as the colours' red channels, row by row.
        fn render(
            &mut self,
            list: &DisplayList<'_>,
            three: bool,
        ) -> (
            Result<Stats, RenderError<core::convert::Infallible>>,
            [u8; (W * H) as usize],
        ) {
            let mut px = [Rgb888::new(7, 7, 7); (W * H) as usize];
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let mut c = Controller::new(Rasterizer::new(&mut self.edges));
            if three {
                c = c.with_3d(Storage3d {
                    store: StoreMemory {
                        trapezoids: &mut self.traps,
                        faces: &mut self.faces,
                        segments: &mut self.segs,
                        rows: &mut self.rows,
                        edges: &mut self.slots,
                    },
                    active: &mut self.active,
                    cover: &mut self.cover,
                    runs: &mut self.runs,
                    resolve: Resolve::Bisect,
                });
            }
            let r = c.render(list, &mut fb);
            (r, core::array::from_fn(|i| px[i].r()))
        }
    }

    fn list(bytes: &mut [u8], f: impl FnOnce(&mut Writer<'_>)) -> usize {
        let mut w = Writer::new(bytes, W, H).unwrap();
        f(&mut w);
        w.finish().len()
    }

    #[test]
    fn poly3_needs_3d_storage() {
        let mut bytes = [0u8; 256];
        let n = list(&mut bytes, |w| {
            w.poly3([v(1, 1, 1), v(1, 9, 1), v(9, 5, 1)]).unwrap();
        });
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let mut m = Mem::new();
        let (r, px) = m.render(&l, false);
        assert_eq!(
            r,
            Err(RenderError::Unsupported {
                offset: 16,
                command: "poly3"
            })
        );
        assert!(px.iter().all(|&p| p == 7), "nothing drawn");
        let (r, px) = m.render(&l, true);
        assert_eq!(r.unwrap().poly3, 1);
        assert_eq!(px[5 * W as usize + 3], 255);
    }

    #[test]
    fn the_3d_layer_is_drawn_over_the_2d_commands_where_it_covers() {
        let mut bytes = [0u8; 512];
        let n = list(&mut bytes, |w| {
            w.clear(Rgb888::new(10, 0, 0)).unwrap();
            w.color(Rgb888::new(50, 0, 0)).unwrap();
            // A far face, then a 2D square after it, then a near face.
            w.poly3([v(0, 0, 100), v(0, 16, 100), v(12, 16, 100), v(12, 0, 100)])
                .unwrap();
            w.color(Rgb888::new(20, 0, 0)).unwrap();
            w.poly(
                [(0, 0), (24, 0), (24, 4), (0, 4)].map(|(x, y)| Vertex::from_bits(x * 16, y * 16)),
            )
            .unwrap();
            w.color(Rgb888::new(60, 0, 0)).unwrap();
            w.clip(crate::raster::clip::ClipWindow {
                x0: 0,
                y0: 0,
                x1: 5,
                y1: 15,
            })
            .unwrap();
            w.poly3([v(2, 2, 1), v(2, 14, 1), v(20, 14, 1), v(20, 2, 1)])
                .unwrap();
            // Clockwise as displayed: culled.
            w.poly3([v(0, 0, 0), v(24, 0, 0), v(24, 16, 0)]).unwrap();
        });
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let (r, px) = Mem::new().render(&l, true);
        let s = r.unwrap();
        assert_eq!((s.poly3, s.culled, s.polygons), (2, 1, 1));
        let at = |x: usize, y: usize| px[y * W as usize + x];
        assert_eq!(at(3, 8), 60, "near face, inside its clip");
        assert_eq!(at(8, 8), 50, "far face, outside the near face's clip");
        assert_eq!(at(8, 1), 50, "the 3D layer covers the 2D square");
        assert_eq!(at(16, 1), 20, "2D square where no face is");
        assert_eq!(at(16, 8), 10, "the clear where nothing is");
    }

    #[test]
    fn running_out_of_3d_memory_is_found_before_drawing() {
        let mut bytes = [0u8; 1024];
        let n = list(&mut bytes, |w| {
            w.clear(Rgb888::new(1, 0, 0)).unwrap();
            for k in 0..5 {
                w.poly3([v(k, 0, k), v(k, 16, k), v(k + 12, 8, k)]).unwrap();
            }
        });
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let mut m = Mem::new();
        let (r, px) = m.render(&l, true);
        assert!(matches!(
            r,
            Err(RenderError::Capacity3d {
                resource: Resource::Faces,
                capacity: 4,
                ..
            })
        ));
        assert!(px.iter().all(|&p| p == 7), "nothing drawn");
        let mut slots = [EdgeSlot::EMPTY; 3];
        let need = needs_3d(&l, &mut slots).unwrap();
        assert_eq!((need.poly3, need.faces, need.edges), (5, 5, 3));
        assert_eq!(need.trapezoids, 10);
    }
}
