//! A CSV table of a result folder (a header row, then rows of cells), read
//! by column: the tables the plots, the dressing and the correction views
//! draw. A column is asked for as formcam-results describes it
//! (`table.numbers(winding::path::Z)`), or by the name a writer gave it (an
//! axis, a key point).

use std::path::{Path, PathBuf};

use crate::ViewError;

/// A CSV table: its header and rows, each cell as written.
#[derive(Debug, Clone)]
pub struct Table {
    path: PathBuf,
    names: Vec<String>,
    /// Each row's line (1-based) and cells.
    rows: Vec<(usize, Vec<String>)>,
}

impl Table {
    /// Reads the table `text` of the file `path` (named in errors); blank
    /// lines are passed over.
    ///
    /// # Errors
    ///
    /// [`ViewError::Table`] for a file without a header.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ViewError> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, header) = lines.next().ok_or_else(|| ViewError::Table {
            path: path.to_path_buf(),
            line: 1,
            problem: "empty file".into(),
        })?;
        let names = header.split(',').map(|s| s.trim().to_string()).collect();
        let rows = lines
            .map(|(i, l)| (i + 1, l.split(',').map(|s| s.trim().to_string()).collect()))
            .collect();
        Ok(Self {
            path: path.to_path_buf(),
            names,
            rows,
        })
    }

    /// Reads the table file `path`.
    ///
    /// # Errors
    ///
    /// [`ViewError::Read`] or [`ViewError::Table`].
    pub fn read(path: &Path) -> Result<Self, ViewError> {
        let text = formcam_files::read_text(path).map_err(|source| ViewError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::parse(&text, path)
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The column names, as the header gives them.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Whether the table has the column `name` (a [`formcam_results::Column`]
    /// or a name).
    pub fn has(&self, name: impl AsRef<str>) -> bool {
        let name = name.as_ref();
        self.names.iter().any(|n| n == name)
    }

    fn column(&self, name: &str) -> Result<usize, ViewError> {
        self.names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| ViewError::Table {
                path: self.path.clone(),
                line: 1,
                problem: format!("no column `{name}`"),
            })
    }

    /// The column `name`'s (a [`formcam_results::Column`] or a name) cells, as written (trimmed); a row without the
    /// cell gives `""`.
    ///
    /// # Errors
    ///
    /// [`ViewError::Table`] for a missing column.
    pub fn words(&self, name: impl AsRef<str>) -> Result<Vec<&str>, ViewError> {
        let c = self.column(name.as_ref())?;
        Ok(self
            .rows
            .iter()
            .map(|(_, cells)| cells.get(c).map_or("", String::as_str))
            .collect())
    }

    /// The column `name` (a [`formcam_results::Column`] or a name) as finite
    /// numbers.
    ///
    /// # Errors
    ///
    /// [`ViewError::Table`] naming the line and the column for a missing
    /// column or a cell that is no finite number.
    pub fn numbers(&self, name: impl AsRef<str>) -> Result<Vec<f64>, ViewError> {
        let name = name.as_ref();
        let c = self.column(name)?;
        self.rows
            .iter()
            .map(|(line, cells)| {
                cells
                    .get(c)
                    .and_then(|s| s.parse::<f64>().ok())
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| ViewError::Table {
                        path: self.path.clone(),
                        line: *line,
                        problem: format!("`{name}` is no finite number"),
                    })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    use super::*;

    #[test]
    fn columns_by_name_and_errors_naming_the_line() {
        let t = Table::parse("a, b\n1,2\n\n3, 4.5\n", Path::new("t")).unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t.numbers("b").unwrap(), vec![2.0, 4.5]);
        assert!(t.has("a") && !t.has("c"));
        assert_eq!(t.words("a").unwrap(), ["1", "3"]);
        let e = t.numbers("c").unwrap_err().to_string();
        assert_eq!(e, "t:1: no column `c`");
        let t = Table::parse("a\n1\nNaN\n", Path::new("t")).unwrap();
        let e = t.numbers("a").unwrap_err().to_string();
        assert_eq!(e, "t:3: `a` is no finite number");
        assert!(Table::parse("\n", Path::new("e")).is_err());
    }
}
