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
    for command in [
        "render", "asm", "disasm", "import", "checksum", "demo", "help",
    ] {
        assert!(text.contains(&format!("scanvert {command}")), "{command}");
    }
    for word in [
        "--timing",
        "80 MiB",
        "16 MiB",
        "scanvert COMMAND --help",
        "Exit status",
    ] {
        assert!(text.contains(word), "{word}: {text}");
    }
}

#[test]
fn every_command_explains_its_options() {
    let commands: [(&str, &[&str]); 6] = [
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
        ("import", &["--out", "--size", "--color", "--help"]),
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

/// The usage of `command` alone: its help up to the first blank line.
fn usage_block(command: &str) -> String {
    let text = help(&["help", command]);
    text.split("\n\n").next().unwrap().to_string()
}

/// A usage error: exit 2, nothing on standard output, and on standard
/// error the error on one line, then what follows it.
fn usage_error(args: &[&str]) -> (String, String) {
    let o = scanvert(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(o.stdout.is_empty(), "{args:?}");
    let (first, rest) = err.split_once('\n').expect("two lines at least");
    assert!(first.starts_with("scanvert: "), "{args:?}: {err}");
    assert!(!first.contains("usage"), "{args:?}: {err}");
    (first.to_string(), rest.to_string())
}

#[test]
fn a_usage_error_prints_one_line_then_the_usage_of_its_command() {
    let cases: [(&str, &[&str]); 14] = [
        ("render", &["render"]),
        ("render", &["render", "x.dl"]),
        (
            "render",
            &["render", "x.dl", "--out", "x.png", "--band-rows", "0"],
        ),
        ("render", &["render", "--bogus"]),
        (
            "render",
            &["render", "x.dl", "--out", "x.png", "--frames", "2"],
        ),
        ("asm", &["asm"]),
        ("asm", &["asm", "x.dl", "--out", "x.scvl", "--stats"]),
        ("disasm", &["disasm", "a", "b"]),
        ("checksum", &["checksum"]),
        ("checksum", &["checksum", "x.dl", "--out", "y"]),
        ("demo", &["demo", "--frames", "0"]),
        ("demo", &["demo", "--timing", "vga"]),
        ("demo", &["demo", "x.dl"]),
        ("demo", &["demo", "--stats"]),
    ];
    for (command, args) in cases {
        let (_, rest) = usage_error(args);
        assert_eq!(rest, format!("{}\n", usage_block(command)), "{args:?}");
        for other in ["render", "asm", "disasm", "checksum", "demo"] {
            if other != command {
                assert!(
                    !rest.contains(&format!("scanvert {other}")),
                    "{args:?}: {rest}"
                );
            }
        }
    }
    // No command, or an unknown one: a line that names the commands.
    for args in [&[][..], &["bogus"], &["--bogus"]] {
        let (_, rest) = usage_error(args);
        assert_eq!(rest.lines().count(), 1, "{args:?}: {rest}");
        assert!(rest.starts_with("usage: scanvert render|asm|disasm|import|checksum|demo|help"));
    }
    let (_, rest) = usage_error(&["help", "bogus"]);
    assert_eq!(rest, "usage: scanvert help [COMMAND]\n");
}

/// The options named in `text` (`--word`), in order, without repeats.
fn options_in(text: &str) -> Vec<String> {
    let mut v: Vec<String> = Vec::new();
    for (i, _) in text.match_indices("--") {
        let name: String = text[i + 2..]
            .chars()
            .take_while(|c| c.is_ascii_lowercase() || *c == '-')
            .collect();
        let o = format!("--{name}");
        if !name.is_empty() && !v.contains(&o) {
            v.push(o);
        }
    }
    v.sort();
    v
}

/// The lines of `block` for `command`: the one that starts
/// `scanvert COMMAND` (after `prefix`) and the indented ones after it,
/// comments cut off.
fn lines_of(block: &str, prefix: &str, command: &str) -> String {
    let mut out = String::new();
    let mut inside = false;
    for line in block.lines() {
        let body = line.split(" #").next().unwrap();
        if let Some(rest) = body.strip_prefix(prefix) {
            if rest.starts_with("scanvert ") {
                inside = rest.starts_with(&format!("scanvert {command} "));
            } else if !rest.starts_with(' ') {
                inside = false;
            }
        } else {
            inside = false;
        }
        if inside {
            out += body;
            out.push('\n');
        }
    }
    out
}

#[test]
fn every_usage_lists_every_option_its_command_takes() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md"))
        .expect("README.md");
    let section = readme
        .split("## The command line")
        .nth(1)
        .and_then(|s| s.split("```text\n").nth(1))
        .and_then(|s| s.split("```").next())
        .expect("the README's command-line block");
    let all = help(&["help"]);
    let values: [(&str, &[&str]); 11] = [
        ("--out", &["x.out"]),
        ("--timing", &["auto"]),
        ("--stats", &[]),
        ("--band-rows", &["1"]),
        ("--resolve", &["paint"]),
        ("--race", &["168"]),
        ("--fifo", &["2"]),
        ("--ring", &["runs"]),
        ("--frames", &["1"]),
        ("--size", &["32x32"]),
        ("--no-speed", &[]),
    ];
    for command in ["render", "asm", "disasm", "checksum", "demo"] {
        let usage = options_in(&usage_block(command));
        let text = help(&["help", command]);
        let explained: Vec<String> = text
            .lines()
            .filter_map(|l| l.strip_prefix("  --"))
            .map(|l| format!("--{}", l.split([' ', ',']).next().unwrap()))
            .filter(|o| o != "--help")
            .collect();
        let mut explained = explained;
        explained.sort();
        assert_eq!(usage, explained, "{command}: usage against its options");
        let in_all = options_in(&lines_of(&all, "  ", command));
        assert_eq!(in_all, usage, "{command} in `scanvert help`");
        let in_readme = options_in(&lines_of(section, "", command));
        assert_eq!(in_readme, usage, "{command} in the README");
        // The command takes exactly these.
        for (option, value) in values {
            let mut args = vec![command.to_string(), option.to_string()];
            args.extend(value.iter().map(|v| v.to_string()));
            if command == "demo" {
                // An input file: an error once the options are checked,
                // so that nothing runs.
                args.push("x.dl".to_string());
            }
            let e = scanvert_sim::cli::run(&args).expect_err("an error, not a run");
            let taken = !e.message.contains("is not an option");
            assert_eq!(
                taken,
                usage.contains(&option.to_string()),
                "{args:?}: {}",
                e.message
            );
        }
    }
}
