//! `poly3` through the command-line contract: `scanvert render SCENE.dl
//! --out IMAGE.png` on a text scene that mixes `poly` and `poly3`, read
//! back from the PNG the simulated hardware wrote.

use std::path::PathBuf;

const SCENE: &str = "\
frame 48 32
clear #000040
# 2D: a grey band across the top, drawn first whatever its place.
color #808080
poly 0 0 48 0 48 6 0 6
# A red face at depth 10 over most of the frame.
color #ff0000
poly3 2 2 10   2 30 10   46 30 10   46 2 10
# A green face tilted through it: nearer on the left, farther on the right.
color #00ff00
poly3 10 0 0   10 32 0   30 32 20   30 0 20
# Clockwise as displayed: culled.
color #ffffff
poly3 0 0 -5   48 0 -5   48 32 -5
# A blue face behind everything, under a clip window.
clip 36 20 47 31
color #0000ff
poly3 30 14 100   30 32 100   48 32 100   48 14 100
";

fn run(args: &[&str]) -> Result<String, scanvert_sim::cli::CliError> {
    let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    scanvert_sim::cli::run(&args)
}

#[test]
fn render_draws_the_3d_layer_over_the_2d_commands() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("poly3_cli");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let scene = dir.join("mixed.dl");
    let png = dir.join("mixed.png");
    std::fs::write(&scene, SCENE).expect("write scene");
    let out = run(&[
        "render",
        scene.to_str().expect("utf-8 path"),
        "--out",
        png.to_str().expect("utf-8 path"),
        "--stats",
    ])
    .expect("render");
    assert!(
        out.contains("3 poly3, 0 faces (1 culled, 0 clipped away)"),
        "{out}"
    );
    let bytes = std::fs::read(&png).expect("png written");
    let (w, h, rgb) = scanvert_sim::image::decode_png(&bytes).expect("decode");
    assert_eq!((w, h), (48, 32));
    let at = |x: u32, y: u32| {
        let i = 3 * (y * w + x) as usize;
        (rgb[i], rgb[i + 1], rgb[i + 2])
    };
    let (red, green, blue) = ((255, 0, 0), (0, 255, 0), (0, 0, 255));
    assert_eq!(
        at(0, 1),
        (132, 130, 132),
        "2D band where no face is (RGB565)"
    );
    assert_eq!(at(5, 3), red, "the 3D layer over the 2D band");
    assert_eq!(at(12, 20), green, "green nearer on its left");
    assert_eq!(at(27, 20), red, "red nearer where green is beyond depth 10");
    assert_eq!(
        at(47, 24),
        blue,
        "blue inside its clip, where no nearer face is"
    );
    assert_eq!(at(47, 16), (0, 0, 66), "the clear: blue is clipped there");
    assert_eq!(at(40, 24), red, "blue is behind red");
    assert_eq!(at(1, 31), (0, 0, 66), "the clear where nothing is");
}
