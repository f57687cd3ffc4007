//! The simulated display hardware against the figures of its video modes,
//! and the read port against the write port.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::color::ToRgb888;
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::clip::ClipWindow;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert_sim::dual_port::DualPortRam;
use scanvert_sim::image;
use scanvert_sim::refresh::RefreshController;
use scanvert_sim::timing::VideoTiming;
use testkit::rng::Rng;

/// A mode and the figures it must have.
struct Figures {
    timing: VideoTiming,
    clocks_per_line: u32,
    lines_per_frame: u32,
    line_period_ps: u64,
    frame_period_ps: u64,
    refresh_millihertz: u64,
}

const FIGURES: [Figures; 3] = [
    // 25 MHz; 25.6 µs + 6.4 µs = 32 µs per line; 480 + 41 lines = 16.672 ms.
    Figures {
        timing: VideoTiming::REFERENCE_640X480,
        clocks_per_line: 800,
        lines_per_frame: 521,
        line_period_ps: 32_000_000,
        frame_period_ps: 16_672_000_000,
        refresh_millihertz: 59_981,
    },
    // 5 MHz; 320 clocks = 64 µs per line; 312 lines = 19.968 ms.
    Figures {
        timing: VideoTiming::TV_256X256,
        clocks_per_line: 320,
        lines_per_frame: 312,
        line_period_ps: 64_000_000,
        frame_period_ps: 19_968_000_000,
        refresh_millihertz: 50_080,
    },
    // 25.175 MHz; 800 clocks = 31.777 557 µs; 525 lines = 16.683 217 478 ms.
    Figures {
        timing: VideoTiming::VGA_640X480_60,
        clocks_per_line: 800,
        lines_per_frame: 525,
        line_period_ps: 31_777_557,
        frame_period_ps: 16_683_217_478,
        refresh_millihertz: 59_940,
    },
];

#[test]
fn presets_have_their_periods() {
    for f in &FIGURES {
        let t = &f.timing;
        assert_eq!(t.clocks_per_line(), f.clocks_per_line, "{t}");
        assert_eq!(t.lines_per_frame(), f.lines_per_frame, "{t}");
        assert_eq!(
            t.clocks_per_frame(),
            f.clocks_per_line as u64 * f.lines_per_frame as u64
        );
        assert_eq!(t.line_period_ps(), f.line_period_ps, "{t}");
        assert_eq!(t.frame_period_ps(), f.frame_period_ps, "{t}");
        assert_eq!(t.refresh_rate_millihertz(), f.refresh_millihertz, "{t}");
    }
    let r = VideoTiming::REFERENCE_640X480;
    assert_eq!(
        (r.horizontal().blanking(), r.vertical().blanking()),
        (160, 41)
    );
    assert_eq!(r.line_rate_hz(), 31_250);
    assert!((r.frame_period_ms() - 16.672).abs() < 1e-9);
}

#[test]
fn one_frame_has_its_sync_pulses_reads_and_clocks() {
    for f in &FIGURES {
        let t = f.timing;
        let mut ram = DualPortRam::new(t.width(), t.height());
        let frame = RefreshController::new(t).read_frame(&mut ram);
        let n = frame.counters();
        assert_eq!(n.clocks, t.clocks_per_frame(), "{t}");
        assert_eq!(n.lines, f.lines_per_frame as u64, "{t}");
        assert_eq!(n.hsync_pulses, f.lines_per_frame as u64, "{t}");
        assert_eq!(n.vsync_pulses, 1, "{t}");
        let area = t.width() as u64 * t.height() as u64;
        assert_eq!(n.pixels_read, area, "{t}");
        assert_eq!((frame.width(), frame.height()), (t.width(), t.height()));
        // The read port ran on the pixel clock for exactly one frame.
        let r = ram.read_counters();
        assert_eq!(
            (r.cycles, r.pixels_read, r.missed_reads),
            (n.clocks, area, 0)
        );
        assert_eq!(r.clock, t.pixel_clock());
        assert_eq!(r.time_ps(), f.frame_period_ps, "{t}");
        // Power-on black.
        assert!(frame.pixels().iter().all(|&p| p == Rgb565::BLACK));
    }
}

/// A coordinate in sixteenths, up to a quarter of `side` outside it.
fn coord(rng: &mut Rng, side: u16) -> i16 {
    let span = side as i32 * 16 * 3 / 2;
    rng.below(span as u32) as i16 - (side as i32 * 4) as i16
}

/// A list for a `w × h` frame: a clear, random polygons of 3 to 8
/// vertices (many reaching outside the frame), a clip window.
fn scene(buf: &mut [u8], w: u16, h: u16, seed: u32) -> &[u8] {
    let mut rng = Rng(seed as u64);
    let mut list = Writer::new(buf, w, h).unwrap();
    list.clear(Rgb888::new(0x20, 0x40, 0x80)).unwrap();
    for i in 0..40 {
        let c = rng.next_u64() as u32;
        list.color(Rgb888::new(c as u8, (c >> 8) as u8, (c >> 16) as u8))
            .unwrap();
        if i == 20 {
            let clip = ClipWindow {
                x0: (w / 5) as i16,
                y0: (h / 6) as i16,
                x1: (w - w / 7) as i16,
                y1: (h + 10) as i16,
            };
            list.clip(clip).unwrap();
        }
        let n = 3 + rng.below(6) as usize;
        let vs: Vec<Vertex> = (0..n)
            .map(|_| Vertex::from_bits(coord(&mut rng, w), coord(&mut rng, h)))
            .collect();
        list.poly(vs).unwrap();
    }
    list.finish()
}

fn check_read_out_equals_reference(w: u16, h: u16, seed: u32) {
    let mut buf = vec![0u8; 8192];
    let bytes = scene(&mut buf, w, h, seed);
    let list = DisplayList::new_checked(bytes).unwrap();
    let mut edges = [Edge::EMPTY; 16];

    // Through the simulated hardware.
    let mut ram = DualPortRam::new(w, h);
    let stats = Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut ram.write_port())
        .unwrap();
    let frame = RefreshController::new(VideoTiming::for_frame(w, h)).read_frame(&mut ram);

    // Into plain memory.
    let mut pixels = vec![Rgb565::BLACK; FrameBuffer::<Rgb565>::buffer_len(w, h)];
    let mut fb = FrameBuffer::new(&mut pixels, w, h).unwrap();
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut fb)
        .unwrap();

    assert_eq!((frame.width(), frame.height()), (w, h));
    for y in 0..h {
        for x in 0..w {
            assert_eq!(
                frame.pixel(x, y),
                fb.pixel(x, y),
                "pixel ({x}, {y}) of {w}×{h}"
            );
        }
    }
    assert_eq!(
        frame.checksum(),
        scanvert::port::checksum::frame_checksum(fb.pixels())
    );
    let wc = ram.write_counters();
    assert_eq!(wc.clears, 1);
    assert_eq!(
        wc.pixels_written,
        w as u64 * h as u64 + stats.pixels,
        "clear plus the polygons' pixels"
    );
    assert!(stats.polygons == 40 && stats.pixels > 0);

    // And the PNG shows the same, expanded by bit replication.
    let (pw, ph, rgb) = image::decode_png(&image::encode_png(&frame).unwrap()).unwrap();
    assert_eq!((pw, ph), (w as u32, h as u32));
    let expected: Vec<u8> = fb
        .pixels()
        .iter()
        .flat_map(|p| {
            let c = p.to_rgb888();
            [c.r(), c.g(), c.b()]
        })
        .collect();
    assert!(rgb == expected, "PNG differs from the frame buffer");
}

#[test]
fn read_port_shows_what_the_write_port_wrote_reference_640x480() {
    check_read_out_equals_reference(640, 480, 1);
}

#[test]
fn read_port_shows_what_the_write_port_wrote_tv_256x256() {
    check_read_out_equals_reference(256, 256, 2);
}

#[test]
fn read_port_shows_what_the_write_port_wrote_custom_sizes() {
    for (w, h, seed) in [(100, 37, 3), (1, 1, 4), (3, 200, 5), (333, 2, 6)] {
        check_read_out_equals_reference(w, h, seed);
    }
}

#[test]
fn png_file_round_trips() {
    let mut ram = DualPortRam::new(7, 5);
    let mut buf = [0u8; 64];
    let mut list = Writer::new(&mut buf, 7, 5).unwrap();
    list.clear(Rgb888::new(0xff, 0x00, 0x80)).unwrap();
    let list = DisplayList::new_checked(list.finish()).unwrap();
    let mut edges = [Edge::EMPTY; 4];
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut ram.write_port())
        .unwrap();
    let frame = RefreshController::new(VideoTiming::for_frame(7, 5)).read_frame(&mut ram);
    let path = std::env::temp_dir().join(format!("scanvert-sim-{}.png", std::process::id()));
    image::write_png(&path, &frame).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let _ = std::fs::remove_file(&path);
    let (w, h, rgb) = image::decode_png(&bytes).unwrap();
    assert_eq!((w, h, rgb.len()), (7, 5, 7 * 5 * 3));
    // 0x80 → 5 bits 0b10000 → replicated 0x84; 0xff and 0x00 exact.
    assert!(rgb.chunks(3).all(|p| p == [0xff, 0x00, 0x84]));
}
