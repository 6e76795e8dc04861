//! [`read_toolpath`]: a milling program line by line — lexed, its G codes
//! applied to the modal state, its move turned into nodes (arcs and long
//! moves in pieces) — and the number style it was written in.

use formcam_files::quote;
use std::ops::Range;

use super::arc::{Arc, Centre};
use super::refuse::{self, Verdict};
use super::{
    ArcEdit, Line, MotionLine, Node, NodeKind, NumSpan, NumberFormat, Toolpath, ToolpathOptions,
};
use crate::lex::{self, Lexed, Syntax, Word, line_error};
use crate::modal::{GCode, Modal, MotionMode};
use crate::{Dialect, NcError, ProgramFault, Refusal};

/// Reads a milling program.
pub fn read_toolpath(text: &str, options: &ToolpathOptions) -> Result<Toolpath, NcError> {
    check_options(options)?;
    let mut reader = Reader {
        text,
        options,
        syntax: Syntax::milling(options.dialect),
        modal: Modal::default(),
        position: [f64::NAN; 3],
        lines: Vec::new(),
        nodes: Vec::new(),
        arcs: 0,
        segments: 0,
        style: Style::default(),
    };
    for (lineno, (line, eol)) in lex::lines(text).enumerate() {
        reader.line(lineno + 1, line, eol)?;
    }
    let format = reader.style.format(text, &reader.lines);
    Ok(Toolpath {
        text: text.to_string(),
        lines: reader.lines,
        nodes: reader.nodes,
        arcs_linearised: reader.arcs,
        moves_split: reader.segments,
        dialect: options.dialect,
        format,
    })
}

fn check_options(options: &ToolpathOptions) -> Result<(), NcError> {
    if options.dialect == Dialect::Cldata {
        return Err(ProgramFault::CldataToolpath.into());
    }
    if let Some(m) = options.max_segment_mm
        && !(m.is_finite() && m > 0.0)
    {
        return Err(ProgramFault::SegmentNotPositive { mm: m }.into());
    }
    if !(options.arc_tolerance_mm.is_finite() && options.arc_tolerance_mm > 0.0) {
        return Err(ProgramFault::ArcToleranceNotPositive {
            mm: options.arc_tolerance_mm,
        }
        .into());
    }
    Ok(())
}

/// The reader's state between lines.
struct Reader<'a> {
    text: &'a str,
    options: &'a ToolpathOptions,
    syntax: Syntax,
    modal: Modal,
    /// The tool's position (mm; NaN: unknown).
    position: [f64; 3],
    lines: Vec<Line>,
    nodes: Vec<Node>,
    arcs: usize,
    segments: usize,
    style: Style,
}

/// Why a line is not read: a message, or a word refused.
enum Fault {
    /// What is wrong, in words.
    Text(String),
    /// A word the reader does not follow.
    Refused(Refusal),
}

impl From<String> for Fault {
    fn from(what: String) -> Self {
        Self::Text(what)
    }
}

impl From<Refusal> for Fault {
    fn from(refusal: Refusal) -> Self {
        Self::Refused(refusal)
    }
}

/// The fault `refusal` at line `line`, whose text is `text`.
fn refused(line: usize, text: &str, refusal: Refusal) -> NcError {
    ProgramFault::Refused {
        line,
        excerpt: quote(text.trim_end()).to_string(),
        refusal,
    }
    .into()
}

/// What the words of one line say.
#[derive(Default)]
struct LineWords<'l> {
    axes: [Option<&'l Word>; 3],
    centre: [Option<&'l Word>; 3],
    /// The radius (program units) and its word.
    radius: Option<(f64, Range<usize>)>,
    /// The `G0..G3` word.
    g_motion: Option<&'l Word>,
    /// `P` (turns of an arc).
    turns: Option<&'l Word>,
    /// A dwell or home line: its axis words are no move.
    passive: bool,
    /// `G28`, `G30`, `G53`: the axes named become unknown.
    forget: bool,
    /// `G28`/`G30` (which, without axis words, home every axis).
    bare_home: bool,
    /// A G code the reader does not know (refused on a line with a move).
    unknown_g: Option<String>,
}

impl LineWords<'_> {
    fn has_axis(&self) -> bool {
        self.axes.iter().any(Option::is_some)
    }

    fn has_centre(&self) -> bool {
        self.centre.iter().any(Option::is_some) || self.radius.is_some()
    }
}

impl Reader<'_> {
    /// Reads line `lineno` (text `range`, terminator `eol`).
    fn line(
        &mut self,
        lineno: usize,
        range: Range<usize>,
        eol: Range<usize>,
    ) -> Result<(), NcError> {
        let src = self.text;
        let text = &src[range.clone()];
        let err = |what: String| line_error(lineno, text, what);
        let dialect = self.options.dialect;
        if eol.is_empty()
            && let Some(cut) = refuse::truncated(text, dialect)
        {
            return Err(ProgramFault::Truncated {
                line: lineno,
                excerpt: quote(text.trim_end()).to_string(),
                cut,
            }
            .into());
        }
        refuse::keywords(text, dialect).map_err(|r| refused(lineno, text, r))?;
        let lx = lex::lex(text, range.start, lineno, self.syntax)?;
        let first = text.trim_start();
        let program_number = first.starts_with(['O', 'o', '%', '#', ':']);
        let words = self
            .words(&lx, program_number)
            .map_err(|fault| match fault {
                Fault::Text(what) => err(what),
                Fault::Refused(r) => refused(lineno, text, r),
            })?;
        if let Some(c) = &lx.complex {
            let iso_ident = !self.syntax.sinumerik
                && !program_number
                && c.as_bytes().first().is_some_and(u8::is_ascii_alphabetic);
            if words.has_axis() || words.has_centre() || iso_ident {
                return Err(err(format!("cannot read `{}`", quote(c))));
            }
        }
        let mut line = Line {
            text: range.clone(),
            eol,
            motion: None,
            forgets: [false; 3],
        };
        if words.forget {
            self.forget(&words, &mut line.forgets);
        }
        let is_arc = matches!(
            self.modal.motion,
            Some(MotionMode::ArcCw | MotionMode::ArcCcw)
        ) && (words.has_axis() || words.has_centre());
        if !words.passive && (words.has_axis() || is_arc) && !program_number {
            let motion = self
                .motion_block(&lx, &words, is_arc, lineno, range.end)
                .map_err(err)?;
            line.motion = Some(motion);
        }
        self.lines.push(line);
        Ok(())
    }

    /// Sorts the words of a line and applies its G codes to the modal state.
    fn words<'l>(&mut self, lx: &'l Lexed, program_number: bool) -> Result<LineWords<'l>, Fault> {
        let mut w = LineWords {
            radius: lx.cr.clone(),
            ..LineWords::default()
        };
        let sinumerik = self.syntax.sinumerik;
        let moves = lx.cr.is_some()
            || lx.words.iter().any(|w| {
                matches!(w.letter, b'X' | b'Y' | b'Z' | b'I' | b'J' | b'K')
                    || (w.letter == b'R' && !sinumerik)
            });
        for word in &lx.words {
            match word.letter {
                b'X' | b'Y' | b'Z' => {
                    let a = (word.letter - b'X') as usize;
                    if w.axes[a].is_some() {
                        return Err(format!("`{}` twice", word.letter as char).into());
                    }
                    w.axes[a] = Some(word);
                }
                b'I' | b'J' | b'K' => w.centre[(word.letter - b'I') as usize] = Some(word),
                b'P' => w.turns = Some(word),
                b'R' if !self.syntax.sinumerik => w.radius = Some((word.value, word.whole.clone())),
                b'A' | b'B' | b'C' | b'U' | b'V' | b'W' if !program_number => {
                    return Err(format!(
                        "axis `{}`: only X, Y and Z are read",
                        word.letter as char
                    )
                    .into());
                }
                b'G' => self.g_word(word, moves, &mut w)?,
                b'M' => {
                    if let Some(r) = refuse::m_code(word.value) {
                        return Err(r.into());
                    }
                }
                b'L' if sinumerik => {
                    return Err(Refusal::Subprogram {
                        word: format!("L{}", word.value),
                    }
                    .into());
                }
                _ => {}
            }
        }
        if moves && let Some(word) = w.unknown_g.take() {
            return Err(Refusal::AxesWithCode { word }.into());
        }
        Ok(w)
    }

    /// A `G` word: its mode taken on, passed over, or refused; `moves`:
    /// the line has axis, centre or radius words.
    fn g_word<'l>(
        &mut self,
        word: &'l Word,
        moves: bool,
        w: &mut LineWords<'l>,
    ) -> Result<(), Fault> {
        let Some(code) = GCode::of(word.value, self.syntax.sinumerik) else {
            return Err(format!("`G{}` is not a G code", word.value).into());
        };
        match refuse::g_code(word.value, code, self.options.dialect, moves) {
            Verdict::Refused(r) => return Err(r.into()),
            Verdict::Unknown => {
                w.unknown_g
                    .get_or_insert_with(|| format!("G{}", word.value));
            }
            Verdict::Passed => {}
        }
        match code {
            GCode::Motion(_) => {
                w.g_motion = Some(word);
                self.style.g_word(word.num.len());
            }
            GCode::Inch => self.style.inch = true,
            GCode::Dwell => w.passive = true,
            GCode::Home(g) => {
                w.passive = true;
                w.forget = true;
                w.bare_home |= g != 53;
            }
            _ => {}
        }
        self.modal.apply(code);
        Ok(())
    }

    /// The axes a `G28`/`G30`/`G53` line leaves unknown.
    fn forget(&mut self, words: &LineWords<'_>, forgets: &mut [bool; 3]) {
        // `G28`/`G30` without axis words send every axis home.
        let all = words.bare_home && !words.has_axis();
        for (a, w) in words.axes.iter().enumerate() {
            if w.is_some() || all {
                self.position[a] = f64::NAN;
                forgets[a] = true;
            }
        }
    }

    /// The move of a line: its target, its nodes and its editable parts.
    fn motion_block(
        &mut self,
        lx: &Lexed,
        words: &LineWords<'_>,
        is_arc: bool,
        lineno: usize,
        line_end: usize,
    ) -> Result<MotionLine, String> {
        let Some(motion) = self.modal.motion else {
            return Err("an axis word before any G0/G1/G2/G3".into());
        };
        self.style.axis_words(&words.axes);
        let from = self.position;
        let to = self.target(&words.axes)?;
        let first_node = self.nodes.len();
        let arc = if is_arc {
            self.arc_nodes(lx, words, motion, from, to, lineno, line_end)
                .map(Some)?
        } else {
            self.straight_nodes(motion, from, to, lineno)?;
            None
        };
        self.position = to;
        if lx.words.len() > 1 {
            self.style.line(lx.spaced);
        }
        Ok(MotionLine {
            words: words.axes.map(|w| {
                w.map(|w| NumSpan {
                    range: w.num.clone(),
                    value: w.value,
                })
            }),
            insert_at: insert_at(lx, &words.axes),
            incremental: self.modal.incremental,
            scale: self.modal.scale(),
            nodes: first_node..self.nodes.len(),
            arc,
            block_delete: lx.block_delete,
        })
    }

    /// Where the axis words take the tool (mm).
    fn target(&self, axes: &[Option<&Word>; 3]) -> Result<[f64; 3], String> {
        let from = self.position;
        let mut to = from;
        for (a, w) in axes.iter().enumerate() {
            if let Some(w) = w {
                let v = w.value * self.modal.scale();
                to[a] = if self.modal.incremental {
                    if from[a].is_nan() {
                        return Err(format!(
                            "an incremental move of {} from an unknown position",
                            (b'X' + a as u8) as char
                        ));
                    }
                    from[a] + v
                } else {
                    v
                };
            }
        }
        Ok(to)
    }

    /// The nodes of an arc block, and the edits that make it a `G1` block.
    #[allow(clippy::too_many_arguments)]
    fn arc_nodes(
        &mut self,
        lx: &Lexed,
        words: &LineWords<'_>,
        motion: MotionMode,
        from: [f64; 3],
        to: [f64; 3],
        lineno: usize,
        line_end: usize,
    ) -> Result<ArcEdit, String> {
        if self.modal.inverse_time {
            return Err("arcs in inverse-time feed (G93) are not supported".into());
        }
        if let Some(p) = words.turns
            && p.value != 1.0
        {
            return Err(format!(
                "arcs of several turns (P{}) are not supported",
                p.value
            ));
        }
        let scale = self.modal.scale();
        let centre = match &words.radius {
            Some((r, _)) => Centre::Radius(r * scale),
            None => Centre::Offsets {
                ijk: words.centre.map(|w| w.map(|w| w.value * scale)),
                absolute: self.modal.centre_absolute,
            },
        };
        let arc = Arc::new(
            from,
            to,
            self.modal.plane,
            motion == MotionMode::ArcCw,
            &centre,
        )?;
        for position in arc.chord_ends(self.options.arc_tolerance_mm)? {
            self.nodes.push(Node {
                position,
                kind: NodeKind::Arc,
                line: lineno,
            });
        }
        self.arcs += 1;
        let mut remove: Vec<Range<usize>> = lx
            .words
            .iter()
            .filter(|w| {
                matches!(w.letter, b'I' | b'J' | b'K' | b'P')
                    || (w.letter == b'R' && !self.syntax.sinumerik)
            })
            .map(|w| w.whole.clone())
            .collect();
        if let Some((_, r)) = &lx.cr {
            remove.push(r.clone());
        }
        let g_insert_at = lx
            .words
            .iter()
            .find(|w| w.letter != b'N')
            .map_or(line_end, |w| w.whole.start);
        Ok(ArcEdit {
            g_word: words.g_motion.map(|w| w.whole.clone()),
            g_insert_at,
            remove,
        })
    }

    /// The nodes of a straight move: a long feed move in pieces of at most
    /// `max_segment_mm`.
    fn straight_nodes(
        &mut self,
        motion: MotionMode,
        from: [f64; 3],
        to: [f64; 3],
        lineno: usize,
    ) -> Result<(), String> {
        let length = (0..3)
            .map(|a| (to[a] - from[a]).powi(2))
            .sum::<f64>()
            .sqrt();
        let pieces = match self.options.max_segment_mm {
            Some(max) if motion == MotionMode::Linear && length.is_finite() && length > max => {
                if self.modal.inverse_time {
                    return Err(
                        "splitting moves in inverse-time feed (G93) is not supported".into(),
                    );
                }
                let n = (length / max).ceil();
                if n > 1e6 {
                    return Err(format!(
                        "the move ({length:.3} mm) would need {n:.0} pieces of {max} mm"
                    ));
                }
                self.segments += 1;
                n as usize
            }
            _ => 1,
        };
        let kind = if motion == MotionMode::Rapid {
            NodeKind::Rapid
        } else {
            NodeKind::Feed
        };
        for k in 1..=pieces {
            let f = k as f64 / pieces as f64;
            let mut p = to;
            if k < pieces {
                for a in 0..3 {
                    p[a] = from[a] + (to[a] - from[a]) * f;
                }
            }
            self.nodes.push(Node {
                position: p,
                kind,
                line: lineno,
            });
        }
        Ok(())
    }
}

/// Where a missing axis word goes: after the last axis word, else after the
/// last word that is no centre or radius, else at the end of the code.
fn insert_at(lx: &Lexed, axes: &[Option<&Word>; 3]) -> usize {
    axes.iter()
        .flatten()
        .map(|w| w.whole.end)
        .max()
        .or_else(|| {
            lx.words
                .iter()
                .filter(|w| !matches!(w.letter, b'I' | b'J' | b'K' | b'R'))
                .map(|w| w.whole.end)
                .max()
        })
        .unwrap_or(lx.code_end)
}

/// The number style of the program's motion blocks, tallied while reading.
#[derive(Debug, Default)]
struct Style {
    max_dec: u32,
    whole_point: bool,
    whole_bare: bool,
    any_point: bool,
    g_two_digit: usize,
    g_one_digit: usize,
    inch: bool,
    spaced_lines: usize,
    joined_lines: usize,
}

impl Style {
    /// A motion word (`G1`, `G01`) of `digits` digits.
    fn g_word(&mut self, digits: usize) {
        if digits >= 2 {
            self.g_two_digit += 1;
        } else {
            self.g_one_digit += 1;
        }
    }

    /// The axis words of a move.
    fn axis_words(&mut self, axes: &[Option<&Word>; 3]) {
        for w in axes.iter().flatten() {
            if w.point {
                self.any_point = true;
                self.max_dec = self.max_dec.max(w.decimals);
                if w.decimals == 0 {
                    self.whole_point = true;
                }
            } else {
                self.whole_bare = true;
            }
        }
    }

    /// A motion line of several words, with blanks between them or not.
    fn line(&mut self, spaced: bool) {
        if spaced {
            self.spaced_lines += 1;
        } else {
            self.joined_lines += 1;
        }
    }

    /// The format new numbers are written in.
    fn format(&self, text: &str, lines: &[Line]) -> NumberFormat {
        // Every word with a point has `max_dec` places?
        let padded = lines
            .iter()
            .filter_map(|l| l.motion.as_ref())
            .flat_map(|m| m.words.iter().flatten())
            .all(|w| {
                let t = &text[w.range.clone()];
                t.find('.')
                    .is_none_or(|p| (t.len() - p - 1) as u32 == self.max_dec)
            });
        let least = if self.inch { 4 } else { 3 };
        NumberFormat {
            // At least 3 decimals in mm, 4 in inches, whatever the program
            // wrote: a correction of hundredths must not be rounded away.
            decimals: self.max_dec.max(least),
            // Padding is kept only at the program's own precision.
            padded: padded && self.any_point && self.max_dec >= least,
            whole_point: self.whole_point || !self.whole_bare,
            spaced: self.spaced_lines >= self.joined_lines,
            linear: if self.g_two_digit > self.g_one_digit {
                "G01"
            } else {
                "G1"
            },
        }
    }
}
