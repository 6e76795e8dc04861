//! A CSV result file described: its name and its columns.

/// When a column is in its file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Occurs {
    /// In every file of its kind.
    Always,
    /// Only in some files (its help says when).
    Optional,
    /// Once per name the writer gives (an axis, a key point): the column's
    /// name is a placeholder such as `<axis>`.
    Each,
}

/// One column of a CSV result file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    /// The header's name (`alpha_deg`), or a placeholder (`<axis>`) for
    /// [`Occurs::Each`].
    pub name: &'static str,
    /// The unit (`mm`, `rad`, `s`), empty for a plain number or a word.
    pub unit: &'static str,
    /// What the column holds, one line.
    pub help: &'static str,
    /// When the column is in the file.
    pub occurs: Occurs,
}

impl Column {
    /// A column in every file.
    pub const fn new(name: &'static str, unit: &'static str, help: &'static str) -> Self {
        Self {
            name,
            unit,
            help,
            occurs: Occurs::Always,
        }
    }

    /// A column only in some files.
    pub const fn optional(name: &'static str, unit: &'static str, help: &'static str) -> Self {
        Self {
            name,
            unit,
            help,
            occurs: Occurs::Optional,
        }
    }

    /// A column per name the writer gives; `name` is the placeholder.
    pub const fn each(name: &'static str, unit: &'static str, help: &'static str) -> Self {
        Self {
            name,
            unit,
            help,
            occurs: Occurs::Each,
        }
    }
}

/// A column stands for its header's name where a reader asks for a
/// column by name (`table.numbers(winding::path::Z)`).
impl AsRef<str> for Column {
    fn as_ref(&self) -> &str {
        self.name
    }
}

/// A CSV result file: its name and its columns in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Table {
    /// The docs' marker (`winding.path`); tables with the same columns
    /// share one.
    pub id: &'static str,
    /// The file's name in the result folder (`path.csv`).
    pub file: &'static str,
    /// The columns in the order written.
    pub columns: &'static [Column],
}

impl Table {
    /// The header line (with its newline) of a file with only the columns
    /// that are always there.
    pub fn header(&self) -> String {
        self.header_with(&[], false)
    }

    /// The header line (with its newline): each [`Occurs::Each`] column as
    /// the names in `each`, the [`Occurs::Optional`] ones when `optional`.
    pub fn header_with(&self, each: &[&str], optional: bool) -> String {
        let mut names: Vec<&str> = Vec::with_capacity(self.columns.len() + each.len());
        for c in self.columns {
            match c.occurs {
                Occurs::Always => names.push(c.name),
                Occurs::Optional if optional => names.push(c.name),
                Occurs::Optional => {}
                Occurs::Each => names.extend_from_slice(each),
            }
        }
        let mut line = names.join(",");
        line.push('\n');
        line
    }

    /// The column named `name` (placeholders included).
    pub fn column(&self, name: &str) -> Option<&'static Column> {
        self.columns.iter().find(|c| c.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Table = Table {
        id: "t",
        file: "t.csv",
        columns: &[
            Column::new("a", "mm", "a"),
            Column::each("<axis>", "", "each axis"),
            Column::optional("b", "", "sometimes"),
        ],
    };

    #[test]
    fn a_header_names_each_and_optional_columns_as_asked() {
        assert_eq!(T.header(), "a\n");
        assert_eq!(T.header_with(&["X", "Y"], true), "a,X,Y,b\n");
        assert_eq!(T.column("b").map(|c| c.unit), Some(""));
        assert!(T.column("c").is_none());
        assert_eq!(T.columns[0].as_ref(), "a");
    }
}
