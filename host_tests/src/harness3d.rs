//! Running `poly3` scenes through the library's real path: a display list
//! built with `Writer`, checked, and executed by `Controller::render` with
//! memory sized by `needs` (`scanvert_sim::memory::ListMemory`), into an `Rgb888` frame buffer. Each
//! `poly3` gets a colour of its own, so the picture tells which one won
//! each pixel, and [`compare`] counts the pixels that differ from
//! [`testkit::reference3d`].

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use scanvert::controller::RenderStats;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::{Coord, Vertex3};
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::memory::ListMemory;
use testkit::reference::Window;
use testkit::reference3d::{resolve, Poly3};

/// The colour of the `k`-th `poly3` (never the black background).
pub fn color_of(k: usize) -> Rgb888 {
    Rgb888::new(k as u8, (k >> 8) as u8, 0xff)
}

/// The `poly3` a colour belongs to, `None` for the background.
pub fn index_of(c: Rgb888) -> Option<usize> {
    (c.b() == 0xff).then_some(c.r() as usize | (c.g() as usize) << 8)
}

/// A vertex from units; panics outside Q12.4.
pub fn vertex3((x, y, z): (i32, i32, i32)) -> Vertex3 {
    let fit = |v: i32| {
        Coord::from_bits(i16::try_from(v).unwrap_or_else(|_| panic!("{v} is outside Q12.4")))
    };
    Vertex3 {
        x: fit(x),
        y: fit(y),
        z: fit(z),
    }
}

/// The display list of `polys` on a `width × height` frame: a black
/// clear, then for each `poly3` its clip registers, its colour and itself.
pub fn build_list3(polys: &[Poly3], width: u16, height: u16) -> Vec<u8> {
    let size = 16
        + 4
        + polys
            .iter()
            .map(|p| 9 + 4 + 3 + 6 * p.poly.len())
            .sum::<usize>();
    let mut buf = vec![0u8; size];
    let mut w = Writer::new(&mut buf, width, height).expect("frame size");
    w.clear(Rgb888::BLACK).expect("sized");
    for (k, p) in polys.iter().enumerate() {
        let win = p.clip.unwrap_or(Window::full(width, height));
        w.clip(win.to_clip_window()).expect("sized");
        w.color(color_of(k)).expect("sized");
        w.poly3(p.poly.iter().copied().map(vertex3))
            .expect("3..=65535 vertices");
    }
    w.finish().to_vec()
}

/// Renders `polys` through the controller with `mode`; returns the
/// winner at each pixel (by colour) and the stats.
pub fn render3(
    polys: &[Poly3],
    width: u16,
    height: u16,
    mode: Resolve,
) -> (Vec<Option<usize>>, RenderStats) {
    let bytes = build_list3(polys, width, height);
    let list = DisplayList::new_checked(&bytes).expect("Writer output is valid");
    let mut memory = ListMemory::for_list(&list).expect("within the pools' limits");
    let mut pixels = vec![Rgb888::WHITE; width as usize * height as usize];
    let mut fb = FrameBuffer::new(&mut pixels, width, height).expect("frame size");
    let stats = memory
        .controller()
        .with_resolve(mode)
        .render(&list, &mut fb)
        .expect("render");
    (pixels.into_iter().map(index_of).collect(), stats)
}

/// [`render3`] band by band (`Controller::render_bands`, bands of `rows`
/// rows into one band buffer): the winner at each pixel.
pub fn render3_bands(
    polys: &[Poly3],
    width: u16,
    height: u16,
    mode: Resolve,
    rows: u16,
) -> Vec<Option<usize>> {
    use scanvert::port::band::BandTarget;
    /// The bands, one after the other.
    struct Collect(Vec<Rgb888>);
    impl BandTarget for Collect {
        type Color = Rgb888;
        type Error = core::convert::Infallible;
        fn ship(&mut self, _: u16, _: u16, px: &[Rgb888]) -> Result<(), Self::Error> {
            self.0.extend_from_slice(px);
            Ok(())
        }
    }
    let bytes = build_list3(polys, width, height);
    let list = DisplayList::new_checked(&bytes).expect("Writer output is valid");
    let mut memory = ListMemory::for_bands(&list).expect("within the pools' limits");
    let (c, table) = memory.band_parts();
    let mut band = vec![Rgb888::WHITE; rows as usize * width as usize];
    let mut out = Collect(Vec::new());
    c.with_resolve(mode)
        .render_bands(&list, table, rows, &mut band, &mut out)
        .expect("render");
    out.0.into_iter().map(index_of).collect()
}

/// How the library's picture compares with the reference's.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Mismatch {
    /// Pixels covered by the reference.
    pub covered: usize,
    /// Pixels where the library shows another `poly3` (or none, or one
    /// where the reference shows none).
    pub mismatched: usize,
    /// Intersecting spans the library resolved.
    pub intersecting: usize,
    /// Depth comparisons it made exactly (too close for fixed point).
    pub exact: usize,
}

impl Mismatch {
    /// Mismatched pixels per 1000 covered.
    pub fn per_mille(&self) -> f64 {
        if self.covered == 0 {
            0.0
        } else {
            1000.0 * self.mismatched as f64 / self.covered as f64
        }
    }
}

/// A pixel that differs: `(i, j, library's winner, reference's winner)`.
pub type Difference = (u32, u32, Option<usize>, Option<usize>);

/// Renders `polys` with `mode` and counts the pixels that differ from the
/// exact reference; returns the first few differences too, as
/// `(i, j, library, reference)`.
pub fn compare(
    polys: &[Poly3],
    width: u16,
    height: u16,
    mode: Resolve,
) -> (Mismatch, Vec<Difference>) {
    let (got, stats) = render3(polys, width, height, mode);
    let want = resolve(polys, width.into(), height.into());
    let mut m = Mismatch {
        intersecting: stats.visible.intersecting as usize,
        exact: stats.visible.exact as usize,
        ..Mismatch::default()
    };
    let mut first = Vec::new();
    for (n, (g, w)) in got.iter().zip(&want).enumerate() {
        m.covered += w.is_some() as usize;
        if g != w {
            m.mismatched += 1;
            if first.len() < 8 {
                let (i, j) = (n as u32 % width as u32, n as u32 / width as u32);
                first.push((i, j, *g, *w));
            }
        }
    }
    (m, first)
}
