//! Binary form → text form.

use super::asm::label_text_form;
use scanvert::display_list::{Axis, Command, DisplayList, VERSION_2D};
use scanvert::fixed::Coord;
use scanvert::geometry::{Angle, Point3, Q16};
use scanvert::pixelcolor::{Rgb888, RgbColor};
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

/// A coordinate exactly, in the fewest decimals: `12`, `-3.5`, `100.0625`.
pub fn format_coord(c: Coord) -> String {
    format_fixed(c.units() as i64, 4)
}

/// A world value (Q16.16) exactly.
pub fn format_q16(q: Q16) -> String {
    format_fixed(q.to_bits() as i64, 16)
}

/// An angle in degrees, exactly: `bits · 360/65536 = bits · 45 / 2¹³`.
pub fn format_angle(a: Angle) -> String {
    format_fixed(a.to_bits() as i64 * 45, 13)
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

/// The text form of a checked list: one command a line, values exact.
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
    use crate::text::{parse_angle, parse_coord, parse_q16};

    #[test]
    fn every_coordinate_round_trips() {
        for u in i16::MIN..=i16::MAX {
            let c = Coord::from_bits(u);
            let t = format_coord(c);
            assert_eq!(parse_coord(&t), Ok(c), "{u} as {t}");
        }
        assert_eq!(format_coord(Coord::from_bits(-1)), "-0.0625");
        assert_eq!(format_coord(Coord::from_bits(24)), "1.5");
        assert_eq!(format_coord(Coord::MIN), "-2048");
        assert_eq!(format_coord(Coord::MAX), "2047.9375");
    }

    #[test]
    fn every_angle_and_q16_corners_round_trip() {
        for b in 0..=u16::MAX {
            let a = Angle::from_bits(b);
            assert_eq!(parse_angle(&format_angle(a)), Ok(a), "{b}");
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
        assert_eq!(format_angle(Angle::from_bits(16384)), "90");
    }
}
