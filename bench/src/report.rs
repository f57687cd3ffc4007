//! `docs/performance.md`, generated; the on-target section written by the
//! QEMU script is carried over verbatim.

use crate::numbers::thousands;
use crate::visible3d::{Row3, CROSSING, Z16, Z32};
use crate::Row;
use std::fmt::Write;
use testkit::scenes3d::{Version, DEPTH_COMPLEXITY, H, VIEWS, W};

/// Markers of the section another script owns.
pub const ON_TARGET_BEGIN: &str = "<!-- on-target:begin -->";
/// End marker.
pub const ON_TARGET_END: &str = "<!-- on-target:end -->";

/// The reference design's figures (issue 5).
const REF_W1: f64 = 54_945.0;
const REF_W2: f64 = 763.0;

/// Everything one run measured.
#[derive(Debug)]
pub struct Run {
    /// The table.
    pub rows: Vec<Row>,
    /// The exact path against the `i128` reference.
    pub checks: Vec<crate::Check>,
    /// The 3D tables.
    pub rows3: Vec<crate::visible3d::Row3>,
    /// What each 3D scene is like.
    pub scenes3: Vec<crate::visible3d::SceneStats>,
    /// Wall time of the 3D part.
    pub seconds3: f64,
    /// `/proc/loadavg` before the run.
    pub load_before: String,
    /// And after.
    pub load_after: String,
    /// Wall time of the run.
    pub seconds: f64,
}

/// Byte offset of the first line of `text` that is `marker` alone
/// (surrounding spaces allowed), at or after `from`.
pub fn marker_line(text: &str, marker: &str, from: usize) -> Option<usize> {
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        if at >= from && line.trim() == marker {
            return Some(at + line.find(marker).unwrap_or(0));
        }
        at += line.len();
    }
    None
}

/// The section between the markers in `old` (each on a line of its own),
/// markers included, or an empty one.
pub fn on_target_section(old: &str) -> String {
    if let Some(b) = marker_line(old, ON_TARGET_BEGIN, 0) {
        if let Some(e) = marker_line(old, ON_TARGET_END, b) {
            return old[b..e + ON_TARGET_END.len()].to_string();
        }
    }
    format!(
        "{ON_TARGET_BEGIN}\n_Not measured yet: the QEMU script writes its figures here._\n{ON_TARGET_END}"
    )
}

/// Three significant digits.
fn sig3(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else if v >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    }
}

fn first_line(path: &str, key: &str) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    Some(line.split_once(':')?.1.trim().to_string())
}

fn machine() -> String {
    let cpu = first_line("/proc/cpuinfo", "model name").unwrap_or_else(|| "unknown".into());
    let cores = std::fs::read_to_string("/proc/cpuinfo")
        .map(|t| t.lines().filter(|l| l.starts_with("processor")).count())
        .unwrap_or(0);
    let rustc =
        std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
            .arg("--version")
            .output()
            .ok()
            .and_then(|o| String::from_utf8(o.stdout).ok())
            .map(|s| s.trim().to_string())
            .unwrap_or_else(|| "unknown".into());
    format!(
        "- CPU: {cpu} (`model name` in /proc/cpuinfo), {cores} cores seen by the OS\n\
         - Compiler: {rustc}, `--release` (opt-level 3, no LTO, no `target-cpu`)\n\
         - OS: {} {}\n",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn find<'r>(rows: &'r [Row], wl: &str, prefix: &str) -> Option<&'r Row> {
    rows.iter()
        .find(|r| r.workload == wl && r.contender.starts_with(prefix))
}

fn verdict(ok: bool) -> &'static str {
    if ok {
        "**met**"
    } else {
        "**missed**"
    }
}

/// The 3D scene the target names, and how small "a small fraction" of the
/// z-buffer's memory is taken to be.
const TARGET_FACES: usize = 170;
const SMALL_FRACTION: f64 = 0.25;
/// J. H. Jackson (1980): 170 polygons at 3 frames/s at 512×256.
const JACKSON_FPS: f64 = 3.0;

/// Milliseconds with three significant digits.
fn ms(v: f64) -> String {
    sig3(v)
}

/// The target row: the 170-face 3D version against the z-buffers.
fn target_3d(rows: &[Row3]) -> Option<String> {
    let at = |name: &str| {
        rows.iter().find(|r| {
            r.version == Version::Tilted && r.faces == TARGET_FACES && r.contender == name
        })
    };
    let (c, z16, z32) = (at(CROSSING)?, at(Z16)?, at(Z32)?);
    let fastest_z = z16.ms.min(z32.ms);
    let smallest_z = z16.mem.0.min(z32.mem.0);
    let faster = c.ms < fastest_z;
    let frac = c.mem.0 as f64 / smallest_z as f64;
    let small = frac <= SMALL_FRACTION;
    let mut why = Vec::new();
    if !faster {
        why.push(format!("{:.2}× the z-buffer's time", c.ms / fastest_z));
    }
    if !small {
        why.push(format!("{:.0} % of its memory", frac * 100.0));
    }
    Some(format!(
        "| 170-polygon 3D scene faster than the z-buffer, with a small fraction (≤ {:.0} %) of its memory | {} ms a frame (cut + resolve + decode) against {} ms (`i16` depth) and {} ms (`i32`): {:.2}× the faster z-buffer's speed; {} B against {} B (`i16` depth buffer and edge slots): {:.0} % | {}{} |\n",
        SMALL_FRACTION * 100.0,
        ms(c.ms),
        ms(z16.ms),
        ms(z32.ms),
        fastest_z / c.ms,
        thousands(c.mem.0 as f64),
        thousands(smallest_z as f64),
        frac * 100.0,
        verdict(faster && small),
        if why.is_empty() {
            String::new()
        } else {
            format!(": {}", why.join(", "))
        }
    ))
}

/// The 3D section: how it is measured, the scenes, one table per version.
fn section_3d(run: &Run) -> String {
    let mut s = String::new();
    if run.rows3.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "## 3D scenes: scan-line visible surfaces against a z-buffer\n\n\
         ![time against trapezoids](time-vs-trapezoids.png)\n\n\
         Scenes of 10 to 1000 front-facing `poly3` faces (triangles and\n\
         parallelograms, exactly planar in Q12.4) at {W}×{H}, like the classic\n\
         measurements of time against the number of trapezoids, seeded and\n\
         generated by `testkit/src/scenes3d.rs`. The faces shrink as they grow in\n\
         number, so that their summed area stays about {DEPTH_COMPLEXITY} frames\n\
         and the picture about as full. The **2D version** has every face\n\
         parallel to the screen, each at a depth of its own (layered); the\n\
         **3D version** has the same outlines with tilted planes whose depths\n\
         overlap, so that some faces pass through others. Each scene is seen\n\
         from {VIEWS} views, each panned by (5⅝, 2¼) px from the last, as when\n\
         the eye moves: every face changes in every frame.\n\n\
         - **Frame**: every contender first clears its RGB565 frame buffer\n\
           (one `slice::fill`). scanvert empties its one segment, cuts every\n\
           face into trapezoids (`TrapezoidStore::add_polygon`), then\n\
           resolves and decodes (`visible::draw`, no background fill) in\n\
           either mode. *Resolve + decode alone* is the frame where no segment\n\
           changed: the same, from stores cut beforehand. The **z-buffers**\n\
           clear their depth buffer, set up each face's depth plane (Newell's\n\
           normal, the depth at pixel centres in the same fixed point as\n\
           scanvert's, 2⁻¹⁴ of a Q12.4 unit, stepped along the span in `i32`)\n\
           and fill it with scanvert's exact rasteriser (`Rasterizer::fill`,\n\
           the pixel rule), each pixel tested against the buffer: `i16` cells\n\
           hold the depth rounded to Q12.4, `i32` cells the full fixed point;\n\
           a strict test keeps the earlier face at equal depth.\n\
           **`slice::fill`** clears and writes the covered pixel count\n\
           contiguously: the bandwidth limit.\n\
         - **Timing**: each contender draws all {VIEWS} views per pass; passes\n\
           are calibrated to runs of at least 30 ms and timed round-robin, {} runs\n\
           each, best kept. *ms per frame* is a pass over {VIEWS}; *× z-buffer*\n\
           is the `i16` z-buffer's time over the contender's (above 1: faster).\n\
         - **Error**: every view of every contender is compared pixel by pixel\n\
           with an independent exact reference (`testkit/src/reference3d.rs`:\n\
           the `i128` pixel rule, and the nearest depth at each pixel centre by\n\
           barycentric interpolation as exact fractions; ties to the earlier\n\
           face). *per 1000*: mismatched pixels per 1000 covered pixels, all\n\
           views; *worst frame*: most mismatches in one view.\n\
         - **Memory**: working state, the frame buffer ({} B) counted\n\
           separately, `size_of` on this 64-bit host. scanvert: the store's\n\
           slots the worst view needs (trapezoids, faces, one segment, 2 B an\n\
           index row, edge slots for the largest face), the active list and\n\
           cover entries for the most trapezoids on one row\n\
           (`Workspace::check`), one row of runs, and the `TrapezoidStore` and\n\
           `Workspace` structs. z-buffers: the depth buffer, edge slots and\n\
           the rasteriser's structs.\n",
        crate::visible3d::ROUNDS,
        thousands(W as f64 * H as f64 * 2.0)
    );
    let _ = writeln!(
        s,
        "| version | faces | trapezoids per frame | covered px per frame | depth complexity | most trapezoids on a row | intersecting spans per frame | subdivisions per frame (`Crossing` / `Bisect`) |\n\
         |---|--:|--:|--:|--:|--:|--:|--:|"
    );
    for st in &run.scenes3 {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.2} | {} | {} | {} / {} |",
            st.version.short(),
            st.faces,
            thousands(st.trapezoids),
            thousands(st.covered),
            st.complexity,
            st.max_active,
            thousands(st.intersecting),
            thousands(st.splits.0),
            thousands(st.splits.1)
        );
    }
    let _ = writeln!(
        s,
        "\n*Depth complexity*: the faces' pixels (each face alone, by the pixel\n\
         rule) over the covered pixels.\n"
    );
    for version in [Version::Layered, Version::Tilted] {
        let _ = writeln!(
            s,
            "### {}\n\n\
             | faces | contender | trapezoids per frame | frames/s | ms per frame | resolve + decode alone (ms) | × z-buffer (`i16`) | error per 1000 px | worst frame | memory (B) |\n\
             |--:|---|--:|--:|--:|--:|--:|--:|--:|---|",
            version.name()
        );
        for r in run.rows3.iter().filter(|r| r.version == version) {
            let (e, w) = match r.err {
                Some(e) => (format!("{:.3}", e.per_1000), thousands(e.worst as f64)),
                None => ("n/a".into(), "n/a".into()),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {}: {} |",
                r.faces,
                r.contender,
                thousands(r.trapezoids),
                thousands(1e3 / r.ms),
                ms(r.ms),
                r.resolve_ms.map_or("n/a".into(), ms),
                sig3(r.vs_z),
                e,
                w,
                thousands(r.mem.0 as f64),
                r.mem.1
            );
        }
        let _ = writeln!(s);
    }
    let bad: u64 = run
        .rows3
        .iter()
        .filter(|r| r.contender == CROSSING || r.contender == crate::visible3d::BISECT)
        .filter_map(|r| r.err.map(|e| e.total))
        .sum();
    let covered: f64 = run.scenes3.iter().map(|st| st.covered * VIEWS as f64).sum();
    let _ = writeln!(
        s,
        "scanvert, both modes, all scenes and views: {} mismatched pixels in\n\
         {} covered pixels (each mode).\n",
        bad,
        thousands(covered)
    );
    if let Some(c) = run.rows3.iter().find(|r| {
        r.version == Version::Tilted && r.faces == TARGET_FACES && r.contender == CROSSING
    }) {
        let _ = writeln!(
            s,
            "For scale: J. H. Jackson's 1980 figure for the classic scene is 170\n\
             polygons at {JACKSON_FPS} frames/s at 512×256. scanvert's default mode\n\
             draws the 170-face 3D version here at {} frames/s, cut included\n\
             ({:.0}× that), on this host.\n",
            thousands(1e3 / c.ms),
            1e3 / c.ms / JACKSON_FPS
        );
    }
    s
}

/// The whole page.
pub fn markdown(run: &Run, old: &str) -> String {
    let mut s = String::new();
    let rows = &run.rows;
    let _ = writeln!(
        s,
        "# Performance: speed against error\n\n\
         Generated by the benchmark binary; do not edit by hand (except the\n\
         on-target section, which its own script writes). Regenerate with:\n\n\
         ```sh\ncargo run --release -p scanvert-bench\n```\n\n\
         It rewrites this page, [`speed-vs-error.png`](speed-vs-error.png) and\n\
         [`time-vs-trapezoids.png`](time-vs-trapezoids.png) in about {:.0} s\n\
         (the 3D scenes take {:.0} s of it), and keeps the \"On target\" section (between the\n\
         `on-target:begin` and `on-target:end` HTML comments, each on a line\n\
         of its own) exactly as it finds it.\n",
        run.seconds.max(1.0),
        run.seconds3
    );
    let _ = writeln!(s, "## Machine\n\n{}", machine());
    let _ = writeln!(
        s,
        "- Load average (1, 5, 15 min) before the run: {}; after: {}\n",
        run.load_before, run.load_after
    );
    let _ = writeln!(
        s,
        "## How it is measured\n\n\
         - Every contender of a workload runs in the same process run. Each is\n\
           first calibrated so that one timed run repeats its pass for at least\n\
           200 ms; then all are timed round-robin, {} runs each, and the best run\n\
           counts. Ratios within one workload are the robust figures on a shared,\n\
           noisy machine; absolute rates move with the load (one outlier run can\n\
           still slip through: rerun before reading much into a single row).\n\
         - **Rate**: polygons (W3: triangles; W2: clears) per second.\n\
           **Mpixel/s**: the pixels the exact rule covers, per second, so all\n\
           contenders of a workload are counted alike. **× slice::fill**: Mpixel/s\n\
           over that of `slice::fill` writing the same number of pixels,\n\
           contiguously, into the same RGB565 buffer (the memory-bandwidth limit).\n\
         - **Error**: each polygon is drawn alone and every pixel of its box\n\
           (widened by 3 px) is compared with an independent `i128` per-pixel\n\
           implementation of the pixel rule (`testkit/src/reference.rs`).\n\
           *per 1000*: mismatched pixels per 1000 covered pixels; *worst*: most\n\
           mismatches in one polygon. tiny-skia and embedded-graphics follow\n\
           their own conventions; they are drawn from the same geometry and\n\
           compared as they are, not tuned: tiny-skia gets the exact Q12.4\n\
           coordinates as `f32`, embedded-graphics (whole-pixel `Point`s) gets\n\
           the pixel holding each vertex, and polygons become triangle fans.\n\
         - **Memory**: working state besides the frame buffer, which is counted\n\
           separately: 256×256 RGB565 is 131,072 B, 512×256 is 262,144 B;\n\
           tiny-skia's RGBA8888 pixmap is twice that. scanvert: the edge slots a\n\
           polygon needs (`size_of` of the stepper) plus the `Rasterizer`,\n\
           `ClipRect` and `Counts` structs; it allocates nothing.\n\
           tiny-skia: the peak of heap bytes live during `fill_path` above those\n\
           live before it, from a counting global allocator, worst polygon, plus\n\
           the `Path` (its struct, 8 B a point, 1 B a verb). embedded-graphics:\n\
           `size_of` its styled triangles and of the pixel iterator as a stand-in\n\
           for the scan-line state `draw` keeps on the stack. Stack frames are\n\
           not counted for anyone.\n",
        crate::ROUNDS
    );

    let _ = writeln!(s, "## Figures\n");
    let _ = writeln!(
        s,
        "| workload | contender | rate | Mpixel/s | × slice::fill | error per 1000 px | worst (one polygon) | memory (B) |\n\
         |---|---|--:|--:|--:|--:|--:|---|"
    );
    for r in rows {
        let (e, w) = match r.err {
            Some(e) => (format!("{:.3}", e.per_1000), thousands(e.worst as f64)),
            None if r.contender.starts_with("`slice") => ("n/a".into(), "n/a".into()),
            None => ("0 (clear)".into(), "0".into()),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} {} | {} | {} | {} | {} | {}: {} |",
            r.workload,
            r.contender,
            thousands(r.rate),
            r.unit,
            sig3(r.mpx),
            sig3(r.ratio),
            e,
            w,
            thousands(r.mem.0 as f64),
            r.mem.1
        );
    }
    let _ = writeln!(
        s,
        "\nWorkloads: W1 a 30×30 square drawn again and again, each copy 1 px\n\
         down and right of the last (226 positions, wrapping) in 256×256 RGB565;\n\
         W2 clears of 256×256; W3 10,000 random triangles (seeded), each within a\n\
         40×40 px box, vertices on the 1/16 px grid, in 512×256; W4 the W1 square\n\
         rotated by 17° (vertices rounded to 1/16 px, 218 positions); W5 one convex\n\
         12-gon covering most of 512×256.\n"
    );
    let _ = writeln!(
        s,
        "## Speed against error\n\n\
         ![speed against error](speed-vs-error.png)\n\n\
         One point per contender and workload (W2 and the bandwidth limit have\n\
         no error axis and are left out). Up is faster, relative to `slice::fill`\n\
         of the same pixels; left is more exact, with zero error in its own column.\n"
    );
    let _ = writeln!(
        s,
        "## The exact path against the independent reference\n\n\
         Before scanvert's exact path serves as the reference, it is checked\n\
         pixel by pixel against `testkit/src/reference.rs` on every polygon of\n\
         each workload (all of W3):\n\n\
         | workload | polygons | pixels tested | pixels covered | mismatches |\n|---|--:|--:|--:|--:|"
    );
    for c in &run.checks {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            c.workload,
            thousands(c.polygons as f64),
            thousands(c.tested as f64),
            thousands(c.covered as f64),
            c.mismatches
        );
    }
    let _ = writeln!(s);
    s.push_str(&section_3d(run));

    // Targets.
    let _ = writeln!(
        s,
        "## Targets (issue 5)\n\n| target | measured | verdict |\n|---|---|---|"
    );
    let exact = "scanvert exact (`Rasterizer::fill`)";
    if let (Some(e), Some(t)) = (find(rows, "W1", exact), find(rows, "W1", "tiny-skia")) {
        let k = e.rate / t.rate;
        let _ = writeln!(
            s,
            "| W1 ≥ 4× tiny-skia (no AA) | {:.2}× ({} vs {} polygons/s) | {}{} |",
            k,
            thousands(e.rate),
            thousands(t.rate),
            verdict(k >= 4.0),
            if k >= 4.0 {
                String::new()
            } else {
                format!(": short by {:.0} %", (1.0 - k / 4.0) * 100.0)
            }
        );
        let k = e.rate / REF_W1;
        let _ = writeln!(
            s,
            "| W1 ≥ 30× the reference design's 54,945 polygons/s | {:.1}× | {}{} |",
            k,
            verdict(k >= 30.0),
            if k >= 30.0 {
                String::new()
            } else {
                format!(": short by {:.0} %", (1.0 - k / 30.0) * 100.0)
            }
        );
    }
    if let Some(e) = find(rows, "W5", exact) {
        let _ = writeln!(
            s,
            "| W5 ≥ 0.5× slice::fill | {:.2}× | {}{} |",
            e.ratio,
            verdict(e.ratio >= 0.5),
            if e.ratio >= 0.5 {
                String::new()
            } else {
                format!(": short by {:.0} %", (1.0 - e.ratio / 0.5) * 100.0)
            }
        );
    }
    if let Some(e) = find(rows, "W2", "scanvert `FrameBuffer::clear`") {
        let _ = writeln!(
            s,
            "| W2 ≥ 0.9× slice::fill | {:.2}× ({} clears/s, {:.0}× the reference design's 763) | {}{} |",
            e.ratio,
            thousands(e.rate),
            e.rate / REF_W2,
            verdict(e.ratio >= 0.9),
            if e.ratio >= 0.9 { String::new() } else { format!(": short by {:.0} %", (1.0 - e.ratio / 0.9) * 100.0) }
        );
    }
    let exact_err: u64 = rows
        .iter()
        .filter(|r| r.contender == exact || r.contender.starts_with("scanvert exact, display"))
        .filter_map(|r| r.err.map(|e| e.total))
        .sum();
    let checked: u64 = run.checks.iter().map(|c| c.tested).sum();
    let _ = writeln!(
        s,
        "| default path: zero error | {} mismatches in {} pixels tested | {} |\n",
        exact_err,
        thousands(checked as f64),
        verdict(exact_err == 0)
    );
    if let Some(line) = target_3d(&run.rows3) {
        s.insert_str(
            s.rfind("| default path: zero error").unwrap_or(s.len()),
            &line,
        );
    }
    s.push_str(crate::report::NOTES);
    s.push_str(&crate::bands::kept_section(old));
    let _ = writeln!(s, "\n## On target\n\n{}", on_target_section(old));
    s
}

/// Hand-written notes on what limits the figures, from profiles (the
/// figures in them are instruction counts, which do not move with load).
pub const NOTES: &str = r#"## What limits the figures

Instruction counts below are from callgrind on W1 (100 passes, 22,600
polygons, the set-up of a run with 0 passes subtracted), with

```sh
cargo build --release -p scanvert-bench
valgrind --tool=callgrind target/release/scanvert-bench --profile-w1 MODE 100
```

where MODE is `null` (scan conversion into a target that discards the
spans), `framebuffer` (the exact path as measured above) or `tiny-skia`:

| W1, one 30×30 square | instructions per polygon | per row |
|---|--:|--:|
| scanvert scan conversion only (`null`) | 2,411 | 80 |
| scanvert exact into `FrameBuffer` (`framebuffer`) | 4,649 | 155 |
| tiny-skia `fill_path`, no AA (`tiny-skia`) | 14,393 | 480 |

- **W1 against tiny-skia.** Scan conversion itself is 52 % of the exact
  path's instructions; the other 48 % (about 75 instructions a row) is
  `FrameBuffer::fill_span`. A plain `slice::fill` is vectorised into a
  loop of two 16-byte stores for 16 pixels, a loop of 8-byte stores for 4,
  and single pixels, and on a 30-pixel run the set-up of the three loops
  costs more than the stores (6,298 instructions a polygon, 210 a row).
  So `fill_span` writes runs of 8 to 63 pixels as 8-pixel copies with one
  overlapping last copy, and only longer runs with `slice::fill` (8-pixel
  copies for long runs too lost 20 % on W5). tiny-skia spends its 14,393
  instructions in edge set-up and its edge walker (`fill_path_impl`,
  36 %), a `memcpy` of its pipeline state (11 %) and its blitter (20 %).
- **Faster options.** The DDA saves one compare and one conditional add
  per edge and row: about 5-20 % on W1, W3 and W4 (see the table), at the error
  shown. Snapping vertices to 1/4 px or whole pixels buys nothing in
  software (the per-row work is the same; the division per edge is the
  same): it only adds error. Fewer subpixel bits pay in hardware, where
  they narrow the adders.
- **W5 and W2.** A big polygon is bounded by the pixel writes: 256 spans
  of about 400 pixels each. A clear is one `slice::fill` in every
  contender except tiny-skia's, which writes 4 bytes a pixel.

### The 3D scenes against the z-buffer

Counted with callgrind on the 170-face 3D version (25 passes of its 4
views, the set-up of a run with 0 passes subtracted), with its simulated
branch predictor:

```sh
valgrind --tool=callgrind --branch-sim=yes \
  target/release/scanvert-bench --profile-3d MODE 25
```

| 170-face 3D scene, one frame (MODE) | instructions | mispredicted conditional branches (simulated) |
|---|--:|--:|
| scanvert `Crossing`, cut + resolve + decode (`crossing`) | 4.69 M | 77,800 |
| scanvert, the cut alone (`cut`) | 0.48 M | 2,800 |
| scanvert `Crossing`, resolve + decode alone (`crossing-alone`) | 4.21 M | 74,800 |
| scanvert `Bisect`, cut + resolve + decode (`bisect`) | 4.75 M | 79,600 |
| z-buffer, `i16` depth (`z16`) | 4.73 M | 21,100 |
| z-buffer, `i32` depth (`z32`) | 3.79 M | 21,000 |

- scanvert executes about as many instructions a frame as the z-buffers,
  yet takes more time on this host (see the tables). Its resolution branches
  on the data at every span (the sweep is a third of its instructions and
  half of its mispredicted branches); the z-buffer's loop (step the
  depth, compare, store or not; about 2.4 pixels tested per covered
  pixel) is regular, and its 256 or 512 KiB of depth stay in this CPU's
  1 MiB L2 cache. The frame clear (a `memset`) is the same for all.
- Cutting is a tenth of scanvert's frame: the frames where no segment
  changed save only that.
- The z-buffer's cost grows with the pixels it tests and scanvert's with
  the trapezoids, so scanvert leads on a few large faces and the z-buffer
  on many small ones; the tables and the plot show where the lines cross
  on this host.
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn on_target_section_is_kept_verbatim() {
        let old = format!("# x\n\nintro `{ON_TARGET_BEGIN}` `{ON_TARGET_END}`\n{ON_TARGET_BEGIN}\n| a | b |\n|--|--|\n| 1 | 2 |\n{ON_TARGET_END}\ntail\n");
        let kept = on_target_section(&old);
        assert_eq!(
            kept,
            format!("{ON_TARGET_BEGIN}\n| a | b |\n|--|--|\n| 1 | 2 |\n{ON_TARGET_END}")
        );
        assert!(on_target_section("").starts_with(ON_TARGET_BEGIN));
        assert!(on_target_section("").ends_with(ON_TARGET_END));
    }
}
