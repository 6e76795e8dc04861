#![no_main]
//! A dressing job's `initial_contour` table.

use formcam_dress::read_contour;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = read_contour(text);
});
