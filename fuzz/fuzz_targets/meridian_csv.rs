#![no_main]
//! A meridian table (`[mandrel] file`, `z,r`), read and smoothed as a profile job reads it.

use formcam_geom::{Tabulated, read_pairs};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(points) = read_pairs(text, ("z", "r")) {
        let _ = Tabulated::new(&points, 0.0);
    }
});
