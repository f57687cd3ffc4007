//! Inputs found by fuzzing and by the proptests of `arbitrary_input.rs`,
//! kept in `fuzz/regressions/` (docs/robustness.md). Every one of them
//! goes through the program's path (`Scene::from_bytes`, `render_scene`,
//! and for binary lists the disassembler and assembler) without a panic,
//! and an error names a line or a byte offset.
//!
//! Some of them showed faults, now fixed; their tests below say what is
//! owed.

use scanvert::display_list::{DisplayList, MAGIC};
use scanvert_sim::cli::{render_scene, Scene};
use scanvert_sim::text;
use std::path::{Path, PathBuf};

fn regressions() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/regressions")
}

fn read(name: &str) -> Vec<u8> {
    std::fs::read(regressions().join(name)).expect("regression file")
}

#[test]
fn every_regression_input_is_handled() {
    let mut n = 0;
    for entry in std::fs::read_dir(regressions()).expect("fuzz/regressions") {
        let path = entry.expect("entry").path();
        let raw = std::fs::read(&path).expect("readable");
        n += 1;
        let scene = match Scene::from_bytes(&path, raw.clone()) {
            Ok(scene) => scene,
            Err(e) => {
                assert!(e.message.contains("line ") || e.message.contains("byte offset "));
                continue;
            }
        };
        if let Err(e) = render_scene(&scene) {
            assert!(
                e.message.contains("line ") || e.message.contains("byte offset "),
                "{}",
                e.message
            );
        }
        if raw.starts_with(&MAGIC) {
            let list = DisplayList::new_checked(&raw).expect("checked");
            // Disassembling never panics, and the text assembles back to
            // the same bytes.
            let again = text::assemble(&text::disassemble(&list)).expect("assembles");
            assert_eq!(again.bytes, raw);
        }
    }
    assert!(n >= 4, "{n} regression files");
}

/// A `face` that needs a face slot, then a `pop` with nothing saved: the
/// fault, the `pop` on line 3, is the one reported (it once was "line 2:
/// the 3D layer needs more than the 0 faces this renderer holds", when
/// the memory was sized by a function that gave up on the `pop`).
#[test]
fn a_failing_scene_command_is_reported_as_itself() {
    let path = regressions().join("scene-error-behind-capacity.dl");
    let scene =
        Scene::from_bytes(&path, read("scene-error-behind-capacity.dl")).expect("assembles");
    let e = render_scene(&scene).expect_err("the pop fails");
    assert!(
        e.message
            .contains("line 3: pop on an empty transform stack"),
        "{}",
        e.message
    );
}

/// Binary lists that the bare text form could not say: labels with `#`
/// or runs of spaces (the binary form takes any printable ASCII; in text
/// a `#` starts a comment and words are joined by single spaces), written
/// as quoted strings, and a version-2 header over version-1 commands,
/// written as `version 2`. Each disassembles to text that assembles back
/// to the same bytes.
#[test]
fn every_binary_list_survives_disassembly() {
    for name in [
        "label-starting-with-hash.scvl",
        "label-with-hash.scvl",
        "label-with-spaces.scvl",
        "version-2-header-2d-commands.scvl",
    ] {
        let raw = read(name);
        let list = DisplayList::new_checked(&raw).expect("a valid list");
        let txt = text::disassemble(&list);
        let again = text::assemble(&txt).unwrap_or_else(|e| panic!("{name}: {e}\n{txt}"));
        assert_eq!(again.bytes, raw, "{name}:\n{txt}");
    }
}
