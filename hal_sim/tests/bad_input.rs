//! Bad input against the real `scanvert` binary, through the contract
//! `scanvert render SCENE --out IMAGE.png`: every malformed scene, in text
//! or binary form, must exit with a non-zero status that is not the panic
//! status (101), name the place of the fault (`line N` for text,
//! `byte offset N` for binary) on stderr, never print "panicked", and
//! leave no output file behind. Input quoted in a message never reaches
//! the terminal raw: control characters are escaped.

use embedded_graphics_core::pixelcolor::Rgb888;
use scanvert::display_list::{DisplayList, Writer};
use scanvert::fixed::Vertex;
use scanvert::raster::clip::ClipWindow;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Where the fault must be named.
#[derive(Clone, Copy, Debug)]
enum Place {
    /// `line N` with exactly this N.
    Line(usize),
    /// `line N` with any N (a file with no line to blame).
    AnyLine,
    /// `byte offset N` with N in the inclusive range.
    Offset(usize, usize),
    /// Either form: bytes that are neither a valid binary header nor text.
    Either,
}

/// What the binary did with one input.
struct Outcome {
    status: Option<i32>,
    stderr: String,
    leftovers: Vec<PathBuf>,
}

/// A fresh, empty directory for one case.
fn case_dir(test: &str, case: usize) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("bad_input")
        .join(test)
        .join(case.to_string());
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Runs `scanvert render` on `input` written to a file of its own.
fn render(test: &str, case: usize, input: &[u8], ext: &str) -> Outcome {
    let dir = case_dir(test, case);
    let scene = dir.join(format!("scene.{ext}"));
    std::fs::write(&scene, input).expect("write scene");
    let out = dir.join("image.png");
    let result = Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .arg("render")
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run scanvert");
    let leftovers = std::fs::read_dir(&dir)
        .expect("read temp dir")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| *p != scene)
        .collect();
    Outcome {
        status: result.status.code(),
        stderr: String::from_utf8_lossy(&result.stderr).into_owned(),
        leftovers,
    }
}

/// The numbers that follow `key` in `s` (e.g. "line " → [3]).
fn numbers_after(s: &str, key: &str) -> Vec<usize> {
    s.match_indices(key)
        .filter_map(|(i, _)| {
            let digits: String = s[i + key.len()..]
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            digits.parse().ok()
        })
        .collect()
}

/// Why `o` breaks the contract for a fault at `place`, if it does.
fn violation(o: &Outcome, place: Place) -> Option<String> {
    match o.status {
        Some(0) => return Some("exited with status 0".into()),
        Some(101) => return Some("exited with the panic status 101".into()),
        None => return Some("killed by a signal".into()),
        Some(_) => {}
    }
    if o.stderr.contains("panicked") {
        return Some("stderr says \"panicked\"".into());
    }
    if !o.leftovers.is_empty() {
        return Some(format!("left files behind: {:?}", o.leftovers));
    }
    let lines = numbers_after(&o.stderr, "line ");
    let offsets = numbers_after(&o.stderr, "byte offset ");
    let ok = match place {
        Place::Line(n) => lines.contains(&n),
        Place::AnyLine => !lines.is_empty(),
        Place::Offset(lo, hi) => offsets.iter().any(|o| (lo..=hi).contains(o)),
        Place::Either => !lines.is_empty() || !offsets.is_empty(),
    };
    (!ok).then(|| format!("stderr does not name {place:?}"))
}

/// Runs every case and fails once, listing every case that broke the
/// contract.
fn check_all(test: &str, ext: &str, cases: &[(String, Vec<u8>, Place)]) {
    let mut failures = Vec::new();
    for (k, (what, input, place)) in cases.iter().enumerate() {
        let o = render(test, k, input, ext);
        if let Some(why) = violation(&o, *place) {
            failures.push(format!(
                "{what}: {why}\n    stderr: {}",
                o.stderr.trim_end()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases break the contract:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
    let _ = std::fs::remove_dir_all(
        Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join("bad_input")
            .join(test),
    );
}

fn text_case(what: &str, text: &str, line: usize) -> (String, Vec<u8>, Place) {
    (
        what.to_string(),
        text.as_bytes().to_vec(),
        Place::Line(line),
    )
}

/// A valid text scene, as a prefix for the cases.
const HEAD: &str = "frame 64 48\nclear #000000\ncolor #ff8000\n";

#[test]
fn valid_scenes_render_so_the_rejections_below_mean_something() {
    let o = render(
        "valid",
        0,
        format!("{HEAD}poly 1 1  60 5.5  20 40\n").as_bytes(),
        "dl",
    );
    assert_eq!(o.status, Some(0), "text scene: {}", o.stderr);
    assert_eq!(o.leftovers.len(), 1, "one image written");
    let o = render("valid", 1, &valid_binary(), "scvl");
    assert_eq!(o.status, Some(0), "binary scene: {}", o.stderr);
    assert_eq!(o.leftovers.len(), 1, "one image written");
}

#[test]
fn malformed_text_scenes_are_rejected_with_their_line() {
    let p = |body: &str| format!("{HEAD}{body}\n");
    let mut cases = vec![
        text_case("truncated frame", "frame 64\n", 1),
        text_case("frame without numbers", "frame\n", 1),
        text_case("truncated clip", &p("clip 1 2 3"), 4),
        text_case("colour without value", &p("color"), 4),
        text_case("short colour", &p("color #12345"), 4),
        text_case("long colour", &p("color #1234567"), 4),
        text_case("colour without #", &p("color 123456"), 4),
        text_case("colour not hex", &p("clear #12345g"), 4),
        text_case("wrong first command", "color #ffffff\nframe 64 48\n", 1),
        text_case("poly before frame", "poly 0 0 1 1 2 2\n", 1),
        text_case(
            "wrong first command after comments",
            "# a scene\n\n   \ncolor #ffffff\n",
            4,
        ),
        text_case("unknown command", &p("fill 1 2 3"), 4),
        text_case(
            "unknown command among good ones",
            &format!("{HEAD}poly 0 0 9 0 9 9\nrect 0 0 4 4\npoly 1 1 2 1 2 2\n"),
            5,
        ),
        text_case("word in place of a number", &p("poly 0 0 one 1 2 2"), 4),
        text_case("frame size not a number", "frame sixty 48\n", 1),
        text_case("clip not a number", &p("clip a b c d"), 4),
        text_case("number with junk", &p("poly 0 0 1x 1 2 2"), 4),
        text_case("two signs", &p("poly 0 0 --1 1 2 2"), 4),
        text_case("lone sign", &p("poly 0 0 - 1 2 2"), 4),
        text_case("lone point", &p("poly 0 0 . 1 2 2"), 4),
        text_case("nan", &p("poly 0 0 nan 1 2 2"), 4),
        text_case("NaN", &p("poly 0 0 NaN 1 2 2"), 4),
        text_case("inf", &p("poly 0 0 inf 1 2 2"), 4),
        text_case("-inf", &p("poly 0 0 -inf 1 2 2"), 4),
        text_case("infinity", &p("poly 0 0 infinity 1 2 2"), 4),
        text_case("nan frame", "frame nan 48\n", 1),
        text_case("exponent", &p("poly 0 0 1e5 1 2 2"), 4),
        text_case("exponent in frame", "frame 1e3 48\n", 1),
        text_case("coordinate 2048", &p("poly 0 0 2048 1 2 2"), 4),
        text_case("coordinate -2048.0625", &p("poly 0 0 -2048.0625 1 2 2"), 4),
        text_case("coordinate 99999", &p("poly 0 0 99999 1 2 2"), 4),
        text_case(
            "coordinate beyond i64",
            &p("poly 0 0 123456789012345678901234567890 1 2 2"),
            4,
        ),
        text_case("frame width 0", "frame 0 48\n", 1),
        text_case("frame height 4097", "frame 64 4097\n", 1),
        text_case("negative frame", "frame -64 48\n", 1),
        text_case("fractional frame", "frame 64.5 48\n", 1),
        text_case("frame with an extra number", "frame 64 48 2\n", 1),
        text_case("clip beyond i16", &p("clip 0 0 40000 10"), 4),
        text_case("fractional clip", &p("clip 0 0 10.5 10"), 4),
        text_case("clear with an extra word", &p("clear #000000 7"), 4),
        text_case("odd coordinate count", &p("poly 0 0 10 0 10 10 5"), 4),
        text_case("odd count of one", &p("poly 7"), 4),
        text_case("poly without vertices", &p("poly"), 4),
        text_case("one vertex", &p("poly 0 0"), 4),
        text_case("two vertices", &p("poly 0 0 10 10"), 4),
        text_case("poly3 with two vertices", &p("poly3 0 0 1 10 10 1"), 4),
        text_case(
            "poly3 with a coordinate count not a multiple of 3",
            &p("poly3 0 0 1 10 10 1 5 5"),
            4,
        ),
        text_case(
            "error on a late line",
            &format!("{HEAD}{}poly 0 0 1 1 2\n", "poly 0 0 9 0 9 9\n".repeat(20)),
            24,
        ),
        text_case("empty file", "", 1),
        text_case("only comments and blank lines", "# nothing\n\n# here\n", 1),
    ];
    // "empty file" and "only comments" have no command to blame: any line.
    for c in cases
        .iter_mut()
        .filter(|c| c.0 == "empty file" || c.0 == "only comments and blank lines")
    {
        c.2 = Place::AnyLine;
    }
    // A line of 200,000 numbers: 100,000 vertices, more than a polygon of
    // the display list holds (65,535).
    let mut long = String::from(HEAD);
    long.push_str("poly");
    for k in 0..200_000u32 {
        long.push_str(if k % 2 == 0 { " 1.5" } else { " -2" });
    }
    long.push('\n');
    cases.push(text_case("a line of 200,000 numbers", &long, 4));
    // Bytes that are not UTF-8, in a command and in the first line.
    let mut bad = HEAD.as_bytes().to_vec();
    bad.extend_from_slice(b"color #ff\xff\xfe00\n");
    cases.push(("non-UTF-8 in a colour".into(), bad, Place::Line(4)));
    let mut bad = HEAD.as_bytes().to_vec();
    bad.extend_from_slice(b"poly 0 0 1\xc3 1 2 2\n");
    cases.push((
        "truncated UTF-8 sequence in a number".into(),
        bad,
        Place::Line(4),
    ));
    cases.push((
        "non-UTF-8 first line".into(),
        b"fr\xe4me 64 48\n".to_vec(),
        Place::Line(1),
    ));
    check_all("text", "dl", &cases);
}

/// A valid binary list: header, clear, clip, colour, a triangle and a
/// quadrilateral.
fn valid_binary() -> Vec<u8> {
    let mut buf = [0u8; 256];
    let mut w = Writer::new(&mut buf, 64, 48).unwrap();
    let v = |x: i16, y: i16| Vertex::from_bits(x * 16, y * 16);
    w.clear(Rgb888::new(0, 0, 0)).unwrap();
    w.clip(ClipWindow {
        x0: 1,
        y0: 1,
        x1: 60,
        y1: 40,
    })
    .unwrap();
    w.color(Rgb888::new(255, 128, 0)).unwrap();
    w.poly([v(1, 1), v(60, 5), v(20, 40)]).unwrap();
    w.poly([v(30, 2), v(50, 2), v(50, 20), v(30, 20)]).unwrap();
    w.finish().to_vec()
}

/// Offsets of the commands of [`valid_binary`] (after the 16-byte header).
const CLEAR_AT: usize = 16;
const CLIP_AT: usize = CLEAR_AT + 4;
const COLOR_AT: usize = CLIP_AT + 9;
const TRI_AT: usize = COLOR_AT + 4;
const QUAD_AT: usize = TRI_AT + 3 + 4 * 3;
const END: usize = QUAD_AT + 3 + 4 * 4;

/// Sets the header's body length to what follows the header.
fn restamp(mut b: Vec<u8>) -> Vec<u8> {
    let body = (b.len() - 16) as u32;
    b[12..16].copy_from_slice(&body.to_le_bytes());
    b
}

/// A binary case; panics if the library itself would accept the bytes
/// (the case would be mislabelled, not the program wrong).
fn bin_case(what: impl Into<String>, bytes: Vec<u8>, place: Place) -> (String, Vec<u8>, Place) {
    let what = what.into();
    assert!(
        DisplayList::new_checked(&bytes).is_err(),
        "test case \"{what}\" is a valid list"
    );
    (what, bytes, place)
}

#[test]
fn the_valid_binary_list_is_laid_out_as_these_tests_assume() {
    let b = valid_binary();
    assert_eq!(b.len(), END);
    assert_eq!(
        [b[CLEAR_AT], b[CLIP_AT], b[COLOR_AT], b[TRI_AT], b[QUAD_AT]],
        [0x01, 0x02, 0x03, 0x10, 0x10]
    );
}

#[test]
fn truncated_binary_lists_are_rejected_with_a_byte_offset() {
    let good = valid_binary();
    let mut cases = Vec::new();
    for len in 0..good.len() {
        let cut = good[..len].to_vec();
        // Shorter than the magic, the bytes cannot be told from text.
        let place = if len < 4 {
            Place::Either
        } else {
            Place::Offset(0, len)
        };
        cases.push(bin_case(format!("cut to {len} bytes"), cut.clone(), place));
        if len > CLEAR_AT && ![CLIP_AT, COLOR_AT, TRI_AT, QUAD_AT].contains(&len) {
            // The header agrees with the cut: the fault is inside the
            // command that was cut (a cut between commands is a valid,
            // shorter list).
            cases.push(bin_case(
                format!("cut to {len} bytes, length restamped"),
                restamp(cut),
                Place::Offset(CLEAR_AT, len),
            ));
        }
    }
    check_all("truncated", "scvl", &cases);
}

#[test]
fn malformed_binary_lists_are_rejected_with_a_byte_offset() {
    let good = valid_binary();
    let with = |at: usize, bytes: &[u8]| {
        let mut b = good.clone();
        b[at..at + bytes.len()].copy_from_slice(bytes);
        b
    };
    let appended = |tail: &[u8]| {
        let mut b = good.clone();
        b.extend_from_slice(tail);
        b
    };
    let inserted = |at: usize, bytes: &[u8]| {
        let mut b = good.clone();
        b.splice(at..at, bytes.iter().copied());
        restamp(b)
    };
    let at = |o: usize| Place::Offset(o, o);
    let cases = vec![
        // Oversized: trailing bytes the header does not count, or counts.
        bin_case(
            "one trailing zero byte",
            appended(&[0]),
            Place::Offset(0, END),
        ),
        bin_case(
            "eight trailing bytes",
            appended(&[0x10; 8]),
            Place::Offset(0, END),
        ),
        bin_case(
            "a trailing zero byte, counted",
            restamp(appended(&[0])),
            at(END),
        ),
        bin_case(
            "a trailing half command, counted",
            restamp(appended(&[0x01, 0xff])),
            at(END),
        ),
        bin_case(
            "a trailing poly header, counted",
            restamp(appended(&[0x10, 3, 0])),
            at(END),
        ),
        // Header.
        bin_case("wrong magic", with(0, b"SCVM"), Place::Either),
        bin_case("magic in lower case", with(0, b"scvl"), Place::Either),
        bin_case("version 0", with(4, &[0, 0]), at(4)),
        bin_case("version 3", with(4, &[3, 0]), at(4)),
        bin_case("version 0xffff", with(4, &[0xff, 0xff]), at(4)),
        bin_case("width 0", with(6, &[0, 0]), Place::Offset(6, 8)),
        bin_case(
            "width 4097",
            with(6, &4097u16.to_le_bytes()),
            Place::Offset(6, 8),
        ),
        bin_case("height 0", with(8, &[0, 0]), Place::Offset(6, 8)),
        bin_case("height 0xffff", with(8, &[0xff, 0xff]), Place::Offset(6, 8)),
        bin_case("reserved field set", with(10, &[1, 0]), at(10)),
        // Counts that lie.
        bin_case(
            "body length one too many",
            with(12, &((END - 16 + 1) as u32).to_le_bytes()),
            Place::Offset(0, END),
        ),
        bin_case(
            "body length one too few",
            with(12, &((END - 16 - 1) as u32).to_le_bytes()),
            Place::Offset(0, END),
        ),
        bin_case(
            "body length 0xffffffff",
            with(12, &[0xff; 4]),
            Place::Offset(0, END),
        ),
        bin_case("poly count 0", with(TRI_AT + 1, &[0, 0]), at(TRI_AT)),
        bin_case("poly count 2", with(TRI_AT + 1, &[2, 0]), at(TRI_AT)),
        bin_case(
            "poly count 4 of 3 vertices",
            with(TRI_AT + 1, &[4, 0]),
            Place::Offset(TRI_AT, END),
        ),
        bin_case(
            "last poly count 5 of 4 vertices",
            with(QUAD_AT + 1, &[5, 0]),
            at(QUAD_AT),
        ),
        bin_case(
            "last poly count 65535",
            with(QUAD_AT + 1, &[0xff, 0xff]),
            at(QUAD_AT),
        ),
        bin_case(
            "poly count 3 of 4 vertices",
            with(QUAD_AT + 1, &[3, 0]),
            Place::Offset(QUAD_AT, END),
        ),
        // Unknown opcodes, at command boundaries and as the first command.
        bin_case("opcode 0x00 first", with(CLEAR_AT, &[0x00]), at(CLEAR_AT)),
        bin_case("opcode 0x04", with(COLOR_AT, &[0x04]), at(COLOR_AT)),
        bin_case("opcode 0x12", with(TRI_AT, &[0x12]), at(TRI_AT)),
        bin_case("opcode 0xff", with(QUAD_AT, &[0xff]), at(QUAD_AT)),
        bin_case(
            "opcode 0x00 inserted",
            inserted(TRI_AT, &[0x00]),
            at(TRI_AT),
        ),
        bin_case(
            "opcode 0x7f inserted",
            inserted(CLIP_AT, &[0x7f, 1, 2, 3]),
            at(CLIP_AT),
        ),
        // A clip opcode where a colour was: its longer operands run into
        // the next command and misalign the rest.
        bin_case(
            "colour opcode turned clip",
            with(COLOR_AT, &[0x02]),
            Place::Offset(COLOR_AT, END),
        ),
        // Version-2 commands: not in a version-1 list, and their operands
        // checked.
        bin_case(
            "a 3D command in a version-1 list",
            restamp(appended(&[0x26])),
            at(END),
        ),
        bin_case(
            "rotate about axis 3",
            v2(restamp(appended(&[0x29, 3, 0, 0]))),
            at(END),
        ),
        bin_case(
            "light of 101 %",
            v2(restamp(appended(&[
                0x24, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 101,
            ]))),
            at(END),
        ),
        bin_case(
            "negative thickness",
            v2(restamp(appended(&[0x25, 0xff, 0xff]))),
            at(END),
        ),
        bin_case(
            "face of no vertex",
            v2(restamp(appended(&[0x30, 0, 0]))),
            at(END),
        ),
        bin_case(
            "face whose count lies",
            v2(restamp(appended(&[0x30, 2, 0, 1, 2, 3]))),
            at(END),
        ),
        bin_case(
            "empty label",
            v2(restamp(appended(&[
                0x31, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
            ]))),
            at(END),
        ),
        bin_case(
            "label with a control character",
            v2(restamp(appended(&[
                0x31, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, b'a', 7,
            ]))),
            at(END),
        ),
        bin_case(
            "label longer than what follows",
            v2(restamp(appended(&[
                0x31, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 200, b'a',
            ]))),
            at(END),
        ),
    ];
    check_all("malformed", "scvl", &cases);
}

/// The list stamped as version 2.
fn v2(mut b: Vec<u8>) -> Vec<u8> {
    b[4] = 2;
    b
}

/// Why `stderr` could act on a terminal, if it could: a byte below 0x20
/// other than the line ends, DEL, a C1 control or a bidi override.
fn unsafe_for_terminal(stderr: &[u8]) -> Option<String> {
    if let Some(b) = stderr
        .iter()
        .find(|&&b| (b < 0x20 && b != b'\n') || b == 0x7f)
    {
        return Some(format!("raw byte {b:#04x}"));
    }
    let text = String::from_utf8_lossy(stderr);
    text.chars()
        .find(|&c| ('\u{80}'..='\u{9f}').contains(&c) || ('\u{202a}'..='\u{202e}').contains(&c))
        .map(|c| format!("raw {c:?}"))
}

/// Runs the binary with `args` and checks that stderr is a non-empty
/// failure message with nothing raw from the input in it.
fn check_escaped(what: &str, args: &[&std::ffi::OsStr], status: i32, failures: &mut Vec<String>) {
    let o = Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .args(args)
        .output()
        .expect("run scanvert");
    let stderr = String::from_utf8_lossy(&o.stderr);
    if o.status.code() != Some(status) {
        failures.push(format!("{what}: status {:?}: {stderr:?}", o.status.code()));
    } else if !stderr.contains('\\') {
        failures.push(format!("{what}: no escape in {stderr:?}"));
    } else if let Some(why) = unsafe_for_terminal(&o.stderr) {
        failures.push(format!("{what}: {why} in {stderr:?}"));
    }
}

#[test]
fn control_characters_from_the_input_are_escaped_in_messages() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    let dir = case_dir("escapes", 0);
    let mut failures = Vec::new();
    let scenes: [(&str, &[u8]); 8] = [
        ("terminal title as the first command", b"\x1b]0;pwned\x07\n"),
        ("unknown command", b"frame 8 8\n\x1b[2J\x1b[31mred\n"),
        ("bad number", b"frame 8 8\npoly 0 0 1\x07 1 2 2\n"),
        ("bad colour with DEL", b"frame 8 8\ncolor #12\x7f456\n"),
        (
            "bad axis with a C1 CSI",
            b"frame 8 8\nrotate \xc2\x9b31m 90\n",
        ),
        (
            "bidi override in a command",
            b"frame 8 8\n\xe2\x80\xaeylop 1 2\n",
        ),
        ("backspace in the frame size", b"frame 8\x08 8\n"),
        ("NUL before the first command", b"\x00frame 8 8\n"),
    ];
    for (k, (what, bytes)) in scenes.iter().enumerate() {
        let scene = dir.join(format!("scene-{k}.dl"));
        std::fs::write(&scene, bytes).expect("write scene");
        let out = dir.join("image.png");
        let args = [
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("--out"),
            out.as_os_str(),
        ];
        check_escaped(what, &args, 1, &mut failures);
    }
    // File names, options, commands and modes of the command line.
    let good = dir.join("good.dl");
    std::fs::write(&good, "frame 8 8\n").expect("write scene");
    let evil_name = dir.join(OsStr::from_bytes(b"no-such-\x1b]0;x\x07.dl"));
    let evil_out = dir.join(OsStr::from_bytes(b"no-dir-\x1b[5m/out.png"));
    let cases: [(&str, Vec<&OsStr>, i32); 5] = [
        (
            "missing input file",
            vec![
                OsStr::new("render"),
                evil_name.as_os_str(),
                OsStr::new("--out"),
                OsStr::new("x.png"),
            ],
            1,
        ),
        (
            "unwritable output file",
            vec![
                OsStr::new("render"),
                good.as_os_str(),
                OsStr::new("--out"),
                evil_out.as_os_str(),
            ],
            3,
        ),
        (
            "unknown command",
            vec![OsStr::from_bytes(b"\x1b[31mrender")],
            2,
        ),
        (
            "unknown option",
            vec![OsStr::new("render"), OsStr::from_bytes(b"--\x1b[31m")],
            2,
        ),
        (
            "unknown timing",
            vec![
                OsStr::new("render"),
                good.as_os_str(),
                OsStr::new("--out"),
                OsStr::new("x.png"),
                OsStr::new("--timing"),
                OsStr::from_bytes(b"\x9b31m\x1b[0m"),
            ],
            2,
        ),
    ];
    for (what, args, status) in &cases {
        check_escaped(what, args, *status, &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let _ = std::fs::remove_dir_all(dir);
}

/// Every line `--stats` prints names the input, escaped as in the error
/// messages, so that no name can drive the terminal.
#[test]
fn stats_lines_escape_the_input_name() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    let dir = case_dir("stats_name", 0);
    let scene = dir.join(OsStr::from_bytes(b"\x1b]0;pwned\x07\x1b[2J.dl"));
    std::fs::write(
        &scene,
        "frame 16 16\npoly 0 0 8 0 8 8\nperspective 50 1 100\nface 0 0 -5\n",
    )
    .expect("write scene");
    let out = dir.join("image.png");
    let o = Command::new(env!("CARGO_BIN_EXE_scanvert"))
        .args([OsStr::new("render"), scene.as_os_str()])
        .args([OsStr::new("--out"), out.as_os_str(), OsStr::new("--stats")])
        .output()
        .expect("run scanvert");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(unsafe_for_terminal(&o.stdout), None, "{stdout:?}");
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 5, "{stdout}");
    for line in lines {
        assert!(
            line.contains(r"\u{1b}]0;pwned\u{7}\u{1b}[2J.dl: "),
            "{line:?}"
        );
    }
    let _ = std::fs::remove_dir_all(dir);
}
