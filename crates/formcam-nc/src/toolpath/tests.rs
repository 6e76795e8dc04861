//! The milling reader and the style-keeping writer together.

#![allow(clippy::unwrap_used)]

use super::*;
use crate::Dialect;

fn read(text: &str) -> Toolpath {
    read_toolpath(text, &ToolpathOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn arbitrary_text_never_panics() {
    // Lines drawn from the characters programs are made of, and some
    // that they are not; every one must be read or refused, and what is
    // read must be written back.
    let alphabet: Vec<char> = "GgXYZIJKRNFMOo0123456789.-+ ()=;%/#[]\"\tØé,CR\r\n"
        .chars()
        .collect();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for _ in 0..20_000 {
        let len = (next() % 40) as usize;
        let text: String = (0..len)
            .map(|_| alphabet[(next() % alphabet.len() as u64) as usize])
            .collect();
        for dialect in [Dialect::Iso, Dialect::Sinumerik840d, Dialect::LinuxCnc] {
            let opts = ToolpathOptions {
                dialect,
                arc_tolerance_mm: 0.01,
                max_segment_mm: Some(0.5),
            };
            let prefixed = format!("G0 X0 Y0 Z0\n{text}\n");
            for t in [text.as_str(), prefixed.as_str()] {
                if let Ok(tp) = read_toolpath(t, &opts) {
                    let pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
                    assert!(tp.write(&pos, &["x".into()]).is_ok(), "{t:?}");
                }
            }
        }
    }
}

#[test]
fn long_feed_moves_are_split_and_written_as_g1_lines() {
    let text = "G90 G0 X0 Y0 Z2\nG1 Z0 F500\nN30 X10. Y0. ; long\nG0 Z5\n";
    let tp = read_toolpath(
        text,
        &ToolpathOptions {
            max_segment_mm: Some(3.0),
            ..ToolpathOptions::default()
        },
    )
    .unwrap();
    assert_eq!(tp.moves_split, 1);
    let xs: Vec<f64> = tp
        .nodes
        .iter()
        .filter(|n| n.line == 3)
        .map(|n| n.position[0])
        .collect();
    assert_eq!(xs, [2.5, 5.0, 7.5, 10.0]);
    let mut pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    pos[3][2] = -0.2; // the second piece's end
    let out = tp.write(&pos, &[]).unwrap();
    assert_eq!(
        out,
        "G90 G0 X0 Y0 Z2\nG1 Z0 F500\nN30 X2.5 Y0. ; long\nG1 X5. Z-0.2\nG1 X7.5 Z0.\nG1 X10.\nG0 Z5\n"
    );
}

#[test]
fn added_lines_follow_the_program_style() {
    // Two-digit G words, no blanks, block delete, plus signs, zero
    // padding, few decimals.
    let text = "N1G90G00X0Y0Z0\n/N2G02X+20.0Y0R10.0F100\nN3G01X030.5\n";
    let tp = read(text);
    let mut pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    let last = pos.len() - 1;
    pos[last][0] -= 0.05;
    let out = tp.write(&pos, &[]).unwrap();
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[1].starts_with("/N2G01X+"), "{out}");
    assert!(lines[2].starts_with("/G01X"), "{out}");
    assert!(!lines[2].contains(' '), "{out}");
    assert_eq!(lines[lines.len() - 1], "N3G01X030.45", "{out}");
}

#[test]
fn homing_forgets_the_position_and_unsupported_forms_are_refused() {
    let tp = read("G0 X0 Y0 Z5\nG1 Z0 F100\nG28\nG1 X30 Y30\n");
    let last = tp.nodes[tp.nodes.len() - 1].position;
    assert!(last[2].is_nan(), "{last:?}");
    let pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    assert!(tp.write(&pos, &[]).unwrap().ends_with("G1 X30 Y30\n"));
    let bad = [
        ("G0 X0 Y0\nG2 X20 Y0 I10 J0 P3\n", "several turns"),
        ("G0 X0 Y0\nG16 G1 X20 Y45\n", "G16"),
        ("G0 X0 Y0\nG1 @20 ^45\n", "polar"),
        ("G0 X0 Y0 Z0\nG93 G1 X40 F2\n", "inverse-time"),
    ];
    for (text, want) in bad {
        let e = read_toolpath(
            text,
            &ToolpathOptions {
                dialect: Dialect::LinuxCnc,
                max_segment_mm: Some(10.0),
                ..ToolpathOptions::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains(want), "{text:?}: {e}");
    }
}

#[test]
fn the_header_goes_after_the_sinumerik_path_line_and_few_decimals_grow() {
    let text = "%_N_PART_MPF\n;$PATH=/_N_MPF_DIR\nG0 X0 Y0 Z5\nG1 Z0.5 F500\n";
    let tp = read_toolpath(
        text,
        &ToolpathOptions {
            dialect: Dialect::Sinumerik840d,
            ..ToolpathOptions::default()
        },
    )
    .unwrap();
    let mut pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    pos[1][2] = 0.45;
    let out = tp.write(&pos, &["note".into()]).unwrap();
    assert_eq!(
        out,
        "%_N_PART_MPF\n;$PATH=/_N_MPF_DIR\n; note\nG0 X0 Y0 Z5\nG1 Z0.45 F500\n"
    );
}

#[test]
fn unchanged_positions_give_the_same_text() {
    let text = "%\nO1000 (MOULD)\nN10 G21 G90 G17\nN20 G0 X0. Y0. Z10.\nN30 G1 Z-1.250 F300.\n\
                N40 X10.500 Y2.25\nN50 G91 X1. Y-1.\nM30\n%\n";
    let tp = read(text);
    assert_eq!(tp.nodes.len(), 4);
    assert_eq!(tp.nodes[2].position, [10.5, 2.25, -1.25]);
    assert_eq!(tp.nodes[3].position, [11.5, 1.25, -1.25]);
    let pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    assert_eq!(tp.write(&pos, &[]).unwrap(), text);
}

#[test]
fn moved_nodes_change_only_numbers_and_add_missing_words() {
    let text = "N10 G90 G1 X0.000 Y0.000 Z0.000 F500\r\nN20 X10.000 ; along\r\nM5\r\n";
    let tp = read(text);
    let mut pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    pos[1][2] = -0.1234;
    let out = tp.write(&pos, &[]).unwrap();
    assert_eq!(
        out,
        "N10 G90 G1 X0.000 Y0.000 Z0.000 F500\r\nN20 X10.000 Z-0.123 ; along\r\nM5\r\n"
    );
}

#[test]
fn incremental_blocks_are_rewritten_as_deltas() {
    let text = "G90 G0 X0 Y0 Z0\nG91 G1 X1.0 F100\nX1.0\nX1.0\n";
    let tp = read(text);
    let mut pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    pos[2][0] += 0.5; // the second incremental node moves
    let out = tp.write(&pos, &[]).unwrap();
    let again = read(&out);
    let got: Vec<_> = again.nodes.iter().map(|n| n.position).collect();
    assert_eq!(got, pos);
    assert!(out.contains("X1.5\nX0.5\n"), "{out}");
}

#[test]
fn arcs_are_linearised_within_tolerance() {
    // A quarter circle of radius 10 about (0, 0), counter-clockwise.
    let text = "G90 G17 G0 X10 Y0 Z0\nN20 G3 X0 Y10 I-10 J0 F200\nG1 X-5\n";
    let tp = read_toolpath(
        text,
        &ToolpathOptions {
            arc_tolerance_mm: 0.001,
            ..ToolpathOptions::default()
        },
    )
    .unwrap();
    assert_eq!(tp.arcs_linearised, 1);
    let arc: Vec<_> = tp
        .nodes
        .iter()
        .filter(|n| n.kind == NodeKind::Arc)
        .collect();
    assert!(arc.len() > 20);
    let mut prev = [10.0, 0.0];
    for n in &arc {
        let p = n.position;
        assert!(((p[0].hypot(p[1])) - 10.0).abs() < 1e-9);
        assert!(p[1] >= prev[1]);
        let mid = [(p[0] + prev[0]) / 2.0, (p[1] + prev[1]) / 2.0];
        assert!(10.0 - mid[0].hypot(mid[1]) <= 0.001 + 1e-12);
        prev = [p[0], p[1]];
    }
    let pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    let out = tp.write(&pos, &["arcs linearised".into()]).unwrap();
    assert!(out.starts_with("(arcs linearised)\n"));
    assert!(out.contains("N20 G1 X"));
    assert!(!out.contains('I') && !out.contains("G3"));
    let back = read(&out);
    assert_eq!(back.arcs_linearised, 0);
    for (a, b) in back.nodes.iter().zip(&tp.nodes) {
        for k in 0..3 {
            assert!((a.position[k] - b.position[k]).abs() <= 0.0005 + 1e-12);
        }
    }
}

#[test]
fn radius_arcs_and_planes() {
    // G2 with R in the XY plane: a semicircle needs |R| = half the chord.
    let tp = read("G0 X0 Y0 Z0\nG2 X10 Y0 R5 F100\n");
    let mid = tp.nodes[tp.nodes.len() / 2].position;
    assert!(
        mid[1] > 4.9,
        "a clockwise arc from (0,0) to (10,0) goes up: {mid:?}"
    );
    // G18 (ZX plane), G2 from X10 Z0 to X0 Z10 about the origin.
    let tp = read("G0 X10 Y0 Z0\nG18 G2 X0 Z10 I-10 K0 F100\n");
    for n in &tp.nodes[1..] {
        let p = n.position;
        assert!((p[0].hypot(p[2]) - 10.0).abs() < 1e-9);
        assert!(p[0] >= -1e-12 && p[2] >= -1e-12, "{p:?}");
    }
    // Sinumerik CR= and a full circle by I, J.
    let tp = read_toolpath(
        "G0 X0 Y0 Z0\nG2 X10 Y0 CR=5 F100\nG3 X10 Y0 I-5 J0\n",
        &ToolpathOptions {
            dialect: Dialect::Sinumerik840d,
            arc_tolerance_mm: 0.01,
            max_segment_mm: None,
        },
    )
    .unwrap();
    assert_eq!(tp.arcs_linearised, 2);
    let full: Vec<_> = tp.nodes.iter().filter(|n| n.line == 3).collect();
    assert!(full.iter().any(|n| n.position[0] < 0.1));
}

#[test]
fn errors_name_the_line_and_its_text() {
    let bad = [
        ("G0 X0 Y0\nG1 X1.2.3\n", "line 2"),
        ("G0 X\n", "without a number"),
        ("G92 X0\n", "coordinate system"),
        ("G0 X0 Y0 Z0\nG81 X1 Y1 Z-2 R1\n", "canned cycle"),
        ("G0 X0 A10\n", "only X, Y and Z"),
        ("G91 G1 X1\n", "unknown position"),
        ("G0 X0 Y0\nG2 X10 Y0 I3 J0\n", "not on its circle"),
        ("G1 X#100\n", "cannot read"),
        ("X10\n", "before any G0"),
    ];
    for (text, want) in bad {
        let e = read_toolpath(text, &ToolpathOptions::default())
            .err()
            .unwrap_or_else(|| panic!("{text:?} was read"))
            .to_string();
        assert!(e.contains(want), "{text:?}: {e}");
    }
    let e = read_toolpath(
        "G0 X0\nTRANS X10\n",
        &ToolpathOptions {
            dialect: Dialect::Sinumerik840d,
            ..ToolpathOptions::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("line 2: `TRANS X10`"), "{e}");
}

#[test]
fn sinumerik_keywords_lines_are_kept() {
    let text = "; mould\nMSG(\"finishing\")\nG54 G90 G0 X0 Y0 Z5\nG1 Z=-1 F800\nM30\n";
    let tp = read_toolpath(
        text,
        &ToolpathOptions {
            dialect: Dialect::Sinumerik840d,
            ..ToolpathOptions::default()
        },
    )
    .unwrap();
    assert_eq!(tp.nodes.len(), 2);
    assert_eq!(tp.nodes[1].position[2], -1.0);
    let mut pos: Vec<_> = tp.nodes.iter().map(|n| n.position).collect();
    pos[1][2] = -1.5;
    let out = tp.write(&pos, &["corrected".into()]).unwrap();
    assert_eq!(
        out,
        "; corrected\n; mould\nMSG(\"finishing\")\nG54 G90 G0 X0 Y0 Z5\nG1 Z=-1.5 F800\nM30\n"
    );
}

#[test]
fn inch_programs_are_read_in_mm_and_written_in_inches() {
    let tp = read("G20 G90 G0 X1.0000 Y0 Z0\n");
    assert!((tp.nodes[0].position[0] - 25.4).abs() < 1e-12);
    let out = tp.write(&[[50.8, 0.0, 0.0]], &[]).unwrap();
    assert_eq!(out, "G20 G90 G0 X2.0000 Y0 Z0\n");
}
