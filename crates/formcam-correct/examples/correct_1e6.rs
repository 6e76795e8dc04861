//! 10^6 raster nodes corrected against a 200 x 200 grid (the bench's case),
//! timed once; prints `seconds checksum` for `scripts/correct_numpy.py`.

use std::time::Instant;

use formcam_correct::{Corrector, Grid, Interpolation, Options};

fn height(x: f64, y: f64) -> f64 {
    (x - 200.0).powi(2) / 2400.0 + (y - 150.0).powi(2) / 1800.0
}

fn warp(x: f64, y: f64) -> f64 {
    0.4 * (std::f64::consts::PI * x / 400.0).sin() * (std::f64::consts::PI * y / 300.0).sin()
}

fn main() -> Result<(), formcam_correct::CorrectError> {
    let n = 200;
    let mut nominal = Vec::with_capacity(n * n);
    let mut deviation = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (
                400.0 * j as f64 / (n - 1) as f64,
                300.0 * i as f64 / (n - 1) as f64,
            );
            nominal.push([x, y, height(x, y)]);
            deviation.push([0.0, 0.0, warp(x, y)]);
        }
    }
    let grid = Grid {
        nu: n,
        nv: n,
        nominal,
        deviation,
        normal: None,
        resampled: false,
    };
    let m = 1000;
    let mut nodes = Vec::with_capacity(m * m);
    for k in 0..m {
        let y = 300.0 * (k as f64 + 0.5) / m as f64;
        for i in 0..m {
            let i = if k % 2 == 0 { i } else { m - 1 - i };
            let x = 400.0 * (i as f64 + 0.5) / m as f64;
            nodes.push([x, y, height(x, y)]);
        }
    }
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
