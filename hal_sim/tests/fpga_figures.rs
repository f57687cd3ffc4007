//! The reference FPGA unit's own figures against the simulated write
//! port's cycle model (`dual_port`): its set-up calibrated on W1's 54,945
//! polygons/s (30 × 30 squares), 763 clears/s of 256 × 256 at one cycle a
//! pixel, both at 50 MHz; W4 and W3 predicted; the unit's measured 49.3
//! Mpixel/s against the model's.

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use scanvert::controller::Controller;
use scanvert::display_list::{Command, DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert_sim::cli::{self, Scene};
use scanvert_sim::dual_port::{
    CycleModel, DualPortRam, WriteCounters, POLYGON_SETUP_CYCLES, ROW_STEP_CYCLES, WRITE_PORT_CLOCK,
};
use scanvert_sim::refresh::{CoSimulation, RefreshController};
use scanvert_sim::timing::VideoTiming;
use std::path::Path;

/// W1 as the firmware image embeds it (and the benchmark generates it).
const W1: &[u8] = include_bytes!("../../firmware/image/scenes/w1.scvl");
/// W4 (W1's square rotated by 17°) and W3 (10,000 small triangles), as the
/// image embeds them.
const W4: &[u8] = include_bytes!("../../firmware/image/scenes/w4.scvl");
const W3: &[u8] = include_bytes!("../../firmware/image/scenes/w3.scvl");

/// The reference unit's figures.
const REFERENCE_POLYGONS_PER_SECOND: f64 = 54_945.0;
const REFERENCE_CLEARS_PER_SECOND: f64 = 763.0;
const REFERENCE_MPIXELS_PER_SECOND: f64 = 49.3;

fn counters(name: &str, list: &[u8]) -> WriteCounters {
    let scene = Scene::from_bytes(Path::new(name), list.to_vec()).expect("valid");
    cli::render_scene(&scene)
        .expect("render")
        .ram
        .write_counters()
}

/// W1 built here from its definition: a 30 × 30 square at `(k, k)` for
/// `k` in `0..226`, on 256 × 256.
fn w1(buf: &mut [u8], clear_first: bool) -> &[u8] {
    let mut w = Writer::new(buf, 256, 256).expect("header");
    if clear_first {
        w.clear(Rgb888::BLACK).expect("clear");
    }
    w.color(Rgb888::RED).expect("color");
    let px = |x: i16, y: i16| Vertex::from_bits(16 * x, 16 * y);
    for k in 0..226 {
        w.poly([px(k, k), px(k + 30, k), px(k + 30, k + 30), px(k, k + 30)])
            .expect("poly");
    }
    w.finish()
}

fn within(got: f64, want: f64, tolerance: f64) -> bool {
    (got - want).abs() <= tolerance * want
}

#[test]
fn the_embedded_w1_is_the_workload() {
    let mut buf = vec![0u8; 16 * 1024];
    let built = DisplayList::new_checked(w1(&mut buf, false)).expect("valid");
    let embedded = DisplayList::new_checked(W1).expect("valid");
    assert_eq!((embedded.width(), embedded.height()), (256, 256));
    let polys = |l: &DisplayList<'_>| -> Vec<Vec<Vertex>> {
        l.commands()
            .filter_map(|(_, c)| match c {
                Command::Poly(v) => Some(v.iter().collect()),
                _ => None,
            })
            .collect()
    };
    assert_eq!(polys(&embedded), polys(&built));
    assert_eq!(polys(&built).len(), 226);
}

#[test]
fn w1_gives_the_reference_polygon_rate() {
    let scene = Scene::from_bytes(Path::new("w1.scvl"), W1.to_vec()).expect("w1");
    let r = cli::render_scene(&scene).expect("render");
    let w = r.ram.write_counters();
    assert_eq!(w.clock, WRITE_PORT_CLOCK);
    // 900 pixel writes and the set-up a square: 910 cycles.
    assert_eq!((w.polygons, w.pixels_written), (226, 226 * 900));
    assert_eq!(w.cycles, 226 * (900 + POLYGON_SETUP_CYCLES));
    assert_eq!(w.cycles, 226 * 910);
    let rate = w.polygons_per_second().expect("polygons");
    assert!(
        within(rate, REFERENCE_POLYGONS_PER_SECOND, 0.005),
        "{rate} polygons/s"
    );
    // In fact to within a polygon a second: 50 MHz / 910 = 54,945.05.
    assert_eq!(rate.round(), REFERENCE_POLYGONS_PER_SECOND);
    // 20 ns a pixel while writing; the set-ups bring the mean down.
    let px = w.pixels_per_second().expect("pixels");
    assert_eq!(px.round(), (900.0 * 50e6 / 910.0_f64).round());
    assert_eq!(w.clears_per_second(), None);
}

#[test]
fn clears_of_256_square_give_the_reference_clear_rate() {
    // A list draws from its last clear on (the clears before it cannot
    // show), so each clear is a render of its own, into the same RAM.
    for clears in [1, 7, 60] {
        let mut ram = DualPortRam::new(256, 256);
        for i in 0..clears {
            let mut buf = vec![0u8; 1024];
            let mut wr = Writer::new(&mut buf, 256, 256).expect("header");
            wr.clear(if i % 2 == 0 {
                Rgb888::BLUE
            } else {
                Rgb888::BLACK
            })
            .expect("clear");
            let list = DisplayList::new_checked(wr.finish()).expect("valid");
            let mut edges = [Edge::EMPTY; 4];
            Controller::new(Rasterizer::new(&mut edges))
                .render(&list, &mut ram.write_port())
                .expect("render");
        }
        let w = ram.write_counters();
        assert_eq!((w.clears, w.clear_cycles), (clears, clears * 65_536));
        let rate = w.clears_per_second().expect("clears");
        // 50 MHz / 65,536 = 762.94.
        assert_eq!(rate.round(), REFERENCE_CLEARS_PER_SECOND, "{rate}");
        assert_eq!(w.polygons_per_second(), None);
        assert_eq!(w.pixels_per_second(), Some(50e6));
    }
}

#[test]
fn a_clear_does_not_count_against_the_polygon_rate() {
    // W1 after a clear: the same polygons/s, and the clear's own rate.
    let mut buf = vec![0u8; 16 * 1024];
    let with_clear = w1(&mut buf, true).to_vec();
    let scene = Scene::from_bytes(Path::new("w1c.scvl"), with_clear).expect("valid");
    let w = cli::render_scene(&scene)
        .expect("render")
        .ram
        .write_counters();
    assert_eq!(w.clears, 1);
    assert_eq!(w.cycles, 65_536 + 226 * 910);
    assert_eq!(w.polygons_per_second().map(f64::round), Some(54_945.0));
    assert_eq!(w.clears_per_second().map(f64::round), Some(763.0));
}

#[test]
fn the_set_ups_advance_the_co_simulation_too() {
    let list = DisplayList::new_checked(W1).expect("valid");
    let mut edges = [Edge::EMPTY; 4];
    let mut ram = DualPortRam::new(256, 256);
    let mut refresh = RefreshController::new(VideoTiming::TV_256X256);
    let mut co = CoSimulation::new(&mut ram, &mut refresh);
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut co)
        .expect("render");
    assert_eq!(co.cycles().0, 226 * 910);
}

#[test]
fn stats_report_the_rates() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fpga_figures");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (src, png) = (dir.join("w1.scvl"), dir.join("w1.png"));
    std::fs::write(&src, W1).expect("write list");
    let args: Vec<String> = [
        "render",
        src.to_str().expect("utf-8"),
        "--out",
        png.to_str().expect("utf-8"),
        "--stats",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let out = cli::run(&args).expect("render");
    // The existing line first, then the write port's.
    assert!(
        out.contains("256x256, 227 commands, 226 polygons, 6780 spans, 203400 pixels, 0 clears"),
        "{out}"
    );
    assert!(
        out.contains("write port at 50 MHz: 205660 cycles (226 polygon set-ups, 6780 spans, 0 cycles waiting for the edge stepper, 0 clear cycles), 4113.200 us simulated"),
        "{out}"
    );
    assert!(
        out.contains("write port model: 10 cycles a polygon's set-up (calibrated on W1's 54,945 polygons/s), 2 cycles a span for the edge stepper overlapped with the writes (assumed), 1 cycle a pixel"),
        "{out}"
    );
    assert!(
        out.contains("write port rates predicted by the model: "),
        "{out}"
    );
    assert!(out.contains("54945 polygons/s"), "{out}");
    assert!(out.contains("49450549 pixels/s"), "{out}");
    assert!(out.contains("n/a clears/s"), "{out}");
}

#[test]
fn w1_calibrates_the_set_up_to_the_reference_rate() {
    let w = counters("w1.scvl", W1);
    // 30 spans of 30 pixels a square: the writes never wait for the stepper.
    assert_eq!((w.spans, w.stepper_wait_cycles), (226 * 30, 0));
    let model = CycleModel::calibrate(ROW_STEP_CYCLES, &w, 54_945).expect("calibrates");
    assert_eq!(model, CycleModel::REFERENCE);
    assert_eq!(model.setup_cycles(), POLYGON_SETUP_CYCLES);
    // Whatever the stepper's time, W1 gives the same set-up: it cannot
    // see the stepper.
    for row in 1..=8 {
        let m = CycleModel::calibrate(row, &w, 54_945).expect("calibrates");
        assert_eq!(m.setup_cycles(), 10, "stepper of {row}");
    }
    // A stepper that held the writes a cycle a span: the writes and those
    // cycles alone take longer than the reference unit's time for W1
    // (930 against 910 cycles a square), so no set-up can make it.
    let held = w.pixels_written + w.spans;
    let reference = u64::from(WRITE_PORT_CLOCK.hz()) * w.polygons / 54_945;
    assert_eq!((held / w.polygons, reference / w.polygons), (930, 910));
    assert!(held > reference);
}

#[test]
fn w4_and_w3_are_predicted_not_copied() {
    let w1 = counters("w1.scvl", W1);
    let w4 = counters("w4.scvl", W4);
    let w3 = counters("w3.scvl", W3);
    let rate = |w: &WriteCounters| w.polygons_per_second().expect("polygons");
    let mpx = |w: &WriteCounters| w.pixels_per_second().expect("pixels") / 1e6;
    // W4: as many pixels a square as W1, more rows, a wait for the
    // stepper at the 1-pixel spans of its corners: a lower rate.
    assert_eq!((w4.polygons, w4.pixels_written), (218, 218 * 900));
    assert!(w4.spans > w4.polygons * 30);
    assert!(w4.stepper_wait_cycles > 0);
    assert!(rate(&w4) < rate(&w1), "{} {}", rate(&w4), rate(&w1));
    assert_eq!(rate(&w4).round(), 54_825.0);
    // W3: short spans, many waits; its fill rate well below W1's.
    assert!(w3.stepper_wait_cycles > 10 * w4.stepper_wait_cycles);
    assert!(mpx(&w3) < mpx(&w4) && mpx(&w4) < mpx(&w1));
    assert_eq!(rate(&w3).round(), 371_118.0);
    // A stepper of 1 cycle (the writes never wait for it) makes W4 W1's
    // copy; one of 4 lowers it further.
    let re = |w: &WriteCounters, row| {
        let m = CycleModel::calibrate(row, &w1, 54_945).expect("calibrates");
        w.polygons as f64 * 50e6 / m.cycles(w) as f64
    };
    assert_eq!(re(&w4, 1).round(), 54_945.0);
    assert!(re(&w4, 4) < rate(&w4));
}

#[test]
fn the_reference_units_measured_fill_rate_against_the_model() {
    let w = counters("w1.scvl", W1);
    let model = w.pixels_per_second().expect("pixels") / 1e6;
    // The model: 900 pixels in 910 cycles at 50 MHz.
    assert_eq!((model * 100.0).round(), 4945.0);
    // The unit's own 49.3 Mpixel/s is 0.3 % below: 912.8 cycles a square.
    let short = 1.0 - REFERENCE_MPIXELS_PER_SECOND / model;
    assert!((0.0025..0.0035).contains(&short), "{short}");
    let cycles = 900.0 * 50.0 / REFERENCE_MPIXELS_PER_SECOND;
    assert_eq!((cycles * 10.0).round(), 9128.0);
    // And the module docs say so.
    let docs = include_str!("../src/dual_port.rs");
    for said in [
        "49.3 Mpixel/s, is 0.3 %",
        "the model's 49.45 Mpixel/s on W1",
        "912.8 cycles, 2.8 more than the model",
    ] {
        assert!(docs.contains(said), "{said}");
    }
}
