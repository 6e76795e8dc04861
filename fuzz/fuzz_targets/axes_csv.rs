#![no_main]
//! An axes CSV, read as `formcam machine fk MACHINE --axes` reads it for one
//! of the shipped machines (chosen by the first byte), then each row placed.

use std::sync::OnceLock;

use formcam_machine::{Machine, read_axes_csv, shipped::SHIPPED};
use libfuzzer_sys::fuzz_target;

/// The shipped machines, read once.
fn machines() -> &'static [Machine] {
    static MACHINES: OnceLock<Vec<Machine>> = OnceLock::new();
    MACHINES.get_or_init(|| SHIPPED.iter().filter_map(|s| s.machine().ok()).collect())
}

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let machines = machines();
    let Some(m) = machines.get(usize::from(pick) % machines.len().max(1)) else {
        return;
    };
    // formcam reads inputs as UTF-8 text (formcam_files::read_text).
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    if let Ok(rows) = read_axes_csv(m, text) {
        for row in &rows {
            let _ = m.key_points(&row.q);
        }
    }
});
