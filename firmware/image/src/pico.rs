//! The `pico` variant: the Pico board's rendering core
//! (`firmware/boards/pico-st7789/src/ui.rs`, the very file the board's
//! firmware builds), built for `thumbv6m-none-eabi` (the RP2040's
//! Cortex-M0+ instruction set, which the M4 machine runs unchanged) or for
//! `thumbv7em-none-eabihf` (the `ui_3d_panel` example's core on a
//! Cortex-M4F), its frames counted.
//!
//! Printed: a line `pico` a frame, with the rows it sent and the
//! instructions it took, then the largest; measure.sh reads them and the
//! deepest stack, and estimates the board's frames per second.

#[path = "../../boards/pico-st7789/src/ui.rs"]
#[allow(dead_code)]
mod ui;

use crate::platform;
use core::convert::Infallible;
use scanvert::pixelcolor::Rgb565;
use scanvert::port::packed_band::PackedBandTarget;
use semihosting::println;
use static_cell::ConstStaticCell;

/// Frames drawn: the first (every row) and the changes of 23 more.
const FRAMES: u32 = 24;

/// A panel that counts the rows it is sent.
struct Rows(u32);

impl PackedBandTarget for Rows {
    type Color = Rgb565;
    type Error = Infallible;
    fn ship_words(&mut self, _y: u16, rows: u16, _w: u16, _px: &[u32]) -> Result<(), Infallible> {
        self.0 += rows as u32;
        Ok(())
    }
}

/// Draws the frames; `true` when every one was drawn.
pub fn run(counter: &platform::Counter, ok: bool) -> bool {
    // As the board keeps it: made at compile time, taken once.
    static MEMORY: ConstStaticCell<ui::Memory> = ConstStaticCell::new(ui::Memory::new());
    let Some(mem) = MEMORY.try_take() else {
        crate::log::fault("the Pico's memory is taken");
        return false;
    };
    let Ok(mut core) = ui::Ui::new(mem) else {
        crate::log::fault("the Pico's UI did not start");
        return false;
    };
    let (mut most, mut rows_total) = (0, 0);
    for frame in 0..FRAMES {
        let mut rows = Rows(0);
        let t0 = counter.ticks();
        let drawn = core.step(&mut rows);
        let ticks = counter.ticks() - t0;
        if drawn.is_err() {
            crate::log::fault("a Pico frame failed");
            return false;
        }
        let instructions = ticks * platform::INSTRUCTIONS_PER_TICK;
        most = most.max(instructions);
        rows_total += rows.0;
        println!(
            "pico frame {frame} rows={} instructions={instructions}",
            rows.0
        );
    }
    println!(
        "pico frames={FRAMES} rows={rows_total} most={most} memory={}",
        core::mem::size_of::<ui::Memory>()
    );
    ok
}
