//! The four clip registers.
//!
//! A `clip` command loads [`ClipWindow`]: inclusive whole-pixel bounds as
//! written in the display list, which may be empty or reach outside the
//! frame. The controller resolves it against the frame into a [`ClipRect`],
//! the form the rasteriser uses.

/// The clip registers as loaded: inclusive pixel bounds `x0..=x1`,
/// `y0..=y1`, any `i16` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ClipWindow {
    /// Leftmost column written.
    pub x0: i16,
    /// Top row written.
    pub y0: i16,
    /// Rightmost column written.
    pub x1: i16,
    /// Bottom row written.
    pub y1: i16,
}

/// A clip window cut to the frame: columns `x0..x1` and rows `y0..y1`,
/// ends exclusive.
///
/// # Guarantees
/// `x0 <= x1 <= width` and `y0 <= y1 <= height` of the frame it was made
/// for. It may be empty (a window wholly outside the frame, or with
/// `x0 > x1` as loaded); an empty window writes nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ClipRect {
    x0: u16,
    y0: u16,
    x1: u16,
    y1: u16,
}

impl ClipRect {
    /// The whole of a `width × height` frame.
    pub const fn full(width: u16, height: u16) -> Self {
        ClipRect {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    /// The registers `w` cut to a `width × height` frame.
    pub fn from_window(w: ClipWindow, width: u16, height: u16) -> Self {
        // Inclusive i16 bounds become exclusive i32 ends, then are clamped.
        let cut = |lo: i16, hi: i16, side: u16| {
            let lo = (lo as i32).clamp(0, side as i32);
            let hi = (hi as i32 + 1).clamp(0, side as i32);
            (lo as u16, hi.max(lo) as u16)
        };
        let (x0, x1) = cut(w.x0, w.x1, width);
        let (y0, y1) = cut(w.y0, w.y1, height);
        ClipRect { x0, y0, x1, y1 }
    }

    /// The window cut to a `width × height` target (a target smaller
    /// than the frame the window was made for): within it, with the same
    /// guarantees.
    pub const fn within(self, width: u16, height: u16) -> Self {
        let x1 = if self.x1 < width { self.x1 } else { width };
        let y1 = if self.y1 < height { self.y1 } else { height };
        ClipRect {
            x0: if self.x0 < x1 { self.x0 } else { x1 },
            y0: if self.y0 < y1 { self.y0 } else { y1 },
            x1,
            y1,
        }
    }

    /// First column.
    pub const fn x0(&self) -> u16 {
        self.x0
    }
    /// One past the last column.
    pub const fn x1(&self) -> u16 {
        self.x1
    }
    /// First row.
    pub const fn y0(&self) -> u16 {
        self.y0
    }
    /// One past the last row.
    pub const fn y1(&self) -> u16 {
        self.y1
    }

    /// `true` when no pixel is inside.
    pub const fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// `true` when pixel `(x, y)` is inside.
    pub fn contains(&self, x: i32, y: i32) -> bool {
        (self.x0 as i32..self.x1 as i32).contains(&x)
            && (self.y0 as i32..self.y1 as i32).contains(&y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_is_cut_to_frame() {
        let w = ClipWindow {
            x0: -5,
            y0: 3,
            x1: 1000,
            y1: 7,
        };
        let r = ClipRect::from_window(w, 100, 50);
        assert_eq!((r.x0(), r.y0(), r.x1(), r.y1()), (0, 3, 100, 8));
    }

    #[test]
    fn inverted_and_outside_windows_are_empty() {
        let inv = ClipWindow {
            x0: 10,
            y0: 0,
            x1: 5,
            y1: 9,
        };
        assert!(ClipRect::from_window(inv, 100, 50).is_empty());
        let out = ClipWindow {
            x0: 200,
            y0: 0,
            x1: 300,
            y1: 9,
        };
        assert!(ClipRect::from_window(out, 100, 50).is_empty());
        let extreme = ClipWindow {
            x0: i16::MIN,
            y0: i16::MIN,
            x1: i16::MAX,
            y1: i16::MAX,
        };
        assert_eq!(
            ClipRect::from_window(extreme, 4096, 4096),
            ClipRect::full(4096, 4096)
        );
    }

    #[test]
    fn within_cuts_to_a_smaller_target() {
        let c = ClipRect::full(100, 50).within(30, 60);
        assert_eq!((c.x0(), c.y0(), c.x1(), c.y1()), (0, 0, 30, 50));
        let w = ClipWindow {
            x0: 40,
            y0: 10,
            x1: 90,
            y1: 20,
        };
        assert!(ClipRect::from_window(w, 100, 50).within(30, 60).is_empty());
        let c = ClipRect::from_window(w, 100, 50).within(60, 15);
        assert_eq!((c.x0(), c.y0(), c.x1(), c.y1()), (40, 10, 60, 15));
    }
}
