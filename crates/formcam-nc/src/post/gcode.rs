//! The G-code writers (Sinumerik 840D, ISO, LinuxCNC, Marlin): one engine,
//! one [`Style`] per dialect.

use crate::num::{self, DEG, FEED, FEED_FINE, MM, Out, Word};
use crate::post::push_comment_text;
use crate::program::nc_travel;
use crate::{Feed, Motion, NcError, Program};

/// Which program heading and end a dialect writes.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Frame {
    Sinumerik,
    Iso,
    LinuxCnc,
    Marlin,
}

/// How inverse-time blocks are written.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Inverse {
    /// `G93` with `F = 60 / t` (1/min), `G94` again at the next per-minute block.
    G93,
    /// Converted to a per-minute feed `F = travel / t * 60`, the travel being
    /// the Euclidean norm of the axis deltas in NC units (FiberPath's way).
    Convert,
}

/// Which axis names a dialect can address.
#[derive(Clone, Copy)]
enum Axes {
    /// Exactly these single letters.
    Letters(&'static [&'static str], &'static str),
    /// Sinumerik: a free single letter (`X12.5`) or an identifier (`J1=12.5`).
    Sinumerik,
}

/// A G-code dialect's conventions.
pub(super) struct Style {
    name: &'static str,
    frame: Frame,
    axes: Axes,
    line_numbers: bool,
    motion: [&'static str; 2],
    parens: bool,
    keep_point: bool,
    inverse: Inverse,
}

const NINE: &[&str] = &["X", "Y", "Z", "A", "B", "C", "U", "V", "W"];
const NINE_TEXT: &str = "X, Y, Z, A, B, C, U, V, W";

/// Sinumerik 840D.
pub(super) const SINUMERIK: Style = Style {
    name: "sinumerik-840d",
    frame: Frame::Sinumerik,
    axes: Axes::Sinumerik,
    line_numbers: true,
    motion: ["G0", "G1"],
    parens: false,
    keep_point: false,
    inverse: Inverse::G93,
};

/// ISO 6983 / Fanuc.
pub(super) const ISO: Style = Style {
    name: "iso",
    frame: Frame::Iso,
    axes: Axes::Letters(NINE, NINE_TEXT),
    line_numbers: false,
    motion: ["G00", "G01"],
    parens: true,
    keep_point: true,
    inverse: Inverse::G93,
};

/// LinuxCNC.
pub(super) const LINUXCNC: Style = Style {
    name: "linuxcnc",
    frame: Frame::LinuxCnc,
    axes: Axes::Letters(NINE, NINE_TEXT),
    line_numbers: false,
    motion: ["G0", "G1"],
    parens: true,
    keep_point: false,
    inverse: Inverse::G93,
};

/// Marlin with X, A, B (and Y, Z, C).
pub(super) const MARLIN: Style = Style {
    name: "marlin-xab",
    frame: Frame::Marlin,
    axes: Axes::Letters(&["X", "Y", "Z", "A", "B", "C"], "X, Y, Z, A, B, C"),
    line_numbers: false,
    motion: ["G0", "G1"],
    parens: false,
    keep_point: false,
    inverse: Inverse::Convert,
};

/// Single letters Sinumerik reserves for other addresses.
const SINUMERIK_RESERVED: &str = "DFGHLMNOPRST";
const SINUMERIK_TEXT: &str = "a single letter other than D F G H L M N O P R S T, \
     or an identifier like J1 (written J1=value)";

/// The word written before each axis value (`" X"`, `" J1="`) and its decimals.
fn axis_words(p: &Program, st: &Style) -> Result<Vec<(AxisWord, u32)>, NcError> {
    p.axes
        .iter()
        .map(|a| {
            let unsupported = |allowed| NcError::UnsupportedAxis {
                dialect: st.name,
                axis: a.name.clone(),
                allowed,
            };
            let word = match st.axes {
                Axes::Letters(list, text) => {
                    if !list.contains(&a.name.as_str()) {
                        return Err(unsupported(text));
                    }
                    a.name.clone()
                }
                Axes::Sinumerik => {
                    let mut chars = a.name.chars();
                    let first_ok = chars.next().is_some_and(|c| c.is_ascii_uppercase());
                    let rest_ok =
                        chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_');
                    if !(first_ok && rest_ok) {
                        return Err(unsupported(SINUMERIK_TEXT));
                    }
                    if a.name.len() == 1 {
                        if SINUMERIK_RESERVED.contains(a.name.as_str()) {
                            return Err(unsupported(SINUMERIK_TEXT));
                        }
                        a.name.clone()
                    } else {
                        format!("{}=", a.name)
                    }
                }
            };
            let word = format!(" {word}");
            let word = match Word::new(&word) {
                Some(w) => AxisWord::Short(w),
                None => AxisWord::Long(word),
            };
            Ok((word, if a.rotary { DEG } else { MM }))
        })
        .collect()
}

/// The text before an axis value: short ones are written in one store.
enum AxisWord {
    Short(Word),
    Long(String),
}

impl AxisWord {
    #[inline(always)]
    fn push(&self, out: &mut Out) {
        match self {
            AxisWord::Short(w) => out.word(w),
            AxisWord::Long(s) => out.s(s),
        }
    }
}

/// N numbers 10, 20, … when the dialect numbers its blocks.
struct LineNo {
    on: bool,
    next: u64,
}

impl LineNo {
    fn push(&mut self, out: &mut Out) {
        if self.on {
            out.c('N');
            num::push_uint(out, self.next);
            out.c(' ');
            self.next += 10;
        }
    }
}

fn comment_line(out: &mut Out, st: &Style, text: &str) {
    if st.parens {
        out.c('(');
        push_comment_text(out, text, true);
        out.s(")\n");
    } else {
        out.s("; ");
        push_comment_text(out, text, false);
        out.c('\n');
    }
}

fn header(out: &mut Out, p: &Program, st: &Style, ln: &mut LineNo) {
    if st.frame == Frame::Iso {
        out.s("%\nO0001");
        if !p.name.is_empty() {
            out.s(" (");
            push_comment_text(out, &p.name, true);
            out.c(')');
        }
        out.c('\n');
    } else if !p.name.is_empty() {
        comment_line(out, st, &format!("PROGRAM {}", p.name));
    }
    for c in &p.header_comments {
        comment_line(out, st, c);
    }
    match st.frame {
        Frame::Sinumerik => {
            ln.push(out);
            out.s("G90 G94 G71\n");
        }
        Frame::Iso | Frame::LinuxCnc => out.s("G21 G90 G94\n"),
        Frame::Marlin => out.s("G21\nG90\nG94\n"),
    }
}

fn footer(out: &mut Out, st: &Style, ln: &mut LineNo) {
    match st.frame {
        Frame::Sinumerik => {
            ln.push(out);
            out.s("M30\n");
        }
        Frame::Iso => out.s("M30\n%\n"),
        Frame::LinuxCnc => out.s("M2\n"),
        Frame::Marlin => {}
    }
}

/// Writes `p` (already validated) in the style `st`.
pub(super) fn write(p: &Program, st: &Style, out: &mut Out) -> Result<(), NcError> {
    let words = axis_words(p, st)?;
    let n = words.len();
    out.reserve(256 + p.blocks.len() * (16 + 12 * n));
    let mut ln = LineNo {
        on: st.line_numbers,
        next: 10,
    };
    header(out, p, st, &mut ln);

    // Last printed scaled values; `i64::MIN` (never a scaled value): none.
    let mut last: Vec<i64> = vec![i64::MIN; n];
    let mut g93 = false;
    let mut last_feed: Option<(i64, u32)> = None;
    let mut prev: Option<&[f64]> = None;
    for b in &p.blocks {
        ln.push(out);
        // (value, decimals, written even when unchanged)
        let mut feed: Option<(f64, u32, bool)> = None;
        match b.kind {
            Motion::Rapid => out.s(st.motion[0]),
            Motion::Linear => {
                match b.feed {
                    Feed::PerMinute(f) => {
                        if g93 {
                            out.s("G94 ");
                            g93 = false;
                            last_feed = None;
                        }
                        feed = Some((f, FEED, false));
                    }
                    Feed::InverseTime(t) => match st.inverse {
                        Inverse::G93 => {
                            if !g93 {
                                out.s("G93 ");
                                g93 = true;
                            }
                            feed = Some((60.0 / t, FEED_FINE, true));
                        }
                        Inverse::Convert => {
                            let travel = prev.map_or(0.0, |q| nc_travel(q, &b.target));
                            if travel > 0.0 {
                                feed = Some((travel / t * 60.0, FEED_FINE, false));
                            }
                        }
                    },
                    Feed::None => {}
                }
                out.s(st.motion[1]);
            }
        }
        let mut any = false;
        let target = &b.target[..n];
        let last = &mut last[..n];
        for k in 0..n {
            let v = target[k];
            let (word, dec) = &words[k];
            match num::scaled(v, *dec) {
                Some(s) if s == last[k] => continue,
                Some(s) => {
                    word.push(out);
                    num::push_scaled(out, s, *dec, st.keep_point);
                    last[k] = s;
                }
                None => {
                    word.push(out);
                    num::push(out, v, *dec, st.keep_point);
                    last[k] = i64::MIN;
                }
            }
            any = true;
        }
        if !any {
            // Nothing moved: still write one axis word, so the block stays a move.
            if let (Some((word, dec)), Some(v)) = (words.first(), b.target.first()) {
                word.push(out);
                num::push(out, *v, *dec, st.keep_point);
            }
        }
        if let Some((f, dec, always)) = feed {
            let key = num::scaled(f, dec).map(|s| (s, dec));
            if always || key.is_none() || key != last_feed {
                out.s(" F");
                num::push(out, f, dec, st.keep_point);
                if !always {
                    last_feed = key;
                }
            }
        }
        if let Some(c) = &b.comment {
            if st.parens {
                out.s(" (");
                push_comment_text(out, c, true);
                out.c(')');
            } else {
                out.s(" ; ");
                push_comment_text(out, c, false);
            }
        }
        out.c('\n');
        prev = Some(&b.target);
    }
    footer(out, st, &mut ln);
    Ok(())
}
