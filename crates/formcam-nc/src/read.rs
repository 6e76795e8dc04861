//! Readers: G-code (ISO, LinuxCNC, Marlin, Sinumerik 840D) and APT CLDATA
//! back into a [`Program`].
//!
//! # G-code ([`read_gcode`])
//!
//! Parsed with the `gcode` crate, after a light pre-pass for Sinumerik:
//! `NAME=value` words (`J1=12.5`, `X=3`; separated from other words by a
//! space, the value a plain number) are taken out of the line before the
//! parser sees it. Numbers are read again from the source text in `f64` (the
//! parser's own values are `f32`).
//!
//! Understood: `G0`/`G00` and `G1`/`G01` (modal), `G90`/`G91` (absolute,
//! incremental), `G93`/`G94` (inverse time: `F` on every feed block, block
//! time `60 / F` s; per minute: `F` modal), `F`, axis words of the given
//! axes, `N` numbers, `%`, `O` numbers (the comment on the `O` line is the
//! program's name), `(…)` and `;…` comments. Other G codes (`G17`, `G21`,
//! `G71`, `G54`, …), M codes, `T`, `S` and words of letters that are no NC
//! axis are passed over; the arguments of `G4` (dwell) too. Errors: arcs
//! (`G2`/`G3`), inch units (`G20`/`G70`), feed per revolution (`G95`), an
//! axis word (`X Y Z A B C U V W` or `NAME=`) that is not one of the given
//! axes, axis words before any `G0`/`G1`, a feed block without a feed, and
//! whatever the parser rejects — every error with its line number.
//!
//! Modulo rotary axes ([`crate::modulo`]) come back as unwound angles:
//! `G92` with axis words sets those axes' values without moving (the blocks
//! after it are read in the shifted frame, and the next block is marked
//! [`Block::rezero`](crate::Block::rezero)); Sinumerik `A=ACP(v)`,
//! `A=ACN(v)` and `A=DC(v)` go to `v` modulo 360° in the positive, negative
//! or shorter direction; with [`read_gcode_in`] and the LinuxCNC dialect, a
//! plain word of a modulo axis is a wrapped rotary position (`A-v`: to `|v|`
//! in the negative direction). In each case the axis stays put when `v` is
//! where it stands.
//!
//! Axes not yet programmed start at 0. Comments: on a motion line, the
//! block's comment; a comment line before the first motion, a header comment
//! (`PROGRAM name` gives the name); a comment line after it, the comment of
//! the next motion block.
//!
//! # CLDATA ([`read_cldata`])
//!
//! `PARTNO/name`, `UNITS/MM`, `$$` comments (header comments up to the first
//! statement after `PARTNO`, then the comment of the next `GOTO`), `RAPID` (the next `GOTO` only),
//! `FEDRAT/f[,MMPM]` and `FEDRAT/f,INVERS` (modal), `GOTO/v1,..,vn` with one
//! value per axis, `ORIGIN/A,o` (the values of axis `A` from there on
//! measured from `o`; the next block marked re-zeroed), `FINI`. Other statements are passed over; `UNITS/INCHES`
//! and inch or per-revolution feeds are errors. `$` continuation lines are not
//! supported.

use gcode::{Code, CommentKind};

use crate::modulo::{Direction, unwrap};
use crate::program::check_axes;
use crate::{AxisSpec, Block, Dialect, Feed, Motion, NcError, Program};

/// What the pre-pass took out of one line.
#[derive(Default)]
struct LineExtra {
    /// `NAME=value` words, with the direction of `ACP(..)`, `ACN(..)`, `DC(..)`.
    named: Vec<(String, f64, Option<Direction>)>,
    /// The line starts with an `O` program number.
    program_number: bool,
}

/// Takes `NAME=value` words out of `line` (blanking them) and notes `O` lines.
fn prepass(line: &str, lineno: usize, out: &mut String) -> Result<LineExtra, NcError> {
    let b = line.as_bytes();
    let mut bytes = b.to_vec();
    let mut extra = LineExtra::default();
    let t = line.trim_start();
    extra.program_number = (t.starts_with('O') || t.starts_with('o'))
        && t[1..].starts_with(|c: char| c.is_ascii_digit());
    let mut depth = 0usize;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if depth > 0 {
            match c {
                b'(' => depth += 1,
                b')' => depth -= 1,
                _ => {}
            }
            i += 1;
            continue;
        }
        match c {
            b'(' => depth = 1,
            b';' => break,
            b'=' => {
                let mut s = i;
                while s > 0 && (b[s - 1].is_ascii_alphanumeric() || b[s - 1] == b'_') {
                    s -= 1;
                }
                if s == i || !b[s].is_ascii_alphabetic() {
                    return Err(NcError::parse(
                        lineno,
                        "`=` without an address name before it",
                    ));
                }
                let name = &line[s..i];
                let mut e = i + 1;
                while e < b.len() && b[e] == b' ' {
                    e += 1;
                }
                // `ACP(`, `ACN(`, `DC(`: a direction, the number in parentheses.
                let mut dir = None;
                for (f, d) in [
                    ("ACP(", Direction::Positive),
                    ("ACN(", Direction::Negative),
                    ("DC(", Direction::Shortest),
                ] {
                    if b[e..]
                        .get(..f.len())
                        .is_some_and(|w| w.eq_ignore_ascii_case(f.as_bytes()))
                    {
                        dir = Some(d);
                        e += f.len();
                        break;
                    }
                }
                let vs = e;
                if e < b.len() && (b[e] == b'-' || b[e] == b'+') {
                    e += 1;
                }
                while e < b.len() && (b[e].is_ascii_digit() || b[e] == b'.') {
                    e += 1;
                }
                let value: f64 = line[vs..e].parse().map_err(|_| {
                    NcError::parse(lineno, format!("`{name}=` is not followed by a number"))
                })?;
                if dir.is_some() {
                    if b.get(e) != Some(&b')') {
                        return Err(NcError::parse(
                            lineno,
                            format!("`{name}=`: the number in parentheses is not closed"),
                        ));
                    }
                    e += 1;
                }
                extra.named.push((name.to_string(), value, dir));
                bytes[s..e].fill(b' ');
                i = e;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    // Only ASCII bytes were blanked, so the line is still UTF-8.
    out.push_str(&String::from_utf8_lossy(&bytes));
    Ok(extra)
}

/// The value of an argument, read again from the source in `f64`.
fn value_f64(src: &str, span: gcode::core::Span, value: &gcode::Value) -> Option<f64> {
    let text = src.get(span.start..span.end())?;
    let digits: String = text
        .chars()
        .skip(1)
        .filter(|c| !c.is_whitespace())
        .collect();
    digits.parse::<f64>().ok().or(match value {
        gcode::Value::Literal(v) => Some(f64::from(*v)),
        _ => None,
    })
}

const AXIS_LETTERS: &str = "XYZABCUVW";

/// The reader's modal state and the program read so far.
struct Reader<'a> {
    axes: &'a [AxisSpec],
    program: Program,
    motion: Option<Motion>,
    incremental: bool,
    inverse: bool,
    feed: Option<f64>,
    /// Where the axes stand (unwound angles for modulo axes).
    pos: Vec<f64>,
    /// What a `G92` or `ORIGIN` shifted each axis by: written = pos - offset.
    offset: Vec<f64>,
    /// Plain words of modulo axes are wrapped rotary positions (LinuxCNC).
    wrapped: bool,
    /// The next block follows a re-zero.
    rezeroed: bool,
    pending: Option<String>,
}

impl<'a> Reader<'a> {
    fn new(axes: &'a [AxisSpec]) -> Result<Self, NcError> {
        check_axes(axes)?;
        Ok(Self {
            axes,
            program: Program::new("", axes.to_vec()),
            motion: None,
            incremental: false,
            inverse: false,
            feed: None,
            pos: vec![0.0; axes.len()],
            offset: vec![0.0; axes.len()],
            wrapped: false,
            rezeroed: false,
            pending: None,
        })
    }

    fn axis_names(&self) -> String {
        self.axes
            .iter()
            .map(|a| a.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// A comment line (no motion on it).
    fn comment_line(&mut self, text: String) {
        if self.program.blocks.is_empty() {
            match text.strip_prefix("PROGRAM ") {
                Some(name) if self.program.name.is_empty() => {
                    self.program.name = name.trim().to_string();
                }
                _ => self.program.header_comments.push(text),
            }
        } else {
            self.pending = Some(match self.pending.take() {
                Some(p) => format!("{p}; {text}"),
                None => text,
            });
        }
    }

    fn join_comment(&mut self, inline: Option<String>) -> Option<String> {
        match (self.pending.take(), inline) {
            (Some(p), Some(c)) => Some(format!("{p}; {c}")),
            (p, c) => p.or(c),
        }
    }
}

/// Reads G-code written by formcam's ISO, LinuxCNC, Marlin or Sinumerik 840D
/// writers (and similar hand-written programs) on `axes` (see the module
/// documentation for what is understood). A plain word of a modulo axis is an
/// absolute angle (in the frame of the last `G92`); for LinuxCNC's wrapped
/// rotary axes use [`read_gcode_in`].
pub fn read_gcode(text: &str, axes: &[AxisSpec]) -> Result<Program, NcError> {
    read_gcode_with(text, axes, false)
}

/// Reads G-code as [`read_gcode`] does, as `dialect` means it: with
/// [`Dialect::LinuxCnc`] a plain word of a modulo axis is a wrapped rotary
/// position, `|v| < 360` and the sign the direction. `Dialect::Cldata` is
/// not G-code: use [`read_cldata`].
pub fn read_gcode_in(text: &str, axes: &[AxisSpec], dialect: Dialect) -> Result<Program, NcError> {
    read_gcode_with(text, axes, dialect == Dialect::LinuxCnc)
}

fn read_gcode_with(text: &str, axes: &[AxisSpec], wrapped: bool) -> Result<Program, NcError> {
    let mut r = Reader::new(axes)?;
    r.wrapped = wrapped;
    let mut src = String::with_capacity(text.len());
    let mut extras = Vec::new();
    for (i, line) in text.split('\n').enumerate() {
        if i > 0 {
            src.push('\n');
        }
        extras.push(prepass(line, i + 1, &mut src)?);
    }
    let parsed = gcode::parse(&src).map_err(|d| {
        d.iter()
            .min_by_key(|d| d.span.line)
            .map_or(NcError::parse(0, "G-code parse error"), |d| {
                NcError::parse(d.span.line + 1, d.kind.to_string())
            })
    })?;
    let mut by_line: Vec<Option<&gcode::Block>> = vec![None; extras.len()];
    for b in &parsed.blocks {
        if let Some(slot) = by_line.get_mut(b.span.line) {
            *slot = Some(b);
        }
    }

    for (i, (block, extra)) in by_line.into_iter().zip(&extras).enumerate() {
        let lineno = i + 1;
        let mut comments: Vec<String> = Vec::new();
        // (axis index, value, direction)
        let mut axis_words: Vec<(usize, f64, Option<Direction>)> = Vec::new();
        let mut preset = false;
        let mut f_word: Option<f64> = None;
        let mut word = |r: &Reader<'_>, letter: char, v: f64| -> Result<(), NcError> {
            let letter = letter.to_ascii_uppercase();
            if letter == 'F' {
                f_word = Some(v);
            } else if let Some(k) = r
                .axes
                .iter()
                .position(|a| a.name.len() == 1 && a.name.starts_with(letter))
            {
                axis_words.push((k, v, None));
            } else if AXIS_LETTERS.contains(letter) {
                return Err(NcError::parse(
                    lineno,
                    format!(
                        "axis word {letter} is not one of the program's axes ({})",
                        r.axis_names()
                    ),
                ));
            }
            Ok(())
        };
        if let Some(b) = block {
            for c in &b.comments {
                let v = match c.kind {
                    CommentKind::Parentheses => c.value.strip_suffix(')').unwrap_or(&c.value),
                    _ => c.value.as_str(),
                };
                comments.push(v.trim().to_string());
            }
            for code in &b.codes {
                let Code::General(g) = code else { continue };
                let minor = g.number.minor().map(|m| m.get());
                let mut dwell = false;
                match (g.number.major(), minor) {
                    (0, None) => r.motion = Some(Motion::Rapid),
                    (1, None) => r.motion = Some(Motion::Linear),
                    (2 | 3, None) => {
                        return Err(NcError::parse(lineno, "arcs (G2/G3) are not supported"));
                    }
                    (4, None) => dwell = true,
                    (20 | 70, None) => {
                        return Err(NcError::parse(lineno, "inch units are not supported"));
                    }
                    (90, None) => r.incremental = false,
                    (92, None) => preset = true,
                    (92, Some(_)) => {
                        return Err(NcError::parse(
                            lineno,
                            "G92.1, G92.2 and G92.3 are not supported",
                        ));
                    }
                    (91, None) => r.incremental = true,
                    (93, None) => r.inverse = true,
                    (94, None) => r.inverse = false,
                    (95, None) => {
                        return Err(NcError::parse(
                            lineno,
                            "feed per revolution (G95) is not supported",
                        ));
                    }
                    _ => {}
                }
                if dwell {
                    continue;
                }
                for a in &g.args {
                    let v = value_f64(&src, a.span, &a.value).ok_or_else(|| {
                        NcError::parse(lineno, format!("word {} has no numeric value", a.letter))
                    })?;
                    word(&r, a.letter, v)?;
                }
            }
            for w in &b.word_addresses {
                let v = value_f64(&src, w.span, &w.value).ok_or_else(|| {
                    NcError::parse(lineno, format!("word {} has no numeric value", w.letter))
                })?;
                word(&r, w.letter, v)?;
            }
        }
        for (name, v, dir) in &extra.named {
            match r
                .axes
                .iter()
                .position(|a| a.name.eq_ignore_ascii_case(name))
            {
                Some(k) => axis_words.push((k, *v, *dir)),
                None => {
                    return Err(NcError::parse(
                        lineno,
                        format!(
                            "`{name}=` is not one of the program's axes ({})",
                            r.axis_names()
                        ),
                    ));
                }
            }
        }

        if extra.program_number {
            if r.program.name.is_empty()
                && let Some(c) = comments.first()
            {
                r.program.name = c.clone();
            }
            continue;
        }
        if let Some(f) = f_word {
            if !(f.is_finite() && f > 0.0) {
                return Err(NcError::parse(lineno, format!("feed F{f} is not positive")));
            }
            if !r.inverse {
                r.feed = Some(f);
            }
        }
        let inline = (!comments.is_empty()).then(|| comments.join("; "));
        if preset {
            // `G92`: the axes named take these values where they stand.
            for (k, v, _) in axis_words.drain(..) {
                r.offset[k] = r.pos[k] - v;
            }
            r.rezeroed = true;
        }
        if axis_words.is_empty() {
            if let Some(c) = inline {
                r.comment_line(c);
            }
            continue;
        }
        let Some(kind) = r.motion else {
            return Err(NcError::parse(lineno, "axis words before any G0 or G1"));
        };
        let mut target = r.pos.clone();
        for (k, v, dir) in axis_words {
            let wrapped = r.wrapped && r.axes[k].modulo;
            target[k] = match (r.incremental, dir) {
                (true, _) => r.pos[k] + v,
                (false, Some(d)) => unwrap(r.pos[k], v, d),
                (false, None) if wrapped => {
                    let d = if v.is_sign_negative() {
                        Direction::Negative
                    } else {
                        Direction::Positive
                    };
                    unwrap(r.pos[k], v.abs(), d)
                }
                (false, None) => v + r.offset[k],
            };
        }
        let feed = match kind {
            Motion::Rapid => Feed::None,
            Motion::Linear if r.inverse => match f_word {
                Some(f) => Feed::InverseTime(60.0 / f),
                None => {
                    return Err(NcError::parse(lineno, "inverse-time (G93) move without F"));
                }
            },
            Motion::Linear => match r.feed {
                Some(f) => Feed::PerMinute(f),
                None => return Err(NcError::parse(lineno, "feed move without a feed (F)")),
            },
        };
        let comment = r.join_comment(inline);
        r.pos.clone_from(&target);
        r.program.blocks.push(Block {
            kind,
            target,
            feed,
            comment,
            rezero: std::mem::take(&mut r.rezeroed),
        });
    }
    Ok(r.program)
}

fn number(text: &str, lineno: usize, what: &str) -> Result<f64, NcError> {
    let t = text.trim();
    t.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| NcError::parse(lineno, format!("{what}: `{t}` is not a number")))
}

/// Reads APT CLDATA as formcam's CLDATA writer writes it (machine-axis
/// `GOTO` records) on `axes` (see the module documentation).
pub fn read_cldata(text: &str, axes: &[AxisSpec]) -> Result<Program, NcError> {
    let mut r = Reader::new(axes)?;
    let mut rapid = false;
    // (value, inverse)
    let mut feed: Option<(f64, bool)> = None;
    let mut in_header = true;
    // Records continued after a `$` are joined (errors name their first line).
    let mut records: Vec<(usize, String)> = Vec::new();
    let mut open = false;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        let cont = !line.starts_with("$$") && line.ends_with('$') && !line.ends_with("$$");
        let body = if cont { &line[..line.len() - 1] } else { line };
        match records.last_mut() {
            Some((_, r)) if open => r.push_str(body),
            _ => records.push((i + 1, body.to_string())),
        }
        open = cont;
    }
    for (lineno, line) in &records {
        let (lineno, line) = (*lineno, line.as_str());
        if let Some(c) = line.strip_prefix("$$") {
            let c = c.trim().to_string();
            if in_header {
                r.program.header_comments.push(c);
            } else {
                r.pending = Some(match r.pending.take() {
                    Some(p) => format!("{p}; {c}"),
                    None => c,
                });
            }
            continue;
        }
        let stmt = line.split("$$").next().unwrap_or("").trim();
        if stmt.is_empty() {
            continue;
        }
        let (word, args) = match stmt.split_once('/') {
            Some((w, a)) => (w.trim().to_ascii_uppercase(), a),
            None => (stmt.to_ascii_uppercase(), ""),
        };
        in_header &= word == "PARTNO";
        match word.as_str() {
            "PARTNO" => r.program.name = args.trim().to_string(),
            "UNITS" if !args.trim().eq_ignore_ascii_case("MM") => {
                return Err(NcError::parse(
                    lineno,
                    format!("UNITS/{}: only MM is supported", args.trim()),
                ));
            }
            "RAPID" => rapid = true,
            "ORIGIN" => {
                let mut parts = args.split(',');
                let name = parts.next().unwrap_or("").trim();
                let k = r
                    .axes
                    .iter()
                    .position(|a| a.name.eq_ignore_ascii_case(name))
                    .ok_or_else(|| {
                        NcError::parse(
                            lineno,
                            format!(
                                "ORIGIN/{name}: not one of the program's axes ({})",
                                r.axis_names()
                            ),
                        )
                    })?;
                r.offset[k] = number(parts.next().unwrap_or(""), lineno, "ORIGIN")?;
                r.rezeroed = true;
            }
            "FEDRAT" => {
                let mut parts = args.split(',');
                let f = number(parts.next().unwrap_or(""), lineno, "FEDRAT")?;
                let unit = parts.next().map(|u| u.trim().to_ascii_uppercase());
                let inverse = match unit.as_deref() {
                    None | Some("MMPM") => false,
                    Some("INVERS") => true,
                    Some(u) => {
                        return Err(NcError::parse(
                            lineno,
                            format!("FEDRAT unit {u}: only MMPM and INVERS are supported"),
                        ));
                    }
                };
                if f <= 0.0 {
                    return Err(NcError::parse(
                        lineno,
                        format!("FEDRAT/{f} is not positive"),
                    ));
                }
                feed = Some((f, inverse));
            }
            "GOTO" => {
                let values = args
                    .split(',')
                    .zip(r.offset.iter().chain(std::iter::repeat(&0.0)))
                    .map(|(v, o)| number(v, lineno, "GOTO").map(|v| v + o))
                    .collect::<Result<Vec<_>, _>>()?;
                if values.len() != axes.len() {
                    return Err(NcError::parse(
                        lineno,
                        format!(
                            "GOTO has {} values for {} axes ({})",
                            values.len(),
                            axes.len(),
                            r.axis_names()
                        ),
                    ));
                }
                let (kind, feed) = if rapid {
                    (Motion::Rapid, Feed::None)
                } else {
                    match feed {
                        Some((f, false)) => (Motion::Linear, Feed::PerMinute(f)),
                        Some((f, true)) => (Motion::Linear, Feed::InverseTime(60.0 / f)),
                        None => return Err(NcError::parse(lineno, "GOTO before any FEDRAT")),
                    }
                };
                rapid = false;
                let comment = r.join_comment(None);
                r.program.blocks.push(Block {
                    kind,
                    target: values,
                    feed,
                    comment,
                    rezero: std::mem::take(&mut r.rezeroed),
                });
            }
            "FINI" => break,
            _ => {}
        }
    }
    Ok(r.program)
}
