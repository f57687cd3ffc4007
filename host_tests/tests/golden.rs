//! Golden images: small scenes in the text form, rendered through the
//! simulated hardware (display list → graphic controller → dual-port RAM
//! → refresh read-out → PNG) and compared exactly, pixel for pixel, with
//! the PNGs in `host_tests/golden/`.
//!
//! To regenerate the images after an intended change, run
//! `UPDATE_GOLDEN=1 cargo test -p host-tests --test golden` and look at
//! every changed PNG before committing it.
//!
//! The scenes are assembled by [`assemble`] below, a minimal reader of the
//! text form's commands used here (`frame`, `clear`, `clip`, `color`,
//! `fill`, `poly`), which accepts only exact multiples of 1/16.

use embedded_graphics_core::pixelcolor::Rgb888;
use scanvert::controller::Controller;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::raster::clip::ClipWindow;
use scanvert::raster::edge::Edge;
use scanvert::raster::scan::Rasterizer;
use scanvert::raster::FillRule;
use scanvert_sim::dual_port::DualPortRam;
use scanvert_sim::image;
use scanvert_sim::refresh::RefreshController;
use scanvert_sim::timing::VideoTiming;
use std::path::PathBuf;

/// Painter's order: later triangles cover earlier ones.
const OVERLAP: &str = "
frame 48 32
clear #102040
color #ff0000
poly 2 2  30 4  8 28
color #00ff00
poly 14 6  46 10  24 30.5
color #ffff00
poly 20 1  28 1  28 31  20 31
";

/// A self-intersecting pentagram: the even-odd rule leaves the centre
/// pentagon empty.
const PENTAGRAM: &str = "
frame 32 32
clear #000000
color #ffffff
poly 16 1  24.8125 28.125  1.75 11.375  30.25 11.375  7.1875 28.125
";

/// The same star drawn by each fill rule: even-odd leaves its middle
/// empty, non-zero fills it (the middle winds twice).
const STAR_FILL_RULES: &str = "
frame 64 32
clear #000000
color #ffffff
poly 16 1  24.8125 28.125  1.75 11.375  30.25 11.375  7.1875 28.125
fill nonzero
poly 48 1  56.8125 28.125  33.75 11.375  62.25 11.375  39.1875 28.125
";

/// One large polygon drawn three times under three clip windows: inside,
/// partly outside the frame, inverted (draws nothing), and back to the
/// whole frame behind the others.
const CLIPPED: &str = "
frame 40 30
clear #202020
color #4080c0
poly -10 -10  50 -5  45 40  -5 35
clip 4 4 15 12
color #ff8000
poly -10 -10  50 -5  45 40  -5 35
clip 30 -20 100 8
color #00ffff
poly -10 -10  50 -5  45 40  -5 35
clip 20 20 10 25
color #ff00ff
poly -10 -10  50 -5  45 40  -5 35
";

/// Thin triangles fanned around a sub-pixel centre, alternating colours:
/// shared edges leave no gap and no doubled pixel, and sub-pixel vertices
/// decide single pixels.
const FAN: &str = "
frame 64 64
clear #000000
color #e0e0e0
poly 31.6875 32.3125  62 32  60.5 40.25
color #c03030
poly 31.6875 32.3125  60.5 40.25  55.5625 52.125
color #e0e0e0
poly 31.6875 32.3125  55.5625 52.125  44 61.9375
color #c03030
poly 31.6875 32.3125  44 61.9375  30.0625 63
color #e0e0e0
poly 31.6875 32.3125  30.0625 63  12 58
color #c03030
poly 31.6875 32.3125  12 58  2 44.5
color #e0e0e0
poly 31.6875 32.3125  2 44.5  0.5 24
color #c03030
poly 31.6875 32.3125  0.5 24  10 6.0625
color #e0e0e0
poly 31.6875 32.3125  10 6.0625  31 0.25
color #c03030
poly 31.6875 32.3125  31 0.25  52.875 8
color #e0e0e0
poly 31.6875 32.3125  52.875 8  62 32
";

/// Colour channels at the RGB565 extremes and in between: 0x00 and 0xff
/// survive exactly, others are truncated and expanded by bit replication.
const COLOURS: &str = "
frame 16 8
clear #000000
color #ffffff
poly 0 0  4 0  4 4  0 4
color #ff0000
poly 4 0  8 0  8 4  4 4
color #00ff00
poly 8 0  12 0  12 4  8 4
color #0000ff
poly 12 0  16 0  16 4  12 4
color #808080
poly 0 4  4 4  4 8  0 8
color #7f7f7f
poly 4 4  8 4  8 8  4 8
color #123456
poly 8 4  12 4  12 8  8 8
color #fedcba
poly 12 4  16 4  16 8  12 8
";

/// A coordinate of the text form in 1/16 px; panics unless exact.
fn coord(word: &str) -> i16 {
    let (neg, digits) = match word.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, word),
    };
    let (int, frac) = digits.split_once('.').unwrap_or((digits, ""));
    let mut units: i32 = int.parse::<i32>().expect("integer part") * 16;
    if !frac.is_empty() {
        // frac/10^k must be a multiple of 1/16: frac·16 divisible by 10^k.
        let scale = 10i64.pow(frac.len() as u32);
        let f: i64 = frac.parse().expect("fraction");
        assert_eq!(f * 16 % scale, 0, "{word} is not a multiple of 1/16");
        units += (f * 16 / scale) as i32;
    }
    i16::try_from(if neg { -units } else { units }).expect("inside Q12.4")
}

fn colour(word: &str) -> Rgb888 {
    let hex = word.strip_prefix('#').expect("#rrggbb");
    let v = u32::from_str_radix(hex, 16).expect("hex colour");
    Rgb888::new((v >> 16) as u8, (v >> 8) as u8, v as u8)
}

/// The display list of a scene in the text form's subset above.
fn assemble(text: &str) -> Vec<u8> {
    let mut buf = vec![0u8; 16 + 4 * text.len()];
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first: Vec<&str> = lines
        .next()
        .expect("a frame line")
        .split_whitespace()
        .collect();
    assert_eq!(first[0], "frame");
    let (w, h) = (first[1].parse().unwrap(), first[2].parse().unwrap());
    let mut out = Writer::new(&mut buf, w, h).expect("frame size");
    for line in lines {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words[0] {
            "clear" => out.clear(colour(words[1])).unwrap(),
            "color" => out.color(colour(words[1])).unwrap(),
            "fill" => out
                .fill(FillRule::from_name(words[1]).expect("a fill rule"))
                .unwrap(),
            "clip" => {
                let v: Vec<i16> = words[1..].iter().map(|s| s.parse().unwrap()).collect();
                out.clip(ClipWindow {
                    x0: v[0],
                    y0: v[1],
                    x1: v[2],
                    y1: v[3],
                })
                .unwrap();
            }
            "poly" => {
                let c: Vec<i16> = words[1..].iter().map(|s| coord(s)).collect();
                assert_eq!(c.len() % 2, 0, "odd coordinate count: {line}");
                out.poly(c.chunks_exact(2).map(|p| Vertex::from_bits(p[0], p[1])))
                    .unwrap();
            }
            other => panic!("command {other} is not used by the golden scenes"),
        }
    }
    out.finish().to_vec()
}

/// `(width, height, rgb)` of the scene's frame as the simulated hardware
/// reads it out, via its PNG.
fn render(text: &str) -> (u32, u32, Vec<u8>, Vec<u8>) {
    let bytes = assemble(text);
    let list = DisplayList::new_checked(&bytes).expect("valid list");
    let mut edges = [Edge::EMPTY; 16];
    let mut ram = DualPortRam::new(list.width(), list.height());
    Controller::new(Rasterizer::new(&mut edges))
        .render(&list, &mut ram.write_port())
        .expect("render");
    let timing = VideoTiming::for_frame(list.width(), list.height());
    let frame = RefreshController::new(timing).read_frame(&mut ram);
    let png = image::encode_png(&frame).expect("encode");
    let (w, h, rgb) = image::decode_png(&png).expect("decode");
    (w, h, rgb, png)
}

fn golden_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(format!("{name}.png"))
}

#[track_caller]
fn assert_golden(name: &str, scene: &str) {
    let (w, h, rgb, png) = render(scene);
    let path = golden_path(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, &png).expect("write golden");
        return;
    }
    let stored = std::fs::read(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e}; run with UPDATE_GOLDEN=1 to create it",
            path.display()
        )
    });
    let (gw, gh, grgb) = image::decode_png(&stored).expect("golden decodes");
    assert_eq!(
        (w, h),
        (gw, gh),
        "{name}: size differs from the golden image"
    );
    let differ: Vec<(u32, u32)> = (0..w * h)
        .filter(|&k| {
            rgb[3 * k as usize..3 * k as usize + 3] != grgb[3 * k as usize..3 * k as usize + 3]
        })
        .map(|k| (k % w, k / w))
        .collect();
    if !differ.is_empty() {
        let actual = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.actual.png"));
        std::fs::write(&actual, &png).expect("write actual image");
        panic!(
            "{name}: {} pixels differ from {} (first: {:?}); this render is in {}",
            differ.len(),
            path.display(),
            &differ[..differ.len().min(10)],
            actual.display()
        );
    }
}

#[test]
fn overlapping_triangles_in_painters_order() {
    assert_golden("overlap", OVERLAP);
}

#[test]
fn pentagram_is_filled_even_odd() {
    assert_golden("pentagram", PENTAGRAM);
}

#[test]
fn a_star_by_each_fill_rule() {
    assert_golden("star_fill_rules", STAR_FILL_RULES);
}

#[test]
fn clip_windows_inside_partly_outside_and_inverted() {
    assert_golden("clipped", CLIPPED);
}

#[test]
fn fan_of_thin_triangles_around_a_subpixel_centre() {
    assert_golden("fan", FAN);
}

#[test]
fn colour_channels_survive_rgb565_as_documented() {
    assert_golden("colours", COLOURS);
    // Independently of the stored image: 0x00 and 0xff are exact, and
    // #808080 truncates to 0x80 in 5 and 6 bits and replicates back to
    // 0x84 (5-bit channels) and 0x82 (6-bit green).
    let (w, _, rgb, _) = render(COLOURS);
    let at = |x: u32, y: u32| {
        let k = 3 * (y * w + x) as usize;
        [rgb[k], rgb[k + 1], rgb[k + 2]]
    };
    assert_eq!(at(0, 0), [0xff, 0xff, 0xff]);
    assert_eq!(at(5, 1), [0xff, 0x00, 0x00]);
    assert_eq!(at(9, 2), [0x00, 0xff, 0x00]);
    assert_eq!(at(13, 3), [0x00, 0x00, 0xff]);
    assert_eq!(at(1, 5), [0x84, 0x82, 0x84]);
}

#[test]
fn the_text_reader_of_these_tests_is_exact() {
    assert_eq!(coord("0"), 0);
    assert_eq!(coord("-3.5"), -56);
    assert_eq!(coord("100.0625"), 1601);
    assert_eq!(coord("2047.9375"), i16::MAX);
    assert_eq!(coord("-2048"), i16::MIN);
    assert!(std::panic::catch_unwind(|| coord("0.1")).is_err());
}
