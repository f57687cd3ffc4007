//! `docs/performance.md`, generated; the blocks the QEMU script writes (the
//! Cortex-M4 half of the first screen, the on-target section) and what
//! follows the on-target section are carried over verbatim.

use crate::numbers::thousands;
use crate::visible3d::{DepthRow, Row3, SplitRow, CROSSING, Z16, Z32};
use crate::Row;
use std::fmt::Write;
use testkit::scenes3d::{Version, DEPTH_COMPLEXITY, H, VIEWS, W};

/// Markers of the section another script owns.
pub const ON_TARGET_BEGIN: &str = "<!-- on-target:begin -->";
/// End marker.
pub const ON_TARGET_END: &str = "<!-- on-target:end -->";

/// The reference design's figures: polygons/s on W1, clears/s of
/// 256 × 256.
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

/// The contender the default resolve is on the 170-face tilted scene
/// (crossing points when the scene was not run).
fn default_3d(run: &Run) -> &'static str {
    run.scenes3
        .iter()
        .find(|st| st.version == Version::Tilted && st.faces == TARGET_FACES)
        .map_or(CROSSING, |st| st.default)
}

/// The target row: the 170-face 3D version (the default resolve) against
/// the z-buffers.
fn target_3d(rows: &[Row3], default: &str) -> Option<String> {
    let at = |name: &str| {
        rows.iter().find(|r| {
            r.version == Version::Tilted && r.faces == TARGET_FACES && r.contender == name
        })
    };
    let (c, z16, z32) = (at(default)?, at(Z16)?, at(Z32)?);
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

/// The 3D section: how it is measured, the scenes, one table of both
/// versions with a column per contender.
fn section_3d(run: &Run) -> String {
    let mut s = String::new();
    if run.rows3.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "## 3D scenes: scan-line visible surfaces against a z-buffer\n\n\
         ![time against trapezoids](time-vs-trapezoids.png)\n\n\
         Scenes of 10 to 1000 front-facing `poly3` faces at {W}×{H}\n\
         (`testkit/src/scenes3d.rs`, seeded), their summed area about\n\
         {DEPTH_COMPLEXITY} frames. The **2D version** has every face parallel to\n\
         the screen at a depth of its own; the **3D version** has the same\n\
         outlines tilted, some through others. Each is seen from {VIEWS} views,\n\
         panned so that every face changes in every frame.\n\n\
         A frame: the RGB565 frame cleared, every face cut into trapezoids and\n\
         the frame resolved in one of scanvert's three modes (*alone*: nothing\n\
         changed, no cut), or each face filled by the exact rasteriser into a\n\
         z-buffer of `i16` (Q12.4) or `i32` depth. Passes of all {VIEWS} views,\n\
         timed round-robin, {} runs each, best kept; ms per frame. Errors\n\
         against `testkit/src/reference3d.rs`, per 1000 covered pixels. Memory:\n\
         working state besides the frame buffer ({} B), on this 64-bit host.\n",
        crate::visible3d::ROUNDS,
        thousands(W as f64 * H as f64 * 2.0)
    );
    let _ = writeln!(
        s,
        "| version | faces | trapezoids | depth complexity | intersecting spans (subdivisions: `Crossing` / `Bisect`) | `Crossing` (ms) | alone | `Bisect` | `Paint` | alone | z `i16` | z `i32` | `slice::fill` | `Crossing` ÷ faster z | z errors per 1000 (`i16` / `i32`) | scanvert memory (B) | z `i16` memory (B) |\n\
         |---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
    );
    for st in &run.scenes3 {
        let at = |name: &str| {
            run.rows3
                .iter()
                .find(|r| r.version == st.version && r.faces == st.faces && r.contender == name)
        };
        let time = |name: &str| at(name).map_or("n/a".into(), |r| ms(r.ms));
        let alone = |name: &str| at(name).and_then(|r| r.resolve_ms).map_or("n/a".into(), ms);
        let err = |name: &str| {
            at(name)
                .and_then(|r| r.err)
                .map_or("n/a".into(), |e| format!("{:.3}", e.per_1000))
        };
        let mem = |name: &str| at(name).map_or("n/a".into(), |r| thousands(r.mem.0 as f64));
        let ratio = match (at(CROSSING), at(Z16), at(Z32)) {
            (Some(c), Some(a), Some(b)) => format!("{}×", sig3(c.ms / a.ms.min(b.ms))),
            _ => "n/a".into(),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2} | {} ({} / {}) | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} | {} | {} |",
            st.version.short(),
            st.faces,
            thousands(st.trapezoids),
            st.complexity,
            thousands(st.intersecting),
            thousands(st.splits.0),
            thousands(st.splits.1),
            time(CROSSING),
            alone(CROSSING),
            time(crate::visible3d::BISECT),
            time(crate::visible3d::PAINT),
            alone(crate::visible3d::PAINT),
            time(Z16),
            time(Z32),
            time(crate::visible3d::LIMIT),
            ratio,
            err(Z16),
            err(Z32),
            mem(CROSSING),
            mem(Z16)
        );
    }
    let (bad, covered) = exact_3d(run);
    let _ = writeln!(
        s,
        "\n*÷ faster z*: scanvert's time over the faster z-buffer's (below 1:\n\
         scanvert is faster). scanvert, all three modes, all scenes and views:\n\
         **{} mismatched pixels** in {} covered pixels (each mode).\n",
        bad,
        thousands(covered)
    );
    let default = default_3d(run);
    if let Some(c) = run
        .rows3
        .iter()
        .find(|r| r.version == Version::Tilted && r.faces == TARGET_FACES && r.contender == default)
    {
        let _ = writeln!(
            s,
            "For scale: J. H. Jackson's 1980 figure for the classic scene is 170\n\
             polygons at {JACKSON_FPS} frames/s at 512×256; the default mode draws\n\
             the 170-face 3D version here at {} frames/s, cut included.\n",
            thousands(1e3 / c.ms)
        );
    }
    s
}

/// The host's half of the first screen: scanvert against its peers, and
/// how exact it is.
fn headline_host(run: &Run) -> String {
    let mut s = String::new();
    let rows = &run.rows;
    let exact = "scanvert exact (`Rasterizer::fill`)";
    let _ = writeln!(
        s,
        "| Host, timed by `cargo run --release -p scanvert-bench` (ratios within one process run) | |\n\
         |---|--:|"
    );
    let ratio = |wl: &str, peer: &str| match (find(rows, wl, exact), find(rows, wl, peer)) {
        (Some(e), Some(p)) => format!("{}×", sig3(e.rate / p.rate)),
        _ => "n/a".into(),
    };
    let _ = writeln!(
        s,
        "| W1, 30 × 30 squares: scanvert's exact path against tiny-skia (no AA) / embedded-graphics | {} / {} |",
        ratio("W1", "tiny-skia"),
        ratio("W1", "embedded-graphics")
    );
    let _ = writeln!(
        s,
        "| W3, 10,000 small triangles: the same | {} / {} |",
        ratio("W3", "tiny-skia"),
        ratio("W3", "embedded-graphics")
    );
    let fill = |wl: &str| find(rows, wl, exact).map_or("n/a".into(), |r| sig3(r.ratio));
    let _ = writeln!(
        s,
        "| W1 / W3 / W5 (one large 12-gon): × `slice::fill` of the same pixels (the bandwidth limit) | {} / {} / {} |",
        fill("W1"),
        fill("W3"),
        fill("W5")
    );
    let at = |name: &str| {
        run.rows3.iter().find(|r| {
            r.version == Version::Tilted && r.faces == TARGET_FACES && r.contender == name
        })
    };
    let default = default_3d(run);
    if let (Some(c), Some(z16), Some(z32)) = (at(default), at(Z16), at(Z32)) {
        let _ = writeln!(
            s,
            "| {TARGET_FACES} tilted 3D faces: the default resolve's speed ({}) over the faster z-buffer's, and its memory over the `i16` z-buffer's | {}×, {:.0} % |",
            if default == crate::visible3d::PAINT {
                "painted far to near"
            } else {
                "crossing points"
            },
            sig3(z16.ms.min(z32.ms) / c.ms),
            100.0 * c.mem.0 as f64 / z16.mem.0 as f64
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
        "| Exact, 2D: the default path against the `i128` reference, pixels tested | **{}** mismatches in {} |",
        exact_err,
        thousands(checked as f64)
    );
    let (bad, covered) = exact_3d(run);
    let _ = writeln!(
        s,
        "| Exact, 3D: each of the three resolves against the exact reference, covered pixels | **{}** mismatches in {} |",
        bad,
        thousands(covered)
    );
    s
}

/// Markers of the Cortex-M4 half of the first screen, which
/// `firmware/image/measure.sh` writes; the benchmark keeps it.
pub const HEADLINE_BEGIN: &str = "<!-- headline-target:begin -->";
/// End marker.
pub const HEADLINE_END: &str = "<!-- headline-target:end -->";

/// The section between `begin` and `end` in `old` (markers included), or
/// the markers around `placeholder`.
fn kept(old: &str, begin: &str, end: &str, placeholder: &str) -> String {
    if let Some(b) = marker_line(old, begin, 0) {
        if let Some(e) = marker_line(old, end, b) {
            return old[b..e + end.len()].to_string();
        }
    }
    format!("{begin}\n{placeholder}\n{end}")
}

/// The whole page.
pub fn markdown(run: &Run, old: &str) -> String {
    let mut s = String::new();
    let rows = &run.rows;
    let _ = writeln!(
        s,
        "# Performance\n\n\
         What scanvert costs: on the Cortex-M4, instructions counted in QEMU; on\n\
         a host, time against its peers. Every table is written by the tool\n\
         named with it, never by hand. How the figures came to be, and the\n\
         changes measured and not kept, are in [performance-log.md](performance-log.md).\n\n\
         ## At a glance\n\n{}\n\n{}\n\
         Regenerate with `firmware/image/measure.sh` (the Cortex-M4 table and\n\
         [On target](#on-target); `--check` only compares) and\n\
         `cargo run --release -p scanvert-bench` (the host's tables, about\n\
         {:.0} s; the 3D scenes {:.0} s of it). The benchmark keeps the blocks\n\
         other tools write (between `NAME:begin` and `NAME:end` HTML comments)\n\
         and everything after the on-target block as it finds them; `-- --only\n\
         depth`, `-- --only bands`, `-- --only worst` and `-- --only model`\n\
         rewrite their own block.\n",
        kept(
            old,
            HEADLINE_BEGIN,
            HEADLINE_END,
            "_Not measured yet: `firmware/image/measure.sh` writes its figures here._"
        ),
        headline_host(run),
        run.seconds.max(1.0),
        run.seconds3
    );
    let _ = writeln!(
        s,
        "## 2D polygons: speed against error\n\n\
         Written by `cargo run --release -p scanvert-bench`.\n\n{}\
         - Load average (1, 5, 15 min) before the run: {}; after: {}\n",
        machine(),
        run.load_before,
        run.load_after
    );
    let _ = writeln!(
        s,
        "Every contender of a workload runs in one process, each pass calibrated\n\
         to at least 200 ms, timed round-robin, {} runs each, best kept: ratios\n\
         within a workload hold on a shared machine, absolute rates move with\n\
         the load. *Mpixel/s*: pixels the exact rule covers, per second; *×\n\
         slice::fill*: over `slice::fill` writing as many pixels. *Error*: each\n\
         polygon alone against an `i128` implementation of the pixel rule\n\
         (`testkit/src/reference.rs`), per 1000 covered pixels (tiny-skia gets\n\
         the exact coordinates as `f32`, embedded-graphics the pixel holding\n\
         each vertex). *Memory*: working state besides the frame buffer.\n",
        crate::ROUNDS
    );
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
         12-gon covering most of 512×256; W6 2,000 slivers (seeded), triangles\n\
         40–120 px long and 1–2 px wide at any angle, in 512×256 (host only).\n\n\
         ![speed against error](speed-vs-error.png)\n"
    );
    let _ = writeln!(
        s,
        "### The exact path against the independent reference\n\n\
         Every polygon of each workload, pixel by pixel, against\n\
         `testkit/src/reference.rs`:\n\n\
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

    // Targets.
    let _ = writeln!(
        s,
        "## Targets\n\n| target | measured | verdict |\n|---|---|---|"
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
    s.push_str(
        "The Cortex-M4 image's targets (the 3D layer in 16-row bands) and the\n\
         racing path's are tabled with their verdicts beside their measurements:\n\
         [Targets of the 3D layer in 16-row bands](#targets-of-the-3d-layer-in-16-row-bands)\n\
         and [Racing the beam](#racing-the-beam).\n\n",
    );
    if let Some(line) = target_3d(&run.rows3, default_3d(run)) {
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

/// Hand-written notes on what limits the figures; the instruction counts
/// of the profiles behind them are in `docs/performance-log.md`.
pub const NOTES: &str = r#"## What limits the figures

Counted with callgrind on the benchmark's profiling modes (`valgrind
--tool=callgrind target/release/scanvert-bench --profile-w1 MODE 100`,
MODE `null`, `framebuffer` or `tiny-skia`; `--profile-3d MODE 25`). **2D**:
scan conversion is about half of the exact path's instructions, the span
writes the other half; the DDA saves a compare and an add per edge and
row, at the error shown; W5 and W2 are bounded by the pixel writes.
**3D**: the sweep executes about as many instructions as the z-buffers
but branches on the data at every span, while the z-buffer's loop is
regular and its depth buffer stays in this host's cache.
"#;

/// Markers of the section `--only depth` rewrites.
pub const DEPTH_BEGIN: &str = "<!-- depth-sweep:begin -->";
/// End marker.
pub const DEPTH_END: &str = "<!-- depth-sweep:end -->";

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
         Written by `cargo run --release -p scanvert-bench -- --only depth` (about\n\
         {:.0} s; the full run writes it too), with its two plots. Timing, error\n\
         and the z-buffers as in the 3D section, with {} timed runs each.\n",
        seconds.max(1.0),
        crate::visible3d::ROUNDS_DEPTH
    );
    if !depth.is_empty() {
        let _ = writeln!(
            s,
            "### Time against depth complexity\n\n\
             ![time against depth complexity](time-vs-depth.png)\n\n\
             {} faces at {W}×{H} (`testkit::scenes3d::depth_scene`: layers of\n\
             parallelograms tiling the frame, each pixel covered exactly *depth*\n\
             times), parallel to the screen (2D) or tilted through each other\n\
             (3D). The face count is fixed, so the trapezoids change little while\n\
             the pixels a z-buffer tests grow as covered × depth.\n",
            depth[0].faces
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
            "\nscanvert against the exact reference, all depths, versions and views:\n\
             **{bad} mismatched pixels** in {} covered pixels. *Faster z-buffer ÷\n\
             scanvert* above 1: scanvert is faster. The z-buffer's time follows\n\
             the pixels it tests, the sweep's its trapezoid rows (nearly flat per\n\
             row): the z-buffer wins where few pixels are tested twice, the sweep\n\
             from where the pixels tested outgrow the trapezoid rows.\n",
            thousands(covered)
        );
    }
    if !split.is_empty() {
        let _ = writeln!(
            s,
            "### P3 and P4 against trapezoids\n\n\
             ![P3 and P4 against trapezoids](p3-p4-vs-trapezoids.png)\n\n\
             The 3D section's scenes, their visible-surface time split as J. H.\n\
             Jackson's 1980 figures split it: **P3**, the sweep producing\n\
             run-length rows with no pixel written (`Workspace::resolve`), and\n\
             **P4**, the frame cleared and those rows decoded into pixels\n\
             (`rle::decode_row`). *Fused* is `visible::draw`, the two row by row.\n\
             From stores cut beforehand; both versions of a size timed together.\n"
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
        let _ = writeln!(s);
    }
    let _ = writeln!(s, "{DEPTH_END}\n");
    s
}

/// Mismatched pixels of scanvert's three resolves against the exact
/// reference, over all 3D scenes and views, and the pixels covered.
fn exact_3d(run: &Run) -> (u64, f64) {
    let bad = run
        .rows3
        .iter()
        .filter(|r| {
            r.contender == CROSSING
                || r.contender == crate::visible3d::BISECT
                || r.contender == crate::visible3d::PAINT
        })
        .filter_map(|r| r.err.map(|e| e.total))
        .sum();
    let covered = run.scenes3.iter().map(|st| st.covered * VIEWS as f64).sum();
    (bad, covered)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_full_page_holds_each_block_once_and_keeps_the_others() {
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
        for m in [DEPTH_BEGIN, DEPTH_END, ON_TARGET_BEGIN, HEADLINE_BEGIN] {
            assert_eq!(page.matches(&format!("{m}\n")).count(), 1, "{m}");
        }
        assert!(page.contains("time-vs-depth.png") && page.contains("p3-p4-vs-trapezoids.png"));
        // What `--only depth` does to the page changes nothing more.
        let section = section_depth(&run.depth, &run.split, run.seconds_depth);
        let again = splice(&page, DEPTH_BEGIN, DEPTH_END, &section, "## Targets");
        assert_eq!(again, page);
        // The blocks measure.sh writes survive a full run.
        let old = format!(
            "# x\n{HEADLINE_BEGIN}\n| M4 | 1 |\n{HEADLINE_END}\n{ON_TARGET_BEGIN}\nfigures\n{ON_TARGET_END}\n## after\n"
        );
        let page = markdown(&run, &old);
        assert!(page.contains(&format!("{HEADLINE_BEGIN}\n| M4 | 1 |\n{HEADLINE_END}")));
        assert!(page.contains(&format!(
            "{ON_TARGET_BEGIN}\nfigures\n{ON_TARGET_END}\n## after\n"
        )));
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
