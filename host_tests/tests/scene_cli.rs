//! The 3D scene commands through the command line: `scanvert render` on
//! text scenes with segments, transforms, a light, faces, points, lines
//! and labels, read back from the PNG; and scene commands that fail,
//! reported with their line and no image written.

use std::path::PathBuf;

fn run(args: &[&str]) -> Result<String, scanvert_sim::cli::CliError> {
    let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    scanvert_sim::cli::run(&args)
}

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("scene_cli");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Renders `scene` (text) as `name`; returns the output and the pixels.
fn render(name: &str, scene: &str) -> Result<(String, u32, Vec<u8>), String> {
    let (src, png) = (
        dir().join(format!("{name}.dl")),
        dir().join(format!("{name}.png")),
    );
    let _ = std::fs::remove_file(&png);
    std::fs::write(&src, scene).expect("write scene");
    let out = run(&[
        "render",
        src.to_str().expect("utf-8"),
        "--out",
        png.to_str().expect("utf-8"),
        "--stats",
    ])
    .map_err(|e| {
        assert!(!png.exists(), "no image on an error");
        e.message
    })?;
    let (w, _, rgb) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    Ok((out, w, rgb))
}

const CUBE: &str = "\
frame 96 64
clear #000000
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
segment 2
push
translate 0 1.6 0
color #00ff00
face 0 0 0
pop
color #ffffff
label -200 0 0 far off to the left
label 1 1 1 hi
";

#[test]
fn a_lit_cube_with_a_point_and_labels() {
    let (out, w, rgb) = render("cube", CUBE).expect("renders");
    assert!(
        out.contains("4 faces (3 culled, 0 clipped away), 1 labels"),
        "{out}"
    );
    let at = |x: u32, y: u32| {
        let i = 3 * (y * w + x) as usize;
        (rgb[i], rgb[i + 1], rgb[i + 2])
    };
    // Three faces show, each a different shade of red (hue kept, light
    // sets the intensity), none brighter than the colour itself.
    let mut shades: Vec<(u8, u8, u8)> = Vec::new();
    for y in 0..64 {
        for x in 0..96 {
            let c = at(x, y);
            if c.0 > 0 && c.1 == 0 && c.2 == 0 && !shades.contains(&c) {
                shades.push(c);
            }
        }
    }
    assert_eq!(shades.len(), 3, "{shades:?}");
    // The green point above the cube, and white label pixels.
    assert!(rgb.chunks(3).any(|c| c == [0, 255, 0]));
    assert!(rgb.chunks(3).any(|c| c == [255, 255, 255]));
}

#[test]
fn failing_scene_commands_name_their_line() {
    for (scene, line, what) in [
        ("frame 8 8\nsegment 1\npop\n", 3, "stack"),
        ("frame 8 8\n\nperspective 60 5 2\n", 3, "far"),
        ("frame 8 8\nlight 0 0 0 50\n", 2, "light"),
        (
            "frame 8 8\nscale 1000 1000 1000\nface 20 0 -30  0 20 -30  0 0 -30\n",
            3,
            "range",
        ),
    ] {
        let e = render("bad", scene).expect_err(scene);
        assert!(e.contains(&format!("line {line}:")), "{scene:?}: {e}");
        assert!(e.to_lowercase().contains(what), "{scene:?}: {e}");
    }
}
