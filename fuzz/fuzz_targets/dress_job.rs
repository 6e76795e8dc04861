#![no_main]
//! A dressing job's TOML, read as `formcam dress` reads it, and its spec built.

use formcam_dress::DressJob;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(job) = DressJob::from_toml(text) {
        let _ = job.spec(None);
    }
});
