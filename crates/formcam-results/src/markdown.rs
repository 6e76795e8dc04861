//! The columns of a table as the Markdown table of the docs, and the docs'
//! marked sections replaced by it.

use formcam_schema::markdown::{cell, push_row, replace_section};

use crate::table::{Occurs, Table};

/// The columns of `table` as a Markdown table: column, unit, meaning (a
/// column only in some files says so).
pub fn markdown(table: &Table) -> String {
    let mut out = String::from("| column | unit | meaning |\n| --- | --- | --- |\n");
    for c in table.columns {
        let help = match c.occurs {
            Occurs::Optional if !c.help.contains("only") && !c.help.contains("when") => {
                format!("optional: {}", c.help)
            }
            _ => c.help.to_string(),
        };
        push_row(
            &mut out,
            &[format!("`{}`", c.name), c.unit.to_string(), cell(&help)],
        );
    }
    out
}

/// A docs page whose marked section is missing or unclosed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("no section `<!-- columns: {marker} -->` ... `<!-- /columns -->` in the page")]
pub struct MarkedError {
    /// The marker's name (`winding.path`).
    pub marker: String,
}

/// `page` with the section of every table of `tables` (between
/// `<!-- columns: ID -->` and `<!-- /columns -->`, `ID` the table's
/// [`Table::id`]) replaced by the table's [`markdown`]. Every id must have
/// its section; tables sharing an id are written once, from the first.
pub fn replace_marked(page: &str, tables: &[Table]) -> Result<String, MarkedError> {
    let mut page = page.to_string();
    let mut done: Vec<&str> = Vec::new();
    for t in tables {
        if done.contains(&t.id) {
            continue;
        }
        done.push(t.id);
        let open = format!("<!-- columns: {} -->", t.id);
        page =
            replace_section(&page, &open, "<!-- /columns -->", &markdown(t)).ok_or_else(|| {
                MarkedError {
                    marker: t.id.to_string(),
                }
            })?;
    }
    Ok(page)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Column;

    const T: Table = Table {
        id: "x.t",
        file: "t.csv",
        columns: &[
            Column::new("a", "mm", "a | b"),
            Column::optional("n", "", "the normal"),
        ],
    };

    #[test]
    fn a_marked_section_is_replaced_and_a_missing_one_named() -> Result<(), MarkedError> {
        let page = "intro\n<!-- columns: x.t -->\nold\n<!-- /columns -->\nend\n";
        let new = replace_marked(page, &[T])?;
        assert_eq!(
            new,
            "intro\n<!-- columns: x.t -->\n| column | unit | meaning |\n| --- | --- | --- |\n\
             | `a` | mm | a \\| b |\n| `n` | | optional: the normal |\n<!-- /columns -->\nend\n"
        );
        assert_eq!(
            replace_marked("nothing", &[T]),
            Err(MarkedError {
                marker: "x.t".into()
            })
        );
        Ok(())
    }
}
