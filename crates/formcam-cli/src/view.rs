//! `formcam view OUT`: serves a result folder to the browser until the
//! process ends; the page's address is the first line on stdout.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use formcam_view::{Page, ViewOptions, ViewServer};

use crate::CliError;

/// Serves `folder` on `127.0.0.1:port` (0: any free port).
pub fn run(folder: &Path, port: u16, machine: Option<PathBuf>) -> Result<(), CliError> {
    let page = Page::embedded()?;
    let server = ViewServer::bind(folder, &ViewOptions { port, machine }, page)?;
    let mut out = std::io::stdout().lock();
    // The address is what callers wait for: written and flushed first.
    let _ = writeln!(out, "{}", server.url());
    let _ = out.flush();
    drop(out);
    eprintln!("formcam view: {} (Ctrl-C ends)", folder.display());
    server.serve();
    Ok(())
}
