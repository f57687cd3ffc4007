//! Shared helpers of the `host-tests` suites: the harnesses that run
//! scenes through the library's real path ([`harness`] for `poly`,
//! [`harness3d`] for `poly3`). The exact references and the scene
//! generators they are checked against are in the `testkit` crate.

pub mod harness;
pub mod harness3d;

/// The repository README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;
