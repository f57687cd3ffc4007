//! A UTF-8 byte-order mark at the start of a text scene is skipped: the
//! scene renders as without it, and faults keep their line numbers.

use std::path::{Path, PathBuf};

const BOM: &[u8] = b"\xef\xbb\xbf";
const SCENE: &str = "frame 16 8\r\nclear #000000\r\ncolor #00ff00\r\npoly 1 1 15 2 4 7\r\n";

fn dir() -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("byte_order_mark");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn run(args: &[&Path]) -> Result<String, scanvert_sim::cli::CliError> {
    let args: Vec<String> = args
        .iter()
        .map(|a| a.to_str().expect("utf-8").to_string())
        .collect();
    scanvert_sim::cli::run(&args)
}

/// Renders `bytes` as `name` and returns the PNG.
fn render(name: &str, bytes: &[u8]) -> Result<Vec<u8>, String> {
    let (src, png) = (
        dir().join(format!("{name}.dl")),
        dir().join(format!("{name}.png")),
    );
    std::fs::write(&src, bytes).expect("write scene");
    let _ = std::fs::remove_file(&png);
    run(&[Path::new("render"), &src, Path::new("--out"), &png]).map_err(|e| e.message)?;
    Ok(std::fs::read(&png).expect("png"))
}

#[test]
fn a_bom_at_the_start_is_skipped() {
    let plain = render("plain", SCENE.as_bytes()).expect("renders");
    let with_bom = render("bom", &[BOM, SCENE.as_bytes()].concat()).expect("renders with a BOM");
    assert_eq!(plain, with_bom);
    // Before a comment, and assembled to the same binary.
    let commented = [BOM, b"# a scene\n", SCENE.as_bytes()].concat();
    let a = scanvert_sim::text::assemble_bytes(&commented).expect("assembles");
    let b = scanvert_sim::text::assemble(SCENE).expect("assembles");
    assert_eq!(a.bytes, b.bytes);
}

#[test]
fn faults_after_a_bom_keep_their_line() {
    let e = render("bom_fault", &[BOM, b"frame 8 8\npoly 0 0 1\n"].concat()).expect_err("bad poly");
    assert!(e.contains("line 2:"), "{e}");
    let e = render("bom_first", &[BOM, b"color #000000\n"].concat()).expect_err("no frame");
    assert!(e.contains("line 1:") && e.contains("before `frame`"), "{e}");
}

#[test]
fn a_bom_elsewhere_is_not_skipped() {
    // Two marks: the second is part of the first word.
    let e = render("two_boms", &[BOM, BOM, SCENE.as_bytes()].concat()).expect_err("refused");
    assert!(e.contains("line 1:"), "{e}");
    // A mark at the start of a later line.
    let e = render(
        "bom_line_2",
        &[b"frame 8 8\n".as_slice(), BOM, b"clear #000000\n"].concat(),
    )
    .expect_err("refused");
    assert!(e.contains("line 2:") && e.contains("\\u{feff}"), "{e}");
}
