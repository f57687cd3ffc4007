//! Double buffering against tearing: the graphic controller and the
//! refresh controller run at once ([`CoSimulation`]), the controller
//! alternating two renders. Single-buffered, the monitor sees frames that
//! mix two renders; double-buffered, every frame is one whole render.

use embedded_graphics_core::pixelcolor::{Rgb565, Rgb888, RgbColor};
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert_sim::dual_port::DualPortRam;
use scanvert_sim::refresh::{CoSimulation, Frame, RefreshController};
use scanvert_sim::timing::VideoTiming;

const W: u16 = 64;
const H: u16 = 48;
/// Renders per run.
const RENDERS: usize = 16;
/// Write-port cycles the controller idles after each render: not a
/// multiple of the frame, so renders drift across the frame.
const PAUSE: u64 = 1_777;

fn px(x: i16, y: i16) -> Vertex {
    Vertex::from_bits(x * 16, y * 16)
}

/// Two scenes that differ at every pixel.
fn scenes<'b>(a: &'b mut [u8], b: &'b mut [u8]) -> [DisplayList<'b>; 2] {
    let mut la = Writer::new(a, W, H).unwrap();
    la.clear(Rgb888::RED).unwrap();
    la.color(Rgb888::WHITE).unwrap();
    la.poly([px(0, 0), px(60, 4), px(8, 44)]).unwrap();
    let mut lb = Writer::new(b, W, H).unwrap();
    lb.clear(Rgb888::BLUE).unwrap();
    lb.color(Rgb888::GREEN).unwrap();
    lb.poly([px(10, 10), px(70, 20), px(50, 50), px(-5, 40)])
        .unwrap();
    let lists = [
        DisplayList::new_checked(la.finish()).unwrap(),
        DisplayList::new_checked(lb.finish()).unwrap(),
    ];
    let refs = lists.each_ref().map(reference);
    assert!(refs[0].iter().zip(&refs[1]).all(|(p, q)| p != q));
    lists
}

fn reference(list: &DisplayList<'_>) -> Vec<Rgb565> {
    let mut pixels = vec![Rgb565::BLACK; W as usize * H as usize];
    let mut fb = FrameBuffer::new(&mut pixels, W, H).unwrap();
    let mut edges = [Edge::EMPTY; 8];
    Controller::new(Rasterizer::new(&mut edges))
        .render(list, &mut fb)
        .unwrap();
    pixels
}

/// Runs `RENDERS` alternating renders against the refresh controller and
/// returns the frames the monitor saw that began after the first render
/// was complete (and, double-buffered, swapped in).
fn run(mut ram: DualPortRam, lists: &[DisplayList<'_>; 2]) -> Vec<Frame> {
    let mut refresh = RefreshController::new(VideoTiming::for_frame(W, H));
    let mut co = CoSimulation::new(&mut ram, &mut refresh);
    let mut edges = [Edge::EMPTY; 8];
    let mut controller = Controller::new(Rasterizer::new(&mut edges));
    let mut first_complete = None;
    for i in 0..RENDERS {
        controller.render(&lists[i % 2], &mut co).unwrap();
        co.request_swap();
        co.wait_for_swap();
        // The frame in progress still shows (part of) the power-on black.
        first_complete.get_or_insert(co.frames().len() + 1);
        co.wait(PAUSE);
    }
    co.wait_for_frame();
    let frames = co.into_frames();
    assert!(frames.len() > RENDERS / 2, "{} frames", frames.len());
    frames[first_complete.unwrap_or(0)..].to_vec()
}

#[test]
fn single_buffered_frames_can_mix_two_renders() {
    let (mut a, mut b) = ([0u8; 128], [0u8; 128]);
    let lists = scenes(&mut a, &mut b);
    let refs = lists.each_ref().map(reference);
    let frames = run(DualPortRam::new(W, H), &lists);
    // The scenes differ at every pixel: a frame showing some pixels of
    // each mixes the two renders.
    let shows = |f: &Frame, r: &[Rgb565]| f.pixels().iter().zip(r).any(|(p, q)| p == q);
    let torn = frames
        .iter()
        .filter(|f| shows(f, &refs[0]) && shows(f, &refs[1]))
        .count();
    assert!(torn > 0, "no torn frame in {}", frames.len());
    eprintln!("{torn} of {} frames torn", frames.len());
    assert!(frames.iter().all(|f| f.counters().bank_swaps == 0));
}

#[test]
fn double_buffered_frames_are_whole_renders() {
    let (mut a, mut b) = ([0u8; 128], [0u8; 128]);
    let lists = scenes(&mut a, &mut b);
    let refs = lists.each_ref().map(reference);
    let frames = run(DualPortRam::double_buffered(W, H), &lists);
    let mut seen = [0usize; 2];
    for (n, f) in frames.iter().enumerate() {
        let which = refs.iter().position(|r| f.pixels() == r.as_slice());
        let which = which.unwrap_or_else(|| panic!("frame {n} mixes renders"));
        seen[which] += 1;
    }
    assert!(seen[0] > 0 && seen[1] > 0, "{seen:?}");
    eprintln!("{} frames, whole renders {seen:?}", frames.len());
    // Every render but the first was swapped in during the retrace of one
    // of these frames (the first one's swap ended the frame before).
    let swaps: u64 = frames.iter().map(|f| f.counters().bank_swaps).sum();
    assert_eq!(swaps, RENDERS as u64 - 1);
}
