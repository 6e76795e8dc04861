//! Short, escaped excerpts of user text for error messages.
//!
//! An error that quotes what a user wrote (a line of a CSV, G-code or DMIS
//! file, a TOML value, a word, a name) quotes it through [`quote`]: at most
//! [`QUOTE_MAX_CHARS`] characters, cut on a character boundary with `…`
//! marking the cut, and every control or invisible character escaped the way
//! Rust's `escape_debug` writes it (`\0`, `\t`, `\n`, `\r`, `\u{1b}`), while
//! printable non-ASCII text (`ø`, `µ`, `°`) stays as it is. A 10 MB line gives
//! an 80-character message, and no ESC or NUL byte reaches the terminal.
//!
//! [`syntax_message`] gives a parser's message that says nothing (a TOML cut
//! right after `key =`, a NUL in the text) what was expected instead.

use std::fmt;

/// The most characters a quote writes, the `…` of a cut included.
pub const QUOTE_MAX_CHARS: usize = 80;

/// The mark of a cut quote.
const CUT: char = '…';

/// `text` quoted for an error message: at most [`QUOTE_MAX_CHARS`]
/// characters, controls and invisible characters escaped. Writing it reads
/// at most that many characters of `text`, however long `text` is.
pub fn quote(text: &str) -> Quote<'_> {
    Quote { text }
}

/// `text` quoted for an error message, as an owned string to keep in an
/// error's field (the same text as [`quote`] writes).
pub fn excerpt(text: &str) -> String {
    quote(text).to_string()
}

/// User text as an error message quotes it; see [`quote`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quote<'a> {
    text: &'a str,
}

impl fmt::Display for Quote<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let cut = cut_at(self.text);
        for c in self.text[..cut].chars() {
            write_char(f, c)?;
        }
        if cut < self.text.len() {
            write!(f, "{CUT}")?;
        }
        Ok(())
    }
}

/// The byte index where the quote of `text` stops: `text.len()` when the
/// whole text fits in [`QUOTE_MAX_CHARS`], else the end of the longest
/// prefix whose escaped form leaves room for the `…`.
fn cut_at(text: &str) -> usize {
    let mut written = 0;
    // The end of the prefix that fits with the cut mark after it.
    let mut fits_with_mark = 0;
    for (at, c) in text.char_indices() {
        let width = escaped_width(c);
        if written + width > QUOTE_MAX_CHARS {
            return fits_with_mark;
        }
        written += width;
        if written < QUOTE_MAX_CHARS {
            fits_with_mark = at + c.len_utf8();
        }
    }
    text.len()
}

/// How a character is written in a quote.
enum Shown {
    /// As itself.
    Plain(char),
    /// As a backslash escape of one letter: `\0`, `\t`, `\n`, `\r`.
    Short(char),
    /// As `\u{hex}`.
    Unicode(u32),
}

/// How `c` is written: controls and invisible characters escaped.
fn shown(c: char) -> Shown {
    match c {
        '\0' => Shown::Short('0'),
        '\t' => Shown::Short('t'),
        '\n' => Shown::Short('n'),
        '\r' => Shown::Short('r'),
        c if is_hidden(c) => Shown::Unicode(u32::from(c)),
        c => Shown::Plain(c),
    }
}

/// Characters written as `\u{...}`: controls (C0, DEL, C1) and the
/// characters that print nothing or change how the rest prints (format
/// characters such as zero-width spaces and bidirectional overrides, line
/// and paragraph separators, the byte-order mark, tags, noncharacters).
fn is_hidden(c: char) -> bool {
    c.is_control()
        || matches!(
            u32::from(c),
            0xAD | 0x061C
                | 0x180E
                | 0x200B..=0x200F
                | 0x2028..=0x202E
                | 0x2060..=0x206F
                | 0xFEFF
                | 0xFFF9..=0xFFFB
                | 0xFFFE..=0xFFFF
                | 0xE0000..=0xE007F
        )
}

/// The characters `c` takes in a quote.
fn escaped_width(c: char) -> usize {
    match shown(c) {
        Shown::Plain(_) => 1,
        Shown::Short(_) => 2,
        // `\u{` + hex digits + `}`.
        Shown::Unicode(code) => 4 + hex_digits(code),
    }
}

/// Lowercase hex digits of `code` (at least one).
fn hex_digits(code: u32) -> usize {
    let bits = 32 - code.leading_zeros() as usize;
    bits.div_ceil(4).max(1)
}

fn write_char(f: &mut fmt::Formatter<'_>, c: char) -> fmt::Result {
    match shown(c) {
        Shown::Plain(c) => write!(f, "{c}"),
        Shown::Short(letter) => write!(f, "\\{letter}"),
        Shown::Unicode(code) => write!(f, "\\u{{{code:x}}}"),
    }
}

/// A parser's `message` about `text` at byte `at`, or, when the message is
/// empty or the parser stopped at a control character, what was expected
/// there: `NUL characters are not allowed` (or
/// another control character), `expected a value after `=`` when the line
/// stops after `key =`, `unexpected end of the text`, `unexpected `c``.
/// Newlines in the message become spaces (a message is one line). An
/// unknown field names the nearest field instead of the list of all
/// (`unknown field `vmax_deg_min`; did you mean `v_max_deg_min`?`), or lists
/// them without backticks when none is near.
pub fn syntax_message(message: &str, text: &str, at: usize) -> String {
    let at = floor_char_boundary(text, at);
    let stray = |c: char| c.is_control() && !matches!(c, '\t' | '\n' | '\r');
    let message = message.trim();
    // A control character where the parser stopped is what it could not
    // read, whatever it says it expected (the user cannot see it).
    let here = text[at..].chars().next().filter(|&c| stray(c));
    if !message.is_empty() && here.is_none() {
        let message = message.replace('\n', " ");
        return unknown_field(&message).unwrap_or(message);
    }
    if let Some(c) = here.or_else(|| text.chars().find(|&c| stray(c))) {
        return if c == '\0' {
            "NUL characters are not allowed".to_string()
        } else {
            format!(
                "control character `{}` is not allowed",
                quote(c.encode_utf8(&mut [0; 4]))
            )
        };
    }
    let rest_of_line = text[at..].split('\n').next().unwrap_or_default();
    if text[..at].trim_end().ends_with('=') && rest_of_line.trim().is_empty() {
        return "expected a value after `=`".to_string();
    }
    match text[at..].chars().next() {
        None => "unexpected end of the text".to_string(),
        Some(c) => format!("unexpected `{}`", quote(c.encode_utf8(&mut [0; 4]))),
    }
}

/// serde's `unknown field `x`, expected one of `a`, `b`, ...` made short:
/// the nearest field when one is near, else the fields without backticks.
fn unknown_field(message: &str) -> Option<String> {
    let (name, rest) = message.strip_prefix("unknown field `")?.split_once('`')?;
    let list = rest.strip_prefix(", expected one of ")?;
    let fields: Vec<&str> = list.split(", ").map(|f| f.trim_matches('`')).collect();
    Some(match nearest(name, &fields) {
        Some(field) => format!("unknown field `{}`; did you mean `{field}`?", quote(name)),
        None => format!(
            "unknown field `{}`; allowed: {}",
            quote(name),
            fields.join(", ")
        ),
    })
}

/// The field a mistyped `name` most likely meant, if one is near: the
/// field that is `name` with a unit suffix (`margin` for `margin_mm`), else
/// the closest within a quarter of its letters' edits (`band_widht` for
/// `band_width`). Words under four letters are matched by suffix only.
pub fn nearest<'a>(name: &str, fields: &[&'a str]) -> Option<&'a str> {
    let suffixed = fields.iter().copied().find(|f| {
        !name.is_empty()
            && f.strip_prefix(name)
                .is_some_and(|rest| rest.starts_with('_'))
    });
    if suffixed.is_some() {
        return suffixed;
    }
    let most = name.chars().count() / 4;
    fields
        .iter()
        .map(|f| (edit_distance(name, f), *f))
        .filter(|&(d, _)| d > 0 && d <= most)
        .min()
        .map(|(_, f)| f)
}

/// The Levenshtein distance of two words, in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// The largest char boundary of `text` at or before `at`.
fn floor_char_boundary(text: &str, at: usize) -> usize {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use proptest::prelude::*;

    #[test]
    fn an_unknown_field_names_the_nearest_or_lists_the_fields() {
        let serde =
            "unknown field `vmax_deg_min`, expected one of `name`, `v_max_deg_min`, `min_deg`";
        assert_eq!(
            syntax_message(serde, "", 0),
            "unknown field `vmax_deg_min`; did you mean `v_max_deg_min`?"
        );
        let serde = "unknown field `linear`, expected one of `block`, `rapid`, `footer`";
        assert_eq!(
            syntax_message(serde, "", 0),
            "unknown field `linear`; allowed: block, rapid, footer"
        );
        let serde = "unknown field `x`, expected `a` or `b`";
        assert_eq!(syntax_message(serde, "", 0), serde);
    }

    #[test]
    fn the_nearest_field_is_the_suffixed_or_the_closest() {
        let fields = ["band_width", "winding_angle_deg", "margin_mm", "on", "mu"];
        assert_eq!(nearest("band_widht", &fields), Some("band_width"));
        assert_eq!(nearest("winding_angle", &fields), Some("winding_angle_deg"));
        assert_eq!(nearest("margin", &fields), Some("margin_mm"));
        assert_eq!(nearest("of", &fields), None);
        assert_eq!(nearest("thickness", &fields), None);
        assert_eq!(nearest("", &fields), None);
    }

    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("band_widht", "band_width"), 2);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("same", "same"), 0);
    }

    /// Rust's own escape of a character, as the quote writes it (controls
    /// and invisible characters; printable text unescaped).
    fn std_escape(c: char) -> String {
        match c {
            '\0' | '\t' | '\n' | '\r' => c.escape_debug().to_string(),
            c if is_hidden(c) => format!("\\u{{{:x}}}", u32::from(c)),
            c => c.to_string(),
        }
    }

    #[test]
    fn short_text_is_quoted_whole() {
        assert_eq!(quote("G1 X10 Y20").to_string(), "G1 X10 Y20");
        assert_eq!(quote("").to_string(), "");
        assert_eq!(quote("Ø 12 µm, 45°").to_string(), "Ø 12 µm, 45°");
    }

    #[test]
    fn controls_are_escaped_like_escape_debug() {
        assert_eq!(quote("a\u{1b}[31mb").to_string(), "a\\u{1b}[31mb");
        assert_eq!(quote("x\0y").to_string(), "x\\0y");
        assert_eq!(quote("a\tb\r\n").to_string(), "a\\tb\\r\\n");
        assert_eq!(quote("\u{7f}\u{85}").to_string(), "\\u{7f}\\u{85}");
        for c in [
            '\0', '\t', '\n', '\r', '\u{1}', '\u{1b}', '\u{7f}', '\u{9b}',
        ] {
            let escaped = c.escape_debug().to_string();
            assert_eq!(quote(c.encode_utf8(&mut [0; 4])).to_string(), escaped);
        }
    }

    #[test]
    fn invisible_characters_are_escaped() {
        assert_eq!(quote("a\u{202e}b").to_string(), "a\\u{202e}b");
        assert_eq!(quote("\u{feff}X").to_string(), "\\u{feff}X");
        assert_eq!(quote("\u{200b}").to_string(), "\\u{200b}");
    }

    #[test]
    fn backslashes_and_quotes_stay() {
        assert_eq!(quote(r#"C:\jobs\"a""#).to_string(), r#"C:\jobs\"a""#);
    }

    #[test]
    fn text_of_exactly_the_cap_is_not_cut() {
        let text = "x".repeat(QUOTE_MAX_CHARS);
        assert_eq!(quote(&text).to_string(), text);
        let longer = "x".repeat(QUOTE_MAX_CHARS + 1);
        let q = quote(&longer).to_string();
        assert_eq!(q.chars().count(), QUOTE_MAX_CHARS);
        assert_eq!(q, format!("{}…", "x".repeat(QUOTE_MAX_CHARS - 1)));
    }

    #[test]
    fn a_cut_never_splits_an_escape_or_a_character() {
        let text = format!("{}\u{1b}\u{1b}", "é".repeat(QUOTE_MAX_CHARS - 4));
        let q = quote(&text).to_string();
        assert_eq!(q, format!("{}…", "é".repeat(QUOTE_MAX_CHARS - 4)));
        assert!(q.chars().count() <= QUOTE_MAX_CHARS);
    }

    #[test]
    fn a_ten_megabyte_line_gives_a_short_quote() {
        let line = format!("G1 X{}\u{1b}\0", "9".repeat(10 << 20));
        let q = excerpt(&line);
        assert_eq!(q.chars().count(), QUOTE_MAX_CHARS);
        assert!(q.starts_with("G1 X999") && q.ends_with('…'));
    }

    #[test]
    fn empty_parser_messages_say_what_was_expected() {
        let text = "[a]\nb = 1\nkey =\n";
        assert_eq!(syntax_message("", text, 15), "expected a value after `=`");
        assert_eq!(
            syntax_message("  ", "key =", 5),
            "expected a value after `=`"
        );
        assert_eq!(
            syntax_message("", "key = 1\0", 7),
            "NUL characters are not allowed"
        );
        assert_eq!(
            syntax_message("", "key = \u{1b}", 6),
            "control character `\\u{1b}` is not allowed"
        );
        assert_eq!(
            syntax_message("", "key = [1,", 9),
            "unexpected end of the text"
        );
        assert_eq!(syntax_message("", "key = }", 6), "unexpected `}`");
        assert_eq!(syntax_message("invalid\nkey", "x", 0), "invalid key");
        assert_eq!(
            syntax_message("expected newline", "a = 1\0\n", 6),
            "expected newline"
        );
        assert_eq!(
            syntax_message("expected newline", "a = 1\0\n", 5),
            "NUL characters are not allowed"
        );
    }

    proptest! {
        #[test]
        fn never_longer_than_the_cap_never_a_raw_control(text in any::<String>()) {
            let q = quote(&text).to_string();
            prop_assert!(q.chars().count() <= QUOTE_MAX_CHARS);
            prop_assert!(!q.chars().any(is_hidden));
            prop_assert!(!q.chars().any(char::is_control));
        }

        #[test]
        fn the_quote_is_the_escaped_text_or_its_prefix_and_a_cut(text in any::<String>()) {
            let full: String = text.chars().map(std_escape).collect();
            let q = quote(&text).to_string();
            if full.chars().count() <= QUOTE_MAX_CHARS {
                prop_assert_eq!(q, full);
            } else {
                let kept = q.strip_suffix('…').unwrap();
                prop_assert!(full.starts_with(kept));
                // Cut only where the next escape would not fit (`\u{10ffff}`
                // is the longest, 10 characters).
                prop_assert!(q.chars().count() > QUOTE_MAX_CHARS - 10);
            }
        }

        #[test]
        fn long_ascii_lines_are_cut_to_the_cap(text in "[ -~\\x00\\x1b]{81,400}") {
            let q = quote(&text).to_string();
            prop_assert!(q.ends_with('…'));
            prop_assert!(q.chars().count() <= QUOTE_MAX_CHARS);
            prop_assert!(q.chars().count() >= QUOTE_MAX_CHARS - 6);
        }
    }
}
