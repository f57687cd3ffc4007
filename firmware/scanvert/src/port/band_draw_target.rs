//! Bands into an embedded-graphics [`DrawTarget`]: each band becomes ONE
//! [`fill_contiguous`](DrawTarget::fill_contiguous) of the rectangle of
//! its rows, so a display driver sets one address window and streams the
//! band's pixels in one burst.
//!
//! [`DrawTargetPort`] is a [`BandTarget`], and [`fill_band`] does the same
//! for a bare `DrawTarget`. Frame pixel `(x, y)` is the target's point
//! `(x, y)`, as for the span path of [`DrawTargetPort`].
//!
//! ```
//! use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
//! use scanvert::controller::Controller;
//! use scanvert::display_list::{DisplayList, Writer};
//! use scanvert::fixed::Vertex;
//! use scanvert::port::draw_target::DrawTargetPort;
//! use scanvert::port::framebuffer::FrameBuffer;
//! use scanvert::raster::edge::Edge;
//! use scanvert::raster::scan::Rasterizer;
//! use scanvert::raster::table::{TableMemory, TablePolygon};
//!
//! let mut bytes = [0u8; 64];
//! let mut w = Writer::new(&mut bytes, 32, 16)?;
//! w.color(Rgb888::RED)?;
//! let px = |x: i16, y: i16| Vertex::from_bits(x * 16, y * 16);
//! w.poly([px(2, 2), px(30, 8), px(4, 14)])?;
//! let list = DisplayList::new_checked(w.finish()).unwrap();
//!
//! let mut pixels = [Rgb565::BLACK; 32 * 16];
//! let mut fb = FrameBuffer::new(&mut pixels, 32, 16).unwrap();
//! let mut port = DrawTargetPort::new(&mut fb);
//! let (mut edges, mut polygons) = ([Edge::EMPTY; 3], [TablePolygon::EMPTY; 1]);
//! let (mut index, mut table_edges) = ([0u32; 2], [Edge::EMPTY; 3]);
//! let table = TableMemory { polygons: &mut polygons, index: &mut index, edges: &mut table_edges, lines: &mut [] };
//! // 4-row bands through a buffer of 4 × 32 pixels: 4 fill_contiguous calls.
//! let mut band = [Rgb565::BLACK; 4 * 32];
//! Controller::new(Rasterizer::new(&mut edges))
//!     .render_bands(&list, table, 4, &mut band, &mut port)
//!     .unwrap();
//! assert_eq!(port.get_ref().pixel(10, 8), Some(Rgb565::RED));
//! # Ok::<(), scanvert::display_list::WriteError>(())
//! ```

use crate::port::band::BandTarget;
use crate::port::draw_target::DrawTargetPort;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Point, Size};
use embedded_graphics_core::primitives::Rectangle;

/// Writes rows `y..y + rows` of the frame, held row by row in `pixels`,
/// into `target` with one [`fill_contiguous`](DrawTarget::fill_contiguous)
/// of the rectangle from `(0, y)`, `pixels.len() / rows` pixels wide and
/// `rows` high. Pixels past `rows × width` are not sent; `rows == 0` (or
/// an empty slice) sends nothing. Pixels outside the target are discarded
/// by the target, as every `DrawTarget` must.
#[doc(hidden)]
pub fn fill_band<D: DrawTarget>(
    target: &mut D,
    y: u16,
    rows: u16,
    pixels: &[D::Color],
) -> Result<(), D::Error> {
    if rows == 0 {
        return Ok(());
    }
    let width = pixels.len() / rows as usize;
    if width == 0 {
        return Ok(());
    }
    // `width` ≤ `pixels.len()`, and a slice of pixels of at least one
    // byte each is shorter than `isize::MAX`; a wider band than `u32`
    // holds is cut (the target discards it anyway).
    let area = Rectangle::new(
        Point::new(0, y as i32),
        Size::new(u32::try_from(width).unwrap_or(u32::MAX), rows as u32),
    );
    let n = width * rows as usize;
    target.fill_contiguous(&area, pixels[..n].iter().copied())
}

impl<D: DrawTarget> BandTarget for DrawTargetPort<'_, D> {
    type Color = D::Color;
    type Error = D::Error;

    /// One [`fill_contiguous`](DrawTarget::fill_contiguous) per band: see
    /// [`fill_band`].
    fn ship(&mut self, y: u16, rows: u16, pixels: &[D::Color]) -> Result<(), D::Error> {
        fill_band(self.get_mut(), y, rows, pixels)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::convert::Infallible;
    use embedded_graphics_core::geometry::OriginDimensions;
    use embedded_graphics_core::pixelcolor::{BinaryColor, Rgb565, RgbColor};
    use embedded_graphics_core::Pixel;

    /// Records the last `fill_contiguous` area and counts the calls.
    struct Calls {
        area: Option<Rectangle>,
        contiguous: u32,
        pixels: usize,
    }

    impl OriginDimensions for Calls {
        fn size(&self) -> Size {
            Size::new(8, 8)
        }
    }

    impl DrawTarget for Calls {
        type Color = Rgb565;
        type Error = Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
            &mut self,
            _: I,
        ) -> Result<(), Infallible> {
            panic!("a band is one fill_contiguous");
        }
        fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
            &mut self,
            area: &Rectangle,
            colors: I,
        ) -> Result<(), Infallible> {
            self.area = Some(*area);
            self.contiguous += 1;
            self.pixels += colors.into_iter().count();
            Ok(())
        }
    }

    #[test]
    fn a_band_is_one_fill_contiguous_of_its_rows() {
        let mut calls = Calls {
            area: None,
            contiguous: 0,
            pixels: 0,
        };
        let mut port = DrawTargetPort::new(&mut calls);
        let px = [Rgb565::RED; 8 * 3 + 5];
        port.ship(4, 3, &px).unwrap();
        let c = port.get_ref();
        assert_eq!(
            c.area,
            Some(Rectangle::new(Point::new(0, 4), Size::new(9, 3)))
        );
        assert_eq!((c.contiguous, c.pixels), (1, 27), "cut to rows × width");
        port.ship(0, 0, &px).unwrap();
        port.ship(0, 2, &px[..1]).unwrap();
        assert_eq!(port.get_ref().contiguous, 1, "nothing to send");
    }

    #[test]
    fn a_bare_target_takes_bands_too() {
        use crate::port::framebuffer::FrameBuffer;
        let mut px = [BinaryColor::Off; 4 * 4];
        let mut fb = FrameBuffer::new(&mut px, 4, 4).unwrap();
        fill_band(&mut fb, 3, 2, &[BinaryColor::On; 8]).unwrap();
        let on = |y| fb.row(y).unwrap().iter().all(|&c| c == BinaryColor::On);
        assert!(!on(2) && on(3), "row 4 is outside and discarded");
    }

    #[test]
    fn bands_through_the_port_equal_the_whole_frame() {
        use crate::controller::Controller;
        use crate::display_list::{DisplayList, Writer};
        use crate::fixed::Vertex;
        use crate::port::framebuffer::FrameBuffer;
        use crate::raster::edge::Edge;
        use crate::raster::scan::Rasterizer;
        use crate::raster::table::{TableMemory, TablePolygon};
        use embedded_graphics_core::pixelcolor::Rgb888;

        const W: u16 = 23;
        const H: u16 = 19;
        let px = |x: i16, y: i16| Vertex::from_bits(x, y);
        let mut bytes = [0u8; 256];
        let mut w = Writer::new(&mut bytes, W, H).unwrap();
        w.clear(Rgb888::new(10, 20, 30)).unwrap();
        w.color(Rgb888::RED).unwrap();
        w.poly([px(5, 3), px(360, 40), px(20, 300)]).unwrap();
        w.color(Rgb888::GREEN).unwrap();
        w.poly([px(-40, 100), px(200, 90), px(300, 310), px(100, 250)])
            .unwrap();
        let list = DisplayList::new_checked(w.finish()).unwrap();
        let mut edges = [Edge::EMPTY; 8];
        let mut c = Controller::new(Rasterizer::new(&mut edges));
        let mut whole = [Rgb565::BLACK; W as usize * H as usize];
        c.render(&list, &mut FrameBuffer::new(&mut whole, W, H).unwrap())
            .unwrap();
        let has = |c| whole.contains(&c);
        assert!(
            has(Rgb565::RED) && has(Rgb565::GREEN),
            "both polygons drawn"
        );
        for rows in [1, 4, 7, H, H + 3] {
            let mut shown = [Rgb565::BLUE; W as usize * H as usize];
            let mut fb = FrameBuffer::new(&mut shown, W, H).unwrap();
            let mut port = DrawTargetPort::new(&mut fb);
            let (mut polygons, mut index) = ([TablePolygon::EMPTY; 2], [0u32; 4]);
            let mut table_edges = [Edge::EMPTY; 7];
            let table = TableMemory {
                polygons: &mut polygons,
                index: &mut index,
                edges: &mut table_edges,
                lines: &mut [],
            };
            let mut band = [Rgb565::WHITE; W as usize * H as usize];
            c.render_bands(&list, table, rows, &mut band, &mut port)
                .unwrap();
            assert_eq!(shown, whole, "bands of {rows} rows");
        }
    }
}
