//! Shared helpers of the `host-tests` suites: the exact reference
//! rasteriser ([`reference`]) and the harness that runs polygons through
//! the library's real path ([`harness`]).

pub mod harness;
pub mod reference;
