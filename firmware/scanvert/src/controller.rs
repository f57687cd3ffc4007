//! The graphic controller: executes a display list into a frame-buffer
//! port, holding the clip registers and the current colour.
//!
//! # `poly` and `poly3` in one list
//!
//! `clear` and `poly` are executed in list order (painter's order). The
//! `poly3`s are the *3D layer*: all of them are resolved together by the
//! visible-surface stages ([`trapezoid`](crate::visible::trapezoid) →
//! [`store`](crate::visible::store) → [`sweep`](mod@crate::visible::sweep) →
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
//! The scene commands of version 2 feed the same 3D layer. The layer is a
//! [`Scene`] of one segment, and every 3D command is executed by the
//! scene's one interpreter ([`Builder::command`], see
//! [`scene::list`](crate::scene::list)), in list order, through a
//! [`Pipeline`] of [`LIST_STACK`] saved transforms and polygons of up to
//! [`LIST_VERTICES`] vertices (after clipping), starting from these
//! defaults ([`list_pipeline`]):
//!
//! | state | default | set by |
//! |---|---|---|
//! | projection | perspective, 60° horizontal field of view, near 1, far 1000 | `perspective`, `ortho` |
//! | window | the list's frame, the view axis through its middle | (fixed) |
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
//! `face`s are culled by the orientation of the whole polygon as
//! displayed (see [`geometry::cull`](crate::geometry::cull)) and lit;
//! `label`s are drawn after the whole 3D layer, in the colour in force at
//! their place, with the lower-left corner of their first character at
//! the projected point (see [`scene::label`](crate::scene::label)), never
//! hidden.
//!
//! The 3D layer is projected for the list's frame and, like the 2D
//! commands, cut to the target: a target smaller than the frame shows the
//! frame's top-left part, unchanged.
//!
//! # Memory
//!
//! The 3D layer needs memory of its own: a [`SceneMemory`] (store, active
//! list, runs, label slots and text), given with [`Controller::with_3d`];
//! [`SceneStorage`](crate::scene::SceneStorage) owns one with const-generic
//! capacities. Without it a list with a `poly3` or any scene command is
//! rejected as [`RenderError::Unsupported`]; with too little, as
//! [`RenderError::Capacity3d`] naming the command that ran out. A scene
//! command that fails (a `pop` with nothing saved, a vertex outside view
//! space, a projection out of range) is a [`RenderError::Scene`] naming
//! that command. All of these are found before anything is drawn, and the
//! first failing command in list order is the one named. [`needs`] sizes
//! the memory for a list, and refuses a list that needs more than a pool
//! can address ([`POOL_LIMIT`]) before anything is allocated.
//!
//! # Timing
//!
//! [`Controller::render_with`] tells a [`Hook`] when each stage of the
//! render ends ([`Stage`]); [`render`](Controller::render) passes one that
//! does nothing, which compiles to nothing.
//!
//! [`Pipeline`]: crate::geometry::Pipeline
//! [`Scene`]: crate::scene::Scene
//! [`Builder::command`]: crate::scene::Builder::command

use crate::color::ListColor;
use crate::display_list::{Command, Commands, DisplayList, Summary};
use crate::geometry::project::WINDOW_MAX;
use crate::geometry::{Outcome, Pipeline, ViewPoint};
use crate::port::SpanTarget;
use crate::raster::clip::ClipRect;
use crate::raster::draw::Draw;
use crate::raster::line;
use crate::raster::scan::{FillError, Rasterizer};
use crate::scene::label::{self, LabelError};
use crate::scene::list::{execute, MeshCounts, Out};
use crate::scene::VertexTable;
use crate::scene::{
    list_pipeline, Builder, Executed, Hook, ListState, Scene, SceneError, SceneMemory, Stage,
};
use crate::visible::store::StoreError;
use crate::visible::trapezoid::{EdgeSlot, Polygon, TriangleCut};
use crate::visible::{Resolve, VisibleError, VisibleStats};
use core::fmt;
use embedded_graphics_core::pixelcolor::Rgb888;

pub mod bands;
pub mod frame;
pub use bands::{ListBands, ListBandsError, PrepareError};

/// Matrices the transform stack of a list's 3D scene saves (`push`
/// without `pop`).
pub const LIST_STACK: usize = 16;

/// Vertices of one 3D polygon of a list, at every stage of clipping: a
/// `face` may have up to `LIST_VERTICES − 6`, and is drawn whole when each
/// clip pass leaves it at most `LIST_VERTICES`. A pass adds at most one
/// vertex for each separate part of the polygon it cuts off, so a convex
/// face (one part a plane) always fits; a concave one whose teeth a plane
/// cuts off one by one can need more, and is then refused at its command
/// ([`Resource::ClippedVertices`]), before anything is drawn.
pub const LIST_VERTICES: usize = 64;

/// The most slots of one pool that a list may need: the store's pools
/// and the active list index their slots with `u16`, one value reserved.
/// [`needs`] refuses a list that needs more.
pub const POOL_LIMIT: usize = u16::MAX as usize;

/// The geometry stage of a list's 3D scene.
type ListPipeline = Pipeline<LIST_STACK, LIST_VERTICES>;

/// The 3D layer of a list: a scene of one segment.
type ListScene<'t> = Scene<'t, LIST_STACK, LIST_VERTICES>;

/// Why a display list could not be rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
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
    /// The 3D storage is too small for the list's 3D layer, or the list
    /// needs more than a pool can address ([`POOL_LIMIT`]). Found before
    /// anything is drawn.
    Capacity3d {
        /// Byte offset of the command that ran out (the first command of
        /// the 3D layer when the layer as a whole does not fit).
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

impl<E: fmt::Debug> core::error::Error for RenderError<E> {}

/// A pool of the 3D storage, in a [`RenderError::Capacity3d`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Resource {
    /// Trapezoid slots.
    Trapezoids,
    /// Face slots (one per drawn `poly3`).
    Faces,
    /// Edge slots (a `poly3` of `n` vertices needs `n`).
    EdgeSlots,
    /// Segments (a list uses one).
    Segments,
    /// Rows of the scan-line index (the frame's height).
    Rows,
    /// Active-list entries (trapezoids overlapping one row).
    Active,
    /// Runs of one row (the frame's width).
    Runs,
    /// Vertices of one 3D `face` ([`LIST_VERTICES`] less six).
    FaceVertices,
    /// Vertices of one 3D polygon after a clip pass ([`LIST_VERTICES`]): a
    /// concave face gains a vertex for each part of it a plane cuts off.
    ClippedVertices,
    /// Label slots.
    Labels,
    /// Bytes of label text.
    LabelText,
    /// Slots of the mesh vertex table ([`Controller::with_vertices`]).
    Vertices,
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
            Resource::ClippedVertices => "vertices of a face after clipping",
            Resource::Labels => "labels",
            Resource::LabelText => "bytes of label text",
            Resource::Vertices => "mesh vertex slots",
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
}

/// A failure of the 3D command at `offset`, as a render error: running out
/// of a pool is [`RenderError::Capacity3d`], the rest
/// [`RenderError::Scene`].
fn error_at(offset: usize, error: SceneError) -> RenderError<core::convert::Infallible> {
    let (resource, capacity) = match error {
        SceneError::Store(e) => Resource::of_store(e),
        SceneError::Labels(LabelError::Labels { capacity }) => (Resource::Labels, capacity),
        SceneError::Labels(LabelError::Text { capacity }) => (Resource::LabelText, capacity),
        SceneError::Vertices { .. } => (Resource::ClippedVertices, LIST_VERTICES),
        SceneError::VertexTable { capacity } => (Resource::Vertices, capacity),
        _ => return RenderError::Scene { offset, error },
    };
    RenderError::Capacity3d {
        offset,
        resource,
        capacity,
    }
}

/// What a render did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RenderStats {
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
    /// Mesh vertices (`v`s) transformed, each once.
    pub vertices: u32,
    /// Labels drawn (at least partly on the frame).
    pub labels: u32,
    /// What the visible-surface stage did.
    pub visible: VisibleStats,
}

/// What a display list needs to be rendered, from [`needs`]: the
/// rasteriser's edge storage and, for a 3D layer, the capacities of its
/// [`SceneMemory`]. Every pool is at most [`POOL_LIMIT`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Needs {
    /// `poly3` commands in the list.
    pub poly3: usize,
    /// Scene commands (version 2) in the list.
    pub scene: usize,
    /// Edge storage of the rasteriser
    /// ([`Edge`](crate::raster::edge::Edge)s): the most vertices of one
    /// `poly`.
    pub edges: usize,
    /// Edge slots of the store ([`EdgeSlot`]s): the most vertices of one
    /// polygon reaching the 3D layer ([`edges_3d`]).
    pub edge_slots: usize,
    /// Trapezoid slots.
    pub trapezoids: usize,
    /// Face slots.
    pub faces: usize,
    /// Segments: one with a 3D layer.
    pub segments: usize,
    /// Rows of the scan-line index: the frame's height.
    pub rows: usize,
    /// Active-list slots: at most the trapezoids (the exact
    /// number, the most that overlap one row, is [`Scene::check`]'s).
    ///
    /// [`Scene::check`]: crate::scene::Scene::check
    pub active: usize,
    /// Runs of one row: the frame's width.
    pub runs: usize,
    /// Label slots.
    pub labels: usize,
    /// Bytes of label text.
    pub text: usize,
    /// Slots of the mesh vertex table: the most `v`s of one segment
    /// ([`Controller::with_vertices`]).
    pub vertices: usize,
}

impl Needs {
    /// `true` when the list has a 3D layer at all.
    pub fn any(&self) -> bool {
        self.poly3 + self.scene > 0
    }
}

/// Edge slots a polygon of the 3D layer may need, from its command alone:
/// a `poly3`'s vertices; a `face`'s plus the six it may gain by clipping,
/// at most [`LIST_VERTICES`], and at least four (points and lines).
fn edge_bound(cmd: &Command<'_>) -> usize {
    match cmd {
        Command::Poly3(v) => v.len(),
        Command::Face(p) => (p.len() + 6).clamp(4, LIST_VERTICES),
        Command::MeshFace(p) => (p.len() + 6).clamp(4, LIST_VERTICES),
        _ => 0,
    }
}

/// Edge slots the 3D layer of `list` needs: what [`needs`] wants as
/// scratch, and the store of the [`SceneMemory`] as edge slots.
#[doc(hidden)]
pub fn edges_3d(list: &DisplayList<'_>) -> usize {
    list.commands()
        .map(|(_, c)| edge_bound(&c))
        .max()
        .unwrap_or(0)
}

/// `true` for the commands of the 3D layer: `poly3` and the scene's.
fn is_3d(cmd: &Command<'_>) -> bool {
    cmd.is_3d()
}

/// `true` for the commands of the 3D scene (version 2).
fn is_scene_command(cmd: &Command<'_>) -> bool {
    is_3d(cmd) && !matches!(cmd, Command::Poly3(_))
}

/// The geometry stage of `list`'s 3D layer ([`list_pipeline`] on the
/// list's frame). A frame wider or taller than a window may be
/// (2047 px), or too narrow for the default projection (its focal length
/// below 1 px), can still hold `poly3`s: the pipeline is then made on a
/// window of a size that works, and the default's error is returned with
/// it, for the first scene command to report.
fn layer_pipeline(
    list: &DisplayList<'_>,
    first: usize,
) -> Result<(ListPipeline, Option<SceneError>), RenderError<core::convert::Infallible>> {
    let (w, h) = (list.width(), list.height());
    // The default's error, from a pipeline of the least capacities (its
    // checks are those of the window and the projection alone), so that
    // the list's pipeline is made once, in place: each one more is a copy
    // of about 1 KB on the stack.
    let window = list_pipeline::<1, 4>(w, h).err();
    // `poly3`s need no pipeline, so they are drawn whatever the frame; a
    // scene command reports the default's error.
    let (pw, ph) = match window {
        None => (w, h),
        Some(_) => (w.clamp(16, WINDOW_MAX), h.clamp(16, WINDOW_MAX)),
    };
    let p = list_pipeline(pw, ph).map_err(|e| error_at(first, e))?;
    Ok((p, window))
}

/// Counts what the 3D layer needs, cutting polygons without keeping them.
struct Count<'e> {
    edges: &'e mut [EdgeSlot],
    need: Needs,
}

impl Count<'_> {
    /// A polygon cut into `t` trapezoids: a face with them, when any.
    fn took(&mut self, t: usize) {
        self.need.trapezoids += t;
        self.need.faces += (t > 0) as usize;
    }
}

impl Out for Count<'_> {
    fn polygon<I: IntoIterator<Item = crate::fixed::Vertex3>>(
        &mut self,
        v: I,
        _: Rgb888,
        clip: &ClipRect,
        _: bool,
    ) -> Result<(), SceneError> {
        let poly = Polygon::load(&mut *self.edges, v, clip)
            .map_err(|e| SceneError::Store(StoreError::from(e)))?;
        // As the store: no plane or fewer than two edges, no trapezoid.
        if poly.plane().is_none() || poly.edges() < 2 {
            return Ok(());
        }
        // Stopped as soon as the layer needs more than a pool can hold.
        let room = POOL_LIMIT - self.need.trapezoids;
        let mut t = 0usize;
        poly.cut(|_, _| {
            t += 1;
            if t > room {
                Err(())
            } else {
                Ok(())
            }
        })
        .map_err(|()| {
            SceneError::Store(StoreError::Trapezoids {
                capacity: POOL_LIMIT,
            })
        })?;
        self.took(t);
        Ok(())
    }

    /// As the store cuts a triangle (from its three vertices,
    /// [`TriangleCut`]), with the same trapezoids.
    fn triangle(
        &mut self,
        v: [crate::fixed::Vertex3; 3],
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<(), SceneError> {
        let cut = match self.edges.len() >= 3 {
            true => TriangleCut::of(&v, clip),
            false => None,
        };
        let Some(cut) = cut else {
            return self.polygon(v, color, clip, false);
        };
        if cut.plane().is_none() {
            return Ok(());
        }
        let t = match cut.cut(|_, _, _, _| Ok::<(), ()>(())) {
            Ok(t) => t as usize,
            Err(()) => 0,
        };
        if t > POOL_LIMIT - self.need.trapezoids {
            return Err(SceneError::Store(StoreError::Trapezoids {
                capacity: POOL_LIMIT,
            }));
        }
        self.took(t);
        Ok(())
    }

    fn label(&mut self, _: (i32, i32), _: Rgb888, text: &str) -> Result<bool, SceneError> {
        self.need.labels += 1;
        self.need.text += text.len();
        Ok(true)
    }

    fn changed(&mut self) {}
}

/// What rendering `list` needs: the rasteriser's edges and the 3D layer's
/// memory, found by running its 3D commands through the interpreter the
/// render uses (nothing is drawn), with `scratch` as edge slots (at least
/// [`edges_3d`]).
///
/// Every pool is at most [`POOL_LIMIT`]: a list whose 3D layer would need
/// more trapezoids is refused with [`RenderError::Capacity3d`] at the
/// command that goes beyond, as soon as it does, so nothing need be
/// allocated for it. A 3D command that fails is reported as the render
/// would report it, at that command. Labels are counted when their point
/// is in front of the eye, on the frame or not.
pub fn needs(
    list: &DisplayList<'_>,
    scratch: &mut [EdgeSlot],
) -> Result<Needs, RenderError<core::convert::Infallible>> {
    needs_with(list, scratch, &mut [])
}

/// [`needs`] of a list with meshes: their `v`s are kept in `vertices`
/// while counting (at least [`Summary::vertices`] slots, else
/// [`RenderError::Capacity3d`] with [`Resource::Vertices`] at the `v`
/// that goes beyond).
pub fn needs_with(
    list: &DisplayList<'_>,
    scratch: &mut [EdgeSlot],
    vertices: &mut [ViewPoint],
) -> Result<Needs, RenderError<core::convert::Infallible>> {
    let mut need = Needs::default();
    let mut first = None;
    let mut widest = (0, 0);
    need.edges = list.summary().poly as usize;
    for (offset, cmd) in list.commands() {
        match &cmd {
            Command::Poly3(_) => need.poly3 += 1,
            _ if !cmd.is_3d() => {}
            _ => need.scene += 1,
        }
        if is_3d(&cmd) && first.is_none() {
            first = Some(offset);
        }
        if edge_bound(&cmd) > widest.1 {
            widest = (offset, edge_bound(&cmd));
        }
    }
    let Some(first) = first else {
        return Ok(need);
    };
    need.edge_slots = widest.1;
    if scratch.len() < need.edge_slots {
        return Err(RenderError::Capacity3d {
            offset: widest.0,
            resource: Resource::EdgeSlots,
            capacity: scratch.len(),
        });
    }
    let (w, h) = (list.width(), list.height());
    need.segments = 1;
    need.rows = h as usize;
    need.runs = w as usize;
    let (mut pipe, window) = layer_pipeline(list, first)?;
    need.vertices = list.summary().vertices;
    let mut st = ListState::new(w, h);
    let mut count = Count {
        edges: scratch,
        need,
    };
    let mut table = VertexTable::new(vertices);
    for (offset, cmd) in list.commands() {
        if let (Some(e), true) = (window, is_scene_command(&cmd)) {
            return Err(error_at(offset, e));
        }
        if let Command::Segment(id) = cmd {
            st.enter_segment(crate::scene::list::attributes(list, id));
        }
        execute(&mut pipe, &mut count, &mut st, &mut table, cmd)
            .map_err(|e| error_at(offset, e))?;
    }
    let mut need = count.need;
    need.active = need.trapezoids;
    Ok(need)
}

/// The graphic controller.
///
/// For 2D lists it needs only a [`Rasterizer`]; `poly3` and the 3D scene
/// also need the memory of the 3D layer:
///
/// ```
/// use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
/// use scanvert::{
///     controller::Controller, display_list::{DisplayList, Writer}, raster::edge::Edge,
///     fixed::{Coord, Vertex3}, port::framebuffer::FrameBuffer, raster::scan::Rasterizer,
///     scene::SceneStorage, visible::Resolve,
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
/// // 32 trapezoids, 8 faces, 1 segment, 16 rows, 8 edge slots,
/// // 16 active entries, 32 runs, no labels.
/// let mut storage = SceneStorage::<32, 8, 1, 16, 8, 16, 32, 0, 0>::new();
/// let mut pixels = [Rgb565::BLACK; 32 * 16];
/// let mut fb = FrameBuffer::new(&mut pixels, 32, 16).unwrap();
/// let stats = Controller::new(Rasterizer::new(&mut edges))
///     .with_3d(storage.as_memory())
///     .with_resolve(Resolve::Crossing)
///     .render(&list, &mut fb)
///     .unwrap();
/// assert_eq!(stats.poly3, 2);
/// assert_eq!(fb.pixel(13, 8), Some(Rgb565::BLUE));
/// assert_eq!(fb.pixel(19, 8), Some(Rgb565::RED));
/// # Ok::<(), scanvert::display_list::WriteError>(())
/// ```
#[derive(Debug)]
pub struct Controller<'e> {
    raster: Rasterizer<'e>,
    three: Option<SceneMemory<'e>>,
    resolve: Resolve,
    vertices: &'e mut [ViewPoint],
}

impl<'e> Controller<'e> {
    /// A controller scan-converting with `raster`, for 2D lists.
    pub fn new(raster: Rasterizer<'e>) -> Self {
        Controller {
            raster,
            three: None,
            resolve: Resolve::default(),
            vertices: &mut [],
        }
    }

    /// The same controller, keeping the `v`s of a list's meshes in
    /// `slots`: as many as the most `v`s of one segment
    /// ([`Needs::vertices`]); one more is [`RenderError::Capacity3d`] with
    /// [`Resource::Vertices`] at that `v`. Without it, a list has no room
    /// for a `v`.
    pub fn with_vertices(mut self, slots: &'e mut [ViewPoint]) -> Self {
        self.vertices = slots;
        self
    }

    /// The same controller, rendering `poly3`, the 3D scene and its
    /// labels in `memory` ([`needs`] sizes it).
    pub fn with_3d(mut self, memory: SceneMemory<'e>) -> Self {
        self.three = Some(memory);
        self
    }

    /// The same controller, resolving intersecting spans of the 3D layer
    /// with `resolve` (the default is [`Resolve::default`]).
    pub fn with_resolve(mut self, resolve: Resolve) -> Self {
        self.resolve = resolve;
        self
    }

    /// Checks, without drawing, what can be checked before the 3D layer
    /// is built: polygon sizes against the edge storage, `poly3` and
    /// `face` sizes against the edge slots, known commands, the 3D layer
    /// only with 3D storage. [`render`](Self::render) checks the rest
    /// (trapezoids, faces, labels, active entries, the scene's commands)
    /// while building the layer, still before drawing.
    pub fn check(
        &self,
        list: &DisplayList<'_>,
    ) -> Result<(), RenderError<core::convert::Infallible>> {
        // The list is walked only to name the command at fault.
        match self.fits(list.summary()) {
            true => Ok(()),
            false => self.fault(list),
        }
    }

    /// [`check`](Self::check) by walking the list: the first command at
    /// fault, in list order.
    fn fault(&self, list: &DisplayList<'_>) -> Result<(), RenderError<core::convert::Infallible>> {
        let capacity = self.raster.capacity();
        for (offset, cmd) in list.commands() {
            match cmd.poly_vertices() {
                Some(vertices) if vertices > capacity => {
                    return Err(RenderError::Capacity {
                        offset,
                        vertices,
                        capacity,
                    })
                }
                _ if !cmd.is_3d() => {}
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
                    let n = match &cmd {
                        Command::Face(p) => Some(p.len()),
                        Command::MeshFace(p) => Some(p.len()),
                        _ => None,
                    };
                    if let Some(n) = n {
                        if n > LIST_VERTICES - 6 {
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
                }
            }
        }
        Ok(())
    }

    /// `true` when [`check`](Self::check) finds nothing in a list of
    /// `summary`: each of its limits holds for the list's widest polygons
    /// (each limit is one on a polygon's vertices, and grows with them).
    fn fits(&self, summary: &Summary) -> bool {
        if summary.poly as usize > self.raster.capacity() {
            return false;
        }
        if summary.first_3d.is_none() {
            return true;
        }
        let Some(t) = &self.three else {
            return false;
        };
        let face = summary.face.max(summary.mesh_face) as usize;
        let slots = t.store.edges.len();
        summary.poly3 as usize <= slots
            && face <= LIST_VERTICES - 6
            && (face == 0 || (face + 6).clamp(4, LIST_VERTICES) <= slots)
    }

    /// Executes `list` into `target`, starting with the clip registers on
    /// the whole frame and the colour
    /// [`DEFAULT_COLOR`](crate::color::DEFAULT_COLOR).
    ///
    /// The frame is the list's, cut to the target's size. The list is
    /// [`check`](Self::check)ed and its 3D layer built first: on any error
    /// but the port's, nothing is drawn.
    pub fn render<T>(
        &mut self,
        list: &DisplayList<'_>,
        target: &mut T,
    ) -> Result<RenderStats, RenderError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
    {
        self.render_with(list, target, &mut |_| {})
    }

    /// [`render`](Self::render), telling `hook` when each stage ends: for
    /// a list with a 3D layer [`Stage::Start`] (checked, the layer's build
    /// begins), [`Stage::Cut`], [`Stage::Checked`]; for every list
    /// [`Stage::Painted`] (the 2D commands drawn); with a 3D layer then
    /// [`Stage::Resolved`] and [`Stage::Labelled`].
    pub fn render_with<T, H>(
        &mut self,
        list: &DisplayList<'_>,
        target: &mut T,
        hook: &mut H,
    ) -> Result<RenderStats, RenderError<T::Error>>
    where
        T: SpanTarget + ?Sized,
        T::Color: ListColor,
        H: Hook + ?Sized,
    {
        self.check(list).map_err(widen)?;
        let (tw, th) = target.size();
        let (w, h) = (list.width().min(tw), list.height().min(th));
        let mut stats = RenderStats::default();
        let Controller {
            raster,
            three,
            resolve,
            vertices,
        } = self;
        // The 3D layer is built first: running out of memory, or a scene
        // command that fails, is found before anything is drawn.
        // Without 3D storage, `check` has refused a 3D layer; the list is
        // not read again for it.
        let first = match three {
            Some(_) => list.summary().first_3d,
            None => None,
        };
        let mut built = None;
        let layer = match (three.as_mut(), first) {
            (Some(mem), Some(first)) => {
                hook.stage(Stage::Start);
                let scene = build_layer(
                    &mut built,
                    (mem.reborrow(), vertices),
                    list,
                    (w, h),
                    first,
                    &mut stats,
                )
                .map_err(widen)?;
                hook.stage(Stage::Cut);
                scene.check().map_err(|e| widen(visible_error(first, e)))?;
                hook.stage(Stage::Checked);
                Some(first)
            }
            _ => None,
        };
        stats.commands = list.summary().commands as u32;
        // The colour in the target's format, converted when it changes.
        let mut rgb = crate::color::DEFAULT_COLOR;
        let mut pixel = T::Color::from_rgb888(rgb);
        let mut convert = |c: Rgb888| {
            if c != rgb {
                (rgb, pixel) = (c, T::Color::from_rgb888(c));
            }
            pixel
        };
        // The list's one 2D interpreter: a list with no `clear`, `poly`
        // or `line` draws nothing here, and is not read again.
        list.for_each_draw((w, h), |offset, draw| {
            match draw {
                Draw::Clear(c) => {
                    target
                        .clear(T::Color::from_rgb888(c))
                        .map_err(|error| RenderError::Target { offset, error })?;
                    stats.clears += 1;
                }
                Draw::Poly {
                    vertices,
                    rule,
                    clip,
                    color,
                } => {
                    let color = convert(color);
                    // An axis-aligned rectangle without edges, else the scan
                    // converter.
                    let rectangle = match vertices.len() {
                        4 => raster.fill_quad(vertices, 4, &clip, color, target),
                        _ => None,
                    };
                    let counts = rectangle
                        .unwrap_or_else(|| raster.fill_with(rule, vertices, &clip, color, target))
                        .map_err(|e| match e {
                            FillError::Target(error) => RenderError::Target { offset, error },
                            FillError::Capacity { capacity } => RenderError::Capacity {
                                offset,
                                vertices: vertices.len(),
                                capacity,
                            },
                        })?;
                    stats.polygons += 1;
                    stats.spans += counts.spans;
                    stats.pixels += counts.pixels as u64;
                }
                Draw::Line {
                    from,
                    to,
                    clip,
                    color,
                } => {
                    let color = convert(color);
                    let counts = line::draw_line(from, to, &clip, color, target)
                        .map_err(|error| RenderError::Target { offset, error })?;
                    stats.spans += counts.spans;
                    stats.pixels += counts.pixels as u64;
                }
            }
            Ok(())
        })?;
        hook.stage(Stage::Painted);
        if let (Some(scene), Some(first)) = (built.as_mut(), layer) {
            draw_layer(scene, first, *resolve, target, &mut stats, hook)?;
        }
        Ok(stats)
    }
}

/// The workspace's check of the layer whose first command is at `first`,
/// as a render error.
fn visible_error(
    first: usize,
    e: VisibleError<core::convert::Infallible>,
) -> RenderError<core::convert::Infallible> {
    match e {
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
        VisibleError::Sink(e) => match e {},
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
fn draw_layer<T, H>(
    scene: &mut ListScene<'_>,
    first: usize,
    resolve: Resolve,
    target: &mut T,
    stats: &mut RenderStats,
    hook: &mut H,
) -> Result<(), RenderError<T::Error>>
where
    T: SpanTarget + ?Sized,
    T::Color: ListColor,
    H: Hook + ?Sized,
{
    let f = scene
        .draw_with(resolve, None, label::DEFAULT_FONT, target, hook)
        .map_err(|e| match e {
            VisibleError::Sink(error) => RenderError::Target {
                offset: first,
                error,
            },
            // Checked before drawing.
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
    stats.visible = f.visible;
    stats.spans += f.decoded.spans + f.labels.written.spans;
    stats.pixels += f.decoded.pixels as u64 + f.labels.written.pixels as u64;
    stats.labels = f.labels.drawn;
    Ok(())
}

/// Builds the 3D layer of `list` in `mem`, projected for the list's frame
/// and cut to `w × h`: one segment, every 3D command through the scene's
/// interpreter in list order, into `slot`.
#[inline(never)]
fn build_layer<'s, 't>(
    slot: &'s mut Option<ListScene<'t>>,
    (mem, vertices): (SceneMemory<'t>, &mut [ViewPoint]),
    list: &DisplayList<'_>,
    (w, h): (u16, u16),
    first: usize,
    stats: &mut RenderStats,
) -> Result<&'s mut ListScene<'t>, RenderError<core::convert::Infallible>> {
    let (pipeline, window) = layer_pipeline(list, first)?;
    // Made in the caller's slot, not returned: the scene (about a
    // kilobyte, most of it the pipeline) is then not copied again on its
    // way out.
    let scene =
        slot.insert(Scene::with_frame(mem, pipeline, w, h).map_err(|e| error_at(first, e))?);
    let mut st = ListState::new(list.width(), list.height());
    let mut b = scene.open(0).map_err(|e| error_at(first, e))?;
    let mut table = VertexTable::new(vertices);
    let mut cmds = list.commands();
    while let Some((offset, cmd)) = cmds.next() {
        if let (Some(e), true) = (window, is_scene_command(&cmd)) {
            return Err(error_at(offset, e));
        }
        if let Command::Segment(id) = cmd {
            st.enter_segment(crate::scene::list::attributes(list, id));
        }
        let executed = b
            .command_in(cmd, &mut st, &mut table)
            .map_err(|e| error_at(offset, e))?;
        let mesh = match executed {
            Executed::Vertex => {
                stats.vertices += 1;
                true
            }
            Executed::Poly3 { drawn: true } => {
                stats.poly3 += 1;
                false
            }
            Executed::Poly3 { drawn: false } => {
                stats.culled += 1;
                false
            }
            Executed::Face(o) => {
                match o {
                    Outcome::Culled => stats.culled += 1,
                    Outcome::Emitted => stats.faces += 1,
                    Outcome::ClippedAway => stats.clipped_away += 1,
                    Outcome::Empty => {}
                }
                matches!(cmd, Command::MeshFace(_))
            }
            Executed::State | Executed::Label { .. } => false,
        };
        // The `v`s and `f`s after a `v` or an `f`, in one loop.
        if mesh {
            mesh_run(&mut b, &mut cmds, (&st, &mut table), stats)?;
        }
    }
    stats.trapezoids = scene.store().counters().trapezoids;
    Ok(scene)
}

/// The `v`s and `f`s that come next in `cmds`, into the layer's segment
/// `b` in one loop ([`Builder::mesh_run`]), counted in `stats`.
#[inline(never)]
fn mesh_run(
    b: &mut Builder<'_, '_, LIST_STACK, LIST_VERTICES>,
    cmds: &mut Commands<'_>,
    (st, table): (&ListState, &mut VertexTable<'_>),
    stats: &mut RenderStats,
) -> Result<(), RenderError<core::convert::Infallible>> {
    let mut n = MeshCounts::default();
    let r = b.mesh_run(cmds, st, table, &mut n);
    stats.vertices += n.vertices;
    stats.faces += n.faces;
    stats.culled += n.culled;
    stats.clipped_away += n.clipped_away;
    r.map_err(|(offset, e)| error_at(offset, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::display_list::Writer;
    use crate::fixed::{Coord, Vertex, Vertex3};
    use crate::port::framebuffer::FrameBuffer;
    use crate::raster::edge::Edge;
    use crate::scene::SceneStorage;
    use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

    const W: u16 = 24;
    const H: u16 = 16;

    fn v(x: i16, y: i16, z: i16) -> Vertex3 {
        Vertex3 {
            x: Coord::from_bits(x * 16),
            y: Coord::from_bits(y * 16),
            z: Coord::from_bits(z * 16),
        }
    }

    /// 16 trapezoids, 4 faces, 1 segment, the rows, 16 edge slots, 8 active
    /// entries, the runs, 2 labels of 8 bytes.
    type Storage = SceneStorage<16, 4, 1, { H as usize }, 16, 8, { W as usize }, 2, 8>;

    struct Mem {
        edges: [Edge; 8],
        three: Storage,
    }

    impl Mem {
        fn new() -> Self {
            Mem {
                edges: [Edge::EMPTY; 8],
                three: Storage::new(),
            }
        }

        /// Renders `list` with 3D storage (`three`) or without into a
        /// `w × h` target; returns the frame as the colours' red channels,
        /// row by row.
        fn render_in(
            &mut self,
            list: &DisplayList<'_>,
            three: bool,
            (w, h): (u16, u16),
        ) -> (
            Result<RenderStats, RenderError<core::convert::Infallible>>,
            [u8; (W * H) as usize],
        ) {
            let mut px = [Rgb888::new(7, 7, 7); (W * H) as usize];
            let mut fb = FrameBuffer::new(&mut px[..(w * h) as usize], w, h).unwrap();
            let mut c = Controller::new(Rasterizer::new(&mut self.edges));
            if three {
                c = c
                    .with_3d(self.three.as_memory())
                    .with_resolve(Resolve::Bisect);
            }
            let r = c.render(list, &mut fb);
            (r, core::array::from_fn(|i| px[i].r()))
        }

        fn render(
            &mut self,
            list: &DisplayList<'_>,
            three: bool,
        ) -> (
            Result<RenderStats, RenderError<core::convert::Infallible>>,
            [u8; (W * H) as usize],
        ) {
            self.render_in(list, three, (W, H))
        }
    }

    fn list(bytes: &mut [u8], f: impl FnOnce(&mut Writer<'_>)) -> usize {
        let mut w = Writer::new(bytes, W, H).unwrap();
        f(&mut w);
        w.finish().len()
    }

    /// A list of three segments through `v`/`f` (`mesh`) or the same
    /// faces through `face`: segment 0 with faces of both windings, a
    /// colour change between its `f`s, a point; segment 1
    /// hidden; segment 2 highlighted.
    fn mesh_or_faces(bytes: &mut [u8], mesh: bool) -> usize {
        let p = |x: i16, y: i16| crate::geometry::Point3::from_int(x, y, -10);
        let segments: [(&[_], &[&[u16]]); 3] = [
            (
                &[p(-3, -3), p(3, -3), p(3, 3), p(-3, 3)],
                &[&[0, 1, 2], &[0, 2, 1], &[], &[0, 2, 3], &[1]],
            ),
            (&[p(-2, -2), p(2, -2), p(0, 2)], &[&[0, 1, 2]]),
            (&[p(-1, -4), p(1, -4), p(0, -2)], &[&[0, 1, 2]]),
        ];
        list(bytes, |w| {
            w.hide(1).unwrap();
            w.highlight(2, Some(Rgb888::BLUE)).unwrap();
            w.color(Rgb888::RED).unwrap();
            for (id, (points, faces)) in segments.iter().enumerate() {
                w.segment(id as u16).unwrap();
                if mesh {
                    points.iter().for_each(|&q| w.mesh_vertex(q).unwrap());
                }
                for f in faces.iter() {
                    match (f.is_empty(), mesh) {
                        (true, _) => w.color(Rgb888::GREEN).unwrap(),
                        (false, true) => w.mesh_face(f.iter().copied()).unwrap(),
                        (false, false) => {
                            w.face(f.iter().map(|&i| points[usize::from(i)])).unwrap()
                        }
                    }
                }
            }
        })
    }

    #[test]
    fn a_mesh_run_draws_and_counts_what_its_faces_do() {
        let render = |mesh: bool| {
            let mut bytes = [0u8; 1024];
            let n = mesh_or_faces(&mut bytes, mesh);
            let l = DisplayList::new_checked(&bytes[..n]).unwrap();
            let mut slots = [ViewPoint::EMPTY; 4];
            let mut m = Mem::new();
            let mut px = [Rgb888::new(7, 7, 7); (W * H) as usize];
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let r = Controller::new(Rasterizer::new(&mut m.edges))
                .with_3d(m.three.as_memory())
                .with_vertices(&mut slots)
                .render(&l, &mut fb)
                .unwrap();
            (r, px)
        };
        let (mesh, mesh_px) = render(true);
        let (faces, faces_px) = render(false);
        assert_eq!(mesh_px, faces_px);
        assert!(mesh_px.contains(&Rgb888::RED) && mesh_px.contains(&Rgb888::GREEN));
        assert!(mesh_px.contains(&Rgb888::BLUE), "the highlight");
        assert_eq!(mesh.vertices, 10);
        assert_eq!(
            (mesh.faces, mesh.culled, mesh.clipped_away),
            (faces.faces, faces.culled, faces.clipped_away)
        );
        assert_eq!((mesh.faces, mesh.culled), (4, 1), "the hidden face skipped");
    }

    /// A mesh run adds what became of its faces to the pipeline's
    /// counters as the faces one by one would have.
    #[test]
    fn a_mesh_run_counts_in_the_pipeline_as_one_by_one() {
        let mut bytes = [0u8; 1024];
        let n = mesh_or_faces(&mut bytes, true);
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let stats = |run: bool| {
            let mut m = Mem::new();
            let mut slots = [ViewPoint::EMPTY; 4];
            let (pipeline, _) = layer_pipeline(&l, 0).unwrap();
            let mut slot = None;
            let scene =
                slot.insert(Scene::with_frame(m.three.as_memory(), pipeline, W, H).unwrap());
            let mut st = ListState::new(l.width(), l.height());
            let mut b = scene.open(0).unwrap();
            let mut table = VertexTable::new(&mut slots);
            let mut cmds = l.commands();
            let mut runs = 0;
            while let Some((_, cmd)) = cmds.next() {
                if let Command::Segment(id) = cmd {
                    st.enter_segment(crate::scene::list::attributes(&l, id));
                }
                b.command_in(cmd, &mut st, &mut table).unwrap();
                if run && matches!(cmd, Command::MeshVertex(_) | Command::MeshFace(_)) {
                    let mut counts = MeshCounts::default();
                    b.mesh_run(&mut cmds, &st, &mut table, &mut counts).unwrap();
                    runs += (counts != MeshCounts::default()) as u32;
                }
            }
            (scene.pipeline().stats(), runs)
        };
        let ((run, runs), (one, _)) = (stats(true), stats(false));
        assert!(runs > 0);
        assert_eq!(run, one);
        assert!(one.emitted > 0 && one.culled > 0, "{one:?}");
    }

    #[test]
    fn a_full_vertex_table_inside_a_mesh_run_names_its_v() {
        let mut bytes = [0u8; 1024];
        let n = mesh_or_faces(&mut bytes, true);
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        for capacity in 0..4 {
            // The `v` past the table, inside the run its first `v` starts
            // (the first itself when the table has no slot).
            let offset = l
                .commands()
                .filter(|(_, c)| matches!(c, Command::MeshVertex(_)))
                .nth(capacity)
                .unwrap()
                .0;
            let mut slots = [ViewPoint::EMPTY; 4];
            let mut m = Mem::new();
            let mut px = [Rgb888::new(7, 7, 7); (W * H) as usize];
            let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
            let r = Controller::new(Rasterizer::new(&mut m.edges))
                .with_3d(m.three.as_memory())
                .with_vertices(&mut slots[..capacity])
                .render(&l, &mut fb);
            assert_eq!(
                r,
                Err(RenderError::Capacity3d {
                    offset,
                    resource: Resource::Vertices,
                    capacity,
                })
            );
        }
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
    fn poly3_on_a_frame_too_narrow_for_the_default_projection() {
        // One column: the default 60° perspective would have a focal
        // length below 1 px, but `poly3`s use no projection.
        let mut bytes = [0u8; 256];
        let mut w = Writer::new(&mut bytes, 1, H).unwrap();
        w.color(Rgb888::WHITE).unwrap();
        w.poly3([v(0, 1, 1), v(0, 9, 1), v(1, 5, 1)]).unwrap();
        let n = w.finish().len();
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let mut m = Mem::new();
        let (r, px) = m.render_in(&l, true, (1, H));
        assert_eq!(r.unwrap().poly3, 1);
        assert_eq!(px[5], 255, "the pixel at row 5 is the face's");
        // A scene command there reports the default projection's fault.
        let mut bytes = [0u8; 256];
        let mut w = Writer::new(&mut bytes, 1, H).unwrap();
        w.push().unwrap();
        let n = w.finish().len();
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let (r, _) = m.render_in(&l, true, (1, H));
        assert!(
            matches!(r, Err(RenderError::Scene { offset: 16, .. })),
            "{r:?}"
        );
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
        let need = needs(&l, &mut slots).unwrap();
        assert_eq!((need.poly3, need.faces, need.edge_slots), (5, 5, 3));
        assert_eq!((need.trapezoids, need.active, need.segments), (10, 10, 1));
        assert_eq!(
            (need.rows, need.runs, need.edges),
            (H as usize, W as usize, 0)
        );
    }

    use crate::geometry::{Point3, Q16};

    /// A square of side 2 at depth `z`, counter-clockwise seen from +z (y
    /// up), and the same with `reverse`.
    fn square(z: i16, reverse: bool) -> [Point3; 4] {
        let mut sq = [(-1, -1), (1, -1), (1, 1), (-1, 1)].map(|(x, y)| Point3::from_int(x, y, z));
        if reverse {
            sq.reverse();
        }
        sq
    }

    #[test]
    fn the_first_failing_command_is_named_with_its_own_reason() {
        // A `poly3` that needs more than the store holds after a `pop`
        // with nothing saved: the `pop` is named, as a transform error.
        let mut bytes = [0u8; 1024];
        let n = list(&mut bytes, |w| {
            w.poly3([v(1, 1, 1), v(1, 9, 1), v(9, 5, 1)]).unwrap();
            w.pop().unwrap();
            for k in 0..8 {
                w.poly3([v(k, 0, k), v(k, 16, k), v(k + 12, 8, k)]).unwrap();
            }
        });
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let offset_of = |l: &DisplayList<'_>, k: usize| l.commands().nth(k).unwrap().0;
        let pop_at = offset_of(&l, 1);
        let (r, px) = Mem::new().render(&l, true);
        assert_eq!(
            r,
            Err(RenderError::Scene {
                offset: pop_at,
                error: SceneError::Transform(crate::geometry::TransformError::StackUnderflow)
            })
        );
        assert!(px.iter().all(|&p| p == 7), "nothing drawn");
        let mut slots = [EdgeSlot::EMPTY; 3];
        assert_eq!(needs(&l, &mut slots).map(|_| ()), r.map(|_| ()));

        // A `scale` chain that leaves the range after a `poly3`: the
        // `scale` that does is named.
        let n = list(&mut bytes, |w| {
            w.poly3([v(1, 1, 1), v(1, 9, 1), v(9, 5, 1)]).unwrap();
            let big = Point3::from_int(1000, 1000, 1000);
            w.scale(big).unwrap();
            w.face(square(-5, false)).unwrap();
            w.scale(big).unwrap();
            w.face(square(-5, false)).unwrap();
        });
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let scale_at = offset_of(&l, 3);
        let (r, _) = Mem::new().render(&l, true);
        assert_eq!(
            r,
            Err(RenderError::Scene {
                offset: scale_at,
                error: SceneError::Transform(crate::geometry::TransformError::Range)
            })
        );
        let mut slots = [EdgeSlot::EMPTY; 16];
        assert_eq!(needs(&l, &mut slots).map(|_| ()), r.map(|_| ()));
    }

    #[test]
    fn the_default_camera_looks_along_minus_z_with_y_up() {
        let mut bytes = [0u8; 1024];
        for (z, drawn) in [(-5, true), (5, false)] {
            for reverse in [false, true] {
                let n = list(&mut bytes, |w| {
                    w.color(Rgb888::new(200, 0, 0)).unwrap();
                    w.face(square(z, reverse)).unwrap();
                    // y up: a point above the axis lands above the middle.
                    w.face([Point3::from_int(0, 3, -10)]).unwrap();
                });
                let l = DisplayList::new_checked(&bytes[..n]).unwrap();
                let (r, px) = Mem::new().render(&l, true);
                let s = r.unwrap();
                let hit = px[8 * W as usize + 12] == 200;
                assert_eq!(hit, drawn && !reverse, "z = {z}, reversed: {reverse}");
                assert_eq!(s.faces, 1 + (drawn && !reverse) as u32);
                // At y ≈ 8 − 6.2: above the square, which reaches y ≈ 4.
                let above = (0..4).any(|y| (9..15).any(|x| px[y * W as usize + x] == 200));
                assert!(above, "the point is above the middle");
            }
        }
    }

    #[test]
    fn a_target_smaller_than_the_frame_shows_its_top_left_part() {
        let mut bytes = [0u8; 1024];
        let n = list(&mut bytes, |w| {
            w.clear(Rgb888::new(1, 0, 0)).unwrap();
            w.color(Rgb888::new(90, 0, 0)).unwrap();
            w.poly3([v(2, 2, 3), v(4, 14, 3), v(22, 6, 9)]).unwrap();
            w.color(Rgb888::new(150, 0, 0)).unwrap();
            w.face(square(-4, false)).unwrap();
            w.perspective(
                crate::geometry::Angle::from_degrees(40),
                Q16::ONE,
                Q16::from_int(50),
            )
            .unwrap();
            w.color(Rgb888::new(250, 0, 0)).unwrap();
            w.face([Point3::from_int(-1, 1, -6)]).unwrap();
        });
        let l = DisplayList::new_checked(&bytes[..n]).unwrap();
        let (r, full) = Mem::new().render(&l, true);
        r.unwrap();
        for (tw, th) in [(12, 8), (24, 5), (7, 16)] {
            let (r, small) = Mem::new().render_in(&l, true, (tw, th));
            r.unwrap();
            let mut covered = 0;
            for y in 0..th as usize {
                for x in 0..tw as usize {
                    let f = full[y * W as usize + x];
                    assert_eq!(small[y * tw as usize + x], f, "({x}, {y}) of {tw}x{th}");
                    covered += (f > 1) as usize;
                }
            }
            assert!(covered > 0, "{tw}x{th}");
        }
    }

    #[test]
    fn the_summary_passes_a_list_exactly_when_the_walk_finds_no_fault() {
        // Random lists of polygons around every limit, against
        // controllers of every size: `check` (from the summary when it
        // fits) gives what the walk gives, and the summary never passes
        // a list the walk refuses.
        let mut rng = testkit::rng::Rng(0x5ca7_7e11);
        let mut bytes = [0u8; 8192];
        for _ in 0..3000 {
            let n = list(&mut bytes, |w| {
                for _ in 0..rng.range(1, 6) {
                    let k = rng.range(1, 61) as i16;
                    match rng.below(7) {
                        0 => w.poly((0..k.max(3)).map(|i| Vertex::from_bits(i, 2 * i))),
                        1 => w.poly3((0..k.max(3)).map(|i| v(i, 2 * i, 1))),
                        2 => w.face((0..k).map(|i| Point3::from_int(i, 1, -5))),
                        3 => w.color(Rgb888::new(1, 2, 3)),
                        4 => w.clear(Rgb888::new(4, 5, 6)),
                        5 => w.push(),
                        _ => w.line(Vertex::from_bits(0, 0), Vertex::from_bits(16, 16)),
                    }
                    .unwrap();
                }
            });
            let l = DisplayList::new_checked(&bytes[..n]).unwrap();
            let mut edges = [Edge::EMPTY; 12];
            let mut slots = [EdgeSlot::EMPTY; 72];
            let mut three = Storage::new();
            let cap = rng.range(3, 13) as usize;
            let mut c = Controller::new(Rasterizer::new(&mut edges[..cap]));
            if rng.below(4) > 0 {
                let mut mem = three.as_memory();
                mem.store.edges = &mut slots[..rng.range(0, 73) as usize];
                c = c.with_3d(mem);
            }
            let walked = c.fault(&l);
            assert_eq!(c.check(&l), walked);
            assert!(!c.fits(l.summary()) || walked.is_ok());
        }
    }

    #[test]
    fn needs_refuses_more_than_a_pool_can_address() {
        // Two star polygons of 1001 vertices whose edges cross each other
        // about half a million times, each cut into some 37,000
        // trapezoids: together more than 65535.
        const N: usize = 1001;
        let mut bytes = [0u8; 64 + 2 * (6 * N + 16)];
        let mut w = Writer::new(&mut bytes, 2048, 2048).unwrap();
        w.color(Rgb888::new(1, 2, 3)).unwrap();
        let star = (0..N).map(|k| {
            // A quarter turn is 2¹⁴; vertex k at angle k · 501/1001 turn,
            // counter-clockwise as displayed.
            let a = crate::geometry::Angle::from_bits(((k * 501 % N) * 65536 / N) as u16);
            let (s, c) = (
                crate::geometry::trig::sin(a) as i64,
                crate::geometry::trig::cos(a) as i64,
            );
            let px = |t: i64| Coord::from_bits((16 * 1024 + ((t * 1000 * 16) >> 16)) as i16);
            Vertex3 {
                x: px(c),
                y: px(s),
                z: Coord::from_bits(16),
            }
        });
        w.poly3(star.clone()).unwrap();
        w.poly3(star).unwrap();
        let l = DisplayList::new_checked(w.finish()).unwrap();
        let at = l.commands().nth(2).unwrap().0;
        let mut slots = [EdgeSlot::EMPTY; N];
        assert_eq!(edges_3d(&l), N);
        assert_eq!(
            needs(&l, &mut slots),
            Err(RenderError::Capacity3d {
                offset: at,
                resource: Resource::Trapezoids,
                capacity: POOL_LIMIT,
            })
        );
        // Too little scratch is refused too, at the widest polygon.
        assert_eq!(
            needs(&l, &mut slots[..3]),
            Err(RenderError::Capacity3d {
                offset: l.commands().nth(1).unwrap().0,
                resource: Resource::EdgeSlots,
                capacity: 3,
            })
        );
    }
}
