//! The speed case shared by the bench and the `correct_1e6` example: a
//! 400 x 300 mm doubly curved surface measured on a 200 x 200 grid with a
//! smooth warp, and 10^6 raster nodes on it.

use formcam_correct::Grid;

/// The bench's surface: 400 x 300 mm, doubly curved.
/// The surface's height.
pub fn height(x: f64, y: f64) -> f64 {
    (x - 200.0).powi(2) / 2400.0 + (y - 150.0).powi(2) / 1800.0
}

/// The warp along z.
pub fn warp(x: f64, y: f64) -> f64 {
    0.4 * (std::f64::consts::PI * x / 400.0).sin() * (std::f64::consts::PI * y / 300.0).sin()
}

/// The measured `n x n` grid.
pub fn grid(n: usize) -> Grid {
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
    Grid {
        nu: n,
        nv: n,
        nominal,
        deviation,
        normal: None,
        resampled: false,
        reordered: false,
    }
}

/// `n x n` zig-zag raster nodes on the surface.
pub fn nodes(n: usize) -> Vec<[f64; 3]> {
    let mut out = Vec::with_capacity(n * n);
    for k in 0..n {
        let y = 300.0 * (k as f64 + 0.5) / n as f64;
        for i in 0..n {
            let i = if k % 2 == 0 { i } else { n - 1 - i };
            let x = 400.0 * (i as f64 + 0.5) / n as f64;
            out.push([x, y, height(x, y)]);
        }
    }
    out
}
