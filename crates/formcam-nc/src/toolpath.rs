//! Milling programs read as text lines with their tool-path nodes, and
//! written back with only the coordinates of motion blocks changed.
//!
//! [`read_toolpath`] reads a 3-axis milling program (ISO/Fanuc, Sinumerik
//! 840D, LinuxCNC) into a [`Toolpath`]: the program's lines as they are, and
//! the [`Node`]s — the tool's position (mm) at the end of every motion block.
//! [`Toolpath::write`] writes the program again with new node positions:
//! every line that is not a motion block is kept byte for byte, and in motion
//! blocks only the numbers of the `X`, `Y`, `Z` words change, in the same
//! number format (decimals, padding, a missing word added where an axis now
//! moves).
//!
//! Understood: `G0/G1/G2/G3` (also `G00..G03`, modal), `G90/G91` (absolute,
//! incremental), `G90.1/G91.1` (arc centres absolute or incremental; the
//! default is incremental), `G17/G18/G19` (arc planes), `G20/G21` (inch, mm;
//! `G70/G71`, `G700/G710` on Sinumerik), `I J K` centres, `R` (ISO, LinuxCNC)
//! and `CR=` (Sinumerik) radii, helical arcs, `N` numbers, `/` block delete,
//! `(…)` comments (not on Sinumerik), `;` comments, `%` and program-number
//! lines. `G4` dwell lines are kept as they are; `G28/G30/G53` lines too, and
//! the axes they name become unknown until the program sets them again.
//!
//! Arcs are linearised: every arc block becomes `G1` blocks whose chords stay
//! within `arc_tolerance_mm` of the arc (the first keeps the block's other
//! words, the rest are new lines). The caller says so in the header comment it
//! passes to [`Toolpath::write`].
//!
//! Errors name the line (1-based) and quote its text: an unreadable number, a
//! letter without a value, an expression or keyword in a motion block,
//! coordinate-system changes (`G92`, `G52`, `G10`, `G51`, `G68`, Sinumerik
//! frames), canned cycles, rotary or secondary axes, an incremental move from
//! an unknown position, an arc whose end is not on its circle, arcs in
//! inverse-time feed.

use std::ops::Range;

use crate::NcError;

/// Which controller's syntax a program is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flavor {
    /// ISO / Fanuc: `(…)` comments, `R` arc radii.
    Iso,
    /// Siemens Sinumerik 840D: `;` comments, `CR=` radii, keywords on their own lines.
    Sinumerik,
    /// LinuxCNC: `(…)` and `;` comments, `R` radii.
    LinuxCnc,
}

impl Flavor {
    /// The flavor named `iso`, `fanuc`, `sinumerik-840d`, `840d` or `linuxcnc`.
    pub fn from_name(name: &str) -> Result<Self, NcError> {
        match name.to_ascii_lowercase().as_str() {
            "iso" | "fanuc" => Ok(Self::Iso),
            "sinumerik-840d" | "sinumerik" | "840d" => Ok(Self::Sinumerik),
            "linuxcnc" => Ok(Self::LinuxCnc),
            _ => Err(NcError::UnknownDialect {
                name: name.to_string(),
                allowed: "iso, fanuc, sinumerik-840d, linuxcnc".into(),
            }),
        }
    }

    /// The flavor a file extension suggests: `mpf`/`spf` Sinumerik, `ngc`
    /// LinuxCNC, anything else ISO.
    pub fn from_extension(ext: &str) -> Self {
        match ext.to_ascii_lowercase().as_str() {
            "mpf" | "spf" => Self::Sinumerik,
            "ngc" => Self::LinuxCnc,
            _ => Self::Iso,
        }
    }
}

/// How a node was reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeKind {
    /// A rapid move (`G0`).
    Rapid,
    /// A straight feed move (`G1`).
    Feed,
    /// A point of a linearised arc (`G2`/`G3`).
    Arc,
}

/// A node of the tool path: the tool's position at the end of a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// `X, Y, Z` in mm; NaN for an axis the program has not set yet.
    pub position: [f64; 3],
    /// The move that reached it.
    pub kind: NodeKind,
    /// The program line (1-based).
    pub line: usize,
}

/// Reading options.
#[derive(Debug, Clone, Copy)]
pub struct ToolpathOptions {
    /// The syntax.
    pub flavor: Flavor,
    /// The largest distance of an arc's chords from the arc, mm (> 0).
    pub arc_tolerance_mm: f64,
    /// Straight feed moves (`G1`) longer than this (mm) are split into equal
    /// pieces, each a node (written back as `G1` lines), so that a correction
    /// can bend them; `None` keeps them whole.
    pub max_segment_mm: Option<f64>,
}

impl Default for ToolpathOptions {
    fn default() -> Self {
        Self {
            flavor: Flavor::Iso,
            arc_tolerance_mm: 0.001,
            max_segment_mm: None,
        }
    }
}

/// The number of one axis word in the text.
#[derive(Debug, Clone)]
struct NumSpan {
    /// Bytes of the number (after the letter, `=` and blanks).
    range: Range<usize>,
    /// The value as written (program units).
    value: f64,
}

/// A motion block's editable parts.
#[derive(Debug, Clone)]
struct MotionLine {
    /// The `X`, `Y`, `Z` numbers.
    words: [Option<NumSpan>; 3],
    /// Where a missing axis word goes (a byte offset in the text).
    insert_at: usize,
    /// Incremental (`G91`) block.
    incremental: bool,
    /// mm per program unit.
    scale: f64,
    /// The nodes of the block.
    nodes: Range<usize>,
    /// For an arc block: what turns it into a `G1` block.
    arc: Option<ArcEdit>,
    /// The block starts with `/`: so do the lines added after it.
    block_delete: bool,
}

/// The edits that make an arc block a straight one.
#[derive(Debug, Clone)]
struct ArcEdit {
    /// The `G2`/`G3` word (letter and number), if the block has one.
    g_word: Option<Range<usize>>,
    /// Where `G1 ` goes when the arc mode is modal.
    g_insert_at: usize,
    /// The centre and radius words (with the blanks before them).
    remove: Vec<Range<usize>>,
}

/// One line of the program.
#[derive(Debug, Clone)]
struct Line {
    /// The line's text, without its terminator.
    text: Range<usize>,
    /// Its terminator (`\n`, `\r\n`, or empty at the end).
    eol: Range<usize>,
    /// The motion block on it.
    motion: Option<MotionLine>,
    /// Axes this line leaves unknown (`G28`, `G30`, `G53`).
    forgets: [bool; 3],
}

/// A milling program: its text, lines and tool-path nodes.
#[derive(Debug, Clone)]
pub struct Toolpath {
    text: String,
    lines: Vec<Line>,
    /// The nodes in program order.
    pub nodes: Vec<Node>,
    /// Arc blocks that were linearised.
    pub arcs_linearised: usize,
    /// Feed moves split into pieces (`max_segment_mm`).
    pub moves_split: usize,
    flavor: Flavor,
    format: NumberFormat,
}

/// How the program writes coordinates.
#[derive(Debug, Clone, Copy)]
struct NumberFormat {
    /// Decimals of the most precise axis word.
    decimals: u32,
    /// Every word with a point has all `decimals` places (`10.500`).
    padded: bool,
    /// Whole numbers are written with a point (`10.`).
    whole_point: bool,
    /// Blanks between words.
    spaced: bool,
    /// The motion word of added lines (`G1` or `G01`).
    linear: &'static str,
}

/// A word of a line.
#[derive(Debug, Clone)]
struct Word {
    letter: u8,
    value: f64,
    /// Letter to the end of the number.
    whole: Range<usize>,
    /// The number.
    num: Range<usize>,
    /// The number's text had a decimal point.
    point: bool,
    decimals: u32,
}

/// A line split into words.
#[derive(Debug, Default)]
struct Lexed {
    words: Vec<Word>,
    /// `CR=` value and span (Sinumerik).
    cr: Option<(f64, Range<usize>)>,
    /// Something not read as words (keywords, expressions, macros).
    complex: Option<String>,
    /// End of the code before any comment (a byte offset).
    code_end: usize,
    /// Blanks between words.
    spaced: bool,
    /// The line starts with `/` (block delete).
    block_delete: bool,
}

/// Sinumerik keywords that change the coordinate system.
const FRAMES: [&str; 10] = [
    "TRANS", "ATRANS", "ROT", "AROT", "SCALE", "ASCALE", "MIRROR", "AMIRROR", "RPL", "CYCLE800",
];

fn parse_err(line: usize, text: &str, what: impl std::fmt::Display) -> NcError {
    NcError::parse(line, format!("`{}`: {what}", text.trim_end()))
}

/// Reads a number at `b[i..]`: `[+-]digits[.digits]` or `[+-].digits`.
fn number_end(b: &[u8], mut i: usize) -> Option<usize> {
    let start = i;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let digits_from = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let mut any = i > digits_from;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let f = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        any |= i > f;
    }
    (any && i > start).then_some(i)
}

fn lex(text: &str, base: usize, lineno: usize, flavor: Flavor) -> Result<Lexed, NcError> {
    let b = text.as_bytes();
    let mut out = Lexed {
        code_end: base + b.len(),
        ..Lexed::default()
    };
    let mut i = 0;
    let mut blanks = 0usize;
    let mut joins = 0usize;
    let mut last_was_word = false;
    while i < b.len() {
        let c = b[i];
        if c == b' ' || c == b'\t' {
            i += 1;
            if last_was_word {
                blanks += 1;
                last_was_word = false;
            }
            continue;
        }
        if c == b';' {
            out.code_end = base + i;
            break;
        }
        if c == b'(' && flavor != Flavor::Sinumerik {
            match text[i..].find(')') {
                Some(k) => {
                    i += k + 1;
                    last_was_word = false;
                    continue;
                }
                None => return Err(parse_err(lineno, text, "a comment `(` without `)`")),
            }
        }
        if (c == b'/' || c == b'%') && out.words.is_empty() && out.complex.is_none() {
            out.block_delete |= c == b'/';
            i += 1;
            continue;
        }
        if c == b'@' || c == b'^' {
            return Err(parse_err(
                lineno,
                text,
                "polar coordinates (`@`, `^`) are not supported",
            ));
        }
        if c.is_ascii_alphabetic() {
            let s = i;
            let mut e = i + 1;
            while e < b.len() && (b[e].is_ascii_alphabetic() || b[e] == b'_') {
                e += 1;
            }
            if e - s > 1 {
                let ident = text[s..e].to_ascii_uppercase();
                if flavor == Flavor::Sinumerik && ident == "CR" {
                    let mut j = e;
                    while j < b.len() && b[j] == b' ' {
                        j += 1;
                    }
                    if j < b.len() && b[j] == b'=' {
                        j += 1;
                        while j < b.len() && b[j] == b' ' {
                            j += 1;
                        }
                        if let Some(ne) = number_end(b, j) {
                            let v: f64 = text[j..ne].parse().map_err(|_| {
                                parse_err(lineno, text, "an unreadable `CR=` value")
                            })?;
                            out.cr = Some((v, base + s..base + ne));
                            i = ne;
                            last_was_word = true;
                            continue;
                        }
                    }
                }
                if flavor == Flavor::Sinumerik && FRAMES.contains(&ident.as_str()) {
                    return Err(parse_err(
                        lineno,
                        text,
                        format!("`{ident}` changes the coordinate system, which is not supported"),
                    ));
                }
                out.complex
                    .get_or_insert_with(|| text[s..].trim_end().to_string());
                // Skip the rest of this token.
                i = e;
                while i < b.len() && b[i] != b' ' && b[i] != b'\t' && b[i] != b';' {
                    if b[i] == b'"' {
                        i += 1;
                        while i < b.len() && b[i] != b'"' {
                            i += 1;
                        }
                    }
                    i += 1;
                }
                last_was_word = false;
                continue;
            }
            // A one-letter word.
            let letter = c.to_ascii_uppercase();
            let mut j = i + 1;
            while j < b.len() && (b[j] == b' ' || b[j] == b'\t') {
                j += 1;
            }
            if flavor == Flavor::Sinumerik && j < b.len() && b[j] == b'=' {
                j += 1;
                while j < b.len() && b[j] == b' ' {
                    j += 1;
                }
            }
            match number_end(b, j) {
                Some(ne) => {
                    let num = &text[j..ne];
                    let value: f64 = num
                        .parse()
                        .map_err(|_| parse_err(lineno, text, format!("unreadable `{num}`")))?;
                    if !value.is_finite() {
                        return Err(parse_err(lineno, text, format!("`{num}` is not finite")));
                    }
                    let (point, decimals) = match num.find('.') {
                        Some(p) => (true, (num.len() - p - 1) as u32),
                        None => (false, 0),
                    };
                    if last_was_word {
                        joins += 1;
                    }
                    out.words.push(Word {
                        letter,
                        value,
                        whole: base + i..base + ne,
                        num: base + j..base + ne,
                        point,
                        decimals,
                    });
                    i = ne;
                    last_was_word = true;
                }
                None => {
                    if matches!(
                        letter,
                        b'X' | b'Y' | b'Z' | b'I' | b'J' | b'K' | b'R' | b'G'
                    ) {
                        let what = if j < b.len() && !matches!(b[j], b' ' | b'\t' | b';' | b'(') {
                            let end = text[j..]
                                .find([' ', '\t', ';'])
                                .map_or(text.len(), |k| j + k);
                            format!("cannot read `{}`", &text[i..end])
                        } else {
                            format!("`{}` without a number", letter as char)
                        };
                        return Err(parse_err(lineno, text, what));
                    }
                    out.complex
                        .get_or_insert_with(|| text[i..].trim_end().to_string());
                    i = j.max(i + 1);
                    last_was_word = false;
                }
            }
            continue;
        }
        // Anything else: macros, expressions, stray characters (a whole
        // UTF-8 character at a time).
        if out.complex.is_none() {
            out.complex = Some(text[i..].trim_end().to_string());
        }
        i += text[i..].chars().next().map_or(1, char::len_utf8);
        last_was_word = false;
    }
    out.spaced = blanks >= joins;
    Ok(out)
}

/// The modal state while reading.
#[derive(Debug, Clone, Copy)]
struct Modal {
    motion: u8,
    incremental: bool,
    centre_absolute: bool,
    plane: u8,
    scale: f64,
    inverse_time: bool,
    position: [f64; 3],
}

fn g_code(v: f64) -> Option<(u32, u32)> {
    let whole = v.trunc();
    let frac = ((v - whole) * 10.0).round();
    (v >= 0.0 && (v - whole - frac / 10.0).abs() < 1e-9).then_some((whole as u32, frac as u32))
}

/// Reads a milling program.
pub fn read_toolpath(text: &str, options: &ToolpathOptions) -> Result<Toolpath, NcError> {
    if let Some(m) = options.max_segment_mm
        && !(m.is_finite() && m > 0.0)
    {
        return Err(NcError::program(format!(
            "largest segment {m} mm: must be > 0"
        )));
    }
    if !(options.arc_tolerance_mm.is_finite() && options.arc_tolerance_mm > 0.0) {
        return Err(NcError::program(format!(
            "arc tolerance {} mm: must be > 0",
            options.arc_tolerance_mm
        )));
    }
    let flavor = options.flavor;
    let mut lines = Vec::new();
    let mut nodes: Vec<Node> = Vec::new();
    let mut st = Modal {
        motion: 255,
        incremental: false,
        centre_absolute: false,
        plane: 17,
        scale: 1.0,
        inverse_time: false,
        position: [f64::NAN; 3],
    };
    let mut arcs = 0usize;
    let mut segments = 0usize;
    let mut max_dec = 0u32;
    let mut padded = true;
    let mut whole_point = false;
    let mut whole_bare = false;
    let mut any_point = false;
    let mut g_two_digit = 0usize;
    let mut g_one_digit = 0usize;
    let mut inch = false;
    let mut spaced_lines = 0usize;
    let mut joined_lines = 0usize;
    let mut start = 0usize;
    let mut lineno = 0usize;
    while start < text.len() {
        lineno += 1;
        let rest = &text[start..];
        let (len, eol_len) = match rest.find('\n') {
            Some(k) if k > 0 && rest.as_bytes()[k - 1] == b'\r' => (k - 1, 2),
            Some(k) => (k, 1),
            None => (rest.len(), 0),
        };
        let line_text = &rest[..len];
        let mut line = Line {
            text: start..start + len,
            eol: start + len..start + len + eol_len,
            motion: None,
            forgets: [false; 3],
        };
        let lx = lex(line_text, start, lineno, flavor)?;
        let err = |what: String| parse_err(lineno, line_text, what);
        let first = line_text.trim_start();
        let program_number = first.starts_with(['O', 'o', '%', '#', ':']);
        let mut axis_words: [Option<&Word>; 3] = [None; 3];
        let mut centre: [Option<&Word>; 3] = [None; 3];
        let mut radius: Option<(f64, Range<usize>)> = lx.cr.clone();
        let mut g_motion: Option<&Word> = None;
        let mut passive = false;
        let mut forget = false;
        let mut bare_home = false;
        let mut turns: Option<&Word> = None;
        for w in &lx.words {
            match w.letter {
                b'X' | b'Y' | b'Z' => {
                    let a = (w.letter - b'X') as usize;
                    if axis_words[a].is_some() {
                        return Err(err(format!("`{}` twice", w.letter as char)));
                    }
                    axis_words[a] = Some(w);
                }
                b'I' | b'J' | b'K' => centre[(w.letter - b'I') as usize] = Some(w),
                b'P' => turns = Some(w),
                b'R' if flavor != Flavor::Sinumerik => radius = Some((w.value, w.whole.clone())),
                b'A' | b'B' | b'C' | b'U' | b'V' | b'W' if !program_number => {
                    return Err(err(format!(
                        "axis `{}`: only X, Y and Z are read",
                        w.letter as char
                    )));
                }
                b'G' => {
                    let Some((g, sub)) = g_code(w.value) else {
                        return Err(err(format!("`G{}` is not a G code", w.value)));
                    };
                    match (g, sub) {
                        (0..=3, 0) => {
                            st.motion = g as u8;
                            g_motion = Some(w);
                            let digits = text[w.num.clone()].len();
                            if digits >= 2 {
                                g_two_digit += 1;
                            } else {
                                g_one_digit += 1;
                            }
                        }
                        (90, 0) => st.incremental = false,
                        (91, 0) => st.incremental = true,
                        (90, 1) => st.centre_absolute = true,
                        (91, 1) => st.centre_absolute = false,
                        (17..=19, 0) => st.plane = g as u8,
                        (20, 0) => {
                            st.scale = 25.4;
                            inch = true;
                        }
                        (21, 0) => st.scale = 1.0,
                        (70 | 700, 0) if flavor == Flavor::Sinumerik => {
                            st.scale = 25.4;
                            inch = true;
                        }
                        (71 | 710, 0) if flavor == Flavor::Sinumerik => st.scale = 1.0,
                        (93, 0) => st.inverse_time = true,
                        (94 | 95, 0) => st.inverse_time = false,
                        (4, 0) => passive = true,
                        (28 | 30 | 53, _) => {
                            passive = true;
                            forget = true;
                            bare_home |= g != 53;
                        }
                        (16, 0) => {
                            return Err(err("polar coordinates (`G16`) are not supported".into()));
                        }
                        (92 | 52 | 10 | 51 | 68, _) => {
                            return Err(err(format!(
                                "`G{g}` changes the coordinate system, which is not supported"
                            )));
                        }
                        (73 | 74 | 76 | 81..=89, _) => {
                            return Err(err(format!("the canned cycle `G{g}` is not supported")));
                        }
                        _ => {}
                    }
                }
                _ => {}
            }
        }
        let has_axis = axis_words.iter().any(Option::is_some);
        let has_centre = centre.iter().any(Option::is_some) || radius.is_some();
        if let Some(c) = &lx.complex {
            let iso_ident = flavor != Flavor::Sinumerik
                && !program_number
                && c.as_bytes().first().is_some_and(u8::is_ascii_alphabetic);
            if has_axis || has_centre || iso_ident {
                return Err(err(format!("cannot read `{c}`")));
            }
        }
        if forget {
            // `G28`/`G30` without axis words send every axis home.
            let all = bare_home && axis_words.iter().all(Option::is_none);
            for (a, w) in axis_words.iter().enumerate() {
                if w.is_some() || all {
                    st.position[a] = f64::NAN;
                    line.forgets[a] = true;
                }
            }
        }
        let is_arc = matches!(st.motion, 2 | 3) && (has_axis || has_centre);
        if !passive && (has_axis || is_arc) && !program_number {
            if st.motion == 255 {
                return Err(err("an axis word before any G0/G1/G2/G3".into()));
            }
            for w in axis_words.iter().flatten() {
                if w.point {
                    any_point = true;
                    max_dec = max_dec.max(w.decimals);
                    if w.decimals == 0 {
                        whole_point = true;
                    }
                } else {
                    whole_bare = true;
                }
            }
            let from = st.position;
            let mut to = from;
            for (a, w) in axis_words.iter().enumerate() {
                if let Some(w) = w {
                    let v = w.value * st.scale;
                    to[a] = if st.incremental {
                        if from[a].is_nan() {
                            return Err(err(format!(
                                "an incremental move of {} from an unknown position",
                                (b'X' + a as u8) as char
                            )));
                        }
                        from[a] + v
                    } else {
                        v
                    };
                }
            }
            let first_node = nodes.len();
            let mut arc_edit = None;
            if is_arc {
                if st.inverse_time {
                    return Err(err(
                        "arcs in inverse-time feed (G93) are not supported".into()
                    ));
                }
                if let Some(p) = turns
                    && p.value != 1.0
                {
                    return Err(err(format!(
                        "arcs of several turns (P{}) are not supported",
                        p.value
                    )));
                }
                let (u, v, n) = match st.plane {
                    17 => (0usize, 1usize, 2usize),
                    18 => (2, 0, 1),
                    _ => (1, 2, 0),
                };
                if from[u].is_nan() || from[v].is_nan() || from[n].is_nan() && !to[n].is_nan() {
                    return Err(err("an arc from an unknown position".into()));
                }
                let cw = st.motion == 2;
                let (cu, cv) = if let Some((r, _)) = &radius {
                    let r = r * st.scale;
                    let (du, dv) = (to[u] - from[u], to[v] - from[v]);
                    let d = du.hypot(dv);
                    if d < 1e-12 {
                        return Err(err("a radius arc whose end is its start".into()));
                    }
                    let h2 = r * r - d * d / 4.0;
                    if h2 < -(1e-6 * r * r).max(1e-8) {
                        return Err(err(format!(
                            "radius {} is shorter than half the chord {}",
                            r.abs(),
                            d / 2.0
                        )));
                    }
                    let h = h2.max(0.0).sqrt();
                    let (pu, pv) = (-dv / d, du / d);
                    // Centre left of the chord for a counter-clockwise minor arc.
                    let side = if cw { -1.0 } else { 1.0 } * r.signum();
                    (
                        (from[u] + to[u]) / 2.0 + side * h * pu,
                        (from[v] + to[v]) / 2.0 + side * h * pv,
                    )
                } else {
                    let off = |k: usize| centre[k].map_or(0.0, |w| w.value * st.scale);
                    // Plane offsets (u, v) from I, J, K.
                    let (ou, ov) = match st.plane {
                        17 => (off(0), off(1)),
                        18 => (off(2), off(0)),
                        _ => (off(1), off(2)),
                    };
                    if st.centre_absolute {
                        // I, J, K belong to X, Y, Z; a missing one is the start's.
                        let abs = |k: usize, o: f64| if centre[k].is_some() { o } else { from[k] };
                        (abs(u, ou), abs(v, ov))
                    } else {
                        (from[u] + ou, from[v] + ov)
                    }
                };
                let rs = (from[u] - cu).hypot(from[v] - cv);
                let re = (to[u] - cu).hypot(to[v] - cv);
                if (rs - re).abs() > 0.002 + 1e-3 * rs || rs < 1e-9 {
                    return Err(err(format!(
                        "the arc's end is not on its circle (radius {rs:.4} at the start, {re:.4} at the end)"
                    )));
                }
                let a0 = (from[v] - cv).atan2(from[u] - cu);
                let a1 = (to[v] - cv).atan2(to[u] - cu);
                let tau = std::f64::consts::TAU;
                let mut sweep = if cw { a0 - a1 } else { a1 - a0 };
                sweep = sweep.rem_euclid(tau);
                let same = (to[u] - from[u]).hypot(to[v] - from[v]) < 1e-9;
                if same && radius.is_none() {
                    sweep = tau;
                }
                let r = rs.max(re);
                let tol = options.arc_tolerance_mm;
                let step = if tol < r {
                    (2.0 * (1.0 - tol / r).acos()).min(std::f64::consts::FRAC_PI_2)
                } else {
                    std::f64::consts::FRAC_PI_2
                };
                let chords = (sweep / step).ceil();
                if chords > 1e6 {
                    return Err(err(format!(
                        "the arc (radius {r:.3}) would need {chords:.0} chords within {tol} mm; \
                         give a larger arc tolerance"
                    )));
                }
                let count = (chords as usize).max(1);
                let dir = if cw { -1.0 } else { 1.0 };
                for k in 1..=count {
                    let f = k as f64 / count as f64;
                    let mut p = to;
                    if k < count {
                        let ang = a0 + dir * sweep * f;
                        let rad = rs + (re - rs) * f;
                        p[u] = cu + rad * ang.cos();
                        p[v] = cv + rad * ang.sin();
                        p[n] = if to[n].is_nan() {
                            f64::NAN
                        } else {
                            from[n] + (to[n] - from[n]) * f
                        };
                    }
                    nodes.push(Node {
                        position: p,
                        kind: NodeKind::Arc,
                        line: lineno,
                    });
                }
                let mut remove: Vec<Range<usize>> = lx
                    .words
                    .iter()
                    .filter(|w| {
                        matches!(w.letter, b'I' | b'J' | b'K')
                            || (w.letter == b'R' && flavor != Flavor::Sinumerik)
                            || w.letter == b'P'
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
                    .map_or(start + len, |w| w.whole.start);
                arc_edit = Some(ArcEdit {
                    g_word: g_motion.map(|w| w.whole.clone()),
                    g_insert_at,
                    remove,
                });
                arcs += 1;
            } else {
                // A long feed move in pieces of at most `max_segment_mm`.
                let length = (0..3)
                    .map(|a| (to[a] - from[a]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                let pieces = match options.max_segment_mm {
                    Some(max) if st.motion == 1 && length.is_finite() && length > max => {
                        if st.inverse_time {
                            return Err(err(
                                "splitting moves in inverse-time feed (G93) is not supported"
                                    .into(),
                            ));
                        }
                        let n = (length / max).ceil();
                        if n > 1e6 {
                            return Err(err(format!(
                                "the move ({length:.3} mm) would need {n:.0} pieces of {max} mm"
                            )));
                        }
                        segments += 1;
                        n as usize
                    }
                    _ => 1,
                };
                for k in 1..=pieces {
                    let f = k as f64 / pieces as f64;
                    let mut p = to;
                    if k < pieces {
                        for a in 0..3 {
                            p[a] = from[a] + (to[a] - from[a]) * f;
                        }
                    }
                    nodes.push(Node {
                        position: p,
                        kind: if st.motion == 0 {
                            NodeKind::Rapid
                        } else {
                            NodeKind::Feed
                        },
                        line: lineno,
                    });
                }
            }
            st.position = to;
            let insert_at = axis_words
                .iter()
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
                .unwrap_or(lx.code_end);
            if lx.words.len() > 1 {
                if lx.spaced {
                    spaced_lines += 1;
                } else {
                    joined_lines += 1;
                }
            }
            line.motion = Some(MotionLine {
                words: axis_words.map(|w| {
                    w.map(|w| NumSpan {
                        range: w.num.clone(),
                        value: w.value,
                    })
                }),
                insert_at,
                incremental: st.incremental,
                scale: st.scale,
                nodes: first_node..nodes.len(),
                arc: arc_edit,
                block_delete: lx.block_delete,
            });
        }
        lines.push(line);
        start += len + eol_len;
    }
    // Every word with a point has `max_dec` places?
    for l in &lines {
        if let Some(m) = &l.motion {
            for w in m.words.iter().flatten() {
                let t = &text[w.range.clone()];
                if let Some(p) = t.find('.')
                    && (t.len() - p - 1) as u32 != max_dec
                {
                    padded = false;
                }
            }
        }
    }
    Ok(Toolpath {
        text: text.to_string(),
        lines,
        nodes,
        arcs_linearised: arcs,
        moves_split: segments,
        flavor,
        format: NumberFormat {
            // At least 3 decimals in mm, 4 in inches, whatever the program
            // wrote: a correction of hundredths must not be rounded away.
            decimals: max_dec.max(if inch { 4 } else { 3 }),
            // Padding is kept only at the program's own precision.
            padded: padded && any_point && max_dec >= if inch { 4 } else { 3 },
            whole_point: whole_point || !whole_bare,
            spaced: spaced_lines >= joined_lines,
            linear: if g_two_digit > g_one_digit {
                "G01"
            } else {
                "G1"
            },
        },
    })
}

impl Toolpath {
    /// The number of lines.
    pub fn line_count(&self) -> usize {
        self.lines.len()
    }

    /// The syntax it was read in.
    pub fn flavor(&self) -> Flavor {
        self.flavor
    }

    /// Decimals of the program's coordinates.
    pub fn decimals(&self) -> u32 {
        self.format.decimals
    }

    /// Writes the program with the nodes at `positions` (one per node, mm).
    /// `header` lines go first as comments of the program's flavor (after a
    /// leading `%` or program-number line). Lines that are not motion blocks
    /// are copied byte for byte; motion blocks whose nodes did not move (to
    /// the printed precision) too.
    pub fn write(&self, positions: &[[f64; 3]], header: &[String]) -> Result<String, NcError> {
        if positions.len() != self.nodes.len() {
            return Err(NcError::program(format!(
                "{} positions for {} nodes",
                positions.len(),
                self.nodes.len()
            )));
        }
        let t = &self.text;
        let mut out = String::with_capacity(t.len() + t.len() / 8 + 256);
        let eol = self
            .lines
            .first()
            .map_or("\n", |l| if l.eol.len() == 2 { "\r\n" } else { "\n" });
        let mut header_done = header.is_empty();
        // The value each axis has in the new program (mm), as printed.
        let mut written = [f64::NAN; 3];
        for line in &self.lines {
            if !header_done {
                let lt = t[line.text.clone()].trim_start();
                // After the leading `%` and program-number lines.
                let lead = lt.starts_with('%')
                    || lt.starts_with(";$PATH")
                    || (lt.starts_with(['O', 'o'])
                        && lt[1..].starts_with(|c: char| c.is_ascii_digit()));
                if !lead {
                    for h in header {
                        match self.flavor {
                            Flavor::Sinumerik => {
                                out.push_str("; ");
                                out.push_str(h);
                            }
                            _ => {
                                out.push('(');
                                out.push_str(&h.replace(['(', ')'], " "));
                                out.push(')');
                            }
                        }
                        out.push_str(eol);
                    }
                    header_done = true;
                }
            }
            let Some(m) = &line.motion else {
                out.push_str(&t[line.text.start..line.eol.end]);
                for (a, f) in line.forgets.iter().enumerate() {
                    if *f {
                        written[a] = f64::NAN;
                    }
                }
                continue;
            };
            let line_eol = if line.eol.is_empty() {
                eol
            } else {
                &t[line.eol.clone()]
            };
            let count = m.nodes.len();
            for (k, ni) in m.nodes.clone().enumerate() {
                let target = positions[ni];
                let mut edits: Vec<(Range<usize>, String)> = Vec::new();
                let mut inserts = String::new();
                for a in 0..3 {
                    let goal = target[a];
                    if goal.is_nan() {
                        continue;
                    }
                    let prog = if m.incremental {
                        (goal - written[a]) / m.scale
                    } else {
                        goal / m.scale
                    };
                    let word = if k == 0 { m.words[a].as_ref() } else { None };
                    match word {
                        Some(w) => {
                            let orig = &t[w.range.clone()];
                            let keep = same_printed(prog, w.value, self.format.decimals);
                            let printed = if keep {
                                w.value
                            } else {
                                let s = self.format_like(prog, orig);
                                let v = printed(prog, self.format.decimals);
                                edits.push((w.range.clone(), s));
                                v
                            };
                            written[a] = if m.incremental {
                                written[a] + printed * m.scale
                            } else {
                                printed * m.scale
                            };
                        }
                        None => {
                            let moves = if m.incremental {
                                !same_printed(prog, 0.0, self.format.decimals)
                            } else {
                                written[a].is_nan()
                                    || !same_printed(
                                        prog,
                                        written[a] / m.scale,
                                        self.format.decimals,
                                    )
                            };
                            if moves {
                                let s = self.format_like(prog, "");
                                let v = printed(prog, self.format.decimals);
                                if self.format.spaced {
                                    inserts.push(' ');
                                }
                                inserts.push((b'X' + a as u8) as char);
                                inserts.push_str(&s);
                                written[a] = if m.incremental {
                                    written[a] + v * m.scale
                                } else {
                                    v * m.scale
                                };
                            }
                        }
                    }
                }
                if k == 0 {
                    if let Some(arc) = &m.arc {
                        match &arc.g_word {
                            Some(g) => edits.push((g.clone(), self.format.linear.into())),
                            None => edits.push((
                                arc.g_insert_at..arc.g_insert_at,
                                if self.format.spaced {
                                    format!("{} ", self.format.linear)
                                } else {
                                    self.format.linear.into()
                                },
                            )),
                        }
                        for r in &arc.remove {
                            // Take the blanks before the word with it.
                            let mut s = r.start;
                            while s > line.text.start && matches!(t.as_bytes()[s - 1], b' ' | b'\t')
                            {
                                s -= 1;
                            }
                            edits.push((s..r.end, String::new()));
                        }
                    }
                    if !inserts.is_empty() {
                        edits.push((m.insert_at..m.insert_at, inserts));
                    }
                    edits.sort_by_key(|e| (e.0.start, e.0.end));
                    let mut at = line.text.start;
                    for (r, s) in &edits {
                        if r.start < at {
                            continue;
                        }
                        out.push_str(&t[at..r.start]);
                        out.push_str(s);
                        at = r.end;
                    }
                    out.push_str(&t[at..line.text.end]);
                    if k + 1 < count {
                        out.push_str(line_eol);
                    } else {
                        out.push_str(&t[line.eol.clone()]);
                    }
                } else {
                    if m.block_delete {
                        out.push('/');
                    }
                    out.push_str(self.format.linear);
                    out.push_str(&inserts);
                    if k + 1 < count {
                        out.push_str(line_eol);
                    } else {
                        out.push_str(&t[line.eol.clone()]);
                    }
                }
            }
        }
        Ok(out)
    }

    /// `v` in the program's number format, following `like` (the word it
    /// replaces) for a leading zero and a plus sign.
    fn format_like(&self, v: f64, like: &str) -> String {
        let f = self.format;
        let mut s = fixed(v, f.decimals);
        if !f.padded && s.contains('.') {
            while s.ends_with('0') {
                s.pop();
            }
        }
        if s.ends_with('.') && !f.whole_point {
            s.pop();
        }
        let plus = like.starts_with('+');
        let like = like.trim_start_matches('+');
        // Zero-padded whole part (`030.000`): keep its width.
        let whole_width = like
            .trim_start_matches('-')
            .split('.')
            .next()
            .map_or(0, str::len);
        if like.trim_start_matches('-').starts_with('0') && whole_width > 1 {
            let neg = s.starts_with('-');
            let body = s.trim_start_matches('-');
            let whole = body.split('.').next().map_or(0, str::len);
            if whole < whole_width {
                s = format!(
                    "{}{}{body}",
                    if neg { "-" } else { "" },
                    "0".repeat(whole_width - whole)
                );
            }
        }
        if plus && !s.starts_with('-') {
            s.insert(0, '+');
        }
        if (like.starts_with('.') || like.starts_with("-.")) && s.contains('.') {
            if let Some(rest) = s.strip_prefix("0.") {
                s = format!(".{rest}");
            } else if let Some(rest) = s.strip_prefix("-0.") {
                s = format!("-.{rest}");
            }
        }
        s
    }
}

/// `v` with exactly `decimals` places (rounded half away from zero), never
/// `-0`: integer arithmetic, much faster than `format!("{:.d$}")`.
fn fixed(v: f64, decimals: u32) -> String {
    let k = 10f64.powi(decimals as i32);
    let scaled = (v * k).round();
    if !scaled.is_finite() || scaled.abs() >= 9e15 {
        let d = decimals as usize;
        return format!("{v:.d$}");
    }
    let n = scaled as i64;
    let mut s = String::with_capacity(24);
    if n < 0 {
        s.push('-');
    }
    let a = n.unsigned_abs();
    let p = 10u64.pow(decimals);
    s.push_str(&(a / p).to_string());
    if decimals > 0 {
        s.push('.');
        let frac = (a % p).to_string();
        for _ in frac.len()..decimals as usize {
            s.push('0');
        }
        s.push_str(&frac);
    }
    s
}

/// The value `fixed(v, decimals)` prints.
fn printed(v: f64, decimals: u32) -> f64 {
    let k = 10f64.powi(decimals as i32);
    (v * k).round() / k
}

/// `a` and `b` print the same with `decimals` places.
fn same_printed(a: f64, b: f64, decimals: u32) -> bool {
    let k = 10f64.powi(decimals as i32);
    (a * k).round() == (b * k).round()
}

#[cfg(test)]
mod tests {
    use super::*;

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
            for flavor in [Flavor::Iso, Flavor::Sinumerik, Flavor::LinuxCnc] {
                let opts = ToolpathOptions {
                    flavor,
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
                    flavor: Flavor::LinuxCnc,
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
                flavor: Flavor::Sinumerik,
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
    fn fixed_decimals() {
        assert_eq!(fixed(-0.0004, 3), "0.000");
        assert_eq!(fixed(12.0, 0), "12");
        assert_eq!(fixed(-4.56789, 4), "-4.5679");
        assert_eq!(fixed(0.05, 3), "0.050");
        assert_eq!(printed(-4.56789, 4), -4.5679);
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
                flavor: Flavor::Sinumerik,
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
                flavor: Flavor::Sinumerik,
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
                flavor: Flavor::Sinumerik,
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
}
