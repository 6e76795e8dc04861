//! The fields of a table as the Markdown table of the docs, and the docs'
//! marked sections replaced by it; the pieces any docs table is written
//! with ([`cell`], [`push_row`], [`replace_section`]), formcam-results'
//! column tables too.

use crate::describe::{Default, Field, JobSchema, Kind, Table};

/// The fields of `table` as a Markdown table: field, type, unit, allowed
/// values, default, meaning (a list of tables gets a row per sub-field).
pub fn markdown(table: &Table) -> String {
    let mut out = String::from(
        "| field | type | unit | allowed | default | meaning |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    for f in table.fields {
        row(&mut out, f.name, f);
        if let Kind::Tables(sub) = f.kind {
            for s in sub {
                row(&mut out, &format!("{}[].{}", f.name, s.name), s);
            }
        }
    }
    out
}

fn row(out: &mut String, name: &str, f: &Field) {
    let allowed = {
        let words = f
            .kind
            .words()
            .iter()
            .map(|w| format!("`{w}`"))
            .collect::<Vec<_>>()
            .join(", ");
        match (f.range, words.is_empty()) {
            (Some(r), true) => r.to_string(),
            (Some(r), false) => format!("{r}, or {words}"),
            (None, false) => words,
            (None, true) => String::new(),
        }
    };
    let default = match f.default {
        Default::Required => "required".to_string(),
        Default::RequiredWhen(c) => format!("required {c}"),
        Default::Value(v) => format!("`{v}`"),
        Default::Described(d) => d.to_string(),
        Default::None => "none".into(),
    };
    let cells = [
        format!("`{name}`"),
        f.kind.describe(),
        f.unit.symbol().to_string(),
        cell(&allowed),
        cell(&default),
        cell(f.help),
    ];
    push_row(out, &cells);
}

/// Text made safe for a table cell: `|` escaped, lines joined.
pub fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// A table row of `cells` (already made safe, [`cell`]) added to `out`
/// with its newline: `| a | b |`, an empty cell as ` |`.
pub fn push_row(out: &mut String, cells: &[String]) {
    out.push('|');
    for c in cells {
        if c.is_empty() {
            out.push_str(" |");
        } else {
            out.push_str(&format!(" {c} |"));
        }
    }
    out.push('\n');
}

/// `page` with the text between the line `open` (a marker such as
/// `<!-- fields: winding.mandrel -->`, on a line of its own) and the next
/// `close` after it replaced by `body`; `None` when either is missing.
pub fn replace_section(page: &str, open: &str, close: &str, body: &str) -> Option<String> {
    let open = format!("{open}\n");
    let from = page.find(&open)? + open.len();
    let to = from + page[from..].find(close)?;
    let mut page = page.to_string();
    page.replace_range(from..to, body);
    Some(page)
}

/// A docs page whose marked section is missing or unclosed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("no section `<!-- fields: {marker} -->` ... `<!-- /fields -->` in the page")]
pub struct MarkedError {
    /// The marker's name (`winding.mandrel`).
    pub marker: String,
}

/// `page` with the section of every table of `schema` (between
/// `<!-- fields: NAME.TABLE -->` and `<!-- /fields -->`) replaced by the
/// table's [`markdown`]. Every table must have its section.
pub fn replace_marked(page: &str, schema: &JobSchema) -> Result<String, MarkedError> {
    let mut page = page.to_string();
    for t in schema.tables {
        let marker = format!("{}.{}", schema.name, t.name);
        let open = format!("<!-- fields: {marker} -->");
        page = replace_section(&page, &open, "<!-- /fields -->", &markdown(t))
            .ok_or(MarkedError { marker })?;
    }
    Ok(page)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::describe::{Range, Repeat, Unit, Value};

    const FIELDS: &[Field] = &[
        Field {
            name: "radius",
            kind: Kind::Number,
            unit: Unit::Mm,
            range: Some(Range::above(0.0)),
            default: Default::Required,
            help: "the radius | not the diameter",
        },
        Field {
            name: "mode",
            kind: Kind::Word(&["a", "b"]),
            unit: Unit::None,
            range: None,
            default: Default::Value(Value::Text("a")),
            help: "how",
        },
    ];
    const SCHEMA: JobSchema = JobSchema {
        name: "demo",
        help: "a demo",
        tables: &[Table {
            name: "t",
            repeat: Repeat::Single,
            required: true,
            help: "a table",
            fields: FIELDS,
        }],
    };

    #[test]
    fn a_table_writes_a_row_per_field_with_pipes_escaped() {
        let md = markdown(&SCHEMA.tables[0]);
        let rows: Vec<&str> = md.lines().collect();
        assert_eq!(rows.len(), 4, "{md}");
        assert_eq!(
            rows[2],
            "| `radius` | number | mm | > 0 | required | the radius \\| not the diameter |"
        );
        assert_eq!(rows[3], "| `mode` | word | | `a`, `b` | `a` | how |");
    }

    #[test]
    fn marked_sections_are_replaced_and_missing_ones_named() {
        let page = "# T\n<!-- fields: demo.t -->\nold\n<!-- /fields -->\nafter\n";
        let new = replace_marked(page, &SCHEMA).unwrap_or_default();
        assert_eq!(
            new,
            format!(
                "# T\n<!-- fields: demo.t -->\n{}<!-- /fields -->\nafter\n",
                markdown(&SCHEMA.tables[0])
            )
        );
        assert_eq!(replace_marked(&new, &SCHEMA).as_deref(), Ok(new.as_str()));
        assert_eq!(
            replace_marked("# T\n", &SCHEMA),
            Err(MarkedError {
                marker: "demo.t".into()
            })
        );
    }
}
