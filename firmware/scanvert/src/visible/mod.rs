//! Stages 3 to 5 of the 3D path: screen-space polygons into run-length
//! rows, with no z-buffer.
//!
//! | stage | module | what happens |
//! |---|---|---|
//! | cut | [`trapezoid`] | a polygon into trapezoids with horizontal parallel sides, with its exact plane |
//! | store | [`store`] | trapezoids and faces by segment, in caller-owned pools, indexed by top row |
//! | resolve | [`sweep`] | active trapezoids per row, spans classified and resolved by depth |
//! | encode, decode | [`rle`] | one run-length scan line per row, and its decoder into the port |

pub mod rle;
pub mod store;
pub mod sweep;
pub mod trapezoid;

#[doc(hidden)]
pub use rle::RunWriter;
pub use rle::{Run, RunsFull};
pub use store::{Face, Segment, StoreError, StoreMemory, TrapezoidStore};
#[doc(hidden)]
pub use sweep::{draw, Sweep};
pub use sweep::{Active, Resolve, VisibleError, VisibleStats, Workspace, PAINT_FROM};
pub use trapezoid::{EdgeSlot, Trapezoid};
