//! The text form: text → binary → text → binary is stable, for scenes
//! written the way people write them (signs, leading zeros, needless
//! decimals, values that need rounding, comments, tabs, CRLF).

use proptest::prelude::*;
use scanvert::display_list::DisplayList;
use scanvert_sim::text::{assemble, disassemble};

/// A number in the text form whose value is within the coordinate range,
/// written in one of many ways.
fn number() -> impl Strategy<Value = String> {
    (
        -2048i32..2048,
        0u32..10_000,
        0usize..6,
        any::<bool>(),
        0usize..3,
    )
        .prop_map(|(int, frac, style, plus, zeros)| {
            let sign = if int < 0 {
                "-"
            } else if plus {
                "+"
            } else {
                ""
            };
            let (m, f) = (int.unsigned_abs(), frac);
            let lead = "0".repeat(zeros);
            match style {
                0 => format!("{sign}{lead}{m}"),
                1 => format!("{sign}{lead}{m}.{f:04}"),
                2 => format!("{sign}{lead}{m}.{f}"),
                3 => format!("{sign}{m}."),
                4 if m == 0 => format!("{sign}.{f}"),
                // A tie (k/32) or a long fraction.
                _ => format!("{sign}{m}.{:05}000000000{f}", (f % 32) * 3125),
            }
        })
        // Values that round up to 2048 are out of range: keep them out.
        .prop_filter("in range", |s| {
            let v: f64 = s.parse().unwrap_or(0.0);
            (-2048.03..2047.96).contains(&v)
        })
}

fn colour() -> impl Strategy<Value = String> {
    (any::<[u8; 3]>(), any::<bool>()).prop_map(|(c, upper)| {
        let s = format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
        if upper {
            s.to_uppercase()
        } else {
            s
        }
    })
}

/// A world value (Q16.16 range) or an angle in degrees, in many spellings.
fn world() -> impl Strategy<Value = String> {
    (-32767i32..32767, 0u64..100_000_000, 0usize..3).prop_map(|(int, frac, style)| {
        let sign = if int < 0 { "-" } else { "" };
        let m = int.unsigned_abs();
        match style {
            0 => format!("{sign}{m}"),
            1 => format!("{sign}{m}.{frac}"),
            _ => format!("{sign}{m}.{frac:08}5"),
        }
    })
}

fn command3d() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u32..65536).prop_map(|id| format!("segment {id}")),
        (world(), world(), world()).prop_map(|(a, n, f)| format!("perspective {a} {n} {f}")),
        (world(), world(), world()).prop_map(|(a, n, f)| format!("ortho {a} {n} {f}")),
        prop::collection::vec(world(), 5).prop_map(|v| format!("view {}", v.join(" "))),
        (prop::collection::vec(world(), 3), 0u8..=100)
            .prop_map(|(v, p)| format!("light {} {p}", v.join(" "))),
        (0u16..32768).prop_map(|t| format!("thickness {}", t as f64 / 16.0)),
        Just("push".to_string()),
        Just("pop".to_string()),
        prop::collection::vec(world(), 3).prop_map(|v| format!("translate {}", v.join(" "))),
        prop::collection::vec(world(), 3).prop_map(|v| format!("scale {}", v.join(" "))),
        (prop::sample::select(vec!["x", "y", "z"]), world())
            .prop_map(|(a, d)| format!("rotate {a} {d}")),
        prop::collection::vec(world(), 3..18).prop_map(|v| {
            let n = v.len() / 3 * 3;
            format!("face {}", v[..n].join(" "))
        }),
        (
            prop::collection::vec(world(), 3),
            "[a-zA-Z0-9.,:;!?()+-]{1,12}( [a-z]{1,5}){0,3}"
        )
            .prop_map(|(v, t)| format!("label {} {t}", v.join(" "))),
    ]
}

/// A segment with a mesh: `v`s, then `f`s of 1-based and negative
/// indices into them.
fn mesh() -> impl Strategy<Value = String> {
    (
        0u32..65536,
        prop::collection::vec(prop::collection::vec(world(), 3), 1..7),
        prop::collection::vec(prop::collection::vec(any::<(bool, u8)>(), 1..6), 0..5),
    )
        .prop_map(|(id, vs, fs)| {
            let n = vs.len() as i64;
            let mut s = format!("segment {id}");
            for v in &vs {
                s += &format!("\nv {}", v.join(" "));
            }
            for f in fs {
                s += "\nf";
                for (neg, k) in f {
                    let k = k as i64 % n;
                    let i = if neg { -(k + 1) } else { k + 1 };
                    s += &format!(" {i}");
                }
            }
            s
        })
}

fn command() -> impl Strategy<Value = String> {
    prop_oneof![
        colour().prop_map(|c| format!("clear {c}")),
        colour().prop_map(|c| format!("color\t{c} # a comment")),
        (any::<[i16; 4]>()).prop_map(|v| format!("clip {} {} {} {}", v[0], v[1], v[2], v[3])),
        prop::collection::vec((number(), number()), 3..9).prop_map(|v| {
            let mut s = String::from("poly");
            for (x, y) in v {
                s += &format!(" {x} {y}");
            }
            s
        }),
        prop::collection::vec((number(), number(), number()), 3..7).prop_map(|v| {
            let mut s = String::from("poly3 ");
            for (x, y, z) in v {
                s += &format!("  {x} {y} {z}");
            }
            s
        }),
        Just("# only a comment".to_string()),
        Just(String::new()),
        command3d(),
        command3d(),
        mesh(),
    ]
}

fn scene() -> impl Strategy<Value = String> {
    (
        1u16..=4096,
        1u16..=4096,
        prop::collection::vec(command(), 0..20),
        any::<bool>(),
    )
        .prop_map(|(w, h, cmds, crlf)| {
            let nl = if crlf { "\r\n" } else { "\n" };
            let mut s = format!("# scene{nl}frame {w} {h}{nl}");
            for c in cmds {
                s += &c;
                s += nl;
            }
            s
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn text_binary_text_binary_is_stable(text in scene()) {
        let b1 = assemble(&text).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?.bytes;
        let t1 = disassemble(&DisplayList::new_checked(&b1).unwrap());
        let b2 = assemble(&t1).map_err(|e| TestCaseError::fail(format!("{e}\n{t1}")))?.bytes;
        prop_assert_eq!(&b1, &b2);
        let t2 = disassemble(&DisplayList::new_checked(&b2).unwrap());
        prop_assert_eq!(t1, t2);
    }
}

#[test]
fn the_demo_scene_round_trips() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/demo.dl"))
        .expect("scenes/demo.dl");
    let b1 = assemble(&text).expect("demo assembles").bytes;
    let t1 = disassemble(&DisplayList::new_checked(&b1).unwrap());
    assert_eq!(assemble(&t1).expect("disassembly assembles").bytes, b1);
}

/// An angle is rounded once, from the exact decimal, to the nearest
/// 1/65536 of a turn (ties away from zero); rounding first to 1/65536 of a
/// degree would make `rotate x 0.00274` (0.4988 of a step) a whole step.
#[test]
fn angles_are_rounded_once() {
    let asm = assemble("frame 4 4\nrotate x 0.00274\nrotate y 0.0028\n").unwrap();
    let text = disassemble(&DisplayList::new_checked(&asm.bytes).unwrap());
    assert_eq!(text, "frame 4 4\nrotate x 0\nrotate y 0.005\n");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// `k / 10^6` degrees against the exact quotient `k · 65536 / (360 · 10^6)`.
    #[test]
    fn an_angle_is_its_nearest_step(k in -32_768_000_000i64..32_768_000_000) {
        let sign = if k < 0 { "-" } else { "" };
        let m = k.unsigned_abs();
        let text = format!("{sign}{}.{:06}", m / 1_000_000, m % 1_000_000);
        let got = scanvert_sim::text::parse_angle(&text).unwrap().to_bits();
        let (num, den) = (m as i128 * 65536, 360_000_000i128);
        let steps = (2 * num + den) / (2 * den); // half away from zero
        let steps = if k < 0 { -steps } else { steps };
        prop_assert_eq!(i128::from(got), steps.rem_euclid(65536), "{}", text);
    }
}
