//! What a result folder holds, told by its files and the top-level keys
//! of its summary or report: the one rule every reader of a result folder
//! follows.

use crate::names::{REPORT, SUMMARY};

/// The kind of a result folder: a correction writes `report.json` naming
/// its measurements (a closed-loop simulation, one listing its `rounds`)
/// and no `summary.json`; a dressing's `summary.json` has
/// `dressing_time_s`; any other `summary.json` is a winding result's, a
/// [`Kind::Path`] one without `program_file`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `formcam wind`: the machine, the program, the path.
    Winding,
    /// `formcam dress`: the profile, the dresser's path, the program.
    Dressing,
    /// `formcam correct`: the measurements' deviations, the report; or
    /// `formcam correct simulate`: those of every round.
    Correction,
    /// A winding result without a program (its summary names no
    /// `program_file`): the path, its tables and plots.
    Path,
}

/// What the top level of a JSON file holds at a key, as [`Kind::of`] asks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Entry {
    /// No such key.
    Absent,
    /// A value that is no list.
    Value,
    /// A list.
    List,
}

impl Kind {
    /// The kind of a result folder: `has_file(name)` says whether the
    /// folder has the file `name` ([`SUMMARY`], [`REPORT`]); `keys(name)`
    /// reads that file (only one the folder has), giving what its top
    /// level holds at a key, or the reader's error, passed on. `None`: no
    /// result of a kind formcam writes.
    ///
    /// # Errors
    ///
    /// The error of `keys`.
    pub fn of<E, K: Fn(&str) -> Entry>(
        has_file: impl Fn(&str) -> bool,
        mut keys: impl FnMut(&'static str) -> Result<K, E>,
    ) -> Result<Option<Self>, E> {
        if has_file(SUMMARY) {
            let s = keys(SUMMARY)?;
            return Ok(Some(if s("dressing_time_s") != Entry::Absent {
                Self::Dressing
            } else if s("program_file") != Entry::Absent {
                Self::Winding
            } else {
                Self::Path
            }));
        }
        if has_file(REPORT) {
            let r = keys(REPORT)?;
            if r("measurements") != Entry::Absent || r("rounds") == Entry::List {
                return Ok(Some(Self::Correction));
            }
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kind of a folder of `files`, each with its top-level keys
    /// (a key ending in `[]` holds a list).
    fn kind(files: &[(&str, &[&str])]) -> Result<Option<Kind>, String> {
        Kind::of(
            |name| files.iter().any(|(f, _)| *f == name),
            |name| {
                let (_, keys) = files
                    .iter()
                    .find(|(f, _)| *f == name)
                    .ok_or(format!("{name} read but not there"))?;
                Ok(move |key: &str| {
                    if keys.contains(&key) {
                        Entry::Value
                    } else if keys.iter().any(|k| k.strip_suffix("[]") == Some(key)) {
                        Entry::List
                    } else {
                        Entry::Absent
                    }
                })
            },
        )
    }

    #[test]
    fn a_summary_with_a_program_is_a_winding() {
        let k = kind(&[(SUMMARY, &["job", "program_file"])]);
        assert_eq!(k, Ok(Some(Kind::Winding)));
    }

    #[test]
    fn a_summary_with_the_dressing_time_is_a_dressing() {
        let k = kind(&[(SUMMARY, &["dressing_time_s", "program_file"])]);
        assert_eq!(k, Ok(Some(Kind::Dressing)));
    }

    #[test]
    fn a_summary_without_a_program_is_a_path() {
        // The summary is asked first, a report beside it is not read.
        let k = kind(&[(SUMMARY, &["job", "circuits"]), (REPORT, &["measurements"])]);
        assert_eq!(k, Ok(Some(Kind::Path)));
    }

    #[test]
    fn a_report_naming_measurements_or_listing_rounds_is_a_correction() {
        assert_eq!(
            kind(&[(REPORT, &["measurements"])]),
            Ok(Some(Kind::Correction))
        );
        assert_eq!(kind(&[(REPORT, &["rounds[]"])]), Ok(Some(Kind::Correction)));
        // Rounds that are no list, or a report of neither: no kind.
        assert_eq!(kind(&[(REPORT, &["rounds"])]), Ok(None));
        assert_eq!(kind(&[(REPORT, &["job"])]), Ok(None));
    }

    #[test]
    fn a_folder_of_neither_file_has_no_kind_and_a_read_error_is_passed_on() {
        assert_eq!(kind(&[("path.csv", &[])]), Ok(None));
        let e = Kind::of(|_| true, Err::<fn(&str) -> Entry, _>);
        assert_eq!(e, Err(SUMMARY));
    }
}
