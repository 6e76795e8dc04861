//! The axes CSV of `formcam machine fk --axes`: a header naming the
//! machine's axes (and an optional `x` column, the position along the path),
//! then one row of axis values per line, in mm for linear axes and degrees
//! for rotary ones. Blank lines and lines starting with `#` are skipped, a
//! leading byte-order mark is ignored, and columns the machine does not have
//! are left alone (the `axes.csv` that `formcam wind axes` writes reads as
//! it is).

use formcam_files::excerpt;

use crate::{AxesCsvError, Machine};

/// One row of an axes CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct AxesRow {
    /// The `x` column, when the file has one.
    pub x: Option<f64>,
    /// The axis values in the machine's axis order (rad for rotary axes, mm).
    pub q: Vec<f64>,
}

/// Where the values of a row are: the `x` column and one column per axis.
struct Columns {
    /// The `x` column's index, when the header has one.
    x: Option<usize>,
    /// For each of the machine's axes, the index of its column.
    axes: Vec<usize>,
    /// How many cells the header has.
    count: usize,
    /// The header's names, comma-separated and quoted short, for messages.
    names: String,
}

/// The rows of an axes CSV's text for `machine`; errors name the line (1-based,
/// as the text counts them), the column and what it needs.
pub fn read_axes_csv(machine: &Machine, text: &str) -> Result<Vec<AxesRow>, AxesCsvError> {
    let mut lines = data_lines(text);
    let Some((header_line, header)) = lines.next() else {
        return Err(AxesCsvError::Empty {
            axes: axis_list(machine),
        });
    };
    let columns = locate_columns(machine, header_line, header)?;
    lines
        .map(|(line, row)| read_row(machine, &columns, line, row))
        .collect()
}

/// The lines that hold data, with their 1-based numbers: not blank, not a
/// `#` comment, a byte-order mark at the start removed.
fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    text.lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
}

/// The machine's axes, comma-separated, as errors list them.
fn axis_list(machine: &Machine) -> String {
    machine
        .axes
        .iter()
        .map(|a| excerpt(&a.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The columns of the header row (on line `line`) that hold `x` and each of
/// the machine's axes.
fn locate_columns(machine: &Machine, line: usize, header: &str) -> Result<Columns, AxesCsvError> {
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |name: &str| names.iter().position(|n| *n == name);
    let axes = machine
        .axes
        .iter()
        .map(|a| {
            find(&a.name).ok_or_else(|| AxesCsvError::NoColumn {
                line,
                axis: excerpt(&a.name),
                axes: axis_list(machine),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Columns {
        x: find("x"),
        axes,
        count: names.len(),
        names: excerpt(&names.join(", ")),
    })
}

/// One data row (on line `line`): `x` when the header has it, the axes in
/// the machine's order, rotary ones turned from degrees to radians.
fn read_row(
    machine: &Machine,
    columns: &Columns,
    line: usize,
    row: &str,
) -> Result<AxesRow, AxesCsvError> {
    let cells: Vec<&str> = row.split(',').map(str::trim).collect();
    let x = columns
        .x
        .map(|c| cell_value(&cells, columns, c, "x", line))
        .transpose()?;
    let q = machine
        .axes
        .iter()
        .zip(&columns.axes)
        .map(|(a, &c)| {
            let v = cell_value(&cells, columns, c, &a.name, line)?;
            // Finite degrees give finite radians (|π/180| < 1).
            Ok(if a.is_rotary() { v.to_radians() } else { v })
        })
        .collect::<Result<_, AxesCsvError>>()?;
    Ok(AxesRow { x, q })
}

/// The finite number in cell `index` of a row, the column named `name`.
fn cell_value(
    cells: &[&str],
    columns: &Columns,
    index: usize,
    name: &str,
    line: usize,
) -> Result<f64, AxesCsvError> {
    let cell = cells.get(index).ok_or_else(|| AxesCsvError::MissingCell {
        line,
        column: excerpt(name),
        position: index + 1,
        cells: cells.len(),
        expected: columns.count,
        header: columns.names.clone(),
    })?;
    cell.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| AxesCsvError::NotANumber {
            line,
            column: excerpt(name),
            cell: excerpt(cell),
        })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::shipped;
    use proptest::prelude::*;

    /// The 4-axis winder: axes A (rotary), X, Y, B (rotary).
    fn winder() -> Machine {
        shipped::shipped("winder-4axis").unwrap().machine().unwrap()
    }

    fn names(m: &Machine) -> Vec<String> {
        m.axes.iter().map(|a| a.name.clone()).collect()
    }

    fn error(text: &str) -> String {
        let e = read_axes_csv(&winder(), text).unwrap_err().to_string();
        assert!(!e.contains('\n'), "one line: {e}");
        e
    }

    #[test]
    fn the_winder_has_the_axes_these_tests_expect() {
        let m = winder();
        assert_eq!(names(&m), ["A", "X", "Y", "B"]);
        let rotary: Vec<bool> = m.axes.iter().map(|a| a.is_rotary()).collect();
        assert_eq!(rotary, [true, false, false, true]);
    }

    #[test]
    fn rows_come_in_the_machine_order_with_degrees_as_radians() {
        let text = "# written by hand\n\u{20}B , Y, X,A,extra\n\n90,120, 10 ,180,zz\n-45,0,0,0,\n";
        let rows = read_axes_csv(&winder(), text).unwrap();
        let pi = std::f64::consts::PI;
        assert_eq!(
            rows,
            vec![
                AxesRow {
                    x: None,
                    q: vec![pi, 10.0, 120.0, pi / 2.0]
                },
                AxesRow {
                    x: None,
                    q: vec![0.0, 0.0, 0.0, -pi / 4.0]
                },
            ]
        );
    }

    #[test]
    fn an_x_column_is_read_and_a_byte_order_mark_ignored() {
        let rows = read_axes_csv(&winder(), "\u{feff}x,A,X,Y,B\n2.5,0,1,2,0\n").unwrap();
        assert_eq!(
            rows,
            vec![AxesRow {
                x: Some(2.5),
                q: vec![0.0, 1.0, 2.0, 0.0]
            }]
        );
    }

    #[test]
    fn a_header_alone_gives_no_rows() {
        assert_eq!(read_axes_csv(&winder(), "A,X,Y,B\n").unwrap(), vec![]);
    }

    #[test]
    fn an_empty_file_needs_a_header_naming_the_axes() {
        for text in ["", "\n  \n# only a comment\n", "\u{feff}"] {
            assert_eq!(
                error(text),
                "empty file (need a header row naming the machine's axes: A, X, Y, B)"
            );
        }
    }

    #[test]
    fn a_missing_axis_column_names_the_header_line_and_the_axes() {
        assert_eq!(
            error("# comment\n\nA,X,Y\n0,0,0\n"),
            "3: no column \"B\" (the machine's axes are A, X, Y, B)"
        );
    }

    #[test]
    fn a_bad_cell_names_its_line_column_and_text() {
        assert_eq!(
            error("A,X,Y,B\n0,0,0,0\n\n0,abc,0,0\n"),
            "4: column \"X\": not a finite number: \"abc\""
        );
        assert_eq!(
            error("x,A,X,Y,B\ninf,0,0,0,0\n"),
            "2: column \"x\": not a finite number: \"inf\""
        );
        assert_eq!(
            error("A,X,Y,B\nNaN,0,0,0\n"),
            "2: column \"A\": not a finite number: \"NaN\""
        );
        assert_eq!(
            error("A,X,Y,B\n0,0,,0\n"),
            "2: column \"Y\": not a finite number: \"\""
        );
    }

    #[test]
    fn a_short_row_names_the_missing_column() {
        assert_eq!(
            error("A,X,Y,B\n0,0,0\n"),
            "2: column \"B\" (cell 4) is missing: the row has 3 cells, the header 4 (A, X, Y, B)"
        );
        assert_eq!(
            error("x, A,X,Y,B,extra\n0,0,0,0,0,0\n1\n"),
            "3: column \"A\" (cell 2) is missing: the row has 1 cell, \
             the header 6 (x, A, X, Y, B, extra)"
        );
    }

    #[test]
    fn control_characters_and_long_cells_are_quoted_short() {
        let long = "9".repeat(500) + "x";
        let e = error(&format!("A,X,Y,B\n0,\u{1b}[31m,0,0\n0,0,0,{long}\n"));
        assert_eq!(e, "2: column \"X\": not a finite number: \"\\u{1b}[31m\"");
        let e = error(&format!("A,X,Y,B\n0,0,0,{long}\n"));
        assert!(e.len() < 160 && e.ends_with("…\""), "{e}");
    }

    proptest! {
        #[test]
        fn written_rows_read_back(rows in proptest::collection::vec(
            (-1e6f64..1e6, proptest::array::uniform4(-1e4f64..1e4)), 0..8)
        ) {
            let m = winder();
            let mut text = String::from("x,A,X,Y,B\n");
            for (x, q) in &rows {
                text.push_str(&format!("{x},{},{},{},{}\n", q[0], q[1], q[2], q[3]));
            }
            let back = read_axes_csv(&m, &text).unwrap();
            prop_assert_eq!(back.len(), rows.len());
            for ((x, q), r) in rows.iter().zip(&back) {
                prop_assert_eq!(r.x, Some(*x));
                prop_assert_eq!(r.q[1], q[1]);
                prop_assert_eq!(r.q[2], q[2]);
                prop_assert_eq!(r.q[0], q[0].to_radians());
                prop_assert_eq!(r.q[3], q[3].to_radians());
            }
        }

        #[test]
        fn any_text_reads_or_fails_on_one_line(text in "[ -~\n\u{feff}\u{1b}]{0,200}") {
            let header = format!("A,X,Y,B\n{text}");
            for t in [text.as_str(), header.as_str()] {
                match read_axes_csv(&winder(), t) {
                    Ok(rows) => prop_assert!(rows.iter().all(|r| r.q.len() == 4
                        && r.q.iter().chain(&r.x).all(|v| v.is_finite()))),
                    Err(e) => prop_assert!(!e.to_string().contains('\n')),
                }
            }
        }
    }
}
