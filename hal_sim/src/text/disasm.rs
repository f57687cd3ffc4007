//! Binary form → text form.

use super::asm::label_text_form;
use super::number::{parse_angle, parse_coord, parse_q16};
use scanvert::display_list::{Axis, Command, DisplayList, VERSION_2D};
use scanvert::fixed::Coord;
use scanvert::geometry::{Angle, Point3, Q16};
use scanvert::pixelcolor::{Rgb888, RgbColor};
use scanvert::scene::Placement;
use std::fmt::Write;

/// `raw · 2^−frac_bits` exactly, in the fewest decimals (`frac_bits` ≤ 16):
/// `k/2^f = k·5^f / 10^f`, so `f` decimals always suffice.
pub fn format_fixed(raw: i64, frac_bits: u32) -> String {
    let sign = if raw < 0 { "-" } else { "" };
    let m = raw.unsigned_abs();
    let (int, frac) = (m >> frac_bits, m & ((1 << frac_bits) - 1));
    if frac == 0 {
        return format!("{sign}{int}");
    }
    let digits = format!(
        "{:0width$}",
        frac * 5u64.pow(frac_bits),
        width = frac_bits as usize
    );
    format!("{sign}{int}.{}", digits.trim_end_matches('0'))
}

/// `c · 10^−decimals` as a decimal, without trailing zeros.
fn decimal(negative: bool, c: u128, decimals: u32) -> String {
    let sign = if negative { "-" } else { "" };
    let p = 10u128.pow(decimals);
    let (int, frac) = (c / p, c % p);
    if frac == 0 {
        return format!("{sign}{int}");
    }
    let digits = format!("{frac:0width$}", width = decimals as usize);
    format!("{sign}{int}.{}", digits.trim_end_matches('0'))
}

/// The shortest decimal that `reads_back` accepts for the value
/// `raw · 2^−frac_bits` (`frac_bits` ≤ 16, `raw` within ±2³⁸), as Rust
/// prints a float: the fewest decimals, and of two candidates with as few
/// the one nearer the value. With `d` decimals the candidates are the two
/// multiples of 10^−d around the value; with `frac_bits` decimals the value
/// itself is one, so the search ends there at the latest.
///
/// `reads_back` is the assembler's own parser compared with the bits, so
/// what is written assembles to the same bits by construction.
pub fn format_shortest(raw: i64, frac_bits: u32, reads_back: impl Fn(&str) -> bool) -> String {
    shortest(raw, frac_bits, |_, _| true, reads_back)
}

/// [`format_shortest`], a candidate `c · 10^−d` given to the parser only
/// when `may(c, 10^d)`, the parser's rounding computed on its magnitude,
/// says it reads back: one parse a value instead of one a candidate.
fn shortest(
    raw: i64,
    frac_bits: u32,
    may: impl Fn(u128, u128) -> bool,
    reads_back: impl Fn(&str) -> bool,
) -> String {
    if raw == 0 {
        return "0".to_string();
    }
    let negative = raw < 0;
    let m = u128::from(raw.unsigned_abs());
    let unit = 1u128 << frac_bits;
    for decimals in 0..frac_bits {
        // value · 10^d = lo + rem / 2^f.
        let p = 10u128.pow(decimals);
        let scaled = m * p;
        let (lo, rem) = (scaled >> frac_bits, scaled & (unit - 1));
        let candidates = if rem == 0 {
            [lo, lo]
        } else if 2 * rem <= unit {
            [lo, lo + 1]
        } else {
            [lo + 1, lo]
        };
        for c in candidates.into_iter().filter(|&c| c != 0) {
            if !may(c, p) {
                continue;
            }
            let s = decimal(negative, c, decimals);
            if reads_back(&s) {
                return s;
            }
        }
    }
    format_fixed(raw, frac_bits)
}

/// `n / d` rounded half up: the parser's rounding of a magnitude.
fn round_half_up(n: u128, d: u128) -> u128 {
    (2 * n + d) / (2 * d)
}

/// A coordinate in the fewest decimals that assemble to it: `12`, `-3.5`,
/// `100.06` (100.0625).
pub fn format_coord(c: Coord) -> String {
    let m = u128::from(c.units().unsigned_abs());
    shortest(
        c.units() as i64,
        4,
        |k, p| round_half_up(k << 4, p) == m,
        |s| parse_coord(s) == Ok(c),
    )
}

/// A world value (Q16.16) in the fewest decimals that assemble to it.
pub fn format_q16(q: Q16) -> String {
    let m = u128::from(q.to_bits().unsigned_abs());
    shortest(
        q.to_bits() as i64,
        16,
        |k, p| round_half_up(k << 16, p) == m,
        |s| parse_q16(s) == Ok(q),
    )
}

/// An angle in degrees, in the fewest decimals that assemble to it: its
/// exact value is `bits · 360/65536 = bits · 45 / 2¹³` (`perspective 50`
/// is stored as 49.998779296875° and written `50`).
pub fn format_angle(a: Angle) -> String {
    let bits = u128::from(a.to_bits());
    shortest(
        a.to_bits() as i64 * 45,
        13,
        // Degrees to 1/65536 turn: · 2¹³/45.
        |k, p| round_half_up(k << 13, 45 * p) == bits,
        |s| parse_angle(s) == Ok(a),
    )
}

fn point(p: Point3) -> String {
    format!(
        "{} {} {}",
        format_q16(p.x),
        format_q16(p.y),
        format_q16(p.z)
    )
}

fn hex(c: Rgb888) -> String {
    format!("#{:02x}{:02x}{:02x}", c.r(), c.g(), c.b())
}

/// The text form of a checked list: one command a line, each value in
/// the fewest decimals that assemble to the same bits.
pub fn disassemble(list: &DisplayList<'_>) -> String {
    let mut s = format!("frame {} {}\n", list.width(), list.height());
    // The header's version, where the commands alone would give a lower
    // one: without it the text would assemble to other bytes.
    let needed = list
        .commands()
        .map(|(_, c)| c.opcode().version())
        .max()
        .unwrap_or(VERSION_2D);
    if list.version() > needed {
        let _ = writeln!(s, "version {}", list.version());
    }
    for (_, cmd) in list.commands() {
        // The name from the format's table, then the operands. Writing
        // into a String cannot fail.
        s.push_str(cmd.opcode().name());
        let _ = match cmd {
            Command::Clear(c) | Command::Color(c) => write!(s, " {}", hex(c)),
            Command::Clip(w) => write!(s, " {} {} {} {}", w.x0, w.y0, w.x1, w.y1),
            Command::Poly(v) => {
                for p in v.iter() {
                    s.push(' ');
                    s.push_str(&format_coord(p.x));
                    s.push(' ');
                    s.push_str(&format_coord(p.y));
                }
                Ok(())
            }
            Command::Poly3(v) => {
                for p in v.iter() {
                    for c in [p.x, p.y, p.z] {
                        s.push(' ');
                        s.push_str(&format_coord(c));
                    }
                }
                Ok(())
            }
            Command::Line(a, b) => {
                for c in [a.x, a.y, b.x, b.y] {
                    s.push(' ');
                    s.push_str(&format_coord(c));
                }
                Ok(())
            }
            Command::Segment(id) => write!(s, " {id}"),
            Command::Perspective { fov, near, far } => write!(
                s,
                " {} {} {}",
                format_angle(fov),
                format_q16(near),
                format_q16(far)
            ),
            Command::Ortho { scale, near, far } => write!(
                s,
                " {} {} {}",
                format_q16(scale),
                format_q16(near),
                format_q16(far)
            ),
            Command::View { eye, yaw, pitch } => write!(
                s,
                " {} {} {}",
                point(eye),
                format_angle(yaw),
                format_angle(pitch)
            ),
            Command::Light { toward, percent } => write!(s, " {} {percent}", point(toward)),
            Command::Thickness(t) => write!(s, " {}", format_coord(t)),
            Command::Fill(rule) => write!(s, " {}", rule.name()),
            Command::Push | Command::Pop => Ok(()),
            Command::Translate(p) | Command::Scale(p) => write!(s, " {}", point(p)),
            Command::Rotate(axis, a) => {
                let axis = match axis {
                    Axis::X => "x",
                    Axis::Y => "y",
                    Axis::Z => "z",
                };
                write!(s, " {axis} {}", format_angle(a))
            }
            Command::Face(v) => {
                for p in v.iter() {
                    s.push(' ');
                    s.push_str(&point(p));
                }
                Ok(())
            }
            Command::Label { at, text } => {
                write!(s, " {} {}", point(at), label_text_form(text))
            }
            Command::MeshVertex(p) => write!(s, " {}", point(p)),
            // 1-based, as the text form counts.
            Command::MeshFace(ix) => {
                for i in ix.iter() {
                    let _ = write!(s, " {}", i as u32 + 1);
                }
                Ok(())
            }
            Command::Hide(id) | Command::Show(id) => write!(s, " {id}"),
            Command::Highlight(id, Some(c)) => write!(s, " {id} {}", hex(c)),
            Command::Highlight(id, None) => write!(s, " {id} off"),
            Command::Place(placed) => {
                let (id, p) = (placed.id(), placed.placement());
                let _ = write!(s, " {id} {}", point(p.translate));
                let turned = p.rotate != Placement::IDENTITY.rotate;
                let scaled = p.scale != Placement::IDENTITY.scale;
                if turned || scaled {
                    for a in p.rotate {
                        let _ = write!(s, " {}", format_angle(a));
                    }
                }
                if scaled {
                    let _ = write!(s, " {}", point(p.scale));
                }
                Ok(())
            }
            // A command added to the library after this disassembler: a
            // line that names it and that the assembler refuses, rather
            // than a silent gap.
            other => writeln!(s, "unsupported {other:?}"),
        };
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_coordinate_round_trips() {
        for u in i16::MIN..=i16::MAX {
            let c = Coord::from_bits(u);
            let t = format_coord(c);
            assert_eq!(parse_coord(&t), Ok(c), "{u} as {t}");
            // Never more than 2 decimals: 1/100 is finer than 1/16.
            assert!(t.split('.').nth(1).is_none_or(|f| f.len() <= 2), "{t}");
        }
        assert_eq!(format_coord(Coord::from_bits(-1)), "-0.06");
        assert_eq!(format_coord(Coord::from_bits(24)), "1.5");
        assert_eq!(format_coord(Coord::from_bits(2)), "0.1"); // 0.125
        assert_eq!(format_coord(Coord::from_bits(4)), "0.25");
        assert_eq!(format_coord(Coord::MIN), "-2048");
        assert_eq!(format_coord(Coord::MAX), "2047.94");
    }

    #[test]
    fn every_angle_and_q16_corners_round_trip() {
        for b in 0..=u16::MAX {
            let a = Angle::from_bits(b);
            let t = format_angle(a);
            assert_eq!(parse_angle(&t), Ok(a), "{b} as {t}");
            // 1/1000 of a degree is finer than 1/65536 of a turn.
            assert!(t.split('.').nth(1).is_none_or(|f| f.len() <= 3), "{t}");
        }
        for b in [
            i32::MIN,
            i32::MIN + 1,
            -65536,
            -1,
            0,
            1,
            3,
            65535,
            65536,
            i32::MAX,
        ] {
            let q = Q16::from_bits(b);
            assert_eq!(parse_q16(&format_q16(q)), Ok(q), "{b}");
        }
        assert_eq!(format_q16(Q16::from_bits(-98304)), "-1.5");
        assert_eq!(format_q16(Q16::from_bits(1)), "0.00002");
        assert_eq!(format_q16(Q16::from_bits(i32::MAX)), "32767.99998");
        assert_eq!(format_q16(Q16::from_bits(i32::MIN)), "-32768");
        assert_eq!(format_angle(Angle::from_bits(16384)), "90");
        assert_eq!(format_angle(parse_angle("50").unwrap()), "50");
        assert_eq!(format_angle(Angle::from_bits(1)), "0.005");
    }

    /// The parser's rounding computed on the magnitude lets the same
    /// candidates through as the parser itself.
    #[test]
    fn the_quick_check_agrees_with_the_parser() {
        for u in i16::MIN..=i16::MAX {
            let c = Coord::from_bits(u);
            let slow = format_shortest(u as i64, 4, |s| parse_coord(s) == Ok(c));
            assert_eq!(format_coord(c), slow, "{u}");
        }
        for b in 0..=u16::MAX {
            let a = Angle::from_bits(b);
            let slow = format_shortest(b as i64 * 45, 13, |s| parse_angle(s) == Ok(a));
            assert_eq!(format_angle(a), slow, "{b}");
        }
        for b in (i32::MIN..=i32::MAX)
            .step_by(40_009)
            .chain([i32::MAX, -1, 1])
        {
            let q = Q16::from_bits(b);
            let slow = format_shortest(b as i64, 16, |s| parse_q16(s) == Ok(q));
            assert_eq!(format_q16(q), slow, "{b}");
        }
    }

    #[test]
    fn of_two_as_short_the_nearer() {
        // 0.4375 reads back from 0.43 and 0.44; 0.44 is nearer.
        assert_eq!(format_coord(Coord::from_bits(7)), "0.44");
        // 0.375 reads back from 0.4, one decimal.
        assert_eq!(format_coord(Coord::from_bits(6)), "0.4");
    }
}
