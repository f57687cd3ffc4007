//! The plots, drawn with embedded-graphics primitives and its mono font
//! into an RGB888 frame, written as PNG: speed against error (2D
//! workloads) and time per frame against trapezoids per frame (3D scenes).

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
        "scanvert speed vs error: 2D workloads W1, W3, W4, W5, W6",
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

/// One line of the 3D plot: a contender's time per frame (ms) on one
/// version, by trapezoids per frame.
struct Series {
    name: String,
    layered: bool,
    color: Rgb888,
    points: Vec<(f64, f64)>,
}

/// Renders time per frame against trapezoids per frame for the 3D scenes
/// (both log scales) and returns `(width, height, rgb bytes)`.
pub fn render_3d(rows: &[crate::visible3d::Row3]) -> (u32, u32, Vec<u8>) {
    use crate::visible3d::CROSSING;
    use testkit::scenes3d::Version;
    let mut series: Vec<Series> = Vec::new();
    let mut names: Vec<String> = Vec::new();
    let mut push = |name: String, layered: bool, p: (f64, f64)| {
        if !names.contains(&name) {
            names.push(name.clone());
        }
        let k = names.iter().position(|n| *n == name).unwrap_or(0);
        match series
            .iter_mut()
            .find(|s| s.name == name && s.layered == layered)
        {
            Some(s) => s.points.push(p),
            None => series.push(Series {
                name,
                layered,
                color: PALETTE[k % PALETTE.len()],
                points: vec![p],
            }),
        }
    };
    for r in rows {
        let layered = r.version == Version::Layered;
        push(legend(r.contender), layered, (r.trapezoids, r.ms));
        if let (true, Some(alone)) = (r.contender == CROSSING, r.resolve_ms) {
            push(
                "scanvert Resolve::Crossing, resolve + decode alone".into(),
                layered,
                (r.trapezoids, alone),
            );
        }
    }
    let mut f = EgFrame::new(W, H, Rgb888::WHITE);
    let Ok(()) = draw_3d(&mut f, &series, &TRAPEZOIDS);
    let bytes = f
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .collect();
    (W, H, bytes)
}

/// The texts of a log-log plot.
struct Labels {
    title: &'static str,
    x: &'static str,
    y: &'static str,
    /// Whether the marks of the two versions are explained.
    versions: bool,
}

/// The y axis of the plots of milliseconds per frame.
const MS_PER_FRAME: &str = "milliseconds per frame, 512x256, this host (log scale)";

/// The labels of the time-against-trapezoids plot.
const TRAPEZOIDS: Labels = Labels {
    title: "3D scenes: time against trapezoids, 10 to 1000 faces",
    x: "trapezoids per frame (log scale)",
    y: MS_PER_FRAME,
    versions: true,
};

fn draw_3d(
    f: &mut EgFrame<Rgb888>,
    series: &[Series],
    labels: &Labels,
) -> Result<(), core::convert::Infallible> {
    let text = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let grey = PrimitiveStyle::with_stroke(Rgb888::new(0xdd, 0xdd, 0xdd), 1);
    let axis = PrimitiveStyle::with_stroke(Rgb888::BLACK, 1);
    let all = || series.iter().flat_map(|s| s.points.iter());
    let decades = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            let l = x.max(1e-9).log10();
            (lo.min(l), hi.max(l))
        });
        let lo = if lo.is_finite() { lo.floor() } else { 0.0 };
        (lo, hi.ceil().max(lo + 1.0))
    };
    let (x_lo, x_hi) = decades(&mut all().map(|p| p.0));
    let (y_lo, y_hi) = decades(&mut all().map(|p| p.1));
    let xpix =
        |v: f64| L + ((v.max(1e-9).log10() - x_lo) / (x_hi - x_lo) * (R - L) as f64).round() as i32;
    let ypix =
        |v: f64| B - ((v.max(1e-9).log10() - y_lo) / (y_hi - y_lo) * (B - T) as f64).round() as i32;

    for d in y_lo as i32..=y_hi as i32 {
        for m in [1.0, 2.0, 5.0] {
            let v = m * 10f64.powi(d);
            if v.log10() > y_hi + 1e-9 {
                continue;
            }
            let y = ypix(v);
            Line::new(Point::new(L, y), Point::new(R, y))
                .into_styled(grey)
                .draw(f)?;
            Text::with_alignment(&number(v), Point::new(L - 6, y + 3), text, Alignment::Right)
                .draw(f)?;
        }
    }
    for d in x_lo as i32..=x_hi as i32 {
        for m in [1.0, 2.0, 5.0] {
            let v = m * 10f64.powi(d);
            if v.log10() > x_hi + 1e-9 {
                continue;
            }
            let x = xpix(v);
            Line::new(Point::new(x, T), Point::new(x, B))
                .into_styled(grey)
                .draw(f)?;
            Text::with_alignment(&number(v), Point::new(x, B + 14), text, Alignment::Center)
                .draw(f)?;
        }
    }
    Rectangle::with_corners(Point::new(L, T), Point::new(R, B))
        .into_styled(axis)
        .draw(f)?;
    Text::with_alignment(
        labels.x,
        Point::new((L + R) / 2, B + 32),
        text,
        Alignment::Center,
    )
    .draw(f)?;
    Text::new(labels.y, Point::new(L - 60, T - 8), text).draw(f)?;
    Text::new(labels.title, Point::new(L - 60, T - 22), text).draw(f)?;

    // Lines first, then the marks over them.
    for s in series {
        let style = PrimitiveStyle::with_stroke(s.color, if s.layered { 1 } else { 2 });
        for w in s.points.windows(2) {
            Line::new(
                Point::new(xpix(w[0].0), ypix(w[0].1)),
                Point::new(xpix(w[1].0), ypix(w[1].1)),
            )
            .into_styled(style)
            .draw(f)?;
        }
    }
    for s in series {
        for &(x, y) in &s.points {
            mark(f, Point::new(xpix(x), ypix(y)), s.color, s.layered)?;
        }
    }

    // Legend: colours, then the two marks.
    let mut names: Vec<(&str, Rgb888)> = Vec::new();
    for s in series {
        if !names.iter().any(|n| n.0 == s.name) {
            names.push((&s.name, s.color));
        }
    }
    let mut y = T + 10;
    for (n, c) in &names {
        Line::new(Point::new(R + 12, y), Point::new(R + 28, y))
            .into_styled(PrimitiveStyle::with_stroke(*c, 2))
            .draw(f)?;
        Text::new(
            &n.chars().take(58).collect::<String>(),
            Point::new(R + 34, y + 3),
            text,
        )
        .draw(f)?;
        y += 18;
    }
    y += 8;
    if !labels.versions {
        return Ok(());
    }
    for (layered, what) in [
        (true, "2D version: faces parallel to the screen"),
        (false, "3D version: tilted, interpenetrating"),
    ] {
        mark(f, Point::new(R + 20, y), Rgb888::BLACK, layered)?;
        Text::new(what, Point::new(R + 34, y + 3), text).draw(f)?;
        y += 18;
    }
    Ok(())
}

/// A filled disc (2D version) or a square outline (3D version).
fn mark(
    f: &mut EgFrame<Rgb888>,
    p: Point,
    c: Rgb888,
    layered: bool,
) -> Result<(), core::convert::Infallible> {
    if layered {
        Circle::with_center(p, 9)
            .into_styled(PrimitiveStyle::with_fill(c))
            .draw(f)
    } else {
        Rectangle::with_center(p, Size::new(9, 9))
            .into_styled(PrimitiveStyle::with_stroke(c, 2))
            .draw(f)
    }
}

/// A tick label: `0.05`, `2`, `1000`.
fn number(v: f64) -> String {
    if v >= 1.0 {
        format!("{v:.0}")
    } else {
        let s = format!("{v:.6}");
        s.trim_end_matches('0').to_string()
    }
}

/// `series` as a plot of `labels`, `(width, height, rgb bytes)`.
fn render_series(series: &[Series], labels: &Labels) -> (u32, u32, Vec<u8>) {
    let mut f = EgFrame::new(W, H, Rgb888::WHITE);
    let Ok(()) = draw_3d(&mut f, series, labels);
    let bytes = f
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .collect();
    (W, H, bytes)
}

/// Puts `p` in the series `name` of `version`, coloured by `name`'s order.
fn push_point(series: &mut Vec<Series>, names: &[&str], name: &str, layered: bool, p: (f64, f64)) {
    let k = names.iter().position(|n| *n == name).unwrap_or(0);
    match series
        .iter_mut()
        .find(|s| s.name == name && s.layered == layered)
    {
        Some(s) => s.points.push(p),
        None => series.push(Series {
            name: name.into(),
            layered,
            color: PALETTE[k % PALETTE.len()],
            points: vec![p],
        }),
    }
}

/// Time per frame against the measured depth complexity (the sweep at a
/// fixed face count), both log scales.
pub fn render_depth(rows: &[crate::visible3d::DepthRow]) -> (u32, u32, Vec<u8>) {
    use testkit::scenes3d::Version;
    let names = [
        "scanvert Resolve::Crossing (cut + resolve + decode)",
        "z-buffer, i16 depth (Q12.4)",
        "z-buffer, i32 depth (Q12.4 + 14 bits)",
    ];
    let mut series = Vec::new();
    for r in rows {
        for (k, name) in names.iter().enumerate() {
            let layered = r.version == Version::Layered;
            push_point(&mut series, &names, name, layered, (r.complexity, r.ms[k]));
        }
    }
    render_series(
        &series,
        &Labels {
            title: "3D scenes of 170 faces: time against depth complexity",
            x: "depth complexity, measured (log scale)",
            y: MS_PER_FRAME,
            versions: true,
        },
    )
}

/// P3 (the sweep, no pixel written) and P4 (decode and pixel writes)
/// against trapezoids per frame, both log scales.
pub fn render_split(rows: &[crate::visible3d::SplitRow]) -> (u32, u32, Vec<u8>) {
    use testkit::scenes3d::Version;
    let names = [
        "P3: resolve into run-length rows (no pixel writes)",
        "P4: clear + decode stored rows (pixel writes)",
        "P3 + P4 fused (visible::draw), as measured",
    ];
    let mut series = Vec::new();
    for r in rows {
        let layered = r.version == Version::Layered;
        for (k, ms) in [r.p3_ms, r.p4_ms, r.both_ms].into_iter().enumerate() {
            push_point(&mut series, &names, names[k], layered, (r.trapezoids, ms));
        }
    }
    render_series(
        &series,
        &Labels {
            title: "P3 and P4 against trapezoids, 10 to 1000 faces",
            x: "trapezoids per frame (log scale)",
            y: MS_PER_FRAME,
            versions: true,
        },
    )
}

/// The worst cases: seconds against faces, one line an order, both log
/// scales.
pub fn render_worst(rows: &[crate::worst::WorstRow]) -> (u32, u32, Vec<u8>) {
    use crate::worst::ORDERS;
    let names: Vec<String> = ORDERS
        .iter()
        .map(|(_, n)| format!("staggered faces, {n}"))
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut series = Vec::new();
    for r in rows {
        push_point(
            &mut series,
            &refs,
            refs[r.order],
            true,
            (r.faces as f64, r.seconds),
        );
    }
    render_series(
        &series,
        &Labels {
            title: "Worst cases: a 1024x1024 frame of staggered faces, time against faces",
            x: "faces (log scale)",
            y: "seconds a frame, this host (log scale)",
            versions: false,
        },
    )
}
