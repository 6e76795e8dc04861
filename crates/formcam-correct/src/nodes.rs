//! A tool path given as a plain CSV of nodes `x,y,z`.

use crate::{CorrectError, ProgramError};

/// A node table: its lines as they are and the nodes of its data rows.
#[derive(Debug, Clone)]
pub struct NodeTable {
    lines: Vec<String>,
    /// `(line index, node)` of the data rows.
    rows: Vec<usize>,
    /// The nodes, mm.
    pub nodes: Vec<[f64; 3]>,
    decimals: usize,
    sep: char,
}

impl NodeTable {
    /// Reads `x,y,z` rows (`,` or `;`; an optional header of the names `x, y,
    /// z`; `#` comment lines and blank lines kept). Extra columns are kept as
    /// they are.
    pub fn from_csv(text: &str) -> Result<Self, CorrectError> {
        let mut t = Self {
            lines: text.lines().map(str::to_string).collect(),
            rows: Vec::new(),
            nodes: Vec::new(),
            decimals: 0,
            sep: if text.contains(';') && !text.contains(',') {
                ';'
            } else {
                ','
            },
        };
        for (k, l) in t.lines.iter().enumerate() {
            let s = l.trim();
            if s.is_empty() || s.starts_with('#') {
                continue;
            }
            let f: Vec<&str> = s.split(t.sep).map(str::trim).collect();
            if t.rows.is_empty() && t.nodes.is_empty() && f[0].eq_ignore_ascii_case("x") {
                continue;
            }
            if f.len() < 3 {
                return Err(ProgramError::ShortRow {
                    line: k + 1,
                    row: s.into(),
                }
                .into());
            }
            let mut p = [0.0; 3];
            for c in 0..3 {
                let v: f64 = f[c].parse().map_err(|_| ProgramError::NotANumber {
                    line: k + 1,
                    row: s.into(),
                    text: f[c].into(),
                })?;
                if !v.is_finite() {
                    return Err(ProgramError::NotFinite {
                        line: k + 1,
                        row: s.into(),
                        text: f[c].into(),
                    }
                    .into());
                }
                p[c] = v;
                if let Some(d) = f[c].find('.') {
                    t.decimals = t.decimals.max(f[c].len() - d - 1);
                }
            }
            t.rows.push(k);
            t.nodes.push(p);
        }
        if t.nodes.is_empty() {
            return Err(ProgramError::NoNodes.into());
        }
        if t.decimals == 0 {
            t.decimals = 4;
        }
        Ok(t)
    }

    /// The table with the nodes at `positions`, in the input's decimals.
    pub fn write(&self, positions: &[[f64; 3]]) -> String {
        let mut lines = self.lines.clone();
        let d = self.decimals;
        for (&row, p) in self.rows.iter().zip(positions) {
            let l = &lines[row];
            let rest: Vec<&str> = l.trim().split(self.sep).skip(3).collect();
            let mut s = format!(
                "{:.d$}{sep}{:.d$}{sep}{:.d$}",
                p[0],
                p[1],
                p[2],
                sep = self.sep
            );
            for r in rest {
                s.push(self.sep);
                s.push_str(r);
            }
            lines[row] = s;
        }
        let mut out = lines.join("\n");
        out.push('\n');
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_round_trips() {
        let text = "x,y,z\n# finishing\n0.000,1.000,2.500\n1.000,1.000,2.600\n";
        let t = NodeTable::from_csv(text).unwrap();
        assert_eq!(t.nodes.len(), 2);
        assert_eq!(t.write(&t.nodes), text);
        let e = NodeTable::from_csv("x,y,z\n1,2,nan\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2") && e.contains("not finite"), "{e}");
    }
}
