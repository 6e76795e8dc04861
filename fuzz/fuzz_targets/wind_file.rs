#![no_main]
//! A Cyclone/FiberPath `.wind` document, read as `formcam wind tube.wind` reads it.

use formcam_program::{EYE_CLEARANCE_MM, WindJob};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = WindJob::from_wind(text, EYE_CLEARANCE_MM, &[]);
});
