//! A `clear` fills the whole frame, so what a list draws before its last
//! `clear` cannot show: the render draws from the last `clear` on, with
//! the clip registers and colour that the commands before it left. The
//! pixels are those of drawing every command, and the work is bounded by
//! one clear and the commands after it, however many `clear`s come first.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use host_tests::harness::vertex;
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::clip::ClipWindow;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;

const W: u16 = 40;
const H: u16 = 30;

/// A list of `clears` clears, each followed by a triangle in a new colour,
/// then a clip window and a colour set before one last clear, and one
/// triangle after it.
fn list(clears: usize) -> Vec<u8> {
    let mut buf = vec![0u8; 64 + clears * 64];
    let mut w = Writer::new(&mut buf, W, H).unwrap();
    let tri = |k: i32| [(16 * k % 400, 0), (400, 16 * 20), (0, 16 * 25)].map(vertex);
    for k in 0..clears {
        w.clear(Rgb888::new(k as u8, 0, 0)).unwrap();
        w.color(Rgb888::new(0, k as u8, 200)).unwrap();
        w.poly(tri(k as i32)).unwrap();
    }
    // State set before the last clear holds after it.
    w.clip(ClipWindow {
        x0: 4,
        y0: 2,
        x1: 30,
        y1: 25,
    })
    .unwrap();
    w.color(Rgb888::new(10, 200, 30)).unwrap();
    w.clear(Rgb888::new(1, 2, 3)).unwrap();
    w.poly(tri(7)).unwrap();
    w.finish().to_vec()
}

/// Renders `bytes`; returns the pixels and the clears and polygons drawn.
fn render(bytes: &[u8]) -> (Vec<Rgb565>, u32, u32) {
    let list = DisplayList::new_checked(bytes).unwrap();
    let mut edges = [Edge::EMPTY; 8];
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
    let stats = Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut fb)
        .unwrap();
    (px, stats.clears, stats.polygons)
}

#[test]
fn only_the_last_clear_and_what_follows_are_drawn() {
    let (alone, clears, polygons) = render(&list(0));
    assert_eq!((clears, polygons), (1, 1));
    for n in [1, 2, 17, 300] {
        let (px, clears, polygons) = render(&list(n));
        assert_eq!(px, alone, "{n} clears before the last");
        assert_eq!((clears, polygons), (1, 1), "{n} clears before the last");
    }
}

#[test]
fn the_summary_knows_the_last_clear() {
    let bytes = list(3);
    let list = DisplayList::new_checked(&bytes).unwrap();
    let last = list
        .commands()
        .filter(|(_, c)| matches!(c, scanvert::display_list::Command::Clear(_)))
        .map(|(at, _)| at)
        .last();
    assert_eq!(list.summary().last_clear, last);
    assert!(last.is_some());
}
