//! Errors name what is wrong: the dialect, the axis, the placeholder, the line.

#![allow(clippy::unwrap_used)]

mod common;

use formcam_nc::{
    AxisSpec, Block, Dialect, Feed, NcError, Program, Template, ToolpathOptions, read_cldata,
    read_gcode, read_gcode_in, read_toolpath, write, write_template,
};

#[test]
fn unknown_dialect_lists_the_allowed_ones() {
    let e = Dialect::from_name("heidenhain").unwrap_err();
    let m = e.to_string();
    assert!(m.contains("`heidenhain`"), "{m}");
    for n in Dialect::NAMES {
        assert!(m.contains(n), "{m}");
    }
}

fn on_axes(names: &[&str]) -> Program {
    let mut p = Program::new("P", names.iter().map(|n| AxisSpec::linear(*n)).collect());
    p.blocks.push(Block::rapid(vec![0.0; names.len()]));
    p
}

#[test]
fn axes_a_dialect_cannot_address() {
    let cases = [
        (Dialect::LinuxCnc, &["X", "J1"][..], "J1"),
        (Dialect::Iso, &["X", "Q"][..], "Q"),
        (Dialect::MarlinXab, &["X", "U"][..], "U"),
        (Dialect::Sinumerik840d, &["X", "F"][..], "F"),
        (Dialect::Sinumerik840d, &["X", "j-1"][..], "j-1"),
    ];
    for (d, axes, bad) in cases {
        let mut out = String::new();
        let e = write(&on_axes(axes), d, &mut out).unwrap_err();
        let m = e.to_string();
        assert!(matches!(e, NcError::UnsupportedAxis { .. }), "{m}");
        assert!(
            m.contains(&format!("`{bad}`")) && m.contains(d.name()),
            "{m}"
        );
        assert!(out.is_empty());
    }
    // CLDATA and Sinumerik identifiers take any such name.
    let mut out = String::new();
    write(&on_axes(&["X", "J1"]), Dialect::Sinumerik840d, &mut out).unwrap();
    write(&on_axes(&["X", "J1"]), Dialect::Cldata, &mut out).unwrap();
}

#[test]
fn inconsistent_programs() {
    let mut p = on_axes(&["X", "Y"]);
    p.blocks
        .push(Block::linear(vec![1.0], Feed::PerMinute(100.0)));
    let e = write(&p, Dialect::LinuxCnc, &mut String::new()).unwrap_err();
    assert!(e.to_string().contains("block 1"), "{e}");

    let mut p = on_axes(&["X", "Y"]);
    p.blocks
        .push(Block::linear(vec![1.0, f64::NAN], Feed::PerMinute(100.0)));
    let e = write(&p, Dialect::Cldata, &mut String::new()).unwrap_err();
    assert!(e.to_string().contains("axis Y"), "{e}");

    let mut p = on_axes(&["X", "Y"]);
    p.blocks
        .push(Block::linear(vec![1.0, 2.0], Feed::InverseTime(0.0)));
    assert!(write(&p, Dialect::Iso, &mut String::new()).is_err());

    let p = on_axes(&["X", "X"]);
    let e = write(&p, Dialect::Iso, &mut String::new()).unwrap_err();
    assert!(e.to_string().contains("twice"), "{e}");
}

#[test]
fn template_unknown_placeholder() {
    let e = Template::from_toml("extension = \"x\"\nblock = \"L {axes} {feed}\"").unwrap_err();
    let m = e.to_string();
    assert!(m.contains("{feed}") && m.contains("`block`"), "{m}");
    assert!(!m.contains('\n'), "one line: {m}");

    // A block placeholder in the header.
    let e =
        Template::from_toml("extension = \"x\"\nheader = \"{f}\"\nblock = \"{axes}\"").unwrap_err();
    let m = e.to_string();
    assert!(m.contains("{f}") && m.contains("`header`"), "{m}");

    // Lower-case names are not axes.
    let e = Template::from_toml("extension = \"x\"\nblock = \"{x}\"").unwrap_err();
    assert!(e.to_string().contains("{x}"));

    // With axis_letters, only its keys are axis placeholders.
    let e = Template::from_toml("extension = \"x\"\nblock = \"{Z}\"\naxis_letters = { X = \"X\" }")
        .unwrap_err();
    assert!(e.to_string().contains("{Z}"));

    // An axis the program does not have: when writing.
    let t = Template::from_toml("extension = \"x\"\nrapid = \"{W}\"\nblock = \"{X}\"").unwrap();
    let e = write_template(&common::xayb(), &t, &mut String::new()).unwrap_err();
    let m = e.to_string();
    assert!(m.contains("{W}") && m.contains("`rapid`"), "{m}");

    // Not TOML, a missing field, an unclosed brace.
    assert!(Template::from_toml("extension = ").is_err());
    let e = Template::from_toml("extension = \"x\"").unwrap_err();
    assert!(e.to_string().contains("block"), "{e}");
    let e = Template::from_toml("extension = \"x\"\nblock = \"{axes\"").unwrap_err();
    assert!(e.to_string().contains("`block`"), "{e}");
}

fn line_of(e: NcError) -> usize {
    match e {
        NcError::Parse { line, .. } => line,
        e => panic!("not a parse error: {e}"),
    }
}

#[test]
fn unreadable_gcode_lines() {
    let axes = [AxisSpec::linear("X"), AxisSpec::rotary("A")];
    let cases = [
        ("G0 X0 A0\nG1 X10 F100\nG1 X# A3\n", 3),
        ("G0 X0 A0\nG1 X10 Y5 F100\n", 2),
        ("G21\n\nX10\n", 3),
        ("G0 X0\nG2 X1 A0 I1\n", 2),
        ("G0 X0\nG93 G1 X4\n", 2),
        ("G0 X0\nG1 X4\n", 2),
        ("G20\n", 1),
        ("N10 G0 X0\nN20 G1 Q1=4 F10\n", 2),
        ("N10 G0 X0\nN20 G1 A=four F10\n", 2),
    ];
    for (text, line) in cases {
        let e = read_gcode(text, &axes).unwrap_err();
        let m = e.to_string();
        assert!(m.starts_with(&format!("line {line}:")), "{text:?}: {m}");
        assert_eq!(line_of(e), line);
    }
}

#[test]
fn unreadable_cldata_lines() {
    let axes = [AxisSpec::linear("X"), AxisSpec::rotary("A")];
    let cases = [
        ("PARTNO/P\nUNITS/MM\nRAPID\nGOTO/1,2,3\n", 4),
        ("PARTNO/P\nGOTO/1,2\n", 2),
        ("UNITS/INCHES\n", 1),
        ("FEDRAT/100,IPM\n", 1),
        ("FEDRAT/1e3\nGOTO/1,x\n", 2),
    ];
    for (text, line) in cases {
        let e = read_cldata(text, &axes).unwrap_err();
        assert_eq!(line_of(e.clone()), line, "{text:?}: {e}");
    }
}

/// A line of 10 MB with ESC and NUL bytes in it.
fn hostile_line() -> String {
    format!("G1 X1 \u{1b}[2J\0{} F100", "Q#".repeat(5 << 20))
}

/// A message short enough to read, with no raw control character.
fn assert_short_and_escaped(m: &str) {
    assert!(m.chars().count() < 400, "{} characters", m.chars().count());
    assert!(!m.chars().any(char::is_control), "{m:?}");
    assert!(m.contains("\\u{1b}[2J\\0"), "{m}");
    assert!(m.contains('…'), "{m}");
}

#[test]
fn a_huge_gcode_line_is_quoted_short_and_escaped() {
    let text = format!("G0 X0\n{}\n", hostile_line());
    let axes = [AxisSpec::linear("X")];
    let e = read_gcode(&text, &axes).unwrap_err();
    assert_eq!(line_of(e.clone()), 2);
    assert_short_and_escaped(&e.to_string());
    let e = read_toolpath(&text, &ToolpathOptions::default()).unwrap_err();
    assert_eq!(line_of(e.clone()), 2);
    assert_short_and_escaped(&e.to_string());
}

#[test]
fn a_template_cut_after_its_equals_sign_says_a_value_is_expected() {
    for text in ["extension = \"x\"\nblock =", "extension = \"x\"\nblock =\n"] {
        let e = Template::from_toml(text).unwrap_err();
        let m = e.to_string();
        let said = m.split_once("line 2:").map(|(_, said)| said.trim());
        assert!(said.is_some_and(|s| s.len() > 5), "{m}");
    }
    let e = Template::from_toml("extension = \"x\0\"\n").unwrap_err();
    assert!(!e.to_string().ends_with(": "), "{e}");
    assert!(!e.to_string().contains('\0'), "{e}");
}

#[test]
fn a_template_extension_is_a_plain_word_and_its_line_numbers_advance() {
    for ext in [".h", "", "h/../x", "n c"] {
        let text = format!("extension = \"{ext}\"\nblock = \"{{axes}}\"");
        let e = Template::from_toml(&text).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("extension = ") && m.contains("without the dot"),
            "{m}"
        );
    }
    for ext in ["h", "nc", "mpf", "p_1-b"] {
        let text = format!("extension = \"{ext}\"\nblock = \"{{axes}}\"");
        assert_eq!(Template::from_toml(&text).unwrap().extension(), ext);
    }
    let steps = "extension = \"h\"\nblock = \"{axes}\"\nline_numbers = { start = 0, step = 0 }";
    let e = Template::from_toml(steps).unwrap_err();
    assert!(
        e.to_string()
            .contains("line_numbers.step = 0: allowed >= 1"),
        "{e}"
    );
    assert!(Template::from_toml(&steps.replace("step = 0", "step = 1")).is_ok());
}

#[test]
fn template_decimals_outside_0_to_9_name_the_field_the_range_and_the_value() {
    for (field, value) in [
        ("decimals_mm", "-1"),
        ("decimals_deg", "-4"),
        ("decimals_mm", "10"),
        ("decimals_deg", "4294967296"),
    ] {
        let text = format!("extension = \"h\"\nblock = \"{{axes}}\"\n{field} = {value}\n");
        let e = Template::from_toml(&text).unwrap_err().to_string();
        assert_eq!(
            e,
            format!("template: {field} = {value}: allowed 0 to 9 (decimals)"),
            "{text}"
        );
    }
    for d in [0, 9] {
        let text = format!("extension = \"h\"\nblock = \"{{axes}}\"\ndecimals_mm = {d}\n");
        assert!(Template::from_toml(&text).is_ok(), "{d}");
    }
}

/// NC words take plain decimals: a number with an exponent, or one too large
/// to be finite, is refused with its line and the word quoted, by every
/// G-code dialect's reader and by the milling (correction) reader.
#[test]
fn exponents_and_non_finite_numbers_are_refused_in_every_gcode_reader() {
    let axes = [AxisSpec::linear("X"), AxisSpec::rotary("A")];
    let huge = format!("X1{}", "0".repeat(400));
    let words = [
        ("X1e400", "exponent"),
        ("X1E5", "exponent"),
        ("X2.5e-3", "exponent"),
        ("X-.5E+2", "exponent"),
        (huge.as_str(), "not finite"),
    ];
    let dialects = [
        Dialect::Sinumerik840d,
        Dialect::Iso,
        Dialect::LinuxCnc,
        Dialect::MarlinXab,
    ];
    for (word, why) in words {
        let text = format!("G0 X0 A0\nG1 {word} F100\n");
        let quoted = format!("`{}", &word[..word.len().min(20)]);
        for d in dialects {
            let e = read_gcode_in(&text, &axes, d).unwrap_err();
            let m = e.to_string();
            assert!(m.contains(why) && m.contains(&quoted), "{d}: {m}");
            assert_eq!(line_of(e), 2, "{d}: {m}");
        }
        let milled = format!("G0 X0 Y0 Z0\nG1 {word} F100\n");
        let e = read_toolpath(&milled, &ToolpathOptions::default()).unwrap_err();
        let m = e.to_string();
        assert!(m.contains(why) && m.contains(&quoted), "toolpath: {m}");
        assert_eq!(line_of(e), 2, "toolpath: {m}");
    }
    // Sinumerik's `NAME=value` and `CR=` take plain decimals too.
    for line in ["G1 A=1e2 F100", "G1 A=ACP(1e2) F100"] {
        let text = format!("N10 G0 X0 A0\nN20 {line}\n");
        let e = read_gcode_in(&text, &axes, Dialect::Sinumerik840d).unwrap_err();
        assert!(e.to_string().contains("exponent"), "{e}");
        assert_eq!(line_of(e), 2);
    }
    let opts = ToolpathOptions {
        dialect: Dialect::Sinumerik840d,
        ..ToolpathOptions::default()
    };
    let e = read_toolpath("G0 X0 Y0 Z0\nG2 X1 Y1 CR=1e1 F100\n", &opts).unwrap_err();
    assert!(e.to_string().contains("exponent"), "{e}");
    assert_eq!(line_of(e), 2);
    // Plain decimals read as before.
    read_gcode_in("G0 X0 A0\nG1 X-.5 A12. F100\n", &axes, Dialect::Iso).unwrap();
}
