//! Long runs of words stored eight registers at a time, on Thumb-2 cores.
//!
//! The one `unsafe` block of the library, and why it is there: a run of
//! 32 words or more (a span of 64 pixels or more in the packed ports, a
//! clear) is the place where scan conversion meets the memory limit. In
//! safe code LLVM stores a run as double words (`strd`, two words an
//! instruction) and never as a store-multiple of eight registers (`stm`,
//! eight words an instruction), because the eight registers would all
//! hold the same value. On the Cortex-M4 image the W5 polygon (a 12-gon
//! covering most of 512 × 256) then costs about 1.9× a compiler-unrolled
//! fill of its words, and clears and wide spans pay the same. With the
//! run stored here, W5 is within 1.2× of that fill; `docs/performance.md`
//! ("Cortex-M4") publishes the counts, and its performance log the
//! variants measured before this one.
//!
//! The block is built only where the build script sets `scanvert_stm`
//! (targets whose cores run Thumb-2; ARMv6-M and RISC-V use the safe
//! loop), and not at all when `SCANVERT_PORTABLE` is set in the build's
//! environment. It takes its three operands in whatever registers the compiler
//! chose, saves every register it uses and restores them, so the scan
//! converter's row loops around it keep their registers: a version that
//! named its operands' registers, or called a function, moved those
//! loops' registers and cost the short spans more than the long ones
//! gained.
//!
//! Tested by the Cortex-M4 image, whose frames (W2's clear, W5, the demo
//! and the band path) must equal the host's checksums, and whose start
//! checks every run length from 32 to 300 words at every alignment
//! against a guard band (`firmware/image/src/main.rs`, `check_fills`).

/// Stores `v` in every word of `run`. A run shorter than 32 words is left
/// to the caller's smaller groups and is written here word by word, so
/// the function is total.
#[allow(unsafe_code)]
#[inline(always)]
pub(super) fn fill(run: &mut [u32], v: u32) {
    let n = run.len();
    if n < 32 {
        // Not reached from `packed::fill_words`, which sends only runs of
        // 32 words or more.
        run.fill(v);
        return;
    }
    let start = run.as_mut_ptr();
    // One past the last word: `n ≥ 32`, so `end − 128` bytes is `start`
    // or after it.
    let end = start.wrapping_add(n);
    // SAFETY: the block stores only to the words `start..end` of `run`,
    // which is borrowed mutably here and word-aligned (`[u32]`):
    // - the loop stores 32 words (128 bytes) from `r0` and goes on while
    //   the next 32 end at `end` or before (`r0 ≤ end − 128`); its first
    //   group is inside since `n ≥ 32`;
    // - the last four stores are the 32 words that end at `end`, which
    //   start at or after `start`.
    // It pushes the operands and the ten registers it uses, and pops them
    // all before it ends: `sp` and every register are as they were, and
    // the flags (`cmp`) are not promised to the compiler. It uses neither
    // `r6`, `r7` (the frame pointer) nor `r9`.
    unsafe {
        core::arch::asm!(
            // The operands to the stack, then the registers they may be
            // in among those used below, then the operands back into
            // fixed registers: r0 the address, r1 the end, r2 the value.
            "str {v}, [sp, #-4]!",
            "str {e}, [sp, #-4]!",
            "str {p}, [sp, #-4]!",
            "push {{r0, r1, r2, r3, r4, r5, r8, r10, r11, r12}}",
            "add r0, sp, #40",
            "ldm r0, {{r0, r1, r2}}",
            "mov r3, r2",
            "mov r4, r2",
            "mov r5, r2",
            "mov r8, r2",
            "mov r10, r2",
            "mov r11, r2",
            "mov r12, r2",
            // r1: where the last group of 32 words starts.
            "sub r1, r1, #128",
            "2:",
            "stm r0!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "stm r0!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "stm r0!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "stm r0!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "cmp r0, r1",
            "bls 2b",
            // The last 32 words, over the loop's last group.
            "stm r1!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "stm r1!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "stm r1!, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "stm r1, {{r2, r3, r4, r5, r8, r10, r11, r12}}",
            "pop {{r0, r1, r2, r3, r4, r5, r8, r10, r11, r12}}",
            "add sp, sp, #12",
            p = in(reg) start,
            e = in(reg) end,
            v = in(reg) v,
        );
    }
}
