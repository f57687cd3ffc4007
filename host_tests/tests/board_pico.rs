//! The Pico board's rendering core (`firmware/boards/pico-st7789/src/ui.rs`,
//! the very file the firmware builds) drawn into a model of the panel that
//! keeps what it is sent: after every frame, the panel equals the frame
//! rendered whole into a frame buffer, layer by layer, with no bands.

#[path = "../../firmware/boards/pico-st7789/src/ui.rs"]
#[allow(dead_code)]
mod ui;

use embedded_graphics::Drawable;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use scanvert::port::packed_band::PackedBandTarget;
use scanvert::prelude::*;
use scanvert::scene::DEFAULT_FONT;
use scanvert::Resolve;
use ui::{Memory, Ui, H, W};

/// The panel: keeps the rows it is sent, and counts them.
struct Panel {
    pixels: Vec<Rgb565>,
    rows: u32,
}

impl PackedBandTarget for Panel {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn ship_words(&mut self, y: u16, rows: u16, w: u16, words: &[u32]) -> Result<(), Self::Error> {
        // Wire order: each pixel's two bytes big-endian, from the start.
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let n = rows as usize * w as usize;
        let at = y as usize * W as usize;
        for (i, p) in bytes.chunks_exact(2).take(n).enumerate() {
            let raw = u16::from_be_bytes([p[0], p[1]]);
            self.pixels[at + i] =
                Rgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(raw));
        }
        self.rows += rows as u32;
        Ok(())
    }
}

/// Frame `frame` rendered whole, layer by layer, into a frame buffer.
fn full_render(frame: u32) -> Vec<Rgb565> {
    let mut bytes = [0u8; 128];
    let list = ui::ui_list(&mut bytes).expect("list");
    let mut px = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut px, W, H).expect("frame");
    let mut edges = [Edge::EMPTY; 8];
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut fb)
        .expect("2D");
    // The scene as the core builds it, at this frame's turn.
    let mut mem = Box::new(Memory::new());
    let mut core = Ui::new(&mut mem).expect("core");
    let mut sink = Panel {
        pixels: vec![Rgb565::BLACK; W as usize * H as usize],
        rows: 0,
    };
    for _ in 0..=frame {
        core.step(&mut sink).expect("frame");
    }
    core.scene()
        .draw(Resolve::default(), None, DEFAULT_FONT, &mut fb)
        .expect("3D");
    ui::clock(frame).draw(&mut fb).expect("clock");
    ui::dot(frame).draw(&mut fb).expect("dot");
    px
}

#[test]
fn the_panel_equals_a_full_render_every_frame() {
    let mut mem = Box::new(Memory::new());
    let mut core = Ui::new(&mut mem).expect("core");
    let mut panel = Panel {
        pixels: vec![Rgb565::RED; W as usize * H as usize],
        rows: 0,
    };
    let frames = 12;
    for frame in 0..frames {
        let sent = core.step(&mut panel).expect("frame");
        assert!(sent > 0 && sent <= H as u32, "frame {frame}: {sent} rows");
        assert!(panel.pixels == full_render(frame), "frame {frame}");
    }
    // The first frame sends every row; the others send what changed.
    assert!(
        panel.rows < frames * H as u32 * 6 / 10,
        "{} rows",
        panel.rows
    );
}
