//! The host-only kit that `host_tests` and `bench` share, so that each
//! piece exists once:
//!
//! * [`reference`](mod@reference): the exact 2D reference, the pixel rule decided pixel
//!   by pixel in `i128` (no stepper, no active-edge list, no division),
//!   with the bitmap type the tests compare with.
//! * [`reference3d`]: the exact 3D reference: culling, coverage by the
//!   pixel rule, and the nearest plane at each pixel centre by exact
//!   barycentric depth, ties to the earlier polygon.
//! * [`line_reference`]: the exact line rule, pixel by pixel in `i128`.
//! * [`meshes`]: triangle meshes from about 100 to 20,000 triangles (an
//!   icosphere, a torus, a terrain, the Utah teapot).
//! * [`workloads`]: the 2D workloads W1–W5.
//! * [`scenes3d`]: the 3D scenes at several sizes, in a layered and a
//!   tilted version, seen from a few views (the benchmark's).
//! * [`poly3_scenes`]: the four 512 × 256 `poly3` scenes of about 170
//!   faces (`flat`, `tilted`, `bars`, `dense`) measured on the host and on
//!   target.
//! * [`staggered`]: the sweep's worst case, staggered overlapping faces
//!   each nearer than the last.
//! * [`winding_reference`]: the exact winding number of a pixel centre
//!   (signed crossings of the ray going right, decided by cross products
//!   in `i128`), and both fill rules decided from it.
//! * [`rng`]: the one random-number generator all of them draw from.
//!
//! Nothing here calls scanvert's rasteriser, stepper or visible-surface
//! code: only its vertex types are used, to hand scenes over.

#![deny(missing_docs)]

pub mod line_reference;
pub mod meshes;
pub mod poly3_scenes;
pub mod reference;
pub mod reference3d;
pub mod rng;
pub mod scenes3d;
pub mod staggered;
pub mod winding_reference;
pub mod workloads;
