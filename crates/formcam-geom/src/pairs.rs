//! Reading two-column numeric tables (CSV and the like).

use crate::GeomError;

/// Reads `a, b` pairs, one per line, named `names` in errors.
///
/// Values are separated by a comma, a semicolon or whitespace. With
/// semicolons a decimal comma is accepted (`12,5; 40,0`). Blank lines and
/// lines starting with `#` are skipped, and so is a first line in which no
/// field is a number (a header such as `z,r`). Row numbers in errors count
/// data lines only.
pub fn read_pairs(text: &str, names: (&str, &str)) -> Result<Vec<(f64, f64)>, GeomError> {
    let mut points = Vec::new();
    let mut first = true;
    let lines = text
        .lines()
        .map(|l| l.trim_start_matches('\u{feff}').trim());
    for line in lines.filter(|l| !l.is_empty() && !l.starts_with('#')) {
        let fields = split_fields(line);
        if std::mem::take(&mut first) && fields.iter().all(|f| parse_number(f).is_none()) {
            continue;
        }
        let row = points.len() + 1;
        if fields.len() != 2 {
            return Err(GeomError::Table {
                row,
                reason: format!(
                    "expected 2 values ({}, {}), found {}: '{line}'",
                    names.0,
                    names.1,
                    fields.len()
                ),
            });
        }
        let read = |name: &str, field: &str| {
            parse_number(field).ok_or_else(|| GeomError::Table {
                row,
                reason: format!("cannot read {name}: '{field}'"),
            })
        };
        points.push((read(names.0, fields[0])?, read(names.1, fields[1])?));
    }
    Ok(points)
}

/// The fields of one CSV line: split on `;` if present, else on `,` if
/// present, else on whitespace. Trailing empty fields are dropped.
fn split_fields(line: &str) -> Vec<&str> {
    let mut fields: Vec<&str> = if line.contains(';') {
        line.split(';').map(str::trim).collect()
    } else if line.contains(',') {
        line.split(',').map(str::trim).collect()
    } else {
        line.split_whitespace().collect()
    };
    while fields.last().is_some_and(|f| f.is_empty()) {
        fields.pop();
    }
    fields
}

/// A finite number, with a decimal comma accepted in place of the point.
fn parse_number(field: &str) -> Option<f64> {
    let value = match field.parse::<f64>() {
        Ok(v) => v,
        Err(_) if field.contains(',') && !field.contains('.') => {
            field.replace(',', ".").parse().ok()?
        }
        Err(_) => return None,
    };
    value.is_finite().then_some(value)
}
