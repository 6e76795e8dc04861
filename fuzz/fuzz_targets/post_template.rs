#![no_main]
//! A user post template, read as a winding job's `[post] template` is read.

use formcam_nc::Template;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = Template::from_toml(text);
});
