//! The simulated write port's cycle model (`scanvert_sim::dual_port`) on
//! the firmware image's 2D lists: calibrated on W1, predicted for the
//! others. Nothing here is timed: the spans are counted exactly as the
//! simulator writes them. `--only model` rewrites the section between
//! [`BEGIN`] and [`END`] of `docs/performance.md`; the tests below fail
//! when that section or the table in `hal_sim/src/dual_port.rs`'s module
//! docs differs from what the simulator gives.

use crate::numbers::thousands;
use scanvert_sim::cli::{self, Scene};
use scanvert_sim::dual_port::{CycleModel, WriteCounters, ROW_STEP_CYCLES};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Markers of the section `--only model` rewrites.
pub const BEGIN: &str = "<!-- write-port-model:begin -->";
/// End marker.
pub const END: &str = "<!-- write-port-model:end -->";

/// The reference unit's figures: polygons/s on W1 (what the set-up is
/// calibrated on) and its own measured fill rate, in pixels/s.
pub const REFERENCE_W1_POLYGONS_PER_SECOND: u64 = 54_945;
/// The reference unit's measured fill rate, Mpixel/s.
pub const REFERENCE_MPIXELS_PER_SECOND: f64 = 49.3;

/// Stepper times (cycles a span) whose predictions the table shows
/// beside the model's own.
pub const OTHER_STEPPERS: [u64; 3] = [1, 4, 8];

/// The lists: the image's file, its name in the table, and whether the
/// model was calibrated on it.
const LISTS: [(&str, &str, bool); 5] = [
    ("w1", "W1, 30 × 30 squares", true),
    ("w4", "W4, W1 rotated by 17°", false),
    ("w3", "W3, 10,000 small triangles", false),
    ("w5", "W5, one 12-gon", false),
    ("demo", "the 2D demo (`scenes/demo.dl`)", false),
];

/// One list's counters under the reference model.
pub struct ModelRow {
    /// Its name in the table.
    pub what: &'static str,
    /// `true` for W1.
    pub calibrated: bool,
    /// The write port's counters.
    pub counters: WriteCounters,
}

impl ModelRow {
    /// Pixels of the polygons and lines (clears left out).
    fn pixels(&self) -> u64 {
        self.counters.pixels_written - self.counters.clear_cycles
    }

    /// Cycles outside clears under `model`.
    fn cycles(&self, model: &CycleModel) -> u64 {
        model.cycles(&self.counters) - self.counters.clear_cycles
    }

    /// Polygons a second under `model`.
    fn polygons_per_second(&self, model: &CycleModel) -> f64 {
        let hz = f64::from(self.counters.clock.hz());
        self.counters.polygons as f64 * hz / self.cycles(model) as f64
    }
}

fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../firmware/image/scenes")
}

/// Renders each list through the simulator's write port.
pub fn measure() -> Vec<ModelRow> {
    LISTS
        .iter()
        .map(|&(file, what, calibrated)| {
            let path = scenes_dir().join(format!("{file}.scvl"));
            let bytes = std::fs::read(&path).expect("the image's scene");
            let scene = Scene::from_bytes(Path::new(&path), bytes).expect("a valid list");
            let counters = cli::render_scene(&scene)
                .expect("render")
                .ram
                .write_counters();
            ModelRow {
                what,
                calibrated,
                counters,
            }
        })
        .collect()
}

/// The model with a stepper of `row` cycles a span, calibrated on W1 (the
/// first row).
fn calibrated(rows: &[ModelRow], row: u64) -> CycleModel {
    CycleModel::calibrate(row, &rows[0].counters, REFERENCE_W1_POLYGONS_PER_SECOND)
        .expect("W1 calibrates every stepper of up to 8 cycles")
}

/// The table, one line a list (as in `hal_sim/src/dual_port.rs`'s docs).
pub fn table(rows: &[ModelRow]) -> String {
    let model = calibrated(rows, ROW_STEP_CYCLES);
    let others: Vec<CycleModel> = OTHER_STEPPERS
        .iter()
        .map(|&r| calibrated(rows, r))
        .collect();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| list | polygons | spans | pixels | waits for the stepper (cycles) | cycles a polygon | polygons/s | Mpixel/s | | polygons/s with a stepper of {} cycles a span |",
        OTHER_STEPPERS.map(|r| r.to_string()).join(" / ")
    );
    let _ = writeln!(s, "|---|--:|--:|--:|--:|--:|--:|--:|---|--:|");
    for r in rows {
        let w = &r.counters;
        let cycles = r.cycles(&model);
        // Cycles a polygon in tenths, rounded.
        let tenths = (cycles * 10 + w.polygons / 2) / w.polygons;
        let hz = f64::from(w.clock.hz());
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {}{} | {} | {:.2} | {} | {} |",
            r.what,
            thousands(w.polygons as f64),
            thousands(w.spans as f64),
            thousands(r.pixels() as f64),
            thousands(model.waits(w) as f64),
            thousands((tenths / 10) as f64),
            format_args!(".{}", tenths % 10),
            thousands(r.polygons_per_second(&model)),
            r.pixels() as f64 * hz / cycles as f64 / 1e6,
            if r.calibrated {
                "calibrated"
            } else {
                "predicted"
            },
            others
                .iter()
                .map(|m| thousands(r.polygons_per_second(m)))
                .collect::<Vec<_>>()
                .join(" / ")
        );
    }
    s
}

/// The model's W1 fill rate against the reference unit's measured one:
/// (the model's Mpixel/s, the reference's cycles a W1 square, the
/// reference's shortfall in %).
fn fill_rate(rows: &[ModelRow]) -> (f64, f64, f64) {
    let w1 = &rows[0];
    let w = &w1.counters;
    let model = calibrated(rows, ROW_STEP_CYCLES);
    let hz = f64::from(w.clock.hz());
    let mpx = w1.pixels() as f64 * hz / w1.cycles(&model) as f64 / 1e6;
    let per_polygon = w1.pixels() as f64 / w.polygons as f64;
    let cycles = per_polygon * hz / (REFERENCE_MPIXELS_PER_SECOND * 1e6);
    (
        mpx,
        cycles,
        (1.0 - REFERENCE_MPIXELS_PER_SECOND / mpx) * 100.0,
    )
}

/// The section of `docs/performance.md`, markers included.
pub fn section(rows: &[ModelRow]) -> String {
    let model = calibrated(rows, ROW_STEP_CYCLES);
    let (mpx, cycles, short) = fill_rate(rows);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{BEGIN}\n## The reference unit's write port: calibrated and predicted\n\n\
         Written by `cargo run --release -p scanvert-bench -- --only model` (no\n\
         timing: the simulator's spans, counted; a test of the benchmark fails when\n\
         this table or the one in `hal_sim/src/dual_port.rs` is stale). The write port\n\
         of the simulator (`scanvert render LIST --stats`) charges what the reference\n\
         unit, an FPGA at 50 MHz, would spend: 1 cycle a pixel (its 20 ns); {} cycles a\n\
         polygon's set-up, **calibrated on W1** (its 54,945 polygons/s are 910 cycles a\n\
         square, 900 of them pixel writes); and {} cycles a span for the edge stepper\n\
         (one an edge), **assumed**, overlapped with the writing of the span before,\n\
         so that the writes wait only after a span shorter than that. W1 cannot show\n\
         the stepper (its spans are 30 pixels), and leaves no room for a stepper that\n\
         holds the writes (a cycle a row would cost 930 cycles a square). Every other\n\
         line is a **prediction**; the last column shows how it moves with the\n\
         stepper's time, the set-up calibrated on W1 again each time. Clears are left\n\
         out of the cycles and pixels (1 cycle a pixel: 763 clears/s of 256 × 256).\n",
        model.setup_cycles(),
        model.row_cycles(),
    );
    s.push_str(&table(rows));
    let _ = writeln!(
        s,
        "\nThe reference unit's own measured fill rate, {REFERENCE_MPIXELS_PER_SECOND} Mpixel/s, is {short:.1} %\n\
         below the model's {mpx:.2} Mpixel/s on W1: {cycles:.1} cycles a square, {:.1} more than\n\
         the model, which it does not place.\n\n{END}\n",
        cycles - rows[0].cycles(&model) as f64 / rows[0].counters.polygons as f64
    );
    s
}

/// `--only model`: the section of `docs/performance.md` rewritten in
/// place (before the racing section when it is not there yet).
pub fn write_section(page: &Path) -> std::io::Result<()> {
    let rows = measure();
    eprint!("{}", table(&rows));
    let old = std::fs::read_to_string(page).unwrap_or_default();
    let md = crate::report::splice(&old, BEGIN, END, &section(&rows), "## Racing the beam");
    std::fs::write(page, md)?;
    eprintln!("rewrote the write-port model section of docs/performance.md");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(rel: &str) -> String {
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel))
            .expect("a file of the repository")
    }

    #[test]
    fn the_performance_page_has_the_current_section() {
        let page = read("../docs/performance.md");
        let section = section(&measure());
        assert!(
            page.contains(&section),
            "docs/performance.md: run `cargo run --release -p scanvert-bench -- --only model`; it should hold\n{section}"
        );
    }

    #[test]
    fn the_module_docs_have_the_current_table() {
        let docs = read("../hal_sim/src/dual_port.rs");
        let table: String = table(&measure())
            .lines()
            .map(|l| format!("//! {l}\n"))
            .collect();
        assert!(
            docs.contains(&table),
            "hal_sim/src/dual_port.rs's module docs should hold\n{table}"
        );
    }

    #[test]
    fn w1_calibrates_the_set_up_alone() {
        let rows = measure();
        for row in 1..=8 {
            assert_eq!(calibrated(&rows, row).setup_cycles(), 10, "stepper {row}");
        }
        let model = calibrated(&rows, ROW_STEP_CYCLES);
        assert_eq!(model, CycleModel::REFERENCE);
        assert_eq!(
            rows[0].polygons_per_second(&model).round() as u64,
            REFERENCE_W1_POLYGONS_PER_SECOND
        );
        // The predictions are the model's, not W1's copied: W4's squares
        // wait for the stepper at their corners, W3's triangles more.
        let w1 = rows[0].polygons_per_second(&model);
        let w4 = rows[1].polygons_per_second(&model);
        assert!(w4 < w1, "{w4} {w1}");
        assert!(rows[1].counters.stepper_wait_cycles > 0);
        let mpx = |r: &ModelRow| r.pixels() as f64 / r.cycles(&model) as f64;
        assert!(mpx(&rows[2]) < mpx(&rows[1]) && mpx(&rows[1]) < mpx(&rows[0]));
    }
}
