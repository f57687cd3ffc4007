//! Video timing: the pixel clock and the hsync/vsync geometry that the
//! refresh controller generates.
//!
//! A line is `active` pixel clocks of display followed by the horizontal
//! retrace: front porch, sync pulse, back porch. A frame is `active` lines
//! followed by the vertical retrace, split the same way, in whole lines.
//! Every derived figure is computed in integers; the `f64` accessors are
//! for display only.
//!
//! | preset | clock | line (clocks) | frame (lines) | line period | frame period |
//! |---|---|---|---|---|---|
//! | [`VideoTiming::REFERENCE_640X480`] | 25 MHz | 640 + 16 + 96 + 48 = 800 | 480 + 10 + 2 + 29 = 521 | 32 µs | 16.672 ms (59.98 Hz) |
//! | [`VideoTiming::TV_256X256`] | 5 MHz | 256 + 8 + 24 + 32 = 320 | 256 + 24 + 3 + 29 = 312 | 64 µs | 19.968 ms (50.08 Hz) |
//! | [`VideoTiming::VGA_640X480_60`] | 25.175 MHz | 640 + 16 + 96 + 48 = 800 | 480 + 10 + 2 + 33 = 525 | 31.778 µs | 16.683 ms (59.94 Hz) |

use core::fmt;
use core::num::NonZeroU32;

/// Picoseconds in one second.
pub const PS_PER_SECOND: u64 = 1_000_000_000_000;

/// Largest active width or height, in pixels (as for the frame buffer).
pub const MAX_ACTIVE: u16 = 4096;

/// A clock of a fixed, non-zero frequency in hertz.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Clock(NonZeroU32);

impl Clock {
    /// A clock of `hz` hertz, or `None` for 0.
    pub const fn from_hz(hz: u32) -> Option<Clock> {
        match NonZeroU32::new(hz) {
            Some(hz) => Some(Clock(hz)),
            None => None,
        }
    }

    /// A clock of `mhz` megahertz, or `None` for 0 or above `u32::MAX` Hz.
    pub const fn from_mhz(mhz: u32) -> Option<Clock> {
        match mhz.checked_mul(1_000_000) {
            Some(hz) => Clock::from_hz(hz),
            None => None,
        }
    }

    /// Frequency in hertz.
    pub const fn hz(self) -> u32 {
        self.0.get()
    }

    /// The time `cycles` clock periods take, in picoseconds, rounded to the
    /// nearest (exact when the frequency divides `cycles × 10¹²`);
    /// saturates at `u64::MAX`.
    pub const fn time_ps(self, cycles: u64) -> u64 {
        let hz = self.0.get() as u128;
        let ps = (cycles as u128 * PS_PER_SECOND as u128 + hz / 2) / hz;
        if ps > u64::MAX as u128 {
            u64::MAX
        } else {
            ps as u64
        }
    }

    /// One clock period in picoseconds, rounded to the nearest.
    pub const fn period_ps(self) -> u64 {
        self.time_ps(1)
    }
}

impl fmt::Display for Clock {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let hz = self.hz();
        if hz.is_multiple_of(1_000_000) {
            write!(f, "{} MHz", hz / 1_000_000)
        } else {
            write!(f, "{} Hz", hz)
        }
    }
}

const fn clock(hz: u32) -> Clock {
    match Clock::from_hz(hz) {
        Some(c) => c,
        None => panic!("zero clock"),
    }
}

/// One axis of the raster: horizontally in pixel clocks, vertically in
/// lines. The order on the wire is active, front porch, sync, back porch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct AxisTiming {
    /// Displayed pixels (clocks) or lines.
    pub active: u16,
    /// Blanking before the sync pulse.
    pub front_porch: u16,
    /// The sync pulse.
    pub sync: u16,
    /// Blanking after the sync pulse.
    pub back_porch: u16,
}

impl AxisTiming {
    /// An axis of `active` displayed positions, then the retrace.
    pub const fn new(active: u16, front_porch: u16, sync: u16, back_porch: u16) -> Self {
        AxisTiming {
            active,
            front_porch,
            sync,
            back_porch,
        }
    }

    /// Active, front porch, sync and back porch together.
    pub const fn total(&self) -> u32 {
        self.active as u32 + self.blanking()
    }

    /// The retrace: front porch, sync and back porch.
    pub const fn blanking(&self) -> u32 {
        self.front_porch as u32 + self.sync as u32 + self.back_porch as u32
    }

    /// First position (counting from the first active one) with sync
    /// asserted.
    pub const fn sync_start(&self) -> u32 {
        self.active as u32 + self.front_porch as u32
    }

    /// First position after the sync pulse.
    pub const fn sync_end(&self) -> u32 {
        self.sync_start() + self.sync as u32
    }
}

/// A video mode: pixel clock plus horizontal and vertical timing.
///
/// # Guarantees
/// The active width and height are in `1..=4096` and both sync pulses are
/// at least one clock (line) long, so each line has one hsync pulse and
/// each frame one vsync pulse.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct VideoTiming {
    name: &'static str,
    pixel_clock: Clock,
    horizontal: AxisTiming,
    vertical: AxisTiming,
}

const fn preset(name: &'static str, hz: u32, h: [u16; 4], v: [u16; 4]) -> VideoTiming {
    let (h, v) = (
        AxisTiming::new(h[0], h[1], h[2], h[3]),
        AxisTiming::new(v[0], v[1], v[2], v[3]),
    );
    match VideoTiming::new(name, clock(hz), h, v) {
        Some(t) => t,
        None => panic!("invalid preset"),
    }
}

impl VideoTiming {
    /// The reference design: 25 MHz pixel clock; horizontal display 25.6 µs
    /// (640 clocks) and retrace 6.4 µs (160 clocks), vertical display
    /// 15.36 ms (480 lines) and retrace 1.312 ms (41 lines).
    ///
    /// The design gives the retraces only as totals; they are split here as
    /// VGA splits them where that fits: horizontal front porch 16 clocks
    /// (0.64 µs), sync 96 (3.84 µs), back porch 48 (1.92 µs); vertical front
    /// porch 10 lines, sync 2, and the back porch takes the remaining 29
    /// (VGA's 33, four lines shorter). Line 800 clocks = 32 µs, frame
    /// 521 lines = 16.672 ms, 59.98 Hz.
    pub const REFERENCE_640X480: VideoTiming = preset(
        "reference 640x480",
        25_000_000,
        [640, 16, 96, 48],
        [480, 10, 2, 29],
    );

    /// A 256 × 256 mode on a 50 Hz TV-like raster: 5 MHz pixel clock
    /// (200 ns per pixel), 320 clocks per line = 64 µs as in 625-line TV,
    /// 312 lines per frame (non-interlaced, 19.968 ms, 50.08 Hz).
    ///
    /// Horizontal: 256 active (51.2 µs), front porch 8 (1.6 µs), sync 24
    /// (4.8 µs, TV's line sync is 4.7 µs), back porch 32 (6.4 µs).
    /// Vertical: 256 active lines, front porch 24, sync 3, back porch 29,
    /// which centres the picture roughly in TV's 288 visible lines.
    pub const TV_256X256: VideoTiming = preset(
        "TV 256x256@50",
        5_000_000,
        [256, 8, 24, 32],
        [256, 24, 3, 29],
    );

    /// Standard VGA 640 × 480 at 60 Hz: 25.175 MHz, 640 + 16 + 96 + 48 =
    /// 800 clocks per line, 480 + 10 + 2 + 33 = 525 lines per frame.
    pub const VGA_640X480_60: VideoTiming = preset(
        "VGA 640x480@60",
        25_175_000,
        [640, 16, 96, 48],
        [480, 10, 2, 33],
    );

    /// Every preset, the one [`for_frame`](Self::for_frame) prefers first.
    pub const PRESETS: [VideoTiming; 3] = [
        VideoTiming::REFERENCE_640X480,
        VideoTiming::TV_256X256,
        VideoTiming::VGA_640X480_60,
    ];

    /// A mode, or `None` when an active side is outside `1..=4096` or a
    /// sync pulse is 0 long.
    pub const fn new(
        name: &'static str,
        pixel_clock: Clock,
        horizontal: AxisTiming,
        vertical: AxisTiming,
    ) -> Option<VideoTiming> {
        let ok = horizontal.active >= 1
            && horizontal.active <= MAX_ACTIVE
            && vertical.active >= 1
            && vertical.active <= MAX_ACTIVE
            && horizontal.sync >= 1
            && vertical.sync >= 1;
        if ok {
            Some(VideoTiming {
                name,
                pixel_clock,
                horizontal,
                vertical,
            })
        } else {
            None
        }
    }

    /// The mode for a `width × height` frame: the first of [`PRESETS`]
    /// with that active area (the reference design for 640 × 480), else a
    /// custom mode named `"custom"`.
    ///
    /// The custom mode keeps the reference design's 25 MHz pixel clock and
    /// scales its porches and syncs with the active size, each rounded up:
    /// horizontal front porch ⌈w/40⌉, sync ⌈3w/20⌉, back porch ⌈3w/40⌉;
    /// vertical front porch ⌈h/48⌉, sync 2 lines, back porch ⌈29h/480⌉.
    /// (At 640 × 480 this is the reference design exactly.) The refresh
    /// rate then falls as the area grows.
    ///
    /// Sides outside `1..=4096` are clamped into it, so this never fails.
    ///
    /// [`PRESETS`]: Self::PRESETS
    pub fn for_frame(width: u16, height: u16) -> VideoTiming {
        let w = width.clamp(1, MAX_ACTIVE);
        let h = height.clamp(1, MAX_ACTIVE);
        if let Some(t) = Self::PRESETS
            .iter()
            .find(|t| t.width() == w && t.height() == h)
        {
            return *t;
        }
        let ceil = |num: u32, den: u32| num.div_ceil(den) as u16;
        let (w32, h32) = (w as u32, h as u32);
        VideoTiming {
            name: "custom",
            pixel_clock: clock(25_000_000),
            horizontal: AxisTiming {
                active: w,
                front_porch: ceil(w32, 40),
                sync: ceil(3 * w32, 20),
                back_porch: ceil(3 * w32, 40),
            },
            vertical: AxisTiming {
                active: h,
                front_porch: ceil(h32, 48),
                sync: 2,
                back_porch: ceil(29 * h32, 480),
            },
        }
    }

    /// The mode's name.
    pub const fn name(&self) -> &'static str {
        self.name
    }

    /// The pixel clock: one pixel (or blanking clock) per period.
    pub const fn pixel_clock(&self) -> Clock {
        self.pixel_clock
    }

    /// Horizontal timing, in pixel clocks.
    pub const fn horizontal(&self) -> AxisTiming {
        self.horizontal
    }

    /// Vertical timing, in lines.
    pub const fn vertical(&self) -> AxisTiming {
        self.vertical
    }

    /// Active width in pixels.
    pub const fn width(&self) -> u16 {
        self.horizontal.active
    }

    /// Active height in lines.
    pub const fn height(&self) -> u16 {
        self.vertical.active
    }

    /// Pixel clocks per line, retrace included.
    pub const fn clocks_per_line(&self) -> u32 {
        self.horizontal.total()
    }

    /// Lines per frame, retrace included.
    pub const fn lines_per_frame(&self) -> u32 {
        self.vertical.total()
    }

    /// Pixel clocks per frame.
    pub const fn clocks_per_frame(&self) -> u64 {
        self.clocks_per_line() as u64 * self.lines_per_frame() as u64
    }

    /// Line period in picoseconds, rounded to the nearest.
    pub const fn line_period_ps(&self) -> u64 {
        self.pixel_clock.time_ps(self.clocks_per_line() as u64)
    }

    /// Frame period in picoseconds, rounded to the nearest (computed from
    /// the clocks per frame, not from the rounded line period).
    pub const fn frame_period_ps(&self) -> u64 {
        self.pixel_clock.time_ps(self.clocks_per_frame())
    }

    /// The refresh rate as the exact fraction `(numerator, denominator)`
    /// hertz: pixel clock over clocks per frame, not reduced.
    pub const fn refresh_rate_ratio(&self) -> (u64, u64) {
        (self.pixel_clock.hz() as u64, self.clocks_per_frame())
    }

    /// The refresh rate in millihertz, rounded to the nearest.
    pub const fn refresh_rate_millihertz(&self) -> u64 {
        let (num, den) = self.refresh_rate_ratio();
        (num * 1000 + den / 2) / den
    }

    /// The line frequency in hertz, rounded to the nearest.
    pub const fn line_rate_hz(&self) -> u64 {
        let den = self.clocks_per_line() as u64;
        (self.pixel_clock.hz() as u64 + den / 2) / den
    }

    /// Line period in microseconds, for display.
    pub fn line_period_us(&self) -> f64 {
        self.clocks_per_line() as f64 * 1e6 / self.pixel_clock.hz() as f64
    }

    /// Frame period in milliseconds, for display.
    pub fn frame_period_ms(&self) -> f64 {
        self.clocks_per_frame() as f64 * 1e3 / self.pixel_clock.hz() as f64
    }

    /// Refresh rate in hertz, for display.
    pub fn refresh_rate_hz(&self) -> f64 {
        self.pixel_clock.hz() as f64 / self.clocks_per_frame() as f64
    }
}

impl fmt::Display for VideoTiming {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (h, v) = (self.horizontal, self.vertical);
        write!(
            f,
            "{}: {}×{}, {} pixel clock, {}+{}+{}+{} clocks × {}+{}+{}+{} lines, {:.3} Hz",
            self.name,
            h.active,
            v.active,
            self.pixel_clock,
            h.active,
            h.front_porch,
            h.sync,
            h.back_porch,
            v.active,
            v.front_porch,
            v.sync,
            v.back_porch,
            self.refresh_rate_hz()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_matches_the_design_figures() {
        let t = VideoTiming::REFERENCE_640X480;
        let clk = t.pixel_clock();
        assert_eq!(clk.time_ps(t.width() as u64), 25_600_000);
        assert_eq!(clk.time_ps(t.horizontal().blanking() as u64), 6_400_000);
        let line = t.line_period_ps();
        assert_eq!(line * t.height() as u64, 15_360_000_000);
        assert_eq!(line * t.vertical().blanking() as u64, 1_312_000_000);
    }

    #[test]
    fn for_frame_prefers_presets_and_scales_custom_modes() {
        assert_eq!(
            VideoTiming::for_frame(640, 480),
            VideoTiming::REFERENCE_640X480
        );
        assert_eq!(VideoTiming::for_frame(256, 256), VideoTiming::TV_256X256);
        let c = VideoTiming::for_frame(320, 200);
        assert_eq!((c.name(), c.width(), c.height()), ("custom", 320, 200));
        assert_eq!(c.horizontal().sync_start(), 328);
        // The custom rule near 640 × 480 gives the reference design's split.
        let r = VideoTiming::for_frame(640, 479);
        assert_eq!(r.horizontal(), VideoTiming::REFERENCE_640X480.horizontal());
        assert_eq!(r.vertical(), AxisTiming::new(479, 10, 2, 29));
        assert_eq!(
            r.pixel_clock(),
            VideoTiming::REFERENCE_640X480.pixel_clock()
        );
        // Clamped, never failing.
        assert_eq!(VideoTiming::for_frame(0, 9999).width(), 1);
        assert_eq!(VideoTiming::for_frame(0, 9999).height(), 4096);
    }

    #[test]
    fn invalid_modes_are_refused() {
        let a = AxisTiming {
            active: 10,
            front_porch: 0,
            sync: 0,
            back_porch: 0,
        };
        let ok = AxisTiming { sync: 1, ..a };
        let clk = Clock::from_mhz(1).unwrap();
        assert!(VideoTiming::new("x", clk, a, ok).is_none());
        assert!(VideoTiming::new("x", clk, ok, ok).is_some());
        assert!(VideoTiming::new("x", clk, AxisTiming { active: 0, ..ok }, ok).is_none());
        assert!(Clock::from_hz(0).is_none());
        assert!(Clock::from_mhz(5000).is_none());
    }
}
