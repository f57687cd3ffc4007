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
