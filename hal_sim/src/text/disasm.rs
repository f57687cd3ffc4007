//! Binary form → text form.

use scanvert::display_list::{Command, DisplayList};
use scanvert::fixed::Coord;
use scanvert::pixelcolor::{Rgb888, RgbColor};
use std::fmt::Write;

/// A coordinate exactly, in the fewest decimals: `12`, `-3.5`, `100.0625`.
pub fn format_coord(c: Coord) -> String {
    let u = c.units();
    let (sign, m) = if u < 0 { ("-", -u) } else { ("", u) };
    let (int, frac) = (m / 16, m % 16);
    if frac == 0 {
        return format!("{sign}{int}");
    }
    // frac/16 = frac · 625 / 10000: four decimals, trailing zeros dropped.
    let digits = format!("{:04}", frac * 625);
    format!("{sign}{int}.{}", digits.trim_end_matches('0'))
}

fn hex(c: Rgb888) -> String {
    format!("#{:02x}{:02x}{:02x}", c.r(), c.g(), c.b())
}

/// The text form of a checked list: one command a line, values exact.
pub fn disassemble(list: &DisplayList<'_>) -> String {
    let mut s = format!("frame {} {}\n", list.width(), list.height());
    for (_, cmd) in list.commands() {
        // Writing into a String cannot fail.
        let _ = match cmd {
            Command::Clear(c) => writeln!(s, "clear {}", hex(c)),
            Command::Color(c) => writeln!(s, "color {}", hex(c)),
            Command::Clip(w) => writeln!(s, "clip {} {} {} {}", w.x0, w.y0, w.x1, w.y1),
            Command::Poly(v) => {
                s.push_str("poly");
                for p in v.iter() {
                    s.push(' ');
                    s.push_str(&format_coord(p.x));
                    s.push(' ');
                    s.push_str(&format_coord(p.y));
                }
                writeln!(s)
            }
            Command::Poly3(v) => {
                s.push_str("poly3");
                for p in v.iter() {
                    for c in [p.x, p.y, p.z] {
                        s.push(' ');
                        s.push_str(&format_coord(c));
                    }
                }
                writeln!(s)
            }
        };
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::text::parse_coord;

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
}
