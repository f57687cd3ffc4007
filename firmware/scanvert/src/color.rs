//! Colours: the 24-bit colours of the display list and their conversion to
//! the frame buffer's pixel format.
//!
//! The display list always carries `#rrggbb`. A frame buffer may hold fewer
//! bits; the conversion keeps the high bits of each channel (truncation),
//! as a hardware bus does when it drops the low wires. The simulator expands
//! them back by bit replication, so `0x00` and `0xff` survive exactly and a
//! colour that fits the format round-trips unchanged.

use embedded_graphics_core::pixelcolor::raw::RawU16;
use embedded_graphics_core::pixelcolor::{
    BinaryColor, Gray8, Rgb555, Rgb565, Rgb666, Rgb888, RgbColor,
};

/// The colour of `poly`, `line`, `poly3` and `face` before a list's
/// first `color` command.
pub const DEFAULT_COLOR: Rgb888 = Rgb888::WHITE;

/// A pixel format that a display-list colour can be written in.
pub trait ListColor: embedded_graphics_core::pixelcolor::PixelColor {
    /// The pixel nearest below `c` in this format (each channel truncated).
    fn from_rgb888(c: Rgb888) -> Self;

    /// The pixel of `w`, a colour in the form the 3D sweep carries with
    /// each face: the `Rgb565` pixel in the low 16 bits and the bits it
    /// drops (`r & 7`, `g & 3`, `b & 7`) in bits 16 to 23. The default is
    /// [`from_rgb888`](Self::from_rgb888) of the colour; `Rgb565` takes
    /// the low half as it is.
    #[inline]
    fn from_list_word(w: u32) -> Self {
        Self::from_rgb888(word_rgb888(w))
    }
}

/// A 24-bit colour `0x00rrggbb` in the form the 3D sweep carries with
/// each face, converted once per face rather than once per run: the
/// `Rgb565` pixel in the low 16 bits, and the bits it drops in bits 16 to
/// 23 (`r & 7`, `g & 3`, `b & 7`), so that two colours have the same word
/// only when they are equal. The word is below `1 << 24`.
#[inline]
pub(crate) const fn list_word(rgb: u32) -> u32 {
    let (r, g, b) = ((rgb >> 16) & 0xff, (rgb >> 8) & 0xff, rgb & 0xff);
    let pixel = (r >> 3) << 11 | (g >> 2) << 5 | b >> 3;
    let low = (r & 7) << 5 | (g & 3) << 3 | (b & 7);
    pixel | low << 16
}

/// The 24-bit colour of a [`list_word`].
#[inline]
pub(crate) const fn word_rgb888(w: u32) -> Rgb888 {
    let r = ((w >> 11) & 0x1f) << 3 | (w >> 21) & 7;
    let g = ((w >> 5) & 0x3f) << 2 | (w >> 19) & 3;
    let b = (w & 0x1f) << 3 | (w >> 16) & 7;
    Rgb888::new(r as u8, g as u8, b as u8)
}

impl ListColor for Rgb888 {
    #[inline]
    fn from_rgb888(c: Rgb888) -> Self {
        c
    }
}

impl ListColor for Rgb565 {
    #[inline]
    fn from_rgb888(c: Rgb888) -> Self {
        Rgb565::new(c.r() >> 3, c.g() >> 2, c.b() >> 3)
    }

    #[inline]
    fn from_list_word(w: u32) -> Self {
        Rgb565::from(RawU16::new(w as u16))
    }
}

impl ListColor for Rgb555 {
    #[inline]
    fn from_rgb888(c: Rgb888) -> Self {
        Rgb555::new(c.r() >> 3, c.g() >> 3, c.b() >> 3)
    }
}

impl ListColor for Rgb666 {
    #[inline]
    fn from_rgb888(c: Rgb888) -> Self {
        Rgb666::new(c.r() >> 2, c.g() >> 2, c.b() >> 2)
    }
}

impl ListColor for Gray8 {
    /// Luma by the integer weights 77/150/29 (sum 256) of ITU-R BT.601.
    #[inline]
    fn from_rgb888(c: Rgb888) -> Self {
        let y = (77 * c.r() as u32 + 150 * c.g() as u32 + 29 * c.b() as u32) >> 8;
        Gray8::new(y as u8)
    }
}

impl ListColor for BinaryColor {
    /// On when the BT.601 luma is at least half.
    #[inline]
    fn from_rgb888(c: Rgb888) -> Self {
        let y = (77 * c.r() as u32 + 150 * c.g() as u32 + 29 * c.b() as u32) >> 8;
        if y >= 128 {
            BinaryColor::On
        } else {
            BinaryColor::Off
        }
    }
}

/// Expands a pixel back to 24 bits by bit replication (the inverse of
/// [`ListColor::from_rgb888`] on the colours the format holds).
pub trait ToRgb888: Copy {
    /// The 24-bit colour shown for this pixel.
    fn to_rgb888(self) -> Rgb888;
}

#[inline]
const fn rep5(v: u8) -> u8 {
    (v << 3) | (v >> 2)
}
#[inline]
const fn rep6(v: u8) -> u8 {
    (v << 2) | (v >> 4)
}

impl ToRgb888 for Rgb565 {
    #[inline]
    fn to_rgb888(self) -> Rgb888 {
        Rgb888::new(rep5(self.r()), rep6(self.g()), rep5(self.b()))
    }
}
impl ToRgb888 for Rgb555 {
    #[inline]
    fn to_rgb888(self) -> Rgb888 {
        Rgb888::new(rep5(self.r()), rep5(self.g()), rep5(self.b()))
    }
}
impl ToRgb888 for Rgb666 {
    #[inline]
    fn to_rgb888(self) -> Rgb888 {
        Rgb888::new(rep6(self.r()), rep6(self.g()), rep6(self.b()))
    }
}
impl ToRgb888 for Rgb888 {
    #[inline]
    fn to_rgb888(self) -> Rgb888 {
        self
    }
}
impl ToRgb888 for Gray8 {
    #[inline]
    fn to_rgb888(self) -> Rgb888 {
        use embedded_graphics_core::pixelcolor::GrayColor;
        Rgb888::new(self.luma(), self.luma(), self.luma())
    }
}
impl ToRgb888 for BinaryColor {
    #[inline]
    fn to_rgb888(self) -> Rgb888 {
        if self.is_on() {
            Rgb888::WHITE
        } else {
            Rgb888::BLACK
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgb565_round_trip_keeps_extremes_and_fitting_colours() {
        for c in [Rgb888::BLACK, Rgb888::WHITE, Rgb888::new(0xff, 0, 0)] {
            assert_eq!(Rgb565::from_rgb888(c).to_rgb888(), c);
        }
        for r in 0..32u8 {
            for g in 0..64u8 {
                let p = Rgb565::new(r, g, r);
                assert_eq!(Rgb565::from_rgb888(p.to_rgb888()), p);
            }
        }
    }

    #[test]
    fn list_words_round_trip_and_give_each_format_its_pixel() {
        for r in 0..=255u32 {
            for g in (0..=255u32).step_by(3) {
                for b in (0..=255u32).step_by(5).chain([254, 255]) {
                    let c = Rgb888::new(r as u8, g as u8, b as u8);
                    let w = list_word(r << 16 | g << 8 | b);
                    assert!(w < 1 << 24);
                    assert_eq!(word_rgb888(w), c);
                    assert_eq!(Rgb565::from_list_word(w), Rgb565::from_rgb888(c));
                    assert_eq!(Rgb888::from_list_word(w), c);
                    assert_eq!(Gray8::from_list_word(w), Gray8::from_rgb888(c));
                }
            }
        }
    }
}
