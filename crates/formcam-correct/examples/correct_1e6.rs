//! 10^6 raster nodes corrected against a 200 x 200 grid (the bench's case),
//! timed once from the measured grid to the corrections (the patches, the
//! k-d tree and every node; building the case is not timed, as in the
//! NumPy version); prints `seconds checksum cpu_seconds` for
//! `scripts/correct_numpy.py`: the wall time, the sum of the displacements
//! along z, and the CPU time of all threads over the same span (NaN where
//! `/proc` does not give it), which a loaded machine leaves comparable.

use std::time::Instant;

use formcam_correct::{Corrector, Interpolation, Options};

#[allow(dead_code)]
#[path = "../benches/common/mod.rs"]
mod case;

fn main() -> Result<(), formcam_correct::CorrectError> {
    let grid = case::grid(200);
    let nodes = case::nodes(1000);
    let interpolation = match std::env::args().nth(1).as_deref() {
        Some("bicubic") => Interpolation::Bicubic,
        _ => Interpolation::Bilinear,
    };
    let cpu = cpu_seconds();
    let t = Instant::now();
    let corrector = Corrector::new(
        &grid,
        Options {
            interpolation,
            ..Options::default()
        },
    )?;
    let c = corrector.correct(&nodes);
    let secs = t.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - cpu;
    let checksum: f64 = c.iter().map(|c| c.displacement[2]).sum();
    println!("{secs} {checksum} {cpu}");
    Ok(())
}

/// The time every thread of this process has spent on a CPU so far, s:
/// the first field of each `/proc/self/task/*/schedstat` (ns); NaN where
/// there is none. The pool's threads live on, so none is missed.
fn cpu_seconds() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    let mut ns = 0u64;
    for task in tasks.flatten() {
        let Ok(text) = std::fs::read_to_string(task.path().join("schedstat")) else {
            return f64::NAN;
        };
        match text.split_whitespace().next().map(str::parse::<u64>) {
            Some(Ok(v)) => ns += v,
            _ => return f64::NAN,
        }
    }
    ns as f64 * 1e-9
}
