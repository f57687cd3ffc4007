//! Input files are limited to 16 MiB of binary list (`cli::INPUT_LIMIT`)
//! and 80 MiB of text (`cli::TEXT_LIMIT`, room for the disassembly of any
//! binary list): `/dev/zero` and files larger than that fail fast, with
//! exit status 1 and the message "… input larger than the N MiB limit",
//! and write nothing.

use scanvert::display_list::MAGIC;
use scanvert_sim::cli::{Scene, INPUT_LIMIT, TEXT_LIMIT};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

const BINARY: &str = "binary input larger than the 16 MiB limit";
const TEXT: &str = "text input larger than the 80 MiB limit";

fn dir(test: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("input_limit")
        .join(test);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Every command that reads an input, on `input`: refused for its size.
fn assert_refused_by_size(input: &Path, dir: &Path, message: &str) {
    let out = dir.join("out");
    let commands: [&[&str]; 4] = [
        &["render", "--out"],
        &["asm", "--out"],
        &["disasm", "--out"],
        &["checksum"],
    ];
    for args in commands {
        let start = Instant::now();
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_scanvert"));
        cmd.arg(args[0]).arg(input);
        if args.len() > 1 {
            cmd.arg(args[1]).arg(&out);
        }
        let o = cmd.output().expect("run scanvert");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&input.display().to_string()),
            "{args:?}: {stderr}"
        );
        assert!(!out.exists(), "{args:?} wrote output");
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{args:?} took {:?}",
            start.elapsed()
        );
    }
}

#[test]
fn dev_zero_is_refused() {
    let zero = Path::new("/dev/zero");
    if !zero.exists() {
        return;
    }
    assert_refused_by_size(zero, &dir("dev_zero"), TEXT);
}

#[test]
fn files_over_their_limit_are_refused() {
    let d = dir("sparse");
    let big = d.join("big.dl");
    let f = std::fs::File::create(&big).expect("create");
    f.set_len(TEXT_LIMIT + 1).expect("set_len");
    drop(f);
    assert_refused_by_size(&big, &d, TEXT);
    // Text that starts well is refused all the same.
    std::fs::write(&big, "frame 8 8\n").expect("write");
    std::fs::OpenOptions::new()
        .write(true)
        .open(&big)
        .and_then(|f| f.set_len(TEXT_LIMIT + 1))
        .expect("grow");
    assert_refused_by_size(&big, &d, TEXT);
    // A binary list is judged by its own limit.
    std::fs::write(&big, MAGIC).expect("write");
    std::fs::OpenOptions::new()
        .write(true)
        .open(&big)
        .and_then(|f| f.set_len(INPUT_LIMIT + 1))
        .expect("grow");
    assert_refused_by_size(&big, &d, BINARY);
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn a_file_of_exactly_16_mib_is_read() {
    let d = dir("exact");
    let scene = d.join("scene.dl");
    let mut text = b"frame 8 8\ncolor #ff0000\npoly 0 0 8 0 4 8\n".to_vec();
    text.resize(INPUT_LIMIT as usize - 1, b' ');
    text.push(b'\n');
    std::fs::write(&scene, &text).expect("write");
    let out = d.join("image.png");
    let o = Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .arg("render")
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run scanvert");
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.exists());
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn from_bytes_applies_the_limits_too() {
    let mut raw = b"frame 8 8\n".to_vec();
    raw.resize(TEXT_LIMIT as usize + 1, b'\n');
    let e = Scene::from_bytes(Path::new("big.dl"), raw).expect_err("refused");
    assert_eq!(e.status, 1);
    assert!(e.message.contains(TEXT), "{}", e.message);
    let mut raw = MAGIC.to_vec();
    raw.resize(INPUT_LIMIT as usize + 1, 0);
    let e = Scene::from_bytes(Path::new("big.scvl"), raw).expect_err("refused");
    assert!(e.message.contains(BINARY), "{}", e.message);
}
