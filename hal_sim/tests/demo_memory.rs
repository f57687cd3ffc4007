//! `scanvert demo` holds one frame at a time: each frame's PNG is written
//! as the frame is shown, and the co-simulation keeps only the newest frame
//! read out. Kept until the end, the frames of `demo --size 2047x2047
//! --frames 100` would take about 2.5 GB.
//!
//! The allocator of this test binary counts the bytes in use and their
//! peak; the file holds this one test, so nothing else allocates meanwhile.

use scanvert_sim::demo::{run_at, Size};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grew(n: usize) {
    let now = IN_USE.fetch_add(n, Relaxed) + n;
    PEAK.fetch_max(now, Relaxed);
}

// SAFETY: every call is passed on to `System` unchanged; the counters
// only observe the sizes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            grew(layout.size());
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        IN_USE.fetch_sub(layout.size(), Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            IN_USE.fetch_sub(layout.size(), Relaxed);
            grew(new_size);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most bytes in use above those in use before, while the demo writes
/// `frames` frames at `size` into a directory of their own.
fn peak_of(size: Size, frames: usize) -> usize {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("demo_memory")
        .join(frames.to_string());
    let _ = std::fs::remove_dir_all(&dir);
    let base = IN_USE.load(Relaxed);
    PEAK.store(base, Relaxed);
    let report = run_at(size, &dir, frames, false).expect("the demo runs");
    let peak = PEAK.load(Relaxed) - base;
    assert_eq!(
        report.lines().count(),
        frames + 3 + scanvert_sim::demo::ATTRIBUTE_FRAMES,
        "{report}"
    );
    for i in 0..frames {
        assert!(dir.join(format!("frame-{i:02}.png")).is_file(), "frame {i}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    peak
}

#[test]
fn the_demo_holds_one_frame_at_a_time() {
    let size = Size::new(320, 240).expect("a size");
    // A frame as shown: 320 × 240 pixels of 2 bytes.
    let frame = 320 * 240 * 2;
    let few = peak_of(size, 2);
    let many = peak_of(size, 16);
    eprintln!("peak: {few} B for 2 frames, {many} B for 16");
    assert!(
        many < few + 2 * frame,
        "16 frames peak at {many} B, 2 frames at {few} B: more than 2 frames ({} B) apart",
        2 * frame
    );
}
