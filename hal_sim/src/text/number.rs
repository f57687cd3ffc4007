//! Numbers of the text form, converted exactly from their digits.
//!
//! Grammar: an optional sign, then digits with an optional fraction
//! (`12`, `-3.5`, `.5`, `5.`). There is no exponent, `nan` or `inf`.
//! A coordinate is rounded to the nearest 1/16 (ties away from zero) from
//! the exact decimal value, however many digits it has: the fraction is
//! multiplied by 16 digit by digit, so no digit is lost and nothing
//! overflows.

use scanvert::fixed::Coord;
use scanvert::geometry::{Angle, Q16};
use std::fmt;

/// Why a word is not an acceptable number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NumberError {
    /// Not a decimal number of the text form.
    Syntax,
    /// A number where an integer is needed.
    NotInteger,
    /// Outside the range the operand takes (inclusive bounds, as text).
    Range(&'static str),
}

impl fmt::Display for NumberError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumberError::Syntax => {
                f.write_str("not a decimal number (digits, an optional sign and fraction)")
            }
            NumberError::NotInteger => f.write_str("must be a whole number"),
            NumberError::Range(r) => write!(f, "out of range {r}"),
        }
    }
}

/// A decimal split into its parts; digits are ASCII digits only.
struct Decimal<'a> {
    negative: bool,
    int: &'a [u8],
    frac: &'a [u8],
}

fn split(word: &str) -> Result<Decimal<'_>, NumberError> {
    let b = word.as_bytes();
    let (negative, rest) = match b.first() {
        Some(b'-') => (true, &b[1..]),
        Some(b'+') => (false, &b[1..]),
        _ => (false, b),
    };
    let (int, frac) = match rest.iter().position(|&c| c == b'.') {
        Some(p) => (&rest[..p], &rest[p + 1..]),
        None => (rest, &rest[rest.len()..]),
    };
    let digits = |s: &[u8]| s.iter().all(u8::is_ascii_digit);
    if (int.is_empty() && frac.is_empty()) || !digits(int) || !digits(frac) {
        return Err(NumberError::Syntax);
    }
    Ok(Decimal {
        negative,
        int,
        frac,
    })
}

/// The integer part's value, or `None` when it exceeds `limit`.
fn int_value(int: &[u8], limit: i64) -> Option<i64> {
    let mut v: i64 = 0;
    for &d in int {
        v = v * 10 + (d - b'0') as i64;
        if v > limit {
            return None;
        }
    }
    Some(v)
}

/// The decimal fraction `0.frac` (its digits) times 2^`frac_bits`
/// (`frac_bits` ≤ 16), as `q + rest` with `rest` in [0, 1): returns `q`
/// and whether `rest` ≥ 1/2. The digit string is multiplied from its last
/// digit (9·2¹⁶ + 2¹⁶ fits `u32`), so no digit is lost.
fn scale_fraction(frac: &[u8], frac_bits: u32) -> (u32, bool) {
    let mut rest: Vec<u8> = frac.iter().map(|c| c - b'0').collect();
    let mut carry = 0u32;
    for digit in rest.iter_mut().rev() {
        let v = ((*digit as u32) << frac_bits) + carry;
        *digit = (v % 10) as u8;
        carry = v / 10;
    }
    (carry, rest.first().is_some_and(|&first| first >= 5))
}

/// The exact decimal `word` rounded to the nearest multiple of
/// 2^−`frac_bits` (ties away from zero), as a count of those steps, which
/// must lie in `lo..=hi`. `frac_bits` is at most 16.
pub fn parse_fixed(
    word: &str,
    frac_bits: u32,
    lo: i64,
    hi: i64,
    range: &'static str,
) -> Result<i64, NumberError> {
    let d = split(word)?;
    let limit = (lo.unsigned_abs().max(hi.unsigned_abs()) >> frac_bits) as i64 + 1;
    let int = int_value(d.int, limit).ok_or(NumberError::Range(range))?;
    let (carry, half_or_more) = scale_fraction(d.frac, frac_bits);
    // Round half up on the magnitude, which is ties away from zero.
    let magnitude = (int << frac_bits) + carry as i64 + half_or_more as i64;
    let v = if d.negative { -magnitude } else { magnitude };
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(NumberError::Range(range))
    }
}

/// A screen coordinate (Q12.4): rounded to the nearest 1/16, ties away
/// from zero, and then required to lie in −2048 … +2047.9375.
pub fn parse_coord(word: &str) -> Result<Coord, NumberError> {
    parse_fixed(
        word,
        4,
        i16::MIN as i64,
        i16::MAX as i64,
        "-2048 … 2047.9375",
    )
    .map(|v| Coord::from_bits(v as i16))
}

/// A world value (Q16.16): rounded to the nearest 1/65536, ties away from
/// zero, in −32768 … 32767.99998.
pub fn parse_q16(word: &str) -> Result<Q16, NumberError> {
    parse_fixed(
        word,
        16,
        i32::MIN as i64,
        i32::MAX as i64,
        "-32768 … 32767.99998",
    )
    .map(|v| Q16::from_bits(v as i32))
}

/// An angle in degrees (any value in ±32768, wrapping at a turn), rounded
/// once, from the exact decimal, to the nearest 1/65536 of a turn (ties
/// away from zero).
pub fn parse_angle(word: &str) -> Result<Angle, NumberError> {
    // The range (and the syntax) is that of a world value.
    parse_fixed(
        word,
        16,
        i32::MIN as i64,
        i32::MAX as i64,
        "-32768 … 32767 degrees",
    )?;
    let d = split(word)?;
    let int = int_value(d.int, 1 << 16).ok_or(NumberError::Range("-32768 … 32767 degrees"))?;
    // Turns = degrees · 65536/360 = degrees · 2¹³/45. The magnitude times
    // 2¹³ is `n + rest`, rest in [0, 1); its quotient by 45 is `n / 45`
    // and a fraction `(n % 45 + rest) / 45`, which is at least 1/2 when
    // `n % 45 + rest` ≥ 22.5.
    let (carry, half_or_more) = scale_fraction(d.frac, 13);
    let n = (int << 13) + carry as i64;
    let (q, r) = (n / 45, n % 45);
    let magnitude = q + (r > 22 || (r == 22 && half_or_more)) as i64;
    let turns = if d.negative { -magnitude } else { magnitude };
    Ok(Angle::from_bits(turns.rem_euclid(65536) as u16))
}

/// A whole number in `lo..=hi`. A fraction of zeros (`64.0`) is whole.
pub fn parse_int(word: &str, lo: i64, hi: i64, range: &'static str) -> Result<i64, NumberError> {
    let d = split(word)?;
    if d.frac.iter().any(|&c| c != b'0') {
        return Err(NumberError::NotInteger);
    }
    let limit = lo.unsigned_abs().max(hi.unsigned_abs()) as i64;
    let v = int_value(d.int, limit).ok_or(NumberError::Range(range))?;
    let v = if d.negative { -v } else { v };
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(NumberError::Range(range))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn units(w: &str) -> i16 {
        parse_coord(w).unwrap().to_bits()
    }

    #[test]
    fn exact_values_and_rounding() {
        assert_eq!(units("12"), 192);
        assert_eq!(units("-3.5"), -56);
        assert_eq!(units("100.0625"), 1601);
        assert_eq!(units(".5"), 8);
        assert_eq!(units("5."), 80);
        assert_eq!(units("+1"), 16);
        assert_eq!(units("-0"), 0);
        // 1/32 is a tie: away from zero.
        assert_eq!(units("0.03125"), 1);
        assert_eq!(units("-0.03125"), -1);
        assert_eq!(units("0.03124999999999999999999999"), 0);
        assert_eq!(units("0.03125000000000000000000001"), 1);
        assert_eq!(units("277.688"), 4443); // 277.6875
        assert_eq!(units("2047.9375"), i16::MAX);
        assert_eq!(units("-2048"), i16::MIN);
        // 2047 + 31/32 is a tie that rounds away from zero, to 2048.
        assert!(parse_coord("2047.96875").is_err());
    }

    #[test]
    fn range_is_checked_after_rounding() {
        assert_eq!(units("2047.96874"), i16::MAX);
        assert!(parse_coord("2047.97").is_err());
        assert!(parse_coord("2048").is_err());
        assert!(parse_coord("-2048.0625").is_err());
        assert_eq!(units("-2048.03"), i16::MIN);
        assert!(parse_coord("-2048.04").is_err());
        assert!(parse_coord("123456789012345678901234567890").is_err());
    }

    #[test]
    fn syntax() {
        for bad in [
            "", "-", "+", ".", "-.", "--1", "1x", "nan", "NaN", "inf", "-inf", "1e5", "0x10",
            "1.2.3", "١",
        ] {
            assert_eq!(parse_coord(bad), Err(NumberError::Syntax), "{bad:?}");
        }
    }

    #[test]
    fn world_values_and_angles() {
        assert_eq!(parse_q16("1.5").unwrap().to_bits(), 98304);
        assert_eq!(parse_q16("-32768").unwrap().to_bits(), i32::MIN);
        assert!(parse_q16("32768").is_err());
        assert_eq!(parse_q16("0.0000076293945").unwrap().to_bits(), 0); // 1/131072 - ε
        assert_eq!(parse_q16("0.00000762939453125").unwrap().to_bits(), 1); // a tie
        assert_eq!(parse_angle("90").unwrap().to_bits(), 16384);
        assert_eq!(parse_angle("-90").unwrap().to_bits(), 49152);
        assert_eq!(parse_angle("360").unwrap().to_bits(), 0);
        assert_eq!(parse_angle("720.0054931640625").unwrap().to_bits(), 1);
        // Rounded once, from the decimal: 0.00274° is 0.4988 of a step.
        // (Rounded first to 1/65536°, it was 0.5 of a step, and went up.)
        assert_eq!(parse_angle("0.00274").unwrap().to_bits(), 0);
        assert_eq!(parse_angle("-0.00274").unwrap().to_bits(), 0);
        // Half a step, 45/16384 = 0.00274658203125°, is a tie: away from zero.
        assert_eq!(parse_angle("0.00274658203125").unwrap().to_bits(), 1);
        assert_eq!(parse_angle("-0.00274658203125").unwrap().to_bits(), 65535);
        assert_eq!(parse_angle("0.00274658203124999").unwrap().to_bits(), 0);
        // 32768° is 5965232.35 steps, 1456 past whole turns.
        assert_eq!(parse_angle("-32768").unwrap().to_bits(), 64080); // -1456
        assert!(parse_angle("32768").is_err());
    }

    #[test]
    fn integers() {
        let r = "1 … 4096";
        assert_eq!(parse_int("64", 1, 4096, r), Ok(64));
        assert_eq!(parse_int("64.000", 1, 4096, r), Ok(64));
        assert_eq!(parse_int("64.5", 1, 4096, r), Err(NumberError::NotInteger));
        assert_eq!(parse_int("0", 1, 4096, r), Err(NumberError::Range(r)));
        assert_eq!(parse_int("-64", 1, 4096, r), Err(NumberError::Range(r)));
        assert_eq!(
            parse_int("99999999999999999999999", 1, 4096, r),
            Err(NumberError::Range(r))
        );
        assert_eq!(parse_int("-32768", -32768, 32767, r), Ok(-32768));
    }
}
