#![no_main]
//! A CMM report in CSV, read as `formcam correct --measurements` reads `*.csv`.

use formcam_correct::Measurements;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(m) = Measurements::from_csv(text) {
        let _ = m.max_deviation();
    }
});
