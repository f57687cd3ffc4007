//! The fill rule, and the pairing of a row's crossings by the non-zero
//! winding rule.
//!
//! A polygon is filled by one of two rules ([`FillRule`]), chosen per
//! polygon. Even-odd covers a pixel whose centre has an odd number of
//! crossings at or left of it; non-zero covers a pixel whose centre has a
//! non-zero winding number: the sum, over the edges crossing its row at or
//! left of it, of +1 for an edge running down the rows (its second vertex
//! below its first, in the polygon's order) and −1 for one running up.
//! Both count the same crossings (the half-open rule of
//! [`edge`](super::edge)); only what a count means differs.
//!
//! The scan converter's walk is chosen once per polygon, by a const
//! parameter: by the non-zero rule, every row goes through its general
//! loop, where each edge's pixel is loaded with the edge's direction
//! beside it ([`Stepper::load_wound`]: `2·c + u`, `u` 1 for an edge
//! running up), sorted, and paired by `emit_nonzero`. The direction
//! rides in the pixel's slot, so an edge stays the size it is and the
//! even-odd walk, its two-edge runs included, is compiled as without it.
//!
//! The winding sum is taken over the crossings sorted by pixel: a pixel
//! `i` is covered when the sum over the crossings with pixel `≤ i` is not
//! zero, which only depends on the integers, as the even-odd count does.
//! Crossings with equal pixels may come in any order.

use crate::port::{Counts, SpanTarget};
use crate::raster::edge::Stepper;
use crate::raster::scan::emit_span;

/// Which pixels a polygon covers: those whose centre has an odd number of
/// crossings at or left of it ([`EvenOdd`](FillRule::EvenOdd), the
/// default), or a non-zero winding number ([`NonZero`](FillRule::NonZero)).
///
/// A polygon that does not cross itself covers the same pixels by both;
/// they differ where a self-intersecting polygon winds around a pixel
/// twice or more in one direction (the middle of a five-pointed star
/// drawn in one stroke is empty by even-odd, filled by non-zero).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FillRule {
    /// An odd number of crossings at or left of the pixel's centre.
    #[default]
    EvenOdd,
    /// A non-zero winding number at the pixel's centre.
    NonZero,
}

impl FillRule {
    /// The rule's byte in the binary form's `fill` command: 0 even-odd,
    /// 1 non-zero.
    pub const fn to_byte(self) -> u8 {
        match self {
            FillRule::EvenOdd => 0,
            FillRule::NonZero => 1,
        }
    }

    /// The rule of a `fill` command's byte, if it names one.
    pub const fn from_byte(b: u8) -> Option<FillRule> {
        match b {
            0 => Some(FillRule::EvenOdd),
            1 => Some(FillRule::NonZero),
            _ => None,
        }
    }

    /// The rule's name in the text form: `evenodd` or `nonzero`.
    pub const fn name(self) -> &'static str {
        match self {
            FillRule::EvenOdd => "evenodd",
            FillRule::NonZero => "nonzero",
        }
    }

    /// The rule of a text-form name.
    pub fn from_name(name: &str) -> Option<FillRule> {
        [FillRule::EvenOdd, FillRule::NonZero]
            .into_iter()
            .find(|r| r.name() == name)
    }
}

/// Writes the spans of row `y` by the non-zero rule, cut to the clip
/// columns `cx`: `live` holds the row's crossings, loaded by
/// [`Stepper::load_wound`] and sorted. A span starts at a crossing that
/// takes the winding sum from zero and ends at the one that brings it
/// back.
#[inline(never)]
pub(super) fn emit_nonzero<const BAND: bool, S: Stepper, T: SpanTarget + ?Sized>(
    y: i32,
    live: &[S],
    cx: (i32, i32),
    color: T::Color,
    target: &mut T,
    counts: &mut Counts,
) -> Result<(), T::Error> {
    // |sum| ≤ the number of edges, which fits the slice's length.
    let mut sum = 0isize;
    let mut start = 0;
    for e in live {
        let (px, up) = (e.pixel() >> 1, e.pixel() & 1);
        let was = sum;
        // +1 running down, −1 running up.
        sum += 1 - 2 * up as isize;
        if was == 0 {
            start = px;
        } else if sum == 0 {
            emit_span::<BAND, T>(y, start, px, cx, color, target, counts)?;
        }
    }
    Ok(())
}
