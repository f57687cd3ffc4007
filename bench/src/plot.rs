//! The speed-vs-error plot, drawn with embedded-graphics primitives and its
//! mono font into an RGB888 frame, written as PNG.

use crate::contenders::EgFrame;
use crate::Row;
use embedded_graphics::{
    mono_font::{ascii::FONT_6X10, MonoTextStyle},
    pixelcolor::Rgb888,
    prelude::*,
    primitives::{Circle, Line, PrimitiveStyle, Rectangle},
    text::{Alignment, Text},
};

const W: u32 = 960;
const H: u32 = 600;
/// Plot area: left, top, right, bottom.
const L: i32 = 80;
const T: i32 = 40;
const R: i32 = 600;
const B: i32 = 540;

const PALETTE: [Rgb888; 10] = [
    Rgb888::new(0xd6, 0x27, 0x28),
    Rgb888::new(0xff, 0x7f, 0x0e),
    Rgb888::new(0x2c, 0xa0, 0x2c),
    Rgb888::new(0x1f, 0x77, 0xb4),
    Rgb888::new(0x94, 0x67, 0xbd),
    Rgb888::new(0x8c, 0x56, 0x4b),
    Rgb888::new(0xe3, 0x77, 0xc2),
    Rgb888::new(0x17, 0xbe, 0xcf),
    Rgb888::new(0xbc, 0xbd, 0x22),
    Rgb888::new(0x7f, 0x7f, 0x7f),
];

/// Renders the plot of `rows` (those with an error figure) and returns
/// `(width, height, rgb bytes)`.
pub fn render(rows: &[Row]) -> (u32, u32, Vec<u8>) {
    let mut f = EgFrame::new(W, H, Rgb888::WHITE);
    let Ok(()) = draw(&mut f, rows);
    let bytes = f
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .collect();
    (W, H, bytes)
}

fn draw(f: &mut EgFrame<Rgb888>, rows: &[Row]) -> Result<(), core::convert::Infallible> {
    let pts: Vec<&Row> = rows.iter().filter(|r| r.err.is_some()).collect();
    let text = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let grey = PrimitiveStyle::with_stroke(Rgb888::new(0xdd, 0xdd, 0xdd), 1);
    let axis = PrimitiveStyle::with_stroke(Rgb888::BLACK, 1);

    // y: speed relative to slice::fill, log10, whole decades.
    let ys: Vec<f64> = pts.iter().map(|r| r.ratio.max(1e-6).log10()).collect();
    let y_lo = ys.iter().copied().fold(0.0f64, f64::min).floor();
    let y_hi = ys
        .iter()
        .copied()
        .fold(-9.0f64, f64::max)
        .ceil()
        .max(y_lo + 1.0);
    let ypix = |v: f64| B - ((v - y_lo) / (y_hi - y_lo) * (B - T) as f64).round() as i32;
    // x: mismatches per 1000 px; 0 in its own column, then log10 decades.
    let xs: Vec<f64> = pts
        .iter()
        .filter_map(|r| r.err.map(|e| e.per_1000))
        .filter(|&e| e > 0.0)
        .map(f64::log10)
        .collect();
    let x_lo = xs.iter().copied().fold(0.0f64, f64::min).floor();
    let x_hi = xs
        .iter()
        .copied()
        .fold(-9.0f64, f64::max)
        .ceil()
        .max(x_lo + 1.0);
    let x0 = L + 70;
    let xpix = |e: f64| {
        if e <= 0.0 {
            L + 20
        } else {
            x0 + ((e.log10() - x_lo) / (x_hi - x_lo) * (R - x0) as f64).round() as i32
        }
    };

    for d in y_lo as i32..=y_hi as i32 {
        let y = ypix(d as f64);
        Line::new(Point::new(L, y), Point::new(R, y))
            .into_styled(grey)
            .draw(f)?;
        Text::with_alignment(&decade(d), Point::new(L - 6, y + 3), text, Alignment::Right)
            .draw(f)?;
    }
    for d in x_lo as i32..=x_hi as i32 {
        let x = xpix(10f64.powi(d));
        Line::new(Point::new(x, T), Point::new(x, B))
            .into_styled(grey)
            .draw(f)?;
        Text::with_alignment(&decade(d), Point::new(x, B + 14), text, Alignment::Center).draw(f)?;
    }
    Line::new(Point::new(L + 20, T), Point::new(L + 20, B))
        .into_styled(grey)
        .draw(f)?;
    Text::with_alignment("0", Point::new(L + 20, B + 14), text, Alignment::Center).draw(f)?;
    Rectangle::with_corners(Point::new(L, T), Point::new(R, B))
        .into_styled(axis)
        .draw(f)?;
    Text::with_alignment(
        "mismatched pixels per 1000 covered (0, then log scale)",
        Point::new((L + R) / 2, B + 32),
        text,
        Alignment::Center,
    )
    .draw(f)?;
    Text::new(
        "speed as a fraction of slice::fill of the same pixel count (log scale)",
        Point::new(L - 60, T - 8),
        text,
    )
    .draw(f)?;
    Text::new(
        "scanvert speed vs error: 2D workloads W1, W3, W4, W5",
        Point::new(L - 60, T - 22),
        text,
    )
    .draw(f)?;

    // Legend: one colour per contender, in order of appearance.
    let mut names: Vec<&str> = Vec::new();
    for r in &pts {
        if !names.contains(&r.contender) {
            names.push(r.contender);
        }
    }
    for (k, n) in names.iter().enumerate() {
        let c = PALETTE[k % PALETTE.len()];
        let y = T + 10 + 18 * k as i32;
        Circle::with_center(Point::new(R + 20, y), 9)
            .into_styled(PrimitiveStyle::with_fill(c))
            .draw(f)?;
        Text::new(&legend(n), Point::new(R + 30, y + 3), text).draw(f)?;
    }
    for r in &pts {
        let Some(e) = r.err else { continue };
        let k = names.iter().position(|n| *n == r.contender).unwrap_or(0);
        let c = PALETTE[k % PALETTE.len()];
        let p = Point::new(xpix(e.per_1000), ypix(r.ratio.max(1e-6).log10()));
        Circle::with_center(p, 9)
            .into_styled(PrimitiveStyle::with_fill(c))
            .draw(f)?;
        Text::new(
            r.workload,
            p + Point::new(6, -4),
            MonoTextStyle::new(&FONT_6X10, c),
        )
        .draw(f)?;
    }
    Ok(())
}

/// `10^d` as plain decimals.
fn decade(d: i32) -> String {
    if d >= 0 {
        format!("{}", 10u64.pow(d as u32))
    } else {
        format!("{:.*}", (-d) as usize, 10f64.powi(d))
    }
}

/// A contender's name without Markdown backticks, cut to fit.
fn legend(n: &str) -> String {
    let s: String = n.chars().filter(|&c| c != '`').collect();
    s.chars().take(58).collect()
}
