//! The binary format's documentation against its one table: every row of
//! the command table in `docs/display-list.md` names an opcode, its
//! text-form name, version and size exactly as
//! `scanvert::display_list::layout` has them, and every opcode has a row.

use scanvert::display_list::layout::Tail;
use scanvert::display_list::Opcode;

#[test]
fn docs_command_table_matches_the_layout() {
    let doc = include_str!("../../docs/display-list.md");
    let section = doc.split("## Binary form").nth(1).expect("binary section");
    let mut seen = Vec::new();
    for row in section.lines().filter(|l| l.starts_with("| `0x")) {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        // "", opcode, command, version, operands, size, ""
        assert_eq!(cells.len(), 7, "{row}");
        let code = u8::from_str_radix(cells[1].trim_matches('`').trim_start_matches("0x"), 16)
            .expect("hex opcode");
        let op = Opcode::from_byte(code).unwrap_or_else(|| panic!("0x{code:02x} is no opcode"));
        assert_eq!(cells[2].trim_matches('`'), op.name(), "{row}");
        assert_eq!(cells[3], op.version().to_string(), "{row}");
        let layout = op.layout();
        let size = cells[5];
        match layout.tail {
            Tail::None => assert_eq!(size, layout.fixed.to_string(), "{row}"),
            Tail::Packed { stride, .. } => {
                assert_eq!(size, format!("{} + {stride}n", layout.fixed), "{row}")
            }
            Tail::Text { .. } => assert_eq!(size, format!("{} + len", layout.fixed), "{row}"),
        }
        seen.push(op);
    }
    let all: Vec<Opcode> = (0..=255u8).filter_map(Opcode::from_byte).collect();
    assert_eq!(seen, all, "one row per opcode, in code order");
}

#[test]
fn only_the_3d_layer_is_3d() {
    let two_d = [
        Opcode::Clear,
        Opcode::Clip,
        Opcode::Color,
        Opcode::Fill,
        Opcode::Poly,
        Opcode::Line,
    ];
    for op in (0..=255u8).filter_map(Opcode::from_byte) {
        assert_eq!(op.is_3d(), !two_d.contains(&op), "{op:?}");
        assert_eq!(op.is_scene(), op.is_3d() && op != Opcode::Poly3, "{op:?}");
    }
}
