//! `--help`: `scanvert --help`, `scanvert help COMMAND` and
//! `scanvert COMMAND --help` print to standard output, exit 0, and explain
//! every option of the command.

use std::process::{Command, Output};

fn scanvert(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .args(args)
        .output()
        .expect("run scanvert")
}

/// The help printed by `args`, checked to be a success with nothing on
/// standard error.
fn help(args: &[&str]) -> String {
    let o = scanvert(args);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(0), "{args:?}: {err}");
    assert!(err.is_empty(), "{args:?} wrote to stderr: {err}");
    assert!(out.starts_with("usage:"), "{args:?}: {out}");
    out
}

#[test]
fn the_program_help_lists_every_command() {
    let text = help(&["--help"]);
    assert_eq!(help(&["-h"]), text);
    assert_eq!(help(&["help"]), text);
    for command in ["render", "asm", "disasm", "checksum", "demo", "help"] {
        assert!(text.contains(&format!("scanvert {command}")), "{command}");
    }
    for word in [
        "--timing",
        "16 MiB",
        "scanvert COMMAND --help",
        "Exit status",
    ] {
        assert!(text.contains(word), "{word}: {text}");
    }
}

#[test]
fn every_command_explains_its_options() {
    let commands: [(&str, &[&str]); 5] = [
        (
            "render",
            &[
                "--out",
                "--timing",
                "auto",
                "reference",
                "vga",
                "256",
                "visible area",
                "cropped",
                "refresh",
                "--stats",
                "--help",
            ],
        ),
        ("asm", &["--out", "--help"]),
        ("disasm", &["--out", "standard output", "--help"]),
        ("checksum", &["checksum NAME", "--help"]),
        ("demo", &["--out", "--frames", "--no-speed", "--help"]),
    ];
    for (command, words) in commands {
        let text = help(&["help", command]);
        assert!(
            text.starts_with(&format!("usage: scanvert {command}")),
            "{command}: {text}"
        );
        assert_eq!(help(&[command, "--help"]), text, "{command} --help");
        assert_eq!(help(&[command, "-h"]), text, "{command} -h");
        // Wherever it comes among the arguments.
        assert_eq!(
            help(&[command, "x.dl", "--help"]),
            text,
            "{command} x --help"
        );
        for word in words {
            assert!(text.contains(word), "{command}: no {word}: {text}");
        }
    }
}

#[test]
fn help_on_an_unknown_command_is_a_usage_error() {
    for args in [
        &["help", "bogus"][..],
        &["bogus", "--help"],
        &["help", "a", "b"],
    ] {
        let o = scanvert(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(o.stdout.is_empty(), "{args:?}");
    }
}
