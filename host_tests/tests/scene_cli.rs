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

/// Red pixels of a decoded image.
fn red(rgb: &[u8]) -> usize {
    rgb.chunks(3).filter(|c| c == &[255, 0, 0]).count()
}

/// Without `view` or `lookat` the eye is at the origin looking along −z
/// with y up (docs/display-list.md): a face at z = −5 is drawn, one at
/// z = +5 (behind the eye) is not.
#[test]
fn the_default_camera_looks_along_minus_z_with_y_up() {
    let face = |z: i32| {
        format!("frame 64 48\ncolor #ff0000\nface -1 -1 {z}  1 -1 {z}  1 1 {z}  -1 1 {z}\n")
    };
    let (_, w, rgb) = render("ahead", &face(-5)).expect("renders");
    assert!(red(&rgb) > 100);
    let i = 3 * (24 * w + 32) as usize;
    assert_eq!(&rgb[i..i + 3], [255, 0, 0], "on the view axis");
    let (out, _, rgb) = render("behind", &face(5)).expect("renders");
    assert_eq!(red(&rgb), 0, "{out}");
    // y up: a point above the axis is drawn above the middle row.
    let (_, w, rgb) = render(
        "up",
        "frame 64 48\ncolor #ff0000\nthickness 3\nface 0 2 -5\n",
    )
    .expect("renders");
    let rows: Vec<u32> = (0..48)
        .filter(|&y| (0..w).any(|x| rgb[3 * (y * w + x) as usize..][..3] == [255, 0, 0]))
        .collect();
    assert!(!rows.is_empty() && rows.iter().all(|&y| y < 24), "{rows:?}");
}

/// Facing is decided by the whole polygon: a concave face listed from its
/// reflex corner (the corner of its first three vertices) is drawn, and
/// the same face wound the other way is culled.
#[test]
fn a_concave_face_from_its_reflex_corner_is_drawn() {
    let arrow = "3 3 -10  0 1 -10  -3 3 -10  0 -3 -10";
    let reversed = "0 -3 -10  -3 3 -10  0 1 -10  3 3 -10";
    let (out, _, rgb) = render(
        "arrow",
        &format!("frame 64 48\ncolor #ff0000\nface {arrow}\n"),
    )
    .expect("renders");
    assert!(out.contains("1 faces (0 culled"), "{out}");
    assert!(red(&rgb) > 100);
    let (out, _, rgb) = render(
        "arrow-back",
        &format!("frame 64 48\ncolor #ff0000\nface {reversed}\n"),
    )
    .expect("renders");
    assert!(out.contains("0 faces (1 culled"), "{out}");
    assert_eq!(red(&rgb), 0);
}

/// The first failing command is the one named, with its own reason,
/// whatever comes before it.
#[test]
fn the_first_failing_command_is_named_after_a_poly3() {
    for (scene, line, what) in [
        (
            "frame 8 8\ncolor #ff0000\npoly3 1 1 1  1 6 1  6 3 1\npop\n",
            4,
            "pop on an empty transform stack",
        ),
        (
            "frame 8 8\npoly3 1 1 1  1 6 1  6 3 1\nscale 1000 1000 1000\nscale 1000 1000 1000\n\
             face 1 0 -30  0 1 -30  0 0 -30\n",
            4,
            "transform result outside the fixed-point range",
        ),
    ] {
        let e = render("first", scene).expect_err(scene);
        assert!(
            e.contains(&format!("line {line}: {what}")),
            "{scene:?}: {e}"
        );
    }
}

/// A list whose 3D layer needs more trapezoids than a pool can address
/// (65535) is refused, naming the line that goes beyond, before anything
/// is allocated for it (a few hundred kilobytes of self-intersecting
/// `poly3`s once asked for gigabytes).
#[test]
fn a_list_needing_more_than_a_pool_holds_is_refused_with_its_line() {
    // A star of 1001 vertices, each edge crossing about 1000 others.
    let n = 1001;
    let star: String = (0..n)
        .map(|k| {
            let a = 2.0 * std::f64::consts::PI * ((k * 501) % n) as f64 / n as f64;
            format!(
                " {:.2} {:.2} 1",
                1024.0 + 1000.0 * a.cos(),
                1024.0 + 1000.0 * a.sin()
            )
        })
        .collect();
    let scene = format!("frame 2048 2048\ncolor #ff0000\npoly3{star}\npoly3{star}\npoly3{star}\n");
    let (src, png) = (dir().join("huge.dl"), dir().join("huge.png"));
    std::fs::write(&src, &scene).expect("write scene");
    let _ = std::fs::remove_file(&png);
    let (src, out) = (src.to_str().expect("utf-8"), png.to_str().expect("utf-8"));
    let e = run(&["render", src, "--out", out]).expect_err("refused");
    assert_eq!(e.status, scanvert_sim::cli::EXIT_INPUT);
    assert!(e.message.contains("line 4:"), "{}", e.message);
    assert!(e.message.contains("65535 trapezoids"), "{}", e.message);
    assert!(!png.exists());
}
