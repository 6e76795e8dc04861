#![no_main]
//! A LinuxCNC milling program, read as `formcam correct --program *.ngc` reads it and written back unchanged.

use formcam_correct::{MillingProgram, Settings};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(p) = MillingProgram::read(text, "ngc", &Settings::default()) {
        let _ = p.write(&p.positions());
    }
});
