//! A panel UI over a 3D view, sending only the rows that changed: what a
//! firmware engineer with a 240 × 240 SPI panel (an ST7789) and no room
//! for a frame buffer writes.
//!
//! One frame is a stack of layers, drawn band by band (16 rows, 7.5 KiB,
//! two pixels a word in the panel's byte order, ready for its DMA) by one
//! [`FramePass`] and shipped to the panel:
//!
//! 1. a display list's 2D UI: the background, a title bar and a toolbar;
//! 2. a 3D scene: a lit cube that turns, with hidden surfaces, and a HUD
//!    label on its corner;
//! 3. embedded-graphics drawables: the time as text in a large font, and
//!    a dot that moves along the toolbar.
//!
//! Nothing is marked by hand: `Scene::update_marking` marks the rows
//! whose content the turning cube changed, and each `DrawableLayer` marks
//! the rows of what changed in it. After every frame the panel (a host
//! model that keeps what it is sent) is compared with the frame rendered
//! whole into a frame buffer, layer by layer, with no bands.
//!
//! ```sh
//! cargo run --release --example ui_3d_panel [-- --out PANEL.ppm]
//! ```

use embedded_graphics::mono_font::{ascii::FONT_10X20, MonoTextStyle};
use embedded_graphics::prelude::{Point, Primitive};
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Styled};
use embedded_graphics::text::Text;
use embedded_graphics::Drawable;
use scanvert::display_list::Axis;
use scanvert::frame::{DrawableLayer, FramePass, PackedLayer};
use scanvert::pixelcolor::raw::RawU16;
use scanvert::port::band::DirtyRows;
use scanvert::port::packed_band::{PackedBand, PackedBandTarget};
use scanvert::prelude::*;
use scanvert::raster::table::{TableMemory, TablePolygon};
use scanvert::scene::{Capacities, DEFAULT_FONT};
use scanvert::{Angle, Builder, Light, Perspective, Pipeline, Point3, Procedure, Resolve, Scene};
use scanvert::{SceneError, View, Viewport, Q16};

const W: u16 = 240;
const H: u16 = 240;
const ROWS: u16 = 16;
const FRAMES: u32 = 24;
type Segment<'s, 'a> = Builder<'s, 'a, 4, 16>;
/// The scene's memory, by name.
const CAPS: Capacities = Capacities {
    trapezoids: 64,
    faces: 16,
    segments: 2,
    rows: H as usize,
    edges: 16,
    active: 32,
    runs: W as usize,
    labels: 2,
    text: 32,
};
type Storage = scanvert::scene_storage!(CAPS);

/// The panel: keeps the rows it is sent, and counts them.
struct Panel {
    pixels: Vec<Rgb565>,
    rows: u32,
}

impl PackedBandTarget for Panel {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    /// The words as the SPI bus would send them: their bytes in memory
    /// order, each pixel's two bytes big-endian.
    fn ship_words(&mut self, y: u16, rows: u16, w: u16, words: &[u32]) -> Result<(), Self::Error> {
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let at = y as usize * W as usize;
        let n = rows as usize * w as usize;
        for (i, p) in bytes.chunks_exact(2).take(n).enumerate() {
            self.pixels[at + i] = RawU16::new(u16::from_be_bytes([p[0], p[1]])).into();
        }
        self.rows += rows as u32;
        Ok(())
    }
}

/// The cube, turned by `turn` degrees about the vertical axis.
fn cube(b: &mut Segment<'_, '_>, turn: i32) -> Result<(), SceneError> {
    b.rotate(Axis::Y, Angle::from_degrees(turn))?;
    let p = Point3::from_int;
    for f in [
        [p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1)],
        [p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1)],
        [p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1)],
        [p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1)],
        [p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1)],
        [p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1)],
    ] {
        b.face(&f, Rgb888::new(0xe0, 0x50, 0x40))?;
    }
    b.label(p(1, 1, 1), "HUD: cube", Rgb888::WHITE).map(|_| ())
}

/// The 2D UI as a display list: a background, a title bar, a toolbar.
fn ui_list(bytes: &mut [u8]) -> DisplayList<'_> {
    let px = |x, y| Vertex::from_px(x, y).unwrap();
    let mut w = Writer::new(bytes, W, H).unwrap();
    w.clear(Rgb888::new(0x10, 0x18, 0x28)).unwrap();
    w.color(Rgb888::new(0x30, 0x40, 0x70)).unwrap();
    w.poly([px(0, 0), px(240, 0), px(240, 28), px(0, 28)])
        .unwrap();
    w.color(Rgb888::new(0x28, 0x30, 0x48)).unwrap();
    w.poly([px(8, 204), px(232, 204), px(224, 234), px(16, 234)])
        .unwrap();
    DisplayList::new_checked(w.finish()).unwrap()
}

/// The time, as a layer.
type Clock = DrawableLayer<Text<'static, MonoTextStyle<'static, Rgb565>>>;
/// The dot, as a layer.
type Dot = DrawableLayer<Styled<Circle, PrimitiveStyle<Rgb565>>>;

fn clock(frame: u32) -> Text<'static, MonoTextStyle<'static, Rgb565>> {
    const TIMES: [&str; 3] = ["12:00", "12:01", "12:02"];
    let style = MonoTextStyle::new(&FONT_10X20, Rgb565::WHITE);
    Text::new(TIMES[(frame / 10) as usize % 3], Point::new(8, 20), style)
}

fn dot(frame: u32) -> Styled<Circle, PrimitiveStyle<Rgb565>> {
    let x = 20 + (frame as i32 * 8) % 190;
    Circle::new(Point::new(x, 212), 14).into_styled(PrimitiveStyle::with_fill(Rgb565::GREEN))
}

// The drawing core: one frame through the layers, changed rows only.
fn draw_frame(
    list: &DisplayList<'_>,
    scene: &mut Scene<'_, 4, 16>,
    (clock, dot): (&mut Clock, &mut Dot),
    pass: &mut FramePass<Rgb565>,
    dirty: &mut DirtyRows<'_>,
    band: &mut [u32],
    panel: &mut Panel,
) -> Result<u32, Box<dyn std::error::Error>> {
    // The 2D layer: its polygons entered once into an edge table.
    let need = list.table_needs();
    let (mut polygons, mut index) = (
        vec![TablePolygon::EMPTY; need.polygons],
        vec![0; 2 * need.polygons],
    );
    let (mut table_edges, mut edges) = (vec![Edge::EMPTY; need.edges], [Edge::EMPTY; 8]);
    let table = TableMemory {
        polygons: &mut polygons,
        index: &mut index,
        edges: &mut table_edges,
        lines: &mut [],
    };
    let mut controller = Controller::new(Rasterizer::new(&mut edges));
    let mut ui = controller.bands(list, table)?;
    // The 3D layer over it: faces and the HUD label, no background.
    let mut view = scene.bands(Resolve::default(), Rgb565::BLACK, DEFAULT_FONT)?;
    let layers: &mut [&mut dyn PackedLayer<Rgb565>] = &mut [&mut ui, &mut view, clock, dot];
    Ok(pass.draw_marked_packed(layers, dirty, ROWS, band, panel)?)
}

/// The same frame rendered whole, layer by layer, into a frame buffer.
fn full_render(list: &DisplayList<'_>, scene: &mut Scene<'_, 4, 16>, frame: u32) -> Vec<Rgb565> {
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).unwrap();
    let mut edges = [Edge::EMPTY; 8];
    Controller::new(Rasterizer::new(&mut edges))
        .render(list, &mut fb)
        .unwrap();
    scene
        .draw(Resolve::default(), None, DEFAULT_FONT, &mut fb)
        .unwrap();
    clock(frame).draw(&mut fb).unwrap();
    dot(frame).draw(&mut fb).unwrap();
    px
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut bytes = [0u8; 128];
    let list = ui_list(&mut bytes);
    let mut storage = Box::new(Storage::new());
    let persp = Perspective::from_fov(
        Angle::from_degrees(50),
        W,
        Q16::from_int(1),
        Q16::from_int(100),
    )?;
    let mut pipeline = Pipeline::new(persp, Viewport::centred(W, H)?);
    pipeline.set_light(Light::new([1, 2, 3], 70)?);
    let mut scene = Scene::new(storage.as_memory(), pipeline)?;
    scene.set_view(&View::look_at(
        Point3::from_int(4, 3, 7),
        Point3::from_int(0, 0, 0),
    )?)?;
    let (mut clock_layer, mut dot_layer) =
        (DrawableLayer::new(clock(0)), DrawableLayer::new(dot(0)));
    let mut bits = [0u32; DirtyRows::words(H)];
    let mut dirty = DirtyRows::new(&mut bits, H).ok_or("bits")?;
    let mut scratch = vec![0u64; 2 * H as usize];
    let mut band = vec![0u32; PackedBand::<Rgb565>::words_len(W, ROWS)];
    let mut panel = Panel {
        pixels: vec![Rgb565::RED; W as usize * H as usize],
        rows: 0,
    };
    let (mut last, mut ratios) = (Vec::new(), Vec::new());
    // Kept from frame to frame: on the first, every row is sent.
    let mut pass = FramePass::new((W, H), Rgb565::BLACK);
    for frame in 0..FRAMES {
        // The application's changes: the cube turns, the clock and the dot.
        scene.invalidate(0)?;
        let mut turn = |b: &mut Segment<'_, '_>| cube(b, 9 * frame as i32);
        let procs: &mut [&mut dyn Procedure<4, 16>] = &mut [&mut turn];
        scene.update_marking(procs, DEFAULT_FONT, &mut dirty, &mut scratch)?;
        clock_layer.set(clock(frame));
        dot_layer.set(dot(frame));
        let sent = draw_frame(
            &list,
            &mut scene,
            (&mut clock_layer, &mut dot_layer),
            &mut pass,
            &mut dirty,
            &mut band,
            &mut panel,
        )?;
        let whole = full_render(&list, &mut scene, frame);
        assert!(panel.pixels == whole, "frame {frame}");
        // Rows whose pixels really changed since the last frame.
        let row = |f: &[Rgb565], y: usize| f[y * W as usize..(y + 1) * W as usize].to_vec();
        let changed = (0..H as usize)
            .filter(|&y| last.is_empty() || row(&last, y) != row(&whole, y))
            .count();
        println!("frame {frame:>2}: {sent:>3} rows sent, {changed:>3} changed");
        ratios.push(sent as f64 / changed.max(1) as f64);
        last = whole;
        dirty.clear();
    }
    println!("equal to full render: yes ({FRAMES} frames)");
    println!("rows sent: {} of {}", panel.rows, FRAMES * H as u32);
    // `--out FILE.ppm`: what the panel shows after the last frame.
    if let [_, flag, path] = std::env::args().collect::<Vec<_>>().as_slice() {
        if flag == "--out" {
            let mut ppm = format!("P6\n{W} {H}\n255\n").into_bytes();
            for c in &panel.pixels {
                let c = c.to_rgb888();
                ppm.extend([c.r(), c.g(), c.b()]);
            }
            std::fs::write(path, ppm)?;
        }
    }
    ratios.sort_by(f64::total_cmp);
    println!(
        "rows sent per row changed: median {:.2}, most {:.2}",
        ratios[ratios.len() / 2],
        ratios[ratios.len() - 1]
    );
    Ok(())
}
