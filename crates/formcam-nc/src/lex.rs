//! Words of a G-code line: the one lexer of formcam's G-code readers, the
//! milling-program reader ([`crate::read_toolpath`], which must keep every
//! byte and so records where each word is) and the program reader
//! ([`crate::read_gcode`], which checks what the writers wrote).
//!
//! A line is lexed into one-letter address words (`X-1.5`, `G01`, `N10`),
//! Sinumerik `NAME=value` assignments (`J1=12.5`, `A=ACP(90)`) where the
//! [`Syntax`] asks for them, comments and a note of the first thing that is
//! not a word (a keyword, an expression). What a word means is the readers'
//! business ([`crate::modal`] for the G codes).

use formcam_files::quote;
use std::ops::Range;

use crate::modulo::Direction;
use crate::{Dialect, NcError};

/// What a reader takes as G-code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Syntax {
    /// `(…)` is a comment (not on Sinumerik).
    pub(crate) paren_comments: bool,
    /// Sinumerik addresses: `X=1`, `CR=` radii; frame keywords refused.
    pub(crate) sinumerik: bool,
    /// The program reader's rules: `NAME=value` and `NAME=ACP(v)`
    /// assignments, letters read one by one (no keywords), nested comments,
    /// and every letter needs a number.
    pub(crate) strict: bool,
}

impl Syntax {
    /// The milling-program syntax of `dialect` (Marlin and CLDATA read as
    /// ISO).
    pub(crate) fn milling(dialect: Dialect) -> Self {
        let sinumerik = dialect == Dialect::Sinumerik840d;
        Self {
            paren_comments: !sinumerik,
            sinumerik,
            strict: false,
        }
    }

    /// The program reader's syntax (any of formcam's G-code dialects).
    pub(crate) const PROGRAM: Self = Self {
        paren_comments: true,
        sinumerik: false,
        strict: true,
    };
}

/// A one-letter address word.
#[derive(Debug, Clone)]
pub(crate) struct Word {
    /// The letter, upper case.
    pub(crate) letter: u8,
    /// The number.
    pub(crate) value: f64,
    /// Letter to the end of the number (bytes of the text).
    pub(crate) whole: Range<usize>,
    /// The number.
    pub(crate) num: Range<usize>,
    /// The number's text has a decimal point.
    pub(crate) point: bool,
    /// Digits after the point.
    pub(crate) decimals: u32,
}

/// A Sinumerik assignment `NAME=value`, `NAME=ACP(v)`, `ACN(v)`, `DC(v)`.
#[derive(Debug, Clone)]
pub(crate) struct Assignment {
    /// The name as written.
    pub(crate) name: String,
    /// The number.
    pub(crate) value: f64,
    /// The direction of `ACP`, `ACN` or `DC`.
    pub(crate) direction: Option<Direction>,
}

/// A line split into words.
#[derive(Debug, Default)]
pub(crate) struct Lexed {
    /// The address words, in order.
    pub(crate) words: Vec<Word>,
    /// Assignments (strict syntax only), in order.
    pub(crate) assignments: Vec<Assignment>,
    /// `CR=` value and span (Sinumerik).
    pub(crate) cr: Option<(f64, Range<usize>)>,
    /// The comments' texts (without `(`, `)`, `;`).
    pub(crate) comments: Vec<Range<usize>>,
    /// Something not read as words (keywords, expressions, macros), from
    /// where it starts to the end of the line.
    pub(crate) complex: Option<String>,
    /// End of the code before any `;` comment (a byte offset).
    pub(crate) code_end: usize,
    /// Blanks between words.
    pub(crate) spaced: bool,
    /// The line starts with `/` (block delete).
    pub(crate) block_delete: bool,
    /// Where comments and `%` marks stand (strict syntax): they end the
    /// arguments of a G, M or T code.
    pub(crate) breaks: Vec<usize>,
}

/// Sinumerik keywords that change the coordinate system.
const FRAMES: [&str; 10] = [
    "TRANS", "ATRANS", "ROT", "AROT", "SCALE", "ASCALE", "MIRROR", "AMIRROR", "RPL", "CYCLE800",
];

/// The lines of `text`: each line's text and its terminator (`\n`, `\r\n`,
/// or empty at the end), as byte ranges.
pub(crate) fn lines(text: &str) -> impl Iterator<Item = (Range<usize>, Range<usize>)> + '_ {
    let mut start = 0;
    std::iter::from_fn(move || {
        if start >= text.len() {
            return None;
        }
        let rest = &text[start..];
        let (len, eol_len) = match rest.find('\n') {
            Some(k) if k > 0 && rest.as_bytes()[k - 1] == b'\r' => (k - 1, 2),
            Some(k) => (k, 1),
            None => (rest.len(), 0),
        };
        let line = (start..start + len, start + len..start + len + eol_len);
        start += len + eol_len;
        Some(line)
    })
}

/// An error on line `line` whose text is `text`.
pub(crate) fn line_error(line: usize, text: &str, what: impl std::fmt::Display) -> NcError {
    NcError::parse(line, format!("`{}`: {what}", quote(text.trim_end())))
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

/// Whether the number ending at `b[ne]` goes on with an exponent (`e5`,
/// `E-3`): NC words take plain decimals, and `X1e400` is neither `X1` and an
/// `E` word nor a number to round to infinity.
fn exponent_follows(b: &[u8], ne: usize) -> bool {
    let digit = |k: usize| b.get(k).is_some_and(u8::is_ascii_digit);
    matches!(b.get(ne), Some(b'e' | b'E'))
        && (digit(ne + 1) || (matches!(b.get(ne + 1), Some(b'+' | b'-')) && digit(ne + 2)))
}

/// The end of the token at `b[i..]`: the next blank, `;` or the line's end.
fn token_end(b: &[u8], i: usize) -> usize {
    b[i..]
        .iter()
        .position(|c| matches!(c, b' ' | b'\t' | b';'))
        .map_or(b.len(), |k| i + k)
}

fn skip_blanks(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && b[i] == b' ' {
        i += 1;
    }
    i
}

/// The lexer's place in one line.
struct Lexer<'a> {
    text: &'a str,
    b: &'a [u8],
    /// Byte offset of the line in the program.
    base: usize,
    lineno: usize,
    syntax: Syntax,
    out: Lexed,
    blanks: usize,
    joins: usize,
    last_was_word: bool,
}

/// Lexes line `lineno` (1-based), whose text `text` starts at byte `base` of
/// the program.
pub(crate) fn lex(
    text: &str,
    base: usize,
    lineno: usize,
    syntax: Syntax,
) -> Result<Lexed, NcError> {
    let mut lx = Lexer {
        text,
        b: text.as_bytes(),
        base,
        lineno,
        syntax,
        out: Lexed {
            code_end: base + text.len(),
            ..Lexed::default()
        },
        blanks: 0,
        joins: 0,
        last_was_word: false,
    };
    let mut i = 0;
    while i < lx.b.len() {
        i = match lx.b[i] {
            b' ' | b'\t' => lx.blank(i),
            b';' => {
                lx.out.code_end = base + i;
                lx.out.comments.push(base + i + 1..base + lx.b.len());
                break;
            }
            b'(' if syntax.paren_comments => lx.paren_comment(i)?,
            b'%' if syntax.strict => {
                lx.out.breaks.push(base + i);
                i + 1
            }
            b'/' if syntax.strict => return Err(lx.err("a `/` block delete is not supported")),
            c @ (b'/' | b'%') if lx.out.words.is_empty() && lx.out.complex.is_none() => {
                lx.out.block_delete |= c == b'/';
                i + 1
            }
            b'@' | b'^' if !syntax.strict => {
                return Err(lx.err("polar coordinates (`@`, `^`) are not supported"));
            }
            c if c.is_ascii_alphabetic() => lx.letters(i)?,
            _ => lx.stray(i)?,
        };
    }
    lx.out.spaced = lx.blanks >= lx.joins;
    Ok(lx.out)
}

impl Lexer<'_> {
    fn err(&self, what: impl std::fmt::Display) -> NcError {
        line_error(self.lineno, self.text, what)
    }

    /// The number `text[j..ne]` of the word or assignment starting at `i`:
    /// plain decimals only (no exponent), finite.
    fn number(&self, i: usize, j: usize, ne: usize) -> Result<f64, NcError> {
        let word = || quote(&self.text[i..token_end(self.b, i)]);
        if exponent_follows(self.b, ne) {
            return Err(self.err(format!(
                "`{}`: a number with an exponent; NC words take plain decimals (like 12.5)",
                word()
            )));
        }
        let num = &self.text[j..ne];
        let value: f64 = num
            .parse()
            .map_err(|_| self.err(format!("unreadable `{}`", quote(num))))?;
        if !value.is_finite() {
            return Err(self.err(format!(
                "`{}`: the number is too large (not finite)",
                word()
            )));
        }
        Ok(value)
    }

    fn blank(&mut self, i: usize) -> usize {
        if self.last_was_word {
            self.blanks += 1;
            self.last_was_word = false;
        }
        i + 1
    }

    /// A `(…)` comment at `i`; nested ones in the strict syntax.
    fn paren_comment(&mut self, i: usize) -> Result<usize, NcError> {
        let mut depth = 0usize;
        for (k, c) in self.b[i..].iter().enumerate() {
            match c {
                b'(' if self.syntax.strict || depth == 0 => depth += 1,
                b')' => {
                    depth -= 1;
                    if depth == 0 {
                        let end = i + k;
                        if self.syntax.strict {
                            self.out.breaks.push(self.base + i);
                        }
                        self.out.comments.push(self.base + i + 1..self.base + end);
                        self.last_was_word = false;
                        return Ok(end + 1);
                    }
                }
                _ => {}
            }
        }
        Err(self.err("a comment `(` without `)`"))
    }

    /// Something that is not a word: refused in the strict syntax, else
    /// noted and skipped a character at a time.
    fn stray(&mut self, i: usize) -> Result<usize, NcError> {
        if self.syntax.strict {
            let end = self.text[i..]
                .find([' ', '\t', ';'])
                .map_or(self.text.len(), |k| i + k);
            return Err(self.err(format!("cannot read `{}`", quote(&self.text[i..end]))));
        }
        if self.out.complex.is_none() {
            self.out.complex = Some(self.text[i..].trim_end().to_string());
        }
        self.last_was_word = false;
        Ok(i + self.text[i..].chars().next().map_or(1, char::len_utf8))
    }

    /// Letters at `i`: an assignment, a keyword or a one-letter word.
    fn letters(&mut self, i: usize) -> Result<usize, NcError> {
        if self.syntax.strict {
            if let Some(next) = self.assignment(i)? {
                return Ok(next);
            }
            return self.word(i);
        }
        let b = self.b;
        let mut e = i + 1;
        while e < b.len() && (b[e].is_ascii_alphabetic() || b[e] == b'_') {
            e += 1;
        }
        if e - i > 1 {
            self.keyword(i, e)
        } else {
            self.word(i)
        }
    }

    /// `NAME=value` or `NAME=ACP(v)` at `i` (strict syntax); `None` when the
    /// name is not followed by `=`.
    fn assignment(&mut self, i: usize) -> Result<Option<usize>, NcError> {
        let b = self.b;
        let mut e = i + 1;
        while e < b.len() && (b[e].is_ascii_alphanumeric() || b[e] == b'_') {
            e += 1;
        }
        let eq = skip_blanks(b, e);
        if b.get(eq) != Some(&b'=') {
            return Ok(None);
        }
        let name = &self.text[i..e];
        let mut j = skip_blanks(b, eq + 1);
        let mut direction = None;
        for (f, d) in [
            ("ACP(", Direction::Positive),
            ("ACN(", Direction::Negative),
            ("DC(", Direction::Shortest),
        ] {
            if b[j..]
                .get(..f.len())
                .is_some_and(|w| w.eq_ignore_ascii_case(f.as_bytes()))
            {
                direction = Some(d);
                j += f.len();
                break;
            }
        }
        let Some(mut end) = number_end(b, j) else {
            return Err(self.err(format!("`{}=` is not followed by a number", quote(name))));
        };
        let value = self.number(i, j, end)?;
        if direction.is_some() {
            if b.get(end) != Some(&b')') {
                return Err(self.err(format!(
                    "`{}=`: the number in parentheses is not closed",
                    quote(name)
                )));
            }
            end += 1;
        }
        self.out.assignments.push(Assignment {
            name: name.to_string(),
            value,
            direction,
        });
        self.last_was_word = true;
        Ok(Some(end))
    }

    /// A keyword `b[i..e]` of several letters (milling syntax): a Sinumerik
    /// `CR=` radius, a refused frame, or something that is not a word.
    fn keyword(&mut self, i: usize, e: usize) -> Result<usize, NcError> {
        let b = self.b;
        let ident = self.text[i..e].to_ascii_uppercase();
        if self.syntax.sinumerik && ident == "CR" {
            let j = skip_blanks(b, e);
            if b.get(j) == Some(&b'=') {
                let j = skip_blanks(b, j + 1);
                if let Some(ne) = number_end(b, j) {
                    let v = self.number(i, j, ne)?;
                    self.out.cr = Some((v, self.base + i..self.base + ne));
                    self.last_was_word = true;
                    return Ok(ne);
                }
            }
        }
        if self.syntax.sinumerik && FRAMES.contains(&ident.as_str()) {
            return Err(self.err(format!(
                "`{}` changes the coordinate system, which is not supported",
                quote(&ident)
            )));
        }
        self.out
            .complex
            .get_or_insert_with(|| self.text[i..].trim_end().to_string());
        // Skip the rest of this token.
        let mut k = e;
        while k < b.len() && b[k] != b' ' && b[k] != b'\t' && b[k] != b';' {
            if b[k] == b'"' {
                k += 1;
                while k < b.len() && b[k] != b'"' {
                    k += 1;
                }
            }
            k += 1;
        }
        self.last_was_word = false;
        Ok(k)
    }

    /// A one-letter word at `i`: the letter, blanks, (Sinumerik: `=`), the
    /// number.
    fn word(&mut self, i: usize) -> Result<usize, NcError> {
        let (b, text) = (self.b, self.text);
        let letter = b[i].to_ascii_uppercase();
        let mut j = i + 1;
        while j < b.len() && (b[j] == b' ' || b[j] == b'\t') {
            j += 1;
        }
        if self.syntax.sinumerik && b.get(j) == Some(&b'=') {
            j = skip_blanks(b, j + 1);
        }
        let Some(ne) = number_end(b, j) else {
            let strict_letter = self.syntax.strict
                || matches!(
                    letter,
                    b'X' | b'Y' | b'Z' | b'I' | b'J' | b'K' | b'R' | b'G'
                );
            if strict_letter {
                let what = if j < b.len() && !matches!(b[j], b' ' | b'\t' | b';' | b'(') {
                    let end = text[j..]
                        .find([' ', '\t', ';'])
                        .map_or(text.len(), |k| j + k);
                    format!("cannot read `{}`", quote(&text[i..end]))
                } else {
                    format!("`{}` without a number", letter as char)
                };
                return Err(self.err(what));
            }
            self.out
                .complex
                .get_or_insert_with(|| text[i..].trim_end().to_string());
            self.last_was_word = false;
            return Ok(j.max(i + 1));
        };
        let num = &text[j..ne];
        let value = self.number(i, j, ne)?;
        let (point, decimals) = match num.find('.') {
            Some(p) => (true, (num.len() - p - 1) as u32),
            None => (false, 0),
        };
        if self.syntax.strict && matches!(letter, b'N' | b'O') {
            let after_code = self
                .out
                .words
                .iter()
                .any(|w| matches!(w.letter, b'G' | b'M' | b'T'));
            if after_code {
                return Err(self.err(format!("`{}` after a G, M or T code", letter as char)));
            }
        }
        if self.last_was_word {
            self.joins += 1;
        }
        self.out.words.push(Word {
            letter,
            value,
            whole: self.base + i..self.base + ne,
            num: self.base + j..self.base + ne,
            point,
            decimals,
        });
        self.last_was_word = true;
        Ok(ne)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;

    fn milling(text: &str) -> Lexed {
        lex(text, 0, 1, Syntax::milling(Dialect::Iso)).unwrap()
    }

    #[test]
    fn words_keep_their_places_and_number_style() {
        let lx = milling("N10 G01X-1.50 Y.5 (note) Z2 ; end");
        let letters: Vec<u8> = lx.words.iter().map(|w| w.letter).collect();
        assert_eq!(letters, b"NGXYZ");
        let x = &lx.words[2];
        assert_eq!((x.value, x.point, x.decimals), (-1.5, true, 2));
        assert_eq!(x.whole, 7..13);
        assert_eq!(x.num, 8..13);
        assert_eq!(lx.words[3].value, 0.5);
        assert_eq!(lx.comments, vec![19..23, 29..33]);
        assert_eq!(lx.code_end, 28);
        assert!(lx.complex.is_none());
    }

    #[test]
    fn milling_keywords_are_noted_and_program_assignments_read() {
        let lx = lex(
            "MSG(\"x\") G1 X=2",
            0,
            1,
            Syntax::milling(Dialect::Sinumerik840d),
        )
        .unwrap();
        assert_eq!(lx.complex.as_deref(), Some("MSG(\"x\") G1 X=2"));
        assert_eq!(lx.words.last().map(|w| w.value), Some(2.0));
        let lx = lex("N20 G1 J1=12.5 A=ACN(3.25) F10", 0, 1, Syntax::PROGRAM).unwrap();
        let names: Vec<_> = lx.assignments.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["J1", "A"]);
        assert_eq!(lx.assignments[1].value, 3.25);
        assert_eq!(lx.assignments[1].direction, Some(Direction::Negative));
        assert!(lex("G1 A=four", 0, 1, Syntax::PROGRAM).is_err());
        assert!(lex("G1 A=ACP(4", 0, 1, Syntax::PROGRAM).is_err());
        assert!(lex("MSG", 0, 1, Syntax::PROGRAM).is_err());
        let lx = lex("(a (nested) one) G1", 0, 1, Syntax::PROGRAM).unwrap();
        assert_eq!(lx.comments, vec![1..15]);
    }

    #[test]
    fn lines_and_their_ends() {
        let t = "a\r\nb\n\nc";
        let got: Vec<_> = lines(t).map(|(l, e)| (&t[l], &t[e])).collect();
        assert_eq!(got, [("a", "\r\n"), ("b", "\n"), ("", "\n"), ("c", "")]);
    }
}
