use std::fmt;
use std::sync::Arc;

use formcam_files::quote;
use thiserror::Error;

/// Everything that can stop reading a machine or solving its kinematics.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MachineError {
    /// The file is not valid TOML or does not match the format.
    #[error("{line}:{column}: {message}")]
    Syntax {
        /// Line of the error (1-based; 0 when unknown).
        line: usize,
        /// Column of the error (1-based; 0 when unknown).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A field of a link, joint, point or the `[machine]` table is wrong.
    #[error("{place}: {field}: {reason}")]
    Field {
        /// Where: `link "carriage"`, `point "payout"`, `[machine]`.
        place: String,
        /// The field's name.
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A URDF document that cannot be read.
    #[error("URDF: {0}")]
    Urdf(#[from] UrdfFault),
    /// A URDF document without the `<formcam>` element that holds what URDF
    /// has no place for.
    #[error(
        "URDF: no <formcam> element: a URDF machine needs the [machine] table and the \
         [[point]] key points, as TOML, in a <formcam> element inside <robot>"
    )]
    NoFormcamElement,
    /// A URDF document's XML that cannot be read again for its `<formcam>`
    /// element.
    #[error("URDF: {message}")]
    Xml {
        /// The XML reader's reason.
        message: String,
    },
    /// The TOML inside the `<formcam>` element is not valid or does not
    /// match the format.
    #[error("URDF: <formcam> {line}:{column}: {message}")]
    FormcamElement {
        /// Line inside the element (1-based; 0 when unknown).
        line: usize,
        /// Column of the error (1-based; 0 when unknown).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// The inverse kinematics cannot be set up for this machine and target.
    #[error("inverse kinematics: {0}")]
    Ik(#[from] IkFault),
}

/// urdf-rs's reason for refusing a document, shared so that the error stays
/// `Clone`; it prints on one line. Where the elements are not properly
/// nested, it says where instead (urdf-rs does not).
#[derive(Debug, Clone)]
pub struct UrdfFault(Arc<urdf_rs::UrdfError>, Option<String>);

impl UrdfFault {
    /// urdf-rs's error.
    pub fn source_error(&self) -> &urdf_rs::UrdfError {
        &self.0
    }

    /// The fault with `place` (the line of a misnested element and what is
    /// open there) said instead of urdf-rs's reason, when there is one.
    pub(crate) fn misnested(mut self, place: Option<String>) -> Self {
        self.1 = place;
        self
    }
}

impl From<urdf_rs::UrdfError> for UrdfFault {
    fn from(e: urdf_rs::UrdfError) -> Self {
        Self(Arc::new(e), None)
    }
}

impl PartialEq for UrdfFault {
    /// The same reason: the same text.
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0) || self.to_string() == other.to_string()
    }
}

impl fmt::Display for UrdfFault {
    /// urdf-rs's reason on one line; an empty or non-XML document says what
    /// a URDF document is, and serde's `custom: ` prefix is dropped.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(place) = &self.1 {
            return write!(f, "{place}");
        }
        let text = self.0.to_string();
        if text.trim() == "No elements found" {
            return write!(
                f,
                "no XML element found: a URDF document is XML, a <robot> element holding \
                 <link> and <joint> elements"
            );
        }
        let text = text.trim_start().strip_prefix("custom: ").unwrap_or(&text);
        let mut words = text.split_whitespace();
        if let Some(first) = words.next() {
            write!(f, "{first}")?;
        }
        for w in words {
            write!(f, " {w}")?;
        }
        Ok(())
    }
}

impl std::error::Error for UrdfFault {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&*self.0)
    }
}

/// Why the inverse kinematics cannot be set up.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IkFault {
    /// A winder whose payout point lies on its spindle's axis.
    #[error("the payout point lies on the spindle axis at the home position")]
    PayoutOnSpindleAxis,
    /// `machine.ik = "closed-form"` on a machine that is no lathe-type winder.
    #[error(
        "\"{}\" has no closed form (it is not a lathe-type winder: spindle, carriage along it, \
         radial cross feed, eye rotation about the cross feed)",
        quote(.machine)
    )]
    NoClosedForm {
        /// The machine's name.
        machine: String,
    },
}

/// Why an axes CSV (`formcam machine fk --axes`) cannot be read; lines are
/// 1-based, names and cells quoted short and escaped.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum AxesCsvError {
    /// No header row: the text is empty, blank or comments only.
    #[error("empty file (need a header row naming the machine's axes: {axes})")]
    Empty {
        /// The machine's axes, comma-separated.
        axes: String,
    },
    /// The header has no column for one of the machine's axes.
    #[error("{line}: no column \"{axis}\" (the machine's axes are {axes})")]
    NoColumn {
        /// The header's line.
        line: usize,
        /// The axis missing.
        axis: String,
        /// The machine's axes, comma-separated.
        axes: String,
    },
    /// A row too short to reach a column.
    #[error(
        "{line}: column \"{column}\" (cell {position}) is missing: the row has {}, \
         the header {expected} ({header})",
        cell_count(*cells)
    )]
    MissingCell {
        /// The row's line.
        line: usize,
        /// The column's name.
        column: String,
        /// The column's place in the header (1-based).
        position: usize,
        /// How many cells the row has.
        cells: usize,
        /// How many cells the header has.
        expected: usize,
        /// The header's column names, comma-separated (quoted short).
        header: String,
    },
    /// A cell that is no finite number.
    #[error("{line}: column \"{column}\": not a finite number: \"{cell}\"")]
    NotANumber {
        /// The row's line.
        line: usize,
        /// The column's name.
        column: String,
        /// The cell's text.
        cell: String,
    },
}

impl AxesCsvError {
    /// The line the error is on; none for an empty file.
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::Empty { .. } => None,
            Self::NoColumn { line, .. }
            | Self::MissingCell { line, .. }
            | Self::NotANumber { line, .. } => Some(*line),
        }
    }
}

/// `1 cell`, `3 cells`.
fn cell_count(n: usize) -> String {
    if n == 1 {
        "1 cell".to_string()
    } else {
        format!("{n} cells")
    }
}

impl MachineError {
    /// A field error at `place`.
    pub fn field(
        place: impl Into<String>,
        field: impl Into<String>,
        reason: impl Into<String>,
    ) -> Self {
        Self::Field {
            place: place.into(),
            field: field.into(),
            reason: reason.into(),
        }
    }
}
