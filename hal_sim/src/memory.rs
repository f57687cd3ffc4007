//! Memory on the heap, sized by what it holds: the graphic controller's
//! for one display list, by what the list needs
//! ([`scanvert::controller::needs`]), and a program's scene's, by running
//! it ([`SceneHeap::fit`]).

use scanvert::controller::{edges_3d, needs_with, Controller, Needs, RenderError};
use scanvert::display_list::DisplayList;
use scanvert::geometry::ViewPoint;
use scanvert::raster::edge::Edge;
use scanvert::raster::line::Line;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::scene::label::{Label, LabelError};
use scanvert::scene::{Capacities, SceneError, SceneMemory, UpdateError};
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment, StoreError, StoreMemory};
use scanvert::visible::sweep::Active;
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};
use scanvert::visible::VisibleError;
use std::convert::Infallible;

/// Edge storage for the rasteriser and the 3D layer's memory, each pool
/// as large as the list needs and no larger: a list that would need more
/// than a pool can address is refused before anything is allocated.
#[derive(Debug)]
pub struct ListMemory {
    need: Needs,
    edges: Vec<Edge>,
    three: SceneHeap,
    table_polygons: Vec<TablePolygon>,
    table_index: Vec<u32>,
    table_edges: Vec<Edge>,
    table_lines: Vec<Option<Line>>,
    vertices: Vec<ViewPoint>,
}

impl ListMemory {
    /// The memory `list` needs. Fails, naming the command, when its 3D
    /// layer needs more than a pool can address or a 3D command fails
    /// (as rendering would).
    pub fn for_list(
        list: &DisplayList<'_>,
    ) -> Result<ListMemory, RenderError<core::convert::Infallible>> {
        let slots = edges_3d(list);
        let mut vertices = vec![ViewPoint::EMPTY; list.summary().vertices];
        let need = needs_with(list, &mut vec![EdgeSlot::EMPTY; slots], &mut vertices)?;
        Ok(ListMemory {
            need,
            edges: vec![Edge::EMPTY; need.edges],
            three: SceneHeap::new(Capacities {
                trapezoids: need.trapezoids,
                faces: need.faces,
                segments: need.segments,
                rows: need.rows,
                edges: slots,
                active: need.active,
                runs: need.runs,
                labels: need.labels,
                text: need.text,
            }),
            table_polygons: Vec::new(),
            table_index: Vec::new(),
            table_edges: Vec::new(),
            table_lines: Vec::new(),
            vertices,
        })
    }

    /// [`for_list`](Self::for_list) with an edge table for the band path
    /// ([`Controller::bands`]): as [`DisplayList::table_needs`] counts it, for the
    /// `poly`s and `line`s after the last `clear`.
    pub fn for_bands(
        list: &DisplayList<'_>,
    ) -> Result<ListMemory, RenderError<core::convert::Infallible>> {
        let mut m = Self::for_list(list)?;
        let t = list.table_needs();
        m.table_polygons = vec![TablePolygon::EMPTY; t.polygons];
        m.table_index = vec![0; 2 * t.polygons];
        m.table_edges = vec![Edge::EMPTY; t.edges];
        m.table_lines = vec![None; t.lines];
        Ok(m)
    }

    /// A controller over this memory, as [`controller`](Self::controller),
    /// and the edge table's memory (empty unless made by
    /// [`for_bands`](Self::for_bands)).
    pub fn band_parts(&mut self) -> (Controller<'_>, TableMemory<'_>) {
        let any = self.need.any();
        let (edges, three, table, vertices) = self.parts();
        let c = Controller::new(Rasterizer::new(edges)).with_vertices(vertices);
        (if any { c.with_3d(three) } else { c }, table)
    }

    /// What the list needs.
    pub fn needs(&self) -> &Needs {
        &self.need
    }

    /// The 3D layer's memory.
    pub fn memory_3d(&mut self) -> SceneMemory<'_> {
        self.parts().1
    }

    /// A controller over this memory: with the 3D layer's when the list
    /// has one.
    pub fn controller(&mut self) -> Controller<'_> {
        let any = self.need.any();
        let (edges, three, _, vertices) = self.parts();
        let c = Controller::new(Rasterizer::new(edges)).with_vertices(vertices);
        if any {
            c.with_3d(three)
        } else {
            c
        }
    }

    /// The rasteriser's edges, the 3D layer's memory, the edge table's
    /// and the mesh vertex table.
    fn parts(
        &mut self,
    ) -> (
        &mut [Edge],
        SceneMemory<'_>,
        TableMemory<'_>,
        &mut [ViewPoint],
    ) {
        let three = self.three.memory();
        let table = TableMemory {
            polygons: &mut self.table_polygons,
            index: &mut self.table_index,
            edges: &mut self.table_edges,
            lines: &mut self.table_lines,
        };
        (&mut self.edges, three, table, &mut self.vertices)
    }
}

/// A [`Scene`](scanvert::scene::Scene)'s memory on the heap, each pool as
/// large as [`Capacities`] say: those a program's scene needs are found
/// with [`SceneHeap::fit`], by running it.
///
/// The same capacities, as const generics of
/// [`SceneStorage`](scanvert::scene::SceneStorage), size the scene's
/// `static` on a target with no heap.
#[derive(Debug)]
pub struct SceneHeap {
    caps: Capacities,
    trapezoids: Vec<Trapezoid>,
    faces: Vec<Face>,
    segments: Vec<Segment>,
    rows: Vec<u16>,
    edges: Vec<EdgeSlot>,
    active: Vec<Active>,
    runs: Vec<Run>,
    labels: Vec<Label>,
    text: Vec<u8>,
}

/// Why a scene could not be built or checked in a [`SceneHeap`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shortfall {
    /// Building failed (a pool ran out, or anything else).
    Scene(SceneError),
    /// The active list is shorter than the most trapezoids on one row.
    Visible(VisibleError<Infallible>),
}

impl From<SceneError> for Shortfall {
    fn from(e: SceneError) -> Self {
        Shortfall::Scene(e)
    }
}

impl From<UpdateError> for Shortfall {
    fn from(e: UpdateError) -> Self {
        Shortfall::Scene(e.error)
    }
}

impl From<VisibleError<Infallible>> for Shortfall {
    fn from(e: VisibleError<Infallible>) -> Self {
        Shortfall::Visible(e)
    }
}

impl std::fmt::Display for Shortfall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Shortfall::Scene(e) => write!(f, "{e}"),
            Shortfall::Visible(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for Shortfall {}

impl SceneHeap {
    /// Memory of these capacities, every slot unused.
    pub fn new(caps: Capacities) -> SceneHeap {
        SceneHeap {
            caps,
            trapezoids: vec![Trapezoid::EMPTY; caps.trapezoids],
            faces: vec![Face::EMPTY; caps.faces],
            segments: vec![Segment::EMPTY; caps.segments],
            rows: vec![0; caps.rows],
            edges: vec![EdgeSlot::EMPTY; caps.edges],
            active: vec![Active::EMPTY; caps.active],
            runs: vec![Run::EMPTY; caps.runs],
            labels: vec![Label::EMPTY; caps.labels],
            text: vec![0; caps.text],
        }
    }

    /// The capacities it was made with.
    pub fn capacities(&self) -> Capacities {
        self.caps
    }

    /// The memory as the scene takes it.
    pub fn memory(&mut self) -> SceneMemory<'_> {
        SceneMemory {
            store: StoreMemory {
                trapezoids: &mut self.trapezoids,
                faces: &mut self.faces,
                segments: &mut self.segments,
                rows: &mut self.rows,
                edges: &mut self.edges,
            },
            active: &mut self.active,
            runs: &mut self.runs,
            labels: &mut self.labels,
            text: &mut self.text,
        }
    }

    /// The capacities a program's scene needs: `run` builds the scene in
    /// the memory it is given, frame after frame as the program does, and
    /// returns the [`Capacities::max`] of
    /// [`Scene::needed`](scanvert::scene::Scene::needed) over its frames
    /// (the library's planning: the most each pool held at once, so
    /// enough for every moment of the run). `start` gives the frame's rows
    /// and width, the segments and the edge slots (the pipeline's `N`),
    /// and the first size of the pools; whenever a pool runs out
    /// (trapezoids, faces, labels, text, active slots) it is doubled and
    /// `run` starts again from nothing. Any other failure, or a pool past
    /// 65,535, is returned.
    pub fn fit(
        start: Capacities,
        mut run: impl FnMut(SceneMemory<'_>) -> Result<Capacities, Shortfall>,
    ) -> Result<Capacities, Shortfall> {
        let mut caps = start;
        loop {
            let mut heap = SceneHeap::new(caps);
            let e = match run(heap.memory()) {
                Ok(needed) => return Ok(needed),
                Err(e) => e,
            };
            let pool = match e {
                Shortfall::Scene(SceneError::Store(StoreError::Trapezoids { .. })) => {
                    &mut caps.trapezoids
                }
                Shortfall::Scene(SceneError::Store(StoreError::Faces { .. })) => &mut caps.faces,
                Shortfall::Scene(SceneError::Labels(LabelError::Labels { .. })) => &mut caps.labels,
                Shortfall::Scene(SceneError::Labels(LabelError::Text { .. })) => &mut caps.text,
                Shortfall::Visible(VisibleError::Active { .. }) => &mut caps.active,
                _ => return Err(e),
            };
            if *pool >= u16::MAX as usize {
                return Err(e);
            }
            *pool = (*pool * 2).clamp(8, u16::MAX as usize);
        }
    }
}
