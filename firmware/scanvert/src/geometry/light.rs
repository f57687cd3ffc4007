//! Lighting: one parallel light source and ambient light; faces are ideal
//! diffusers (Lambert).
//!
//! A [`Light`] is a direction toward the source and a percentage `p`; the
//! remaining `100 − p` percent is ambient. A face with unit normal `n̂` and
//! the unit direction `l̂` to the light has the intensity
//!
//! ```text
//! I = (100 − p)% + p% · max(0, n̂ · l̂)
//! ```
//!
//! and its colour's red, green and blue are each scaled by `I`: the colour
//! keeps its hue and saturation, the light sets only its intensity. A face
//! turned away from the light gets the ambient part alone, a face facing it
//! squarely gets the full colour. Points and lines are not lit.
//!
//! The normal is the face's from the culling stage, in view space, and the
//! light direction is turned into view space when the view is set, so
//! `n̂ · l̂` is the world's angle (rotations keep dot products).
//!
//! # Formats and widths
//!
//! | quantity | format | bound |
//! |---|---|---|
//! | light direction, stored | unit vector, Q16.16 per component | `≤ 2¹⁶` |
//! | normal, scaled by a power of two | `i32` per component | largest in `[2¹⁴, 2¹⁵]` |
//! | its squared length | `u32` | `≤ 3 · 2³⁰` |
//! | its length, `isqrt` | `u16` | `≥ 2¹⁴` |
//! | light direction in the product | Q14 (`>> 2`) | `≤ 2¹⁴` |
//! | `n · l` | `i32` | each product `< 2²⁹`; `≤ |n| · 2¹⁴` |
//! | `cos = 4 · n · l / |n|` | Q16.16 in `u32`, clamped to `[0, 1]` | one 32-bit division per face |
//! | intensity `((100 − p) · 2¹⁶ + p · cos) / 100` | Q16.16 | `≤ 2¹⁶` |
//! | channel `(c · I + 2¹⁵) >> 16` | `u8` | `≤ 255` |
//!
//! Scaling the normal to 15 bits before its square root costs nothing in
//! accuracy that matters: the cosine is within about 2⁻¹³ of the exact one,
//! far below one step of an 8-bit channel.

use super::trig::isqrt;
use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};

/// One parallel light source, plus ambient light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Light {
    direction: [i32; 3],
    percent: u8,
}

impl Default for Light {
    fn default() -> Self {
        Light::AMBIENT
    }
}

impl Light {
    /// No directed light: every face keeps its colour.
    pub const AMBIENT: Light = Light {
        direction: [0, 0, 1 << 16],
        percent: 0,
    };

    /// A light shining from direction `toward` (from the scene toward the
    /// source, in world coordinates, any length), providing `percent` of the
    /// illumination; the rest is ambient. `percent` above 100 counts as
    /// 100. [`ZeroDirection`] when `toward` is zero.
    pub fn new(toward: [i32; 3], percent: u8) -> Result<Light, ZeroDirection> {
        let direction =
            unit([toward[0] as i64, toward[1] as i64, toward[2] as i64]).ok_or(ZeroDirection)?;
        Ok(Light {
            direction,
            percent: percent.min(100),
        })
    }

    /// The unit direction toward the source, Q16.16 per component.
    pub const fn direction(&self) -> [i32; 3] {
        self.direction
    }

    /// The directed share of the light, 0 to 100.
    pub const fn percent(&self) -> u8 {
        self.percent
    }
}

/// A direction of length zero: a light's toward nothing, or a view whose
/// eye is its target. `?` carries it into a
/// [`SceneError`](crate::scene::SceneError).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ZeroDirection;

impl core::fmt::Display for ZeroDirection {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("a direction of length zero (a light toward nothing, or an eye at its target)")
    }
}

impl core::error::Error for ZeroDirection {}

/// `v` scaled by a power of two so that its largest component has 15
/// bits; `None` for the zero vector. Components are `i64` below 2⁶³.
#[inline]
pub(super) fn scale15(v: [i64; 3]) -> Option<[i32; 3]> {
    // The usual case, every component within `i32`: the same shifts in
    // 32 bits. The bitwise or of the magnitudes has the largest one's
    // leading bit.
    if let (Ok(x), Ok(y), Ok(z)) = (
        i32::try_from(v[0]),
        i32::try_from(v[1]),
        i32::try_from(v[2]),
    ) {
        let m = x.unsigned_abs() | y.unsigned_abs() | z.unsigned_abs();
        if m == 0 {
            return None;
        }
        let bits = 32 - m.leading_zeros();
        // |c| ≤ 2³¹ has at most `bits` bits: shifted right by `bits − 15`
        // it is within 2¹⁵, and shifted left by `15 − bits` too.
        let shift = |c: i32| {
            if bits > 15 {
                c >> (bits - 15)
            } else {
                c << (15 - bits)
            }
        };
        return Some([shift(x), shift(y), shift(z)]);
    }
    let m = v.iter().fold(0, |m, c| m | c.unsigned_abs());
    if m == 0 {
        return None;
    }
    let bits = 64 - m.leading_zeros();
    let mut out = [0i32; 3];
    for (o, &c) in out.iter_mut().zip(&v) {
        *o = if bits > 15 {
            (c >> (bits - 15)) as i32
        } else {
            (c << (15 - bits)) as i32
        };
    }
    Some(out)
}

/// The length of a vector from [`scale15`]: at least 2¹⁴.
#[inline]
pub(super) fn length15(s: [i32; 3]) -> u32 {
    let sq = s.iter().map(|&c| (c as i64 * c as i64) as u32).sum::<u32>();
    isqrt(sq) as u32
}

/// `v` as a unit vector in Q16.16, or `None` for zero.
pub(super) fn unit(v: [i64; 3]) -> Option<[i32; 3]> {
    let s = scale15(v)?;
    let len = length15(s) as i64;
    // |s| ≤ len, so each component is at most 2¹⁶.
    Some(s.map(|c| ((c as i64 * 65536 + len / 2).div_euclid(len)) as i32))
}

/// The colour of a face with view-space normal `n` (non-zero) under the
/// light from view-space unit direction `toward`, `percent` of it directed.
pub(super) fn shade(color: Rgb888, n: [i64; 3], toward: [i32; 3], percent: u8) -> Rgb888 {
    if percent == 0 {
        return color;
    }
    let Some(s) = scale15(n) else {
        return color;
    };
    // The light's direction in Q14: each product is below 2²⁹, and a
    // positive n · l is at most |n| · 2¹⁴ < 2²⁹·⁶, so four times it fits
    // u32 and one 32-bit division gives the cosine. A face turned away
    // from the light takes none of it, whatever its length: the length
    // and its square root are worked out only for the others.
    let dot: i32 = s.iter().zip(&toward).map(|(&a, &b)| a * (b >> 2)).sum();
    let cos = if dot <= 0 {
        0
    } else {
        ((dot as u32 * 4) / length15(s)).min(65536)
    };
    let p = percent as u32;
    // ≤ 100 · 2¹⁶ before the division.
    let i = ((100 - p) * 65536 + p * cos) / 100;
    let ch = |c: u8| ((c as u32 * i + 32768) >> 16) as u8;
    Rgb888::new(ch(color.r()), ch(color.g()), ch(color.b()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const GREY: Rgb888 = Rgb888::new(200, 100, 50);

    #[test]
    fn lambert_intensities() {
        let up = [0, 0, 65536];
        // Facing the light squarely: full colour.
        assert_eq!(shade(GREY, [0, 0, 7], up, 60), GREY);
        // Facing away: ambient only, 40 %.
        assert_eq!(shade(GREY, [0, 0, -7], up, 60), Rgb888::new(80, 40, 20));
        // Edge-on to the light: ambient only.
        assert_eq!(shade(GREY, [3, 0, 0], up, 60), Rgb888::new(80, 40, 20));
        // At 60°: cos = ½, intensity 40 % + 30 % = 70 %.
        let n = [0, 866_025, 500_000];
        assert_eq!(shade(GREY, n, up, 60), Rgb888::new(140, 70, 35));
        // No directed light: unchanged; all directed, facing away: black.
        assert_eq!(shade(GREY, [0, 0, -1], up, 0), GREY);
        assert_eq!(shade(GREY, [0, 0, -1], up, 100), Rgb888::new(0, 0, 0));
    }

    /// `scale15`'s 32-bit path gives what the 64-bit shifts give, for
    /// components within `i32` and past it.
    #[test]
    fn scale15_in_32_bits_is_the_64_bit_one() {
        fn wide(v: [i64; 3]) -> Option<[i32; 3]> {
            let m = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
            if m == 0 {
                return None;
            }
            let bits = 64 - m.leading_zeros();
            Some(v.map(|c| {
                if bits > 15 {
                    (c >> (bits - 15)) as i32
                } else {
                    (c << (15 - bits)) as i32
                }
            }))
        }
        let mut next = crate::rng::xorshift64(0x9e37_79b9_7f4a_7c15);
        let edges = [
            0,
            1,
            -1,
            i32::MAX as i64,
            i32::MIN as i64,
            i32::MAX as i64 + 1,
            i32::MIN as i64 - 1,
            1 << 14,
            (1 << 15) - 1,
            -(1 << 15),
        ];
        for _ in 0..200_000 {
            let mut pick = || {
                let r = next();
                match r % 3 {
                    0 => edges[(r >> 8) as usize % edges.len()],
                    1 => (r as i64) >> (r >> 58),
                    _ => (r as i64) >> (32 + (r >> 59) % 32),
                }
            };
            let v = [pick(), pick(), pick()];
            assert_eq!(scale15(v), wide(v), "{v:?}");
        }
    }

    #[test]
    fn units_and_limits() {
        assert_eq!(unit([0, 0, 5]), Some([0, 0, 65536]));
        assert_eq!(unit([-3, 4, 0]), Some([-39322, 52429, 0]));
        assert_eq!(unit([0, 0, 0]), None);
        assert_eq!(Light::new([0, 0, 0], 50), Err(ZeroDirection));
        assert_eq!(Light::new([1, 1, 1], 250).map(|l| l.percent()), Ok(100));
        let big = i64::MAX;
        let u = unit([big, -big, big]).unwrap();
        assert!(
            u.iter().all(|c| (37_830..=37_840).contains(&c.abs())),
            "{u:?}"
        );
        assert!(unit([1, 0, 0]) == Some([65536, 0, 0]));
        assert_eq!(shade(GREY, [big, -big, -big], [0, 0, 65536], 50).r(), 100);
        assert_eq!(scale15([i32::MIN as i64, 0, 0]), Some([-(1 << 14), 0, 0]));
        assert_eq!(scale15([1 - (1 << 16), 0, 0]), Some([-(1 << 15), 0, 0]));
    }
}
