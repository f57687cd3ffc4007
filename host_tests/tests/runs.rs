//! Rows made of runs (`port::runs`): every row of every list composed as
//! colour runs (`ListBands::draw_runs`, `SceneBands::draw_runs`) decodes
//! to exactly the pixels the band path draws for it (`draw` of a 1-row
//! band), is in the row format's canonical form (the runs the row's
//! pixels encode to), never needs more runs than the row has pixels, and
//! decodes to the same pixels again through the `pico_scanvideo` token
//! encoder and decoder. Lists: the repository's scenes, the image's
//! lists, hand-made 2D and 3D lists with clips, clears and labels,
//! generated 2D and 3D lists, and the 3D demo scene.

use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use proptest::prelude::*;
use scanvert::display_list::DisplayList;
use scanvert::port::runs::{ColorRun, RowRuns, RowsError};
use scanvert::port::scanvideo::{self, DecodeError, Opcodes};
use scanvert::scene::DEFAULT_FONT;
use scanvert::visible::sweep::Resolve;
use scanvert_sim::memory::ListMemory;
use scanvert_sim::race::{decode_tokens, encode_row, tokens, Run};
use std::path::Path;

/// The row's runs as the ring's (length, colour) runs.
fn lengths(row: &RowRuns<'_, Rgb565>) -> Vec<Run> {
    row.runs()
        .map(|(x0, x1, color)| Run {
            len: x1 - x0,
            color,
        })
        .collect()
}

/// Checks row `y` composed as runs against the band path's `pixels`.
fn same_row(what: &str, y: u16, row: &RowRuns<'_, Rgb565>, pixels: &[Rgb565]) {
    let w = pixels.len();
    let mut decoded = vec![Rgb565::RED; w];
    assert_eq!(row.decode(&mut decoded), w, "{what}: row {y}");
    assert!(
        decoded == pixels,
        "{what}: row {y} differs from the band path"
    );
    let mut canonical = Vec::new();
    encode_row(pixels, &mut canonical);
    let runs = lengths(row);
    assert_eq!(runs, canonical, "{what}: row {y} is not canonical");
    assert!(row.peak() <= w, "{what}: row {y} took {} runs", row.peak());
    // Through pico_scanvideo's tokens and back.
    let words = tokens(&runs);
    assert!(!words.is_empty(), "{what}: row {y} has no tokens");
    let mut back = Vec::new();
    assert!(
        decode_tokens(&words, w as u16, &mut back),
        "{what}: row {y}: the tokens do not decode"
    );
    assert_eq!(back, canonical, "{what}: row {y} through tokens");
}

/// Every row of `list`, its 3D layer resolved by `mode`, composed as runs
/// against the band path.
fn list_rows_match(what: &str, list: &DisplayList<'_>, mode: Resolve) {
    let mut m1 = ListMemory::for_bands(list).expect("memory");
    let mut m2 = ListMemory::for_bands(list).expect("memory");
    let (c1, t1) = m1.band_parts();
    let (c2, t2) = m2.band_parts();
    let (mut c1, mut c2) = (c1.with_resolve(mode), c2.with_resolve(mode));
    let mut bands = c1.bands(list, t1).expect("bands");
    let mut composed = c2.bands(list, t2).expect("bands");
    let (w, h) = bands.size();
    let mut pixels = vec![Rgb565::BLACK; usize::from(w)];
    let mut runs = vec![ColorRun::new(0, Rgb565::BLACK); usize::from(w)];
    for y in 0..h {
        bands.draw(y, 1, &mut pixels).expect("band");
        let mut row = RowRuns::new(&mut runs);
        composed.draw_runs(y, &mut row).expect("runs");
        same_row(what, y, &row, &pixels);
    }
    assert_eq!(bands.stats().spans, composed.stats().spans, "{what}");
}

fn text_list_rows_match(what: &str, text: &str) {
    let asm = scanvert_sim::text::assemble_bytes(text.as_bytes()).expect("assembles");
    let list = DisplayList::new_checked(&asm.bytes).expect("list");
    for mode in [Resolve::Crossing, Resolve::Paint, Resolve::Auto] {
        list_rows_match(what, &list, mode);
    }
}

#[test]
fn the_repository_lists_compose_into_the_band_paths_rows() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut n = 0;
    for dir in [
        "scenes",
        "firmware/image/scenes",
        "firmware/image/scenes/budget",
    ] {
        let mut files: Vec<_> = std::fs::read_dir(root.join(dir))
            .expect("dir")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.is_file())
            .collect();
        files.sort();
        for p in files {
            let bytes = std::fs::read(&p).expect("read");
            let bytes = match p.extension().and_then(|e| e.to_str()) {
                Some("dl") => {
                    scanvert_sim::text::assemble_bytes(&bytes)
                        .expect("asm")
                        .bytes
                }
                Some("scvl") => bytes,
                _ => continue,
            };
            let list = DisplayList::new_checked(&bytes).expect("list");
            list_rows_match(&p.display().to_string(), &list, Resolve::Crossing);
            n += 1;
        }
    }
    assert!(n >= 18, "{n} lists");
}

/// Polygons, lines, clips and two clears; rows no command writes.
const FLAT: &str = "\
frame 70 50
color #ff0000
poly 2 2 60 5 30 45
clear #203040
color #00ff00
poly 5 5 65 10 10 48.5 40 20
clip 10 10 40 30
color #0000ff
poly 0 0 70 0 70 50 0 50
clip 0 0 70 50
color #203040
poly 30 0 31 0 31 50 30 50
color #ffffff
line 0 49 69 0
line 3 3 3 3
";

/// 2D under a 3D layer with a scene, labels across rows and off the
/// frame, a clip, and a clear after the 3D layer.
const THREE_D: &str = "\
frame 96 64
color #404040
poly 0 40 96 40 96 64 0 64
clip 0 0 60 63
color #e0e000
poly3 10 10 50  10 50 50  50 30 50
clip -1 -1 200 200
perspective 60 1 100
lookat 3 2.5 5  0 0 0
light 1 2 3 70
segment 1
color #ff0000
face -1 -1 1  1 -1 1  1 1 1  -1 1 1
face 1 -1 -1  -1 -1 -1  -1 1 -1  1 1 -1
face 1 -1 1  1 -1 -1  1 1 -1  1 1 1
face -1 -1 -1  -1 -1 1  -1 1 1  -1 1 -1
face -1 1 1  1 1 1  1 1 -1  -1 1 -1
face -1 -1 -1  1 -1 -1  1 -1 1  -1 -1 1
color #ffffff
label -200 0 0 far off to the left
label 1 1 1 hi
label -1 1.2 1 a longer label across rows
clip 20 20 70 50
color #00c0ff
poly3 0 0 30  96 0 30  0 64 30
";

#[test]
fn hand_made_lists_compose_into_the_band_paths_rows() {
    text_list_rows_match("flat", FLAT);
    text_list_rows_match("3D", THREE_D);
    text_list_rows_match("3D, then a clear", &format!("{THREE_D}clear #000040\n"));
    text_list_rows_match("nothing", "frame 33 7\n");
    text_list_rows_match("one pixel", "frame 1 1\ncolor #ffffff\npoly 0 0 1 0 1 1\n");
}

#[test]
fn the_demo_scene_composes_into_the_band_paths_rows() {
    use scanvert_sim::demo::{steps, with_scene, HEIGHT, WIDTH};
    let w = usize::from(WIDTH);
    for step in steps(8).into_iter().step_by(2) {
        with_scene(step, |scene, bg| {
            let mut pixels = vec![Rgb565::BLACK; w * usize::from(HEIGHT)];
            {
                let mut bands = scene
                    .bands(Resolve::default(), bg, DEFAULT_FONT)
                    .expect("bands");
                bands.draw(0, HEIGHT, &mut pixels).expect("band");
            }
            let mut bands = scene
                .bands(Resolve::default(), bg, DEFAULT_FONT)
                .expect("bands");
            let mut runs = vec![ColorRun::new(0, Rgb565::BLACK); w];
            // Every other row, the ones between skipped.
            for y in (0..HEIGHT).step_by(2) {
                let mut row = RowRuns::new(&mut runs);
                bands.draw_runs(y, &mut row).expect("runs");
                let at = usize::from(y) * w;
                same_row(&format!("{step:?}"), y, &row, &pixels[at..at + w]);
            }
        })
        .expect("demo scene");
    }
}

#[test]
fn too_few_runs_and_rows_out_of_order_are_typed_errors() {
    let asm = scanvert_sim::text::assemble_bytes(FLAT.as_bytes()).expect("asm");
    let list = DisplayList::new_checked(&asm.bytes).expect("list");
    let mut m = ListMemory::for_bands(&list).expect("memory");
    let (mut c, t) = m.band_parts();
    let mut bands = c.bands(&list, t).expect("bands");
    let mut two = [ColorRun::new(0, Rgb565::BLACK); 2];
    let mut row = RowRuns::new(&mut two);
    assert_eq!(
        bands.draw_runs(20, &mut row),
        Err(RowsError::Full { y: 20, capacity: 2 })
    );
    assert!(matches!(
        bands.draw_runs(3, &mut row),
        Err(RowsError::Band(_))
    ));
    assert!(matches!(
        bands.draw_runs(50, &mut row),
        Err(RowsError::Band(_))
    ));
    let mut none: [ColorRun<Rgb565>; 0] = [];
    let mut row = RowRuns::new(&mut none);
    assert_eq!(
        bands.draw_runs(21, &mut row),
        Err(RowsError::Full { y: 21, capacity: 0 })
    );
}

#[test]
fn a_token_stream_is_whole_words_and_ends_black() {
    let op = Opcodes::DEFAULT;
    // Every run of lengths 1 to 4 of two colours, black or not, three
    // runs long.
    for a in 1..5u16 {
        for b in 1..5u16 {
            for c in 1..5u16 {
                for colors in 0..8u16 {
                    let col = |i: u16| if colors >> i & 1 == 1 { 0x1234 + i } else { 0 };
                    let runs = [(a, col(0)), (b, col(1)), (c, col(2))];
                    let mut words = [0u32; 32];
                    let n = scanvideo::encode(runs, &op, &mut words).expect("fits");
                    let mut px = [0xffffu16; 16];
                    let got = scanvideo::decode(&words[..n], &op, &mut px).expect("decodes");
                    let want: Vec<u16> = runs
                        .iter()
                        .flat_map(|&(l, c)| std::iter::repeat_n(c, usize::from(l)))
                        .collect();
                    assert_eq!(&px[..want.len()], &want[..], "{runs:?}");
                    assert_eq!(got, want.len() + usize::from(col(2) != 0), "{runs:?}");
                    // One word fewer is refused, as is a stream cut short.
                    assert!(scanvideo::encode(runs, &op, &mut words[..n - 1]).is_err());
                    assert!(matches!(
                        scanvideo::decode(&words[..n - 1], &op, &mut px),
                        Err(DecodeError::Truncated { .. } | DecodeError::Misaligned { .. })
                    ));
                }
            }
        }
    }
}

/// A random list in text form: clears, clips, colours, polygons, lines
/// and, when `three`, `poly3`s.
fn list_text(three: bool) -> impl Strategy<Value = String> {
    let coord = |side: i32| (-8 * 16..(side + 8) * 16).prop_map(|u| u as f64 / 16.0);
    let poly = prop::collection::vec((coord(48), coord(32)), 3..9).prop_map(|v| {
        let mut s = String::from("poly");
        for (x, y) in v {
            s += &format!(" {x} {y}");
        }
        s
    });
    let line = (coord(48), coord(32), coord(48), coord(32))
        .prop_map(|(a, b, c, d)| format!("line {a} {b} {c} {d}"));
    let poly3 = (
        prop::collection::vec((coord(48), coord(32), 1i32..60), 3..6),
        0..2u8,
    )
        .prop_map(|(v, _)| {
            let mut s = String::from("poly3");
            for (x, y, z) in v {
                s += &format!(" {x} {y} {z}");
            }
            s
        });
    let three = if three { 5u32 } else { 0 };
    let cmd = prop_oneof![
        1 => (0u32..0xffffff).prop_map(|c| format!("clear #{c:06x}")),
        2 => (-5i32..50, -5i32..35, -5i32..55, -5i32..40)
            .prop_map(|(a, b, c, d)| format!("clip {a} {b} {c} {d}")),
        // Few colours, so that neighbouring runs often share one.
        3 => prop::sample::select(vec!["#000000", "#ff0000", "#00ff00", "#ffffff"])
            .prop_map(|c| format!("color {c}")),
        8 => poly,
        4 => line,
        three => poly3,
    ];
    (1u16..=48, 1u16..=32, prop::collection::vec(cmd, 0..24)).prop_map(|(w, h, cmds)| {
        let mut s = format!("frame {w} {h}\n");
        for c in cmds {
            s += &c;
            s.push('\n');
        }
        s
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn generated_lists_compose_into_the_band_paths_rows(
        text in prop_oneof![list_text(false), list_text(true)]
    ) {
        text_list_rows_match(&text, &text);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, failure_persistence: None, ..ProptestConfig::default() })]

    /// Any words decode to pixels or a typed error, never a panic.
    #[test]
    fn any_words_decode_or_are_refused(
        words in prop::collection::vec(
            prop_oneof![
                any::<u32>(),
                (0u32..16, 0u32..16).prop_map(|(a, b)| a | b << 16),
            ],
            0..12,
        ),
        len in 0usize..40,
    ) {
        let mut px = vec![0u16; len];
        if let Ok(n) = scanvideo::decode(&words, &Opcodes::DEFAULT, &mut px) {
            prop_assert!(n <= len);
        }
    }

    /// Any runs encode to tokens that decode to their pixels, the black
    /// pixel after them when the last is not black.
    #[test]
    fn any_runs_come_back_through_tokens(
        runs in prop::collection::vec((1u16..6, prop_oneof![Just(0u16), 1u16..4]), 0..20),
    ) {
        let pixels: usize = runs.iter().map(|r| usize::from(r.0)).sum();
        let mut words = vec![0u32; (3 * runs.len() + pixels + 4).div_ceil(2)];
        let n = scanvideo::encode(runs.iter().copied(), &Opcodes::DEFAULT, &mut words).expect("fits");
        let mut px = vec![0xffffu16; pixels + 1];
        let got = scanvideo::decode(&words[..n], &Opcodes::DEFAULT, &mut px).expect("decodes");
        let want: Vec<u16> = runs
            .iter()
            .flat_map(|&(l, c)| std::iter::repeat_n(c, usize::from(l)))
            .collect();
        let black = usize::from(want.last().is_some_and(|&c| c != 0));
        prop_assert_eq!(got, want.len() + black);
        prop_assert_eq!(&px[..want.len()], &want[..]);
    }
}
