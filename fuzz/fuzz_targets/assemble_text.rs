//! Arbitrary bytes as the text form → the assembler
//! (`scanvert_sim::text::assemble_bytes`), and what it accepts → the
//! binary reader and the renderer (frame cut to 64×64). An error names a
//! line of the input; an assembled list passes `new_checked`, and each of
//! its commands maps back to a line of the input.
#![no_main]

use libfuzzer_sys::fuzz_target;
use scanvert::display_list::{DisplayList, MAGIC};
use scanvert::visible::sweep::Resolve;
use scanvert_fuzz::{check_rendered, render_small};
use scanvert_sim::cli::Scene;
use scanvert_sim::text;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let lines = data.split(|&b| b == b'\n').count();
    let asm = match text::assemble_bytes(data) {
        Ok(asm) => asm,
        Err(e) => {
            assert!(
                (1..=lines).contains(&e.line),
                "line {} of {lines}: {e}",
                e.line
            );
            if !data.starts_with(&MAGIC) {
                let cli = Scene::from_bytes(Path::new("fuzz.dl"), data.to_vec())
                    .expect_err("the program refuses what the assembler refuses");
                assert!(
                    cli.message.contains(&format!("line {}:", e.line)),
                    "{}",
                    cli.message
                );
            }
            return;
        }
    };
    let list = DisplayList::new_checked(&asm.bytes).expect("assembled lists are valid");
    for (offset, _) in list.commands() {
        let line = asm.line_of(offset).expect("every command has a line");
        assert!((1..=lines).contains(&line), "line {line} of {lines}");
    }
    if let Some(r) = render_small(&list, Resolve::default()) {
        check_rendered(&list, &r);
        if let Err(e) = &r.result {
            let line = asm.line_of(e.offset()).expect("errors name a command");
            assert!((1..=lines).contains(&line));
        }
    }
});
