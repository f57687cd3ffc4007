//! PNG images of read-out frames: 8-bit RGB, each pixel expanded from the
//! frame buffer's format by bit replication
//! ([`scanvert::color::ToRgb888`]), so channels 0x00 and 0xff survive
//! exactly.
//!
//! Errors are [`std::io::Error`]s; nothing here panics.

use crate::refresh::Frame;
use embedded_graphics_core::pixelcolor::RgbColor;
use scanvert::color::ToRgb888;
use std::io::{self, Cursor};
use std::path::Path;

/// The PNG of `frame`.
pub fn encode_png(frame: &Frame) -> io::Result<Vec<u8>> {
    encode_pixels(frame.width().into(), frame.height().into(), frame.pixels())
}

/// The PNG of `width × height` pixels given row-major in any format that
/// expands to 24 bits. An `InvalidInput` error when a side is 0 or the
/// slice's length is not `width × height`.
pub fn encode_pixels<C: ToRgb888>(width: u32, height: u32, pixels: &[C]) -> io::Result<Vec<u8>> {
    let area = u64::from(width) * u64::from(height);
    if width == 0 || height == 0 || pixels.len() as u64 != area {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "{} pixels do not make a {width}×{height} image",
                pixels.len()
            ),
        ));
    }
    let rgb: Vec<u8> = pixels
        .iter()
        .flat_map(|p| {
            let c = p.to_rgb888();
            [c.r(), c.g(), c.b()]
        })
        .collect();
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&rgb)?;
    writer.finish()?;
    Ok(out)
}

/// Writes the PNG of `frame` to `path`. The image is encoded in full
/// before the file is created, so a failed encoding leaves no file.
pub fn write_png(path: impl AsRef<Path>, frame: &Frame) -> io::Result<()> {
    let bytes = encode_png(frame)?;
    std::fs::write(path, bytes)
}

/// Decodes a PNG into `(width, height, rgb)`, with `rgb` 8-bit RGB,
/// row-major. Palette, grey and 16-bit images are converted; alpha is
/// dropped. For tests and tools.
pub fn decode_png(bytes: &[u8]) -> io::Result<(u32, u32, Vec<u8>)> {
    let mut decoder = png::Decoder::new(Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info()?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidData, "PNG too large to decode"))?;
    let mut buf = vec![0; size];
    let info = reader.next_frame(&mut buf)?;
    buf.truncate(info.buffer_size());
    let rgb = match info.color_type {
        png::ColorType::Rgb => buf,
        png::ColorType::Rgba => buf
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect(),
        png::ColorType::Grayscale => buf.iter().flat_map(|&g| [g, g, g]).collect(),
        png::ColorType::GrayscaleAlpha => buf
            .chunks_exact(2)
            .flat_map(|p| [p[0], p[0], p[0]])
            .collect(),
        png::ColorType::Indexed => {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                "indexed PNG was not expanded",
            ))
        }
    };
    Ok((info.width, info.height, rgb))
}

#[cfg(test)]
mod tests {
    use super::*;
    use embedded_graphics_core::pixelcolor::Rgb565;

    #[test]
    fn round_trip_expands_by_bit_replication() {
        let px = vec![
            Rgb565::new(0, 0, 0),
            Rgb565::new(31, 63, 31),
            Rgb565::new(16, 32, 1),
            Rgb565::new(1, 1, 30),
            Rgb565::new(31, 0, 0),
            Rgb565::new(0, 63, 0),
        ];
        let frame = Frame::from_pixels(3, 2, px).unwrap();
        let (w, h, rgb) = decode_png(&encode_png(&frame).unwrap()).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(
            rgb,
            [0, 0, 0, 255, 255, 255, 0x84, 0x82, 0x08, 0x08, 0x04, 0xf7, 255, 0, 0, 0, 255, 0]
        );
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        assert!(encode_pixels::<Rgb565>(0, 1, &[]).is_err());
        assert!(encode_pixels(2, 2, &[Rgb565::new(0, 0, 0)]).is_err());
        assert!(decode_png(b"not a png").is_err());
        assert!(decode_png(&[]).is_err());
        let frame = Frame::from_pixels(0, 0, Vec::new()).unwrap();
        let dir = std::env::temp_dir().join("scanvert-sim-image-test-empty.png");
        assert!(write_png(&dir, &frame).is_err());
        assert!(!dir.exists());
    }
}
