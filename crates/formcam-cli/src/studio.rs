//! `formcam studio [JOB_OR_FOLDER]`: the job editor served to the browser
//! until the process ends; the page's address is the first line on stdout.

use std::io::Write as _;
use std::path::Path;

use formcam_studio::{Studio, StudioServer};
use formcam_view::Page;

use crate::CliError;

/// Opens the studio on `path` (a folder, or a job file in it) on
/// `127.0.0.1:port` (0: any free port).
pub fn run(path: &Path, port: u16) -> Result<(), CliError> {
    let server = StudioServer::bind(Studio::open(path, Page::embedded()?)?, port)?;
    let mut out = std::io::stdout().lock();
    // The address is what callers wait for: written and flushed first.
    let _ = writeln!(out, "{}", server.url());
    let _ = out.flush();
    drop(out);
    eprintln!("formcam studio: {} (Ctrl-C ends)", path.display());
    server.serve();
    Ok(())
}
