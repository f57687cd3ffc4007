//! `--out` of `render`, `asm`, `disasm` and `demo` writes safely: through a
//! new temporary file next to the destination (never following a link
//! planted at its name), then renamed; a destination that exists and is not
//! a regular file (a symbolic link, a directory, a device, a fifo) is
//! refused, left as it was, with exit status 3 and a message naming it.
#![cfg(unix)]

use std::os::unix::fs::{symlink, FileTypeExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENE: &str = "frame 16 8\nclear #000000\ncolor #ff0000\npoly 1 1 15 2 4 7\n";
const VICTIM: &[u8] = b"precious, not an image\n";

/// A fresh, empty directory for one test, holding `scene.dl` and a
/// `victim` file that nothing may change.
fn setup(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("output_files")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("scene.dl"), SCENE).expect("scene");
    std::fs::write(dir.join("victim"), VICTIM).expect("victim");
    dir
}

fn scanvert(args: &[&Path]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .args(args)
        .output()
        .expect("run scanvert")
}

fn p(s: &str) -> &Path {
    Path::new(s)
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// `o` is a refusal of `out`: status 3, a message naming it, no panic.
fn assert_refused(o: &Output, out: &Path) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "stderr: {stderr}");
    assert!(
        stderr.contains(&out.display().to_string()),
        "message names {}: {stderr}",
        out.display()
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn a_symlink_at_the_destination_is_refused_and_its_target_untouched() {
    let dir = setup("symlink_destination");
    let scene = dir.join("scene.dl");
    let out = dir.join("out.bin");
    symlink(dir.join("victim"), &out).expect("symlink");
    let runs: [&[&Path]; 3] = [
        &[p("render"), &scene, p("--out"), &out],
        &[p("asm"), &scene, p("--out"), &out],
        &[p("disasm"), &scene, p("--out"), &out],
    ];
    for args in runs {
        let o = scanvert(args);
        assert_refused(&o, &out);
        assert_eq!(std::fs::read(dir.join("victim")).unwrap(), VICTIM);
        assert!(std::fs::symlink_metadata(&out)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(names(&dir), ["out.bin", "scene.dl", "victim"]);
    }
    // A dangling link is refused too, and nothing is created at its target.
    let dangling = dir.join("dangling.png");
    symlink(dir.join("nowhere"), &dangling).expect("symlink");
    let o = scanvert(&[p("render"), &scene, p("--out"), &dangling]);
    assert_refused(&o, &dangling);
    assert!(!dir.join("nowhere").exists());
}

#[test]
fn links_planted_at_temporary_names_are_never_followed() {
    let dir = setup("planted_temp");
    let scene = dir.join("scene.dl");
    let out = dir.join("image.png");
    // The old temporary name, and the first temporary names this process
    // would pick (`.NAME.PID.N.tmp`).
    let pid = std::process::id();
    let mut planted = vec![dir.join("image.png.partial")];
    planted.extend((0..4).map(|n| dir.join(format!(".image.png.{pid}.{n}.tmp"))));
    for link in &planted {
        symlink(dir.join("victim"), link).expect("symlink");
    }
    let args: Vec<String> = [&scene, p("--out"), &out]
        .iter()
        .map(|a| a.to_str().unwrap().to_string())
        .collect();
    let args = [vec!["render".to_string()], args].concat();
    scanvert_sim::cli::run(&args).expect("renders");
    assert_eq!(std::fs::read(dir.join("victim")).unwrap(), VICTIM);
    for link in &planted {
        let m = std::fs::symlink_metadata(link).expect("still there");
        assert!(m.file_type().is_symlink(), "{} replaced", link.display());
    }
    let m = std::fs::symlink_metadata(&out).expect("written");
    assert!(m.file_type().is_file());
    let (w, h, _) = scanvert_sim::image::decode_png(&std::fs::read(&out).unwrap()).expect("png");
    assert_eq!((w, h), (16, 8));
    // Only the planted links, the image and the inputs: no temporary left.
    assert_eq!(names(&dir).len(), 3 + planted.len());
    // The same through the real binary (another process id).
    std::fs::remove_file(&out).unwrap();
    let o = scanvert(&[p("render"), &scene, p("--out"), &out]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(std::fs::read(dir.join("victim")).unwrap(), VICTIM);
    assert_eq!(names(&dir).len(), 3 + planted.len());
}

/// Device nodes of our own, in the test's directory, like `/dev/null` and
/// `/dev/full` (the system's own are never aimed at: a regression would
/// replace them). `None` where nodes cannot be made (not root).
fn devices(dir: &Path) -> Option<Vec<PathBuf>> {
    let mut made = Vec::new();
    for (name, minor) in [("null", "3"), ("full", "7")] {
        let node = dir.join(name);
        let ok = Command::new("mknod")
            .arg(&node)
            .args(["c", "1", minor])
            .status();
        if !matches!(ok, Ok(s) if s.success()) {
            eprintln!("mknod unavailable: device nodes not tested");
            return None;
        }
        made.push(node);
    }
    Some(made)
}

#[test]
fn devices_are_refused() {
    let dir = setup("devices");
    let scene = dir.join("scene.dl");
    let Some(nodes) = devices(&dir) else {
        return;
    };
    for dev in &nodes {
        for cmd in ["render", "asm", "disasm"] {
            let o = scanvert(&[p(cmd), &scene, p("--out"), dev]);
            assert_refused(&o, dev);
            let m = std::fs::symlink_metadata(dev).unwrap();
            assert!(m.file_type().is_char_device(), "{} replaced", dev.display());
        }
    }
    assert_eq!(names(&dir), ["full", "null", "scene.dl", "victim"]);
}

#[test]
fn a_fifo_is_refused() {
    let dir = setup("fifo");
    let scene = dir.join("scene.dl");
    let fifo = dir.join("pipe");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !matches!(made, Ok(s) if s.success()) {
        eprintln!("mkfifo unavailable: skipped");
        return;
    }
    // Were the fifo opened for writing, this would block: it is not.
    let o = scanvert(&[p("render"), &scene, p("--out"), &fifo]);
    assert_refused(&o, &fifo);
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    assert_eq!(names(&dir), ["pipe", "scene.dl", "victim"]);
}

#[test]
fn a_directory_is_refused() {
    let dir = setup("directory");
    let scene = dir.join("scene.dl");
    let sub = dir.join("sub");
    std::fs::create_dir(&sub).unwrap();
    for cmd in ["render", "asm", "disasm"] {
        let o = scanvert(&[p(cmd), &scene, p("--out"), &sub]);
        assert_refused(&o, &sub);
        assert!(sub.is_dir());
        assert!(names(&sub).is_empty());
    }
    assert_eq!(names(&dir), ["scene.dl", "sub", "victim"]);
}

#[test]
fn write_errors_exit_3_naming_the_path() {
    let dir = setup("write_errors");
    let scene = dir.join("scene.dl");
    let out = dir.join("no-such-dir").join("image.png");
    let o = scanvert(&[p("render"), &scene, p("--out"), &out]);
    assert_refused(&o, &out);
    assert_eq!(names(&dir), ["scene.dl", "victim"]);
}

#[test]
fn a_regular_file_is_replaced() {
    let dir = setup("regular");
    let scene = dir.join("scene.dl");
    let out = dir.join("copy.dl");
    std::fs::write(&out, "old").unwrap();
    let o = scanvert(&[p("disasm"), &scene, p("--out"), &out]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), SCENE);
    assert_eq!(names(&dir), ["copy.dl", "scene.dl", "victim"]);
}

#[test]
fn demo_frames_are_written_safely() {
    let dir = setup("demo");
    let frames = dir.join("frames");
    std::fs::create_dir(&frames).unwrap();
    let first = frames.join("frame-00.png");
    symlink(dir.join("victim"), &first).expect("symlink");
    let o = scanvert(&[
        p("demo"),
        p("--out"),
        &frames,
        p("--frames"),
        p("1"),
        p("--no-speed"),
    ]);
    assert_refused(&o, &first);
    assert_eq!(std::fs::read(dir.join("victim")).unwrap(), VICTIM);
    assert_eq!(names(&frames), ["frame-00.png"]);
    // A device as the directory: refused, not replaced.
    if let Some(nodes) = devices(&dir) {
        let o = scanvert(&[p("demo"), p("--out"), &nodes[0], p("--frames"), p("1")]);
        assert_eq!(o.status.code(), Some(3), "{o:?}");
        let m = std::fs::symlink_metadata(&nodes[0]).unwrap();
        assert!(m.file_type().is_char_device());
    }
}

/// `--out` naming the input (as written, spelled another way, through a
/// hard or a symbolic link) is a usage error, exit 2, and nothing is
/// written: the scene is not replaced by its own image.
#[test]
fn out_onto_the_input_is_refused() {
    let dir = setup("out_is_input");
    let scene = dir.join("scene.dl");
    let hard = dir.join("hard.dl");
    std::fs::hard_link(&scene, &hard).expect("hard link");
    let soft = dir.join("soft.dl");
    symlink(&scene, &soft).expect("symlink");
    let other_spelling = dir
        .join(".")
        .join("..")
        .join("out_is_input")
        .join("scene.dl");
    for cmd in ["render", "asm", "disasm"] {
        for out in [&scene, &hard, &soft, &other_spelling] {
            let o = scanvert(&[p(cmd), &scene, p("--out"), out]);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{cmd} {out:?}: {stderr}");
            assert!(stderr.contains("is the input file"), "{cmd}: {stderr}");
            assert!(stderr.contains(&out.display().to_string()), "{stderr}");
            assert!(o.stdout.is_empty());
            assert_eq!(std::fs::read_to_string(&scene).unwrap(), SCENE);
            assert_eq!(names(&dir), ["hard.dl", "scene.dl", "soft.dl", "victim"]);
        }
    }
    // The same input as another file is fine.
    let copy = dir.join("copy.dl");
    std::fs::write(&copy, SCENE).unwrap();
    let o = scanvert(&[p("disasm"), &scene, p("--out"), &copy]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
}

/// A regular file that `--out` replaces keeps its access mode: 600 stays
/// 600, not the 644 a new file gets by default.
#[test]
fn a_replaced_file_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt;
    let dir = setup("mode");
    let scene = dir.join("scene.dl");
    let runs = [
        ("render", 0o600),
        ("asm", 0o640),
        ("disasm", 0o604),
        ("render", 0o755),
    ];
    for (cmd, mode) in runs {
        let out = dir.join(format!("out-{cmd}-{mode:o}"));
        std::fs::write(&out, "old").unwrap();
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(mode)).unwrap();
        let o = scanvert(&[p(cmd), &scene, p("--out"), &out]);
        assert_eq!(o.status.code(), Some(0), "{o:?}");
        assert_ne!(std::fs::read(&out).unwrap(), b"old");
        let m = std::fs::metadata(&out).unwrap().permissions().mode() & 0o7777;
        assert_eq!(m, mode, "{cmd}: {m:o}, not {mode:o}");
    }
    // A new file: the usual mode, through the umask, never executable.
    let out = dir.join("new.png");
    let o = scanvert(&[p("render"), &scene, p("--out"), &out]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let m = std::fs::metadata(&out).unwrap().permissions().mode();
    assert_eq!(m & 0o111, 0, "{m:o}");
}
