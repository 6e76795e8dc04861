#![no_main]
//! A winding job's TOML, read as `formcam wind` reads it (tables, layers, eye, machine, motion, post).

use libfuzzer_sys::fuzz_target;
use std::path::Path;

use formcam_program::WindJob;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // Files it names are looked for in a folder that does not exist.
    let _ = WindJob::from_toml(text, Path::new("/nonexistent-formcam-fuzz"));
});
