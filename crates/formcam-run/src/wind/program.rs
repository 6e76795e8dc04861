//! The written program's files (`program.<ext>`, `blocks.csv`), its summary
//! fields and its part of the line.

use formcam_machine::Machine;
use formcam_program::{Assembled, WoundProgram};
use formcam_results::names;
use formcam_results::winding::BLOCKS;
use serde_json::{Map, Value};

use super::csv::{blocks_csv, program_axes};
use super::line::program_line;
use super::summary::program_summary;
use crate::ResultFile;

/// The program's files (`program.<ext>`, `blocks.csv`), its summary fields
/// and its part of the line.
pub(super) fn program_files(
    m: &Machine,
    p: &Assembled,
    wound: &WoundProgram,
    text: Vec<u8>,
) -> (Vec<ResultFile>, Map<String, Value>, String) {
    let ext = wound.post.extension();
    let (_, axis_ranges) = program_axes(m, p);
    let summary = program_summary(p, ext, axis_ranges);
    let line = program_line(p, ext);
    let files = vec![
        ResultFile::new(names::program(ext), text),
        ResultFile::new(BLOCKS.file, blocks_csv(m, p)),
    ];
    (files, summary, line)
}
