//! `disasm` writes each value as the shortest decimal that assembles to
//! the same bits, as Rust prints a float: `perspective 50` comes back as
//! `50`, not as the 49.998779296875° it is stored as. Every encoding
//! (Q12.4 coordinates, Q16.16 world values, angles in 1/65536 turn) goes
//! binary → text → binary to the same bytes, and no decimal with fewer
//! digits would have.

use proptest::prelude::*;
use scanvert::display_list::{Axis, DisplayList, Writer};
use scanvert::fixed::{Coord, Vertex};
use scanvert::geometry::{Angle, Point3, Q16};
use scanvert_sim::text::{
    assemble, disassemble, format_angle, format_coord, format_q16, parse_angle, parse_coord,
    parse_q16,
};

/// The text of a list built by `build`, and its bytes assembled again.
fn through_text(build: impl FnOnce(&mut Writer<'_>)) -> (Vec<u8>, String, Vec<u8>) {
    let mut buf = vec![0u8; 1024];
    let mut w = Writer::new(&mut buf, 64, 64).expect("header");
    build(&mut w);
    let bytes = w.finish().to_vec();
    let text = disassemble(&DisplayList::new_checked(&bytes).expect("valid"));
    let again = assemble(&text)
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .bytes;
    (bytes, text, again)
}

/// The decimals of `t` after the point.
fn decimals(t: &str) -> usize {
    t.split_once('.').map_or(0, |(_, f)| f.len())
}

/// No decimal with fewer digits than `t` reads back as `t` does: the
/// multiples of 10^−d around `value` are the only candidates with `d`
/// decimals (what reads back to one value is an interval around it), and
/// a few more on either side are tried too.
fn nothing_shorter(t: &str, value: f64, reads_back: impl Fn(&str) -> bool) -> bool {
    (0..decimals(t)).all(|d| {
        let p = 10f64.powi(d as i32);
        let c = (value * p).floor() as i64;
        (c - 2..=c + 2).all(|k| {
            let (sign, m, p) = (if k < 0 { "-" } else { "" }, k.unsigned_abs(), p as u64);
            let s = if d == 0 {
                format!("{sign}{m}")
            } else {
                format!("{sign}{}.{:0d$}", m / p, m % p)
            };
            !reads_back(&s)
        })
    })
}

#[test]
fn perspective_50_comes_back_as_50() {
    let asm = assemble("frame 64 48\nperspective 50 0.1 100\nrotate y 30\nview 0 2 10 -20 12.5\n")
        .expect("assembles");
    let text = disassemble(&DisplayList::new_checked(&asm.bytes).unwrap());
    assert_eq!(
        text,
        "frame 64 48\nperspective 50 0.1 100\nrotate y 30\nview 0 2 10 340 12.5\n"
    );
    assert_eq!(assemble(&text).unwrap().bytes, asm.bytes);
}

#[test]
fn disasm_then_asm_through_the_program_keeps_the_bytes() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("disasm_shortest");
    std::fs::create_dir_all(&dir).unwrap();
    let (scene, bin, txt, again) = (
        dir.join("scene.dl"),
        dir.join("list.scvl"),
        dir.join("list.dl"),
        dir.join("again.scvl"),
    );
    std::fs::write(
        &scene,
        "frame 64 48\nperspective 50 0.1 100\nthickness 0.0625\nlight 1 3 2 70\n\
         face 0.1 0.2 0.3 1 0 0 0 1 0\npoly 0.0625 0 10 0 5 7.3\n",
    )
    .unwrap();
    let run = |args: &[&std::path::Path]| {
        let args: Vec<String> = args
            .iter()
            .map(|a| a.to_str().unwrap().to_string())
            .collect();
        scanvert_sim::cli::run(&args).expect("runs")
    };
    let p = std::path::Path::new;
    run(&[p("asm"), &scene, p("--out"), &bin]);
    run(&[p("disasm"), &bin, p("--out"), &txt]);
    run(&[p("asm"), &txt, p("--out"), &again]);
    assert_eq!(std::fs::read(&again).unwrap(), std::fs::read(&bin).unwrap());
    assert_eq!(
        std::fs::read_to_string(&txt).unwrap(),
        "frame 64 48\nperspective 50 0.1 100\nthickness 0.06\nlight 1 3 2 70\n\
         face 0.1 0.2 0.3 1 0 0 0 1 0\npoly 0.06 0 10 0 5 7.3\n"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Q12.4, in `poly`, `poly3`, `line` and `thickness`.
    #[test]
    fn coordinates_are_shortest_and_exact(u in prop::array::uniform4(any::<i16>())) {
        let c = u.map(Coord::from_bits);
        let (bytes, text, again) = through_text(|w| {
            let v = |x, y| Vertex { x, y };
            w.poly([v(c[0], c[1]), v(c[2], c[3]), v(c[1], c[0])]).unwrap();
            w.line(v(c[0], c[1]), v(c[2], c[3])).unwrap();
            w.thickness(Coord::from_bits(u[0].unsigned_abs().min(i16::MAX as u16) as i16)).unwrap();
        });
        prop_assert_eq!(&again, &bytes, "{}", text);
        for c in c {
            let t = format_coord(c);
            prop_assert!(decimals(&t) <= 2, "{}", t);
            prop_assert!(nothing_shorter(&t, c.units() as f64 / 16.0, |s| parse_coord(s) == Ok(c)), "{}", t);
        }
    }

    /// Q16.16, in points (`translate`, `scale`, `face`, `light`) and
    /// `ortho`.
    #[test]
    fn world_values_are_shortest_and_exact(b in prop::array::uniform3(any::<i32>())) {
        let q = b.map(Q16::from_bits);
        let (bytes, text, again) = through_text(|w| {
            let p = Point3::new(q[0], q[1], q[2]);
            w.translate(p).unwrap();
            w.scale(p).unwrap();
            w.face([p, p, p]).unwrap();
            w.ortho(q[0], q[1], q[2]).unwrap();
        });
        prop_assert_eq!(&again, &bytes, "{}", text);
        for q in q {
            let t = format_q16(q);
            prop_assert!(decimals(&t) <= 5, "{}", t);
            prop_assert!(nothing_shorter(&t, q.to_bits() as f64 / 65536.0, |s| parse_q16(s) == Ok(q)), "{}", t);
        }
    }

    /// Angles, in `rotate`, `perspective` and `view`.
    #[test]
    fn angles_are_shortest_and_exact(b in prop::array::uniform3(any::<u16>())) {
        let a = b.map(Angle::from_bits);
        let (bytes, text, again) = through_text(|w| {
            w.rotate(Axis::Z, a[0]).unwrap();
            w.perspective(a[1], Q16::from_bits(65536), Q16::from_bits(1 << 20)).unwrap();
            w.view(Point3::new(Q16::ZERO, Q16::ZERO, Q16::ZERO), a[1], a[2]).unwrap();
        });
        prop_assert_eq!(&again, &bytes, "{}", text);
        for a in a {
            let t = format_angle(a);
            prop_assert!(decimals(&t) <= 3, "{}", t);
            prop_assert!(nothing_shorter(&t, a.to_bits() as f64 * 360.0 / 65536.0, |s| parse_angle(s) == Ok(a)), "{}", t);
        }
    }

    /// A decimal with up to 3 decimals that an angle is written as reads
    /// back as the angle: writing is the inverse of reading on what it
    /// writes.
    #[test]
    fn short_angles_come_back_as_written(d in 0u32..360_000) {
        let text = format!("{}.{:03}", d / 1000, d % 1000);
        let a = parse_angle(&text).unwrap();
        let back = format_angle(a);
        prop_assert_eq!(parse_angle(&back), Ok(a));
        prop_assert!(back.len() <= text.trim_end_matches('0').trim_end_matches('.').len(), "{} {}", text, back);
    }
}
