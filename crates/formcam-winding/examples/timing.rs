//! Rough timing of the parts of a pass (use the criterion benches for figures).
#![allow(clippy::unwrap_used, missing_docs)]
use formcam_geom::*;
use formcam_winding::*;
use std::time::Instant;
fn main() {
    let v = Vessel::new(
        100.0,
        300.0,
        (DomeShape::Hemisphere, 30.0),
        (DomeShape::Hemisphere, 30.0),
    )
    .unwrap();
    let law = MuLaw::Constant(0.0);
    let o = TraceOptions::default();
    let t = Instant::now();
    let mut tr = None;
    for _ in 0..100 {
        tr = Some(trace(&v, &law, std::f64::consts::FRAC_PI_2, &o).unwrap());
    }
    println!("trace {:.3} ms", t.elapsed().as_secs_f64() * 10.0);
    let tr = tr.unwrap();
    let t = Instant::now();
    for _ in 0..20 {
        std::hint::black_box(tr.sample(&v, &law, 100_000));
    }
    println!("sample 1e5 {:.3} ms", t.elapsed().as_secs_f64() * 50.0);
    let v2 = Vessel::new(
        100.0,
        300.0,
        (DomeShape::Hemisphere, 30.0),
        (DomeShape::Hemisphere, 45.0),
    )
    .unwrap();
    let t = Instant::now();
    let s = shoot(&v2, 0.6).unwrap();
    println!(
        "shoot {:.3} ms evals {} residual {:e}",
        t.elapsed().as_secs_f64() * 1e3,
        s.evaluations,
        s.residual_mm
    );
}
