//! `docs/performance.md`, generated; the on-target section written by the
//! QEMU script is carried over verbatim.

use crate::numbers::thousands;
use crate::visible3d::{DepthRow, Row3, SplitRow, CROSSING, Z16, Z32};
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
    /// The depth-complexity sweep.
    pub depth: Vec<crate::visible3d::DepthRow>,
    /// P3 and P4 on the 3D scenes.
    pub split: Vec<crate::visible3d::SplitRow>,
    /// Wall time of those two.
    pub seconds_depth: f64,
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
           index row, edge slots for the largest face), the active list's\n\
           slots for the most trapezoids on one row\n\
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
        .filter(|r| {
            r.contender == CROSSING
                || r.contender == crate::visible3d::BISECT
                || r.contender == crate::visible3d::PAINT
        })
        .filter_map(|r| r.err.map(|e| e.total))
        .sum();
    let covered: f64 = run.scenes3.iter().map(|st| st.covered * VIEWS as f64).sum();
    let _ = writeln!(
        s,
        "scanvert, all three modes, all scenes and views: {} mismatched pixels in\n\
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
         It rewrites this page, [`speed-vs-error.png`](speed-vs-error.png),\n\
         [`time-vs-trapezoids.png`](time-vs-trapezoids.png),\n\
         [`time-vs-depth.png`](time-vs-depth.png) and\n\
         [`p3-p4-vs-trapezoids.png`](p3-p4-vs-trapezoids.png) in about {:.0} s\n\
         (the 3D scenes take {:.0} s of it), and keeps the \"On target\" section (between the\n\
         `on-target:begin` and `on-target:end` HTML comments, each on a line\n\
         of its own) and the sections after it (written by the examples and\n\
         tests they name) exactly as it finds them. The depth-complexity\n\
         sweep and the P3/P4 split alone are rewritten by `-- --only depth`\n\
         (see [their section](#depth-complexity-and-p3-against-p4)), the bands\n\
         by `-- --only bands`, and the worst cases' curve\n\
         ([`worst-case.png`](worst-case.png)) only by `-- --only worst`.\n",
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
    s.push_str(&section_depth(&run.depth, &run.split, run.seconds_depth));
    s.push_str(HISTORY);

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
    s.push_str(after_on_target(old));
    s
}

/// What follows the on-target section in `old`: the sections that other
/// tools write (the display path, racing the beam, RAM), kept verbatim.
pub fn after_on_target(old: &str) -> &str {
    marker_line(old, ON_TARGET_BEGIN, 0)
        .and_then(|b| marker_line(old, ON_TARGET_END, b))
        .map_or("", |e| {
            let rest = &old[e + ON_TARGET_END.len()..];
            rest.strip_prefix('\n').unwrap_or(rest)
        })
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
  on this host. The depth-complexity sweep above separates the two at a
  fixed face count: scanvert's time follows its trapezoid rows, the
  z-buffer's the pixels it tests.
- **From 300 to 1000 faces** (the 3D version; one frame, resolve +
  decode alone, `PROFILE_FACES=N` with the command above, the counts by
  a temporary counter in the sweep):

  | faces | 170 | 300 | 1000 |
  |---|--:|--:|--:|
  | trapezoids entering | 396 | 706 | 2,367 |
  | live trapezoids, summed over the 256 rows | 8,670 | 12,300 | 23,450 |
  | rows of more than 64 live (`sweep_many`) | 0 | 0 | 254 |
  | spans: empty / single / multiple / intersecting | 1,343 / 2,588 / 4,242 / 291 | 1,271 / 2,804 / 5,589 / 279 | 2,039 / 4,722 / 10,657 / 536 |
  | fronts sought; covers compared on average (most) | 7,120; 2.3 (8) | 8,670; 2.3 (9) | 15,900; 2.2 (8) |
  | instructions, before → after | 3.62 M → 3.67 M | 4.83 M → 4.89 M | 16.36 M → 10.91 M |
  | mispredicted branches, before → after | 65.9 k → 56.3 k | 86.2 k → 72.9 k | 249.8 k → 149.1 k |

  The covers stay at about 2, so nothing in the sweep was quadratic; the
  growth was the sort. At 1000 faces 254 of the 256 rows have more than
  64 live trapezoids, and on 55 of them one that entered (listed after
  the live ones) or that had pixels again after a row with none (sorted
  last) moved more than 64 places and sent the row to the heap sort
  (about 85 entries each): 30 % of the frame's instructions. Such rows now
  sort the entered trapezoids apart, merge them in, and allow the whole
  row 64 moves an entry. What grows from 300 to 1000 faces is then the
  live trapezoid rows (1.9×), the spans (1.8×) and the entering
  trapezoids (3.35×: edge set-up, the merge), 2.2× in all (the 2D version:
  16.01 M → 10.56 M instructions at 1000 faces). On this host the
  mispredicted branches weigh as much as the instructions: the edges'
  carries were mispredicted about every other step (21 k a frame at 1000
  faces) and now step by a mask on x86 and AArch64 (the Cortex-M4 keeps
  the branch), 12 % fewer mispredicted branches for 1 % more
  instructions and about 9 % less time. The `i32` z-buffer's frame at 1000 faces is 6.95 M
  instructions and 67 k mispredicted branches; what separates scanvert
  from it is the data-dependent branches of the sweep at every live
  trapezoid and span (the depth compares, the covers' ends, the front's
  end), not one term that grows faster than the scene. With about 2
  covers, `sweep` would take 5 to 8 % fewer instructions than `sweep_many`
  on the rows of 65 to 111 but 3 % more mispredicted branches, and timed
  no faster; `sweep_many` stays for the worst cases.
- **A one-row depth buffer for crowded rows**, measured and not kept.
  A row was resolved in a buffer of one row instead of by the sweep:
  8 pixels a cell of 64 bytes, 4 KiB at 512 pixels. Each live trapezoid
  was tested pixel by pixel with the sweep's own test, in groups of 8
  with no branch (SSE2 on this host). Cells within `DEPTH_TOLERANCE`
  were decided by the exact comparison. The row was then read back as
  runs. It was exact: 0 mismatched pixels in every scene of the
  benchmark. The times are for the 3D version, with the same binary and
  only the rule changed, from `perf record -e cpu-clock` samples of
  `--profile-3d crossing-alone 500`. The set-up of the scene is included
  and is the same in every case.

  | rows in the depth row | 170 faces | 300 faces | 1000 faces |
  |---|--:|--:|--:|
  | none (the sweep, as published) | 3,178 | 4,493 | 10,972 |
  | every row of ≥ 32 live trapezoids | 4,005 (+26 %) | 5,418 (+21 %) | 10,263 (−6.5 %) |
  | ≥ 24 live, and their mean span under 16 pixels | 3,141 (−1 %) | 4,552 (+1 %) | 9,833 (−10 %) |

  The layered 1000-face version gained 1–3 % under the same rules.
  - Testing a pixel took about 2.5 cycles. The spans are short, so
    about half the lanes of a group of 8 sit outside the span.
  - Reading the 512 pixels back and writing the runs cost about as much
    as the sweep's own run writes.
  - A z-buffer wins where pixels are few per trapezoid. At 170 faces,
    with 2.4 surfaces a pixel, testing the pixels costs more than the
    sweep's spans.

  At 1000 faces the gain is at most 10 %, against the 1.8× that the
  `i32` z-buffer is ahead there. It would also need a buffer the
  caller lends and a rule tuned to this host's vector width, and it would
  lose on cores without SIMD, the Cortex-M4 among them (about 8
  instructions a pixel tested). So the sweep stays the only path.
"#;

/// Markers of the section `--only depth` rewrites.
pub const DEPTH_BEGIN: &str = "<!-- depth-sweep:begin -->";
/// End marker.
pub const DEPTH_END: &str = "<!-- depth-sweep:end -->";
/// Markers of the history section.
pub const HISTORY_BEGIN: &str = "<!-- history:begin -->";
/// End marker.
pub const HISTORY_END: &str = "<!-- history:end -->";

/// `old` with the section between `begin` and `end` (markers included,
/// each on a line of its own, and the blank lines after the end) replaced
/// by `new`; when `old` has no such
/// section, `new` goes before the line `before` (or at the end).
pub fn splice(old: &str, begin: &str, end: &str, new: &str, before: &str) -> String {
    if let Some(b) = marker_line(old, begin, 0) {
        if let Some(e) = marker_line(old, end, b) {
            // The end marker and the blank lines after it: `new` brings
            // its own.
            let e = e + end.len();
            let e = e + (old[e..].len() - old[e..].trim_start_matches('\n').len());
            return format!("{}{}{}", &old[..b], new, &old[e..]);
        }
    }
    match marker_line(old, before, 0) {
        Some(at) => format!("{}{}{}", &old[..at], new, &old[at..]),
        None => format!("{old}{new}"),
    }
}

/// The depth-complexity sweep and the P3/P4 split, between their markers.
pub fn section_depth(depth: &[DepthRow], split: &[SplitRow], seconds: f64) -> String {
    let mut s = String::new();
    if depth.is_empty() && split.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "{DEPTH_BEGIN}\n## Depth complexity, and P3 against P4\n\n\
         This section and its two plots are rewritten alone, in about {:.0} s, by\n\n\
         ```sh\ncargo run --release -p scanvert-bench -- --only depth\n```\n\n\
         (the rest of the page is kept as it is); the full run writes them too.\n\
         Timing, error and the z-buffers are as in the section above, but\n\
         with {} timed runs of each contender (best kept), as these ratios are\n\
         read across scenes timed at different moments.\n",
        seconds.max(1.0),
        crate::visible3d::ROUNDS_DEPTH
    );
    if !depth.is_empty() {
        let _ = writeln!(
            s,
            "### Time against depth complexity\n\n\
             ![time against depth complexity](time-vs-depth.png)\n\n\
             {} faces at {W}×{H}, whose *depth complexity* (the faces' pixels,\n\
             each face alone by the pixel rule, over the covered pixels, all\n\
             {VIEWS} views) is aimed at 1, 2, 4, 8, 16 and 40 and measured here\n\
             exactly: `testkit::scenes3d::depth_scene` stacks that many layers,\n\
             each a tiling of the frame by about {} ÷ depth parallelograms\n\
             (a grid turned by 7° to 27°, jittered), so that every pixel is\n\
             covered exactly that many times. The **2D version** gives each\n\
             face a depth of its own (parallel to the screen); the **3D\n\
             version** tilts the same outlines through each other. The faces\n\
             grow with the depth complexity (the face count is fixed), so the\n\
             trapezoid count changes little while the pixels a z-buffer tests\n\
             grow as covered × depth complexity.\n",
            depth[0].faces, depth[0].faces
        );
        let _ = writeln!(
            s,
            "| version | depth aimed | depth measured | covered px per frame | trapezoids per frame | trapezoid rows per frame | spans per frame | hidden per frame | intersecting spans per frame | scanvert (ms) | z-buffer `i16` (ms) | z-buffer `i32` (ms) | faster z-buffer ÷ scanvert | z `i16` ns per tested px | scanvert ns per trapezoid row | mismatches: scanvert / `i16` / `i32` |\n\
             |---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|"
        );
        let v = VIEWS as f64;
        for r in depth {
            let tested = r.covered * r.complexity;
            let _ = writeln!(
                s,
                "| {} | {} | {:.2} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2}× | {:.2} | {:.2} | {} / {} / {} |",
                r.version.short(),
                r.aimed,
                r.complexity,
                thousands(r.covered),
                thousands(r.trapezoids),
                thousands(r.trapezoid_rows),
                thousands(r.spans()),
                thousands(r.stats.hidden as f64 / v),
                thousands(r.stats.intersecting as f64 / v),
                ms(r.ms[0]),
                ms(r.ms[1]),
                ms(r.ms[2]),
                r.ms[1].min(r.ms[2]) / r.ms[0],
                r.ms[1] * 1e6 / tested.max(1.0),
                r.ms[0] * 1e6 / r.trapezoid_rows.max(1.0),
                r.err[0].total,
                r.err[1].total,
                r.err[2].total
            );
        }
        let bad: u64 = depth.iter().map(|r| r.err[0].total).sum();
        let covered: f64 = depth.iter().map(|r| r.covered * VIEWS as f64).sum();
        let _ = writeln!(
            s,
            "\nscanvert (`Resolve::Crossing`, cut + resolve + decode) against the\n\
             exact reference, all depths, versions and views: **{bad} mismatched\n\
             pixels** in {} covered pixels. *Faster z-buffer ÷ scanvert*: above 1,\n\
             scanvert is faster; it compares contenders timed round-robin together\n\
             and is the robust figure, while a scene timed when this shared machine\n\
             was busier shifts all three of its times together. *Spans*: what the\n\
             sweep classified (empty,\n\
             single, multiple, intersecting); *hidden*: trapezoids left out\n\
             where they start because the front hides them.\n",
            thousands(covered)
        );
        let _ = writeln!(s, "Where each wins, on this host:\n");
        for version in [Version::Layered, Version::Tilted] {
            let rows: Vec<&DepthRow> = depth.iter().filter(|r| r.version == version).collect();
            let (Some(lo), Some(hi)) = (rows.first(), rows.last()) else {
                continue;
            };
            let at = |keep: &dyn Fn(f64) -> bool| {
                let v: Vec<String> = rows
                    .iter()
                    .filter(|r| keep(r.ms[1].min(r.ms[2]) / r.ms[0]))
                    .map(|r| format!("{}", (r.complexity * 100.0).round() / 100.0))
                    .collect();
                if v.is_empty() {
                    "none".to_string()
                } else {
                    v.join(", ")
                }
            };
            let wins = format!(
                "{}; within 5 % of the faster z-buffer at {}; the z-buffer faster\n  \
                 by more than 5 % at {}",
                at(&|k| k > 1.05),
                at(&|k| (1.0 / 1.05..=1.05).contains(&k)),
                at(&|k| k < 1.0 / 1.05)
            );
            let z_grow = hi.ms[1] / lo.ms[1];
            let s_grow = hi.ms[0] / lo.ms[0];
            let _ = writeln!(
                s,
                "- **{}**: scanvert faster than both z-buffers by more than\n  \
                 5 % at depth complexity {}. From {:.2} to {:.2}, the `i16`\n  \
                 z-buffer's time grows {:.1}× ({} to {} ms; the pixels it tests,\n  \
                 covered × depth, grow {:.1}×) and scanvert's {:.1}× ({} to {} ms;\n  \
                 its trapezoid rows grow {:.1}×, its spans {:.2}×, its trapezoids\n  \
                 {:.2}×).",
                version.name(),
                wins,
                lo.complexity,
                hi.complexity,
                z_grow,
                ms(lo.ms[1]),
                ms(hi.ms[1]),
                (hi.covered * hi.complexity) / (lo.covered * lo.complexity).max(1.0),
                s_grow,
                ms(lo.ms[0]),
                ms(hi.ms[0]),
                hi.trapezoid_rows / lo.trapezoid_rows.max(1.0),
                hi.spans() / lo.spans().max(1.0),
                hi.trapezoids / lo.trapezoids.max(1.0)
            );
        }
        let range = |f: &dyn Fn(&DepthRow) -> f64| {
            let v = depth.iter().map(f);
            let (lo, hi) = v.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
            format!("{} to {}", sig3(lo), sig3(hi))
        };
        let _ = writeln!(
            s,
            "\nWhy: the z-buffer steps, compares and perhaps stores at every pixel\n\
             of every face, so its time follows covered pixels × depth\n\
             complexity, plus a part that does not (the depth and frame clears,\n\
             the set-up of each face and span), which is why its time per tested\n\
             pixel falls as the faces grow ({} ns, `i16`). The sweep does\n\
             nothing per pixel: each active trapezoid is stepped, kept in order\n\
             and looked through on every row it spans, so its time follows the\n\
             trapezoid rows ({} ns a trapezoid row, nearly flat). With\n\
             the face count fixed, the faces grow in area as the depth complexity\n\
             and in height as its square root, and so do the trapezoid rows,\n\
             while the spans even fall, because a face that starts behind the\n\
             front is hidden for two depth compares. So the z-buffer wins where\n\
             few pixels are tested twice (depth complexity near 1, where the sweep\n\
             still pays per row for every trapezoid) and the sweep wins from\n\
             where the pixels tested outgrow the trapezoid rows; interpenetrating\n\
             faces (3D version) cost the sweep its intersecting spans'\n\
             subdivisions and a front that holds less often, a little more a row.\n",
            range(&|r| r.ms[1] * 1e6 / (r.covered * r.complexity).max(1.0)),
            range(&|r| r.ms[0] * 1e6 / r.trapezoid_rows.max(1.0))
        );
    }
    if !split.is_empty() {
        let _ = writeln!(
            s,
            "### P3 and P4 against trapezoids\n\n\
             ![P3 and P4 against trapezoids](p3-p4-vs-trapezoids.png)\n\n\
             The scenes of the section above (10 to 1000 faces), their\n\
             visible-surface time split as J. H. Jackson's 1980 figures split\n\
             it: **P3**, the sweep producing run-length rows with no pixel\n\
             written (`Workspace::resolve` in `Resolve::Crossing` into a sink\n\
             that discards each row), and **P4**, the frame cleared and the\n\
             stored rows decoded into RGB565 pixels (`rle::decode_row` over the\n\
             runs P3 produced, kept beforehand; the decoded frame is checked\n\
             equal to `visible::draw`'s). *Fused* is `visible::draw` (the frame\n\
             cleared, then resolved and written with no row buffer between): the\n\
             \"resolve + decode alone\" of the tables above. All from stores cut\n\
             beforehand (no cut); the six passes of both versions of a size are\n\
             timed round-robin together, so that their ratios hold under load.\n"
        );
        let _ = writeln!(
            s,
            "| version | faces | trapezoids per frame | runs per frame | P3 (ms) | P4 (ms) | P3 + P4 (ms) | fused (ms) | P3 share |\n\
             |---|--:|--:|--:|--:|--:|--:|--:|--:|"
        );
        for r in split {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {:.0} % |",
                r.version.short(),
                r.faces,
                thousands(r.trapezoids),
                thousands(r.runs),
                ms(r.p3_ms),
                ms(r.p4_ms),
                ms(r.p3_ms + r.p4_ms),
                ms(r.both_ms),
                100.0 * r.p3_ms / (r.p3_ms + r.p4_ms)
            );
        }
        let ratios: Vec<String> = split
            .iter()
            .filter(|r| r.version == Version::Tilted)
            .filter_map(|t| {
                let l = split
                    .iter()
                    .find(|l| l.version == Version::Layered && l.faces == t.faces)?;
                Some(format!("{}: {:.2}×", t.faces, t.p3_ms / l.p3_ms))
            })
            .collect();
        let _ = writeln!(
            s,
            "\nP3 of the 3D version over P3 of the 2D version, by faces: {}.\n\
             The fused path takes {} × P3 + P4: the same work, sweep and\n\
             writes alternating row by row, against two separate passes (not\n\
             profiled here).\n\
             Jackson found his P3 about ten times slower in 3D than in 2D; here\n\
             the two versions share outlines and depth complexity, and the sweep\n\
             resolves a parallel and a tilted plane alike (a depth compare at\n\
             both ends of a common span), so the 3D version costs only its\n\
             intersecting spans' subdivisions more. P4 follows the runs and the\n\
             pixels, the same in both versions.\n",
            ratios.join(", "),
            {
                let v = split.iter().map(|r| r.both_ms / (r.p3_ms + r.p4_ms));
                let (lo, hi) = v.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
                format!("{lo:.2} to {hi:.2}")
            }
        );
    }
    let _ = writeln!(s, "{DEPTH_END}\n");
    s
}

/// Measured figures and their history, moved here from module docs.
pub const HISTORY: &str = r#"<!-- history:begin -->
## History: figures measured before

Figures measured on earlier states of the code, kept here so that module
docs describe the code and this page holds what was measured. Each says
where and how it was measured; they are not rerun by the benchmark.

### The sweep before it kept a front (Cortex-M4 image, instructions)

From the module docs of `firmware/scanvert/src/visible/sweep.rs` (the
*Measured* section, as of commit `d3fa7ac`). Before the sweep kept a
front (it classified a span between every two neighbouring `l` and `r`:
about 9 500 spans a `flat` row set against 5 500 fronts since), an
earlier variant of the firmware image measured four 512 × 256 scenes,
every pixel written (background filled), against a plain z-buffer at the
same precision (32-bit depth per pixel, the same fixed-point planes, the
exact rasteriser's spans, runs of passing pixels written as spans; its
depth clear included), in instructions per 512 × 256 RGB565 frame:

| scene | faces drawn | trapezoids | cut (once per change) | resolve + decode, crossing | bisection | z-buffer |
|---|---|---|---|---|---|---|
| flat: 170 faces parallel to the screen | 170 | 249 | 0.60 M | 2.61 M | 2.61 M | 4.36 M |
| tilted: 170 tilted faces, interpenetrating | 170 | 375 | 0.83 M | 2.94 M | 2.95 M | 3.89 M |
| bars: a 10 × 7 map and 20 bars | 130 | 386 | 0.80 M | 1.87 M | 1.87 M | 2.68 M |
| dense: 170 large triangles through each other (depth complexity about 40) | 170 | 322 | 0.79 M | 23.4 M | 23.7 M | 46.0 M |

At 168 M instructions/s that was 64, 57, 90 and 7 frames/s when only the
visible surfaces are recomputed, against 39, 43, 63 and 4 for the
z-buffer, with 512 KiB less memory (the whole 3D layer of `bars` took
about 54 KiB). The two modes differ only where planes intersect: on
`tilted`, 246 intersecting spans took 709 subdivisions by bisection and
246 at the crossing point; on `dense`, 951 took 2 028 and 974. The
crossing point was made the default.

### The sweep with a front (Cortex-M4 image, instructions)

From the same module docs: the firmware image renders `flat` and
`tilted` as `poly3-layered` and `poly3-tilted` (one colour per face, the
background left as it is) and counts the cut and the resolution
separately. There resolving and decoding took about 2.1 M instructions a
frame on `flat` and 2.5 M on `tilted`, and cutting 0.48 M and 0.69 M. The
current counts are in the on-target section below (*The 3D layer, stage
by stage*), written by `firmware/image/measure.sh`.

### Error (host)

From the same module docs: against the exact reference of `host_tests`
(coverage by the pixel rule, nearest plane at each pixel centre, ties to
the earlier polygon), **0 mismatched pixels** in both modes on the
property tests' layered and interpenetrating scenes (about 120 000
covered pixels a run of 200 scenes, with a few hundred intersecting
spans) and on the four scenes above; a z-buffer at the same depth
precision missed ties and near-ties (1 pixel in 131 072 on `dense`).
`cargo run --release -p host-tests --example visible_modes` measures the
same scenes on the host.
<!-- history:end -->

"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_full_page_holds_the_depth_and_history_sections_once() {
        use crate::visible3d::{DepthRow, Err3, SplitRow};
        let depth = vec![DepthRow {
            version: Version::Tilted,
            faces: 170,
            aimed: 4,
            complexity: 4.0,
            covered: 131_072.0,
            trapezoids: 435.0,
            trapezoid_rows: 10_000.0,
            stats: Default::default(),
            ms: [0.4, 0.5, 0.45],
            err: [Err3::default(); 3],
        }];
        let split = vec![SplitRow {
            version: Version::Layered,
            faces: 10,
            trapezoids: 23.0,
            runs: 1_000.0,
            p3_ms: 0.02,
            p4_ms: 0.01,
            both_ms: 0.03,
        }];
        let run = Run {
            rows: Vec::new(),
            checks: Vec::new(),
            rows3: Vec::new(),
            scenes3: Vec::new(),
            seconds3: 1.0,
            load_before: "0".into(),
            load_after: "0".into(),
            seconds: 2.0,
            depth,
            split,
            seconds_depth: 3.0,
        };
        let page = markdown(&run, "");
        for m in [
            DEPTH_BEGIN,
            DEPTH_END,
            HISTORY_BEGIN,
            HISTORY_END,
            ON_TARGET_BEGIN,
        ] {
            assert_eq!(page.matches(&format!("{m}\n")).count(), 1, "{m}");
        }
        assert!(page.contains("time-vs-depth.png") && page.contains("p3-p4-vs-trapezoids.png"));
        // What `--only depth` does to the page changes nothing more.
        let section = section_depth(&run.depth, &run.split, run.seconds_depth);
        let again = splice(
            &page,
            DEPTH_BEGIN,
            DEPTH_END,
            &section,
            "## Targets (issue 5)",
        );
        let again = splice(
            &again,
            HISTORY_BEGIN,
            HISTORY_END,
            HISTORY,
            "## Targets (issue 5)",
        );
        assert_eq!(again, page);
    }

    #[test]
    fn splice_replaces_the_marked_section_or_inserts_it() {
        let new = format!("{DEPTH_BEGIN}\nnew\n{DEPTH_END}\n");
        let old = format!("# x\n{DEPTH_BEGIN}\nold\n{DEPTH_END}\n## Targets\ntail\n");
        assert_eq!(
            splice(&old, DEPTH_BEGIN, DEPTH_END, &new, "## Targets"),
            format!("# x\n{new}## Targets\ntail\n")
        );
        let bare = "# x\n## Targets\ntail\n";
        let once = splice(bare, DEPTH_BEGIN, DEPTH_END, &new, "## Targets");
        assert_eq!(once, format!("# x\n{new}## Targets\ntail\n"));
        assert_eq!(
            splice(&once, DEPTH_BEGIN, DEPTH_END, &new, "## Targets"),
            once,
            "idempotent"
        );
        assert_eq!(splice("a\n", "<b>", "<e>", "n\n", "## T"), "a\nn\n");
    }

    #[test]
    fn on_target_section_is_kept_verbatim() {
        let old = format!("# x\n\nintro `{ON_TARGET_BEGIN}` `{ON_TARGET_END}`\n{ON_TARGET_BEGIN}\n| a | b |\n|--|--|\n| 1 | 2 |\n{ON_TARGET_END}\ntail\n");
        let kept = on_target_section(&old);
        assert_eq!(
            kept,
            format!("{ON_TARGET_BEGIN}\n| a | b |\n|--|--|\n| 1 | 2 |\n{ON_TARGET_END}")
        );
        assert_eq!(after_on_target(&old), "tail\n");
        assert_eq!(after_on_target(""), "");
        assert!(on_target_section("").starts_with(ON_TARGET_BEGIN));
        assert!(on_target_section("").ends_with(ON_TARGET_END));
    }
}
