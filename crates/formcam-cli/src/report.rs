//! `formcam report OUT -o report.html`: a result's read-only views as one
//! self-contained HTML file (the page and its data inlined; it opens from a
//! `file://` URL with no server and no network).

use std::path::{Path, PathBuf};

use formcam_view::Page;

use crate::CliError;

/// Writes the report of the result folder `folder` to `output` (atomically,
/// never over the result's files or inputs) and returns the line printed;
/// `machine` replaces the machine the result names.
pub fn run(folder: &Path, output: &Path, machine: Option<&Path>) -> Result<String, CliError> {
    let page = Page::embedded()?;
    let report = formcam_view::report(folder, output, machine, &page)?;
    let files: [(PathBuf, &[u8]); 1] = [(output.to_path_buf(), &report.html)];
    crate::output::write_files(&files, &report.inputs)?;
    let knots = if report.knots == 0 {
        String::new()
    } else if report.thinned {
        format!(
            ", poses drawn from {} knots (thinned: within {:.3} mm)",
            report.knots, report.worst_mm
        )
    } else {
        format!(
            ", poses within {:.1e} mm of the server's ({} knots)",
            report.worst_mm, report.knots
        )
    };
    Ok(format!(
        "formcam report: {} ({} result, {} bytes{knots})",
        output.display(),
        kind_name(report.kind),
        report.html.len()
    ))
}

fn kind_name(kind: formcam_view::ResultKind) -> &'static str {
    match kind {
        formcam_view::ResultKind::Winding => "winding",
        formcam_view::ResultKind::Dressing => "dressing",
        formcam_view::ResultKind::Correction => "correction",
        formcam_view::ResultKind::Path => "winding path",
    }
}
