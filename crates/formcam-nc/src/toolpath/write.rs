//! The style-keeping writer: a toolpath written back with new node
//! positions in the program's own style — the same number format as the
//! word it replaces (decimals, padding, leading zeros, a plus sign), missing
//! words added after the last axis word, incremental blocks as deltas of the
//! new positions, arcs as `G1` chords.

use std::ops::Range;

use super::{Line, MotionLine, Toolpath};
use crate::num::{self, Out};
use crate::{Dialect, NcError, ProgramFault};

impl Toolpath {
    /// Writes the program with the nodes at `positions` (one per node, mm).
    /// `header` lines go first as comments of the program's dialect (after a
    /// leading `%` or program-number line). Lines that are not motion blocks
    /// are copied byte for byte; motion blocks whose nodes did not move (to
    /// the printed precision) too.
    pub fn write(&self, positions: &[[f64; 3]], header: &[String]) -> Result<String, NcError> {
        if positions.len() != self.nodes.len() {
            return Err(ProgramFault::PositionCount {
                positions: positions.len(),
                nodes: self.nodes.len(),
            }
            .into());
        }
        let t = &self.text;
        let mut w = Writer {
            tp: self,
            out: String::with_capacity(t.len() + t.len() / 8 + 256),
            scratch: Out::new(Vec::with_capacity(32)),
            eol: self
                .lines
                .first()
                .map_or("\n", |l| if l.eol.len() == 2 { "\r\n" } else { "\n" }),
            written: [f64::NAN; 3],
        };
        let mut header_done = header.is_empty();
        for line in &self.lines {
            if !header_done && !leads(&t[line.text.clone()]) {
                w.header(header);
                header_done = true;
            }
            match &line.motion {
                Some(m) => w.motion_line(line, m, positions),
                None => w.kept_line(line),
            }
        }
        Ok(w.out)
    }
}

/// A leading `%`, Sinumerik path or program-number line (the header goes
/// after them).
fn leads(line: &str) -> bool {
    let lt = line.trim_start();
    lt.starts_with('%')
        || lt.starts_with(";$PATH")
        || (lt.starts_with(['O', 'o']) && lt[1..].starts_with(|c: char| c.is_ascii_digit()))
}

/// The writer's state.
struct Writer<'a> {
    tp: &'a Toolpath,
    out: String,
    /// Numbers are formatted here.
    scratch: Out,
    /// The program's line terminator.
    eol: &'static str,
    /// The value each axis has in the new program (mm), as printed.
    written: [f64; 3],
}

impl Writer<'_> {
    fn header(&mut self, header: &[String]) {
        for h in header {
            match self.tp.dialect {
                Dialect::Sinumerik840d => {
                    self.out.push_str("; ");
                    self.out.push_str(h);
                }
                _ => {
                    self.out.push('(');
                    self.out.push_str(&h.replace(['(', ')'], " "));
                    self.out.push(')');
                }
            }
            self.out.push_str(self.eol);
        }
    }

    /// A line that is no motion block, byte for byte.
    fn kept_line(&mut self, line: &Line) {
        let t = &self.tp.text;
        self.out.push_str(&t[line.text.start..line.eol.end]);
        for (a, f) in line.forgets.iter().enumerate() {
            if *f {
                self.written[a] = f64::NAN;
            }
        }
    }

    /// A motion block: its first node on the block's own line (edited), the
    /// other nodes on `G1` lines after it.
    fn motion_line(&mut self, line: &Line, m: &MotionLine, positions: &[[f64; 3]]) {
        let t = &self.tp.text;
        let line_eol = if line.eol.is_empty() {
            self.eol
        } else {
            &t[line.eol.clone()]
        };
        let count = m.nodes.len();
        for (k, ni) in m.nodes.clone().enumerate() {
            let (mut edits, inserts) = self.axis_edits(m, k, positions[ni]);
            if k == 0 {
                if let Some(arc) = &m.arc {
                    self.arc_edits(line, arc, &mut edits);
                }
                if !inserts.is_empty() {
                    edits.push((m.insert_at..m.insert_at, inserts));
                }
                self.edited(line.text.clone(), edits);
            } else {
                if m.block_delete {
                    self.out.push('/');
                }
                self.out.push_str(self.tp.format.linear);
                self.out.push_str(&inserts);
            }
            if k + 1 < count {
                self.out.push_str(line_eol);
            } else {
                self.out.push_str(&t[line.eol.clone()]);
            }
        }
    }

    /// The edits of the axis words of node `k` of a block (only the first
    /// node has words of its own) and the words to add.
    fn axis_edits(
        &mut self,
        m: &MotionLine,
        k: usize,
        target: [f64; 3],
    ) -> (Vec<(Range<usize>, String)>, String) {
        let t = &self.tp.text;
        let decimals = self.tp.format.decimals;
        let mut edits = Vec::new();
        let mut inserts = String::new();
        for (a, goal) in target.into_iter().enumerate() {
            if goal.is_nan() {
                continue;
            }
            let before = self.written[a];
            let prog = if m.incremental {
                (goal - before) / m.scale
            } else {
                goal / m.scale
            };
            let word = if k == 0 { m.words[a].as_ref() } else { None };
            let printed = match word {
                Some(w) => {
                    if num::same_printed(prog, w.value, decimals) {
                        w.value
                    } else {
                        let s = self.format_like(prog, &t[w.range.clone()]);
                        edits.push((w.range.clone(), s));
                        num::rounded(prog, decimals)
                    }
                }
                None => {
                    let moves = if m.incremental {
                        !num::same_printed(prog, 0.0, decimals)
                    } else {
                        before.is_nan() || !num::same_printed(prog, before / m.scale, decimals)
                    };
                    if !moves {
                        continue;
                    }
                    let s = self.format_like(prog, "");
                    if self.tp.format.spaced {
                        inserts.push(' ');
                    }
                    inserts.push((b'X' + a as u8) as char);
                    inserts.push_str(&s);
                    num::rounded(prog, decimals)
                }
            };
            self.written[a] = if m.incremental {
                before + printed * m.scale
            } else {
                printed * m.scale
            };
        }
        (edits, inserts)
    }

    /// The edits that make an arc block a `G1` block: the motion word
    /// replaced (or added), centre and radius words removed with the blanks
    /// before them.
    fn arc_edits(
        &self,
        line: &Line,
        arc: &super::ArcEdit,
        edits: &mut Vec<(Range<usize>, String)>,
    ) {
        let f = self.tp.format;
        match &arc.g_word {
            Some(g) => edits.push((g.clone(), f.linear.into())),
            None => edits.push((
                arc.g_insert_at..arc.g_insert_at,
                if f.spaced {
                    format!("{} ", f.linear)
                } else {
                    f.linear.into()
                },
            )),
        }
        let b = self.tp.text.as_bytes();
        for r in &arc.remove {
            let mut s = r.start;
            while s > line.text.start && matches!(b[s - 1], b' ' | b'\t') {
                s -= 1;
            }
            edits.push((s..r.end, String::new()));
        }
    }

    /// The line `text` with `edits` applied (overlapping ones skipped).
    fn edited(&mut self, text: Range<usize>, mut edits: Vec<(Range<usize>, String)>) {
        let t = &self.tp.text;
        edits.sort_by_key(|e| (e.0.start, e.0.end));
        let mut at = text.start;
        for (r, s) in &edits {
            if r.start < at {
                continue;
            }
            self.out.push_str(&t[at..r.start]);
            self.out.push_str(s);
            at = r.end;
        }
        self.out.push_str(&t[at..text.end]);
    }

    /// `v` in the program's number format, following `like` (the word it
    /// replaces) for a leading zero and a plus sign.
    fn format_like(&mut self, v: f64, like: &str) -> String {
        let f = self.tp.format;
        num::push_fixed(&mut self.scratch, v, f.decimals);
        let mut s = self.scratch.take_string();
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
