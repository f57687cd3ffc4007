//! Puts the memory map where the linker finds it: the top-level
//! `memory.x` (mps2-an386: 4 MiB flash, 4 MiB RAM) for Cortex-M, or
//! `memory-riscv.x` (QEMU virt: everything in RAM) for RISC-V, copied into
//! OUT_DIR as `memory.x`. Adds `-Tdefmt.x` when the `defmt` feature is on.

use std::env;
use std::fs;
use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("set by cargo"));
    let arch = env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    let source = if arch == "riscv32" {
        manifest.join("memory-riscv.x")
    } else {
        manifest.join("../../memory.x")
    };
    fs::copy(&source, out.join("memory.x")).expect("copy the memory map into OUT_DIR");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", source.display());
    println!("cargo:rerun-if-changed=build.rs");
    if env::var_os("CARGO_FEATURE_DEFMT").is_some() {
        println!("cargo:rustc-link-arg=-Tdefmt.x");
    }
}
