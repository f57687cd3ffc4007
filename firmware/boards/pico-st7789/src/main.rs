//! scanvert on a Raspberry Pi Pico with a 240 × 240 ST7789 panel
//! (Waveshare Pico-LCD-1.3, or any ST7789 module wired the same way):
//! a 3D cube turning under a 2D UI, drawn in 16-row bands with no frame
//! buffer and sending only the rows that changed.
//!
//! What is drawn is in [`ui`], which has no hardware in it; a host test
//! (`host_tests/tests/board_pico.rs`) runs that same file against a full
//! render. This file is the board: clocks, the pins (all in [`pins`]),
//! the SPI bus, the panel's start-up, and the frame loop.

#![no_std]
#![no_main]

mod ui;

use embedded_hal::delay::DelayNs;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiDevice;
use embedded_hal_bus::spi::ExclusiveDevice;
use hal::clocks::Clock;
use hal::fugit::RateExtU32;
use hal::gpio::FunctionSpi;
use hal::pac;
use panic_halt as _;
use rp2040_hal as hal;
use scanvert::port::panel::Panel;
use static_cell::ConstStaticCell;

/// The second-stage boot loader, for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The drawing's memory.
static MEMORY: ConstStaticCell<ui::Memory> = ConstStaticCell::new(ui::Memory::new());
/// The SPI byte buffer: pixels are converted into it, big-endian, and sent.
static BYTES: ConstStaticCell<[u8; 512]> = ConstStaticCell::new([0; 512]);

/// The Pico's crystal.
const XTAL_HZ: u32 = 12_000_000;

/// The SPI clock: the ST7789's fastest write clock is 62.5 MHz, which the
/// RP2040 reaches from its 125 MHz peripheral clock.
const SPI_HZ: u32 = 62_500_000;

/// Every pin the board uses (the Waveshare Pico-LCD-1.3's wiring). To
/// wire another ST7789 module, change them here only.
mod pins {
    /// SPI1 clock (SCL on the panel).
    pub type Sck = rp2040_hal::gpio::bank0::Gpio10;
    /// SPI1 data out (SDA on the panel).
    pub type Mosi = rp2040_hal::gpio::bank0::Gpio11;
    /// Chip select, driven by the `SpiDevice`.
    pub type Cs = rp2040_hal::gpio::bank0::Gpio9;
    /// Data/command.
    pub type Dc = rp2040_hal::gpio::bank0::Gpio8;
    /// Reset, active low.
    pub type Rst = rp2040_hal::gpio::bank0::Gpio12;
    /// Backlight, on when high.
    pub type Bl = rp2040_hal::gpio::bank0::Gpio13;
}

/// The panel's start-up: a hardware reset, then out of sleep, 16-bit
/// colour, rows top to bottom, colours inverted (IPS panels), display on.
fn start_panel<S: SpiDevice, P: OutputPin>(
    spi: &mut S,
    dc: &mut P,
    rst: &mut impl OutputPin,
    delay: &mut impl DelayNs,
) {
    let _ = rst.set_low();
    delay.delay_ms(10);
    let _ = rst.set_high();
    delay.delay_ms(120);
    let mut command = |op: u8, data: &[u8], wait_ms: u32, delay: &mut dyn DelayNs| {
        let _ = dc.set_low();
        let _ = spi.write(&[op]);
        if !data.is_empty() {
            let _ = dc.set_high();
            let _ = spi.write(data);
        }
        delay.delay_ms(wait_ms);
    };
    command(0x01, &[], 150, delay); // SWRESET
    command(0x11, &[], 120, delay); // SLPOUT
    command(0x3a, &[0x55], 0, delay); // COLMOD: RGB565
    command(0x36, &[0x00], 0, delay); // MADCTL: rows top to bottom, RGB
    command(0x21, &[], 0, delay); // INVON
    command(0x13, &[], 0, delay); // NORON
    command(0x29, &[], 20, delay); // DISPON
}

#[hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .ok()
    .unwrap();
    let sio = hal::Sio::new(pac.SIO);
    let io = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    let sck = io.gpio10.into_function::<FunctionSpi>();
    let mosi = io.gpio11.into_function::<FunctionSpi>();
    let _: (
        &hal::gpio::Pin<pins::Sck, _, _>,
        &hal::gpio::Pin<pins::Mosi, _, _>,
    ) = (&sck, &mosi);
    let bus = hal::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        SPI_HZ.Hz(),
        embedded_hal::spi::MODE_3,
    );
    let cs: hal::gpio::Pin<pins::Cs, _, _> = io.gpio9.into_push_pull_output();
    let mut dc: hal::gpio::Pin<pins::Dc, _, _> = io.gpio8.into_push_pull_output();
    let mut rst: hal::gpio::Pin<pins::Rst, _, _> = io.gpio12.into_push_pull_output();
    let mut bl: hal::gpio::Pin<pins::Bl, _, _> = io.gpio13.into_push_pull_output();
    let mut spi = ExclusiveDevice::new(bus, cs, timer).unwrap();

    start_panel(&mut spi, &mut dc, &mut rst, &mut timer);
    let _ = bl.set_high();

    // All of the drawing memory, made at compile time (in `.bss`, being
    // zeros) and taken once, never copied through the stack.
    let mem: &'static mut ui::Memory = MEMORY.take();
    let bytes: &'static mut [u8; 512] = BYTES.take();
    let mut panel = Panel::new(spi, dc, bytes);
    let mut core = ui::Ui::new(mem).unwrap();
    loop {
        // A frame that fails to reach the panel is followed by a whole
        // one: the frame pass marks every row after a failed frame.
        let _ = core.step(&mut panel);
    }
}
