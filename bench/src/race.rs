//! Racing the beam (`scanvert_sim::race`): the cost model
//! `race::CostModel::M4` fitted to the instructions the Cortex-M4 image
//! counted for every row of the lists it embeds
//! (`firmware/image/rows-m4.txt`), its error, and the table of lowest
//! clocks and missed lines. Nothing here is timed. `--only race` prints
//! the fit and rewrites the section between [`BEGIN`] and [`END`] of
//! `docs/performance.md`; the tests below fail when the fit no longer
//! gives `CostModel::M4`, when its error exceeds the published one, or
//! when the section is stale.
//!
//! The fit weighs each row by the inverse square of its count, so it
//! minimises the sum of squared *relative* errors; the coefficients are
//! rounded to 1/16 instruction. Labels appear in none of the measured
//! lists, so their coefficient stays 0: a label costs its spans and
//! pixels.

use crate::numbers::thousands;
use scanvert::display_list::DisplayList;
use scanvert_sim::race::{list_work, CostModel, PrepareWork, RowWork};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Markers of the section `--only race` rewrites.
pub const BEGIN: &str = "<!-- race-table:begin -->";
/// End marker.
pub const END: &str = "<!-- race-table:end -->";

const SCENES: [&str; 8] = [
    "demo",
    "w1",
    "w2",
    "w3",
    "w4",
    "w5",
    "poly3-layered",
    "poly3-tilted",
];

fn image_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../firmware/image")
}

/// Measured counts: `(prepare by scene, row by (scene, y))`.
fn measured() -> (HashMap<String, u64>, HashMap<(String, u16), u64>) {
    let text = std::fs::read_to_string(image_dir().join("rows-m4.txt")).expect("rows-m4.txt");
    let (mut prep, mut rows) = (HashMap::new(), HashMap::new());
    let count = |w: &str| -> u64 {
        w.strip_prefix("instructions=")
            .and_then(|n| n.parse().ok())
            .expect("instructions=N")
    };
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        match line.split_whitespace().collect::<Vec<_>>()[..] {
            ["prepare", name, n] => {
                prep.insert(name.to_string(), count(n));
            }
            ["row", name, y, n] => {
                rows.insert((name.to_string(), y.parse().expect("y")), count(n));
            }
            // The token encoder's counts and the empty list's, for the
            // log; not part of the fit.
            ["tokens" | "empty" | "insert", _, _, _] => {}
            _ => panic!("unexpected line {line:?}"),
        }
    }
    (prep, rows)
}

/// Every measured row with its work, and every list's preparation.
#[allow(clippy::type_complexity)]
fn samples() -> (
    Vec<(&'static str, PrepareWork, u64)>,
    Vec<(&'static str, RowWork, u64)>,
) {
    let (prep, rows) = measured();
    let (mut p, mut r) = (Vec::new(), Vec::new());
    for name in SCENES {
        let bytes = std::fs::read(image_dir().join(format!("scenes/{name}.scvl"))).expect("scene");
        let list = DisplayList::new_checked(&bytes).expect("list");
        let (pw, work) = list_work(&list).expect("work");
        p.push((name, pw, prep[name]));
        for (y, w) in work.into_iter().enumerate() {
            r.push((name, w, rows[&(name.to_string(), y as u16)]));
        }
    }
    assert_eq!(r.len(), rows.len(), "a measured row has no row of the host");
    (p, r)
}

fn row_features(w: &RowWork) -> [f64; 10] {
    [
        1.0,
        w.width.into(),
        w.spans.into(),
        w.pixels.into(),
        w.runs.into(),
        w.entered.into(),
        w.resolved.into(),
        w.live.into(),
        w.words.into(),
        w.moved.into(),
    ]
}

/// Weighted least squares: minimises Σ ((x·c − y) / y)².
#[allow(clippy::needless_range_loop)]
fn fit<const N: usize>(samples: &[([f64; N], u64)]) -> [f64; N] {
    let mut a = [[0.0f64; N]; N];
    let mut b = [0.0f64; N];
    for (x, y) in samples {
        let w = 1.0 / (*y as f64 * *y as f64);
        for i in 0..N {
            b[i] += w * x[i] * *y as f64;
            for j in 0..N {
                a[i][j] += w * x[i] * x[j];
            }
        }
    }
    // Gaussian elimination with partial pivoting.
    for c in 0..N {
        let p = (c..N)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        for r in 0..N {
            if r != c && a[c][c] != 0.0 {
                let f = a[r][c] / a[c][c];
                for k in c..N {
                    a[r][k] -= f * a[c][k];
                }
                b[r] -= f * b[c];
            }
        }
    }
    std::array::from_fn(|i| if a[i][i] == 0.0 { 0.0 } else { b[i] / a[i][i] })
}

/// Mean and worst relative error of `model` over the rows, and per list.
fn errors(model: &CostModel, rows: &[(&str, RowWork, u64)]) -> (f64, f64) {
    let e: Vec<f64> = rows
        .iter()
        .map(|(_, w, m)| (model.row(w) as f64 - *m as f64).abs() / *m as f64)
        .collect();
    (
        e.iter().sum::<f64>() / e.len() as f64,
        e.iter().copied().fold(0.0, f64::max),
    )
}

/// The model's coefficients fitted to the measured rows and
/// preparations, in 1/16 instruction.
pub fn fitted() -> CostModel {
    let (prep, rows) = samples();
    let x: Vec<_> = rows.iter().map(|(_, w, m)| (row_features(w), *m)).collect();
    let c = fit(&x).map(|v| (v * 16.0).round() as i64);
    let px: Vec<_> = prep
        .iter()
        .map(|(_, w, m)| ([1.0, f64::from(w.commands), f64::from(w.trapezoids)], *m))
        .collect();
    let p = fit(&px).map(|v| (v * 16.0).round() as i64);
    CostModel {
        row: c[0],
        width: c[1],
        span: c[2],
        pixel: c[3],
        run: c[4],
        entered: c[5],
        resolved: c[6],
        label: 0,
        live: c[7],
        word: c[8],
        moved: c[9],
        frame: p[0],
        command: p[1],
        trapezoid: p[2],
    }
}

fn percent(v: f64) -> String {
    format!("{:.1} %", 100.0 * v)
}

/// The table of the model's error: all rows, the 2D lists' range, the 3D
/// lists one by one.
fn error_table() -> String {
    let (_, rows) = samples();
    let of = |name: &str| {
        let r: Vec<_> = rows.iter().filter(|r| r.0 == name).cloned().collect();
        errors(&CostModel::M4, &r)
    };
    let (mean, worst) = errors(&CostModel::M4, &rows);
    let two_d: Vec<(f64, f64)> = ["demo", "w1", "w2", "w3", "w4", "w5"]
        .iter()
        .map(|n| of(n))
        .collect();
    let range = |f: fn(&(f64, f64)) -> f64| {
        let lo = two_d.iter().map(f).fold(f64::INFINITY, f64::min);
        let hi = two_d.iter().map(f).fold(0.0, f64::max);
        format!("{} to {}", percent(lo), percent(hi))
    };
    let (layered, tilted) = (of("poly3-layered"), of("poly3-tilted"));
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| rows of | mean relative error | worst |\n|---|--:|--:|"
    );
    let _ = writeln!(
        s,
        "| all eight lists ({} rows) | {} | {} |",
        thousands(rows.len() as f64),
        percent(mean),
        percent(worst)
    );
    let _ = writeln!(
        s,
        "| 2D lists (demo, W1–W5) | {} | {} |",
        range(|e| e.0),
        range(|e| e.1)
    );
    let _ = writeln!(
        s,
        "| 3D lists (poly3-layered, poly3-tilted) | {}, {} | {}, {} |",
        percent(layered.0),
        percent(tilted.0),
        percent(layered.1),
        percent(tilted.1)
    );
    s
}

/// The `p`-th percentile (nearest rank) of `v`.
fn percentile(v: &[u64], p: usize) -> u64 {
    let mut s = v.to_vec();
    s.sort_unstable();
    s[(s.len() * p).div_ceil(100).clamp(1, s.len()) - 1]
}

fn mhz(c: Option<scanvert_sim::race::CpuClock>) -> String {
    c.map_or("> 100,000".into(), |c| {
        format!("{:.0}", c.hz() as f64 / 1e6)
    })
}

/// A scene's name, instructions of preparing it and of each row from the
/// model, of each row measured on the M4 if it was, and the most runs a
/// row of it needs.
type Costs = (String, u64, Vec<u64>, Option<Vec<u64>>, usize);

/// The ring's depths the table shows.
const KS: [u16; 4] = [2, 4, 16, 64];

/// The racing table: each scene's lowest clocks, misses and worst rows.
fn race_table() -> String {
    use scanvert_sim::race::CpuClock;
    use scanvert_sim::race::{
        demo_costs, lowest_clock, lowest_clock_cores, lowest_clock_spread,
        lowest_clock_spread_cores, schedule,
    };
    use scanvert_sim::timing::VideoTiming;
    let (_, measured_rows) = measured();
    let m4 = CostModel::M4;
    // (name, prepare, rows, measured rows on the M4 if any)
    let mut scenes: Vec<Costs> = Vec::new();
    let demo = demo_costs(8, &m4).expect("demo");
    // The demo's frame of the most instructions.
    let most = demo.iter().map(|d| d.2).max().unwrap_or(0);
    let demo_frames: Vec<(u64, Vec<u64>)> = demo.iter().map(|(p, r, _)| (*p, r.clone())).collect();
    let (dp, dr, _) = demo
        .into_iter()
        .max_by_key(|(p, r, _)| p + r.iter().sum::<u64>())
        .expect("frames");
    scenes.push((
        "3D demo (`scanvert demo`, worst of 8 frames), 512×256".into(),
        dp,
        dr,
        None,
        most,
    ));
    let mut list = |name: String, bytes: Vec<u8>, m4rows: Option<Vec<u64>>| {
        let l = DisplayList::new_checked(&bytes).expect("list");
        let (pw, work) = list_work(&l).expect("work");
        let rows = work.iter().map(|w| m4.row(w)).collect();
        let most = work.iter().map(|w| w.peak as usize).max().unwrap_or(0);
        scenes.push((name, m4.prepare(&pw), rows, m4rows, most));
    };
    for (name, label) in [
        ("demo", "2D demo (`scenes/demo.dl`), 320×200"),
        ("poly3-layered", "poly3-layered (170 faces), 512×256"),
        ("poly3-tilted", "poly3-tilted (170 faces), 512×256"),
        ("w3", "W3 (10,000 polygons), 512×256"),
    ] {
        let bytes = std::fs::read(image_dir().join(format!("scenes/{name}.scvl"))).expect("scene");
        let mut ys: Vec<_> = measured_rows
            .iter()
            .filter(|((n, _), _)| n == name)
            .map(|((_, y), c)| (*y, *c))
            .collect();
        ys.sort_unstable();
        list(
            label.into(),
            bytes,
            Some(ys.into_iter().map(|(_, c)| c).collect()),
        );
    }
    let cube = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes/cube.dl"),
    )
    .expect("cube")
    .replace("frame 320 240", "frame 640 480");
    let cube = scanvert_sim::text::assemble_bytes(cube.as_bytes())
        .expect("cube")
        .bytes;
    list(
        "cube (`scenes/cube.dl` at 640×480: 3D, labels)".into(),
        cube,
        None,
    );

    let timings = [
        ("reference", VideoTiming::REFERENCE_640X480),
        ("VGA", VideoTiming::VGA_640X480_60),
    ];
    let mut s = String::new();
    s.push_str("| scene | lowest MHz, reference, K = 2 / 4 / 16 / 64 | two producers, reference, K = 2 / 4 / 16 / 64 | preparing in the frame before's spare time, reference, K = 2 / 4 / 16 / 64 | two producers, preparing in the frame before's spare time, reference, K = 2 / 4 / 16 / 64 | lowest MHz, VGA 60 Hz, K = 2 / 4 / 16 / 64 | misses at 168 MHz, reference, K = 2 / 4 / 16 / 64 | ring's RAM, K = 2 / 4 / 16 / 64 (bytes; most runs a row) | worst row (instructions) | 99th-percentile row | of 5,376 a line at 168 MHz |\n");
    s.push_str("|---|---|---|---|---|---|---|---|---|---|---|\n");
    let cpu = CpuClock::from_mhz(168).expect("168 MHz");
    for (name, prep, rows, m4rows, most) in &scenes {
        let mut cells = Vec::new();
        for (i, (_, t)) in timings.iter().enumerate() {
            let c: Vec<String> = KS
                .iter()
                .map(|&k| mhz(lowest_clock(*prep, rows, t, k)))
                .collect();
            cells.push(c.join(" / "));
            if i == 0 {
                let two: Vec<String> = KS
                    .iter()
                    .map(|&k| mhz(lowest_clock_cores(*prep, rows, t, k, 2)))
                    .collect();
                cells.push(two.join(" / "));
                let spread: Vec<String> = KS
                    .iter()
                    .map(|&k| mhz(lowest_clock_spread(*prep, rows, t, k)))
                    .collect();
                cells.push(spread.join(" / "));
                let both: Vec<String> = KS
                    .iter()
                    .map(|&k| mhz(lowest_clock_spread_cores(*prep, rows, t, k, 2)))
                    .collect();
                cells.push(both.join(" / "));
            }
        }
        let shown = rows.len().min(480);
        let m: Vec<String> = KS
            .iter()
            .map(|&k| {
                let n = schedule(*prep, &rows[..shown], &timings[0].1, cpu, k)
                    .iter()
                    .filter(|&&m| m)
                    .count();
                format!("{n}")
            })
            .collect();
        cells.push(format!("{} of {shown}", m.join(" / ")));
        let ram: Vec<String> = KS
            .iter()
            .map(|&k| thousands((usize::from(k) * most * 4) as f64))
            .collect();
        cells.push(format!("{} ({most})", ram.join(" / ")));
        let (src, r) = match m4rows {
            Some(r) => ("M4", r),
            None => ("model", rows),
        };
        let (worst, p99) = (*r.iter().max().unwrap(), percentile(r, 99));
        cells.push(format!("{} ({src})", thousands(worst as f64)));
        cells.push(format!("{} ({src})", thousands(p99 as f64)));
        cells.push(format!(
            "{:.2}× / {:.2}×",
            worst as f64 / 5376.0,
            p99 as f64 / 5376.0
        ));
        let _ = writeln!(s, "| {name} | {} |", cells.join(" | "));
    }
    for (name, prep, ..) in &scenes {
        eprintln!("prepare {name}: {prep}");
    }
    let costs = |label: &str| {
        let (_, p, r, ..) = scenes
            .iter()
            .find(|c| c.0.starts_with(label))
            .expect("a scene of the table");
        vec![(*p, r.clone())]
    };
    s.push('\n');
    s.push_str(&targets_table(&[
        (
            "2D demo at 168 MHz, a ring of 2 rows",
            costs("2D demo"),
            168,
            2,
        ),
        (
            "3D demo, every one of its 8 frames, at 168 MHz, a ring of at most 16 rows",
            demo_frames,
            168,
            16,
        ),
        (
            "`poly3-layered` at 168 MHz or less, a ring of at most 64 rows",
            costs("poly3-layered"),
            168,
            64,
        ),
        (
            "2D demo at 133 MHz (an RP2040's clock), a ring of at most 16 rows",
            costs("2D demo"),
            133,
            16,
        ),
    ]));
    s
}

/// A racing target: what it asks for, the frames it asks it of (each
/// frame's preparation and rows, by the model), the clock in MHz and the
/// deepest ring.
type Target = (&'static str, Vec<(u64, Vec<u64>)>, u64, u16);

/// The racing targets at the reference timing against the lowest clock
/// that shows every frame of each with no missed line, with the deepest
/// ring the target allows: one producer, preparing in the retrace or in
/// the frame before's spare time (the lower clock of the two), and two
/// producers beside it.
fn targets_table(targets: &[Target]) -> String {
    use scanvert_sim::race::{
        lowest_clock, lowest_clock_cores, lowest_clock_spread, lowest_clock_spread_cores, CpuClock,
    };
    use scanvert_sim::timing::VideoTiming;
    let t = VideoTiming::REFERENCE_640X480;
    // The lowest clock every frame takes: the highest of the frames'.
    let every = |frames: &[(u64, Vec<u64>)], one: &dyn Fn(u64, &[u64]) -> Option<CpuClock>| {
        frames
            .iter()
            .map(|(p, r)| one(*p, r).map(|c| c.hz()))
            .try_fold(0, |most, c| c.map(|c| most.max(c)))
    };
    let best =
        |a: Option<CpuClock>, b: Option<CpuClock>| a.into_iter().chain(b).min_by_key(|c| c.hz());
    let shown = |hz: Option<u64>| mhz(hz.and_then(CpuClock::from_hz));
    let mut s = String::from(
        "| target, reference timing | lowest MHz, one producer | lowest MHz, two producers | verdict (one producer) |\n|---|--:|--:|---|\n",
    );
    for (what, frames, target, k) in targets {
        let k = *k;
        let one = every(frames, &|p, r| {
            best(lowest_clock(p, r, &t, k), lowest_clock_spread(p, r, &t, k))
        });
        let two = every(frames, &|p, r| {
            best(
                lowest_clock_cores(p, r, &t, k, 2),
                lowest_clock_spread_cores(p, r, &t, k, 2),
            )
        });
        let verdict = match one {
            Some(hz) if hz <= target * 1_000_000 => "**met**".to_string(),
            Some(hz) => format!(
                "missed: {:.2}× the clock",
                hz as f64 / (target * 1_000_000) as f64
            ),
            None => "missed".to_string(),
        };
        let _ = writeln!(
            s,
            "| {what} | {} | {} | {verdict} |",
            shown(one),
            shown(two)
        );
    }
    s
}

/// The `NAME N rows=R instructions=I` lines of `rows-m4.txt`: `(N, R, I)`.
fn totals(name: &str) -> Vec<(u64, u64, u64)> {
    let text = std::fs::read_to_string(image_dir().join("rows-m4.txt")).expect("rows-m4.txt");
    let num = |w: &str, key: &str| -> u64 {
        w.strip_prefix(key)
            .and_then(|n| n.parse().ok())
            .expect("a count")
    };
    text.lines()
        .filter_map(|l| match l.split_whitespace().collect::<Vec<_>>()[..] {
            [n, a, r, i] if n == name => {
                Some((num(a, ""), num(r, "rows="), num(i, "instructions=")))
            }
            _ => None,
        })
        .collect()
}

/// An empty row of 512 pixels on the M4, in instructions.
fn empty_row() -> String {
    let (_, rows, n) = totals("empty")[0];
    format!("{:.0}", n as f64 / rows as f64)
}

/// Instructions a span inserted, with 1, 4, 16 and 64 spans a row.
fn per_insert() -> String {
    let v: Vec<String> = totals("insert")
        .iter()
        .map(|&(spans, rows, n)| format!("{:.0}", n as f64 / (rows * spans) as f64))
        .collect();
    v.join(", ")
}

/// The section of `docs/performance.md`, markers included.
pub fn section() -> String {
    format!(
        "{BEGIN}\n{}\n\
         Rows are composed as colour runs with no pixel buffer\n\
         (`ListBands::draw_runs`, `port::runs`): on the M4 an empty row of 512\n\
         pixels costs {} instructions (the 256 rows of an empty list counted\n\
         together), and a span inserted into a row of 320 pixels {} instructions\n\
         with 1, 4, 16 and 64 spans on the row (`insert` in `rows-m4.txt`, with\n\
         the pseudo-random spans' own arithmetic).\n\n\
         The lowest clock with no missed line (one producer, and two taking the\n\
         rows in turn, the first preparing the frame; and one producer, then two,\n\
         that prepare each frame in the spare time of the frame before, with two\n\
         sets of the frame's memory, `race::schedule_spread` and\n\
         `race::schedule_spread_cores`), the lines missed at 168 MHz, the\n\
         ring's RAM (K rows of the most runs a row needs, 4 bytes a run), and\n\
         the worst and 99th-percentile row (*M4*: measured; *model*: predicted)\n\
         against the 5,376 instructions of a 32 µs line at 168 MHz. The tables are\n\
         written by `cargo run --release -p scanvert-bench -- --only race` (no\n\
         timing; the benchmark's tests fail when they are stale). The last\n\
         table holds the targets the racing path is held to, each against the\n\
         lowest clock at which every frame it names misses no line, with the\n\
         deepest ring it allows (one producer preparing in the retrace or in\n\
         the frame before's spare time, whichever needs the lower clock; two\n\
         producers likewise).\n\n{}\n{END}\n\n",
        error_table(),
        empty_row(),
        per_insert(),
        race_table()
    )
}

/// `--only race`: the fit printed against `CostModel::M4`, and the
/// section of `docs/performance.md` rewritten in place.
pub fn write_section(page: &Path) -> std::io::Result<()> {
    let f = fitted();
    eprintln!(
        "fit: row {}, width {}, span {}, pixel {}, run {}, entered {}, resolved {}, live {}, word {}, moved {}; frame {}, command {}, trapezoid {} ({})",
        f.row, f.width, f.span, f.pixel, f.run, f.entered, f.resolved, f.live, f.word, f.moved, f.frame, f.command, f.trapezoid,
        if f == CostModel::M4 { "CostModel::M4" } else { "differs from CostModel::M4" }
    );
    let old = std::fs::read_to_string(page).unwrap_or_default();
    let md = crate::report::splice(
        &old,
        BEGIN,
        END,
        &section(),
        "## RAM without a frame buffer",
    );
    std::fs::write(page, md)?;
    eprintln!("rewrote the racing section of docs/performance.md");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_m4_model_is_within_its_published_error() {
        let (_, rows) = samples();
        let (mean, worst) = errors(&CostModel::M4, &rows);
        // The figures published in CostModel::M4's docs and
        // docs/performance.md.
        assert!(
            mean <= 0.083 && worst <= 0.49,
            "mean relative error {mean}, worst {worst}"
        );
    }

    #[test]
    fn the_fit_of_the_measured_rows_is_cost_model_m4() {
        assert_eq!(fitted(), CostModel::M4);
    }

    #[test]
    fn the_performance_page_has_the_current_section() {
        let page = std::fs::read_to_string(
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/performance.md"),
        )
        .expect("the page");
        let section = section();
        assert!(
            page.contains(&section),
            "docs/performance.md: run `cargo run --release -p scanvert-bench -- --only race`; it should hold\n{section}"
        );
    }
}
