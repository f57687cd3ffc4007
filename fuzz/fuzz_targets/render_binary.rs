//! Arbitrary bytes → `DisplayList::new_checked` → `Controller::render`,
//! with memory sized as the `scanvert` program sizes it, into a frame of
//! at most 64×64. Small frames also go through the program's own path
//! (`Scene::from_bytes`, `render_scene` into the dual-port RAM), which
//! must agree pixel for pixel, and so must band rendering (bands of 1 to
//! 17 rows, chosen by the input's length).
#![no_main]

use libfuzzer_sys::fuzz_target;
use scanvert::display_list::{DisplayList, HEADER_LEN};
use scanvert::visible::sweep::Resolve;
use scanvert_fuzz::{check_bands, check_rendered, render_small};
use scanvert_sim::cli::{render_scene, Scene};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let list = match DisplayList::new_checked(data) {
        Ok(list) => list,
        Err(e) => {
            // The offset is inside the input (or its end, where it ran out).
            assert!(e.offset <= data.len(), "{e} for {} bytes", data.len());
            return;
        }
    };
    // The commands of a checked list are in order, inside the body.
    let mut next = HEADER_LEN;
    for (offset, _) in list.commands() {
        assert!(offset >= next && offset < data.len(), "command at {offset}");
        next = offset + 1;
    }
    let Some(r) = render_small(&list, Resolve::default()) else {
        return;
    };
    check_rendered(&list, &r);
    // Bands of 1 to 17 rows against the full frame.
    check_bands(&list, &r, 1 + (data.len() % 17) as u16);
    if r.whole {
        let scene = Scene::from_bytes(Path::new("fuzz.scvl"), data.to_vec())
            .expect("the program accepts what new_checked accepts");
        match (render_scene(&scene), &r.result) {
            (Ok(cli), Ok(_)) => assert_eq!(
                cli.ram.contents(),
                &r.pixels[..],
                "the program's frame differs"
            ),
            (Err(e), Err(_)) => assert!(e.message.contains("byte offset"), "{}", e.message),
            (cli, lib) => panic!(
                "the program and the library disagree: {:?} vs {:?}",
                cli.map(|c| c.stats),
                lib
            ),
        }
    }
});
