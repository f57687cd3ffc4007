//! Shared helpers of the `host-tests` suites: the exact reference
//! rasterisers ([`reference`] for `poly`, [`reference3d`] for `poly3`,
//! [`line_reference`] for `line`) and
//! the harnesses that run scenes through the library's real path
//! ([`harness`], [`harness3d`]), and the measured `poly3` scenes
//! ([`scenes3d`]).

pub mod harness;
pub mod harness3d;
pub mod line_reference;
pub mod reference;
pub mod reference3d;
pub mod scenes3d;
