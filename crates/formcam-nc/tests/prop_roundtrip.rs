//! Property: a program written in any dialect and read back with the
//! matching reader gives the same blocks. Random programs (linear, rotary
//! and modulo rotary axes; rapid and linear moves; feeds per minute and
//! inverse time; comments with parentheses, semicolons, line breaks, tabs
//! and non-ASCII characters) come back with
//!
//! * the same number of blocks, the same motions and re-zeros,
//! * every axis value to half a unit of its written precision (3 decimals
//!   in mm, 4 in degrees),
//! * every feed to its written precision as the dialect keeps it: per-minute
//!   feeds (1 decimal), inverse time as `G93 F = 60 / t` (3 decimals) in
//!   840D, ISO and LinuxCNC; Marlin writes `travel / t * 60` over every axis,
//!   CLDATA over the linear axes (`INVERS` where they do not move),
//! * every comment and header comment as the dialect writes it: line breaks
//!   made spaces, parentheses made brackets inside parenthesis comments,
//!   surrounding blanks dropped.
//!
//! A user template that writes ISO-like G-code reads back the same way.
//!
//! Every program starts with a rapid move and moves X in every block, as
//! formcam's programs do: Marlin has no inverse time and converts a timed
//! block's time into a feed over the block's travel, which the first block
//! (from an unknown position) and a block that moves nothing do not have;
//! such a block keeps the feed in force, or with none in force yet takes the
//! feed ahead (`tests/roundtrip.rs` reads such programs back), which this
//! property would have to predict.

#![allow(clippy::unwrap_used, clippy::expect_used, missing_docs)]

use formcam_nc::{
    AxisSpec, Block, Dialect, Feed, ModuloStyle, Motion, Program, Template, keep_within_turns,
    read_cldata, read_gcode_in, write, write_template,
};
use proptest::prelude::*;

/// A comment as the dialect keeps it: formcam-nc's own rule
/// ([`Dialect::comment_as_written`]), trimmed as readers trim.
fn kept(text: &str, d: Dialect) -> String {
    d.comment_as_written(text).trim().to_string()
}

/// The rule spelled out, for the dialects that write comments in
/// parentheses.
#[test]
fn comments_as_written_per_dialect() {
    let text = "layer 2 (helical)\nnext";
    for d in Dialect::ALL {
        let want = match d {
            Dialect::Iso | Dialect::LinuxCnc => "layer 2 [helical] next",
            _ => "layer 2 (helical) next",
        };
        assert_eq!(d.comment_as_written(text), want, "{d}");
    }
}

/// Comments built from the characters that trouble G-code readers.
fn comment() -> impl Strategy<Value = String> {
    proptest::collection::vec(
        prop_oneof![
            4 => proptest::char::range('a', 'z'),
            2 => Just(' '),
            1 => proptest::sample::select(vec![
                '(', ')', ';', '\n', '\r', '\t', '%', '$', '/', '=', ',', 'é', '°', 'µ', 'N', 'G',
                'X', '0', '9', '.', '-', '"', '\'', '[', ']',
            ]),
        ],
        0..24,
    )
    .prop_map(|v| v.into_iter().collect())
}

/// One block: rapid or linear, a step per axis (from unit numbers), the feed
/// (per minute, or a time) and an optional comment.
type RawBlock = (bool, Vec<f64>, bool, f64, Option<String>);

fn raw_block() -> impl Strategy<Value = RawBlock> {
    (
        any::<bool>(),
        proptest::collection::vec(-1.0f64..1.0, 4),
        any::<bool>(),
        0.0f64..1.0,
        proptest::option::weighted(0.3, comment()),
    )
}

/// The axes of a program in `d`: X, A (modulo or not), B, and Y unless the
/// dialect is Marlin's X/A/B.
fn axes(d: Dialect, modulo: bool) -> Vec<AxisSpec> {
    let a = if modulo {
        AxisSpec::rotary_modulo("A")
    } else {
        AxisSpec::rotary("A")
    };
    let mut v = vec![AxisSpec::linear("X"), a, AxisSpec::rotary("B")];
    if d != Dialect::MarlinXab {
        v.push(AxisSpec::linear("Y"));
    }
    v
}

/// A random walk of blocks on the axes of `d`: linear steps up to 400 mm,
/// rotary up to 4000° (the modulo axis winds far), feeds from 0.1 to
/// 60 000 mm/min or times from 1 ms to 100 s.
fn program(d: Dialect, modulo: bool, name: &str, header: &[String], raw: &[RawBlock]) -> Program {
    let mut p = Program::new(name, axes(d, modulo));
    p.header_comments = header.to_vec();
    let mut pos = vec![0.0; p.axes.len()];
    for (i, (rapid, steps, inverse, f, comment)) in raw.iter().enumerate() {
        for (k, (v, a)) in pos.iter_mut().zip(&p.axes).enumerate() {
            *v += steps[k] * if a.rotary { 4000.0 } else { 400.0 };
        }
        // X moves at least 1 mm in every block (see the module's note on
        // Marlin).
        pos[0] += 1.0_f64.copysign(steps[0]);
        let mut b = if *rapid || i == 0 {
            Block::rapid(pos.clone())
        } else if *inverse {
            Block::linear(pos.clone(), Feed::InverseTime(1e-3 + 100.0 * f))
        } else {
            Block::linear(pos.clone(), Feed::PerMinute(0.1 + 60_000.0 * f))
        };
        b.comment.clone_from(comment);
        p.blocks.push(b);
    }
    p
}

fn read(text: &str, d: Dialect, axes: &[AxisSpec]) -> Result<Program, TestCaseError> {
    match d {
        Dialect::Cldata => read_cldata(text, axes),
        _ => read_gcode_in(text, axes, d),
    }
    .map_err(|e| TestCaseError::fail(format!("{d}: {e}\n{text}")))
}

/// Distance between two points over the linear axes, or every axis.
fn travel(axes: &[AxisSpec], a: &[f64], b: &[f64], linear_only: bool) -> f64 {
    axes.iter()
        .zip(a.iter().zip(b))
        .filter(|(s, _)| !(linear_only && s.rotary))
        .map(|(_, (p, q))| (q - p) * (q - p))
        .sum::<f64>()
        .sqrt()
}

/// The feed `d` writes for block `i` of `p` and how closely it comes back:
/// `None` where the dialect writes none to compare.
fn expected_feed(p: &Program, i: usize, d: Dialect) -> Option<(Feed, f64)> {
    let b = &p.blocks[i];
    let prev = i.checked_sub(1).map(|k| p.blocks[k].target.as_slice());
    let fine = 0.5e-3 + 1e-9;
    match (b.kind, b.feed) {
        (Motion::Rapid, _) => Some((Feed::None, 0.0)),
        (_, Feed::PerMinute(f)) => Some((Feed::PerMinute(f), 0.05 + 1e-9 + f * 1e-15)),
        (_, Feed::InverseTime(t)) => match d {
            Dialect::Sinumerik840d | Dialect::Iso | Dialect::LinuxCnc => {
                Some((Feed::InverseTime(t), fine))
            }
            Dialect::MarlinXab => {
                let s = travel(&p.axes, prev?, &b.target, false);
                (s > 0.0).then(|| (Feed::PerMinute(s / t * 60.0), fine + s / t * 1e-14))
            }
            Dialect::Cldata => {
                let s = prev.map_or(0.0, |q| travel(&p.axes, q, &b.target, true));
                if s > 0.0 {
                    Some((Feed::PerMinute(s / t * 60.0), fine + s / t * 1e-14))
                } else {
                    Some((Feed::InverseTime(t), fine))
                }
            }
        },
        (_, Feed::None) => None,
    }
}

/// Whether `got` is `want` within `tol` (inverse times compared as the
/// `F = 60 / t` written).
fn feed_close(want: Feed, got: Feed, tol: f64) -> bool {
    match (want, got) {
        (Feed::None, Feed::None) => true,
        (Feed::PerMinute(f), Feed::PerMinute(g)) => (f - g).abs() <= tol,
        (Feed::InverseTime(t), Feed::InverseTime(u)) => (60.0 / t - 60.0 / u).abs() <= tol,
        _ => false,
    }
}

/// Writes `p` in `d` (prepared for its modulo axes), reads it back and
/// compares.
fn round_trip(p: &Program, d: Dialect) -> Result<(), TestCaseError> {
    let p = keep_within_turns(p, ModuloStyle::of(d)).unwrap();
    let mut text = String::new();
    write(&p, d, &mut text).unwrap();
    let q = read(&text, d, &p.axes)?;
    prop_assert_eq!(&q.name, &p.name, "{}", d);
    let header: Vec<String> = p
        .header_comments
        .iter()
        .map(|c| kept(c, d))
        .filter(|c| !c.is_empty())
        .collect();
    let got: Vec<String> = q
        .header_comments
        .iter()
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect();
    prop_assert_eq!(got, header, "{}: header comments\n{}", d, text);
    prop_assert_eq!(q.blocks.len(), p.blocks.len(), "{}: blocks\n{}", d, text);
    let rezeroes = ModuloStyle::of(d) == ModuloStyle::Rezero;
    for (i, (a, b)) in p.blocks.iter().zip(&q.blocks).enumerate() {
        prop_assert_eq!(a.kind, b.kind, "{}: block {} motion", d, i);
        if rezeroes && i > 0 {
            prop_assert_eq!(a.rezero, b.rezero, "{}: block {} re-zero", d, i);
        }
        for (k, axis) in p.axes.iter().enumerate() {
            let unit = if axis.rotary { 1e-4 } else { 1e-3 };
            let tol = 0.5 * unit + 1e-9 + a.target[k].abs() * 1e-15;
            prop_assert!(
                (a.target[k] - b.target[k]).abs() <= tol,
                "{}: block {} axis {}: {} read back as {}\n{}",
                d,
                i,
                axis.name,
                a.target[k],
                b.target[k],
                text
            );
        }
        if let Some((want, tol)) = expected_feed(&p, i, d) {
            prop_assert!(
                feed_close(want, b.feed, tol),
                "{}: block {}: feed {:?} (written as {:?}) read back as {:?}",
                d,
                i,
                a.feed,
                want,
                b.feed
            );
        }
        let want = a
            .comment
            .as_deref()
            .map(|c| kept(c, d))
            .filter(|c| !c.is_empty());
        let got = b
            .comment
            .as_deref()
            .map(str::trim)
            .filter(|c| !c.is_empty());
        prop_assert_eq!(
            got,
            want.as_deref(),
            "{}: block {} comment {:?}\n{}",
            d,
            i,
            a.comment,
            text
        );
    }
    Ok(())
}

/// A user template that writes G-code: every axis in every block, `;`
/// comments on their own lines, `G93` inverse time, `G92` re-zeros.
const TEMPLATE: &str = r#"
extension = "ngc"
header = "; PROGRAM {name}\nG21 G90 G94"
comment = "; {comment}"
rapid = "G0 {axes}"
block = "G94 G1 {axes} F{f}"
inverse = "G93 G1 {axes} F{fi}"
rezero = "G92 {axes}"
footer = "M2"
modal_axes = false
"#;

/// Writes `p` with [`TEMPLATE`] and reads it back as ISO G-code (re-zeroed
/// modulo axes): what the ISO writer gives back, comments as written (no
/// parentheses to replace).
fn template_round_trip(p: &Program) -> Result<(), TestCaseError> {
    let t = Template::from_toml(TEMPLATE).unwrap();
    let p = keep_within_turns(p, t.modulo_style().unwrap()).unwrap();
    let mut text = String::new();
    write_template(&p, &t, &mut text).unwrap();
    let q = read(&text, Dialect::Iso, &p.axes)?;
    prop_assert_eq!(&q.name, &p.name);
    prop_assert_eq!(q.blocks.len(), p.blocks.len(), "template: blocks\n{}", text);
    // The template writes a block's comment on the line before it, so the
    // first block's comes back as a header comment (a comment line before
    // the first motion).
    let kept_all = |c: &String| kept(c, Dialect::MarlinXab);
    let header: Vec<String> = p
        .header_comments
        .iter()
        .chain(&p.blocks[0].comment)
        .map(kept_all)
        .filter(|c| !c.is_empty())
        .collect();
    let got: Vec<String> = q
        .header_comments
        .iter()
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect();
    prop_assert_eq!(got, header, "template: header comments\n{}", text);
    for (i, (a, b)) in p.blocks.iter().zip(&q.blocks).enumerate() {
        prop_assert_eq!(a.kind, b.kind, "template: block {} motion", i);
        if i > 0 {
            prop_assert_eq!(
                a.rezero,
                b.rezero,
                "template: block {} re-zero\n{}",
                i,
                text
            );
        }
        for (k, axis) in p.axes.iter().enumerate() {
            let unit = if axis.rotary { 1e-4 } else { 1e-3 };
            let tol = 0.5 * unit + 1e-9 + a.target[k].abs() * 1e-15;
            prop_assert!(
                (a.target[k] - b.target[k]).abs() <= tol,
                "template: block {} axis {}: {} read back as {}\n{}",
                i,
                axis.name,
                a.target[k],
                b.target[k],
                text
            );
        }
        if let Some((want, tol)) = expected_feed(&p, i, Dialect::Iso) {
            prop_assert!(
                feed_close(want, b.feed, tol),
                "template: block {}: feed {:?} read back as {:?}",
                i,
                a.feed,
                b.feed
            );
        }
        let want = a
            .comment
            .as_deref()
            .filter(|_| i > 0)
            .map(|c| kept(c, Dialect::MarlinXab))
            .filter(|c| !c.is_empty());
        let got = b
            .comment
            .as_deref()
            .map(str::trim)
            .filter(|c| !c.is_empty());
        prop_assert_eq!(
            got,
            want.as_deref(),
            "template: block {} comment\n{}",
            i,
            text
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Every dialect gives back what it wrote.
    #[test]
    fn a_program_written_in_any_dialect_reads_back_equal(
        modulo in any::<bool>(),
        name in "[A-Z][A-Z0-9_]{0,11}",
        header in proptest::collection::vec(comment(), 0..3),
        raw in proptest::collection::vec(raw_block(), 1..40),
    ) {
        for d in Dialect::ALL {
            round_trip(&program(d, modulo, &name, &header, &raw), d)?;
        }
        template_round_trip(&program(Dialect::LinuxCnc, modulo, &name, &header, &raw))?;
    }
}
