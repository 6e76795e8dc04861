//! Speed of the path engine: a geodesic pass sampled at 1e5 points, a
//! `mu = "auto"` pass, the minimax search on a concave meridian and on a shell
//! whose ends flare, and a tube's layer turned by friction.

#![allow(clippy::expect_used, missing_docs)]

use std::f64::consts::{FRAC_PI_2, PI};
use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use formcam_geom::{Cylinder, DomeShape, Jet, Meridian, Vessel};
use formcam_winding::{
    Ends, LayerSpec, MuLaw, Slippage, TraceOptions, TubeTurn, minimax, plan_layer, shoot, trace,
};

fn vessel(rp2: f64) -> Vessel {
    Vessel::new(
        100.0,
        300.0,
        (DomeShape::Hemisphere, 30.0),
        (DomeShape::Hemisphere, rp2),
    )
    .expect("valid vessel")
}

struct Waist;

impl Meridian for Waist {
    fn z_range(&self) -> (f64, f64) {
        (0.0, 300.0)
    }
    fn eval(&self, z: f64) -> Jet {
        let k = PI / 300.0;
        let u = (z - 150.0) / 40.0;
        let g = (-u * u).exp();
        Jet {
            r: 40.0 + 60.0 * (k * z).sin() - 15.0 * g,
            dr: 60.0 * k * (k * z).cos() + 15.0 * g * 2.0 * u / 40.0,
            d2r: -60.0 * k * k * (k * z).sin() + 15.0 * g * (2.0 - 4.0 * u * u) / 1600.0,
        }
    }
}

/// A waisted shell whose ends flare (r' = -0.1 and +0.1 at the ends).
struct Flare;

impl Meridian for Flare {
    fn z_range(&self) -> (f64, f64) {
        (0.0, 300.0)
    }
    fn eval(&self, z: f64) -> Jet {
        let k = PI / 300.0;
        let d = z - 150.0;
        Jet {
            r: 40.0 + 30.0 * (k * z).cos().powi(2) + d * d / 3000.0,
            dr: -30.0 * k * (2.0 * k * z).sin() + 2.0 * d / 3000.0,
            d2r: -60.0 * k * k * (2.0 * k * z).cos() + 2.0 / 3000.0,
        }
    }
}

fn benches(c: &mut Criterion) {
    let v = vessel(30.0);
    let law = MuLaw::Constant(0.0);
    let opts = TraceOptions::default();
    c.bench_function("geodesic pass, hemisphere vessel, 1e5 samples", |b| {
        b.iter(|| {
            let tr = trace(&v, &law, FRAC_PI_2, &opts).expect("trace");
            black_box(tr.sample(&v, &law, 100_000))
        })
    });
    let v2 = vessel(45.0);
    c.bench_function("mu = auto pass (shooting + final pass), 1e5 samples", |b| {
        b.iter(|| {
            let shot = shoot(&v2, 0.6).expect("shoot");
            let law = MuLaw::Constant(shot.mu);
            black_box(shot.trace.sample(&v2, &law, 100_000))
        })
    });
    c.bench_function("minimax on a concave meridian, 4000 nodes", |b| {
        b.iter(|| black_box(minimax(&Waist, 4000, 3.0).expect("minimax")))
    });
    c.bench_function("minimax on a shell whose ends flare, 4000 nodes", |b| {
        b.iter(|| black_box(minimax(&Flare, 4000, 3.0).expect("minimax")))
    });
    let cyl = Cylinder::new(50.0, 600.0).expect("cylinder");
    let spec = LayerSpec {
        slippage: Slippage::Constant(0.2),
        ends: Ends::Tube {
            winding_angle: 40f64.to_radians(),
        },
        turnaround: TubeTurn::Friction,
        ..LayerSpec::default()
    };
    c.bench_function(
        "tube layer turned by friction (zones, pass, pattern), 2001 samples",
        |b| b.iter(|| black_box(plan_layer(&cyl, &spec).expect("layer"))),
    );
}

criterion_group!(name = g; config = Criterion::default().sample_size(20); targets = benches);
criterion_main!(g);
