//! `scanvert render --timing`: the image is the visible area of the chosen
//! timing, read from the frame's top-left corner. Where that area is smaller
//! than the frame, the image is cropped and a warning says so on standard
//! error; otherwise nothing is said.

use std::path::PathBuf;

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("timing_crop");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Renders a `w × h` frame under `timing` through the binary; returns the
/// image's size and standard error.
fn render(w: u16, h: u16, timing: &str) -> ((u32, u32), String) {
    let name = format!("{w}x{h}-{timing}");
    let (src, png) = (
        dir().join(format!("{name}.dl")),
        dir().join(format!("{name}.png")),
    );
    std::fs::write(
        &src,
        format!("frame {w} {h}\nclear #203040\ncolor #ffffff\npoly 0 0 {w} 0 0 {h}\n"),
    )
    .expect("write scene");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .arg("render")
        .arg(&src)
        .arg("--out")
        .arg(&png)
        .args(["--timing", timing])
        .output()
        .expect("run scanvert");
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(0), "{name}: {stderr}");
    let (iw, ih, _) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    ((iw, ih), stderr)
}

#[test]
fn a_visible_area_smaller_than_the_frame_is_a_warning() {
    let (size, stderr) = render(1024, 768, "vga");
    assert_eq!(size, (640, 480));
    assert!(
        stderr.contains(
            "warning: timing vga shows 640×480 of the 1024×768 frame; the image is cropped"
        ),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    // Cropped in one direction only.
    let (size, stderr) = render(320, 200, "256");
    assert_eq!(size, (256, 256));
    assert!(
        stderr.contains(
            "warning: timing 256 shows 256×256 of the 320×200 frame; the image is cropped"
        ),
        "{stderr}"
    );
    let (size, stderr) = render(640, 481, "reference");
    assert_eq!(size, (640, 480));
    assert!(stderr.contains("timing reference shows 640×480 of the 640×481 frame"));
}

#[test]
fn a_visible_area_that_holds_the_frame_is_not() {
    for (w, h, timing, size) in [
        (1024, 768, "auto", (1024, 768)),
        (320, 200, "vga", (640, 480)),
        (640, 480, "reference", (640, 480)),
        (256, 256, "256", (256, 256)),
    ] {
        let (got, stderr) = render(w, h, timing);
        assert_eq!(got, size, "{w}x{h} {timing}");
        assert!(stderr.is_empty(), "{w}x{h} {timing}: {stderr}");
    }
}

#[test]
fn run_reporting_hands_over_the_warning() {
    let src = dir().join("reporting.dl");
    let png = dir().join("reporting.png");
    std::fs::write(&src, "frame 300 300\n").expect("write scene");
    let args: Vec<String> = [
        "render",
        src.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--timing",
        "256",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let mut warnings = Vec::new();
    scanvert_sim::cli::run_reporting(&args, &mut |w| warnings.push(w.to_string()))
        .expect("renders");
    assert_eq!(
        warnings,
        ["warning: timing 256 shows 256×256 of the 300×300 frame; the image is cropped"]
    );
}
