//! Stage 2 of the 2D path: polygons into spans.
//!
//! A polygon's edges are set up once ([`edge`]), stepped down the rows
//! by exact integer steppers and paired into spans by the polygon's
//! fill rule, even-odd ([`scan`]) or non-zero winding ([`winding`]); `line`s are stepped row by row ([`line`](mod@line)); every span is cut to the clip registers ([`clip`]) before it
//! leaves for the port. [`dda`] holds the faster, approximate steppers,
//! with their error measured.

pub mod clip;
pub mod dda;
pub mod draw;
pub mod edge;
pub mod line;
pub mod scan;
pub mod table;
pub mod winding;

pub use clip::{ClipRect, ClipWindow};
pub use draw::Draw;
pub use edge::{Edge, Stepper};
pub use scan::{FillError, Rasterizer};
pub use winding::FillRule;
