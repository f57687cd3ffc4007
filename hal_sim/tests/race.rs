//! `scanvert render --race MHZ [--fifo K] [--ring runs|scanvideo]`:
//! racing the beam with no frame RAM. At a very high clock (up to
//! 100 GHz) no line is missed and the image is the plain render's, with
//! the ring's rows as colour runs or as `pico_scanvideo` tokens; at a very
//! low clock lines are missed, every pixel of a missed line is pure red,
//! and the printed count is the red lines; the ring's memory is printed
//! after the misses; bad options are usage errors (exit 2) that write no
//! image, and a clock out of range is told the range.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("race");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// 2D polygons and a line in painter's order, and interpenetrating
/// `poly3`s.
const SCENE: &str = "frame 96 64
clear #203040
color #ffffff
poly 4 4 90 10 40 60
color #ff8000
poly 50 2 94 30 60 62 10 40
line 0 63 95 0
poly3 10 10 5 80 12 5 70 50 5 12 52 5
color #00ff00
poly3 30 5 2 60 8 9 50 58 9 20 60 2
";

fn scanvert(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .args(args)
        .output()
        .expect("run scanvert")
}

fn scene(name: &str, text: &str) -> PathBuf {
    let p = dir().join(format!("{name}.dl"));
    std::fs::write(&p, text).expect("write scene");
    p
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// Renders with `extra` options; returns standard output and the image's
/// pixels (8-bit RGB).
fn render(src: &Path, name: &str, extra: &[&str]) -> (String, Vec<u8>) {
    let png = dir().join(format!("{name}.png"));
    let _ = std::fs::remove_file(&png);
    let mut args = vec!["render", s(src), "--out", s(&png)];
    args.extend_from_slice(extra);
    let o = scanvert(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{extra:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (_, _, px) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    (String::from_utf8_lossy(&o.stdout).into_owned(), px)
}

/// `(M, N)` of the line `deadline misses: M of N lines`, which the line
/// of the ring's memory follows.
fn misses(out: &str) -> (usize, usize) {
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    ring_bytes(lines[1]);
    let rest = lines[0]
        .strip_prefix("deadline misses: ")
        .and_then(|r| r.strip_suffix(" lines"))
        .unwrap_or_else(|| panic!("{out:?}"));
    let (m, n) = rest.split_once(" of ").expect("M of N");
    (m.parse().expect("M"), n.parse().expect("N"))
}

/// The bytes of a line `ring: K rows of at most R runs (4 bytes a run):
/// B bytes` (or of words of tokens), checked to be `K × R × 4`.
fn ring_bytes(line: &str) -> usize {
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words[0], "ring:", "{line}");
    let k: usize = words[1].parse().expect("K");
    let r: usize = words[6].parse().expect("R");
    let b: usize = words[words.len() - 2].parse().expect("B");
    assert_eq!(b, k * r * 4, "{line}");
    b
}

/// Rows of `px` (`w` pixels of 3 bytes) that are pure red throughout.
fn red_rows(px: &[u8], w: usize) -> usize {
    px.chunks(3 * w)
        .filter(|row| row.chunks(3).all(|p| p == [0xff, 0, 0]))
        .count()
}

#[test]
fn a_fast_cpu_misses_nothing_and_shows_the_plain_render() {
    let src = scene("plain", SCENE);
    let (_, plain) = render(&src, "plain", &[]);
    for (k, name) in [
        (None, "fast"),
        (Some("1"), "fast-k1"),
        (Some("16"), "fast-k16"),
    ] {
        for (mhz, ring) in [("4000", "runs"), ("10000", "scanvideo"), ("100000", "runs")] {
            let mut extra = vec!["--race", mhz, "--ring", ring];
            extra.extend(k.iter().flat_map(|k| ["--fifo", *k]));
            let (out, px) = render(&src, name, &extra);
            assert_eq!(misses(&out), (0, 64));
            assert!(
                px == plain,
                "{name} at {mhz} MHz, {ring}: the image differs from the plain render"
            );
        }
    }
}

#[test]
fn a_slow_cpu_misses_lines_shown_red_and_counted() {
    let src = scene("slow", SCENE);
    let (_, plain) = render(&src, "slow-plain", &[]);
    // 1 Hz: nothing is ready in time.
    let (out, px) = render(&src, "slow-1hz", &["--race", "0.000001"]);
    assert_eq!(misses(&out), (64, 64));
    assert_eq!(red_rows(&px, 96), 64);
    // Clocks between: the count is the red lines, and every other line
    // is the plain render's.
    let mut some = false;
    for mhz in ["100", "200", "300", "400", "500", "600", "700", "800"] {
        for k in ["1", "2", "4"] {
            let name = format!("slow-{mhz}-{k}");
            let ring = if k == "2" { "scanvideo" } else { "runs" };
            let (out, px) = render(&src, &name, &["--race", mhz, "--fifo", k, "--ring", ring]);
            let (m, n) = misses(&out);
            assert_eq!(n, 64);
            assert_eq!(red_rows(&px, 96), m, "{name}");
            for (row, want) in px.chunks(3 * 96).zip(plain.chunks(3 * 96)) {
                let red = row.chunks(3).all(|p| p == [0xff, 0, 0]);
                assert!(red || row == want, "{name}");
            }
            some |= 0 < m && m < n;
        }
    }
    assert!(some, "no clock missed some lines and not others");
}

/// Without `--timing`, a frame that fits in 640 × 480 is raced on the
/// reference design's raster (32 µs lines), where the racing figures are
/// given: the 2D demo misses nothing at 168 MHz with the default ring of
/// 2 rows, and the image is the frame, equal to the plain render. Its own
/// mode (`--timing auto`, 16 µs lines at 320 px) is twice as tight.
#[test]
fn the_demo_races_at_168_mhz_on_the_reference_raster_by_default() {
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes/demo.dl");
    let (_, plain) = render(&src, "demo-plain", &[]);
    let (out, px) = render(&src, "demo-168", &["--race", "168"]);
    assert_eq!(misses(&out), (0, 200), "{out}");
    assert!(px == plain, "the raced demo differs from the plain render");
    let (out, px) = render(
        &src,
        "demo-168-auto",
        &["--race", "168", "--timing", "auto"],
    );
    let (m, n) = misses(&out);
    assert_eq!(n, 200);
    assert!(m > 0, "{out}");
    assert_eq!(red_rows(&px, 320), m);
    let (out, px) = render(&src, "demo-1", &["--race", "1"]);
    assert_eq!(misses(&out), (200, 200), "{out}");
    assert_eq!(red_rows(&px, 320), 200);
}

#[test]
fn bad_race_options_are_usage_errors_and_write_no_image() {
    let src = scene("bad", SCENE);
    let png = dir().join("bad.png");
    for extra in [
        &["--race", "0"][..],
        &["--race", "0.0"],
        &["--race", "-168"],
        &["--race", "fast"],
        &["--race", "1e3"],
        &["--race"],
        &["--race", "168", "--fifo", "0"],
        &["--race", "168", "--fifo", "-2"],
        &["--race", "168", "--fifo", "two"],
        &["--race", "168", "--fifo"],
        &["--fifo", "2"],
        &["--race", "168", "--band-rows", "4"],
        &["--race", "168", "--stats"],
        &["--race", "100000.000001"],
        &["--race", "1000000"],
        &["--race", "168", "--ring", "pixels"],
        &["--race", "168", "--ring"],
        &["--ring", "runs"],
    ] {
        let _ = std::fs::remove_file(&png);
        let mut args = vec!["render", s(&src), "--out", s(&png)];
        args.extend_from_slice(extra);
        let o = scanvert(&args);
        assert_eq!(o.status.code(), Some(2), "{extra:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--race") || err.contains("--fifo") || err.contains("--ring"),
            "{extra:?}: {err}"
        );
        assert!(!png.exists(), "{extra:?} wrote an image");
        assert!(o.stdout.is_empty(), "{extra:?}");
    }
    // A clock out of range is told the range.
    let mut args = vec!["render", s(&src), "--out", s(&png)];
    args.extend_from_slice(&["--race", "200000"]);
    let err = String::from_utf8_lossy(&scanvert(&args).stderr).into_owned();
    assert!(
        err.contains("from 0.000001 to 100000") && err.contains("100 GHz"),
        "{err}"
    );
}

#[test]
fn the_demo_races_every_frame() {
    let out = dir().join("demo");
    let _ = std::fs::remove_dir_all(&out);
    let o = scanvert(&["demo", "--race", "4000", "--frames", "2", "--out", s(&out)]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8_lossy(&o.stdout);
    let (frames, ring) = text.rsplit_once("ring: ").expect("the ring's line");
    assert_eq!(
        frames,
        "frame 00: deadline misses: 0 of 256 lines\nframe 01: deadline misses: 0 of 256 lines\n"
    );
    assert!(ring_bytes(&format!("ring: {ring}")) > 0);
    // Each frame is the demo's step drawn from scratch into a frame buffer.
    for (i, step) in scanvert_sim::demo::steps(2).into_iter().enumerate() {
        let want = scanvert_sim::demo::reference_frame(step).expect("reference");
        let (w, h) = (scanvert_sim::demo::WIDTH, scanvert_sim::demo::HEIGHT);
        let want = scanvert_sim::image::encode_pixels(w.into(), h.into(), &want).expect("png");
        let want = scanvert_sim::image::decode_png(&want).expect("decode").2;
        let got = std::fs::read(out.join(format!("frame-{i:02}.png"))).expect("frame");
        let got = scanvert_sim::image::decode_png(&got).expect("decode").2;
        assert!(got == want, "frame {i} differs from the plain render");
    }
    // 1 Hz: every line of every frame is red.
    let o = scanvert(&[
        "demo",
        "--race",
        "0.000001",
        "--frames",
        "1",
        "--out",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&o.stdout)
        .starts_with("frame 00: deadline misses: 256 of 256 lines\nring: "));
    let png = std::fs::read(out.join("frame-00.png")).expect("frame");
    let (w, _, px) = scanvert_sim::image::decode_png(&png).expect("decode");
    assert_eq!(red_rows(&px, w as usize), 256);
    for bad in [&["--race", "0"][..], &["--race", "x"], &["--fifo", "2"]] {
        let mut args = vec!["demo", "--frames", "1", "--out", s(&out)];
        args.extend_from_slice(bad);
        assert_eq!(scanvert(&args).status.code(), Some(2), "{bad:?}");
    }
}
