//! `disasm ∘ asm`: text the assembler accepts, disassembled and assembled
//! again, gives the same bytes, and its disassembly is a fixed point.
//! Binary input that the reader accepts disassembles to text that
//! assembles to the same bytes (labels the bare text form cannot say are
//! written as quoted strings).
#![no_main]

use libfuzzer_sys::fuzz_target;
use scanvert::display_list::{DisplayList, MAGIC};
use scanvert_sim::text;

fn round_trip(bytes: &[u8]) {
    let list = DisplayList::new_checked(bytes).expect("assembled lists are valid");
    let txt = text::disassemble(&list);
    let again = text::assemble(&txt)
        .unwrap_or_else(|e| panic!("disassembly does not assemble: {e}\n{txt}"));
    assert_eq!(
        again.bytes, bytes,
        "text → bytes → text → bytes changed the bytes\n{txt}"
    );
    let list2 = DisplayList::new_checked(&again.bytes).expect("valid");
    assert_eq!(
        text::disassemble(&list2),
        txt,
        "disassembly is not a fixed point"
    );
}

fuzz_target!(|data: &[u8]| {
    if data.starts_with(&MAGIC) {
        // A binary list: its text must assemble and then be stable.
        if DisplayList::new_checked(data).is_ok() {
            round_trip(data);
        }
    } else if let Ok(asm) = text::assemble_bytes(data) {
        round_trip(&asm.bytes);
    }
});
