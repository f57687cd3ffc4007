//! Band rendering against the full-frame render of the same frame, in one
//! run: W3 (10 000 triangles) and the two `poly3` lists of the firmware
//! image through the controller, and the 3D demo scene through
//! `Scene::draw_bands`; then the demo's bands drawn by two threads
//! (every other band each, a top and a bottom part split where their times
//! are equal, or bands claimed from a shared counter) against one thread,
//! with a calibration loop on one and two threads in the same timing,
//! which says what the host's two cores give at that moment.
//! `--only bands`.
//!
//! The full frame is rendered into a frame buffer; the bands into one
//! band buffer, each band handed to a provider that only reads it (the
//! panel's link is not counted). Both include the frame's preparation
//! (the list checked, its 3D layer built; for bands, the edge table).

use crate::time_fns;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use scanvert::display_list::DisplayList;
use scanvert::port::band::BandTarget;
use scanvert::port::framebuffer::FrameBuffer;
use scanvert::scene::{Scene, DEFAULT_FONT};
use scanvert::visible::rle::Run;
use scanvert::visible::sweep::{Active, Resolve, Workspace};
use scanvert_sim::memory::ListMemory;
use std::fmt::Write as _;
use std::hint::black_box;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc;
use std::time::Duration;

/// Band heights measured.
const HEIGHTS: [u16; 4] = [1, 8, 16, 64];

/// A provider that reads the band and drops it.
struct Drop;

impl BandTarget for Drop {
    type Color = Rgb565;
    type Error = core::convert::Infallible;
    fn ship(&mut self, _: u16, _: u16, px: &[Rgb565]) -> Result<(), Self::Error> {
        black_box(px);
        Ok(())
    }
}

/// The full frame (`None`) or bands of `rows` of `list`, in memory sized
/// from it ([`ListMemory::for_bands`]), its 3D layer resolved by `mode`.
fn render(
    m: &mut ListMemory,
    list: &DisplayList<'_>,
    fb: &mut [Rgb565],
    band: Option<u16>,
    mode: Resolve,
) {
    let (w, h) = (list.width(), list.height());
    match band {
        None => {
            let mut f = FrameBuffer::new(fb, w, h).expect("frame");
            let mut c = m.controller().with_resolve(mode);
            c.render(list, &mut f).expect("renders");
        }
        Some(rows) => {
            let (c, table) = m.band_parts();
            let mut c = c.with_resolve(mode);
            let n = rows as usize * w as usize;
            c.render_bands(list, table, rows, &mut fb[..n], &mut Drop)
                .expect("renders");
        }
    }
}

/// Times the full frame and the band heights of one list, its 3D layer
/// resolved by `mode`: ms per frame.
fn list_times(bytes: &[u8], mode: Resolve) -> (f64, Vec<f64>) {
    let list = DisplayList::new_checked(bytes).expect("list");
    let mut mem = ListMemory::for_bands(&list).expect("the list's 3D layer runs");
    let mut fb = vec![Rgb565::BLACK; list.width() as usize * list.height() as usize];
    let cell = std::cell::RefCell::new((&mut mem, &mut fb));
    let mut fs: Vec<Box<dyn FnMut() + '_>> = Vec::new();
    for band in std::iter::once(None).chain(HEIGHTS.map(Some)) {
        let cell = &cell;
        let list = &list;
        fs.push(Box::new(move || {
            let mut g = cell.borrow_mut();
            let (m, f) = &mut *g;
            render(m, black_box(list), f, band, mode);
        }));
    }
    let t = time_fns(&mut fs, LIST_RUN, LIST_ROUNDS);
    (t[0] * 1e3, t[1..].iter().map(|s| s * 1e3).collect())
}

/// The visible-surface memory of one worker on the demo.
struct Work {
    active: Vec<Active>,
    runs: Vec<Run>,
}

impl Work {
    /// A workspace for a scene with at most `most` trapezoids on a row
    /// (`Scene::check`).
    fn new(most: usize) -> Work {
        Work {
            active: vec![Active::EMPTY; most],
            runs: vec![Run::EMPTY; scanvert_sim::demo::WIDTH as usize],
        }
    }
    fn workspace(&mut self) -> Workspace<'_> {
        Workspace::new(&mut self.active, &mut self.runs)
    }
}

/// Rows of a band in the two-thread measurement.
const ROWS2: u16 = 16;

/// How two workers share the bands of a frame.
#[derive(Clone, Copy, Debug)]
enum Share {
    /// Every other band of [`ROWS2`] rows, from band `k` (0 or 1).
    Alternate(u16),
    /// The rows above `row` (`first`) or the others, in bands of
    /// [`ROWS2`] rows from the first of them.
    Split { row: u16, first: bool },
}

/// `frames` frames of `scene` in bands of at most [`ROWS2`] rows: each
/// frame one pass in `work`'s workspace, drawing the bands `share` takes
/// (`None`: all) into `band` and stepping over the other rows.
fn frames<const D: usize, const M: usize>(
    scene: &Scene<'_, D, M>,
    bg: Rgb565,
    share: Option<Share>,
    frames: u32,
    work: &mut Work,
    band: &mut [Rgb565],
) {
    use scanvert_sim::demo::HEIGHT;
    let (first, last, step) = match share {
        None => (0, HEIGHT, ROWS2),
        Some(Share::Alternate(k)) => (k * ROWS2, HEIGHT, 2 * ROWS2),
        Some(Share::Split { row, first: true }) => (0, row, ROWS2),
        Some(Share::Split { row, first: false }) => (row, HEIGHT, ROWS2),
    };
    let mut ws = work.workspace();
    for _ in 0..frames {
        let mut pass = scene
            .bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT)
            .expect("pass");
        let mut y = first;
        while y < last {
            pass.draw(y, ROWS2.min(last - y), band).expect("band");
            black_box(&band);
            y += step;
        }
    }
}

/// `frames` frames of `scene` in bands of [`ROWS2`], the bands claimed
/// one at a time from `next` (an index over all the frames' bands, shared
/// with the other worker): a pass per frame, each band claimed drawn and
/// the others stepped over. Returns the bands drawn.
fn claimed<const D: usize, const M: usize>(
    scene: &Scene<'_, D, M>,
    bg: Rgb565,
    next: &AtomicU32,
    frames: u32,
    work: &mut Work,
    band: &mut [Rgb565],
) -> u32 {
    use scanvert_sim::demo::HEIGHT;
    let per = HEIGHT.div_ceil(ROWS2) as u32;
    let total = frames * per;
    let mut ws = work.workspace();
    let mut i = next.fetch_add(1, Ordering::Relaxed);
    let mut drawn = 0;
    while i < total {
        let frame = i / per;
        let mut pass = scene
            .bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT)
            .expect("pass");
        while i < total && i / per == frame {
            pass.draw((i % per) as u16 * ROWS2, ROWS2, band)
                .expect("band");
            black_box(&band);
            drawn += 1;
            i = next.fetch_add(1, Ordering::Relaxed);
        }
    }
    drawn
}

/// A value alone on its cache line (128 bytes: two lines are fetched
/// together on this host).
#[repr(align(128))]
struct Line<T>(T);

/// The calibration: `n` steps of a multiply-add chain, all in registers.
fn spin(n: u64) -> u64 {
    let mut x = 1u64;
    for i in 0..black_box(n) {
        x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(i);
    }
    x
}

/// What the second thread is asked to do.
enum Task {
    /// [`spin`] this many steps.
    Spin(u64),
    /// Its share of `frames` frames.
    Frames(Share, u32),
    /// Bands claimed from the shared counter, over this many frames.
    Claim(u32),
    /// Every band of this many frames of its own.
    Whole(u32),
}

/// The two-thread figures of one run, ms per frame (the calibration: ms
/// per call).
#[derive(Debug)]
struct Threads {
    /// One thread, every band, one pass a frame.
    one: f64,
    /// Two threads, every other band each.
    alternate: f64,
    /// Two threads, the bands above `at` and the others.
    halves: f64,
    /// The row the halves split at (the balanced split).
    row: u16,
    /// Two threads, bands claimed from a shared counter.
    claim: f64,
    /// The calibration loop on one thread and split over two.
    spin: (f64, f64),
    /// Two threads, each drawing every band of its own frames: ms per
    /// frame of each.
    whole: f64,
}

/// Frames per timed call in the two-thread measurement: the second
/// thread is woken once a call.
const FRAMES2: u32 = 5;
/// Timed calls of each, round-robin, in the two-thread measurement.
const CALLS: usize = 3000;

/// The best seconds of one call of each of `fs`, over `calls` calls of
/// each, round-robin: on a host other work shares, the calls that ran
/// with both cores free.
fn best_calls(fs: &mut [Box<dyn FnMut() + '_>], calls: usize) -> Vec<f64> {
    let mut best = vec![f64::INFINITY; fs.len()];
    for f in fs.iter_mut() {
        f();
    }
    for _ in 0..calls {
        for (b, f) in best.iter_mut().zip(fs.iter_mut()) {
            let t = std::time::Instant::now();
            f();
            *b = b.min(t.elapsed().as_secs_f64());
        }
    }
    best
}
/// Each frame's heights are timed in runs of this long, the same call
/// again and again (so the full frame's buffer stays as warm as the band
/// buffer)...
const LIST_RUN: Duration = Duration::from_millis(10);
/// ... round-robin, this many times: the best run of each is one no other
/// work on the host interrupted.
const LIST_ROUNDS: usize = 60;

/// Steps of the calibration loop per timed call.
const SPIN: u64 = 2_000_000;

/// The row (a multiple of 4) that splits the frame into a top and a
/// bottom part of about the same time: each part drawn alone (the bottom
/// one stepping over the top's rows) on this thread, best of a few
/// frames, for every such row.
fn balanced_split<const D: usize, const M: usize>(
    scene: &Scene<'_, D, M>,
    bg: Rgb565,
    work: &mut Work,
    band: &mut [Rgb565],
) -> u16 {
    use scanvert_sim::demo::HEIGHT;
    let rows: Vec<u16> = (4..HEIGHT).step_by(4).collect();
    // The best time of each part at each split, over six sweeps of the
    // splits, so that a moment of load on one of them does not move it.
    let mut parts = vec![(f64::INFINITY, f64::INFINITY); rows.len()];
    for _ in 0..6 {
        for (p, &row) in parts.iter_mut().zip(&rows) {
            let mut part = |first| {
                let mut t = f64::INFINITY;
                for _ in 0..15 {
                    let s = std::time::Instant::now();
                    frames(scene, bg, Some(Share::Split { row, first }), 1, work, band);
                    t = t.min(s.elapsed().as_secs_f64());
                }
                t
            };
            *p = (p.0.min(part(true)), p.1.min(part(false)));
        }
    }
    let slower = |p: &(f64, f64)| p.0.max(p.1);
    rows.iter()
        .zip(&parts)
        .min_by(|a, b| slower(a.1).total_cmp(&slower(b.1)))
        .map_or(HEIGHT / 2, |(&row, _)| row)
}

/// The demo's first frame in 16-row bands on one and two threads, and the
/// calibration loop on one and two, round-robin in one timing.
fn thread_times() -> Threads {
    use scanvert_sim::demo::{steps, with_scene, WIDTH};
    let step = steps(1)[0];
    with_scene(step, |scene, bg| {
        let w = WIDTH as usize;
        let most = scene.check().expect("the scene fits its workspace") as usize;
        // Each band buffer and workspace its thread's own, made once.
        let mut mine = (Work::new(most), vec![Rgb565::BLACK; ROWS2 as usize * w]);
        let row = balanced_split(scene, bg, &mut mine.0, &mut mine.1);
        // The counter on a cache line of its own.
        let next = Line(AtomicU32::new(0));
        let scene: &Scene<'_, _, _> = scene;
        let (go, tasks) = mpsc::channel::<Task>();
        let (done, finished) = mpsc::channel::<u64>();
        std::thread::scope(|s| {
            let next = &next.0;
            s.spawn(move || {
                let mut work = Work::new(most);
                let mut band = vec![Rgb565::BLACK; ROWS2 as usize * w];
                while let Ok(t) = tasks.recv() {
                    let r = match t {
                        Task::Spin(n) => spin(n),
                        Task::Frames(share, n) => {
                            frames(scene, bg, Some(share), n, &mut work, &mut band);
                            0
                        }
                        Task::Claim(n) => claimed(scene, bg, next, n, &mut work, &mut band) as u64,
                        Task::Whole(n) => {
                            frames(scene, bg, None, n, &mut work, &mut band);
                            0
                        }
                    };
                    done.send(r).expect("the timing thread waits");
                }
            });
            let mine = std::cell::RefCell::new(&mut mine);
            let other_bands = std::cell::Cell::new((0u64, 0u64));
            let both = |task: Task, own: &mut dyn FnMut() -> u64| {
                go.send(task).expect("the second thread runs");
                let a = own();
                let b = finished.recv().expect("the second thread answers");
                black_box((a, b))
            };
            let mut fs: Vec<Box<dyn FnMut() + '_>> = Vec::new();
            fs.push(Box::new(|| {
                let mut g = mine.borrow_mut();
                let (wk, band) = &mut **g;
                frames(scene, bg, None, FRAMES2, wk, band);
            }));
            for (a, b) in [
                (Share::Alternate(0), Share::Alternate(1)),
                (
                    Share::Split { row, first: true },
                    Share::Split { row, first: false },
                ),
            ] {
                let mine = &mine;
                let both = &both;
                fs.push(Box::new(move || {
                    let mut g = mine.borrow_mut();
                    let (wk, band) = &mut **g;
                    both(Task::Frames(b, FRAMES2), &mut || {
                        frames(scene, bg, Some(a), FRAMES2, wk, band);
                        0
                    });
                }));
            }
            fs.push(Box::new(|| {
                let mut g = mine.borrow_mut();
                let (wk, band) = &mut **g;
                next.store(0, Ordering::Relaxed);
                let (a, b) = both(Task::Claim(FRAMES2), &mut || {
                    claimed(scene, bg, next, FRAMES2, wk, band) as u64
                });
                let (x, y) = other_bands.get();
                other_bands.set((x + a, y + b));
            }));
            fs.push(Box::new(|| {
                let mut g = mine.borrow_mut();
                let (wk, band) = &mut **g;
                both(Task::Whole(FRAMES2), &mut || {
                    frames(scene, bg, None, FRAMES2, wk, band);
                    0
                });
            }));
            fs.push(Box::new(|| {
                black_box(spin(SPIN));
            }));
            fs.push(Box::new(|| {
                both(Task::Spin(SPIN / 2), &mut || spin(SPIN / 2));
            }));
            let t = best_calls(&mut fs, CALLS);
            drop(fs);
            drop(go);
            let (a, b) = other_bands.get();
            eprintln!("  claimed bands: this thread {a}, the other {b}");
            let f = |s: f64| s * 1e3 / FRAMES2 as f64;
            Threads {
                one: f(t[0]),
                alternate: f(t[1]),
                halves: f(t[2]),
                row,
                claim: f(t[3]),
                whole: f(t[4]),
                spin: (t[5] * 1e3, t[6] * 1e3),
            }
        })
    })
    .expect("demo scene")
}

/// The demo's first frame: full and bands.
/// `(full ms, band ms per height)`.
fn demo_times() -> (f64, Vec<f64>) {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let step = steps(1)[0];
    with_scene(step, |scene, bg| {
        let w = WIDTH as usize;
        let mut fb = vec![Rgb565::BLACK; w * HEIGHT as usize];
        let cell = std::cell::RefCell::new((scene, &mut fb));
        let mut fs: Vec<Box<dyn FnMut() + '_>> = Vec::new();
        fs.push(Box::new(|| {
            let mut g = cell.borrow_mut();
            let (scene, f) = &mut *g;
            let mut t = FrameBuffer::new(f, WIDTH, HEIGHT).expect("frame");
            scene
                .draw(Resolve::default(), Some(bg), DEFAULT_FONT, &mut t)
                .expect("draws");
        }));
        for rows in HEIGHTS {
            let cell = &cell;
            fs.push(Box::new(move || {
                let mut g = cell.borrow_mut();
                let (scene, f) = &mut *g;
                let n = rows as usize * w;
                scene
                    .draw_bands(
                        Resolve::default(),
                        bg,
                        DEFAULT_FONT,
                        rows,
                        &mut f[..n],
                        &mut Drop,
                    )
                    .expect("bands");
            }));
        }
        let t = time_fns(&mut fs, LIST_RUN, LIST_ROUNDS);
        let ms: Vec<f64> = t.iter().map(|s| s * 1e3).collect();
        (ms[0], ms[1..5].to_vec())
    })
    .expect("demo scene")
}

/// Measures everything and returns the section of `performance.md`.
pub fn run() -> String {
    let layered: &[u8] = include_bytes!("../../firmware/image/scenes/poly3-layered.scvl");
    let tilted: &[u8] = include_bytes!("../../firmware/image/scenes/poly3-tilted.scvl");
    let lists: [(&str, &[u8], Resolve); 5] = [
        (
            "W3: 10 000 triangles, 2D",
            include_bytes!("../../firmware/image/scenes/w3.scvl"),
            Resolve::default(),
        ),
        (
            "poly3-layered: 170 faces (the default: painted)",
            layered,
            Resolve::default(),
        ),
        (
            "poly3-layered, crossing points (`Resolve::Crossing`)",
            layered,
            Resolve::Crossing,
        ),
        (
            "poly3-tilted: 170 faces, interpenetrating (the default: painted)",
            tilted,
            Resolve::default(),
        ),
        (
            "poly3-tilted, crossing points (`Resolve::Crossing`)",
            tilted,
            Resolve::Crossing,
        ),
    ];
    let mut md = String::new();
    md += "| frame | full frame, ms | 1 row | 8 rows | 16 rows | 64 rows |\n|---|---|---|---|---|---|\n";
    // The 16-row ratios, for the targets' verdict under the table.
    let at16 = HEIGHTS
        .iter()
        .position(|&h| h == 16)
        .expect("16 rows measured");
    let mut ratios16: Vec<f64> = Vec::new();
    let mut row = |name: &str, full: f64, bands: &[f64]| {
        ratios16.push(bands[at16] / full);
        let _ = write!(md, "| {name} | {full:.3} |");
        for b in bands {
            let _ = write!(md, " {:.2}× |", b / full);
        }
        md.push('\n');
        eprintln!("  {name}: full {full:.3} ms, bands {bands:.3?} ms");
    };
    for (name, bytes, mode) in lists {
        let (full, bands) = list_times(bytes, mode);
        row(name, full, &bands);
    }
    let (full, bands) = demo_times();
    row("the 3D demo's first frame (Scene)", full, &bands);
    // W3 first, then the 3D frames.
    let w3 = ratios16[0];
    let worst3d = ratios16[1..].iter().copied().fold(0.0, f64::max);
    let verdict = |r: f64, target: f64| if r <= target { "met" } else { "missed" };
    let _ = writeln!(
        md,
        "\nIn 16-row bands W3 takes {w3:.2}× its full frame's time (target 1.25×: {}), \
         and the 3D frames at most {worst3d:.2}× (target 1.1×: {}). The full frame \
         draws each of W3's triangles in one call, its edges held in registers; the bands \
         set up and store every edge before the first band (the band table) and visit \
         each triangle once for each band it crosses (about twice at 16 rows), reading \
         its edges back from memory each time (see the performance log).",
        verdict(w3, 1.25),
        verdict(worst3d, 1.1)
    );
    threads_table(&mut md);
    md
}

/// The two-thread measurement, as a paragraph and a table of `md`.
fn threads_table(md: &mut String) {
    use scanvert_sim::demo::HEIGHT;
    let load = std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into());
    let t = thread_times();
    eprintln!("  {t:?}");
    let _ = write!(
        md,
        "\nTwo threads on the demo's first frame in bands of {ROWS2} rows (load average {load} when \
         this part started). Each thread has its own workspace and band buffer and runs one \
         pass a frame over the shared scene (`Scene::bands_in`), drawing its bands and stepping \
         over the other rows; the second thread is made once and woken once per {FRAMES2} \
         frames. Best single call of {CALLS} of each, round-robin with the calibration (the \
         calls that ran with both cores free):\n\n\
         | | ms per frame | speed-up over one thread |\n|---|--:|--:|\n\
         | one thread, every band | {:.3} | 1.00× |\n",
        t.one
    );
    let mut line = |name: String, ms: f64| {
        let _ = writeln!(md, "| {name} | {ms:.3} | {:.2}× |", t.one / ms);
    };
    line("two threads: every other band".into(), t.alternate);
    line(
        format!(
            "two threads: rows 0–{} and {}–{} (the split of equal times, found on one thread first)",
            t.row - 1,
            t.row,
            HEIGHT - 1
        ),
        t.halves,
    );
    line(
        "two threads: each band claimed from a shared counter".into(),
        t.claim,
    );
    let best = t.one / t.alternate.min(t.halves).min(t.claim);
    let spin = t.spin.0 / t.spin.1;
    let whole = 2.0 * t.one / t.whole;
    let _ = writeln!(
        md,
        "| calibration with the demo's own work: two threads, each drawing every band of frames of its own (ms a frame of each; the speed-up is two frames' work over one thread's) | {:.3} | {whole:.2}× |",
        t.whole
    );
    let _ = write!(
        md,
        "| calibration: a chain of {} million multiply-adds on one thread, two of {} million on two (ms a call) | {:.3} / {:.3} | {spin:.2}× |\n\n\
         The best two-thread figure, {best:.2}×, is {:.0}% of the calibration's {spin:.2}× in the same run, and {:.0}% of the {whole:.2}× two threads give the demo's own work, nothing split. \
         Two threads each drawing whole frames \
         of the demo, sharing nothing but the scene, are the most a split of its frame can \
         reach; on this host that moved from run to run (1.70× to 1.96× in runs minutes apart, \
         while the multiply-add chain stayed at 1.97× to 1.99×), and the split's speed-up moved \
         with it, at 89% to 104% of it.\n",
        SPIN / 1_000_000,
        SPIN / 2_000_000,
        t.spin.0,
        t.spin.1,
        100.0 * best / spin,
        100.0 * best / whole
    );
}

/// `--profile-bands ROWS PASSES`: W3 alone in bands of ROWS (0: the full
/// frame), for a profiler.
pub fn profile(rows: u16, passes: u32) {
    let bytes: &[u8] = match std::env::var("BANDS_LIST").as_deref() {
        Ok("layered") => include_bytes!("../../firmware/image/scenes/poly3-layered.scvl"),
        Ok("tilted") => include_bytes!("../../firmware/image/scenes/poly3-tilted.scvl"),
        Ok("demo") => return profile_demo(rows, passes),
        _ => include_bytes!("../../firmware/image/scenes/w3.scvl"),
    };
    let list = DisplayList::new_checked(bytes).expect("list");
    let mut mem = ListMemory::for_bands(&list).expect("the list's 3D layer runs");
    let mut fb = vec![Rgb565::BLACK; list.width() as usize * list.height() as usize];
    for _ in 0..passes {
        let mode = match std::env::var("BANDS_RESOLVE").as_deref() {
            Ok("paint") => Resolve::Paint,
            Ok("crossing") => Resolve::Crossing,
            _ => Resolve::default(),
        };
        render(&mut mem, &list, &mut fb, (rows > 0).then_some(rows), mode);
    }
}

/// Begin marker of the bands section of `performance.md`.
pub const BEGIN: &str = "<!-- bands:begin -->";
/// End marker.
pub const END: &str = "<!-- bands:end -->";

/// The bands section of `old` (markers included, after a blank line), or
/// nothing: the full run keeps what `--only bands` wrote.
pub fn kept_section(old: &str) -> String {
    use crate::report::marker_line;
    match marker_line(old, BEGIN, 0).and_then(|b| Some((b, marker_line(old, END, b)?))) {
        Some((b, e)) => format!("\n{}\n", &old[b..e + END.len()]),
        None => String::new(),
    }
}

/// `--only bands`: measures, prints, and writes the section into
/// `performance.md` (replacing the last one, or before "## On target").
pub fn write_section(path: &std::path::Path, machine: &str) -> std::io::Result<()> {
    use crate::report::marker_line;
    let table = run();
    let section = format!(
        "{BEGIN}\n## Bands: rendering without a frame buffer\n\n\
         Written by `cargo run --release -p scanvert-bench -- --only bands` ({machine}); the full\n\
         run keeps it. Time of a frame rendered band by band (`Controller::render_bands`,\n\
         `Scene::draw_bands`) over the full-frame render of the same frame into a frame buffer\n\
         (`Controller::render`, `Scene::draw`), the best of 60 runs of 10 ms of each, round-robin, in one process. Both\n\
         include the frame's preparation (the list checked, the 3D layer built; for bands the\n\
         edge table); the bands are shipped to a provider that only reads them, and each band is\n\
         filled with the background first. The targets are 1.25× for W3 in bands\n\
         of 16 rows and 1.1× for the 3D frames.\n\n{table}\n\
         The host's two vCPUs are shared with other work: the best single calls\n\
         catch the moments when both cores are free, and the calibration, timed\n\
         round-robin with them, says how free they were. A worker still works on\n\
         the rows it does not draw: it jumps its active list over them\n\
         (`Sweep::skip`) and draws again the labels cut by its first band's top;\n\
         split into a top and a bottom part, only the second worker jumps, once.\n\n\
         The Cortex-M4's counts are in the on-target section (*Band by band, with\n\
         no frame buffer*), written by `firmware/image/measure.sh`.\n{END}\n"
    );
    print!("{section}");
    let old = std::fs::read_to_string(path).unwrap_or_default();
    let new = match marker_line(&old, BEGIN, 0).and_then(|b| Some((b, marker_line(&old, END, b)?)))
    {
        Some((b, e)) => {
            let end = old[e..].find('\n').map_or(old.len(), |n| e + n + 1);
            format!("{}{section}{}", &old[..b], &old[end..])
        }
        None => match old.find("\n## On target") {
            Some(at) => format!("{}\n{section}{}", &old[..at + 1], &old[at..]),
            None => format!("{old}\n{section}"),
        },
    };
    std::fs::write(path, new)
}

/// The demo's first frame, full (`rows` 0) or in bands, `passes` times.
/// `BANDS_WORKER` = `0` or `1` (every other band of 16 rows from band 0
/// or 1), `top` or `bottom` (the bands of the top or the bottom half) or
/// `all` (every band, in one pass a frame): only that worker's bands, in
/// a workspace of its own, the others stepped over.
fn profile_demo(rows: u16, passes: u32) {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    with_scene(steps(1)[0], |scene, bg| {
        let most = scene.check().expect("the scene fits its workspace") as usize;
        let mut work = Work::new(most);
        let mut fb = vec![Rgb565::BLACK; WIDTH as usize * HEIGHT as usize];
        let half = std::env::var("BANDS_SPLIT")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(HEIGHT / 2);
        let share = match std::env::var("BANDS_WORKER").as_deref() {
            Ok("0") => Some(Some(Share::Alternate(0))),
            Ok("1") => Some(Some(Share::Alternate(1))),
            Ok("top") => Some(Some(Share::Split {
                row: half,
                first: true,
            })),
            Ok("bottom") => Some(Some(Share::Split {
                row: half,
                first: false,
            })),
            Ok("all") => Some(None),
            _ => None,
        };
        if let Some(share) = share {
            let n = ROWS2 as usize * WIDTH as usize;
            frames(scene, bg, share, passes, &mut work, &mut fb[..n]);
            return;
        }
        for _ in 0..passes {
            if rows == 0 {
                let mut t = FrameBuffer::new(&mut fb, WIDTH, HEIGHT).expect("frame");
                scene
                    .draw(Resolve::default(), Some(bg), DEFAULT_FONT, &mut t)
                    .expect("draws");
            } else {
                let n = rows as usize * WIDTH as usize;
                scene
                    .draw_bands(
                        Resolve::default(),
                        bg,
                        DEFAULT_FONT,
                        rows,
                        &mut fb[..n],
                        &mut Drop,
                    )
                    .expect("bands");
            }
        }
    })
    .expect("demo scene");
}
