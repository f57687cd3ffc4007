//! What the image reports: plain text through semihosting, or defmt
//! frames with the `defmt` feature. The lines starting `frame` and
//! `checksum` are read by `measure.sh` and by CI.

use crate::{Cost, Stages};
use core::convert::Infallible;
use scanvert::controller::{RenderError, RenderStats};
use scanvert::display_list::Error;

#[cfg(not(feature = "defmt"))]
use semihosting::println;

/// The banner.
pub fn start(machine: &str, counter: &str, per_tick: u64) {
    #[cfg(not(feature = "defmt"))]
    println!("scanvert image on {machine}: {counter}, {per_tick} instructions per tick");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "scanvert image on {=str}: {=str}, {=u64} instructions per tick",
        machine,
        counter,
        per_tick
    );
}

/// The check of the counter against the known loop.
pub fn calibration(expected: u64, ticks: u64, measured: u64, ok: bool) {
    let verdict = if ok { "ok" } else { "WRONG" };
    #[cfg(not(feature = "defmt"))]
    println!("calibration: loop of {expected} instructions, {ticks} ticks = {measured} instructions: {verdict}");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "calibration: loop of {=u64} instructions, {=u64} ticks = {=u64} instructions: {=str}",
        expected,
        ticks,
        measured,
        verdict
    );
}

/// The count of one `[u32]::fill` of `words` words (`kind`: on a slice or
/// an array), what a frame's pixel writes are compared with.
#[cfg(not(feature = "halfword"))]
pub fn fill(kind: &str, words: usize, ticks: u64) {
    let instructions = ticks * crate::platform::INSTRUCTIONS_PER_TICK;
    #[cfg(not(feature = "defmt"))]
    println!("fill {kind} words={words} ticks={ticks} instructions={instructions}");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "fill {=str} words={=usize} ticks={=u64} instructions={=u64}",
        kind,
        words,
        ticks,
        instructions
    );
}

/// How a frame's 3D layer was resolved, as its line says it: the mode
/// the default settled to, or the one asked for.
pub fn resolve_name(mode: scanvert::visible::Resolve) -> &'static str {
    use scanvert::visible::Resolve;
    match mode {
        Resolve::Paint => "paint",
        Resolve::Bisect => "bisect",
        Resolve::Crossing => "crossing",
        _ => "auto",
    }
}

/// One frame's statistics and cost.
pub fn frame(name: &str, w: u16, h: u16, s: &RenderStats, cost: Cost) {
    #[cfg(not(feature = "defmt"))]
    println!(
        "frame {name} {w}x{h} commands={} polygons={} clears={} spans={} pixels={} poly3={} trapezoids={} mode={} ticks={} instructions={}",
        s.commands, s.polygons, s.clears, s.spans, s.pixels, s.poly3, s.trapezoids, resolve_name(s.visible.mode), cost.ticks, cost.instructions
    );
    #[cfg(feature = "defmt")]
    defmt::info!(
        "frame {=str} {=u16}x{=u16} {} ticks={=u64} instructions={=u64}",
        name,
        w,
        h,
        s,
        cost.ticks,
        cost.instructions
    );
}

/// The instructions of each stage of a 3D layer, and what the
/// visible-surface stage did.
pub fn stages(name: &str, s: &Stages) {
    let v = &s.visible;
    #[cfg(not(feature = "defmt"))]
    println!(
        "stages {name} faces={} trapezoids={} cut={} check={} resolve={} max_active={} hidden={} empty={} single={} multiple={} intersecting={} splits={} exact={} runs={}",
        s.faces, s.trapezoids, s.cut, s.check, s.resolve, v.max_active, v.hidden, v.empty, v.single,
        v.multiple, v.intersecting, v.splits, v.exact, v.runs
    );
    #[cfg(feature = "defmt")]
    defmt::info!(
        "stages {=str} faces={=u32} trapezoids={=u32} cut={=u64} check={=u64} resolve={=u64} {}",
        name,
        s.faces,
        s.trapezoids,
        s.cut,
        s.check,
        s.resolve,
        v
    );
}

/// One frame's checksum, in the form `scanvert checksum` prints.
pub fn checksum(name: &str, sum: u32) {
    #[cfg(not(feature = "defmt"))]
    println!("checksum {name} {sum:08x}");
    #[cfg(feature = "defmt")]
    defmt::info!("checksum {=str} {=u32:08x}", name, sum);
}

/// A frame whose checksum is not the host's.
pub fn mismatch(name: &str, expected: u32) {
    #[cfg(not(feature = "defmt"))]
    println!("MISMATCH {name}: the host's checksum is {expected:08x}");
    #[cfg(feature = "defmt")]
    defmt::error!(
        "MISMATCH {=str}: the host's checksum is {=u32:08x}",
        name,
        expected
    );
}

/// An embedded list that does not read.
pub fn bad_list(name: &str, e: Error) {
    #[cfg(not(feature = "defmt"))]
    println!("ERROR {name}: {e}");
    #[cfg(feature = "defmt")]
    defmt::error!("ERROR {=str}: {}", name, e);
}

/// A list whose frame does not fit the frame buffer.
#[cfg(not(feature = "discard"))]
pub fn too_big(name: &str, w: u16, h: u16) {
    #[cfg(not(feature = "defmt"))]
    println!("ERROR {name}: frame {w}x{h} is larger than the frame buffer");
    #[cfg(feature = "defmt")]
    defmt::error!(
        "ERROR {=str}: frame {=u16}x{=u16} is larger than the frame buffer",
        name,
        w,
        h
    );
}

/// A render that failed.
pub fn render_error(name: &str, e: RenderError<Infallible>) {
    #[cfg(not(feature = "defmt"))]
    println!("ERROR {name}: {e}");
    #[cfg(feature = "defmt")]
    defmt::error!("ERROR {=str}: {}", name, e);
}

/// A fault outside any frame.
pub fn fault(what: &str) {
    #[cfg(not(feature = "defmt"))]
    println!("ERROR {what}");
    #[cfg(feature = "defmt")]
    defmt::error!("ERROR {=str}", what);
}

/// The verdict.
pub fn summary(matched: usize, frames: usize, ok: bool) {
    let verdict = if ok { "PASS" } else { "FAIL" };
    #[cfg(all(not(feature = "defmt"), feature = "discard"))]
    println!("{verdict}: {matched} of {frames} frames rendered (spans discarded, no checksums)");
    #[cfg(all(not(feature = "defmt"), not(feature = "discard")))]
    println!("{verdict}: {matched} of {frames} frames equal the host's");
    #[cfg(feature = "defmt")]
    defmt::info!(
        "{=str}: {=usize} of {=usize} frames equal the host's",
        verdict,
        matched,
        frames
    );
}
