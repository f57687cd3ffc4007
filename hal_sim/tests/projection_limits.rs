//! The projections' limits through the command line, as
//! `docs/display-list.md` states them: an orthographic near plane may be
//! zero or behind the eye (nothing divides by depth); a perspective near
//! plane may not; `far` must lie beyond `near`.

use std::path::PathBuf;

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("projection_limits");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Renders a red square 2 units in front of the eye (at the origin,
/// looking along −z) under `projection`;
/// returns the PNG's pixels, or the error message.
fn render(name: &str, projection: &str) -> Result<Vec<u8>, String> {
    let scene = format!(
        "frame 32 32\nclear #000000\n{projection}\nview 0 0 0 0 0\nsegment 1\ncolor #ff0000\n\
         face -0.5 -0.5 -2  0.5 -0.5 -2  0.5 0.5 -2  -0.5 0.5 -2\n"
    );
    let (src, png) = (
        dir().join(format!("{name}.dl")),
        dir().join(format!("{name}.png")),
    );
    std::fs::write(&src, scene).expect("write scene");
    let _ = std::fs::remove_file(&png);
    let args: Vec<String> = [
        "render",
        src.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    scanvert_sim::cli::run(&args).map_err(|e| {
        assert_eq!(e.status, 1, "{}", e.message);
        assert!(!png.exists(), "no image on an error");
        e.message
    })?;
    let (w, h, rgb) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    assert_eq!((w, h), (32, 32));
    Ok(rgb)
}

/// Red pixels in an RGB image.
fn red(rgb: &[u8]) -> usize {
    rgb.chunks_exact(3).filter(|p| *p == [255, 0, 0]).count()
}

#[test]
fn orthographic_near_plane_at_or_behind_the_eye_renders() {
    let base = render("ortho_1_100", "ortho 16 1 100").expect("renders");
    // 16 px per unit: the 1-unit square is 16 × 16 px.
    assert_eq!(red(&base), 256);
    for (name, projection) in [
        ("ortho_0_100", "ortho 16 0 100"),
        ("ortho_-100_100", "ortho 16 -100 100"),
        ("ortho_lowest_near", "ortho 16 -16383.99 100"),
    ] {
        let rgb = render(name, projection).unwrap_or_else(|e| panic!("{projection}: {e}"));
        assert_eq!(rgb, base, "{projection}");
    }
    // The square 2 units in front lies beyond a far plane at 1.5.
    let rgb = render("ortho_far_1.5", "ortho 16 -1 1.5").expect("renders");
    assert_eq!(red(&rgb), 0);
}

#[test]
fn projections_out_of_range_are_refused_with_their_line() {
    for (name, projection, what) in [
        ("ortho_far_eq_near", "ortho 16 5 5", "far plane"),
        ("ortho_far_before_near", "ortho 16 0 -1", "far plane"),
        ("ortho_scale_0", "ortho 0 1 100", "scale"),
        ("ortho_near_limit", "ortho 16 -16384 100", "near plane"),
        ("ortho_far_limit", "ortho 16 1 16384", "far plane"),
        ("perspective_near_0", "perspective 60 0 100", "near plane"),
        (
            "perspective_near_negative",
            "perspective 60 -1 100",
            "near plane",
        ),
        (
            "perspective_near_small",
            "perspective 60 0.0038 100",
            "near plane",
        ),
        ("perspective_fov_0", "perspective 0 1 100", "field of view"),
        (
            "perspective_fov_180",
            "perspective 180 1 100",
            "field of view",
        ),
        (
            "perspective_depth",
            "perspective 60 100 100.05",
            "too close",
        ),
    ] {
        let e = render(name, projection).expect_err(projection);
        assert!(e.contains("line 3:"), "{projection}: {e}");
        assert!(e.contains(what), "{projection}: {e}");
    }
    for (name, projection) in [
        ("perspective_near_least", "perspective 60 0.00390625 100"),
        ("perspective_depth_ok", "perspective 60 100 100.2"),
        ("perspective_fov_170", "perspective 170 1 100"),
    ] {
        render(name, projection).unwrap_or_else(|e| panic!("{projection}: {e}"));
    }
}
