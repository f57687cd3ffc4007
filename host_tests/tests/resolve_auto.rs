//! The default resolve, `Resolve::Auto`: it paints a frame of tall
//! trapezoids into memory and takes crossing points for small ones and
//! for targets whose overdraw costs (a `DrawTarget`'s window), always to
//! the pixels of the other modes; the frame's stats say which it took.

use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{OriginDimensions, Size};
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics_core::Pixel;
use scanvert::display_list::DisplayList;
use scanvert::port::draw_target::DrawTargetPort;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::visible::{Resolve, PAINT_FROM};
use scanvert_sim::memory::ListMemory;
use std::path::Path;

fn list_bytes(rel: &str) -> Vec<u8> {
    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(rel)).expect("list")
}

/// `list` rendered whole into a frame buffer with `mode`: the pixels and
/// the mode the frame took.
fn render(list: &DisplayList<'_>, mode: Resolve) -> (Vec<Rgb888>, Resolve) {
    let mut mem = ListMemory::for_list(list).expect("memory");
    let (w, h) = (list.width(), list.height());
    let mut px = vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
    let mut fb = FrameBuffer::new(&mut px, w, h).expect("frame");
    let stats = mem
        .controller()
        .with_resolve(mode)
        .render(list, &mut fb)
        .expect("render");
    (px, stats.visible.mode)
}

/// A display that counts every pixel it is sent.
struct Counting {
    size: Size,
    pixels: Vec<Rgb888>,
    sent: u64,
}

impl OriginDimensions for Counting {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Counting {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(p, c) in pixels {
            self.sent += 1;
            let (x, y) = (p.x as u32, p.y as u32);
            if x < self.size.width && y < self.size.height {
                self.pixels[(y * self.size.width + x) as usize] = c;
            }
        }
        Ok(())
    }
}

#[test]
fn tall_faces_are_painted_and_small_ones_swept_to_the_same_pixels() {
    for (rel, took) in [
        ("firmware/image/scenes/poly3-layered.scvl", Resolve::Paint),
        ("firmware/image/scenes/poly3-tilted.scvl", Resolve::Paint),
        (
            "firmware/image/scenes/meshes/mesh-icosphere.scvl",
            Resolve::Crossing,
        ),
        (
            "firmware/image/scenes/meshes/mesh-teapot.scvl",
            Resolve::Crossing,
        ),
    ] {
        let bytes = list_bytes(rel);
        let list = DisplayList::new_checked(&bytes).expect("list");
        let (auto, mode) = render(&list, Resolve::default());
        assert_eq!(mode, took, "{rel}");
        for other in [Resolve::Crossing, Resolve::Paint] {
            let (px, m) = render(&list, other);
            assert_eq!(m, other, "{rel}: {other:?} is what was asked");
            assert!(px == auto, "{rel}: {other:?} differs from the default");
        }
    }
}

#[test]
fn a_display_window_is_never_painted() {
    let bytes = list_bytes("firmware/image/scenes/poly3-layered.scvl");
    let list = DisplayList::new_checked(&bytes).expect("list");
    let (want, _) = render(&list, Resolve::Crossing);
    let (w, h) = (list.width() as u32, list.height() as u32);
    let mut display = Counting {
        size: Size::new(w, h),
        pixels: vec![Rgb888::BLACK; (w * h) as usize],
        sent: 0,
    };
    let mut mem = ListMemory::for_list(&list).expect("memory");
    let stats = mem
        .controller()
        .render(&list, &mut DrawTargetPort::new(&mut display))
        .expect("render");
    assert_eq!(stats.visible.mode, Resolve::Crossing);
    assert!(display.pixels == want);
    // Each pixel sent once at most: no face painted over another (painted,
    // this list sends more pixels than the frame has).
    assert!(display.sent <= u64::from(w * h), "{} sent", display.sent);
}

#[test]
fn bands_settle_as_the_whole_frame_does() {
    for rel in [
        "firmware/image/scenes/poly3-layered.scvl",
        "firmware/image/scenes/meshes/mesh-torus.scvl",
    ] {
        let bytes = list_bytes(rel);
        let list = DisplayList::new_checked(&bytes).expect("list");
        let (want, whole) = render(&list, Resolve::default());
        let mut mem = ListMemory::for_bands(&list).expect("memory");
        let (c, table) = mem.band_parts();
        let mut c = c;
        let mut bands = c.bands(&list, table).expect("bands");
        let (w, h) = bands.size();
        let mut px = vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
        for y in (0..h).step_by(16) {
            let rows = 16.min(h - y);
            let at = usize::from(y) * usize::from(w);
            let end = at + usize::from(rows) * usize::from(w);
            bands.draw(y, rows, &mut px[at..end]).expect("band");
        }
        assert_eq!(bands.stats().visible.mode, whole, "{rel}");
        assert!(px == want, "{rel}: the bands differ from the frame");
    }
}

#[test]
fn the_threshold_is_a_mean_height() {
    assert_eq!(Resolve::default(), Resolve::Auto);
    assert_eq!(Resolve::Auto.settle(3, 3 * PAINT_FROM), Resolve::Paint);
    assert_eq!(
        Resolve::Auto.settle(3, 3 * PAINT_FROM - 1),
        Resolve::Crossing
    );
}
