//! Sets `scanvert_stm` on targets whose cores run Thumb-2 (ARMv7-M,
//! ARMv7E-M, ARMv8-M Mainline and the Thumb-2 A/R-profile targets): there
//! long runs of words are stored eight registers at a time
//! (`src/port/store_multiple.rs`, the crate's one `unsafe` block).
//! Target features other than the stable ones are not visible to `cfg`
//! on a stable compiler, so the target's name decides, as the
//! `cortex-m` crate's build script does.
//!
//! `SCANVERT_PORTABLE` set in the build's environment (to anything)
//! leaves the cfg unset: every target then stores runs in safe Rust, for
//! a product whose rules allow no assembly.
fn main() {
    println!("cargo::rustc-check-cfg=cfg(scanvert_stm)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-env-changed=SCANVERT_PORTABLE");
    let target = std::env::var("TARGET").unwrap_or_default();
    let thumb2 = ["thumbv7", "thumbv8m.main"]
        .iter()
        .any(|prefix| target.starts_with(prefix));
    let portable = std::env::var_os("SCANVERT_PORTABLE").is_some();
    if thumb2 && !portable {
        println!("cargo::rustc-cfg=scanvert_stm");
    }
}
