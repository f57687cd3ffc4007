//! The fill rules against the exact winding-number reference
//! (`testkit::winding_reference`): self-intersecting polygons (stars,
//! figure-eights, polygons with repeated vertices, loops traversed twice,
//! two loops from one vertex) under random clip windows, drawn by both
//! rules through the whole frame's render and through the band path in
//! bands of 1, 7 and 16 rows; polygons that do not cross themselves
//! cover the same pixels by both rules; the `fill` command in the text
//! and binary forms, and its errors.

use embedded_graphics_core::pixelcolor::Rgb888;
use host_tests::harness::{vertex, CountingTarget};
use proptest::prelude::*;
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Error, ErrorKind, Opcode, Writer};
use scanvert::raster::clip::ClipRect;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::FillRule;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::cli::{render_scene, render_scene_bands_with, Scene};
use scanvert_sim::text::{assemble, disassemble, TextErrorKind};
use std::f64::consts::TAU;
use std::path::Path;
use testkit::reference::{Coverage, Window};
use testkit::winding_reference;

const W: u16 = 48;
const H: u16 = 40;
const RULES: [FillRule; 2] = [FillRule::EvenOdd, FillRule::NonZero];

/// A point in units of 1/16 px from pixels, rounded to the nearest unit.
fn unit(x: f64, y: f64) -> (i32, i32) {
    ((x * 16.0).round() as i32, (y * 16.0).round() as i32)
}

/// The `{n/q}` star polygon: `n` points on a circle, joined every `q`th.
fn star(n: u32, q: u32, c: (f64, f64), r: f64, phase: f64) -> Vec<(i32, i32)> {
    (0..n)
        .map(|k| {
            let t = phase + TAU * ((k * q) % n) as f64 / n as f64;
            unit(c.0 + r * t.cos(), c.1 + r * t.sin())
        })
        .collect()
}

/// A figure-eight (a lemniscate of Gerono) through `n` points: its two
/// lobes wind opposite ways.
fn figure_eight(n: u32, c: (f64, f64), r: (f64, f64)) -> Vec<(i32, i32)> {
    (0..n)
        .map(|k| {
            let t = TAU * k as f64 / n as f64;
            unit(c.0 + r.0 * t.cos(), c.1 + r.1 * t.sin() * t.cos())
        })
        .collect()
}

/// Random points inside the frame and a few pixels beyond.
fn points(n: std::ops::Range<usize>) -> impl Strategy<Value = Vec<(i32, i32)>> {
    prop::collection::vec(
        (-64i32..(W as i32 + 4) * 16, -64i32..(H as i32 + 4) * 16),
        n,
    )
}

/// Self-intersecting polygons of every kind the brief names, and plain
/// random ones.
fn tangled() -> impl Strategy<Value = Vec<(i32, i32)>> {
    let centre = (4.0..44.0f64, 4.0..36.0f64);
    prop_oneof![
        // Stars {5/2}, {7/2}, {7/3}, {8/3}, {9/4}.
        (
            prop_oneof![
                Just((5u32, 2u32)),
                Just((7, 2)),
                Just((7, 3)),
                Just((8, 3)),
                Just((9, 4))
            ],
            centre.clone(),
            3.0..30.0f64,
            0.0..TAU,
        )
            .prop_map(|((n, q), c, r, phase)| star(n, q, c, r, phase)),
        // Figure-eights, sideways or upright.
        (4u32..24, centre.clone(), -30.0..30.0f64, -30.0..30.0f64)
            .prop_map(|(n, c, rx, ry)| figure_eight(n, c, (rx, ry))),
        // A loop traversed two or three times (winding 2, 3).
        (points(3..7), 2usize..4).prop_map(|(p, k)| p.repeat(k)),
        // Two loops from one vertex, either way round each.
        (points(3..6), points(2..6), any::<bool>()).prop_map(|(a, mut b, flip)| {
            if flip {
                b.reverse();
            }
            let mut p = a.clone();
            p.push(a[0]);
            p.extend(b);
            p
        }),
        // Repeated vertices: some doubled in place, one visited again.
        (
            points(3..9),
            prop::collection::vec(any::<prop::sample::Index>(), 1..4)
        )
            .prop_map(|(mut p, picks)| {
                for ix in picks {
                    let k = ix.index(p.len());
                    let v = p[k];
                    p.insert(k, v);
                    let far = ix.index(p.len() + 1);
                    p.insert(far, v);
                }
                p
            }),
        points(3..14),
    ]
}

/// A clip window: mostly the whole frame, else random (empty, inverted
/// or past the frame too).
fn window() -> impl Strategy<Value = Window> {
    prop_oneof![
        Just(Window::full(W, H)),
        (-5i16..50, -5i16..45, -5i16..55, -5i16..45).prop_map(|(x0, y0, x1, y1)| Window {
            x0,
            y0,
            x1,
            y1
        }),
    ]
}

/// The list `clip`, `fill rule`, `poly` through the library's writer.
fn list_bytes(poly: &[(i32, i32)], rule: FillRule, win: Window) -> Vec<u8> {
    let mut buf = vec![0u8; 64 + 4 * poly.len()];
    let mut w = Writer::new(&mut buf, W, H).unwrap();
    w.clip(win.to_clip_window()).unwrap();
    w.fill(rule).unwrap();
    w.poly(poly.iter().copied().map(vertex)).unwrap();
    w.finish().to_vec()
}

/// A vertex coordinate in the text form: units of 1/16 are exact in
/// binary, so the shortest decimal is exact too.
fn text_coord(u: i32) -> String {
    format!("{}", u as f64 / 16.0)
}

/// The same list in the text form, on black, drawn in white.
fn list_text(poly: &[(i32, i32)], rule: FillRule, win: Window) -> String {
    let mut s = format!(
        "frame {W} {H}\nclear #000000\nclip {} {} {} {}\nfill {}\ncolor #ffffff\npoly",
        win.x0,
        win.y0,
        win.x1,
        win.y1,
        rule.name()
    );
    for &(x, y) in poly {
        s += &format!(" {} {}", text_coord(x), text_coord(y));
    }
    s + "\n"
}

/// The library's full-frame render of the list into a counting target:
/// the pixels written, checked written once each.
fn render_counting(bytes: &[u8]) -> Coverage {
    let list = DisplayList::new_checked(bytes).expect("writer output is valid");
    let mut edges = vec![Edge::EMPTY; 256];
    let mut target = CountingTarget::new(W, H);
    let stats = Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut target)
        .expect("render");
    let over = target.overdrawn();
    assert!(over.is_empty(), "pixels written twice: {over:?}");
    let written: u64 = target.spans.iter().map(|s| s.len() as u64).sum();
    assert_eq!(stats.pixels, written);
    target.coverage()
}

/// The non-black pixels of a simulator render.
fn lit(r: &scanvert_sim::cli::Rendered) -> Coverage {
    let px = r.ram.contents();
    Coverage::from_fn(W.into(), H.into(), |i, j| {
        px[(j * W as u32 + i) as usize] != Default::default()
    })
}

#[track_caller]
fn same(got: &Coverage, want: &Coverage, what: &str) {
    if got != want {
        let d = got.diff(want);
        panic!(
            "{what}: {} pixels differ (i, j, library's): {:?}\nlibrary: {got:?}reference: {want:?}",
            d.len(),
            &d[..d.len().min(12)]
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Every pixel of the full-frame render and of the band renders (1,
    /// 7 and 16 rows) is the reference's, for both rules.
    #[test]
    fn tangled_polygons_match_the_winding_reference(poly in tangled(), win in window()) {
        for rule in RULES {
            let want = winding_reference::rasterize(&poly, rule, win, W.into(), H.into());
            same(&render_counting(&list_bytes(&poly, rule, win)), &want, &format!("{rule:?} full frame"));
            let scene = Scene::from_bytes(
                Path::new("winding.dl"),
                list_text(&poly, rule, win).into_bytes(),
            )
            .expect("scene reads");
            same(&lit(&render_scene(&scene).unwrap()), &want, &format!("{rule:?} text, full"));
            for rows in [1u16, 7, 16] {
                let band = render_scene_bands_with(&scene, rows, Resolve::default()).unwrap();
                same(&lit(&band), &want, &format!("{rule:?} bands of {rows}"));
            }
        }
    }

    /// Polygons that do not cross themselves (convex, and star-shaped
    /// about a point: vertices in angle order, any radii), either way
    /// round: the non-zero rule covers the pixels the even-odd rule does.
    #[test]
    fn simple_polygons_cover_the_same_pixels_by_both_rules(
        c in (8.0..40.0f64, 8.0..32.0f64),
        radii in prop::collection::vec(1.0..24.0f64, 3..12),
        convex in any::<bool>(),
        reverse in any::<bool>(),
        phase in 0.0..TAU,
        win in window(),
    ) {
        let n = radii.len();
        let r0 = radii[0];
        let mut poly: Vec<(i32, i32)> = radii
            .iter()
            .enumerate()
            .map(|(k, &r)| {
                let r = if convex { r0 } else { r };
                let t = phase + TAU * k as f64 / n as f64;
                unit(c.0 + r * t.cos(), c.1 + r * t.sin())
            })
            .collect();
        if reverse {
            poly.reverse();
        }
        let even = render_counting(&list_bytes(&poly, FillRule::EvenOdd, win));
        let nonzero = render_counting(&list_bytes(&poly, FillRule::NonZero, win));
        same(&nonzero, &even, "non-zero against even-odd");
        let want = winding_reference::rasterize(&poly, FillRule::NonZero, win, W.into(), H.into());
        same(&nonzero, &want, "non-zero against the reference");
    }
}

/// Random lists of polygons in both rules and colours, under clip
/// windows: the band renders equal the full render.
#[test]
fn mixed_rules_in_one_list_are_the_same_in_bands() {
    let mut rng = testkit::rng::Rng(0xf111);
    for _ in 0..40 {
        let mut text = format!("frame {W} {H}\nclear #102030\n");
        for k in 0..rng.range(2, 8) {
            if rng.below(3) == 0 {
                let (x0, y0) = (rng.range(-3, 40), rng.range(-3, 30));
                text += &format!(
                    "clip {x0} {y0} {} {}\n",
                    x0 + rng.range(0, 50),
                    y0 + rng.range(0, 40)
                );
            }
            if rng.below(2) == 0 {
                text += &format!("fill {}\n", RULES[rng.below(2) as usize].name());
            }
            text += &format!("color #{:06x}\npoly", 0x40 + k * 0x1f2f3f);
            let c = (rng.range(4, 44) as f64, rng.range(4, 36) as f64);
            let p = star(7, 3, c, rng.range(4, 30) as f64, rng.range(0, 100) as f64);
            for (x, y) in p {
                text += &format!(" {} {}", text_coord(x), text_coord(y));
            }
            text += "\n";
        }
        let scene = Scene::from_bytes(Path::new("mixed.dl"), text.clone().into_bytes()).unwrap();
        let full = render_scene(&scene).unwrap();
        for rows in [1u16, 7, 16] {
            let band = render_scene_bands_with(&scene, rows, Resolve::default()).unwrap();
            assert!(
                full.ram.contents() == band.ram.contents(),
                "bands of {rows} differ:\n{text}"
            );
        }
    }
}

/// The rule is the state of the `poly`s after a `fill`, like `color`,
/// across `clear`s; a list starts with even-odd.
#[test]
fn fill_sets_the_rule_of_the_polys_after_it() {
    let star = "poly 16 1  24.8125 28.125  1.75 11.375  30.25 11.375  7.1875 28.125";
    // Pixels (16, 16), the middle, and (16, 5), on the top point.
    let lit = |text: &str| {
        let scene = Scene::from_bytes(Path::new("s.dl"), text.as_bytes().to_vec()).unwrap();
        let r = render_scene(&scene).unwrap();
        let at = |i: usize, j: usize| r.ram.contents()[j * 32 + i] != Default::default();
        (at(16, 16), at(16, 5))
    };
    let f = |body: &str| format!("frame 32 32\ncolor #ffffff\n{body}\n");
    assert_eq!(lit(&f(star)), (false, true));
    assert_eq!(lit(&f(&format!("fill nonzero\n{star}"))), (true, true));
    assert_eq!(
        lit(&f(&format!("fill nonzero\nclear #000000\n{star}"))),
        (true, true)
    );
    assert_eq!(
        lit(&f(&format!("fill nonzero\nfill evenodd\n{star}"))),
        (false, true)
    );
    // `fill` leaves `poly3` alone: the star as a `poly3`, counter-clockwise
    // as displayed, keeps the pixel rule's even-odd coverage.
    let star3 = "poly3 16 1 1  7.1875 28.125 1  30.25 11.375 1  1.75 11.375 1  24.8125 28.125 1";
    assert_eq!(lit(&f(star3)), (false, true));
    assert_eq!(lit(&f(&format!("fill nonzero\n{star3}"))), (false, true));
}

#[test]
fn fill_in_the_text_form_round_trips_and_bad_rules_name_their_line() {
    let text = "frame 8 8\nfill nonzero\npoly 0 0 8 0 4 7\nfill evenodd\npoly 0 0 8 0 4 7\n";
    let bytes = assemble(text).unwrap().bytes;
    let list = DisplayList::new_checked(&bytes).unwrap();
    assert_eq!(list.version(), 2);
    assert_eq!(disassemble(&list), text);
    // opcode 0x34, one byte: 1 non-zero.
    assert_eq!(&bytes[16..18], &[0x34, 1]);
    assert_eq!(Opcode::Fill as u8, 0x34);

    for (bad, line) in [
        ("frame 8 8\ncolor #ffffff\nfill foo\n", 3),
        ("frame 8 8\nfill\n", 2),
        ("frame 8 8\nfill nonzero evenodd\n", 2),
        ("frame 8 8\nfill NonZero\n", 2),
    ] {
        let e = assemble(bad).unwrap_err();
        assert_eq!(e.line, line, "{bad:?}: {e}");
    }
    let e = assemble("frame 8 8\n\nfill foo\n").unwrap_err();
    assert_eq!(e.kind, TextErrorKind::FillRule("foo".into()));
    assert!(e.to_string().contains("foo"), "{e}");
}

#[test]
fn a_bad_fill_operand_is_a_typed_error_at_its_byte() {
    let mut buf = [0u8; 64];
    let mut w = Writer::new(&mut buf, 8, 8).unwrap();
    w.color(Rgb888::new(1, 2, 3)).unwrap();
    w.fill(FillRule::NonZero).unwrap();
    let mut bytes = w.finish().to_vec();
    let at = 16 + 4;
    assert_eq!(bytes[at], 0x34);
    for b in [2u8, 0x80, 0xff] {
        bytes[at + 1] = b;
        assert_eq!(
            DisplayList::new_checked(&bytes).unwrap_err(),
            Error {
                offset: at,
                kind: ErrorKind::BadOperand(Opcode::Fill)
            }
        );
    }
    // Cut after the opcode: truncated, at the command.
    let short = {
        let mut s = bytes[..at + 1].to_vec();
        s[12..16].copy_from_slice(&((at + 1 - 16) as u32).to_le_bytes());
        s
    };
    assert_eq!(
        DisplayList::new_checked(&short).unwrap_err(),
        Error {
            offset: at,
            kind: ErrorKind::Truncated
        }
    );
    // A version-1 list may not hold it.
    let mut v1 = bytes.clone();
    v1[at + 1] = 0;
    v1[4] = 1;
    assert_eq!(
        DisplayList::new_checked(&v1).unwrap_err().kind,
        ErrorKind::UnknownOpcode(0x34)
    );
}

/// The rasteriser's own entry point, with every stepper: `fill_with`
/// by each rule is the reference's on a star under a clip.
#[test]
fn fill_with_by_each_rule_is_the_references() {
    let poly = star(7, 3, (24.0, 20.0), 18.0, 0.3);
    let win = Window {
        x0: 3,
        y0: 5,
        x1: 40,
        y1: 33,
    };
    let clip = ClipRect::from_window(win.to_clip_window(), W, H);
    for rule in RULES {
        let mut slots = [Edge::EMPTY; 8];
        let mut target = CountingTarget::new(W, H);
        Rasterizer::new(&mut slots)
            .fill_with(
                rule,
                poly.iter().copied().map(vertex),
                &clip,
                embedded_graphics_core::pixelcolor::BinaryColor::On,
                &mut target,
            )
            .unwrap();
        let want = winding_reference::rasterize(&poly, rule, win, W.into(), H.into());
        same(&target.coverage(), &want, &format!("{rule:?}"));
        assert!(target.overdrawn().is_empty());
    }
    // The two rules differ here: the star's middle winds three times.
    let (e, n) = (
        winding_reference::rasterize(&poly, FillRule::EvenOdd, win, W.into(), H.into()),
        winding_reference::rasterize(&poly, FillRule::NonZero, win, W.into(), H.into()),
    );
    assert!(n.count() > e.count());
}
