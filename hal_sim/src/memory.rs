//! The graphic controller's memory for one display list, on the heap,
//! sized by what the list needs ([`scanvert::controller::needs`]).

use scanvert::controller::{edges_3d, needs, Controller, Needs, RenderError};
use scanvert::display_list::DisplayList;
use scanvert::raster::edge::Edge;
use scanvert::raster::line::Line;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::{needs_table, TableMemory, TablePolygon};
use scanvert::scene::label::Label;
use scanvert::scene::SceneMemory;
use scanvert::visible::rle::Run;
use scanvert::visible::store::{Face, Segment, StoreMemory};
use scanvert::visible::sweep::Active;
use scanvert::visible::trapezoid::{EdgeSlot, Trapezoid};

/// Edge storage for the rasteriser and the 3D layer's memory, each pool
/// as large as the list needs and no larger: a list that would need more
/// than a pool can address is refused before anything is allocated.
#[derive(Debug)]
pub struct ListMemory {
    need: Needs,
    edges: Vec<Edge>,
    trapezoids: Vec<Trapezoid>,
    faces: Vec<Face>,
    segments: Vec<Segment>,
    rows: Vec<u16>,
    slots: Vec<EdgeSlot>,
    active: Vec<Active>,
    runs: Vec<Run>,
    labels: Vec<Label>,
    text: Vec<u8>,
    table_polygons: Vec<TablePolygon>,
    table_index: Vec<u32>,
    table_edges: Vec<Edge>,
    table_lines: Vec<Option<Line>>,
}

impl ListMemory {
    /// The memory `list` needs. Fails, naming the command, when its 3D
    /// layer needs more than a pool can address or a 3D command fails
    /// (as rendering would).
    pub fn for_list(
        list: &DisplayList<'_>,
    ) -> Result<ListMemory, RenderError<core::convert::Infallible>> {
        let mut slots = vec![EdgeSlot::EMPTY; edges_3d(list)];
        let need = needs(list, &mut slots)?;
        Ok(ListMemory {
            need,
            edges: vec![Edge::EMPTY; need.edges],
            trapezoids: vec![Trapezoid::EMPTY; need.trapezoids],
            faces: vec![Face::EMPTY; need.faces],
            segments: vec![Segment::EMPTY; need.segments],
            rows: vec![0; need.rows],
            slots,
            active: vec![Active::EMPTY; need.active],
            runs: vec![Run::EMPTY; need.runs],
            labels: vec![Label::EMPTY; need.labels],
            text: vec![0; need.text],
            table_polygons: Vec::new(),
            table_index: Vec::new(),
            table_edges: Vec::new(),
            table_lines: Vec::new(),
        })
    }

    /// [`for_list`](Self::for_list) with an edge table for the band path
    /// ([`Controller::bands`]): as [`needs_table`] counts it, for the
    /// `poly`s and `line`s after the last `clear`.
    pub fn for_bands(
        list: &DisplayList<'_>,
    ) -> Result<ListMemory, RenderError<core::convert::Infallible>> {
        let mut m = Self::for_list(list)?;
        let t = needs_table(list);
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
        let (edges, three, table) = self.parts();
        let c = Controller::new(Rasterizer::new(edges));
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
        let (edges, three, _) = self.parts();
        let c = Controller::new(Rasterizer::new(edges));
        if any {
            c.with_3d(three)
        } else {
            c
        }
    }

    /// The rasteriser's edges, the 3D layer's memory and the edge
    /// table's.
    fn parts(&mut self) -> (&mut [Edge], SceneMemory<'_>, TableMemory<'_>) {
        let three = SceneMemory {
            store: StoreMemory {
                trapezoids: &mut self.trapezoids,
                faces: &mut self.faces,
                segments: &mut self.segments,
                rows: &mut self.rows,
                edges: &mut self.slots,
            },
            active: &mut self.active,
            runs: &mut self.runs,
            labels: &mut self.labels,
            text: &mut self.text,
        };
        let table = TableMemory {
            polygons: &mut self.table_polygons,
            index: &mut self.table_index,
            edges: &mut self.table_edges,
            lines: &mut self.table_lines,
        };
        (&mut self.edges, three, table)
    }
}
