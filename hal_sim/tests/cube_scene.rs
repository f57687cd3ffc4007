//! `scenes/cube.dl`, the 3D example scene, renders through the program:
//! exit status 0, a 320 × 240 PNG with the lit cube, the pyramid and the
//! labels in it; and it survives `asm` and `disasm`.

use std::path::{Path, PathBuf};
use std::process::Command;

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cube.dl")
}

fn dir() -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cube_scene");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// `scanvert render` of the scene into `png` with `--stats` and `extra`.
fn render(png: &Path, extra: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .arg("render")
        .arg(scene())
        .arg("--out")
        .arg(png)
        .arg("--stats")
        .args(extra)
        .output()
        .expect("run scanvert")
}

#[test]
fn the_cube_scene_renders() {
    let png = dir().join("cube.png");
    let _ = std::fs::remove_file(&png);
    let o = render(&png, &[]);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(0), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
    assert!(stdout.contains("5 labels"), "{stdout}");
    let (w, h, rgb) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("PNG written")).expect("PNG");
    assert_eq!((w, h), (320, 240));
    let pixels: Vec<[u8; 3]> = rgb.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    // The faces are lit: shades of the cube's red and the pyramid's yellow,
    // more than one each (faces turned differently to the light).
    let shades = |is: &dyn Fn(&[u8; 3]) -> bool| {
        let mut v: Vec<[u8; 3]> = pixels.iter().filter(|p| is(p)).copied().collect();
        v.sort();
        v.dedup();
        v.len()
    };
    assert!(shades(&|p| p[0] / 2 > p[1] && p[0] / 2 > p[2] && p[0] > 80) >= 2);
    assert!(shades(&|p| p[0] > 100 && p[1] > 70 && p[2] < p[1] / 2) >= 2);
    // The labels, in white.
    assert!(pixels.iter().filter(|p| **p == [255, 255, 255]).count() > 50);
}

#[test]
fn the_cube_scene_survives_asm_and_disasm() {
    let run = |args: &[&Path]| {
        let args: Vec<String> = args
            .iter()
            .map(|a| a.to_str().expect("utf-8").to_string())
            .collect();
        scanvert_sim::cli::run(&args).unwrap_or_else(|e| panic!("{e}"))
    };
    let p = Path::new;
    let (bin, txt, again) = (
        dir().join("cube.scvl"),
        dir().join("cube.dl"),
        dir().join("again.scvl"),
    );
    run(&[p("asm"), &scene(), p("--out"), &bin]);
    run(&[p("disasm"), &bin, p("--out"), &txt]);
    run(&[p("asm"), &txt, p("--out"), &again]);
    assert_eq!(std::fs::read(&bin).unwrap(), std::fs::read(&again).unwrap());
}

/// Its labels are counted once whatever the bands: a label across two
/// bands is drawn in both and counted in the first.
#[test]
fn the_cube_scenes_labels_count_once_in_bands() {
    let stats = |extra: &[&str]| {
        let o = render(&dir().join("cube-labels.png"), extra);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8(o.stdout).expect("utf-8");
        out.lines()
            .find(|l| l.contains(" labels, "))
            .and_then(|l| {
                l.split(", ")
                    .find(|p| p.ends_with(" labels"))
                    .map(str::to_string)
            })
            .expect("a labels count")
    };
    let whole = stats(&[]);
    assert_eq!(whole, "5 labels");
    for rows in ["1", "7", "16"] {
        assert_eq!(stats(&["--band-rows", rows]), whole, "bands of {rows} rows");
    }
}
