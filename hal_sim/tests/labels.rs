//! Labels in the text form: every label text the binary reader accepts
//! disassembles to text that assembles back to the same bytes (quoted
//! where the bare form would not read back), and the bare form reads as it
//! always did.

use proptest::prelude::*;
use scanvert::display_list::{DisplayList, ErrorKind, Opcode, HEADER_LEN};
use scanvert_sim::text::{assemble, disassemble, TextErrorKind};

/// A version-2 list of a 4 × 4 frame holding one label with `text` at
/// (1, -2, 0.5), built byte by byte so that any text can be tried.
fn list_with_label(text: &[u8]) -> Vec<u8> {
    let mut b = b"SCVL".to_vec();
    b.extend_from_slice(&2u16.to_le_bytes());
    b.extend_from_slice(&4u16.to_le_bytes());
    b.extend_from_slice(&4u16.to_le_bytes());
    b.extend_from_slice(&[0, 0]);
    let body = 14 + text.len() as u32;
    b.extend_from_slice(&body.to_le_bytes());
    b.push(0x31);
    for v in [65536i32, -131072, 32768] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.push(text.len() as u8);
    b.extend_from_slice(text);
    b
}

/// The text of the only label of an assembled scene.
fn label_of(scene: &str) -> Result<String, TextErrorKind> {
    let a = assemble(scene).map_err(|e| e.kind)?;
    let list = DisplayList::new_checked(&a.bytes).expect("assembled lists are valid");
    let text = list
        .commands()
        .find_map(|(_, c)| match c {
            scanvert::display_list::Command::Label { text, .. } => Some(text.to_string()),
            _ => None,
        })
        .expect("a label");
    Ok(text)
}

/// Disassembles `bytes` (a valid list) and assembles the text again.
fn round_trip(bytes: &[u8]) -> Result<(), TestCaseError> {
    let list = DisplayList::new_checked(bytes).expect("valid");
    let text = disassemble(&list);
    let again = assemble(&text).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
    prop_assert_eq!(&again.bytes[..], bytes, "through {}", text);
    Ok(())
}

/// Label texts with many of the characters that matter: quotes,
/// backslashes, `#`, spaces (leading, trailing, doubled), escape-like runs.
fn tricky_text() -> impl Strategy<Value = Vec<u8>> {
    let piece = prop_oneof![
        3 => prop::sample::select(vec![
            b" ".to_vec(), b"  ".to_vec(), b"#".to_vec(), b"\"".to_vec(), b"\\".to_vec(),
            b"\\x41".to_vec(), b"\\x0".to_vec(), b"\\\"".to_vec(), b"\\\\".to_vec(),
            b"\"\"".to_vec(), b"x".to_vec(), b"label".to_vec(), b"color".to_vec(),
            b"#ff0000".to_vec(), b"0".to_vec(),
        ]),
        2 => (0x20u8..0x7f).prop_map(|c| vec![c]),
    ];
    prop::collection::vec(piece, 1..12)
        .prop_map(|v| v.concat())
        .prop_filter("1 to 255 bytes", |t| (1..=255).contains(&t.len()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn every_label_the_reader_accepts_round_trips(text in tricky_text()) {
        let bytes = list_with_label(&text);
        prop_assert!(DisplayList::new_checked(&bytes).is_ok());
        round_trip(&bytes)?;
    }

    #[test]
    fn arbitrary_label_bytes_round_trip_or_are_refused_at_the_label(
        text in prop::collection::vec(any::<u8>(), 0..=255),
    ) {
        let bytes = list_with_label(&text);
        match DisplayList::new_checked(&bytes) {
            Ok(_) => round_trip(&bytes)?,
            Err(e) => {
                prop_assert_eq!(e.offset, HEADER_LEN);
                prop_assert_eq!(e.kind, ErrorKind::BadOperand(Opcode::Label));
            }
        }
    }

    #[test]
    fn printable_ascii_labels_round_trip(text in "[ -~]{1,255}") {
        round_trip(&list_with_label(text.as_bytes()))?;
    }
}

#[test]
fn labels_the_bare_form_cannot_say_are_quoted() {
    for (text, written) in [
        ("a#b", r##""a#b""##),
        (" lead", r#"" lead""#),
        ("trail ", r#""trail ""#),
        ("dou  ble", r#""dou  ble""#),
        (" ", r#"" ""#),
        ("\"hi\"", r#""\"hi\"""#),
        ("\"a\\x41\"", r#""\"a\\x41\"""#),
        ("\"\"", r#""\"\"""#),
    ] {
        let list = list_with_label(text.as_bytes());
        let dis = disassemble(&DisplayList::new_checked(&list).unwrap());
        assert!(dis.ends_with(&format!(" {written}\n")), "{text:?}: {dis}");
        assert_eq!(assemble(&dis).unwrap().bytes, list, "{text:?}");
    }
    // Texts that read back bare stay bare.
    for text in [
        "Amsterdam 24",
        "\"unclosed",
        "say \"hi\"",
        "\"a\" \"b\"",
        "back\\slash",
    ] {
        let list = list_with_label(text.as_bytes());
        let dis = disassemble(&DisplayList::new_checked(&list).unwrap());
        assert!(dis.ends_with(&format!(" {text}\n")), "{text:?}: {dis}");
    }
}

#[test]
fn the_bare_form_reads_as_before() {
    for (line, text) in [
        ("label 0 1 0 Amsterdam 24", "Amsterdam 24"),
        ("label 0 0 0   a \t  b   # a comment", "a b"),
        ("label 0 0 0 a#b", "a"),
        ("label 0 0 0 \"unclosed", "\"unclosed"),
        ("label 0 0 0 \"a\" \"b\"", "\"a\" \"b\""),
        ("label 0 0 0 say \"hi\"", "say \"hi\""),
        ("label 0 0 0 \"bad \\q escape\"", "\"bad \\q escape\""),
        ("label 0 0 0 \"short \\x4\"", "\"short \\x4\""),
        ("label 0 0 0 \"a\"b", "\"a\"b"),
    ] {
        let scene = format!("frame 4 4\n{line}\n");
        assert_eq!(label_of(&scene).as_deref(), Ok(text), "{line}");
    }
}

#[test]
fn the_quoted_form() {
    for (line, text) in [
        ("label 0 0 0 \"a#b\"", "a#b"),
        ("label 0 0 0 \"  x  \"  # the spaces are kept", "  x  "),
        ("label 0 0 0 \" \"", " "),
        ("label 0 0 0 \"\\x41\\x7e\\\\\\\"\"", "A~\\\""),
        ("label 0 0 0 \"\\\"hi\\\"\"\r", "\"hi\""),
        ("label 0 0 0 \"#\"#", "#"),
    ] {
        let scene = format!("frame 4 4\n{line}\n");
        assert_eq!(label_of(&scene).as_deref(), Ok(text), "{line}");
    }
    // A quoted text must still be a label the list can hold.
    for line in [
        "label 0 0 0 \"\"",
        "label 0 0 0 \"\\x07\"",
        "label 0 0 0 \"\\xc3\\xa9\"",
        &format!("label 0 0 0 \"{}\"", "x".repeat(256)),
    ] {
        let scene = format!("frame 4 4\n{line}\n");
        assert_eq!(label_of(&scene), Err(TextErrorKind::Label), "{line}");
    }
}

#[test]
fn disasm_then_asm_through_the_program() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("labels");
    std::fs::create_dir_all(&dir).unwrap();
    let (bin, txt, again) = (
        dir.join("list.scvl"),
        dir.join("list.dl"),
        dir.join("again.scvl"),
    );
    let list = list_with_label(b"  #1 \"best\"  ");
    std::fs::write(&bin, &list).unwrap();
    let run = |args: &[&std::path::Path]| {
        let args: Vec<String> = args
            .iter()
            .map(|a| a.to_str().unwrap().to_string())
            .collect();
        scanvert_sim::cli::run(&args).expect("runs")
    };
    let p = std::path::Path::new;
    run(&[p("disasm"), &bin, p("--out"), &txt]);
    run(&[p("asm"), &txt, p("--out"), &again]);
    assert_eq!(std::fs::read(&again).unwrap(), list);
    assert!(std::fs::read_to_string(&txt)
        .unwrap()
        .contains(r#" "  #1 \"best\"  ""#));
}
