//! A display list streamed band by band into an embedded-graphics
//! `DrawTarget`, with no frame buffer on the library's side.
//!
//! The list (2D polygons, a lit 3D cube, labels) is rendered 16 rows at a
//! time through one band buffer of 16 × width pixels; each band goes to
//! the target as ONE `fill_contiguous` of its rows (`DrawTargetPort` is a
//! `BandTarget`). The target here is a counting wrapper over scanvert's
//! in-memory `FrameBuffer`, standing for a display driver. The program
//! prints the bands, the `fill_contiguous` calls and the pixels sent, and
//! checks that the picture equals the frame rendered whole. With
//! `--out FILE.ppm` it also writes the picture as a PPM image.
//!
//! ```sh
//! cargo run -p scanvert --example bands_draw_target
//! ```

use core::convert::Infallible;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use scanvert::color::ToRgb888;
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::geometry::{Angle, Point3, View, Q16};
use scanvert::pixelcolor::{Rgb565, Rgb888};
use scanvert::port::draw_target::DrawTargetPort;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::scene::SceneStorage;

const W: u16 = 128;
const H: u16 = 96;
/// Rows per band.
const ROWS: u16 = 16;

/// A vertex at `(x, y)` pixels.
fn v(x: i16, y: i16) -> Vertex {
    Vertex::from_bits(x * 16, y * 16)
}

/// The list: a background, a 2D ground and sun, a lit cube with two
/// labels, and a 2D badge drawn over the 3D layer.
fn list(buf: &mut [u8]) -> &[u8] {
    let mut w = Writer::new(buf, W, H).expect("frame size");
    w.clear(Rgb888::new(0x10, 0x18, 0x28)).unwrap();
    w.color(Rgb888::new(0x30, 0x50, 0x30)).unwrap();
    w.poly([v(0, 60), v(128, 52), v(128, 96), v(0, 96)])
        .unwrap();
    w.color(Rgb888::new(0xff, 0xc0, 0x40)).unwrap();
    w.poly([v(100, 6), v(116, 12), v(112, 26), v(98, 22)])
        .unwrap();
    w.perspective(
        Angle::from_degrees(60),
        Q16::from_int(1),
        Q16::from_int(100),
    )
    .unwrap();
    let eye = View::look_at(Point3::from_int(3, 3, 5), Point3::from_int(0, 0, 0)).unwrap();
    w.view(eye.eye, eye.yaw, eye.pitch).unwrap();
    w.light(Point3::from_int(1, 2, 3), 70).unwrap();
    w.segment(1).unwrap();
    w.color(Rgb888::new(0xe0, 0x40, 0x40)).unwrap();
    let p = Point3::from_int;
    for face in [
        [p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1)],
        [p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1)],
        [p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1)],
        [p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1)],
        [p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1)],
        [p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1)],
    ] {
        w.face(face).unwrap();
    }
    w.color(Rgb888::new(0xff, 0xff, 0xff)).unwrap();
    w.label(p(1, 1, 1), "cube").unwrap();
    w.label(p(-1, -1, 1), "scanvert").unwrap();
    w.color(Rgb888::new(0x40, 0xc0, 0xff)).unwrap();
    w.poly([v(4, 80), v(40, 80), v(40, 92), v(4, 92)]).unwrap();
    w.finish()
}

/// A `DrawTarget` over a frame buffer that counts what it is sent.
struct Counting<'a> {
    fb: FrameBuffer<'a, Rgb565>,
    contiguous: u32,
    other: u32,
    pixels: u64,
}

impl OriginDimensions for Counting<'_> {
    fn size(&self) -> Size {
        OriginDimensions::size(&self.fb)
    }
}

impl DrawTarget for Counting<'_> {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        px: I,
    ) -> Result<(), Infallible> {
        self.other += 1;
        self.fb.draw_iter(px)
    }

    fn fill_contiguous<I: IntoIterator<Item = Rgb565>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Infallible> {
        self.contiguous += 1;
        self.pixels += area.size.width as u64 * area.size.height as u64;
        self.fb.fill_contiguous(area, colors)
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Rgb565) -> Result<(), Infallible> {
        self.other += 1;
        self.fb.fill_solid(area, color)
    }
}

fn main() {
    let mut bytes = [0u8; 1024];
    let list = DisplayList::new_checked(list(&mut bytes)).expect("valid list");

    // The 3D layer's memory in one value, capacities as const generics
    // (`controller::needs` tells what a list needs): 128 trapezoids, 32
    // faces, 1 segment, H rows of the index, 16 edge slots, 64 active
    // trapezoids a row, W runs, 4 labels, 32 bytes of label text. No frame.
    let mut storage =
        SceneStorage::<128, 32, 1, { H as usize }, 16, 64, { W as usize }, 4, 32>::new();
    let mut edges = [Edge::EMPTY; 64];
    let mut controller = Controller::new(Rasterizer::new(&mut edges)).with_3d(storage.as_memory());

    // The whole frame, for the check.
    let mut whole = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut whole, W, H).expect("frame size");
    controller.render(&list, &mut fb).expect("renders");

    // Band by band into the counting target.
    let t = list.table_needs();
    let mut polygons = vec![TablePolygon::EMPTY; t.polygons];
    let mut table_index = vec![0u32; 2 * t.polygons];
    let mut table_edges = vec![Edge::EMPTY; t.edges];
    let mut table_lines = vec![None; t.lines];
    let table = TableMemory {
        polygons: &mut polygons,
        index: &mut table_index,
        edges: &mut table_edges,
        lines: &mut table_lines,
    };
    let mut shown = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut counting = Counting {
        fb: FrameBuffer::new(&mut shown, W, H).expect("frame size"),
        contiguous: 0,
        other: 0,
        pixels: 0,
    };
    let mut display = DrawTargetPort::new(&mut counting);
    let mut band = vec![Rgb565::BLACK; ROWS as usize * W as usize];
    let stats = controller
        .render_bands(&list, table, ROWS, &mut band, &mut display)
        .expect("renders in bands");
    let c = counting;
    let bands = H.div_ceil(ROWS);
    println!(
        "{W}x{H} in {ROWS}-row bands: {bands} bands, {} fill_contiguous calls, {} other DrawTarget calls, {} pixels sent ({} polygons, {} faces, {} label draws); band buffer {} pixels, the frame {}",
        c.contiguous,
        c.other,
        c.pixels,
        stats.polygons,
        stats.faces,
        stats.labels,
        band.len(),
        whole.len()
    );
    assert_eq!(c.contiguous, bands as u32, "one fill_contiguous per band");
    assert_eq!(c.other, 0);
    assert_eq!(c.pixels, whole.len() as u64, "every pixel once");
    assert!(shown == whole, "the bands equal the whole frame");
    println!("the picture equals the frame rendered whole: yes");

    let args: Vec<String> = std::env::args().collect();
    if let [_, flag, path] = args.as_slice() {
        if flag == "--out" {
            let mut ppm = format!("P6\n{W} {H}\n255\n").into_bytes();
            for &c in &shown {
                let c = c.to_rgb888();
                ppm.extend([c.r(), c.g(), c.b()]);
            }
            std::fs::write(path, ppm).expect("writes the image");
            println!("wrote {path}");
        }
    }
}
