//! The frame checksum that the host and the target compare.
//!
//! FNV-1a (32 bit) over the frame's pixels in row-major order, each pixel
//! as its raw storage value in little-endian bytes (two bytes for RGB565).
//! It is cheap enough to run on the target after every frame.

use embedded_graphics_core::pixelcolor::raw::ToBytes;
use embedded_graphics_core::pixelcolor::PixelColor;

const OFFSET: u32 = 0x811c_9dc5;
const PRIME: u32 = 0x0100_0193;

/// A running FNV-1a checksum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Checksum(u32);

impl Default for Checksum {
    fn default() -> Self {
        Checksum(OFFSET)
    }
}

impl Checksum {
    /// Adds bytes.
    #[inline]
    pub fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ b as u32).wrapping_mul(PRIME);
        }
    }

    /// Adds pixels as their raw little-endian storage.
    pub fn write_pixels<C>(&mut self, pixels: &[C])
    where
        C: PixelColor,
        C::Raw: From<C> + ToBytes,
        <C::Raw as ToBytes>::Bytes: AsRef<[u8]>,
    {
        for &p in pixels {
            let raw: C::Raw = p.into();
            self.write(raw.to_le_bytes().as_ref());
        }
    }

    /// The value so far.
    pub fn value(&self) -> u32 {
        self.0
    }
}

/// The checksum of a frame's pixels (row-major).
pub fn frame_checksum<C>(pixels: &[C]) -> u32
where
    C: PixelColor,
    C::Raw: From<C> + ToBytes,
    <C::Raw as ToBytes>::Bytes: AsRef<[u8]>,
{
    let mut c = Checksum::default();
    c.write_pixels(pixels);
    c.value()
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};

    #[test]
    fn known_values() {
        // FNV-1a of the empty string and of "a".
        assert_eq!(Checksum::default().value(), 0x811c_9dc5);
        let mut c = Checksum::default();
        c.write(b"a");
        assert_eq!(c.value(), 0xe40c_292c);
        // One white RGB565 pixel is the bytes ff ff.
        let mut d = Checksum::default();
        d.write(&[0xff, 0xff]);
        assert_eq!(frame_checksum(&[Rgb565::WHITE]), d.value());
    }
}
