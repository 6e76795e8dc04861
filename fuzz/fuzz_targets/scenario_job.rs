#![no_main]
//! A closed-loop scenario's TOML, read as `formcam correct simulate` reads it.

use formcam_correct::ScenarioJob;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = ScenarioJob::from_toml(text);
});
