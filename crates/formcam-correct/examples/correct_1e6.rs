//! 10^6 raster nodes corrected against a 200 x 200 grid (the bench's case),
//! timed once; prints `seconds checksum` for `scripts/correct_numpy.py`.

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
    let checksum: f64 = c.iter().map(|c| c.displacement[2]).sum();
    println!("{secs} {checksum}");
    Ok(())
}
