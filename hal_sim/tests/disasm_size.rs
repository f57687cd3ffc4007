//! `disasm` writes at most five characters for a byte of list, so the
//! text of any binary list within `cli::INPUT_LIMIT` fits in
//! `cli::TEXT_LIMIT` and `asm` reads it back. The widest command for its
//! size is `push` (one byte, five characters with its newline); each
//! command with its widest operands is checked here.

use scanvert::display_list::DisplayList;
use scanvert_sim::cli::{INPUT_LIMIT, TEXT_LIMIT};
use scanvert_sim::text::{assemble, disassemble};

/// Commands with the operands that print longest.
const WIDEST: &[&str] = &[
    "push",
    "pop",
    "clear #ffffff",
    "color #ffffff",
    "clip -2048 -2048 2047 2047",
    "poly -2047.94 -2047.94 -2047.94 -2047.94 -2047.94 -2047.94",
    "line -2047.94 -2047.94 -2047.94 -2047.94",
    "poly3 -2047.94 -2047.94 -2047.94 -2047.94 -2047.94 -2047.94 -2047.94 -2047.94 -2047.94",
    "face -32767.99998 -32767.99998 -32767.99998",
    "face -32767.99998 -32767.99998 -32767.99998 -32767.99998 -32767.99998 -32767.99998",
    "rotate x -0.00274",
    "rotate z 359.99451",
    "translate -32767.99998 -32767.99998 -32767.99998",
    "scale -32767.99998 -32767.99998 -32767.99998",
    "segment 65535",
    "thickness 2047.94",
    "light -32767.99998 -32767.99998 -32767.99998 100",
    "perspective 179.99451 -32767.99998 32767.99998",
    "ortho -32767.99998 -32767.99998 32767.99998",
    "lookat -32767.99998 -32767.99998 -32767.99998 32767.99998 32767.99998 32767.99998",
    "label -32767.99998 -32767.99998 -32767.99998 \"\\\"\\\"\\\"\\\\\\\\\"",
];

const HEAD: &str = "frame 4096 4096\nversion 2\n";

#[test]
fn every_command_prints_at_most_five_characters_a_byte() {
    let head = assemble(HEAD).expect("header").bytes.len();
    for line in WIDEST {
        let text = format!("{HEAD}{line}\n");
        let asm = assemble(&text).unwrap_or_else(|e| panic!("{line}: {e}"));
        let list = DisplayList::new_checked(&asm.bytes).expect("assembled list");
        let back = disassemble(&list);
        let printed = back.len() - back.lines().take(2).map(|l| l.len() + 1).sum::<usize>();
        let bytes = asm.bytes.len() - head;
        assert!(
            printed <= 5 * bytes,
            "{line}: {printed} characters for {bytes} bytes: {back}"
        );
        assert_eq!(assemble(&back).expect("reads back").bytes, asm.bytes);
    }
}

#[test]
fn the_text_of_a_list_of_pushes_reads_back() {
    // 1 MiB of the widest command, and its header.
    let text = format!("{HEAD}{}", "push\n".repeat(1 << 20));
    let asm = assemble(&text).expect("assembles");
    let list = DisplayList::new_checked(&asm.bytes).expect("list");
    let back = disassemble(&list);
    assert!(back.len() <= 5 * asm.bytes.len());
    assert_eq!(assemble(&back).expect("reads back").bytes, asm.bytes);
}

#[test]
fn the_text_limit_holds_the_widest_disassembly() {
    assert_eq!(TEXT_LIMIT, 5 * INPUT_LIMIT);
}
