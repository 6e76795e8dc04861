//! The wheel's contour before dressing as users give it: a CSV of the
//! program's axes, `z,x` (mm; `z` along the wheel's axis, `x` radial, the
//! ball's centre at the origin), read into the profile's frame.
//!
//! The first line that is not blank or a `#` comment may be a header naming
//! the columns, in any order: `z,x` (or `x,z`), or the older `x,y` (`x` along
//! the axis, `y` radial), read as it always was. Without a header the
//! columns are `z,x`. Every other line holds numbers, `z` non-decreasing.

use formcam_files::excerpt;

use crate::{ContourFault, ContourLineProblem, DressError, Point};

/// Which columns hold the axial and the radial coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Columns {
    axial: usize,
    radial: usize,
}

/// Reads the contour CSV `text` (the file of `process.initial_contour`)
/// into points of the profile's frame (`Point::x` along the wheel's axis,
/// `Point::y` radial). Errors name the field and the line.
pub fn read_contour(text: &str) -> Result<Vec<Point>, DressError> {
    let mut columns: Option<Columns> = None;
    let mut points: Vec<Point> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let row = raw.trim();
        if row.is_empty() || row.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        let numbers: Option<Vec<f64>> = cells.iter().map(|c| c.parse().ok()).collect();
        let cols = match (columns, numbers) {
            (Some(c), Some(v)) => {
                push(&mut points, point(&v, c, line)?, line)?;
                continue;
            }
            (Some(_), None) => {
                return Err(at(line, ContourLineProblem::NotNumbers));
            }
            (None, Some(v)) => {
                let c = Columns {
                    axial: 0,
                    radial: 1,
                };
                push(&mut points, point(&v, c, line)?, line)?;
                c
            }
            (None, None) => header(&cells, line)?,
        };
        columns = Some(cols);
    }
    check(&points)?;
    Ok(points)
}

/// The columns a header names.
fn header(cells: &[&str], line: usize) -> Result<Columns, DressError> {
    let names: Vec<String> = cells.iter().map(|c| c.to_ascii_lowercase()).collect();
    let find = |name: &str| names.iter().position(|n| n == name);
    let columns = match (find("z"), find("x"), find("y")) {
        (Some(z), Some(x), None) => Columns {
            axial: z,
            radial: x,
        },
        // The older header: x along the wheel's axis, y radial.
        (None, Some(x), Some(y)) => Columns {
            axial: x,
            radial: y,
        },
        _ => {
            return Err(at(
                line,
                ContourLineProblem::Header {
                    header: excerpt(&cells.join(",")),
                },
            ));
        }
    };
    Ok(columns)
}

/// The point of a row of numbers.
fn point(values: &[f64], c: Columns, line: usize) -> Result<Point, DressError> {
    match (values.get(c.axial), values.get(c.radial)) {
        (Some(&z), Some(&x)) if z.is_finite() && x.is_finite() => Ok(Point::new(z, x)),
        (Some(_), Some(_)) => Err(at(line, ContourLineProblem::NotFinite)),
        _ => Err(at(line, ContourLineProblem::TooFewNumbers)),
    }
}

/// Adds `p` (read on `line`) after the points before, in order along the
/// wheel's axis.
fn push(points: &mut Vec<Point>, p: Point, line: usize) -> Result<(), DressError> {
    if let Some(last) = points.last()
        && p.x < last.x
    {
        return Err(at(
            line,
            ContourLineProblem::Decreasing {
                from: last.x,
                to: p.x,
            },
        ));
    }
    points.push(p);
    Ok(())
}

/// Enough points.
fn check(points: &[Point]) -> Result<(), DressError> {
    if points.len() < 2 {
        return Err(ContourFault::FileTooShort.into());
    }
    Ok(())
}

fn at(line: usize, problem: ContourLineProblem) -> DressError {
    DressError::ContourLine { line, problem }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn xy(points: &[Point]) -> Vec<(f64, f64)> {
        points.iter().map(|p| (p.x, p.y)).collect()
    }

    #[test]
    fn the_program_axes_header_reads_in_either_order() {
        let want = vec![(-3.0, 1.95), (0.0, 2.0), (3.0, 1.95)];
        let zx = read_contour("z,x\n-3,1.95\n0,2\n3,1.95\n").unwrap();
        assert_eq!(xy(&zx), want);
        let xz = read_contour("# worn wheel\n\nX , Z\n1.95,-3\n2,0\n1.95,3\n").unwrap();
        assert_eq!(xy(&xz), want);
        let bare = read_contour("-3,1.95\n0,2\n3,1.95\n").unwrap();
        assert_eq!(xy(&bare), want);
    }

    #[test]
    fn the_older_header_reads_as_before() {
        let old = read_contour("x,y\n-3,1.95\n0,2\n3,1.95\n").unwrap();
        assert_eq!(xy(&old), vec![(-3.0, 1.95), (0.0, 2.0), (3.0, 1.95)]);
        let swapped = read_contour("y,x\n1.95,-3\n2,0\n").unwrap();
        assert_eq!(xy(&swapped), vec![(-3.0, 1.95), (0.0, 2.0)]);
    }

    #[test]
    fn errors_name_the_field_and_the_line() {
        let cases = [
            ("z,x\n-3,1.95\n0,two\n", 3, "expected numbers z,x"),
            ("z,x\n-3,1.95\n0\n", 3, "expected two numbers z,x"),
            ("a,b\n-3,1.95\n", 1, "the header names the columns a,b"),
            ("z,x,y\n-3,1.95,0\n", 1, "expected z,x"),
            ("# c\nz,x\n-3,inf\n", 3, "finite"),
            ("z,x\n0,2\n1,2\n0.5,2\n", 4, "z decreases from 1 to 0.5"),
        ];
        for (text, line, expect) in cases {
            let e = read_contour(text).unwrap_err();
            assert!(
                matches!(&e, DressError::ContourLine { line: l, .. } if *l == line),
                "{text:?}: {e:?}"
            );
            let shown = e.to_string();
            assert!(
                shown.starts_with(&format!("process.initial_contour, line {line}: "))
                    && shown.contains(expect),
                "{text:?}: {shown}"
            );
        }
        let e = read_contour("z,x\n0,2\n").unwrap_err().to_string();
        assert!(
            e.starts_with("process.initial_contour: ") && e.contains("fewer than two"),
            "{e}"
        );
    }
}
