#![no_main]
//! An eye curve (`[eye] curve`, `Z,R`), read as an eye job reads it.

use formcam_geom::read_pairs;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = read_pairs(text, ("Z", "R"));
});
