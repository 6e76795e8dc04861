//! The description of a job type: tables, fields, types, units, ranges,
//! defaults and help, as static data.

use std::fmt;

use serde::Serialize;

/// A job type: the tables its file may hold.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct JobSchema {
    /// The job type's name (`winding`, `dressing`, ...).
    pub name: &'static str,
    /// What a job of this type does.
    pub help: &'static str,
    /// Its tables, in the order the docs list them.
    pub tables: &'static [Table],
}

impl JobSchema {
    /// The table named `name`.
    pub fn table(&self, name: &str) -> Option<&'static Table> {
        self.tables.iter().find(|t| t.name == name)
    }
}

/// Whether a table is written once (`[mandrel]`) or as an array
/// (`[[layer]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Repeat {
    /// `[name]`.
    Single,
    /// `[[name]]`, one table per entry.
    Array,
}

/// A table of a job file.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Table {
    /// The table's name (`mandrel`).
    pub name: &'static str,
    /// Single or array.
    pub repeat: Repeat,
    /// Whether every job must hold it.
    pub required: bool,
    /// What the table describes.
    pub help: &'static str,
    /// Its fields, in the order the docs list them.
    pub fields: &'static [Field],
}

impl Table {
    /// The table as users write its header: `[mandrel]` or `[[layer]]`.
    pub fn header(&self) -> String {
        match self.repeat {
            Repeat::Single => format!("[{}]", self.name),
            Repeat::Array => format!("[[{}]]", self.name),
        }
    }

    /// The field named `name`.
    pub fn field(&self, name: &str) -> Option<&'static Field> {
        self.fields.iter().find(|f| f.name == name)
    }

    /// The names of its fields, sorted (to compare with [`reader_keys`]).
    pub fn field_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.fields.iter().map(|f| f.name.to_string()).collect();
        names.sort();
        names
    }
}

/// The keys a serde-read table `T` takes, sorted, as its reader lists them
/// when it refuses an unknown key: what tests compare with a description's
/// [`Table::field_names`] so that a field added to one is added to the other.
/// Empty when `T` takes any key.
pub fn reader_keys<T: serde::de::DeserializeOwned>() -> Vec<String> {
    let message = toml::from_str::<T>("zz_probe = 1")
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    let list = message.split("expected").nth(1).unwrap_or_default();
    let mut keys: Vec<String> = list
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect();
    keys.sort();
    keys
}

/// A field of a table.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Field {
    /// The key users write.
    pub name: &'static str,
    /// Its type.
    pub kind: Kind,
    /// Its unit.
    pub unit: Unit,
    /// The values allowed (numbers and integers; `None`: any finite one for
    /// numbers, any for integers).
    pub range: Option<Range>,
    /// Its default, or whether it is required.
    pub default: Default,
    /// What it means.
    pub help: &'static str,
}

/// A field, written in a description's `const` tables.
pub const fn field(
    name: &'static str,
    kind: Kind,
    unit: Unit,
    range: Option<Range>,
    default: Default,
    help: &'static str,
) -> Field {
    Field {
        name,
        kind,
        unit,
        range,
        default,
        help,
    }
}

/// The type of a field.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(rename_all = "kebab-case", tag = "type", content = "of")]
pub enum Kind {
    /// A number (a TOML float or integer).
    Number,
    /// A whole number.
    Integer,
    /// `true` or `false`.
    Boolean,
    /// Free text.
    Text,
    /// A file's path, relative to the job's folder.
    File,
    /// One of a list of words.
    Word(&'static [&'static str]),
    /// One of a list of names, in any case (`dialect = "ISO"`).
    Name(&'static [&'static str]),
    /// A number or one of a list of words (`mu = 0.1` or `mu = "auto"`).
    NumberOrWord(&'static [&'static str]),
    /// A list of words, each from the list (`allow = ["slack"]`).
    Words(&'static [&'static str]),
    /// A list of whole numbers, each in the field's range
    /// (`section_study = [3, 5, 9]`).
    Integers,
    /// A list of tables with these fields (`mu_segments = [{ ... }]`).
    Tables(&'static [Field]),
}

impl Kind {
    /// How the kind is named in messages and the docs.
    pub fn describe(&self) -> String {
        match self {
            Kind::Number => "number".into(),
            Kind::Integer => "integer".into(),
            Kind::Boolean => "boolean".into(),
            Kind::Text => "text".into(),
            Kind::File => "file".into(),
            Kind::Word(_) => "word".into(),
            Kind::Name(_) => "word (any case)".into(),
            Kind::NumberOrWord(_) => "number or word".into(),
            Kind::Words(_) => "list of words".into(),
            Kind::Integers => "list of integers".into(),
            Kind::Tables(fields) => format!(
                "list of tables ({})",
                fields.iter().map(|f| f.name).collect::<Vec<_>>().join(", ")
            ),
        }
    }

    /// The words allowed, if the kind has a list.
    pub fn words(&self) -> &'static [&'static str] {
        match self {
            Kind::Word(w) | Kind::Name(w) | Kind::NumberOrWord(w) | Kind::Words(w) => w,
            _ => &[],
        }
    }
}

/// The unit of a field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Unit {
    /// No unit (counts, ratios, words, files).
    None,
    /// Millimetres.
    Mm,
    /// Degrees (fields whose names end `_deg`).
    Deg,
    /// Seconds.
    S,
    /// Millimetres per minute (feeds).
    MmPerMin,
    /// Square millimetres per minute (removal rates of a section).
    Mm2PerMin,
}

impl Unit {
    /// The symbol written after a value (empty for [`Unit::None`]).
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::None => "",
            Unit::Mm => "mm",
            Unit::Deg => "deg",
            Unit::S => "s",
            Unit::MmPerMin => "mm/min",
            Unit::Mm2PerMin => "mm²/min",
        }
    }
}

/// One end of a range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bound {
    /// The value.
    pub value: f64,
    /// Whether the value itself is allowed.
    pub closed: bool,
}

/// The values a number or integer may take; the ends open or closed, each
/// optional. Infinities and not-a-number are outside every range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Range {
    /// The lower end.
    pub min: Option<Bound>,
    /// The upper end.
    pub max: Option<Bound>,
}

impl Range {
    /// `> v`.
    pub const fn above(v: f64) -> Range {
        Range {
            min: Some(Bound {
                value: v,
                closed: false,
            }),
            max: None,
        }
    }

    /// `>= v`.
    pub const fn at_least(v: f64) -> Range {
        Range {
            min: Some(Bound {
                value: v,
                closed: true,
            }),
            max: None,
        }
    }

    /// `[a, b]`.
    pub const fn closed(a: f64, b: f64) -> Range {
        Range {
            min: Some(Bound {
                value: a,
                closed: true,
            }),
            max: Some(Bound {
                value: b,
                closed: true,
            }),
        }
    }

    /// `(a, b)`.
    pub const fn open(a: f64, b: f64) -> Range {
        Range {
            min: Some(Bound {
                value: a,
                closed: false,
            }),
            max: Some(Bound {
                value: b,
                closed: false,
            }),
        }
    }

    /// `[a, b)`.
    pub const fn closed_open(a: f64, b: f64) -> Range {
        Range {
            min: Some(Bound {
                value: a,
                closed: true,
            }),
            max: Some(Bound {
                value: b,
                closed: false,
            }),
        }
    }

    /// `(a, b]`.
    pub const fn open_closed(a: f64, b: f64) -> Range {
        Range {
            min: Some(Bound {
                value: a,
                closed: false,
            }),
            max: Some(Bound {
                value: b,
                closed: true,
            }),
        }
    }

    /// Whether `v` lies in the range (never for an infinite number or
    /// not-a-number).
    pub fn contains(&self, v: f64) -> bool {
        if !v.is_finite() {
            return false;
        }
        let lo = self
            .min
            .is_none_or(|b| if b.closed { v >= b.value } else { v > b.value });
        let hi = self
            .max
            .is_none_or(|b| if b.closed { v <= b.value } else { v < b.value });
        lo && hi
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.min, self.max) {
            (Some(a), Some(b)) => write!(
                f,
                "{}{}, {}{}",
                if a.closed { '[' } else { '(' },
                a.value,
                b.value,
                if b.closed { ']' } else { ')' }
            ),
            (Some(a), None) => write!(f, "{} {}", if a.closed { ">=" } else { ">" }, a.value),
            (None, Some(b)) => write!(f, "{} {}", if b.closed { "<=" } else { "<" }, b.value),
            (None, None) => f.write_str("any"),
        }
    }
}

/// A field's default.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(rename_all = "kebab-case", tag = "is", content = "value")]
pub enum Default {
    /// Every job must give it.
    Required,
    /// Required when the condition holds; else optional.
    RequiredWhen(Condition),
    /// This value when the field is left out.
    Value(Value),
    /// A default that depends on other fields, in words ("0 for vessels,
    /// 180 for tubes").
    Described(&'static str),
    /// Optional, nothing when left out.
    None,
}

/// When a field is required.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(rename_all = "kebab-case", tag = "when")]
pub enum Condition {
    /// Another field of the same table holds one of these words.
    Is {
        /// The other field.
        field: &'static str,
        /// Its values that make this one required.
        words: &'static [&'static str],
    },
    /// Another field of the same table does not hold one of these words
    /// (left out, it does not).
    Not {
        /// The other field.
        field: &'static str,
        /// Its values that make this one optional.
        words: &'static [&'static str],
    },
    /// Another field of the same table is left out.
    Absent {
        /// The other field.
        field: &'static str,
    },
}

impl fmt::Display for Condition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Condition::Is { field, words } => {
                write!(f, "when {field} = {}", words.join(" or "))
            }
            Condition::Not { field, words } => {
                write!(f, "unless {field} = {}", words.join(" or "))
            }
            Condition::Absent { field } => write!(f, "unless {field} is given"),
        }
    }
}

/// A default value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Value {
    /// A number.
    Number(f64),
    /// A whole number.
    Integer(i64),
    /// A boolean.
    Boolean(bool),
    /// A word or text.
    Text(&'static str),
    /// An empty list.
    EmptyList(EmptyList),
}

/// The empty list, serialised as `[]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmptyList;

impl Serialize for EmptyList {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_seq(Some(0))
            .and_then(serde::ser::SerializeSeq::end)
    }
}

impl Value {
    /// The value as TOML writes it (`0.05`, `2001`, `true`, `"pull-speed"`,
    /// `[]`).
    pub fn toml(&self) -> String {
        match self {
            Value::Number(v) => format!("{v:?}"),
            Value::Integer(v) => v.to_string(),
            Value::Boolean(v) => v.to_string(),
            Value::Text(v) => format!("\"{v}\""),
            Value::EmptyList(_) => "[]".into(),
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Number(v) => write!(f, "{v}"),
            Value::Integer(v) => write!(f, "{v}"),
            Value::Boolean(v) => write!(f, "{v}"),
            Value::Text(v) => f.write_str(v),
            Value::EmptyList(_) => f.write_str("none"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_keep_their_ends_and_refuse_nan() {
        let r = Range::open_closed(0.0, 2.0);
        assert!(!r.contains(0.0) && r.contains(1e-12) && r.contains(2.0) && !r.contains(2.0001));
        assert!(!r.contains(f64::NAN));
        assert!(Range::at_least(0.0).contains(0.0) && !Range::above(0.0).contains(0.0));
        assert!(!Range::above(0.0).contains(f64::INFINITY));
        assert_eq!(r.to_string(), "(0, 2]");
        assert_eq!(Range::closed_open(0.0, 1.0).to_string(), "[0, 1)");
        assert_eq!(Range::above(0.0).to_string(), "> 0");
        assert_eq!(Range::at_least(1.0).to_string(), ">= 1");
    }

    #[test]
    fn values_write_as_toml() {
        assert_eq!(Value::Number(0.05).toml(), "0.05");
        assert_eq!(Value::Number(20.0).toml(), "20.0");
        assert_eq!(Value::Integer(2001).toml(), "2001");
        assert_eq!(Value::Text("pull-speed").toml(), "\"pull-speed\"");
        assert_eq!(Value::EmptyList(EmptyList).toml(), "[]");
        for v in ["0.05", "20.0", "2001", "true", "\"pull-speed\"", "[]"] {
            assert!(format!("x = {v}").parse::<toml::Table>().is_ok(), "{v}");
        }
    }
}
