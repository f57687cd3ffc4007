//! Meshes (`v` and `f`) through the command line: each mesh is written
//! once with `v`/`f` and once as the `face`s through the same
//! coordinates, and the two render to the same pixels, whole frame and in
//! bands; bad indices are refused with their line (text) or byte offset
//! (binary), with no image written; binary → text → binary is byte-exact.

use std::fmt::Write;
use std::path::PathBuf;

fn run(args: &[&str]) -> Result<String, scanvert_sim::cli::CliError> {
    let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    scanvert_sim::cli::run(&args)
}

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("mesh");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn path(name: &str) -> String {
    dir().join(name).to_str().expect("utf-8").to_string()
}

/// Renders the text `scene` as `name` with `extra` options: the pixels,
/// or the error's message (no image written).
fn render(name: &str, scene: &str, extra: &[&str]) -> Result<Vec<u8>, String> {
    let (src, png) = (path(&format!("{name}.dl")), path(&format!("{name}.png")));
    let _ = std::fs::remove_file(&png);
    std::fs::write(&src, scene).expect("write scene");
    let mut args = vec!["render", &src, "--out", &png];
    args.extend_from_slice(extra);
    run(&args).map_err(|e| {
        assert!(!std::path::Path::new(&png).exists(), "no image on an error");
        e.message
    })?;
    let (_, _, rgb) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    Ok(rgb)
}

/// A mesh: its vertices as the text writes them, and faces of 0-based
/// indices, counter-clockwise seen from outside.
struct Mesh {
    vertices: Vec<String>,
    faces: Vec<Vec<usize>>,
}

fn num(x: f64) -> String {
    format!("{x:.4}")
}

/// A torus about the y axis: `n` around, `m` around the tube.
fn torus(r: f64, tube: f64, n: usize, m: usize) -> Mesh {
    let mut vertices = Vec::new();
    for i in 0..n {
        let a = i as f64 / n as f64 * std::f64::consts::TAU;
        for j in 0..m {
            let b = j as f64 / m as f64 * std::f64::consts::TAU;
            let d = r + tube * b.cos();
            vertices.push(format!(
                "{} {} {}",
                num(d * a.cos()),
                num(tube * b.sin()),
                num(-d * a.sin())
            ));
        }
    }
    let at = |i: usize, j: usize| (i % n) * m + (j % m);
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            // Quads alternate with pairs of triangles.
            if (i + j) % 2 == 0 {
                faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            } else {
                faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                faces.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    Mesh { vertices, faces }
}

/// A UV sphere with poles: `n` around, `m` bands.
fn sphere(r: f64, n: usize, m: usize) -> Mesh {
    let mut vertices = vec![format!("0 {} 0", num(r)), format!("0 {} 0", num(-r))];
    for k in 1..m {
        let t = k as f64 / m as f64 * std::f64::consts::PI;
        for i in 0..n {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            vertices.push(format!(
                "{} {} {}",
                num(r * t.sin() * a.cos()),
                num(r * t.cos()),
                num(-r * t.sin() * a.sin())
            ));
        }
    }
    let ring = |k: usize, i: usize| 2 + (k - 1) * n + i % n;
    let mut faces = Vec::new();
    for i in 0..n {
        faces.push(vec![0, ring(1, i + 1), ring(1, i)]);
        faces.push(vec![1, ring(m - 1, i), ring(m - 1, i + 1)]);
    }
    for k in 1..m - 1 {
        for i in 0..n {
            faces.push(vec![
                ring(k, i),
                ring(k, i + 1),
                ring(k + 1, i + 1),
                ring(k + 1, i),
            ]);
        }
    }
    Mesh { vertices, faces }
}

/// The mesh as `v` lines then `f` lines (every third face with negative
/// indices), after `base` vertices of the segment's table, and as `face`
/// lines.
fn write_mesh(m: &Mesh, base: usize, mesh: &mut String, faces: &mut String) {
    for v in &m.vertices {
        let _ = writeln!(mesh, "v {v}");
    }
    let n = m.vertices.len() as i64;
    for (k, f) in m.faces.iter().enumerate() {
        mesh.push('f');
        faces.push_str("face");
        for &i in f {
            if k % 3 == 1 {
                let _ = write!(mesh, " {}", i as i64 - n);
            } else {
                let _ = write!(mesh, " {}", base + i + 1);
            }
            let _ = write!(faces, " {}", m.vertices[i]);
        }
        mesh.push('\n');
        faces.push('\n');
    }
}

/// The same scene twice: `parts` are (text before the mesh, mesh), each
/// mesh written with `v`/`f` in one and as `face`s in the other.
fn scenes(head: &str, parts: &[(&str, &Mesh)]) -> (String, String) {
    let (mut a, mut b) = (head.to_string(), head.to_string());
    let mut base = 0;
    for (pre, m) in parts {
        a.push_str(pre);
        b.push_str(pre);
        if pre.contains("segment ") {
            base = 0;
        }
        write_mesh(m, base, &mut a, &mut b);
        base += m.vertices.len();
    }
    (a, b)
}

fn assert_same_pixels(name: &str, a: &str, b: &str) {
    for extra in [
        &[][..],
        &["--band-rows", "7"][..],
        &["--band-rows", "1"][..],
    ] {
        let pa = render(&format!("{name}-mesh"), a, extra).expect("mesh renders");
        let pb = render(&format!("{name}-face"), b, extra).expect("faces render");
        let lit = pa.chunks(3).filter(|p| p != &[0, 0, 0]).count();
        assert!(lit > 200, "{name}: the mesh shows ({lit} pixels)");
        let differ = pa
            .chunks(3)
            .zip(pb.chunks(3))
            .filter(|(x, y)| x != y)
            .count();
        assert_eq!(differ, 0, "{name} {extra:?}: differing pixels");
    }
}

const HEAD: &str = "\
frame 160 120
clear #000000
perspective 50 0.5 100
lookat 2 3 7  0 0 0
light 1 2 3 70
";

#[test]
fn a_torus_as_v_and_f_is_the_torus_as_faces() {
    let t = torus(1.6, 0.6, 24, 12);
    let (a, b) = scenes(HEAD, &[("color #d0a070\n", &t)]);
    assert_same_pixels("torus", &a, &b);
}

#[test]
fn meshes_under_transforms_in_several_segments() {
    let t = torus(1.0, 0.35, 18, 9);
    let s = sphere(0.8, 16, 9);
    let (a, b) = scenes(
        HEAD,
        &[
            (
                "segment 1\ncolor #ff8040\npush\ntranslate -1.2 0.3 0\nrotate x 60\nrotate y 25\n",
                &t,
            ),
            (
                "pop\nsegment 2\ncolor #40a0ff\npush\ntranslate 1.3 0 0.5\nscale 1 1.4 1\n",
                &s,
            ),
            (
                "pop\nsegment 3\ncolor #80ff80\ntranslate 0 -1.5 -1\nrotate z 30\n",
                &s,
            ),
            // A second mesh in the same segment: its table goes on.
            ("color #ffffff\ntranslate 0 0 -2.5\n", &t),
        ],
    );
    assert_same_pixels("several", &a, &b);
}

#[test]
fn a_mesh_cut_by_the_near_plane_and_the_window() {
    let s = sphere(3.0, 20, 12);
    let head =
        "frame 120 90\nclear #000000\nperspective 70 1 50\nview 0 0 3.5 0 0\nlight 0 1 2 60\n";
    let (a, b) = scenes(head, &[("color #c0c0c0\n", &s)]);
    // Seen from inside the near plane of the sphere's front: its back.
    let s2 = sphere(1.5, 12, 7);
    let (c, d) = scenes(head, &[("translate 1.5 1 0\ncolor #a08060\n", &s2)]);
    assert_same_pixels("near", &a, &b);
    assert_same_pixels("window", &c, &d);
}

#[test]
fn faces_after_a_change_of_projection_in_the_segment() {
    // The faces through the table after `perspective` or `ortho` are
    // projected by the new projection, not the one the first faces were.
    let s = sphere(1.0, 14, 8);
    for change in ["perspective 30 0.5 100\n", "ortho 40 -50 50\n"] {
        let (mut a, mut b) = scenes(HEAD, &[("color #c08040\n", &s)]);
        a.push_str(change);
        b.push_str(change);
        a.push_str("color #4080c0\n");
        b.push_str("color #4080c0\n");
        for f in &s.faces {
            a.push('f');
            b.push_str("face");
            for &i in f {
                a.push_str(&format!(" {}", i + 1));
                b.push_str(&format!(" {}", s.vertices[i]));
            }
            a.push('\n');
            b.push('\n');
        }
        assert_same_pixels("reprojected", &a, &b);
    }
}

#[test]
fn points_and_lines_through_the_table() {
    let scene = "frame 64 48\nclear #000000\nview 0 0 6 0 0\nthickness 2\ncolor #ffff00\n\
                 v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1\nf -2 -1\nf 1 3\n";
    let faces = "frame 64 48\nclear #000000\nview 0 0 6 0 0\nthickness 2\ncolor #ffff00\n\
                 face -1 -1 0\nface 1 -1 0 0 1 0\nface -1 -1 0 0 1 0\n";
    for extra in [&[][..], &["--band-rows", "5"][..]] {
        let a = render("pl-mesh", scene, extra).expect("renders");
        let b = render("pl-face", faces, extra).expect("renders");
        assert!(a.iter().any(|&c| c != 0));
        assert_eq!(a, b);
    }
}

fn refused(name: &str, scene: &str, line: usize) -> String {
    let e = render(name, scene, &[]).expect_err("refused");
    assert!(e.contains(&format!("line {line}")), "{name}: {e}");
    e
}

#[test]
fn bad_indices_are_refused_with_their_line() {
    let head = "frame 32 32\nview 0 0 5 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    refused("zero", &format!("{head}f 1 0 2\n"), 6);
    refused("past", &format!("{head}f 1 2 4\n"), 6);
    refused("before", &format!("{head}f 1 2 -4\n"), 6);
    let e = refused("none", "frame 32 32\nf 1\nv 0 0 0\n", 2);
    assert!(e.contains("no `v`"), "{e}");
    refused(
        "reset",
        &format!("{head}f 1 2 3\nsegment 2\nv 0 0 0\nf 1 2\n"),
        9,
    );
    refused("reset-neg", &format!("{head}segment 2\nf -1\n"), 7);
    refused("count", &format!("{head}f\n"), 6);
    refused("word", &format!("{head}f 1 x 2\n"), 6);
    // Before any segment the list's own table; `f 3` after a second
    // segment's 3 `v`s is fine.
    render(
        "ok",
        &format!("{head}f 1 2 3\nsegment 2\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 3 2 1\nf -1 -2 -3\n"),
        &[],
    )
    .expect("good indices render");
}

/// The assembled bytes of `scene`.
fn asm(name: &str, scene: &str) -> Vec<u8> {
    let (src, out) = (path(&format!("{name}.dl")), path(&format!("{name}.scvl")));
    std::fs::write(&src, scene).expect("write");
    run(&["asm", &src, "--out", &out]).expect("asm");
    std::fs::read(&out).expect("read")
}

#[test]
fn binary_bad_indices_are_refused_with_the_byte_offset() {
    let bytes = asm(
        "bin",
        "frame 32 32\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nsegment 1\nv 0 0 0\nf 1\n",
    );
    let list = scanvert::display_list::DisplayList::new_checked(&bytes).expect("valid");
    assert_eq!(list.summary().vertices, 3);
    // The `f` of the second segment is the last command: 3 + 2 bytes.
    let last = bytes.len() - 5;
    assert_eq!(bytes[last], scanvert::display_list::Opcode::MeshFace as u8);
    for (at, value) in [
        (last + 3, 1u16),
        (last + 3, 0xffff),
        (last - 13 - 3 - 9 + 5, 3),
    ] {
        let mut b = bytes.clone();
        b[at..at + 2].copy_from_slice(&value.to_le_bytes());
        let e = scanvert::display_list::DisplayList::new_checked(&b).expect_err("refused");
        assert_eq!(e.offset, at, "{value}");
        assert!(matches!(
            e.kind,
            scanvert::display_list::ErrorKind::BadIndex { index, .. } if index == value
        ));
        let file = path("bin-bad.scvl");
        std::fs::write(&file, &b).expect("write");
        let png = path("bin-bad.png");
        let _ = std::fs::remove_file(&png);
        let msg = run(&["render", &file, "--out", &png])
            .expect_err("refused")
            .message;
        assert!(msg.contains(&format!("byte offset {at}")), "{msg}");
        assert!(!std::path::Path::new(&png).exists());
    }
}

#[test]
fn binary_text_binary_is_byte_exact() {
    let t = torus(1.0, 0.4, 10, 6);
    let s = sphere(0.7, 8, 5);
    let (a, _) = scenes(
        HEAD,
        &[
            ("segment 4\ncolor #123456\n", &t),
            ("segment 5\nrotate y 10\n", &s),
        ],
    );
    let bytes = asm("rt", &a);
    let list = scanvert::display_list::DisplayList::new_checked(&bytes).expect("valid");
    let text = scanvert_sim::text::disassemble(&list);
    assert!(text.contains("\nv ") && text.contains("\nf "));
    assert!(!text.contains("f -"), "disasm writes positive indices");
    let again = asm("rt2", &text);
    assert_eq!(again, bytes);
}

/// `Builder::mesh` against `Builder::face` through the same points: the
/// same pixels, each vertex transformed once, the counts in its stats.
#[test]
fn builder_mesh_draws_what_its_faces_draw() {
    use scanvert::geometry::ViewPoint;
    use scanvert::prelude::*;
    use scanvert::scene::{MeshStats, SceneStorage, DEFAULT_FONT};
    use scanvert::visible::Resolve;
    use scanvert::{Angle, Builder, Perspective, Pipeline, Point3, Scene, View, Viewport, Q16};
    const W: u16 = 96;
    const H: u16 = 72;
    // An octahedron, counter-clockwise seen from outside.
    let q = |x: f64, y: f64, z: f64| {
        Point3::from_bits(
            (x * 65536.0) as i32,
            (y * 65536.0) as i32,
            (z * 65536.0) as i32,
        )
    };
    let vs = [
        q(1.5, 0.0, 0.0),
        q(-1.5, 0.0, 0.0),
        q(0.0, 1.5, 0.0),
        q(0.0, -1.5, 0.0),
        q(0.0, 0.0, 1.5),
        q(0.0, 0.0, -1.5),
    ];
    let tris: [u16; 24] = [
        0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
    ];
    let draw = |mesh: bool| {
        let mut storage = Box::new(SceneStorage::<
            512,
            64,
            1,
            { H as usize },
            16,
            64,
            { W as usize },
            0,
            0,
        >::new());
        let persp = Perspective::from_fov(
            Angle::from_degrees(60),
            W,
            Q16::from_int(1),
            Q16::from_int(100),
        )
        .unwrap();
        let mut scene = Scene::new(
            storage.as_memory(),
            Pipeline::<4, 16>::new(persp, Viewport::centred(W, H).unwrap()),
        )
        .unwrap();
        scene
            .set_view(&View {
                eye: Point3::from_int(0, 0, 6),
                yaw: Angle::ZERO,
                pitch: Angle::ZERO,
            })
            .unwrap();
        let mut stats = MeshStats::default();
        let mut slots = [ViewPoint::EMPTY; 6];
        let mut proc = |b: &mut Builder<'_, '_, 4, 16>| {
            b.rotate(scanvert::display_list::Axis::Y, Angle::from_degrees(30))?;
            b.rotate(scanvert::display_list::Axis::X, Angle::from_degrees(20))?;
            if mesh {
                stats = b.mesh(&vs, &tris, 3, Rgb888::new(255, 160, 40), &mut slots)?;
            } else {
                for t in tris.chunks(3) {
                    let p = [vs[t[0] as usize], vs[t[1] as usize], vs[t[2] as usize]];
                    b.face(&p, Rgb888::new(255, 160, 40))?;
                }
            }
            Ok(())
        };
        scene.update(&mut [&mut proc]).unwrap();
        let mut pixels = vec![Rgb565::BLACK; W as usize * H as usize];
        let mut fb = FrameBuffer::new(&mut pixels, W, H).unwrap();
        scene
            .draw(
                Resolve::Crossing,
                Some(Rgb565::BLACK),
                DEFAULT_FONT,
                &mut fb,
            )
            .unwrap();
        (pixels, stats)
    };
    let (a, stats) = draw(true);
    let (b, _) = draw(false);
    assert!(a.iter().filter(|&&c| c != Rgb565::BLACK).count() > 300);
    assert_eq!(a, b);
    assert_eq!(stats.vertices, 6);
    assert_eq!(stats.faces + stats.culled + stats.clipped_away, 8);
    // Seen in perspective from outside, at most half the faces show.
    assert!((3..=4).contains(&stats.faces), "{stats:?}");
    assert_eq!(stats.clipped_away, 0);
}
