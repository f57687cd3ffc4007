//! `scanvert import`: one torus, generated here as Wavefront OBJ, ASCII
//! STL and binary STL, imports to lists that render to the same picture
//! with every triangle kept; OBJ's polygons, `v/vt/vn` and negative
//! indices; malformed and empty models refused with no list written.

use std::path::{Path, PathBuf};

fn run(args: &[&str]) -> Result<String, scanvert_sim::cli::CliError> {
    let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    scanvert_sim::cli::run(&args)
}

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("import");
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn path(name: &str) -> String {
    dir().join(name).to_str().expect("utf-8").to_string()
}

/// A torus about the y axis as triangles of `f32` corners,
/// counter-clockwise seen from outside.
fn torus(n: usize, m: usize) -> (Vec<[f32; 3]>, Vec<[usize; 3]>) {
    let mut v = Vec::new();
    for i in 0..n {
        let a = i as f32 / n as f32 * std::f32::consts::TAU;
        for j in 0..m {
            let b = j as f32 / m as f32 * std::f32::consts::TAU;
            let d = 3.0 + 1.2 * b.cos();
            v.push([d * a.cos(), 1.2 * b.sin(), -d * a.sin()]);
        }
    }
    let at = |i: usize, j: usize| (i % n) * m + (j % m);
    let mut t = Vec::new();
    for i in 0..n {
        for j in 0..m {
            t.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            t.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (v, t)
}

fn normal(p: [[f32; 3]; 3]) -> [f32; 3] {
    let u: [f32; 3] = std::array::from_fn(|k| p[1][k] - p[0][k]);
    let w: [f32; 3] = std::array::from_fn(|k| p[2][k] - p[0][k]);
    [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ]
}

fn obj(v: &[[f32; 3]], t: &[[usize; 3]]) -> String {
    let mut s = String::from("# torus\nmtllib none.mtl\no torus\n");
    for p in v {
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    s += "vt 0 0\nvn 0 1 0\nusemtl none\n";
    for (k, f) in t.iter().enumerate() {
        // Every other face with negative indices and v/vt/vn triples.
        if k % 2 == 0 {
            s += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
        } else {
            let n = v.len() as i64;
            let neg = |i: usize| i as i64 - n;
            s += &format!("f {}/1/1 {}/1/1 {}/1/1\n", neg(f[0]), neg(f[1]), neg(f[2]));
        }
    }
    s
}

fn stl_ascii(v: &[[f32; 3]], t: &[[usize; 3]]) -> String {
    let mut s = String::from("solid torus\n");
    for f in t {
        let p = f.map(|i| v[i]);
        let n = normal(p);
        s += &format!(
            "  facet normal {} {} {}\n    outer loop\n",
            n[0], n[1], n[2]
        );
        for q in p {
            s += &format!("      vertex {} {} {}\n", q[0], q[1], q[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid torus\n"
}

fn stl_binary(v: &[[f32; 3]], t: &[[usize; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend_from_slice(&(t.len() as u32).to_le_bytes());
    for f in t {
        let p = f.map(|i| v[i]);
        for c in std::iter::once(normal(p)).chain(p) {
            for x in c {
                b.extend_from_slice(&x.to_le_bytes());
            }
        }
        b.extend_from_slice(&[0, 0]);
    }
    b
}

/// Imports `file` (written with `bytes`) with `extra` options: the list's
/// text, or the error (no list written).
fn import(file: &str, bytes: &[u8], extra: &[&str]) -> Result<String, scanvert_sim::cli::CliError> {
    let (src, out) = (path(file), path(&format!("{file}.dl")));
    std::fs::write(&src, bytes).expect("write model");
    let _ = std::fs::remove_file(&out);
    let mut args = vec!["import", &src, "--out", &out];
    args.extend_from_slice(extra);
    match run(&args) {
        Ok(_) => Ok(std::fs::read_to_string(&out).expect("list written")),
        Err(e) => {
            assert!(!Path::new(&out).exists(), "no list on an error");
            Err(e)
        }
    }
}

fn render(name: &str, list: &str, extra: &[&str]) -> Vec<u8> {
    let (src, png) = (path(&format!("{name}.dl")), path(&format!("{name}.png")));
    std::fs::write(&src, list).expect("write");
    let mut args = vec!["render", &src, "--out", &png];
    args.extend_from_slice(extra);
    run(&args).expect("renders");
    let (_, _, rgb) =
        scanvert_sim::image::decode_png(&std::fs::read(&png).expect("png")).expect("decode");
    rgb
}

#[test]
fn one_torus_as_obj_ascii_stl_and_binary_stl_is_one_picture() {
    let (v, t) = torus(24, 12);
    let lists = [
        import("torus.obj", obj(&v, &t).as_bytes(), &[]).expect("obj"),
        import("torus-ascii.stl", stl_ascii(&v, &t).as_bytes(), &[]).expect("ascii stl"),
        import("torus-binary.stl", &stl_binary(&v, &t), &[]).expect("binary stl"),
        // Told apart by their contents without the extension.
        import("torus-binary.model", &stl_binary(&v, &t), &[]).expect("binary stl"),
    ];
    for l in &lists {
        assert_eq!(l.lines().filter(|l| l.starts_with("f ")).count(), t.len());
        assert_eq!(l.lines().filter(|l| l.starts_with("v ")).count(), v.len());
        assert!(l.contains("frame 320 240"));
    }
    let first = render("torus-0", &lists[0], &[]);
    let lit = first.chunks(3).filter(|p| p != &[0, 0, 0]).count();
    assert!(lit > 320 * 240 / 10, "the torus fills the frame: {lit}");
    // The bounding box is in the frame: no lit pixel on its border.
    let at = |x: usize, y: usize| &first[3 * (y * 320 + x)..3 * (y * 320 + x) + 3];
    for x in 0..320 {
        assert_eq!(at(x, 0), [0, 0, 0]);
        assert_eq!(at(x, 239), [0, 0, 0]);
    }
    for (k, l) in lists.iter().enumerate().skip(1) {
        assert_eq!(render(&format!("torus-{k}"), l, &[]), first, "{k}");
    }
    assert_eq!(
        render("torus-bands", &lists[2], &["--band-rows", "16"]),
        first
    );
}

#[test]
fn size_colour_and_polygons_of_any_size() {
    // A cube of quads, counter-clockwise seen from outside.
    let cube =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
                f 5 6 7 8\nf 2 1 4 3\nf 6 2 3 7\nf 1 5 8 4\nf 8 7 3 4\nf 1 2 6 5\n";
    let l = import(
        "cube.obj",
        cube.as_bytes(),
        &["--size", "64x48", "--color", "#ff8000"],
    )
    .expect("cube");
    assert!(l.contains("frame 64 48") && l.contains("color #ff8000"));
    assert!(l.contains("\nf 5 6 7 8\n"), "{l}");
    let px = render("cube", &l, &[]);
    let orange = px
        .chunks(3)
        .filter(|p| p[0] > 0 && p[2] == 0 && p[0] > p[1])
        .count();
    assert!(orange > 300, "{orange}");
}

#[test]
fn malformed_and_empty_models_are_refused() {
    let (v, t) = torus(6, 4);
    let mut cut = stl_binary(&v, &t);
    cut.truncate(cut.len() - 7);
    for (file, bytes) in [
        ("empty.obj", b"".to_vec()),
        ("points.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_vec()),
        ("bad.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n".to_vec()),
        ("past.obj", b"v 0 0 0\nv 1 0 0\nf 1 2 3\n".to_vec()),
        (
            "nan.obj",
            b"v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
        ),
        ("empty.stl", b"solid x\nendsolid x\n".to_vec()),
        (
            "bad.stl",
            b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0\n".to_vec(),
        ),
        ("cut.stl", cut),
        ("nothing.stl", Vec::new()),
    ] {
        let e = import(file, &bytes, &[]).expect_err(file);
        assert_eq!(e.status, 1, "{file}: {}", e.message);
        assert!(e.message.contains(file), "{file}: {}", e.message);
    }
    let e = import("c.obj", b"v 0 0 0\nf 1 1 1\n", &["--color", "red"]).expect_err("usage");
    assert_eq!(e.status, 2);
}
