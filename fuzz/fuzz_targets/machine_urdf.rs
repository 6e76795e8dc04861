#![no_main]
//! A URDF machine file, read as `formcam machine show|fk` reads `*.urdf`, then shown and placed at home.

use formcam_machine::{Machine, MachineFormat};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(m) = Machine::parse(text, MachineFormat::Urdf) {
        let _ = m.table();
        let _ = m.key_points(&m.home());
    }
});
