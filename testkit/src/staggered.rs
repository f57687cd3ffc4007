//! The worst case of the scan-line visible-surface sweep: staggered
//! overlapping faces, each nearer than the last.
//!
//! Face `k` of `n` is a right triangle parallel to the screen, its legs
//! 256 pixels long, up and left, moved right and down by `k · 12,272 / n` units (1/16 px) from
//! the last, at depth `19,000 − k` (nearer than every face before it), on
//! a 1024 × 1024 frame. On a row, up to a third of the faces overlap, and
//! every face that starts is in front of all those already there: a
//! sweep that keeps every face that started until it ends, or sorts
//! them by insertion, spends time quadratic in the faces on each row.
//!
//! [`Order::Reversed`] lists the same faces last to first (the picture is
//! the same, the faces enter each row in the opposite order);
//! [`Order::Farther`] puts each face behind the last instead, so that the
//! faces that start while one is in front are hidden until it ends.

use crate::reference3d::{drawn, Poly3};

/// Frame width of the scene.
pub const W: u16 = 1024;
/// Frame height of the scene.
pub const H: u16 = 1024;
/// Side of a face in pixels.
pub const SIDE: i32 = 256;
/// Most faces the depths (`19,000 − k` within `i16`) allow.
pub const MAX_FACES: usize = 51_000;

/// The order of the faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// Each face nearer than the last, listed first to last.
    Nearer,
    /// The faces of [`Order::Nearer`] listed last to first.
    Reversed,
    /// Each face farther than the last, listed first to last.
    Farther,
}

/// `n` staggered faces (at most [`MAX_FACES`]) in `order`.
pub fn staggered(n: usize, order: Order) -> Vec<Poly3> {
    assert!(n <= MAX_FACES, "{n} faces do not fit the depth range");
    let side = SIDE * 16;
    let span = W as i64 * 16 - side as i64 - 16;
    let mut faces: Vec<Poly3> = (0..n)
        .map(|k| {
            let o = (k as i64 * span / n.max(1) as i64) as i32;
            let z = match order {
                Order::Farther => k as i32 - 19_000,
                _ => 19_000 - k as i32,
            };
            let mut p = vec![(o, o, z), (o, o + side, z), (o + side, o, z)];
            if !drawn(&p) {
                p.reverse();
            }
            Poly3 {
                poly: p,
                clip: None,
            }
        })
        .collect();
    if order == Order::Reversed {
        faces.reverse();
    }
    faces
}
