//! The demo's animation: only what changed is rebuilt, and every frame the
//! monitor shows (double-buffered, through the co-simulation) is one
//! whole render of its step.

use scanvert_sim::demo::{animate, reference_frame, steps};

#[test]
fn threshold_steps_rebuild_bars_alone_and_frames_are_whole_renders() {
    let frames = animate(5).expect("demo runs");
    assert_eq!(frames.len(), 5);
    // Emptied-so-far counters of (ground, bars, names).
    let rebuilt: Vec<[u32; 3]> = frames.iter().map(|f| f.rebuilt).collect();
    assert_eq!(rebuilt[0], [1, 1, 1]);
    assert_eq!(rebuilt[1], [1, 2, 1]);
    assert_eq!(rebuilt[2], [1, 3, 1]);
    assert_eq!(rebuilt[3], [1, 4, 1]);
    // The camera moves: everything is rebuilt.
    assert_eq!(rebuilt[4], [2, 5, 2]);
    assert_eq!(frames[1].update.regenerated, 1);
    assert_eq!(frames[4].update.regenerated, 3);
    for (f, step) in frames.iter().zip(steps(5)) {
        assert!(f.trapezoids > 300, "{}", f.trapezoids);
        assert!(f.drawn.labels.drawn > 5);
        let want = reference_frame(step).expect("renders");
        assert!(
            f.shown.pixels() == want.as_slice(),
            "frame of {step:?} is not its render"
        );
    }
}

/// The demo's memory is sized by running its frames, and a frame can need
/// more while it is built than it uses once built (a rebuilt segment that
/// grew is stored while a later one still holds its last frame): sized by
/// use alone, `demo --size 256x256 --frames 16` ran out of trapezoids.
#[test]
fn the_memory_found_by_running_the_frames_is_enough() {
    use scanvert_sim::demo::{run_at, Size};
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("demo_sizes");
    for (w, h, frames) in [(256, 256, 16), (64, 64, 24), (300, 17, 12)] {
        let _ = std::fs::remove_dir_all(&dir);
        let size = Size::new(w, h).expect("a size");
        let report = run_at(size, &dir, frames, false)
            .unwrap_or_else(|e| panic!("{w}x{h}, {frames} frames: {e}"));
        assert_eq!(
            report.lines().count(),
            frames + 3 + scanvert_sim::demo::ATTRIBUTE_FRAMES,
            "{report}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The segment attributes on the demo's last frame run no procedure, the
/// placement re-cuts the bars from their record, and undoing them all
/// gives the frame back.
#[test]
fn attributes_change_the_frame_without_running_procedures() {
    use scanvert_sim::demo::{attribute_frames, DEFAULT_SIZE};
    let last = *steps(8).last().expect("steps");
    let frames = attribute_frames(DEFAULT_SIZE, last).expect("attributes run");
    let want = reference_frame(last).expect("renders");
    assert_eq!(frames.len(), 6);
    for (i, (what, update, pixels, marked, changed)) in frames.iter().enumerate() {
        assert!(
            marked >= changed,
            "{what}: {marked} rows marked, {changed} changed"
        );
        assert_eq!(update.regenerated, 0, "{what}");
        let placed = what.starts_with("place");
        assert_eq!(update.recut, placed as u32, "{what}");
        assert_eq!(pixels == &want, i == 5, "{what}");
    }
}

/// Each frame marks at least the rows it changed (`bands.rs` checks that a
/// panel sent only the marked rows equals the full render), and the
/// README quotes the ratio `scanvert demo` prints on its default frames.
#[test]
fn the_demo_marks_the_rows_it_changes_and_the_readme_quotes_the_ratio() {
    use scanvert_sim::demo::{run_at, DEFAULT_SIZE};
    for f in animate(6).expect("demo runs") {
        assert!(
            f.marked >= f.changed,
            "{:?}: {} of {}",
            f.step,
            f.marked,
            f.changed
        );
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("demo_marks");
    let report = run_at(DEFAULT_SIZE, &dir, 8, false).expect("demo runs");
    let _ = std::fs::remove_dir_all(&dir);
    let line = report
        .lines()
        .find(|l| l.starts_with("rows marked per row changed"))
        .expect("the ratio's line");
    let readme = include_str!("../../README.md");
    assert!(readme.contains(line), "README.md does not quote `{line}`");
}
