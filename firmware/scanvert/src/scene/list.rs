//! The one interpreter of a display list's 3D commands.
//!
//! `poly3` and the scene commands of version 2 are executed here, and
//! only here: by [`Builder::command`](super::Builder::command) into a
//! segment of a [`Scene`](super::Scene) (which is how
//! [`Controller`](crate::controller::Controller) renders a list's 3D
//! layer), and by [`controller::needs`](crate::controller::needs), which
//! runs the same commands into counters to size the memory.
//!
//! What a command does is documented with the
//! [controller](crate::controller#the-3d-scene-version-2); the state a
//! list carries besides the geometry stage's ([`Pipeline`]) is its colour,
//! its clip registers and its frame ([`ListState`]).

use crate::color::DEFAULT_COLOR;
use crate::display_list::{Axis, Command, Commands, DisplayList, Vertices3};
use crate::fixed::Vertex3;
use crate::geometry::{
    Angle, Light, Orthographic, Outcome, Perspective, Pipeline, PipelineError, Point3, PolygonSink,
    View, Viewport, Q16,
};
use crate::raster::clip::ClipRect;
use crate::visible::store::front_facing;
use embedded_graphics_core::pixelcolor::Rgb888;

use super::{label, Placement, SceneError, VertexTable};

/// What a list carries besides the geometry stage: the current colour,
/// the clip registers, and the list's frame (clip windows are cut to it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ListState {
    color: Rgb888,
    clip: ClipRect,
    width: u16,
    height: u16,
    /// The attributes of the segment being built ([`attributes`]).
    attributes: Attributes,
}

/// What a list says of one of its segments: `hide`/`show`, `highlight`
/// and `place`, the last of each naming it anywhere in the list.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Attributes {
    /// Hidden: its drawing commands are skipped.
    pub hidden: bool,
    /// Its faces, points, lines and `poly3`s are drawn in this colour,
    /// unlit.
    pub highlight: Option<Rgb888>,
    /// Its commands are built after these transforms.
    pub placement: Placement,
}

/// The attributes `list` gives segment `id` (see [`Attributes`]): the
/// whole list is one frame, so an attribute holds wherever it stands.
/// A list without attributes costs nothing
/// ([`Summary::attributes`](crate::display_list::Summary::attributes)),
/// one with them a walk of its commands.
pub fn attributes(list: &DisplayList<'_>, id: u16) -> Attributes {
    let mut a = Attributes::default();
    if !list.summary().attributes {
        return a;
    }
    for (_, cmd) in list.commands() {
        match cmd {
            Command::Hide(s) if s == id => a.hidden = true,
            Command::Show(s) if s == id => a.hidden = false,
            Command::Highlight(s, c) if s == id => a.highlight = c,
            Command::Place(p) if p.id() == id => a.placement = p.placement(),
            _ => {}
        }
    }
    a
}

impl ListState {
    /// The state at the start of a list of a `width × height` frame: the
    /// colour [`DEFAULT_COLOR`], the clip registers on the whole frame.
    pub fn new(width: u16, height: u16) -> Self {
        ListState {
            color: DEFAULT_COLOR,
            clip: ClipRect::full(width, height),
            width,
            height,
            attributes: Attributes::default(),
        }
    }

    /// Takes the attributes of the segment a `segment` command is about
    /// to start (from [`attributes`]): they hold up to the next one.
    pub fn enter_segment(&mut self, attributes: Attributes) {
        self.attributes = attributes;
    }

    /// The state at the start of a list of a `width × height` frame, the
    /// clip registers on `clip`.
    pub(crate) fn with_clip(width: u16, height: u16, clip: ClipRect) -> Self {
        ListState {
            clip,
            ..ListState::new(width, height)
        }
    }

    /// The current colour.
    pub fn color(&self) -> Rgb888 {
        self.color
    }

    /// `true` when the segment being built is hidden.
    pub(crate) fn hidden(&self) -> bool {
        self.attributes.hidden
    }

    /// The clip registers, cut to the frame.
    pub fn clip(&self) -> &ClipRect {
        &self.clip
    }
}

/// What one command did, for the counters of a render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Executed {
    /// A command that changes state (colour, clip, camera, projection,
    /// light, thickness, a transform, `segment`), or a 2D command, which
    /// the 3D layer leaves to the rasteriser.
    State,
    /// A `poly3`: drawn (counter-clockwise as displayed) or culled.
    Poly3 {
        /// `false`: culled.
        drawn: bool,
    },
    /// A `face` (a point or a line too): what became of it.
    Face(Outcome),
    /// A `v`: a vertex transformed into the table.
    Vertex,
    /// A `label`: placed, or not (behind the eye, or too far off).
    Label {
        /// `false`: not placed.
        placed: bool,
    },
}

/// Where the interpreter puts what it makes: a segment of a scene, or
/// counters.
pub(crate) trait Out {
    /// A polygon of the layer in screen space, `clip` applied; the one a
    /// point or a line became when `point_or_line` is set.
    fn polygon<I: IntoIterator<Item = Vertex3>>(
        &mut self,
        vertices: I,
        color: Rgb888,
        clip: &ClipRect,
        point_or_line: bool,
    ) -> Result<(), SceneError>;
    /// A triangle, as [`polygon`](Out::polygon) takes it (not a point or
    /// a line).
    fn triangle(
        &mut self,
        v: [Vertex3; 3],
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<(), SceneError> {
        self.polygon(v, color, clip, false)
    }
    /// A `poly3`: its vertices as [`polygon`](Out::polygon) when they are
    /// front-facing ([`front_facing`]); `Ok(false)`, nothing done, when
    /// they are not.
    fn poly3(
        &mut self,
        vertices: &Vertices3<'_>,
        color: Rgb888,
        clip: &ClipRect,
    ) -> Result<bool, SceneError> {
        let drawn = front_facing(vertices);
        if drawn {
            self.polygon(vertices.iter(), color, clip, false)?;
        }
        Ok(drawn)
    }
    /// A label at whole pixels `at`.
    fn label(&mut self, at: (i32, i32), color: Rgb888, text: &str) -> Result<bool, SceneError>;
    /// The camera, projection, light or thickness changed.
    fn changed(&mut self);
}

/// The geometry stage's polygons into an [`Out`], under one clip.
struct Faces<'o, O> {
    out: &'o mut O,
    clip: ClipRect,
    /// A highlight's colour, drawn instead of the lit one.
    highlight: Option<Rgb888>,
}

impl<O: Out> PolygonSink for Faces<'_, O> {
    type Error = SceneError;
    fn polygon(&mut self, v: &[Vertex3], color: Rgb888, two: bool) -> Result<(), SceneError> {
        let color = self.highlight.unwrap_or(color);
        if let (false, &[a, b, c]) = (two, v) {
            return self.out.triangle([a, b, c], color, &self.clip);
        }
        self.out.polygon(v.iter().copied(), color, &self.clip, two)
    }
}

/// The geometry stage a list starts with, for a `width × height` frame:
/// perspective with a 60° horizontal field of view, near 1, far 1000; the
/// window the frame, the view axis through its middle; the eye at the
/// origin with yaw and pitch 0, looking along −z with y up (the world of
/// [`View`]); ambient light only; points and lines 1 px thick.
///
/// Fails when the frame is wider or taller than a window may be
/// ([`Viewport`]: 2047 px a side).
pub fn list_pipeline<const DEPTH: usize, const N: usize>(
    width: u16,
    height: u16,
) -> Result<Pipeline<DEPTH, N>, SceneError> {
    let window = Viewport::centred(width, height)?;
    let q = Q16::from_int;
    let persp = Perspective::from_fov(Angle::from_degrees(60), width, q(1), q(1000))?;
    let mut pipe = Pipeline::new(persp, window);
    pipe.set_view(&View {
        eye: Point3::ORIGIN,
        yaw: Angle::ZERO,
        pitch: Angle::ZERO,
    })?;
    Ok(pipe)
}

/// Executes one command of a list into `out`. 2D commands (`clear`, `fill`,
/// `line`, `poly`) are left alone; `color` and `clip` change `st`, as they do for
/// the rasteriser.
pub(crate) fn execute<const DEPTH: usize, const N: usize, O: Out>(
    pipe: &mut Pipeline<DEPTH, N>,
    out: &mut O,
    st: &mut ListState,
    table: &mut VertexTable<'_>,
    cmd: Command<'_>,
) -> Result<Executed, SceneError> {
    let (w, h) = (st.width, st.height);
    // Not the whole `Attributes`: copied for every command, its placement
    // costs the cut stage on the Cortex-M4.
    let (hidden, highlight) = (st.attributes.hidden, st.attributes.highlight);
    if hidden
        && matches!(
            cmd,
            Command::Face(_) | Command::MeshFace(_) | Command::Poly3(_) | Command::Label { .. }
        )
    {
        return Ok(Executed::State);
    }
    match cmd {
        Command::Clear(_) | Command::Fill(_) | Command::Poly(_) | Command::Line(..) => {}
        Command::Color(c) => st.color = c,
        Command::Clip(win) => st.clip = ClipRect::from_window(win, w, h),
        Command::Poly3(v) => {
            let drawn = out.poly3(&v, highlight.unwrap_or(st.color), &st.clip)?;
            return Ok(Executed::Poly3 { drawn });
        }
        Command::Segment(_) => {
            pipe.reset_stack();
            table.clear();
            st.attributes.placement.apply(pipe.stack_mut())?;
        }
        // Taken by `attributes` when a `segment` starts.
        Command::Hide(_) | Command::Show(_) | Command::Highlight(..) | Command::Place(..) => {}
        Command::MeshVertex(p) => {
            table.push(pipe.view_point(p))?;
            return Ok(Executed::Vertex);
        }
        Command::MeshFace(indices) => {
            let indices = indices.iter().map(usize::from);
            return Ok(Executed::Face(mesh_face(
                pipe, out, table, indices, st.color, st.clip, highlight,
            )?));
        }
        Command::Perspective { fov, near, far } => {
            pipe.set_projection(Perspective::from_fov(fov, w, near, far)?);
            out.changed();
        }
        Command::Ortho { scale, near, far } => {
            pipe.set_projection(Orthographic::new(scale, near, far)?);
            out.changed();
        }
        Command::View { eye, yaw, pitch } => {
            pipe.set_view(&View { eye, yaw, pitch })?;
            out.changed();
        }
        Command::Light { toward, percent } => {
            pipe.set_light(Light::new(toward.to_bits(), percent)?);
            out.changed();
        }
        Command::Thickness(t) => {
            pipe.set_thickness(t);
            out.changed();
        }
        Command::Push => pipe.stack_mut().push()?,
        Command::Pop => pipe.stack_mut().pop()?,
        Command::Translate(t) => pipe.stack_mut().translate(t.x, t.y, t.z)?,
        Command::Rotate(axis, a) => {
            let s = pipe.stack_mut();
            match axis {
                Axis::X => s.rotate_x(a),
                Axis::Y => s.rotate_y(a),
                Axis::Z => s.rotate_z(a),
            }?
        }
        Command::Scale(f) => pipe.stack_mut().scale(f.x, f.y, f.z)?,
        Command::Face(points) => {
            return Ok(Executed::Face(face(
                pipe,
                out,
                points.iter(),
                st.color,
                st.clip,
                highlight,
            )?));
        }
        Command::Label { at, text } => {
            return Ok(Executed::Label {
                placed: place_label(pipe, out, at, text, st.color)?,
            })
        }
    }
    Ok(Executed::State)
}

/// What a run of `v`s and `f`s did ([`mesh_run`]), for the counters of
/// a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[doc(hidden)]
pub struct MeshCounts {
    /// `v`s: vertices transformed into the table.
    pub vertices: u32,
    /// `f`s emitted ([`Outcome::Emitted`]).
    pub faces: u32,
    /// `f`s culled.
    pub culled: u32,
    /// `f`s clipped away.
    pub clipped_away: u32,
}

/// The `v`s and `f`s that come next in `cmds`, executed as [`execute`]
/// does, in one loop that reads nothing but them
/// ([`Commands::next_mesh`]); it stops before any other command, which
/// the caller takes. `st` is not changed by a `v` or an `f`. The error
/// names the offset of the command that failed.
pub(crate) fn mesh_run<const DEPTH: usize, const N: usize, O: Out>(
    pipe: &mut Pipeline<DEPTH, N>,
    out: &mut O,
    st: &ListState,
    table: &mut VertexTable<'_>,
    cmds: &mut Commands<'_>,
    counts: &mut MeshCounts,
) -> Result<(), (usize, SceneError)> {
    let (color, clip, highlight) = (st.color, st.clip, st.attributes.highlight);
    // One sink for the run's triangles, made once: each call hands it on
    // by one pointer.
    let mut sink = Faces {
        out,
        clip,
        highlight,
    };
    // The run's triangles are counted here only (the pipeline counts
    // the other faces itself): what became of them is added to the
    // pipeline's counters once, at the end, as the difference of
    // `counts` less the other faces'.
    let before = *counts;
    let mut general = MeshCounts::default();
    // Nothing in a run changes the projection or the window.
    table.sync(pipe);
    let r = loop {
        let Some((offset, cmd)) = cmds.next_mesh() else {
            break Ok(());
        };
        match cmd {
            Command::MeshVertex(p) => {
                if let Err(e) = table.push(pipe.view_point(p)) {
                    break Err((offset, e));
                }
                counts.vertices += 1;
            }
            Command::MeshFace(ix) => {
                let outcome = match ix.triangle() {
                    Some(t) => {
                        let corners = t.map(usize::from);
                        mesh_triangle(pipe, &mut sink, table, corners, color)
                    }
                    None => {
                        let indices = ix.iter().map(usize::from);
                        let r = mesh_face(pipe, sink.out, table, indices, color, clip, highlight);
                        match r {
                            Ok(Outcome::Emitted) => general.faces += 1,
                            Ok(Outcome::Culled) => general.culled += 1,
                            Ok(Outcome::ClippedAway) => general.clipped_away += 1,
                            _ => {}
                        }
                        r
                    }
                };
                match outcome {
                    Ok(Outcome::Emitted) => counts.faces += 1,
                    Ok(Outcome::Culled) => counts.culled += 1,
                    Ok(Outcome::ClippedAway) => counts.clipped_away += 1,
                    Ok(Outcome::Empty) => {}
                    Err(e) => break Err((offset, e)),
                }
            }
            _ => {}
        }
    };
    let added = |now: u32, was: u32, other: u32| now.wrapping_sub(was).wrapping_sub(other);
    pipe.add_counts(
        added(counts.faces, before.faces, general.faces),
        added(counts.culled, before.culled, general.culled),
        added(
            counts.clipped_away,
            before.clipped_away,
            general.clipped_away,
        ),
        0,
    );
    r
}

/// A polygon of model points through the geometry stage into `out`. Out
/// of line, so that a list's `poly3`s are executed without the geometry
/// stage's buffers in the frame, which makes the cut stage cheaper on the
/// Cortex-M4.
#[inline(never)]
pub(crate) fn face<const DEPTH: usize, const N: usize, O: Out>(
    pipe: &mut Pipeline<DEPTH, N>,
    out: &mut O,
    points: impl ExactSizeIterator<Item = Point3>,
    color: Rgb888,
    clip: ClipRect,
    highlight: Option<Rgb888>,
) -> Result<Outcome, SceneError> {
    let mut sink = Faces {
        out,
        clip,
        highlight,
    };
    pipe.polygon_from(points, color, &mut sink)
        .map_err(pipeline_error)
}

/// A face through vertices of `table` into `out`: the stages of
/// [`face`] after the transform, from the view-space points the `v`s
/// stored. Out of line for the reason `face` is.
#[inline(never)]
pub(crate) fn mesh_face<const DEPTH: usize, const N: usize, O: Out>(
    pipe: &mut Pipeline<DEPTH, N>,
    out: &mut O,
    table: &mut VertexTable<'_>,
    indices: impl ExactSizeIterator<Item = usize> + Clone,
    color: Rgb888,
    clip: ClipRect,
    highlight: Option<Rgb888>,
) -> Result<Outcome, SceneError> {
    let mut sink = Faces {
        out,
        clip,
        highlight,
    };
    if indices.len() == 3 {
        let mut corners = [0; 3];
        for (c, i) in corners.iter_mut().zip(indices) {
            *c = i;
        }
        table.sync(pipe);
        let r = mesh_triangle(pipe, &mut sink, table, corners, color);
        if let Ok(o) = r {
            let is = |k: Outcome| (o == k) as u32;
            pipe.add_counts(
                is(Outcome::Emitted),
                is(Outcome::Culled),
                is(Outcome::ClippedAway),
                0,
            );
        }
        return r;
    }
    table.check(indices.clone())?;
    let points = indices.map(|i| table.get(i).and_then(|v| v.raw()));
    pipe.polygon_view(points, color, &mut sink)
        .map_err(pipeline_error)
}

/// A triangle through vertices `corners` (0-based) of `table` into
/// `sink`, as [`mesh_face`] draws it; the table synced with the
/// pipeline's projection and window before ([`VertexTable::sync`]: once
/// a run of them, [`mesh_run`]). Its indices are checked at once by
/// their largest, and one by one only when that is bad, so that the
/// error names the first bad one; its corners' output vertices are kept
/// in the table for the faces after it. Out of line for the reason
/// `face` is. Of `pipe`'s counters, only a triangle the pipeline refuses
/// is counted: the caller adds what became of the others ([`mesh_run`]
/// once a run).
#[inline(never)]
fn mesh_triangle<const DEPTH: usize, const N: usize, O: Out>(
    pipe: &mut Pipeline<DEPTH, N>,
    sink: &mut Faces<'_, O>,
    table: &mut VertexTable<'_>,
    corners: [usize; 3],
    color: Rgb888,
) -> Result<Outcome, SceneError> {
    let slots = table.synced();
    if corners[0].max(corners[1]).max(corners[2]) >= slots.len() {
        for &c in &corners {
            table.checked(c)?;
        }
    }
    let slots = table.synced();
    let r = pipe.mesh_triangle_uncounted(slots, corners, color, sink);
    if r.is_err() {
        pipe.add_counts(0, 0, 0, 1);
    }
    r.map_err(pipeline_error)
}

fn pipeline_error(e: PipelineError<SceneError>) -> SceneError {
    match e {
        PipelineError::Range => SceneError::Range,
        PipelineError::Capacity { capacity } => SceneError::Vertices { capacity },
        PipelineError::Sink(e) => e,
    }
}

/// A label at the model point `at` into `out`: `Ok(false)` when the point
/// lies before the near plane (the text is checked all the same, so that
/// a bad text fails whatever the view) or too far off to show.
pub(crate) fn place_label<const DEPTH: usize, const N: usize, O: Out>(
    pipe: &Pipeline<DEPTH, N>,
    out: &mut O,
    at: Point3,
    text: &str,
    color: Rgb888,
) -> Result<bool, SceneError> {
    let a = pipe.project_point(at)?;
    if !a.in_front {
        return label::check_text(text).map(|_| false).map_err(Into::into);
    }
    out.label(label::to_pixels(a), color, text)
}
