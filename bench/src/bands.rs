//! Band rendering against the full-frame render of the same frame, in one
//! run: W3 (10 000 triangles) and the two `poly3` lists of the firmware
//! image through the controller, and the 3D demo scene through
//! `Scene::draw_bands`; then the demo's bands drawn by two threads, each
//! taking every other band, against one thread. `--only bands`.
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
use std::time::Duration;

/// Frames each worker draws per timed call in the two-thread measurement.
const FRAMES: u32 = 20;

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
/// from it ([`ListMemory::for_bands`]).
fn render(m: &mut ListMemory, list: &DisplayList<'_>, fb: &mut [Rgb565], band: Option<u16>) {
    let (w, h) = (list.width(), list.height());
    match band {
        None => {
            let mut f = FrameBuffer::new(fb, w, h).expect("frame");
            m.controller().render(list, &mut f).expect("renders");
        }
        Some(rows) => {
            let (mut c, table) = m.band_parts();
            let n = rows as usize * w as usize;
            c.render_bands(list, table, rows, &mut fb[..n], &mut Drop)
                .expect("renders");
        }
    }
}

/// Times the full frame and the band heights of one list: ms per frame.
fn list_times(bytes: &[u8]) -> (f64, Vec<f64>) {
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
            render(m, black_box(list), f, band);
        }));
    }
    let t = time_fns(&mut fs, Duration::from_millis(150), 5);
    (t[0] * 1e3, t[1..].iter().map(|s| s * 1e3).collect())
}

/// The visible-surface memory of one worker on the demo.
struct Work {
    active: Vec<Active>,
    runs: Vec<Run>,
}

impl Work {
    fn new() -> Work {
        Work {
            active: vec![Active::EMPTY; 512],
            runs: vec![Run::EMPTY; scanvert_sim::demo::WIDTH as usize],
        }
    }
    fn workspace(&mut self) -> Workspace<'_> {
        Workspace::new(&mut self.active, &mut self.runs)
    }
}

/// Every other band of 16 rows of `scene` from band `k` of `workers`, in
/// `work`'s workspace and `band` (each worker's, made once).
fn job<const D: usize, const M: usize>(
    scene: &Scene<'_, D, M>,
    bg: Rgb565,
    k: u16,
    workers: u16,
    work: &mut Work,
    band: &mut [Rgb565],
) {
    use scanvert_sim::demo::HEIGHT;
    let rows = 16u16;
    let mut ws = work.workspace();
    let mut pass = scene
        .bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT)
        .expect("pass");
    let mut y = k * rows;
    while y < HEIGHT {
        pass.draw(y, rows, band).expect("band");
        black_box(&band);
        y += workers * rows;
    }
}

/// The demo's first frame: full, bands, and 16-row bands on one and two
/// threads. `(full ms, band ms per height, one thread ms, two threads ms)`.
fn demo_times() -> (f64, Vec<f64>, f64, f64) {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let step = steps(1)[0];
    with_scene(step, |scene, bg| {
        let w = WIDTH as usize;
        let mut fb = vec![Rgb565::BLACK; w * HEIGHT as usize];
        let cell = std::cell::RefCell::new((scene, &mut fb));
        let mine = std::cell::RefCell::new((Work::new(), vec![Rgb565::BLACK; 16 * w]));
        let other = std::cell::RefCell::new((Work::new(), vec![Rgb565::BLACK; 16 * w]));
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
        // FRAMES frames a call, so that starting the second thread is
        // not counted per frame.
        fs.push(Box::new(|| {
            let g = cell.borrow();
            let mut a = mine.borrow_mut();
            let (wk, band) = &mut *a;
            for _ in 0..FRAMES {
                job(&*g.0, bg, 0, 1, wk, band);
            }
        }));
        fs.push(Box::new(|| {
            let g = cell.borrow();
            let scene = &*g.0;
            let mut a = mine.borrow_mut();
            let mut b = other.borrow_mut();
            let (wa, ba) = &mut *a;
            let (wb, bb) = &mut *b;
            std::thread::scope(|s| {
                let h = s.spawn(|| {
                    for _ in 0..FRAMES {
                        job(scene, bg, 1, 2, wb, bb);
                    }
                });
                for _ in 0..FRAMES {
                    job(scene, bg, 0, 2, wa, ba);
                }
                h.join().expect("worker");
            });
        }));
        let t = time_fns(&mut fs, Duration::from_millis(150), 5);
        let ms: Vec<f64> = t.iter().map(|s| s * 1e3).collect();
        (
            ms[0],
            ms[1..5].to_vec(),
            ms[5] / FRAMES as f64,
            ms[6] / FRAMES as f64,
        )
    })
    .expect("demo scene")
}

/// Measures everything and returns the section of `performance.md`.
pub fn run() -> String {
    let lists: [(&str, &[u8]); 3] = [
        (
            "W3: 10 000 triangles, 2D",
            include_bytes!("../../firmware/image/scenes/w3.scvl"),
        ),
        (
            "poly3-layered: 170 faces",
            include_bytes!("../../firmware/image/scenes/poly3-layered.scvl"),
        ),
        (
            "poly3-tilted: 170 faces, interpenetrating",
            include_bytes!("../../firmware/image/scenes/poly3-tilted.scvl"),
        ),
    ];
    let mut md = String::new();
    md += "| frame | full frame, ms | 1 row | 8 rows | 16 rows | 64 rows |\n|---|---|---|---|---|---|\n";
    let mut row = |name: &str, full: f64, bands: &[f64]| {
        let _ = write!(md, "| {name} | {full:.3} |");
        for b in bands {
            let _ = write!(md, " {:.2}× |", b / full);
        }
        md.push('\n');
        eprintln!("  {name}: full {full:.3} ms, bands {bands:.3?} ms");
    };
    for (name, bytes) in lists {
        let (full, bands) = list_times(bytes);
        row(name, full, &bands);
    }
    let (full, bands, one, two) = demo_times();
    row("the 3D demo's first frame (Scene)", full, &bands);
    let _ = write!(
        md,
        "\nThe demo's first frame in bands of 16 rows, every other band on each of two threads (each with its own workspace, stepping over the other's bands): {two:.3} ms against {one:.3} ms on one thread, a speed-up of {:.2}×.\n",
        one / two
    );
    eprintln!(
        "  two threads {two:.3} ms, one {one:.3} ms: {:.2}×",
        one / two
    );
    md
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
        render(&mut mem, &list, &mut fb, (rows > 0).then_some(rows));
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
         (`Controller::render`, `Scene::draw`), best of 5 round-robin runs, in one process. Both\n\
         include the frame's preparation (the list checked, the 3D layer built; for bands the\n\
         edge table); the bands are shipped to a provider that only reads them, and each band is\n\
         filled with the background first. On a loaded host these ratios move by ±0.2. The\n\
         targets are 1.25× for W3 in bands of 16 rows and 1.1× for the 3D frames.\n\n{table}\n\
         Where the time goes (profiles of `--profile-bands ROWS PASSES`, `BANDS_LIST=layered`\n\
         for the `poly3` list): the fixed part (W3 in 64-row bands: 1.04× the instructions on\n\
         x86-64, 1.13× on the M4) is entering the 10 000 polygons into the table (their edges\n\
         written out and read back, the order by first row); each further band revisits every\n\
         polygon it meets, reloading its state and edges, which is most of the cost at 1 row.\n\
         The `poly3` lists resolve the same rows with the same sweep; what they add is filling\n\
         each band with the background (they have no `clear`, and the full frame leaves what\n\
         was there). The demo draws each label in every band it reaches (a glyph pass of\n\
         `embedded-graphics` per band), which dominates at 1 and 8 rows.\n\n\
         Instructions per frame (x86-64, from `valgrind --tool=callgrind` on\n\
         `--profile-bands ROWS PASSES` with `BANDS_LIST` = `w3`, `layered`, `tilted` or `demo`,\n\
         ROWS 0 for the full frame; 6 passes less 1, over 5), which do not move with the load:\n\n{COUNTS}{END}\n"
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
fn profile_demo(rows: u16, passes: u32) {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    with_scene(steps(1)[0], |scene, bg| {
        let mut work = Work::new();
        let mut fb = vec![Rgb565::BLACK; WIDTH as usize * HEIGHT as usize];
        // `BANDS_WORKER=k`: only every other band from band k, as one of
        // two workers.
        let worker: Option<u16> = std::env::var("BANDS_WORKER")
            .ok()
            .and_then(|k| k.parse().ok());
        for _ in 0..passes {
            let mut ws = work.workspace();
            if let (Some(k), true) = (worker, rows > 0) {
                let mut pass = scene
                    .bands_in(&mut ws, Resolve::default(), bg, DEFAULT_FONT)
                    .expect("pass");
                let mut y = k * rows;
                while y < HEIGHT {
                    pass.draw(y, rows, &mut fb).expect("band");
                    y += 2 * rows;
                }
            } else if rows == 0 {
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

/// Instructions per frame on this host, from `valgrind --tool=callgrind`
/// on `--profile-bands ROWS PASSES` (`BANDS_LIST` = `w3`, `layered`,
/// `tilted`, `demo`; ROWS 0 for the full frame): the count of 6 passes
/// less that of 1, over 5. They do not move with the host's load.
const COUNTS: &str = "| frame | full frame, instructions | 1 row | 8 rows | 16 rows | 64 rows |\n|---|---|---|---|---|---|\n| W3: 10 000 triangles, 2D | 35,472,208 | 2.07× | 1.15× | 1.09× | 1.04× |\n| poly3-layered: 170 faces | 2,495,536 | 1.05× | 1.02× | 1.01× | 1.01× |\n| poly3-tilted: 170 faces, interpenetrating | 2,980,302 | 1.04× | 1.01× | 1.01× | 1.01× |\n| the 3D demo's first frame (Scene) | 2,803,513 | 2.33× | 1.18× | 1.09× | 1.03× |\n\nTwo workers on the demo's first frame, 16-row bands, each drawing every other band and stepping over the other's (`BANDS_WORKER=0` or `1` with `BANDS_LIST=demo`): 1,682,560 and 1,764,522 instructions, against 3,054,427 for all the bands on one: a bound of 1.73× on the speed-up (1.59× against the full frame) on two free cores; the rest is each worker's own work on the other's rows (stepping its active list, the workspace check, the labels' tests).\n\nOn the Cortex-M4F (the firmware image with `--features bands`, QEMU `mps2-an386`, `-icount shift=0`: every list rendered again in bands into a running checksum, which equals the host's for every list and band height; the instructions are those of a run shipping nowhere, as the full frame's exclude its checksum):\n\n| list | full frame, instructions | 1 row | 16 rows | 64 rows |\n|---|---|---|---|---|\n| demo (2D, 320 × 200) | 431,560 | 1.53× | 1.06× | 1.04× |\n| W1 | 1,219,680 | 2.26× | 1.21× | 1.15× |\n| W2 (a clear) | 115,320 | 1.31× | 1.06× | 1.05× |\n| W3: 10 000 triangles | 36,130,120 | 2.30× | 1.18× | 1.13× |\n| W4 | 1,511,360 | 2.32× | 1.20× | 1.14× |\n| W5 (no clear: each band is filled black first) | 408,680 | 1.81× | 1.59× | 1.58× |\n| poly3-layered (no clear, as W5) | 2,740,880 | 1.12× | 1.10× | 1.10× |\n| poly3-tilted (no clear, as W5) | 3,394,360 | 1.10× | 1.09× | 1.09× |\n";
