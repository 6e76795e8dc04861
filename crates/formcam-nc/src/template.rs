//! User post-processors: text templates read from TOML.
//!
//! ```toml
//! extension = "h"
//! header = "{n} BEGIN PGM {name} MM"   # written once at the top
//! comment = "{n} ; {comment}"          # optional: each header comment, and before each commented block
//! rapid = "{n} L {axes} FMAX"          # optional: rapid blocks (else `block`)
//! block = "{n} L {axes} F{f}"          # linear blocks
//! inverse = "{n} L {axes} FT{t}"       # optional: inverse-time blocks (else `block`)
//! footer = "{n} END PGM {name} MM"     # written once at the end
//! rezero = "{n} ; preset {axes}"       # optional: re-zeroes the modulo axes
//! decimals_mm = 3                      # optional, default 3
//! decimals_deg = 4                     # optional, default 4
//! signed = true                        # optional: `X+12.5`, default false
//! modal_axes = true                    # optional: {axes} has only the changed axes, default true
//! line_numbers = { start = 0, step = 1 }  # optional, default start 1 step 1
//! [axis_letters]                       # optional: program axis name -> printed letter
//! X = "X"
//! J1 = "Q1="
//! ```
//!
//! Every field's text is written followed by a line break (unless it is empty
//! or already ends with one); a field may hold several lines. Placeholders:
//!
//! | placeholder | value | fields |
//! | --- | --- | --- |
//! | `{name}` | the program's name | all |
//! | `{n}` | the next line number (each `{n}` takes one) | all |
//! | `{comment}` | the comment (empty when none) | `comment`, `block`, `rapid`, `inverse` |
//! | `{axes}` | the axis words, letter and value: `X12.5 A30` | `block`, `rapid`, `inverse` |
//! | `{X}`, `{A}`, `{J1}` … | one axis value, by program axis name | `block`, `rapid`, `inverse` |
//! | `{f}` | feed, mm/min: the block's, or for inverse time `travel / t * 60` (travel: the norm of the axis deltas in NC units); empty for rapids | `block`, `rapid`, `inverse` |
//! | `{fi}` | inverse-time `F = 60 / t` (1/min); empty otherwise | `block`, `rapid`, `inverse` |
//! | `{t}` | block time in s where known ([`Program::block_time_s`]); empty otherwise | `block`, `rapid`, `inverse` |
//!
//! With `rezero`, modulo rotary axes ([`crate::modulo`]) are re-zeroed:
//! before a block marked [`Block::rezero`](crate::Block::rezero) the field is
//! written with `{axes}` the modulo axes and their angles within the turn
//! (`{A}` one of them; `{comment}`, `{f}`, `{fi}`, `{t}` empty), and every
//! later value of those axes is the angle less the re-zeroed turns (the
//! program must keep the bound: [`Template::modulo_style`]). Without it they
//! are written unwound.
//!
//! `{{` and `}}` write braces. A placeholder that is not known, or not known
//! in its field, is an error when the template is read. An axis placeholder
//! is an upper-case NC name (`[A-Z][A-Z0-9_]*`), and a key of `axis_letters`
//! when that table is given; one that names no axis of the program is an
//! error when the program is written.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use crate::TemplateProblem;
use crate::modulo::{self, ModuloStyle};
use crate::num::{self, Out};
use crate::program::nc_travel;
use crate::{Feed, Motion, NcError, Program};
use formcam_files::{excerpt, syntax_message};

/// The TOML form.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TemplateFile {
    extension: String,
    #[serde(default)]
    header: String,
    #[serde(default)]
    comment: Option<String>,
    #[serde(default)]
    rapid: Option<String>,
    block: String,
    #[serde(default)]
    inverse: Option<String>,
    #[serde(default)]
    footer: String,
    #[serde(default)]
    rezero: Option<String>,
    #[serde(default = "default_mm")]
    decimals_mm: i64,
    #[serde(default = "default_deg")]
    decimals_deg: i64,
    #[serde(default)]
    signed: bool,
    #[serde(default = "default_true")]
    modal_axes: bool,
    #[serde(default)]
    axis_letters: Option<BTreeMap<String, String>>,
    #[serde(default)]
    line_numbers: Option<LineNumbers>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LineNumbers {
    start: u64,
    step: u64,
}

fn default_mm() -> i64 {
    i64::from(num::MM)
}

fn default_deg() -> i64 {
    i64::from(num::DEG)
}

/// The most decimals a template may ask for.
const MAX_DECIMALS: u32 = 9;

fn default_true() -> bool {
    true
}

/// One piece of a parsed template field.
#[derive(Debug, Clone, PartialEq)]
enum Piece {
    Text(String),
    Name,
    N,
    Comment,
    Axes,
    Axis(String),
    F,
    Fi,
    T,
}

/// Which placeholders a field allows.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Scope {
    /// `header`, `footer`.
    Frame,
    /// `comment`.
    Comment,
    /// `block`, `rapid`, `inverse`.
    Block,
}

impl Scope {
    fn allowed(self) -> &'static str {
        match self {
            Scope::Frame => "{name}, {n}",
            Scope::Comment => "{name}, {n}, {comment}",
            Scope::Block => {
                "{name}, {n}, {comment}, {axes}, {f}, {fi}, {t}, or an axis name like {X}"
            }
        }
    }
}

/// A text field parsed into pieces.
#[derive(Debug, Clone, PartialEq)]
struct Field {
    name: &'static str,
    pieces: Vec<Piece>,
    /// Append a line break after it.
    newline: bool,
}

/// A user post-processor read from TOML (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Template {
    extension: String,
    header: Field,
    comment: Option<Field>,
    rapid: Option<Field>,
    block: Field,
    inverse: Option<Field>,
    footer: Field,
    rezero: Option<Field>,
    decimals_mm: u32,
    decimals_deg: u32,
    signed: bool,
    modal_axes: bool,
    axis_letters: BTreeMap<String, String>,
    line_start: u64,
    line_step: u64,
}

impl Template {
    /// Reads a template from TOML text, checking every placeholder.
    pub fn from_toml(text: &str) -> Result<Self, NcError> {
        let f: TemplateFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|span| span.start.min(text.len()));
            NcError::template(TemplateProblem::Toml {
                line: at.map(|at| text[..at].matches('\n').count() + 1),
                message: syntax_message(e.message(), text, at.unwrap_or(text.len())),
            })
        })?;
        let decimals = |field, d: i64| {
            u32::try_from(d)
                .ok()
                .filter(|d| *d <= MAX_DECIMALS)
                .ok_or_else(|| NcError::template(TemplateProblem::Decimals { field, decimals: d }))
        };
        let decimals_mm = decimals("decimals_mm", f.decimals_mm)?;
        let decimals_deg = decimals("decimals_deg", f.decimals_deg)?;
        let plain = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
        if f.extension.is_empty() || !f.extension.chars().all(plain) {
            return Err(NcError::template(TemplateProblem::Extension {
                extension: formcam_files::quote(&f.extension).to_string(),
            }));
        }
        if f.line_numbers.as_ref().is_some_and(|l| l.step == 0) {
            return Err(NcError::template(TemplateProblem::LineStep));
        }
        let letters = f.axis_letters.as_ref();
        let parse = |name, text: &str, scope| parse_field(name, text, scope, letters);
        Ok(Self {
            header: parse("header", &f.header, Scope::Frame)?,
            comment: f
                .comment
                .as_deref()
                .map(|t| parse("comment", t, Scope::Comment))
                .transpose()?,
            rapid: f
                .rapid
                .as_deref()
                .map(|t| parse("rapid", t, Scope::Block))
                .transpose()?,
            block: parse("block", &f.block, Scope::Block)?,
            inverse: f
                .inverse
                .as_deref()
                .map(|t| parse("inverse", t, Scope::Block))
                .transpose()?,
            footer: parse("footer", &f.footer, Scope::Frame)?,
            rezero: f
                .rezero
                .as_deref()
                .map(|t| parse("rezero", t, Scope::Block))
                .transpose()?,
            extension: f.extension,
            decimals_mm,
            decimals_deg,
            signed: f.signed,
            modal_axes: f.modal_axes,
            axis_letters: f.axis_letters.unwrap_or_default(),
            line_start: f.line_numbers.as_ref().map_or(1, |l| l.start),
            line_step: f.line_numbers.as_ref().map_or(1, |l| l.step),
        })
    }

    /// Reads a template file.
    pub fn load(path: &Path) -> Result<Self, NcError> {
        let text = formcam_files::read_text(path).map_err(|e| NcError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::from_toml(&text).map_err(|e| match e {
            NcError::Template {
                file: None,
                problem,
            } => NcError::Template {
                file: Some(path.display().to_string()),
                problem,
            },
            e => e,
        })
    }

    /// How it keeps modulo axes within the bound: re-zeroing when it has a
    /// `rezero` field, else not at all (`None`: written unwound).
    pub fn modulo_style(&self) -> Option<ModuloStyle> {
        self.rezero.as_ref().map(|_| ModuloStyle::Rezero)
    }

    /// The file extension of the programs it writes, without the dot.
    pub fn extension(&self) -> &str {
        &self.extension
    }

    fn fields(&self) -> impl Iterator<Item = &Field> {
        [&self.header, &self.block, &self.footer]
            .into_iter()
            .chain(self.comment.iter())
            .chain(self.rapid.iter())
            .chain(self.inverse.iter())
            .chain(self.rezero.iter())
    }
}

impl std::str::FromStr for Template {
    type Err = NcError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_toml(s)
    }
}

fn is_axis_name(s: &str) -> bool {
    let mut c = s.chars();
    c.next().is_some_and(|c| c.is_ascii_uppercase())
        && c.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

fn parse_field(
    name: &'static str,
    text: &str,
    scope: Scope,
    letters: Option<&BTreeMap<String, String>>,
) -> Result<Field, NcError> {
    let mut pieces = Vec::new();
    let mut lit = String::new();
    let mut rest = text;
    while let Some(i) = rest.find(['{', '}']) {
        lit.push_str(&rest[..i]);
        let tail = &rest[i..];
        if let Some(r) = tail.strip_prefix("{{") {
            lit.push('{');
            rest = r;
        } else if let Some(r) = tail.strip_prefix("}}").or_else(|| tail.strip_prefix('}')) {
            lit.push('}');
            rest = r;
        } else {
            let Some(end) = tail.find('}') else {
                return Err(NcError::template(TemplateProblem::Unclosed { field: name }));
            };
            let ph = &tail[1..end];
            let unknown = || NcError::UnknownPlaceholder {
                placeholder: excerpt(ph),
                field: name.to_string(),
                allowed: scope.allowed().to_string(),
            };
            let piece = match (ph, scope) {
                ("name", _) => Piece::Name,
                ("n", _) => Piece::N,
                ("comment", Scope::Comment | Scope::Block) => Piece::Comment,
                ("axes", Scope::Block) => Piece::Axes,
                ("f", Scope::Block) => Piece::F,
                ("fi", Scope::Block) => Piece::Fi,
                ("t", Scope::Block) => Piece::T,
                (a, Scope::Block)
                    if is_axis_name(a) && letters.is_none_or(|l| l.contains_key(a)) =>
                {
                    Piece::Axis(a.to_string())
                }
                _ => return Err(unknown()),
            };
            if !lit.is_empty() {
                pieces.push(Piece::Text(std::mem::take(&mut lit)));
            }
            pieces.push(piece);
            rest = &tail[end + 1..];
        }
    }
    lit.push_str(rest);
    if !lit.is_empty() {
        pieces.push(Piece::Text(lit));
    }
    Ok(Field {
        name,
        newline: !text.is_empty() && !text.ends_with('\n'),
        pieces,
    })
}

/// What one block's placeholders expand to.
struct BlockCtx<'a> {
    index: usize,
    comment: &'a str,
    /// The re-zero before block `index`: the modulo axes where the block
    /// before ends.
    rezero: bool,
}

/// The writer's running state.
struct Writer<'a> {
    p: &'a Program,
    t: &'a Template,
    /// Per axis: printed letter, decimals.
    axes: Vec<(&'a str, u32)>,
    /// Last printed scaled values for modal `{axes}`.
    last: Vec<Option<i64>>,
    /// The re-zeroed whole turns per axis, scaled by its decimals.
    off: Vec<i64>,
    line: u64,
}

impl Writer<'_> {
    fn value(&self, out: &mut Out, k: usize, v: f64) {
        let (_, d) = self.axes[k];
        match num::scaled(v, d) {
            Some(s) if self.off[k] != 0 => {
                if self.t.signed && s - self.off[k] >= 0 {
                    out.c('+');
                }
                num::push_scaled(out, s - self.off[k], d, false);
            }
            s => {
                if self.t.signed && s.is_some_and(|s| s >= 0) {
                    out.c('+');
                }
                num::push(out, v, d, false);
            }
        }
    }

    /// Re-zeroes the modulo axes where block `index - 1` ends.
    fn rezero(&mut self, index: usize) {
        let Some(before) = index.checked_sub(1).map(|i| &self.p.blocks[i].target) else {
            return;
        };
        for (k, a) in self.p.axes.iter().enumerate() {
            let d = self.axes[k].1;
            if let (true, Some(s)) = (a.modulo, num::scaled(before[k], d)) {
                self.off[k] = modulo::turns_below_in(s, 360 * 10i64.pow(d));
            }
        }
    }

    /// The modulo axes and their re-zeroed angles where block `index - 1` ends.
    fn rezero_words(&self, out: &mut Out, index: usize) {
        let Some(before) = index.checked_sub(1).map(|i| &self.p.blocks[i].target) else {
            return;
        };
        let mut any = false;
        for k in (0..before.len()).filter(|&k| self.p.axes[k].modulo) {
            if any {
                out.c(' ');
            }
            out.s(self.axes[k].0);
            self.value(out, k, before[k]);
            any = true;
        }
    }

    fn render(&mut self, out: &mut Out, field: &Field, blk: Option<&BlockCtx<'_>>) {
        for piece in &field.pieces {
            match piece {
                Piece::Text(s) => out.s(s),
                Piece::Name => out.s(&self.p.name),
                Piece::N => {
                    num::push_uint(out, self.line);
                    self.line += self.t.line_step;
                }
                Piece::Comment => {
                    if let Some(b) = blk.filter(|b| !b.rezero) {
                        crate::post::push_comment_text(out, b.comment, false);
                    }
                }
                Piece::Axes => match blk {
                    Some(b) if b.rezero => self.rezero_words(out, b.index),
                    Some(b) => self.axes_words(out, b.index),
                    None => {}
                },
                Piece::Axis(a) => {
                    if let (Some(b), Some(k)) = (blk, self.p.axes.iter().position(|x| x.name == *a))
                    {
                        let i = if b.rezero { b.index - 1 } else { b.index };
                        self.value(out, k, self.p.blocks[i].target[k]);
                    }
                }
                Piece::F | Piece::Fi | Piece::T => {
                    if let Some(b) = blk.filter(|b| !b.rezero) {
                        self.feed(out, piece, b.index);
                    }
                }
            }
        }
        if field.newline {
            out.c('\n');
        }
    }

    fn axes_words(&mut self, out: &mut Out, index: usize) {
        let target = &self.p.blocks[index].target;
        let mut any = false;
        for (k, v) in target.iter().enumerate() {
            let s = num::scaled(*v, self.axes[k].1);
            if self.t.modal_axes && s.is_some() && s == self.last[k] {
                continue;
            }
            if any {
                out.c(' ');
            }
            out.s(self.axes[k].0);
            self.value(out, k, *v);
            self.last[k] = s;
            any = true;
        }
        if !any && !target.is_empty() {
            out.s(self.axes[0].0);
            self.value(out, 0, target[0]);
        }
    }

    fn feed(&self, out: &mut Out, piece: &Piece, index: usize) {
        let b = &self.p.blocks[index];
        match (piece, b.feed) {
            (Piece::F, Feed::PerMinute(f)) => num::push(out, f, num::FEED, false),
            (Piece::F, Feed::InverseTime(t)) => {
                let travel = index
                    .checked_sub(1)
                    .map_or(0.0, |i| nc_travel(&self.p.blocks[i].target, &b.target));
                if travel > 0.0 {
                    num::push(out, travel / t * 60.0, num::FEED_FINE, false);
                }
            }
            (Piece::Fi, Feed::InverseTime(t)) => num::push(out, 60.0 / t, num::FEED_FINE, false),
            (Piece::T, _) => {
                if let Some(t) = self.p.block_time_s(index) {
                    num::push(out, t, 4, false);
                }
            }
            _ => {}
        }
    }
}

/// Writes `program` with the user template `template`, appending to `out`.
///
/// Fails, writing nothing, when the program is inconsistent
/// ([`Program::validate`]), an axis placeholder names no axis of it, or (with
/// a `rezero` field) a modulo axis would be written beyond the bound.
pub fn write_template(
    program: &Program,
    template: &Template,
    out: &mut String,
) -> Result<(), NcError> {
    program.validate()?;
    if let Some(style) = template.modulo_style() {
        modulo::check(program, style)?;
    }
    for field in template.fields() {
        for piece in &field.pieces {
            if let Piece::Axis(a) = piece
                && !program.axes.iter().any(|x| x.name == *a)
            {
                return Err(NcError::UnknownPlaceholder {
                    placeholder: a.clone(),
                    field: field.name.to_string(),
                    allowed: format!(
                        "the program's axes {}",
                        program
                            .axes
                            .iter()
                            .map(|x| format!("{{{}}}", x.name))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                });
            }
        }
    }
    let axes = program
        .axes
        .iter()
        .map(|a| {
            let letter = template
                .axis_letters
                .get(&a.name)
                .map_or(a.name.as_str(), String::as_str);
            let d = if a.rotary {
                template.decimals_deg
            } else {
                template.decimals_mm
            };
            (letter, d)
        })
        .collect();
    num::with_out(out, |out| {
        let mut w = Writer {
            p: program,
            t: template,
            axes,
            last: vec![None; program.axes.len()],
            off: vec![0; program.axes.len()],
            line: template.line_start,
        };
        out.reserve(256 + program.blocks.len() * (16 + 12 * program.axes.len()));
        w.render(out, &template.header, None);
        if let Some(c) = &template.comment {
            for text in &program.header_comments {
                let ctx = BlockCtx {
                    index: 0,
                    comment: text,
                    rezero: false,
                };
                w.render(out, c, Some(&ctx));
            }
        }
        for (index, b) in program.blocks.iter().enumerate() {
            if let (Some(r), true, true) = (&template.rezero, b.rezero, index > 0) {
                w.rezero(index);
                let ctx = BlockCtx {
                    index,
                    comment: "",
                    rezero: true,
                };
                w.render(out, r, Some(&ctx));
            }
            if let (Some(c), Some(text)) = (&template.comment, &b.comment) {
                let ctx = BlockCtx {
                    index,
                    comment: text,
                    rezero: false,
                };
                w.render(out, c, Some(&ctx));
            }
            let field = match (b.kind, b.feed) {
                (Motion::Rapid, _) => template.rapid.as_ref().unwrap_or(&template.block),
                (Motion::Linear, Feed::InverseTime(_)) => {
                    template.inverse.as_ref().unwrap_or(&template.block)
                }
                _ => &template.block,
            };
            let ctx = BlockCtx {
                index,
                comment: b.comment.as_deref().unwrap_or(""),
                rezero: false,
            };
            w.render(out, field, Some(&ctx));
        }
        w.render(out, &template.footer, None);
        Ok(())
    })
}
