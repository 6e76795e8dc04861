#![no_main]
//! A `[correct]` job's TOML, read as `formcam correct JOB` reads it.

use libfuzzer_sys::fuzz_target;
use std::path::Path;

use formcam_correct::CorrectionJob;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = CorrectionJob::from_toml(text, Path::new("/nonexistent-formcam-fuzz"));
});
