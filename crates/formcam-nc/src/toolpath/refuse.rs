//! What the milling reader refuses: the words that would change the tool's
//! path in a way the reader does not follow (polar coordinates, splines,
//! subprogram and cycle calls, frames, radius compensation, program flow),
//! and a last line cut off in the middle of a word.
//!
//! Each word is read (the modal state and the moves), passed over because
//! it does not move the programmed points (feed and spindle words, look-ahead
//! modes, work offsets, tool length compensation), or refused with a
//! [`Refusal`]; `docs/correction.md` has the table.

use formcam_files::quote;

use crate::modal::GCode;
use crate::{Dialect, Refusal, Truncation};

/// What a G code the modal state does not know does to the correction.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum Verdict {
    /// It does not move the programmed points: passed over, the line's
    /// axis words are a move in the current mode.
    Passed,
    /// Unknown: passed over on a line without axis words, refused with them.
    Unknown,
    /// Refused.
    Refused(Refusal),
}

/// The word `G<g>.<sub>` as written in messages.
fn g_name(g: u32, sub: u32) -> String {
    if sub == 0 {
        format!("G{g}")
    } else {
        format!("G{g}.{sub}")
    }
}

/// The verdict on `G<value>` in `dialect`, whose class is `code`;
/// `moves` says whether the line has axis, centre or radius words.
pub(super) fn g_code(value: f64, code: GCode, dialect: Dialect, moves: bool) -> Verdict {
    let g = value.trunc() as u32;
    let sub = ((value - value.trunc()) * 10.0).round() as u32;
    let word = g_name(g, sub);
    let sinumerik = dialect == Dialect::Sinumerik840d;
    let refused = Verdict::Refused;
    match code {
        GCode::Polar => return refused(Refusal::Polar { word }),
        GCode::Preset | GCode::PresetOther | GCode::CoordinateSystem(_) => {
            return refused(Refusal::Frame { word });
        }
        GCode::Cycle(_) => return refused(Refusal::Cycle { word }),
        GCode::Other => {}
        _ => return Verdict::Passed,
    }
    match (g, sub) {
        // Fanuc's look-ahead modes (`G05 P10000`, `G05.1 Q1`) move nothing;
        // with axis words G5 is a spline (LinuxCNC, Marlin).
        (5, 0 | 1) if dialect != Dialect::LinuxCnc && !moves => Verdict::Passed,
        (5, _) | (6, 2) => refused(Refusal::Spline { word }),
        (7, 1) => refused(Refusal::Frame { word }),
        (7, 0) if dialect == Dialect::LinuxCnc => refused(Refusal::Frame { word }),
        (12, 1) | (110..=112, 0) => refused(Refusal::Polar { word }),
        (17..=19, 1) => refused(Refusal::Plane { word }),
        (31, _) | (38, _) => refused(Refusal::Probe { word }),
        (41 | 42, _) | (43, 1 | 2) => refused(Refusal::Compensation { word }),
        (58 | 59, 0) if sinumerik => refused(Refusal::Frame { word }),
        (65 | 66, _) => refused(Refusal::Subprogram { word }),
        _ if passed(g, sub, sinumerik) => Verdict::Passed,
        _ => Verdict::Unknown,
    }
}

/// G codes that do not move the programmed points: exact stop and
/// look-ahead modes, cancels, tool length compensation, work offsets,
/// spindle and cycle-return modes.
fn passed(g: u32, sub: u32, sinumerik: bool) -> bool {
    match (g, sub) {
        (9 | 40 | 60 | 64 | 96 | 97, 0) => true,
        _ if sinumerik => matches!(
            (g, sub),
            (54..=57 | 500 | 505..=599 | 601..=603 | 641..=645 | 450 | 451, 0)
        ),
        (8 | 15 | 43 | 44 | 49 | 61 | 62 | 63 | 69 | 80 | 98 | 99, 0) => true,
        (13 | 50 | 61 | 64, 1) => true,
        (54..=59, _) => true,
        _ => false,
    }
}

/// The refusal of `M<value>`, if any: subprogram calls.
pub(super) fn m_code(value: f64) -> Option<Refusal> {
    (value == 98.0 || value == 198.0).then(|| Refusal::Subprogram {
        word: format!("M{value}"),
    })
}

/// Sinumerik keywords that do not move the programmed points: messages,
/// look-ahead and smoothing, feed profiles, spindle positioning, the
/// simulation's blank, the end of a transformation or a subprogram, the
/// high-speed settings cycle (tolerances only), the cancel of a modal call
/// (the call itself names a cycle or subprogram, refused).
const PASSED_840D: [&str; 31] = [
    "MSG",
    "STOPRE",
    "SOFT",
    "BRISK",
    "DRIVE",
    "FFWON",
    "FFWOF",
    "COMPON",
    "COMPCURV",
    "COMPCAD",
    "COMPSURF",
    "COMPOF",
    "CYCLE832",
    "CFC",
    "CFTCP",
    "CFIN",
    "FNORM",
    "FLIN",
    "FCUB",
    "UPATH",
    "SPATH",
    "ADIS",
    "ADISPOS",
    "SPOS",
    "SPOSA",
    "WORKPIECE",
    "TRAFOOF",
    "RET",
    "MCALL",
    "OFFN",
    "CUT2D",
];

/// Sinumerik keywords that change the coordinate system or the axes'
/// meaning.
const FRAMES_840D: [&str; 21] = [
    "TRANS", "ATRANS", "CTRANS", "ROT", "AROT", "CROT", "ROTS", "AROTS", "SCALE", "ASCALE",
    "CSCALE", "MIRROR", "AMIRROR", "CMIRROR", "RPL", "CYCLE800", "TRAORI", "TRACYL", "TRANSMIT",
    "TRAANG", "SUPA",
];

/// Sinumerik spline words (and their end conditions and parameters).
const SPLINES_840D: [&str; 12] = [
    "BSPLINE", "ASPLINE", "CSPLINE", "POLY", "POLYPATH", "BAUTO", "BNAT", "BTAN", "EAUTO", "ENAT",
    "ETAN", "SD",
];

/// Program flow: jumps, loops and conditions (Sinumerik, Fanuc macros,
/// LinuxCNC O-words).
const FLOW: [&str; 25] = [
    "GOTO",
    "GOTOF",
    "GOTOB",
    "GOTOC",
    "GOTOS",
    "IF",
    "ELSE",
    "ELSEIF",
    "ENDIF",
    "WHILE",
    "ENDWHILE",
    "DO",
    "END",
    "LOOP",
    "ENDLOOP",
    "FOR",
    "ENDFOR",
    "REPEAT",
    "REPEATB",
    "ENDREPEAT",
    "UNTIL",
    "CASE",
    "BREAK",
    "CONTINUE",
    "RETURN",
];

/// Subprogram calls and definitions.
const CALLS: [&str; 7] = [
    "CALL", "PCALL", "EXTCALL", "SUB", "ENDSUB", "PROC", "CALLPATH",
];

/// Cycle names by their start (Sinumerik's standard cycles).
const CYCLES_840D: [&str; 6] = ["CYCLE", "POCKET", "SLOT", "LONGHOLE", "HOLES", "CONTPR"];

/// The refusal of a keyword (several letters) in `dialect`, if any; on
/// Sinumerik a keyword not known to be harmless is refused (it may name a
/// subprogram). `Ok(true)`: a harmless call whose parentheses the caller
/// skips.
fn keyword(word: &str, dialect: Dialect) -> Result<bool, Refusal> {
    let up = word.to_ascii_uppercase();
    let named = || quote(word).to_string();
    let sinumerik = dialect == Dialect::Sinumerik840d;
    // `END1`, `DO2`: Fanuc's loop labels.
    let stem = up.trim_end_matches(|c: char| c.is_ascii_digit());
    if FLOW.contains(&stem) {
        return Err(Refusal::Flow { word: named() });
    }
    if CALLS.contains(&stem) {
        return Err(Refusal::Subprogram { word: named() });
    }
    if !sinumerik {
        // Other keywords of ISO and LinuxCNC lines are the line reader's.
        return Ok(false);
    }
    match up.as_str() {
        "CR" => return Ok(false),
        "AP" | "RP" => return Err(Refusal::Polar { word: named() }),
        "CIP" | "CT" | "AR" | "TURN" => return Err(Refusal::ArcForm { word: named() }),
        _ => {}
    }
    if PASSED_840D.contains(&up.as_str()) {
        return Ok(true);
    }
    if FRAMES_840D.contains(&up.as_str()) {
        return Err(Refusal::Frame { word: named() });
    }
    if SPLINES_840D.contains(&up.as_str()) {
        return Err(Refusal::Spline { word: named() });
    }
    if up.starts_with("CUT3D") || up.starts_with("TOFF") {
        return Err(Refusal::Compensation { word: named() });
    }
    if CYCLES_840D.iter().any(|c| up.starts_with(c)) {
        return Err(Refusal::Cycle { word: named() });
    }
    Err(Refusal::Keyword { word: named() })
}

/// The first keyword of a line that the reader refuses, if any. Comments,
/// strings, LinuxCNC `<names>` and the arguments of harmless calls are
/// skipped; a Sinumerik `%_N_..` header line is no code.
pub(super) fn keywords(text: &str, dialect: Dialect) -> Result<(), Refusal> {
    let sinumerik = dialect == Dialect::Sinumerik840d;
    if sinumerik && text.trim_start().starts_with('%') {
        return Ok(());
    }
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b';' => break,
            b'(' if !sinumerik => i = close(b, i, b')'),
            b'<' if dialect == Dialect::LinuxCnc => i = close(b, i, b'>'),
            b'"' => i = close(b, i, b'"'),
            c if c.is_ascii_alphabetic() => {
                let run = b[i..]
                    .iter()
                    .take_while(|c| c.is_ascii_alphabetic() || **c == b'_')
                    .count();
                if run < 2 {
                    i += 1;
                    continue;
                }
                let end = i + b[i..]
                    .iter()
                    .take_while(|c| c.is_ascii_alphanumeric() || **c == b'_')
                    .count();
                let harmless_call = keyword(&text[i..end], dialect)?;
                i = end;
                let j = i + b[i..].iter().take_while(|c| **c == b' ').count();
                if harmless_call && b.get(j) == Some(&b'(') {
                    i = call_end(b, j);
                }
            }
            _ => i += 1,
        }
    }
    Ok(())
}

/// Past the `close` that ends what opens at `i` (or the end of the line).
fn close(b: &[u8], i: usize, close: u8) -> usize {
    b[i + 1..]
        .iter()
        .position(|c| *c == close)
        .map_or(b.len(), |k| i + 1 + k + 1)
}

/// Past the `)` that closes the `(` at `i`, strings skipped.
fn call_end(b: &[u8], i: usize) -> usize {
    let mut depth = 0usize;
    let mut k = i;
    while k < b.len() {
        match b[k] {
            b'"' => {
                k = close(b, k, b'"');
                continue;
            }
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
        k += 1;
    }
    b.len()
}

/// Whether the last line of a program, `text` (without a line end), stops
/// in the middle of a word: a letter (or a Sinumerik `NAME=`) without its
/// number (`X`, `X-`, `X.`, `Z=`, `#`), an unclosed comment, string or
/// bracket. A number is whole once it has a digit (`X12.` and `X12.5` are
/// complete); a line ending in a `;` comment is complete.
pub(super) fn truncated(text: &str, dialect: Dialect) -> Option<Truncation> {
    let sinumerik = dialect == Dialect::Sinumerik840d;
    let b = text.as_bytes();
    let mut depth = 0usize;
    let mut i = 0;
    let mut code_end = b.len();
    while i < b.len() {
        match b[i] {
            b';' => {
                code_end = i;
                if depth > 0 {
                    return None;
                }
                break;
            }
            b'(' if !sinumerik => {
                let next = close(b, i, b')');
                if b[next - 1] != b')' || next - 1 == i {
                    return Some(Truncation::Comment);
                }
                i = next;
                continue;
            }
            b'"' => {
                let next = close(b, i, b'"');
                if b[next - 1] != b'"' || next - 1 == i {
                    return Some(Truncation::String);
                }
                i = next;
                continue;
            }
            b'[' | b'(' => depth += 1,
            b']' | b')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    if depth > 0 {
        return Some(Truncation::Bracket);
    }
    last_word(&text[..code_end])
}

/// The last word of `code` if it is a letter or name without a number.
fn last_word(code: &str) -> Option<Truncation> {
    let t = code.trim_end_matches([' ', '\t']);
    let b = t.as_bytes();
    // Back over a sign, a point, blanks and `=`: what a number would follow.
    let mut k = b.len();
    while k > 0 && matches!(b[k - 1], b'+' | b'-' | b'.' | b' ' | b'\t' | b'=') {
        k -= 1;
    }
    if k == 0 {
        return None;
    }
    let back = |keep: fn(&u8) -> bool| b[..k].iter().rev().take_while(|c| keep(c)).count();
    // A name followed by `=` needs its value, a parameter `#` its number,
    // a one-letter address its number; a keyword ending the line (`M30`
    // has its digits, `STOPRE` is a word) is whole.
    let start = if t[k..].contains('=') {
        k - back(|c| c.is_ascii_alphanumeric() || *c == b'_')
    } else if b[k - 1] == b'#' || back(|c| c.is_ascii_alphabetic() || *c == b'_') == 1 {
        k - 1
    } else {
        return None;
    };
    Some(Truncation::Word {
        word: quote(&t[start..]).to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cut_words_and_whole_ones() {
        let iso = Dialect::Iso;
        for cut in [
            "X", "G1 X", "G1 X-", "G1 X.", "N", "G1 X10 Y", "G1 X #", "X -",
        ] {
            assert!(
                matches!(truncated(cut, iso), Some(Truncation::Word { .. })),
                "{cut:?}"
            );
        }
        for whole in [
            "X12.5",
            "G1 X12.",
            "M30",
            "%",
            "G1 X1 ; a comment (",
            "(done)",
            "",
        ] {
            assert_eq!(truncated(whole, iso), None, "{whole:?}");
        }
        assert_eq!(truncated("G1 X1 (feed", iso), Some(Truncation::Comment));
        assert_eq!(
            truncated("G1 X[1+", Dialect::LinuxCnc),
            Some(Truncation::Bracket)
        );
        let s = Dialect::Sinumerik840d;
        assert_eq!(truncated("MSG(\"fin", s), Some(Truncation::String));
        assert_eq!(truncated("CYCLE81(10, 0", s), Some(Truncation::Bracket));
        assert!(matches!(
            truncated("G1 Z=", s),
            Some(Truncation::Word { .. })
        ));
        assert!(matches!(
            truncated("G2 X1 CR=-", s),
            Some(Truncation::Word { .. })
        ));
        assert_eq!(truncated("STOPRE", s), None);
        assert_eq!(truncated("G1 Z=-1.5", s), None);
    }

    #[test]
    fn keywords_by_kind() {
        let s = Dialect::Sinumerik840d;
        let kind = |t: &str, d| keywords(t, d).err();
        assert!(matches!(
            kind("G1 AP=45 RP=10", s),
            Some(Refusal::Polar { .. })
        ));
        assert!(matches!(
            kind("CYCLE81(10,0,1,-5)", s),
            Some(Refusal::Cycle { .. })
        ));
        assert!(matches!(
            kind("N10 POCKET3(5)", s),
            Some(Refusal::Cycle { .. })
        ));
        assert!(matches!(kind("BSPLINE", s), Some(Refusal::Spline { .. })));
        assert!(matches!(kind("AROT Z45", s), Some(Refusal::Frame { .. })));
        assert!(matches!(
            kind("CALL \"PART\"", s),
            Some(Refusal::Subprogram { .. })
        ));
        assert!(matches!(kind("GOTOF END1", s), Some(Refusal::Flow { .. })));
        assert!(matches!(kind("PART_SUB", s), Some(Refusal::Keyword { .. })));
        assert!(matches!(
            kind("o100 call [1]", Dialect::LinuxCnc),
            Some(Refusal::Subprogram { .. })
        ));
        for ok in [
            "%_N_PART_MPF",
            "MSG(\"finish CYCLE81\")",
            "CYCLE832(0.01, _ORI_FINISH, 1)",
            "G1 X=10 CR=5 ; AP=",
            "T=\"BALL 12\" D1",
            "MCALL",
        ] {
            assert_eq!(keywords(ok, s), Ok(()), "{ok:?}");
        }
        for ok in ["O1000 (PANEL AP)", "#<depth> = 5", "G1 X1 (ROT)"] {
            assert_eq!(keywords(ok, Dialect::LinuxCnc), Ok(()), "{ok:?}");
        }
    }
}
