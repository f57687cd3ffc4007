//! The always-on layer of the robustness tests (docs/robustness.md): any
//! input, run through the reader, the assembler and the renderer on the
//! stable toolchain, a few hundred cases a property.
//!
//! - Arbitrary bytes: with no header, with the magic and a valid header,
//!   and as a body of well-sized commands with arbitrary operands.
//! - Arbitrary well-formed commands of the text form, generated
//!   structurally (2D, `poly3` and the 3D scene), with operands in range
//!   and now and then out of it.
//!
//! Each accepted list is rendered through the program's own path
//! (`scanvert_sim::cli::render_scene`, memory sized from the scene). The
//! properties: nothing panics; an error names a place inside the input
//! (a byte offset within it and at a command, or a line of it); and the
//! work is bounded by the input: the commands executed are the list's and
//! the pixels written at most `(commands + 1) · W · H`. Hangs are the
//! fuzz job's to catch (libFuzzer's `-timeout`), not a timed test's.

use proptest::prelude::*;
use scanvert::controller::{edges_3d, needs};
use scanvert::display_list::{DisplayList, MAGIC};
use scanvert::visible::trapezoid::EdgeSlot;
use scanvert_sim::cli::{render_scene, Scene};
use scanvert_sim::text::{self, format_fixed};
use std::path::Path;

/// Frames are kept this small so that a case stays cheap.
const SIDE: u16 = 48;

fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Checks a binary list (or its refusal) and renders what is accepted.
fn check_binary(bytes: &[u8]) -> Result<(), TestCaseError> {
    let list = match DisplayList::new_checked(bytes) {
        Ok(list) => list,
        Err(e) => {
            prop_assert!(
                e.offset <= bytes.len(),
                "{e}: outside the {} bytes",
                bytes.len()
            );
            if bytes.starts_with(&MAGIC) {
                let cli = Scene::from_bytes(Path::new("case.scvl"), bytes.to_vec())
                    .expect_err("the program refuses what the reader refuses");
                prop_assert!(
                    cli.message.contains(&format!("byte offset {}:", e.offset)),
                    "{}",
                    cli.message
                );
            }
            return Ok(());
        }
    };
    // Only small frames are rendered (a valid header found by chance may
    // declare up to 4096 × 4096).
    if list.width() as usize * list.height() as usize > 256 * 256 {
        return Ok(());
    }
    let scene = Scene::from_bytes(Path::new("case.scvl"), bytes.to_vec())
        .map_err(|e| TestCaseError::fail(format!("checked list refused: {e}")))?;
    check_render(&scene, &list, |at| format!("byte offset {at}:"))
}

/// Renders a checked scene through the program's path and checks the
/// result against the list: errors at a command, work bounded.
fn check_render(
    scene: &Scene,
    list: &DisplayList<'_>,
    place: impl Fn(usize) -> String,
) -> Result<(), TestCaseError> {
    let commands = list.commands().count();
    match render_scene(scene) {
        Ok(r) => {
            let s = r.stats;
            prop_assert_eq!(s.commands as usize, commands);
            let frame = list.width() as u64 * list.height() as u64;
            prop_assert!(
                s.pixels <= (commands as u64 + 1) * frame,
                "{} pixels for {commands} commands on {frame}",
                s.pixels
            );
            prop_assert!(s.visible.rows <= list.height() as u32);
        }
        Err(e) => {
            // The message names the place; find the command it names.
            let at = list
                .commands()
                .map(|(offset, _)| offset)
                .find(|&o| e.message.contains(&place(o)));
            prop_assert!(at.is_some(), "{}: names no command of the list", e.message);
            // Memory sized from the scene never runs out; a face of more
            // than 58 vertices is a limit of the format's executor, not of
            // the memory. When a scene command fails, `needs` reports it
            // at that command, as the render does.
            let mut slots = vec![EdgeSlot::EMPTY; edges_3d(list)];
            let sized = needs(list, &mut slots).is_ok();
            let ran_out = sized
                && e.message.contains("this renderer holds")
                && !e.message.contains("vertices of a face");
            // ("vertices of a face after clipping" contains it too.)
            prop_assert!(
                !ran_out && !e.message.contains("not supported"),
                "memory sized from the scene ran out: {}",
                e.message
            );
        }
    }
    Ok(())
}

/// Checks a text scene (or its refusal) and renders what is accepted.
fn check_text(src: &str) -> Result<(), TestCaseError> {
    let raw = src.as_bytes();
    let lines = raw.split(|&b| b == b'\n').count();
    match text::assemble(src) {
        Err(e) => {
            prop_assert!(
                (1..=lines).contains(&e.line),
                "line {} of {lines}: {e}",
                e.line
            );
            let cli = Scene::from_bytes(Path::new("case.dl"), raw.to_vec())
                .expect_err("the program refuses what the assembler refuses");
            prop_assert!(
                cli.message.contains(&format!("line {}:", e.line)),
                "{}",
                cli.message
            );
        }
        Ok(asm) => {
            let list = DisplayList::new_checked(&asm.bytes)
                .map_err(|e| TestCaseError::fail(format!("assembled list refused: {e}")))?;
            let scene = Scene::from_bytes(Path::new("case.dl"), raw.to_vec())
                .map_err(|e| TestCaseError::fail(format!("assembled scene refused: {e}")))?;
            // Render errors are named by line: the line of the command.
            let line_of = |at| {
                let line = asm.line_of(at).expect("a command has a line");
                format!("line {line}:")
            };
            for (offset, _) in list.commands() {
                let line = asm.line_of(offset).expect("a command has a line");
                prop_assert!((1..=lines).contains(&line));
            }
            check_render(&scene, &list, line_of)?;
        }
    }
    Ok(())
}

/// A valid header for a `w × h` frame and `body`.
fn with_header(version: u16, w: u16, h: u16, body: &[u8]) -> Vec<u8> {
    let mut b = MAGIC.to_vec();
    b.extend_from_slice(&version.to_le_bytes());
    b.extend_from_slice(&w.to_le_bytes());
    b.extend_from_slice(&h.to_le_bytes());
    b.extend_from_slice(&0u16.to_le_bytes());
    b.extend_from_slice(&(body.len() as u32).to_le_bytes());
    b.extend_from_slice(body);
    b
}

/// One binary command: a known opcode (now and then any byte) and operand
/// bytes of the size it takes, with arbitrary values (counts kept small
/// and sometimes lying).
fn binary_command() -> impl Strategy<Value = Vec<u8>> {
    let fixed = prop::sample::select(vec![
        (0x01u8, 3usize),
        (0x02, 8),
        (0x03, 3),
        (0x20, 2),
        (0x21, 10),
        (0x22, 12),
        (0x23, 16),
        (0x24, 13),
        (0x25, 2),
        (0x26, 0),
        (0x27, 0),
        (0x28, 12),
        (0x29, 3),
        (0x2a, 12),
    ])
    .prop_flat_map(|(op, n)| {
        prop::collection::vec(any::<u8>(), n).prop_map(move |mut v| {
            v.insert(0, op);
            v
        })
    });
    let counted = (
        prop::sample::select(vec![(0x10u8, 4usize), (0x11, 6), (0x30, 12)]),
        0u16..8,
        -1i32..=1,
    )
        .prop_flat_map(|((op, size), n, lie)| {
            let bytes = size * n as usize;
            prop::collection::vec(any::<u8>(), bytes).prop_map(move |v| {
                let mut c = vec![op];
                c.extend_from_slice(&((n as i32 + lie).max(0) as u16).to_le_bytes());
                c.extend_from_slice(&v);
                c
            })
        });
    let label = (
        prop::collection::vec(any::<u8>(), 12),
        0u8..12,
        any::<bool>(),
    )
        .prop_map(|(at, len, printable)| {
            let mut c = vec![0x31];
            c.extend_from_slice(&at);
            c.push(len);
            c.extend((0..len).map(|k| if printable { b'a' + k } else { 0x7f }));
            c
        });
    prop_oneof![
        8 => fixed,
        6 => counted,
        2 => label,
        1 => prop::collection::vec(any::<u8>(), 1..4),
    ]
}

// --- the text form, structurally ---------------------------------------

/// A coordinate in sixteenths: mostly near the frame, sometimes anywhere
/// in Q12.4.
fn coord() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => (-16 * 16..(SIDE as i64 + 16) * 16).prop_map(|v| format_fixed(v, 4)),
        1 => (i16::MIN as i64..=i16::MAX as i64).prop_map(|v| format_fixed(v, 4)),
    ]
}

/// A world value: mostly small, now and then anywhere in Q16.16.
fn world() -> impl Strategy<Value = String> {
    prop_oneof![
        40 => (-10 * 65536..10 * 65536i64).prop_map(|v| format_fixed(v, 16)),
        1 => (i32::MIN as i64..=i32::MAX as i64).prop_map(|v| format_fixed(v, 16)),
    ]
}

fn angle() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => (-720i64..720).prop_map(|d| d.to_string()),
        1 => (-(32768i64 << 16)..(32768i64 << 16)).prop_map(|v| format_fixed(v, 16)),
    ]
}

fn words<S: Strategy<Value = String>>(s: S, n: usize) -> impl Strategy<Value = String> {
    prop::collection::vec(s, n).prop_map(|v| v.join(" "))
}

fn colour() -> impl Strategy<Value = String> {
    any::<[u8; 3]>().prop_map(|c| format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]))
}

/// Printable ASCII but `#` (which starts a comment), words joined by
/// single spaces.
fn label_text() -> impl Strategy<Value = String> {
    "[a-zA-Z0-9!-\"$-~]{1,12}( [a-z]{1,6}){0,2}"
}

/// A line the assembler refuses, or that fails when rendered.
fn bad_line() -> impl Strategy<Value = String> {
    prop::sample::select(vec![
        "poly 0 0 2048 0 0 4",
        "poly 0 0 -2048.0625 0 0 4",
        "poly 0 0 1e3 0 0 4",
        "poly 0 0 nan 0 0 4",
        "poly 0 0 --1 0 0 4",
        "poly 0 0 . 0 0 4",
        "poly 0 0 4 4",
        "poly3 0 0 0 4 4 4 8 0",
        "translate 32768 0 0",
        "scale -32768.0001 1 1",
        "face x 0 0",
        "face",
        "clear #12345",
        "color red",
        "color #gg0000",
        "clear #",
        "label 0 0 0",
        "light 1 1 1 101",
        "thickness -1",
        "rotate w 10",
        "segment 65536",
        "lookat 1 2 3 1 2 3",
        "clip 0 0 32768 4",
        "frame 8 8",
        "pop",
        "perspective 0 1 100",
        "perspective 60 0 100",
        "ortho 0 1 100",
        "ortho 4 10 1",
        "light 0 0 0 50",
        "scale 30000 30000 30000",
        "frob 1 2 3",
        "poly3",
        "\u{ff} 1 2",
    ])
    .prop_map(String::from)
}

/// One line of the text form.
fn text_command() -> impl Strategy<Value = String> {
    let clip = -8i32..(SIDE as i32 + 8);
    prop_oneof![
        2 => colour().prop_map(|c| format!("clear {c}")),
        4 => colour().prop_map(|c| format!("color {c}")),
        2 => (clip.clone(), clip.clone(), clip.clone(), clip).prop_map(|(a, b, c, d)| format!("clip {a} {b} {c} {d}")),
        5 => (3usize..8).prop_flat_map(|n| words(coord(), 2 * n)).prop_map(|v| format!("poly {v}")),
        5 => (3usize..6).prop_flat_map(|n| words(coord(), 3 * n)).prop_map(|v| format!("poly3 {v}")),
        2 => (0u32..65536).prop_map(|id| format!("segment {id}")),
        1 => (1u32..180, 1u32..100, 1u32..2000).prop_map(|(a, n, f)| format!("perspective {a} {} {}", format_fixed(n as i64, 3), n + f)),
        1 => (1u32..200, 1u32..100, 1u32..2000).prop_map(|(k, n, f)| format!("ortho {} {} {}", format_fixed(k as i64, 3), format_fixed(n as i64, 3), n + f)),
        1 => (words(world(), 3), angle(), angle()).prop_map(|(p, y, q)| format!("view {p} {y} {q}")),
        1 => words(world(), 6).prop_map(|v| format!("lookat {v}")),
        1 => (words(world(), 3), 0u32..=110).prop_map(|(p, k)| format!("light {p} {k}")),
        1 => (0i64..32 * 16).prop_map(|t| format!("thickness {}", format_fixed(t, 4))),
        2 => Just("push".to_string()),
        1 => Just("pop".to_string()),
        2 => words(world(), 3).prop_map(|v| format!("translate {v}")),
        2 => (prop::sample::select(vec!["x", "y", "z"]), angle()).prop_map(|(a, d)| format!("rotate {a} {d}")),
        1 => words(world(), 3).prop_map(|v| format!("scale {v}")),
        6 => (1usize..8).prop_flat_map(|n| words(world(), 3 * n)).prop_map(|v| format!("face {v}")),
        2 => (words(world(), 3), label_text()).prop_map(|(p, t)| format!("label {p} {t}")),
    ]
}

/// A scene of the text form: a `frame` line (now and then a bad one),
/// commands, comments and blank lines, and in half of the scenes one
/// line that is refused or fails.
fn text_scene() -> impl Strategy<Value = String> {
    let frame = prop_oneof![
        12 => (1u16..=SIDE, 1u16..=SIDE).prop_map(|(w, h)| format!("frame {w} {h}")),
        1 => prop::sample::select(vec!["frame 0 4", "frame 4", "frame 4097 1", "clear #000000"]).prop_map(String::from),
    ];
    let line = prop_oneof![
        12 => text_command(),
        1 => Just(String::new()),
        1 => Just("# a comment".to_string()),
    ];
    let bad = prop::option::of((any::<prop::sample::Index>(), bad_line()));
    (frame, prop::collection::vec(line, 0..24), bad).prop_map(|(f, mut lines, bad)| {
        if let Some((at, line)) = bad {
            lines.insert(at.index(lines.len() + 1), line);
        }
        std::iter::once(f)
            .chain(lines)
            .collect::<Vec<_>>()
            .join("\n")
    })
}

/// The 3D scene in particular: a projection and a camera, a light, then
/// segments of transformed faces, points, lines and labels.
fn scene_3d() -> impl Strategy<Value = String> {
    let eye = (-200i32..200, -200i32..200, 100i32..400);
    let body = prop::collection::vec(
        prop_oneof![
            4 => (1usize..6).prop_flat_map(|n| words((-3 * 65536..3 * 65536i64).prop_map(|v| format_fixed(v, 16)), 3 * n)).prop_map(|v| format!("face {v}")),
            1 => (0u32..4).prop_map(|s| format!("segment {s}")),
            1 => Just("push".to_string()),
            1 => Just("pop".to_string()),
            1 => (prop::sample::select(vec!["x", "y", "z"]), -360i32..360).prop_map(|(a, d)| format!("rotate {a} {d}")),
            1 => (-4i32..4, -4i32..4, -4i32..4).prop_map(|(x, y, z)| format!("translate {x} {y} {z}")),
            1 => (1i32..4, 1i32..4, 1i32..4).prop_map(|(x, y, z)| format!("scale {x} {y} {z}")),
            1 => any::<[u8; 3]>().prop_map(|c| format!("color #{:02x}{:02x}{:02x}", c[0], c[1], c[2])),
            1 => (0u32..40).prop_map(|t| format!("thickness {}", format_fixed(t as i64, 4))),
            1 => "[a-z]{1,8}".prop_map(|t| format!("label 0 1 0 {t}")),
        ],
        1..20,
    );
    (1u16..=SIDE, 1u16..=SIDE, any::<bool>(), eye, 0u32..=100, body).prop_map(
        |(w, h, ortho, (x, y, z), light, body)| {
            let projection = if ortho {
                "ortho 4 1 1000"
            } else {
                "perspective 60 1 1000"
            };
            let mut s = format!(
                "frame {w} {h}\nclear #000000\n{projection}\nlookat {} {} {} 0 0 0\nlight 1 2 3 {light}\nsegment 1\n",
                format_fixed(x as i64, 4),
                format_fixed(y as i64, 4),
                format_fixed(z as i64, 4)
            );
            s.push_str(&body.join("\n"));
            s
        },
    )
}

proptest! {
    #![proptest_config(cases(400))]

    /// Any bytes at all: mostly refused by the magic, and through the
    /// program, as text, refused with a line or accepted.
    #[test]
    fn arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
        check_binary(&bytes)?;
        if !bytes.starts_with(&MAGIC) {
            let lines = bytes.split(|&b| b == b'\n').count();
            match text::assemble_bytes(&bytes) {
                Err(e) => prop_assert!((1..=lines).contains(&e.line), "{e}"),
                Ok(asm) => prop_assert!(DisplayList::new_checked(&asm.bytes).is_ok()),
            }
        }
    }

    /// The magic, then anything: the header's checks.
    #[test]
    fn bytes_after_the_magic(rest in prop::collection::vec(any::<u8>(), 0..64)) {
        let mut bytes = MAGIC.to_vec();
        bytes.extend_from_slice(&rest);
        check_binary(&bytes)?;
    }

    /// A valid header and an arbitrary body.
    #[test]
    fn arbitrary_body(
        version in 0u16..4,
        w in 1u16..=SIDE,
        h in 1u16..=SIDE,
        body in prop::collection::vec(any::<u8>(), 0..200),
    ) {
        check_binary(&with_header(version, w, h, &body))?;
    }

    /// A valid header and a body of commands of the right sizes with
    /// arbitrary operands: most are accepted and rendered.
    #[test]
    fn commands_with_arbitrary_operands(
        version in prop::sample::select(vec![1u16, 2, 2, 2]),
        w in 1u16..=SIDE,
        h in 1u16..=SIDE,
        cmds in prop::collection::vec(binary_command(), 0..16),
        cut in any::<prop::sample::Index>(),
    ) {
        let body = cmds.concat();
        check_binary(&with_header(version, w, h, &body))?;
        // And the same list cut short anywhere.
        let full = with_header(version, w, h, &body);
        check_binary(&full[..cut.index(full.len() + 1)])?;
    }

    /// Well-formed lines of every command, operands now and then out of
    /// range.
    #[test]
    fn structured_text(src in text_scene()) {
        check_text(&src)?;
    }
}

proptest! {
    #![proptest_config(cases(300))]

    /// 3D scenes that mostly render: projections, cameras, transforms,
    /// faces, points, lines and labels.
    #[test]
    fn structured_3d_scenes(src in scene_3d()) {
        check_text(&src)?;
    }
}

/// The generators reach the renderer: a fair share of the structured
/// cases are accepted and drawn (so the properties above are not only
/// about refusals).
#[test]
fn structured_cases_are_mostly_rendered() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let mut rendered = [0usize; 2];
    for _ in 0..100 {
        for (k, src) in [
            text_scene().new_tree(&mut runner).unwrap().current(),
            scene_3d().new_tree(&mut runner).unwrap().current(),
        ]
        .iter()
        .enumerate()
        {
            if let Ok(scene) = Scene::from_bytes(Path::new("case.dl"), src.as_bytes().to_vec()) {
                rendered[k] += render_scene(&scene).is_ok() as usize;
            }
        }
    }
    println!(
        "rendered: {} of 100 text scenes, {} of 100 3D scenes",
        rendered[0], rendered[1]
    );
    assert!(rendered[0] >= 20, "text scenes rendered: {}", rendered[0]);
    assert!(rendered[1] >= 30, "3D scenes rendered: {}", rendered[1]);
}
