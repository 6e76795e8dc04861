//! APT CLDATA ([`read_cldata`]) read back: records joined across `$`
//! continuations, then read one after another.

use super::Reader;
use crate::{AxisSpec, Block, Feed, Motion, NcError, Program};
use formcam_files::quote;

/// `text` as a finite number; the error names `what` at `lineno`.
fn number(text: &str, lineno: usize, what: &str) -> Result<f64, NcError> {
    let t = text.trim();
    t.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| NcError::parse(lineno, format!("{what}: `{}` is not a number", quote(t))))
}

/// Reads APT CLDATA as formcam's CLDATA writer writes it (machine-axis
/// `GOTO` records) on `axes` (see the module documentation).
pub fn read_cldata(text: &str, axes: &[AxisSpec]) -> Result<Program, NcError> {
    read_cldata_lines(text, axes).map(|(p, _)| p)
}

/// Reads CLDATA as [`read_cldata`] does, with the line (1-based) of each
/// block's `GOTO` (its first line when continued).
pub fn read_cldata_lines(text: &str, axes: &[AxisSpec]) -> Result<(Program, Vec<usize>), NcError> {
    let mut r = Cldata {
        r: Reader::new(axes)?,
        rapid: false,
        feed: None,
        in_header: true,
    };
    for (lineno, line) in &records(text) {
        if !r.record(*lineno, line)? {
            break;
        }
    }
    Ok((r.r.program, r.r.lines))
}

/// The records of `text` with the line (1-based) each starts on: records
/// continued after a `$` are joined (errors name their first line).
fn records(text: &str) -> Vec<(usize, String)> {
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
    records
}

/// The CLDATA reader's state over the common reader's.
struct Cldata<'a> {
    /// The common reader: axes, offsets, comments, the program read so far.
    r: Reader<'a>,
    /// The next `GOTO` is a rapid.
    rapid: bool,
    /// The feed: `(value, inverse)`.
    feed: Option<(f64, bool)>,
    /// Only comments and `PARTNO` read so far.
    in_header: bool,
}

impl Cldata<'_> {
    /// Reads the record `line` at `lineno`; `false` at `FINI`.
    fn record(&mut self, lineno: usize, line: &str) -> Result<bool, NcError> {
        if let Some(c) = line.strip_prefix("$$") {
            self.comment(c.trim().to_string());
            return Ok(true);
        }
        let stmt = line.split("$$").next().unwrap_or("").trim();
        if stmt.is_empty() {
            return Ok(true);
        }
        let (word, args) = match stmt.split_once('/') {
            Some((w, a)) => (w.trim().to_ascii_uppercase(), a),
            None => (stmt.to_ascii_uppercase(), ""),
        };
        self.in_header &= word == "PARTNO";
        match word.as_str() {
            "PARTNO" => self.r.program.name = args.trim().to_string(),
            "UNITS" if !args.trim().eq_ignore_ascii_case("MM") => {
                return Err(NcError::parse(
                    lineno,
                    format!("UNITS/{}: only MM is supported", quote(args.trim())),
                ));
            }
            "RAPID" => self.rapid = true,
            "ORIGIN" => self.origin(lineno, args)?,
            "FEDRAT" => self.fedrat(lineno, args)?,
            "GOTO" => self.goto(lineno, args)?,
            "FINI" => return Ok(false),
            _ => {}
        }
        Ok(true)
    }

    /// A `$$` comment: the header's before any statement but `PARTNO`, else
    /// the next block's.
    fn comment(&mut self, c: String) {
        if self.in_header {
            self.r.program.header_comments.push(c);
        } else {
            self.r.pending = Some(match self.r.pending.take() {
                Some(p) => format!("{p}; {c}"),
                None => c,
            });
        }
    }

    /// `ORIGIN/axis,value`: the axis re-zeroed.
    fn origin(&mut self, lineno: usize, args: &str) -> Result<(), NcError> {
        let r = &mut self.r;
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
                        "ORIGIN/{}: not one of the program's axes ({})",
                        quote(name),
                        r.axis_names()
                    ),
                )
            })?;
        r.offset[k] = number(parts.next().unwrap_or(""), lineno, "ORIGIN")?;
        r.rezeroed = true;
        Ok(())
    }

    /// `FEDRAT/f[,MMPM|INVERS]`: the feed of the blocks after.
    fn fedrat(&mut self, lineno: usize, args: &str) -> Result<(), NcError> {
        let mut parts = args.split(',');
        let f = number(parts.next().unwrap_or(""), lineno, "FEDRAT")?;
        let unit = parts.next().map(|u| u.trim().to_ascii_uppercase());
        let inverse = match unit.as_deref() {
            None | Some("MMPM") => false,
            Some("INVERS") => true,
            Some(u) => {
                return Err(NcError::parse(
                    lineno,
                    format!(
                        "FEDRAT unit {}: only MMPM and INVERS are supported",
                        quote(u)
                    ),
                ));
            }
        };
        if f <= 0.0 {
            return Err(NcError::parse(
                lineno,
                format!("FEDRAT/{f} is not positive"),
            ));
        }
        self.feed = Some((f, inverse));
        Ok(())
    }

    /// `GOTO/values`: one block to the axes (shifted by their origins).
    fn goto(&mut self, lineno: usize, args: &str) -> Result<(), NcError> {
        let r = &mut self.r;
        let values = args
            .split(',')
            .zip(r.offset.iter().chain(std::iter::repeat(&0.0)))
            .map(|(v, o)| number(v, lineno, "GOTO").map(|v| v + o))
            .collect::<Result<Vec<_>, _>>()?;
        if values.len() != r.axes.len() {
            return Err(NcError::parse(
                lineno,
                format!(
                    "GOTO has {} values for {} axes ({})",
                    values.len(),
                    r.axes.len(),
                    r.axis_names()
                ),
            ));
        }
        let (kind, feed) = if self.rapid {
            (Motion::Rapid, Feed::None)
        } else {
            match self.feed {
                Some((f, false)) => (Motion::Linear, Feed::PerMinute(f)),
                Some((f, true)) => (Motion::Linear, Feed::InverseTime(60.0 / f)),
                None => return Err(NcError::parse(lineno, "GOTO before any FEDRAT")),
            }
        };
        self.rapid = false;
        let comment = r.join_comment(None);
        r.lines.push(lineno);
        r.program.blocks.push(Block {
            kind,
            target: values,
            feed,
            comment,
            rezero: std::mem::take(&mut r.rezeroed),
        });
        Ok(())
    }
}
