//! Speed against error: scanvert's rasterisers, their faster options and
//! their peers on the 2D workloads W1–W6, and its scan-line visible
//! surfaces against z-buffers on the 3D scenes, timed in one process run.
//!
//! `cargo run --release -p scanvert-bench` writes `docs/performance.md`,
//! `docs/speed-vs-error.png` and `docs/time-vs-trapezoids.png`. Speed is
//! measured here only, never in a test. `-- --only W3` times one workload
//! and writes nothing (`-- --only 2D` all of W1–W6, with the exact
//! path's ratios to the plain 16.16 filler); `-- --only 3D` times the
//! 3D scenes alone, and
//! `-- --only 3D:170` those of 170 faces; `-- --only depth` runs the
//! depth-complexity sweep and the P3/P4 split alone and rewrites their
//! section of `docs/performance.md` (and `docs/time-vs-depth.png`,
//! `docs/p3-p4-vs-trapezoids.png`), keeping the rest of the page;
//! `-- --profile-w1 MODE PASSES`
//! runs W1 alone and `-- --profile-3d MODE PASSES` the 170-face 3D scene
//! alone, for callgrind. `-- --only bands` times band rendering
//! against the full frame and writes only `docs/performance.md`'s section
//! on bands (which the full run keeps). `-- --only model` counts the
//! simulated write port's cycles on the image's 2D lists (the model
//! calibrated on W1, the others predicted) and rewrites its section;
//! `-- --only race` fits the racing cost model to the image's row counts
//! and rewrites the racing tables; `-- --only ram` counts the RAM of band
//! rendering by part and rewrites its table. `-- --only meshes` times the
//! mesh sweep and rewrites its section and `docs/mesh-sweep.svg`;
//! `-- --only meshes --print` prints it and writes nothing.

mod bands;
mod contenders;
mod dual_port;
mod heap;
mod meshes;
mod numbers;
mod plot;
mod race;
mod ram;
mod report;
mod visible3d;
mod worst;

use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};
use testkit::reference;
use testkit::scenes3d;
use testkit::workloads::{self, Kind, Workload};

#[global_allocator]
static ALLOC: heap::Counting = heap::Counting;

/// Each timed run repeats a pass at least this long.
const MIN_RUN: Duration = Duration::from_millis(200);
/// Timed runs per contender, round-robin over the contenders; best kept.
const ROUNDS: usize = 7;

/// A contender's error on a workload.
#[derive(Clone, Copy, Debug)]
pub struct ErrorStats {
    /// Mismatched pixels per 1000 pixels the rule covers.
    pub per_1000: f64,
    /// Most mismatches in one polygon.
    pub worst: u64,
    /// All mismatches.
    pub total: u64,
}

/// One line of the table.
#[derive(Debug)]
pub struct Row {
    /// Workload id.
    pub workload: &'static str,
    /// Rate unit.
    pub unit: &'static str,
    /// Contender name.
    pub contender: &'static str,
    /// Operations per second.
    pub rate: f64,
    /// Covered (rule) pixels per second, in millions.
    pub mpx: f64,
    /// `mpx` over the bandwidth limit's.
    pub ratio: f64,
    /// `None` for the bandwidth limit and for clears.
    pub err: Option<ErrorStats>,
    /// Bytes of working state and how they were counted.
    pub mem: (usize, String),
}

/// The independent check of the exact path on one workload.
#[derive(Debug)]
pub struct Check {
    /// Workload id.
    pub workload: &'static str,
    /// Polygons checked.
    pub polygons: usize,
    /// Pixels tested (the polygons' boxes, widened).
    pub tested: u64,
    /// Pixels the rule covers.
    pub covered: u64,
    /// Pixels where the exact path and the `i128` reference differ.
    pub mismatches: u64,
}

/// Per polygon: its box and the reference's coverage inside it.
type Masks = Vec<((i32, i32, i32, i32), Vec<bool>)>;

fn reference_masks(wl: &Workload) -> Masks {
    wl.polys
        .iter()
        .map(|p| {
            let p = &reference::units(p);
            let b = reference::pixel_box(p, 3, wl.width, wl.height);
            let mut m = Vec::with_capacity(((b.2 - b.0) * (b.3 - b.1)) as usize);
            for y in b.1..b.3 {
                for x in b.0..b.2 {
                    m.push(reference::covers(p, x, y));
                }
            }
            (b, m)
        })
        .collect()
}

/// Draws every polygon alone with `c` and compares with the reference.
fn error_of(c: &mut dyn contenders::Contender, masks: &Masks, covered: u64) -> ErrorStats {
    let (mut total, mut worst) = (0u64, 0u64);
    for (i, (b, m)) in masks.iter().enumerate() {
        c.draw_one(i);
        let mut bad = 0u64;
        let mut k = 0;
        for y in b.1..b.3 {
            for x in b.0..b.2 {
                bad += (c.covered(x, y) != m[k]) as u64;
                k += 1;
            }
        }
        c.reset(*b);
        total += bad;
        worst = worst.max(bad);
    }
    ErrorStats {
        per_1000: total as f64 * 1000.0 / covered.max(1) as f64,
        worst,
        total,
    }
}

/// Best seconds per pass of each contender: each is calibrated to runs of
/// at least [`MIN_RUN`], then all are timed round-robin [`ROUNDS`] times.
fn time_all(cs: &mut [Box<dyn contenders::Contender>]) -> Vec<f64> {
    let mut fs: Vec<Box<dyn FnMut() + '_>> = cs
        .iter_mut()
        .map(|c| Box::new(move || black_box(&mut **c).pass()) as Box<dyn FnMut()>)
        .collect();
    time_fns(&mut fs, MIN_RUN, ROUNDS)
}

/// Best seconds per call of each of `fs`: each is calibrated (for an
/// eighth of `min_run`) to runs of at least `min_run`, then all are timed
/// round-robin `rounds` times.
pub fn time_fns(fs: &mut [Box<dyn FnMut() + '_>], min_run: Duration, rounds: usize) -> Vec<f64> {
    let iters: Vec<u32> = fs
        .iter_mut()
        .map(|f| {
            f();
            let t = Instant::now();
            let mut n = 0u32;
            while t.elapsed() < min_run / 8 {
                f();
                n += 1;
            }
            let per = t.elapsed().as_secs_f64() / n as f64;
            (min_run.as_secs_f64() / per).ceil().max(1.0) as u32
        })
        .collect();
    let mut best = vec![f64::INFINITY; fs.len()];
    for _ in 0..rounds {
        for (k, f) in fs.iter_mut().enumerate() {
            let t = Instant::now();
            for _ in 0..iters[k] {
                f();
            }
            best[k] = best[k].min(t.elapsed().as_secs_f64() / iters[k] as f64);
        }
    }
    best
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

/// `--profile-w1 MODE PASSES`: only W1, for `valgrind --tool=callgrind`.
/// MODE is `framebuffer` (the exact path), `null` (scan conversion
/// without pixel writes) or `tiny-skia`.
fn profile_w1(mode: &str, passes: u32) {
    use scanvert::{raster::clip::ClipRect, raster::edge::Edge, raster::scan::Rasterizer};
    let wl = workloads::w1();
    if mode == "null" {
        let mut slots = [Edge::EMPTY; 4];
        let mut r = Rasterizer::new(&mut slots);
        let clip = ClipRect::full(wl.width, wl.height);
        let mut t = contenders::NullTarget(wl.width, wl.height);
        for _ in 0..passes {
            for p in &wl.polys {
                let _ = r.fill(
                    black_box(p).iter().copied(),
                    &clip,
                    Default::default(),
                    &mut t,
                );
            }
        }
        return;
    }
    let prefix = match mode {
        "tiny-skia" => "tiny-skia",
        _ => "scanvert exact (",
    };
    let counts = vec![900; wl.polys.len()];
    let mut cs = contenders::for_workload(&wl, counts);
    if let Some(c) = cs.iter_mut().find(|c| c.name().starts_with(prefix)) {
        for _ in 0..passes {
            black_box(&mut *c).pass();
        }
    }
}

/// What `--help` (or any argument not understood) prints.
const USAGE: &str = "\
scanvert-bench: speed against error, written to docs/performance.md and its plots

  (no argument)             everything; rewrites the page and all its plots
  --only W1|W2|W3|W4|W5|W6  one 2D workload, printed, nothing written
  --only 2D                 every 2D workload, printed with the exact path's
                            ratios to the plain 16.16 filler, nothing written
  --only 3D | --only 3D:N   the 3D scenes (of N faces), printed, nothing written
  --only depth              the depth-complexity sweep and the P3/P4 split;
                            rewrites their section of the page and their plots
  --only bands              bands against the full frame (W3, the 3D scenes, the
                            demo, two threads); rewrites its section of the page
  --only meshes             the mesh sweep (testkit::meshes, 100 to 20,000
                            triangles, 240 x 240): scanvert's resolves, its bands
                            and stages, and two i32 z-buffers; rewrites its section
                            of docs/performance.md and docs/mesh-sweep.svg
  --only meshes --print     the same, printed, nothing written
  --only worst              the worst cases (staggered faces, 1,000 to 38,835);
                            rewrites its section of the page and its plot
  --only model              the write port's cycle model on the image's 2D lists
                            (counted, not timed); rewrites its section of the page
  --only race               racing the beam: the M4 cost model's fit and error, the
                            lowest clocks (not timed); rewrites its section
  --only ram                the RAM of band rendering by part (counted, not
                            timed); rewrites its table
  --write-worst DIR         writes the worst-case lists (nearer-N.dl, reversed-N.dl,
                            farther-N.dl) into DIR, for timing `scanvert render`
  --profile-w1 MODE PASSES  W1 alone, for callgrind (null, framebuffer, tiny-skia)
  --profile-3d MODE PASSES  the 170-face 3D scene alone, for callgrind
                            ($PROFILE_FACES=N: of N faces; $PROFILE_VERSION=layered:
                            the 2D version)
  --profile-bands ROWS PASSES  W3 (or $BANDS_LIST: layered, tilted, demo) in
                            bands of ROWS rows alone, for callgrind";

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() > 1
        && !matches!(
            args[1].as_str(),
            "--only" | "--profile-3d" | "--profile-w1" | "--profile-bands" | "--write-worst"
        )
    {
        eprintln!("{USAGE}");
        return Ok(());
    }
    if args.len() == 4 && args[1] == "--profile-3d" {
        visible3d::profile(&args[2], args[3].parse().unwrap_or(25));
        return Ok(());
    }
    if args.len() == 4 && args[1] == "--profile-bands" {
        bands::profile(
            args[2].parse().unwrap_or(16),
            args[3].parse().unwrap_or(100),
        );
        return Ok(());
    }
    if args.len() == 3 && args[1] == "--write-worst" {
        return worst::write_lists(std::path::Path::new(&args[2]));
    }
    if args.len() == 4 && args[1] == "--profile-w1" {
        profile_w1(&args[2], args[3].parse().unwrap_or(100));
        return Ok(());
    }
    if args.len() == 4 && args[1] == "--only" && args[2] == "meshes" && args[3] == "--print" {
        return only_meshes(false);
    }
    // `--only W2`: time one workload, print it, write nothing.
    let only = (args.len() == 3 && args[1] == "--only").then(|| args[2].clone());
    if only.as_deref() == Some("depth") {
        return only_depth();
    }
    if only.as_deref() == Some("worst") {
        return only_worst();
    }
    if only.as_deref() == Some("meshes") {
        return only_meshes(true);
    }
    if only.as_deref() == Some("race") {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/performance.md");
        return race::write_section(&path);
    }
    if only.as_deref() == Some("ram") {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/performance.md");
        return ram::write_section(&path);
    }
    if only.as_deref() == Some("model") {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/performance.md");
        return dual_port::write_section(&path);
    }
    if only.as_deref() == Some("bands") {
        eprintln!("bands against the full frame (ms per frame, ratios):");
        let machine = format!("load average {} before the run", load_average());
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/performance.md");
        return bands::write_section(&path, &machine);
    }
    let start = Instant::now();
    let load_before = load_average();
    let mut rows = Vec::new();
    let mut checks = Vec::new();
    // The image's W1–W5, and the host's slivers.
    let mut all2d = workloads::all();
    all2d.push(workloads::w6());
    for wl in all2d {
        if only.as_ref().is_some_and(|id| id != wl.id && id != "2D") {
            continue;
        }
        eprintln!("{}: {}", wl.id, wl.what);
        let masks = reference_masks(&wl);
        let counts: Vec<usize> = match wl.kind {
            Kind::Polygons => masks
                .iter()
                .map(|(_, m)| m.iter().filter(|&&c| c).count())
                .collect(),
            Kind::Clear => vec![wl.width as usize * wl.height as usize],
        };
        let covered: u64 = counts.iter().map(|&n| n as u64).sum();
        let mut cs = contenders::for_workload(&wl, counts);
        let errs: Vec<Option<ErrorStats>> = cs
            .iter_mut()
            .map(|c| {
                (wl.kind == Kind::Polygons && c.has_coverage())
                    .then(|| error_of(c.as_mut(), &masks, covered))
            })
            .collect();
        if let Some(Some(e)) = errs.first() {
            checks.push(Check {
                workload: wl.id,
                polygons: masks.len(),
                tested: masks.iter().map(|(_, m)| m.len() as u64).sum(),
                covered,
                mismatches: e.total,
            });
        }
        let secs = time_all(&mut cs);
        let limit = covered as f64 / secs[secs.len() - 1];
        for ((c, s), e) in cs.iter().zip(&secs).zip(errs) {
            let px = covered as f64 / s;
            let row = Row {
                workload: wl.id,
                unit: wl.unit(),
                contender: c.name(),
                rate: wl.ops_per_pass() as f64 / s,
                mpx: px / 1e6,
                ratio: px / limit,
                err: e,
                mem: c.memory(),
            };
            eprintln!(
                "  {:<55} {:>12.0} {} {:>8.1} Mpx/s {:>6.3}× {}",
                row.contender,
                row.rate,
                row.unit,
                row.mpx,
                row.ratio,
                row.err
                    .map(|e| format!("err {:.3}/1000 worst {}", e.per_1000, e.worst))
                    .unwrap_or_default()
            );
            rows.push(row);
        }
    }
    let mut rows3 = Vec::new();
    let mut scenes3 = Vec::new();
    let start3 = Instant::now();
    for scene in scenes3d::all() {
        if let Some(id) = &only {
            if id == "2D" {
                break;
            }
            let all = id == "3D";
            let this = id.strip_prefix("3D:") == Some(scene.faces.to_string().as_str());
            if !all && !this {
                continue;
            }
        }
        let (rows, st) = visible3d::measure(&scene);
        eprintln!(
            "3D scene, {}: {} faces, {:.0} trapezoids, {:.0} px covered, depth complexity {:.2}, {} active at most, {:.0} intersecting spans",
            scene.version.short(),
            st.faces,
            st.trapezoids,
            st.covered,
            st.complexity,
            st.max_active,
            st.intersecting
        );
        for r in &rows {
            eprintln!(
                "  {:<48} {:>8.3} ms/frame {} {:>6.2}× z16 {} mem {}",
                r.contender,
                r.ms,
                r.resolve_ms
                    .map(|m| format!("(alone {m:.3})"))
                    .unwrap_or_default(),
                r.vs_z,
                r.err
                    .map(|e| format!("err {:.3}/1000 worst {}", e.per_1000, e.worst))
                    .unwrap_or_default(),
                r.mem.0
            );
        }
        rows3.extend(rows);
        scenes3.push(st);
    }
    let seconds3 = start3.elapsed().as_secs_f64();
    if only.as_deref() == Some("2D") {
        eprintln!("{}", ratios_to_plain(&rows));
        return Ok(());
    }
    if only.is_some() {
        eprintln!("3D part: {seconds3:.1} s");
        return Ok(());
    }
    let (depth, split, seconds_depth) = depth_part();
    let run = report::Run {
        rows,
        checks,
        rows3,
        scenes3,
        seconds3,
        load_before,
        load_after: load_average(),
        seconds: start.elapsed().as_secs_f64(),
        depth,
        split,
        seconds_depth,
    };
    let docs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs");
    std::fs::create_dir_all(&docs)?;
    let md_path = docs.join("performance.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    std::fs::write(&md_path, report::markdown(&run, &old))?;
    write_png(&docs.join("speed-vs-error.png"), plot::render(&run.rows))?;
    write_png(
        &docs.join("time-vs-trapezoids.png"),
        plot::render_3d(&run.rows3),
    )?;
    write_depth_pngs(&docs, &run.depth, &run.split)?;
    eprintln!(
        "wrote docs/performance.md, docs/speed-vs-error.png, docs/time-vs-trapezoids.png, docs/time-vs-depth.png and docs/p3-p4-vs-trapezoids.png in {:.0} s",
        run.seconds
    );
    Ok(())
}

/// Per 2D workload, each scanvert contender's speed over the plain 16.16
/// filler's in the same run.
fn ratios_to_plain(rows: &[Row]) -> String {
    let mut s = String::from("ratios to the plain 16.16 filler (same run):\n");
    for plain in rows
        .iter()
        .filter(|r| r.contender.starts_with("plain 16.16"))
    {
        for r in rows
            .iter()
            .filter(|r| r.workload == plain.workload && r.contender.starts_with("scanvert"))
        {
            s += &format!(
                "  {} {:<50} {:>6.2}×\n",
                r.workload,
                r.contender,
                r.rate / plain.rate
            );
        }
    }
    s
}

/// The depth-complexity sweep and the P3/P4 split of the 3D scenes, and
/// their wall time.
fn depth_part() -> (Vec<visible3d::DepthRow>, Vec<visible3d::SplitRow>, f64) {
    let start = Instant::now();
    let mut depth = Vec::new();
    for (aimed, scene) in scenes3d::depth_all() {
        let r = visible3d::measure_depth(&scene, aimed);
        eprintln!(
            "depth {} {:>2}: measured {:.2}, {:.0} trapezoids, {:.0} spans, scanvert {:.3} ms, z16 {:.3} ms, z32 {:.3} ms, mismatches {} / {} / {}",
            r.version.short(),
            aimed,
            r.complexity,
            r.trapezoids,
            r.spans(),
            r.ms[0],
            r.ms[1],
            r.ms[2],
            r.err[0].total,
            r.err[1].total,
            r.err[2].total
        );
        depth.push(r);
    }
    // Both versions of a size timed together, so that their ratio holds.
    let mut split = Vec::new();
    for &n in &scenes3d::SIZES {
        let pair = [
            scenes3d::scene(scenes3d::Version::Layered, n),
            scenes3d::scene(scenes3d::Version::Tilted, n),
        ];
        for r in visible3d::measure_split(&[&pair[0], &pair[1]]) {
            eprintln!(
                "split {} {:>4} faces: {:.0} trapezoids, P3 {:.3} ms, P4 {:.3} ms, fused {:.3} ms",
                r.version.short(),
                r.faces,
                r.trapezoids,
                r.p3_ms,
                r.p4_ms,
                r.both_ms
            );
            split.push(r);
        }
    }
    // Report order: the 2D version, then the 3D version.
    split.sort_by_key(|r| (r.version == scenes3d::Version::Tilted, r.faces));
    (depth, split, start.elapsed().as_secs_f64())
}

/// Writes the plots of the depth sweep and of the P3/P4 split.
fn write_depth_pngs(
    docs: &std::path::Path,
    depth: &[visible3d::DepthRow],
    split: &[visible3d::SplitRow],
) -> std::io::Result<()> {
    write_png(&docs.join("time-vs-depth.png"), plot::render_depth(depth))?;
    write_png(
        &docs.join("p3-p4-vs-trapezoids.png"),
        plot::render_split(split),
    )
}

/// `--only depth`: the sweep and the split alone; their section of
/// `docs/performance.md` rewritten in place.
fn only_depth() -> std::io::Result<()> {
    let (depth, split, seconds) = depth_part();
    let docs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs");
    let md_path = docs.join("performance.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    let md = report::splice(
        &old,
        report::DEPTH_BEGIN,
        report::DEPTH_END,
        &report::section_depth(&depth, &split, seconds),
        "## Targets",
    );
    std::fs::write(&md_path, md)?;
    write_depth_pngs(&docs, &depth, &split)?;
    eprintln!(
        "rewrote the depth section of docs/performance.md, docs/time-vs-depth.png and docs/p3-p4-vs-trapezoids.png in {seconds:.0} s"
    );
    Ok(())
}

/// `--only worst`: the worst cases timed; their section of
/// `docs/performance.md` (in "Worst cases") and
/// `docs/worst-case.png` rewritten.
fn only_worst() -> std::io::Result<()> {
    let machine = format!("load average {} before the run", load_average());
    let rows = worst::measure(Duration::from_millis(300));
    let docs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs");
    let md_path = docs.join("performance.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    let md = report::splice(
        &old,
        worst::BEGIN,
        worst::END,
        &worst::section(&rows, &machine),
        "## Painting far to near (`Resolve::Paint`)",
    );
    std::fs::write(&md_path, md)?;
    write_png(&docs.join("worst-case.png"), plot::render_worst(&rows))?;
    eprintln!("rewrote the worst-case curve of docs/performance.md and docs/worst-case.png");
    Ok(())
}

/// `--only meshes`: the mesh sweep timed; its section of
/// `docs/performance.md` and `docs/mesh-sweep.svg` rewritten.
/// The mesh sweep, printed; with `write`, also spliced into
/// docs/performance.md, and its plot written.
fn only_meshes(write: bool) -> std::io::Result<()> {
    let machine = format!("load average {} before the run", load_average());
    let rows = meshes::measure(Duration::from_millis(100), meshes::ROUNDS);
    let docs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs");
    let md_path = docs.join("performance.md");
    let old = std::fs::read_to_string(&md_path).unwrap_or_default();
    let section = meshes::section(&rows, &machine);
    print!("{section}");
    if !write {
        return Ok(());
    }
    let md = report::splice(
        &old,
        meshes::BEGIN,
        meshes::END,
        &section,
        "## Painting far to near (`Resolve::Paint`)",
    );
    std::fs::write(&md_path, md)?;
    std::fs::write(docs.join("mesh-sweep.svg"), meshes::svg(&rows))?;
    eprintln!("rewrote the mesh sweep of docs/performance.md and docs/mesh-sweep.svg");
    Ok(())
}

/// Writes an RGB888 picture `(width, height, bytes)` as PNG.
fn write_png(path: &std::path::Path, (w, h, rgb): (u32, u32, Vec<u8>)) -> std::io::Result<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = png::Encoder::new(file, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(&rgb)?;
    Ok(())
}
