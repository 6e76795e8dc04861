//! A job's text checked against its description before the reader's serde
//! structs see it: the first unknown table or key, wrong type, value out of
//! range, word not in the list or missing field, by `table.field` and
//! `line:column`.

pub(crate) use formcam_files::line_col;
use std::ops::Range as Span;

use toml_edit::{ImDocument, Item, Key, Value as Toml};

use crate::describe::{Condition, Default, Field, JobSchema, Kind, Repeat, Table};

/// Why a job does not match its description. Each message names the field
/// (`table.field`, `layer[2].kind`), where it is (`line:column`) and what
/// is allowed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SchemaError {
    /// The text is not TOML.
    #[error("{line}:{column}: {message}")]
    Syntax {
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// What the parser said.
        message: String,
    },
    /// A table the job type does not have.
    #[error("[{table}] at {line}:{column}: unknown table; allowed: {allowed}")]
    UnknownTable {
        /// The table's name.
        table: String,
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// The tables allowed.
        allowed: String,
    },
    /// A key its table does not have.
    #[error("{field} at {line}:{column}: unknown field `{key}`; {allowed}")]
    UnknownKey {
        /// The dotted field.
        field: String,
        /// The key as written.
        key: String,
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// The nearest key (`did you mean `band_width`?`), or the keys
        /// allowed (`allowed: mu, band_width`).
        allowed: String,
    },
    /// A value of the wrong type.
    #[error("{field} at {line}:{column}: expected {expected}, found {found}")]
    WrongType {
        /// The dotted field.
        field: String,
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// The type allowed (with its unit).
        expected: String,
        /// The type given.
        found: &'static str,
    },
    /// A number outside its range.
    #[error("{field} = {value} at {line}:{column}: out of range; allowed {allowed}")]
    OutOfRange {
        /// The dotted field.
        field: String,
        /// The value as written.
        value: String,
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// The range with its unit.
        allowed: String,
    },
    /// A word not in the field's list.
    #[error("{field} = \"{value}\" at {line}:{column}: not allowed; allowed: {allowed}")]
    NotAWord {
        /// The dotted field.
        field: String,
        /// The word given.
        value: String,
        /// Line (1-based).
        line: usize,
        /// Column (1-based).
        column: usize,
        /// The words allowed.
        allowed: String,
    },
    /// A required field left out.
    #[error("{field}: missing in the table at {line}:{column} ({when}): {what}")]
    Missing {
        /// The dotted field.
        field: String,
        /// Line (1-based) of the table.
        line: usize,
        /// Column (1-based) of the table.
        column: usize,
        /// `required` or `required when kind = cylinder or vessel`.
        when: String,
        /// The field's type, unit and range.
        what: String,
    },
    /// A required table left out.
    #[error("{table}: missing table")]
    MissingTable {
        /// The table as users write it (`[mandrel]`).
        table: String,
    },
}

impl SchemaError {
    /// Whether the text is not TOML at all.
    pub fn is_syntax(&self) -> bool {
        matches!(self, SchemaError::Syntax { .. })
    }

    /// The order in which kinds of error are reported.
    fn rank(&self) -> u8 {
        match self {
            SchemaError::Syntax { .. } => 0,
            SchemaError::UnknownTable { .. } | SchemaError::UnknownKey { .. } => 1,
            SchemaError::WrongType { .. } => 2,
            SchemaError::OutOfRange { .. } => 3,
            SchemaError::NotAWord { .. } => 4,
            SchemaError::Missing { .. } => 5,
            SchemaError::MissingTable { .. } => 6,
        }
    }
}

/// Checks `text` against `schema`: `Ok` when every table and key is
/// described, every value has its type, lies in its range or list, and no
/// required field or table is left out. Else the first problem: by kind
/// (unknown names, types, ranges, words, missing fields, missing tables),
/// then by place in the text.
pub fn validate(schema: &JobSchema, text: &str) -> Result<(), SchemaError> {
    let doc = ImDocument::parse(text).map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        let (line, column) = line_col(text, at);
        SchemaError::Syntax {
            line,
            column,
            message: formcam_files::syntax_message(e.message(), text, at),
        }
    })?;
    let mut check = Checker {
        text,
        found: Vec::new(),
    };
    check.document(schema, doc.as_table());
    match check
        .found
        .into_iter()
        .min_by_key(|(e, at)| (e.rank(), *at))
    {
        Some((e, _)) => Err(e),
        None => Ok(()),
    }
}

/// The entries of a table or an inline table, with their keys' places.
type Entries<'a> = Vec<(&'a Key, &'a Item)>;

fn entries_of_table(t: &toml_edit::Table) -> Entries<'_> {
    t.iter().filter_map(|(k, _)| t.get_key_value(k)).collect()
}

fn entries_of_inline(t: &toml_edit::InlineTable) -> Entries<'_> {
    t.iter().filter_map(|(k, _)| t.get_key_value(k)).collect()
}

/// The problems found so far, each with its byte offset.
struct Checker<'t> {
    text: &'t str,
    found: Vec<(SchemaError, usize)>,
}

fn type_name(item: &Item) -> &'static str {
    match item {
        Item::None => "nothing",
        Item::Table(_) | Item::Value(Toml::InlineTable(_)) => "a table",
        Item::ArrayOfTables(_) => "an array of tables",
        Item::Value(v) => match v {
            Toml::String(_) => "a string",
            Toml::Integer(_) => "an integer",
            Toml::Float(_) => "a float",
            Toml::Boolean(_) => "a boolean",
            Toml::Datetime(_) => "a date",
            Toml::Array(_) => "an array",
            Toml::InlineTable(_) => "a table",
        },
    }
}

fn start(span: Option<Span<usize>>) -> Option<usize> {
    span.map(|s| s.start)
}

fn quoted(words: &[&str]) -> String {
    words.join(", ")
}

impl Checker<'_> {
    /// An array of inline tables (`[{ ... }, { ... }]`), each against
    /// `fields`, named `prefix[1]`, `prefix[2]`, ...
    fn inline_tables(&mut self, prefix: &str, fields: &[Field], a: &toml_edit::Array, at: usize) {
        for (i, v) in a.iter().enumerate() {
            let path = format!("{prefix}[{}]", i + 1);
            let at = start(v.span()).unwrap_or(at);
            match v {
                Toml::InlineTable(t) => self.fields(&path, fields, &entries_of_inline(t), at),
                other => {
                    let found = type_name(&Item::Value(other.clone()));
                    self.push(at, |line, column| SchemaError::WrongType {
                        field: path,
                        line,
                        column,
                        expected: "a table".into(),
                        found,
                    });
                }
            }
        }
    }

    fn push(&mut self, at: usize, make: impl FnOnce(usize, usize) -> SchemaError) {
        let (line, column) = line_col(self.text, at);
        self.found.push((make(line, column), at));
    }

    fn document(&mut self, schema: &JobSchema, root: &toml_edit::Table) {
        let allowed = schema
            .tables
            .iter()
            .map(Table::header)
            .collect::<Vec<_>>()
            .join(", ");
        for (key, item) in entries_of_table(root) {
            let at = start(key.span()).unwrap_or(0);
            let Some(table) = schema.table(key.get()) else {
                let name = key.get().to_string();
                let allowed = allowed.clone();
                self.push(at, |line, column| SchemaError::UnknownTable {
                    table: name,
                    line,
                    column,
                    allowed,
                });
                continue;
            };
            self.table_item(table, item, at);
        }
        for t in schema.tables.iter().filter(|t| t.required) {
            if !root.contains_key(t.name) {
                self.found.push((
                    SchemaError::MissingTable { table: t.header() },
                    self.text.len(),
                ));
            }
        }
    }

    /// A described table as the text gives it: a table, an inline table or
    /// (arrays) a list of them.
    fn table_item(&mut self, table: &Table, item: &Item, at: usize) {
        match (table.repeat, item) {
            (Repeat::Single, Item::Table(t)) => {
                let at = start(t.span()).unwrap_or(at);
                self.fields(table.name, table.fields, &entries_of_table(t), at);
            }
            (Repeat::Single, Item::Value(Toml::InlineTable(t))) => {
                self.fields(table.name, table.fields, &entries_of_inline(t), at);
            }
            (Repeat::Array, Item::ArrayOfTables(a)) => {
                for (i, t) in a.iter().enumerate() {
                    let at = start(t.span()).unwrap_or(at);
                    let path = format!("{}[{}]", table.name, i + 1);
                    self.fields(&path, table.fields, &entries_of_table(t), at);
                }
            }
            (Repeat::Array, Item::Value(Toml::Array(a))) => {
                self.inline_tables(table.name, table.fields, a, at)
            }
            (repeat, other) => {
                let expected = match repeat {
                    Repeat::Single => format!("a table {}", table.header()),
                    Repeat::Array => format!("tables {}", table.header()),
                };
                let found = type_name(other);
                let field = table.name.to_string();
                self.push(at, |line, column| SchemaError::WrongType {
                    field,
                    line,
                    column,
                    expected,
                    found,
                });
            }
        }
    }

    /// The entries of one table (`path` names it in messages) against its
    /// fields; `at` is where the table starts.
    fn fields(&mut self, path: &str, fields: &[Field], entries: &Entries<'_>, at: usize) {
        for (key, item) in entries {
            let key_at = start(key.span()).unwrap_or(at);
            let dotted = format!("{path}.{}", key.get());
            match fields.iter().find(|f| f.name == key.get()) {
                None => {
                    let names: Vec<&str> = fields.iter().map(|f| f.name).collect();
                    let allowed = match formcam_files::nearest(key.get(), &names) {
                        Some(near) => format!("did you mean `{near}`?"),
                        None => format!("allowed: {}", names.join(", ")),
                    };
                    let key = key.get().to_string();
                    self.push(key_at, |line, column| SchemaError::UnknownKey {
                        field: dotted,
                        key,
                        line,
                        column,
                        allowed,
                    });
                }
                Some(f) => self.value(&dotted, f, item, key_at),
            }
        }
        let given = |name: &str| entries.iter().find(|(k, _)| k.get() == name);
        for f in fields {
            if given(f.name).is_some() {
                continue;
            }
            let when = match f.default {
                Default::Required => Some("required".to_string()),
                Default::RequiredWhen(c) => {
                    let holds = match c {
                        Condition::Is { field, words } => given(field)
                            .is_some_and(|(_, v)| v.as_str().is_some_and(|s| words.contains(&s))),
                        Condition::Not { field, words } => !given(field)
                            .is_some_and(|(_, v)| v.as_str().is_some_and(|s| words.contains(&s))),
                        Condition::Absent { field } => given(field).is_none(),
                    };
                    holds.then(|| format!("required {c}"))
                }
                _ => None,
            };
            if let Some(when) = when {
                let field = format!("{path}.{}", f.name);
                let what = expected(f);
                self.push(at, |line, column| SchemaError::Missing {
                    field,
                    line,
                    column,
                    when,
                    what,
                });
            }
        }
    }

    /// One value against its field.
    fn value(&mut self, dotted: &str, f: &Field, item: &Item, key_at: usize) {
        let at = item
            .as_value()
            .and_then(|v| start(v.span()))
            .unwrap_or(key_at);
        let wrong = |c: &mut Self| {
            let found = type_name(item);
            let field = dotted.to_string();
            let expected = expected(f);
            c.push(at, |line, column| SchemaError::WrongType {
                field,
                line,
                column,
                expected,
                found,
            });
        };
        match (f.kind, item) {
            (Kind::Number | Kind::NumberOrWord(_), Item::Value(Toml::Float(v))) => {
                self.number(dotted, f, *v.value(), v.to_string().trim(), at)
            }
            (
                Kind::Number | Kind::NumberOrWord(_) | Kind::Integer,
                Item::Value(Toml::Integer(v)),
            ) => self.number(dotted, f, *v.value() as f64, v.to_string().trim(), at),
            (Kind::Boolean, Item::Value(Toml::Boolean(_)))
            | (Kind::Text | Kind::File, Item::Value(Toml::String(_))) => {}
            (Kind::Word(words) | Kind::NumberOrWord(words), Item::Value(Toml::String(s))) => {
                self.word(dotted, words, s.value(), at)
            }
            (Kind::Name(words), Item::Value(Toml::String(s))) => {
                let lower = s.value().to_ascii_lowercase();
                if !words.contains(&lower.as_str()) {
                    self.word(dotted, words, s.value(), at)
                }
            }
            (Kind::Words(words), Item::Value(Toml::Array(a))) => {
                for (i, v) in a.iter().enumerate() {
                    let path = format!("{dotted}[{}]", i + 1);
                    let at = start(v.span()).unwrap_or(at);
                    match v.as_str() {
                        Some(s) => self.word(&path, words, s, at),
                        None => {
                            let found = type_name(&Item::Value(v.clone()));
                            self.push(at, |line, column| SchemaError::WrongType {
                                field: path,
                                line,
                                column,
                                expected: format!("one of {}", quoted(words)),
                                found,
                            });
                        }
                    }
                }
            }
            (Kind::Integers, Item::Value(Toml::Array(a))) => {
                for (i, v) in a.iter().enumerate() {
                    let path = format!("{dotted}[{}]", i + 1);
                    let at = start(v.span()).unwrap_or(at);
                    match v {
                        Toml::Integer(n) => {
                            self.number(&path, f, *n.value() as f64, n.to_string().trim(), at)
                        }
                        other => {
                            let found = type_name(&Item::Value(other.clone()));
                            let expected = format!("an integer {}", allowed_numbers(f));
                            self.push(at, |line, column| SchemaError::WrongType {
                                field: path,
                                line,
                                column,
                                expected,
                                found,
                            });
                        }
                    }
                }
            }
            (Kind::Tables(sub), Item::Value(Toml::Array(a))) => {
                self.inline_tables(dotted, sub, a, at)
            }
            (Kind::Tables(sub), Item::ArrayOfTables(a)) => {
                for (i, t) in a.iter().enumerate() {
                    let path = format!("{dotted}[{}]", i + 1);
                    let at = start(t.span()).unwrap_or(at);
                    self.fields(&path, sub, &entries_of_table(t), at);
                }
            }
            _ => wrong(self),
        }
    }

    fn number(&mut self, dotted: &str, f: &Field, v: f64, written: &str, at: usize) {
        let ok = match f.range {
            Some(r) => r.contains(v),
            None => v.is_finite(),
        };
        if !ok {
            let field = dotted.to_string();
            let value = written.to_string();
            let allowed = allowed_numbers(f);
            self.push(at, |line, column| SchemaError::OutOfRange {
                field,
                value,
                line,
                column,
                allowed,
            });
        }
    }

    fn word(&mut self, dotted: &str, words: &[&str], s: &str, at: usize) {
        if !words.contains(&s) {
            let field = dotted.to_string();
            let value = s.to_string();
            let allowed = quoted(words);
            self.push(at, |line, column| SchemaError::NotAWord {
                field,
                value,
                line,
                column,
                allowed,
            });
        }
    }
}

/// The numbers a field allows, with its unit: `(0, 90) deg`, `a finite
/// number mm`.
fn allowed_numbers(f: &Field) -> String {
    let unit = f.unit.symbol();
    let range = match f.range {
        Some(r) => r.to_string(),
        None => "a finite number".into(),
    };
    let words = f.kind.words();
    let mut s = if unit.is_empty() {
        range
    } else {
        format!("{range} {unit}")
    };
    if !words.is_empty() {
        s.push_str(&format!(", or one of {}", quoted(words)));
    }
    s
}

/// What a field takes, for messages: `a number > 0 mm`, `one of cylinder,
/// cone`.
fn expected(f: &Field) -> String {
    match f.kind {
        Kind::Number | Kind::Integer => expected_number(an(f.kind), f),
        Kind::NumberOrWord(_) => expected_number("a number", f),
        Kind::Word(words) => format!("one of {}", quoted(words)),
        Kind::Name(words) => format!("one of {} (any case)", quoted(words)),
        Kind::Words(words) => format!("a list of words from {}", quoted(words)),
        Kind::Integers => format!("a list of integers {}", allowed_numbers(f)),
        Kind::Boolean => "true or false".into(),
        Kind::Text => "text".into(),
        Kind::File => "a file name (text)".into(),
        Kind::Tables(_) => format!("a {}", f.kind.describe()),
    }
}

/// `a number > 0 mm`; without a range `a finite number deg`, `an integer`.
fn expected_number(noun: &str, f: &Field) -> String {
    let allowed = allowed_numbers(f);
    match f.range {
        Some(_) => format!("{noun} {allowed}"),
        None if noun == "a number" => allowed,
        None => allowed.replacen("a finite number", noun, 1),
    }
}

fn an(kind: Kind) -> &'static str {
    match kind {
        Kind::Integer => "an integer",
        _ => "a number",
    }
}
