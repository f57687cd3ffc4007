//! Shared helpers of the `host-tests` suites: the exact reference
//! rasterisers ([`reference`] for `poly`, [`reference3d`] for `poly3`) and
//! the harnesses that run scenes through the library's real path
//! ([`harness`], [`harness3d`]), and the measured `poly3` scenes
//! ([`scenes3d`]).

pub mod harness;
pub mod harness3d;
pub mod reference;
pub mod reference3d;
pub mod scenes3d;

/// The repository README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;
